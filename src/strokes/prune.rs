//! Cleaning the skeleton graph before it becomes strokes: bubbles between strokes laid side by
//! side, filled corners of a thick pen, and the spurs thinning leaves at bumps of the outline.

use std::collections::HashMap;

use kurbo::Vec2;

use crate::geometry::grid::PointGrid;
use crate::geometry::polyline::polyline_length;

use super::graph::SkeletonGraph;
use super::DIRECTION_SCALE_FLOOR_PX;

/// A filled corner's spur points away from both sides: each side leaves the junction within 60°
/// of the direction opposite the spur, so the cosine between the spur and either side is below
/// cos 120° = −0.5. A stroke's branch in a T or a crossing meets the others at about 90°.
const CORNER_SPUR_MAX_COSINE: f64 = -0.5;

/// A spur's free end faces another free end within this many degrees of both their lines.
const FACING_MAX_DEGREES: f64 = 30.0;

/// How far a spur's free end looks for a free end it faces ([`SkeletonGraph::prune_spurs`]), and
/// over what length the ends' directions are read.
pub(super) struct FacingEnds {
    pub(super) reach: f64,
    pub(super) direction_scale: f64,
}

/// How long a filled corner's spur may be ([`SkeletonGraph::fold_corner_spurs`]), in pixels.
pub(super) struct CornerSpurs {
    /// Never longer than this, however sharp the corner.
    pub(super) max_length: f64,
    /// At most this much longer than the corner's outer point lies from its centre lines'
    /// meeting point.
    pub(super) slack: f64,
    pub(super) stroke_width: f64,
}

impl CornerSpurs {
    /// The longest spur of a corner whose sides leave it along `side_a` and `side_b` (unit
    /// vectors): the outer point of the ink lies `pen / 2 / sin(α / 2)` beyond the centre lines'
    /// meeting point, α the angle between the sides.
    fn longest(&self, side_a: Vec2, side_b: Vec2) -> f64 {
        let half_angle = side_a.dot(side_b).clamp(-1.0, 1.0).acos() / 2.0;
        // The floor keeps sides leaving the same way from dividing by zero; the cap takes over.
        let outer_point = self.stroke_width / 2.0 / half_angle.sin().max(1e-6);
        (outer_point + self.slack).min(self.max_length)
    }
}

impl SkeletonGraph {
    /// Removes small loops: a branch from a node back to itself, and all but the shortest of
    /// several branches between the same two nodes, when shorter than `max_length`.
    pub(super) fn collapse_bubbles(&mut self, max_length: f64) {
        let mut shortest_between: HashMap<(usize, usize), (f64, usize)> = HashMap::new();
        let mut to_remove = Vec::new();
        for (i, branch) in self.branches.iter().enumerate() {
            let Some((a, z)) = branch.nodes else { continue };
            let length = polyline_length(&branch.points, false);
            if length >= max_length {
                continue;
            }
            if a == z {
                to_remove.push(i);
                continue;
            }
            let key = (a.min(z), a.max(z));
            match shortest_between.get(&key) {
                Some(&(best, _)) if best <= length => to_remove.push(i),
                Some(&(_, best_branch)) => {
                    to_remove.push(best_branch);
                    shortest_between.insert(key, (length, i));
                }
                None => {
                    shortest_between.insert(key, (length, i));
                }
            }
        }
        to_remove.sort_unstable();
        to_remove.dedup();
        for branch in to_remove {
            self.remove_branch(branch);
        }
    }

    /// Merges two junctions joined by a branch shorter than `max_link` into one: where two lines
    /// cross at a slant or two curves touch, thinning splits the meeting point into two
    /// three-way junctions a pixel or two apart. Paired one at a time, neither sees the other
    /// line's far branch, and a line turns into the link; merged, the four branches pair as two
    /// lines going on through.
    pub(super) fn merge_linked_junctions(&mut self, max_link: f64) {
        for link in 0..self.branches.len() {
            let branch = &self.branches[link];
            let Some((a, z)) = branch.nodes else { continue };
            if branch.removed
                || a == z
                || self.degree(a) < 3
                || self.degree(z) < 3
                || polyline_length(&branch.points, false) > max_link
            {
                continue;
            }
            self.remove_branch(link);
            let moved = std::mem::take(&mut self.nodes[z].ends);
            for &(b, at_start) in &moved {
                if let Some((start, end)) = self.branches[b].nodes.as_mut() {
                    if at_start {
                        *start = a;
                    } else {
                        *end = a;
                    }
                }
            }
            self.nodes[z].pruned = true;
            let (pa, pz) = (self.nodes[a].position, self.nodes[z].position);
            self.nodes[a].position = pa.midpoint(pz);
            self.nodes[a].ends.extend(moved);
        }
    }

