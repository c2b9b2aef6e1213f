//! Double strands: where an outline comes back within about a pen width of itself (a narrow
//! spike, a leg, a tail, two runs side by side), the ink of its two stretches merges into one
//! band and the skeleton keeps one centre line for two curves. This stage measures the ink's
//! width across the branches, finds the bands clearly wider than one stroke, and replaces each
//! by its two sides, so that the skeleton graph says what a person tracing the outline sees: a
//! band that ends is where the outline turns back (its sides' two free ends meet there, unless
//! they go on across a gap), a band between two junctions is travelled once by each side. A
//! dash that is a band over one end only (a spike drawn out and back whose base is a pen lift)
//! is cut where its band ends, and the stroke goes on into one side of it.
//! Junctions then pair such branches without crossing ([`super::junctions`]).
//!
//! The paper (Parakkat & Muthuganapathy 2016) reconstructs a curve from samples only and has no
//! notion of ink width; this stage is ours (issue 9, "outlines whose parts touch").

use kurbo::{Point, Vec2};

use super::graph::{Branch, Node, SkeletonGraph};
use crate::geometry::grid::PointGrid;
use crate::geometry::polyline::signed_turn;
use crate::raster::bitmap::Bitmap;

/// A band is a double strand where it is this much wider than the page's typical stroke, over a
/// stretch of [`DOUBLE_STRETCH_IN_PEN_WIDTHS`]. A single stroke's width wanders by up to about a
/// fifth (jitter, scan noise, pixel steps across a 3-px pen); two strokes merged are at least
/// half again as wide, so the band's widest stretch clears this with room on both sides.
// DECISION: 1.3×, where the issue suggests a radius of about 0.7 pen widths (1.4× the width):
// measured on the benchmark's dev split, single strokes' widest stretch of two pen widths reaches
// 1.31× the page's median width and narrow spikes' 1.29–2.6×, so the line is drawn at 1.3×,
// inside the little overlap.
const DOUBLE_WIDTH_RATIO: f64 = 1.3;

/// ... and at least this much wider, in pixels: a thin pen's edges fall on pixel steps, which can
/// add a pixel to its width over a whole stretch, and a cross-section is counted in steps of
/// [`CROSS_STEP_PX`], which can add one more step.
// DECISION: one pixel and one cross-section step. At one pixel flat, a 3-px pen's slightly
// sloping bar (an "F"'s middle bar, 3–4 px of ink across) measured exactly one pixel over the
// page's stroke and was split into two sides, which took the letter's T-junction apart. Measured
// on the dev split: 1.1–1.3 px gain the same three drawings (that F, an arch, a meander), none
// lost; from 1.35 px narrow spikes' bands are missed (2–3 lost).
const DOUBLE_MIN_EXCESS_PX: f64 = 1.0 + CROSS_STEP_PX;

/// The width is averaged over stretches this long (in pen widths) before it is compared: long
/// enough to average out pixel steps and scan noise, short enough that a tapering spike's base
/// still counts.
const DOUBLE_STRETCH_IN_PEN_WIDTHS: f64 = 2.0;

/// Near a junction the ink of the other branches widens the cross-section; points nearer than
/// this (in pen widths) to a junction are not measured.
const JUNCTION_CLEARANCE_IN_PEN_WIDTHS: f64 = 2.0;

/// A branch's own corner widens the cross-section as a junction does: near the corner's vertex
/// the cross-section runs into the other arm's ink. A corner turns by at least this much
/// (degrees), measured over [`CORNER_ARM_IN_PEN_WIDTHS`] each way: the lines of a letter's
/// junctions meet at 45° or more (as [`crate::crawl`]'s corners to go on through).
const CORNER_MIN_TURN_DEGREES: f64 = 45.0;

/// ... and at most this much: a sharper turn is a hairpin, the two arms side by side all along,
/// which is what a band's tip looks like when the skeleton kept both of its sides.
const CORNER_MAX_TURN_DEGREES: f64 = 135.0;

/// A corner's turn is measured between the chords over this much of the branch (pen widths) on
/// each side of its vertex, the scale at which a junction's branch directions are measured.
const CORNER_ARM_IN_PEN_WIDTHS: f64 = 2.0;

/// The cross-section's direction is taken from the points this far (in pen widths) before and
/// after the measured point: past a pixel step, within a curve's bend.
const NORMAL_SPAN_IN_PEN_WIDTHS: f64 = 1.0;

/// The cross-section's direction is taken over at least this many skeleton points each way:
/// the step to the next pixel alone points only in one of the grid's eight directions.
const MIN_NORMAL_SPAN_POINTS: usize = 2;

/// Cross-sections are not followed further than this (in pen widths) from the centre line: a
/// blob of ink or a filled area is not a band.
const MAX_CROSS_WIDTH_IN_PEN_WIDTHS: f64 = 6.0;

/// What a band is judged against: the page's ink and typical stroke.
struct BandJudge {
    /// The ink widths across each branch's points, by branch, measured once before any branch
    /// is split (a split changes only the branch it splits, and adds its sides after these).
    widths: Vec<Vec<Option<f64>>>,
    /// The page's typical stroke width, as the cross-sections measure it.
    typical: f64,
    stroke_width: f64,
    /// Points per stretch the width is averaged over.
    stretch: usize,
    /// The longest stretch of a band's centre line (pixels) along which one of its sides may
    /// have a gap ([`BAND_GAP_REACH_IN_PEN_WIDTHS`]).
    side_lift: f64,
}

impl BandJudge {
    /// Whether ink of these widths along a branch is a band: its widest stretch clearly wider
    /// than one stroke ([`DOUBLE_WIDTH_RATIO`], [`DOUBLE_MIN_EXCESS_PX`]).
    fn is_band(&self, widths: &[Option<f64>]) -> bool {
        self.is_wide(widest_stretch(widths, self.stretch))
    }

    /// Whether a stretch's mean width is clearly wider than one stroke ([`DOUBLE_WIDTH_RATIO`],
    /// [`DOUBLE_MIN_EXCESS_PX`]).
    fn is_wide(&self, mean: f64) -> bool {
        mean >= DOUBLE_WIDTH_RATIO * self.typical && mean >= self.typical + DOUBLE_MIN_EXCESS_PX
    }
}

/// A lone dash whose end lies this near (pen widths) to a band's tip is judged as the band's
/// next piece: gaps in a skip-stroke sketch are a few pen widths long.
const BAND_GAP_REACH_IN_PEN_WIDTHS: f64 = 5.0;

/// A branch is judged only if this many stretches of it lie clear of junctions: a spike or a
/// leg is several pen widths long, while the stub a contact between two curves leaves in the
/// skeleton is short and all contact ink (and lies within the junction's clearance,
/// [`JUNCTION_CLEARANCE_IN_PEN_WIDTHS`], which is not measured).
// DECISION: (stop 30) one stretch, not two. A spike 30 px long drawn with a 5–7 px pen is six
// pen widths or less; two of them lie in the junction's clearance, and its points, a diagonal's
// 1.4 px apart, then cover fewer than two stretches' worth: a thick spike whose tip stretch is
// 1.4 times the pen wide stayed a stem. Measured on the benchmark: seeds 1, 3, 5 358 → 360,
// 349 → 352, 344 → 347 (spikes, meanders, an arch, a dumbbell's neck, an animal; one animal lost
// on seed 1), validation 344 → 346, seed 4 342 → 345, none lost there.
const MIN_MEASURED_STRETCHES: usize = 1;

/// A lone dash is a band over one end ([`band_end_cut`]) where its wide stretches run on for at
/// least this many stretches ([`DOUBLE_STRETCH_IN_PEN_WIDTHS`] each) ...
// DECISION: (stop 26) two stretches of window starts, so the wide ink runs on for about six pen
// widths: a corner's cross-section, which crosses the other arm, is wide for one or two, and a
// stroke whose end hooks back on itself (pen jitter at a pen lift) for about as much. Measured on
// seeds 1 and 3: one stretch breaks two line-art drawings on each (a hooked star arm, a nested
// triangle's corner), three fixes one spike fewer; no line-art dash of seeds 1, 2 or 3 is cut.
const BAND_END_MIN_RUN_IN_STRETCHES: usize = 2;

/// A branch from a junction to a free end, found a band ([`BandJudge::is_band`]), is cut where
/// its band ends ([`band_end_cut`]) when the band's wide windows run on for at least this many
/// stretches; otherwise it is split into two sides all along.
// DECISION: (stop 33) one stretch, where a lone dash needs two: the branch is a band already
// (its widest stretch is clearly wide), and what is decided is only where its band ends, not
// whether it is one; the corner or hooked end that two stretches keep out of a lone dash's
// bands is no question here. Two spiral turns that touch for a few pen widths next to the
// junction where they part, on a thin pen, were split into two sides all along the turn.
// Measured on the benchmark: seeds 1, 3, 5 368, 361 → 363 (an animal, a spike), 356;
// validation 356 → 357 (+3 −2), seed 4 356 → 358.
const BAND_END_MIN_RUN_FROM_JUNCTION_IN_STRETCHES: usize = 1;

