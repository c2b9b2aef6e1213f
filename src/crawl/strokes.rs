//! Reconstructs the shapes of a skip-stroke sketch from its sampled pen strokes: the crawl of
//! Parakkat & Muthuganapathy (2016, Algorithm 1) run on a neighbour graph made of the strokes' own
//! edges and of bridges across the gaps between stroke ends.
//!
//! The paper crawls the Delaunay triangulation of all samples (§4.2). On real sketches that joins
//! the end of an open stroke to the middle of a nearby stroke and zig-zags between strokes drawn
//! side by side: the triangulation does not know which samples the pen drew in one go. Here it
//! does: within a stroke only the stroke's own edges are offered, and only the pen's lift-off
//! points (free stroke ends) may be bridged, to each other, along Delaunay edges. The crawl then
//! decides, with the paper's seeds, candidates, `d > d1` stop and a closing rule, how the strokes
//! chain into shapes. [`Method::Points`] keeps the paper's plain crawl for comparison.

use std::collections::{HashMap, HashSet};

use kurbo::Point;

use super::algorithm::{crawl, Chain, ChainEnds};
use super::bridges::{match_gap_bridges, FreeEnd};
use super::neighbours::NeighbourGraph;
use super::reconstruct::{self, canonical_orientation};
use crate::geometry::polyline::polyline_length;
use crate::geometry::Polyline;
use crate::strokes::{Stroke, StrokeEnd};

/// How samples are connected into curves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// The crawl on stroke edges and gap bridges (the default; see the module documentation).
    #[default]
    Strokes,
    /// The paper's crawl on the Delaunay triangulation of all samples, ignoring which stroke
    /// they came from.
    Points,
}

/// DECISION: a curve shorter than two pen widths is a stray mark (a speck that survived cleaning, a
/// blot), not a shape.
const MIN_CURVE_LENGTH_IN_PEN_WIDTHS: f64 = 2.0;

/// Thinning erodes every stroke end by about half a pen width; open curves get it back.
const END_EXTENSION_IN_PEN_WIDTHS: f64 = 0.5;

/// DECISION: a free-ended dash no longer than two sample spacings is a dot (see
/// [`StrokeVertices::new`]).
const DOT_MAX_LENGTH_IN_SPACINGS: f64 = 2.0;

/// The direction in which the pen left a stroke end is measured this many samples in: the last
/// sample alone wobbles.
const END_DIRECTION_REACH_IN_SAMPLES: usize = 2;

/// The paper's closing condition: a chain closes only with more than this many edges.
const MIN_EDGES_BEFORE_CLOSING: usize = 2;

/// The length below which [`connect`] drops a curve as a stray mark, for a pen of `stroke_width`
/// pixels: two pen widths.
pub fn minimum_curve_length(stroke_width: f64) -> f64 {
    MIN_CURVE_LENGTH_IN_PEN_WIDTHS * stroke_width
}

/// How far [`connect`] extends the free ends of open curves, for a pen of `stroke_width` pixels:
/// half a pen width, what thinning took off.
pub fn end_extension(stroke_width: f64) -> f64 {
    END_EXTENSION_IN_PEN_WIDTHS * stroke_width
}

/// Connects sampled strokes into curves with `method`. `spacing` is the sample spacing; curves
/// shorter than `minimum_length` are dropped as stray marks; the free ends of open curves are
/// extended by `end_extension` (thinning erodes every stroke end by half a pen width).
pub fn connect(
    strokes: &[Stroke],
    method: Method,
    spacing: f64,
    minimum_length: f64,
    end_extension: f64,
) -> Vec<Polyline> {
    let curves = match method {
        Method::Strokes => connect_strokes(strokes, spacing),
        Method::Points => crawl_all_samples(strokes),
    };
    // A set, not a list: a page of noise has about as many attachment points as curves, and a
    // list searched once per curve end made this step quadratic (16 MP of noise: 70 s).
    let attached: HashSet<PointKey> = strokes
        .iter()
        .flat_map(|s| s.ends)
        .filter_map(|end| match end {
            StrokeEnd::Attached(p) => Some(point_key(p)),
            StrokeEnd::Free => None,
        })
        .collect();
    curves
        .into_iter()
        .filter(|curve| curve.length() >= minimum_length)
        .map(|mut curve| {
            if !curve.closed && curve.points.len() >= 2 {
                extend_end(&mut curve.points, false, end_extension, &attached);
                extend_end(&mut curve.points, true, end_extension, &attached);
            }
            curve
        })
        .collect()
}

/// A point as a hashable key: its coordinates' bits (pixel coordinates are never -0 or NaN, so
/// equal keys are equal points).
type PointKey = (u64, u64);

fn point_key(p: Point) -> PointKey {
    (p.x.to_bits(), p.y.to_bits())
}