    /// At a junction of exactly three branches where one is a spur pointing away from both
    /// others (each other branch leaves within 60° of the direction opposite the spur), no longer
    /// than `spurs` allows for the angle between the two others, the spur is a filled corner: it
    /// is removed and the junction moves to its tip, so the two sides meet there in a sharp
    /// corner.
    pub(super) fn fold_corner_spurs(&mut self, spurs: &CornerSpurs, direction_scale: f64) {
        for node in 0..self.nodes.len() {
            let ends = self.nodes[node].ends.clone();
            if ends.len() != 3 {
                continue;
            }
            // Of the short free-ended branches here, the one that points most squarely away
            // from both others.
            let mut best: Option<(f64, usize)> = None;
            for (k, &(b, at_start)) in ends.iter().enumerate() {
                let branch = &self.branches[b];
                let (a, z) = branch.nodes.expect("node branches have nodes");
                let far = if at_start { z } else { a };
                let length = polyline_length(&branch.points, false);
                if far == node || self.degree(far) != 1 || length >= spurs.max_length {
                    continue;
                }
                let direction = self.leaving_direction(b, at_start, direction_scale);
                let score_over = |scale: f64| {
                    ends.iter()
                        .filter(|&&(other, _)| other != b)
                        .map(|&(other, other_at_start)| {
                            direction.dot(self.leaving_direction(other, other_at_start, scale))
                        })
                        .fold(f64::NEG_INFINITY, f64::max)
                };
                // DECISION: (stop 46) a spur shorter than the direction scale has its way from
                // its own few pixels; the sides are then also compared over the spur's length
                // (at least the scale's floor), and the spur is a filled corner where either
                // comparison finds it pointing away from both. A thick cloud's notch between two
                // round lobes: its 5-px spur lay 118° from one lobe measured over two pen widths
                // (the lobe curving away), 10° off the sides' bisector, and the notch came out
                // cut by 6–10 px. Measured on the benchmark (exact of 432): seeds 3 and 8 +1,
                // seed 5 +2, the other development seeds and validation unchanged, seed 4 +1 −1.
                // Comparing over the spur's length alone lost three on seed 4, one on seed 1 and
                // one on validation; over half the direction scale a balloon's string took the
                // balloon's short piece past the knot as a corner.
                let mut score = score_over(direction_scale);
                if length < direction_scale {
                    score = score.min(score_over(length.max(DIRECTION_SCALE_FLOOR_PX)));
                }
                if score < CORNER_SPUR_MAX_COSINE && best.is_none_or(|(s, _)| score < s) {
                    best = Some((score, k));
                }
            }
            let Some((_, spur)) = best else { continue };
            let (spur_branch, spur_at_start) = ends[spur];
            let sides: Vec<(usize, bool)> = ends
                .iter()
                .copied()
                .filter(|&(b, _)| b != spur_branch)
                .collect();
            if sides.len() != 2 {
                continue;
            }
            let [side_a, side_b] = [sides[0], sides[1]]
                .map(|(b, at_start)| self.leaving_direction(b, at_start, direction_scale));
            if polyline_length(&self.branches[spur_branch].points, false)
                > spurs.longest(side_a, side_b)
            {
                continue;
            }
            let tip = {
                let points = &self.branches[spur_branch].points;
                if spur_at_start {
                    points[points.len() - 1]
                } else {
                    points[0]
                }
            };
            self.remove_branch(spur_branch);
            self.nodes[node].position = tip;
            for (b, at_start) in sides {
                let points = &mut self.branches[b].points;
                if at_start {
                    points[0] = tip;
                } else {
                    let last = points.len() - 1;
                    points[last] = tip;
                }
            }
        }
    }

    /// Removes branches from a free end to a junction that are shorter than `spur_length`,
    /// shortest first.
    pub(super) fn prune_spurs(&mut self, spur_length: f64, facing: &FacingEnds) {
        let mut spurs: Vec<(f64, usize)> = self
            .branches
            .iter()
            .enumerate()
            .filter(|(_, b)| !b.removed)
            .filter_map(|(i, b)| {
                let (a, z) = b.nodes?;
                let length = polyline_length(&b.points, false);
                let is_spur = (self.degree(a) == 1 && self.degree(z) >= 3)
                    || (self.degree(z) == 1 && self.degree(a) >= 3);
                (is_spur && length < spur_length).then_some((length, i))
            })
            .collect();
        spurs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        // The free ends by position, for the spurs that face one across a gap: made when the
        // first T's stem needs them (a removed spur's free end has no branch left and is passed
        // over, so the grid made once stays true).
        let mut free_ends: Option<PointGrid<usize>> = None;
        for (_, branch) in spurs {
            let (a, z) = self.branches[branch].nodes.expect("spurs have nodes");
            // An earlier removal may have turned the junction into a pass-through: keep it then.
            let junction = if self.degree(a) == 1 { z } else { a };
            if self.degree(junction) < 3 {
                continue;
            }
            let free = if self.degree(a) == 1 { a } else { z };
            // DECISION: (stop 54) a spur that is the stem of a T and faces another stroke's
            // free end across a gap is no bump of the outline: it is a line that goes on across
            // a pen lift to where it stands on another line (a foot's end resting on the next
            // leg, whose side has its pen lift just above the foot; pruned, that side's end
            // found nothing to go on to but the foot's top, and the space between the legs
            // closed as a loop of its own). Measured on the benchmark (exact of 432): seeds 3,
            // 5 and 7 +1 each (two animals, a meander), none lost; validation and seed 4
            // unchanged. Without the T test (any spur facing an end) it lost a letter or an
            // object on seven of the eight splits, at T-junctions whose line goes on through the
            // kept spur; the reach is the same from 4 to 7 pen widths (at 3 the seed 7 animal
            // is not gained), the angle best at 30° (20°: the meander not gained; 45°: a thick
            // meander lost).
            if self.is_stem_of_a_t(branch, junction, facing.direction_scale) {
                let free_ends = free_ends.get_or_insert_with(|| self.free_ends_grid(facing.reach));
                if self.faces_a_free_end(branch, free, free_ends, facing) {
                    continue;
                }
            }
            self.remove_branch(branch);
        }
    }