/// ... the dash's end beyond them (a spike's tip, where its two sides close in to one pen width)
/// is at most this share of their run ...
// DECISION: (stop 26) a straight-sided spike is wider than 1.3 strokes over about 70 % of the way
// from its tip to where its sides part, so its tip is about 0.4 of the run; twice the run leaves
// room for jitter and still says which end of the dash the band is at. 1.5 to 3 and no limit at
// all measured the same on seeds 1 and 3.
const BAND_END_MAX_TIP_SHARE: f64 = 2.0;

/// ... and the stroke on its other side is at least this many stretches long.
const BAND_END_MIN_STROKE_IN_STRETCHES: usize = 2;

/// Which side of a band the stroke beyond its cut goes on from is seen this far (pen widths)
/// along the stroke: the side whose end lies nearer that point.
// DECISION: (stop 33) three pen widths, not one and a half: a band is up to two pen widths
// across, and a point one and a half on still lies in its ink, where a stroke that leaves at a
// slant can be as near the far side's end. Measured on the benchmark: seeds 1, 3, 5 368, 360 →
// 361 (a spike), 356; validation 355 → 356, seed 4 356; none lost; 2.5 and 4 pen widths
// measured the same.
const SIDE_PROBE_IN_PEN_WIDTHS: f64 = 3.0;

/// A band cut where it ends ([`band_end_cut`]) is cut at the end of its last wide window, up to
/// a stretch past where its ink is last two strokes wide; where one of two merged lines ends
/// (a meander's or a spike's line parting across a pen lift) the skeleton slides across onto the
/// line that goes on over that stretch, and the side that ends free slid with it, a band's spacing
/// off its own line, so that its bridge across the lift dipped over the other line. That side
/// ends at the band's last point at least this share of its spacing wider than one stroke.
// DECISION: (stop 61) half the spacing, the midpoint between two strokes side by side and one.
// Measured on the benchmark (with the move below at 1.1): development +7 (four thick meanders,
// two scanned ones, a spike page), none lost; at 0.35 +5; at 0.65 +7 −4 (the smoothed end of a
// band still two strokes wide cut back: a scanned meander, thin spikes).
const FREE_SIDE_MIN_SPACING_SHARE: f64 = 0.5;

/// ... where that moves the side's end by at least this much (pen widths): a thinner move is
/// within the pen's round cap and the pixel steps of a thin pen's band, and moved ends there
/// only reshuffle later pairings.
// DECISION: (stop 61) measured on the benchmark: 0.9 and 1.0 development +8 −1 (a thin spike
// whose two sides coincide towards its tip, moved 1.06 pen widths, lost; a thin animal gained),
// 1.1 +7 −0, 1.25 +4 −0; with no floor +8 −4 (moves of one or two points on thin pens).
const FREE_SIDE_MIN_MOVE_IN_PEN_WIDTHS: f64 = 1.1;

/// A band out of a junction whose stroke beyond is shorter than
/// [`BAND_END_MIN_STROKE_IN_STRETCHES`] (but at least one stretch) is still cut where it ends
/// when that stroke leaves the band's centre line by at least this share of half its spacing
/// ([`parts_from_band`]): it goes on along one side's line or away from the band, where one of
/// two merged lines parts from the other at a pen lift; a hairpin's or thin spike's tip, whose
/// two sides close in, runs on along the middle.
// DECISION: (stop 61) one half spacing, the line of a side. Measured on the benchmark: development
// +2 (two thick meanders, the tail 2.9 px off the centre line on a 2.0 px half spacing, and one
// turning away), nothing lost; 1.0 to 1.4 the same; 0.75 loses a scanned meander (0.76); 1.6
// loses a thick meander. A thin meander's hairpin tip runs on at 0.0.
const PARTING_MIN_OFFSET_IN_HALF_SPACINGS: f64 = 1.0;

/// ... and that stroke is at least this many stretches long (one stroke's width over a stretch
/// is what tells it from the band at all).
const PARTING_MIN_STROKE_IN_STRETCHES: usize = 1;

/// The two sides of a band are at least this far (pixels) to either side of its centre line,
/// where the band is hardly wider than one stroke (a spike's tip): two curves, not one.
const MIN_SIDE_OFFSET_PX: f64 = 0.35;

/// The width is averaged over at least this many points, so that no single pixel step decides
/// it, however thin the pen.
const MIN_STRETCH_POINTS: usize = 2;

/// Each side of a band lies at most this far (in pen widths) from its centre line: two pens that
/// merged into one band lie half a pen width to either side of its middle, and a cross-section
/// that ran on into other ink asks for more.
const MAX_SIDE_OFFSET_IN_PEN_WIDTHS: f64 = 1.0;

/// The step along a cross-section, in pixels: fine enough that averaging over a stretch gives
/// sub-pixel widths.
const CROSS_STEP_PX: f64 = 0.25;

/// The width of ink across `point` along the unit vector `normal`, in steps of
/// [`CROSS_STEP_PX`] and at most [`MAX_CROSS_WIDTH_IN_PEN_WIDTHS`]; 0 off the ink. The measure a
/// band is told by, here and where the crawl's collapsed spikes are ([`crate::crawl::spikes`]).
pub(crate) fn ink_width_across(
    mask: &Bitmap,
    point: Point,
    normal: Vec2,
    stroke_width: f64,
) -> f64 {
    let reach = MAX_CROSS_WIDTH_IN_PEN_WIDTHS * stroke_width / 2.0;
    mask.ink_across(point, normal, CROSS_STEP_PX, reach)
}

/// How many skeleton points (a pixel apart, or a diagonal's) cover `length` pixels: at least
/// `min`.
fn skeleton_points(length: f64, min: usize) -> usize {
    (length.ceil() as usize).max(min)
}

/// The unit normal (left of the direction of travel) at `points[k]`, from the points
/// [`NORMAL_SPAN_IN_PEN_WIDTHS`] before and after it; `None` where they coincide.
fn normal_at(points: &[Point], k: usize, stroke_width: f64) -> Option<Vec2> {
    let span = skeleton_points(
        NORMAL_SPAN_IN_PEN_WIDTHS * stroke_width,
        MIN_NORMAL_SPAN_POINTS,
    );
    let last = points.len().saturating_sub(1);
    let along = points[(k + span).min(last)] - points[k.saturating_sub(span)];
    let length = along.hypot();
    (length > 0.0).then(|| Vec2::new(-along.y / length, along.x / length))
}

/// The vertices of `points` (a branch's skeleton pixels) where it turns a corner: turning by
/// [`CORNER_MIN_TURN_DEGREES`]–[`CORNER_MAX_TURN_DEGREES`] between the chords over `arm` pixels
/// before and after, and more than anywhere within `arm` along it (one vertex per corner; the
/// earlier of equal turns).
fn corner_vertices(points: &[Point], arm: f64) -> Vec<Point> {
    let turns: Vec<Option<f64>> = (0..points.len())
        .map(|k| {
            let here = points[k];
            let before = (0..k).rev().find(|&j| points[j].distance(here) >= arm)?;
            let after = (k + 1..points.len()).find(|&j| points[j].distance(here) >= arm)?;
            let turn = signed_turn(here - points[before], points[after] - here);
            Some(turn.abs().to_degrees())
        })
        .collect();
    let window = skeleton_points(arm, MIN_NORMAL_SPAN_POINTS);
    (0..points.len())
        .filter(|&k| {
            let Some(turn) = turns[k] else { return false };
            let (lo, hi) = (k.saturating_sub(window), (k + window).min(points.len() - 1));
            let sharpest = (lo..=hi).all(|j| match turns[j] {
                Some(other) => other < turn || (other == turn && j >= k),
                None => true,
            });
            sharpest && (CORNER_MIN_TURN_DEGREES..=CORNER_MAX_TURN_DEGREES).contains(&turn)
        })
        .map(|k| points[k])
        .collect()
}

/// The ink width across each point of `points` (skeleton pixel centres along a branch); `None`
/// where the direction is undefined.
fn widths_along(mask: &Bitmap, points: &[Point], stroke_width: f64) -> Vec<Option<f64>> {
    (0..points.len())
        .map(|k| {
            normal_at(points, k, stroke_width)
                .map(|normal| ink_width_across(mask, points[k], normal, stroke_width))
        })
        .collect()
}

/// The widest mean width over any run of `stretch` consecutive measured points; 0 when fewer
/// than [`MIN_MEASURED_STRETCHES`] stretches were measured (a stub next to a junction is all
/// junction ink).
fn widest_stretch(widths: &[Option<f64>], stretch: usize) -> f64 {
    let measured: Vec<f64> = widths.iter().flatten().copied().collect();
    if measured.len() < MIN_MEASURED_STRETCHES * stretch.max(1) {
        return 0.0;
    }
    measured
        .windows(stretch.max(1))
        .map(|run| run.iter().sum::<f64>() / run.len() as f64)
        .fold(0.0, f64::max)
}

/// A band over one end of a dash: it runs from that end to the point at this index (counted
/// from the dash's start, or from its end).
enum BandEnd {
    AtStart(usize),
    AtEnd(usize),
}

/// Which band's end is looked for: a lone dash's, or a band's out of a junction (a branch from
/// a junction to a free end).
#[derive(Clone, Copy, PartialEq)]
enum BandOf {
    LoneDash,
    Junction,
}

