//! Benchmarks of batch tracing, 200 files through `run_batch` on 1 and 2 worker threads, to show
//! how throughput scales with `jobs`:
//! - with the real tracer (`trace_file_to_document`, what `crawltrace trace` runs per file) on 200
//!   one-megapixel skip-stroke drawings, generated once from a fixed seed before any timing;
//! - with a CPU-bound fake processor (about 5 ms of hashing a file), which measures the engine
//!   alone, and with a processor that does nothing (the engine's own cost per file).
//!
//! The allocator settings of the binary (`src/bin/crawltrace/allocator.rs`) are applied as in
//! `crawltrace`. What they bring does not show here even without them: generating the drawings
//! frees large blocks first, which raises glibc's adaptive thresholds before any timing. It shows
//! on the binary (see that file).
//!
//! Run: `cargo bench --bench batch` (only the real tracer: `cargo bench --bench batch -- real`).
//!
//! Measured 2026-11 on the 2-core development machine (1-minute load 0.4–1.1 at the start, other
//! engineers' work in the background), four runs, mean throughput of the real tracer: 111–132
//! drawings/s at jobs=1 and 202–251 at jobs=2, jobs=2 1.82–1.90× jobs=1 (best quiet run 129.5 →
//! 244.3, 1.89×). One drawing takes about 6.7 ms to read, decode and trace; the engine adds about
//! 0.6 ms per file (mostly flushing the output to disk: `run_batch_200_files_no_work`).

#[path = "../tests/support/random.rs"]
mod random;
use random::SplitMix64;

use std::fs;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use crawltrace::batch::{
    discover_inputs, fnv1a_64, run_batch, trace_file_to_document, BatchOptions, Discovery,
    FileResult,
};
use crawltrace::{ExportOptions, TraceOptions};
use divan::counter::ItemsCount;
use divan::Bencher;
use image::{DynamicImage, ImageFormat};

const FILES: usize = 200;
/// Hashing this many bytes takes about 5 ms on the 2-core development machine (see the
/// `fake_trace_one_file` benchmark), the order of a small drawing through the real tracer.
const WORK_BYTES: usize = 64 * 1024;
const WORK_ROUNDS: usize = 56;

/// Side of the generated drawings, in pixels: 1000 × 1000 is one megapixel.
const DRAWING_SIDE: u32 = 1000;

/// The generated drawings, made on first use and deleted when the benchmarks end.
static DRAWINGS: Mutex<Option<tempfile::TempDir>> = Mutex::new(None);

#[path = "../src/bin/crawltrace/allocator.rs"]
mod allocator;

fn main() {
    allocator::keep_freed_memory_for_reuse();
    divan::main();
    // A `TempDir` in a static is never dropped on its own.
    drop(DRAWINGS.lock().map(|mut drawings| drawings.take()));
}

/// One skip-stroke drawing as SVG: three or four shapes (circle, ellipse, rounded rectangle,
/// open wave), each in its own quarter of the page so that they do not cross, drawn with dashes
/// (the strokes and gaps of a sketch) of a pen width, dash and gap picked by `random`.
fn drawing_svg(random: &mut SplitMix64) -> String {
    let quarter = f64::from(DRAWING_SIDE) / 2.0;
    let mut shapes = String::new();
    let skipped_quarter = (random.next_u64() % 5) as usize; // 4: all four quarters are drawn
    for quarter_index in (0..4).filter(|&index| index != skipped_quarter) {
        let left = quarter * (quarter_index % 2) as f64;
        let top = quarter * (quarter_index / 2) as f64;
        // Centre and size inside the quarter, with a margin for the pen.
        let size = random.range(0.25, 0.42) * quarter;
        let cx = left + quarter / 2.0 + random.range(-0.5, 0.5) * (quarter / 2.0 - size);
        let cy = top + quarter / 2.0 + random.range(-0.5, 0.5) * (quarter / 2.0 - size);
        let pen = random.range(3.0, 6.0);
        let dash = random.range(18.0, 40.0);
        let gap = random.range(5.0, 10.0);
        let style = format!(
            r#"fill="none" stroke="black" stroke-width="{pen:.1}" stroke-linecap="round" stroke-dasharray="{dash:.1} {gap:.1}""#
        );
        let shape = match random.next_u64() % 4 {
            0 => format!(r#"<circle cx="{cx:.1}" cy="{cy:.1}" r="{size:.1}" {style}/>"#),
            1 => format!(
                r#"<ellipse cx="{cx:.1}" cy="{cy:.1}" rx="{size:.1}" ry="{:.1}" {style}/>"#,
                size * random.range(0.45, 0.9)
            ),
            2 => format!(
                r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" rx="{:.1}" {style}/>"#,
                cx - size,
                cy - size * 0.7,
                2.0 * size,
                1.4 * size,
                random.range(0.0, 0.3) * size
            ),
            _ => format!(
                r#"<path d="M{:.1} {cy:.1} C{:.1} {:.1} {:.1} {:.1} {cx:.1} {cy:.1} S{:.1} {:.1} {:.1} {cy:.1}" {style}/>"#,
                cx - size,
                cx - size / 2.0,
                cy - size * random.range(0.3, 0.9),
                cx - size / 4.0,
                cy + size * random.range(0.3, 0.9),
                cx + size / 2.0,
                cy - size * random.range(0.3, 0.9),
                cx + size
            ),
        };
        shapes.push_str(&shape);
    }
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{DRAWING_SIDE}" height="{DRAWING_SIDE}"><rect width="100%" height="100%" fill="white"/>{shapes}</svg>"#
    )
}

