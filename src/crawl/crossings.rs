//! Curves paired again at junctions the crawl went round the wrong way: two open curves that
//! turn a corner at the same point, where each went on into the other's line (a "K" whose stem
//! broke at its junction comes out as the upper stem turning into the leg and the arm turning
//! into the lower stem), and an open curve whose end points at another's corner across a gap (an
//! "A" whose left leg broke where the bar meets it: the upper leg turned into the bar, the lower
//! leg stayed alone). At a junction the branches are paired straightest first (good
//! continuation, Wertheimer 1923; the crawl's own rule at the skeleton's junctions), so the stem
//! goes through and the arm and the leg meet in their corner, and the leg goes on through the
//! bar's corner. The paper (Parakkat & Muthuganapathy 2016) crawls each curve on its own; these
//! rules are ours.

use kurbo::{Point, Vec2};

use std::collections::BTreeMap;

use super::bridges::BRIDGE_MAX_IN_TYPICAL_GAPS;
use crate::geometry::grid::PointGrid;
use crate::geometry::polyline::{lines_meet, point_along, signed_turn, within_of_chain, Polyline};

/// Two curves meet at a point where a vertex of one lies within this much (pen widths) of a
/// vertex of the other: both passed the same junction of the ink.
const MEET_IN_PEN_WIDTHS: f64 = 1.0;

/// An arm's direction is the chord from [`CORNER_LINE_FROM`] of this much of the curve (pen
/// widths) from the meeting point to all of it, past the junction's blur.
// DECISION: (stop 48) five pen widths. Measured over three (from the meeting point, as
// [`super::tips`] measures a tip's arms), a thin "K"'s stem read bent by 35° in its junction's
// blur and was paired the wrong way (development +2 −1); from half of five to five, +3 −0.
const ARM_IN_PEN_WIDTHS: f64 = 5.0;

/// DECISION: (stop 48) two arms go straight on through a junction where they turn by at most
/// this much (degrees): a stem broken at the junction, drawn with a little jitter.
const STRAIGHT_MAX_TURN_DEGREES: f64 = 20.0;

/// DECISION: (stop 48) the other two arms meet in a corner of at least this turn (degrees): a
/// "K"'s arm and leg turn by 100° and more; two lines side by side that a bridge took across
/// from one to the other, and back, turn by less (41° where a thin pair of lines crossed).
const OTHER_PAIR_MIN_TURN_DEGREES: f64 = 60.0;

/// DECISION: (stop 48) each curve turns a corner at the meeting point by at least this much
/// (degrees): a curve that goes straight through a junction is paired well already (an "X").
const CORNER_MIN_TURN_DEGREES: f64 = 30.0;

/// Pairs again the arms of every two open curves of `curves` that turn a corner at the same
/// point, straightest first, where one pair of arms then goes straight through
/// ([`STRAIGHT_MAX_TURN_DEGREES`]), the other pair makes a corner
/// ([`OTHER_PAIR_MIN_TURN_DEGREES`]) and both curves turned a corner there
/// ([`CORNER_MIN_TURN_DEGREES`]). Each curve is paired again at most once.
pub fn pair_arms_straightest_first(curves: &mut [Polyline], stroke_width: f64) {
    if stroke_width <= 0.0 {
        return;
    }
    let reach = MEET_IN_PEN_WIDTHS * stroke_width;
    let arm = ARM_IN_PEN_WIDTHS * stroke_width;
    let open: Vec<usize> = (0..curves.len()).filter(|&c| !curves[c].closed).collect();
    let interior = open_interior_points(curves, reach);
    // The nearest meeting of each two curves, by the pair (in order, for byte-identical output).
    let mut meetings: BTreeMap<(usize, usize), (f64, usize, usize)> = BTreeMap::new();
    for &p in &open {
        let n = curves[p].points.len();
        for i in 1..n.saturating_sub(1) {
            let here = curves[p].points[i];
            for &(q, j) in interior.around(here) {
                let distance = here.distance(curves[q].points[j]);
                if q <= p || distance > reach {
                    continue;
                }
                let nearest = meetings.entry((p, q)).or_insert((distance, i, j));
                if distance < nearest.0 {
                    *nearest = (distance, i, j);
                }
            }
        }
    }
    // A curve paired again is done with: its points are no longer where the meetings found them.
    let mut paired_again = vec![false; curves.len()];
    for ((p, q), (_, i, j)) in meetings {
        if paired_again[p] || paired_again[q] {
            continue;
        }
        if let Some((first, second)) = repaired(&curves[p].points, i, &curves[q].points, j, arm) {
            curves[p].points = first;
            curves[q].points = second;
            paired_again[p] = true;
            paired_again[q] = true;
        }
    }
}

