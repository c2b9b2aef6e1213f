//! Output of point-set reconstruction: the JSON format and the SVG drawing of
//! `docs/design.md` ("Command line"), for the `points` command.

use std::io::{self, Write};

use kurbo::{Point, Rect};
use rayon::prelude::*;
use serde::Serialize;

use crate::crawl::reconstruct::Reconstruction;
use crate::output::svg::{CurvePath, Drawing};

#[derive(Serialize)]
struct JsonCurve<'a> {
    closed: bool,
    indices: &'a [usize],
    points: Vec<[f64; 2]>,
}

/// Writes `{"curves":[{"closed":…,"indices":[…],"points":[[x,y],…]}],"outliers":[…],"duplicates":[[dropped,kept],…]}`
/// followed by a newline. Indices count the input points from 0; coordinates are the input's.
///
/// The curves are formatted in parallel, each by serde_json on its own, then joined: the bytes
/// are those serde_json writes for the whole document at once.
pub fn write_json(
    out: &mut impl Write,
    points: &[Point],
    reconstruction: &Reconstruction,
) -> io::Result<()> {
    let curves: Vec<Vec<u8>> = reconstruction
        .curves
        .par_iter()
        .map(|curve| {
            let json = JsonCurve {
                closed: curve.closed,
                indices: &curve.indices,
                points: curve
                    .indices
                    .iter()
                    .map(|&i| [points[i].x, points[i].y])
                    .collect(),
            };
            serde_json::to_vec(&json).expect("a curve serializes: it holds numbers only")
        })
        .collect();
    out.write_all(b"{\"curves\":[")?;
    for (k, curve) in curves.iter().enumerate() {
        if k > 0 {
            out.write_all(b",")?;
        }
        out.write_all(curve)?;
    }
    out.write_all(b"],\"outliers\":")?;
    serde_json::to_writer(&mut *out, &reconstruction.outliers).map_err(io::Error::from)?;
    out.write_all(b",\"duplicates\":")?;
    // `[dropped, kept]` input indices of exact duplicates that were merged.
    let duplicates: Vec<[usize; 2]> = reconstruction
        .merged_duplicates
        .iter()
        .map(|d| [d.dropped, d.kept])
        .collect();
    serde_json::to_writer(&mut *out, &duplicates).map_err(io::Error::from)?;
    out.write_all(b"}\n")
}

/// The longer side of the canvas a point set is drawn on, in pixels.
const CANVAS_SIZE: f64 = 1000.0;

/// The margin around the points, as a share of [`CANVAS_SIZE`]: room for the dots at the edge.
const MARGIN_SHARE: f64 = 0.02;

/// The stroke width of the curves on that canvas, in pixels: thin next to 1000 px, yet visible
/// when the drawing is shown small.
const STROKE_WIDTH_PX: f64 = 2.0;

/// Draws the reconstruction: the point set's bounding box is scaled onto a canvas 1000 px on its
/// longer side (so that two decimals are enough whatever the input's units), with a margin.
/// Outliers are drawn as red dots, and with `show_points` every input point as a blue dot. The y
/// axis points down, as in the input's own units.
pub fn to_drawing(points: &[Point], reconstruction: &Reconstruction, show_points: bool) -> Drawing {
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
    let margin = MARGIN_SHARE * CANVAS_SIZE;
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
        stroke_width: STROKE_WIDTH_PX,
        color: "#000000".into(),
        dots: reconstruction
            .outliers
            .iter()
            .map(|&i| map(points[i]))
            .collect(),
        points: if show_points {
            points.iter().map(|&p| map(p)).collect()
        } else {
            Vec::new()
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::crawl::reconstruct::{Curve, MergedDuplicate};

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
    fn json_is_what_serde_json_writes_for_the_whole_document() {
        #[derive(Serialize)]
        struct Document<'a> {
            curves: Vec<JsonCurve<'a>>,
            outliers: &'a [usize],
            duplicates: Vec<[usize; 2]>,
        }
        let points: Vec<Point> = (0..40)
            .map(|k| Point::new(k as f64 * 0.1 - 1.0, (k * k) as f64 / 7.0 + 1e-9))
            .collect();
        let curve = |indices: Vec<usize>, closed| Curve { indices, closed };
        for reconstruction in [
            Reconstruction::default(),
            Reconstruction {
                curves: vec![
                    curve((0..10).collect(), true),
                    curve(vec![12, 11, 13], false),
                    curve((20..40).rev().collect(), true),
                ],
                outliers: vec![10, 14, 15],
                merged_duplicates: vec![
                    MergedDuplicate {
                        dropped: 16,
                        kept: 3,
                    },
                    MergedDuplicate {
                        dropped: 17,
                        kept: 3,
                    },
                ],
            },
        ] {
            let document = Document {
                curves: reconstruction
                    .curves
                    .iter()
                    .map(|c| JsonCurve {
                        closed: c.closed,
                        indices: &c.indices,
                        points: c
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
            let mut expected = serde_json::to_vec(&document).unwrap();
            expected.push(b'\n');
            let mut out = Vec::new();
            write_json(&mut out, &points, &reconstruction).unwrap();
            assert_eq!(
                String::from_utf8(out).unwrap(),
                String::from_utf8(expected).unwrap()
            );
        }
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
        let drawing = to_drawing(&points, &reconstruction, false);
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
