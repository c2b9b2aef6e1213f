//! Dots: the marks a pen leaves when it touches the paper without moving (periods, the dot of an
//! i, dotted lines). Their skeleton is a point or a stub no longer than the ink is wide; they are
//! kept as dots, never bridged into a stroke and never dropped as stray marks.

use kurbo::Point;

use super::{Stroke, StrokeEnd};
use crate::geometry::polyline::polyline_length;
use crate::raster::bitmap::Bitmap;
use crate::raster::radius::ink_radius;

/// A dot: where it is and how wide its ink is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dot {
    /// The middle of its skeleton.
    pub centre: Point,
    /// The width of its ink, in pixels.
    pub diameter: f64,
}

/// DECISION: a mark is a dot when it is about as wide as it is long: its skeleton no longer than
/// the ink's radius, so the whole mark at most 1.5 times as long as wide. A dash drawn with the
/// pen is at least about twice as long as wide (its skeleton a pen width or more); a round dot
/// thins to a point or a stub of a pixel or two.
const DOT_MAX_SKELETON_IN_RADII: f64 = 1.0;

/// The ink's radius is looked for this many pen widths out at most: dots are 1–3 pen widths wide.
const DOT_RADIUS_SEARCH_IN_PEN_WIDTHS: f64 = 3.0;

/// Takes the dots out of `strokes`: free-ended open strokes whose skeleton is no longer than the
/// ink around it is wide (`DOT_MAX_SKELETON_IN_RADII`). The others are returned in order.
pub fn split_dots(
    strokes: Vec<Stroke>,
    mask: &Bitmap,
    stroke_width: f64,
) -> (Vec<Stroke>, Vec<Dot>) {
    let limit = DOT_RADIUS_SEARCH_IN_PEN_WIDTHS * stroke_width.max(1.0);
    let mut kept = Vec::with_capacity(strokes.len());
    let mut dots = Vec::new();
    for stroke in strokes {
        match as_dot(&stroke, mask, limit) {
            Some(dot) => dots.push(dot),
            None => kept.push(stroke),
        }
    }
    (kept, dots)
}

fn as_dot(stroke: &Stroke, mask: &Bitmap, limit: f64) -> Option<Dot> {
    let points = &stroke.line.points;
    if stroke.line.closed || stroke.ends != [StrokeEnd::Free, StrokeEnd::Free] {
        return None;
    }
    let length = polyline_length(points, false);
    // Cheap first: a stroke longer than the widest dot is no dot.
    if length > DOT_MAX_SKELETON_IN_RADII * limit {
        return None;
    }
    let radius = points
        .iter()
        .map(|&p| ink_radius(mask, p, limit))
        .fold(0.0, f64::max);
    if length > DOT_MAX_SKELETON_IN_RADII * radius {
        return None;
    }
    let centre = Stroke::point_at_half_length(points);
    Some(Dot {
        centre,
        diameter: 2.0 * radius,
    })
}

impl Stroke {
    /// The point halfway along `points`.
    fn point_at_half_length(points: &[Point]) -> Point {
        let half = 0.5 * polyline_length(points, false);
        let mut walked = 0.0;
        for pair in points.windows(2) {
            let step = pair[0].distance(pair[1]);
            if walked + step >= half && step > 0.0 {
                return pair[0].lerp(pair[1], (half - walked) / step);
            }
            walked += step;
        }
        points[0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::thin::thin;
    use crate::strokes::extract_strokes;

    fn dots_and_strokes(grid: &str, stroke_width: f64) -> (Vec<Stroke>, Vec<Dot>) {
        let mask = Bitmap::from_grid(grid);
        let strokes = extract_strokes(&thin(&mask), &mask, stroke_width);
        split_dots(strokes, &mask, stroke_width)
    }

    #[test]
    fn a_round_blob_is_a_dot_and_a_dash_is_not() {
        let (strokes, dots) = dots_and_strokes(
            "
            ....................
            ..###...............
            .#####..##########..
            .#####..##########..
            .#####..##########..
            ..###...............
            ....................",
            3.0,
        );
        assert_eq!(dots.len(), 1, "{dots:?}");
        assert!(
            dots[0].centre.distance(Point::new(3.5, 3.5)) < 1.0,
            "{dots:?}"
        );
        assert!((4.0..=6.0).contains(&dots[0].diameter), "{dots:?}");
        assert_eq!(strokes.len(), 1, "{strokes:?}");
    }

    #[test]
    fn a_single_pixel_is_a_dot() {
        let (strokes, dots) = dots_and_strokes("...\n.#.\n...", 1.0);
        assert!(strokes.is_empty());
        assert_eq!(dots.len(), 1);
        assert_eq!(dots[0].centre, Point::new(1.5, 1.5));
    }
}
