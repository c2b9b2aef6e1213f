//! The crawl: curve reconstruction by Crawl through Neighbors (Parakkat & Muthuganapathy,
//! Computer Graphics Forum 35(5), 2016), on point sets and on sampled pen strokes.
//!
//! [`algorithm`] is the paper's crawl on any [`neighbours::NeighbourGraph`] (the Delaunay
//! triangulation is [`neighbours::NeighbourGraph::delaunay`]); [`reconstruct`] runs it on a point
//! set with the paper's closing rule; [`robust`] is a crawl for point sets beyond the paper (stray
//! points, sharp corners, open ends, thin parts; issue 10, `docs/point-sets.md`); [`strokes`] runs
//! the crawl on sampled pen strokes, with bridges across the gaps between their free ends.

pub mod algorithm;
pub mod band_gaps;
mod bands;
pub mod bases;
mod bridges;
mod closure;
mod clusters;
pub mod contacts;
pub mod crossings;
mod hairpins;
pub mod hooks;
pub mod ink_ends;
pub mod legs;
pub mod necks;
pub mod neighbours;
pub mod outline_gaps;
pub mod reconstruct;
pub mod retraced;
pub mod robust;
pub mod slivers;
pub mod spikes;
pub mod strokes;
mod through;
pub mod tips;
mod triangulation;
pub mod twists;

/// Removes the items whose flag in `marked` is set (one flag per item), keeping the others in
/// order: the curves a post-crawl stage folded or spliced into others.
pub(crate) fn remove_marked<T>(items: &mut Vec<T>, marked: &[bool]) {
    let mut flags = marked.iter();
    items.retain(|_| !flags.next().copied().unwrap_or(false));
}

/// Why a point set could not be reconstructed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReconstructError {
    /// A coordinate is NaN or infinite.
    #[error("point {index} has a coordinate that is not a finite number")]
    NotFinite {
        /// Input index of the offending point.
        index: usize,
    },
    /// spade refused a coordinate (too large, or too close to zero without being zero).
    #[error("point {index} has a coordinate the triangulation cannot represent ({value:e}); the magnitude must lie between 1e-42 and 1e60, or be 0")]
    OutOfRange {
        /// Input index of the offending point.
        index: usize,
        /// The offending coordinate.
        value: f64,
    },
}

#[cfg(test)]
pub(crate) mod tests {
    use std::f64::consts::TAU;

    use kurbo::Point;

    /// `count` points on an ellipse, evenly spaced in angle, starting at `phase`.
    pub(crate) fn ellipse(
        center: (f64, f64),
        radii: (f64, f64),
        count: usize,
        phase: f64,
    ) -> Vec<Point> {
        (0..count)
            .map(|i| {
                let angle = phase + TAU * i as f64 / count as f64;
                Point::new(
                    center.0 + radii.0 * angle.cos(),
                    center.1 + radii.1 * angle.sin(),
                )
            })
            .collect()
    }
}
