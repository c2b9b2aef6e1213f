//! Bridges through a corner: a line broken by a gap right where another line meets or crosses
//! it. The skeleton then joins the piece on one side of the crossing to the other line in a
//! corner (an "H" whose left stem has a gap just below the crossbar becomes an "L" of the upper
//! stem and the crossbar), and the piece on the far side ends pointing at that corner. The
//! broken line goes on through the corner; the other line ends there. This is issue 9's "bridges
//! to junctions", on the crawl's stroke graph (Parakkat & Muthuganapathy 2016 bridge only free
//! ends; the good-continuation rule is the same as for [`super::bridges`]).

use std::collections::{HashMap, HashSet};

use kurbo::{Point, Vec2};

use super::bridges::{continuation_cost, BridgeableEnd};
use super::strokes::StrokeVertices;
use crate::geometry::grid::PointGrid;

/// A corner of a stroke sharper than this (degrees of turn) may be where a broken line crosses
/// it: the lines of a letter's crossings and junctions meet at 45° or more.
const MIN_CORNER_TURN_DEGREES: f64 = 45.0;

/// DECISION: (stop 28) a corner where a T-end of another stroke ends (a junction of the
/// skeleton) may be gone through from a turn of this much (degrees): the T-end's stub is ink of a
/// fourth line meeting there, so the corner is a crossing or a "K"'s junction, not a stroke's own
/// bend. Thinning rounds such a junction, and a "K" whose arm leaves the stem at about 45°
/// measures under 45° there, so its broken stem found no corner to go on through. Measured on
/// the benchmark: seeds 1 and 3 +2 and +3 (a "K" on each and two arches), seed 5 and the
/// validation split unchanged, seed 4 −1 (a meander); 35° fixes three fewer, 25° loses one on
/// seed 1. A lower turn everywhere (stop 27) lost drawings on both held-out splits.
const MIN_CORNER_TURN_AT_JUNCTION_DEGREES: f64 = 30.0;

/// A corner's vertex is at a junction where a T-end's junction point lies within this share of
/// [`junction_reach`] of it (1.5 px for a 3 px pen; a whole pen width also loses an arch on
/// seed 4).
const JUNCTION_NEAR_SHARE: f64 = 0.5;

/// DECISION: (stop 45) how far a stroke's corner vertex may lie from a junction point and still
/// be the same place: a pen width, or a sample spacing where that is more. The corner's vertex is
/// a sample, and the samples of a stroke lie a spacing apart, so the vertex nearest the point
/// where the skeleton's branches meet can be up to half a spacing from it along the stroke,
/// plus the rounding of the corner across it. With a thin pen (3 px, spacing 4.5 px) a "K"'s
/// junction lay 1.8 px and 3.2 px from the corner vertex of the stroke through it, beyond half a
/// pen and a pen: its corner was no junction's (so under 45° it was no corner), its leg's T-end
/// was still bridged to the broken stem's end, and the cut arm was not joined to the T-end at
/// the corner. Used here at [`JUNCTION_NEAR_SHARE`] and whole by the bridges
/// ([`super::bridges`]). Measured on the benchmark: seeds 1, 3, 5 and validation unchanged,
/// seed 4 +2, and three fresh seeds (6, 7, 8) +1, 0, +2; none lost.
pub(super) fn junction_reach(stroke_width: f64, spacing: f64) -> f64 {
    stroke_width.max(spacing)
}

/// The arms of a corner are measured this many sample spacings from it: far enough that the
/// skeleton's rounding of the corner does not bend them.
pub(super) const ARM_IN_SPACINGS: f64 = 2.0;

/// The end must point at the corner, and the corner's kept arm go on from the end's line, each
/// within this angle (degrees): a straight continuation, with room for the wobble of a
/// short end's direction.
const MAX_THROUGH_TURN_DEGREES: f64 = 40.0;

/// Where the corner's vertex is off the end's line, the end's line and the kept arm must go on
/// within this angle (degrees) of the line from the end to the arm's measured point
/// ([`straight_on_to_arm_point`]): that line is two spacings longer than the one to the corner,
/// so it wobbles less than [`MAX_THROUGH_TURN_DEGREES`] allows for. Measured on the benchmark's
/// dev split: 20° fixes one drawing, 25°–30° two, 40° also breaks a meander.
const ARM_POINT_MAX_TURN_DEGREES: f64 = 25.0;

