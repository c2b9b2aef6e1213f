//! The raster stages: image bytes → gray → ink mask → cleaned mask → 1-px skeleton.
pub mod binarize;
pub mod bitmap;
pub mod clean;
pub mod decode;
pub mod thin;
