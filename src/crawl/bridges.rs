//! Gap bridges: which free stroke ends (the pen's lift-off points) are joined across a pen lift,
//! matched greedily from the cheapest bridge (shortest, straightest) along Delaunay edges, each end
//! used once, with bridges much longer than the drawing's typical gap left out.

use std::collections::HashMap;

use kurbo::{Point, Vec2};

use super::neighbours::NeighbourGraph;
use super::strokes::StrokeVertices;
use crate::geometry::polyline::polyline_length;
use crate::geometry::UnionFind;
use crate::strokes::MIN_LOOP_SAMPLES;

/// A free stroke end: a vertex and which end of which stroke it is.
#[derive(Clone, Copy, Debug)]
pub(super) struct FreeEnd {
    pub(super) vertex: u32,
    pub(super) stroke: usize,
    /// The unit direction in which the pen was moving when it lifted here; `None` for a dot.
    pub(super) outward: Option<Vec2>,
}

/// A possible bridge: (cost, length, end, other end), the ends as vertices, `end < other end`.
type Candidate = (f64, f64, u32, u32);

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
/// DECISION: a bridge that closes a loop may be at most this share of the loop (bridge
/// included); see [`match_gap_bridges`].
const LOOP_GAP_MAX_SHARE: f64 = 0.25;

/// The drawing's typical gap is clamped to this range, in sample spacings, so that the bridge
/// limit stays sane with almost no gaps or no true open ends.
const TYPICAL_GAP_MIN_IN_SPACINGS: f64 = 1.0;
/// See [`TYPICAL_GAP_MIN_IN_SPACINGS`].
const TYPICAL_GAP_MAX_IN_SPACINGS: f64 = 3.0;

/// DECISION: a bridge may be at most this many typical gaps long; see [`match_gap_bridges`].
const BRIDGE_MAX_IN_TYPICAL_GAPS: f64 = 2.0;

/// A stroke may be bridged to itself only with at least this many samples (the paper's "more
/// than two edges" before a chain closes).
const MIN_SELF_BRIDGED_SAMPLES: usize = MIN_LOOP_SAMPLES;

pub(super) fn match_gap_bridges(
    vertices: &StrokeVertices,
    delaunay: &NeighbourGraph,
    free_ends: &[FreeEnd],
    spacing: f64,
) -> Vec<(u32, u32)> {
    let candidates = bridge_candidates(vertices, delaunay, free_ends);
    // How many bridges each vertex may take: one per free end it is (two for a one-sample dot).
    let mut slots: HashMap<u32, u8> = HashMap::new();
    for end in free_ends {
        *slots.entry(end.vertex).or_default() += 1;
    }
    let stroke_of: HashMap<u32, usize> = free_ends.iter().map(|e| (e.vertex, e.stroke)).collect();
    let greedy_match = |longest: f64| -> Vec<(f64, u32, u32)> {
        let mut groups = StrokeGroups::new(vertices);
        let mut matched: Vec<(f64, u32, u32)> = Vec::new();
        let mut remaining = slots.clone();
        for &(_, length, a, b) in &candidates {
            // Each pair is a candidate once: `dedup` removed the copy a two-slot dot makes.
            if length > longest || remaining[&a] == 0 || remaining[&b] == 0 {
                continue;
            }
            let (stroke_a, stroke_b) = (stroke_of[&a], stroke_of[&b]);
            // DECISION: a bridge that closes a loop must be short next to the loop: at most a
            // quarter of its length. A skip-stroke gap is a small part of the outline it
            // interrupts; an opening as wide as a quarter of the curve is drawn on purpose (an
            // open mouth, a "C"), and tiny loops of a few dashes are no shapes at all.
            if groups.same(stroke_a, stroke_b)
                && length > LOOP_GAP_MAX_SHARE * (groups.length(stroke_a) + length)
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
    let typical_gap = lengths[lengths.len() / 2].clamp(
        TYPICAL_GAP_MIN_IN_SPACINGS * spacing,
        TYPICAL_GAP_MAX_IN_SPACINGS * spacing,
    );
    greedy_match(BRIDGE_MAX_IN_TYPICAL_GAPS * typical_gap)
        .into_iter()
        .map(|m| (m.1, m.2))
        .collect()
}

/// Every Delaunay edge between two free ends that may be a bridge, cheapest first, each pair once.
fn bridge_candidates(
    vertices: &StrokeVertices,
    delaunay: &NeighbourGraph,
    free_ends: &[FreeEnd],
) -> Vec<Candidate> {
    let positions = &vertices.positions;
    let stroke_of: HashMap<u32, usize> = free_ends.iter().map(|e| (e.vertex, e.stroke)).collect();
    let outward_of: HashMap<u32, Option<Vec2>> =
        free_ends.iter().map(|e| (e.vertex, e.outward)).collect();
    // How much a bridge from `vertex` towards `direction` turns away from where the pen was
    // going: 0 straight on, 1 straight back; nothing for a dot.
    let turn = |vertex: u32, direction: Vec2| -> f64 {
        outward_of
            .get(&vertex)
            .copied()
            .flatten()
            .map_or(0.0, |outward| (1.0 - outward.dot(direction)) / 2.0)
    };
    let mut candidates: Vec<Candidate> = Vec::new();
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
            if other_stroke == end.stroke
                && vertices.of_stroke[end.stroke].len() < MIN_SELF_BRIDGED_SAMPLES
            {
                continue;
            }
            // Gaps are measured between rims: a dot has the size of the dash it stands for.
            let rims = vertices.dot_radius.get(&end.vertex).unwrap_or(&0.0)
                + vertices.dot_radius.get(&other).unwrap_or(&0.0);
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
                Vec2::ZERO
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
    candidates
}

/// Strokes joined by accepted bridges, with the total length of each group (strokes plus
/// bridges), to see when a bridge would close a loop.
struct StrokeGroups {
    sets: UnionFind,
    /// At a root, the group's length.
    length: Vec<f64>,
}

impl StrokeGroups {
    /// Every stroke in a group of its own.
    fn new(vertices: &StrokeVertices) -> Self {
        let stroke_length = |of_stroke: &Vec<u32>| -> f64 {
            let points: Vec<Point> = of_stroke
                .iter()
                .map(|&v| vertices.positions[v as usize])
                .collect();
            polyline_length(&points, false)
        };
        Self {
            sets: UnionFind::new(vertices.of_stroke.len()),
            length: vertices.of_stroke.iter().map(stroke_length).collect(),
        }
    }

    fn root(&mut self, stroke: usize) -> usize {
        self.sets.find(stroke as u32) as usize
    }

    fn same(&mut self, a: usize, b: usize) -> bool {
        self.root(a) == self.root(b)
    }

    fn length(&mut self, stroke: usize) -> f64 {
        let root = self.root(stroke);
        self.length[root]
    }

    /// Joins the groups of strokes `a` and `b` by a bridge (a bridge within one group closes a
    /// loop and only adds its length).
    fn join(&mut self, a: usize, b: usize, bridge_length: f64) {
        let (root_a, root_b) = (self.root(a), self.root(b));
        if root_a == root_b {
            self.length[root_a] += bridge_length;
        } else {
            self.sets.attach(root_b as u32, root_a as u32);
            self.length[root_a] += self.length[root_b] + bridge_length;
        }
    }
}
