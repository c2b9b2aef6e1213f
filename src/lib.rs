//! crawltrace turns scanned skip-stroke line drawings and raw 2D point sets into clean vector
//! curves, with the Crawl through Neighbors reconstruction (Parakkat & Muthuganapathy, 2016) at its
//! heart. The pipeline and its conventions are described in `../shared/DESIGN.md`.
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
pub mod binarize;
pub mod bitmap;
pub mod clean;
pub mod debug;
pub mod decode;
pub mod fit;
pub mod pointfile;
pub mod pointset;
pub mod reconstruct;
pub mod render;
pub mod robust_crawl;
pub mod sample;
pub mod sketch;
pub mod strokes;
pub mod svg;
pub mod thin;
pub mod trace;

pub use kurbo::Point;
pub use reconstruct::{reconstruct, Curve, Reconstruction};
pub use svg::{CurvePath, Drawing};
pub use trace::{trace, TraceError, TraceOptions, Traced};
