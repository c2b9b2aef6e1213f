//! Geometry shared by the stages: [`Polyline`] (length, simplification, resampling) and
//! [`UnionFind`].

pub mod polyline;
pub mod union_find;

pub use polyline::Polyline;
pub use union_find::UnionFind;
