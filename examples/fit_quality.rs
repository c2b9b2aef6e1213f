//! Measures how smooth and how close the fitted paths are (issue 8's fitting): traces every
//! drawing with a truth file in the given folders (the benchmark's, or `samples/`), matches the
//! output to the truth with `tests/support`'s matcher (pen width / 2 + 2 px), and prints, over
//! the matched curves: the number of path elements written, the mean distance from the output
//! to its true curve, and how much the output turns against the truth at the pen-width scale
//! (both resampled every pen width, |turn| summed; 1.0 means no wobble beyond the truth's own).
//!
//! Run: `cargo run --release --example fit_quality -- /tmp/fit/dev [samples]`

#[path = "../tests/support/mod.rs"]
mod support;

use std::path::{Path, PathBuf};

use crawltrace::stages::decode;
use crawltrace::{to_svg, trace, TraceOptions};
use kurbo::{Line, ParamCurveNearest, Point};
use support::Polyline;

/// Output points are taken this far apart (px) for the distance to the truth.
const DISTANCE_STEP_PX: f64 = 1.0;

/// Totals over the matched curves.
#[derive(Default)]
struct Totals {
    drawings: usize,
    curves: usize,
    elements: usize,
    distance_sum: f64,
    distance_points: usize,
    output_turn: f64,
    truth_turn: f64,
}

fn main() {
    let folders: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    if folders.is_empty() {
        eprintln!("usage: fit_quality FOLDER...");
        std::process::exit(2);
    }
    let mut totals = Totals::default();
    for (image, truth) in folders.iter().flat_map(|f| drawings(f)) {
        measure(&image, &truth, &mut totals);
    }
    println!(
        "{} drawings, {} matched curves, {} path elements; mean distance to the truth {:.3} px; \
         turning output / truth at the pen-width scale {:.3}",
        totals.drawings,
        totals.curves,
        totals.elements,
        totals.distance_sum / totals.distance_points.max(1) as f64,
        totals.output_turn / totals.truth_turn
    );
}

/// Every image in `folder` with a `NAME.truth.svg` beside it, sorted (the 12-megapixel page
/// left out: it is for timing).
fn drawings(folder: &Path) -> Vec<(PathBuf, PathBuf)> {
    let listing = std::fs::read_dir(folder)
        .unwrap_or_else(|e| panic!("{}: {e}", folder.display()))
        .filter_map(|entry| entry.ok().map(|e| e.path()));
    let mut images: Vec<PathBuf> = listing
        .filter(|p| crawltrace::batch::is_image_path(p))
        .filter(|p| !p.to_string_lossy().contains("page-4000x3000"))
        .collect();
    images.sort();
    images
        .into_iter()
        .filter_map(|image| {
            let stem = image.file_stem()?.to_string_lossy().into_owned();
            let truth = image.with_file_name(format!("{stem}.truth.svg"));
            truth.exists().then_some((image, truth))
        })
        .collect()
}

fn measure(image: &Path, truth_file: &Path, totals: &mut Totals) {
    let truth_svg = std::fs::read_to_string(truth_file).expect("the truth reads");
    let truth = support::load_curves(&truth_svg);
    let pen = support::load_stroke_width(&truth_svg).unwrap_or(3.0);
    let bytes = std::fs::read(image).expect("the image reads");
    let picture = decode::decode_image(&bytes).expect("the image decodes");
    totals.drawings += 1;
    let Ok(traced) = trace(&picture, &TraceOptions::default()) else {
        return;
    };
    totals.elements += traced
        .drawing
        .paths
        .iter()
        .map(|p| p.path.elements().len())
        .sum::<usize>();
    let output = support::load_curves(&to_svg(&traced.drawing));
    let report = support::match_curves(&truth, &output, pen / 2.0 + 2.0);
    for curve in &report.curves {
        let Some(matched) = curve.matched else {
            continue;
        };
        let (true_curve, output_curve) = (&truth[curve.truth], &output[matched]);
        let reference = resample(true_curve, DISTANCE_STEP_PX);
        let points = resample(output_curve, DISTANCE_STEP_PX);
        if reference.len() < 3 || points.len() < 3 {
            // A dot: nothing to turn.
            continue;
        }
        for q in points {
            totals.distance_sum += distance_to_chain(q, &reference);
            totals.distance_points += 1;
        }
        let scale = pen.max(1.0);
        totals.output_turn += total_turn(&resample(output_curve, scale));
        totals.truth_turn += total_turn(&resample(true_curve, scale));
        totals.curves += 1;
    }
}

/// Points every `step` along the curve (its closing segment included), from its start.
fn resample(curve: &Polyline, step: f64) -> Vec<Point> {
    let mut points = curve.points.clone();
    if curve.closed && !points.is_empty() {
        points.push(points[0]);
    }
    let mut out: Vec<Point> = points.first().copied().into_iter().collect();
    let mut to_next = step;
    for pair in points.windows(2) {
        let length = pair[0].distance(pair[1]);
        let mut at = to_next;
        while at <= length {
            out.push(pair[0].lerp(pair[1], at / length));
            at += step;
        }
        to_next = at - length;
    }
    out
}

/// The sum of the absolute turns at the inner points, in radians.
fn total_turn(points: &[Point]) -> f64 {
    points
        .windows(3)
        .map(|w| {
            let (a, b) = (w[1] - w[0], w[2] - w[1]);
            a.cross(b).atan2(a.dot(b)).abs()
        })
        .sum()
}

fn distance_to_chain(q: Point, chain: &[Point]) -> f64 {
    chain
        .windows(2)
        .map(|w| Line::new(w[0], w[1]).nearest(q, 1e-9).distance_sq)
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}
