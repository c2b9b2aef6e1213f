//! A robust crawl for point sets beyond the paper's assumptions: stray points, sharp corners, open
//! curves near other curves, thin parts and uneven closing gaps. It keeps the shape of Crawl
//! through Neighbors (Parakkat & Muthuganapathy, Computer Graphics Forum 35(5), 2016, Algorithm 1)
//! — seeds, chains growing from both extremities along Delaunay edges, termination, closing — but
//! every rule is stated against the *local spacing* of the samples, so it has no parameter and
//! does not depend on scale. The design, the reasons for each rule and the measurements are in
//! `docs/point-sets.md`; the paper's crawl stays in [`crate::reconstruct`].
//!
//! In short:
//! - **Seeds** are triples (p, v, q) where the curve is plainest: two near neighbours of v on
//!   opposite sides, of similar length; the straightest and densest first. A seed that is much
//!   sparser than a curve already found right beside it is a stray and is not used.
//! - **Steps** go to the unvisited Delaunay neighbour of an extremity that best continues the
//!   chain: its length weighed by how much the chain would turn (good continuation). A step may be
//!   at most [`STEP_LIMIT`] times the chain's recent spacing and [`CANDIDATE_LIMIT`] times the
//!   candidate's own second-nearest distance. A turn back of more than 120° is taken only when the
//!   step after it goes on gently (a corner, not a zig-zag).
//! - **Closing** is a step from one extremity to the other, with the same limits, taken when it
//!   is better than any other step and short against the chain's length.
//! - A chain of fewer than [`MIN_CURVE_POINTS`] points is no curve; its points are free again.
//! - **Tips**: a point left over whose two nearest points are consecutive on a curve, at similar
//!   distances, is put back between them (the tip of a corner sharper than the crawl's turns).

mod grow;
mod join;
mod measure;
mod seeds;
mod tips;

use kurbo::Point;

use crate::reconstruct::{
    reconstruct_with, Chain, NeighbourGraph, ReconstructError, Reconstruction,
};

use grow::Crawler;
use measure::Local;

/// A step may be at most this many times the chain's spacing at its extremity (the longer of its
/// last two edges). Feature-size sampling changes the spacing by at most 1 + ε ≈ 1.5 per step;
/// strays kept 4 spacings off a curve, and the ends of other curves 3 spacings away, stay out.
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

/// A chain needs this many points to be a curve. The paper checks nothing before a chain has
/// three edges (its termination and closing tests both need "more than two edges"), so a chain of
/// two edges carries no evidence: any three points make one.
pub const MIN_CURVE_POINTS: usize = 4;

/// An open chain this long that is also regular (no turn over 60°, no edge over twice its
/// neighbour) is a curve even where it is sparse beside a denser one: eight points make six turns
/// and seven edges, and strays scattered at random rarely line up like that (none did in 300
/// sets of the outliers family with 20 % strays); shorter smooth runs of strays do.
pub const EVIDENT_CURVE_POINTS: usize = 8;

/// A seed or a chain this many times sparser than a curve point beside it is strays. Strays kept
/// 4 spacings off a curve are typically 5 or more spacings apart; two curves sampled at densities
/// a factor of 2 apart side by side are both kept.
pub const SPARSE_RATIO: f64 = 2.0;

/// "Beside": within this many of the strays' own spacings, beyond the reach of their own steps
/// ([`STEP_LIMIT`]), so that a cluster just out of a curve's reach still counts as beside it.
pub const BESIDE: f64 = 4.0;

/// The closing edge may be at most this fraction of the chain's length: closing joins the two
/// ends of a curve, not the two ends of a short hook.
pub const CLOSING_GAP_OF_LENGTH: f64 = 1.0 / 3.0;

/// Reconstructs curves from a planar point set with the robust crawl; the same conventions as
/// [`crate::reconstruct::reconstruct`] (canonical orientation, outliers ascending, duplicates
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
