//! Fits reconstructed polylines with smooth cubic Béziers (a Catmull–Rom spline through the
//! samples, simplified by kurbo's curve fitting within a pixel tolerance), keeping corners sharp;
//! or writes them as (optionally Douglas–Peucker simplified) polylines.

use kurbo::{BezPath, Point, Vec2};

use crate::sample::simplify_polyline;
use crate::svg::CurvePath;

/// How curves are turned into paths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// Smooth cubic Béziers (true) or straight segments (false).
    pub smooth: bool,
    /// The largest distance the path may stray from the reconstructed polyline, in pixels.
    pub tolerance: f64,
}

/// DECISION: a vertex is a corner when the curve turns by at least this much there, measured both
/// to its neighbours and to the samples two steps away. Gentle curves sampled every 1.5 pen widths
/// turn by far less; one noisy sample may exceed it at one scale but rarely at both.
const CORNER_TURN_DEGREES: f64 = 50.0;

/// Turns an ordered chain of points into a path; closed chains end with `ClosePath`.
pub fn fit_curve(points: &[Point], closed: bool, options: &FitOptions) -> BezPath {
    let closed = closed && points.len() > 2;
    if !options.smooth || points.len() < 3 {
        let simplified = simplify_polyline(points, closed, options.tolerance);
        return CurvePath::polyline(&simplified, closed).path;
    }
    let corners = find_corners(points, closed);
    let spline = if closed && corners.is_empty() {
        catmull_rom(&smooth_interior(points, closed, &[]), true)
    } else {
        // Rotate a closed curve to start at a corner, so every run goes corner to corner.
        let mut ordered = points.to_vec();
        let mut corner_indices = corners.clone();
        if closed {
            let start = corners[0];
            ordered.rotate_left(start);
            ordered.push(ordered[0]);
            corner_indices = corners
                .iter()
                .map(|&c| (c + points.len() - start) % points.len())
                .collect();
            corner_indices.push(ordered.len() - 1);
        }
        let smoothed = smooth_interior(&ordered, false, &corner_indices);
        let mut breaks: Vec<usize> = vec![0];
        breaks.extend(corner_indices.iter().copied().filter(|&c| c != 0));
        if *breaks.last().expect("has a start") != smoothed.len() - 1 {
            breaks.push(smoothed.len() - 1);
        }
        breaks.dedup();
        let mut path = BezPath::new();
        path.move_to(smoothed[0]);
        for run in breaks.windows(2) {
            let piece = catmull_rom(&smoothed[run[0]..=run[1]], false);
            for element in piece.elements().iter().skip(1) {
                path.push(*element);
            }
        }
        if closed {
            path.close_path();
        }
        path
    };
    // Corners are sharp joins of straight or curved runs; kurbo keeps joins sharper than the
    // angle threshold and fits each smooth stretch with as few cubics as the tolerance allows.
    let options_for_kurbo = kurbo::simplify::SimplifyOptions::default()
        .angle_thresh(CORNER_TURN_DEGREES.to_radians().tan() * 0.5);
    let simplified =
        kurbo::simplify::simplify_bezpath(spline, options.tolerance, &options_for_kurbo);
    if closed && !matches!(simplified.elements().last(), Some(kurbo::PathEl::ClosePath)) {
        let mut with_close = simplified;
        with_close.close_path();
        return with_close;
    }
    simplified
}

fn turn_degrees(incoming: Vec2, outgoing: Vec2) -> f64 {
    if incoming.hypot2() == 0.0 || outgoing.hypot2() == 0.0 {
        return 0.0;
    }
    incoming
        .cross(outgoing)
        .atan2(incoming.dot(outgoing))
        .abs()
        .to_degrees()
}

/// Indices of the corner vertices, with non-maximum suppression between neighbours.
fn find_corners(points: &[Point], closed: bool) -> Vec<usize> {
    let n = points.len();
    let at = |i: isize| -> Option<Point> {
        if closed {
            Some(points[i.rem_euclid(n as isize) as usize])
        } else if (0..n as isize).contains(&i) {
            Some(points[i as usize])
        } else {
            None
        }
    };
    let turn_at_scale = |i: usize, step: isize| -> Option<f64> {
        let (before, here, after) = (at(i as isize - step)?, points[i], at(i as isize + step)?);
        Some(turn_degrees(here - before, after - here))
    };
    let turns: Vec<f64> = (0..n)
        .map(|i| {
            let near = turn_at_scale(i, 1).unwrap_or(0.0);
            // Near an open end there is no second scale: trust the first.
            let far = turn_at_scale(i, 2).unwrap_or(near);
            near.min(far)
        })
        .collect();
    (0..n)
        .filter(|&i| turns[i] >= CORNER_TURN_DEGREES)
        .filter(|&i| {
            // A rounded corner turns at two neighbouring samples: keep the sharper (ties go to
            // the earlier one).
            let previous = if closed || i > 0 {
                turns[(i + n - 1) % n]
            } else {
                0.0
            };
            let next = if closed || i + 1 < n {
                turns[(i + 1) % n]
            } else {
                0.0
            };
            turns[i] > previous && turns[i] >= next
        })
        .filter(|&i| closed || (i > 0 && i + 1 < n))
        .collect()
}

