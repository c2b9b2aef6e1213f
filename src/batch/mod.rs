//! Batch tracing of image folders.
mod engine;

pub use engine::*;
