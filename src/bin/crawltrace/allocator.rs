//! Allocator settings of the `crawltrace` binary (not part of the library): glibc's `malloc` is
//! told to keep freed memory for reuse instead of handing it back to the system after each image.
//!
//! Why: tracing a drawing allocates a few image-sized buffers and frees them all at the end. With
//! glibc's defaults the freed top of each thread's heap is returned to the system (`madvise`) and
//! large blocks are `mmap`ed and `munmap`ed, so every image starts again on fresh pages that the
//! kernel must fault in and zero, and the faults of two worker threads contend in the kernel.
//! Kept, the pages are reused by the next image. What is kept is at most what the largest image
//! needed; it is returned when the process ends.
//!
//! Measured on the 2-core development machine, quiet, `crawltrace trace drawings -o out -j N -q`
//! on the 200 one-megapixel drawings of `benches/batch.rs`: page faults 190 000 → 1 600; system
//! CPU time 0.54 → 0.11 s; wall time at `-j 1` 2.01 → 1.79 s, at `-j 2` 1.17 → 0.93 s, so two
//! jobs went from 1.73× to 1.94× the throughput of one. Peak memory is unchanged (12 MB at
//! `-j 1`, 18 MB at `-j 2`).
//!
//! Shared with `benches/batch.rs` (by `#[path]`), so that the benchmark runs what users run.

/// Blocks up to this size come from the heap and are reused; larger ones are still `mmap`ed.
/// 32 MiB is the largest value glibc accepts on 64-bit systems (half its per-thread heap size).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const MMAP_THRESHOLD: libc::c_int = 32 << 20;

/// Free memory at the top of a heap is returned to the system only beyond this much.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const TRIM_THRESHOLD: libc::c_int = 256 << 20;

/// Applies the settings; call it first thing in `main`, before any other thread starts.
/// Does nothing on other C libraries (musl, macOS, Windows), whose allocators work differently.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[allow(unsafe_code)]
pub fn keep_freed_memory_for_reuse() {
    // SAFETY: `mallopt` only sets allocator parameters and is safe to call at any time; it
    // returns 0 (ignored: the defaults then stay, which is merely slower) for a value it refuses.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD);
        libc::mallopt(libc::M_TRIM_THRESHOLD, TRIM_THRESHOLD);
    }
}

/// Does nothing: only glibc needs this.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
pub fn keep_freed_memory_for_reuse() {}
