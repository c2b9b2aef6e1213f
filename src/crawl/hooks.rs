//! An open curve's end that hooks along the line of another curve it ends on is cut back to
//! where its own line meets that line (a balloon's string whose top ran on along the loop), and
//! one that hooks across to a line running beside it is cut back to where it leaves its own line
//! (two thin lines whose round caps touch where they end together).
//! Ours, on top of the stroke crawl; the paper (Parakkat & Muthuganapathy 2016) has no junctions.

use kurbo::{Point, Vec2};

use super::spikes::{segment, SegmentGrid};
use crate::geometry::polyline::{distance_to_segment, Polyline};

/// An end lies on another curve's line within this much (pen widths): where the other line's
/// stroke ended just beyond the junction, its line is the bridge across its pen lift, which cuts
/// the stub's tip by a pixel or two.
const END_ON_LINE_IN_PEN_WIDTHS: f64 = 1.0;

/// The hook runs along the other line within this much (pen widths): the skeleton's branch
/// along a line is that line's centre, a pixel or so off.
const ON_LINE_IN_PEN_WIDTHS: f64 = 0.75;

/// The hook along the other line is at least this long (pen widths): shorter, it is where a line
/// ending on another meets its ink.
const MIN_HOOK_IN_PEN_WIDTHS: f64 = 1.0;

/// The hook is at most this long (pen widths): longer, the curve runs along the other line (a
/// band's side, two lines side by side).
const MAX_HOOK_IN_PEN_WIDTHS: f64 = 4.0;

/// The curve's own line is measured from this much (pen widths) past the hook, beyond the
/// junction's rounding ...
const OWN_LINE_FROM_IN_PEN_WIDTHS: f64 = 1.0;

/// ... over this much (pen widths).
const OWN_LINE_IN_PEN_WIDTHS: f64 = 3.0;

/// The curve's own line meets the other line at this angle (degrees) or more: a line ending on
/// another, not one running into it at a grazing angle.
const MIN_MEETING_DEGREES: f64 = 30.0;

/// The meeting point lies at most this far (pen widths) ahead of where the hook leaves the line.
const MEET_REACH_IN_PEN_WIDTHS: f64 = 2.0;

/// Step (pixels) at which a curve is walked along the other line.
const WALK_STEP_PX: f64 = 0.5;

/// [`trim_hooked_ends`], then [`unhook_ends_beside_lines`], as the trace runs them. The second
/// reads the first's grid of segments again where the first cut no end back (the curves then
/// the same), instead of building the same grid anew: about 6 M instructions on a 12-megapixel
/// page (docs/performance.md, stop 70).
pub fn trim_and_unhook_ends(curves: &mut [Polyline], stroke_width: f64) {
    let grid = trim_hooked_ends(curves, stroke_width, None);
    unhook_ends_beside_lines(curves, stroke_width, grid);
}

/// DECISION: (stop 62) an open curve whose end lies on another curve's line
/// ([`END_ON_LINE_IN_PEN_WIDTHS`]) and whose last stretch runs along that line for
/// [`MIN_HOOK_IN_PEN_WIDTHS`] to [`MAX_HOOK_IN_PEN_WIDTHS`] (within [`ON_LINE_IN_PEN_WIDTHS`])
/// before leaving it at
/// [`MIN_MEETING_DEGREES`] or more is a line ending on the other whose end hooked along it: the
/// skeleton of a junction where the other line's stroke ends just beyond it (a balloon's loop
/// whose pen lift fell beside the string) runs on from the meeting line along that stroke's stub
/// to its tip. The hook is dropped, and the curve ends where its own line
/// (from [`OWN_LINE_FROM_IN_PEN_WIDTHS`] past the hook, over [`OWN_LINE_IN_PEN_WIDTHS`]) meets the
/// other line within [`MEET_REACH_IN_PEN_WIDTHS`]. After every join but the lasso's rope
/// ([`super::necks`]): a hook is judged on the curves as they are output. Measured on the benchmark (exact): seed 11
/// 1544 → 1550 of 1728 (six balloons' strings, objects clean, scan and thin), seeds 5 and 8 +1
/// each (a balloon each), seeds 1, 3, 6, 7 unchanged, nothing lost on any split; validation seed
/// 2 unchanged and seed 12 +3, held-out seed 4 +4; no exact drawing's worst distance grew. The
/// hook measured within 0.6 pen widths of the other line (with the end within 0.75, hooks of at
/// most 3.5 pen widths and a meeting at 40° or more): seed 11 +5, the rest the same; within a
/// whole pen width the walk runs on past the junction down the string: seed 11 +3, seed 8's
/// gain lost, still nothing lost. Placing the string's end at the hairpin corner's cut arm in
/// the bridges instead (where its line crosses the line going through) gained four on seed 11
/// but lost a thin dumbbell's neck and a meander's parting legs, whose hairpins look the same
/// there and are joined by later stages.
///
/// `grid` and the result as [`cut_back_hooked_ends`]'s.
fn trim_hooked_ends(
    curves: &mut [Polyline],
    stroke_width: f64,
    grid: Option<SegmentGrid>,
) -> Option<SegmentGrid> {
    cut_back_hooked_ends(
        curves,
        stroke_width,
        grid,
        |points, curves, _own, other, grid| hook(points, curves, other, grid, stroke_width),
    )
}

