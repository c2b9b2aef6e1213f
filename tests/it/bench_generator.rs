//! The benchmark generator (`examples/make_bench`): deterministic to the byte, every truth file
//! reads with the scorer's loader and agrees with the manifest, and the ink of every drawing lies
//! along its truth. One drawing of each family, the styles taken in turn, so it stays fast.

#![allow(dead_code)]

// `drawing` and `families` are also used by `fit_property`, in this same test binary.
#[path = "../../examples/make_bench/drawing.rs"]
pub(crate) mod drawing;
#[path = "../../examples/make_bench/families.rs"]
pub(crate) mod families;
#[path = "../../examples/make_bench/figure.rs"]
mod figure;
#[path = "../../examples/make_samples/geometry.rs"]
mod geometry;
#[path = "../../examples/make_bench/objects.rs"]
mod objects;
#[path = "../../examples/make_samples/paper.rs"]
mod paper;
#[path = "../../examples/make_bench/pen.rs"]
mod pen;
#[path = "../../examples/make_samples/random.rs"]
mod random;
#[path = "../../examples/make_bench/shapes.rs"]
mod shapes;
#[path = "../../examples/make_samples/sketch.rs"]
mod sketch;
use crate::support;
#[path = "../../examples/make_bench/touching.rs"]
mod touching;

use crawltrace::render_svg;
use crawltrace::{to_svg, CurvePath, Drawing};
use support::bench::{load_bench_truth, BenchTruth};

/// Ink may lie this far beyond the tolerance band of the truth (antialiasing, round caps).
const INK_MARGIN: f64 = 1.5;
/// At most this share of the dark pixels may lie outside that band.
const STRAY_INK_ALLOWED: f64 = 0.002;

/// One drawing of every family: (family, style, number), styles in turn.
fn sample_jobs() -> Vec<(usize, usize, usize)> {
    (0..families::FAMILIES.len())
        .map(|family| (family, family % families::STYLES.len(), family / 7))
        .collect()
}

fn generate((family, style, index): (usize, usize, usize), seed: u64) -> drawing::Generated {
    drawing::generate(family, families::STYLES[style], style, index, seed)
}

#[test]
fn the_generator_is_deterministic_and_seeds_differ() {
    for job in sample_jobs().into_iter().step_by(5) {
        let (first, second) = (generate(job, 1), generate(job, 1));
        assert_eq!(first.name, second.name);
        assert!(
            first.image == second.image,
            "{}: image bytes differ",
            first.name
        );
        assert_eq!(first.truth, second.truth, "{}", first.name);
        assert_eq!(first.manifest, second.manifest, "{}", first.name);
        let other_split = generate(job, 2);
        assert_ne!(
            first.truth, other_split.truth,
            "{}: seed 2 repeats seed 1",
            first.name
        );
    }
}

#[test]
fn every_truth_reads_and_agrees_with_the_manifest_and_the_ink() {
    let mut failures = Vec::new();
    for job in sample_jobs() {
        let generated = generate(job, 1);
        let name = &generated.name;
        let truth = load_bench_truth(&generated.truth)
            .unwrap_or_else(|e| panic!("{name}: truth does not read: {e}"));
        let manifest: serde_json::Value =
            serde_json::from_str(&generated.manifest).expect("manifest line is JSON");
        assert_eq!(manifest["family"], truth.family.as_str(), "{name}");
        assert_eq!(manifest["style"], truth.style.as_str(), "{name}");
        assert_eq!(manifest["curves"], truth.curves.len(), "{name}");
        assert_eq!(manifest["dots"], truth.dots.len(), "{name}");
        let closed = truth.curves.iter().filter(|c| c.closed).count();
        assert_eq!(manifest["closed_curves"], closed, "{name}");
        assert!(
            !truth.curves.is_empty() || !truth.dots.is_empty(),
            "{name}: nothing to find"
        );
        assert!(
            (0.0..=1.5).contains(&truth.jitter) && (1.75..=7.0).contains(&truth.pen),
            "{name}: pen {} jitter {}",
            truth.pen,
            truth.jitter
        );
        let picture = image::load_from_memory(&generated.image).expect("the image decodes");
        let size = (
            manifest["width"].as_u64().unwrap(),
            manifest["height"].as_u64().unwrap(),
        );
        assert_eq!(
            (u64::from(picture.width()), u64::from(picture.height())),
            size,
            "{name}"
        );
        assert!(
            (300..=1000).contains(&size.0) && (300..=1000).contains(&size.1),
            "{name}: page {size:?}"
        );
        if truth.style != "scan" {
            if let Some(problem) = stray_ink(&truth, &picture.to_luma8()) {
                failures.push(format!("{name}: {problem}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Dark pixels far from every true curve and dot, if there are too many.
fn stray_ink(truth: &BenchTruth, gray: &image::GrayImage) -> Option<String> {
    let reach = truth.pen / 2.0 + truth.jitter + INK_MARGIN;
    let mut paths: Vec<CurvePath> = truth
        .curves
        .iter()
        .map(|c| CurvePath::polyline(&c.points, c.closed))
        .collect();
    let mut band_width = 2.0 * reach;
    for dot in &truth.dots {
        let mut path = kurbo::BezPath::new();
        path.move_to(dot.centre);
        path.line_to(dot.centre);
        paths.push(CurvePath {
            stroke_width: None,
            path,
            closed: false,
        });
        band_width = band_width.max(dot.diameter + 2.0 * INK_MARGIN);
    }
    let band = render_svg(
        &to_svg(&Drawing {
            width: f64::from(gray.width()),
            height: f64::from(gray.height()),
            paths,
            stroke_width: band_width,
            color: "black".into(),
            dots: Vec::new(),
            points: Vec::new(),
        }),
        1.0,
    )
    .expect("the band renders");
    let (mut dark, mut stray) = (0usize, 0usize);
    for (pixel, near) in gray.pixels().zip(band.pixels()) {
        if pixel.0[0] < 128 {
            dark += 1;
            stray += usize::from(near.0[0] == 255);
        }
    }
    let share = stray as f64 / dark.max(1) as f64;
    (dark == 0 || share > STRAY_INK_ALLOWED).then(|| {
        format!("{stray} of {dark} dark pixels lie farther than {reach:.1} px from the truth")
    })
}
