//! Outlines left open at one small gap: where the pen lifted across the end of a leg, a foot or
//! the belly between two legs, the outline's two sides end side by side, and no bridge joins two
//! ends that are no continuation of each other; and a closing gap the matching left (two ends
//! facing each other) is no different once the whole curve is known. An open curve whose own two
//! ends lie close, a small part of the outline apart, and do not part from each other, is closed
//! (issue 9, "a double strand that ends is a U-turn", its turn here in a pen lift; issue 8,
//! "Closing"). The paper (Parakkat & Muthuganapathy 2016) bridges ends by distance alone; this
//! rule is ours.

use kurbo::{Point, Vec2};

use super::bands::end_direction;
use super::bridges::LOOP_GAP_MAX_IN_TYPICAL_GAPS;
use crate::geometry::grid::PointGrid;
use crate::geometry::Polyline;
use crate::raster::bitmap::Bitmap;

/// The gap is at most this share of the closed outline: the end of a band is a small part of
/// the outline it ends (a "U" or a "C" whose opening is its whole width stays open).
const MAX_SHARE_OF_OUTLINE: f64 = 0.1;

/// An end's direction is measured over this much of the curve behind it (pen widths).
const DIRECTION_REACH_IN_PEN_WIDTHS: f64 = 2.0;

/// Closes every open curve of `curves` whose two ends lie at most a loop-closing bridge apart
/// ([`LOOP_GAP_MAX_IN_TYPICAL_GAPS`] times the drawing's `typical_gap`, in pixels), the gap a
/// small share of the outline ([`MAX_SHARE_OF_OUTLINE`]), the ends not parting ([`ends_part`],
/// directions measured over a reach in `stroke_width`s), and no other curve's end nearer to
/// either than they lie apart.
pub fn close_outline_gaps(curves: &mut [Polyline], stroke_width: f64, typical_gap: f64) {
    close_gaps_measured(curves, None, stroke_width, typical_gap);
}

/// DECISION: (stop 56) [`close_outline_gaps`] once more at the end, with the gap between the two
/// ends measured off the ink of `mask`: the stretch of the straight line between them that runs
/// within half a pen width of ink is no pen lift but ink the crawl did not take (a thin dumbbell
/// whose neck's two sides, 1.25–2 pen widths apart, merged into a ladder of skeleton: the outline
/// came out open along one side of the neck, its ends 24 px apart, 6 typical gaps, over ink all
/// the way). Run after the protrusions' tips are closed ([`super::spikes`]): measured off the
/// ink in the first pass, a thin animal's outline open from a leg's tip to its base closed
/// straight along the leg instead of back along it. Measured on the benchmark (exact of 432):
/// seeds 1 and 6 +1 each (thin dumbbells), the other splits unchanged, nothing lost; in the first
/// pass +2 −1 (that animal).
pub fn close_outline_gaps_across_ink(
    curves: &mut [Polyline],
    mask: &Bitmap,
    stroke_width: f64,
    typical_gap: f64,
) {
    close_gaps_measured(curves, Some(mask), stroke_width, typical_gap);
}

/// [`close_outline_gaps`], the gap measured off the ink of `mask` where there is one.
fn close_gaps_measured(
    curves: &mut [Polyline],
    mask: Option<&Bitmap>,
    stroke_width: f64,
    typical_gap: f64,
) {
    if stroke_width <= 0.0 || typical_gap <= 0.0 {
        return;
    }
    // DECISION: (stop 40) the two ends lie at most as far apart as the matching bridges to
    // close a loop ([`LOOP_GAP_MAX_IN_TYPICAL_GAPS`] typical gaps): a gap the drawing's own pen
    // lifts could have left. Stop 39 capped it at five pen widths (a band's base looked for
    // across a pen lift, [`super::bands`]); that cap was binding: a scanned spike's, a star's and
    // a meander's outline open across one pen lift of 6–12 pen widths stayed open. Measured on
    // the benchmark: +1 on each of the five splits (validation too), nothing lost, from 3.5 to 4
    // typical gaps; at 3 the spike stayed open, at 5 a thin meander closed across its two parting
    // lines' ends (lost), at 7–10 spirals' and meanders' open ends closed (2–3 lost a split).
    let max_across = LOOP_GAP_MAX_IN_TYPICAL_GAPS * typical_gap;
    let reach = DIRECTION_REACH_IN_PEN_WIDTHS * stroke_width;
    let closing: Vec<usize> = curves
        .iter()
        .enumerate()
        .filter(|(_, curve)| closes_across_its_ends(curve, mask, stroke_width, max_across, reach))
        .map(|(k, _)| k)
        .collect();
    if closing.is_empty() {
        return;
    }
    // The open curves' ends, by position: a page of noise has thousands.
    let mut ends = PointGrid::new(max_across);
    for (k, curve) in curves.iter().enumerate() {
        if let (false, Some(&first), Some(&last)) =
            (curve.closed, curve.points.first(), curve.points.last())
        {
            ends.insert(first, (first, k));
            ends.insert(last, (last, k));
        }
    }
    for k in closing {
        let points = &curves[k].points;
        let (a, b) = (points[0], points[points.len() - 1]);
        let across = a.distance(b);
        // Another curve's end beside them may be what one of them goes on to.
        let crowded = [a, b].iter().any(|&end| {
            ends.around(end)
                .any(|&(p, c)| c != k && p.distance(end) <= across)
        });
        if !crowded {
            curves[k].closed = true;
        }
    }
}

