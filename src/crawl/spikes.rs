//! Collapsed spikes folded back into their outline: a protrusion whose two sides merged into one
//! band of ink hardly wider than the pen comes out of the crawl as an open curve hanging off a
//! closed one (its base on the outline, its tip free); where its ink is wider than one stroke, or
//! it is short beside the outline it stands on (a quarter of its size or less: a spike, an ear, a
//! toe, where a string or a stem is about as long as its shape), it is two sides of the outline,
//! and the outline goes out along it and back (issue 9, "a double strand that ends is a
//! U-turn"); so is a neck whose two sides merged between two closed outlines, out along it,
//! round the far one and back (stop 56); an open outline that ends at such a protrusion's tip,
//! its other end at the protrusion's base, comes back along it and is closed; and a free end near
//! the root of a curve's collapsed end goes on to its tip. The paper (Parakkat & Muthuganapathy 2016) has no
//! notion of ink width; these rules are ours.

use kurbo::{Line, Point, Vec2};

use std::collections::HashMap;

use super::contacts::once_round;
use super::remove_marked;
use crate::geometry::grid::PointGrid;
use crate::geometry::polyline::{
    bounding_box, distance_to_segment, distances_along, nearest_point_index, polyline_length,
    within_of_chain, Polyline,
};
use crate::raster::bitmap::Bitmap;
use crate::strokes::ink_width_across;

/// A hanging curve's base lies on a closed curve, and its tip away from every other curve,
/// within this much (pen widths): where the crawl ends a curve at a junction, its end lies on the
/// other curve's centre line, a pixel or two off.
const ON_CURVE_IN_PEN_WIDTHS: f64 = 1.0;

/// The ink next to the base is the outline's as much as the spike's: it is not measured within
/// this much (pen widths) of the base.
// DECISION: (stop 53) one and a half pen widths, from two: the outline's ink reaches half a pen
// width off its centre line and the fillet where the spike leaves it about a pen width more;
// beyond that a cross-section along the spike's normal meets the spike's ink only. At two, a
// thick pen's short spike (four or five pen widths, its sides merged) kept too few measured
// points past the clearance to be judged, and hung off its outline as an open curve. Measured on
// the benchmark's development splits (exact of 432): seeds 1 and 8 +1 each (two thick spikes),
// the others unchanged, nothing lost, the same from 1.0 to 1.75; 2.5 loses a thin animal.
const BASE_CLEARANCE_IN_PEN_WIDTHS: f64 = 1.5;

/// A hanging curve is a collapsed spike when the median width of its ink is at least this many
/// times the page's median stroke width ...
// DECISION: (stop 36) 1.2. Measured on the benchmark's five splits (output curves with one end on
// a closed curve and the other free, ink measured across them): the single lines of line art that
// hang off an outline (a balloon's string, a flower's stem, a letter's stem) measure at most 1.15
// times the page's stroke, the spikes, ears and tails of silhouettes whose two sides the skeleton
// kept as one line 1.2–2.2 (a dozen of them 0.9–1.15, left as they are).
const SPIKE_WIDTH_RATIO: f64 = 1.2;

/// ... measured at this many points at least, so that no single pixel step decides.
const MIN_MEASURED_POINTS: usize = 3;

/// A hanging curve no longer than this share of the size of the closed curve it stands on (the
/// diagonal of that curve's bounding box) is a protrusion of that outline, whatever its ink's
/// width: a spike, an ear, a toe, a tail is a small part of the silhouette it sticks out of,
/// while a line that hangs off a shape as a line of its own (a balloon's string, a flower's stem,
/// a lollipop's stick) is about as long as the shape or longer. The same share tells an open
/// curve's end piece that is a protrusion ([`close_curves_ending_at_a_protrusion_tip`]).
// DECISION: (stop 54) a quarter. The ink of a narrow spike whose sides merged is often no wider
// than one stroke (apex under 10°, base a pen width or less: measured median widths 0.9–1.19
// times the page's stroke on the development splits, where the width rule wants 1.2), and then
// only its length tells it from a string. Measured on the benchmark's development splits,
// hanging curves: the spikes, ears and legs left hanging were 0.08–0.20 of their outline's
// diagonal, every string and stem of line art 0.59–0.75. Exact of 432 with the hanging rule
// alone: seeds 1, 5, 6, 7, 8 +1, +5, +4, +2, +3 (eleven spikes, an animal, a dumbbell's ball,
// an object's short stroke), seed 3 unchanged, none lost; the same from 0.2 to 0.5. Validation
// unchanged; seed 4 +2 −1 (a face). A width floor for the short ones (0.9 or 1.0 of a stroke)
// loses an animal and a spike and keeps the face's loss. For an open curve's end piece
// (closed, then its hanging spikes folded again): seeds 5, 6, 8 +1 each (two spikes, an animal),
// validation +1, seed 4 +2, none lost, the same from 0.2 to 0.3; a third closes two thick
// letters whose stroke runs on past the bowl it ended on (a "P" drawn from the top of its
// stem). Drawn twice, a short line of line art taken for a protrusion looks the same.
const PROTRUSION_MAX_SHARE_OF_OUTLINE: f64 = 0.25;

/// Folds every collapsed spike of `curves` into the closed curve its base stands on: the
/// outline runs from the base out to the tip and back ([`SPIKE_WIDTH_RATIO`]).
pub fn fold_collapsed_spikes(curves: &mut Vec<Polyline>, mask: &Bitmap, stroke_width: f64) {
    if stroke_width <= 0.0 || !curves.iter().any(|c| c.closed) {
        return;
    }
    let reach = ON_CURVE_IN_PEN_WIDTHS * stroke_width;
    let segments = SegmentGrid::new(curves, reach);
    let mut hanging: Vec<(usize, usize, bool)> = Vec::new();
    for (i, curve) in curves.iter().enumerate() {
        if curve.closed || curve.points.len() < 2 {
            continue;
        }
        let ends = [curve.points[0], curve.points[curve.points.len() - 1]];
        let near: Vec<Option<usize>> = ends
            .iter()
            .map(|&end| segments.nearest_other_curve(curves, end, i, reach))
            .collect();
        match (near[0], near[1]) {
            (Some(c), None) if curves[c].closed => hanging.push((i, c, true)),
            (None, Some(c)) if curves[c].closed => hanging.push((i, c, false)),
            _ => {}
        }
    }
    if hanging.is_empty() {
        return;
    }
    // Which hanging curves are short beside their outline, judged before any is folded in; the
    // page's stroke (measured along every curve: a page of noise has a million points) only
    // where another one must be judged by its ink.
    let short: Vec<bool> = hanging
        .iter()
        .map(|&(i, c, _)| {
            polyline_length(&curves[i].points, false)
                <= PROTRUSION_MAX_SHARE_OF_OUTLINE * diagonal(&curves[c].points)
        })
        .collect();
    let typical = if short.iter().all(|&s| s) {
        None
    } else {
        median_width(curves.iter(), mask, stroke_width).filter(|&w| w > 0.0)
    };
    let mut folded = vec![false; curves.len()];
    for ((i, c, base_first), short) in hanging.into_iter().zip(short) {
        let mut spike = curves[i].points.clone();
        if !base_first {
            spike.reverse();
        }
        if !short && !typical.is_some_and(|t| ink_is_double(&spike, mask, stroke_width, t)) {
            continue;
        }
        let outline = &mut curves[c].points;
        let base = spike[0];
        let at = nearest_point_index(outline, base).unwrap_or(0);
        // Out along the spike to its tip and back to its base, then on along the outline.
        let mut excursion = spike.clone();
        excursion.extend(spike.iter().rev().skip(1));
        outline.splice(at + 1..at + 1, excursion);
        folded[i] = true;
    }
    remove_marked(curves, &folded);
}

/// A neck's ends lie on the two closed curves it joins within this much (pen widths): the
/// crawl ends it at the junction where its merged sides meet each part's outline, a pen width
/// or more off that outline's centre line once the free ends are lengthened past thinning.
// DECISION: (stop 56) two pen widths, the reach at which an open curve's end lies on itself
// ([`ON_ITSELF_IN_PEN_WIDTHS`]); at one ([`ON_CURVE_IN_PEN_WIDTHS`]) the thin dumbbell's neck
// that this rule is for ended 2.9 px (1.45 pen widths) off its ball's line.
const NECK_ON_CURVE_IN_PEN_WIDTHS: f64 = 2.0;

