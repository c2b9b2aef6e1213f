//! The output stages: polylines → paths ([`fit`]) → SVG text ([`svg`]); SVG → pixels
//! ([`render`]); and the pictures of every stage for `--debug` ([`debug`]).

pub mod debug;
pub mod fit;
pub mod render;
mod render_budget;
pub mod svg;
