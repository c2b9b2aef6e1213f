//! A lasso's second rope that ends on the first where the two part is threaded up the neck and
//! round the loop (issue 9, touching parts). A lasso's two lines run merged into one line of ink
//! along its neck and part below it; where the crawl reads the neck once, it goes up it and round
//! the loop with one rope and ends free where the loop comes back to the neck, and the other
//! rope ends on the first rope's line where the two part. Ours, on top of the stroke crawl; the
//! paper (Parakkat & Muthuganapathy 2016) has no ink width and no necks.

use kurbo::{Line, Point, Vec2};

use super::remove_marked;
use super::spikes::SegmentGrid;
use crate::geometry::polyline::{distance_to_segment, distances_along, Polyline};

/// The rope's end lies within this much (pen widths) of the other curve's line: the merged neck's
/// centre line lies half a pen width or so off each line's centre, and where the rope's pen
/// lifted just where the two lines part its end stops up to an ordinary pen lift short of the
/// neck (measured: 2.9 pen widths on a scanned lasso; 1 and 2 gain two lassos, 3 to 4.5 three).
const END_ON_NECK_IN_PEN_WIDTHS: f64 = 3.0;

/// The loop's free end lies within this much (pen widths) of its own curve's line where that
/// comes back to the neck: the loop's last stretch before the neck, beside its first.
const LOOP_END_REACH_IN_PEN_WIDTHS: f64 = 2.5;

/// The loop, from its free end round to where it comes back beside it, is at least this long
/// (pen widths): shorter, the curve turns back at a hairpin, not round a loop.
const MIN_LOOP_IN_PEN_WIDTHS: f64 = 8.0;

/// The neck, from where the loop comes back to where the rope ends on it, is at least this long
/// (pen widths): shorter, the rope ends where the loop closes, which the loop stages join.
const MIN_NECK_IN_PEN_WIDTHS: f64 = 2.0;

/// The rope's end points up the neck within this angle: the two lines part at 30°–60° below
/// the neck, and the rope's end is read before it turns into the neck.
const ROPE_ALONG_NECK_MAX_DEGREES: f64 = 60.0;

/// The rope's end direction is read over this much of it (pen widths).
const ROPE_DIRECTION_IN_PEN_WIDTHS: f64 = 2.0;

/// DECISION: (stop 62) an open curve (the second rope) whose free end lies on another open
/// curve's line ([`END_ON_NECK_IN_PEN_WIDTHS`]), away from its ends, pointing back along it
/// ([`ROPE_ALONG_NECK_MAX_DEGREES`]) towards where that curve's own free end lies beside its
/// line ([`LOOP_END_REACH_IN_PEN_WIDTHS`], after a loop of at least
/// [`MIN_LOOP_IN_PEN_WIDTHS`] and a neck of at least [`MIN_NECK_IN_PEN_WIDTHS`]) is the lasso's
/// second line merged into the neck: it goes on up the neck (retracing the other curve's line
/// from its end to where the loop comes back), and on from the loop's free end round the loop,
/// down the neck and along the first rope. The last stage: the joining stages before it read
/// the rope's end as a string ending on its balloon's line. Measured on the benchmark (exact):
/// seed 11 1560 → 1563 (`meanders-thick-000`, `-thick-020`, `-scan-007`: lassos and a looped
/// hairpin split at the neck), seeds 1, 3, 5–8 unchanged (no output changes), nothing lost;
/// validation seed 12 +2, seeds 2 and 4 unchanged; no worst distance grows. The end on the line
/// within 1–2 pen widths gains two, 3–4.5 three; the loop's end within 1.5 pen widths of its
/// line gains one (a thick neck's loop end lies two pen widths off), 2.5 three; the rope's end
/// along the neck within 45° or 60° the same.
pub fn thread_ropes_up_merged_necks(curves: &mut Vec<Polyline>, stroke_width: f64) {
    if stroke_width <= 0.0 {
        return;
    }
    let reach = END_ON_NECK_IN_PEN_WIDTHS * stroke_width;
    // One pass, a curve in one join at most, looking only at the curves whose line passes near a
    // rope's end. Passes repeated until none joins measured the same on the benchmark and on a
    // page of noise chained rope after rope onto ever longer curves (four seconds).
    let grid = SegmentGrid::new(curves, reach);
    let mut used = vec![false; curves.len()];
    let mut joins = Vec::new();
    for rope in 0..curves.len() {
        let points = &curves[rope].points;
        if curves[rope].closed || points.len() < 2 {
            continue;
        }
        'ends: for rope_at_last in [true, false] {
            let Some((end, rope_way)) = rope_end_way(points, rope_at_last, stroke_width) else {
                continue;
            };
            let mut others: Vec<usize> = grid
                .around(end)
                .map(|&(i, _)| i)
                .filter(|&i| i != rope && !curves[i].closed && curves[i].points.len() >= 3)
                .collect();
            others.sort_unstable();
            others.dedup();
            for other in others {
                if used[rope] || used[other] {
                    continue;
                }
                if let Some(tail) = rope_up_neck(curves, (end, rope_way), other, stroke_width) {
                    used[rope] = true;
                    used[other] = true;
                    joins.push((rope, rope_at_last, other, tail));
                    break 'ends;
                }
            }
        }
    }
    let mut dropped = vec![false; curves.len()];
    for (rope, rope_at_last, other, tail) in joins {
        let points = &mut curves[rope].points;
        if !rope_at_last {
            points.reverse();
        }
        points.extend(tail);
        dropped[other] = true;
    }
    remove_marked(curves, &dropped);
}