/// DECISION: (stop 56) folds every collapsed neck of `curves` into the outline it joins: an
/// open curve that runs from one closed curve to another, whose ink is two lines side by side
/// ([`neck_ink_is_double`]), is the narrow neck between two parts of one silhouette (a
/// dumbbell's bar, a waist), its two sides one line of skeleton; the crawl sealed each part on
/// itself across the neck's mouth. The outline goes out along the neck, once round the far
/// part, and back (issue 9: a double strand traced once each way along its centre). A line of
/// one stroke's ink between two shapes (a barbell drawn with one line) stays three curves. Runs
/// before the spikes are folded: a neck whose far end missed its part would be folded as a
/// spike. Measured on the benchmark (exact of 432): seed 1 +1 (a thin dumbbell whose neck's
/// sides merged into a ladder of skeleton), the other development splits, validation and seed
/// 4 unchanged. The ink is measured across paper gaps of up to a pen width
/// ([`ink_extent_across`]): a thin pen's two sides 1.25–2 pen widths apart leave a hairline of
/// paper between them in most places, where the spikes' width ([`width_at`]) measured one side,
/// 1.25–2.25 px on a 2 px pen.
pub fn fold_collapsed_necks(curves: &mut Vec<Polyline>, mask: &Bitmap, stroke_width: f64) {
    if stroke_width <= 0.0 || curves.iter().filter(|c| c.closed).count() < 2 {
        return;
    }
    let reach = NECK_ON_CURVE_IN_PEN_WIDTHS * stroke_width;
    let segments = SegmentGrid::new(curves, reach);
    let mut necks: Vec<(usize, usize, usize)> = Vec::new();
    for (i, curve) in curves.iter().enumerate() {
        if curve.closed || curve.points.len() < 2 {
            continue;
        }
        let on = |end: Point| segments.nearest_other_curve(curves, end, i, reach);
        if let (Some(a), Some(b)) = (
            on(curve.points[0]),
            on(curve.points[curve.points.len() - 1]),
        ) {
            if a != b && a != i && b != i && curves[a].closed && curves[b].closed {
                necks.push((i, a, b));
            }
        }
    }
    if necks.is_empty() {
        return;
    }
    let Some(typical) = median_width(curves.iter(), mask, stroke_width).filter(|&w| w > 0.0) else {
        return;
    };
    let mut folded = vec![false; curves.len()];
    for (i, a, b) in necks {
        if folded[i] || folded[a] || folded[b] {
            continue;
        }
        let neck = curves[i].points.clone();
        if !neck_ink_is_double(&neck, mask, stroke_width, typical) {
            continue;
        }
        let far = &curves[b].points;
        let at_far = nearest_point_index(far, neck[neck.len() - 1]).unwrap_or(0);
        let mut excursion = neck.clone();
        excursion.extend(once_round(far, at_far));
        excursion.extend(neck.iter().rev());
        let near = &mut curves[a].points;
        let at_near = nearest_point_index(near, neck[0]).unwrap_or(0);
        near.splice(at_near + 1..at_near + 1, excursion);
        folded[i] = true;
        folded[b] = true;
    }
    remove_marked(curves, &folded);
}

/// Whether the ink along a neck (`neck`, an open curve between two outlines) is two sides
/// side by side: its median width across, paper gaps of up to a pen width inside it counted
/// ([`ink_extent_across`]), away from both ends ([`BASE_CLEARANCE_IN_PEN_WIDTHS`]), at least
/// [`SPIKE_WIDTH_RATIO`] times the page's stroke (`typical`).
fn neck_ink_is_double(neck: &[Point], mask: &Bitmap, stroke_width: f64, typical: f64) -> bool {
    let clearance = BASE_CLEARANCE_IN_PEN_WIDTHS * stroke_width;
    let (first, last) = (neck[0], neck[neck.len() - 1]);
    let widths: Vec<f64> = (0..neck.len())
        .filter(|&k| neck[k].distance(first) > clearance && neck[k].distance(last) > clearance)
        .filter_map(|k| {
            let width = ink_extent_across(mask, neck[k], normal_at(neck, k)?, stroke_width);
            (width > 0.0).then_some(width)
        })
        .collect();
    wider_than_a_stroke(widths, typical)
}

/// A neck's ink is looked for this far (pen widths) to each side of its centre line: its two
/// sides lie up to two pen widths apart centre to centre, and the far side's ink reaches half a
/// pen width beyond its centre.
const NECK_INK_REACH_IN_PEN_WIDTHS: f64 = 2.5;

/// The step (pixels) at which the ink across a neck is sampled.
const NECK_INK_STEP_PX: f64 = 0.25;

/// The width of the ink across `point` along `normal`, from its farthest ink on one side to its
/// farthest on the other, within [`NECK_INK_REACH_IN_PEN_WIDTHS`], across gaps of paper up to a
/// pen width wide (two lines drawn side by side, their ink merged in places); nothing where no
/// ink lies within half a pen width of `point`.
fn ink_extent_across(mask: &Bitmap, point: Point, normal: Vec2, stroke_width: f64) -> f64 {
    const STEP_PX: f64 = NECK_INK_STEP_PX;
    let ink = |q: Point| mask.get_signed(q.x.floor() as isize, q.y.floor() as isize);
    let reach = NECK_INK_REACH_IN_PEN_WIDTHS * stroke_width;
    let mut farthest = [None, None];
    for (side, sign) in [1.0, -1.0].into_iter().enumerate() {
        let mut t = 0.0;
        while t <= reach {
            if ink(point + normal * (sign * t)) {
                farthest[side] = Some(t);
            } else if farthest[side].is_none_or(|f| t - f > stroke_width) && t > stroke_width / 2.0
            {
                break;
            }
            t += STEP_PX;
        }
    }
    match farthest {
        [Some(a), Some(b)] => a + b + STEP_PX,
        [Some(a), None] | [None, Some(a)] => a + STEP_PX,
        _ => 0.0,
    }
}

/// An open curve's end lies on the curve itself within this much (pen widths): where the crawl
/// ends a stroke at the junction a protrusion leaves from, its end lies on the protrusion's
/// base, a pixel or two off, and up to a pen width beside a collapsed protrusion's centre line.
// DECISION: (stop 54) two pen widths, the reach at which an open curve's end lies on a loop for
// a theta (stop 53), from the 1.5 at which an outline's two ends stop on one stretch of itself
// (`crate::crawl::closure`): a scanned spike's outline ended 6.6 px (1.54 pen widths) off its
// base.
// Measured on the benchmark (exact of 432) against 1.5: seed 7 +1 (that spike), the other
// development splits, validation and seed 4 unchanged; the same from 2 to 5.
const ON_ITSELF_IN_PEN_WIDTHS: f64 = 2.0;

/// Closes every open curve of `curves` that goes out along a protrusion of itself and ends at
/// its tip, its other end stopping at the protrusion's base: the outline of a silhouette whose
/// spike's two sides merged into one line, which the crawl took out to the tip, with nothing to
/// bring it back (the stroke that met the spike's base ended there, at the junction). The pen's
/// way back is the same line: the curve is closed from the tip back along the protrusion to its
/// base and on to its other end. A protrusion is no longer than
/// [`PROTRUSION_MAX_SHARE_OF_OUTLINE`] of the curve's size, as a hanging one
/// ([`fold_collapsed_spikes`]). Returns whether any curve was closed.
pub fn close_curves_ending_at_a_protrusion_tip(curves: &mut [Polyline], stroke_width: f64) -> bool {
    if stroke_width <= 0.0 {
        return false;
    }
    let mut any = false;
    let on_itself = ON_ITSELF_IN_PEN_WIDTHS * stroke_width;
    for curve in curves.iter_mut() {
        if curve.closed || curve.points.len() < 4 {
            continue;
        }
        let max_protrusion = PROTRUSION_MAX_SHARE_OF_OUTLINE * diagonal(&curve.points);
        // The tip at the curve's last point, or at its first.
        let closing = closed_back_along_protrusion(&curve.points, on_itself, max_protrusion)
            .or_else(|| {
                let reversed: Vec<Point> = curve.points.iter().rev().copied().collect();
                closed_back_along_protrusion(&reversed, on_itself, max_protrusion)
            });
        if let Some(points) = closing {
            *curve = Polyline::new(points, true);
            any = true;
        }
    }
    any
}

