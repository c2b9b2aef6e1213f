//! Skeleton → pen strokes.
mod graph;

pub use graph::*;