/// The driver both hook stages share: every end of an open curve that lies on another curve's
/// line ([`END_ON_LINE_IN_PEN_WIDTHS`]) is read by `find` from a copy of its curve starting at
/// that end (with the curve's index and the nearest other curve's), and the ends it finds
/// hooked are cut back only after all were read, so that no cut changes what another end reads.
///
/// `grid` is the curves' grid of segments within [`END_ON_LINE_IN_PEN_WIDTHS`] if the caller has
/// it (built here if not); it is handed back when no end was cut, the curves left as they were.
fn cut_back_hooked_ends(
    curves: &mut [Polyline],
    stroke_width: f64,
    grid: Option<SegmentGrid>,
    find: impl Fn(&[Point], &[Polyline], usize, usize, &SegmentGrid) -> Option<(usize, Point)>,
) -> Option<SegmentGrid> {
    if stroke_width <= 0.0 || curves.len() < 2 {
        return None;
    }
    let on = END_ON_LINE_IN_PEN_WIDTHS * stroke_width;
    let grid = grid.unwrap_or_else(|| SegmentGrid::new(curves, on));
    let mut trims: Vec<(usize, bool, usize, Point)> = Vec::new();
    for (i, curve) in curves.iter().enumerate() {
        if curve.closed || curve.points.len() < 2 {
            continue;
        }
        for from_last in [false, true] {
            let end = if from_last {
                curve.points[curve.points.len() - 1]
            } else {
                curve.points[0]
            };
            let Some(other) = other_curve_under(&grid, curves, end, i, on) else {
                continue;
            };
            let mut points = curve.points.clone();
            if from_last {
                points.reverse();
            }
            if let Some((keep_from, new_end)) = find(&points, curves, i, other, &grid) {
                trims.push((i, from_last, keep_from, new_end));
            }
        }
    }
    if trims.is_empty() {
        return Some(grid);
    }
    for (i, from_last, keep_from, new_end) in trims {
        cut_end_back(&mut curves[i], from_last, keep_from, new_end);
    }
    None
}

/// Cuts the end of `curve` (its last point's end where `from_last`) back to `new_end`: the points
/// before `keep_from`, counted from that end, are dropped and `new_end` put in their place.
fn cut_end_back(curve: &mut Polyline, from_last: bool, keep_from: usize, new_end: Point) {
    if curve.points.len() < 2 {
        return;
    }
    let mut points = curve.points.clone();
    if from_last {
        points.reverse();
    }
    if keep_from >= points.len() {
        return;
    }
    let mut trimmed = vec![new_end];
    trimmed.extend_from_slice(&points[keep_from..]);
    trimmed.dedup();
    if trimmed.len() < 2 {
        return;
    }
    if from_last {
        trimmed.reverse();
    }
    curve.points = trimmed;
}

/// The other curve whose line passes within `reach` of `point`, nearest first.
fn other_curve_under(
    grid: &SegmentGrid,
    curves: &[Polyline],
    point: Point,
    own: usize,
    reach: f64,
) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for &(i, s) in grid.around(point) {
        if i == own {
            continue;
        }
        let d = distance_to_segment(point, segment(curves, i, s));
        if d <= reach && best.is_none_or(|(bd, bi)| d < bd || (d == bd && i < bi)) {
            best = Some((d, i));
        }
    }
    best.map(|(_, i)| i)
}

