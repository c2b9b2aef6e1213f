//! Writes a [`Drawing`] as SVG text, following the conventions of `docs/design.md` ("SVG
//! conventions"): viewBox in pixels, one `<path>` per curve, `Z` on closed curves, at most two
//! decimals, byte-identical output for identical input; `width`/`height` in pixels, or in mm or
//! inches at a given density ([`to_svg_with_size`]).

use std::fmt::Write as _;

use kurbo::{BezPath, PathEl, Point};

pub use super::fit::CurvePath;
use super::units::PhysicalSize;

/// Vector curves on a canvas, ready to be written as SVG.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawing {
    /// Canvas width in pixels.
    pub width: f64,
    /// Canvas height in pixels.
    pub height: f64,
    /// One entry per curve, in a stable order.
    pub paths: Vec<CurvePath>,
    /// Stroke width in pixels.
    pub stroke_width: f64,
    /// Stroke colour, any SVG colour (`#000000`, `black`, …).
    pub color: String,
    /// Points drawn as small red dots (outliers of a point set); empty for traced images.
    pub dots: Vec<Point>,
    /// Points drawn as small blue dots over the curves (every input point of a point set, with
    /// `points --show-points`); empty otherwise.
    pub points: Vec<Point>,
}

/// Coordinates and sizes are written with at most this many decimals: a hundredth of a pixel is
/// below what any renderer shows, and shorter numbers keep the files small.
const DECIMALS: usize = 2;

/// The thinnest stroke and the smallest dot written: what two decimals can still show (a width
/// of 0 would hide the paths).
const MIN_SIZE: f64 = 0.01;

/// Input points (`points --show-points`) are dots of this radius, in stroke widths: visible over
/// the curve they lie on.
const POINT_RADIUS_IN_STROKE_WIDTHS: f64 = 1.2;
/// Their colour: a blue that stands out on the black curves.
const POINT_COLOUR: &str = "#1e5adc";

/// Outliers of a point set are dots of this radius, in stroke widths: a little larger than the
/// input points, so that they show over them.
const OUTLIER_RADIUS_IN_STROKE_WIDTHS: f64 = 1.5;
/// Their colour: red, for points that belong to no curve.
const OUTLIER_COLOUR: &str = "#d33";

/// Formats a number with at most two decimals, no trailing zeros and no `-0`.
pub fn format_number(value: f64) -> String {
    format_hundredths(value).unwrap_or_else(|| format_exactly(value))
}

/// [`format_number`] by the formatter's exact decimal rounding, for the numbers
/// [`format_hundredths`] leaves to it.
fn format_exactly(value: f64) -> String {
    let mut text = format!("{value:.DECIMALS$}");
    if text.contains('.') {
        let trimmed = text.trim_end_matches('0').trim_end_matches('.').len();
        text.truncate(trimmed);
    }
    if text == "-0" {
        text = "0".to_string();
    }
    text
}

/// Largest magnitude (in hundredths) [`format_hundredths`] formats: below it the product
/// `value × 100` is within 1.2e-7 of the exact one.
const HUNDREDTHS_LIMIT: f64 = 1e9;

/// How near (in hundredths) a half the product may come for [`format_hundredths`] to leave the
/// number to the exact formatting: far above the product's own rounding error.
const HALF_MARGIN: f64 = 1e-6;