/// Whether the open curve's two ends lie at most `max_across` apart (off the ink of `mask`
/// where there is one, [`off_ink_length`]), a small share of the closed outline, and do not part
/// (directions measured over `reach`).
fn closes_across_its_ends(
    curve: &Polyline,
    mask: Option<&Bitmap>,
    stroke_width: f64,
    max_across: f64,
    reach: f64,
) -> bool {
    let points = &curve.points;
    if curve.closed || points.len() < 3 {
        return false;
    }
    let (a, b) = (points[0], points[points.len() - 1]);
    let across = a.distance(b);
    if across == 0.0 || across > MAX_SHARE_OF_OUTLINE * (curve.length() + across) {
        return false;
    }
    let gap = mask.map_or(across, |mask| off_ink_length(mask, a, b, stroke_width));
    if gap > max_across {
        return false;
    }
    let (Some(way_a), Some(way_b)) = (
        end_direction(points, false, reach),
        end_direction(points, true, reach),
    ) else {
        return false;
    };
    !ends_part(a, way_a, b, way_b)
}

/// The samples along a line to the ink are this far apart (pixels).
const INK_STEP_PX: f64 = 0.5;

/// How much of the straight line from `a` to `b` lies farther than half a pen width from the
/// ink of `mask` (along the line and square to its pixel axes).
fn off_ink_length(mask: &Bitmap, a: Point, b: Point, stroke_width: f64) -> f64 {
    let half = stroke_width / 2.0;
    let near_ink = |p: Point| {
        [
            (0.0, 0.0),
            (half, 0.0),
            (-half, 0.0),
            (0.0, half),
            (0.0, -half),
        ]
        .iter()
        .any(|&(dx, dy)| mask.get_signed((p.x + dx).floor() as isize, (p.y + dy).floor() as isize))
    };
    let steps = (a.distance(b) / INK_STEP_PX).ceil().max(1.0) as usize;
    let off = (0..=steps)
        .filter(|&k| !near_ink(a.lerp(b, k as f64 / steps as f64)))
        .count();
    a.distance(b) * off as f64 / (steps + 1) as f64
}