/// The end of the open curve `points` (its last point, or its first) and the way it points out
/// of it, read over [`ROPE_DIRECTION_IN_PEN_WIDTHS`]; none where the curve is shorter.
fn rope_end_way(points: &[Point], at_last: bool, stroke_width: f64) -> Option<(Point, Vec2)> {
    let mut rope_points = points.to_vec();
    if !at_last {
        rope_points.reverse();
    }
    let end = *rope_points.last()?;
    let rope_lengths = distances_along(&rope_points);
    let rope_total = *rope_lengths.last()?;
    let reach_back = ROPE_DIRECTION_IN_PEN_WIDTHS * stroke_width;
    if rope_total < reach_back {
        return None;
    }
    let back = rope_points
        .iter()
        .zip(&rope_lengths)
        .rev()
        .find(|(_, &l)| rope_total - l >= reach_back)
        .map(|(p, _)| *p)?;
    let rope_way = end - back;
    (rope_way.hypot() > f64::EPSILON).then_some((end, rope_way))
}

/// Where the rope's end (`end`, pointing out along `rope_way`) ends on curve `other`'s merged
/// neck: the points the rope goes on through (up the neck, then from the loop's free end along
/// the whole other curve).
fn rope_up_neck(
    curves: &[Polyline],
    (end, rope_way): (Point, Vec2),
    other: usize,
    stroke_width: f64,
) -> Option<Vec<Point>> {
    let reach_back = ROPE_DIRECTION_IN_PEN_WIDTHS * stroke_width;
    for loop_at_first in [true, false] {
        let mut points = curves[other].points.clone();
        if !loop_at_first {
            points.reverse();
        }
        let lengths = distances_along(&points);
        let total = *lengths.last()?;
        // The rope's end on the other curve's line: the nearest segment.
        let (s, distance) = (0..points.len() - 1)
            .map(|s| {
                (
                    s,
                    distance_to_segment(end, Line::new(points[s], points[s + 1])),
                )
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        if distance > END_ON_NECK_IN_PEN_WIDTHS * stroke_width {
            return None;
        }
        let at = lengths[s];
        if at < MIN_LOOP_IN_PEN_WIDTHS * stroke_width || total - lengths[s + 1] < stroke_width {
            continue;
        }
        // Where the loop comes back beside its free end: the nearest point at least a loop's
        // length along, before the rope's end.
        let free = points[0];
        let Some((k, back_distance)) = (0..=s)
            .filter(|&k| lengths[k] >= MIN_LOOP_IN_PEN_WIDTHS * stroke_width)
            .map(|k| (k, free.distance(points[k])))
            .min_by(|a, b| a.1.total_cmp(&b.1))
        else {
            continue;
        };
        if back_distance > LOOP_END_REACH_IN_PEN_WIDTHS * stroke_width
            || at - lengths[k] < MIN_NECK_IN_PEN_WIDTHS * stroke_width
        {
            continue;
        }
        // The rope's end points up the neck.
        let neck_from = points[s];
        let target = reach_back.min(at - lengths[k]);
        let up = (k..=s)
            .rev()
            .find(|&m| at - lengths[m] >= target)
            .map(|m| points[m])?;
        let neck_way: Vec2 = up - neck_from;
        if neck_way.hypot() <= f64::EPSILON {
            continue;
        }
        let cos = rope_way.dot(neck_way) / (rope_way.hypot() * neck_way.hypot());
        if cos < ROPE_ALONG_NECK_MAX_DEGREES.to_radians().cos() {
            continue;
        }
        let mut tail: Vec<Point> = (k..=s).rev().map(|m| points[m]).collect();
        tail.extend(points.iter().copied());
        return Some(tail);
    }
    None
}
