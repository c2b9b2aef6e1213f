//! Acute tips put back: thinning rounds the wedge of ink at a sharp tip and cuts the centre line
//! short of the apex (by 3–9 px for tips of 15°–60°); the apex is recovered where the lines of
//! the tip's two arms meet, if the new corner stays in the ink (issue 8, "Tips"), and goes on
//! towards the ink's edge where the lines meet inside the ink (stop 59). The turn is
//! measured over arms of a few pen widths, as corner detectors on digital curves do (Rosenfeld and
//! Johnston, "Angle detection on digital curves", IEEE Trans. Computers, 1973). Where the curve
//! turns back on itself (a hairpin: the end of a band the crawl turned round in), the end is put
//! where the ink ends, with two corners where that end is flat (issue 9); and where a blunter
//! corner's ink runs on into a nub no curve took (a cloud's notch, its two lobes' ink merged), the
//! corner goes on to the nub's end (stop 52).

use std::cell::OnceCell;

use kurbo::{Point, Vec2};

use crate::geometry::grid::PointGrid;
use crate::geometry::polyline::{distances_along, lines_meet, signed_turn, Polyline};
use crate::raster::bitmap::Bitmap;

/// DECISION: a tip turns by at least this much between its arms, measured over
/// [`DETECTION_ARM_IN_PEN_WIDTHS`] from the rounded vertex: what an apex of 60° measures there.
/// Wider corners lose less than the tolerance to thinning. The rounding lies inside the arms, so
/// the measured turn falls short of the true one: tips of 60° drawn with 2–7 px pens and thinned
/// measure 103°–111°, tips of 40° 121°–126° (design change, stop 24: at 120° tips of 41°–60°
/// whose skeleton thinning had rounded were left unrestored, three stars of seed 3 among them).
const MIN_TIP_TURN_DEGREES: f64 = 100.0;
/// A hairpin turns by at least this much over [`DETECTION_ARM_IN_PEN_WIDTHS`]: its arms run
/// side by side, and their lines meet far off or nowhere.
// DECISION: (stop 36) 140°. The end of a band the crawl turned round in (a finger, a leg, an
// arch's horn, a folded spike, [`super::spikes`]) measures 150°–180° over three pen widths, a
// thinned acute tip 100°–130°; only where the arms' lines do not meet near the curve
// ([`recover_apex`]) is the end moved. Measured on the benchmark (seeds 1, 3, 5): 140° gains four
// drawings (two arches, a spike, a cloud), 150°–160° lose the spike and the cloud of seed 5 again,
// 100°–120° lose a cloud of seed 3 whose rounded lobes then poke out.
const MIN_HAIRPIN_TURN_DEGREES: f64 = 140.0;
/// A hairpin's rounded end is the curve within this much (pen widths) of its vertex.
const HAIRPIN_ARM_IN_PEN_WIDTHS: f64 = 1.0;
/// The ink ahead of a hairpin is followed at most this far (pen widths); ink running on further
/// is no end.
const MAX_HAIRPIN_REACH_IN_PEN_WIDTHS: f64 = 2.0;
/// A hairpin's end is moved only when it lies at least this far (pixels) short of the ink's end.
const MIN_HAIRPIN_SHIFT_PX: f64 = 0.5;
/// A hairpin's end is flat, with two corners, where the pen's centre line across it is at least
/// this long (pixels).
const MIN_FLAT_END_PX: f64 = 1.0;
/// A staggered flat end (one side of a finger or a band stops short of the end, its pen lifted
/// there, and the other runs on to it): the two sides are read across the hairpin's rough axis at
/// these levels (pen widths) behind where the pen's centre turned, the nearest level that shows
/// the stagger taken. The short side's cap ends about a pen width behind the end or more.
// DECISION: (stop 61) a staggered flat end's short-side corner goes abreast of the end, on the
// short side's line as its ink shows it behind the end: the staggered tip of stop 55 within one
// stroke (the two sides' ink merged, or thinning running the short side's line into the long
// side's before the end, so that no two ends are left to bridge). The hairpin end came out
// pointed at the long side's tip, cutting the flat end's corner by 4.6–5.4 px. The short side
// reaches at least [`MIN_STAGGER_IN_PEN_WIDTHS`] farther across behind the end than at it, at most
// [`MAX_STAGGER_IN_PEN_WIDTHS`] from the long side, and runs parallel to it over the next half pen
// width ([`MAX_SIDE_SPREAD_IN_PEN_WIDTHS`]); the long side lies on the axis
// ([`LONG_SIDE_ON_AXIS_IN_PEN_WIDTHS`]) and does not widen: a wedge (a star's tip whose arms
// merged) widens on both sides or keeps spreading, a junction's ink (a foot, a fork) leaves the
// axis. Also where the end already lies at the ink's edge (the long side's tip). Measured on
// the benchmark (exact of 432): seeds 1, 5, 6, 7, 8 +1, +2, +3, +1, +1 (`spikes-thick-004`,
// `spikes-clean-001`, `spikes-thick-005`, two thick arches' horns, two animals' legs, a scanned
// arch), seed 3 unchanged, nothing lost; validation and seed 4 unchanged. Worst distance grows
// on 12 development drawings exact either way (at most 1.4 px). Each bound alone, moved: the
// least stagger 0.5 loses a thick star, 0.7 two of the gains; the spread 0.15 four gains, 0.35
// loses an object; the axis 0.2 two gains, 0.35 the same; the widest 1.25 the same, 2 loses a
// thick spike; the long side's widening 0.15 two gains, 0.4 one more gain (an animal).
const STAGGER_BEHIND_IN_PEN_WIDTHS: [f64; 3] = [1.0, 1.5, 2.0];
/// The short side's pen centre lies at least this much (pen widths) farther across behind the
/// end than at it ...
const MIN_STAGGER_IN_PEN_WIDTHS: f64 = 0.6;
/// ... and at most this far (pen widths) from the axis: two strokes farther apart leave paper
/// between them, two lines rather than a finger's sides.
const MAX_STAGGER_IN_PEN_WIDTHS: f64 = 1.5;
/// ... and runs parallel to the long side: half a pen width further behind
/// ([`SIDE_SPREAD_STEP_IN_PEN_WIDTHS`]) it lies within this much (pen widths) as far across.
const MAX_SIDE_SPREAD_IN_PEN_WIDTHS: f64 = 0.25;
/// The step over which a staggered side's spread is read (pen widths).
const SIDE_SPREAD_STEP_IN_PEN_WIDTHS: f64 = 0.5;
/// The long side runs on the axis: its pen centre lies within this much (pen widths) of it ...
const LONG_SIDE_ON_AXIS_IN_PEN_WIDTHS: f64 = 0.25;
/// ... and lies less than this much (pen widths) farther across behind the end than at it.
const MAX_LONG_SIDE_WIDENING_IN_PEN_WIDTHS: f64 = 0.25;
/// The arms' directions are measured over this much of the curve on each side of a vertex: long
/// enough to reach past the rounded part of a 60° tip.
const DETECTION_ARM_IN_PEN_WIDTHS: f64 = 3.0;
/// DECISION: (stop 62) a closed curve shorter than this many detection arms has no tips: round a
/// loop that small each vertex's arms reach past the loop's other corners, and the turn measured
/// over them is the whole loop's, not a tip's. A thick pen's small square window (sides three
/// pen widths) measured turns of a hairpin at two of its corners, which went out along the
/// diagonals by 7 px. Measured on the benchmark: seed 11 +1, nothing else changes from 3.8 to 8.
const MIN_LOOP_IN_ARMS: f64 = 6.0;
/// Each arm's line runs through the arm from where the rounding ends, over this much of it.
const ARM_LINE_IN_PEN_WIDTHS: f64 = 2.5;
/// Thinning rounds the tip where the ink of the two arms merges: within half a pen width of both
/// arms' centre lines, `pen / 2 / sin(apex / 2)` from the apex; at least this much, its value at
/// the bluntest tip taken (60°, [`MIN_TIP_TURN_DEGREES`]) ...
const MIN_ROUNDED_IN_PEN_WIDTHS: f64 = 1.0;
/// ... and never more than this (an 18° apex).
// DECISION: (stop 57) 3.2 pen widths, down from 4 (a 14° apex): on sharper tips the arms' lines
// start so far back that a thick spike's curving sides bend them off the apex. Measured on the
// benchmark (exact of 432) with stop 57's dot bound: seed 6 +1 (a thick spike), nothing lost on
// any split; seed 4 +1. 5 pen widths: +1 −1.
const MAX_ROUNDED_IN_PEN_WIDTHS: f64 = 3.2;
/// DECISION: (stop 63) at a vertex turning as much as a hairpin ([`MIN_HAIRPIN_TURN_DEGREES`]),
/// arms' lines that meet more than this far (degrees) off the outward bisector, seen from the
/// rounded vertex (farther to one side than ahead of it), mark a flat end, not a tip: a thinned
/// acute tip is rounded symmetrically, its arms' lines meet ahead of the vertex on its
/// bisector; a finger's or a leg's flat end (two corners near 90° a pen width or two apart)
/// whose sides converge a little has its lines meet beside one corner, and the apex put there
/// (and run on to the ink's edge that way) cut the other corner. Such an end is left to
/// [`hairpin_end`], which puts both corners back. Measured on the benchmark (exact of 432 /
/// 1728): seed 11 +2 (`spikes-thin-015`, a thin finger whose lines met 87° off the bisector;
/// `spikes-scan-007`, 46°), seeds 1, 3, 5–8 unchanged, none lost; seed 12 +4, seed 2 −1, seed 4
/// unchanged. 60°: seed 11 +1 (the finger), the rest the same; 30°: seed 8 −1 (a thick star's
/// tip whose lines meet 43° off). The worst distance of development drawings exact either way
/// grows on two (0.7 px at most) and shrinks on five.
const MAX_TIP_MEET_OFF_AXIS_DEGREES: f64 = 45.0;
/// The new edges must lie within this much (in pen widths) of ink all along: the ink's half
/// width, so that they run inside the stroke the pen drew.
const INK_REACH_IN_PEN_WIDTHS: f64 = 0.5;
/// The new corner may move this far from the curve at most (the cut is 3–9 px on the benchmark's
/// 1.75–7 px pens; further is a different shape, not a rounded tip).
const MAX_APEX_SHIFT_IN_PEN_WIDTHS: f64 = 3.0;
/// The apex is walked back towards the rounded vertex by at most this much (pen widths) to find
/// the ink's end of the tip; farther off, the ink does not confirm a tip there.
const MAX_APEX_WALK_BACK_IN_PEN_WIDTHS: f64 = 1.0;
/// A restored apex on the ink goes on towards the ink's edge where that lies at most this far
/// beyond it (pen widths); ink running on further is another stroke's, not the tip's.
const MAX_APEX_TO_INK_EDGE_IN_PEN_WIDTHS: f64 = 1.0;
/// ... and stops this far (pen widths) inside the edge: half-way between where a drawn tip's
/// apex lies (half a pen width inside, the pen's round cap beyond it) and the edge itself, the
/// nearest the ink comes to an apex that fell in a pen lift.
const APEX_INSIDE_INK_EDGE_IN_PEN_WIDTHS: f64 = 0.25;
/// The new edges are checked against the ink at points this many pixels apart: half a pixel, so
/// that no pixel they cross goes unchecked.
const INK_CHECK_STEP_PX: f64 = 0.5;