impl BandOf {
    /// The fewest stretches the band's wide windows run on for.
    fn min_run(self) -> usize {
        match self {
            BandOf::LoneDash => BAND_END_MIN_RUN_IN_STRETCHES,
            BandOf::Junction => BAND_END_MIN_RUN_FROM_JUNCTION_IN_STRETCHES,
        }
    }
}

/// Where a dash with these widths is a band over one end and one stroke over the rest: the
/// longest run of stretches wider than one stroke ([`BandJudge::is_wide`]) is at least
/// [`BandOf::min_run`] stretches long ([`BAND_END_MIN_RUN_IN_STRETCHES`] for a lone dash,
/// [`BAND_END_MIN_RUN_FROM_JUNCTION_IN_STRETCHES`] for a band out of a junction), the end beyond
/// it (a spike's tip, where its sides close in) no longer than [`BAND_END_MAX_TIP_SHARE`] of the
/// run, and the stroke on the other side at least [`BAND_END_MIN_STROKE_IN_STRETCHES`] long. The
/// nearer end wins when both would do.
///
/// DECISION: (stop 32) runs that are wide all along (their median width) with at most
/// [`BAND_GAP_REACH_IN_PEN_WIDTHS`] of one stroke's width between them are read as one band,
/// counted by their wide windows: a narrow spike whose one side has a pen lift halfway narrows to
/// one stroke there, and neither piece alone is long enough. The median keeps out two corners a few
/// pen widths apart, whose cross-sections are wide only where they run along the other arm (a thick
/// star's tip and the next notch: without it, one star lost on seed 1). Measured on the benchmark:
/// seed 5 349 → 352 (three spikes), seeds 1 and 3, validation and seed 4 unchanged; none lost.
///
/// DECISION: (stop 37) the band read across such lifts is tried before the longest run alone:
/// it says which end of the dash the band is at, where the longest run alone can lie midway. A
/// stroke along a body's outline that turns a corner into a narrow finger, one of whose sides
/// has a pen lift halfway, had its longest run between the corner and the lift, as near the
/// stroke's end as the finger's tip; the nearer end won, and the body's stroke was cut into
/// a band's two sides, whose second end took the finger's side away from its corner. Measured on the
/// benchmark: seeds 1, 3, 5 376 → 377, 367 → 368, 364 → 364 (three meanders fixed, a thin spike
/// lost by 0.3 px); validation 364 → 366, seed 4 366 → 366.
fn band_end_cut(widths: &[Option<f64>], judge: &BandJudge, of: BandOf) -> Option<BandEnd> {
    band_end_cut_with(widths, judge, of, BAND_END_MIN_STROKE_IN_STRETCHES)
}

/// [`band_end_cut`] with the stroke beyond the band at least `min_stroke` stretches long.
fn band_end_cut_with(
    widths: &[Option<f64>],
    judge: &BandJudge,
    of: BandOf,
    min_stroke: usize,
) -> Option<BandEnd> {
    let stretch = judge.stretch.max(1);
    let n = widths.len();
    if n < stretch {
        return None;
    }
    let wide_window = |k: usize| {
        // Summed in place, not collected first: this runs at every window of every stroke.
        let window = &widths[k..k + stretch];
        let measured = window.iter().flatten().count();
        // Half the window unmeasured (the direction undefined) says nothing.
        if 2 * measured < stretch {
            return false;
        }
        judge.is_wide(window.iter().flatten().sum::<f64>() / measured as f64)
    };
    // The runs of wide windows (a corner's cross-section is wide for a pen width or two, as it
    // crosses the other arm; a band's for many), as window starts from..to.
    let mut runs: Vec<(usize, usize)> = Vec::new();
    let mut k = 0;
    while k + stretch <= n {
        let start = k;
        while k + stretch <= n && wide_window(k) {
            k += 1;
        }
        if k > start {
            runs.push((start, k));
        }
        k += 1;
    }
    // Runs with a short stretch of one stroke's width between them, read as one band whose side
    // has a gap there, where each is wide all along (its median width: a corner's cross-section
    // is wide only where it crosses the other arm); then the longest run alone.
    let longest = runs
        .iter()
        .rev()
        .max_by_key(|&&(start, end)| end - start)
        .copied()?;
    let max_lift = skeleton_points(judge.side_lift, 1);
    let wide_all_along = |&(start, end): &(usize, usize)| {
        let mut measured: Vec<f64> = widths[start..end + stretch - 1]
            .iter()
            .flatten()
            .copied()
            .collect();
        measured.sort_by(f64::total_cmp);
        !measured.is_empty() && judge.is_wide(measured[measured.len() / 2])
    };
    let mut lifted: Vec<(usize, usize, usize)> = Vec::new();
    for run in runs.iter().filter(|run| wide_all_along(run)) {
        let (start, end) = *run;
        match lifted.last_mut() {
            Some((_, to, wide)) if start <= *to + stretch - 1 + max_lift => {
                *to = end;
                *wide += end - start;
            }
            _ => lifted.push((start, end, end - start)),
        }
    }
    let merged = lifted
        .iter()
        .rev()
        .max_by_key(|&&(_, _, wide)| wide)
        .filter(|&&(from, to, wide)| wide < to - from);
    merged
        .copied()
        .into_iter()
        .chain(std::iter::once((
            longest.0,
            longest.1,
            longest.1 - longest.0,
        )))
        .find_map(|(from, to, wide)| {
            // DECISION: (stop 61) out of a junction, the stroke beyond the band holds no other
            // band: a spike's side with a pen lift halfway is wide again beyond the lift, and with
            // the stroke measured from the windows' centres (below) its first piece alone was cut
            // (a scanned spike page lost on seed 5).
            let other_band = |beyond: &dyn Fn(&(usize, usize)) -> bool| {
                of == BandOf::Junction && runs.iter().any(|run| beyond(run) && wide_all_along(run))
            };
            match band_over_one_end(from, to, wide, n, stretch, of, min_stroke) {
                Some(BandEnd::AtStart(_)) if other_band(&|run| run.0 > to) => None,
                Some(BandEnd::AtEnd(_)) if other_band(&|run| run.1 < from) => None,
                cut => cut,
            }
        })
}

/// Whether the stroke beyond a band at the start of `points` (a branch from a junction to a
/// free end) leaves the band's centre line, as the band ran one to three stretches before its
/// last wide point, by at least [`PARTING_MIN_OFFSET_IN_HALF_SPACINGS`] of half the band's
/// spacing on average over its first two stretches: one of two merged lines going on, not a
/// hairpin's two sides closing in to its tip along the middle.
fn parts_from_band(points: &[Point], widths: &[Option<f64>], judge: &BandJudge) -> bool {
    let stretch = judge.stretch.max(1);
    let n = points.len();
    let Some(last_wide) = (0..n)
        .rev()
        .find(|&k| widths[k].is_some_and(|w| judge.is_wide(w)))
    else {
        return false;
    };
    // The band's centre line: the chord one to three stretches before its last wide point.
    let (from, to) = (
        last_wide.saturating_sub(3 * stretch),
        last_wide.saturating_sub(stretch),
    );
    if to <= from || last_wide + 1 >= n {
        return false;
    }
    let (chord_start, chord) = (points[from], points[to] - points[from]);
    let chord_length = chord.hypot();
    if chord_length <= 0.0 {
        return false;
    }
    // Half the band's spacing: its median wide width less one stroke, halved (`last_wide` is
    // wide, so there is one).
    let mut wide: Vec<f64> = widths
        .iter()
        .flatten()
        .copied()
        .filter(|&w| judge.is_wide(w))
        .collect();
    wide.sort_by(f64::total_cmp);
    let half_spacing = (wide[wide.len() / 2] - judge.typical) / 2.0;
    let tail = &points[last_wide + 1..(last_wide + 1 + 2 * stretch).min(n)];
    let mean_offset = tail
        .iter()
        .map(|&p| ((p - chord_start).cross(chord) / chord_length).abs())
        .sum::<f64>()
        / tail.len() as f64;
    mean_offset >= PARTING_MIN_OFFSET_IN_HALF_SPACINGS * half_spacing
}

/// The band over one end of a dash of `n` points whose band has wide windows (starts) from..to,
/// `wide` of them wide ([`band_end_cut`]).
fn band_over_one_end(
    from: usize,
    to: usize,
    wide: usize,
    n: usize,
    stretch: usize,
    of: BandOf,
    min_stroke: usize,
) -> Option<BandEnd> {
    let run = to - from;
    if wide == 0 || wide < of.min_run() * stretch {
        return None;
    }
    // The wide points are from..to + stretch - 1; the tip lies beyond them, the stroke on the
    // other side.
    let last_wide = to + stretch - 2;
    let (mut tip_at_start, mut tip_at_end) = (from, n - 1 - last_wide);
    // DECISION: (stop 61) a band out of a junction measures the stroke beyond it from its wide
    // windows' centres, not their starts, which lie half a stretch into the stroke: a thick
    // meander's line parting from the band, 21 points one stroke wide, counted 15 (seed 6).
    if of == BandOf::Junction {
        tip_at_start = from + stretch / 2;
        tip_at_end += (stretch - 1) / 2;
    }
    let min_stroke = min_stroke * stretch;
    let short_tip = |tip: usize| tip as f64 <= BAND_END_MAX_TIP_SHARE * run as f64;
    let at_start = short_tip(tip_at_start) && tip_at_end >= min_stroke;
    let at_end = short_tip(tip_at_end) && tip_at_start >= min_stroke;
    match (at_start, at_end) {
        (true, false) => Some(BandEnd::AtStart(last_wide)),
        (false, true) => Some(BandEnd::AtEnd(n - 1 - from)),
        (true, true) if tip_at_start <= tip_at_end => Some(BandEnd::AtStart(last_wide)),
        (true, true) => Some(BandEnd::AtEnd(n - 1 - from)),
        (false, false) => None,
    }
}

