//! Corners of a reconstructed polyline, found by the turn accumulated over a short stretch of it
//! (issue 8: a right angle sampled as two 45° turns is a corner, a smooth circle sampled coarsely
//! is not). The fit breaks its cubics at corners so they stay sharp.

use kurbo::Point;

use crate::geometry::polyline::signed_turn;

/// DECISION: turns are accumulated over stretches of the polyline at most this many pen widths
/// long. The skeleton rounds or chamfers a sharp corner over about one pen width, and samples
/// lie 1.5 pen widths apart by default, so two pen widths hold both vertices of a chamfer; a
/// longer stretch would add up the turns of a gentle curve.
pub const CORNER_STRETCH_IN_PEN_WIDTHS: f64 = 2.0;

/// DECISION: a stretch is a corner when the polyline turns by at least this much along it.
/// A right angle (90°) or a regular hexagon's vertex (60°) is one, however it is sampled; a
/// circle sampled every 1.5 pen widths turns by 2 × 1.5 / r radians over two samples, under
/// 55° for every radius of more than 3.1 pen widths (a smaller loop is a knot of ink).
pub const CORNER_TURN_DEGREES: f64 = 55.0;

/// Indices of the corner vertices of `points`, in order. A corner is the shortest stretch, at
/// most `stretch` long, whose vertices turn by [`CORNER_TURN_DEGREES`] in all (a stretch of
/// one vertex may be any length); its vertices that turn the same way are corners. The two
/// ends of an open polyline are not corners. A `stretch` that is not a positive number makes
/// every stretch one vertex.
pub fn find_corners(points: &[Point], closed: bool, stretch: f64) -> Vec<usize> {
    let n = points.len();
    if n < 3 {
        return Vec::new();
    }
    let turns = signed_turns(points, closed);
    let stretch = if stretch.is_finite() { stretch } else { 0.0 };
    let threshold = CORNER_TURN_DEGREES.to_radians();
    // The arc length from vertex i to vertex i + 1 (the closing segment last).
    let step = |i: usize| points[i % n].distance(points[(i + 1) % n]);
    let mut is_corner = vec![false; n];
    let starts = if closed { 0..n } else { 1..n - 1 };
    for first in starts {
        if turns[first] == 0.0 {
            continue;
        }
        // Grow the stretch from `first` until it turns enough, stays short or runs out.
        let (mut total, mut length, mut last) = (turns[first], 0.0, first);
        while total.abs() < threshold {
            let next = last + 1;
            let within = if closed {
                next < first + n
            } else {
                next < n - 1
            };
            if !within {
                break;
            }
            length += step(last);
            if length > stretch {
                break;
            }
            last = next;
            total += turns[last % n];
        }
        if total.abs() < threshold {
            continue;
        }
        // The shortest stretch: without its first vertex it must not turn enough (the
        // stretch from `first + 1` is tried on its own).
        if last > first && (total - turns[first]).abs() >= threshold {
            continue;
        }
        for i in first..=last {
            if turns[i % n] * total > 0.0 {
                is_corner[i % n] = true;
            }
        }
    }
    (0..n).filter(|&i| is_corner[i]).collect()
}

