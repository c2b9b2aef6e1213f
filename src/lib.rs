//! crawltrace turns scanned skip-stroke line drawings and raw 2D point sets into clean vector
//! curves, with the Crawl through Neighbors reconstruction (S. N. Parakkat and
//! R. Muthuganapathy, Computer Graphics Forum 35(5), 2016) at its heart. The pipeline and its
//! conventions are described in `docs/design.md`.
//!
//! # Entry points
//!
//! | task | function | result |
//! |---|---|---|
//! | trace an image in memory | [`trace()`] | [`Traced`]: a [`Drawing`], one path per drawn shape |
//! | trace an image file | [`trace_file`] | [`Traced`] |
//! | trace an image file held in memory | [`trace_bytes`] | [`Traced`] |
//! | write SVG | [`to_svg`], [`to_svg_with_size`] | the SVG text of a [`Drawing`], in pixels or at a physical size |
//! | write DXF | [`to_dxf`] | the DXF text of a [`Drawing`], one polyline per curve |
//! | write a traced drawing as SVG or DXF at its physical size | [`export()`] | the file's text |
//! | reconstruct curves from points (the paper's crawl) | [`reconstruct()`] | [`Reconstruction`]: chains of input indices, open or closed, and outliers |
//! | reconstruct curves from points with stray points, sharp corners, open ends or thin parts (the robust crawl, `crawltrace points`' default) | [`reconstruct_robust()`] | [`Reconstruction`] |
//! | read a point file | [`parse_points`] | [`PointFile`]: the points and their line numbers |
//! | render SVG to pixels | [`render_svg`], [`render_svg_with`] | an RGBA image |
//!
//! Folders of images are traced by [`batch`]; every stage of the pipeline is in [`stages`], for
//! benchmarks, tests and front ends that run a stage on its own.
//!
//! ```
//! use crawltrace::{reconstruct, Point};
//!
//! // Twelve points on a circle are one closed curve.
//! let points: Vec<Point> = (0..12)
//!     .map(|k| f64::from(k) * std::f64::consts::TAU / 12.0)
//!     .map(|angle| Point::new(angle.cos(), angle.sin()))
//!     .collect();
//! let reconstruction = reconstruct(&points)?;
//! assert_eq!(reconstruction.curves.len(), 1);
//! assert!(reconstruction.curves[0].closed);
//! # Ok::<(), crawltrace::ReconstructError>(())
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod batch;
pub mod files;
pub mod stages;

mod crawl;
mod export;
mod geometry;
mod output;
mod points;
mod raster;
mod strokes;
mod trace;

pub use kurbo::Point;

pub use crawl::reconstruct::{reconstruct, Curve, MergedDuplicate, Reconstruction};
pub use crawl::robust::reconstruct as reconstruct_robust;
pub use crawl::strokes::Method;
pub use crawl::ReconstructError;
pub use export::{export, ExportOptions, OutputFormat};
pub use output::dxf::to_dxf;
pub use output::render::{
    prepare_render, render_svg, render_svg_with, PreparedRender, RenderError, RenderOptions,
};
pub use output::svg::{to_svg, to_svg_with_size, CurvePath, Drawing};
pub use output::units::{Length, PhysicalSize, SizeRequest, SizeRequestError, Units, UnitsError};
pub use points::read::{parse_points, PointFile, PointFileError};
pub use raster::binarize::{BinarizeOptions, ThresholdMethod};
pub use trace::{
    trace, trace_bytes, trace_file, TraceError, TraceFileError, TraceOptions, TraceReport, Traced,
};
