//! Output of point-set reconstruction: the JSON format and the SVG drawing of
//! `../shared/DESIGN.md` ("Command line"), for the `points` command.

use std::io::{self, Write};

use kurbo::{Point, Rect};
use serde::Serialize;

use crate::reconstruct::Reconstruction;
use crate::svg::{CurvePath, Drawing};

#[derive(Serialize)]
struct JsonCurve<'a> {
    closed: bool,
    indices: &'a [usize],
    points: Vec<[f64; 2]>,
}

#[derive(Serialize)]
struct JsonReconstruction<'a> {
    curves: Vec<JsonCurve<'a>>,
    outliers: &'a [usize],
    /// `[dropped, kept]` input indices of exact duplicates that were merged.
    duplicates: Vec<[usize; 2]>,
}

/// Writes `{"curves":[{"closed":…,"indices":[…],"points":[[x,y],…]}],"outliers":[…],"duplicates":[[dropped,kept],…]}`
/// followed by a newline. Indices count the input points from 0; coordinates are the input's.
pub fn write_json(
    out: &mut impl Write,
    points: &[Point],
    reconstruction: &Reconstruction,
) -> io::Result<()> {
    let document = JsonReconstruction {
        curves: reconstruction
            .curves
            .iter()
            .map(|curve| JsonCurve {
                closed: curve.closed,
                indices: &curve.indices,
                points: curve
                    .indices
                    .iter()
                    .map(|&i| [points[i].x, points[i].y])
                    .collect(),
            })
            .collect(),
        outliers: &reconstruction.outliers,
        duplicates: reconstruction
            .merged_duplicates
            .iter()
            .map(|d| [d.dropped, d.kept])
            .collect(),
    };
    serde_json::to_writer(&mut *out, &document).map_err(io::Error::from)?;
    out.write_all(b"\n")
}

/// The longer side of the canvas a point set is drawn on, in pixels.
const CANVAS_SIZE: f64 = 1000.0;

/// Draws the reconstruction: the point set's bounding box is scaled onto a canvas 1000 px on its
/// longer side (so that two decimals are enough whatever the input's units), with a margin.
/// Outliers are drawn as red dots. The y axis points down, as in the input's own units.
pub fn to_drawing(points: &[Point], reconstruction: &Reconstruction) -> Drawing {
    let bounds = points
        .iter()
        .fold(None::<Rect>, |bounds, &p| {
            Some(match bounds {
                Some(r) => r.union_pt(p),
                None => Rect::from_points(p, p),
            })
        })
        .unwrap_or(Rect::new(0.0, 0.0, 1.0, 1.0));
    let extent = bounds.width().max(bounds.height());
    let scale = if extent > 0.0 {
        CANVAS_SIZE / extent
    } else {
        1.0
    };
    let margin = 0.02 * CANVAS_SIZE;
    let map = |p: Point| {
        Point::new(
            (p.x - bounds.x0) * scale + margin,
            (p.y - bounds.y0) * scale + margin,
        )
    };
    Drawing {
        width: (bounds.width() * scale + 2.0 * margin).ceil(),
        height: (bounds.height() * scale + 2.0 * margin).ceil(),
        paths: reconstruction
            .curves
            .iter()
            .map(|curve| {
                let mapped: Vec<Point> = curve.indices.iter().map(|&i| map(points[i])).collect();
                CurvePath::polyline(&mapped, curve.closed)
            })
            .collect(),
        stroke_width: 2.0,
        color: "#000000".into(),
        dots: reconstruction
            .outliers
            .iter()
            .map(|&i| map(points[i]))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reconstruct::{Curve, MergedDuplicate};

    #[test]
    fn json_names_curves_by_input_index_with_their_coordinates() {
        let points = [
            Point::new(0.0, 0.0),
            Point::new(1.5, 0.0),
            Point::new(1.5, 2.0),
            Point::new(9.0, 9.0),
            Point::new(0.0, 0.0),
        ];
        let reconstruction = Reconstruction {
            curves: vec![Curve {
                indices: vec![0, 1, 2],
                closed: true,
            }],
            outliers: vec![3],
            merged_duplicates: vec![MergedDuplicate {
                dropped: 4,
                kept: 0,
            }],
        };
        let mut out = Vec::new();
        write_json(&mut out, &points, &reconstruction).unwrap();
        assert_eq!(
            String::from_utf8(out).unwrap(),
            "{\"curves\":[{\"closed\":true,\"indices\":[0,1,2],\"points\":[[0.0,0.0],[1.5,0.0],[1.5,2.0]]}],\"outliers\":[3],\"duplicates\":[[4,0]]}\n"
        );
    }

    #[test]
    fn drawing_fits_the_points_on_the_canvas() {
        let points = [
            Point::new(0.0, 0.0),
            Point::new(0.002, 0.0),
            Point::new(0.002, 0.001),
        ];
        let reconstruction = Reconstruction {
            curves: vec![Curve {
                indices: vec![0, 1, 2],
                closed: false,
            }],
            ..Default::default()
        };
        let drawing = to_drawing(&points, &reconstruction);
        assert_eq!((drawing.width, drawing.height), (1040.0, 540.0));
        let end = drawing.paths[0]
            .path
            .elements()
            .last()
            .unwrap()
            .end_point()
            .unwrap();
        assert!(
            (end.x - 1020.0).abs() < 1e-9 && (end.y - 520.0).abs() < 1e-9,
            "{end:?}"
        );
    }
}
