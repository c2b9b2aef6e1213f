//! One benchmark drawing from its family, style, number and split seed: the figure laid out on a
//! page of random size, sketched with the hand's strokes, rendered and encoded like the samples,
//! with its ground truth (`NAME.truth.svg`) and its manifest line.

use std::fmt::Write as _;

use crawltrace::stages::svg::format_number;
use crawltrace::{to_svg, CurvePath, Drawing};
use kurbo::{Affine, Vec2};

use super::families::{hand_for, pen_width, Family, FAMILIES};
use super::figure::Figure;
use super::geometry::TrueCurve;
use super::paper::Style;
use super::pen::{draw_dot, draw_intervals, pen_intervals, Hand};
use super::random::SplitMix64;
use super::sketch::{strokes_to_svg, Stroke};

/// Truth polylines stay this close to the dense true curves, px (as for the samples).
const TRUTH_TOLERANCE: f64 = 0.05;
/// Pages are at least this wide and high, px.
const SMALLEST_PAGE: f64 = 300.0;
/// Room around the drawing: at least this many pen widths plus 10 px, plus up to this much more.
const MARGIN_PENS: f64 = 2.0;
const EXTRA_MARGIN: f64 = 90.0;

/// A generated drawing, ready to be written.
pub struct Generated {
    /// File name without extension, `FAMILY-STYLE-NNN`.
    pub name: String,
    /// Image file name (`.png`, or `.jpg` for the scan style).
    pub image_file: String,
    /// The encoded image.
    pub image: Vec<u8>,
    /// The ground truth SVG.
    pub truth: String,
    /// The drawing's line of `manifest.jsonl`.
    pub manifest: String,
}

/// The seed of drawing `index` of `family` in `style` within the split `split_seed`.
pub fn drawing_seed(split_seed: u64, family: usize, style: usize, index: usize) -> u64 {
    let key = split_seed.wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ ((family as u64) << 40)
        ^ ((style as u64) << 32)
        ^ index as u64;
    SplitMix64::new(key).next_u64()
}

/// Drawing number `index` of family `family` (an index into [`FAMILIES`]) in `style`.
pub fn generate(
    family: usize,
    style: Style,
    style_index: usize,
    index: usize,
    split_seed: u64,
) -> Generated {
    let seed = drawing_seed(split_seed, family, style_index, index);
    let family: &Family = &FAMILIES[family];
    let mut random = SplitMix64::new(seed);
    let pen = pen_width(style, family.touching, &mut random);
    let mut hand = hand_for(family, pen, &mut random);
    let figure = family.build(&mut hand, &mut random);
    let (figure, width, height) = lay_out(&figure, &hand, &mut random);

    let curves: Vec<TrueCurve> = figure
        .parts
        .iter()
        .map(|part| TrueCurve::from_points(part.shape.points.clone(), part.shape.closed))
        .collect();
    let strokes = sketch_figure(&figure, &curves, &hand, style, &mut random);
    let sketch = strokes_to_svg(width, height, &strokes);
    let rendered = crawltrace::render_svg(&sketch, 1.0).expect("the sketch renders");
    let image = style.encode(&rendered, seed);

    let name = format!("{}-{}-{index:03}", family.name, style.name());
    let image_file = format!("{name}.{}", style.extension());
    let drawn = Drawn {
        name: &name,
        family,
        style,
        hand: &hand,
        seed,
        size: (width, height),
        curves: &curves,
        figure: &figure,
    };
    let truth = truth_svg(&drawn);
    let manifest = manifest_line(&drawn, &image_file, strokes.len());
    Generated {
        name,
        image_file,
        image,
        truth,
        manifest,
    }
}

/// What the ground truth and the manifest line describe: one drawing as it was made.
struct Drawn<'a> {
    name: &'a str,
    family: &'a Family,
    style: Style,
    hand: &'a Hand,
    seed: u64,
    /// Page width and height, px.
    size: (u32, u32),
    curves: &'a [TrueCurve],
    figure: &'a Figure,
}

/// Every stroke of the figure (curves along their plans, then dots), in a random drawing order.
fn sketch_figure(
    figure: &Figure,
    curves: &[TrueCurve],
    hand: &Hand,
    style: Style,
    random: &mut SplitMix64,
) -> Vec<Stroke> {
    let mut strokes: Vec<Stroke> = Vec::new();
    for (curve, part) in curves.iter().zip(&figure.parts) {
        let intervals = pen_intervals(curve, &part.plan, hand, random);
        strokes.extend(draw_intervals(
            curve,
            &intervals,
            hand,
            style.lightest_ink(),
            random,
        ));
    }
    for dot in &figure.dots {
        strokes.push(draw_dot(
            dot.centre,
            dot.diameter,
            style.lightest_ink(),
            random,
        ));
    }
    // People start anywhere and draw in any order.
    random.shuffle_by_index(&mut strokes);
    strokes
}

