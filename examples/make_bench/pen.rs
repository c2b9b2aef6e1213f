//! How the benchmark's hand draws a true curve: where the pen is down (arc-length intervals, with
//! gaps placed at random, at forced places, at tips, or kept off corners), and the wobbling strokes
//! themselves, built on the sample generator's sketcher (`examples/make_samples/sketch.rs`).

use kurbo::{Point, Vec2};

use super::geometry::TrueCurve;
use super::random::SplitMix64;
use super::sketch::{wobbled_points, Stroke};

/// A gap stays this many pen widths clear of a sharp corner when corners keep their ink (as in
/// the samples), so the corner is not cut off by the hand.
const CORNER_CLEARANCE: f64 = 1.0;
/// Each stroke's width varies by this fraction around the pen width, as in the samples.
const WIDTH_VARIATION: f64 = 0.08;
/// Free stretches shorter than this many pen widths are left blank (they would be a speck between
/// two forced gaps).
const SHORTEST_STRETCH: f64 = 0.5;

/// What the hand does at sharp corners.
#[derive(Clone, Copy, Debug)]
pub enum Corners {
    /// Gaps never cover a corner, except that with `tip_gap_chance` a gap is put exactly at a
    /// corner (the corner anywhere inside it, the apex then drawn by neither stroke).
    KeepInk { tip_gap_chance: f64 },
    /// Gaps fall wherever the random phase puts them, corners included.
    Anywhere,
}

/// The hand of one drawing: pen, wobble and the lengths of strokes and gaps.
#[derive(Clone, Copy, Debug)]
pub struct Hand {
    /// Nominal pen width, px.
    pub pen: f64,
    /// Largest sideways wobble of a stroke, px (each stroke gets 50–100 % of it).
    pub jitter: f64,
    /// Stroke lengths, px (centre line, without the round caps).
    pub stroke: (f64, f64),
    /// Visible gaps between the ink of two strokes, px.
    pub gap: (f64, f64),
    /// The corner rule.
    pub corners: Corners,
}

impl Hand {
    /// A visible gap drawn at random from the hand's range.
    pub fn random_gap(&self, random: &mut SplitMix64) -> f64 {
        random.range(self.gap.0, self.gap.1)
    }

    /// How far the pen travels lifted for a visible gap `visible`: round caps reach half a pen
    /// into the gap from each side.
    pub fn lifted(&self, visible: f64) -> f64 {
        visible + self.pen
    }
}

/// How one true curve is drawn.
#[derive(Clone, Debug)]
pub enum Plan {
    /// Random strokes and gaps from the hand, around forced gaps (arc-length centre, visible
    /// length) and never breaking the solid stretches (arc-length intervals drawn in one stroke).
    Auto {
        forced_gaps: Vec<(f64, f64)>,
        solid: Vec<(f64, f64)>,
    },
    /// Exactly these pen-down intervals (arc length; on closed curves they may run past the end).
    Intervals(Vec<(f64, f64)>),
}

impl Plan {
    /// Random strokes and gaps, nothing forced.
    pub fn auto() -> Plan {
        Plan::Auto {
            forced_gaps: Vec::new(),
            solid: Vec::new(),
        }
    }
}

/// Where the pen is down along `curve`, following `plan`.
pub fn pen_intervals(
    curve: &TrueCurve,
    plan: &Plan,
    hand: &Hand,
    random: &mut SplitMix64,
) -> Vec<(f64, f64)> {
    match plan {
        Plan::Intervals(intervals) => intervals.clone(),
        Plan::Auto { forced_gaps, solid } => {
            auto_intervals(curve, forced_gaps, solid, hand, random)
        }
    }
}

