//! Scores crawltrace on the generalization benchmark (issue 8): traces every drawing of a folder
//! written by `make_bench` with the library's default options, judges each against its
//! `NAME.truth.svg` with `tests/support/bench.rs` (exactly one path per true curve, of its
//! closedness, within jitter + pen / 2 + 2 px by symmetric Hausdorff distance; dots kept as
//! dots; nothing extra), and prints Markdown tables: pass rate per family × style, the count of
//! each failure reason, the largest distance of any output path from the truth, and the time.
//! `--sheet` draws the failures on contact sheets, `--json` writes one line per drawing.
//!
//! Run: `cargo run --release --example bench_score -- DIR [--method strokes|points|both]
//! [--sheet failures.png] [--json results.jsonl] [--filter FAMILY]`

#[path = "bench_score/sheet.rs"]
mod sheet;
#[path = "../tests/support/mod.rs"]
mod support;
#[path = "bench_score/table.rs"]
mod table;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, ValueEnum};
use crawltrace::stages::decode;
use crawltrace::{to_svg, trace, Method, TraceOptions};
use rayon::prelude::*;

use support::bench::{load_bench_truth, score_drawing, BenchTruth, DrawingScore};
use support::Polyline;

/// Traces every benchmark drawing in DIR and scores it against its ground truth.
#[derive(Parser)]
struct Arguments {
    /// The benchmark folder (written by `make_bench`).
    dir: PathBuf,
    /// The crawl to measure: the stroke-aware default, the paper's crawl, or both.
    #[arg(long, value_enum, default_value_t = Which::Strokes)]
    method: Which,
    /// Draw the failures on contact sheets: PATH becomes PATH-1.png, PATH-2.png, … (with
    /// `--method both`, PATH-strokes-1.png, PATH-points-1.png, …).
    #[arg(long)]
    sheet: Option<PathBuf>,
    /// Write one JSON line per drawing and method.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Only the drawings of these families (comma-separated names).
    #[arg(long)]
    filter: Option<String>,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Which {
    Strokes,
    Points,
    Both,
}

/// One drawing of the benchmark.
pub struct Entry {
    pub name: String,
    pub image: PathBuf,
    pub truth: BenchTruth,
}

/// One drawing traced and judged.
pub struct Outcome {
    pub output: Vec<Polyline>,
    pub score: DrawingScore,
    pub seconds: f64,
    /// Why the drawing could not be traced, if it could not.
    pub error: Option<String>,
}

fn main() -> ExitCode {
    let arguments = Arguments::parse();
    match run(&arguments) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

/// Returns whether every drawing could be read.
fn run(arguments: &Arguments) -> Result<bool, String> {
    let (entries, unreadable) = load_entries(&arguments.dir, arguments.filter.as_deref())?;
    if entries.is_empty() {
        return Err(format!(
            "{}: no benchmark drawing (an image with its NAME.truth.svg){}",
            arguments.dir.display(),
            arguments
                .filter
                .as_ref()
                .map(|f| format!(" of family {f}"))
                .unwrap_or_default()
        ));
    }
    let methods: &[(Method, &str)] = match arguments.method {
        Which::Strokes => &[(Method::Strokes, "strokes")],
        Which::Points => &[(Method::Points, "points")],
        Which::Both => &[(Method::Strokes, "strokes"), (Method::Points, "points")],
    };
    let mut json_lines = Vec::new();
    for &(method, label) in methods {
        let started = Instant::now();
        let outcomes: Vec<Outcome> = entries
            .par_iter()
            .map(|e| trace_and_score(e, method))
            .collect();
        let wall = started.elapsed().as_secs_f64();
        println!("{}", table::report(label, &entries, &outcomes, wall));
        json_lines.extend(
            entries
                .iter()
                .zip(&outcomes)
                .map(|(entry, outcome)| table::json_line(label, entry, outcome)),
        );
        if let Some(path) = &arguments.sheet {
            let suffix = if methods.len() > 1 { Some(label) } else { None };
            let pages = sheet::write_sheets(path, suffix, label, &entries, &outcomes)?;
            for page in pages {
                println!("contact sheet: {}", page.display());
            }
        }
    }
    if let Some(path) = &arguments.json {
        let mut text = json_lines.join("\n");
        text.push('\n');
        std::fs::write(path, text).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    Ok(unreadable == 0)
}

/// Every image in `folder` with a truth file beside it, sorted by name; unreadable truth files
/// are reported (one line each) and counted.
fn load_entries(folder: &Path, filter: Option<&str>) -> Result<(Vec<Entry>, usize), String> {
    let listing = std::fs::read_dir(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    let mut images: Vec<PathBuf> = listing
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|path| crawltrace::batch::is_image_path(path))
        .collect();
    images.sort();
    let families: Option<Vec<&str>> = filter.map(|f| f.split(',').map(str::trim).collect());
    let mut entries = Vec::new();
    let mut unreadable = 0;
    for image in images {
        let name = image
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        let truth_path = image.with_file_name(format!("{name}.truth.svg"));
        let Ok(text) = std::fs::read_to_string(&truth_path) else {
            continue;
        };
        match load_bench_truth(&text) {
            Ok(truth) => {
                if families
                    .as_ref()
                    .is_none_or(|names| names.contains(&truth.family.as_str()))
                {
                    entries.push(Entry { name, image, truth });
                }
            }
            Err(problem) => {
                eprintln!("error: {}: {problem}", truth_path.display());
                unreadable += 1;
            }
        }
    }
    Ok((entries, unreadable))
}

fn trace_and_score(entry: &Entry, method: Method) -> Outcome {
    let started = Instant::now();
    let options = TraceOptions {
        method,
        ..TraceOptions::default()
    };
    let traced = std::fs::read(&entry.image)
        .map_err(|e| e.to_string())
        .and_then(|bytes| decode::decode_image(&bytes).map_err(|e| e.to_string()))
        .and_then(|picture| trace(&picture, &options).map_err(|e| e.to_string()));
    let seconds = started.elapsed().as_secs_f64();
    let (output, error) = match traced {
        Ok(traced) => (support::load_curves(&to_svg(&traced.drawing)), None),
        Err(error) => (Vec::new(), Some(error)),
    };
    let score = score_drawing(&entry.truth, &output);
    Outcome {
        output,
        score,
        seconds,
        error,
    }
}