/// DECISION: (stop 61) an end that lies within this many arms ([`ARM_IN_SPACINGS`]) of a corner
/// (a pen lift's length) and does not point at it as measured is tried again along its stroke's
/// own chord (its direction without the bend carried into it, as the bridges try it): a short
/// piece of a stem whose last pixels curl by 15° or more points off the corner by more than
/// [`MAX_THROUGH_TURN_DEGREES`] (a scanned "P" whose stem has its lift just below the bowl: its
/// lower piece curled 43° off the corner, 27° along its chord). Farther off, the bend is the
/// stroke's curving on into the gap, not a curl: at 2.5 arms, a thick animal's ear went on
/// through a corner of its head 30 px away. Measured on the benchmark (exact of 432): seed 7 +1,
/// nothing lost on any split, the same from 0.8 to 1.5 arms; validation and seed 4 unchanged;
/// the samples unchanged.
const UNBENT_MAX_IN_ARMS: f64 = 1.0;

/// DECISION: a bridge through a corner costs this plus its straight-bridge cost: it is taken
/// only by an end that no ordinary bridge took. Breaking a corner open is the less likely
/// reading: where the end has a partner (the other side of a neck meeting an outline at a
/// corner), the two ends joined leave nothing dangling, while opening the corner would leave
/// its cut arm and the partner both ending in the air. Cusps ([`super::bridges`]) come after.
/// Except at a crossing: where each arm of a corner has an end going on into it from the far
/// side (an "X" or an "8" broken where its lines cross), both lines go straight through, at the
/// cost of straight bridges, before the two ends can be joined round the corner.
const THROUGH_COST_OFFSET: f64 = 1e8;

/// DECISION: at a hairpin (both arms of the corner run on within [`MAX_THROUGH_TURN_DEGREES`] of
/// the end's line) the arm an end goes on into is the one whose line it continues, across, not
/// the one it turns least into: where two lines side by side touch at their tips, the skeleton
/// joins them in a hairpin whose corner lies between the two lines, and from an end beyond it
/// the direction to that corner points at the wrong line. The kept arm must lie at least this
/// much nearer the end's line than the other (pen widths; two lines side by side are a pen
/// width or more apart, centre to centre), and the lines go on past the corner point, which is
/// no part of either (measured on the benchmark: dev 288 → 290, val 283 → 284).
const HAIRPIN_MIN_SIDE_STEP_IN_PEN_WIDTHS: f64 = 0.5;

/// The two ends of a crossing lie across the same gap from it: the farther at most this many
/// times as far from the corner as the nearer, plus a pen width for the skeleton's wobble.
const CROSSING_DISTANCE_RATIO: f64 = 2.0;

/// A corner of a stroke that a free end may go on through: the corner's vertex, the neighbour on
/// the arm that continues the end's line (`keep`), and the neighbour on the other arm (`cut`),
/// which ends at the corner when the bridge is taken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ThroughCorner {
    pub(super) corner: u32,
    pub(super) stroke: usize,
    pub(super) keep: u32,
    pub(super) cut: u32,
    /// Whether the corner is a hairpin, the touching tips of two lines side by side: the lines
    /// go on past it, the corner point between them is no part of either.
    pub(super) hairpin: bool,
    /// Whether a T-end of another stroke ends at the corner: a junction of the skeleton, whose
    /// vertex is where the lines meet, not a stroke's own corner rounded by thinning.
    pub(super) at_junction: bool,
}

/// A possible bridge from a free end through a corner, with its cost and length.
pub(super) struct ThroughCandidate {
    pub(super) end: u32,
    pub(super) through: ThroughCorner,
    pub(super) cost: f64,
    pub(super) length: f64,
}

/// A corner found on a stroke: its vertex, the neighbours on both sides and the unit directions
/// of the two arms leaving it.
struct Corner {
    vertex: u32,
    stroke: usize,
    neighbours: [u32; 2],
    arms: [Vec2; 2],
    /// The points where the arms were measured.
    arm_points: [Point; 2],
    /// Whether a T-end's junction lies beside it.
    at_junction: bool,
}