/// Joins two open curves where one ends at a protrusion's tip and the other's end stops on it at
/// that protrusion's base: the outline comes along the second curve to the base, goes out along
/// the protrusion to its tip and back, and on along the first curve. What
/// [`close_curves_ending_at_a_protrusion_tip`] does for one curve's two ends, for the ends of two
/// curves, with the same reach ([`ON_ITSELF_IN_PEN_WIDTHS`]) and the same largest protrusion
/// ([`PROTRUSION_MAX_SHARE_OF_OUTLINE`] of the two curves' size); the protrusion's ink must be
/// two sides merged ([`ink_is_double`]). Returns whether any curves were joined.
///
/// DECISION: (stop 70) a band whose two sides merged (a fork's tine, a thin star's narrow tip)
/// and that a pen lift cuts across is read as one side going out to the tip, and the outline's
/// other side, coming up the band from its base, ends on it where the two sides merge; the two
/// sides are two curves, each ending on the band, and the outline stays open in two pieces
/// (`samples/cat-fork-clean.png`: the second and fourth tines of the fork; seed 11
/// `stars-thin-023`: a thin star's tip). Unlike a lone open curve, the piece out to the tip is
/// not the curve's own: the join is judged on the two curves' ends. The ink check keeps lines
/// side by side apart: without it, development +2 −11 (nine parallel-lines drawings and two thick
/// letters: a line's end beside its neighbour's), validation seed 12 +3 −9. Measured on the
/// benchmark (exact): seed 11 +1 (`stars-thin-023`), the other development splits unchanged,
/// validation seed 12 +1, seed 2 and held-out seed 4 unchanged, nothing lost; the sample
/// `cat-fork-clean.png` passes. The reach the same from 1.4 to 2.6 pen widths; the share the same
/// at 0.175, at 0.325 development −5 (letters: a stroke running on past where another ends, as
/// for a lone curve at a third); the width ratio ([`SPIKE_WIDTH_RATIO`]) the same on development
/// from 1.0 (seed 7 +1 more, seed 12 +3 −1) to 1.4; at 1.56 the sample's tines are too narrow.
pub fn join_curves_at_a_protrusion_tip(
    curves: &mut Vec<Polyline>,
    mask: &Bitmap,
    stroke_width: f64,
) -> bool {
    if stroke_width <= 0.0 {
        return false;
    }
    let on_itself = ON_ITSELF_IN_PEN_WIDTHS * stroke_width;
    // The page's stroke is measured (along every curve) only where the shapes call for a join.
    if protrusion_join(curves, on_itself, &|_| true).is_none() {
        return false;
    }
    let Some(typical) = median_width(curves.iter(), mask, stroke_width).filter(|&w| w > 0.0) else {
        return false;
    };
    let double = |piece: &[Point]| ink_is_double(piece, mask, stroke_width, typical);
    let mut any = false;
    for _ in 0..MAX_PROTRUSION_JOINS {
        let Some((i, j, joined)) = protrusion_join(curves, on_itself, &double) else {
            break;
        };
        curves[i] = Polyline::new(joined, false);
        curves.remove(j);
        any = true;
    }
    any
}

/// At most this many joins at protrusion tips in one drawing (or window): each join searches
/// every open curve again.
// DECISION: (stop 72) a bound, since the search after each join costs the whole drawing again: a
// 1500×1500 page of noise made thousands of joins and ran for over five minutes (400×400: 358
// joins, 2.3 s). A drawing of line art needs a few (the benchmark's and the samples' outputs are
// the same with the bound); a page of noise keeps its first joins and stops.
const MAX_PROTRUSION_JOINS: usize = 32;

/// The first two open curves `i < j` of `curves` of which one ends at a protrusion's tip and the
/// other at its base ([`join_curves_at_a_protrusion_tip`]), the protrusion's piece of curve
/// (from the base out to the tip) passing `double`, and their joined points.
fn protrusion_join(
    curves: &[Polyline],
    on_itself: f64,
    double: &dyn Fn(&[Point]) -> bool,
) -> Option<(usize, usize, Vec<Point>)> {
    let open: Vec<usize> = (0..curves.len())
        .filter(|&i| !curves[i].closed && curves[i].points.len() >= 2)
        .collect();
    if open.len() < 2 || on_itself <= 0.0 {
        return None;
    }
    // DECISION: (stop 72) the open curves' ends are looked up in a grid round the curve's points,
    // not tried against every curve: on a page of noise (thousands of open curves) the search,
    // run again after every join, took 15 s on 400×400 pixels and over 9 minutes on 1500×1500.
    // An end farther than `on_itself` from every point of the curve never stops on it (its
    // nearest point is the base's test), and the candidates are taken in the order the full scan
    // took them (curve by curve, its last end first), so the join found is the same.
    let mut ends: PointGrid<(usize, bool)> =
        PointGrid::with_capacity(on_itself, 2 * open.len(), 2 * open.len());
    for &j in &open {
        let other = &curves[j].points;
        ends.insert(other[other.len() - 1], (j, true));
        ends.insert(other[0], (j, false));
    }
    let mut candidates: Vec<(usize, bool)> = Vec::new();
    for &i in &open {
        let points = &curves[i].points;
        if points.len() < 4 {
            continue;
        }
        let own_box = bounding_box(points);
        let reach = own_box.inflate(on_itself, on_itself);
        candidates.clear();
        // Only an end within `on_itself` of one of the curve's points can stop on it.
        for &p in points {
            candidates.extend(ends.around(p).filter(|&&(j, _)| j != i));
        }
        candidates.sort_unstable_by_key(|&(j, end_last)| (j, !end_last));
        candidates.dedup();
        if candidates.is_empty() {
            continue;
        }
        // The curve with its tip last, one way round and then the other.
        for tip_last in [true, false] {
            let mut a = points.clone();
            if !tip_last {
                a.reverse();
            }
            let n = a.len();
            let tip = a[n - 1];
            let along = distances_along(&a);
            let total = along[n - 1];
            for &(j, end_last) in &candidates {
                let other = &curves[j].points;
                let end = if end_last {
                    other[other.len() - 1]
                } else {
                    other[0]
                };
                if !reach.contains(end) || end.distance(tip) <= on_itself {
                    continue;
                }
                let size = own_box.union(bounding_box(other));
                let max_protrusion =
                    PROTRUSION_MAX_SHARE_OF_OUTLINE * size.width().hypot(size.height());
                // Where the end stops on the curve: its nearest point farther than the reach
                // from the tip along it.
                let away = (0..n - 1).filter(|&k| total - along[k] > on_itself);
                let Some(base) =
                    base_where_stopping(&a, &along, end, away, on_itself, max_protrusion)
                else {
                    continue;
                };
                if !double(&a[base..]) {
                    continue;
                }
                // The other curve up to its end, out from the base to the tip, and back
                // along the whole curve.
                let mut joined = other.clone();
                if !end_last {
                    joined.reverse();
                }
                joined.extend(a[base..].iter().copied());
                joined.extend(a[..n - 1].iter().rev().copied());
                joined.dedup();
                return Some((i.min(j), i.max(j), joined));
            }
        }
    }
    None
}

/// The points of the open curve `points` closed from its last point, a protrusion's tip, back
/// along the protrusion to its base ([`protrusion_base`]); none where it ends otherwise.
fn closed_back_along_protrusion(
    points: &[Point],
    on_itself: f64,
    max_protrusion: f64,
) -> Option<Vec<Point>> {
    let base = protrusion_base(points, on_itself, max_protrusion)?;
    let mut closed = points.to_vec();
    closed.extend(points[base..points.len() - 1].iter().rev());
    closed.dedup();
    Some(closed)
}