/// The distance from `p` to the line of curve `other`, where that is within the grid's reach
/// (infinite beyond it).
fn distance_to_curve(p: Point, curves: &[Polyline], other: usize, grid: &SegmentGrid) -> f64 {
    grid.around(p)
        .filter(|&&(i, _)| i == other)
        .map(|&(i, s)| distance_to_segment(p, segment(curves, i, s)))
        .fold(f64::INFINITY, f64::min)
}

/// The point `length` along `points` from its first, and the index of the first point past it;
/// none where the polyline is shorter.
fn along(points: &[Point], length: f64) -> Option<(Point, usize)> {
    let mut walked = 0.0;
    for (k, pair) in points.windows(2).enumerate() {
        let step = pair[0].distance(pair[1]);
        if walked + step >= length && step > 0.0 {
            return Some((pair[0].lerp(pair[1], (length - walked) / step), k + 1));
        }
        walked += step;
    }
    None
}

/// For the curve `points` starting at an end on `other`'s line: the index from which its points
/// are kept and the point where it then ends, where its first stretch hooks along that line
/// ([`trim_hooked_ends`]).
fn hook(
    points: &[Point],
    curves: &[Polyline],
    other: usize,
    grid: &SegmentGrid,
    stroke_width: f64,
) -> Option<(usize, Point)> {
    let on = ON_LINE_IN_PEN_WIDTHS * stroke_width;
    let max_hook = MAX_HOOK_IN_PEN_WIDTHS * stroke_width;
    // Walk along the curve while it stays on the other line.
    let mut hook = 0.0;
    loop {
        let next = hook + WALK_STEP_PX;
        let (p, _) = along(points, next)?;
        if distance_to_curve(p, curves, other, grid) > on {
            break;
        }
        hook = next;
        if hook > max_hook {
            return None;
        }
    }
    if hook < MIN_HOOK_IN_PEN_WIDTHS * stroke_width {
        return None;
    }
    let (_, keep_from) = along(points, hook)?;
    let from = hook + OWN_LINE_FROM_IN_PEN_WIDTHS * stroke_width;
    let (leaves, _) = along(points, from)?;
    let (back, _) = along(points, from + OWN_LINE_IN_PEN_WIDTHS * stroke_width)?;
    let way = leaves - back;
    if way.hypot() == 0.0 {
        return None;
    }
    let way: Vec2 = way / way.hypot();
    let min_sine = MIN_MEETING_DEGREES.to_radians().sin();
    let reach = MEET_REACH_IN_PEN_WIDTHS * stroke_width;
    let other = &curves[other];
    let n = other.points.len();
    let count = if other.closed { n } else { n.saturating_sub(1) };
    let mut best: Option<(f64, Point)> = None;
    for s in 0..count {
        let (a, b) = (other.points[s], other.points[(s + 1) % n]);
        let chord = b - a;
        let length = chord.hypot();
        let denominator = way.cross(chord);
        if length == 0.0 || denominator.abs() < min_sine * length {
            continue;
        }
        // leaves + way·t = a + chord·u
        let d = a - leaves;
        let t = d.cross(chord) / denominator;
        let u = d.cross(way) / denominator;
        if (0.0..=1.0).contains(&u) && t.abs() <= reach && best.is_none_or(|(bt, _)| t.abs() < bt) {
            best = Some((t.abs(), leaves + way * t));
        }
    }
    best.map(|(_, meet)| (keep_from, meet))
}

/// An end hooks across to the line beside it where it lies more than this far (pen widths) off
/// its own line; within it, a point is on its own line (and the stretch its own line is measured
/// over keeps within it, else the line is not straight enough to tell a hook by).
// DECISION: (stop 64) 0.75. The line beside is 1.5–2 pen widths away, so a hook to it is at least
// that far off; a thin pen's skeleton wobbles by half a pen width along a straight line, which
// at 0.5 kept the own-line stretch of `parallel-thin-022` (seed 11) from reading as straight.
// Parallel family on the development seeds: 0.4–0.6 +3, 0.7–1.0 +4 (seed 11 `parallel-thin-002`,
// `-005`, `-022`, seed 5 `parallel-scan-003`), none lost; the whole benchmark at 0.5, 0.75 and
// 1.0 in the rule's comment below.
const BESIDE_HOOK_MIN_OFF_IN_PEN_WIDTHS: f64 = 0.75;

