//! Double strands: where an outline comes back within about a pen width of itself (a narrow
//! spike, a leg, a tail, two runs side by side), the ink of its two stretches merges into one
//! band and the skeleton keeps one centre line for two curves. This stage measures the ink's
//! width across every branch, finds the bands clearly wider than one stroke, and makes the
//! skeleton graph say what a person tracing the outline sees: a band that ends is a U-turn (the
//! outline goes out along it and comes back), a band between two junctions is travelled twice,
//! once by each side. Junctions then pair such branches without crossing
//! ([`super::junctions`]).
//!
//! The paper (Parakkat & Muthuganapathy 2016) reconstructs a curve from samples only and has no
//! notion of ink width; this stage is ours (issue 9, "outlines whose parts touch").

use kurbo::{Point, Vec2};

use super::graph::{Branch, SkeletonGraph};
use crate::raster::bitmap::Bitmap;

/// A band is a double strand where it is this much wider than the page's typical stroke, over a
/// stretch of [`DOUBLE_STRETCH_IN_PEN_WIDTHS`]. A single stroke's width wanders by up to about a
/// fifth (jitter, scan noise, pixel steps across a 3-px pen); two strokes merged are at least
/// half again as wide, so the band's widest stretch clears this with room on both sides.
// DECISION: the issue suggests a radius of about 0.7 pen widths (1.4× the width); measured on
// the benchmark's dev split, single strokes' widest 2-pen stretch reaches 1.31× the page's
// median width and narrow spikes' 1.29–2.6×, so the line is drawn at 1.3×.
const DOUBLE_WIDTH_RATIO: f64 = 1.3;

/// ... and at least this much wider, in pixels: a thin pen's edges fall on pixel steps, which can
/// add a pixel to its width over a whole stretch.
const DOUBLE_MIN_EXCESS_PX: f64 = 1.0;

/// The width is averaged over stretches this long (in pen widths) before it is compared: long
/// enough to average out pixel steps and scan noise, short enough that a tapering spike's base
/// still counts.
const DOUBLE_STRETCH_IN_PEN_WIDTHS: f64 = 2.0;

/// Near a junction the ink of the other branches widens the cross-section; points nearer than
/// this (in pen widths) to a junction are not measured.
const JUNCTION_CLEARANCE_IN_PEN_WIDTHS: f64 = 2.0;

/// The cross-section's direction is taken from the points this far (in pen widths) before and
/// after the measured point: past a pixel step, within a curve's bend.
const NORMAL_SPAN_IN_PEN_WIDTHS: f64 = 1.0;

/// Cross-sections are not followed further than this (in pen widths) from the centre line: a
/// blob of ink or a filled area is not a band.
const MAX_CROSS_WIDTH_IN_PEN_WIDTHS: f64 = 6.0;

/// A branch is judged only if this many stretches of it lie clear of junctions: a spike or a
/// leg is several pen widths long, while the stub a contact between two curves leaves in the
/// skeleton is short and all contact ink.
const MIN_MEASURED_STRETCHES: usize = 2;

/// The step along a cross-section, in pixels: fine enough that averaging over a stretch gives
/// sub-pixel widths.
const CROSS_STEP_PX: f64 = 0.25;

/// The width of ink across `point` along the unit vector `normal`, at most `limit`; 0 off the ink.
fn cross_width(mask: &Bitmap, point: Point, normal: Vec2, limit: f64) -> f64 {
    let ink = |q: Point| mask.get_signed(q.x.floor() as isize, q.y.floor() as isize);
    if !ink(point) {
        return 0.0;
    }
    let mut width = CROSS_STEP_PX;
    for sign in [1.0, -1.0] {
        let mut t = CROSS_STEP_PX;
        while t < limit / 2.0 && ink(point + normal * (sign * t)) {
            t += CROSS_STEP_PX;
            width += CROSS_STEP_PX;
        }
    }
    width
}