/// Every free end that points at a corner of a stroke (within `reach`) from the far side of
/// one of its arms: the end's line goes straight on into that arm, and clearly not into the
/// other. They cost as straight bridges ([`continuation_cost`]), plus
/// [`THROUGH_COST_OFFSET`] where the corner is not a crossing.
pub(super) fn through_candidates(
    vertices: &StrokeVertices,
    ends: &[BridgeableEnd],
    reach: f64,
    spacing: f64,
    stroke_width: f64,
) -> Vec<ThroughCandidate> {
    let arm = ARM_IN_SPACINGS * spacing;
    let junctions: Vec<Point> = ends
        .iter()
        .filter(|end| end.attached)
        .map(|end| end.at)
        .collect();
    let near_junction = JUNCTION_NEAR_SHARE * junction_reach(stroke_width, spacing);
    let corners = find_corners(vertices, arm, &junctions, near_junction);
    if corners.is_empty() || reach <= 0.0 {
        return Vec::new();
    }
    // A grid of cells `reach` wide, so that each end looks only at the corners in the cells
    // around it (a page of noise has hundreds of thousands of both).
    let mut grid = PointGrid::new(reach);
    for (index, corner) in corners.iter().enumerate() {
        grid.insert(vertices.positions[corner.vertex as usize], index);
    }
    let max_turn = MAX_THROUGH_TURN_DEGREES.to_radians();
    let mut candidates = Vec::new();
    for end in ends.iter().filter(|end| !end.attached) {
        let Some(outward) = end.outward else {
            continue; // a dot has no line to go on with
        };
        let mut near: Vec<usize> = grid.around(end.at).copied().collect();
        near.sort_unstable();
        for corner in near.iter().map(|&index| &corners[index]) {
            let at = vertices.positions[corner.vertex as usize];
            let offset = at - end.at;
            let distance = offset.hypot();
            if distance > reach || distance == 0.0 || corner.neighbours.contains(&end.vertex) {
                continue;
            }
            let towards = offset / distance;
            let turns = corner.arms.map(|arm| angle(towards, arm));
            let judged = |outward: Vec2| -> Option<(bool, usize, usize, f64, f64)> {
                // At a hairpin (two lines side by side whose tips touch) both arms run on the way
                // the end points, and the corner lies between the two lines: the arm the end goes
                // on into is the one whose line it continues, the nearer across. Elsewhere it is
                // the one it turns least into, clearly: the other turns off at least twice as much.
                let hairpin = corner
                    .arms
                    .iter()
                    .all(|&arm| angle(outward, arm) <= max_turn);
                let (keep, cut, clearly) = if hairpin {
                    let across = corner.arm_points.map(|p| (p - end.at).cross(outward).abs());
                    let (keep, cut) = if across[0] <= across[1] {
                        (0, 1)
                    } else {
                        (1, 0)
                    };
                    let clearly = across[cut]
                        >= across[keep] + HAIRPIN_MIN_SIDE_STEP_IN_PEN_WIDTHS * stroke_width;
                    (keep, cut, clearly)
                } else {
                    let (keep, cut) = if turns[0] <= turns[1] { (0, 1) } else { (1, 0) };
                    (keep, cut, turns[cut] >= 2.0 * turns[keep])
                };
                // The line the end goes on along: to the corner, or at a hairpin, whose corner lies
                // off to the side between the two lines, to the kept arm.
                let (turn_at_end, turn_into_arm) = if hairpin {
                    let onto = corner.arm_points[keep] - end.at;
                    (
                        angle(outward, onto / onto.hypot().max(1e-9)),
                        angle(outward, corner.arms[keep]),
                    )
                } else {
                    (angle(outward, towards), turns[keep])
                };
                let straight_on = turn_at_end <= max_turn && turn_into_arm <= max_turn && clearly;
                let (keep, cut, turn_at_end, turn_into_arm) = if straight_on {
                    (keep, cut, turn_at_end, turn_into_arm)
                } else if hairpin || distance > arm {
                    return None;
                } else if let Some((keep, turn_at_end, turn_into_arm)) =
                    straight_on_to_arm_point(corner, end.at, outward)
                {
                    (keep, 1 - keep, turn_at_end, turn_into_arm)
                } else {
                    return None;
                };
                Some((hairpin, keep, cut, turn_at_end, turn_into_arm))
            };
            // An end's line is tried as measured and, where the end lies within an arm's length
            // of the corner, along its stroke's own chord ([`UNBENT_MAX_IN_ARMS`]).
            let unbent = (end.bend != 0.0 && distance <= UNBENT_MAX_IN_ARMS * arm)
                .then(|| outward.rotate_scale(Vec2::from_angle(-end.bend)));
            let Some((hairpin, keep, cut, turn_at_end, turn_into_arm)) =
                judged(outward).or_else(|| unbent.and_then(judged))
            else {
                continue;
            };
            let cost = continuation_cost(distance, turn_at_end, turn_into_arm);
            candidates.push(ThroughCandidate {
                end: end.vertex,
                through: ThroughCorner {
                    corner: corner.vertex,
                    stroke: corner.stroke,
                    keep: corner.neighbours[keep],
                    cut: corner.neighbours[cut],
                    hairpin,
                    at_junction: corner.at_junction,
                },
                cost,
                length: distance,
            });
        }
    }
    // Corners that two different ends go on through, one into each arm: crossings. Compared
    // within each corner's own candidates (few), not across the page's.
    let mut at_corner: HashMap<u32, Vec<&ThroughCandidate>> = HashMap::new();
    for candidate in &candidates {
        at_corner
            .entry(candidate.through.corner)
            .or_default()
            .push(candidate);
    }
    let crossing: HashSet<u32> = at_corner
        .iter()
        .filter(|(_, group)| {
            group.iter().any(|a| {
                group.iter().any(|b| {
                    b.through.keep != a.through.keep
                        && b.end != a.end
                        && a.length.max(b.length)
                            <= CROSSING_DISTANCE_RATIO * a.length.min(b.length) + stroke_width
                })
            })
        })
        .map(|(&corner, _)| corner)
        .collect();
    for candidate in &mut candidates {
        if !crossing.contains(&candidate.through.corner) {
            candidate.cost += THROUGH_COST_OFFSET;
        }
    }
    candidates
}

