//! Curve reconstruction by Crawl through Neighbors (Parakkat & Muthuganapathy, Computer Graphics
//! Forum 35(5), 2016, Algorithm 1) on spade's Delaunay triangulation.
//!
//! The crawl follows the paper's *text* (see `../shared/DESIGN.md`, "The crawl"):
//!
//! 1. **Seed**: the shortest graph edge whose two endpoints are unvisited and are each other's
//!    nearest neighbour.
//! 2. **Crawl**: of all edges from either extremity of the chain to an unvisited vertex, the shortest
//!    is the candidate (length `d`).
//! 3. **Terminate** when there is no candidate, or the chain has more than two edges and `d` is
//!    greater than the distance `d1` between its extremities (tested *before* the candidate is added).
//! 4. **Close** if the chain is closable (more than two edges and one extremity is the other's
//!    nearest or second-nearest Delaunay neighbour).
//! 5. Repeat; vertices that never join a chain are outliers.
//!
//! Decisions the paper leaves open are made at the spot they matter and marked `DECISION:`.
//! The crawl itself ([`crawl`]) runs on any [`NeighbourGraph`], so the raster pipeline can run it on
//! a graph that knows which samples belong to the same pen stroke.

use std::cmp::Ordering;
use std::collections::VecDeque;

use kurbo::Point;
use rayon::prelude::*;
use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation};

/// One reconstructed curve: a chain of input point indices.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Curve {
    /// Indices into the input point list, in order along the curve. A closed curve does not
    /// repeat its first index at the end.
    pub indices: Vec<usize>,
    /// Whether the last point connects back to the first.
    pub closed: bool,
}

/// A point that was dropped because another input point has exactly the same coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MergedDuplicate {
    /// The dropped point's input index.
    pub dropped: usize,
    /// The input index of the point it was merged into (the first one with those coordinates).
    pub kept: usize,
}

/// The result of reconstructing curves from a point set.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Reconstruction {
    /// The reconstructed curves, in the order the crawl found them, each in a canonical
    /// orientation (see [`reconstruct`]).
    pub curves: Vec<Curve>,
    /// Input indices of the points that belong to no curve, ascending.
    pub outliers: Vec<usize>,
    /// Exact duplicates that were merged before triangulating, in input order.
    pub merged_duplicates: Vec<MergedDuplicate>,
}

/// Why a point set could not be reconstructed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReconstructError {
    /// A coordinate is NaN or infinite.
    #[error("point {index} has a coordinate that is not a finite number")]
    NotFinite {
        /// Input index of the offending point.
        index: usize,
    },
    /// spade refused a coordinate (too large, or too close to zero without being zero).
    #[error("point {index} has a coordinate the triangulation cannot represent ({value:e}); the magnitude must lie between 1e-42 and 1e60, or be 0")]
    OutOfRange {
        /// Input index of the offending point.
        index: usize,
        /// The offending coordinate.
        value: f64,
    },
}

/// Reconstructs curves from a planar point set with no parameter.
///
/// This is [`NeighbourGraph::delaunay`] followed by [`crawl`] with [`paper_closable`], on the
/// distinct points in lexicographic order.
///
/// Exact duplicate points are merged into the first occurrence (reported in
/// [`Reconstruction::merged_duplicates`]). The result does not depend on the order of the input
/// points: ties between equal distances are broken by the points' coordinates, never by their
/// position in the input. Open curves start at their lexicographically smaller end (by x, then y);
/// closed curves start at their lexicographically smallest point and continue towards its smaller
/// neighbour.
pub fn reconstruct(points: &[Point]) -> Result<Reconstruction, ReconstructError> {
    let canonical = CanonicalPoints::new(points)?;
    let graph = NeighbourGraph::delaunay(&canonical.positions)?;
    let chains = crawl(&canonical.positions, &graph, |chain| {
        paper_closable(&canonical.positions, &graph, chain)
    });
    Ok(canonical.into_reconstruction(chains))
}

/// Reconstructs curves like [`reconstruct`], with `crawler` in place of the paper's crawl: the same
/// canonical points (distinct, in lexicographic order), Delaunay graph and output conventions.
/// Chains of fewer than three points are dropped, their points reported as outliers.
pub fn reconstruct_with(
    points: &[Point],
    crawler: impl FnOnce(&[Point], &NeighbourGraph) -> Vec<Chain>,
) -> Result<Reconstruction, ReconstructError> {
    let canonical = CanonicalPoints::new(points)?;
    let graph = NeighbourGraph::delaunay(&canonical.positions)?;
    let chains = crawler(&canonical.positions, &graph);
    Ok(canonical.into_reconstruction(chains))
}

/// The paper's closing rule: more than two edges, and one extremity is the other's nearest or
/// second-nearest neighbour.
///
/// DECISION: "second-nearest neighbour" means among *all* points, as the paper's text says, not
/// among Delaunay neighbours only (as DESIGN.md words it). With Delaunay neighbours only, any open
/// arc whose two ends are neighbours on the convex hull (a parabola, a "C") closes, because the
/// hull edge makes the far end the second Delaunay neighbour of an end vertex of degree two.
/// The closing edge must still be a Delaunay edge, so every output edge is one.
///
/// DECISION: ties count generously: the other extremity qualifies if it is no farther than the
/// second-nearest neighbour. On evenly spaced samples the chain neighbour and the other extremity
/// are often exactly equally far; breaking that tie by coordinates would leave perfectly sampled
/// circles open. A *nearest* extremity qualifies too.
pub fn paper_closable(positions: &[Point], graph: &NeighbourGraph, chain: &ChainEnds) -> bool {
    if chain.edge_count <= 2 || !graph.has_edge(chain.front, chain.back) {
        return false;
    }
    let gap = squared_distance(
        positions[chain.front as usize],
        positions[chain.back as usize],
    );
    [chain.front, chain.back].into_iter().any(|v| {
        graph
            .second_nearest_squared_distance(positions, v)
            .is_none_or(|d| gap <= d)
    })
}

