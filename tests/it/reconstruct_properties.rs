//! Invariants of the crawls (the paper's, `crawltrace::reconstruct`, and the robust one,
//! `crawltrace::reconstruct_robust`) on seeded random point sets, and the paper's ε-sampling theorem:
//! densely sampled smooth closed curves come back exactly.
//!
//! Every input is made by a tiny SplitMix64 generator from a seed, so a failure names the seed that
//! reproduces it. Shapes are smooth parametric curves; their minimum radius of curvature and their
//! distances to each other are measured on a fine polyline, and the sampling density is chosen from
//! those measurements.

use crate::point_sets::edges_of;
use crate::support::random::SplitMix64;
use std::collections::{BTreeMap, BTreeSet};
use std::f64::consts::TAU;

use crawltrace::stages::crawl::neighbours::NeighbourGraph;
use crawltrace::{reconstruct, reconstruct_robust, Point, ReconstructError, Reconstruction};

/// A reconstruction method: the paper's crawl or the robust one.
type Method = fn(&[Point]) -> Result<Reconstruction, ReconstructError>;

/// Both methods, named for failure messages. Every property below holds for both.
const METHODS: [(&str, Method); 2] = [("paper", reconstruct), ("robust", reconstruct_robust)];

/// A smooth closed curve γ(t), t ∈ [0, 2π), with a fine polyline of it for measurements.
struct ClosedCurve {
    function: Box<dyn Fn(f64) -> (f64, f64)>,
    /// Parameters of the fine polyline, ending with 2π.
    table_parameters: Vec<f64>,
    /// Arc length from t = 0 to each table parameter.
    table_lengths: Vec<f64>,
    /// The fine polyline's points (the last equals the first).
    table_points: Vec<(f64, f64)>,
}

/// Fine polyline resolution used for measuring curves.
const TABLE_SIZE: usize = 2048;

impl ClosedCurve {
    fn new(function: impl Fn(f64) -> (f64, f64) + 'static) -> Self {
        let function: Box<dyn Fn(f64) -> (f64, f64)> = Box::new(function);
        let table_parameters: Vec<f64> = (0..=TABLE_SIZE)
            .map(|i| TAU * i as f64 / TABLE_SIZE as f64)
            .collect();
        let table_points: Vec<(f64, f64)> = table_parameters.iter().map(|&t| function(t)).collect();
        let mut table_lengths = vec![0.0];
        for pair in table_points.windows(2) {
            let length = table_lengths.last().unwrap() + distance(pair[0], pair[1]);
            table_lengths.push(length);
        }
        Self {
            function,
            table_parameters,
            table_lengths,
            table_points,
        }
    }

    fn length(&self) -> f64 {
        *self.table_lengths.last().unwrap()
    }