/// DECISION: thinning rounds a corner, and sampling can leave the corner's vertex a couple of
/// pixels along the arm that is cut (an "E" whose stem has its gap just below the middle bar:
/// the corner sits on the bar, off the stem's line), so that the direction from the end to it
/// misleads. Judged instead along the line from the end to the point where the kept arm was
/// measured, two spacings up it, the end's line must go straight on into that arm within
/// [`ARM_POINT_MAX_TURN_DEGREES`] at both ends, and the other arm leave it at least twice as
/// steeply. Only for an end no farther from the corner than the arm is measured: farther off, a
/// corner a couple of pixels aside hardly turns the line to it, and the test is not made at
/// all (on a page of noise, where ends and corners abound, that keeps it cheap). Returns the
/// kept arm (0 or 1) and the two turns (radians).
fn straight_on_to_arm_point(
    corner: &Corner,
    end: Point,
    outward: Vec2,
) -> Option<(usize, f64, f64)> {
    let max_turn = ARM_POINT_MAX_TURN_DEGREES.to_radians();
    (0..2).find_map(|keep| {
        let onto = corner.arm_points[keep] - end;
        let length = onto.hypot();
        if length == 0.0 {
            return None;
        }
        let onto = onto / length;
        let turn_at_end = angle(outward, onto);
        let turn_into_arm = angle(onto, corner.arms[keep]);
        let cut_turn = angle(onto, corner.arms[1 - keep]);
        (turn_at_end <= max_turn && turn_into_arm <= max_turn && cut_turn >= 2.0 * turn_into_arm)
            .then_some((keep, turn_at_end, turn_into_arm))
    })
}

/// The angle between two unit vectors, in radians.
pub(super) fn angle(a: Vec2, b: Vec2) -> f64 {
    a.dot(b).clamp(-1.0, 1.0).acos()
}

/// The turn at a vertex of a stroke, the unit directions of its two arms, and the points where
/// they were measured.
type TurnAt = (f64, [Vec2; 2], [Point; 2]);