/// Moves the first (or last) point of an open curve `extension` further along the curve's
/// direction there, unless it is a T-junction attachment point.
fn extend_end(points: &mut [Point], at_last: bool, extension: f64, attached: &HashSet<PointKey>) {
    let n = points.len();
    let (end, inner) = if at_last { (n - 1, n - 2) } else { (0, 1) };
    if attached.contains(&point_key(points[end])) {
        return;
    }
    let direction = points[end] - points[inner];
    let length = direction.hypot();
    if length > 0.0 {
        points[end] += direction * (extension / length);
    }
}

/// The paper's approach: one point set, one crawl.
fn crawl_all_samples(strokes: &[Stroke]) -> Vec<Polyline> {
    let points: Vec<Point> = strokes
        .iter()
        .flat_map(|s| s.line.points.iter().copied())
        .collect();
    let Ok(result) = reconstruct::reconstruct(&points) else {
        return Vec::new(); // pixel coordinates are always finite and in range
    };
    result
        .curves
        .iter()
        .map(|curve| {
            Polyline::new(
                curve.indices.iter().map(|&i| points[i]).collect(),
                curve.closed,
            )
        })
        .collect()
}

/// The crawl's vertices: every distinct sample, with the dots that stand for short dashes.
#[derive(Default)]
pub(super) struct StrokeVertices {
    /// The position of each vertex.
    pub(super) positions: Vec<Point>,
    /// The vertices of each stroke, in order along it.
    pub(super) of_stroke: Vec<Vec<u32>>,
    /// For a dot, half the length of the dash it stands for: gaps are measured from its rim.
    pub(super) dot_radius: HashMap<u32, f64>,
    /// For a dot, the two ends of the dash it stands for, to draw it back in the output.
    dot_dash: HashMap<u32, (Point, Point)>,
}

impl StrokeVertices {
    /// Numbers the samples of `strokes`. A sample that repeats an earlier one (strokes crossing
    /// exactly on a sample) is dropped from the later stroke.
    ///
    /// DECISION: a free-ended dash no longer than two sample spacings is a dot: one vertex at its
    /// middle that may be bridged on both sides, with gaps measured from its rim. Sampled as a
    /// stroke, its two ends sit so close together that the gap matching can hand both neighbours
    /// to the same end and leave the shape open.
    fn new(strokes: &[Stroke], spacing: f64) -> Self {
        let mut vertices = Self::default();
        let mut vertex_at: HashMap<PointKey, u32> = HashMap::new();
        let dot_of = |stroke: &Stroke| -> Option<(Point, f64)> {
            let points = &stroke.line.points;
            let (first, last) = (*points.first()?, *points.last()?);
            let length = polyline_length(points, false);
            let free = stroke.ends == [StrokeEnd::Free, StrokeEnd::Free];
            (!stroke.line.closed && free && length <= DOT_MAX_LENGTH_IN_SPACINGS * spacing)
                .then(|| (first.midpoint(last), 0.5 * length))
        };
        for stroke in strokes {
            let dot = dot_of(stroke);
            let points = match dot {
                Some((middle, _)) => vec![middle],
                None => stroke.line.points.clone(),
            };
            let mut of_stroke = Vec::with_capacity(points.len());
            for p in points {
                let key = point_key(p);
                if vertex_at.contains_key(&key) {
                    continue;
                }
                let v = vertices.positions.len() as u32;
                vertex_at.insert(key, v);
                vertices.positions.push(p);
                of_stroke.push(v);
                if let Some((_, radius)) = dot {
                    vertices.dot_radius.insert(v, radius);
                    let line = &stroke.line.points;
                    if let (Some(&first), Some(&last)) = (line.first(), line.last()) {
                        vertices.dot_dash.insert(v, (first, last));
                    }
                }
            }
            vertices.of_stroke.push(of_stroke);
        }
        vertices
    }
}

/// The stroke edges, the free ends that may be bridged, and the T-junction attachment points of
/// the strokes' vertices.
struct StrokeGraph {
    edges: Vec<(u32, u32)>,
    free_ends: Vec<FreeEnd>,
    /// Points where a chain ending at this vertex should be extended to (T-junctions).
    attachment: HashMap<u32, Point>,
}

