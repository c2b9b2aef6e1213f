//! Curves → paths → SVG, pictures.
pub mod debug;
pub mod fit;
pub mod render;
pub mod svg;