/// Whether two ends part: each points away from the other (more than 90° from the line to it),
/// as two lines diverging from where they met do (a meander's two ends).
// DECISION: (stop 39) parting is both ends pointing away from each other. Measured on the
// benchmark: the same at 0.1 past perpendicular; at 0.3 (about 17°) a meander's two ends parting
// by about 25° closed on seed 5 (lost), and validation and seed 4 gained one each (not looked
// at).
fn ends_part(a: Point, way_a: Vec2, b: Point, way_b: Vec2) -> bool {
    way_a.dot(b - a) < 0.0 && way_b.dot(a - b) < 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A typical gap for a 3 px pen: one sample spacing (1.5 pen widths); ends up to 15.75 px
    /// apart may close.
    const TYPICAL_GAP_PEN_3: f64 = 4.5;

    fn open(corners: &[(f64, f64)]) -> Polyline {
        Polyline::new(
            corners.iter().map(|&(x, y)| Point::new(x, y)).collect(),
            false,
        )
    }

    /// An animal's outline with one leg, traced with a 3 px pen, whose foot fell in a pen lift:
    /// the leg's two sides end side by side 10 px apart, pointing down.
    fn leg_open_at_its_foot() -> Polyline {
        leg_of_width(10.0)
    }

    /// [`leg_open_at_its_foot`] with the leg `width` px wide.
    fn leg_of_width(width: f64) -> Polyline {
        open(&[
            (60.0, 200.0),
            (60.0, 100.0),
            (20.0, 100.0),
            (20.0, 20.0),
            (180.0, 20.0),
            (180.0, 100.0),
            (60.0 + width, 100.0),
            (60.0 + width, 200.0),
        ])
    }

    #[test]
    fn an_outline_open_across_a_legs_foot_is_closed() {
        let mut curves = vec![leg_open_at_its_foot()];
        close_outline_gaps(&mut curves, 3.0, TYPICAL_GAP_PEN_3);
        assert!(curves[0].closed);
    }

    #[test]
    fn ends_farther_apart_than_a_loop_closing_bridge_stay_open() {
        // 10 px apart: within 3.5 typical gaps of 3 px (10.5 px), beyond 3.5 of 2.8 px (9.8 px).
        let mut curves = vec![leg_open_at_its_foot()];
        close_outline_gaps(&mut curves, 3.0, 2.8);
        assert!(!curves[0].closed);
        close_outline_gaps(&mut curves, 3.0, 3.0);
        assert!(curves[0].closed);
    }

    #[test]
    fn a_wide_leg_open_across_its_foot_closes_in_a_drawing_of_wide_pen_lifts() {
        // A 3 px pen whose pen lifts are typically 6 px: the leg's sides end 20 px (6.7 pen
        // widths) apart, within 3.5 typical gaps (21 px).
        let mut curves = vec![leg_of_width(20.0)];
        close_outline_gaps(&mut curves, 3.0, 6.0);
        assert!(curves[0].closed);
    }

    #[test]
    fn an_outline_open_across_a_gap_its_ends_face_is_closed() {
        // A square 100 px a side whose last side stops 12 px short of its start, pointing at it.
        let mut curves = vec![open(&[
            (0.0, 0.0),
            (100.0, 0.0),
            (100.0, 100.0),
            (0.0, 100.0),
            (0.0, 12.0),
        ])];
        close_outline_gaps(&mut curves, 3.0, TYPICAL_GAP_PEN_3);
        assert!(curves[0].closed);
    }

    #[test]
    fn a_u_whose_opening_is_its_whole_width_stays_open() {
        // Ends 12 px apart side by side, pointing up, but the opening is 12 % of the outline.
        let mut curves = vec![open(&[(0.0, 0.0), (0.0, 40.0), (12.0, 40.0), (12.0, 0.0)])];
        close_outline_gaps(&mut curves, 3.0, TYPICAL_GAP_PEN_3);
        assert!(!curves[0].closed);
    }

    #[test]
    fn lines_parting_at_thirty_degrees_stay_open() {
        // A meander's two ends (pen 6): its two lines run 4 px apart for 260 px from the bend at
        // x = -300, then part by 15° each over the last 40 px, ending 25 px apart.
        let spread = 2.0 + 40.0 * 15f64.to_radians().tan();
        let mut curves = vec![open(&[
            (0.0, -spread),
            (-40.0, -2.0),
            (-300.0, -2.0),
            (-300.0, 2.0),
            (-40.0, 2.0),
            (0.0, spread),
        ])];
        close_outline_gaps(&mut curves, 6.0, 2.0 * TYPICAL_GAP_PEN_3);
        assert!(!curves[0].closed);
    }

    #[test]
    fn ends_farther_apart_than_a_pen_lift_close_where_ink_runs_between_them() {
        // A leg 20 px wide on a 3 px pen whose pen lifts are typically 3 px: its sides' ends lie
        // 20 px apart, beyond 3.5 typical gaps (10.5 px), ...
        let mut curves = vec![leg_of_width(20.0)];
        close_outline_gaps(&mut curves, 3.0, 3.0);
        assert!(!curves[0].closed);
        // ... and stay open measured off the ink where no ink runs between them, ...
        let mut mask = Bitmap::new(200, 220);
        close_outline_gaps_across_ink(&mut curves, &mask, 3.0, 3.0);
        assert!(!curves[0].closed);
        // ... but close where a line of ink the crawl did not take runs from one to the other.
        for x in 60..=80 {
            for y in 199..=201 {
                mask.set(x, y, true);
            }
        }
        close_outline_gaps_across_ink(&mut curves, &mask, 3.0, 3.0);
        assert!(curves[0].closed);
    }

    #[test]
    fn an_end_with_another_curves_end_beside_it_stays_open() {
        let mut curves = vec![
            leg_open_at_its_foot(),
            open(&[(65.0, 203.0), (65.0, 260.0)]),
        ];
        close_outline_gaps(&mut curves, 3.0, TYPICAL_GAP_PEN_3);
        assert!(!curves[0].closed);
    }
}
