//! crawltrace turns scanned skip-stroke line drawings and raw 2D point sets into clean vector
//! curves, with the Crawl through Neighbors reconstruction (Parakkat & Muthuganapathy, 2016) at its
//! heart. The pipeline and its conventions are described in `docs/design.md`.
//!
//! Images: [`trace()`] takes a decoded image ([`decode::decode_image`]) and returns a
//! [`Drawing`], one path per drawn shape, which [`svg::to_svg`] writes.
//!
//! Point sets: [`reconstruct::reconstruct`] takes points and returns curves as chains of input
//! indices, each open or closed, plus the outliers.
//!
//! Images, stage by stage: [`decode::decode_image`] and [`decode::to_gray`] → [`binarize::binarize`]
//! → [`clean::estimate_stroke_width`] and [`clean::clean`] → [`thin::thin`], a 1-px skeleton.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod batch;
pub mod crawl;
pub mod files;
pub mod geometry;
pub mod output;
pub mod points;
pub mod raster;
pub mod strokes;
pub mod trace;

// The paths of the flat layout, kept until the library API is curated.
pub use crawl::strokes as sketch;
/// The point-set crawl under its old path (interim, until the library API is curated).
pub mod reconstruct {
    pub use crate::crawl::algorithm::*;
    pub use crate::crawl::neighbours::*;
    pub use crate::crawl::reconstruct::*;
    pub use crate::crawl::ReconstructError;
}
pub use geometry::polyline as sample;
pub use output::{debug, fit, render, svg};
pub use points::{read as pointfile, write as pointset};
pub use raster::{binarize, bitmap, clean, decode, thin};

pub use kurbo::Point;
pub use reconstruct::{reconstruct, Curve, Reconstruction};
pub use svg::{CurvePath, Drawing};
pub use trace::{trace, TraceError, TraceOptions, Traced};
