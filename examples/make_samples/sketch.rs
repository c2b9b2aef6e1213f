//! Draws true curves the way a person draws a skip-stroke sketch: short strokes with small gaps,
//! each a little off the true line, written as SVG strokes with round caps for resvg to rasterise.

use std::fmt::Write as _;

use crawltrace::stages::svg::format_number;
use kurbo::Point;

use super::geometry::TrueCurve;
use super::random::SplitMix64;

/// Stroke lengths, in pen widths.
const STROKE_LENGTH: (f64, f64) = (4.0, 15.0);
/// Visible gap lengths, in pen widths. Round caps reach half a pen into the gap from each side,
/// so the pen lifts for one pen width more than this.
const GAP_LENGTH: (f64, f64) = (1.0, 3.0);
/// A gap stays this many pen widths clear of a sharp corner, so the corner keeps its ink.
const CORNER_CLEARANCE: f64 = 1.0;

/// One pen stroke: a polyline drawn with round caps and joins.
pub struct Stroke {
    /// The pen's path, in pixels.
    pub points: Vec<Point>,
    /// The pen width, in pixels.
    pub width: f64,
    /// The ink's grey level (0 = black).
    pub gray: u8,
}

/// The strokes a person would draw along `curve` with a pen `pen` pixels wide and ink no lighter
/// than `lightest_ink` (0 = black).
pub fn sketch_curve(
    curve: &TrueCurve,
    pen: f64,
    lightest_ink: u8,
    random: &mut SplitMix64,
) -> Vec<Stroke> {
    stroke_intervals(curve, pen, random)
        .into_iter()
        .map(|(start, end)| Stroke {
            points: jittered_points(curve, start, end, pen, random),
            width: pen * random.range(0.92, 1.08),
            gray: random.range(0.0, f64::from(lightest_ink) + 1.0) as u8,
        })
        .collect()
}

/// An SVG document of `strokes` on a `width`×`height` canvas, stroke order as given.
pub fn strokes_to_svg(width: u32, height: u32, strokes: &[Stroke]) -> String {
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         viewBox=\"0 0 {width} {height}\">\n\
         <g fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n"
    );
    for stroke in strokes {
        let _ = write!(
            svg,
            "<path stroke=\"#{0:02x}{0:02x}{0:02x}\" stroke-width=\"{1}\" d=\"",
            stroke.gray,
            format_number(stroke.width)
        );
        for (index, point) in stroke.points.iter().enumerate() {
            let command = if index == 0 { 'M' } else { 'L' };
            let _ = write!(
                svg,
                "{command}{} {} ",
                format_number(point.x),
                format_number(point.y)
            );
        }
        svg.push_str("\"/>\n");
    }
    svg.push_str("</g>\n</svg>\n");
    svg
}

/// Where the pen is down, as arc-length intervals. Open curves begin and end with a stroke end at
/// their true ends; closed curves begin at a random place and leave one gap before it.
fn stroke_intervals(curve: &TrueCurve, pen: f64, random: &mut SplitMix64) -> Vec<(f64, f64)> {
    let length = curve.length();
    // Corners in "unrolled" positions, so a closed curve can be followed past its start.
    let laps = if curve.closed { 3 } else { 1 };
    let corners: Vec<f64> = (0..laps)
        .flat_map(|lap| curve.corners.iter().map(move |c| c + lap as f64 * length))
        .collect();
    let corner_within =
        |from: f64, to: f64| corners.iter().copied().find(|&c| c >= from && c <= to);
    let gap = |random: &mut SplitMix64| centreline_gap(pen, random);
    let clearance = CORNER_CLEARANCE * pen;

    let (start, finish) = if curve.closed {
        closed_start_and_finish(curve, pen, random, &corner_within)
    } else {
        (0.0, length)
    };
    let mut intervals = Vec::new();
    let mut stroke_start = start;
    loop {
        let mut stroke_end = stroke_start + pen * random.range(STROKE_LENGTH.0, STROKE_LENGTH.1);
        let mut next_start = stroke_end + gap(random);
        // A gap over a corner would cut the corner off: run through it, or lift exactly at it.
        while let Some(corner) = corner_within(stroke_end - clearance, next_start + clearance) {
            if random.chance(0.5) {
                stroke_end = corner + pen * random.range(1.5, 3.0);
                next_start = stroke_end + gap(random);
            } else {
                stroke_end = corner;
                next_start = corner;
                break;
            }
        }
        // Too little left for one more gap and a short stroke: this stroke goes to the finish.
        let shortest_rest = pen * (GAP_LENGTH.0 + 1.0 + STROKE_LENGTH.0);
        if stroke_end + shortest_rest >= finish {
            intervals.push((stroke_start, finish));
            return intervals;
        }
        intervals.push((stroke_start, stroke_end));
        stroke_start = next_start;
    }
}

/// Start and finish of the pen on a closed curve: a random start, and a last gap that keeps clear
/// of corners (else the drawing starts and ends at a corner, with no gap).
fn closed_start_and_finish(
    curve: &TrueCurve,
    pen: f64,
    random: &mut SplitMix64,
    corner_within: &dyn Fn(f64, f64) -> Option<f64>,
) -> (f64, f64) {
    let length = curve.length();
    let clearance = CORNER_CLEARANCE * pen;
    for _ in 0..50 {
        let start = random.range(0.0, length);
        let last_gap = centreline_gap(pen, random);
        let gap_from = start + length - last_gap;
        if corner_within(gap_from - clearance, start + length + clearance).is_none() {
            return (start, gap_from);
        }
    }
    let corner = curve.corners[random.index(curve.corners.len())];
    (corner, corner + length)
}

/// How far the pen travels lifted: a visible gap plus the two half-pen caps.
fn centreline_gap(pen: f64, random: &mut SplitMix64) -> f64 {
    pen * (random.range(GAP_LENGTH.0, GAP_LENGTH.1) + 1.0)
}

/// The stroke's polyline: the true curve from `start` to `end`, offset sideways by a smooth wobble
/// of at most a pixel (a third of the pen for thin pens), different for every stroke.
fn jittered_points(
    curve: &TrueCurve,
    start: f64,
    end: f64,
    pen: f64,
    random: &mut SplitMix64,
) -> Vec<Point> {
    let amplitude = (pen / 3.0).min(1.0) * random.range(0.5, 1.0);
    wobbled_points(curve, start, end, amplitude, random)
}

/// The true curve from `start` to `end`, offset sideways by a smooth wobble of at most
/// `amplitude` pixels: a sum of two sine waves of random wavelength and phase.
pub fn wobbled_points(
    curve: &TrueCurve,
    start: f64,
    end: f64,
    amplitude: f64,
    random: &mut SplitMix64,
) -> Vec<Point> {
    let long_wave = random.range(30.0, 80.0);
    let short_wave = random.range(10.0, 25.0);
    let (long_phase, short_phase) = (random.range(0.0, 6.3), random.range(0.0, 6.3));
    let wobble = |position: f64| {
        let along = position - start;
        amplitude
            * (0.65 * (std::f64::consts::TAU * along / long_wave + long_phase).sin()
                + 0.35 * (std::f64::consts::TAU * along / short_wave + short_phase).sin())
    };
    let mut positions = vec![start];
    positions.extend(curve.vertex_positions_between(start, end));
    positions.push(end);
    positions
        .into_iter()
        .map(|position| {
            let (point, normal) = curve.point_and_normal(position);
            point + normal * wobble(position)
        })
        .collect()
}