impl SkeletonGraph {
    /// Finds the double strands and replaces each by its two sides ([`Self::split_into_sides`]):
    /// first among the branches that end at a junction, then among lone dashes that continue a
    /// band across a gap (a band's piece beyond a pen lift), piece after piece.
    pub(super) fn split_double_strands(&mut self, mask: &Bitmap, stroke_width: f64) {
        if stroke_width <= 0.0 {
            return;
        }
        let widths: Vec<Vec<Option<f64>>> = self
            .branches
            .iter()
            .map(|branch| {
                if branch.removed {
                    Vec::new()
                } else {
                    widths_along(mask, &branch.points, stroke_width)
                }
            })
            .collect();
        let Some(typical) = typical_width(&widths) else {
            return;
        };
        let mut judge = BandJudge {
            widths,
            typical,
            stroke_width,
            stretch: skeleton_points(
                DOUBLE_STRETCH_IN_PEN_WIDTHS * stroke_width,
                MIN_STRETCH_POINTS,
            ),
            side_lift: BAND_GAP_REACH_IN_PEN_WIDTHS * stroke_width,
        };
        let mut tips: Vec<Point> = Vec::new();
        for b in 0..self.branches.len() {
            let Some((a, z)) = self.branches[b].nodes else {
                continue;
            };
            // DECISION: a dash on its own is not judged unless it goes on from a band's tip:
            // skip-stroke drawings are made of dashes, and a dash a little wider in places (a
            // pen pressing harder) is far more common than a band cut off on both sides.
            if self.degree(a) >= 3 || self.degree(z) >= 3 {
                tips.extend(self.split_if_double(b, &mut judge));
            }
        }
        let reach = BAND_GAP_REACH_IN_PEN_WIDTHS * stroke_width;
        while !tips.is_empty() {
            // The tips bucketed by position: a page of noise has thousands of them.
            let mut tip_grid = PointGrid::new(reach.max(1.0));
            for &tip in &tips {
                tip_grid.insert(tip, tip);
            }
            let near_a_tip = |p: Point| {
                tip_grid
                    .around(p)
                    .any(|tip: &Point| tip.distance(p) <= reach)
            };
            let mut new_tips = Vec::new();
            for b in 0..self.branches.len() {
                let Some((a, z)) = self.branches[b].nodes else {
                    continue;
                };
                let lone = self.degree(a) == 1 && self.degree(z) == 1;
                if !lone || self.branches[b].strand_of.is_some() {
                    continue;
                }
                let (pa, pz) = (self.nodes[a].position, self.nodes[z].position);
                if !near_a_tip(pa) && !near_a_tip(pz) {
                    continue;
                }
                // DECISION: (stop 33) a piece that is a band over one end only and one stroke
                // over the rest ([`band_end_cut`]) is not split whole: it is cut where the band
                // ends ([`Self::split_band_end`], below), so that the stroke goes on from one
                // side. Split whole, a thin leg beyond a pen lift and the body's line the pen
                // drew on into it became two sides all along that line, ending side by side
                // where one stroke ends. Measured on the benchmark: all five splits unchanged
                // in count (the leg's top in `--debug` pictures traced right, on an animal that
                // fails elsewhere).
                let band_over_one_end = judge
                    .widths
                    .get(b)
                    .is_some_and(|widths| band_end_cut(widths, &judge, BandOf::LoneDash).is_some());
                if !band_over_one_end {
                    new_tips.extend(self.split_if_double(b, &mut judge));
                }
            }
            tips = new_tips;
        }
        self.join_lone_dashes(mask, &mut judge);
        // A dash whose one end is a band and the rest one stroke: a spike drawn up one side,
        // round its tip and back, whose base is where the pen lifted.
        for b in 0..self.branches.len() {
            self.split_band_end(b, &mut judge);
        }
        // The lone dashes left that are bands all the same: not split (nothing says which way
        // their outline runs), but marked, for the crawl to splice into the outline they stand
        // on ([`crate::crawl`]'s lone bands).
        for b in 0..self.branches.len() {
            let Some((a, z)) = self.branches[b].nodes else {
                continue;
            };
            let branch = &self.branches[b];
            let lone = self.degree(a) == 1 && self.degree(z) == 1 && a != z;
            if lone && !branch.removed && branch.strand_of.is_none() {
                self.branches[b].wide = judge.widths.get(b).is_some_and(|w| judge.is_band(w));
            }
        }
    }

    /// DECISION: (stop 32) a dash whose skeleton still has a node where a spur was pruned (the
    /// junction of a stub that the pen's overshoot left, now joining two branches only) is
    /// judged as one dash: a spike's side that runs on along the body as one stroke, whose
    /// other side's stub at the base was pruned, is then a band over one end of that dash
    /// ([`band_end_cut`]) like any other, not a branch between a free end and a node of two.
    fn join_lone_dashes(&mut self, mask: &Bitmap, judge: &mut BandJudge) {
        for node in 0..self.nodes.len() {
            if self.degree(node) != 2 || !self.on_a_lone_dash(node) {
                continue;
            }
            if let Some(joined) = self.dissolve_pass_through_node(node) {
                if judge.widths.len() <= joined {
                    judge.widths.resize(joined + 1, Vec::new());
                }
                judge.widths[joined] =
                    widths_along(mask, &self.branches[joined].points, judge.stroke_width);
            }
        }
    }

    /// Whether the node of two branch ends `node` lies on a dash: going from it both ways
    /// through nodes of two, each way ends in a free end, through branches that are no band's
    /// sides.
    fn on_a_lone_dash(&self, node: usize) -> bool {
        self.nodes[node].ends.iter().all(|&(start, _)| {
            let (mut branch, mut from) = (start, node);
            loop {
                let Some((a, z)) = self.branches[branch].nodes else {
                    return false;
                };
                if self.branches[branch].strand_of.is_some() || a == z {
                    return false;
                }
                let next = if a == from { z } else { a };
                match self.nodes[next].ends[..] {
                    _ if next == node => return false,
                    [_] => return true,
                    [(first, _), (second, _)] if first != second => {
                        branch = if first == branch { second } else { first };
                        from = next;
                    }
                    _ => return false,
                }
            }
        })
    }

    /// Reverses `b`'s direction of travel (its points and its nodes' ends).
    pub(super) fn reverse_branch(&mut self, b: usize) {
        let Some((a, z)) = self.branches[b].nodes else {
            return;
        };
        self.branches[b].points.reverse();
        self.branches[b].nodes = Some((z, a));
        for node in [a, z] {
            for end in self.nodes[node].ends.iter_mut() {
                if end.0 == b {
                    end.1 = !end.1;
                }
            }
        }
    }

    /// Where a lone dash is a band over one end and one stroke over the rest (a narrow spike
    /// drawn up one side, round its tip and back, ending where the pen lifted at its base), cuts
    /// it where the band ends and splits the band into its two sides: the side the stroke runs
    /// on goes on into it, the other ends free at the cut (to cross the pen lift).
    fn split_band_end(&mut self, b: usize, judge: &mut BandJudge) {
        let branch = &self.branches[b];
        let Some((a, z)) = branch.nodes else {
            return;
        };
        let lone = self.degree(a) == 1 && self.degree(z) == 1;
        if branch.removed || a == z || branch.strand_of.is_some() || !lone {
            return;
        }
        let Some(cut) = band_end_cut(&judge.widths[b], judge, BandOf::LoneDash) else {
            return;
        };
        self.cut_band_end(b, cut, judge);
    }

