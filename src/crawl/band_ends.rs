//! Outlines left open at a band's end: where the pen lifted across the end of a leg, a foot or the
//! gap between two legs, the outline's two sides end side by side, pointing the same way, and no
//! bridge joins them (two ends side by side are no continuation of each other). When those are
//! the two ends of one long open curve, the curve is an outline open at that end alone, and it is
//! closed across it (issue 9, "a double strand that ends is a U-turn", here with its turn in a
//! pen lift). The paper (Parakkat & Muthuganapathy 2016) bridges ends by distance alone; this rule
//! is ours.

use kurbo::{Point, Vec2};

use super::strokes::point_at_length;
use crate::geometry::grid::PointGrid;
use crate::geometry::Polyline;

/// DECISION: (stop 39) the two ends lie at most this many pen widths apart: a band's two sides
/// stand up to three pen widths apart centre to centre (a leg, a foot), and the pen lift leaves
/// one of them longer; five pen widths is the reach a band's base is looked for in across a pen
/// lift ([`super::bands`]). Measured on the benchmark: seed 3 376 → 377 (a leg's foot at 4.1
/// pen widths), the other four splits the same; at four pen widths nothing changed. With ends
/// allowed to part by 45° instead of 20° ([`SAME_WAY_COSINE`]) a meander's two parting ends of
/// seed 5 closed (lost) and the validation and fourth splits gained one each (not looked at).
const MAX_ACROSS_IN_PEN_WIDTHS: f64 = 5.0;

/// The closing segment is at most this share of the closed outline: the end of a band is a small
/// part of the outline it ends (a "U" or a "C" whose opening is its whole width stays open).
const MAX_SHARE_OF_OUTLINE: f64 = 0.1;

/// The two ends point the same way, a band's sides running side by side: the cosine of the angle
/// between their directions is at least this (20°); ends that diverge more are two lines parting.
const SAME_WAY_COSINE: f64 = 0.94;

/// Neither end lies well ahead of the other: the chord between them makes at least 45° with each
/// end's direction (this is the cosine).
const SIDE_BY_SIDE_COSINE: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// An end's direction is measured over this much of the curve behind it (pen widths).
const DIRECTION_REACH_IN_PEN_WIDTHS: f64 = 2.0;

/// Closes every open curve of `curves` whose two ends stand side by side, pointing the same way,
/// a band's width apart ([`MAX_ACROSS_IN_PEN_WIDTHS`]), the closing segment a small share of the
/// outline ([`MAX_SHARE_OF_OUTLINE`]), and no other curve's end beside them.
pub fn close_band_ends(curves: &mut [Polyline], stroke_width: f64) {
    if stroke_width <= 0.0 {
        return;
    }
    let max_across = MAX_ACROSS_IN_PEN_WIDTHS * stroke_width;
    let reach = DIRECTION_REACH_IN_PEN_WIDTHS * stroke_width;
    let closing: Vec<usize> = curves
        .iter()
        .enumerate()
        .filter(|(_, curve)| ends_side_by_side(curve, max_across, reach))
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

/// Whether the open curve's two ends stand side by side, pointing the same way (directions
/// measured over `reach`), at most `max_across` apart and a small share of the closed outline.
fn ends_side_by_side(curve: &Polyline, max_across: f64, reach: f64) -> bool {
    let points = &curve.points;
    if curve.closed || points.len() < 3 {
        return false;
    }
    let (a, b) = (points[0], points[points.len() - 1]);
    let across = a.distance(b);
    if across == 0.0
        || across > max_across
        || across > MAX_SHARE_OF_OUTLINE * (curve.length() + across)
    {
        return false;
    }
    let reversed: Vec<Point> = points.iter().rev().copied().collect();
    let (Some(way_a), Some(way_b)) = (outward(points, reach), outward(&reversed, reach)) else {
        return false;
    };
    let chord = (b - a) / across;
    way_a.dot(way_b) >= SAME_WAY_COSINE
        && chord.dot(way_a).abs() <= SIDE_BY_SIDE_COSINE
        && chord.dot(way_b).abs() <= SIDE_BY_SIDE_COSINE
}

/// The unit direction in which the curve `points` leaves its first point, measured from the point
/// `reach` along it.
fn outward(points: &[Point], reach: f64) -> Option<Vec2> {
    let behind = point_at_length(points, reach);
    let way = points[0] - behind;
    let length = way.hypot();
    (length > 0.0).then(|| way / length)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn open(corners: &[(f64, f64)]) -> Polyline {
        Polyline::new(
            corners.iter().map(|&(x, y)| Point::new(x, y)).collect(),
            false,
        )
    }

    /// An animal's outline with one leg, traced with a 3 px pen, whose foot fell in a pen lift:
    /// the leg's two sides end side by side 10 px apart, pointing down.
    fn leg_open_at_its_foot() -> Polyline {
        open(&[
            (60.0, 200.0),
            (60.0, 100.0),
            (20.0, 100.0),
            (20.0, 20.0),
            (180.0, 20.0),
            (180.0, 100.0),
            (70.0, 100.0),
            (70.0, 200.0),
        ])
    }

    #[test]
    fn an_outline_open_across_a_legs_foot_is_closed() {
        let mut curves = vec![leg_open_at_its_foot()];
        close_band_ends(&mut curves, 3.0);
        assert!(curves[0].closed);
    }

    #[test]
    fn a_u_whose_opening_is_its_whole_width_stays_open() {
        // Ends 12 px apart side by side, pointing up, but the opening is 12 % of the outline.
        let mut curves = vec![open(&[(0.0, 0.0), (0.0, 40.0), (12.0, 40.0), (12.0, 0.0)])];
        close_band_ends(&mut curves, 3.0);
        assert!(!curves[0].closed);
    }

    #[test]
    fn lines_parting_at_thirty_degrees_stay_open() {
        // A long hairpin whose two ends diverge by 30°, 12 px apart.
        let mut curves = vec![open(&[
            (0.0, -6.0),
            (-40.0 * 0.966, -6.0 - 40.0 * 0.259),
            (-300.0, -20.0),
            (-300.0, 20.0),
            (-40.0 * 0.966, 6.0 + 40.0 * 0.259),
            (0.0, 6.0),
        ])];
        // The ends' directions: along (0.966, ±0.259) away from the hairpin.
        close_band_ends(&mut curves, 3.0);
        assert!(!curves[0].closed);
    }

    #[test]
    fn an_end_with_another_curves_end_beside_it_stays_open() {
        let mut curves = vec![
            leg_open_at_its_foot(),
            open(&[(65.0, 203.0), (65.0, 260.0)]),
        ];
        close_band_ends(&mut curves, 3.0);
        assert!(!curves[0].closed);
    }
}
