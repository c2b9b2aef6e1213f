//! Pictures of what each stage saw, for `crawltrace trace --debug DIR`: ink mask, skeleton,
//! sample points, the Delaunay triangulation with the chosen edges, and the result over the input.

use image::{GrayImage, Rgb, RgbImage};
use imageproc::drawing::{draw_filled_circle_mut, draw_line_segment_mut};
use kurbo::Point;

use crate::crawl::neighbours::NeighbourGraph;
use crate::geometry::Polyline;
use crate::output::render::{render_svg_with, RenderOptions};
use crate::raster::bitmap::Bitmap;
use crate::strokes::{Stroke, StrokeEnd};

/// The intermediate results of one trace, kept when [`crate::trace::TraceOptions::keep_stages`]
/// is set: what the stage pictures draw.
#[derive(Clone, Debug)]
pub struct Stages {
    /// The gray image the pipeline started from.
    pub gray: GrayImage,
    /// Ink after thresholding and cleaning.
    pub mask: Bitmap,
    /// The 1-px skeleton.
    pub skeleton: Bitmap,
    /// The centre lines of the double strands (bands of ink where an outline's two sides merged).
    pub bands: Vec<Polyline>,
    /// The sampled strokes.
    pub strokes: Vec<Stroke>,
    /// The reconstructed polylines before fitting.
    pub curves: Vec<Polyline>,
}

const WHITE: Rgb<u8> = Rgb([255, 255, 255]);
const INK: Rgb<u8> = Rgb([0, 0, 0]);
const SKELETON: Rgb<u8> = Rgb([220, 20, 20]);
const DOUBLE_STRAND: Rgb<u8> = Rgb([0, 160, 150]);
const FREE_END: Rgb<u8> = Rgb([230, 120, 0]);
const ATTACHED_END: Rgb<u8> = Rgb([150, 0, 200]);
const DELAUNAY: Rgb<u8> = Rgb([200, 200, 215]);
const OPEN_CURVE: Rgb<u8> = Rgb([230, 60, 20]);
const CLOSED_CURVE: Rgb<u8> = Rgb([20, 90, 220]);

/// The input is faded into the gray levels from this one up, so that what is drawn over it shows.
const FADED_BLACK: u8 = 200;
/// The input's gray levels are divided by this to fit between [`FADED_BLACK`] and white.
const FADE_DIVISOR: u8 = 5;

/// The radius of a sample or curve point, in pixels.
const POINT_RADIUS: i32 = 1;
/// The radius of a stroke end, in pixels: larger than a sample, to tell free and attached ends.
const END_RADIUS: i32 = 3;

/// Rendered pixels lighter than this are paper, left out of the result picture (anti-aliasing
/// fringes included).
const RESULT_PAPER_LEVEL: u8 = 250;

/// The file names of the debug pictures, in pipeline order (known before tracing, so that a
/// front end can check where they go first).
pub const PICTURE_NAMES: [&str; 5] = [
    "1-mask.png",
    "2-skeleton.png",
    "3-samples.png",
    "4-delaunay.png",
    "5-result.png",
];

/// The debug pictures, each with its file name from [`PICTURE_NAMES`], in pipeline order. `svg`
/// is the traced result, drawn over the input in the last picture.
pub fn debug_images(stages: &Stages, svg: &str) -> Vec<(&'static str, RgbImage)> {
    let [mask, skeleton, samples, delaunay, result] = PICTURE_NAMES;
    vec![
        (mask, mask_picture(stages)),
        (skeleton, skeleton_picture(stages)),
        (samples, samples_picture(stages)),
        (delaunay, delaunay_picture(stages)),
        (result, result_picture(stages, svg)),
    ]
}

/// The input, faded to light gray, as the background the other pictures draw on.
fn faded(gray: &GrayImage) -> RgbImage {
    RgbImage::from_fn(gray.width(), gray.height(), |x, y| {
        let level = FADED_BLACK + gray.get_pixel(x, y).0[0] / FADE_DIVISOR;
        Rgb([level, level, level])
    })
}

/// Ink after thresholding and cleaning, black on white.
fn mask_picture(stages: &Stages) -> RgbImage {
    let (width, height) = stages.gray.dimensions();
    RgbImage::from_fn(width, height, |x, y| {
        if stages.mask.get(x as usize, y as usize) {
            INK
        } else {
            WHITE
        }
    })
}

/// The 1-px skeleton in red over the input; double strands (bands where an outline's two sides
/// merged) in teal.
fn skeleton_picture(stages: &Stages) -> RgbImage {
    let mut skeleton = faded(&stages.gray);
    for y in 0..stages.skeleton.height() {
        for x in 0..stages.skeleton.width() {
            if stages.skeleton.get(x, y) {
                skeleton.put_pixel(x as u32, y as u32, SKELETON);
            }
        }
    }
    for band in &stages.bands {
        for &p in &band.points {
            let (x, y) = (p.x.floor() as u32, p.y.floor() as u32);
            if x < skeleton.width() && y < skeleton.height() {
                skeleton.put_pixel(x, y, DOUBLE_STRAND);
            }
        }
    }
    skeleton
}

