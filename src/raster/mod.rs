//! The raster stages of the pipeline (`docs/design.md`, "The pipeline"): image bytes → gray
//! ([`decode`]) → ink mask ([`binarize`]) → paper between strokes that nearly touch ([`valleys`])
//! → cleaned mask and pen width ([`clean`]) → 1-px skeleton ([`thin`]), all on the
//! one-byte-a-pixel [`bitmap::Bitmap`]; and the pixel density the image file records
//! ([`density`]), for the output's physical size.

pub mod binarize;
pub mod bitmap;
pub mod clean;
pub mod decode;
pub mod density;
mod limits;
pub mod radius;
pub mod thin;
pub mod valleys;

/// The tests' seeded generator (`tests/support/random.rs`), for the unit tests' random shapes and
/// noise: one copy for the whole repository.
#[cfg(test)]
#[path = "../../tests/support/random.rs"]
mod test_random;