/// One pass of [1/4, 1/2, 1/4] smoothing on every vertex except the ends of an open chain and
/// the `fixed` ones (corners): it takes out the skeleton's pixel jitter without moving corners.
fn smooth_interior(points: &[Point], closed: bool, fixed: &[usize]) -> Vec<Point> {
    let n = points.len();
    (0..n)
        .map(|i| {
            let is_end = !closed && (i == 0 || i + 1 == n);
            if is_end || fixed.contains(&i) || n < 3 {
                return points[i];
            }
            let (before, after) = (points[(i + n - 1) % n], points[(i + 1) % n]);
            Point::new(
                0.25 * before.x + 0.5 * points[i].x + 0.25 * after.x,
                0.25 * before.y + 0.5 * points[i].y + 0.25 * after.y,
            )
        })
        .collect()
}

/// A uniform Catmull–Rom spline through `points` as cubic Béziers; open runs use one-sided
/// tangents at their ends.
fn catmull_rom(points: &[Point], closed: bool) -> BezPath {
    let n = points.len();
    let mut path = BezPath::new();
    if n == 0 {
        return path;
    }
    path.move_to(points[0]);
    if n == 1 {
        return path;
    }
    let at = |i: isize| -> Point {
        if closed {
            points[i.rem_euclid(n as isize) as usize]
        } else {
            points[i.clamp(0, n as isize - 1) as usize]
        }
    };
    let segments = if closed { n } else { n - 1 };
    for k in 0..segments as isize {
        let (p0, p1, p2, p3) = (at(k - 1), at(k), at(k + 1), at(k + 2));
        let c1 = p1 + (p2 - p0) / 6.0;
        let c2 = p2 - (p3 - p1) / 6.0;
        path.curve_to(c1, c2, p2);
    }
    if closed {
        path.close_path();
    }
    path
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{ParamCurve, PathEl, Shape};

    fn smooth() -> FitOptions {
        FitOptions {
            smooth: true,
            tolerance: 0.5,
        }
    }

    /// The largest distance from any point of `points` to the path.
    fn deviation(path: &BezPath, points: &[Point]) -> f64 {
        let mut flattened = Vec::new();
        for segment in path.segments() {
            for k in 0..=32 {
                flattened.push(segment.eval(k as f64 / 32.0));
            }
        }
        points
            .iter()
            .map(|p| {
                flattened
                    .iter()
                    .map(|q| p.distance(*q))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_circle_becomes_a_few_closed_cubics_close_to_it() {
        let points: Vec<Point> = (0..40)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 40.0;
                Point::new(50.0 + 30.0 * a.cos(), 50.0 + 30.0 * a.sin())
            })
            .collect();
        let path = fit_curve(&points, true, &smooth());
        assert!(matches!(path.elements().last(), Some(PathEl::ClosePath)));
        let cubics = path
            .elements()
            .iter()
            .filter(|e| matches!(e, PathEl::CurveTo(..)))
            .count();
        assert!((2..=12).contains(&cubics), "{cubics} cubics");
        assert!(deviation(&path, &points) < 1.0);
        assert!((path.area().abs() - std::f64::consts::PI * 900.0).abs() < 60.0);
    }

    #[test]
    fn a_square_keeps_its_four_corners() {
        let mut points = Vec::new();
        let corners = [(0.0, 0.0), (40.0, 0.0), (40.0, 40.0), (0.0, 40.0)];
        for k in 0..4 {
            let (a, b) = (corners[k], corners[(k + 1) % 4]);
            for step in 0..8 {
                let t = step as f64 / 8.0;
                points.push(Point::new(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            }
        }
        let path = fit_curve(&points, true, &smooth());
        for (x, y) in corners {
            let corner = Point::new(x, y);
            let nearest = path
                .elements()
                .iter()
                .filter_map(|e| e.end_point())
                .map(|p| p.distance(corner))
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest < 0.01,
                "corner {corner:?} is not a path vertex: {path:?}"
            );
        }
        assert!(deviation(&path, &points) < 0.6);
    }

    #[test]
    fn open_curves_stay_open_and_keep_their_ends() {
        let points: Vec<Point> = (0..30)
            .map(|i| Point::new(i as f64 * 3.0, 20.0 * (i as f64 * 0.2).sin()))
            .collect();
        let path = fit_curve(&points, false, &smooth());
        assert!(!matches!(path.elements().last(), Some(PathEl::ClosePath)));
        let first = path.elements()[0].end_point().unwrap();
        let last = path.elements().last().unwrap().end_point().unwrap();
        assert_eq!((first, last), (points[0], points[29]));
        assert!(deviation(&path, &points) < 1.5);
    }

    #[test]
    fn polylines_are_simplified_within_the_tolerance() {
        let points: Vec<Point> = (0..50)
            .map(|i| Point::new(i as f64, 0.2 * (i % 2) as f64))
            .collect();
        let options = FitOptions {
            smooth: false,
            tolerance: 0.5,
        };
        let path = fit_curve(&points, false, &options);
        assert_eq!(path.elements().len(), 2, "{path:?}");
        assert!(path
            .elements()
            .iter()
            .all(|e| !matches!(e, PathEl::CurveTo(..))));
    }
}