/// The distinct input points in lexicographic order, with the way back to input indices.
///
/// Working in this order makes every tie-break (by vertex id) a tie-break by coordinates, so the
/// result is independent of input order, translation and scaling by powers of two.
struct CanonicalPoints {
    positions: Vec<Point>,
    /// For each canonical vertex, the smallest input index with its coordinates.
    input_index: Vec<usize>,
    merged_duplicates: Vec<MergedDuplicate>,
}

impl CanonicalPoints {
    fn new(points: &[Point]) -> Result<Self, ReconstructError> {
        for (index, p) in points.iter().enumerate() {
            if !(p.x.is_finite() && p.y.is_finite()) {
                return Err(ReconstructError::NotFinite { index });
            }
            for value in [p.x, p.y] {
                let magnitude = value.abs();
                if value != 0.0 && !(spade::MIN_ALLOWED_VALUE..=1e60).contains(&magnitude) {
                    return Err(ReconstructError::OutOfRange { index, value });
                }
            }
        }
        // Sorting by (x, y, input index) puts duplicates side by side with the first one leading.
        // -0.0 and 0.0 compare equal here, as they are the same position. The keys are sorted
        // directly (not indices by looking the points up), in parallel: this is a sort of n items.
        let mut order: Vec<(u64, u64, usize)> = points
            .par_iter()
            .enumerate()
            .map(|(i, p)| (ordered_bits(p.x), ordered_bits(p.y), i))
            .collect();
        order.par_sort_unstable();
        let mut positions = Vec::with_capacity(points.len());
        let mut input_index = Vec::with_capacity(points.len());
        let mut merged_duplicates = Vec::new();
        for &(_, _, i) in &order {
            let p = points[i];
            match positions.last() {
                Some(&last) if lexicographic(last, p) == Ordering::Equal => {
                    merged_duplicates.push(MergedDuplicate {
                        dropped: i,
                        kept: *input_index
                            .last()
                            .expect("positions and input_index grow together"),
                    });
                }
                _ => {
                    // Normalise -0.0 so that equal positions are bit-identical downstream.
                    positions.push(Point::new(p.x + 0.0, p.y + 0.0));
                    input_index.push(i);
                }
            }
        }
        merged_duplicates.sort_unstable_by_key(|d| d.dropped);
        Ok(Self {
            positions,
            input_index,
            merged_duplicates,
        })
    }

    fn into_reconstruction(self, chains: Vec<Chain>) -> Reconstruction {
        let mut in_curve = vec![false; self.positions.len()];
        let mut curves = Vec::new();
        for chain in chains {
            // DECISION: a chain of two points (one edge) is not a curve. It is what a pair of
            // stray points that are each other's nearest neighbours produces, and a single edge
            // carries no evidence of a curve; its points are reported as outliers. Chains of three
            // points (two edges) are kept as open curves: the paper never closes them.
            if chain.vertices.len() < 3 {
                continue;
            }
            for &v in &chain.vertices {
                in_curve[v as usize] = true;
            }
            let vertices = canonical_orientation(chain.vertices, chain.closed);
            curves.push(Curve {
                indices: vertices
                    .iter()
                    .map(|&v| self.input_index[v as usize])
                    .collect(),
                closed: chain.closed,
            });
        }
        let mut outliers: Vec<usize> = in_curve
            .iter()
            .enumerate()
            .filter(|(_, &used)| !used)
            .map(|(v, _)| self.input_index[v])
            .collect();
        outliers.sort_unstable();
        Reconstruction {
            curves,
            outliers,
            merged_duplicates: self.merged_duplicates,
        }
    }
}

/// A key whose unsigned order is the numeric order of finite `f64` values, with -0.0 = 0.0.
fn ordered_bits(value: f64) -> u64 {
    let bits = (value + 0.0).to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | (1 << 63)
    }
}

fn lexicographic(a: Point, b: Point) -> Ordering {
    a.x.partial_cmp(&b.x)
        .unwrap_or(Ordering::Equal)
        .then(a.y.partial_cmp(&b.y).unwrap_or(Ordering::Equal))
}

/// Open chains start at the end with the smaller vertex id; closed chains start at their smallest
/// id and go towards the smaller of its two neighbours. Vertex ids are canonical, so this
/// orientation is a property of the geometry alone.
pub fn canonical_orientation(vertices: VecDeque<u32>, closed: bool) -> Vec<u32> {
    let mut vertices: Vec<u32> = vertices.into();
    if vertices.len() < 2 {
        return vertices;
    }
    if closed {
        let start = (0..vertices.len())
            .min_by_key(|&i| vertices[i])
            .expect("non-empty");
        vertices.rotate_left(start);
        if vertices[vertices.len() - 1] < vertices[1] {
            vertices[1..].reverse();
        }
    } else if vertices[vertices.len() - 1] < vertices[0] {
        vertices.reverse();
    }
    vertices
}

/// An undirected graph on points whose adjacency lists are sorted by edge length (ties by
/// neighbour id), stored compactly (compressed sparse rows).
#[derive(Clone, Debug, Default)]
pub struct NeighbourGraph {
    offsets: Vec<usize>,
    neighbours: Vec<u32>,
    squared_lengths: Vec<f64>,
}

/// A vertex handed to spade: its position and our id for it.
#[derive(Clone, Copy, Debug)]
struct IdentifiedVertex {
    position: Point2<f64>,
    id: u32,
}

impl HasPosition for IdentifiedVertex {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.position
    }
}