/// Puts the apex back into every acute tip of `curves` that thinning rounded off, where the ink
/// of `mask` confirms it: both new edges lie within half a pen width of ink all along
/// (`INK_REACH_IN_PEN_WIDTHS`).
pub fn restore_tips(curves: &mut [Polyline], mask: &Bitmap, stroke_width: f64) {
    // Every curve's tips are found before any moves, so that all see the same curves.
    let tips: Vec<Vec<Tip>> = {
        let traced = TracedInk::new(curves, stroke_width);
        curves
            .iter()
            .enumerate()
            .map(|(c, curve)| find_tips(curve, c, &traced, mask, stroke_width))
            .collect()
    };
    for (curve, tips) in curves.iter_mut().zip(tips) {
        if !tips.is_empty() {
            curve.points = with_tips(curve, &tips);
        }
    }
}

/// Where the curves run: points along every curve at most half a pen width apart, each with its
/// curve and its arc length along it, in a grid of cells a pen width wide. Built when first asked
/// (a page of noise has half a million curve points, and most pages no nub to check).
struct TracedInk<'a> {
    curves: &'a [Polyline],
    grid: OnceCell<PointGrid<(Point, usize, f64)>>,
    reach: f64,
}

impl<'a> TracedInk<'a> {
    fn new(curves: &'a [Polyline], stroke_width: f64) -> Self {
        Self {
            curves,
            grid: OnceCell::new(),
            reach: stroke_width.max(1.0),
        }
    }

    fn grid(&self) -> &PointGrid<(Point, usize, f64)> {
        self.grid.get_or_init(|| self.index())
    }

    fn index(&self) -> PointGrid<(Point, usize, f64)> {
        let (curves, reach) = (self.curves, self.reach);
        let mut grid = PointGrid::new(reach);
        let step = reach / 2.0;
        for (c, curve) in curves.iter().enumerate() {
            let points = &curve.points;
            let mut along = 0.0;
            let last = if curve.closed {
                points.len()
            } else {
                points.len().saturating_sub(1)
            };
            for k in 0..last {
                let (a, b) = (points[k], points[(k + 1) % points.len()]);
                let length = a.distance(b);
                let pieces = (length / step).ceil().max(1.0) as usize;
                for j in 0..pieces {
                    let t = j as f64 / pieces as f64;
                    grid.insert(a.lerp(b, t), (a.lerp(b, t), c, along + t * length));
                }
                along += length;
            }
            if let Some(&end) = points.last() {
                grid.insert(end, (end, c, along));
            }
        }
        grid
    }

    /// Whether some curve other than `curve`, or `curve` itself farther than `apart` along it
    /// from arc length `at` (on a closed curve of length `total`), runs within a pen width of `p`.
    fn traced_near(&self, p: Point, curve: usize, at: f64, apart: f64, total: f64) -> bool {
        self.grid().around(p).any(|&(q, c, s)| {
            let gap = (s - at).abs();
            let gap = if total > 0.0 {
                gap.min(total - gap)
            } else {
                gap
            };
            q.distance(p) <= self.reach && (c != curve || gap > apart)
        })
    }
}

/// A rounded tip to replace: the vertices strictly between `keep_before` and `keep_after` (in
/// curve order, wrapping on closed curves) give way to `apex`.
#[derive(Clone, Copy, Debug)]
struct Tip {
    keep_before: usize,
    keep_after: usize,
    apex: Point,
    /// A flat end's second corner, after `apex`.
    far_corner: Option<Point>,
}

/// The curve read by arc length from a vertex, backwards or forwards, wrapping on closed curves.
struct ArcWalk<'a> {
    points: &'a [Point],
    closed: bool,
    cumulative: Vec<f64>,
    total: f64,
}

impl<'a> ArcWalk<'a> {
    fn new(curve: &'a Polyline) -> Self {
        let points = &curve.points;
        let cumulative = distances_along(points);
        let length = cumulative.last().copied().unwrap_or(0.0);
        let total = if curve.closed && !points.is_empty() {
            length + points[points.len() - 1].distance(points[0])
        } else {
            length
        };
        Self {
            points,
            closed: curve.closed,
            cumulative,
            total,
        }
    }

