//! Large and degenerate point sets (100 000 points each): collinear, on a lattice (everything
//! cocircular), mostly duplicates, a cluster far smaller than its coordinates, uniform noise, and
//! many sampled curves. None may panic; each must keep the structural invariants, and those with
//! a known answer must give it. Speed is measured in `benches/reconstruct.rs`, not here.

use crate::support::random::SplitMix64;
use std::collections::BTreeSet;
use std::f64::consts::TAU;

use crawltrace::{reconstruct, Point, Reconstruction};

const COUNT: usize = 100_000;

/// Every point is on at most one curve, once; curves have at least three points (four if
/// closed); curves, outliers and merged duplicates together account for every input point.
fn check_structure(what: &str, count: usize, result: &Reconstruction) {
    let mut seen = vec![false; count];
    let mut mark = |index: usize, role: &str| {
        assert!(
            !seen[index],
            "{what}: point {index} appears again as {role}"
        );
        seen[index] = true;
    };
    for curve in &result.curves {
        let minimum = if curve.closed { 4 } else { 3 };
        assert!(
            curve.indices.len() >= minimum,
            "{what}: a curve of {} points",
            curve.indices.len()
        );
        for &index in &curve.indices {
            mark(index, "a curve point");
        }
    }
    for &index in &result.outliers {
        mark(index, "an outlier");
    }
    for duplicate in &result.merged_duplicates {
        mark(duplicate.dropped, "a merged duplicate");
    }
    assert!(
        seen.iter().all(|&s| s),
        "{what}: some point is unaccounted for"
    );
}

#[test]
fn evenly_spaced_collinear_points_make_one_open_curve_in_order() {
    let mut random = SplitMix64::new(1);
    let mut steps: Vec<usize> = (0..COUNT).collect();
    random.shuffle(&mut steps);
    let points: Vec<Point> = steps
        .iter()
        .map(|&k| Point::new(3.0 * k as f64, -2.0 * k as f64))
        .collect();
    let result = reconstruct(&points).unwrap();
    check_structure("collinear", COUNT, &result);
    assert_eq!(result.curves.len(), 1);
    let curve = &result.curves[0];
    assert!(!curve.closed);
    let along: Vec<usize> = curve.indices.iter().map(|&i| steps[i]).collect();
    assert_eq!(along, (0..COUNT).collect::<Vec<_>>());
}

#[test]
fn a_lattice_where_everything_is_cocircular() {
    let side = (COUNT as f64).sqrt() as usize;
    let mut points: Vec<Point> = (0..side * side)
        .map(|k| Point::new((k % side) as f64, (k / side) as f64))
        .collect();
    SplitMix64::new(2).shuffle(&mut points);
    let result = reconstruct(&points).unwrap();
    check_structure("lattice", points.len(), &result);
}

#[test]
fn mostly_duplicates() {
    let mut random = SplitMix64::new(3);
    let points: Vec<Point> = (0..COUNT)
        .map(|_| {
            let k = random.next_u64() % 1000;
            Point::new((k % 40) as f64, (k / 40) as f64 * 0.5)
        })
        .collect();
    let result = reconstruct(&points).unwrap();
    check_structure("duplicates", COUNT, &result);
    let distinct: BTreeSet<(u64, u64)> = points
        .iter()
        .map(|p| (p.x.to_bits(), p.y.to_bits()))
        .collect();
    assert_eq!(result.merged_duplicates.len(), COUNT - distinct.len());
}

#[test]
fn a_cluster_far_smaller_than_its_coordinates() {
    let mut random = SplitMix64::new(4);
    let points: Vec<Point> = (0..COUNT)
        .map(|_| Point::new(1e6 + random.unit() * 1e-4, -1e6 + random.unit() * 1e-4))
        .collect();
    let result = reconstruct(&points).unwrap();
    check_structure("cluster", COUNT, &result);
}

#[test]
fn uniform_noise_at_extreme_scales() {
    for scale in [1e-30, 1.0, 1e55] {
        let mut random = SplitMix64::new(5);
        let points: Vec<Point> = (0..COUNT / 4)
            .map(|_| Point::new(random.unit() * scale, random.unit() * scale))
            .collect();
        let result = reconstruct(&points).unwrap();
        check_structure(&format!("noise at scale {scale:e}"), points.len(), &result);
    }
}

#[test]
fn many_sampled_circles_come_back_as_closed_curves() {
    // Circles of 100 to 400 points, evenly spaced up to ±15 % jitter along the arc, each in its
    // own cell: dense, well-separated samples the paper's theorem covers.
    let mut random = SplitMix64::new(6);
    let mut points = Vec::with_capacity(COUNT);
    let mut circles = Vec::new();
    let columns = 25;
    while points.len() < COUNT {
        let size = (100 + random.next_u64() % 301) as usize;
        let size = size.min(COUNT - points.len()).max(8);
        let cell = circles.len();
        let centre = (3.0 * (cell % columns) as f64, 3.0 * (cell / columns) as f64);
        // Cells are 3 apart and radii below 1.2: neighbouring circles stay 0.6 apart, 8 spacings.
        let radius = 0.5 + 0.7 * random.unit();
        let start = points.len();
        for k in 0..size {
            let angle = TAU * (k as f64 + 0.15 * (2.0 * random.unit() - 1.0)) / size as f64;
            points.push(Point::new(
                centre.0 + radius * angle.cos(),
                centre.1 + radius * angle.sin(),
            ));
        }
        circles.push(start..points.len());
    }
    let result = reconstruct(&points).unwrap();
    check_structure("circles", points.len(), &result);
    assert!(result.outliers.is_empty());
    assert_eq!(result.curves.len(), circles.len());
    for curve in &result.curves {
        assert!(curve.closed);
        let circle = circles
            .iter()
            .find(|range| range.contains(&curve.indices[0]))
            .unwrap();
        let mut sorted = curve.indices.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, circle.clone().collect::<Vec<_>>());
    }
}

/// A 1000 × 1000 page of 2 × 2 px specks covering 5 % of it, traced with the default options.
/// Before the fit stage had its own bounded fitter, `kurbo::simplify_bezpath` never returned on
/// this page (kurbo issue #602): the test would hang instead of passing.
#[test]
fn a_page_of_specks_is_traced_not_hung() {
    let (width, height) = (1000u32, 1000u32);
    let mut page = image::GrayImage::from_pixel(width, height, image::Luma([255]));
    let mut random = SplitMix64::new(1);
    let specks = (width * height) as usize * 5 / 100 / 4;
    for _ in 0..specks {
        let x = (random.next_u64() % u64::from(width - 2)) as u32;
        let y = (random.next_u64() % u64::from(height - 2)) as u32;
        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            page.put_pixel(x + dx, y + dy, image::Luma([0]));
        }
    }
    let traced = crawltrace::trace(
        &image::DynamicImage::ImageLuma8(page),
        &crawltrace::TraceOptions::default(),
    )
    .expect("the specks are ink");
    assert!(!traced.drawing.paths.is_empty());
}
