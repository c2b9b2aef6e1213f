//! Curve reconstruction from a planar point set by Crawl through Neighbors (Parakkat &
//! Muthuganapathy, Computer Graphics Forum 35(5), 2016): the Delaunay triangulation of the
//! distinct points in lexicographic order, the crawl of [`super::algorithm`] on it, and the
//! paper's closing rule (more than two edges, and one extremity is the other's nearest or
//! second-nearest neighbour), with input indices, outliers and merged duplicates in the result.

use std::cmp::Ordering;
use std::collections::VecDeque;

use kurbo::Point;
use rayon::prelude::*;

use super::algorithm::{crawl, Chain, ChainEnds};
use super::neighbours::{squared_distance, NeighbourGraph};
use super::triangulation::lexicographic;
use super::ReconstructError;

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

/// The largest coordinate magnitude accepted: spade's limit for exact predicates without overflow
/// (`spade::MAX_ALLOWED_VALUE`, 2^201 ≈ 3.2e60) rounded down to the figure the error quotes.
const MAX_COORDINATE_MAGNITUDE: f64 = 1e60;

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
///
/// # Examples
///
/// ```
/// use crawltrace::{reconstruct, Point};
///
/// // An open arc of 10 points and a stray point far from it.
/// let mut points: Vec<Point> = (0..10)
///     .map(|k| f64::from(k) * 0.3)
///     .map(|angle| Point::new(10.0 * angle.cos(), 10.0 * angle.sin()))
///     .collect();
/// points.push(Point::new(40.0, 40.0));
/// let reconstruction = reconstruct(&points)?;
/// assert_eq!(reconstruction.curves.len(), 1);
/// let arc = &reconstruction.curves[0];
/// assert!(!arc.closed);
/// assert_eq!(arc.indices.len(), 10);
/// assert_eq!(reconstruction.outliers, vec![10]);
/// # Ok::<(), crawltrace::ReconstructError>(())
/// ```
///
/// # Errors
///
/// [`ReconstructError::NotFinite`] for a NaN or infinite coordinate, and
/// [`ReconstructError::OutOfRange`] for one the triangulation cannot represent (its magnitude
/// must lie between 1e-42 and 1e60, or be 0); both name the point's index.
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
///
/// # Errors
///
/// As [`reconstruct`].
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
/// among Delaunay neighbours only. With Delaunay neighbours only, any open arc whose two ends are
/// neighbours on the convex hull (a parabola, a "C") closes, because the hull edge makes the far
/// end the second Delaunay neighbour of an end vertex of degree two.
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
                let representable = spade::MIN_ALLOWED_VALUE..=MAX_COORDINATE_MAGNITUDE;
                if value != 0.0 && !representable.contains(&magnitude) {
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

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use super::*;
    use crate::crawl::tests::ellipse;

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