/// The hook across is at most this long (pen widths along the curve from its end): two lines
/// 1.5–2 pen widths apart, one curled over their touching caps to the other's end (2–3 the same
/// on the parallel family, 4 loses `parallel-thin-002`, whose own-line stretch then reaches
/// into the turn).
const BESIDE_HOOK_MAX_IN_PEN_WIDTHS: f64 = 3.0;

/// The curve's own line is measured over this much (pen widths) behind the hook.
const BESIDE_OWN_LINE_IN_PEN_WIDTHS: f64 = 6.0;

/// The line beside runs within this angle (degrees) of the curve's own line (15–35 the same on
/// the parallel family).
const BESIDE_MAX_DEGREES: f64 = 25.0;

/// DECISION: (stop 64) an open curve whose end lies on another curve's line
/// ([`END_ON_LINE_IN_PEN_WIDTHS`]; 0.75–1.25 the same) running beside and along its own (within
/// [`BESIDE_MAX_DEGREES`]), the end more than [`BESIDE_HOOK_MIN_OFF_IN_PEN_WIDTHS`] off its own
/// line (measured straight over [`BESIDE_OWN_LINE_IN_PEN_WIDTHS`] behind the last
/// [`BESIDE_HOOK_MAX_IN_PEN_WIDTHS`]), is hooked across to the line beside: two thin lines
/// 1.5–2 pen widths apart touch at their round caps where they end together, the skeleton of
/// the touching ends is one U, and whichever line keeps the U's bottom curls over to the other's
/// end (seed 11 `parallel-thin-005`, 3.6–5.1 px off). The hook is dropped and the curve ends on
/// its own line where the hook leaves it: not abreast of the other line's end, which lies
/// 2–8 px farther on where the lines' ends are staggered (ending there, `parallel-thin-005`'s
/// line ran 3.7 px past its ink). After [`trim_hooked_ends`], on the curves as they are output.
/// Measured on the benchmark (exact): seed 11 1573 → 1576 (`parallel-thin-002`, `-005`, `-022`),
/// seed 5 +1 (`parallel-scan-003`), seeds 1, 3, 6, 7, 8 unchanged, nothing lost on development;
/// validation seed 2 +1, seed 12 +4; held-out seed 4 −1 (not looked at). At 0.5 pen widths off:
/// development +3 (not `-022`), validation +1 and +3, seed 4 unchanged.
///
/// `grid` as [`cut_back_hooked_ends`]'s.
fn unhook_ends_beside_lines(curves: &mut [Polyline], stroke_width: f64, grid: Option<SegmentGrid>) {
    let on = END_ON_LINE_IN_PEN_WIDTHS * stroke_width;
    cut_back_hooked_ends(
        curves,
        stroke_width,
        grid,
        |points, curves, own, _other, grid| {
            hook_across(points, curves, own, grid, on, stroke_width)
        },
    );
}