/// The sharp corners of every stroke: vertices where the stroke turns by more than
/// [`MIN_CORNER_TURN_DEGREES`] between its arms measured `arm` away (by more than
/// [`MIN_CORNER_TURN_AT_JUNCTION_DEGREES`] at a vertex within `near_junction` of one of the
/// `junctions`, where T-ends end), the sharpest of each run of such vertices. Both arms must
/// reach `arm`; a closed stroke's corners may lie anywhere on it.
fn find_corners(
    vertices: &StrokeVertices,
    arm: f64,
    junctions: &[Point],
    near_junction: f64,
) -> Vec<Corner> {
    let min_turn = MIN_CORNER_TURN_DEGREES.to_radians();
    let min_turn_at_junction = MIN_CORNER_TURN_AT_JUNCTION_DEGREES.to_radians();
    let near = near_junction.max(f64::MIN_POSITIVE);
    // The junctions in cells `near` wide (a page of noise has hundreds of thousands).
    let mut by_cell = PointGrid::new(near);
    for &junction in junctions {
        by_cell.insert(junction, junction);
    }
    let at_junction = |p: Point| by_cell.around(p).any(|j| j.distance(p) <= near);
    let mut corners = Vec::new();
    for (stroke, of_stroke) in vertices.of_stroke.iter().enumerate() {
        let closed = vertices.closed[stroke];
        let n = of_stroke.len();
        if n < 3 {
            continue;
        }
        let point = |k: usize| vertices.positions[of_stroke[k] as usize];
        // The turn at each vertex, and the arms that give it (none where an arm runs out).
        let measured: Vec<Option<TurnAt>> = (0..n)
            .map(|k| {
                let (back, back_end) = arm_direction(&point, k, n, closed, arm, false)?;
                let (ahead, ahead_end) = arm_direction(&point, k, n, closed, arm, true)?;
                let turn = std::f64::consts::PI - angle(back, ahead);
                Some((turn, [back, ahead], [back_end, ahead_end]))
            })
            .collect();
        let turn_at = |k: usize| measured[k].map_or(0.0, |(turn, _, _)| turn);
        for k in 0..n {
            let Some((turn, arms, arm_ends)) = measured[k] else {
                continue;
            };
            let Some((before, after)) = vertex_neighbours(k, n, closed) else {
                continue;
            };
            // The sharpest of a run: ties go to the first.
            let beside_junction = at_junction(point(k));
            let least = if beside_junction {
                min_turn_at_junction
            } else {
                min_turn
            };
            if turn < least || turn < turn_at(before) || turn <= turn_at(after) {
                continue;
            }
            corners.push(Corner {
                vertex: of_stroke[k],
                stroke,
                neighbours: [of_stroke[before], of_stroke[after]],
                arms,
                arm_points: arm_ends,
                at_junction: beside_junction,
            });
        }
    }
    corners
}

/// The vertices before and after vertex `k` of a stroke of `n` vertices: round a closed stroke,
/// none at an open stroke's two ends.
pub(super) fn vertex_neighbours(k: usize, n: usize, closed: bool) -> Option<(usize, usize)> {
    if closed {
        Some(((k + n - 1) % n, (k + 1) % n))
    } else if k == 0 || k + 1 == n {
        None
    } else {
        Some((k - 1, k + 1))
    }
}

/// The unit direction from vertex `k` to the point `arm` along the stroke (ahead or back), and
/// that point, if the stroke reaches that far (round a closed stroke, at most halfway).
pub(super) fn arm_direction(
    point: &impl Fn(usize) -> Point,
    k: usize,
    n: usize,
    closed: bool,
    arm: f64,
    ahead: bool,
) -> Option<(Vec2, Point)> {
    let from = point(k);
    let steps = if closed {
        n / 2
    } else if ahead {
        n - 1 - k
    } else {
        k
    };
    let mut walked = 0.0;
    let mut previous = from;
    for step in 1..=steps {
        let index = if ahead {
            (k + step) % n
        } else {
            (k + n - step) % n
        };
        let p = point(index);
        walked += previous.distance(p);
        previous = p;
        if walked >= arm {
            let direction = p - from;
            let length = direction.hypot();
            return (length > 0.0).then(|| (direction / length, p));
        }
    }
    None
}
