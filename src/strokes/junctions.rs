//! Junction pairing: at every node the straightest pairs of branch ends go on through it (good
//! continuation); the rest end there, attached. Paired branches are then chained into strokes.

use std::collections::{HashMap, HashSet};

use kurbo::Point;

use super::graph::{Node, SkeletonGraph};
use super::{Stroke, StrokeEnd};
use crate::geometry::Polyline;

/// A branch end: the branch and whether it is the branch's start.
type BranchEnd = (usize, bool);

/// Pairings forced at junctions (by node index), in place of what the junction would decide:
/// indices into the junction's branch ends, as a [`ContactChoice`] gives them.
pub(crate) type ForcedPairings = HashMap<usize, Vec<(usize, usize)>>;

/// Another way a four-way junction's branches could be paired without crossing: where an
/// outline touches itself, which way round it goes on shows only after the gaps are bridged.
#[derive(Clone, Debug)]
pub(crate) struct ContactChoice {
    /// The junction's node.
    pub(crate) node: usize,
    /// Where it is.
    pub(crate) position: Point,
    /// The other pairing, for [`ForcedPairings`].
    pub(crate) pairs: Vec<(usize, usize)>,
}

/// What the junctions decided, for chaining the branches into strokes.
#[derive(Default)]
struct Pairing {
    /// The branch end each paired end continues into at its node.
    partner: HashMap<BranchEnd, BranchEnd>,
    /// Ends detached at a junction, with the junction's position.
    attached: HashMap<BranchEnd, Point>,
    /// Branch ends whose node position is dropped from the polyline, so that no two strokes
    /// share a point (a crossing's second pair and detached branches).
    skip_node_point: HashSet<BranchEnd>,
    /// Paired ends at a junction where another pair goes on through too, with its position.
    contact: HashMap<BranchEnd, Point>,
}

impl Pairing {
    /// How a stroke ends at the branch end `end` where no partner continues it.
    fn stroke_end(&self, end: BranchEnd) -> StrokeEnd {
        self.attached
            .get(&end)
            .map_or(StrokeEnd::Free, |&p| StrokeEnd::Attached(p))
    }
}

impl SkeletonGraph {
    /// Pairs the branch ends at every node and chains paired branches into strokes: lone dots
    /// first, then open strokes, then closed ones.
    pub(super) fn into_strokes(
        self,
        direction_scale: f64,
        forced: &ForcedPairings,
    ) -> (Vec<Stroke>, Vec<ContactChoice>) {
        let mut pairing = Pairing::default();
        let mut choices = Vec::new();
        for (n, node) in self.nodes.iter().enumerate() {
            let ends = self.live_ends(node);
            if ends.len() < 2 {
                continue;
            }
            if let Some(pairs) = forced.get(&n) {
                record_pairs(node, &ends, pairs, &mut pairing);
                continue;
            }
            let chosen = self.pair_ends_at(&ends, direction_scale);
            if let Some(alternatives) =
                self.other_pairings_without_crossing(&ends, &chosen, direction_scale)
            {
                for pairs in alternatives {
                    choices.push(ContactChoice {
                        node: n,
                        position: node.position,
                        pairs,
                    });
                }
            }
            record_pairs(node, &ends, &chosen, &mut pairing);
        }
        let mut visited = vec![false; self.branches.len()];
        let mut strokes = self.lone_dots();
        self.chain_open_strokes(&pairing, &mut visited, &mut strokes);
        self.chain_closed_strokes(&pairing, &mut visited, &mut strokes);
        (strokes, choices)
    }

    /// The branch ends at `node` that are still there.
    fn live_ends(&self, node: &Node) -> Vec<BranchEnd> {
        node.ends
            .iter()
            .copied()
            .filter(|&(b, _)| !self.branches[b].removed)
            .collect()
    }