/// The pen lifts (centre-line intervals) that are fixed before the random filling: forced gaps
/// and gaps at tips, sorted, without overlaps, inside an open curve's ends.
fn fixed_lifts(
    curve: &TrueCurve,
    forced_gaps: &[(f64, f64)],
    hand: &Hand,
    random: &mut SplitMix64,
) -> Vec<(f64, f64)> {
    let length = curve.length();
    let mut lifts: Vec<(f64, f64)> = forced_gaps
        .iter()
        .map(|&(centre, visible)| {
            let half = hand.lifted(visible) / 2.0;
            (centre - half, centre + half)
        })
        .collect();
    if let Corners::KeepInk { tip_gap_chance } = hand.corners {
        for &corner in &curve.corners {
            if random.chance(tip_gap_chance) {
                let lifted = hand.lifted(hand.random_gap(random));
                let start = corner - random.unit() * lifted;
                lifts.push((start, start + lifted));
            }
        }
    }
    if curve.closed {
        for lift in &mut lifts {
            let shift = lift.0.rem_euclid(length) - lift.0;
            *lift = (lift.0 + shift, lift.1 + shift);
        }
    } else {
        // An open curve starts and ends with ink at its true ends.
        let margin = hand.pen;
        lifts.retain(|&(a, b)| a > margin && b < length - margin);
    }
    lifts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut kept: Vec<(f64, f64)> = Vec::new();
    for lift in lifts {
        let clear_of_last = kept.last().is_none_or(|last| lift.0 > last.1 + hand.pen);
        let clear_of_first = !curve.closed
            || kept
                .first()
                .is_none_or(|first| lift.1 < first.0 + length - hand.pen);
        if clear_of_last && clear_of_first {
            kept.push(lift);
        }
    }
    kept
}

fn auto_intervals(
    curve: &TrueCurve,
    forced_gaps: &[(f64, f64)],
    solid: &[(f64, f64)],
    hand: &Hand,
    random: &mut SplitMix64,
) -> Vec<(f64, f64)> {
    let length = curve.length();
    let lifts = fixed_lifts(curve, forced_gaps, hand, random);
    // The stretches between fixed lifts, each filled with strokes and random gaps.
    let mut stretches: Vec<(f64, f64)> = Vec::new();
    if curve.closed {
        if lifts.is_empty() {
            stretches.push(closed_stretch(curve, hand, random));
        } else {
            for (index, lift) in lifts.iter().enumerate() {
                let next = lifts
                    .get(index + 1)
                    .map_or(lifts[0].0 + length, |next| next.0);
                stretches.push((lift.1, next));
            }
        }
    } else {
        let mut from = 0.0;
        for lift in &lifts {
            stretches.push((from, lift.0));
            from = lift.1;
        }
        stretches.push((from, length));
    }
    let solid = unrolled(solid, curve.closed, length);
    let corners = unrolled_corners(curve);
    let mut intervals = Vec::new();
    for (from, to) in stretches {
        if to - from >= SHORTEST_STRETCH * hand.pen {
            fill_stretch(from, to, hand, &solid, &corners, random, &mut intervals);
        }
    }
    intervals
}

/// Intervals repeated over three laps of a closed curve, so stretches past its start see them.
fn unrolled(intervals: &[(f64, f64)], closed: bool, length: f64) -> Vec<(f64, f64)> {
    let laps = if closed { 3 } else { 1 };
    (0..laps)
        .flat_map(|lap| {
            let offset = lap as f64 * length;
            intervals
                .iter()
                .map(move |&(a, b)| (a + offset, b + offset))
        })
        .collect()
}

fn unrolled_corners(curve: &TrueCurve) -> Vec<f64> {
    let laps = if curve.closed { 3 } else { 1 };
    let length = curve.length();
    (0..laps)
        .flat_map(|lap| curve.corners.iter().map(move |c| c + lap as f64 * length))
        .collect()
}