/// For the curve `points` from one end: the index from which its points are kept and its new
/// end, where that end hooks across to a line beside ([`unhook_ends_beside_lines`]).
fn hook_across(
    points: &[Point],
    curves: &[Polyline],
    own: usize,
    grid: &SegmentGrid,
    on: f64,
    stroke_width: f64,
) -> Option<(usize, Point)> {
    let end = points[0];
    let min_off = BESIDE_HOOK_MIN_OFF_IN_PEN_WIDTHS * stroke_width;
    let hook_length = BESIDE_HOOK_MAX_IN_PEN_WIDTHS * stroke_width;
    let (a, a_index) = along(points, hook_length)?;
    let (b, b_index) = along(
        points,
        hook_length + BESIDE_OWN_LINE_IN_PEN_WIDTHS * stroke_width,
    )?;
    let way = a - b;
    if way.hypot() == 0.0 {
        return None;
    }
    let way: Vec2 = way / way.hypot();
    let normal = Vec2::new(-way.y, way.x);
    let off = |p: Point| (p - a).dot(normal).abs();
    if off(end) <= min_off || points[a_index..b_index].iter().any(|&p| off(p) > min_off) {
        return None;
    }
    let min_cos = BESIDE_MAX_DEGREES.to_radians().cos();
    let beside = grid.around(end).any(|&(j, s)| {
        if j == own {
            return false;
        }
        let line = segment(curves, j, s);
        let chord = line.p1 - line.p0;
        let length = chord.hypot();
        length > 0.0
            && distance_to_segment(end, line) <= on
            && (chord.dot(way) / length).abs() >= min_cos
    });
    if !beside {
        return None;
    }
    let mut keep_from = a_index;
    while keep_from > 0 && off(points[keep_from - 1]) <= min_off {
        keep_from -= 1;
    }
    if keep_from == 0 {
        return None;
    }
    // The curve ends where the hook leaves its own line, put on that line.
    let (on_line, off_line) = (points[keep_from], points[keep_from - 1]);
    let (near, far) = (off(on_line), off(off_line));
    let t = ((min_off - near) / (far - near).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
    let leaves = on_line.lerp(off_line, t);
    let ahead = |p: Point| (p - a).dot(way);
    Some((keep_from, a + way * ahead(leaves)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight line along y = `y` from x = `from` to 150, sampled every 3 px.
    fn line(y: f64, from: f64) -> Vec<Point> {
        let mut points: Vec<Point> = (0..=((150.0 - from) / 3.0) as usize)
            .map(|k| Point::new(from + k as f64 * 3.0, y))
            .collect();
        points.push(Point::new(150.0, y));
        points.dedup();
        points
    }

    /// A line along y = 0 from x = 0 whose skeleton curls down from (1.5, 1) to (-2, 3.5): an
    /// end hooked over the touching caps of a line beside it.
    fn hooked_line() -> Vec<Point> {
        let mut hooked = vec![
            Point::new(-2.0, 3.5),
            Point::new(0.0, 2.5),
            Point::new(1.5, 1.0),
        ];
        hooked.extend(line(0.0, 3.0));
        hooked
    }

    #[test]
    fn an_end_curled_over_touching_caps_to_the_line_beside_ends_on_its_own_line() {
        let pen = 2.0;
        // The upper line's ink ends at x = 3; its skeleton curls down over the touching caps to
        // the lower line's end, 3.5 px below and staggered 5 px farther on.
        let upper = hooked_line();
        let lower = line(3.5, -2.0);
        let mut curves = vec![
            Polyline::new(upper, false),
            Polyline::new(lower.clone(), false),
        ];
        unhook_ends_beside_lines(&mut curves, pen, None);
        // It ends where it leaves its own line, kept within the hook's reach of it, short of
        // the lower line's end.
        let end = curves[0].points[0];
        assert!(
            end.y.abs() <= 0.25 && (0.0..=3.0).contains(&end.x),
            "{end:?}"
        );
        let reach = BESIDE_HOOK_MIN_OFF_IN_PEN_WIDTHS * pen;
        assert!(
            curves[0].points.iter().all(|p| p.y.abs() <= reach),
            "{:?}",
            curves[0]
        );
        // The lower line, straight to its end, is left as it was.
        assert_eq!(curves[1].points, lower);
    }

    #[test]
    fn an_end_turning_away_from_any_line_beside_is_kept() {
        let pen = 2.0;
        let turning = hooked_line();
        let far = line(12.0, -2.0);
        let mut curves = vec![
            Polyline::new(turning.clone(), false),
            Polyline::new(far, false),
        ];
        unhook_ends_beside_lines(&mut curves, pen, None);
        assert_eq!(curves[0].points, turning);
    }

    #[test]
    fn both_hook_stages_together_cut_as_each_with_its_own_grid() {
        let pen = 2.0;
        let upper = hooked_line();
        let curves = vec![
            Polyline::new(upper, false),
            Polyline::new(line(3.5, -2.0), false),
            Polyline::new(line(40.0, 10.0), false),
        ];
        let mut apart = curves.clone();
        let kept = trim_hooked_ends(&mut apart, pen, None);
        // No end hooks along a line: the first stage cuts nothing and hands its grid on.
        assert!(kept.is_some());
        assert_eq!(apart, curves);
        unhook_ends_beside_lines(&mut apart, pen, None);
        assert_ne!(apart, curves);
        let mut together = curves;
        trim_and_unhook_ends(&mut together, pen);
        assert_eq!(together, apart);
    }
}
