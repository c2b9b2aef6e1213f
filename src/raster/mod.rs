//! The raster stages of the pipeline (`docs/design.md`, "The pipeline"): image bytes → gray
//! ([`decode`]) → ink mask ([`binarize`]) → cleaned mask and pen width ([`clean`]) → 1-px skeleton
//! ([`thin`]), all on the one-byte-a-pixel [`bitmap::Bitmap`].

pub mod binarize;
pub mod bitmap;
pub mod clean;
pub mod decode;
mod limits;
pub mod thin;