    /// The smallest radius of curvature, from the circumcircles of consecutive polyline triples.
    fn minimum_radius_of_curvature(&self) -> f64 {
        let points = &self.table_points[..TABLE_SIZE];
        (0..TABLE_SIZE)
            .map(|i| {
                circumradius(
                    points[(i + TABLE_SIZE - 1) % TABLE_SIZE],
                    points[i],
                    points[(i + 1) % TABLE_SIZE],
                )
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// A lower bound on the distance between this curve and `other`: the smallest distance
    /// between every 8th point of their fine polylines, less half the longest step between those
    /// points on each (debug builds are too slow for all pairs of the fine polylines).
    fn distance_to(&self, other: &ClosedCurve) -> f64 {
        const STRIDE: usize = 8;
        let coarse = |curve: &ClosedCurve| -> (Vec<(f64, f64)>, f64) {
            let points: Vec<(f64, f64)> =
                curve.table_points.iter().step_by(STRIDE).copied().collect();
            let longest_step = points
                .windows(2)
                .map(|pair| distance(pair[0], pair[1]))
                .fold(0.0, f64::max);
            (points, longest_step)
        };
        let ((mine, my_step), (theirs, their_step)) = (coarse(self), coarse(other));
        let mut best = f64::INFINITY;
        for &p in &mine {
            for &q in &theirs {
                best = best.min(distance(p, q));
            }
        }
        (best - (my_step + their_step) / 2.0).max(0.0)
    }

    /// The point at arc length `s` (0 ≤ s < length), on the exact curve.
    fn at_length(&self, s: f64) -> (f64, f64) {
        let i = self
            .table_lengths
            .partition_point(|&length| length <= s)
            .clamp(1, TABLE_SIZE);
        let (s0, s1) = (self.table_lengths[i - 1], self.table_lengths[i]);
        let fraction = if s1 > s0 { (s - s0) / (s1 - s0) } else { 0.0 };
        let (t0, t1) = (self.table_parameters[i - 1], self.table_parameters[i]);
        (self.function)(t0 + fraction * (t1 - t0))
    }

    /// Samples around the whole curve with spacings drawn from [(1 − jitter)·h, h] (h the largest
    /// spacing), starting at a random place.
    fn sample(
        &self,
        random: &mut SplitMix64,
        largest_spacing: f64,
        jitter: f64,
    ) -> Vec<(f64, f64)> {
        let length = self.length();
        let mean_spacing = largest_spacing * (1.0 - jitter / 2.0);
        let count = ((length / mean_spacing).ceil() as usize).max(8);
        let weights: Vec<f64> = (0..count)
            .map(|_| random.range(1.0 - jitter, 1.0))
            .collect();
        let total: f64 = weights.iter().sum();
        let start = random.range(0.0, length);
        let mut along = 0.0;
        weights
            .iter()
            .map(|weight| {
                let point = self.at_length((start + along) % length);
                along += weight / total * length;
                point
            })
            .collect()
    }
}

fn distance(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - b.0).hypot(a.1 - b.1)
}

fn circumradius(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> f64 {
    let cross = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    if cross == 0.0 {
        return f64::INFINITY;
    }
    distance(a, b) * distance(b, c) * distance(c, a) / (2.0 * cross.abs())
}

/// A random smooth star-shaped curve around the origin with radius about 1: an ellipse, a
/// superellipse (a rounded rectangle) or a circle with a few small random harmonics, turned by a
/// random angle.
fn random_shape(random: &mut SplitMix64) -> Box<dyn Fn(f64) -> (f64, f64)> {
    let turn = random.range(0.0, TAU);
    let (cos_turn, sin_turn) = (turn.cos(), turn.sin());
    let rotate =
        move |(x, y): (f64, f64)| (x * cos_turn - y * sin_turn, x * sin_turn + y * cos_turn);
    match random.below(3) {
        0 => {
            let aspect = random.range(1.0, 4.0);
            Box::new(move |t: f64| rotate((t.cos(), t.sin() / aspect)))
        }
        1 => {
            // |x|^p + |b·y|^p = 1 with 2 < p ≤ 5: flat sides, rounded corners. Parametrized by
            // the polar angle, which keeps the speed bounded (the usual |cos t|^(2/p) form has
            // infinite speed at the axes, so samples even in t would be far from even in length).
            let exponent = random.range(2.2, 5.0);
            let aspect = random.range(1.0, 2.5);
            Box::new(move |t: f64| {
                let (c, s) = (t.cos(), t.sin());
                let radius = (c.abs().powf(exponent) + (aspect * s).abs().powf(exponent))
                    .powf(-1.0 / exponent);
                rotate((radius * c, radius * s))
            })
        }
        _ => {
            let harmonics: Vec<(f64, f64, f64)> = (0..random.below(4) + 1)
                .map(|_| {
                    let order = (random.below(5) + 2) as f64;
                    // Small amplitudes, shrinking with the order, keep the curve smooth and
                    // star-shaped.
                    let amplitude = random.range(0.0, 0.25) / order;
                    (order, amplitude, random.range(0.0, TAU))
                })
                .collect();
            Box::new(move |t: f64| {
                let radius = 1.0
                    + harmonics
                        .iter()
                        .map(|&(order, amplitude, phase)| amplitude * (order * t + phase).cos())
                        .sum::<f64>();
                rotate((radius * t.cos(), radius * t.sin()))
            })
        }
    }
}

/// `shape` scaled by `scale` and moved to `centre`.
fn placed(
    shape: Box<dyn Fn(f64) -> (f64, f64)>,
    centre: (f64, f64),
    scale: f64,
) -> impl Fn(f64) -> (f64, f64) {
    move |t| {
        let (x, y) = shape(t);
        (centre.0 + scale * x, centre.1 + scale * y)
    }
}

/// A random scene of one to five closed curves: some side by side on a coarse grid, some nested
/// inside others. Curves never touch: nested ones are shrunk until they clear their host.
fn random_closed_curves(random: &mut SplitMix64) -> Vec<ClosedCurve> {
    let mut curves = Vec::new();
    let hosts = random.below(3) + 1;
    for host in 0..hosts {
        // Shapes reach at most 1.5 from their centre, scaled by at most 4: centres 15 apart (moved
        // by at most half a unit) keep neighbours at least 2 apart.
        let centre = (
            15.0 * host as f64 + random.range(-0.5, 0.5),
            random.range(-0.5, 0.5),
        );
        let scale = random.range(1.0, 4.0);
        curves.push(ClosedCurve::new(placed(
            random_shape(random),
            centre,
            scale,
        )));
        if random.below(2) == 0 {
            let host_curve = curves.last().unwrap();
            let host_inner_radius = host_curve
                .table_points
                .iter()
                .map(|&p| distance(p, centre))
                .fold(f64::INFINITY, f64::min);
            // Shapes reach at most 1.5 from their centre; leave a clear ring between.
            let inner_scale = host_inner_radius / 1.5 * random.range(0.3, 0.75);
            let offset = host_inner_radius * 0.05;
            let inner_centre = (
                centre.0 + random.range(-offset, offset),
                centre.1 + random.range(-offset, offset),
            );
            curves.push(ClosedCurve::new(placed(
                random_shape(random),
                inner_centre,
                inner_scale,
            )));
        }
    }
    curves
}

/// Whether `found` is `expected` read cyclically, from any start, in either direction.
fn same_cycle(found: &[usize], expected: &[usize]) -> bool {
    if found.len() != expected.len() || found.is_empty() {
        return false;
    }
    let Some(start) = expected.iter().position(|&i| i == found[0]) else {
        return false;
    };
    let count = expected.len();
    let forward = (0..count).all(|k| found[k] == expected[(start + k) % count]);
    let backward = (0..count).all(|k| found[k] == expected[(start + count - k) % count]);
    forward || backward
}

/// Densest sampling the theorem test uses, relative to the curve's smallest radius of curvature
/// and to its distance from the nearest other curve.
struct Density {
    of_radius_of_curvature: f64,
    of_separation: f64,
    jitter: f64,
}

/// Samples every curve of a scene at the given density, shuffles all points, and returns them
/// with each curve's true cyclic order as indices into them.
fn sample_scene(
    random: &mut SplitMix64,
    curves: &[ClosedCurve],
    density: &Density,
) -> (Vec<Point>, Vec<Vec<usize>>) {
    let mut coordinates = Vec::new();
    let mut ranges = Vec::new();
    for (i, curve) in curves.iter().enumerate() {
        let separation = curves
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, other)| curve.distance_to(other))
            .fold(f64::INFINITY, f64::min);
        let spacing = (density.of_radius_of_curvature * curve.minimum_radius_of_curvature())
            .min(density.of_separation * separation);
        let start = coordinates.len();
        coordinates.extend(curve.sample(random, spacing, density.jitter));
        ranges.push(start..coordinates.len());
    }
    // Shuffle so that input order carries no hint of the curves.
    let mut order: Vec<usize> = (0..coordinates.len()).collect();
    random.shuffle(&mut order);
    let mut position_of = vec![0; order.len()];
    for (position, &original) in order.iter().enumerate() {
        position_of[original] = position;
    }
    let points = order
        .iter()
        .map(|&original| Point::new(coordinates[original].0, coordinates[original].1))
        .collect();
    let cycles = ranges
        .into_iter()
        .map(|range| range.map(|original| position_of[original]).collect())
        .collect();
    (points, cycles)
}

/// How the reconstruction of `points` differs from exactly the closed curves `cycles` with no
/// outlier, if it does.
fn exact_mismatch(method: Method, points: &[Point], cycles: &[Vec<usize>]) -> Option<String> {
    let result = method(points).unwrap();
    let context = || {
        format!(
            "{} points on {} curves (sizes {:?}); found curves of sizes {:?} (closed: {:?}), {} outliers",
            points.len(),
            cycles.len(),
            cycles.iter().map(Vec::len).collect::<Vec<_>>(),
            result.curves.iter().map(|c| c.indices.len()).collect::<Vec<_>>(),
            result.curves.iter().map(|c| c.closed).collect::<Vec<_>>(),
            result.outliers.len()
        )
    };
    if !result.merged_duplicates.is_empty() || !result.outliers.is_empty() {
        return Some(format!("{}: outliers or duplicates", context()));
    }
    if result.curves.len() != cycles.len() {
        return Some(format!("{}: wrong number of curves", context()));
    }
    for cycle in cycles {
        let Some(found) = result
            .curves
            .iter()
            .find(|curve| curve.indices.contains(&cycle[0]))
        else {
            return Some(format!(
                "{}: curve of point {} missing",
                context(),
                cycle[0]
            ));
        };
        if !found.closed {
            return Some(format!("{}: a true curve came back open", context()));
        }
        if !same_cycle(&found.indices, cycle) {
            return Some(format!(
                "{}: a true curve came back in another order",
                context()
            ));
        }
    }
    None
}

fn assert_exact(seed: u64, points: &[Point], cycles: &[Vec<usize>]) {
    for (name, method) in METHODS {
        if let Some(mismatch) = exact_mismatch(method, points, cycles) {
            panic!("{name}, seed {seed}: {mismatch}");
        }
    }
}

/// The density the theorem tests use: spacing at most a fifth of the smallest radius of curvature
/// and half the distance to the nearest other curve, neighbouring spacings differing by a factor
/// of at most 1/(1 − 0.4) ≈ 1.7.
///
/// Measured with this file's shapes (60 seeds per setting, in a scan kept out of the suite): exact
/// reconstruction held at every density tried up to half the radius of curvature and 1.5 times the
/// separation as long as spacings varied by at most 50 % (jitter ≤ 0.5). Curves were left open
/// from jitter 0.6 on (1 seed in 60; more at 0.7), and whenever the spacing exceeded the distance
/// between two curves. The factor of about 2 between neighbouring spacings is inherent in
/// the paper's closing rule: see `paper_limit_a_gap_over_twice_the_spacing_leaves_a_circle_open`.
const DENSE: Density = Density {
    of_radius_of_curvature: 0.2,
    of_separation: 0.5,
    jitter: 0.4,
};

#[test]
fn dense_samples_of_smooth_closed_curves_come_back_exactly() {
    for seed in 0..150 {
        let mut random = SplitMix64::new(seed);
        let curves = random_closed_curves(&mut random);
        let (points, cycles) = sample_scene(&mut random, &curves, &DENSE);
        assert_exact(seed, &points, &cycles);
    }
}

#[test]
fn dense_samples_of_one_curve_of_every_shape_come_back_exactly() {
    for seed in 1000..1150 {
        let mut random = SplitMix64::new(seed);
        let scale = random.range(0.01, 100.0);
        let centre = (random.range(-100.0, 100.0), random.range(-100.0, 100.0));
        let curves = [ClosedCurve::new(placed(
            random_shape(&mut random),
            centre,
            scale,
        ))];
        let (points, cycles) = sample_scene(&mut random, &curves, &DENSE);
        assert_exact(seed, &points, &cycles);
    }
}

#[test]
fn evenly_spaced_samples_come_back_exactly() {
    // No jitter: many distances are equal up to rounding, which exercises every tie rule.
    let even = Density {
        jitter: 0.0,
        ..DENSE
    };
    for seed in 2000..2100 {
        let mut random = SplitMix64::new(seed);
        let curves = random_closed_curves(&mut random);
        let (points, cycles) = sample_scene(&mut random, &curves, &even);
        assert_exact(seed, &points, &cycles);
    }
}

/// Samples along a part of `curve` (`fraction` of its length, from a random start), with
/// spacings drawn from [smallest, largest].
fn arc_samples(
    random: &mut SplitMix64,
    curve: &ClosedCurve,
    fraction: f64,
    smallest: f64,
    largest: f64,
) -> Vec<(f64, f64)> {
    let length = curve.length();
    let arc = length * fraction;
    let start = random.range(0.0, length);
    let mut along = 0.0;
    let mut points = Vec::new();
    while along <= arc {
        points.push(curve.at_length((start + along) % length));
        along += random.range(smallest, largest);
    }
    points
}

#[test]
fn dense_samples_of_a_lone_open_arc_come_back_as_one_open_curve() {
    for seed in 5000..5150 {
        let mut random = SplitMix64::new(seed);
        let scale = random.range(0.01, 100.0);
        let centre = (random.range(-100.0, 100.0), random.range(-100.0, 100.0));
        let curve = ClosedCurve::new(placed(random_shape(&mut random), centre, scale));
        // At most three quarters of a closed shape, so that the two ends are far apart compared
        // with the spacing.
        let fraction = random.range(0.2, 0.75);
        let largest = DENSE.of_radius_of_curvature * curve.minimum_radius_of_curvature();
        let smallest = (1.0 - DENSE.jitter) * largest;
        let coordinates = arc_samples(&mut random, &curve, fraction, smallest, largest);
        let mut order: Vec<usize> = (0..coordinates.len()).collect();
        random.shuffle(&mut order);
        let points: Vec<Point> = order
            .iter()
            .map(|&i| Point::new(coordinates[i].0, coordinates[i].1))
            .collect();
        for (name, method) in METHODS {
            let result = method(&points).unwrap();
            let context = format!(
                "{name}, seed {seed}: {} points on an open arc; found curves of sizes {:?} (closed: {:?}), {} outliers",
                points.len(),
                result.curves.iter().map(|c| c.indices.len()).collect::<Vec<_>>(),
                result.curves.iter().map(|c| c.closed).collect::<Vec<_>>(),
                result.outliers.len()
            );
            assert_eq!(result.curves.len(), 1, "{context}");
            assert!(!result.curves[0].closed, "{context}");
            // Back from input positions to places along the arc: 0, 1, 2, … in either direction.
            let along: Vec<usize> = result.curves[0].indices.iter().map(|&i| order[i]).collect();
            let forward: Vec<usize> = (0..coordinates.len()).collect();
            let backward: Vec<usize> = forward.iter().rev().copied().collect();
            assert!(
                along == forward || along == backward,
                "{context}: out of order"
            );
        }
    }
}

/// `count` points evenly spaced by `step` radians on a circle of radius 10, from angle 0.
fn circle_arc(count: usize, step: f64) -> Vec<Point> {
    (0..count)
        .map(|k| {
            let angle = step * k as f64;
            Point::new(10.0 * angle.cos(), 10.0 * angle.sin())
        })
        .collect()
}

/// The paper's closing rule asks one extremity to be the other's nearest or second-nearest point.
/// On evenly spaced samples, the point two steps away along the curve is about twice the spacing
/// away, so a circle whose closing gap exceeds twice the spacing stays open, however dense the
/// sampling is relative to the circle (here spacing ≈ 0.15 of the radius). ε-sampling allows such
/// a gap; the paper's theorem tacitly needs locally uniform samples. We follow the paper.
#[test]
fn paper_limit_a_gap_over_twice_the_spacing_leaves_a_circle_open() {
    let count = 40;
    // The gap between the last point and the first is 1.8 steps: closed.
    let closes = reconstruct(&circle_arc(count, TAU / (count as f64 + 0.8))).unwrap();
    assert_eq!(closes.curves.len(), 1);
    assert!(closes.curves[0].closed);
    assert_eq!(closes.curves[0].indices.len(), count);
    // 2.2 steps: the whole circle is one chain, but it stays open.
    let stays_open = reconstruct(&circle_arc(count, TAU / (count as f64 + 1.2))).unwrap();
    assert_eq!(stays_open.curves.len(), 1);
    assert!(!stays_open.curves[0].closed);
    // An open curve starts at its lexicographically smaller end: the last point, just below
    // the x axis, has the smaller x.
    assert_eq!(
        stays_open.curves[0].indices,
        (0..count).rev().collect::<Vec<_>>()
    );
}

/// `count` points evenly spaced on a circle of radius 10, except the one at angle 0, which
/// becomes a cluster of four points 1/8 of the spacing apart.
fn circle_with_dense_cluster(count: usize) -> Vec<Point> {
    let step = TAU / count as f64;
    let mut points: Vec<Point> = circle_arc(count, step).into_iter().skip(1).collect();
    for k in [-1.5, -0.5, 0.5, 1.5] {
        let angle = k * step / 8.0;
        points.push(Point::new(10.0 * angle.cos(), 10.0 * angle.sin()));
    }
    points
}

/// The paper's termination test (stop when the candidate edge is longer than the distance between
/// the chain's extremities, once the chain has three edges) also fires on a short dense cluster:
/// four points 1/8 of the spacing apart, on an otherwise evenly sampled circle, become a chain of
/// their own that stops after three edges, and the rest of the circle cannot close across them.
/// This is an ε-sample (spacing ≈ 0.1 of the radius), so the paper's theorem, whose proof only
/// looks at the chosen candidates and not at this test, needs locally uniform samples here too.
/// We follow the paper; this pins down what it does.
#[test]
fn paper_limit_a_dense_cluster_splits_a_circle_into_two_open_curves() {
    let count = 60;
    let step = TAU / count as f64;
    let result = reconstruct(&circle_with_dense_cluster(count)).unwrap();
    let mut shapes: Vec<(bool, usize)> = result
        .curves
        .iter()
        .map(|c| (c.closed, c.indices.len()))
        .collect();
    shapes.sort_unstable();
    assert_eq!(shapes, vec![(false, 4), (false, count - 1)]);
    assert!(result.outliers.is_empty());
    // Without the cluster, the same circle closes.
    let even = reconstruct(&circle_arc(count, step)).unwrap();
    assert_eq!(even.curves.len(), 1);
    assert!(even.curves[0].closed);
}

/// The robust crawl closes a curve whose last gap is up to 2.5 times the spacing beside it (the
/// closing edge is judged like any step), where the paper's leaves it open from 2 on.
#[test]
fn robust_closes_a_circle_across_a_gap_of_two_and_a_half_spacings() {
    let count = 40;
    for (gap_in_steps, closes) in [(1.8, true), (2.2, true), (2.4, true), (2.7, false)] {
        let points = circle_arc(count, TAU / (count as f64 - 1.0 + gap_in_steps));
        let result = reconstruct_robust(&points).unwrap();
        assert_eq!(result.curves.len(), 1, "gap {gap_in_steps}");
        assert_eq!(result.curves[0].closed, closes, "gap {gap_in_steps}");
        assert_eq!(result.curves[0].indices.len(), count, "gap {gap_in_steps}");
    }
}

/// The robust crawl keeps a circle whole across a short dense cluster: its steps are limited by
/// the chain's own spacing, not by the distance between its extremities.
#[test]
fn robust_keeps_a_circle_with_a_dense_cluster_whole() {
    let count = 60;
    let result = reconstruct_robust(&circle_with_dense_cluster(count)).unwrap();
    let shapes: Vec<(bool, usize)> = result
        .curves
        .iter()
        .map(|c| (c.closed, c.indices.len()))
        .collect();
    assert_eq!(
        shapes,
        vec![(true, count + 3)],
        "outliers {:?}",
        result.outliers
    );
    assert_eq!(result.curves[0].indices.len(), count + 3);
    assert!(result.outliers.is_empty());
}

/// A random scene for the invariant checks: closed curves sampled with uneven spacing, open arcs,
/// a few stray points, and some exact duplicates; all coordinates multiples of 1/1024, so that
/// translating by integers and scaling by powers of two are exact.
fn random_scene(random: &mut SplitMix64) -> Vec<Point> {
    let mut coordinates = Vec::new();
    for curve in random_closed_curves(random) {
        let spacing = random.range(0.02, 0.5);
        let jitter = random.range(0.0, 0.9);
        coordinates.extend(curve.sample(random, spacing, jitter));
    }
    for _ in 0..random.below(4) {
        let centre = (random.range(-5.0, 35.0), random.range(-8.0, 8.0));
        let scale = random.range(0.5, 4.0);
        let curve = ClosedCurve::new(placed(random_shape(random), centre, scale));
        let fraction = random.range(0.2, 0.75);
        // Random spacing, anywhere from very dense to coarse.
        let (smallest, largest) = (0.005 * scale, 0.2 * scale);
        coordinates.extend(arc_samples(random, &curve, fraction, smallest, largest));
    }
    for _ in 0..random.below(10) {
        coordinates.push((random.range(-5.0, 35.0), random.range(-8.0, 8.0)));
    }
    for _ in 0..random.below(4) {
        let copy = coordinates[random.below(coordinates.len())];
        coordinates.push(copy);
    }
    random.shuffle(&mut coordinates);
    let dyadic = |value: f64| (value * 1024.0).round() / 1024.0 + 0.0;
    coordinates
        .into_iter()
        .map(|(x, y)| Point::new(dyadic(x), dyadic(y)))
        .collect()
}

/// The structural invariants every reconstruction must satisfy; panics naming `seed`.
fn check_invariants(seed: &str, points: &[Point], result: &Reconstruction) {
    // The distinct points in lexicographic order, as the library triangulates them.
    let mut distinct: Vec<(f64, f64)> = points.iter().map(|p| (p.x, p.y)).collect();
    distinct.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    distinct.dedup();
    let vertex_of = |index: usize| -> u32 {
        let p = points[index];
        distinct
            .binary_search_by(|q| q.0.total_cmp(&p.x).then(q.1.total_cmp(&p.y)))
            .expect("every input point is among the distinct points") as u32
    };
    let positions: Vec<Point> = distinct.iter().map(|&(x, y)| Point::new(x, y)).collect();
    let delaunay = NeighbourGraph::delaunay(&positions).unwrap();

    // Duplicates: each dropped point repeats an earlier kept one; every other point is kept.
    let mut first_index_of: BTreeMap<u32, usize> = BTreeMap::new();
    for index in 0..points.len() {
        first_index_of.entry(vertex_of(index)).or_insert(index);
    }
    let expected_duplicates: Vec<(usize, usize)> = (0..points.len())
        .filter_map(|index| {
            let kept = first_index_of[&vertex_of(index)];
            (kept != index).then_some((index, kept))
        })
        .collect();
    let found_duplicates: Vec<(usize, usize)> = result
        .merged_duplicates
        .iter()
        .map(|d| (d.dropped, d.kept))
        .collect();
    assert_eq!(found_duplicates, expected_duplicates, "{seed}: duplicates");
    let kept: BTreeSet<usize> = first_index_of.values().copied().collect();

    let mut degree: BTreeMap<usize, usize> = BTreeMap::new();
    let mut in_curve = BTreeSet::new();
    for (c, curve) in result.curves.iter().enumerate() {
        let minimum = if curve.closed { 4 } else { 3 };
        assert!(
            curve.indices.len() >= minimum,
            "{seed}: curve {c} has {} points (closed: {})",
            curve.indices.len(),
            curve.closed
        );
        for &index in &curve.indices {
            assert!(
                kept.contains(&index),
                "{seed}: curve {c} uses point {index}, a merged duplicate"
            );
            assert!(
                in_curve.insert(index),
                "{seed}: point {index} appears twice (curve {c} or an earlier one)"
            );
        }
    }
    for (a, b) in edges_of(result) {
        assert!(
            delaunay.has_edge(vertex_of(a), vertex_of(b)),
            "{seed}: edge {a}–{b} ({:?}–{:?}) is not a Delaunay edge",
            points[a],
            points[b]
        );
        *degree.entry(a).or_default() += 1;
        *degree.entry(b).or_default() += 1;
    }
    if let Some((&index, &count)) = degree.iter().find(|&(_, &count)| count > 2) {
        panic!("{seed}: point {index} has degree {count}");
    }

    let outliers: BTreeSet<usize> = result.outliers.iter().copied().collect();
    assert!(
        result.outliers.windows(2).all(|w| w[0] < w[1]),
        "{seed}: outliers not strictly ascending"
    );
    assert!(
        outliers.is_disjoint(&in_curve),
        "{seed}: a point is both an outlier and on a curve"
    );
    let covered: BTreeSet<usize> = outliers.union(&in_curve).copied().collect();
    assert_eq!(
        covered, kept,
        "{seed}: outliers ∪ curve points ≠ distinct points"
    );
}

/// A coordinate pair as exact bits, so that comparisons are exact and orderable.
type Key = (u64, u64);

fn key(p: Point) -> Key {
    (p.x.to_bits(), p.y.to_bits())
}

/// The reconstruction in coordinates: curves as (closed, point sequence), outliers sorted.
#[derive(Debug, PartialEq)]
struct Geometry {
    curves: Vec<(bool, Vec<Key>)>,
    edges: BTreeSet<(Key, Key)>,
    outliers: Vec<Key>,
}

fn geometry(points: &[Point], result: &Reconstruction, back: impl Fn(Point) -> Point) -> Geometry {
    let at = |index: usize| key(back(points[index]));
    let mut outliers: Vec<Key> = result.outliers.iter().map(|&i| at(i)).collect();
    outliers.sort_unstable();
    Geometry {
        curves: result
            .curves
            .iter()
            .map(|curve| (curve.closed, curve.indices.iter().map(|&i| at(i)).collect()))
            .collect(),
        edges: edges_of(result)
            .into_iter()
            .map(|(a, b)| (at(a).min(at(b)), at(a).max(at(b))))
            .collect(),
        outliers,
    }
}

#[test]
fn random_scenes_satisfy_the_invariants() {
    for seed in 3000..3150 {
        let mut random = SplitMix64::new(seed);
        let points = random_scene(&mut random);
        for (name, method) in METHODS {
            let result = method(&points).unwrap();
            check_invariants(&format!("{name}, seed {seed}"), &points, &result);
        }
    }
}

#[test]
fn result_does_not_depend_on_order_translation_or_scale() {
    for seed in 4000..4120 {
        let mut random = SplitMix64::new(seed);
        let points = random_scene(&mut random);
        for (name, method) in METHODS {
            invariant_under_order_translation_and_scale(
                &format!("{name}, seed {seed}"),
                method,
                &points,
                &mut random,
            );
        }
    }
}

/// Checks that `method` gives the same curves on `points` shuffled, translated by integers and
/// scaled by a power of two.
fn invariant_under_order_translation_and_scale(
    seed: &str,
    method: Method,
    points: &[Point],
    random: &mut SplitMix64,
) {
    let original = geometry(points, &method(points).unwrap(), |p| p);

    let mut shuffled = points.to_vec();
    random.shuffle(&mut shuffled);
    let shuffled_geometry = geometry(&shuffled, &method(&shuffled).unwrap(), |p| p);

    let shift = (
        random.below(2001) as f64 - 1000.0,
        random.below(2001) as f64 - 1000.0,
    );
    let moved: Vec<Point> = points
        .iter()
        .map(|p| Point::new(p.x + shift.0, p.y + shift.1))
        .collect();
    let moved_geometry = geometry(&moved, &method(&moved).unwrap(), |p| {
        Point::new(p.x - shift.0, p.y - shift.1)
    });

    let factor = 2f64.powi(random.below(9) as i32 - 4);
    let scaled: Vec<Point> = points
        .iter()
        .map(|p| Point::new(p.x * factor, p.y * factor))
        .collect();
    let scaled_geometry = geometry(&scaled, &method(&scaled).unwrap(), |p| {
        Point::new(p.x / factor, p.y / factor)
    });

    for (what, other) in [
        ("shuffled", &shuffled_geometry),
        ("translated", &moved_geometry),
        ("scaled", &scaled_geometry),
    ] {
        assert_eq!(
            original.edges, other.edges,
            "{seed}: {what} input gives another edge set"
        );
        assert_eq!(
            original.outliers, other.outliers,
            "{seed}: {what} input gives other outliers"
        );
        assert_eq!(
            original.curves, other.curves,
            "{seed}: {what} input gives the curves in another order or orientation"
        );
    }
}