/// The interior points (all but the ends) of the open curves of `curves`, as (curve, point)
/// by position, in cells `cell` wide (at least a pixel).
fn open_interior_points(curves: &[Polyline], cell: f64) -> PointGrid<(usize, usize)> {
    let mut interior = PointGrid::new(cell.max(1.0));
    for (c, curve) in curves.iter().enumerate() {
        if !curve.closed {
            for k in 1..curve.points.len().saturating_sub(1) {
                interior.insert(curve.points[k], (c, k));
            }
        }
    }
    interior
}

/// DECISION: (stop 48) an open curve's end points at another curve's corner within this much
/// (degrees): its line runs on into the corner.
const END_AT_CORNER_MAX_DEGREES: f64 = 15.0;

/// DECISION: (stop 55) where the arm a curve's end would go on into through a corner comes back
/// along itself to end free ahead of that end (the straight line from the corner to the arm's
/// end within a pen width of the curve all the way, the arm's end pointing back at the end
/// within this angle, degrees), the end goes on to the arm's end instead, and the corner stays:
/// the two are one line whose two strands coincide there. A thin lasso's rope leaves its loop
/// in two coincident strands that part further on; where one rope's pen lift fell at the
/// parting, its end pointed at the other rope's corner, and going on through it the lasso came
/// out in two. Measured on the benchmark (exact of 432): seed 6 +1 (that lasso), none lost,
/// validation and seed 4 unchanged. Without the angle test, seed 1 lost a thin letter and
/// validation one drawing (seen).
const ARM_END_BACK_MAX_DEGREES: f64 = 45.0;

/// Sends every open curve whose end points at a corner of another open curve, across a gap as
/// long as the longest bridge (`typical_gap` times [`BRIDGE_MAX_IN_TYPICAL_GAPS`]), on through
/// the corner into the arm that goes on along its line ([`STRAIGHT_MAX_TURN_DEGREES`]), where
/// the other arm turns off it ([`CORNER_MIN_TURN_DEGREES`]): an "A" whose left leg broke where
/// the bar meets it came out as the upper leg turning into the bar, and the lower leg alone.
/// The corner's other arm then ends at the corner; or, where that arm comes back to end free
/// ahead ([`ARM_END_BACK_MAX_DEGREES`]), the end goes on to its end. Each curve changes at most
/// once a pass, and the passes go on while one changes something
/// ([`MAX_GO_ON_THROUGH_PASSES`]).
pub fn go_on_through_corners(curves: &mut Vec<Polyline>, typical_gap: f64, stroke_width: f64) {
    let reach = BRIDGE_MAX_IN_TYPICAL_GAPS * typical_gap;
    if stroke_width <= 0.0 || reach <= 0.0 {
        return;
    }
    for _ in 0..MAX_GO_ON_THROUGH_PASSES {
        if !go_on_through_corners_once(curves, reach, stroke_width) {
            break;
        }
    }
}

/// DECISION: (stop 60) ends go on through corners in passes, as long as a pass changes a curve,
/// up to this many: a curve changed in a pass is done with for that pass (its points are no
/// longer where the pass found them), but it may still have a corner another end goes on
/// through. An "H" whose two stems both broke just below the bar can come out of the crawl as
/// one curve round both of the bar's corners, the upper stems and the bar, with the two lower
/// stems pointing at its corners; one pass sends only one lower stem on through its corner.
/// Measured on the benchmark (exact of 432): alone, no drawing gained or lost on any split;
/// with the end ahead's line read past a hook ([`super::bridges`], same stop), which keeps the
/// lower right stem of that "H" from a corner bridge up its own stem, seed 7 +1 (the "H",
/// `letters-scan-003`), nothing lost, validation and seed 4 unchanged. A letter's curve has a
/// few corners; more passes than this would be ends going on through corners round and round.
const MAX_GO_ON_THROUGH_PASSES: usize = 4;