/// For an open curve through `points` whose first point stops on the curve itself at its
/// protrusion's base and whose last point is that protrusion's tip: the index of the base (the
/// point nearest the first of those farther than `on_itself` from it along the curve, and at
/// most `on_itself` from it in a straight line), where the stretch from there to the tip is no
/// longer than `max_protrusion` and its tip farther out than `on_itself`.
fn protrusion_base(points: &[Point], on_itself: f64, max_protrusion: f64) -> Option<usize> {
    let along = distances_along(points);
    // Where the first point stops on the curve: its nearest point away from it along the curve.
    let away = (1..points.len() - 1).filter(|&k| along[k] > on_itself);
    base_where_stopping(points, &along, points[0], away, on_itself, max_protrusion)
}

/// Where a point `stop` lies on the open curve through `points` (a protrusion's tip last,
/// `along` its distances along the curve) at the protrusion's base: the index among `candidates`
/// of the point nearest `stop`, where that is at most `on_itself` from it, the stretch from there
/// to the tip no longer than `max_protrusion` and the tip farther out than `on_itself`.
fn base_where_stopping(
    points: &[Point],
    along: &[f64],
    stop: Point,
    candidates: impl Iterator<Item = usize>,
    on_itself: f64,
    max_protrusion: f64,
) -> Option<usize> {
    let n = points.len();
    let (distance, base) = candidates
        .map(|k| (points[k].distance(stop), k))
        .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))?;
    let protrusion = along[n - 1] - along[base];
    let tip_out = points[n - 1].distance(points[base]);
    (distance <= on_itself && protrusion <= max_protrusion && tip_out > on_itself).then_some(base)
}

/// Whether the ink along a hanging curve (`spike`, its base first) is two sides merged: its
/// median width, away from the base ([`BASE_CLEARANCE_IN_PEN_WIDTHS`]), at least
/// [`SPIKE_WIDTH_RATIO`] times the page's stroke (`typical`).
fn ink_is_double(spike: &[Point], mask: &Bitmap, stroke_width: f64, typical: f64) -> bool {
    let clearance = BASE_CLEARANCE_IN_PEN_WIDTHS * stroke_width;
    let widths: Vec<f64> = (0..spike.len())
        .filter(|&k| spike[k].distance(spike[0]) > clearance)
        .filter_map(|k| width_at(spike, k, mask, stroke_width))
        .collect();
    wider_than_a_stroke(widths, typical)
}

/// Whether ink measured `widths` across at [`MIN_MEASURED_POINTS`] points at least is two sides
/// merged: their median at least [`SPIKE_WIDTH_RATIO`] times the page's stroke (`typical`).
fn wider_than_a_stroke(widths: Vec<f64>, typical: f64) -> bool {
    widths.len() >= MIN_MEASURED_POINTS && median(widths) >= SPIKE_WIDTH_RATIO * typical
}

/// The diagonal of the bounding box of `points` (at least one): the size of a closed curve.
fn diagonal(points: &[Point]) -> f64 {
    let box_of = bounding_box(points);
    box_of.width().hypot(box_of.height())
}

/// A free end within this much (pen widths) of a collapsed spike's root goes on to its tip: gaps
/// in a skip-stroke sketch are a few pen widths long.
// DECISION: (stop 36) five pen widths, the reach a band's piece beyond a pen lift is looked for
// in ([`crate::strokes`]' double strands). Measured on the benchmark (seeds 1, 3, 5): four the
// same, three loses two drawings (a letter's corner, a cloud's notch), seven loses six (letters'
// and open controls' ends taken across the gap between two shapes).
const ROOT_REACH_IN_PEN_WIDTHS: f64 = 5.0;

/// A curve's end piece is looked at over this much of it (pen widths) for a collapsed spike:
/// where the ink of two sides runs merged for longer, the double-strand stage splits it.
// DECISION: (stop 36) eight pen widths; five loses a cloud's notch of seed 5, twelve measures the
// same.
const MAX_SPIKE_END_IN_PEN_WIDTHS: f64 = 8.0;

/// DECISION: (stop 65) the free end of another curve that lies on the spike's curve's line
/// (within [`ON_TIP_LINE_IN_PEN_WIDTHS`] of it: a line ending on that curve, whose end the crawl
/// put on the junction) goes on to the spike's tip only from at most this many typical gaps from
/// the spike's root. The side of a collapsed spike whose last stretch the pen left out ends a pen
/// lift from where the sides merge; a line ending on the curve farther up, over ink one stroke
/// wide, is a T (an "A"'s crossbar ending on its leg, whose pen-down blot at the foot read as a
/// spike one sample long: the crossbar was joined down the leg and back, the letter one path out
/// and back). The curve's own other end is left as it was (an outline's end reaches a spike's
/// tip across its closing lift, up to 1.6 typical gaps from the root on the development splits).
/// Measured on the benchmark (exact): seed 11 +2 (`letters-clean-008`, `letters-scan-021`),
/// every other split unchanged, nothing lost; validation seeds 2 and 12 and held-out seed 4
/// unchanged; the same at 1.25. The T-ends seen lay 1.7 and 1.9 typical gaps from the root,
/// the true sides on the spike's line 0.4 and 1.2. Without the exceptions (any free end, or
/// also the curve's own end, held to 1.5 typical gaps): seed 11 +3, seed 8 −1 (a thick star's
/// spike), seed 12 −2.
/// Holding any free end to 4 pen widths or requiring two wide samples (not one) instead:
/// seed 11 +2 −3 and +4 −6, development −2 and −3.
const T_END_MAX_LIFT_IN_TYPICAL_GAPS: f64 = 1.5;

/// An end lies on a curve's line within this much (pen widths): the crawl ends a line ending on
/// another at the junction, on the other's centre line.
const ON_TIP_LINE_IN_PEN_WIDTHS: f64 = 0.5;

/// Where an open curve ends in a collapsed spike or wedge (its end piece's ink at least
/// [`SPIKE_WIDTH_RATIO`] times the page's stroke, then one stroke wide again at the spike's root)
/// and a free end of an open curve lies near that root, pointing at it, the free end goes on to
/// the spike's tip: the spike's two sides are the free end's stroke, whose last stretch before
/// the tip the pen left out, and the curve's end piece. An acute corner of a letter whose one arm
/// has a pen lift just below the apex, and a cloud's notch whose drop the pen drew in one stroke
/// with the next lobe, the lobe before it ending in a pen lift. A bridge between the two free
/// ends is refused by the crawl: the tip points away from the end that should reach it.
pub fn join_free_ends_to_spike_tips(
    curves: &mut Vec<Polyline>,
    mask: &Bitmap,
    stroke_width: f64,
    typical_gap: f64,
) {
    let reach = ROOT_REACH_IN_PEN_WIDTHS * stroke_width;
    let on_tip_line = ON_TIP_LINE_IN_PEN_WIDTHS * stroke_width;
    let lift_reach = T_END_MAX_LIFT_IN_TYPICAL_GAPS * typical_gap;
    if stroke_width <= 0.0 || !curves.iter().any(|c| !c.closed) {
        return;
    }
    // The open curves' ends, by position: a page of noise has thousands.
    let mut ends = PointGrid::new(reach);
    for (c, curve) in curves.iter().enumerate() {
        if !curve.closed && curve.points.len() >= 2 {
            for start in [true, false] {
                let end = CurveEnd { curve: c, start };
                ends.insert(end.point(curves), end);
            }
        }
    }
    let mut typical = None;
    let mut offers: Vec<(f64, CurveEnd, CurveEnd)> = Vec::new();
    for (c, curve) in curves.iter().enumerate() {
        if curve.closed || curve.points.len() < 3 {
            continue;
        }
        for start in [true, false] {
            let tip = CurveEnd { curve: c, start };
            let points = tip.end_piece(curves, MAX_SPIKE_END_IN_PEN_WIDTHS * stroke_width);
            let typical = *typical.get_or_insert_with(|| {
                median_width(curves.iter(), mask, stroke_width).unwrap_or(f64::INFINITY)
            });
            let Some(root) = spike_root(&points, mask, stroke_width, typical) else {
                continue;
            };
            let at = points[root];
            let nearest = ends
                .around(at)
                .filter(|&&end| end != tip)
                .filter(|end| {
                    let (point, next) = end.point_and_next(curves);
                    // A line ending on the spike's own curve is a side only a pen lift from
                    // the root ([`T_END_MAX_LIFT_IN_TYPICAL_GAPS`]); the walk along that curve
                    // is left for the ends that pass the cheap tests.
                    let t_end_too_far = || {
                        end.curve != tip.curve
                            && point.distance(at) > lift_reach
                            && within_of_chain(point, &curves[tip.curve].points, on_tip_line)
                    };
                    point.distance(at) <= reach
                        && (at - point).dot(point - next) > 0.0
                        && !t_end_too_far()
                })
                .min_by(|a, b| {
                    let d = |e: &CurveEnd| e.point(curves).distance(at);
                    d(a).total_cmp(&d(b)).then(a.cmp(b))
                });
            if let Some(&from) = nearest {
                offers.push((from.point(curves).distance(at), from, tip));
            }
        }
    }
    if offers.is_empty() {
        return;
    }
    // DECISION: (stop 46) a join runs straight from the free end to the tip; where another curve
    // already traces all of that ink, the two ends are the feet of a shape standing on that
    // curve's line (a house's door on its floor, its ink read as wide where the floor crosses it),
    // not the two sides of a spike whose tip the pen left out. Measured on the benchmark: with
    // the redundant arcs' rule on the junctions ([`super::contacts`]) seed 7 gains a house, none
    // lost on the eight splits; alone nothing changes (the door then went in there).
    let on_curve = ON_CURVE_IN_PEN_WIDTHS * stroke_width;
    let segments = SegmentGrid::new(curves, on_curve);
    offers.retain(|&(_, from, tip)| {
        let (a, b) = (from.point(curves), tip.point(curves));
        !segments.traced_by_another(curves, a, b, [from.curve, tip.curve], on_curve)
    });
    // Nearest first, each end joined once.
    offers.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut joined: HashMap<CurveEnd, CurveEnd> = HashMap::new();
    for (_, from, tip) in offers {
        if !joined.contains_key(&from) && !joined.contains_key(&tip) {
            joined.insert(from, tip);
            joined.insert(tip, from);
        }
    }
    *curves = stitched(curves, &joined);
}