    /// At a four-way junction, the pairings of its `ends` that pair all four without crossing
    /// and differ from `chosen`, for the contacts to be decided after the bridges
    /// (`crate::trace`'s `contacts_decided_after_bridges`); `None` at any other junction.
    fn other_pairings_without_crossing(
        &self,
        ends: &[BranchEnd],
        chosen: &[(usize, usize)],
        direction_scale: f64,
    ) -> Option<Vec<Vec<(usize, usize)>>> {
        if ends.len() != 4 {
            return None;
        }
        let directions = self.leaving_directions(ends, direction_scale);
        let order = self.circular_order(ends, &directions);
        let strand = |k: usize| self.branches[ends[k].0].strand_of;
        let allowed = |i: usize, j: usize| {
            ends[i].0 != ends[j].0 && (strand(i).is_none() || strand(i) != strand(j))
        };
        let others = other_non_crossing_pairings(&order, &allowed, chosen);
        (!others.is_empty()).then_some(others)
    }

    /// The indices of `ends` (leaving in `directions`) in their circular order round the
    /// junction, a band's left side a hair counter-clockwise of its right one.
    fn circular_order(&self, ends: &[BranchEnd], directions: &[kurbo::Vec2]) -> Vec<usize> {
        let angle = |k: usize| {
            let (b, at_start) = ends[k];
            let side = self.branches[b].side * if at_start { 1.0 } else { -1.0 };
            // The two sides of a band leave in the same direction; the left one lies a hair
            // counter-clockwise of the right one.
            directions[k].y.atan2(directions[k].x) + side * SIDE_ORDER_RADIANS
        };
        let mut order: Vec<usize> = (0..ends.len()).collect();
        order.sort_by(|&i, &j| angle(i).total_cmp(&angle(j)).then(i.cmp(&j)));
        order
    }

