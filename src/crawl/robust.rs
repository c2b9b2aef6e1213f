//! A robust crawl for point sets beyond the paper's assumptions: stray points, sharp corners, open
//! curves near other curves, thin parts and uneven closing gaps. It keeps the shape of Crawl
//! through Neighbors (Parakkat & Muthuganapathy, Computer Graphics Forum 35(5), 2016, Algorithm 1)
//! — seeds, chains growing from both extremities along Delaunay edges, termination, closing — but
//! every rule is stated against the *local spacing* of the samples, so it has no parameter and
//! does not depend on scale. The design, the reasons for each rule and the measurements are in
//! `docs/point-sets.md`; the paper's crawl stays in [`super::reconstruct`].
//!
//! In short:
//! - **Seeds** are tried densest first (by each point's second-nearest distance). A seed is a
//!   triple (p, v, q): two near neighbours of v, of similar length and turning at most 90°, the
//!   straightest and shortest; its edges pass the same limits as any step.
//! - **Steps** go to the free Delaunay neighbour of an extremity that best continues the chain:
//!   its length weighed by how much the chain would turn (good continuation). A step is at most
//!   [`STEP_LIMIT`] times the chain's spacing at that end and [`CANDIDATE_LIMIT`] times the
//!   candidate's own second-nearest distance, never lands in the middle of a free strand, turns
//!   back by more than 120° only when the step after it goes on gently (a corner, not a
//!   zig-zag), and goes to a dead end only when nothing else goes on.
//! - **Closing** is a step from one extremity to the other, under the same limits, taken when it
//!   is at least as good as any other step and short against the chain's length.
//! - A chain of fewer than [`MIN_CURVE_POINTS`] points is no curve; a chain [`SPARSE_RATIO`] times
//!   sparser than a curve found before, right beside it, is strays unless it is long and regular.
//!   Either way its points are free again.
//! - **Joins**: chain ends that are Delaunay neighbours are joined where the step between them
//!   is acceptable from both sides.
//! - **Skipped points**: one to three points left over between the two ends of a chain edge, each
//!   with its two nearest points as its neighbours on that detour, are put back (the tip of a
//!   corner sharper than the crawl's turns, the bottom of a notch narrower than the spacing).
//!
//! Every output edge is a Delaunay edge: steps, closing edges and joins follow Delaunay edges, and
//! a skipped point goes back between its two nearest Delaunay neighbours.

mod grow;
mod join;
mod measure;
mod seeds;
mod tips;

use kurbo::Point;

use super::algorithm::Chain;
use super::neighbours::NeighbourGraph;
use super::reconstruct::{reconstruct_with, Reconstruction};
use super::ReconstructError;

use grow::Crawler;
use measure::Local;

/// A step may be at most this many times the chain's spacing at its extremity (the longer of its
/// last two edges). Feature-size sampling changes the spacing by at most 1 + ε ≈ 1.5 per step;
/// strays kept 4 spacings off a curve, and the ends of other curves 3 spacings away, stay out.
///
/// DECISION: 2.5, not the "about 4": the candidate-side limit ([`CANDIDATE_LIMIT`]) and
/// the strand rule keep a chain end off other curves, so this limit only has to keep strays out,
/// and 4 would take a stray 4 spacings off a curve whose last edges are a little long. No floor
/// by the end's second-nearest distance is needed: a seed is a triple within the limits, and the
/// spacing is the longer of the last two edges, so a short edge does not freeze a chain.
pub const STEP_LIMIT: f64 = 2.5;

/// A step may be at most this many times the candidate's own second-nearest distance: a point
/// whose two nearest neighbours are both more than twice closer belongs to a denser curve of its
/// own (the end of an open curve must not take the side of a curve 3 spacings away).
pub const CANDIDATE_LIMIT: f64 = 2.0;

/// Good continuation: a step's score is its length × (1 + TURN_WEIGHT × (1 − cos turn)), so a
/// step turning 90° counts as 4 times its length. Across a thin part (sides closer than the
/// spacing) the side ahead then beats the side across down to gaps of about 0.5 spacings.
pub const TURN_WEIGHT: f64 = 3.0;

/// Turns sharper than 120° (cosine below −1/2) are taken only if the step after goes on gently.
pub const SHARP_TURN_COS: f64 = -0.5;

/// "Gently": the step after a sharp turn turns by at most 60° (cosine at least 1/2).
pub const ONWARD_TURN_COS: f64 = 0.5;

/// A chain needs this many points to be a curve.
///
/// DECISION: 4, where the paper keeps chains of 3. The paper checks nothing before a chain has
/// three edges (its termination and closing tests both need "more than two edges"), so a chain of
/// two edges carries no evidence: any three points make one (three strays in a row, for one).
pub const MIN_CURVE_POINTS: usize = 4;

/// A chain this long that is also regular (no turn over 60°, no edge over twice its neighbour) is
/// a curve even where it is sparse beside a denser one: eight points make six turns and seven
/// edges, and strays scattered at random rarely line up like that (none did in 300 sets of the
/// outliers family with 20 % strays); shorter smooth runs of strays do, and so do closed loops of
/// strays, so closing is no evidence.
pub const EVIDENT_CURVE_POINTS: usize = 8;

/// A chain this many times sparser than a curve point beside it (its median edge against that
/// point's second-nearest distance) is strays, unless it is evident as a curve. Strays kept 4
/// spacings off a curve are typically 5 or more spacings apart, and clusters of them 2 to 4.
pub const SPARSE_RATIO: f64 = 2.0;

/// "Beside": within this many of the strays' own spacings, beyond the reach of their own steps
/// ([`STEP_LIMIT`]), so that a cluster just out of a curve's reach still counts as beside it.
pub const BESIDE: f64 = 4.0;

/// The closing edge may be at most this fraction of the chain's length: closing joins the two
/// ends of a curve, not the two ends of a short hook.
pub const CLOSING_GAP_OF_LENGTH: f64 = 1.0 / 3.0;

/// Reconstructs curves from a planar point set with the robust crawl; the same conventions as
/// [`super::reconstruct::reconstruct`] (canonical orientation, outliers ascending, duplicates
/// merged), and the result does not depend on input order, translation or scaling by powers of
/// two.
pub fn reconstruct(points: &[Point]) -> Result<Reconstruction, ReconstructError> {
    reconstruct_with(points, crawl)
}

/// Runs the robust crawl on `graph` (the Delaunay triangulation of the distinct `positions`, in
/// lexicographic order) and returns its curves, in the order of their seeds.
pub fn crawl(positions: &[Point], graph: &NeighbourGraph) -> Vec<Chain> {
    let local = Local::new(positions, graph);
    let mut crawler = Crawler::new(&local);
    for middle in seeds::seed_order(&local) {
        crawler.try_seed(middle);
    }
    let (chains, free) = crawler.finish();
    let mut chains = join::join_chains(&local, chains);
    tips::put_back_tips(&local, &mut chains, &free);
    chains
}