impl NeighbourGraph {
    /// The Delaunay triangulation of `positions`, which must be distinct and finite.
    ///
    /// Points are inserted one by one in a *biased randomized insertion order* (Amenta, Choi &
    /// Rote 2003): random rounds of doubling size, each along a Hilbert curve. spade's `bulk_load`
    /// (a circle sweep) is fast on uniform points but slow on points along curves, the input this
    /// crate exists for: on the 2-core machine, 1M points on closed curves took about 12 s
    /// against 0.9 s for 1M uniform points, nearly all of it in edge flips and exact in-circle
    /// tests. Randomized insertion keeps the expected number of flips per point constant whatever
    /// the input; the Hilbert order keeps each insertion's walk short. The rounds come from a hash
    /// of the vertex id, so the order, and with it the triangulation chosen among several equally
    /// Delaunay ones when points are cocircular, depends on the positions alone.
    ///
    /// Points that all lie on one line have no triangle, and spade sorts all vertices at every
    /// insertion while that lasts (20 000 collinear points took 46 s through `bulk_load`); such
    /// points are joined in order along their line here, and otherwise a point off the line is
    /// inserted third.
    pub fn delaunay(positions: &[Point]) -> Result<Self, ReconstructError> {
        let n = positions.len();
        assert!(
            u32::try_from(n).is_ok(),
            "more than 4 billion points cannot be numbered with u32"
        );
        if n < 2 {
            return Ok(Self::from_edges(positions, []));
        }
        let position = |v: u32| Point2::new(positions[v as usize].x, positions[v as usize].y);
        let vertex = |v: u32| IdentifiedVertex {
            position: position(v),
            id: v,
        };
        let mut order = insertion_order(positions);
        let mut triangulation: DelaunayTriangulation<IdentifiedVertex> =
            DelaunayTriangulation::with_capacity(n, 3 * n, 2 * n);
        let out_of_range = |v: u32| {
            let p = positions[v as usize];
            ReconstructError::OutOfRange {
                index: v as usize,
                value: if spade::validate_coordinate(p.x).is_err() {
                    p.x
                } else {
                    p.y
                },
            }
        };
        let insert = |triangulation: &mut DelaunayTriangulation<IdentifiedVertex>, v: u32| {
            triangulation
                .insert(vertex(v))
                .map(|_| ())
                .map_err(|_| out_of_range(v))
        };
        // The first two are the lexicographically smallest and largest points, so distinct.
        insert(&mut triangulation, order[0])?;
        insert(&mut triangulation, order[1])?;
        // Insert a point off their line third: while all points are on one line, spade sorts
        // them all at every insertion.
        // (No edge only if the caller broke the promise of distinct positions.)
        let Some(line) = triangulation.directed_edges().next() else {
            return Ok(Self::collinear(positions));
        };
        let Some(third) = order[2..]
            .iter()
            .position(|&v| !line.side_query(position(v)).is_on_line())
            .map(|k| k + 2)
        else {
            return Ok(Self::collinear(positions));
        };
        insert(&mut triangulation, order[third])?;
        // Gathered in insertion order first: reading positions in that order inside the insertion
        // loop would stall it on a cache miss per point.
        order.swap(2, third);
        let rest: Vec<IdentifiedVertex> = order[3..].par_iter().map(|&v| vertex(v)).collect();
        for v in rest {
            triangulation.insert(v).map_err(|_| out_of_range(v.id))?;
        }
        debug_assert_eq!(triangulation.num_vertices(), n);

        // Adjacency lists from passes over the edges in memory order, looking ids up by vertex
        // handle in a compact table (spade's own vertex records are larger and farther apart).
        // Walking each vertex's edges instead chases pointers all over the edge list.
        let id_of_handle: Vec<u32> = triangulation.vertices().map(|v| v.data().id).collect();
        let handles: Vec<_> = triangulation.fixed_undirected_edges().collect();
        let edges: Vec<(u32, u32)> = handles
            .par_iter()
            .map(|&handle| {
                let [a, b] = triangulation.undirected_edge(handle).vertices();
                (id_of_handle[a.fix().index()], id_of_handle[b.fix().index()])
            })
            .collect();
        drop(handles);
        drop(triangulation);
        Ok(Self::from_edge_list(positions, &edges))
    }

    /// A graph with the given undirected edges, which must be distinct and not loops.
    ///
    /// The vertices are split into one range per thread; each thread reads every edge and fills
    /// in the adjacency lists of its own range, so no two threads write to the same place.
    fn from_edge_list(positions: &[Point], edges: &[(u32, u32)]) -> Self {
        let n = positions.len();
        let parts = rayon::current_num_threads().clamp(1, 64).min(n.max(1));
        let bounds: Vec<usize> = (0..=parts).map(|k| n * k / parts).collect();
        let degrees: Vec<Vec<u32>> = (0..parts)
            .into_par_iter()
            .map(|k| {
                let range = bounds[k]..bounds[k + 1];
                let mut degree = vec![0u32; range.len()];
                for &(a, b) in edges {
                    for v in [a as usize, b as usize] {
                        if range.contains(&v) {
                            degree[v - range.start] += 1;
                        }
                    }
                }
                degree
            })
            .collect();
        let mut offsets = Vec::with_capacity(n + 1);
        offsets.push(0usize);
        for degree in degrees.iter().flatten() {
            offsets.push(offsets.last().expect("starts with 0") + *degree as usize);
        }
        drop(degrees);
        let mut neighbours = vec![0u32; offsets[n]];
        let mut pieces = Vec::with_capacity(parts);
        let mut rest = &mut neighbours[..];
        for k in 0..parts {
            let (piece, more) = rest.split_at_mut(offsets[bounds[k + 1]] - offsets[bounds[k]]);
            pieces.push((bounds[k]..bounds[k + 1], piece));
            rest = more;
        }
        pieces.into_par_iter().for_each(|(range, piece)| {
            let base = offsets[range.start];
            let mut next_slot: Vec<usize> =
                offsets[range.clone()].iter().map(|o| o - base).collect();
            for &(a, b) in edges {
                for (from, to) in [(a, b), (b, a)] {
                    let from = from as usize;
                    if range.contains(&from) {
                        let slot = &mut next_slot[from - range.start];
                        piece[*slot] = to;
                        *slot += 1;
                    }
                }
            }
        });
        Self::with_sorted_adjacency(positions, offsets, neighbours)
    }

    /// The path through collinear `positions` in order along their line.
    fn collinear(positions: &[Point]) -> Self {
        let mut along: Vec<u32> = (0..positions.len() as u32).collect();
        along
            .sort_unstable_by(|&a, &b| lexicographic(positions[a as usize], positions[b as usize]));
        Self::from_edges(positions, along.windows(2).map(|pair| (pair[0], pair[1])))
    }