/// One end of an open curve: its first point when `start`, else its last.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
struct CurveEnd {
    curve: usize,
    start: bool,
}

impl CurveEnd {
    fn point(self, curves: &[Polyline]) -> Point {
        self.point_and_next(curves).0
    }

    /// The end's point and the curve's point next to it.
    fn point_and_next(self, curves: &[Polyline]) -> (Point, Point) {
        let points = &curves[self.curve].points;
        let n = points.len();
        if self.start {
            (points[0], points[1])
        } else {
            (points[n - 1], points[n - 2])
        }
    }

    /// The curve's points from this end.
    fn points_from(self, curves: &[Polyline]) -> Vec<Point> {
        let mut points = curves[self.curve].points.clone();
        if !self.start {
            points.reverse();
        }
        points
    }

    /// The curve's points from this end as far as the first one more than `length` along it
    /// (or the whole curve, if shorter), and the point after that: all [`spike_root`] reads.
    fn end_piece(self, curves: &[Polyline], length: f64) -> Vec<Point> {
        let points = &curves[self.curve].points;
        let n = points.len();
        let from_end = (0..n).map(|k| {
            if self.start {
                points[k]
            } else {
                points[n - 1 - k]
            }
        });
        let mut piece: Vec<Point> = Vec::new();
        let mut along = 0.0;
        let mut past = 0;
        for point in from_end {
            if let Some(&last) = piece.last() {
                along += last.distance(point);
            }
            piece.push(point);
            if along > length {
                past += 1;
                if past == 2 {
                    break;
                }
            }
        }
        piece
    }

    /// The curve's other end.
    fn other(self) -> Self {
        Self {
            curve: self.curve,
            start: !self.start,
        }
    }
}

/// The curves with the joined ends run into each other: each chain of joined open curves becomes
/// one curve (closed where it comes back round to where it began), put where its first curve was.
fn stitched(curves: &[Polyline], joined: &HashMap<CurveEnd, CurveEnd>) -> Vec<Polyline> {
    let mut done = vec![false; curves.len()];
    let mut result = Vec::with_capacity(curves.len());
    for (c, curve) in curves.iter().enumerate() {
        if done[c] {
            continue;
        }
        let first = CurveEnd {
            curve: c,
            start: true,
        };
        if curve.closed || (!joined.contains_key(&first) && !joined.contains_key(&first.other())) {
            done[c] = true;
            result.push(curve.clone());
            continue;
        }
        // Back along the chain to its first curve's free end, or once round a loop.
        let mut entry = first;
        while let Some(&previous) = joined.get(&entry) {
            entry = previous.other();
            if entry.curve == c {
                break;
            }
        }
        let mut points = Vec::new();
        let mut at = entry;
        let closed = loop {
            done[at.curve] = true;
            points.extend(at.points_from(curves));
            match joined.get(&at.other()) {
                Some(&next) if next == entry => break true,
                Some(&next) if !done[next.curve] => at = next,
                _ => break false,
            }
        };
        result.push(Polyline::new(points, closed));
    }
    result
}

/// Where the curve `points` (its end first) ends in a collapsed spike: the index of the spike's
/// root, the first point past the end's wide ink where the ink is one stroke wide again.
fn spike_root(points: &[Point], mask: &Bitmap, stroke_width: f64, typical: f64) -> Option<usize> {
    let limit = MAX_SPIKE_END_IN_PEN_WIDTHS * stroke_width;
    let mut length = 0.0;
    let mut wide = 0;
    for k in 1..points.len() - 1 {
        length += points[k - 1].distance(points[k]);
        if length > limit {
            return None;
        }
        let width = width_at(points, k, mask, stroke_width)?;
        if width >= SPIKE_WIDTH_RATIO * typical {
            wide += 1;
        } else {
            return (wide >= 1).then_some(k);
        }
    }
    None
}

/// The segments of all curves, bucketed by points along them one `reach` apart in cells twice
/// as wide, so that every segment passing within `reach` of a point is found around it. Also
/// [`super::retraced`]'s, and the contacts stage's (`crate::trace`).
pub(crate) struct SegmentGrid {
    grid: PointGrid<(usize, usize)>,
}

impl SegmentGrid {
    pub(crate) fn new(curves: &[Polyline], reach: f64) -> Self {
        let step = reach.max(1.0);
        // Each segment goes in at least one cell, a few in two; cells hold a few each.
        let segments: usize = curves
            .iter()
            .map(|c| {
                if c.closed {
                    c.points.len()
                } else {
                    c.points.len().saturating_sub(1)
                }
            })
            .sum();
        let mut grid = PointGrid::with_capacity(2.0 * step, segments + segments / 8, segments / 2);
        for (i, curve) in curves.iter().enumerate() {
            let n = curve.points.len();
            let count = if curve.closed { n } else { n.saturating_sub(1) };
            for s in 0..count {
                let (a, b) = (curve.points[s], curve.points[(s + 1) % n]);
                let pieces = (a.distance(b) / step).ceil().max(1.0) as usize;
                // A segment is put once in each cell it passes through: consecutive points along
                // it often fall in one cell, and the copies only cost the queries time.
                let mut last_cell = None;
                for k in 0..=pieces {
                    let p = a.lerp(b, k as f64 / pieces as f64);
                    let cell = grid.cell_of(p);
                    if last_cell != Some(cell) {
                        grid.insert_in_cell(cell, (i, s));
                        last_cell = Some(cell);
                    }
                }
            }
        }
        Self { grid }
    }