/// The drawing's line of `manifest.jsonl`.
fn manifest_line(drawn: &Drawn, image_file: &str, strokes: usize) -> String {
    let name = drawn.name;
    let (width, height) = drawn.size;
    serde_json::json!({
        "name": name,
        "image": image_file,
        "truth": format!("{name}.truth.svg"),
        "family": drawn.family.name,
        "touching": drawn.family.touching,
        "style": drawn.style.name(),
        "pen": round2(drawn.hand.pen),
        "jitter": round2(drawn.hand.jitter),
        "tolerance": round2(drawn.hand.jitter + drawn.hand.pen / 2.0 + 2.0),
        "width": width,
        "height": height,
        "curves": drawn.curves.len(),
        "closed_curves": drawn.curves.iter().filter(|c| c.closed).count(),
        "dots": drawn.figure.dots.len(),
        "strokes": strokes,
        "gap_px": [round2(drawn.hand.gap.0), round2(drawn.hand.gap.1)],
        "stroke_px": [round2(drawn.hand.stroke.0), round2(drawn.hand.stroke.1)],
        "seed": drawn.seed,
    })
    .to_string()
}

fn round2(value: f64) -> f64 {
    (value * 100.0).round() / 100.0
}

/// The figure moved onto a page of random size (at least 300 px a side) at a random place.
fn lay_out(figure: &Figure, hand: &Hand, random: &mut SplitMix64) -> (Figure, u32, u32) {
    let bounds = figure.bounds();
    let margin = MARGIN_PENS * hand.pen + 10.0;
    let mut side = |extent: f64| {
        let needed = extent + 2.0 * margin;
        let page = (needed + random.range(0.0, EXTRA_MARGIN))
            .max(SMALLEST_PAGE)
            .ceil();
        let offset = random.range(margin, page - extent - margin);
        (page, offset)
    };
    let (width, left) = side(bounds.width());
    let (height, top) = side(bounds.height());
    let moved = figure.transformed(Affine::translate(Vec2::new(
        left - bounds.x0,
        top - bounds.y0,
    )));
    (moved, width as u32, height as u32)
}

/// The ground truth: one `<path>` per true curve (like the samples' truth files), then each dot
/// as a zero-length round-capped path as wide as the dot, in a group marked `data-kind="dots"`.
/// The root carries the family, style, pen width and jitter as `data-` attributes.
fn truth_svg(drawn: &Drawn) -> String {
    let &Drawn {
        name,
        family,
        style,
        hand,
        seed,
        size: (width, height),
        curves,
        figure,
    } = drawn;
    let drawing = Drawing {
        width: f64::from(width),
        height: f64::from(height),
        paths: curves
            .iter()
            .map(|curve| CurvePath::polyline(&curve.simplified(TRUTH_TOLERANCE), curve.closed))
            .collect(),
        stroke_width: hand.pen,
        color: "black".into(),
        dots: Vec::new(),
        points: Vec::new(),
    };
    let svg = to_svg(&drawing);
    let (root, rest) = svg.split_once('\n').expect("to_svg writes lines");
    let body = rest
        .strip_suffix("</svg>\n")
        .expect("to_svg ends the document");
    let pen = format_number(hand.pen);
    let jitter = format_number(hand.jitter);
    let mut text = format!(
        "{} data-family=\"{}\" data-touching=\"{}\" data-style=\"{}\" data-pen=\"{pen}\" \
         data-jitter=\"{jitter}\">\n\
         <!-- ground truth of benchmark drawing {name}: family {}, style {}, pen {pen} px, \
         jitter {jitter} px, seed {seed}; made by examples/make_bench.rs, see docs/benchmark.md -->\n{body}",
        root.strip_suffix('>').expect("the root tag ends the line"),
        family.name,
        family.touching,
        style.name(),
        family.name,
        style.name(),
    );
    if !figure.dots.is_empty() {
        text.push_str(
            "<g data-kind=\"dots\" fill=\"none\" stroke=\"black\" stroke-linecap=\"round\">\n",
        );
        for dot in &figure.dots {
            let _ = writeln!(
                text,
                "<path stroke-width=\"{}\" d=\"M{} {} h0\"/>",
                format_number(dot.diameter),
                format_number(dot.centre.x),
                format_number(dot.centre.y)
            );
        }
        text.push_str("</g>\n");
    }
    text.push_str("</svg>\n");
    text
}