    /// Greedy good continuation at one node: the straightest pair of branch ends goes through
    /// first, then the next straightest of the ends left; an end left over is attached here.
    fn pair_ends_at(&self, ends: &[BranchEnd], direction_scale: f64) -> Vec<(usize, usize)> {
        let ends = ends.to_vec();
        let on_outline = ends
            .iter()
            .any(|&(b, _)| self.branches[b].strand_of.is_some());
        if on_outline && ends.len() <= MAX_ENDS_FOR_EXACT_PAIRING {
            let directions = self.leaving_directions(&ends, direction_scale);
            return self.pairs_without_crossing(&ends, &directions, &|_, _| true);
        }
        // Going straight through means the chord between the two branches, a little away from
        // the node, continues both of them: two curves that touch side by side (their skeletons
        // joined by a link a pixel or two long, one node) each go on along their own line, not
        // across to the other's, which leaves the node in the same direction but offset.
        let tangents: Vec<(Point, kurbo::Vec2)> = ends
            .iter()
            .map(|&(b, s)| self.tangent_away_from_node(b, s, direction_scale))
            .collect();
        let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
        for i in 0..ends.len() {
            for j in i + 1..ends.len() {
                pairs.push((chord_straightness(tangents[i], tangents[j]), i, j));
            }
        }
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then((a.1, a.2).cmp(&(b.1, b.2))));
        let mut used = vec![false; ends.len()];
        let mut chosen = Vec::new();
        for (_, i, j) in pairs {
            if used[i] || used[j] || ends[i].0 == ends[j].0 && ends.len() > 2 {
                continue;
            }
            used[i] = true;
            used[j] = true;
            chosen.push((i, j));
        }
        if ends.len() == 4 {
            let directions = self.leaving_directions(&ends, direction_scale);
            if let Some(outline) = self
                .outline_instead_of_turn_back(&ends, &directions, &chosen)
                .or_else(|| self.outline_instead_of_bent_crossing(&ends, &directions, &chosen))
            {
                chosen = outline;
            }
        }
        chosen
    }

    /// DECISION: at a four-way junction, a pair whose two ends leave side by side (within 45°)
    /// would turn the pen back on itself. When the straightest pairing leaves such a pair, the
    /// junction is not a crossing but the mouth of a narrow neck drawn onto a line (its two
    /// T-junctions merged): each side of the neck goes on into the line on its own side, and the
    /// short stretch of line across the mouth is left out. The same where the neck is one branch
    /// leaving the junction and coming back to it (its sides merged into a U at a pen lift
    /// further on), whose two ends leave side by side (measured on the benchmark: no drawing
    /// changed on either split; the right dumbbell of `dumbbell-scan-004` became one outline).
    /// `ends` leave in `directions`. Returns that pairing, or `None` when `chosen` has no turn-back
    /// or no pairing without one
    /// exists.
    fn outline_instead_of_turn_back(
        &self,
        ends: &[BranchEnd],
        directions: &[kurbo::Vec2],
        chosen: &[(usize, usize)],
    ) -> Option<Vec<(usize, usize)>> {
        let turns_back = |i: usize, j: usize| directions[i].dot(directions[j]) > TURN_BACK_COSINE;
        // A branch that leaves the junction and comes back to it is never paired with itself;
        // left over, its two ends are attached, which seals it as surely as a turn-back pair.
        let paired: HashSet<usize> = chosen.iter().flat_map(|&(i, j)| [i, j]).collect();
        let left_over: Vec<usize> = (0..ends.len()).filter(|i| !paired.contains(i)).collect();
        let loop_turns_back =
            matches!(left_over[..], [i, j] if ends[i].0 == ends[j].0 && turns_back(i, j));
        if !loop_turns_back && !chosen.iter().any(|&(i, j)| turns_back(i, j)) {
            return None;
        }
        let pairs = self.pairs_without_crossing(ends, directions, &|i, j| !turns_back(i, j));
        (pairs.len() * 2 == ends.len()).then_some(pairs)
    }

    /// DECISION: (stop 69) at a four-way junction, the straightest pairing is a crossing only
    /// where its two pairs cross each other and at least one of them goes on nearly straight
    /// (turns by less than [`BENT_CROSSING_MIN_TURN_DEGREES`]): two lines drawn across each
    /// other. Where both pairs turn by more, nothing goes straight through: the ink is an
    /// outline touching itself (a thin tail's two sides meeting the body's line at its base, a
    /// foot resting on the next leg), and an outline never crosses itself, so the junction takes
    /// the non-crossing pairing, as a junction a double strand meets does
    /// ([`Self::pairs_without_crossing`]). Measured on the benchmark (exact, against s69a): seed
    /// 11 +1 (`animals-clean-021`, a thin tail's base paired crossed with turns of 45° and 63°),
    /// nothing lost on any split; only two drawings of all ten splits change (the other,
    /// `arches-scan-015`, exact either way, 2.40 → 2.21 px). Kept at net +1, under the usual +2,
    /// because it changes nothing else and states the outline prior issue 9 asks for. Returns
    /// that pairing, or `None` where the junction is a crossing or no pairing without crossing
    /// pairs every end.
    fn outline_instead_of_bent_crossing(
        &self,
        ends: &[BranchEnd],
        directions: &[kurbo::Vec2],
        chosen: &[(usize, usize)],
    ) -> Option<Vec<(usize, usize)>> {
        if !is_bent_crossing(directions, chosen) {
            return None;
        }
        let pairs = self.pairs_without_crossing(ends, directions, &|_, _| true);
        (pairs.len() * 2 == ends.len()).then_some(pairs)
    }

    /// The direction each of `ends` leaves its junction in.
    fn leaving_directions(&self, ends: &[BranchEnd], direction_scale: f64) -> Vec<kurbo::Vec2> {
        ends.iter()
            .map(|&(b, s)| self.leaving_direction(b, s, direction_scale))
            .collect()
    }

    /// The pairing of `ends` (leaving in `directions`) at a junction on an outline whose parts
    /// touch: no two pairs cross (an outline of a solid never crosses itself), as many ends as
    /// possible go on, and of such pairings the straightest. The two sides of one double strand
    /// are never paired with each other (that would close the band on itself), nor two ends
    /// `also_allowed` refuses.
    fn pairs_without_crossing(
        &self,
        ends: &[BranchEnd],
        directions: &[kurbo::Vec2],
        also_allowed: &dyn Fn(usize, usize) -> bool,
    ) -> Vec<(usize, usize)> {
        let order = self.circular_order(ends, directions);
        let strand = |k: usize| self.branches[ends[k].0].strand_of;
        let allowed = |i: usize, j: usize| {
            ends[i].0 != ends[j].0
                && (strand(i).is_none() || strand(i) != strand(j))
                && also_allowed(i, j)
        };
        let turn = |i: usize, j: usize| 1.0 + directions[i].dot(directions[j]);
        non_crossing_matching(&order, &allowed, &turn)
    }

    /// A lone skeleton pixel (a dot) is a node with no branch at all: a one-point stroke.
    fn lone_dots(&self) -> Vec<Stroke> {
        self.nodes
            .iter()
            .filter(|node| node.ends.is_empty() && !node.pruned)
            .map(|node| Stroke {
                line: Polyline::new(vec![node.position], false),
                ends: [StrokeEnd::Free, StrokeEnd::Free],
                wide: false,
                contacts: Vec::new(),
            })
            .collect()
    }

    /// Open strokes: one from every unpartnered branch end, in branch order, following the
    /// partners until an end that has none.
    fn chain_open_strokes(
        &self,
        pairing: &Pairing,
        visited: &mut [bool],
        strokes: &mut Vec<Stroke>,
    ) {
        for start_branch in 0..self.branches.len() {
            for at_start in [true, false] {
                let branch = &self.branches[start_branch];
                if visited[start_branch]
                    || branch.removed
                    || branch.nodes.is_none()
                    || pairing.partner.contains_key(&(start_branch, at_start))
                {
                    continue;
                }
                let first_end = pairing.stroke_end((start_branch, at_start));
                let mut points: Vec<Point> = Vec::new();
                let mut contacts = Vec::new();
                let leaving = self.follow_partners(
                    (start_branch, at_start),
                    pairing,
                    visited,
                    &mut points,
                    &mut contacts,
                );
                let last_end = pairing.stroke_end(leaving);
                if !points.is_empty() {
                    strokes.push(Stroke {
                        line: Polyline::new(points, false),
                        ends: [first_end, last_end],
                        // A lone dash is a stroke of one branch.
                        wide: branch.wide && leaving.0 == start_branch,
                        contacts,
                    });
                }
            }
        }
    }

    /// Closed strokes: loops with no node, and cycles of paired branches (what the open strokes
    /// left unvisited).
    fn chain_closed_strokes(
        &self,
        pairing: &Pairing,
        visited: &mut [bool],
        strokes: &mut Vec<Stroke>,
    ) {
        for start_branch in 0..self.branches.len() {
            if visited[start_branch] || self.branches[start_branch].removed {
                continue;
            }
            let mut points: Vec<Point> = Vec::new();
            let mut contacts = Vec::new();
            self.follow_partners(
                (start_branch, true),
                pairing,
                visited,
                &mut points,
                &mut contacts,
            );
            // A cycle through a node repeats the node point at both ends.
            if points.len() > 1 && points[0] == points[points.len() - 1] {
                points.pop();
            }
            if !points.is_empty() {
                let closed = points.len() > 2;
                strokes.push(Stroke {
                    line: Polyline::new(points, closed),
                    ends: [StrokeEnd::Free, StrokeEnd::Free],
                    wide: false,
                    contacts,
                });
            }
        }
    }

    /// Walks from the branch end `entry` through the branches its partners lead to, appending
    /// their points, until an end with no unvisited partner; returns that last end.
    fn follow_partners(
        &self,
        entry: BranchEnd,
        pairing: &Pairing,
        visited: &mut [bool],
        points: &mut Vec<Point>,
        contacts: &mut Vec<Point>,
    ) -> BranchEnd {
        let (mut b, mut entering_at_start) = entry;
        loop {
            visited[b] = true;
            self.append_branch(points, b, entering_at_start, &pairing.skip_node_point);
            let leaving = (b, !entering_at_start);
            if let Some(&contact) = pairing.contact.get(&leaving) {
                contacts.push(contact);
            }
            match pairing.partner.get(&leaving) {
                Some(&(next, next_at_start)) if !visited[next] => {
                    b = next;
                    entering_at_start = next_at_start;
                }
                _ => return leaving,
            }
        }
    }

    /// Appends the points of `branch`, walked from its start if `from_start`, to `points`,
    /// without repeating the shared node point and without node points marked to be skipped.
    fn append_branch(
        &self,
        points: &mut Vec<Point>,
        branch: usize,
        from_start: bool,
        skip_node_point: &HashSet<BranchEnd>,
    ) {
        let source = &self.branches[branch].points;
        let count = source.len();
        let is_node_end = self.branches[branch].nodes.is_some();
        for k in 0..count {
            let p = if from_start {
                source[k]
            } else {
                source[count - 1 - k]
            };
            if is_node_end {
                let at_first = k == 0;
                let at_last = k + 1 == count;
                // The first/last point of a branch is its node's position.
                let end_key = if at_first {
                    Some((branch, from_start))
                } else if at_last {
                    Some((branch, !from_start))
                } else {
                    None
                };
                // A branch of two points keeps both: without its node point it would be a dot.
                if let Some(key) = end_key {
                    if skip_node_point.contains(&key) && count > 2 {
                        continue;
                    }
                }
            }
            if points.last() != Some(&p) {
                points.push(p);
            }
        }
    }
}