/// One pass of [`go_on_through_corners`]; whether it changed a curve.
fn go_on_through_corners_once(curves: &mut Vec<Polyline>, reach: f64, stroke_width: f64) -> bool {
    let arm = ARM_IN_PEN_WIDTHS * stroke_width;
    let interior = open_interior_points(curves, reach);
    let mut changed = vec![false; curves.len()];
    let mut merged = vec![false; curves.len()];
    for q in 0..curves.len() {
        for at_start in [true, false] {
            if changed[q] || curves[q].closed || curves[q].points.len() < 2 {
                continue;
            }
            let points = &curves[q].points;
            let end = if at_start { 0 } else { points.len() - 1 };
            let Some(inward) = arm_direction(points, end, arm, at_start) else {
                continue;
            };
            let (e, ahead) = (points[end], -inward);
            // The nearest corner straight ahead of the end.
            let mut best: Option<(f64, usize, usize, bool)> = None;
            for &(p, k) in interior.around(e) {
                // A curve changed already is done with: its points are no longer where the grid
                // has them.
                if p == q || changed[p] {
                    continue;
                }
                let gap = curves[p].points[k] - e;
                let distance = gap.hypot();
                if distance > reach || distance == 0.0 {
                    continue;
                }
                if signed_turn(ahead, gap).abs().to_degrees() > END_AT_CORNER_MAX_DEGREES {
                    continue;
                }
                let Some(on) = corner_arm_going_on(&curves[p].points, k, ahead, arm) else {
                    continue;
                };
                if best.is_none_or(|(d, ..)| distance < d) {
                    best = Some((distance, p, k, on));
                }
            }
            let Some((_, p, k, forwards)) = best else {
                continue;
            };
            // The arm going on comes back to end free ahead of the end, along its own first
            // stretch ([`ARM_END_BACK_MAX_DEGREES`]): the end goes on to that free end, along
            // the arm, and the corner stays.
            let arm_end_index = if forwards {
                curves[p].points.len() - 1
            } else {
                0
            };
            let arm_end = curves[p].points[arm_end_index];
            let to_arm_end = arm_end - e;
            let corner_point = curves[p].points[k];
            let along_arm = |t: f64| {
                within_of_chain(
                    corner_point.lerp(arm_end, t),
                    &curves[p].points,
                    stroke_width,
                )
            };
            let steps = corner_point.distance(arm_end).ceil().max(1.0) as usize;
            let comes_back = |inward: Vec2| {
                signed_turn(-inward, -to_arm_end).abs().to_degrees() <= ARM_END_BACK_MAX_DEGREES
            };
            if to_arm_end.hypot() > 0.0
                && signed_turn(ahead, to_arm_end).abs().to_degrees() <= END_AT_CORNER_MAX_DEGREES
                && arm_direction(&curves[p].points, arm_end_index, arm, !forwards)
                    .is_some_and(comes_back)
                && (0..=steps).all(|step| along_arm(step as f64 / steps as f64))
            {
                let mut joined = curves[q].points.clone();
                if at_start {
                    joined.reverse();
                }
                let mut rest = curves[p].points.clone();
                if forwards {
                    rest.reverse();
                }
                joined.extend(rest);
                curves[q].points = joined;
                curves[p].points.clear();
                merged[p] = true;
                changed[p] = true;
                changed[q] = true;
                continue;
            }
            let corner = curves[p].points.clone();
            let (going_on, staying): (Vec<Point>, Vec<Point>) = if forwards {
                (corner[k..].to_vec(), corner[..=k].to_vec())
            } else {
                (
                    corner[..=k].iter().rev().copied().collect(),
                    corner[k..].to_vec(),
                )
            };
            let mut through = curves[q].points.clone();
            if at_start {
                through.reverse();
            }
            through.extend(going_on);
            curves[q].points = through;
            curves[p].points = staying;
            changed[p] = true;
            changed[q] = true;
        }
    }
    super::remove_marked(curves, &merged);
    changed.contains(&true)
}