/// The ink width across each point of `points` (skeleton pixel centres along a branch), or
/// `None` where `skip` says not to measure.
fn widths_along(
    mask: &Bitmap,
    points: &[Point],
    stroke_width: f64,
    skip: impl Fn(Point) -> bool,
) -> Vec<Option<f64>> {
    let span = (NORMAL_SPAN_IN_PEN_WIDTHS * stroke_width).ceil().max(2.0) as usize;
    let limit = MAX_CROSS_WIDTH_IN_PEN_WIDTHS * stroke_width;
    let last = points.len().saturating_sub(1);
    (0..points.len())
        .map(|k| {
            if skip(points[k]) {
                return None;
            }
            let along = points[(k + span).min(last)] - points[k.saturating_sub(span)];
            let length = along.hypot();
            (length > 0.0).then(|| {
                let normal = Vec2::new(-along.y / length, along.x / length);
                cross_width(mask, points[k], normal, limit)
            })
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

impl SkeletonGraph {
    /// Finds the double strands among the branches that end at a junction and rewrites them: a
    /// band from a junction to a free end becomes a U-turn (a loop out and back at the
    /// junction), a band between two junctions gets a copy, so that each side of the outline
    /// has its own branch to travel.
    pub(super) fn split_double_strands(&mut self, mask: &Bitmap, stroke_width: f64) {
        if stroke_width <= 0.0 {
            return;
        }
        let Some(typical) = self.typical_width(mask, stroke_width) else {
            return;
        };
        let stretch = (DOUBLE_STRETCH_IN_PEN_WIDTHS * stroke_width)
            .ceil()
            .max(2.0) as usize;
        let clearance = JUNCTION_CLEARANCE_IN_PEN_WIDTHS * stroke_width;
        for b in 0..self.branches.len() {
            let branch = &self.branches[b];
            let Some((a, z)) = branch.nodes else { continue };
            if branch.removed || a == z {
                continue;
            }
            let (a_is_junction, z_is_junction) = (self.degree(a) >= 3, self.degree(z) >= 3);
            let a_is_free = self.degree(a) == 1;
            let z_is_free = self.degree(z) == 1;
            let is_spur = a_is_junction && z_is_free || z_is_junction && a_is_free;
            let is_link = a_is_junction && z_is_junction;
            if !is_spur && !is_link {
                continue;
            }
            let (pa, pz) = (self.nodes[a].position, self.nodes[z].position);
            let widths = widths_along(mask, &branch.points, stroke_width, |p| {
                a_is_junction && p.distance(pa) <= clearance
                    || z_is_junction && p.distance(pz) <= clearance
            });
            let widest = widest_stretch(&widths, stretch);
            if widest < DOUBLE_WIDTH_RATIO * typical || widest < typical + DOUBLE_MIN_EXCESS_PX {
                continue;
            }
            if is_spur {
                self.make_u_turn(b, if a_is_junction { a } else { z });
            } else {
                self.add_second_side(b);
            }
        }
    }

    /// The page's typical stroke width as the cross-sections measure it (the median over every
    /// branch point): the same measure as the bands are judged by, so that its pixel bias cancels.
    fn typical_width(&self, mask: &Bitmap, stroke_width: f64) -> Option<f64> {
        let mut widths: Vec<f64> = self
            .branches
            .iter()
            .filter(|branch| !branch.removed)
            .flat_map(|branch| widths_along(mask, &branch.points, stroke_width, |_| false))
            .flatten()
            .filter(|&w| w > 0.0)
            .collect();
        if widths.is_empty() {
            return None;
        }
        let middle = widths.len() / 2;
        let (_, median, _) = widths.select_nth_unstable_by(middle, f64::total_cmp);
        Some(*median)
    }

    /// Turns the spur `branch` from `junction` to a free end into a loop at the junction that
    /// goes out to the end and comes back along the same points.
    fn make_u_turn(&mut self, branch: usize, junction: usize) {
        let (a, z) = self.branches[branch].nodes.expect("spurs have nodes");
        let tip = if a == junction { z } else { a };
        let points = &mut self.branches[branch].points;
        if a != junction {
            points.reverse();
        }
        let back: Vec<Point> = points.iter().rev().skip(1).copied().collect();
        points.extend(back);
        let u_turn = &mut self.branches[branch];
        u_turn.nodes = Some((junction, junction));
        u_turn.strand_of = Some(branch);
        u_turn.side = 1.0;
        self.nodes[tip].ends.clear();
        self.nodes[tip].pruned = true;
        let ends = &mut self.nodes[junction].ends;
        ends.retain(|&(b, _)| b != branch);
        ends.push((branch, true));
        ends.push((branch, false));
    }

    /// Gives the band `branch` between two junctions a copy, the other side of the outline.
    fn add_second_side(&mut self, branch: usize) {
        let original = &mut self.branches[branch];
        original.strand_of = Some(branch);
        original.side = 1.0;
        let (a, z) = original.nodes.expect("links have nodes");
        let copy = Branch {
            points: original.points.clone(),
            nodes: Some((a, z)),
            removed: false,
            strand_of: Some(branch),
            side: -1.0,
        };
        let copy_index = self.branches.len();
        self.branches.push(copy);
        self.nodes[a].ends.push((copy_index, true));
        self.nodes[z].ends.push((copy_index, false));
    }
}

#[cfg(test)]
mod tests {
    use crate::raster::bitmap::Bitmap;
    use crate::raster::clean::tests::draw_line;
    use crate::raster::thin::thin;
    use crate::strokes::{extract_strokes, Stroke, StrokeEnd};

    const PEN: f64 = 4.0;

    /// A square outline (pen 4) with a stroke sticking out of its right side, drawn as the two
    /// lines from (90, 40 ± `half_base`) on the side to a tip at (130, 40).
    fn square_with_spike(half_base: f64) -> Vec<Stroke> {
        let mut mask = Bitmap::new(150, 80);
        let corners = [(10.0, 10.0), (90.0, 10.0), (90.0, 70.0), (10.0, 70.0)];
        for k in 0..4 {
            draw_line(&mut mask, corners[k], corners[(k + 1) % 4], PEN);
        }
        draw_line(&mut mask, (90.0, 40.0 - half_base), (130.0, 40.0), PEN);
        draw_line(&mut mask, (90.0, 40.0 + half_base), (130.0, 40.0), PEN);
        extract_strokes(&thin(&mask), &mask, PEN)
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
    fn a_spike_whose_sides_merged_is_a_u_turn_of_the_outline() {
        // Sides 3 px apart at the base (centre to centre): one band of ink, up to 7 px wide.
        let strokes = square_with_spike(1.5);
        assert_eq!(strokes.len(), 1, "{strokes:?}");
        assert!(strokes[0].line.closed, "{strokes:?}");
        let along = points_along_the_spike(&strokes);
        assert!((34..=46).contains(&along), "{along} points: out and back");
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
}
