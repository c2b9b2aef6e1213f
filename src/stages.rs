//! The stages of the pipeline (`docs/design.md`, "The pipeline"), one module each, in pipeline
//! order, for benchmarks, tests and front ends that run or time a stage on its own. The crate
//! root has the entry points that run them together.
//!
//! Images: [`decode`] → [`binarize`] → [`valleys`] → [`clean`] → [`thin`] (all on a
//! [`bitmap::Bitmap`]) → [`strokes`] (the skeleton's pen strokes, sampled) → [`crawl`] (curves) →
//! [`fit`] (paths) → [`svg`] or [`dxf`] (paths [`flatten`]ed), sized by [`units`] (with the
//! file's [`density`]); [`render`] draws SVG back into pixels and [`debug`] pictures every stage.
//!
//! Point sets: [`points`] reads point files and writes reconstructions; [`crawl`] reconstructs.
//!
//! [`geometry`] holds what several stages share.

pub use crate::output::{debug, dxf, fit, flatten, render, svg, units};
pub use crate::raster::{binarize, bitmap, clean, decode, density, radius, thin, valleys};

pub mod strokes {
    //! Skeleton → pen strokes → samples: the skeleton traced as a graph, pruned, its junctions
    //! paired by good continuation, and every stroke sampled for the crawl.
    pub use crate::strokes::{
        default_spacing, extract_strokes, extract_strokes_and_bands, minimum_spacing,
        sample_strokes, simplification_tolerance, split_dots, Dot, Stroke, StrokeEnd,
        MIN_SPACING_PX,
    };
}

pub mod crawl {
    //! The crawl (Parakkat & Muthuganapathy, 2016): [`algorithm`] is the paper's crawl on any
    //! [`neighbours::NeighbourGraph`] (the Delaunay triangulation is
    //! [`neighbours::NeighbourGraph::delaunay`]); [`reconstruct`] runs it on a point set with the
    //! paper's closing rule; [`robust`] is the robust crawl for point sets (stray points, sharp
    //! corners, open ends, thin parts); [`strokes`] runs it on sampled pen strokes, with bridges
    //! across the gaps between their free ends; [`tips`] puts back the acute tips thinning cut.
    pub use crate::crawl::{
        algorithm, neighbours, reconstruct, robust, strokes, tips, ReconstructError,
    };
}

pub mod points {
    //! Point sets on the command line: point files in ([`read`]), reconstructions out as JSON or
    //! as a drawing ([`write`](mod@write)).
    pub use crate::points::{read, write};
}

pub mod geometry {
    //! What several stages share: [`Polyline`] (length, simplification, resampling) and
    //! [`UnionFind`].
    pub use crate::geometry::{Polyline, UnionFind};
}