/// A closed curve with no fixed lift: a random start, and one gap before it that keeps clear of
/// corners when corners keep their ink.
fn closed_stretch(curve: &TrueCurve, hand: &Hand, random: &mut SplitMix64) -> (f64, f64) {
    let length = curve.length();
    let corners = unrolled_corners(curve);
    let clearance = CORNER_CLEARANCE * hand.pen;
    for _ in 0..50 {
        let start = random.range(0.0, length);
        let last_lift = hand.lifted(hand.random_gap(random));
        let from = start + length - last_lift;
        let covers_corner = corners
            .iter()
            .any(|&c| c >= from - clearance && c <= start + length + clearance);
        if matches!(hand.corners, Corners::Anywhere) || !covers_corner {
            return (start, from);
        }
    }
    let corner = curve.corners[random.index(curve.corners.len())];
    (corner, corner + length)
}

/// Strokes from `from` to `to` with random gaps between them; the last stroke ends at `to`.
/// A gap never breaks a solid stretch, and (when corners keep their ink) never covers a corner:
/// the stroke runs on through it, or the pen lifts exactly at it with no gap.
fn fill_stretch(
    from: f64,
    to: f64,
    hand: &Hand,
    solid: &[(f64, f64)],
    corners: &[f64],
    random: &mut SplitMix64,
    intervals: &mut Vec<(f64, f64)>,
) {
    let keep_corners = matches!(hand.corners, Corners::KeepInk { .. });
    let clearance = CORNER_CLEARANCE * hand.pen;
    let shortest_rest = hand.lifted(hand.gap.0) + hand.stroke.0;
    let mut stroke_start = from;
    loop {
        let mut stroke_end = stroke_start + random.range(hand.stroke.0, hand.stroke.1);
        let mut next_start = stroke_end + hand.lifted(hand.random_gap(random));
        for _ in 0..20 {
            if let Some(&(_, solid_end)) = solid
                .iter()
                .find(|&&(a, b)| a < next_start && b > stroke_end)
            {
                stroke_end = solid_end;
                next_start = stroke_end + hand.lifted(hand.random_gap(random));
                continue;
            }
            let corner = corners
                .iter()
                .copied()
                .find(|&c| c >= stroke_end - clearance && c <= next_start + clearance);
            match corner {
                Some(corner) if keep_corners => {
                    if random.chance(0.5) {
                        stroke_end = corner + hand.pen * random.range(1.5, 3.0);
                        next_start = stroke_end + hand.lifted(hand.random_gap(random));
                    } else {
                        (stroke_end, next_start) = (corner, corner);
                        break;
                    }
                }
                _ => break,
            }
        }
        if stroke_end + shortest_rest >= to {
            intervals.push((stroke_start, to));
            return;
        }
        intervals.push((stroke_start, stroke_end));
        stroke_start = next_start;
    }
}

/// The strokes of `curve` drawn over `intervals`, each wobbling by up to the hand's jitter, with
/// its own width and ink grey (no lighter than `lightest_ink`).
pub fn draw_intervals(
    curve: &TrueCurve,
    intervals: &[(f64, f64)],
    hand: &Hand,
    lightest_ink: u8,
    random: &mut SplitMix64,
) -> Vec<Stroke> {
    intervals
        .iter()
        .map(|&(start, end)| {
            let amplitude = hand.jitter * random.range(0.5, 1.0);
            Stroke {
                points: wobbled_points(curve, start, end, amplitude, random),
                width: hand.pen * random.range(1.0 - WIDTH_VARIATION, 1.0 + WIDTH_VARIATION),
                gray: random.range(0.0, f64::from(lightest_ink) + 1.0) as u8,
            }
        })
        .collect()
}

/// A dot: one tap of a pen `diameter` wide, drawn as a round-capped stroke at most 15 % of its
/// diameter long in a random direction.
pub fn draw_dot(centre: Point, diameter: f64, lightest_ink: u8, random: &mut SplitMix64) -> Stroke {
    let angle = random.range(0.0, std::f64::consts::TAU);
    let half = Vec2::new(angle.cos(), angle.sin()) * (diameter * random.range(0.0, 0.075));
    Stroke {
        points: vec![centre - half, centre + half],
        width: diameter,
        gray: random.range(0.0, f64::from(lightest_ink) + 1.0) as u8,
    }
}