    /// Measures each edge and sorts each adjacency list by (length, neighbour id).
    fn with_sorted_adjacency(
        positions: &[Point],
        offsets: Vec<usize>,
        mut neighbours: Vec<u32>,
    ) -> Self {
        let vertex_count = offsets.len() - 1;
        let mut squared_lengths = vec![0.0; neighbours.len()];
        // Vertices in blocks, each block's lists sorted on its own thread.
        const BLOCK: usize = 4096;
        let mut blocks = Vec::new();
        let (mut rest_neighbours, mut rest_lengths) =
            (&mut neighbours[..], &mut squared_lengths[..]);
        for first in (0..vertex_count).step_by(BLOCK) {
            let last = (first + BLOCK).min(vertex_count);
            let size = offsets[last] - offsets[first];
            let (block_neighbours, more_neighbours) = rest_neighbours.split_at_mut(size);
            let (block_lengths, more_lengths) = rest_lengths.split_at_mut(size);
            blocks.push((first..last, block_neighbours, block_lengths));
            (rest_neighbours, rest_lengths) = (more_neighbours, more_lengths);
        }
        blocks
            .into_par_iter()
            .for_each(|(vertices, block_neighbours, block_lengths)| {
                let base = offsets[vertices.start];
                let mut scratch: Vec<(f64, u32)> = Vec::new();
                for v in vertices {
                    let range = offsets[v] - base..offsets[v + 1] - base;
                    scratch.clear();
                    scratch.extend(
                        block_neighbours[range.clone()]
                            .iter()
                            .map(|&w| (squared_distance(positions[v], positions[w as usize]), w)),
                    );
                    scratch.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                    for (k, &(length, w)) in scratch.iter().enumerate() {
                        block_lengths[range.start + k] = length;
                        block_neighbours[range.start + k] = w;
                    }
                }
            });
        Self {
            offsets,
            neighbours,
            squared_lengths,
        }
    }