/// At a corner of `points` (vertex `k`), the arm that goes on along direction `ahead` (true for
/// the arm after `k`), where the other arm turns off that line.
fn corner_arm_going_on(points: &[Point], k: usize, ahead: Vec2, arm: f64) -> Option<bool> {
    let before = arm_direction(points, k, arm, false)?;
    let after = arm_direction(points, k, arm, true)?;
    let along = |x: Vec2| signed_turn(ahead, x).abs().to_degrees();
    let (on, off) = if along(after) <= along(before) {
        (after, before)
    } else {
        (before, after)
    };
    // The arm going off turns from the line through the corner by its own angle.
    (along(on) <= STRAIGHT_MAX_TURN_DEGREES && turn_between(-ahead, off) >= CORNER_MIN_TURN_DEGREES)
        .then_some(on == after)
}

/// The unit direction of an arm of the curve from `points[k]` (forwards or backwards): from the
/// point [`CORNER_LINE_FROM`] of `length` along it to the point `length` along it, past the
/// junction's blur; none where the curve is shorter.
fn arm_direction(points: &[Point], k: usize, length: f64, forwards: bool) -> Option<Vec2> {
    let way = point_along(points, false, k, length, forwards)?
        - point_along(points, false, k, CORNER_LINE_FROM * length, forwards)?;
    let size = way.hypot();
    (size > 0.0).then(|| way / size)
}

/// Where the lines of two arms meet (each through its points [`CORNER_LINE_FROM`] and `arm`
/// along the curve from the meeting point), if within `arm` of `near`: the corner the two arms
/// make, which the junction's blur of ink rounded.
fn corner_of(
    x: (&[Point], usize, bool),
    y: (&[Point], usize, bool),
    arm: f64,
    near: Point,
) -> Option<Point> {
    let line = |(points, k, forwards): (&[Point], usize, bool)| {
        Some((
            point_along(points, false, k, arm, forwards)?,
            point_along(points, false, k, CORNER_LINE_FROM * arm, forwards)?,
        ))
    };
    let ((x_far, x_near), (y_far, y_near)) = (line(x)?, line(y)?);
    let corner = lines_meet(x_far, x_near, y_far, y_near, MIN_CROSSING_SINE)?;
    (corner.distance(near) <= arm).then_some(corner)
}

/// An arm's line for [`corner_of`] starts this share of the arm from the meeting point.
const CORNER_LINE_FROM: f64 = 0.5;

/// Lines closer to parallel than this (the sine of their angle) do not meet in a corner.
const MIN_CROSSING_SINE: f64 = 0.1;

/// How much (degrees) a curve turns going in along arm `x` and out along arm `y`, both
/// directions pointing away from the meeting point.
fn turn_between(x: Vec2, y: Vec2) -> f64 {
    signed_turn(-x, y).abs().to_degrees()
}