    /// The point `distance` along the curve from vertex `from` (negative: backwards), and the
    /// first vertex at or beyond it in that direction; none past an open end or half-way round a
    /// closed curve.
    fn at(&self, from: usize, distance: f64) -> Option<(Point, usize)> {
        if self.closed && distance.abs() >= self.total / 2.0 {
            return None;
        }
        let mut s = self.cumulative[from] + distance;
        if self.closed {
            s = s.rem_euclid(self.total);
        } else if s < 0.0 || s > self.total {
            return None;
        }
        // The segment holding arc length s: vertices k and k + 1 (wrapping).
        let n = self.points.len();
        let k = match self.cumulative.partition_point(|&c| c <= s) {
            0 => 0,
            k => k - 1,
        };
        let next = if k + 1 < n { k + 1 } else { 0 };
        let (a, b) = (self.points[k], self.points[next]);
        let segment = a.distance(b);
        let t = if segment > 0.0 {
            ((s - self.cumulative[k]) / segment).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let passed = if distance >= 0.0 { next } else { k };
        Some((a.lerp(b, t), passed))
    }
}

/// The rounded tips of one curve, at most one per stretch of curve, sharpest first kept; then its
/// nubs ([`nub_end`]) where no tip was.
fn find_tips(
    curve: &Polyline,
    index: usize,
    traced: &TracedInk<'_>,
    mask: &Bitmap,
    stroke_width: f64,
) -> Vec<Tip> {
    let n = curve.points.len();
    if n < 3 {
        return Vec::new();
    }
    let walk = ArcWalk::new(curve);
    let arm = DETECTION_ARM_IN_PEN_WIDTHS * stroke_width;
    if curve.closed && walk.total < MIN_LOOP_IN_ARMS * arm {
        return Vec::new();
    }
    let turns: Vec<f64> = (0..n)
        .map(|i| turn_over_arms(&walk, i, arm).unwrap_or(0.0))
        .collect();
    let mut tips: Vec<Tip> = Vec::new();
    let mut order: Vec<usize> = (0..n)
        .filter(|&i| turns[i] >= MIN_TIP_TURN_DEGREES)
        .collect();
    order.sort_by(|&a, &b| turns[b].total_cmp(&turns[a]).then(a.cmp(&b)));
    // A nub at vertex `i` whose ink runs on at least `min_beyond` pen widths past the pen's half
    // width ([`nub_end`]), unless another curve runs through that ink.
    let untraced_nub = |i: usize, min_beyond: f64| {
        nub_end(&walk, i, arm, mask, stroke_width, min_beyond)
            .filter(|tip| !nub_traced(&walk, i, index, tip.apex, traced, arm))
    };
    let mut taken: Vec<(f64, f64)> = Vec::new();
    for i in order {
        let s = walk.cumulative[i];
        // One tip per stretch: a vertex within the arms of a sharper tip is part of that tip.
        if taken.iter().any(|&(lo, hi)| arc_within(&walk, s, lo, hi)) {
            continue;
        }
        taken.push((s - arm, s + arm));
        let hairpin = turns[i] >= MIN_HAIRPIN_TURN_DEGREES;
        // A hairpin's end is read from the ink by [`hairpin_end`] alone, never as a nub.
        if let Some(tip) = recover_apex(&walk, i, turns[i], mask, stroke_width)
            .or_else(|| {
                hairpin
                    .then(|| hairpin_end(&walk, i, mask, stroke_width))
                    .flatten()
            })
            .or_else(|| {
                (!hairpin)
                    .then(|| untraced_nub(i, MIN_TIP_NUB_BEYOND_IN_PEN_WIDTHS))
                    .flatten()
            })
        {
            tips.push(tip);
        }
    }
    // Nubs: corners too blunt for a tip whose ink runs on past them (see [`nub_end`]).
    let mut nubs: Vec<usize> = (0..n)
        .filter(|&i| (MIN_NUB_TURN_DEGREES..MIN_TIP_TURN_DEGREES).contains(&turns[i]))
        .collect();
    nubs.sort_by(|&a, &b| turns[b].total_cmp(&turns[a]).then(a.cmp(&b)));
    for i in nubs {
        let s = walk.cumulative[i];
        if taken.iter().any(|&(lo, hi)| arc_within(&walk, s, lo, hi)) {
            continue;
        }
        if let Some(tip) = untraced_nub(i, MIN_NUB_BEYOND_IN_PEN_WIDTHS) {
            taken.push((s - arm, s + arm));
            tips.push(tip);
        }
    }
    tips
}

/// Whether the nub from vertex `i` of curve `index` to `apex` is ink some other curve runs
/// through (a string tied to a balloon, a line crossing it), or this curve farther along than the
/// corner's own arms `arm`: a nub is ink no curve took.
fn nub_traced(
    walk: &ArcWalk,
    i: usize,
    index: usize,
    apex: Point,
    traced: &TracedInk<'_>,
    arm: f64,
) -> bool {
    let here = walk.points[i];
    let total = if walk.closed { walk.total } else { 0.0 };
    let at = walk.cumulative[i];
    [0.5, 1.0]
        .iter()
        .any(|&t| traced.traced_near(here.lerp(apex, t), index, at, arm, total))
}

/// A corner turning by at least this much (degrees, over [`DETECTION_ARM_IN_PEN_WIDTHS`]) is
/// looked at for a nub ([`nub_end`]).
const MIN_NUB_TURN_DEGREES: f64 = 30.0;

/// A nub's ink runs on past the corner's vertex by at least this much (pen widths) more than the
/// half pen width a round pen's corner shows there.
const MIN_NUB_BEYOND_IN_PEN_WIDTHS: f64 = 1.0;

/// DECISION: (stop 64) at a vertex turning as much as a tip ([`MIN_TIP_TURN_DEGREES`]), not a
/// hairpin ([`MIN_HAIRPIN_TURN_DEGREES`]: its end is read from the ink already), whose
/// apex neither the arms' lines ([`recover_apex`]) nor a hairpin's end ([`hairpin_end`]) put
/// back, the ink running on along the outward bisector is read as a nub, from half a pen width
/// past the round pen's half width (not [`MIN_NUB_BEYOND_IN_PEN_WIDTHS`]): a cusp, two lobes
/// meeting tangent at an acute point (a heart's notch on a thick pen), fills the V between its
/// arms with ink, and thinning joins the arms where that filled V ends, a pen width short of the
/// point; the arms' lines meet at that junction itself (nothing to recover), and the ink runs on
/// only about 1.4 pen widths past it, short of the nub's bound. Such a vertex was taken as a tip
/// and never looked at as a nub. The apex goes half a pen width inside the ink's end, where the
/// pen's centre turned, as at any nub. Measured on the benchmark (exact of 432 / 1728): seed 11
/// +3 (`objects-thick-017`, its notch cut 6.5 px short, now 0.8 px; `animals-thin-010`,
/// `stars-clean-023`), seeds 1, 3, 5–8 unchanged, none lost; validation seeds 2 and 12 +2 and
/// +3, seed 4 unchanged. Half a pen width from 0.4 to 0.5 the same; 0.75 loses one star, 0.25
/// gains one more star on seed 11 and loses one on seed 12, 1.0 (the nubs' own bound) gains only
/// `animals-thin-010`. Lowering the nubs' own bound to 0.5 (blunter corners) instead lost a
/// thin animal's foot (`animals-clean-018`): a toe's corner read as a nub swept the next corner.
const MIN_TIP_NUB_BEYOND_IN_PEN_WIDTHS: f64 = 0.5;

/// ... and ends within this much (pen widths) of the vertex: ink running on further is another
/// stroke, not the corner's own.
const MAX_NUB_REACH_IN_PEN_WIDTHS: f64 = 4.0;

/// The point of a cusp the crawl went past: where two lobes of an outline meet in a sharp notch
/// (a cloud's), their ink merges into a nub that points out of the notch, and its skeleton is a
/// short spur off the junction that no curve takes; the curve turns at the junction, short of
/// the point. Where the ink runs on along the corner's outward bisector well past a round pen's
/// half width, and ends within a few pen widths, the corner is moved to where the pen's centre
/// was at the nub's end (half a pen width inside it), if both new edges run within the ink.
///
/// DECISION: (stop 52) a corner of 30°–100° (blunter than a tip, [`MIN_TIP_TURN_DEGREES`]) goes
/// on to the end of the ink along its outward bisector where that ink runs on at least a pen
/// width past the half pen width a round pen shows beyond its centre
/// ([`MIN_NUB_BEYOND_IN_PEN_WIDTHS`]), ends within [`MAX_NUB_REACH_IN_PEN_WIDTHS`], and no curve
/// runs through it ([`nub_traced`]): thick clouds' notches, whose spur the stroke stage prunes
/// as a filled corner, were cut 10 px short of their point. Without the last condition a string
/// tied on at a balloon's or a circle's bottom (its ink runs along the bisector for a few pen
/// widths before it leaves at a slant) pulled the circle down into a point: 25 drawings lost.
/// Measured on the benchmark: seeds 5 and 7 +1 (thick clouds' notches, a thick animal's),
/// seed 4 +1, the other splits and validation unchanged, none lost; turns from 15° or from
/// 45°, ink running on by half a pen width and reach 3 or 6 pen widths measure the same; by one
/// and a half pen widths both gains go.
fn nub_end(
    walk: &ArcWalk,
    i: usize,
    window: f64,
    mask: &Bitmap,
    stroke_width: f64,
    min_beyond: f64,
) -> Option<Tip> {
    let here = walk.points[i];
    let (before, _) = walk.at(i, -window)?;
    let (after, _) = walk.at(i, window)?;
    let outward = (here - before).normalize() + (here - after).normalize();
    let length = outward.hypot();
    if length <= 1e-9 || length.is_nan() {
        return None;
    }
    let axis = outward / length;
    if !on_ink(mask, here) {
        return None;
    }
    let limit = MAX_NUB_REACH_IN_PEN_WIDTHS * stroke_width;
    let run = ink_run(mask, here, axis, limit);
    if run > limit || run < (0.5 + min_beyond) * stroke_width {
        return None;
    }
    let apex = here + axis * (run + INK_CHECK_STEP_PX / 2.0 - stroke_width / 2.0);
    let arm = HAIRPIN_ARM_IN_PEN_WIDTHS * stroke_width;
    let (near_before, keep_before) = walk.at(i, -arm)?;
    let (near_after, keep_after) = walk.at(i, arm)?;
    let reach = INK_REACH_IN_PEN_WIDTHS * stroke_width;
    if !(segment_near_ink(mask, near_before, apex, reach)
        && segment_near_ink(mask, apex, near_after, reach))
    {
        return None;
    }
    Some(Tip {
        keep_before,
        keep_after,
        apex,
        far_corner: None,
    })
}

/// Whether arc length `s` lies in `[lo, hi]`, wrapping on closed curves.
fn arc_within(walk: &ArcWalk, s: f64, lo: f64, hi: f64) -> bool {
    if walk.closed {
        [-walk.total, 0.0, walk.total]
            .iter()
            .any(|shift| (lo..=hi).contains(&(s + shift)))
    } else {
        (lo..=hi).contains(&s)
    }
}

/// The turn at vertex `i` in degrees, between the chords over `arm` of curve before and after.
fn turn_over_arms(walk: &ArcWalk, i: usize, arm: f64) -> Option<f64> {
    let here = walk.points[i];
    let (before, _) = walk.at(i, -arm)?;
    let (after, _) = walk.at(i, arm)?;
    let (incoming, outgoing) = (here - before, after - here);
    if incoming.hypot() == 0.0 || outgoing.hypot() == 0.0 {
        return None;
    }
    Some(signed_turn(incoming, outgoing).abs().to_degrees())
}

/// DECISION: (stop 68) a vertex turning less than [`MAX_STRAIGHT_MEETS_CURVE_TURN_DEGREES`]
/// whose one arm runs straight over its line (the two halves of the line within
/// [`MAX_STRAIGHT_ARM_BEND_DEGREES`] of each other) while the other curves on by at least
/// [`MIN_CURVING_ARM_BEND_DEGREES`] is a corner where a straight line meets a curve, not a
/// thinned acute tip: a thinned tip's arms run straight once past the rounding, and a 60° tip
/// measures 103°–111° over the detection arms only because both arms close in on each other. A
/// square corner (a cloud's end, where its base line meets the first lobe's side, which is only
/// a pen width or two tall before it curves over into the lobe) measures over 100° there because
/// the curving arm's far part leans back over the corner; that arm's line, a chord of the lobe,
/// crosses the base line's a pen width beyond the corner the ink shows, and the apex went there
/// (5–7 px off on thick clouds, `objects-thick-002` of seed 6 and `objects-thick-022` of seed
/// 11). Such a corner keeps the vertex thinning left, on the ink's corner. Measured on the
/// benchmark (exact): seed 6 +1 (`objects-thick-002`), nothing lost on any split; validation
/// seeds 2 and 12 and held-out seed 4 unchanged; of the development drawings exact either way
/// the worst distance shrank on 16 (five thin fingers 2.0 → 1.2 px) and grew on two (0.1 px). The same from a
/// curving arm of 10° to 40°, a straight arm of 2° to 10°, and a turn bound of 105° to 115°; at
/// 120° seed 12 −1. Any two arms bending apart by 20° (both may curve a little): +3 −3 on
/// development (thin pens' arms, 2.5 pen widths a few pixels long, bend 20°–35° by pixels alone,
/// both ways at once), seed 12 +1 −4: the straight arm is what marks a line meeting a curve.
const MAX_STRAIGHT_MEETS_CURVE_TURN_DEGREES: f64 = 110.0;
/// ... the straight arm's two halves within this much (degrees) of each other ...
const MAX_STRAIGHT_ARM_BEND_DEGREES: f64 = 5.0;
/// ... and the curving arm's at least this much (degrees) apart.
const MIN_CURVING_ARM_BEND_DEGREES: f64 = 25.0;

/// Whether vertex `i`, turning `turn_degrees` over the detection arms, is a straight line meeting
/// a curve ([`MAX_STRAIGHT_MEETS_CURVE_TURN_DEGREES`]): each arm's bend read between the two
/// halves of its line, `line` long from `rounded` out.
fn straight_meets_curve(
    walk: &ArcWalk,
    i: usize,
    turn_degrees: f64,
    rounded: f64,
    line: f64,
) -> bool {
    if turn_degrees >= MAX_STRAIGHT_MEETS_CURVE_TURN_DEGREES {
        return false;
    }
    let bend = |sign: f64| {
        let at = |d: f64| walk.at(i, sign * d).map(|(p, _)| p);
        let (near, mid, far) = (at(rounded)?, at(rounded + line / 2.0)?, at(rounded + line)?);
        Some(signed_turn(mid - far, near - mid).abs().to_degrees())
    };
    let (Some(before), Some(after)) = (bend(-1.0), bend(1.0)) else {
        return false;
    };
    let (straight, curving) = (before.min(after), before.max(after));
    straight <= MAX_STRAIGHT_ARM_BEND_DEGREES && curving >= MIN_CURVING_ARM_BEND_DEGREES
}

/// The apex of the tip at vertex `i`: where the lines of its two arms meet, past the rounding.
fn recover_apex(
    walk: &ArcWalk,
    i: usize,
    turn_degrees: f64,
    mask: &Bitmap,
    stroke_width: f64,
) -> Option<Tip> {
    let half_apex = ((180.0 - turn_degrees) / 2.0).to_radians();
    // The floor keeps a zero apex from dividing by zero; the clamp takes over long before it.
    let rounded = (stroke_width / 2.0 / half_apex.sin().max(1e-6)).clamp(
        MIN_ROUNDED_IN_PEN_WIDTHS * stroke_width,
        MAX_ROUNDED_IN_PEN_WIDTHS * stroke_width,
    );
    let line = ARM_LINE_IN_PEN_WIDTHS * stroke_width;
    let (near_before, keep_before) = walk.at(i, -rounded)?;
    let (far_before, _) = walk.at(i, -(rounded + line))?;
    let (near_after, keep_after) = walk.at(i, rounded)?;
    let (far_after, _) = walk.at(i, rounded + line)?;
    let apex = lines_meet(
        far_before,
        near_before,
        far_after,
        near_after,
        PARALLEL_SINE,
    )?;
    if straight_meets_curve(walk, i, turn_degrees, rounded, line) {
        return None;
    }
    // The apex lies ahead of both arms' rounded ends and not far from the curve.
    let ahead = |far: Point, near: Point| (apex - near).dot(near - far) > 0.0;
    // It lies beyond the rounded vertex, seen from the arms: recovering a tip never shortens it.
    let here = walk.points[i];
    let outward = (here - near_before) + (here - near_after);
    let shift = apex.distance(here);
    // DECISION: (stop 39) lines meeting less than [`MIN_HAIRPIN_SHIFT_PX`] beyond the rounded
    // vertex recover nothing: the vertex already lies where its arms meet (a thick pen's V whose
    // centre line was sampled straight into the skeleton's end), and the ink's own end is left
    // to decide, as at a hairpin ([`hairpin_end`]). Before, that null tip stood in the way and a
    // thick V stayed 4.5 px short of its apex. Measured on the benchmark: dev 384 → 385, the
    // other four splits the same, none lost.
    // A hairpin's arms whose lines meet off to one side: a flat end, not a tip
    // ([`MAX_TIP_MEET_OFF_AXIS_DEGREES`]).
    let sideways = turn_degrees >= MIN_HAIRPIN_TURN_DEGREES
        && (apex - here).dot(outward)
            <= (apex - here).hypot()
                * outward.hypot()
                * MAX_TIP_MEET_OFF_AXIS_DEGREES.to_radians().cos();
    if (apex - here).dot(outward) <= 0.0
        || sideways
        || shift < MIN_HAIRPIN_SHIFT_PX
        || !ahead(far_before, near_before)
        || !ahead(far_after, near_after)
        || shift > MAX_APEX_SHIFT_IN_PEN_WIDTHS * stroke_width
    {
        return None;
    }
    // DECISION: where the arms' lines meet beyond the ink (the last pixels of a very sharp
    // tip are too thin to survive thresholding, and arms drawn with a little jitter meet a
    // pixel or two further on), the apex is walked back towards the rounded vertex, half a
    // pixel at a time, to the farthest point whose two new edges run within the ink's reach:
    // the ink's own end of the tip (issue 8: "else march along the bisector to the ink's edge"),
    // at most [`MAX_APEX_WALK_BACK_IN_PEN_WIDTHS`] back: lines meeting farther beyond the ink
    // belong to a rounded corner, not to a tip the ink confirms. Measured on the benchmark
    // (stop 29): dev 355 → 356, seed 3 341 → 344, seed 5 335 → 336 (sharp stars' tips cut
    // short), val 340 → 341, seed 4 341, none lost. Walking back any distance gained one more
    // tuning drawing but lost two on val (not looked at); the cap is the ink reach's own scale.
    let reach = INK_REACH_IN_PEN_WIDTHS * stroke_width;
    let in_ink = |apex: Point| {
        segment_near_ink(mask, near_before, apex, reach)
            && segment_near_ink(mask, apex, near_after, reach)
    };
    let steps = ((MAX_APEX_WALK_BACK_IN_PEN_WIDTHS * stroke_width).min(shift) / INK_CHECK_STEP_PX)
        .floor() as usize;
    // The lines' meeting itself is always tried first, however short the shift (`steps` is 0
    // below half a pixel).
    let met = apex;
    let apex = (0..steps.max(1))
        .map(|k| here.lerp(met, 1.0 - k as f64 / (shift / INK_CHECK_STEP_PX)))
        .find(|&apex| in_ink(apex))?;
    // DECISION: (stop 59) an apex on the ink goes on the way it moved, from the rounded vertex,
    // towards the ink's edge, where that edge lies within [`MAX_APEX_TO_INK_EDGE_IN_PEN_WIDTHS`],
    // to [`APEX_INSIDE_INK_EDGE_IN_PEN_WIDTHS`] short of it: where the arms' lines, measured from
    // where the two arms' ink merges, meet inside the ink, the tip may have fallen in a pen lift
    // and its apex lie beyond the ink (a scanned star's tip, seed 8). Measured on the benchmark
    // (exact of 432): seed 8 +1, nothing lost on any split, validation and seed 4 unchanged; the
    // worst distance of drawings exact either way grows on 1–5 drawings a split (0.8 px at most),
    // 11 on seed 6. Going on to the edge itself gains two thick stars more (seeds 1 and 6, whose
    // tips lie 5 px beyond the ink in pen lifts) but carries every drawn tip half a pen width out
    // past its apex: the worst distance grew on 20–30 exact drawings a split, by up to 2.4 px.
    // An eighth of a pen width inside the edge gains the same one as a quarter, with that growth
    // on 4–17 drawings a split.
    let way = (met - here) / shift;
    let apex = if on_ink(mask, apex) {
        let limit = MAX_APEX_TO_INK_EDGE_IN_PEN_WIDTHS * stroke_width;
        let run = ink_run(mask, apex, way, limit);
        let short = APEX_INSIDE_INK_EDGE_IN_PEN_WIDTHS * stroke_width;
        let edge = apex + way * (run + INK_CHECK_STEP_PX / 2.0 - short).max(0.0);
        if run <= limit && in_ink(edge) {
            edge
        } else {
            apex
        }
    } else {
        apex
    };
    Some(Tip {
        keep_before,
        keep_after,
        apex,
        far_corner: None,
    })
}

/// The end of a hairpin: where the curve turns back on itself (its two arms side by side, as
/// at the end of a band whose two sides the crawl joined), the apex is put where the ink ends
/// along the hairpin's axis, on the centre line of the pen across that end; thinning stops a
/// band's centre line half the band's width short of a flat end.
// DECISION: (stop 40) at the ink's edge, not half a pen width inside it where the pen's centre
// turned. Where the pen drew the tip, the ink's edge lies half a pen width beyond the true apex,
// within the width the ink itself shows; where the tip fell in a pen lift (a spike's or a star's
// point, the ink of both sides ending short of it), every pixel nearer the ink's edge is a pixel
// nearer the apex. Measured on the benchmark (bench_score, five splits): seeds 1, 3, 5 386 → 388
// (+3 −1, an arch's horn whose zigzag the moved apex pulled off the other arm), 378 → 382, 376 →
// 378, all spikes and stars; validation 375 → 375 (a spike gained, an arch lost); seed 4 376 →
// 377. A quarter pen width inside gains 6 on seeds 1, 3, 5 and loses one on seed 4; a quarter
// pen width beyond the ink gains 14 there but loses corners and letters (validation 375 → 374).
// Across the end (a band's flat end's two corners) the pen's centre stays half a pen width inside
// the sides' ink: the sides are drawn, the end is where a lift may fall (at the edge: the same
// counts, an animal and a star traded on seed 5).
fn hairpin_end(walk: &ArcWalk, i: usize, mask: &Bitmap, stroke_width: f64) -> Option<Tip> {
    let arm = HAIRPIN_ARM_IN_PEN_WIDTHS * stroke_width;
    let window = DETECTION_ARM_IN_PEN_WIDTHS * stroke_width;
    let axis_over = |i: usize, arm: f64| {
        let here = walk.points[i];
        let outward = (here - walk.at(i, -arm)?.0) + (here - walk.at(i, arm)?.0);
        let length = outward.hypot();
        (length > 0.0).then(|| outward / length)
    };
    // Every vertex near the end of a curve that goes out and straight back turns as much as
    // the end itself over the detection arms: the hairpin's vertex is the one farthest out
    // along its axis, measured over those arms (over a pen width, a vertex that far short of the
    // end has no axis: the way out and the way back cancel).
    let rough = axis_over(i, window)?;
    let s = walk.cumulative[i];
    let i = (0..walk.points.len())
        .filter(|&k| arc_within(walk, walk.cumulative[k], s - window, s + window))
        .max_by(|&a, &b| {
            let out = |k: usize| (walk.points[k] - walk.points[i]).dot(rough);
            out(a).total_cmp(&out(b)).then(b.cmp(&a))
        })?;
    let here = walk.points[i];
    let (near_before, keep_before) = walk.at(i, -arm)?;
    let (_, keep_after) = walk.at(i, arm)?;
    let axis = axis_over(i, arm)?;
    if !on_ink(mask, here) {
        return None;
    }
    let limit = MAX_HAIRPIN_REACH_IN_PEN_WIDTHS * stroke_width;
    let run = |from: Point, way: Vec2| ink_run(mask, from, way, limit);
    let inside = run(here, axis);
    if inside > limit {
        return None;
    }
    // The ink's edge lies between the last sample on ink and the first off it.
    let shift = inside + INK_CHECK_STEP_PX / 2.0;
    // An end already at the ink's edge is moved only where it is a staggered flat end.
    let at_edge = shift < MIN_HAIRPIN_SHIFT_PX;
    let centre = here + axis * shift;
    // Across the end, measured where the pen's centre turned (half a pen width inside the end):
    // the pen's centre runs from half a pen width inside the ink's edge on one side to as far
    // inside on the other; a band's flat end has two corners.
    let turned = here + axis * (shift - stroke_width / 2.0);
    let across = Vec2::new(-axis.y, axis.x);
    let extent = |sign: f64| pen_reach_across(mask, turned, across * sign, stroke_width);
    let (mut left, mut right) = (extent(1.0), extent(-1.0));
    // A staggered flat end ([`STAGGER_BEHIND_IN_PEN_WIDTHS`]), read across the hairpin's rough
    // axis (over the detection arms): the axis over one pen width leans with the rounding where
    // one side stops short.
    let rough_across = Vec2::new(-rough.y, rough.x);
    let stagger = staggered_side(mask, turned, rough, stroke_width, (left, right));
    match stagger {
        Some((true, reach)) => left = reach,
        Some((false, reach)) => right = reach,
        None if at_edge => return None,
        None => {}
    }
    let across = if stagger.is_some() {
        rough_across
    } else {
        across
    };
    let (apex, far_corner) = if left + right >= MIN_FLAT_END_PX {
        let (a, b) = (centre + across * left, centre - across * right);
        if a.distance(near_before) <= b.distance(near_before) {
            (a, Some(b))
        } else {
            (b, Some(a))
        }
    } else {
        (centre, None)
    };
    Some(Tip {
        keep_before,
        keep_after,
        apex,
        far_corner,
    })
}

/// The short side of a staggered flat end ([`STAGGER_BEHIND_IN_PEN_WIDTHS`]) at a hairpin whose
/// pen turned at `turned`, its rough axis `axis` pointing out of the end, and how far across its
/// pen's centre line lies from the axis: `true` for the side to the left of the axis (`(-y, x)`).
/// `at_end` is how far the ink reaches across each side (left, right) at the end.
fn staggered_side(
    mask: &Bitmap,
    turned: Point,
    axis: Vec2,
    stroke_width: f64,
    at_end: (f64, f64),
) -> Option<(bool, f64)> {
    let across = Vec2::new(-axis.y, axis.x);
    // How far the pen's centre reaches across on each side, `behind` pen widths back.
    let reach = |behind: f64| {
        let at = turned - axis * (behind * stroke_width);
        let side = |sign: f64| pen_reach_across(mask, at, across * sign, stroke_width);
        on_ink(mask, at).then(|| (side(1.0), side(-1.0)))
    };
    let least = MIN_STAGGER_IN_PEN_WIDTHS * stroke_width;
    let widest = MAX_STAGGER_IN_PEN_WIDTHS * stroke_width;
    let spread = MAX_SIDE_SPREAD_IN_PEN_WIDTHS * stroke_width;
    let on_axis = LONG_SIDE_ON_AXIS_IN_PEN_WIDTHS * stroke_width;
    let straight = MAX_LONG_SIDE_WIDENING_IN_PEN_WIDTHS * stroke_width;
    // A short side at `out` (at the end `end`, half a pen width further back `next`) beside a
    // long side at `long` (at the end `long_end`).
    let staggered = |out: f64, end: f64, next: f64, long: f64, long_end: f64| {
        out - end.max(0.0) >= least
            && out <= widest
            && (next - out).abs() <= spread
            && long.abs() <= on_axis
            && long - long_end.max(0.0) < straight
    };
    let (left_end, right_end) = at_end;
    STAGGER_BEHIND_IN_PEN_WIDTHS.iter().find_map(|&behind| {
        let (left, right) = reach(behind)?;
        let (left_next, right_next) = reach(behind + SIDE_SPREAD_STEP_IN_PEN_WIDTHS)?;
        if staggered(left, left_end, left_next, right, right_end) {
            Some((true, left))
        } else if staggered(right, right_end, right_next, left, left_end) {
            Some((false, right))
        } else {
            None
        }
    })
}

/// How far the pen's centre reaches from `from` going the unit `way` at a hairpin's end: half a
/// pen width inside where the ink ends (read up to [`MAX_HAIRPIN_REACH_IN_PEN_WIDTHS`], the edge
/// between the last sample on ink and the first off it).
fn pen_reach_across(mask: &Bitmap, from: Point, way: Vec2, stroke_width: f64) -> f64 {
    let limit = MAX_HAIRPIN_REACH_IN_PEN_WIDTHS * stroke_width;
    ink_run(mask, from, way, limit) + INK_CHECK_STEP_PX / 2.0 - stroke_width / 2.0
}

/// Whether `p` lies on an ink pixel of `mask`.
fn on_ink(mask: &Bitmap, p: Point) -> bool {
    mask.get_signed(p.x.floor() as isize, p.y.floor() as isize)
}

/// How far the ink of `mask` runs on from `from` going the unit `way`, in steps of
/// [`INK_CHECK_STEP_PX`], until it ends or the run passes `limit`.
fn ink_run(mask: &Bitmap, from: Point, way: Vec2, limit: f64) -> f64 {
    let mut t = 0.0;
    while t <= limit && on_ink(mask, from + way * (t + INK_CHECK_STEP_PX)) {
        t += INK_CHECK_STEP_PX;
    }
    t
}

/// Lines whose angle's sine is below this are parallel: they would meet about a billion times
/// farther off than they lie apart, far beyond [`MAX_APEX_SHIFT_IN_PEN_WIDTHS`].
const PARALLEL_SINE: f64 = 1e-9;

/// Whether every point of the segment `a`–`b` lies within `reach` of an ink pixel's centre.
fn segment_near_ink(mask: &Bitmap, a: Point, b: Point, reach: f64) -> bool {
    let steps = (a.distance(b) / INK_CHECK_STEP_PX).ceil().max(1.0) as usize;
    (0..=steps).all(|k| near_ink(mask, a.lerp(b, k as f64 / steps as f64), reach))
}

/// Whether an ink pixel's centre lies within `reach` (plus half a pixel, the pixel's own extent)
/// of `point`.
fn near_ink(mask: &Bitmap, point: Point, reach: f64) -> bool {
    let limit = reach + 0.5;
    let r = limit.ceil() as isize + 1;
    let (cx, cy) = (point.x.floor() as isize, point.y.floor() as isize);
    (-r..=r).any(|dy| {
        (-r..=r).any(|dx| {
            let centre = Point::new((cx + dx) as f64 + 0.5, (cy + dy) as f64 + 0.5);
            mask.get_signed(cx + dx, cy + dy) && centre.distance(point) <= limit
        })
    })
}

/// The curve's points with every tip's rounded vertices replaced by its apex.
fn with_tips(curve: &Polyline, tips: &[Tip]) -> Vec<Point> {
    let n = curve.points.len();
    // Vertices to drop, and where each apex goes (after its `keep_before` vertex).
    let mut dropped = vec![false; n];
    let mut apex_after: Vec<Option<(Point, Option<Point>)>> = vec![None; n];
    for tip in tips {
        let mut k = (tip.keep_before + 1) % n;
        let mut span = Vec::new();
        while k != tip.keep_after && span.len() < n {
            span.push(k);
            k = (k + 1) % n;
        }
        // Tips that overlap another's span, or would empty the curve, are left alone.
        if span.len() >= n - 2
            || span.iter().any(|&v| dropped[v])
            || dropped[tip.keep_before]
            || dropped[tip.keep_after]
            || apex_after[tip.keep_before].is_some()
        {
            continue;
        }
        for v in span {
            dropped[v] = true;
        }
        apex_after[tip.keep_before] = Some((tip.apex, tip.far_corner));
    }
    let mut points = Vec::with_capacity(n + tips.len());
    for k in 0..n {
        if !dropped[k] {
            points.push(curve.points[k]);
        }
        if let Some((apex, far_corner)) = apex_after[k] {
            points.push(apex);
            points.extend(far_corner);
        }
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::Vec2;

    /// Ink within `pen / 2` of the polyline through `corners`, on a `size` × `size` bitmap.
    fn inked(corners: &[Point], pen: f64, size: usize) -> Bitmap {
        let mut mask = Bitmap::new(size, size);
        for y in 0..size {
            for x in 0..size {
                let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
                let near = corners.windows(2).any(|w| {
                    let (a, b) = (w[0], w[1]);
                    let t = ((p - a).dot(b - a) / (b - a).hypot2()).clamp(0.0, 1.0);
                    p.distance(a.lerp(b, t)) <= pen / 2.0
                });
                mask.set(x, y, near);
            }
        }
        mask
    }

    /// A 20° tip at (50, 10): arms 60 px long, the centre line cut short 5 px below the apex
    /// as thinning leaves it.
    fn rounded_tip() -> (Vec<Point>, Point, Bitmap) {
        let apex = Point::new(50.0, 10.0);
        let half = 10f64.to_radians();
        let left = apex + Vec2::new(-half.sin(), half.cos()) * 60.0;
        let right = apex + Vec2::new(half.sin(), half.cos()) * 60.0;
        let mask = inked(&[left, apex, right], 3.0, 100);
        // Thinning follows each arm until the two arms' ink merges (9 px from the apex for a
        // 3 px pen), then runs up the middle to 5 px short of the apex.
        let mut points: Vec<Point> = (0..=13)
            .map(|k| left.lerp(apex, k as f64 / 15.0 * 51.0 / 52.0))
            .collect();
        points.push(apex + Vec2::new(0.0, 5.0));
        points.extend(
            (0..=13)
                .rev()
                .map(|k| right.lerp(apex, k as f64 / 15.0 * 51.0 / 52.0)),
        );
        (points, apex, mask)
    }

    /// The smallest y of the curve's points: how far up its tip reaches.
    fn topmost(curve: &Polyline) -> f64 {
        curve.points.iter().map(|p| p.y).fold(f64::MAX, f64::min)
    }

    /// Restores the tips of the open curve through `points` (pen 3) and asserts that one of its
    /// vertices lies within a pixel of `apex`.
    fn assert_apex_restored(points: Vec<Point>, mask: &Bitmap, apex: Point) {
        assert_apex_restored_with_pen(points, mask, apex, 3.0);
    }

    /// As [`assert_apex_restored`], for a pen of `pen` pixels.
    fn assert_apex_restored_with_pen(points: Vec<Point>, mask: &Bitmap, apex: Point, pen: f64) {
        let mut curves = vec![Polyline::new(points, false)];
        restore_tips(&mut curves, mask, pen);
        let nearest = curves[0]
            .points
            .iter()
            .map(|p| p.distance(apex))
            .fold(f64::INFINITY, f64::min);
        assert!(nearest < 1.0, "{:?}", curves[0].points);
    }

    /// A notch at (30, 30) between two arms rising 10 px over 25 px each way (a turn of about
    /// 44°), sampled every 2.5 px, drawn with a 6 px pen; `nub` adds ink from the notch straight
    /// down to (30, 42), the point two lobes of a cloud make where they meet.
    fn notch(nub: bool) -> (Vec<Point>, Bitmap) {
        let (left, vertex, right) = (
            Point::new(5.0, 20.0),
            Point::new(30.0, 30.0),
            Point::new(55.0, 20.0),
        );
        let mut points: Vec<Point> = (0..10)
            .map(|k| left.lerp(vertex, k as f64 / 10.0))
            .collect();
        points.extend((0..=10).map(|k| vertex.lerp(right, k as f64 / 10.0)));
        // The nub is inked out from the notch and back along the same line.
        let nub_end = Point::new(30.0, 42.0);
        let ink: &[Point] = if nub {
            &[left, vertex, nub_end, vertex, right]
        } else {
            &[left, vertex, right]
        };
        (points, inked(ink, 6.0, 80))
    }

    #[test]
    fn a_notch_whose_ink_runs_on_into_a_nub_goes_to_the_nubs_end() {
        let (points, mask) = notch(true);
        assert_apex_restored_with_pen(points, &mask, Point::new(30.0, 42.0), 6.0);
    }

    #[test]
    fn a_notch_without_a_nub_stays_where_it_is() {
        let (points, mask) = notch(false);
        let mut curves = vec![Polyline::new(points.clone(), false)];
        restore_tips(&mut curves, &mask, 6.0);
        assert_eq!(curves[0].points, points);
    }

    #[test]
    fn a_nub_another_curve_runs_through_is_that_curves_ink() {
        // A string tied on at the notch: its ink is the nub, and it is traced already.
        let (points, mask) = notch(true);
        let string = Polyline::new(vec![Point::new(30.0, 30.0), Point::new(30.0, 42.0)], false);
        let mut curves = vec![Polyline::new(points.clone(), false), string];
        restore_tips(&mut curves, &mask, 6.0);
        assert_eq!(curves[0].points, points);
    }

    #[test]
    fn a_cusp_whose_filled_point_runs_on_a_little_goes_to_the_points_end() {
        // Two arms meeting at (30, 50) at a turn of about 110° (a tip's turn, not a hairpin's),
        // their lines meeting at the vertex itself: nothing for the arms' lines to recover. The
        // ink runs on 4 px past the vertex along the bisector (a thick heart's filled notch, 7
        // px past it to the round pen's edge, under the 9 px a nub of a blunter corner needs):
        // the point goes half a pen width inside the ink's end.
        let (left, vertex, right) = (
            Point::new(5.0, 14.0),
            Point::new(30.0, 50.0),
            Point::new(55.0, 14.0),
        );
        let mut points: Vec<Point> = (0..16)
            .map(|k| left.lerp(vertex, k as f64 / 16.0))
            .collect();
        points.extend((0..=16).map(|k| vertex.lerp(right, k as f64 / 16.0)));
        let point = Point::new(30.0, 54.0);
        let mask = inked(&[left, vertex, point, vertex, right], 6.0, 80);
        assert_apex_restored_with_pen(points, &mask, point, 6.0);
    }

    #[test]
    fn a_rounded_acute_tip_gets_its_apex_back() {
        let (points, apex, mask) = rounded_tip();
        assert_apex_restored(points, &mask, apex);
    }

    #[test]
    fn a_sixty_degree_tip_whose_rounding_bends_the_arms_gets_its_apex_back() {
        // A 60° tip at (50, 10) drawn with a 3 px pen: thinning follows each arm to where the
        // arms' ink merges (3 px from the apex), then ends in the middle 2.5 px short of it.
        let apex = Point::new(50.0, 10.0);
        let half = 30f64.to_radians();
        let along =
            |sign: f64, length: f64| apex + Vec2::new(sign * half.sin(), half.cos()) * length;
        let mask = inked(&[along(-1.0, 60.0), apex, along(1.0, 60.0)], 3.0, 100);
        let mut points: Vec<Point> = (0..=14)
            .map(|k| along(-1.0, 60.0 - 4.0 * k as f64))
            .collect();
        points.push(apex + Vec2::new(0.0, 2.5));
        points.extend((0..=14).rev().map(|k| along(1.0, 60.0 - 4.0 * k as f64)));
        let rounded_vertex = 15;
        let measured = turn_over_arms(
            &ArcWalk::new(&Polyline::new(points.clone(), false)),
            rounded_vertex,
            DETECTION_ARM_IN_PEN_WIDTHS * 3.0,
        )
        .unwrap();
        // The arms bend inside the rounding: the turn measured falls well short of 120°.
        assert!((100.0..115.0).contains(&measured), "{measured}");
        // The arms' lines meet at the apex, on the ink; the apex goes on towards the ink's edge,
        // the pen's cap half a pen width beyond it, to a quarter pen width short of it.
        assert_apex_restored(points, &mask, apex - Vec2::new(0.0, 0.75));
    }

    #[test]
    fn a_tip_whose_arms_lines_meet_inside_the_ink_goes_on_towards_the_inks_edge() {
        // The 20° tip's ink, its centre line's arms bent in towards each other where the arms'
        // ink merges: their lines meet at y = 11, 2.5 px inside the ink's edge round the apex
        // (the pen's cap, at y = 8.5). The apex goes on up to a quarter pen width short of that
        // edge, within a pixel of the true apex (the lines' meeting is not).
        let (_, apex, mask) = rounded_tip();
        let meet = apex + Vec2::new(0.0, 1.0);
        let half = 10f64.to_radians();
        let along =
            |sign: f64, length: f64| meet + Vec2::new(sign * half.sin(), half.cos()) * length;
        let mut points: Vec<Point> = (0..=13)
            .map(|k| along(-1.0, 60.0 - 4.0 * k as f64))
            .collect();
        points.push(meet + Vec2::new(0.0, 3.0));
        points.extend((0..=13).rev().map(|k| along(1.0, 60.0 - 4.0 * k as f64)));
        assert_apex_restored(points, &mask, apex - Vec2::new(0.0, 0.75));
    }

    #[test]
    fn a_tip_whose_last_pixels_were_too_thin_for_the_ink_ends_where_the_ink_ends() {
        // The same 20° tip, its ink lost above y = 12 (the last pixels of a sharp tip are too
        // thin to survive thresholding): the arms' lines meet 2.5 px beyond the ink, and the
        // apex goes back along the way it came to where the ink still reaches, at y ≈ 10.5.
        let (points, _, mut mask) = rounded_tip();
        for y in 0..12 {
            for x in 0..100 {
                mask.set(x, y, false);
            }
        }
        assert_apex_restored(points, &mask, Point::new(50.0, 10.75));
    }

    #[test]
    fn a_tip_without_ink_at_the_apex_goes_no_further_than_its_ink() {
        let (points, apex, _) = rounded_tip();
        // The ink itself is rounded: nothing past the pen's cap round the curve's own tip at
        // y = 15, whose edge is at y = 13.5. The arms' lines meet at y = 10, off the ink.
        let cut = apex + Vec2::new(0.0, 5.0);
        let mask = inked(&points, 3.0, 100);
        assert!(!mask.get(cut.x as usize, 3));
        let mut curves = vec![Polyline::new(points.clone(), false)];
        restore_tips(&mut curves, &mask, 3.0);
        let top = topmost(&curves[0]);
        assert!((13.0..=15.0).contains(&top), "{:?}", curves[0].points);
    }

    #[test]
    fn round_curves_keep_their_shape() {
        let points: Vec<Point> = (0..40)
            .map(|k| {
                let angle = k as f64 / 40.0 * std::f64::consts::TAU;
                Point::new(50.0 + 30.0 * angle.cos(), 50.0 + 30.0 * angle.sin())
            })
            .collect();
        let mut ring = points.clone();
        ring.push(points[0]);
        let mask = inked(&ring, 3.0, 100);
        let mut curves = vec![Polyline::new(points.clone(), true)];
        restore_tips(&mut curves, &mask, 3.0);
        assert_eq!(curves[0].points, points);
    }

    /// A closed curve up `x = left`, round the hairpin vertex `(50, top)` and down `x = right`,
    /// back round `(50, bottom)`: points every 2 px.
    fn hairpin_loop(left: f64, right: f64, top: f64, bottom: f64) -> Vec<Point> {
        let mut points: Vec<Point> = (0..)
            .map(|k| Point::new(left, bottom - 2.0 - 2.0 * k as f64))
            .take_while(|p| p.y >= top + 2.0)
            .collect();
        points.push(Point::new(50.0, top));
        points.extend(
            (0..)
                .map(|k| Point::new(right, top + 2.0 + 2.0 * k as f64))
                .take_while(|p| p.y <= bottom - 2.0),
        );
        points.push(Point::new(50.0, bottom));
        points
    }

    #[test]
    fn a_bands_flat_end_gets_its_two_corners_back() {
        // Two 4-px pens side by side, centres at x = 48 and 52, merged into one band 8 px wide
        // with flat ends at y = 20 and 96. Thinning turned the outline round at y = 24, half the
        // band's width from its edge; the end goes to the ink's edge, the corners on the pens'
        // centres.
        let mut mask = Bitmap::new(100, 100);
        for y in 20..96 {
            for x in 46..54 {
                mask.set(x, y, true);
            }
        }
        let mut curves = vec![Polyline::new(hairpin_loop(48.0, 52.0, 24.0, 92.0), true)];
        restore_tips(&mut curves, &mask, 4.0);
        let points = &curves[0].points;
        for corner in [Point::new(48.0, 20.0), Point::new(52.0, 20.0)] {
            let nearest = points
                .iter()
                .map(|p| p.distance(corner))
                .fold(f64::MAX, f64::min);
            assert!(nearest <= 0.5, "{corner:?} missed by {nearest}: {points:?}");
        }
        assert!(points.iter().all(|p| p.y >= 19.5), "{points:?}");
    }

    #[test]
    fn a_thick_v_whose_arms_meet_at_the_skeletons_end_reaches_the_inks_end() {
        // A 30° V drawn with a 7 px pen, apex at (50, 10). Its centre line was sampled straight
        // from each arm into the skeleton's end, 4.5 px short of the apex: the arms' lines meet
        // a third of a pixel beyond that vertex. The ink runs on to the pen's cap round the apex,
        // which ends 3.5 px beyond it: the end goes there.
        let apex = Point::new(50.0, 10.0);
        let half = 15f64.to_radians();
        let along = |from: Point, sign: f64, length: f64| {
            from + Vec2::new(sign * half.sin(), half.cos()) * length
        };
        let mask = inked(
            &[along(apex, -1.0, 80.0), apex, along(apex, 1.0, 80.0)],
            7.0,
            100,
        );
        let cut = apex + Vec2::new(0.0, 4.5);
        let meet = cut - Vec2::new(0.0, 0.3);
        let mut points: Vec<Point> = (0..8)
            .map(|k| along(meet, -1.0, 75.0 - 10.0 * k as f64))
            .collect();
        points.push(cut);
        points.extend(
            (0..8)
                .rev()
                .map(|k| along(meet, 1.0, 75.0 - 10.0 * k as f64)),
        );
        assert_apex_restored_with_pen(points, &mask, apex - Vec2::new(0.0, 3.5), 7.0);
    }

    #[test]
    fn a_one_pen_hairpin_ends_at_its_caps_edge() {
        // One 4-px pen up x = 50 and back down it: the centre line turns at the cap's centre
        // (y = 22), the ink ends 2 px beyond.
        let mask = inked(&[Point::new(50.0, 92.0), Point::new(50.0, 22.0)], 4.0, 100);
        let mut curves = vec![Polyline::new(hairpin_loop(50.0, 50.0, 22.0, 92.0), true)];
        restore_tips(&mut curves, &mask, 4.0);
        let top = topmost(&curves[0]);
        assert!((19.5..=20.5).contains(&top), "{:?}", curves[0].points);
    }

    #[test]
    fn a_hairpin_at_the_inks_edge_is_left_alone() {
        // The same pen from y = 90 up to y = 22, its ink from 20 to 92: the centre line already
        // turns at the ink's edge at both ends.
        let mask = inked(&[Point::new(50.0, 90.0), Point::new(50.0, 22.0)], 4.0, 100);
        let points = hairpin_loop(50.0, 50.0, 20.0, 92.0);
        let mut curves = vec![Polyline::new(points.clone(), true)];
        restore_tips(&mut curves, &mask, 4.0);
        assert_eq!(curves[0].points, points);
    }

    #[test]
    fn a_straight_line_meeting_a_curve_is_no_tip_but_a_v_is() {
        // A straight arm along the x axis up to the vertex, then a circle of radius 5 that
        // leaves the vertex square to it and curves back over it: a cloud's base meeting its
        // first lobe. Points every half pixel.
        let mut points: Vec<Point> = (0..=60).map(|k| Point::new(0.5 * k as f64, 0.0)).collect();
        let vertex = points.len() - 1;
        points.extend((1..=60).map(|k| {
            let t = k as f64 * 0.1;
            Point::new(25.0 + 5.0 * t.cos(), 5.0 * t.sin())
        }));
        let curve = Polyline::new(points, false);
        let walk = ArcWalk::new(&curve);
        assert!(straight_meets_curve(&walk, vertex, 100.0, 0.0, 7.5));
        // Turning as much as a tip does, it is left to the tip's tests.
        assert!(!straight_meets_curve(&walk, vertex, 115.0, 0.0, 7.5));
        // Two straight arms (a V) are a tip's.
        let mut v: Vec<Point> = (0..=60).map(|k| Point::new(0.5 * k as f64, 0.0)).collect();
        v.extend((1..=60).map(|k| Point::new(30.0 - 0.25 * k as f64, 0.43 * k as f64)));
        let v = Polyline::new(v, false);
        assert!(!straight_meets_curve(
            &ArcWalk::new(&v),
            vertex,
            100.0,
            0.0,
            7.5
        ));
    }
}
