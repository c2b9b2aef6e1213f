//! Geometry shared by the stages.
pub mod polyline;
