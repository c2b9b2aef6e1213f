//! Seeded point sets with known curves, for measuring curve reconstruction: the families of
//! published curve-reconstruction test sets (Ohrhallinger, Peethambaran, Parakkat, Dey &
//! Muthuganapathy, "2D Points Curve Reconstruction Survey and Benchmark", Eurographics STAR 2021):
//! smooth closed and open curves sampled by local feature size, sharp corners, open curves,
//! multiple components and holes, noise, outliers and non-uniform sampling, plus the cases of
//! issue 10 (stray points, acute sectors, open ends near curves, thin parts).
//!
//! Shared by `tests/it/robust_points.rs` and `examples/point_benchmark.rs` through `#[path]`.
#![allow(dead_code)] // each includer uses a different part

pub mod families;
pub mod geometry;
#[path = "../support/random.rs"]
mod random;

use std::collections::BTreeSet;

use crawltrace::Point;
use crawltrace::Reconstruction;

use geometry::Xy;
pub use random::SplitMix64;

/// A scene before it becomes a point set: true curves as samples in order, and stray points.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    pub curves: Vec<(Vec<Xy>, bool)>,
    pub strays: Vec<Xy>,
}

impl Scene {
    pub fn curve(mut self, samples: Vec<Xy>, closed: bool) -> Self {
        self.curves.push((samples, closed));
        self
    }

    pub fn strays(mut self, strays: Vec<Xy>) -> Self {
        self.strays.extend(strays);
        self
    }
}

/// A point set with its true edges and outliers, as indices into `points`.
#[derive(Clone, Debug)]
pub struct Instance {
    pub family: &'static str,
    /// What this instance is (parameters), for failure messages.
    pub label: String,
    pub points: Vec<Point>,
    pub edges: BTreeSet<(usize, usize)>,
    pub outliers: BTreeSet<usize>,
}

impl Instance {
    /// Turns `scene` into a point set: a random rotation, scale (a power of two between 1/8 and
    /// 8, so nothing depends on units) and shift, then the points shuffled so that input order
    /// carries no hint of the curves.
    pub fn new(family: &'static str, label: String, scene: Scene, random: &mut SplitMix64) -> Self {
        let turn = random.range(0.0, std::f64::consts::TAU);
        let scale = 2f64.powi(random.below(7) as i32 - 3);
        let shift = (random.range(-500.0, 500.0), random.range(-500.0, 500.0));
        let place = |(x, y): Xy| {
            let (c, s) = (turn.cos(), turn.sin());
            Point::new(
                shift.0 + scale * (c * x - s * y),
                shift.1 + scale * (s * x + c * y),
            )
        };
        let mut placed: Vec<Point> = Vec::new();
        let mut curves: Vec<(Vec<usize>, bool)> = Vec::new();
        for (samples, closed) in &scene.curves {
            let start = placed.len();
            placed.extend(samples.iter().map(|&p| place(p)));
            curves.push(((start..placed.len()).collect(), *closed));
        }
        let first_stray = placed.len();
        placed.extend(scene.strays.iter().map(|&p| place(p)));
        let mut order: Vec<usize> = (0..placed.len()).collect();
        random.shuffle(&mut order);
        let mut position_of = vec![0; order.len()];
        for (position, &original) in order.iter().enumerate() {
            position_of[original] = position;
        }
        let points = order.iter().map(|&original| placed[original]).collect();
        let mut edges = BTreeSet::new();
        for (indices, closed) in &curves {
            let count = indices.len();
            let pairs = if *closed { count } else { count - 1 };
            for k in 0..pairs {
                let (a, b) = (
                    position_of[indices[k]],
                    position_of[indices[(k + 1) % count]],
                );
                edges.insert((a.min(b), a.max(b)));
            }
        }
        let outliers = (first_stray..placed.len())
            .map(|original| position_of[original])
            .collect();
        Self {
            family,
            label,
            points,
            edges,
            outliers,
        }
    }

    /// Why `result` is not exactly this instance's curves and outliers, if it is not.
    pub fn mismatch(&self, result: &Reconstruction) -> Option<String> {
        let found = edges_of(result);
        let outliers: BTreeSet<usize> = result.outliers.iter().copied().collect();
        if found == self.edges && outliers == self.outliers {
            return None;
        }
        let missing = self.edges.difference(&found).count();
        let extra: Vec<_> = found.difference(&self.edges).take(4).collect();
        let extra_count = found.difference(&self.edges).count();
        Some(format!(
            "{} {}: {} true edges missing, {} extra edges (e.g. {:?}), outliers {} found / {} true",
            self.family,
            self.label,
            missing,
            extra_count,
            extra
                .iter()
                .map(|&&(a, b)| (self.points[a], self.points[b]))
                .collect::<Vec<_>>(),
            outliers.len(),
            self.outliers.len(),
        ))
    }
}

/// The result's undirected edges, closing edges included, as sorted index pairs.
pub fn edges_of(result: &Reconstruction) -> BTreeSet<(usize, usize)> {
    let mut edges = BTreeSet::new();
    for curve in &result.curves {
        let indices = &curve.indices;
        let count = indices.len();
        let pairs = if curve.closed { count } else { count - 1 };
        for k in 0..pairs {
            let (a, b) = (indices[k], indices[(k + 1) % count]);
            edges.insert((a.min(b), a.max(b)));
        }
    }
    edges
}