/// How straight the pen goes from one branch into the other through their node: −1 when the
/// chord between the two branches' points a little away from the node continues both branches'
/// tangents there, up to 1 for a full turn back. With both points on the node this is the
/// plain angle between the two leaving directions.
fn chord_straightness(a: (Point, kurbo::Vec2), b: (Point, kurbo::Vec2)) -> f64 {
    let chord = b.0 - a.0;
    let length = chord.hypot();
    if length == 0.0 {
        return a.1.dot(b.1);
    }
    let along = chord / length;
    // Arriving along −a's tangent, leaving along b's; each compared with the chord.
    -(b.1.dot(along) - a.1.dot(along)) / 2.0
}

/// Whether two `pairs` of four branch ends leaving a junction in `directions` cross each other
/// round the junction (their ends alternate) with neither going on straight: both turn by at
/// least [`BENT_CROSSING_MIN_TURN_DEGREES`] (0° straight on, 180° back the way it came).
fn is_bent_crossing(directions: &[kurbo::Vec2], pairs: &[(usize, usize)]) -> bool {
    let [(a, b), (c, d)] = pairs[..] else {
        return false;
    };
    let turn = |i: usize, j: usize| {
        (-directions[i].dot(directions[j]))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    };
    let angle = |k: usize| directions[k].y.atan2(directions[k].x);
    // Whether the end `k` lies on the way round from `a` to `b` (counter-clockwise).
    let on_way = |k: usize| {
        let tau = std::f64::consts::TAU;
        (angle(k) - angle(a)).rem_euclid(tau) < (angle(b) - angle(a)).rem_euclid(tau)
    };
    on_way(c) != on_way(d)
        && turn(a, b) >= BENT_CROSSING_MIN_TURN_DEGREES
        && turn(c, d) >= BENT_CROSSING_MIN_TURN_DEGREES
}