    /// The free ends' nodes by position, in cells `reach` wide (at least a pixel).
    fn free_ends_grid(&self, reach: f64) -> PointGrid<usize> {
        let mut grid = PointGrid::new(reach.max(1.0));
        for (node, at) in self.nodes.iter().enumerate() {
            if at.ends.len() == 1 {
                grid.insert(at.position, node);
            }
        }
        grid
    }

    /// Whether `branch` is the stem of a T at `junction`: the junction's two other branches
    /// leave it the opposite ways (within [`FACING_MAX_DEGREES`]), one line going on through.
    fn is_stem_of_a_t(&self, branch: usize, junction: usize, direction_scale: f64) -> bool {
        let others: Vec<Vec2> = self.nodes[junction]
            .ends
            .iter()
            .filter(|&&(b, _)| b != branch)
            .map(|&(b, at_start)| self.leaving_direction(b, at_start, direction_scale))
            .collect();
        let max_off = FACING_MAX_DEGREES.to_radians().cos();
        others.len() == 2 && others[0].dot(others[1]) <= -max_off
    }

    /// Whether the free end `free` of `branch` faces another branch's free end across a gap:
    /// that end lies within `facing.reach`, within [`FACING_MAX_DEGREES`] of the way `branch`
    /// leaves through `free`, and its own branch leaves it pointing back within as much.
    fn faces_a_free_end(
        &self,
        branch: usize,
        free: usize,
        free_ends: &PointGrid<usize>,
        facing: &FacingEnds,
    ) -> bool {
        let at = self.nodes[free].position;
        let Some(&(_, at_start)) = self.nodes[free].ends.first() else {
            return false;
        };
        // The way the branch leaves through its free end: from its far end's side.
        let outward = -self.leaving_direction(branch, at_start, facing.direction_scale);
        let max_off = FACING_MAX_DEGREES.to_radians().cos();
        free_ends.around(at).any(|&node| {
            let other = &self.nodes[node];
            if node == free || other.ends.len() != 1 || other.ends[0].0 == branch {
                return false;
            }
            let towards = other.position - at;
            let distance = towards.hypot();
            if distance <= 0.0 || distance > facing.reach {
                return false;
            }
            let towards = towards / distance;
            let (b, other_at_start) = other.ends[0];
            let back = -self.leaving_direction(b, other_at_start, facing.direction_scale);
            outward.dot(towards) >= max_off && back.dot(-towards) >= max_off
        })
    }

    /// Joins the two branches that meet at a node of two branch ends into one branch through it:
    /// collapsing a bubble leaves such a node where a junction was, and a branch cut there is
    /// measured in two pieces (a band's piece next to its junction, too short to judge, and the
    /// rest, no longer at a junction). Called before spur pruning, which leaves such nodes too,
    /// on purpose (see the call in [`super::extract_strokes_and_bands`]).
    pub(super) fn dissolve_pass_through_nodes(&mut self) {
        for node in 0..self.nodes.len() {
            self.dissolve_pass_through_node(node);
        }
    }

    /// Joins the two branches that meet at `node`, if it is a node of two ends of different
    /// branches, into one branch through it; returns the joined branch (the other is removed).
    pub(super) fn dissolve_pass_through_node(&mut self, node: usize) -> Option<usize> {
        let [(first, first_at_start), (second, second_at_start)] = self.nodes[node].ends[..] else {
            return None;
        };
        if first == second {
            return None;
        }
        // `first` runs into the node, `second` out of it.
        if first_at_start {
            self.reverse_branch(first);
        }
        if !second_at_start {
            self.reverse_branch(second);
        }
        let (Some((from, _)), Some((_, to))) =
            (self.branches[first].nodes, self.branches[second].nodes)
        else {
            return None;
        };
        let onward = std::mem::take(&mut self.branches[second].points);
        self.branches[first]
            .points
            .extend(onward.into_iter().skip(1));
        self.branches[first].nodes = Some((from, to));
        self.branches[second].removed = true;
        self.branches[second].nodes = None;
        for end in self.nodes[to].ends.iter_mut() {
            if *end == (second, false) {
                *end = (first, false);
            }
        }
        self.nodes[node].ends.clear();
        self.nodes[node].pruned = true;
        Some(first)
    }
}
