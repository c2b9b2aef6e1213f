//! The crawl: curve reconstruction on point sets and on sampled strokes.
pub mod reconstruct;
pub mod strokes;
