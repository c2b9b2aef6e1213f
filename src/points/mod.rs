//! Point files in, reconstructions out.
pub mod read;
pub mod write;