/// [`format_number`]'s text, the same byte for byte, from the value rounded to hundredths as an
/// integer, or `None` where that might differ from the exact decimal rounding of `{:.2}`: a
/// product that lies within [`HALF_MARGIN`] of a half, a value too large or not finite. The
/// formatter's exact rounding cost about 1400 instructions a number (docs/performance.md, stop 70).
fn format_hundredths(value: f64) -> Option<String> {
    debug_assert_eq!(DECIMALS, 2);
    let scaled = value.abs() * 100.0;
    if scaled.is_nan() || scaled >= HUNDREDTHS_LIMIT {
        return None;
    }
    let whole = scaled as u64; // exact: below 2^53, truncated towards zero
    let fraction = scaled - whole as f64;
    if (fraction - 0.5).abs() < HALF_MARGIN {
        return None;
    }
    let units = whole + u64::from(fraction > 0.5);
    let mut text = String::with_capacity(16);
    if units == 0 {
        text.push('0');
        return Some(text);
    }
    if value < 0.0 {
        text.push('-');
    }
    let _ = write!(text, "{}", units / 100);
    let cents = units % 100;
    if cents != 0 {
        text.push('.');
        text.push(char::from(b'0' + (cents / 10) as u8));
        if cents % 10 != 0 {
            text.push(char::from(b'0' + (cents % 10) as u8));
        }
    }
    Some(text)
}

/// The `d` attribute of a path.
pub fn path_data(path: &BezPath) -> String {
    let mut d = String::new();
    let point = |d: &mut String, p: Point| {
        let _ = write!(d, "{} {}", format_number(p.x), format_number(p.y));
    };
    for element in path.elements() {
        if !d.is_empty() {
            d.push(' ');
        }
        match *element {
            PathEl::MoveTo(p) => {
                d.push('M');
                point(&mut d, p);
            }
            PathEl::LineTo(p) => {
                d.push('L');
                point(&mut d, p);
            }
            PathEl::QuadTo(a, p) => {
                d.push('Q');
                point(&mut d, a);
                d.push(' ');
                point(&mut d, p);
            }
            PathEl::CurveTo(a, b, p) => {
                d.push('C');
                point(&mut d, a);
                d.push(' ');
                point(&mut d, b);
                d.push(' ');
                point(&mut d, p);
            }
            PathEl::ClosePath => d.push('Z'),
        }
    }
    d
}

/// Writes `drawing` as a standalone SVG document, following the conventions of `docs/design.md`
/// ("SVG conventions"): the canvas in pixels, one `<path>` per curve, `Z` on closed ones,
/// coordinates with at most two decimals; the same drawing always gives the same bytes.
///
/// # Examples
///
/// ```
/// use crawltrace::{to_svg, CurvePath, Drawing, Point};
///
/// let triangle = [Point::new(10.5, 10.5), Point::new(50.5, 10.5), Point::new(30.5, 40.5)];
/// let drawing = Drawing {
///     width: 64.0,
///     height: 48.0,
///     paths: vec![CurvePath::polyline(&triangle, true)],
///     stroke_width: 2.0,
///     color: "black".into(),
///     dots: Vec::new(),
///     points: Vec::new(),
/// };
/// let svg = to_svg(&drawing);
/// assert!(svg.contains(r#"viewBox="0 0 64 48""#));
/// assert!(svg.contains(r#"<path d="M10.5 10.5 L50.5 10.5 L30.5 40.5 Z"/>"#));
/// ```
///
/// # Errors
///
/// None: every drawing can be written (the text is built in memory).
pub fn to_svg(drawing: &Drawing) -> String {
    write_svg(
        drawing,
        &format_number(drawing.width),
        &format_number(drawing.height),
    )
}

/// Physical sizes (`width="210mm"`) are written with this many decimals: a tenth of a micrometre
/// in millimetres, 2.5 µm in inches, finer than any cutter or plotter moves.
const PHYSICAL_DECIMALS: usize = 4;

