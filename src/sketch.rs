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
//! chain into shapes. [`Method::Points`] crawls all samples as one point set with the robust crawl,
//! and [`Method::Paper`] with the paper's plain crawl, for comparison.

use std::collections::HashMap;

use kurbo::Point;

use crate::reconstruct::{self, crawl, ChainEnds, NeighbourGraph};
use crate::sample::polyline_length;
use crate::strokes::StrokeEnd;

/// A stroke after sampling: what [`connect_strokes`] works on.
#[derive(Clone, Debug, PartialEq)]
pub struct SampledStroke {
    /// Samples in order along the stroke.
    pub points: Vec<Point>,
    /// Whether the stroke is a loop.
    pub closed: bool,
    /// How its first and last sample end.
    pub ends: [StrokeEnd; 2],
}

/// A reconstructed shape outline, in pixel coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct TracedCurve {
    /// Points in order along the curve (a closed curve does not repeat its first point).
    pub points: Vec<Point>,
    /// Whether the curve is closed.
    pub closed: bool,
}

/// How samples are connected into curves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// The crawl on stroke edges and gap bridges (the default; see the module documentation).
    #[default]
    Strokes,
    /// The robust point-set crawl ([`crate::robust_crawl`]) on the Delaunay triangulation of all
    /// samples, ignoring which stroke they came from.
    Points,
    /// The paper's crawl on the Delaunay triangulation of all samples, ignoring which stroke
    /// they came from.
    Paper,
}

/// Connects sampled strokes into curves with `method`. `spacing` is the sample spacing; curves
/// shorter than `minimum_length` are dropped as stray marks; the free ends of open curves are
/// extended by `end_extension` (thinning erodes every stroke end by half a pen width).
pub fn connect(
    strokes: &[SampledStroke],
    method: Method,
    spacing: f64,
    minimum_length: f64,
    end_extension: f64,
) -> Vec<TracedCurve> {
    let curves = match method {
        Method::Strokes => connect_strokes(strokes, spacing),
        Method::Points => crawl_all_samples(strokes, crate::robust_crawl::reconstruct),
        Method::Paper => crawl_all_samples(strokes, reconstruct::reconstruct),
    };
    let attached: Vec<Point> = strokes
        .iter()
        .flat_map(|s| s.ends)
        .filter_map(|end| match end {
            StrokeEnd::Attached(p) => Some(p),
            StrokeEnd::Free => None,
        })
        .collect();
    curves
        .into_iter()
        .filter(|curve| polyline_length(&curve.points, curve.closed) >= minimum_length)
        .map(|mut curve| {
            if !curve.closed && curve.points.len() >= 2 {
                extend_end(&mut curve.points, false, end_extension, &attached);
                extend_end(&mut curve.points, true, end_extension, &attached);
            }
            curve
        })
        .collect()
}

/// Moves the first (or last) point of an open curve `extension` further along the curve's
/// direction there, unless it is a T-junction attachment point.
fn extend_end(points: &mut [Point], at_last: bool, extension: f64, attached: &[Point]) {
    let n = points.len();
    let (end, inner) = if at_last { (n - 1, n - 2) } else { (0, 1) };
    if attached.contains(&points[end]) {
        return;
    }
    let direction = points[end] - points[inner];
    let length = direction.hypot();
    if length > 0.0 {
        points[end] += direction * (extension / length);
    }
}

/// The paper's approach: one point set, one crawl (`reconstruct_points`).
fn crawl_all_samples(
    strokes: &[SampledStroke],
    reconstruct_points: fn(
        &[Point],
    )
        -> Result<reconstruct::Reconstruction, reconstruct::ReconstructError>,
) -> Vec<TracedCurve> {
    let points: Vec<Point> = strokes
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .collect();
    let Ok(result) = reconstruct_points(&points) else {
        return Vec::new(); // pixel coordinates are always finite and in range
    };
    result
        .curves
        .iter()
        .map(|curve| TracedCurve {
            points: curve.indices.iter().map(|&i| points[i]).collect(),
            closed: curve.closed,
        })
        .collect()
}

/// A free stroke end: a vertex and which end of which stroke it is.
#[derive(Clone, Copy, Debug)]
struct FreeEnd {
    vertex: u32,
    stroke: usize,
    /// The unit direction in which the pen was moving when it lifted here; `None` for a dot.
    outward: Option<kurbo::Vec2>,
}

