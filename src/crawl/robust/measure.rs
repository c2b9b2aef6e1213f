//! Local measurements for the robust crawl: each point's second-nearest distance (its local
//! spacing as the point set alone shows it), turn angles and the good-continuation score.

use kurbo::Point;
use rayon::prelude::*;

use super::TURN_WEIGHT;
use crate::crawl::neighbours::NeighbourGraph;

/// What the crawl needs to know of a point, packed so that looking at a point touches one place
/// in memory.
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    pub position: Point,
    /// Squared distance to its second-nearest point (∞ with fewer than two others): the local
    /// spacing as the point set alone shows it.
    pub second_nearest_squared: f64,
    /// Its two nearest Delaunay neighbours (`NONE` if missing).
    pub nearest: [u32; 2],
    /// If those two lie on opposite sides of it, as a point's neighbours along a smoothly sampled
    /// curve do (more than 150° apart), the squared distance to the farther; otherwise −1.
    pub strand_reach: f64,
}

/// No vertex.
pub const NONE: u32 = u32::MAX;

/// The point set, its Delaunay graph and what is measured on them once.
pub struct Local<'a> {
    pub graph: &'a NeighbourGraph,
    pub samples: Vec<Sample>,
}

impl<'a> Local<'a> {
    pub fn new(positions: &'a [Point], graph: &'a NeighbourGraph) -> Self {
        let samples = (0..positions.len() as u32)
            .into_par_iter()
            .map(|v| measure(positions, graph, v))
            .collect();
        Self { graph, samples }
    }

    pub fn vertex_count(&self) -> usize {
        self.samples.len()
    }

    pub fn position(&self, v: u32) -> Point {
        self.samples[v as usize].position
    }

    pub fn second_nearest_squared(&self, v: u32) -> f64 {
        self.samples[v as usize].second_nearest_squared
    }

    /// The distance between two vertices.
    pub fn length(&self, a: u32, b: u32) -> f64 {
        // Not `hypot`: squares, sums and square roots scale exactly by powers of two.
        self.squared_length(a, b).sqrt()
    }

    /// The squared distance between two vertices.
    pub fn squared_length(&self, a: u32, b: u32) -> f64 {
        let (p, q) = (self.position(a), self.position(b));
        let (dx, dy) = (p.x - q.x, p.y - q.y);
        dx * dx + dy * dy
    }

    /// The cosine of the turn at `at` when going from `from` through `at` to `to`: 1 straight on,
    /// −1 straight back.
    pub fn turn_cos(&self, from: u32, at: u32, to: u32) -> f64 {
        let (u, w) = (
            self.position(at) - self.position(from),
            self.position(to) - self.position(at),
        );
        let norms = (u.dot(u) * w.dot(w)).sqrt();
        if norms > 0.0 {
            (u.dot(w) / norms).clamp(-1.0, 1.0)
        } else {
            1.0
        }
    }

    /// Whether the turn at `at` from `from` to `to` has a cosine of at least `min_cos`, without a
    /// square root (so exactly as the points scale).
    pub fn turns_at_most(&self, from: u32, at: u32, to: u32, min_cos: f64) -> bool {
        let (u, w) = (
            self.position(at) - self.position(from),
            self.position(to) - self.position(at),
        );
        let dot = u.dot(w);
        let bound = min_cos * min_cos * u.dot(u) * w.dot(w);
        if min_cos >= 0.0 {
            dot >= 0.0 && dot * dot >= bound
        } else {
            dot >= 0.0 || dot * dot <= bound
        }
    }

    /// Whether `w` lies inside a free strand that `e` is not part of: w's two nearest points are
    /// both free (`is_free`), nearer to it than `e`, and on opposite sides of it. Those two are
    /// then w's neighbours along its curve, and a step from `e` to `w` would land in the middle
    /// of that curve, a T-junction a simple curve never has.
    pub fn inside_strand(&self, w: u32, e: u32, is_free: impl Fn(u32) -> bool) -> bool {
        let sample = &self.samples[w as usize];
        let [a, b] = sample.nearest;
        sample.strand_reach >= 0.0
            && a != e
            && b != e
            && sample.strand_reach < self.squared_length(w, e)
            && is_free(a)
            && is_free(b)
    }
}

/// Measures vertex `v`.
fn measure(positions: &[Point], graph: &NeighbourGraph, v: u32) -> Sample {
    let position = positions[v as usize];
    let second_nearest_squared = graph
        .second_nearest_squared_distance(positions, v)
        .unwrap_or(f64::INFINITY);
    let (nearest, strand_reach) = match (graph.neighbours(v), graph.squared_lengths(v)) {
        ([a, b, ..], [_, farther, ..]) => {
            let (u, w) = (
                positions[*a as usize] - position,
                positions[*b as usize] - position,
            );
            // cos(u, w) ≤ OPPOSITE_COS < 0 without a square root: u·w ≤ 0 and
            // (u·w)² ≥ OPPOSITE_COS² |u|²|w|².
            let dot = u.dot(w);
            let opposite =
                dot <= 0.0 && dot * dot >= OPPOSITE_COS * OPPOSITE_COS * u.dot(u) * w.dot(w);
            ([*a, *b], if opposite { *farther } else { -1.0 })
        }
        ([a], _) => ([*a, NONE], -1.0),
        _ => ([NONE, NONE], -1.0),
    };
    Sample {
        position,
        second_nearest_squared,
        nearest,
        strand_reach,
    }
}

/// Two directions from a point are on opposite sides of it, along a strand, when they are more
/// than 150° apart: a curve sampled densely enough for its turns (ε < 1/2) turns by at most
/// 2 asin(ε/2) ≈ 29° at a sample. A point across a thin part, diagonally behind, is not.
const OPPOSITE_COS: f64 = -0.866;

/// A step's length weighed by its turn: good continuation.
pub fn continuation_score(length: f64, turn_cos: f64) -> f64 {
    length * (1.0 + TURN_WEIGHT * (1.0 - turn_cos))
}