/// A crossing whose two pairs both turn by at least this much (degrees) is no crossing drawn
/// but an outline touching itself ([`SkeletonGraph::outline_instead_of_bent_crossing`]).
// DECISION: (stop 69) 35°: 25°, 30° and 45° measure the same (seed 11 +1, nothing lost); at
// 60° the gain goes (its pairs turn by 45° and 63°). A line drawn across another, jittered and
// blurred by thinning, turns by 20° at most ([`crate::crawl::crossings`]' straight limit).
const BENT_CROSSING_MIN_TURN_DEGREES: f64 = 35.0;

/// Two branch ends leaving a junction within 45° of each other leave side by side: pairing them
/// turns the pen back (the same limit as the bridges' "same way", see `crawl::bridges`).
const TURN_BACK_COSINE: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Orders the two sides of a band that leave a junction in the same direction (radians): far
/// below any angle between real branches.
const SIDE_ORDER_RADIANS: f64 = 1e-6;

/// Junctions with more ends than this are paired greedily even on an outline: the exact search
/// below grows exponentially, and such junctions are blots, not contacts.
const MAX_ENDS_FOR_EXACT_PAIRING: usize = 8;

/// A matching replaces an equally large one only when it is cheaper by more than this: costs
/// are sums of a few turns in [0, 2], so float rounding between two orders of summing the same
/// pairs (about 1e-15) never counts as cheaper: the first matching the search finds wins a tie,
/// whatever the rounding.
const COST_TIE_MARGIN: f64 = 1e-12;