/// The folder of the 200 generated drawings (PNG, 8-bit gray, in 10 subfolders), made on first
/// use from a fixed seed: every run of the benchmark traces the same pictures.
fn drawings() -> PathBuf {
    let mut drawings = DRAWINGS.lock().expect("no benchmark panicked");
    let folder = drawings.get_or_insert_with(|| {
        let root = tempfile::tempdir().expect("a temporary folder");
        let mut random = SplitMix64::new(2016);
        for index in 0..FILES {
            let svg = drawing_svg(&mut random);
            let rgba = crawltrace::render_svg(&svg, 1.0).expect("the drawing renders");
            let folder = root.path().join(format!("group-{}", index % 10));
            fs::create_dir_all(&folder).expect("a subfolder");
            DynamicImage::ImageRgba8(rgba)
                .into_luma8()
                .save_with_format(
                    folder.join(format!("drawing-{index:03}.png")),
                    ImageFormat::Png,
                )
                .expect("the drawing saves");
        }
        root
    });
    folder.path().to_path_buf()
}

/// The options of `crawltrace trace IN -o OUT -r --force -q` on `jobs` threads. `force`: every
/// sample redoes every file instead of finding them up to date.
fn every_file_again(jobs: usize) -> BatchOptions {
    BatchOptions {
        recursive: true,
        jobs: Some(jobs),
        force: true,
        quiet: true,
        ..BatchOptions::default()
    }
}

/// The `FILES` inputs below `folder`, found as the batch finds them.
fn discover_all(folder: &Path, options: &BatchOptions) -> Discovery {
    let discovery =
        discover_inputs(&[folder.to_path_buf()], options).expect("the inputs are found");
    assert_eq!(discovery.inputs.len(), FILES);
    discovery
}

/// 200 one-megapixel drawings traced and written as `crawltrace trace IN -o OUT -r --force -q`
/// would, on `jobs` threads.
#[divan::bench(args = [1, 2], sample_count = 3, sample_size = 1)]
fn real_tracer_200_drawings_of_1_megapixel(bencher: Bencher, jobs: usize) {
    let input = drawings();
    let output = tempfile::tempdir().expect("a temporary folder");
    let options = every_file_again(jobs);
    let trace_options = TraceOptions::default();
    let discovery = discover_all(&input, &options);
    bencher.counter(ItemsCount::new(FILES)).bench(|| {
        let summary = run_batch(&discovery, output.path(), &options, |path| {
            trace_file_to_document(path, &trace_options, &ExportOptions::default())
        })
        .expect("the batch runs");
        assert_eq!(summary.done, FILES, "every drawing traces");
    });
}

/// One of the drawings through the real tracer, on one thread, without writing: the time a
/// worker spends per file.
#[divan::bench(sample_count = 20)]
fn real_tracer_one_drawing(bencher: Bencher) {
    let file = drawings().join("group-0").join("drawing-000.png");
    let trace_options = TraceOptions::default();
    bencher.bench(|| {
        trace_file_to_document(&file, &trace_options, &ExportOptions::default()).expect("it traces")
    });
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
        bytes: format!("<svg xmlns=\"http://www.w3.org/2000/svg\"><!-- {hash:016x} --></svg>")
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
    let options = every_file_again(jobs);
    let discovery = discover_all(input.path(), &options);
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
    let options = every_file_again(jobs);
    let discovery = discover_all(input.path(), &options);
    bencher.counter(ItemsCount::new(FILES)).bench(|| {
        run_batch(&discovery, output.path(), &options, |_| {
            Ok::<_, std::convert::Infallible>(FileResult {
                bytes: b"<svg xmlns=\"http://www.w3.org/2000/svg\"/>".to_vec(),
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
