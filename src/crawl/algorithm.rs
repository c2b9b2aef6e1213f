//! The paper's crawl (Parakkat & Muthuganapathy, Computer Graphics Forum 35(5), 2016,
//! Algorithm 1) on any [`NeighbourGraph`]: seeds, candidates, the `d > d1` stop, and a closing
//! rule chosen by the caller.
//!
//! The crawl follows the paper's *text* (see `docs/design.md`, "The crawl"):
//!
//! 1. **Seed**: the shortest graph edge whose two endpoints are unvisited and are each other's
//!    nearest neighbour.
//! 2. **Crawl**: of all edges from either extremity of the chain to an unvisited vertex, the shortest
//!    is the candidate (length `d`).
//! 3. **Terminate** when there is no candidate, or the chain has more than two edges and `d` is
//!    greater than the distance `d1` between its extremities (tested *before* the candidate is added).
//! 4. **Close** if the caller's closing rule accepts the chain (for point sets,
//!    [`super::reconstruct::paper_closable`]).
//! 5. Repeat; vertices that never join a chain are outliers.
//!
//! Decisions the paper leaves open are made at the spot they matter and marked `DECISION:`.

use std::cmp::Ordering;
use std::collections::VecDeque;

use kurbo::Point;

use super::neighbours::{squared_distance, NeighbourGraph};

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