/// Writes the chosen pairs of `ends` (indices into it) into `pairing`; ends left over are
/// attached at the node. The first pair keeps the node's point, later pairs skip it so that no
/// two strokes share a point.
fn record_pairs(node: &Node, ends: &[BranchEnd], pairs: &[(usize, usize)], pairing: &mut Pairing) {
    let mut used = vec![false; ends.len()];
    for (n, &(i, j)) in pairs.iter().enumerate() {
        used[i] = true;
        used[j] = true;
        pairing.partner.insert(ends[i], ends[j]);
        pairing.partner.insert(ends[j], ends[i]);
        if pairs.len() > 1 {
            pairing.contact.insert(ends[i], node.position);
            pairing.contact.insert(ends[j], node.position);
        }
        if n > 0 {
            pairing.skip_node_point.insert(ends[i]);
            pairing.skip_node_point.insert(ends[j]);
        }
    }
    for (k, &end) in ends.iter().enumerate() {
        if !used[k] {
            pairing.attached.insert(end, node.position);
            pairing.skip_node_point.insert(end);
        }
    }
}

/// The two pairings of the four items in `order` (their circular order round a junction) whose
/// pairs do not cross, each pair `allowed`, other than `chosen` (in either order of pairs and
/// of ends).
fn other_non_crossing_pairings(
    order: &[usize],
    allowed: &dyn Fn(usize, usize) -> bool,
    chosen: &[(usize, usize)],
) -> Vec<Vec<(usize, usize)>> {
    let normal = |pairs: &[(usize, usize)]| {
        let mut pairs: Vec<(usize, usize)> =
            pairs.iter().map(|&(i, j)| (i.min(j), i.max(j))).collect();
        pairs.sort_unstable();
        pairs
    };
    let chosen = normal(chosen);
    let [a, b, c, d] = order[..] else {
        return Vec::new();
    };
    [vec![(a, b), (c, d)], vec![(b, c), (d, a)]]
        .into_iter()
        .filter(|pairs| pairs.iter().all(|&(i, j)| allowed(i, j)) && normal(pairs) != chosen)
        .collect()
}

/// The best matching of the items in `order` (their circular order around a junction) whose
/// pairs do not cross: the most pairs, then the least total `cost`; only `allowed` pairs.
/// Chords between points on a circle cross exactly when their intervals in the circular order
/// interleave, so an interval search over the order finds it.
fn non_crossing_matching(
    order: &[usize],
    allowed: &dyn Fn(usize, usize) -> bool,
    cost: &dyn Fn(usize, usize) -> f64,
) -> Vec<(usize, usize)> {
    best_matching(order, allowed, cost).2
}