/// Writes `drawing` as [`to_svg`] does, but with `width` and `height` in physical units
/// (`210mm`, `8.2677in`) at `size`'s density; the `viewBox` and every coordinate stay in pixels,
/// so only the size the SVG is shown, printed or cut at changes.
///
/// # Examples
///
/// ```
/// use crawltrace::stages::units::{PhysicalSize, Units};
/// use crawltrace::{to_svg_with_size, Drawing};
///
/// let drawing = Drawing {
///     width: 600.0,
///     height: 300.0,
///     paths: Vec::new(),
///     stroke_width: 2.0,
///     color: "black".into(),
///     dots: Vec::new(),
///     points: Vec::new(),
/// };
/// // 600 px at 300 dpi are 2 inches, 50.8 mm.
/// let svg = to_svg_with_size(&drawing, &PhysicalSize { dpi: 300.0, units: Units::Mm });
/// assert!(svg.contains(r#"width="50.8mm" height="25.4mm" viewBox="0 0 600 300""#));
/// ```
pub fn to_svg_with_size(drawing: &Drawing, size: &PhysicalSize) -> String {
    let physical = |pixels: f64| {
        let mut text = format!("{:.PHYSICAL_DECIMALS$}", size.length(pixels));
        let trimmed = text.trim_end_matches('0').trim_end_matches('.').len();
        text.truncate(trimmed);
        format!("{text}{}", size.units.name())
    };
    write_svg(drawing, &physical(drawing.width), &physical(drawing.height))
}

/// The SVG document of `drawing` with the given `width` and `height` attributes.
fn write_svg(drawing: &Drawing, width: &str, height: &str) -> String {
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {} {}">"#,
        format_number(drawing.width),
        format_number(drawing.height),
    );
    let _ = writeln!(
        svg,
        r#"<g fill="none" stroke="{}" stroke-width="{}" stroke-linecap="round" stroke-linejoin="round">"#,
        escape_attribute(&drawing.color),
        format_number(drawing.stroke_width.max(MIN_SIZE)),
    );
    for curve in &drawing.paths {
        match curve.stroke_width {
            Some(width) => {
                let _ = writeln!(
                    svg,
                    r#"<path stroke-width="{}" d="{}"/>"#,
                    format_number(width.max(MIN_SIZE)),
                    path_data(&curve.path)
                );
            }
            None => {
                let _ = writeln!(svg, r#"<path d="{}"/>"#, path_data(&curve.path));
            }
        }
    }
    svg.push_str("</g>\n");
    write_dots(
        &mut svg,
        &drawing.points,
        POINT_COLOUR,
        drawing.stroke_width * POINT_RADIUS_IN_STROKE_WIDTHS,
    );
    write_dots(
        &mut svg,
        &drawing.dots,
        OUTLIER_COLOUR,
        drawing.stroke_width * OUTLIER_RADIUS_IN_STROKE_WIDTHS,
    );
    svg.push_str("</svg>\n");
    svg
}