    /// The segments (curve, segment) bucketed around `p`: every one within the grid's `reach`
    /// of it, and some farther.
    pub(crate) fn around(&self, p: Point) -> impl Iterator<Item = &(usize, usize)> + '_ {
        self.grid.around(p)
    }

    /// Whether the ink between `a` and `b` is already traced by a curve other than `joined`:
    /// every point of the segment farther than `reach` from both ends lies within `reach` of
    /// such a curve (and there is at least one such point).
    fn traced_by_another(
        &self,
        curves: &[Polyline],
        a: Point,
        b: Point,
        joined: [usize; 2],
        reach: f64,
    ) -> bool {
        let steps = a.distance(b).ceil() as usize;
        let mut inner = (1..steps)
            .map(|k| a.lerp(b, k as f64 / steps as f64))
            .filter(|p| p.distance(a) > reach && p.distance(b) > reach)
            .peekable();
        inner.peek().is_some()
            && inner.all(|p| {
                self.grid.around(p).any(|&(i, s)| {
                    !joined.contains(&i) && distance_to_segment(p, segment(curves, i, s)) <= reach
                })
            })
    }

    /// The curve other than `own` that passes nearest to `point`, within `reach`; segments of
    /// `own` count too when they lie away from `point` along it (a curve that comes back near
    /// its own end), and then `own` is returned.
    fn nearest_other_curve(
        &self,
        curves: &[Polyline],
        point: Point,
        own: usize,
        reach: f64,
    ) -> Option<usize> {
        let mut best: Option<(f64, usize)> = None;
        for &(i, s) in self.grid.around(point) {
            let line = segment(curves, i, s);
            if i == own && (line.p0.distance(point) <= reach || line.p1.distance(point) <= reach) {
                continue;
            }
            let d = distance_to_segment(point, line);
            if d <= reach && best.is_none_or(|(bd, bi)| d < bd || (d == bd && i < bi)) {
                best = Some((d, i));
            }
        }
        best.map(|(_, i)| i)
    }
}

/// Segment `s` of curve `i`: from its point `s` to the next (round to the first on a closed
/// curve), as [`SegmentGrid`] buckets them.
pub(super) fn segment(curves: &[Polyline], i: usize, s: usize) -> Line {
    let points = &curves[i].points;
    Line::new(points[s], points[(s + 1) % points.len()])
}

/// The median width of ink across the curves' points.
fn median_width<'a>(
    curves: impl Iterator<Item = &'a Polyline>,
    mask: &Bitmap,
    stroke_width: f64,
) -> Option<f64> {
    let widths: Vec<f64> = curves
        .flat_map(|curve| {
            (0..curve.points.len())
                .filter_map(move |k| width_at(&curve.points, k, mask, stroke_width))
        })
        .collect();
    (!widths.is_empty()).then(|| median(widths))
}

fn median(mut values: Vec<f64>) -> f64 {
    let middle = values.len() / 2;
    let (_, m, _) = values.select_nth_unstable_by(middle, f64::total_cmp);
    *m
}

/// The width of ink across `points[k]`, square to the chord between its neighbours; none at an
/// end or off the ink.
fn width_at(points: &[Point], k: usize, mask: &Bitmap, stroke_width: f64) -> Option<f64> {
    let width = ink_width_across(mask, points[k], normal_at(points, k)?, stroke_width);
    (width > 0.0).then_some(width)
}

