//! The neighbour graph the crawl walks: an undirected graph on points whose adjacency lists are
//! sorted by edge length, stored as compressed sparse rows and built in parallel.

use kurbo::Point;
use rayon::prelude::*;

/// An undirected graph on points whose adjacency lists are sorted by edge length (ties by
/// neighbour id), stored compactly (compressed sparse rows).
#[derive(Clone, Debug, Default)]
pub struct NeighbourGraph {
    /// Where each vertex's adjacency list starts in `neighbours`; one more entry at the end.
    pub(super) offsets: Vec<usize>,
    /// The adjacency lists, one after the other, nearest neighbour first.
    pub(super) neighbours: Vec<u32>,
    /// The squared length of each edge in `neighbours`.
    pub(super) squared_lengths: Vec<f64>,
}

/// Vertices per block when the adjacency lists are sorted in parallel: at a Delaunay graph's
/// fewer than six neighbours a vertex, a block holds up to some 25 000 neighbours, enough work to
/// outweigh handing it to a thread, and small enough that the blocks spread evenly over the cores.
const SORT_BLOCK_VERTICES: usize = 4096;

/// At most this many vertex ranges fill the adjacency lists in parallel: each range reads every
/// edge, so ranges beyond the cores only add work, and a machine with more cores than this gains
/// little from them on edge lists that fit in memory.
const MAX_ADJACENCY_PARTS: usize = 64;

impl NeighbourGraph {
    /// A graph with the given undirected edges, which must be distinct and not loops.
    ///
    /// The vertices are split into one range per thread; each thread reads every edge and fills
    /// in the adjacency lists of its own range, so no two threads write to the same place.
    pub(super) fn from_edge_list(positions: &[Point], edges: &[(u32, u32)]) -> Self {
        let n = positions.len();
        let parts = rayon::current_num_threads()
            .clamp(1, MAX_ADJACENCY_PARTS)
            .min(n.max(1));
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

    /// Measures each edge and sorts each adjacency list by (length, neighbour id).
    fn with_sorted_adjacency(
        positions: &[Point],
        offsets: Vec<usize>,
        mut neighbours: Vec<u32>,
    ) -> Self {
        let vertex_count = offsets.len() - 1;
        let mut squared_lengths = vec![0.0; neighbours.len()];
        // Vertices in blocks, each block's lists sorted on its own thread.
        let mut blocks = Vec::new();
        let (mut rest_neighbours, mut rest_lengths) =
            (&mut neighbours[..], &mut squared_lengths[..]);
        for first in (0..vertex_count).step_by(SORT_BLOCK_VERTICES) {
            let last = (first + SORT_BLOCK_VERTICES).min(vertex_count);
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

/// The squared Euclidean distance between two points.
pub fn squared_distance(a: Point, b: Point) -> f64 {
    let (dx, dy) = (a.x - b.x, a.y - b.y);
    dx * dx + dy * dy
}