/// A group of filled circles of `radius` at `centres`; nothing when there are none.
fn write_dots(svg: &mut String, centres: &[Point], fill: &str, radius: f64) {
    if centres.is_empty() {
        return;
    }
    let radius = format_number(radius.max(MIN_SIZE));
    let _ = writeln!(svg, r#"<g fill="{fill}">"#);
    for centre in centres {
        let _ = writeln!(
            svg,
            r#"<circle cx="{}" cy="{}" r="{radius}"/>"#,
            format_number(centre.x),
            format_number(centre.y)
        );
    }
    svg.push_str("</g>\n");
}

fn escape_attribute(value: &str) -> String {
    value
        .replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::units::Units;

    #[test]
    fn numbers_have_at_most_two_decimals_and_no_negative_zero() {
        assert_eq!(format_number(1.0), "1");
        assert_eq!(format_number(1.5), "1.5");
        assert_eq!(format_number(1.239), "1.24");
        assert_eq!(format_number(-0.001), "0");
        assert_eq!(format_number(-2.10), "-2.1");
        assert_eq!(format_number(100.0), "100");
    }

    #[test]
    fn hundredths_format_every_number_as_the_exact_rounding_does() {
        let mut values = vec![
            0.0,
            -0.0,
            0.005,
            0.015,
            0.125,
            -0.125,
            1.005,
            2.675,
            0.004_999,
            -0.004_999,
            0.5,
            -0.5,
            9.995,
            99.999_999,
            1e7 - 0.005,
            1e7,
            1.5e7,
            1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            4000.0 / 3.0,
            -2_999.999_5,
        ];
        // Every thousandth up to ±5000 and an irregular spread of values up to ±50000.
        values.extend(
            (-5_000_000..=5_000_000)
                .step_by(7)
                .map(|k| f64::from(k) / 1000.0),
        );
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            values.push((state >> 11) as f64 / (1u64 << 53) as f64 * 1e5 - 5e4);
        }
        for value in values {
            assert_eq!(format_number(value), format_exactly(value), "{value:e}");
        }
        // Near a half it leaves the number to the formatter; elsewhere it answers.
        assert_eq!(format_hundredths(0.125), None);
        assert_eq!(format_hundredths(-12.345_6).as_deref(), Some("-12.35"));
        assert_eq!(format_hundredths(3.1), Some("3.1".to_string()));
    }

    #[test]
    fn closed_polylines_end_with_z_and_open_ones_do_not() {
        let square = [
            Point::new(0.5, 0.5),
            Point::new(10.5, 0.5),
            Point::new(10.5, 10.5),
        ];
        let closed = CurvePath::polyline(&square, true);
        assert_eq!(path_data(&closed.path), "M0.5 0.5 L10.5 0.5 L10.5 10.5 Z");
        let open = CurvePath::polyline(&square, false);
        assert_eq!(path_data(&open.path), "M0.5 0.5 L10.5 0.5 L10.5 10.5");
    }

    #[test]
    fn document_has_the_canvas_as_view_box_and_one_path_per_curve() {
        let drawing = Drawing {
            width: 40.0,
            height: 30.0,
            paths: vec![
                CurvePath::polyline(&[Point::new(1.0, 1.0), Point::new(5.0, 5.0)], false),
                CurvePath::polyline(
                    &[
                        Point::new(1.0, 1.0),
                        Point::new(5.0, 1.0),
                        Point::new(5.0, 5.0),
                    ],
                    true,
                ),
            ],
            stroke_width: 2.0,
            color: "black".into(),
            dots: vec![],
            points: vec![],
        };
        let svg = to_svg(&drawing);
        assert!(
            svg.contains(r#"width="40" height="30" viewBox="0 0 40 30""#),
            "{svg}"
        );
        assert_eq!(svg.matches("<path ").count(), 2);
        assert_eq!(svg.matches('Z').count(), 1);
        let tree = usvg::Tree::from_str(&svg, &usvg::Options::default()).expect("usvg parses it");
        assert_eq!(tree.size().width(), 40.0);
    }

    /// usvg, like browsers, takes 96 CSS pixels to the inch: the size it reads back is the
    /// physical size asked for.
    #[test]
    fn physical_sizes_read_back_with_usvg() {
        let drawing = Drawing {
            width: 2480.0,
            height: 3508.0,
            paths: vec![CurvePath::polyline(
                &[Point::new(10.0, 10.0), Point::new(2000.0, 3000.0)],
                false,
            )],
            stroke_width: 3.0,
            color: "black".into(),
            dots: vec![],
            points: vec![],
        };
        for (units, dpi) in [(Units::Mm, 300.0), (Units::In, 300.0), (Units::Mm, 96.0)] {
            let svg = to_svg_with_size(&drawing, &PhysicalSize { dpi, units });
            assert!(svg.contains(r#"viewBox="0 0 2480 3508""#), "{svg}");
            let tree = usvg::Tree::from_str(&svg, &usvg::Options::default()).unwrap();
            let css_pixels_per_image_pixel = 96.0 / dpi;
            let expected_width = 2480.0 * css_pixels_per_image_pixel;
            let expected_height = 3508.0 * css_pixels_per_image_pixel;
            assert!(
                (f64::from(tree.size().width()) - expected_width).abs() < 0.01,
                "{units}: {} vs {expected_width}",
                tree.size().width()
            );
            assert!((f64::from(tree.size().height()) - expected_height).abs() < 0.01);
        }
        let a4 = to_svg_with_size(
            &drawing,
            &PhysicalSize {
                dpi: 300.0,
                units: Units::Mm,
            },
        );
        assert!(
            a4.contains(r#"width="209.9733mm" height="297.0107mm""#),
            "{a4}"
        );
    }
}