/// The two curves paired again at the meeting point (`a[i]`, `b[j]`), or none where the
/// straightest pair of arms is one they already have, or no pair goes straight through.
fn repaired(
    a: &[Point],
    i: usize,
    b: &[Point],
    j: usize,
    arm: f64,
) -> Option<(Vec<Point>, Vec<Point>)> {
    // The four arms, pointing away from the meeting point: a's start and end, b's start and end.
    let arms = [
        arm_direction(a, i, arm, false)?,
        arm_direction(a, i, arm, true)?,
        arm_direction(b, j, arm, false)?,
        arm_direction(b, j, arm, true)?,
    ];
    let turn = |x: usize, y: usize| turn_between(arms[x], arms[y]);
    if turn(0, 1) < CORNER_MIN_TURN_DEGREES || turn(2, 3) < CORNER_MIN_TURN_DEGREES {
        return None;
    }
    // The other two pairings: a's start with b's start (and the ends together), or with b's end.
    // Each pairs arm 0 (a's start) with one of b's arms and arm 1 (a's end) with the other.
    let starts_together = turn(0, 2).min(turn(1, 3)) <= turn(0, 3).min(turn(1, 2));
    let pairs = if starts_together {
        [(0, 2), (1, 3)]
    } else {
        [(0, 3), (1, 2)]
    };
    let pair_turn = |pair: usize| turn(pairs[pair].0, pairs[pair].1);
    // One pair goes straight through; the other two arms meet in their corner.
    let straight = if pair_turn(0) <= pair_turn(1) { 0 } else { 1 };
    if pair_turn(straight) > STRAIGHT_MAX_TURN_DEGREES
        || pair_turn(1 - straight) < OTHER_PAIR_MIN_TURN_DEGREES
    {
        return None;
    }
    let (a_start, a_end) = (&a[..i], &a[i + 1..]);
    let (b_start, b_end) = (&b[..j], &b[j + 1..]);
    let joined = |x: &[Point], at: Point, y: &[Point]| -> Vec<Point> {
        x.iter()
            .copied()
            .chain([at])
            .chain(y.iter().copied())
            .collect()
    };
    let reversed = |x: &[Point]| -> Vec<Point> { x.iter().rev().copied().collect() };
    let meeting = a[i].midpoint(b[j]);
    let arm_of = |x: usize| match x {
        0 => (a, i, false),
        1 => (a, i, true),
        2 => (b, j, false),
        _ => (b, j, true),
    };
    // The straight pair goes through the meeting point; the other pair meets in the corner of
    // its arms' lines, where there is one near (read from the arm the new curve comes in by).
    let at = |pair: usize| {
        if pair == straight {
            return meeting;
        }
        let (x, y) = pairs[pair];
        let (from, to) = if pair == 0 { (x, y) } else { (y, x) };
        corner_of(arm_of(from), arm_of(to), arm, meeting).unwrap_or(meeting)
    };
    // a's start, then b's arm paired with it; b's other arm, then a's end.
    let (after_a_start, before_a_end) = if starts_together {
        (reversed(b_start), reversed(b_end))
    } else {
        (b_end.to_vec(), b_start.to_vec())
    };
    Some((
        joined(a_start, at(0), &after_a_start),
        joined(&before_a_end, at(1), a_end),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(points: &[(f64, f64)]) -> Polyline {
        Polyline::new(
            points.iter().map(|&(x, y)| Point::new(x, y)).collect(),
            false,
        )
        .resample(2.0)
    }

    /// The curve of `curves` that is the "K"'s whole stem, straight down x = 0 from y = 0 to 60.
    fn whole_stem(curves: &[Polyline]) -> &Polyline {
        let stem = curves
            .iter()
            .find(|c| c.points.iter().all(|p| p.x.abs() < 1.0))
            .expect("a straight stem");
        assert!(stem.points.iter().any(|p| p.y < 1.0) && stem.points.iter().any(|p| p.y > 59.0));
        stem
    }

    #[test]
    fn a_k_whose_curves_turned_at_the_junction_gets_its_stem_back() {
        // The stem from (0, 0) down to (0, 60); the arm from (30, 0) and the leg to (30, 60),
        // meeting the stem at (0, 30). The crawl paired the upper stem with the leg and the arm
        // with the lower stem.
        let mut curves = vec![
            line(&[(0.0, 0.0), (0.0, 30.0), (30.0, 60.0)]),
            line(&[(30.0, 0.0), (0.5, 30.5), (0.0, 60.0)]),
        ];
        pair_arms_straightest_first(&mut curves, 3.0);
        let stem = whole_stem(&curves);
        let corner = curves.iter().find(|c| !std::ptr::eq(*c, stem)).unwrap();
        let ends = [corner.points[0], corner.points[corner.points.len() - 1]];
        assert!(ends.iter().all(|p| p.x > 29.0), "{ends:?}");
    }

    #[test]
    fn an_arm_whose_last_stretch_is_one_long_bridge_still_has_a_direction() {
        // The "K" again, the upper stem's last 18 px into the junction one bridge: both of the
        // arm's measuring points (7.5 and 15 px back) lie on it.
        let mut upper_stem_then_leg: Vec<Point> =
            (0..=6).map(|k| Point::new(0.0, 2.0 * k as f64)).collect();
        upper_stem_then_leg.extend(line(&[(0.0, 30.0), (30.0, 60.0)]).points);
        let mut curves = vec![
            Polyline::new(upper_stem_then_leg, false),
            line(&[(30.0, 0.0), (0.5, 30.5), (0.0, 60.0)]),
        ];
        pair_arms_straightest_first(&mut curves, 3.0);
        whole_stem(&curves);
    }

    #[test]
    fn two_corners_touching_with_no_straight_way_through_stay_as_they_are() {
        // An "L" whose corner touches a "<"'s: no two of the four arms go on straight.
        let mut curves = vec![
            line(&[(0.0, 0.0), (0.0, 30.0), (30.0, 30.0)]),
            line(&[(30.0, 0.0), (0.5, 30.5), (30.0, 60.0)]),
        ];
        let before = curves.clone();
        pair_arms_straightest_first(&mut curves, 3.0);
        assert_eq!(curves, before);
    }

    #[test]
    fn a_straight_way_through_whose_other_arms_make_no_corner_is_left_alone() {
        // Two lines crossing at a shared point, each turning there: one line straight through
        // would leave the other two arms turning by only 34°, no corner (two lines side by side
        // that a bridge took across and back).
        let mut curves = vec![
            line(&[(0.0, 0.0), (30.0, 30.0), (60.0, 30.0)]),
            line(&[(0.0, 50.0), (30.5, 30.0), (60.0, 60.0)]),
        ];
        let before = curves.clone();
        pair_arms_straightest_first(&mut curves, 3.0);
        assert_eq!(curves, before);
    }

    #[test]
    fn an_end_at_a_corner_whose_arm_comes_back_to_a_free_end_goes_on_to_that_end() {
        // A lasso: its upper rope comes down to the neck at (40, 0), the neck runs on to the
        // loop and the loop comes back along the neck, the two strands coincident, to end at
        // (50, 1); the lower rope's pen lift fell where it meets the neck, its end pointing at
        // the corner. It goes on to the loop's end, along the neck: one curve, the corner kept.
        let mut curves = vec![
            line(&[
                (20.0, -40.0),
                (40.0, 0.0),
                (80.0, 0.0),
                (95.0, -15.0),
                (110.0, 0.0),
                (95.0, 15.0),
                (80.0, 1.0),
                (50.0, 1.0),
            ]),
            line(&[(0.0, 20.0), (15.0, 4.0), (30.0, 1.0)]),
        ];
        go_on_through_corners(&mut curves, 6.0, 3.0);
        assert_eq!(curves.len(), 1, "{curves:?}");
        let points = &curves[0].points;
        let (first, last) = (points[0], points[points.len() - 1]);
        assert!(
            first.distance(Point::new(0.0, 20.0)) < 1e-9
                && last.distance(Point::new(20.0, -40.0)) < 1e-9,
            "{first:?} {last:?}"
        );
    }

    #[test]
    fn a_leg_broken_where_the_bar_meets_it_goes_on_through_the_bar_s_corner() {
        // An "A"'s left leg from (0, 100) up to the apex (30, 0), broken 10 px below the bar,
        // which meets it at (15, 50): the crawl turned the upper leg into the bar, and left the
        // lower leg on its own, its end pointing up the leg at the corner.
        let leg = |t: f64| (30.0 * (1.0 - t), 100.0 * t);
        // A third line ends beside the upper leg, after the leg's curve has changed.
        let mut curves = vec![
            line(&[leg(0.0), leg(0.5), (45.0, 50.0)]),
            line(&[leg(1.0), leg(0.6)]),
            line(&[(60.0, 30.0), (24.0, 30.0)]),
        ];
        go_on_through_corners(&mut curves, 6.0, 3.0);
        assert_eq!(curves[2], line(&[(60.0, 30.0), (24.0, 30.0)]));
        let whole_leg = curves
            .iter()
            .find(|c| c.points.iter().any(|p| p.y < 1.0) && c.points.iter().any(|p| p.y > 99.0))
            .expect("the leg in one curve");
        assert!(
            whole_leg.points.iter().all(|p| p.x < 31.0),
            "{:?}",
            whole_leg.points
        );
        let bar = &curves[0];
        assert!(
            bar.points.iter().all(|p| (p.y - 50.0).abs() < 1e-9),
            "{:?}",
            bar.points
        );
    }

    #[test]
    fn an_end_pointing_at_a_corner_across_its_arms_stays_where_it_is() {
        // An "L" whose corner (0, 50) a line from (-30, 80) points at, at 45° to both arms.
        let mut curves = vec![
            line(&[(0.0, 0.0), (0.0, 50.0), (50.0, 50.0)]),
            line(&[(-30.0, 80.0), (-8.0, 58.0)]),
        ];
        let before = curves.clone();
        go_on_through_corners(&mut curves, 6.0, 3.0);
        assert_eq!(curves, before);
    }
}
