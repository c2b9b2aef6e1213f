//! The Delaunay triangulation of the samples (with spade), inserted in a biased randomized
//! insertion order along a Hilbert curve (N. Amenta, S. Choi and G. Rote, "Incremental
//! constructions con BRIO", SoCG 2003), and joined in order along their line when all points are
//! collinear.

use std::cmp::Ordering;

use kurbo::Point;
use rayon::prelude::*;
use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation};

use super::neighbours::NeighbourGraph;
use super::ReconstructError;

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
        // By Euler's formula a planar triangulation of n points has fewer than 3n edges and 2n
        // faces.
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

    /// The path through collinear `positions` in order along their line.
    fn collinear(positions: &[Point]) -> Self {
        let mut along: Vec<u32> = (0..positions.len() as u32).collect();
        along
            .sort_unstable_by(|&a, &b| lexicographic(positions[a as usize], positions[b as usize]));
        Self::from_edges(positions, along.windows(2).map(|pair| (pair[0], pair[1])))
    }
}

/// The lexicographic order of points: by x, then by y.
pub(super) fn lexicographic(a: Point, b: Point) -> Ordering {
    a.x.partial_cmp(&b.x)
        .unwrap_or(Ordering::Equal)
        .then(a.y.partial_cmp(&b.y).unwrap_or(Ordering::Equal))
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
            (u64::from(round) << ROUND_SHIFT) | (u64::from(along) << ALONG_SHIFT) | u64::from(v)
        })
        .collect();
    keys.par_sort_unstable();
    keys.into_par_iter().map(|key| key as u32).collect()
}

/// Number of BRIO rounds beyond the first; more than enough for 2^32 points (and less than 2^6).
const BRIO_ROUNDS: u32 = 32;

/// Side of the Hilbert grid: 2^13 cells, so that an index fits in 26 bits.
const HILBERT_SIDE: u32 = 1 << 13;

/// The sort key of a vertex packs, from the top: its round (6 bits, at most `BRIO_ROUNDS + 1`),
/// its Hilbert index (26 bits), its id (32 bits), so that one integer sort orders all three.
const ROUND_SHIFT: u32 = 58;
/// See [`ROUND_SHIFT`]: the Hilbert index sits above the 32 bits of the id.
const ALONG_SHIFT: u32 = 32;

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

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use super::*;
    use crate::crawl::neighbours::squared_distance;
    use crate::crawl::reconstruct::reconstruct;
    use crate::crawl::tests::ellipse;

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
}
