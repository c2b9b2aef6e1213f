//! Writes the generalization benchmark of issues 8 and 9 into a folder: skip-stroke drawings of
//! 18 families in four pen styles (PNG, JPEG for the scan style), each with its ground truth
//! `NAME.truth.svg`, and `manifest.jsonl` (one line per drawing). Deterministic: the same seed
//! gives byte-identical files. Seed 1 is the development split, seed 2 the validation split
//! (measure it, never tune on it); see `docs/benchmark.md`.
//!
//! Run: `cargo run --release --example make_bench -- DIR [--seed N] [--count-per-family K]`

#[path = "make_bench/drawing.rs"]
mod drawing;
#[path = "make_bench/families.rs"]
mod families;
#[path = "make_bench/figure.rs"]
mod figure;
#[path = "make_samples/geometry.rs"]
#[allow(dead_code)]
mod geometry;
#[path = "make_bench/objects.rs"]
mod objects;
#[path = "make_samples/paper.rs"]
#[allow(dead_code)]
mod paper;
#[path = "make_bench/pen.rs"]
mod pen;
#[path = "make_samples/random.rs"]
mod random;
#[path = "make_bench/shapes.rs"]
mod shapes;
#[path = "make_samples/sketch.rs"]
#[allow(dead_code)]
mod sketch;
#[path = "make_bench/touching.rs"]
mod touching;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use rayon::prelude::*;

/// Writes the benchmark drawings, their ground truth and manifest.jsonl into DIR.
#[derive(Parser)]
struct Arguments {
    /// Output folder (created if missing; files of the same names are replaced).
    dir: PathBuf,
    /// Split seed: 1 is the development split, 2 the validation split.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Drawings of each family in each of the four pen styles (18 families × 4 styles × K).
    #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u64).range(1..=999))]
    count_per_family: u64,
}

fn main() -> ExitCode {
    let arguments = Arguments::parse();
    match run(&arguments) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

fn run(arguments: &Arguments) -> Result<(), String> {
    let started = Instant::now();
    let folder = &arguments.dir;
    std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    let jobs: Vec<(usize, usize, usize)> = (0..families::FAMILIES.len())
        .flat_map(|family| {
            (0..families::STYLES.len()).flat_map(move |style| {
                (0..arguments.count_per_family as usize).map(move |index| (family, style, index))
            })
        })
        .collect();
    let manifest: Vec<String> = jobs
        .par_iter()
        .map(|&(family, style, index)| {
            let drawing = drawing::generate(
                family,
                families::STYLES[style],
                style,
                index,
                arguments.seed,
            );
            write(folder, &drawing.image_file, &drawing.image)?;
            write(
                folder,
                &format!("{}.truth.svg", drawing.name),
                drawing.truth.as_bytes(),
            )?;
            Ok(drawing.manifest)
        })
        .collect::<Result<_, String>>()?;
    let mut lines = manifest.join("\n");
    lines.push('\n');
    write(folder, "manifest.jsonl", lines.as_bytes())?;
    println!(
        "{}: {} drawings (seed {}), {:.1} s",
        folder.display(),
        manifest.len(),
        arguments.seed,
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Writes a whole file (a temporary file renamed into place, so no half-written file is left).
fn write(folder: &Path, name: &str, bytes: &[u8]) -> Result<(), String> {
    let path = folder.join(name);
    let temporary = folder.join(format!(".{name}.part"));
    std::fs::write(&temporary, bytes)
        .and_then(|()| std::fs::rename(&temporary, &path))
        .map_err(|e| format!("{}: cannot write: {e}", path.display()))
}