/// The unit normal at `points[k]`, square to the chord between its neighbours; none at an end
/// or where the neighbours coincide.
fn normal_at(points: &[Point], k: usize) -> Option<Vec2> {
    if k == 0 || k + 1 >= points.len() {
        return None;
    }
    let along = points[k + 1] - points[k - 1];
    let length = along.hypot();
    (length > 0.0).then(|| Vec2::new(-along.y / length, along.x / length))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ink within `pen / 2` of the polyline through `corners` (closed or open), added to `mask`.
    fn ink(mask: &mut Bitmap, corners: &[Point], closed: bool, pen: f64) {
        let mut run = corners.to_vec();
        if closed {
            run.push(corners[0]);
        }
        for y in 0..mask.height() {
            for x in 0..mask.width() {
                let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
                let near = run.windows(2).any(|w| {
                    let (a, b) = (w[0], w[1]);
                    let t = ((p - a).dot(b - a) / (b - a).hypot2()).clamp(0.0, 1.0);
                    p.distance(a.lerp(b, t)) <= pen / 2.0
                });
                if near {
                    mask.set(x, y, true);
                }
            }
        }
    }

    /// Points every 4 px along the polyline through `corners` (closed or open).
    fn sampled(corners: &[Point], closed: bool) -> Vec<Point> {
        let mut run = corners.to_vec();
        if closed {
            run.push(corners[0]);
        }
        let mut points = Vec::new();
        for w in run.windows(2) {
            let steps = (w[0].distance(w[1]) / 4.0).ceil() as usize;
            points.extend((0..steps).map(|k| w[0].lerp(w[1], k as f64 / steps as f64)));
        }
        if !closed {
            points.push(run[run.len() - 1]);
        }
        points
    }

    /// A square outline drawn with a 4-px pen, and a line 32 px long standing on its top side,
    /// inked `stem_ink` px wide; the crawl's two curves for them.
    fn square_with_stem(stem_ink: f64) -> (Vec<Polyline>, Bitmap) {
        square_with_stem_drawn(4.0, 8.0, stem_ink)
    }

    /// A box 36 × 56 px drawn with a `pen` (its diagonal 66.6 px), and a line from the middle of
    /// its top side (y = 40) up to y = `stem_top`, inked `stem_ink` px wide; the crawl's two
    /// curves for them. From y = 23.3 up the line is longer than a quarter of the box's size,
    /// and only its ink tells a collapsed spike from a line of its own.
    fn square_with_stem_drawn(pen: f64, stem_top: f64, stem_ink: f64) -> (Vec<Polyline>, Bitmap) {
        let square = [
            Point::new(20.0, 40.0),
            Point::new(56.0, 40.0),
            Point::new(56.0, 96.0),
            Point::new(20.0, 96.0),
        ];
        let stem = [Point::new(38.0, 40.0), Point::new(38.0, stem_top)];
        let mut mask = Bitmap::new(120, 120);
        ink(&mut mask, &square, true, pen);
        ink(&mut mask, &stem, false, stem_ink);
        let curves = vec![
            Polyline::new(sampled(&square, true), true),
            Polyline::new(sampled(&stem, false), false),
        ];
        (curves, mask)
    }

    #[test]
    fn a_hanging_line_wider_than_the_pen_is_folded_into_its_outline_out_and_back() {
        // A spike whose sides merged: 6 px of ink on a 4-px pen.
        let (mut curves, mask) = square_with_stem(6.0);
        fold_collapsed_spikes(&mut curves, &mask, 4.0);
        assert_eq!(curves.len(), 1, "{curves:?}");
        let outline = &curves[0];
        assert!(outline.closed);
        let tip = Point::new(38.0, 8.0);
        assert!(outline.points.iter().any(|p| p.distance(tip) < 1e-9));
        // Out to the tip and straight back: the points before and after it mirror each other.
        let at = outline
            .points
            .iter()
            .position(|p| p.distance(tip) < 1e-9)
            .unwrap();
        for k in 1..8 {
            let (before, after) = (outline.points[at - k], outline.points[at + k]);
            assert!(before.distance(after) < 1e-9, "{before:?} {after:?}");
        }
    }

    #[test]
    fn a_short_thick_spike_is_measured_from_a_pen_width_and_a_half_off_its_base() {
        // A 6-px pen and a spike 24 px long (four pen widths) whose sides merged into 9 px of
        // ink, sampled every 4 px: past two pen widths from the base lie only two points that
        // have a cross-section (the tip has none), too few to judge; past one and a half, three.
        let (mut curves, mask) = square_with_stem_drawn(6.0, 16.0, 9.0);
        fold_collapsed_spikes(&mut curves, &mask, 6.0);
        assert_eq!(curves.len(), 1, "folded: {curves:?}");
    }

    #[test]
    fn a_hanging_line_one_pen_wide_stays_a_line_of_its_own() {
        // A stem drawn with the same pen as the outline (a balloon's string).
        let (mut curves, mask) = square_with_stem(4.0);
        let before = curves.clone();
        fold_collapsed_spikes(&mut curves, &mask, 4.0);
        assert_eq!(curves, before);
    }

    #[test]
    fn a_short_hanging_line_one_pen_wide_is_folded_as_a_protrusion() {
        // A narrow spike whose sides merged into one stroke's ink, 12 px long on a box 66.6 px
        // across (a fifth of its size): a protrusion of the outline, not a line of its own.
        let (mut curves, mask) = square_with_stem_drawn(4.0, 28.0, 4.0);
        fold_collapsed_spikes(&mut curves, &mask, 4.0);
        assert_eq!(curves.len(), 1, "{curves:?}");
        assert!(curves[0].closed);
        assert!(curves[0]
            .points
            .iter()
            .any(|p| p.distance(Point::new(38.0, 28.0)) < 1e-9));
    }

    /// Two boxes 30 px a side drawn with a 2-px pen, 40 px apart, and a neck between the middles
    /// of their facing sides drawn as two lines `apart` px apart centre to centre (one line where
    /// `apart` is 0); the crawl's three curves: the two boxes, each sealed across the neck's
    /// mouth, and the neck's one line of skeleton from box to box, a pixel off each box, along
    /// the upper side's line (where the two inks part, the skeleton runs along one of them).
    fn dumbbell(apart: f64) -> (Vec<Polyline>, Bitmap) {
        let pen = 2.0;
        let corners = |x0: f64| {
            [(x0, 30.0), (x0 + 30.0, 30.0), (x0 + 30.0, 60.0), (x0, 60.0)]
                .map(|(x, y)| Point::new(x, y))
        };
        let (left, right) = (corners(10.0), corners(80.0));
        let mut mask = Bitmap::new(120, 90);
        ink(&mut mask, &left, true, pen);
        ink(&mut mask, &right, true, pen);
        for side in [-apart / 2.0, apart / 2.0] {
            let line = [Point::new(40.0, 45.0 + side), Point::new(80.0, 45.0 + side)];
            ink(&mut mask, &line, false, pen);
        }
        let neck = [
            Point::new(41.0, 45.0 - apart / 2.0),
            Point::new(79.0, 45.0 - apart / 2.0),
        ];
        let curves = vec![
            Polyline::new(sampled(&left, true), true),
            Polyline::new(sampled(&right, true), true),
            Polyline::new(sampled(&neck, false), false),
        ];
        (curves, mask)
    }

    #[test]
    fn a_neck_of_two_lines_side_by_side_joins_its_two_parts_into_one_outline() {
        // The sides 1.75 pen widths apart: two pixels of paper between their inks, which the
        // width across one side alone (2 px) does not see.
        let (mut curves, mask) = dumbbell(3.5);
        fold_collapsed_necks(&mut curves, &mask, 2.0);
        assert_eq!(curves.len(), 1, "{curves:?}");
        let outline = &curves[0];
        assert!(outline.closed);
        // Round the far box, and along the neck once each way.
        assert!(outline
            .points
            .iter()
            .any(|p| p.distance(Point::new(110.0, 60.0)) < 1e-9));
        let on_neck = |p: &&Point| (p.y - 43.25).abs() < 1e-9 && p.x > 50.0 && p.x < 70.0;
        assert!(
            outline.points.iter().filter(on_neck).count() >= 2 * 4,
            "{outline:?}"
        );
    }

    #[test]
    fn a_line_of_one_strokes_ink_between_two_shapes_stays_a_line_of_its_own() {
        // A barbell drawn with one line for its bar.
        let (mut curves, mask) = dumbbell(0.0);
        let before = curves.clone();
        fold_collapsed_necks(&mut curves, &mask, 2.0);
        assert_eq!(curves, before);
    }

    /// The crawl's open curve for a box 36 × 56 px with a spike `spike` px long standing on the
    /// middle of its top side, the spike's sides merged into one line: from the spike's base
    /// (38, 40) round the box and out along the spike to its tip; the stroke that met the
    /// spike's base ended there, a pixel to its right.
    fn box_ending_at_its_spike_tip(spike: f64) -> (Polyline, Point) {
        let outline = [
            Point::new(39.0, 40.0),
            Point::new(56.0, 40.0),
            Point::new(56.0, 96.0),
            Point::new(20.0, 96.0),
            Point::new(20.0, 40.0),
            Point::new(38.0, 40.0),
            Point::new(38.0, 40.0 - spike),
        ];
        let tip = outline[outline.len() - 1];
        (Polyline::new(sampled(&outline, false), false), tip)
    }

    #[test]
    fn an_outline_ending_at_its_spike_tip_comes_back_along_the_spike_and_closes() {
        let (curve, tip) = box_ending_at_its_spike_tip(12.0);
        let mut curves = vec![curve];
        close_curves_ending_at_a_protrusion_tip(&mut curves, 4.0);
        let outline = &curves[0];
        assert!(outline.closed, "{outline:?}");
        // Out to the tip and straight back down the spike.
        let at = outline.points.iter().position(|p| *p == tip).unwrap();
        assert!(at + 1 < outline.points.len(), "{outline:?}");
        assert_eq!(outline.points[at + 1].x, 38.0);
        assert!(outline.points[at + 1].y > tip.y);
    }

    /// The crawl's two open curves for a box 60 × 90 px drawn with a 4-px pen and a spike 24 px
    /// long on the middle of its top side, inked `spike_ink` px wide, with a pen lift on the
    /// box's left side (y 82 to 90): one curve from the spike's tip down to its base (50, 40) and
    /// round the box to the lift, the other from the lift up and along the top to a pixel short
    /// of the spike's base, where the stroke ended at the junction.
    fn box_in_two_pieces_with_a_spike(spike_ink: f64) -> (Vec<Polyline>, Bitmap) {
        let tip = Point::new(50.0, 16.0);
        let out_to_the_tip = [
            tip,
            Point::new(50.0, 40.0),
            Point::new(80.0, 40.0),
            Point::new(80.0, 130.0),
            Point::new(20.0, 130.0),
            Point::new(20.0, 90.0),
        ];
        let up_to_the_base = [
            Point::new(20.0, 82.0),
            Point::new(20.0, 40.0),
            Point::new(49.0, 40.0),
        ];
        let mut mask = Bitmap::new(120, 150);
        ink(&mut mask, &out_to_the_tip[1..], false, 4.0);
        ink(&mut mask, &up_to_the_base, false, 4.0);
        ink(&mut mask, &out_to_the_tip[..2], false, spike_ink);
        let curves = vec![
            Polyline::new(sampled(&out_to_the_tip, false), false),
            Polyline::new(sampled(&up_to_the_base, false), false),
        ];
        (curves, mask)
    }

    #[test]
    fn two_pieces_of_an_outline_meeting_at_a_collapsed_spike_are_joined_out_along_it_and_back() {
        // The spike's sides merged into 7 px of ink on a 4-px pen.
        let (mut curves, mask) = box_in_two_pieces_with_a_spike(7.0);
        assert!(join_curves_at_a_protrusion_tip(&mut curves, &mask, 4.0));
        assert_eq!(curves.len(), 1, "{curves:?}");
        let outline = &curves[0];
        assert!(!outline.closed);
        // From the lift up the left side, out along the spike to its tip and straight back down,
        // round the box to the lift again.
        assert_eq!(outline.points[0], Point::new(20.0, 82.0));
        assert_eq!(
            outline.points[outline.points.len() - 1],
            Point::new(20.0, 90.0)
        );
        let tip = Point::new(50.0, 16.0);
        let at = outline.points.iter().position(|p| *p == tip).unwrap();
        for k in 1..6 {
            let (before, after) = (outline.points[at - k], outline.points[at + k]);
            assert!(before.distance(after) < 1e-9, "{before:?} {after:?}");
        }
    }

    #[test]
    fn two_pieces_meeting_at_a_line_one_pen_wide_stay_apart() {
        // The "spike" inked with the pen itself: a line of its own that the other piece ends on
        // (a T), or the end of a line beside its neighbour's.
        let (mut curves, mask) = box_in_two_pieces_with_a_spike(4.0);
        let before = curves.clone();
        assert!(!join_curves_at_a_protrusion_tip(&mut curves, &mask, 4.0));
        assert_eq!(curves, before);
    }

    #[test]
    fn an_open_curve_whose_end_piece_is_long_beside_it_stays_open() {
        // The "spike" 24 px long, more than a quarter of the box's 66.6 px: a stroke that runs
        // on past the shape it ended on (a "P" drawn from the top of its stem).
        let (curve, _) = box_ending_at_its_spike_tip(24.0);
        let mut curves = vec![curve.clone()];
        close_curves_ending_at_a_protrusion_tip(&mut curves, 4.0);
        assert_eq!(curves, vec![curve]);
    }

    #[test]
    fn a_wide_line_between_two_curves_is_not_a_spike() {
        // Both ends on curves: a bar across, not a protrusion with a free tip.
        let (mut curves, mut mask) = square_with_stem(6.0);
        let lid = [Point::new(10.0, 8.0), Point::new(70.0, 8.0)];
        ink(&mut mask, &lid, false, 4.0);
        curves.push(Polyline::new(sampled(&lid, false), false));
        let before = curves.clone();
        fold_collapsed_spikes(&mut curves, &mask, 4.0);
        assert_eq!(curves, before);
    }

    /// A 20° "V" drawn with a 4-px pen, apex at (50, 10), arms 60 px long: the right arm and
    /// the wedge where the arms' ink merges drawn in one stroke, the left arm below a pen lift
    /// from 12 to 20 px below the apex (`merged`), or missing its upper 20 px altogether. The
    /// crawl's curves: the wedge's centre line from the apex and on down the right arm, and the
    /// left arm's lower piece up to its end below the lift.
    fn v_with_a_lift(merged: bool) -> (Vec<Polyline>, Bitmap, Point, Point) {
        let apex = Point::new(50.0, 10.0);
        let half = 10f64.to_radians();
        let arm = |side: f64, d: f64| apex + Vec2::new(side * half.sin(), half.cos()) * d;
        let mut mask = Bitmap::new(100, 100);
        ink(&mut mask, &[apex, arm(1.0, 60.0)], false, 4.0);
        if merged {
            ink(&mut mask, &[apex, arm(-1.0, 12.0)], false, 4.0);
        }
        ink(&mut mask, &[arm(-1.0, 20.0), arm(-1.0, 60.0)], false, 4.0);
        let mut wedge = vec![apex, Point::new(50.0, 14.0), Point::new(50.0, 18.0)];
        wedge.extend((3..=15).map(|k| arm(1.0, 4.0 * k as f64)));
        let lower: Vec<Point> = (0..=10).map(|k| arm(-1.0, 60.0 - 4.0 * k as f64)).collect();
        let free_end = lower[lower.len() - 1];
        let curves = vec![Polyline::new(wedge, false), Polyline::new(lower, false)];
        (curves, mask, apex, free_end)
    }

    #[test]
    fn a_free_end_below_a_merged_wedge_goes_on_to_its_tip() {
        let (mut curves, mask, apex, free_end) = v_with_a_lift(true);
        join_free_ends_to_spike_tips(&mut curves, &mask, 4.0, 8.0);
        assert_eq!(curves.len(), 1, "{curves:?}");
        let points = &curves[0].points;
        let at = points
            .iter()
            .position(|p| p.distance(free_end) < 1e-9)
            .unwrap();
        // Up the left arm, across its pen lift straight to the apex, down the right arm.
        assert!(points[at + 1].distance(apex) < 1e-9, "{points:?}");
        assert!(!curves[0].closed);
    }

    #[test]
    fn a_free_end_below_a_one_stroke_end_is_not_joined_to_it() {
        // Without the left arm's upper piece the apex is one stroke wide: nothing says the two
        // ends belong together here (the crawl's bridges decide that).
        let (mut curves, mask, _, _) = v_with_a_lift(false);
        let before = curves.clone();
        join_free_ends_to_spike_tips(&mut curves, &mask, 4.0, 8.0);
        assert_eq!(curves, before);
    }

    /// A leg 70 px long drawn with a 3-px pen, blotted at its foot (the pen put down), and a
    /// line ending on the leg 22 px above the foot, its end on the leg's centre line: an "A"'s
    /// leg and crossbar. The foot's blot reads as a collapsed spike one sample long, its root
    /// 12 px below the line's end.
    fn leg_with_a_blot_and_a_line_ending_on_it() -> (Vec<Polyline>, Bitmap) {
        let mut mask = Bitmap::new(100, 100);
        let leg: Vec<Point> = (0..=14)
            .map(|k| Point::new(50.0, 10.0 + 5.0 * k as f64))
            .collect();
        ink(&mut mask, &leg, false, 3.0);
        ink(
            &mut mask,
            &[Point::new(50.0, 78.0), Point::new(50.0, 80.0)],
            false,
            9.0,
        );
        let bar = vec![
            Point::new(90.0, 54.0),
            Point::new(70.0, 56.0),
            Point::new(50.0, 58.0),
        ];
        ink(&mut mask, &bar, false, 3.0);
        let curves = vec![Polyline::new(leg, false), Polyline::new(bar, false)];
        (curves, mask)
    }

    #[test]
    fn a_line_ending_on_a_curve_more_than_a_lift_above_its_blotted_end_is_not_joined_to_it() {
        let (mut curves, mask) = leg_with_a_blot_and_a_line_ending_on_it();
        let before = curves.clone();
        // Typical gaps of 6 px: the line's end lies two gaps above the spike's root.
        join_free_ends_to_spike_tips(&mut curves, &mask, 3.0, 6.0);
        assert_eq!(curves, before);
        // Within a pen lift of it (gaps of 16 px) the same end is taken for the spike's side.
        join_free_ends_to_spike_tips(&mut curves, &mask, 3.0, 16.0);
        assert_eq!(curves.len(), 1, "{curves:?}");
    }

    #[test]
    fn a_door_standing_on_the_floor_is_not_closed_along_it() {
        // A house's outline and a door 20 px wide on its floor, both drawn with a 6-px pen. The
        // door's curve ends where the crawl ended it at the two junctions: on the floor's centre
        // line, its last step a pixel along the floor. Across its right foot the ink runs along
        // the floor (read as wide as a collapsed spike), and its left foot points at the root
        // of that "spike"; but the floor between the feet is the outline's ink, not a gap.
        let house = [
            Point::new(10.0, 110.0),
            Point::new(10.0, 40.0),
            Point::new(110.0, 40.0),
            Point::new(110.0, 110.0),
        ];
        let door = [
            Point::new(72.0, 110.0),
            Point::new(71.5, 109.0),
            Point::new(71.0, 104.0),
            Point::new(70.0, 96.0),
            Point::new(69.0, 88.0),
            Point::new(68.0, 82.0),
            Point::new(60.0, 81.0),
            Point::new(52.0, 82.0),
            Point::new(51.0, 88.0),
            Point::new(50.0, 96.0),
            Point::new(50.0, 104.0),
            Point::new(51.0, 109.0),
            Point::new(51.5, 110.0),
        ];
        let mut mask = Bitmap::new(120, 120);
        ink(&mut mask, &house, true, 6.0);
        ink(&mut mask, &door, false, 6.0);
        let mut curves = vec![
            Polyline::new(sampled(&house, true), true),
            Polyline::new(door.to_vec(), false),
        ];
        let before = curves.clone();
        join_free_ends_to_spike_tips(&mut curves, &mask, 6.0, 8.0);
        assert_eq!(curves, before);
    }

    #[test]
    fn joined_ends_make_one_curve_and_a_chain_round_a_loop_closes() {
        let line = |a: (f64, f64), b: (f64, f64)| {
            Polyline::new(vec![Point::new(a.0, a.1), Point::new(b.0, b.1)], false)
        };
        // Three sides of a triangle, each drawn from a different corner.
        let curves = vec![
            line((0.0, 0.0), (10.0, 0.0)),
            line((0.0, 10.0), (10.0, 0.0)),
            line((0.0, 10.0), (0.0, 0.0)),
        ];
        let end = |curve, start| CurveEnd { curve, start };
        let mut joined = HashMap::new();
        for (a, b) in [(end(0, false), end(1, false)), (end(1, true), end(2, true))] {
            joined.insert(a, b);
            joined.insert(b, a);
        }
        let open = stitched(&curves, &joined);
        assert_eq!(open.len(), 1);
        assert!(!open[0].closed);
        assert_eq!(open[0].points.len(), 6);
        joined.insert(end(2, false), end(0, true));
        joined.insert(end(0, true), end(2, false));
        let closed = stitched(&curves, &joined);
        assert_eq!(closed.len(), 1);
        assert!(closed[0].closed);
        assert_eq!(closed[0].points.len(), 6);
    }
}
