//! Prints the ground-truth table of `docs/results.md`: every sample in `samples/` traced with the stroke-aware
//! crawl (default), the paper's plain crawl (`--method paper`) and the robust point-set crawl on
//! all samples (`--method points`), each scored against the
//! sample's true curves (`<name>.truth.svg`) by `tests/support`'s matcher: a true curve counts
//! when exactly one output path has its closedness and lies within pen width / 2 + 2 px of it
//! (symmetric Hausdorff distance).
//!
//! Run: `cargo run --release --example ground_truth [SAMPLES_FOLDER]`

#[path = "../tests/support/mod.rs"]
mod support;

use std::path::{Path, PathBuf};

use crawltrace::stages::decode;
use crawltrace::{to_svg, trace, Method, TraceOptions};

/// How one method did on one sample.
struct Score {
    matched: usize,
    extra: usize,
    worst_distance: f64,
}

fn score(image: &Path, truth_svg: &str, method: Method) -> Score {
    let truth = support::load_curves(truth_svg);
    let pen = support::load_stroke_width(truth_svg).unwrap_or(3.0);
    let bytes = std::fs::read(image).expect("sample is readable");
    let picture = decode::decode_image(&bytes).expect("sample decodes");
    let options = TraceOptions {
        method,
        ..TraceOptions::default()
    };
    let output = match trace(&picture, &options) {
        Ok(traced) => support::load_curves(&to_svg(&traced.drawing)),
        Err(_) => Vec::new(),
    };
    let report = support::match_curves(&truth, &output, pen / 2.0 + 2.0);
    let matched: Vec<_> = report
        .curves
        .iter()
        .filter(|c| c.matched.is_some())
        .collect();
    Score {
        matched: matched.len(),
        extra: report.unmatched_outputs.len(),
        worst_distance: matched
            .iter()
            .filter_map(|c| c.nearest.map(|n| n.distance))
            .fold(0.0, f64::max),
    }
}

fn main() {
    let folder = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("samples"));
    let mut samples: Vec<PathBuf> = std::fs::read_dir(&folder)
        .unwrap_or_else(|e| panic!("{}: {e}", folder.display()))
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|path| {
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
            crawltrace::batch::is_image_path(path) && !name.starts_with("page-")
        })
        .collect();
    samples.sort();
    println!("| sample | true curves (closed) | stroke-aware crawl: matched, extra paths, worst px | paper's crawl: matched, extra paths | robust point crawl: matched, extra paths |");
    println!("|---|---|---|---|---|");
    let (mut total, mut strokes_ok, mut points_ok, mut robust_ok) = (0, 0, 0, 0);
    let (mut curves, mut strokes_curves, mut points_curves, mut robust_curves) = (0, 0, 0, 0);
    for image in &samples {
        let truth_path = image.with_extension("truth.svg");
        let Ok(truth_svg) = std::fs::read_to_string(&truth_path) else {
            continue;
        };
        let truth = support::load_curves(&truth_svg);
        let closed = truth.iter().filter(|c| c.closed).count();
        let strokes = score(image, &truth_svg, Method::Strokes);
        let points = score(image, &truth_svg, Method::Paper);
        let robust = score(image, &truth_svg, Method::Points);
        let mark = |s: &Score| {
            if s.matched == truth.len() && s.extra == 0 {
                "✔"
            } else {
                "✘"
            }
        };
        println!(
            "| {} | {} ({}) | {} {}/{}, {}, {:.1} | {} {}/{}, {} | {} {}/{}, {} |",
            image.file_name().unwrap().to_string_lossy(),
            truth.len(),
            closed,
            mark(&strokes),
            strokes.matched,
            truth.len(),
            strokes.extra,
            strokes.worst_distance,
            mark(&points),
            points.matched,
            truth.len(),
            points.extra,
            mark(&robust),
            robust.matched,
            truth.len(),
            robust.extra,
        );
        total += 1;
        curves += truth.len();
        strokes_curves += strokes.matched;
        points_curves += points.matched;
        strokes_ok += usize::from(strokes.matched == truth.len() && strokes.extra == 0);
        points_ok += usize::from(points.matched == truth.len() && points.extra == 0);
        robust_curves += robust.matched;
        robust_ok += usize::from(robust.matched == truth.len() && robust.extra == 0);
    }
    println!(
        "| **all** | {curves} | {strokes_ok}/{total} samples, {strokes_curves}/{curves} curves | {points_ok}/{total} samples, {points_curves}/{curves} curves | {robust_ok}/{total} samples, {robust_curves}/{curves} curves |"
    );
}
