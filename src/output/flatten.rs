//! Paths → polylines: each fitted path's Béziers flattened into straight segments within a
//! tolerance (kurbo's `flatten`, after R. Levien's "Flattening quadratic Béziers", 2019), for
//! writers and front ends that want vertices (DXF, the Python `Drawing.curves`).

use kurbo::{flatten, PathEl, Point};

use super::fit::CurvePath;

/// DECISION: the flattening tolerance never goes below a hundredth of a pixel, the precision the
/// SVG writes; `--simplify 0` would otherwise ask for endless subdivision.
pub const MIN_FLATTEN_TOLERANCE: f64 = 0.01;

/// Two vertices closer than this (pixels) are one: far below any visible or machinable distance,
/// well above float rounding.
const SAME_POINT: f64 = 1e-9;

/// The vertices of `path`, its Béziers flattened so that no point of the path is farther than
/// `tolerance` pixels from the polyline (at least [`MIN_FLATTEN_TOLERANCE`]). A closed path does
/// not repeat its first vertex at the end (the closing segment is implied), and consecutive
/// duplicate vertices are dropped.
///
/// # Examples
///
/// ```
/// use crawltrace::stages::flatten::flatten_path;
/// use crawltrace::{CurvePath, Point};
///
/// let square = [Point::new(0.0, 0.0), Point::new(4.0, 0.0), Point::new(4.0, 4.0), Point::new(0.0, 4.0)];
/// let vertices = flatten_path(&CurvePath::polyline(&square, true), 0.25);
/// assert_eq!(vertices, square.to_vec());
/// ```
pub fn flatten_path(path: &CurvePath, tolerance: f64) -> Vec<Point> {
    let tolerance = if tolerance.is_finite() {
        tolerance.max(MIN_FLATTEN_TOLERANCE)
    } else {
        MIN_FLATTEN_TOLERANCE
    };
    let mut vertices: Vec<Point> = Vec::new();
    flatten(path.path.elements().iter().copied(), tolerance, |element| {
        if let PathEl::MoveTo(p) | PathEl::LineTo(p) = element {
            if vertices
                .last()
                .is_none_or(|last| last.distance(p) > SAME_POINT)
            {
                vertices.push(p);
            }
        }
    });
    if path.closed
        && vertices.len() > 1
        && vertices[0].distance(vertices[vertices.len() - 1]) <= SAME_POINT
    {
        vertices.pop();
    }
    vertices
}

#[cfg(test)]
mod tests {
    use kurbo::{BezPath, ParamCurve, ParamCurveNearest};

    use super::*;

    fn circle_path() -> CurvePath {
        // A circle of radius 100 as four cubic arcs, closed.
        let mut path = BezPath::new();
        let k = 0.552_284_749_8 * 100.0;
        path.move_to((100.0, 0.0));
        path.curve_to((100.0, k), (k, 100.0), (0.0, 100.0));
        path.curve_to((-k, 100.0), (-100.0, k), (-100.0, 0.0));
        path.curve_to((-100.0, -k), (-k, -100.0), (0.0, -100.0));
        path.curve_to((k, -100.0), (100.0, -k), (100.0, 0.0));
        path.close_path();
        CurvePath {
            path,
            closed: true,
            stroke_width: None,
        }
    }

    #[test]
    fn vertices_stay_within_the_tolerance_of_the_curve() {
        let circle = circle_path();
        for tolerance in [0.05, 0.5, 2.0] {
            let vertices = flatten_path(&circle, tolerance);
            assert_ne!(
                vertices.first(),
                vertices.last(),
                "closed: no repeated vertex"
            );
            // The midpoint of every segment, closing one included, is near the curve.
            let segments = vertices.iter().zip(vertices.iter().cycle().skip(1));
            for (a, b) in segments {
                let middle = a.midpoint(*b);
                let distance = circle
                    .path
                    .segments()
                    .map(|segment| {
                        let nearest = segment.nearest(middle, 1e-9);
                        segment.eval(nearest.t).distance(middle)
                    })
                    .fold(f64::INFINITY, f64::min);
                assert!(distance <= tolerance * 1.01, "{tolerance}: {distance}");
            }
        }
        // Finer tolerances give more vertices; zero is clamped instead of looping forever.
        assert!(flatten_path(&circle, 0.05).len() > flatten_path(&circle, 2.0).len());
        let finest = flatten_path(&circle, 0.0).len();
        assert_eq!(finest, flatten_path(&circle, MIN_FLATTEN_TOLERANCE).len());
        assert_eq!(finest, flatten_path(&circle, f64::NAN).len());
    }

    #[test]
    fn open_paths_keep_both_ends_and_drop_repeated_vertices() {
        let points = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(0.0, 0.0),
        ];
        let vertices = flatten_path(&CurvePath::polyline(&points, false), 0.5);
        assert_eq!(
            vertices,
            vec![points[0], points[1], points[3]],
            "an open path back to its start keeps both ends"
        );
    }
}