    /// Cuts branch `b` where its band over one end ends (`cut`, on the widths in
    /// `judge.widths[b]`) and splits the band into its two sides: the side the stroke runs on
    /// goes on into it, the other ends free at the cut; returns that free end.
    fn cut_band_end(&mut self, b: usize, cut: BandEnd, judge: &mut BandJudge) -> Point {
        let cut = match cut {
            BandEnd::AtStart(cut) => cut,
            BandEnd::AtEnd(cut) => {
                self.reverse_branch(b);
                judge.widths[b].reverse();
                cut
            }
        };
        // The band runs from the dash's start to `cut`: it becomes a branch of its own, joined
        // to the rest (the stroke) by a node at the cut.
        let (start_node, end_node) = self.branches[b].nodes.expect("checked above");
        let points = std::mem::take(&mut self.branches[b].points);
        let widths = std::mem::take(&mut judge.widths[b]);
        let (cut_node, band) = (self.nodes.len(), self.branches.len());
        self.nodes.push(Node {
            position: points[cut],
            ends: vec![(band, false), (b, true)],
            pruned: false,
        });
        for end in self.nodes[start_node].ends.iter_mut() {
            if end.0 == b {
                end.0 = band;
            }
        }
        self.branches[b].points = points[cut..].to_vec();
        self.branches[b].nodes = Some((cut_node, end_node));
        judge.widths[b] = widths[cut..].to_vec();
        self.branches.push(Branch {
            points: points[..=cut].to_vec(),
            nodes: Some((start_node, cut_node)),
            removed: false,
            strand_of: None,
            side: 0.0,
            wide: false,
        });
        let band_widths = widths[..=cut].to_vec();
        self.bands.push(points[..=cut].to_vec());
        let offsets = side_offsets(
            &band_widths,
            judge.typical,
            judge.stretch,
            judge.stroke_width,
        );
        let right = self.split_into_sides(band, &offsets, judge.stroke_width);
        // The stroke goes on from the side it lies on, as seen [`SIDE_PROBE_IN_PEN_WIDTHS`] on:
        // the cut node goes to that side, and the other side's end is the free one.
        let stroke = &self.branches[b].points;
        let probe = stroke[skeleton_points(SIDE_PROBE_IN_PEN_WIDTHS * judge.stroke_width, 2)
            .min(stroke.len() - 1)];
        let left_end = *self.branches[band]
            .points
            .last()
            .expect("sides have points");
        let right_end = *self.branches[right]
            .points
            .last()
            .expect("sides have points");
        if probe.distance(right_end) < probe.distance(left_end) {
            let (left_start, on_stroke) = self.branches[band].nodes.expect("sides have nodes");
            let (right_start, free) = self.branches[right].nodes.expect("sides have nodes");
            self.branches[band].nodes = Some((left_start, free));
            self.branches[right].nodes = Some((right_start, on_stroke));
            for (node, from, to) in [(on_stroke, band, right), (free, right, band)] {
                for end in self.nodes[node].ends.iter_mut() {
                    if end.0 == from {
                        end.0 = to;
                    }
                }
            }
            self.nodes[on_stroke].position = right_end;
            self.nodes[free].position = left_end;
            return self.end_where_band_ends(band, &points[..=cut], &band_widths, &offsets, judge);
        }
        self.end_where_band_ends(right, &points[..=cut], &band_widths, &offsets, judge)
    }

    /// The side `side` that ends free where a band was cut ([`Self::cut_band_end`]) ends where
    /// the band is last two strokes wide: at the last point of the band's last stretch whose
    /// width still holds [`FREE_SIDE_MIN_SPACING_SHARE`] of the spacing between its two sides
    /// (twice their usual offset over the last two stretches), put at that usual offset from the
    /// centre line, where that moves its end by at least [`FREE_SIDE_MIN_MOVE_IN_PEN_WIDTHS`].
    /// Returns the side's free end.
    fn end_where_band_ends(
        &mut self,
        side: usize,
        band: &[Point],
        widths: &[Option<f64>],
        offsets: &[f64],
        judge: &BandJudge,
    ) -> Point {
        let last = offsets.len() - 1;
        let mut near: Vec<f64> = offsets[last.saturating_sub(2 * judge.stretch)..].to_vec();
        near.sort_by(f64::total_cmp);
        let usual = near[near.len() / 2];
        let min_width = judge.typical + FREE_SIDE_MIN_SPACING_SHARE * 2.0 * usual;
        let keep = (last.saturating_sub(judge.stretch).max(1)..=last)
            .rev()
            .find(|&k| widths[k].is_some_and(|w| w >= min_width))
            .unwrap_or(last);
        let points = &mut self.branches[side].points;
        let across = points[keep] - band[keep];
        if keep < last && across.hypot() > 0.0 {
            let end = band[keep] + across * (usual.max(offsets[keep]) / across.hypot());
            if end.distance(points[last]) >= FREE_SIDE_MIN_MOVE_IN_PEN_WIDTHS * judge.stroke_width {
                points.truncate(keep + 1);
                points[keep] = end;
            }
        }
        let end = *points.last().expect("sides have points");
        let (_, free) = self.branches[side].nodes.expect("sides have nodes");
        self.nodes[free].position = end;
        end
    }

    /// Splits `branch` into its two sides if it is a double strand; returns the free ends the
    /// sides have (where the band stops), to look for its next piece beyond a gap.
    fn split_if_double(&mut self, b: usize, judge: &mut BandJudge) -> Vec<Point> {
        let branch = &self.branches[b];
        let Some((a, z)) = branch.nodes else {
            return Vec::new();
        };
        if branch.removed || a == z {
            return Vec::new();
        }
        // DECISION: (stop 24) near a junction the other branches' ink widens the cross-section,
        // and so does the other arm's near a corner node (two branches: a thick pen's acute
        // corner, whose spur was folded into it, merges the two arms' ink over several pen
        // widths): not measured there. A thick "A" had its left leg split into two sides from
        // the crossbar up to the apex, one of which the crossbar turned into. Measured on the
        // benchmark: seeds 1 and 3 one drawing better each, none worse; seed 2 unchanged.
        let (a_meets_ink, z_meets_ink) = (self.degree(a) >= 2, self.degree(z) >= 2);
        let clearance = JUNCTION_CLEARANCE_IN_PEN_WIDTHS * judge.stroke_width;
        let (pa, pz) = (self.nodes[a].position, self.nodes[z].position);
        let widths: Vec<Option<f64>> = branch
            .points
            .iter()
            .zip(&judge.widths[b])
            .map(|(p, &width)| {
                let near_other_ink = a_meets_ink && p.distance(pa) <= clearance
                    || z_meets_ink && p.distance(pz) <= clearance;
                width.filter(|_| !near_other_ink)
            })
            .collect();
        if !judge.is_band(&widths) {
            return Vec::new();
        }
        // DECISION: (stop 34) a branch is a band only if it is wide away from its own corners too
        // ([`corner_vertices`]), within the same clearance as a junction's: a scanned "A" whose
        // left leg's upper piece turns into the crossbar in one stroke measured 5–6.5 px across
        // its corner on a 3.25-px pen, and was split into two sides from the leg's top to the
        // right leg. The corner-cleared widths only decide; a band's sides are still placed from
        // all its widths (clearing them moved the sides of bent bands and lost two animals).
        // Measured on the benchmark: seeds 1, 3, 5 368 → 368, 363 → 364, 356 → 357 (that "A" and
        // an arch), validation 357 → 358, seed 4 358 → 358, none lost anywhere.
        let corners = corner_vertices(
            &branch.points,
            CORNER_ARM_IN_PEN_WIDTHS * judge.stroke_width,
        );
        if !corners.is_empty() {
            let off_corners: Vec<Option<f64>> = branch
                .points
                .iter()
                .zip(&widths)
                .map(|(p, &width)| {
                    width.filter(|_| corners.iter().all(|c| c.distance(*p) > clearance))
                })
                .collect();
            if !judge.is_band(&off_corners) {
                return Vec::new();
            }
        }
        // DECISION: (stop 33) a branch from a junction to a free end that is a band over its
        // junction end only and one stroke over the rest ([`band_end_cut`]) is cut where its
        // band ends, as a lone dash is ([`Self::split_band_end`]): the side the stroke runs on
        // goes on into it, the other ends free there. Two lines that run side by side out of a
        // junction and part, one of them broken by a gap where they part (a lasso's two lines
        // leaving its loop, a spiral's arm along its outer turn), were split into two sides all
        // along, both running on along the line that goes on, and the broken line's far piece
        // found no end to go on from. Measured on the benchmark: seeds 1, 3, 5 367 → 368,
        // 360 → 360, 353 → 356 (six meanders and animals fixed; two meanders lost, whose two
        // lines coincide beyond the band and read as one stroke there); validation 354 → 355,
        // seed 4 352 → 356.
        let (a_junction, z_junction) = (self.degree(a) >= 3, self.degree(z) >= 3);
        let (a_free, z_free) = (self.degree(a) == 1, self.degree(z) == 1);
        if (a_junction && z_free) || (z_junction && a_free) {
            let band_at_junction = match band_end_cut(&widths, judge, BandOf::Junction) {
                Some(BandEnd::AtStart(cut)) if a_junction => Some(BandEnd::AtStart(cut)),
                Some(BandEnd::AtEnd(cut)) if z_junction => Some(BandEnd::AtEnd(cut)),
                _ => None,
            };
            let band_at_junction = band_at_junction.or_else(|| {
                match band_end_cut_with(
                    &widths,
                    judge,
                    BandOf::Junction,
                    PARTING_MIN_STROKE_IN_STRETCHES,
                )? {
                    BandEnd::AtStart(cut)
                        if a_junction && parts_from_band(&branch.points, &widths, judge) =>
                    {
                        Some(BandEnd::AtStart(cut))
                    }
                    BandEnd::AtEnd(cut)
                        if z_junction && {
                            let mut p = branch.points.clone();
                            p.reverse();
                            let mut w = widths.clone();
                            w.reverse();
                            parts_from_band(&p, &w, judge)
                        } =>
                    {
                        Some(BandEnd::AtEnd(cut))
                    }
                    _ => None,
                }
            });
            if let Some(cut) = band_at_junction {
                judge.widths[b] = widths;
                return vec![self.cut_band_end(b, cut, judge)];
            }
        }
        self.bands.push(branch.points.clone());
        let offsets = side_offsets(&widths, judge.typical, judge.stretch, judge.stroke_width);
        let right = self.split_into_sides(b, &offsets, judge.stroke_width);
        [b, right]
            .into_iter()
            .flat_map(|side| {
                let (a, z) = self.branches[side].nodes.expect("sides have nodes");
                [a, z]
            })
            .filter(|&node| self.degree(node) == 1)
            .map(|node| self.nodes[node].position)
            .collect()
    }