impl StrokeGraph {
    fn new(strokes: &[Stroke], vertices: &StrokeVertices) -> Self {
        let positions = &vertices.positions;
        let mut graph = Self {
            edges: Vec::new(),
            free_ends: Vec::new(),
            attachment: HashMap::new(),
        };
        for (s, (stroke, of_stroke)) in strokes.iter().zip(&vertices.of_stroke).enumerate() {
            graph
                .edges
                .extend(of_stroke.windows(2).map(|w| (w[0], w[1])));
            if stroke.line.closed && of_stroke.len() > 2 {
                graph
                    .edges
                    .push((of_stroke[of_stroke.len() - 1], of_stroke[0]));
                continue;
            }
            let (Some(&first), Some(&last)) = (of_stroke.first(), of_stroke.last()) else {
                continue;
            };
            let n = of_stroke.len();
            // Measured a few samples in, where there are that many.
            let reach = END_DIRECTION_REACH_IN_SAMPLES;
            let inner = [
                of_stroke[(n - 1).min(reach)],
                of_stroke[n.saturating_sub(reach + 1)],
            ];
            for ((end, vertex), inner) in stroke.ends.iter().zip([first, last]).zip(inner) {
                let direction = positions[vertex as usize] - positions[inner as usize];
                let outward = (direction.hypot() > 0.0).then(|| direction / direction.hypot());
                match *end {
                    StrokeEnd::Free => graph.free_ends.push(FreeEnd {
                        vertex,
                        stroke: s,
                        outward,
                    }),
                    StrokeEnd::Attached(point) => {
                        graph.attachment.insert(vertex, point);
                    }
                }
            }
        }
        graph
    }
}

/// The crawl on stroke edges and bridges (see the module documentation).
pub fn connect_strokes(strokes: &[Stroke], spacing: f64) -> Vec<Polyline> {
    let vertices = StrokeVertices::new(strokes, spacing);
    let positions = &vertices.positions;
    let Ok(delaunay) = NeighbourGraph::delaunay(positions) else {
        return Vec::new(); // pixel coordinates are always finite and in range
    };
    let StrokeGraph {
        mut edges,
        free_ends,
        attachment,
    } = StrokeGraph::new(strokes, &vertices);
    edges.extend(match_gap_bridges(&vertices, &delaunay, &free_ends, spacing));
    let graph = NeighbourGraph::from_edges(positions, edges);

    // Closing: the two extremities must be joined by a stroke edge or an accepted bridge. The
    // graph only holds plausible connections, so this is the paper's "second-nearest" rule with
    // the neighbours that are not plausible left out.
    let chains = crawl(positions, &graph, |ends: &ChainEnds| {
        ends.edge_count > MIN_EDGES_BEFORE_CLOSING && graph.has_edge(ends.front, ends.back)
    });
    chains
        .into_iter()
        .filter(|chain| chain.vertices.len() >= 2)
        .map(|chain| chain_to_curve(chain, &vertices, &attachment))
        .collect()
}

/// The curve of a chain: its vertices' positions with every dot drawn back as its dash, and an
/// open chain extended to the T-junction points its ends are attached to.
fn chain_to_curve(
    chain: Chain,
    vertices: &StrokeVertices,
    attachment: &HashMap<u32, Point>,
) -> Polyline {
    let positions = &vertices.positions;
    let order = canonical_orientation(chain.vertices, chain.closed);
    let mut points = Vec::with_capacity(order.len() + 2);
    for (k, &v) in order.iter().enumerate() {
        let Some(&(a, b)) = vertices.dot_dash.get(&v) else {
            points.push(positions[v as usize]);
            continue;
        };
        // Draw the dash with the end nearer to the curve before it first (or, at the start, the
        // end farther from the curve after it).
        let (before, after) = neighbours_along(&order, k, chain.closed);
        let a_first = match (before, after) {
            (Some(p), _) => positions[p as usize].distance(a) <= positions[p as usize].distance(b),
            (None, Some(n)) => {
                positions[n as usize].distance(a) >= positions[n as usize].distance(b)
            }
            (None, None) => true,
        };
        let (first, second) = if a_first { (a, b) } else { (b, a) };
        points.push(first);
        if second != first {
            points.push(second);
        }
    }
    if !chain.closed {
        if let Some(&p) = attachment.get(&order[0]) {
            points.insert(0, p);
        }
        if let Some(&p) = attachment.get(&order[order.len() - 1]) {
            points.push(p);
        }
    }
    Polyline::new(points, chain.closed)
}

