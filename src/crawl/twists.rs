//! Small twists taken out of the traced curves: where a curve crosses itself within a stretch too
//! short to be a loop the pen drew, the stretch between the two crossing segments is reversed (the
//! 2-opt move of G. A. Croes, "A method for solving traveling-salesman problems", Operations
//! Research 6(6), 1958), which uncrosses them and shortens the curve.

use kurbo::Point;

use crate::geometry::polyline::{segments_cross, Polyline};

/// DECISION: (stop 57) a curve that crosses itself within this much of its length (in pen
/// widths) is twisted, not looped: a loop that short round is under two pen widths across and its
/// hole under one, which thresholding and thinning close, so no traced loop that small is one the
/// pen drew. Twists come from the joins after the crawl (the two sides of a band paired across
/// each other, a sharp tip's two sides joined crossed), and a closed outline that crosses itself
/// is what a laser cutter or a plotter must not be given. Measured on the benchmark (exact of
/// 432): seeds 1 and 8 +1 each (a thin animal's foot, a thick star's tip), seed 3 −1 (an arch
/// whose hooked end then runs 0.9 px past the tolerance), seeds 5–7 unchanged; validation
/// unchanged, seed 4 +1. 4.5–5 pen widths lose the star, 3 changes nothing. About 35 twists are
/// taken out per split of 432 drawings; most change no verdict.
const MAX_TWIST_IN_PEN_WIDTHS: f64 = 6.0;

/// Takes every twist (see [`MAX_TWIST_IN_PEN_WIDTHS`]) out of `curves`, open and closed.
pub fn untwist_curves(curves: &mut [Polyline], stroke_width: f64) {
    let window = MAX_TWIST_IN_PEN_WIDTHS * stroke_width;
    for curve in curves.iter_mut() {
        // Each move shortens the curve (the uncrossed pair of segments is shorter than the
        // crossed pair), so the moves end; the count only bounds a degenerate input.
        for _ in 0..curve.points.len() {
            if !untwist_once(curve, window) {
                break;
            }
        }
    }
}

/// Reverses the stretch of `curve` between the first pair of segments found crossing within
/// `window` of each other along the curve; false where there is none.
fn untwist_once(curve: &mut Polyline, window: f64) -> bool {
    let n = curve.points.len();
    if n < 4 {
        return false;
    }
    let points = &curve.points;
    let at = |k: usize| points[k % n];
    let segments = if curve.closed { n } else { n - 1 };
    // On a closed curve both ways round between two crossing segments are stretches; where the
    // whole curve is barely longer than two windows, neither is clearly the twist.
    if curve.closed && 2.0 * window >= curve.length() {
        return false;
    }
    // The last segment a segment may be checked against: not itself, not a neighbour.
    let last = |i: usize| {
        if curve.closed {
            i + n - 2
        } else {
            segments - 1
        }
    };
    for i in 0..segments {
        let (a0, a1) = (at(i), at(i + 1));
        let mut between = 0.0;
        for j in i + 2..=last(i) {
            between += at(j - 1).distance(at(j));
            if between > window {
                break;
            }
            if segments_cross(a0, a1, at(j), at(j + 1)) {
                reverse_stretch(&mut curve.points, i + 1, j);
                return true;
            }
        }
    }
    false
}

/// Reverses the points `from..=to` of a curve of `points`, indices taken round the end.
fn reverse_stretch(points: &mut [Point], from: usize, to: usize) {
    let n = points.len();
    let (mut lo, mut hi) = (from, to);
    while lo < hi {
        points.swap(lo % n, hi % n);
        lo += 1;
        hi -= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn crossings(curve: &Polyline) -> usize {
        let n = curve.points.len();
        let segments = if curve.closed { n } else { n - 1 };
        let seg = |k: usize| (curve.points[k % n], curve.points[(k + 1) % n]);
        let mut count = 0;
        for i in 0..segments {
            for j in i + 2..segments {
                if curve.closed && i == 0 && j == n - 1 {
                    continue;
                }
                let ((a0, a1), (b0, b1)) = (seg(i), seg(j));
                count += usize::from(segments_cross(a0, a1, b0, b1));
            }
        }
        count
    }

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    /// A 100 px square outline whose bottom-right corner is traced crossed: down the right side
    /// past the corner, then back up and across, the two sides of a 3 px pen's band paired the
    /// wrong way round.
    fn square_with_twisted_corner() -> Polyline {
        Polyline::new(
            vec![
                p(0.0, 0.0),
                p(100.0, 0.0),
                p(100.0, 90.0),
                p(96.0, 100.0),
                p(100.0, 96.0),
                p(90.0, 100.0),
                p(0.0, 100.0),
            ],
            true,
        )
    }

    #[test]
    fn a_closed_outline_twisted_at_a_corner_is_uncrossed() {
        let mut curves = vec![square_with_twisted_corner()];
        assert_eq!(crossings(&curves[0]), 1);
        let before = curves[0].length();
        untwist_curves(&mut curves, 3.0);
        assert_eq!(crossings(&curves[0]), 0);
        assert!(curves[0].length() < before);
        assert_eq!(curves[0].points.len(), 7);
    }

    #[test]
    fn a_figure_eight_keeps_its_crossing() {
        // Two 60 px lobes crossing in the middle: a drawn crossing, far along the curve.
        let eight = Polyline::new(
            vec![p(0.0, 0.0), p(60.0, 60.0), p(60.0, 0.0), p(0.0, 60.0)],
            true,
        );
        let mut curves = vec![eight.clone()];
        untwist_curves(&mut curves, 3.0);
        assert_eq!(curves[0], eight);
    }

    #[test]
    fn a_drawn_loop_in_an_open_line_stays_and_a_twist_in_it_goes() {
        // An open line with a loop 40 px round (a cursive "l"), and the same line twisted over
        // 4 px instead.
        let looped = Polyline::new(
            vec![
                p(0.0, 0.0),
                p(30.0, 0.0),
                p(40.0, -10.0),
                p(30.0, -20.0),
                p(25.0, 5.0),
                p(60.0, 5.0),
            ],
            false,
        );
        let mut curves = vec![looped.clone()];
        untwist_curves(&mut curves, 3.0);
        assert_eq!(curves[0], looped);

        let twisted = Polyline::new(
            vec![
                p(0.0, 0.0),
                p(30.0, 0.0),
                p(32.0, 2.0),
                p(32.0, 0.0),
                p(30.0, 2.0),
                p(60.0, 2.0),
            ],
            false,
        );
        let mut curves = vec![twisted.clone()];
        assert_eq!(crossings(&curves[0]), 1);
        untwist_curves(&mut curves, 3.0);
        assert_eq!(crossings(&curves[0]), 0);
        assert_eq!(curves[0].points[0], twisted.points[0]);
        assert_eq!(curves[0].points[5], twisted.points[5]);
    }
}