    /// Replaces the band `branch` by its two sides, offset to either side of its centre line
    /// by `offsets` (one per point): two branches that share the band's junctions, each with
    /// its own free end where the band ends. The sides of a band that ends turn into each other
    /// there unless they go on across a gap ([`crate::crawl`]'s band-tip bridge).
    fn split_into_sides(&mut self, branch: usize, offsets: &[f64], stroke_width: f64) -> usize {
        let (a, z) = self.branches[branch].nodes.expect("bands have nodes");
        let points = &self.branches[branch].points;
        let last = points.len() - 1;
        let side = |sign: f64| -> Vec<Point> {
            (0..points.len())
                .map(|k| {
                    let at_junction =
                        (k == 0 && self.degree(a) >= 3) || (k == last && self.degree(z) >= 3);
                    match normal_at(points, k, stroke_width) {
                        Some(normal) if !at_junction => points[k] + normal * (sign * offsets[k]),
                        _ => points[k],
                    }
                })
                .collect()
        };
        let (left, right) = (side(1.0), side(-1.0));
        // The right side's ends: the band's junctions, or new free ends beside the left side's.
        let right_node = |node: usize, position: Point, at_start: bool, graph: &mut Self| {
            if graph.degree(node) >= 3 {
                graph.nodes[node]
                    .ends
                    .push((graph.branches.len(), at_start));
                node
            } else {
                graph.nodes.push(Node {
                    position,
                    ends: vec![(graph.branches.len(), at_start)],
                    pruned: false,
                });
                graph.nodes.len() - 1
            }
        };
        let right_a = right_node(a, right[0], true, self);
        let right_z = right_node(z, right[last], false, self);
        for (node, position) in [(a, left[0]), (z, left[last])] {
            if self.degree(node) < 3 {
                self.nodes[node].position = position;
            }
        }
        let left_branch = &mut self.branches[branch];
        left_branch.points = left;
        left_branch.strand_of = Some(branch);
        left_branch.side = 1.0;
        self.branches.push(Branch {
            points: right,
            nodes: Some((right_a, right_z)),
            removed: false,
            strand_of: Some(branch),
            side: -1.0,
            wide: false,
        });
        self.branches.len() - 1
    }
}

/// The page's typical stroke width as the cross-sections measure it (the median over every
/// branch point): the same measure as the bands are judged by, so that its pixel bias cancels.
fn typical_width(widths: &[Vec<Option<f64>>]) -> Option<f64> {
    let mut widths: Vec<f64> = widths
        .iter()
        .flatten()
        .flatten()
        .copied()
        .filter(|&w| w > 0.0)
        .collect();
    if widths.is_empty() {
        return None;
    }
    let middle = widths.len() / 2;
    let (_, median, _) = widths.select_nth_unstable_by(middle, f64::total_cmp);
    Some(*median)
}