/// The vertices before and after position `k` of a chain.
fn neighbours_along(vertices: &[u32], k: usize, closed: bool) -> (Option<u32>, Option<u32>) {
    let n = vertices.len();
    let before = if k > 0 {
        Some(vertices[k - 1])
    } else if closed && n > 1 {
        Some(vertices[n - 1])
    } else {
        None
    };
    let after = if k + 1 < n {
        Some(vertices[k + 1])
    } else if closed && n > 1 {
        Some(vertices[0])
    } else {
        None
    };
    (before, after)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn open(points: &[(f64, f64)]) -> Stroke {
        Stroke {
            line: Polyline::new(
                points.iter().map(|&(x, y)| Point::new(x, y)).collect(),
                false,
            ),
            ends: [StrokeEnd::Free, StrokeEnd::Free],
        }
    }

    /// Points along a circle arc from angle `from` to `to` (degrees), about `step` apart.
    fn arc(center: (f64, f64), radius: f64, from: f64, to: f64, step: f64) -> Stroke {
        let length = radius * (to - from).to_radians();
        let count = (length / step).ceil().max(1.0) as usize;
        let points: Vec<(f64, f64)> = (0..=count)
            .map(|k| {
                let angle = (from + (to - from) * k as f64 / count as f64).to_radians();
                (
                    center.0 + radius * angle.cos(),
                    center.1 + radius * angle.sin(),
                )
            })
            .collect();
        open(&points)
    }

    /// A circle drawn as strokes of `stroke_degrees` with gaps of `gap_degrees`.
    fn skip_stroke_circle(
        center: (f64, f64),
        radius: f64,
        stroke_degrees: f64,
        gap_degrees: f64,
    ) -> Vec<Stroke> {
        let mut strokes = Vec::new();
        let mut angle = 0.0;
        while angle + stroke_degrees <= 360.0 - gap_degrees + 1e-9 {
            strokes.push(arc(center, radius, angle, angle + stroke_degrees, 4.0));
            angle += stroke_degrees + gap_degrees;
        }
        strokes
    }

    #[test]
    fn a_skip_stroke_circle_becomes_one_closed_curve() {
        let strokes = skip_stroke_circle((100.0, 100.0), 60.0, 40.0, 5.0);
        assert_eq!(strokes.len(), 8);
        let curves = connect(&strokes, Method::Strokes, 4.0, 6.0, 0.0);
        assert_eq!(curves.len(), 1, "{curves:?}");
        assert!(curves[0].closed);
        let total: usize = strokes.iter().map(|s| s.line.points.len()).sum();
        assert_eq!(curves[0].points.len(), total);
    }

    #[test]
    fn an_open_mouth_inside_a_face_stays_open_and_apart() {
        let mut strokes = skip_stroke_circle((100.0, 100.0), 80.0, 30.0, 6.0);
        // A mouth of two strokes with a small gap, its corners 30 px from the outline's gaps.
        strokes.push(arc((100.0, 90.0), 50.0, 40.0, 88.0, 4.0));
        strokes.push(arc((100.0, 90.0), 50.0, 92.0, 140.0, 4.0));
        let curves = connect(&strokes, Method::Strokes, 4.0, 6.0, 0.0);
        assert_eq!(curves.len(), 2, "{curves:?}");
        let closed: Vec<bool> = curves.iter().map(|c| c.closed).collect();
        assert!(
            closed.contains(&true) && closed.contains(&false),
            "{closed:?}"
        );
        let mouth = curves.iter().find(|c| !c.closed).unwrap();
        assert!(mouth
            .points
            .iter()
            .all(|p| p.distance(Point::new(100.0, 100.0)) < 60.0));
    }

    #[test]
    fn two_open_strokes_far_apart_are_not_bridged() {
        let strokes = vec![
            open(&[(0.0, 0.0), (4.0, 0.0), (8.0, 0.0), (12.0, 0.0), (16.0, 0.0)]),
            open(&[(40.0, 0.0), (44.0, 0.0), (48.0, 0.0), (52.0, 0.0)]),
        ];
        let curves = connect(&strokes, Method::Strokes, 4.0, 6.0, 0.0);
        assert_eq!(curves.len(), 2, "{curves:?}");
        assert!(curves.iter().all(|c| !c.closed));
    }

    #[test]
    fn a_t_stem_ends_on_the_bar() {
        let stem_points: Vec<(f64, f64)> = (0..11).map(|k| (10.0, 58.0 - 4.0 * k as f64)).collect();
        let mut stem = open(&stem_points);
        stem.ends[1] = StrokeEnd::Attached(Point::new(10.0, 14.0));
        let bar = open(&[
            (0.0, 14.0),
            (4.0, 14.0),
            (8.0, 14.0),
            (12.0, 14.0),
            (16.0, 14.0),
            (20.0, 14.0),
        ]);
        let curves = connect(&[bar, stem], Method::Strokes, 4.0, 6.0, 0.0);
        assert_eq!(curves.len(), 2, "{curves:?}");
        let stem = curves.iter().find(|c| c.points.len() == 12).expect("stem");
        assert!(stem.points.contains(&Point::new(10.0, 14.0)), "{stem:?}");
    }

    #[test]
    fn stray_marks_are_dropped() {
        let strokes = vec![open(&[(0.0, 0.0), (2.0, 0.0)])];
        assert!(connect(&strokes, Method::Strokes, 4.0, 6.0, 0.0).is_empty());
    }

    #[test]
    fn the_paper_method_also_runs() {
        let strokes = skip_stroke_circle((100.0, 100.0), 60.0, 40.0, 3.0);
        let curves = connect(&strokes, Method::Points, 4.0, 6.0, 0.0);
        assert!(!curves.is_empty());
    }
}