/// The best non-crossing matching within `order`: its number of pairs, its total cost, and the
/// pairs.
fn best_matching(
    order: &[usize],
    allowed: &dyn Fn(usize, usize) -> bool,
    cost: &dyn Fn(usize, usize) -> f64,
) -> (usize, f64, Vec<(usize, usize)>) {
    let Some((&first, rest)) = order.split_first() else {
        return (0, 0.0, Vec::new());
    };
    // Either the first item stays unpaired…
    let mut best = best_matching(rest, allowed, cost);
    // …or it pairs with an item k, which splits the rest into inside and outside the chord.
    for k in 0..rest.len() {
        if !allowed(first, rest[k]) {
            continue;
        }
        let (inside_count, inside_cost, inside) = best_matching(&rest[..k], allowed, cost);
        let (outside_count, outside_cost, outside) = best_matching(&rest[k + 1..], allowed, cost);
        let count = 1 + inside_count + outside_count;
        let total = cost(first, rest[k]) + inside_cost + outside_cost;
        if count > best.0 || count == best.0 && total < best.1 - COST_TIE_MARGIN {
            let mut pairs = vec![(first, rest[k])];
            pairs.extend(inside);
            pairs.extend(outside);
            best = (count, total, pairs);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_matching_never_crosses_and_pairs_all_it_can() {
        // Four ends around a junction, in circular order 0..4; pairing across (0–2, 1–3) is
        // cheapest but crosses, so the best non-crossing pairing is taken.
        let cost = |i: usize, j: usize| {
            if (i + 2) % 4 == j || (j + 2) % 4 == i {
                0.0
            } else {
                1.0
            }
        };
        let pairs = non_crossing_matching(&[0, 1, 2, 3], &|_, _| true, &cost);
        assert_eq!(pairs.len(), 2, "{pairs:?}");
        let crossing = |(a, b): (usize, usize), (c, d): (usize, usize)| {
            let inside = |x: usize| a.min(b) < x && x < a.max(b);
            inside(c) != inside(d)
        };
        assert!(!crossing(pairs[0], pairs[1]), "{pairs:?}");
        // Forbidden pairs are left out, even when that leaves an end over.
        let pairs = non_crossing_matching(&[0, 1, 2], &|i, j| i + j != 1, &cost);
        assert_eq!(pairs.len(), 1, "{pairs:?}");
        assert_ne!(pairs[0], (0, 1));
    }

    #[test]
    fn a_four_way_junction_offers_its_other_pairings_without_crossing() {
        // Four ends in circular order 2, 0, 3, 1: the pairings without crossing are (2, 0) with
        // (3, 1), and (0, 3) with (1, 2); pairing across, (2, 3) with (0, 1), crosses.
        let order = [2, 0, 3, 1];
        let any = |_: usize, _: usize| true;
        // Chosen crossing: both others are offered.
        let others = other_non_crossing_pairings(&order, &any, &[(2, 3), (0, 1)]);
        assert_eq!(others, vec![vec![(2, 0), (3, 1)], vec![(0, 3), (1, 2)]]);
        // Chosen one of them (its pairs and ends in another order): only the other.
        let others = other_non_crossing_pairings(&order, &any, &[(1, 3), (0, 2)]);
        assert_eq!(others, vec![vec![(0, 3), (1, 2)]]);
        // A pair that is not allowed (a band's two sides) rules its pairing out.
        let others =
            other_non_crossing_pairings(&order, &|i, j| i.min(j) != 0 || i.max(j) != 3, &[]);
        assert_eq!(others, vec![vec![(2, 0), (3, 1)]]);
        // Not four ends: nothing.
        assert!(other_non_crossing_pairings(&[0, 1, 2], &any, &[]).is_empty());
    }

    #[test]
    fn a_crossing_goes_straight_through_and_a_bent_one_is_an_outline_touching_itself() {
        let way = |degrees: f64| {
            let r = degrees.to_radians();
            kurbo::Vec2::new(r.cos(), r.sin())
        };
        // An "X": each pair goes straight on across the other.
        let x = [way(0.0), way(80.0), way(180.0), way(260.0)];
        assert!(!is_bent_crossing(&x, &[(0, 2), (1, 3)]));
        // A contact: ends at −115°, −155°, −20° and 127° (a thin tail's base on the body,
        // `animals-clean-021`), paired straightest as (1, 2) and (0, 3), crossing, turning by
        // 45° and 62°.
        let contact = [way(-115.0), way(-155.0), way(-20.0), way(127.0)];
        assert!(is_bent_crossing(&contact, &[(1, 2), (0, 3)]));
        // The same ends paired without crossing are no bent crossing.
        assert!(!is_bent_crossing(&contact, &[(0, 1), (2, 3)]));
        // One pair straight (within 35°) keeps the crossing.
        let through = [way(0.0), way(60.0), way(170.0), way(250.0)];
        assert!(!is_bent_crossing(&through, &[(0, 2), (1, 3)]));
    }
}