/// How far each side of a band lies from its centre line, per point: half of what the band is
/// wider than one stroke (the two pens' centre lines), averaged over a stretch; where the width
/// was not measured (next to a junction), the nearest measured value. At least
/// [`MIN_SIDE_OFFSET_PX`], so that the two sides stay two curves, and at most
/// [`MAX_SIDE_OFFSET_IN_PEN_WIDTHS`].
fn side_offsets(
    widths: &[Option<f64>],
    typical: f64,
    stretch: usize,
    stroke_width: f64,
) -> Vec<f64> {
    let measured: Vec<(usize, f64)> = widths
        .iter()
        .enumerate()
        .filter_map(|(k, w)| w.map(|w| (k, w)))
        .collect();
    // Never below the least offset: a pen thinner than that still gets two sides.
    let max_offset = (MAX_SIDE_OFFSET_IN_PEN_WIDTHS * stroke_width).max(MIN_SIDE_OFFSET_PX);
    let half = stretch / 2;
    (0..widths.len())
        .map(|k| {
            let nearest = measured.partition_point(|&(index, _)| index < k);
            let from = nearest.saturating_sub(half);
            let to = (nearest + half + 1).min(measured.len());
            let window = &measured[from.min(to.saturating_sub(1))..to];
            let mean = if window.is_empty() {
                typical
            } else {
                window.iter().map(|&(_, w)| w).sum::<f64>() / window.len() as f64
            };
            ((mean - typical) / 2.0).clamp(MIN_SIDE_OFFSET_PX, max_offset)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{band_end_cut, BandEnd, BandJudge, BandOf, BAND_GAP_REACH_IN_PEN_WIDTHS};
    use crate::raster::bitmap::Bitmap;
    use crate::raster::clean::tests::draw_line;
    use crate::raster::thin::thin;
    use crate::strokes::{extract_strokes, Stroke, StrokeEnd};

    const PEN: f64 = 4.0;

    /// A page `width` px wide with a square outline (pen 4) from (10, 10) to (90, 70).
    fn square_outline(width: usize) -> Bitmap {
        let mut mask = Bitmap::new(width, 80);
        let corners = [(10.0, 10.0), (90.0, 10.0), (90.0, 70.0), (10.0, 70.0)];
        for k in 0..4 {
            draw_line(&mut mask, corners[k], corners[(k + 1) % 4], PEN);
        }
        mask
    }

    /// A square outline (pen 4) with a stroke sticking out of its right side, drawn as the two
    /// lines from (90, 40 ± `half_base`) on the side to a tip at (130, 40).
    fn square_with_spike(half_base: f64) -> Vec<Stroke> {
        let mut mask = square_outline(150);
        draw_line(&mut mask, (90.0, 40.0 - half_base), (130.0, 40.0), PEN);
        draw_line(&mut mask, (90.0, 40.0 + half_base), (130.0, 40.0), PEN);
        extract_strokes(&thin(&mask), &mask, PEN)
    }

    /// How many times `strokes` pass between x and x + 1: one skeleton point each time along a
    /// line across x (two sides of a band in one stroke count twice).
    fn passes(strokes: &[Stroke], x: f64) -> usize {
        strokes
            .iter()
            .flat_map(|s| &s.line.points)
            .filter(|p| p.x > x && p.x < x + 1.0)
            .count()
    }

    /// How many skeleton points of `strokes` lie on the spike's outer half (x > 110): about 20
    /// for each time a stroke runs along it.
    fn points_along_the_spike(strokes: &[Stroke]) -> usize {
        strokes
            .iter()
            .flat_map(|s| &s.line.points)
            .filter(|p| p.x > 110.0)
            .count()
    }

    #[test]
    fn a_thick_acute_corner_is_no_band() {
        // A thick "A" (pen 7): legs meeting at a 37° apex, whose merged ink is up to twice the
        // pen wide, and a crossbar. The legs between the bar and the apex are lines, not bands:
        // each is traced once.
        let pen = 7.0;
        let mut mask = Bitmap::new(120, 120);
        draw_line(&mut mask, (30.0, 110.0), (60.0, 20.0), pen);
        draw_line(&mut mask, (60.0, 20.0), (90.0, 110.0), pen);
        draw_line(&mut mask, (43.0, 70.0), (77.0, 70.0), pen);
        let strokes = extract_strokes(&thin(&mask), &mask, pen);
        for middle in [(50.0, 50.0), (70.0, 50.0)] {
            let through = strokes
                .iter()
                .filter(|s| {
                    s.line
                        .points
                        .iter()
                        .any(|p| (p.x - middle.0).abs() <= 3.0 && (p.y - middle.1).abs() <= 3.0)
                })
                .count();
            assert_eq!(through, 1, "{middle:?}: {strokes:?}");
        }
    }

    #[test]
    fn a_stroke_turning_a_corner_into_a_junction_is_no_band() {
        // A scanned "A" whose left leg's upper piece turns into the crossbar in one stroke
        // (its lower piece beyond a gap), the bar ending on the right leg. The scan's blur fills
        // the corner's inside (a fillet of ink across it), so that across the corner the ink
        // measures up to twice the pen, but the stroke is one line, run along once.
        let pen = 3.0;
        let mut mask = Bitmap::new(120, 120);
        draw_line(&mut mask, (50.0, 25.0), (30.0, 60.0), pen);
        draw_line(&mut mask, (30.0, 60.0), (80.0, 60.0), pen);
        draw_line(&mut mask, (33.0, 54.0), (37.0, 58.5), pen);
        draw_line(&mut mask, (80.0, 10.0), (80.0, 110.0), pen);
        let (strokes, bands) = crate::strokes::extract_strokes_and_bands(&thin(&mask), &mask, pen);
        assert!(bands.is_empty(), "{bands:?}");
        assert_eq!(passes(&strokes, 70.0), 1, "along the bar: {strokes:?}");
    }

    #[test]
    fn a_short_spike_leaving_at_a_slant_is_a_band() {
        // A spike only about six pen widths long, leaving the square's right side at 45°: two of
        // those pen widths lie in the junction's clearance, and its skeleton points, a
        // diagonal's 1.4 px apart, cover little more than one stretch beyond it. Its sides,
        // 8 px apart at the base, merged into one band all the same.
        let mut mask = square_outline(150);
        draw_line(&mut mask, (90.0, 36.0), (110.0, 60.0), PEN);
        draw_line(&mut mask, (90.0, 44.0), (110.0, 60.0), PEN);
        let skeleton = thin(&mask);
        let (strokes, bands) = crate::strokes::extract_strokes_and_bands(&skeleton, &mask, PEN);
        assert_eq!(bands.len(), 1, "{strokes:?}");
    }

    #[test]
    fn a_band_whose_skeleton_has_a_bubble_at_its_base_is_a_band() {
        // The square and a spike whose sides merged (as above), with the skeleton drawn by hand:
        // the spike's centre line splits round a sliver of paper 3 px from the junction and
        // joins again (a bubble). Collapsed, the bubble leaves a node that only passes the line
        // on; the spike is still one branch from its junction to its tip, and a band.
        let mut mask = square_outline(150);
        draw_line(&mut mask, (90.0, 38.5), (130.0, 40.0), PEN);
        draw_line(&mut mask, (90.0, 41.5), (130.0, 40.0), PEN);
        let mut skeleton = Bitmap::new(150, 80);
        for k in 10..=90 {
            for (x, y) in [(k, 10), (k, 70), (10, k.min(70)), (90, k.min(70))] {
                skeleton.set(x, y, true);
            }
        }
        for x in (91..=93).chain(97..=128) {
            skeleton.set(x, 40, true);
        }
        for x in 94..=96 {
            skeleton.set(x, 39, true);
            skeleton.set(x, 41, true);
        }
        let (strokes, bands) = crate::strokes::extract_strokes_and_bands(&skeleton, &mask, PEN);
        assert_eq!(bands.len(), 1, "{strokes:?}");
    }

    #[test]
    fn a_spike_whose_sides_merged_is_a_u_turn_of_the_outline() {
        // Sides 3 px apart at the base (centre to centre): one band of ink, up to 7 px wide.
        // The outline runs out along one side of the band and back along the other: one
        // stroke whose two free ends are the band's tip, side by side.
        let strokes = square_with_spike(1.5);
        assert_eq!(strokes.len(), 1, "{strokes:?}");
        let outline = &strokes[0];
        assert_eq!(outline.ends, [StrokeEnd::Free, StrokeEnd::Free]);
        let (first, last) = (outline.line.points[0], *outline.line.points.last().unwrap());
        assert!(first.x > 124.0 && last.x > 124.0, "{first:?} {last:?}");
        assert!(first.distance(last) <= PEN, "{first:?} {last:?}");
        let along = points_along_the_spike(&strokes);
        assert!((34..=46).contains(&along), "{along} points: out and back");
    }

    /// The paths traced, with default options, from a 150 × 80 page inked where `mask` is.
    fn traced_paths(mask: &Bitmap) -> Vec<crate::output::fit::CurvePath> {
        let image = image::GrayImage::from_fn(150, 80, |x, y| {
            image::Luma([if mask.get(x as usize, y as usize) {
                0
            } else {
                255
            }])
        });
        crate::trace(
            &image::DynamicImage::ImageLuma8(image),
            &crate::TraceOptions::default(),
        )
        .expect("traces")
        .drawing
        .paths
    }

    #[test]
    fn the_traced_spike_closes_at_its_tip() {
        let mut mask = square_outline(150);
        draw_line(&mut mask, (90.0, 38.5), (130.0, 40.0), PEN);
        draw_line(&mut mask, (90.0, 41.5), (130.0, 40.0), PEN);
        // A gap in the top side, so that the drawing has an ordinary pen lift too.
        for x in 40..48 {
            for y in 5..16 {
                mask.set(x, y, false);
            }
        }
        let paths = &traced_paths(&mask);
        assert_eq!(paths.len(), 1, "{paths:?}");
        assert!(paths[0].closed, "{paths:?}");
    }

    /// Traces the square with a spike out of its right side from (90, 38.5) and (90, 41.5) to a
    /// tip at (`tip_x`, 40), with a pen lift in the top side and the ink erased in the
    /// rectangle `lift` (x range, y range), and checks that it comes out as one closed outline
    /// that reaches the tip.
    fn assert_one_outline_through_the_spike(
        tip_x: f64,
        lift: (std::ops::Range<usize>, std::ops::Range<usize>),
    ) {
        let mut mask = square_outline(150);
        draw_line(&mut mask, (90.0, 38.5), (tip_x, 40.0), PEN);
        draw_line(&mut mask, (90.0, 41.5), (tip_x, 40.0), PEN);
        for (xs, ys) in [(40..48, 5..16), lift] {
            for x in xs {
                for y in ys.clone() {
                    mask.set(x, y, false);
                }
            }
        }
        let paths = &traced_paths(&mask);
        assert_eq!(paths.len(), 1, "{paths:?}");
        assert!(paths[0].closed, "{paths:?}");
        let tip = kurbo::Shape::bounding_box(&paths[0].path).max_x();
        assert!(
            tip >= tip_x - 5.0,
            "the spike's tip is cut off at x = {tip}: {paths:?}"
        );
    }

    #[test]
    fn a_spike_at_the_end_of_a_dash_is_traced_out_and_back() {
        // The square's right side comes down and turns out into the spike, whose two sides
        // merged into one band, and the pen lifts at the spike's base: below it the right side
        // starts anew, and the top side has a pen lift too. So the spike is the far end of one
        // dash, one stroke wide over the rest: no junction says where its band begins. The
        // outline goes out along the spike and back, and on across the lift below its base.
        assert_one_outline_through_the_spike(130.0, (85..96, 44..50));
    }

    #[test]
    fn a_dash_whose_skeleton_kept_the_node_of_a_pruned_stub_is_judged_whole() {
        // The dash of the test above (the square's right side turning out into the spike),
        // with a stub of three pixels added to its skeleton above the spike, as a pen's
        // overshoot leaves: pruned as a spur, it leaves a node of two branches, and the dash
        // is still one dash whose far end is a band.
        let mut mask = square_outline(150);
        draw_line(&mut mask, (90.0, 38.5), (130.0, 40.0), PEN);
        draw_line(&mut mask, (90.0, 41.5), (130.0, 40.0), PEN);
        for (xs, ys) in [(40..48, 5..16), (85..96, 44..50)] {
            for x in xs {
                for y in ys.clone() {
                    mask.set(x, y, false);
                }
            }
        }
        let mut skeleton = thin(&mask);
        let bands = |skeleton: &Bitmap| {
            crate::strokes::extract_strokes_and_bands(skeleton, &mask, PEN)
                .1
                .len()
        };
        assert_eq!(bands(&skeleton), 1, "the control: a band without the stub");
        let x = (80..100)
            .rev()
            .find(|&x| skeleton.get(x, 25))
            .expect("the square's right side");
        skeleton.set(x + 1, 25, true);
        skeleton.set(x + 2, 25, true);
        skeleton.set(x + 3, 25, true);
        assert_eq!(bands(&skeleton), 1);
    }

    /// A band judge for a pen of 3.25 px whose stretches are 7 points long.
    fn judge() -> BandJudge {
        BandJudge {
            widths: Vec::new(),
            typical: 3.25,
            stroke_width: 3.25,
            stretch: 7,
            side_lift: BAND_GAP_REACH_IN_PEN_WIDTHS * 3.25,
        }
    }

    /// `count` points of each width, in order.
    fn widths(runs: &[(f64, usize)]) -> Vec<Option<f64>> {
        runs.iter()
            .flat_map(|&(width, count)| std::iter::repeat_n(Some(width), count))
            .collect()
    }

    #[test]
    fn a_band_whose_side_has_a_gap_is_a_band_over_its_dash_end() {
        // A spike at the end of a dash, two pens wide, narrowing to one pen for 8 points where
        // one side has a pen lift: neither piece is long enough to be a band on its own, both
        // together are.
        let spike = widths(&[(6.0, 13), (3.0, 8), (5.5, 14), (3.0, 30)]);
        assert!(
            matches!(
                band_end_cut(&spike, &judge(), BandOf::LoneDash),
                Some(BandEnd::AtStart(cut)) if cut >= 32
            ),
            "the band runs from the tip to the dash's stroke"
        );
        // The control: one pen wide between two points where a corner's cross-section runs
        // along the other arm: wide windows only where the mean takes in the corner.
        let corners = widths(&[(3.0, 40), (12.0, 3), (3.0, 8), (12.0, 3), (3.0, 30)]);
        assert!(band_end_cut(&corners, &judge(), BandOf::LoneDash).is_none());
    }

    #[test]
    fn a_band_read_across_a_side_lift_wins_over_its_longest_piece() {
        // A stroke along a body's outline (18 points one pen wide), round a corner into a
        // narrow finger two pens wide (20 points), a pen lift on one of the finger's sides (8
        // points one pen wide) and the finger's tip (14 points two pens wide). The longest wide
        // piece alone lies midway, nearer the stroke's end than the tip; read across the lift,
        // the band runs from the finger's tip (the dash's end) to the corner.
        let dash = widths(&[(3.0, 18), (6.0, 20), (3.0, 8), (6.0, 14)]);
        assert!(
            matches!(
                band_end_cut(&dash, &judge(), BandOf::LoneDash),
                Some(BandEnd::AtEnd(cut)) if cut >= 36
            ),
            "the band runs from the finger's tip back to the corner"
        );
    }

    #[test]
    fn a_spike_whose_side_lifted_at_its_base_goes_down_along_the_other_side() {
        // As above, with a longer spike, but the pen lifted on the spike's lower side from its
        // base out to x = 104: there the band is the upper side's ink alone, and the square's
        // side starts again below the base. The lower side's end is bridged back along the
        // upper side's ink and round the base to the square's side (`crate::crawl`'s band
        // partner): only the stretch off the ink counts as the gap.
        assert_one_outline_through_the_spike(144.0, (85..104, 41..50));
    }

    #[test]
    fn a_band_cut_by_a_gap_goes_on_as_a_band() {
        // The spike's band with a pen lift right across it: its outer piece is a lone dash,
        // judged as the band's next piece, so it too is two sides (four free ends there).
        let mut mask = square_outline(175);
        draw_line(&mut mask, (90.0, 37.5), (160.0, 40.0), PEN);
        draw_line(&mut mask, (90.0, 42.5), (160.0, 40.0), PEN);
        for x in 121..125 {
            for y in 30..50 {
                mask.set(x, y, false);
            }
        }
        let strokes = extract_strokes(&thin(&mask), &mask, PEN);
        let outer: Vec<&Stroke> = strokes
            .iter()
            .filter(|s| s.line.points.iter().all(|p| p.x > 123.0))
            .collect();
        assert_eq!(outer.len(), 2, "{strokes:?}");
    }

    #[test]
    fn a_band_beyond_a_gap_that_goes_on_as_one_stroke_is_cut_where_the_band_ends() {
        // The spike's band (two lines 2.5 px apart) with a pen lift across it at x 111-115, and
        // beyond the band's end at x 150 one line going on to x 210: the piece beyond the gap is
        // a band over one end. Only its band is split into two sides; the line goes on as one
        // stroke (split whole, two sides ran along it side by side).
        let mut mask = square_outline(220);
        draw_line(&mut mask, (90.0, 38.75), (150.0, 38.75), PEN);
        draw_line(&mut mask, (90.0, 41.25), (150.0, 41.25), PEN);
        draw_line(&mut mask, (150.0, 40.0), (210.0, 40.0), PEN);
        for x in 111..115 {
            for y in 30..50 {
                mask.set(x, y, false);
            }
        }
        let strokes = extract_strokes(&thin(&mask), &mask, PEN);
        assert_eq!(passes(&strokes, 180.0), 1, "along the line: {strokes:?}");
    }

    #[test]
    fn a_band_out_of_a_junction_that_goes_on_as_one_stroke_is_cut_where_the_band_ends() {
        // Two lines out of the square's right side, 5 px apart there (a band from a junction),
        // that close in to one line at x 150 and go on as one to x 210, ending free (two lines
        // of an outline that come together and run on side by side): only the band is split
        // into two sides, and the line goes on from one of them as one stroke (split whole, two
        // sides ran along it side by side).
        let mut mask = square_outline(230);
        draw_line(&mut mask, (90.0, 37.5), (150.0, 40.0), PEN);
        draw_line(&mut mask, (90.0, 42.5), (150.0, 40.0), PEN);
        draw_line(&mut mask, (150.0, 40.0), (210.0, 40.0), PEN);
        let strokes = extract_strokes(&thin(&mask), &mask, PEN);
        assert_eq!(passes(&strokes, 185.0), 1, "along the line: {strokes:?}");
        assert_eq!(passes(&strokes, 110.0), 2, "along the band: {strokes:?}");
    }

    #[test]
    fn a_band_standing_apart_from_the_outline_is_marked_wide() {
        // A finger of two lines 2.5 px apart (ink 6.5 px across, pen 4) whose base the pen
        // lifted at, 6 px right of the square's side: a lone dash, not split (it goes on from
        // no band), but marked as a band; a dash one pen wide beside it is not.
        let mut mask = square_outline(150);
        draw_line(&mut mask, (96.0, 28.75), (136.0, 28.75), PEN);
        draw_line(&mut mask, (96.0, 31.25), (136.0, 31.25), PEN);
        draw_line(&mut mask, (96.0, 52.0), (136.0, 52.0), PEN);
        let strokes = extract_strokes(&thin(&mask), &mask, PEN);
        let dash_at = |y: f64| -> Vec<&Stroke> {
            strokes
                .iter()
                .filter(|s| {
                    s.line
                        .points
                        .iter()
                        .all(|p| p.x > 93.0 && (p.y - y).abs() < 4.0)
                })
                .collect()
        };
        let (finger, ray) = (dash_at(30.0), dash_at(52.0));
        assert_eq!((finger.len(), ray.len()), (1, 1), "{strokes:?}");
        assert!(finger[0].wide && !ray[0].wide, "{strokes:?}");
    }

    #[test]
    fn a_stroke_one_pen_wide_stays_a_stem_on_the_outline() {
        // Both lines on top of each other: one stroke of the pen's width, run along once, ending
        // attached to the outline (a T), not turned back into it.
        let strokes = square_with_spike(0.0);
        let along = points_along_the_spike(&strokes);
        assert!((17..=23).contains(&along), "{along} points: once");
        assert!(
            strokes.iter().any(|s| s
                .ends
                .iter()
                .any(|end| matches!(end, StrokeEnd::Attached(_)))),
            "{strokes:?}"
        );
    }

    #[test]
    fn a_pen_thinner_than_the_least_side_offset_keeps_two_sides() {
        // A fifth of a pixel's pen caps the offsets below the least one: the least one wins
        // (the cap used to make `f64::clamp` panic, its bounds crossed).
        let offsets = super::side_offsets(&[Some(3.0), None, Some(0.5)], 1.0, 2, 0.2);
        assert_eq!(offsets, [super::MIN_SIDE_OFFSET_PX; 3]);
        // A real pen caps them at its width.
        let offsets = super::side_offsets(&[Some(9.0), Some(9.0)], 1.0, 2, 2.0);
        assert_eq!(offsets, [2.0; 2]);
    }

    #[test]
    fn two_curves_running_side_by_side_each_keep_their_side() {
        // Two lines merge into one band for 50 px (3 px apart, pen 4) and part again: each
        // comes out on the side it went in (an outline never crosses itself).
        let mut mask = Bitmap::new(170, 80);
        for (y_out, y_in) in [(10.0, 38.5), (70.0, 41.5)] {
            draw_line(&mut mask, (10.0, y_out), (50.0, y_in), PEN);
            draw_line(&mut mask, (50.0, y_in), (110.0, y_in), PEN);
            draw_line(&mut mask, (110.0, y_in), (150.0, y_out), PEN);
        }
        let strokes = extract_strokes(&thin(&mask), &mask, PEN);
        assert_eq!(strokes.len(), 2, "{strokes:?}");
        for stroke in &strokes {
            let (first, last) = (stroke.line.points[0], *stroke.line.points.last().unwrap());
            assert!((first.x - last.x).abs() > 120.0, "{stroke:?}");
            assert!((first.y - last.y).abs() < 10.0, "crossed over: {stroke:?}");
        }
    }

    #[test]
    fn a_sloping_bar_of_one_pen_is_one_strand() {
        // An "F" on a 3-px pen whose middle bar slopes down by a pixel every 12: where its
        // edges step, the bar is 4 px of ink across for 10 px, a pixel over the page's stroke
        // (as scanned: the middle bar of a letter on the benchmark). One stroke, run along once.
        let pen = 3.0;
        let mut mask = Bitmap::new(80, 100);
        for y in 10..90 {
            for x in 19..22 {
                mask.set(x, y, true);
            }
        }
        for x in 19..60 {
            for y in 9..12 {
                mask.set(x, y, true);
            }
        }
        for x in 22..56 {
            let top = 49 + (x - 20) / 12;
            let rows = if (36..46).contains(&x) { 4 } else { 3 };
            for y in top..top + rows {
                mask.set(x, y, true);
            }
        }
        let strokes = extract_strokes(&thin(&mask), &mask, pen);
        let along_the_bar = strokes
            .iter()
            .flat_map(|s| &s.line.points)
            .filter(|p| p.x > 30.0 && p.y > 40.0)
            .count();
        assert!(
            (20..=32).contains(&along_the_bar),
            "{along_the_bar} points: {strokes:?}"
        );
    }
}