/// The crawl on stroke edges and bridges (see the module documentation).
pub fn connect_strokes(strokes: &[SampledStroke], spacing: f64) -> Vec<TracedCurve> {
    // Vertices: every distinct sample. A sample that repeats an earlier one (strokes crossing
    // exactly on a sample) is dropped from the later stroke.
    let mut positions: Vec<Point> = Vec::new();
    let mut vertex_at: HashMap<(u64, u64), u32> = HashMap::new();
    let mut stroke_vertices: Vec<Vec<u32>> = Vec::with_capacity(strokes.len());
    // DECISION: a free-ended dash no longer than two sample spacings is a dot: one vertex at its
    // middle that may be bridged on both sides, with gaps measured from its rim. Sampled as a
    // stroke, its two ends sit so close together that the gap matching can hand both neighbours
    // to the same end and leave the shape open.
    let mut radius_of_vertex: HashMap<u32, f64> = HashMap::new();
    // The dash each dot stands for, to draw it back in the output.
    let mut dash_of_vertex: HashMap<u32, (Point, Point)> = HashMap::new();
    let dot_of = |stroke: &SampledStroke| -> Option<(Point, f64)> {
        let (first, last) = (*stroke.points.first()?, *stroke.points.last()?);
        let length = polyline_length(&stroke.points, false);
        let free = stroke.ends == [StrokeEnd::Free, StrokeEnd::Free];
        (!stroke.closed && free && length <= 2.0 * spacing)
            .then(|| (first.midpoint(last), 0.5 * length))
    };
    for stroke in strokes {
        let dot = dot_of(stroke);
        let points = match dot {
            Some((middle, _)) => vec![middle],
            None => stroke.points.clone(),
        };
        let mut vertices = Vec::with_capacity(points.len());
        for p in points {
            let key = (p.x.to_bits(), p.y.to_bits());
            if vertex_at.contains_key(&key) {
                continue;
            }
            let v = positions.len() as u32;
            vertex_at.insert(key, v);
            positions.push(p);
            vertices.push(v);
            if let Some((_, radius)) = dot {
                radius_of_vertex.insert(v, radius);
                if let (Some(&first), Some(&last)) = (stroke.points.first(), stroke.points.last()) {
                    dash_of_vertex.insert(v, (first, last));
                }
            }
        }
        stroke_vertices.push(vertices);
    }
    let Ok(delaunay) = NeighbourGraph::delaunay(&positions) else {
        return Vec::new(); // pixel coordinates are always finite and in range
    };

    let mut edges: Vec<(u32, u32)> = Vec::new();
    let mut free_ends: Vec<FreeEnd> = Vec::new();
    // Points where a chain ending at this vertex should be extended to (T-junctions).
    let mut attachment: HashMap<u32, Point> = HashMap::new();
    for (s, (stroke, vertices)) in strokes.iter().zip(&stroke_vertices).enumerate() {
        edges.extend(vertices.windows(2).map(|w| (w[0], w[1])));
        if stroke.closed && vertices.len() > 2 {
            edges.push((vertices[vertices.len() - 1], vertices[0]));
            continue;
        }
        let (Some(&first), Some(&last)) = (vertices.first(), vertices.last()) else {
            continue;
        };
        let n = vertices.len();
        // Measured two samples in, where one is there: the last sample alone wobbles.
        let inner = [vertices[(n - 1).min(2)], vertices[n.saturating_sub(3)]];
        for ((end, vertex), inner) in stroke.ends.iter().zip([first, last]).zip(inner) {
            let direction = positions[vertex as usize] - positions[inner as usize];
            let outward = (direction.hypot() > 0.0).then(|| direction / direction.hypot());
            match *end {
                StrokeEnd::Free => free_ends.push(FreeEnd {
                    vertex,
                    stroke: s,
                    outward,
                }),
                StrokeEnd::Attached(point) => {
                    attachment.insert(vertex, point);
                }
            }
        }
    }
    edges.extend(match_gap_bridges(
        &positions,
        &delaunay,
        &free_ends,
        &stroke_vertices,
        &radius_of_vertex,
        spacing,
    ));
    let graph = NeighbourGraph::from_edges(&positions, edges);

    // Closing: the two extremities must be joined by a stroke edge or an accepted bridge. The
    // graph only holds plausible connections, so this is the paper's "second-nearest" rule with
    // the neighbours that are not plausible left out.
    let chains = crawl(&positions, &graph, |ends: &ChainEnds| {
        ends.edge_count > 2 && graph.has_edge(ends.front, ends.back)
    });
    chains
        .into_iter()
        .filter(|chain| chain.vertices.len() >= 2)
        .map(|chain| {
            let vertices = reconstruct::canonical_orientation(chain.vertices, chain.closed);
            let mut points = Vec::with_capacity(vertices.len() + 2);
            for (k, &v) in vertices.iter().enumerate() {
                let Some(&(a, b)) = dash_of_vertex.get(&v) else {
                    points.push(positions[v as usize]);
                    continue;
                };
                // Draw the dash with the end nearer to the curve before it first (or, at the
                // start, the end farther from the curve after it).
                let (before, after) = neighbours_along(&vertices, k, chain.closed);
                let a_first = match (before, after) {
                    (Some(p), _) => {
                        positions[p as usize].distance(a) <= positions[p as usize].distance(b)
                    }
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
                if let Some(&p) = attachment.get(&vertices[0]) {
                    points.insert(0, p);
                }
                if let Some(&p) = attachment.get(&vertices[vertices.len() - 1]) {
                    points.push(p);
                }
            }
            TracedCurve {
                points,
                closed: chain.closed,
            }
        })
        .collect()
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

/// Chooses the bridges across pen lifts: pairs of free stroke ends joined by a Delaunay edge,
/// matched greedily from the shortest, each end used once.
///
/// DECISION: greedy shortest-first matching rather than the crawl's own greedy choice, so that an
/// end cannot be taken by a farther end that happens to be crawled first (the end of an open
/// mouth stealing the end of a nearby face outline).
///
/// DECISION: a bridge may be at most twice the drawing's typical gap, the median matched length
/// clamped to one to three sample spacings. Pen lifts in one sketch are of a similar size;
/// bridges much longer than the typical one join things the person drew apart (two eyebrows, the
/// corners of an open mouth). The clamp keeps the rule sane when almost all ends are true open
/// ends (a drawing in continuous strokes) or when there is no gap at all.
fn match_gap_bridges(
    positions: &[Point],
    delaunay: &NeighbourGraph,
    free_ends: &[FreeEnd],
    stroke_vertices: &[Vec<u32>],
    radius_of_vertex: &HashMap<u32, f64>,
    spacing: f64,
) -> Vec<(u32, u32)> {
    // How many bridges each vertex may take: one per free end it is (two for a one-sample dot).
    let mut slots: HashMap<u32, u8> = HashMap::new();
    for end in free_ends {
        *slots.entry(end.vertex).or_default() += 1;
    }
    let stroke_of: HashMap<u32, usize> = free_ends.iter().map(|e| (e.vertex, e.stroke)).collect();
    let outward_of: HashMap<u32, Option<kurbo::Vec2>> =
        free_ends.iter().map(|e| (e.vertex, e.outward)).collect();
    // How much a bridge from `vertex` towards `direction` turns away from where the pen was
    // going: 0 straight on, 1 straight back; nothing for a dot.
    let turn = |vertex: u32, direction: kurbo::Vec2| -> f64 {
        outward_of
            .get(&vertex)
            .copied()
            .flatten()
            .map_or(0.0, |outward| (1.0 - outward.dot(direction)) / 2.0)
    };
    // (cost, length, end, other end)
    let mut candidates: Vec<(f64, f64, u32, u32)> = Vec::new();
    for end in free_ends {
        for &other in delaunay.neighbours(end.vertex) {
            let Some(&other_stroke) = stroke_of.get(&other) else {
                continue;
            };
            if other <= end.vertex {
                continue;
            }
            // A stroke may close on itself only if it is long enough to be a loop: the paper's
            // "more than two edges" before closing.
            if other_stroke == end.stroke && stroke_vertices[end.stroke].len() < 4 {
                continue;
            }
            // Gaps are measured between rims: a dot has the size of the dash it stands for.
            let rims = radius_of_vertex.get(&end.vertex).unwrap_or(&0.0)
                + radius_of_vertex.get(&other).unwrap_or(&0.0);
            let length = (positions[end.vertex as usize].distance(positions[other as usize])
                - rims)
                .max(0.0);
            // DECISION: good continuation. A bridge is matched by its length times
            // 1 + (turn at each end), the turn going from 0 (straight on) to 1 (straight back):
            // at an acute tip the two arm ends are closer to each other than to the dash at the
            // tip, but reaching each other means turning round; the tip continues both.
            let direction = positions[other as usize] - positions[end.vertex as usize];
            let unit = if direction.hypot() > 0.0 {
                direction / direction.hypot()
            } else {
                kurbo::Vec2::ZERO
            };
            let cost = length * (1.0 + turn(end.vertex, unit) + turn(other, -unit));
            candidates.push((cost, length, end.vertex, other));
        }
    }
    candidates.sort_by(|a, b| {
        a.0.total_cmp(&b.0)
            .then(a.1.total_cmp(&b.1))
            .then((a.2, a.3).cmp(&(b.2, b.3)))
    });
    candidates.dedup();
    // Strokes joined by accepted bridges, with their total length, to see when a bridge would
    // close a loop.
    let stroke_length = |stroke: usize| -> f64 {
        let points: Vec<Point> = stroke_vertices[stroke]
            .iter()
            .map(|&v| positions[v as usize])
            .collect();
        polyline_length(&points, false)
    };
    let greedy_match = |longest: f64| -> Vec<(f64, u32, u32)> {
        let mut groups = StrokeGroups::new(stroke_vertices.len(), stroke_length);
        let mut matched: Vec<(f64, u32, u32)> = Vec::new();
        let mut remaining = slots.clone();
        for &(_, length, a, b) in &candidates {
            // Each pair is a candidate once: `dedup` above removed the copy a two-slot dot makes.
            if length > longest || remaining[&a] == 0 || remaining[&b] == 0 {
                continue;
            }
            let (stroke_a, stroke_b) = (stroke_of[&a], stroke_of[&b]);
            // DECISION: a bridge that closes a loop must be short next to the loop: at most a
            // quarter of its length. A skip-stroke gap is a small part of the outline it
            // interrupts; an opening as wide as a quarter of the curve is drawn on purpose (an
            // open mouth, a "C"), and tiny loops of a few dashes are no shapes at all.
            if groups.same(stroke_a, stroke_b) && length > 0.25 * (groups.length(stroke_a) + length)
            {
                continue;
            }
            groups.join(stroke_a, stroke_b, length);
            *remaining.get_mut(&a).expect("free end") -= 1;
            *remaining.get_mut(&b).expect("free end") -= 1;
            matched.push((length, a, b));
        }
        matched
    };
    // First pass: the drawing's typical gap. Second pass: the matching itself, with overlong
    // bridges out of the running, so that they cannot take an end from a real gap.
    let mut lengths: Vec<f64> = greedy_match(f64::INFINITY).iter().map(|m| m.0).collect();
    if lengths.is_empty() {
        return Vec::new();
    }
    lengths.sort_by(f64::total_cmp);
    let typical_gap = lengths[lengths.len() / 2].clamp(spacing, 3.0 * spacing);
    greedy_match(2.0 * typical_gap)
        .into_iter()
        .map(|m| (m.1, m.2))
        .collect()
}

/// Union–find over strokes, tracking the total length of each group (strokes plus bridges).
struct StrokeGroups {
    parent: Vec<usize>,
    length: Vec<f64>,
}

impl StrokeGroups {
    fn new(count: usize, stroke_length: impl Fn(usize) -> f64) -> Self {
        Self {
            parent: (0..count).collect(),
            length: (0..count).map(stroke_length).collect(),
        }
    }

    fn root(&mut self, mut stroke: usize) -> usize {
        while self.parent[stroke] != stroke {
            self.parent[stroke] = self.parent[self.parent[stroke]];
            stroke = self.parent[stroke];
        }
        stroke
    }

    fn same(&mut self, a: usize, b: usize) -> bool {
        self.root(a) == self.root(b)
    }

    fn length(&mut self, stroke: usize) -> f64 {
        let root = self.root(stroke);
        self.length[root]
    }

    fn join(&mut self, a: usize, b: usize, bridge_length: f64) {
        let (root_a, root_b) = (self.root(a), self.root(b));
        if root_a == root_b {
            self.length[root_a] += bridge_length;
        } else {
            self.parent[root_b] = root_a;
            self.length[root_a] += self.length[root_b] + bridge_length;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn open(points: &[(f64, f64)]) -> SampledStroke {
        SampledStroke {
            points: points.iter().map(|&(x, y)| Point::new(x, y)).collect(),
            closed: false,
            ends: [StrokeEnd::Free, StrokeEnd::Free],
        }
    }

    /// Points along a circle arc from angle `from` to `to` (degrees), about `step` apart.
    fn arc(center: (f64, f64), radius: f64, from: f64, to: f64, step: f64) -> SampledStroke {
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
    ) -> Vec<SampledStroke> {
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
        let total: usize = strokes.iter().map(|s| s.points.len()).sum();
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
    fn the_point_set_methods_also_run() {
        let strokes = skip_stroke_circle((100.0, 100.0), 60.0, 40.0, 3.0);
        for method in [Method::Points, Method::Paper] {
            let curves = connect(&strokes, method, 4.0, 6.0, 0.0);
            assert!(!curves.is_empty(), "{method:?}");
        }
    }
}