/// The samples of each stroke in a colour of its own; free pen ends orange, ends attached at a
/// T-junction purple; double strands' centre lines teal beneath.
fn samples_picture(stages: &Stages) -> RgbImage {
    let mut samples = faded(&stages.gray);
    // Under the samples, each double strand's centre line in teal: the two strokes along it are
    // its two sides, going out and coming back (a U-turn where the band ends).
    for band in &stages.bands {
        for pair in band.points.windows(2) {
            line(&mut samples, pair[0], pair[1], DOUBLE_STRAND);
        }
    }
    for (k, stroke) in stages.strokes.iter().enumerate() {
        let color = palette(k);
        let points = &stroke.line.points;
        for pair in points.windows(2) {
            line(&mut samples, pair[0], pair[1], color);
        }
        for &p in points {
            dot(&mut samples, p, POINT_RADIUS, color);
        }
        if stroke.line.closed {
            continue;
        }
        for (end, p) in stroke.ends.iter().zip([points.first(), points.last()]) {
            let (Some(&p), color) = (
                p,
                match end {
                    StrokeEnd::Free => FREE_END,
                    StrokeEnd::Attached(_) => ATTACHED_END,
                },
            ) else {
                continue;
            };
            dot(&mut samples, p, END_RADIUS, color);
        }
    }
    samples
}

/// The Delaunay triangulation of all samples in gray, with the traced curves over it: closed
/// ones blue, open ones red.
fn delaunay_picture(stages: &Stages) -> RgbImage {
    let mut delaunay = faded(&stages.gray);
    let positions: Vec<Point> = {
        let mut all: Vec<Point> = stages
            .strokes
            .iter()
            .flat_map(|s| s.line.points.iter().copied())
            .collect();
        all.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        all.dedup();
        all
    };
    if let Ok(graph) = NeighbourGraph::delaunay(&positions) {
        for v in 0..graph.vertex_count() as u32 {
            for &w in graph.neighbours(v) {
                if w > v {
                    line(
                        &mut delaunay,
                        positions[v as usize],
                        positions[w as usize],
                        DELAUNAY,
                    );
                }
            }
        }
    }
    for curve in &stages.curves {
        let color = if curve.closed {
            CLOSED_CURVE
        } else {
            OPEN_CURVE
        };
        for pair in curve.points.windows(2) {
            line(&mut delaunay, pair[0], pair[1], color);
        }
        if let (true, Some(&first), Some(&last)) =
            (curve.closed, curve.points.first(), curve.points.last())
        {
            line(&mut delaunay, last, first, color);
        }
        for &p in &curve.points {
            dot(&mut delaunay, p, POINT_RADIUS, color);
        }
    }
    delaunay
}

/// The traced SVG rendered in blue over the input.
fn result_picture(stages: &Stages, svg: &str) -> RgbImage {
    let (width, height) = stages.gray.dimensions();
    let mut result = faded(&stages.gray);
    // Our own SVG, the size of the input: the input's size is its canvas limit.
    let options = RenderOptions {
        scale: 1.0,
        max_pixels: u64::from(width) * u64::from(height),
    };
    if let Ok(rendered) = render_svg_with(&recolor(svg), &options) {
        for (x, y, pixel) in rendered.enumerate_pixels() {
            if x < width && y < height && pixel.0[0] < RESULT_PAPER_LEVEL {
                // The rendered paths are pure blue on white: blend by their coverage, in the
                // blue of closed curves.
                let coverage = 1.0 - f32::from(pixel.0[0]) / 255.0;
                let under = result.get_pixel(x, y).0;
                let mix = |a: u8, b: u8| {
                    (f32::from(a) * (1.0 - coverage) + f32::from(b) * coverage) as u8
                };
                result.put_pixel(
                    x,
                    y,
                    Rgb([
                        mix(under[0], CLOSED_CURVE.0[0]),
                        mix(under[1], CLOSED_CURVE.0[1]),
                        mix(under[2], CLOSED_CURVE.0[2]),
                    ]),
                );
            }
        }
    }
    result
}

/// The traced SVG with its stroke colour made pure blue, so coverage can be read off the red
/// channel whatever `--color` was.
fn recolor(svg: &str) -> String {
    match (svg.find("stroke=\""), svg.find("stroke-width")) {
        (Some(start), Some(_)) => {
            let value_start = start + "stroke=\"".len();
            let value_end = svg[value_start..]
                .find('"')
                .map_or(value_start, |e| value_start + e);
            format!("{}#1e5adc{}", &svg[..value_start], &svg[value_end..])
        }
        _ => svg.to_string(),
    }
}

/// Colours told apart at a glance, one per stroke in turn: six of the Tableau 10 colours (its
/// orange and red, which mark free ends and open curves here, and its pink and gray left out).
fn palette(k: usize) -> Rgb<u8> {
    const COLORS: [[u8; 3]; 6] = [
        [31, 119, 180],
        [44, 160, 44],
        [148, 103, 189],
        [23, 190, 207],
        [140, 86, 75],
        [188, 189, 34],
    ];
    Rgb(COLORS[k % COLORS.len()])
}

fn line(image: &mut RgbImage, a: Point, b: Point, color: Rgb<u8>) {
    draw_line_segment_mut(
        image,
        ((a.x - 0.5) as f32, (a.y - 0.5) as f32),
        ((b.x - 0.5) as f32, (b.y - 0.5) as f32),
        color,
    );
}

fn dot(image: &mut RgbImage, p: Point, radius: i32, color: Rgb<u8>) {
    draw_filled_circle_mut(
        image,
        ((p.x - 0.5) as i32, (p.y - 0.5) as i32),
        radius,
        color,
    );
}
