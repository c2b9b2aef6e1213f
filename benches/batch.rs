//! Benchmarks of the batch engine: 200 files through `run_batch` with a CPU-bound fake processor
//! (about 5 ms of hashing a file) on 1 and 2 worker threads, to show how throughput scales with
//! `jobs`. The real tracer replaces `fake_trace` once it exists.
//!
//! Run: `cargo bench --bench batch`.

use std::fs;
use std::hint::black_box;
use std::path::Path;

use crawltrace::batch::{discover_inputs, fnv1a_64, run_batch, BatchOptions, FileResult};
use divan::counter::ItemsCount;
use divan::Bencher;

const FILES: usize = 200;
/// Hashing this many bytes takes about 5 ms on the 2-core development machine (see the
/// `fake_trace_one_file` benchmark), the order of a small drawing through the real tracer.
const WORK_BYTES: usize = 64 * 1024;
const WORK_ROUNDS: usize = 56;

fn main() {
    divan::main();
}

/// Stands in for the tracer: reads the file and does real CPU work that the optimiser cannot
/// remove, then returns a tiny SVG.
fn fake_trace(path: &Path) -> Result<FileResult, String> {
    let seed = fs::read(path).map_err(|error| error.to_string())?;
    let mut block: Vec<u8> = (0..WORK_BYTES)
        .map(|index| seed[index % seed.len().max(1)] ^ index as u8)
        .collect();
    let mut hash = 0u64;
    for round in 0..WORK_ROUNDS {
        block[round] ^= hash as u8;
        hash ^= fnv1a_64(black_box(&block));
    }
    Ok(FileResult {
        svg: format!("<svg xmlns=\"http://www.w3.org/2000/svg\"><!-- {hash:016x} --></svg>")
            .into_bytes(),
        curves: 1,
        closed_curves: 0,
    })
}

/// 200 files in 10 subfolders of a fresh temporary folder.
fn input_tree() -> tempfile::TempDir {
    let root = tempfile::tempdir().expect("a temporary folder");
    for index in 0..FILES {
        let folder = root.path().join(format!("group-{}", index % 10));
        fs::create_dir_all(&folder).expect("a subfolder");
        fs::write(
            folder.join(format!("scan-{index:03}.png")),
            index.to_string(),
        )
        .expect("an input file");
    }
    root
}

#[divan::bench(args = [1, 2], sample_count = 5, sample_size = 1)]
fn run_batch_200_files(bencher: Bencher, jobs: usize) {
    let input = input_tree();
    let output = tempfile::tempdir().expect("a temporary folder");
    // `force`: every sample redoes every file instead of finding them up to date.
    let options = BatchOptions {
        recursive: true,
        jobs: Some(jobs),
        force: true,
        quiet: true,
        ..BatchOptions::default()
    };
    let discovery =
        discover_inputs(&[input.path().to_path_buf()], &options).expect("the inputs are found");
    assert_eq!(discovery.inputs.len(), FILES);
    bencher.counter(ItemsCount::new(FILES)).bench(|| {
        let summary =
            run_batch(&discovery, output.path(), &options, fake_trace).expect("the batch runs");
        assert_eq!(summary.done, FILES);
    });
}

/// The engine's own cost per file (stat, write, flush to disk, rename), with a processor that
/// does nothing: what the real tracer's time is added to.
#[divan::bench(args = [1, 2], sample_count = 5, sample_size = 1)]
fn run_batch_200_files_no_work(bencher: Bencher, jobs: usize) {
    let input = input_tree();
    let output = tempfile::tempdir().expect("a temporary folder");
    let options = BatchOptions {
        recursive: true,
        jobs: Some(jobs),
        force: true,
        quiet: true,
        ..BatchOptions::default()
    };
    let discovery =
        discover_inputs(&[input.path().to_path_buf()], &options).expect("the inputs are found");
    bencher.counter(ItemsCount::new(FILES)).bench(|| {
        run_batch(&discovery, output.path(), &options, |_| {
            Ok(FileResult {
                svg: b"<svg xmlns=\"http://www.w3.org/2000/svg\"/>".to_vec(),
                curves: 0,
                closed_curves: 0,
            })
        })
        .expect("the batch runs")
    });
}

#[divan::bench(sample_count = 20)]
fn fake_trace_one_file(bencher: Bencher) {
    let input = input_tree();
    let file = input.path().join("group-0").join("scan-000.png");
    bencher.bench(|| fake_trace(&file));
}