    /// A graph with the given undirected edges; duplicate edges and self-loops are ignored.
    pub fn from_edges(positions: &[Point], edges: impl IntoIterator<Item = (u32, u32)>) -> Self {
        let mut pairs: Vec<(u32, u32)> = edges
            .into_iter()
            .filter(|(a, b)| a != b)
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect();
        pairs.par_sort_unstable();
        pairs.dedup();
        Self::from_edge_list(positions, &pairs)
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Number of undirected edges.
    pub fn edge_count(&self) -> usize {
        self.neighbours.len() / 2
    }

    /// The neighbours of `v`, nearest first.
    pub fn neighbours(&self, v: u32) -> &[u32] {
        &self.neighbours[self.offsets[v as usize]..self.offsets[v as usize + 1]]
    }

    /// The squared lengths of the edges to [`Self::neighbours`]`(v)`, in the same order.
    pub fn squared_lengths(&self, v: u32) -> &[f64] {
        &self.squared_lengths[self.offsets[v as usize]..self.offsets[v as usize + 1]]
    }

    /// Whether `v` and `w` are joined by an edge.
    pub fn has_edge(&self, v: u32, w: u32) -> bool {
        self.neighbours(v).contains(&w)
    }

    /// The squared distance from `v` to its second-nearest point among all vertices, if it has
    /// two neighbours at all.
    ///
    /// On a Delaunay triangulation the k-th nearest neighbour of a vertex is adjacent to the vertex
    /// or to one of its k-1 nearest neighbours (Dickerson, Drysdale & Sack, 1992), so for k = 2 it
    /// is the nearer of `v`'s second neighbour and the neighbours of `v`'s nearest one.
    pub fn second_nearest_squared_distance(&self, positions: &[Point], v: u32) -> Option<f64> {
        let nearest = *self.neighbours(v).first()?;
        let beside_v = self.squared_lengths(v).get(1).copied();
        let beside_nearest = self
            .neighbours(nearest)
            .iter()
            .filter(|&&w| w != v)
            .map(|&w| squared_distance(positions[v as usize], positions[w as usize]))
            .min_by(f64::total_cmp);
        match (beside_v, beside_nearest) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

/// The order [`NeighbourGraph::delaunay`] inserts vertices in: the lexicographically smallest and
/// largest points first, then a biased randomized insertion order (BRIO): each vertex is drawn into
/// a round by a hash of its id (round k holds about n / 2^(k+1) vertices; the largest round goes
/// last), and each round runs along a Hilbert curve.
fn insertion_order(positions: &[Point]) -> Vec<u32> {
    let (mut smallest, mut largest) = (0u32, 0u32);
    let (mut low, mut high) = (positions[0], positions[0]);
    for (v, &p) in positions.iter().enumerate() {
        if lexicographic(p, positions[smallest as usize]) == Ordering::Less {
            smallest = v as u32;
        }
        if lexicographic(p, positions[largest as usize]) == Ordering::Greater {
            largest = v as u32;
        }
        low = Point::new(low.x.min(p.x), low.y.min(p.y));
        high = Point::new(high.x.max(p.x), high.y.max(p.y));
    }
    // Map the bounding box onto the Hilbert grid. Differences from the box corner and the
    // scale change exactly under translations and power-of-two scalings of dyadic inputs.
    let extent = (high.x - low.x).max(high.y - low.y);
    let scale = if extent > 0.0 {
        f64::from(HILBERT_SIDE - 1) / extent
    } else {
        0.0
    };
    let cell = |value: f64, origin: f64| {
        ((value - origin) * scale).clamp(0.0, f64::from(HILBERT_SIDE - 1)) as u32
    };
    // One u64 per vertex, sorted: the round (6 bits), the Hilbert index (26 bits), then the id
    // (32 bits) to make every key distinct. The two extreme points get round 0, the smallest
    // first; every other round is at least 1.
    let mut keys: Vec<u64> = positions
        .par_iter()
        .enumerate()
        .map(|(v, p)| {
            let v = v as u32;
            let (round, along) = if v == smallest {
                (0, 0)
            } else if v == largest {
                (0, 1)
            } else {
                let round = BRIO_ROUNDS + 1 - brio_level(v);
                (round, hilbert_index(cell(p.x, low.x), cell(p.y, low.y)))
            };
            (u64::from(round) << 58) | (u64::from(along) << 32) | u64::from(v)
        })
        .collect();
    keys.par_sort_unstable();
    keys.into_par_iter().map(|key| key as u32).collect()
}

/// Number of BRIO rounds beyond the first; more than enough for 2^32 points (and less than 2^6).
const BRIO_ROUNDS: u32 = 32;

/// Side of the Hilbert grid: 2^13 cells, so that an index fits in 26 bits.
const HILBERT_SIDE: u32 = 1 << 13;

/// The BRIO level of a vertex: 0 with probability 1/2, 1 with probability 1/4, …; higher levels are
/// inserted earlier. A SplitMix64 hash of the id stands in for a random draw.
fn brio_level(v: u32) -> u32 {
    let mut z = u64::from(v).wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    z.leading_zeros().min(BRIO_ROUNDS)
}

/// The position of cell (x, y) along the Hilbert curve filling the HILBERT_SIDE² grid.
fn hilbert_index(mut x: u32, mut y: u32) -> u32 {
    let mut index = 0u32;
    let mut half = HILBERT_SIDE / 2;
    while half > 0 {
        let right = u32::from(x & half != 0);
        let up = u32::from(y & half != 0);
        index += half * half * ((3 * right) ^ up);
        // Turn the quadrant so that the curve inside it runs the standard way.
        if up == 0 {
            if right == 1 {
                x = HILBERT_SIDE - 1 - x;
                y = HILBERT_SIDE - 1 - y;
            }
            std::mem::swap(&mut x, &mut y);
        }
        half /= 2;
    }
    index
}

/// The squared Euclidean distance between two points.
pub fn squared_distance(a: Point, b: Point) -> f64 {
    let (dx, dy) = (a.x - b.x, a.y - b.y);
    dx * dx + dy * dy
}

/// A chain the crawl built: vertex ids in order, and whether it was closed.
#[derive(Clone, Debug)]
pub struct Chain {
    /// Vertex ids in order along the chain.
    pub vertices: VecDeque<u32>,
    /// Whether the closing edge between the two ends was added.
    pub closed: bool,
}

/// What a closing rule sees of a terminated chain.
#[derive(Clone, Copy, Debug)]
pub struct ChainEnds {
    /// One extremity.
    pub front: u32,
    /// The other extremity.
    pub back: u32,
    /// Number of edges in the chain (vertices − 1).
    pub edge_count: usize,
}

/// Runs the crawl on `graph` (whose vertices are `positions`) and returns every chain it built,
/// in the order of their seeds, including chains of two vertices.
///
/// `closable` decides, for a terminated chain, whether to add the edge between its extremities.
pub fn crawl(
    positions: &[Point],
    graph: &NeighbourGraph,
    mut closable: impl FnMut(&ChainEnds) -> bool,
) -> Vec<Chain> {
    let n = graph.vertex_count();
    let mut visited = VisitedSet::new(n);
    // The next not-yet-visited entry of each adjacency list. Vertices only ever become visited, so
    // these only move forward: finding candidates costs O(total degree) over the whole crawl.
    let mut cursor: Vec<usize> = graph.offsets[..n].to_vec();
    let mut chains = Vec::new();

    for (a, b) in seed_edges(graph) {
        if visited.contains(a) || visited.contains(b) {
            continue;
        }
        visited.insert(a);
        visited.insert(b);
        let mut vertices = VecDeque::from([a, b]);
        let mut edge_count = 1usize;
        loop {
            let front = *vertices.front().expect("chain has two ends");
            let back = *vertices.back().expect("chain has two ends");
            let at_front = nearest_unvisited(graph, &visited, &mut cursor, front);
            let at_back = nearest_unvisited(graph, &visited, &mut cursor, back);
            // DECISION: when both extremities offer candidates of exactly equal length, the one
            // with the smaller vertex id (lexicographically smaller point) wins; then the front.
            let candidate = match (at_front, at_back) {
                (None, None) => break,
                (Some(f), None) => (true, f),
                (None, Some(b)) => (false, b),
                (Some(f), Some(b)) => {
                    let back_is_better = b.1.total_cmp(&f.1).then(b.0.cmp(&f.0)) == Ordering::Less;
                    if back_is_better {
                        (false, b)
                    } else {
                        (true, f)
                    }
                }
            };
            let (at_front_end, (vertex, squared_length)) = candidate;
            if edge_count > 2 {
                // DECISION: "d > d1" is strict; a candidate exactly as long as the gap between
                // the extremities is still added.
                let squared_gap =
                    squared_distance(positions[front as usize], positions[back as usize]);
                if squared_length > squared_gap {
                    break;
                }
            }
            visited.insert(vertex);
            if at_front_end {
                vertices.push_front(vertex);
            } else {
                vertices.push_back(vertex);
            }
            edge_count += 1;
        }
        let ends = ChainEnds {
            front: *vertices.front().expect("chain has two ends"),
            back: *vertices.back().expect("chain has two ends"),
            edge_count,
        };
        let closed = closable(&ends);
        chains.push(Chain { vertices, closed });
    }
    chains
}

/// The vertices the crawl has visited, one bit each: the crawl tests a vertex for every edge it
/// looks at, and a bit set of a million vertices (128 KiB) stays in cache where a `bool` each
/// would not.
struct VisitedSet {
    words: Vec<u64>,
}

impl VisitedSet {
    fn new(vertex_count: usize) -> Self {
        Self {
            words: vec![0; vertex_count.div_ceil(64)],
        }
    }

    fn contains(&self, v: u32) -> bool {
        self.words[(v / 64) as usize] & (1 << (v % 64)) != 0
    }

    fn insert(&mut self, v: u32) {
        self.words[(v / 64) as usize] |= 1 << (v % 64);
    }
}

/// The nearest unvisited neighbour of `v` and its squared distance.
fn nearest_unvisited(
    graph: &NeighbourGraph,
    visited: &VisitedSet,
    cursor: &mut [usize],
    v: u32,
) -> Option<(u32, f64)> {
    let end = graph.offsets[v as usize + 1];
    let at = &mut cursor[v as usize];
    while *at < end && visited.contains(graph.neighbours[*at]) {
        *at += 1;
    }
    (*at < end).then(|| (graph.neighbours[*at], graph.squared_lengths[*at]))
}

/// Every edge whose endpoints are each other's nearest neighbour, shortest first.
///
/// DECISION: "nearest neighbour" is taken over all neighbours (visited or not) and counts ties: an
/// edge qualifies when no neighbour of either endpoint is strictly closer. The set is therefore
/// fixed before the crawl, and a stray point, whose nearest neighbour lies on a curve that is
/// nearer to something else, never seeds a chain. Equal seeds are ordered by their vertex ids.
fn seed_edges(graph: &NeighbourGraph) -> Vec<(u32, u32)> {
    let n = graph.vertex_count() as u32;
    let nearest = |v: u32| graph.squared_lengths(v).first().copied();
    let mut seeds: Vec<(f64, u32, u32)> = Vec::new();
    for v in 0..n {
        let Some(nearest_v) = nearest(v) else {
            continue;
        };
        for (&w, &length) in graph.neighbours(v).iter().zip(graph.squared_lengths(v)) {
            if length > nearest_v {
                break;
            }
            if w > v && nearest(w) == Some(length) {
                seeds.push((length, v, w));
            }
        }
    }
    seeds.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then((a.1, a.2).cmp(&(b.1, b.2))));
    seeds.into_iter().map(|(_, v, w)| (v, w)).collect()
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;
    use std::f64::consts::TAU;

    use super::*;

    /// `count` points on an ellipse, evenly spaced in angle, starting at `phase`.
    fn ellipse(center: (f64, f64), radii: (f64, f64), count: usize, phase: f64) -> Vec<Point> {
        (0..count)
            .map(|i| {
                let angle = phase + TAU * i as f64 / count as f64;
                Point::new(
                    center.0 + radii.0 * angle.cos(),
                    center.1 + radii.1 * angle.sin(),
                )
            })
            .collect()
    }

    /// The undirected edges of consecutive indices in `range`, closed or not.
    fn chain_edges(range: std::ops::Range<usize>, closed: bool) -> BTreeSet<(usize, usize)> {
        let v: Vec<usize> = range.collect();
        let mut edges: BTreeSet<(usize, usize)> = v
            .windows(2)
            .map(|w| (w[0].min(w[1]), w[0].max(w[1])))
            .collect();
        if closed {
            edges.insert((v[0].min(v[v.len() - 1]), v[0].max(v[v.len() - 1])));
        }
        edges
    }

    fn edges_of(result: &Reconstruction) -> BTreeSet<(usize, usize)> {
        let mut edges = BTreeSet::new();
        for curve in &result.curves {
            let i = &curve.indices;
            for w in i.windows(2) {
                edges.insert((w[0].min(w[1]), w[0].max(w[1])));
            }
            if curve.closed {
                edges.insert((i[0].min(i[i.len() - 1]), i[0].max(i[i.len() - 1])));
            }
        }
        edges
    }

    fn closed_flags(result: &Reconstruction) -> Vec<bool> {
        let mut flags: Vec<bool> = result.curves.iter().map(|c| c.closed).collect();
        flags.sort();
        flags
    }

    #[test]
    fn circle_is_one_closed_curve() {
        let points = ellipse((0.0, 0.0), (10.0, 10.0), 24, 0.1);
        let result = reconstruct(&points).unwrap();
        assert_eq!(closed_flags(&result), vec![true]);
        assert_eq!(edges_of(&result), chain_edges(0..24, true));
        assert!(result.outliers.is_empty());
    }

    #[test]
    fn perfectly_even_circle_closes_despite_equal_distances() {
        // Every edge has the same length up to rounding: the tie rules must still close it.
        let points = ellipse((0.0, 0.0), (1.0, 1.0), 12, 0.0);
        let result = reconstruct(&points).unwrap();
        assert_eq!(closed_flags(&result), vec![true]);
        assert_eq!(edges_of(&result), chain_edges(0..12, true));
    }

    #[test]
    fn ellipse_is_one_closed_curve() {
        let points = ellipse((5.0, -3.0), (30.0, 10.0), 60, 0.05);
        let result = reconstruct(&points).unwrap();
        assert_eq!(closed_flags(&result), vec![true]);
        assert_eq!(edges_of(&result), chain_edges(0..60, true));
    }

    #[test]
    fn nested_curves_stay_apart() {
        let mut points = ellipse((0.0, 0.0), (10.0, 10.0), 48, 0.0);
        points.extend(ellipse((0.5, 0.0), (5.0, 4.0), 30, 0.2));
        let result = reconstruct(&points).unwrap();
        assert_eq!(closed_flags(&result), vec![true, true]);
        let mut expected = chain_edges(0..48, true);
        expected.extend(chain_edges(48..78, true));
        assert_eq!(edges_of(&result), expected);
    }

    #[test]
    fn separate_objects_are_separate_curves() {
        let mut points = ellipse((0.0, 0.0), (5.0, 5.0), 20, 0.0);
        points.extend(ellipse((20.0, 0.0), (6.0, 3.0), 24, 0.3));
        points.extend(ellipse((0.0, 20.0), (4.0, 7.0), 26, 0.7));
        let result = reconstruct(&points).unwrap();
        assert_eq!(closed_flags(&result), vec![true, true, true]);
        let mut expected = chain_edges(0..20, true);
        expected.extend(chain_edges(20..44, true));
        expected.extend(chain_edges(44..70, true));
        assert_eq!(edges_of(&result), expected);
    }

    #[test]
    fn open_arc_stays_open_and_ordered() {
        // A parabola: its two ends are neighbours on the convex hull, the case a Delaunay-only
        // reading of "second-nearest neighbour" gets wrong.
        let points: Vec<Point> = (0..20)
            .map(|i| {
                let x = 10.0 - 20.0 * i as f64 / 19.0;
                Point::new(x, x * x / 10.0)
            })
            .collect();
        let result = reconstruct(&points).unwrap();
        assert_eq!(result.curves.len(), 1);
        let curve = &result.curves[0];
        assert!(!curve.closed);
        // Starts at the lexicographically smaller end (-10, 10), i.e. index 19.
        assert_eq!(curve.indices, (0..20).rev().collect::<Vec<_>>());
    }

    #[test]
    fn sharp_corners_are_kept() {
        // A square and an L sampled along their sides: corners are sample points.
        let mut points = Vec::new();
        let square = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)];
        for k in 0..4 {
            let (a, b) = (square[k], square[(k + 1) % 4]);
            for i in 0..10 {
                let t = i as f64 / 10.0;
                points.push(Point::new(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            }
        }
        // An L with a reflex corner, sampled every 1 along its sides.
        let l_shape = [
            (20.0, 0.0),
            (30.0, 0.0),
            (30.0, 4.0),
            (24.0, 4.0),
            (24.0, 10.0),
            (20.0, 10.0),
        ];
        for k in 0..l_shape.len() {
            let (a, b): ((f64, f64), (f64, f64)) = (l_shape[k], l_shape[(k + 1) % l_shape.len()]);
            let steps = ((b.0 - a.0).abs() + (b.1 - a.1).abs()) as usize;
            for i in 0..steps {
                let t = i as f64 / steps as f64;
                points.push(Point::new(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            }
        }
        let result = reconstruct(&points).unwrap();
        assert_eq!(closed_flags(&result), vec![true, true]);
        let mut expected = chain_edges(0..40, true);
        expected.extend(chain_edges(40..points.len(), true));
        assert_eq!(edges_of(&result), expected);
    }

    #[test]
    fn stray_points_stay_outliers_and_do_not_bend_the_curve() {
        let mut points = ellipse((0.0, 0.0), (10.0, 10.0), 40, 0.0);
        // Spacing on the circle is about 1.57; these are 3 to 6 away from it and from each other.
        points.push(Point::new(0.0, 0.0));
        points.push(Point::new(14.0, 0.5));
        points.push(Point::new(-4.0, 16.0));
        points.push(Point::new(5.0, -15.0));
        let result = reconstruct(&points).unwrap();
        assert_eq!(closed_flags(&result), vec![true]);
        assert_eq!(edges_of(&result), chain_edges(0..40, true));
        assert_eq!(result.outliers, vec![40, 41, 42, 43]);
    }

    #[test]
    fn sparse_samples_of_a_smooth_curve() {
        // Eight points on a circle: sparse, yet every point's nearest neighbours are its curve
        // neighbours.
        let points = ellipse((3.0, 4.0), (2.0, 2.0), 8, 0.4);
        let result = reconstruct(&points).unwrap();
        assert_eq!(edges_of(&result), chain_edges(0..8, true));
    }

    /// The triangulation's edges as sorted pairs.
    fn graph_edges(graph: &NeighbourGraph) -> BTreeSet<(u32, u32)> {
        (0..graph.vertex_count() as u32)
            .flat_map(|v| {
                graph
                    .neighbours(v)
                    .iter()
                    .map(move |&w| (v.min(w), v.max(w)))
            })
            .collect()
    }

    #[test]
    fn delaunay_matches_spade_bulk_load_and_sorts_each_adjacency() {
        // A jittered grid, not in lexicographic order: no four points cocircular, so the
        // Delaunay triangulation is unique and any construction must find it.
        let points: Vec<Point> = (0..400)
            .map(|k| {
                let (i, j) = ((k * 7) % 20, (k * 7) / 20);
                let wobble = ((k * 2654435761_u64 as usize) % 1000) as f64 / 4000.0;
                Point::new(i as f64 + wobble, j as f64 - wobble / 2.0)
            })
            .collect();
        let graph = NeighbourGraph::delaunay(&points).unwrap();
        let vertices: Vec<IdentifiedVertex> = points
            .iter()
            .enumerate()
            .map(|(i, p)| IdentifiedVertex {
                position: Point2::new(p.x, p.y),
                id: i as u32,
            })
            .collect();
        let reference: DelaunayTriangulation<IdentifiedVertex> =
            DelaunayTriangulation::bulk_load(vertices).unwrap();
        let expected: BTreeSet<(u32, u32)> = reference
            .undirected_edges()
            .map(|edge| {
                let [a, b] = edge.vertices().map(|v| v.data().id);
                (a.min(b), a.max(b))
            })
            .collect();
        assert_eq!(graph_edges(&graph), expected);
        for v in 0..points.len() as u32 {
            let pairs: Vec<(f64, u32)> = graph
                .squared_lengths(v)
                .iter()
                .copied()
                .zip(graph.neighbours(v).iter().copied())
                .collect();
            assert!(
                pairs.windows(2).all(|w| w[0] <= w[1]),
                "vertex {v}: {pairs:?}"
            );
            for &(length, w) in &pairs {
                assert_eq!(
                    length,
                    squared_distance(points[v as usize], points[w as usize])
                );
            }
        }
    }

    #[test]
    fn collinear_points_are_joined_along_their_line() {
        // Shuffled points of a vertical and of a slanted line, each in its own graph.
        for direction in [(0.0, 1.0), (3.0, -2.0)] {
            let steps = [5, 0, 9, 3, 1, 8, 2, 7, 4, 6];
            let points: Vec<Point> = steps
                .iter()
                .map(|&k| Point::new(1.0 + direction.0 * k as f64, 2.0 + direction.1 * k as f64))
                .collect();
            let graph = NeighbourGraph::delaunay(&points).unwrap();
            let index_of = |step: usize| steps.iter().position(|&k| k == step).unwrap() as u32;
            let expected: BTreeSet<(u32, u32)> = (0..9)
                .map(|k| {
                    let (a, b) = (index_of(k), index_of(k + 1));
                    (a.min(b), a.max(b))
                })
                .collect();
            assert_eq!(graph_edges(&graph), expected, "direction {direction:?}");
        }
    }

    #[test]
    fn many_collinear_points_and_one_off_the_line() {
        // Large enough that a quadratic treatment of collinear points would take minutes.
        let mut points: Vec<Point> = (0..20_000)
            .map(|k| Point::new(((k * 7919) % 20_000) as f64 * 0.5, 3.0))
            .collect();
        let collinear = reconstruct(&points).unwrap();
        assert_eq!(collinear.curves.len(), 1);
        assert_eq!(collinear.curves[0].indices.len(), 20_000);
        points.push(Point::new(10.25, 4.0));
        let graph = NeighbourGraph::delaunay(&points).unwrap();
        // The fan from the apex to every point of the line, plus the line itself.
        assert_eq!(graph.edge_count(), 2 * 20_000 - 1);
        assert_eq!(graph.neighbours(20_000).len(), 20_000);
    }

    #[test]
    fn insertion_order_is_a_permutation_starting_at_the_extremes() {
        let points = ellipse((0.0, 0.0), (3.0, 1.0), 500, 0.3);
        let order = insertion_order(&points);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..500).collect::<Vec<u32>>());
        let extreme = |ordering: Ordering| {
            (0..500u32)
                .find(|&v| {
                    points
                        .iter()
                        .all(|&q| lexicographic(points[v as usize], q) != ordering.reverse())
                })
                .unwrap()
        };
        assert_eq!(order[0], extreme(Ordering::Less));
        assert_eq!(order[1], extreme(Ordering::Greater));
    }

    #[test]
    fn hilbert_index_visits_every_cell_once_moving_one_step_at_a_time() {
        // The curve starts at the origin and fills the lower-left 2^k × 2^k square with its first
        // 4^k cells, one step at a time; checking that for k = 6 checks the recursion.
        let side = 64u32;
        let mut cells: Vec<(u32, (u32, u32))> = (0..side)
            .flat_map(|x| (0..side).map(move |y| (hilbert_index(x, y), (x, y))))
            .collect();
        cells.sort_unstable();
        let indices: BTreeSet<u32> = cells.iter().map(|&(index, _)| index).collect();
        assert_eq!(indices.len(), cells.len());
        assert_eq!(*indices.iter().next_back().unwrap(), side * side - 1);
        for pair in cells.windows(2) {
            let ((x0, y0), (x1, y1)) = (pair[0].1, pair[1].1);
            assert_eq!(x0.abs_diff(x1) + y0.abs_diff(y1), 1, "{pair:?}");
        }
    }

    #[test]
    fn tiny_inputs_do_not_panic() {
        assert_eq!(reconstruct(&[]).unwrap(), Reconstruction::default());
        let one = reconstruct(&[Point::new(1.0, 2.0)]).unwrap();
        assert_eq!(one.outliers, vec![0]);
        assert!(one.curves.is_empty());
        let two = reconstruct(&[Point::new(1.0, 2.0), Point::new(3.0, 2.0)]).unwrap();
        assert_eq!(two.outliers, vec![0, 1], "a single edge is not a curve");
        let three = reconstruct(&[
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(0.0, 1.0),
        ])
        .unwrap();
        assert_eq!(three.curves.len(), 1);
        assert!(
            !three.curves[0].closed,
            "a triangle has only two edges before closing"
        );
    }

    #[test]
    fn collinear_points_make_one_open_polyline() {
        // Shuffled input order; x positions 0..30 with uneven gaps.
        let xs = [7.0, 0.0, 29.0, 3.0, 12.0, 1.0, 20.0, 5.0, 16.0, 9.0];
        let points: Vec<Point> = xs.iter().map(|&x| Point::new(x, 2.0 * x)).collect();
        let result = reconstruct(&points).unwrap();
        let mut sorted: Vec<usize> = (0..xs.len()).collect();
        sorted.sort_by(|&a, &b| xs[a].total_cmp(&xs[b]));
        // The long last gap (20 → 29) may end the chain early; all else must be one path.
        let covered: usize = result.curves.iter().map(|c| c.indices.len()).sum();
        assert_eq!(covered + result.outliers.len(), xs.len());
        assert!(result.curves.iter().all(|c| !c.closed));
        let first = &result.curves[0].indices;
        assert!(
            sorted.windows(first.len()).any(|w| w == first.as_slice()),
            "{first:?}"
        );
    }

    #[test]
    fn duplicates_are_merged_and_reported() {
        let mut points = ellipse((0.0, 0.0), (10.0, 10.0), 20, 0.0);
        points.push(points[3]);
        points.push(points[7]);
        points.push(points[3]);
        let result = reconstruct(&points).unwrap();
        assert_eq!(
            result.merged_duplicates,
            vec![
                MergedDuplicate {
                    dropped: 20,
                    kept: 3
                },
                MergedDuplicate {
                    dropped: 21,
                    kept: 7
                },
                MergedDuplicate {
                    dropped: 22,
                    kept: 3
                },
            ]
        );
        assert_eq!(edges_of(&result), chain_edges(0..20, true));
        assert!(result.outliers.is_empty());
    }

    #[test]
    fn non_finite_and_unrepresentable_coordinates_are_errors() {
        let points = [Point::new(0.0, 0.0), Point::new(f64::NAN, 1.0)];
        assert_eq!(
            reconstruct(&points),
            Err(ReconstructError::NotFinite { index: 1 })
        );
        let points = [Point::new(0.0, 0.0), Point::new(1.0, f64::INFINITY)];
        assert_eq!(
            reconstruct(&points),
            Err(ReconstructError::NotFinite { index: 1 })
        );
        let points = [Point::new(1e300, 0.0)];
        assert!(matches!(
            reconstruct(&points),
            Err(ReconstructError::OutOfRange { index: 0, .. })
        ));
    }

    #[test]
    fn closing_rule_counts_ties_and_needs_more_than_two_edges() {
        // A square with one point per corner plus midpoints: every edge is 1 long.
        let points = [
            (0, 0),
            (1, 0),
            (2, 0),
            (2, 1),
            (2, 2),
            (1, 2),
            (0, 2),
            (0, 1),
        ]
        .map(|(x, y)| Point::new(x as f64, y as f64));
        let result = reconstruct(&points).unwrap();
        assert_eq!(closed_flags(&result), vec![true]);
        assert_eq!(edges_of(&result), chain_edges(0..8, true));
    }
}
