//! Geometry shared by the stages: [`Polyline`] (length, simplification, resampling),
//! [`UnionFind`] and a grid of points for finding what lies near one (`grid::PointGrid`).

pub(crate) mod grid;
pub mod polyline;
pub mod union_find;

pub use polyline::Polyline;
pub use union_find::UnionFind;
