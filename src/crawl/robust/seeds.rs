//! Seeds of the robust crawl: the order in which points are tried (densest first), and at a
//! point the two neighbours that make the plainest piece of curve through it — similar lengths,
//! within the step limits, turning at most 90° — scored like a step (length weighed by turn).
//!
//! The paper seeds with the shortest edge between mutual nearest neighbours and adds its first two
//! candidates unchecked; two stray points closer than the spacing then seed first and grow into a
//! curve. A triple carries its own spacing, so the first steps are checked like every other.

use rayon::prelude::*;

use super::measure::{continuation_score, Local};
use super::{CANDIDATE_LIMIT, STEP_LIMIT};

/// A seed: the middle point and its two neighbours on the curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seed {
    pub middle: u32,
    pub ends: [u32; 2],
    /// The longer of its two edges: the spacing the chain starts with.
    pub spacing: f64,
}

/// Neighbours considered for a seed's ends: the nearest few Delaunay neighbours hold both curve
/// neighbours wherever the sampling is dense enough for a seed to matter (across a thin part the
/// side across comes first, the two along next).
const SEED_NEIGHBOURS: usize = 4;

/// Turns of more than 90° are not seeds: a seed is where the curve is plainest.
const SEED_TURN_COS: f64 = 0.0;

/// Every point, densest first (by second-nearest distance; ties by id): the order in which seeds
/// are tried. A seed is made by [`seed_at`] only when its turn comes and its point is still free:
/// most points are on a curve by then.
///
/// DECISION: densest first, as the paper's shortest seed edge first: curves are found before the
/// strays among them, and a seed starts where the sampling is finest.
pub fn seed_order(local: &Local) -> Vec<u32> {
    let mut keyed: Vec<(u64, u32)> = local
        .samples
        .par_iter()
        .enumerate()
        // Non-negative floats order like their bit patterns.
        .map(|(v, sample)| (sample.second_nearest_squared.to_bits(), v as u32))
        .collect();
    keyed.par_sort_unstable();
    keyed.into_iter().map(|(_, v)| v).collect()
}

/// The seed whose middle point is `v`, if it has one.
pub fn seed_at(local: &Local, v: u32) -> Option<Seed> {
    best_triple(local, v).map(|(_, [p, q])| Seed {
        middle: v,
        ends: [p, q],
        spacing: local.length(v, p).max(local.length(v, q)),
    })
}

/// The best triple through `v`: its score and its two ends.
fn best_triple(local: &Local, v: u32) -> Option<(f64, [u32; 2])> {
    let neighbours = local.graph.neighbours(v);
    let near = &neighbours[..neighbours.len().min(SEED_NEIGHBOURS)];
    let mut lengths = [0.0; SEED_NEIGHBOURS];
    for (length, &squared) in lengths.iter_mut().zip(local.graph.squared_lengths(v)) {
        *length = squared.sqrt();
    }
    let mut best: Option<(f64, [u32; 2])> = None;
    for i in 0..near.len() {
        for j in i + 1..near.len() {
            let (p, q) = (near[i], near[j]);
            let (short, long) = (lengths[i].min(lengths[j]), lengths[i].max(lengths[j]));
            let limit = |w: u32| CANDIDATE_LIMIT * local.second_nearest_squared(w).sqrt();
            let fits =
                long <= STEP_LIMIT * short && lengths[i] <= limit(p) && lengths[j] <= limit(q);
            let turn = local.turn_cos(p, v, q);
            if !fits || turn < SEED_TURN_COS {
                continue;
            }
            let score = continuation_score(long, turn);
            let ends = [p.min(q), p.max(q)];
            let better = best.is_none_or(|(s, e)| (score, ends) < (s, e));
            if better {
                best = Some((score, ends));
            }
        }
    }
    best
}