/// The signed turn at every vertex in radians (left positive), between the nearest distinct
/// points before and after it; 0 at the ends of an open polyline and where a point repeats its
/// predecessor (the repeat's turn is counted once, at the first of them).
fn signed_turns(points: &[Point], closed: bool) -> Vec<f64> {
    let n = points.len();
    let mut turns = vec![0.0; n];
    for (i, turn) in turns.iter_mut().enumerate() {
        let here = points[i];
        let previous = if closed || i > 0 {
            points[(i + n - 1) % n]
        } else {
            continue;
        };
        if previous == here {
            continue;
        }
        // The first point after `here` that is not `here`: a repeated point has its turn once.
        let Some(after) = (1..n)
            .map(|k| i + k)
            .take_while(|&j| closed || j < n)
            .map(|j| points[j % n])
            .find(|&p| p != here)
        else {
            continue;
        };
        *turn = signed_turn(here - previous, after - here);
    }
    turns
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points every `spacing` along the chain through `vertices`.
    fn sampled(vertices: &[(f64, f64)], spacing: f64) -> Vec<Point> {
        let mut points = Vec::new();
        for pair in vertices.windows(2) {
            let (a, b) = (
                Point::new(pair[0].0, pair[0].1),
                Point::new(pair[1].0, pair[1].1),
            );
            let steps = (a.distance(b) / spacing).round().max(1.0) as usize;
            points.extend((0..steps).map(|k| a.lerp(b, k as f64 / steps as f64)));
        }
        let last = vertices[vertices.len() - 1];
        points.push(Point::new(last.0, last.1));
        points
    }

    #[test]
    fn a_right_angle_sampled_as_two_45_degree_turns_is_a_corner() {
        // Pen 4 px, samples 6 px apart, the corner chamfered by one sample: two 45° turns.
        let points = sampled(&[(0.0, 0.0), (30.0, 0.0), (34.0, 4.0), (34.0, 34.0)], 6.0);
        let corners = find_corners(&points, false, CORNER_STRETCH_IN_PEN_WIDTHS * 4.0);
        let at: Vec<Point> = corners.iter().map(|&i| points[i]).collect();
        assert_eq!(at, [Point::new(30.0, 0.0), Point::new(34.0, 4.0)]);
        // Farther apart than the stretch, the two 45° turns are two bends, not a corner.
        let points = sampled(&[(0.0, 0.0), (30.0, 0.0), (54.0, 24.0), (54.0, 54.0)], 6.0);
        assert!(find_corners(&points, false, 8.0).is_empty());
    }

    #[test]
    fn a_circle_sampled_every_one_and_a_half_pen_widths_has_no_corner() {
        for (pen, radius) in [(7.0, 25.0), (2.0, 25.0), (3.0, 10.0), (7.0, 60.0)] {
            let spacing = 1.5 * pen;
            let count = (std::f64::consts::TAU * radius / spacing).round() as usize;
            let circle: Vec<Point> = (0..count)
                .map(|k| {
                    let angle = std::f64::consts::TAU * k as f64 / count as f64;
                    Point::new(radius * angle.cos(), radius * angle.sin())
                })
                .collect();
            let stretch = CORNER_STRETCH_IN_PEN_WIDTHS * pen;
            assert_eq!(
                find_corners(&circle, true, stretch),
                Vec::<usize>::new(),
                "pen {pen}, radius {radius}"
            );
        }
    }

    #[test]
    fn a_square_has_four_corners_and_a_zig_zag_of_small_turns_none() {
        let square = sampled(
            &[
                (0.0, 0.0),
                (40.0, 0.0),
                (40.0, 40.0),
                (0.0, 40.0),
                (0.0, 0.0),
            ],
            5.0,
        );
        let square = &square[..square.len() - 1];
        let corners: Vec<Point> = find_corners(square, true, 6.0)
            .into_iter()
            .map(|i| square[i])
            .collect();
        assert_eq!(
            corners,
            [(0.0, 0.0), (40.0, 0.0), (40.0, 40.0), (0.0, 40.0)].map(|(x, y)| Point::new(x, y))
        );
        // Noise: ±30° turns in turn add up to nothing over any stretch.
        let zig_zag: Vec<Point> = (0..20)
            .map(|k| Point::new(3.0 * k as f64, if k % 2 == 0 { 0.0 } else { 0.8 }))
            .collect();
        assert!(find_corners(&zig_zag, false, 6.0).is_empty());
    }

    #[test]
    fn a_repeated_point_does_not_hide_a_corner() {
        let points: Vec<Point> = [(0.0, 0.0), (10.0, 0.0), (10.0, 0.0), (10.0, 10.0)]
            .map(|(x, y)| Point::new(x, y))
            .to_vec();
        assert_eq!(find_corners(&points, false, 0.0), [1]);
    }
}
