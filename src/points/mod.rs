//! Point sets on the command line: point files in ([`read`]), reconstructions out as JSON or as a
//! drawing ([`write`](mod@write)); the reconstruction itself is [`crate::crawl::reconstruct`].

pub mod read;
pub mod write;
