//! The output stages: polylines → paths ([`fit`]) → SVG text ([`svg`]) or DXF text ([`dxf`],
//! the paths [`flatten`]ed), at a physical size ([`units`]); SVG → pixels ([`render`]); and the
//! pictures of every stage for `--debug` ([`debug`]).

pub mod debug;
pub mod dxf;
pub mod fit;
pub mod flatten;
pub mod render;
mod render_budget;
pub mod svg;
pub mod units;
