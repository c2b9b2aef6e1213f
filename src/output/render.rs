//! Rasterizes SVG with usvg + resvg (<https://github.com/linebender/resvg>), for previews, the
//! golden-image round-trip tests and the `--debug` pictures, within limits: no file is read (an
//! `<image>` is never loaded, wherever it points), the canvas has at most so many pixels, and a
//! document whose layers, filters or pattern tiles would take more work or memory than the
//! budget is refused before rendering (`render_budget`).

use std::panic::{catch_unwind, AssertUnwindSafe};

use image::RgbaImage;

use super::render_budget::{estimate, parse_hazard, Cost, ParseHazard};
pub use super::render_budget::{MAX_ARC_CURVES, MAX_USE_ELEMENTS};

/// Why an SVG could not be rasterized.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// usvg rejected the document.
    #[error("not a valid SVG: {0}")]
    Parse(#[from] usvg::Error),
    /// The requested raster is empty, or its scale is not a positive number.
    #[error("cannot make a {width}×{height} raster (scale {scale})")]
    Size {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
        /// The scale that led to it.
        scale: f32,
    },
    /// The raster would have more pixels than [`RenderOptions::max_pixels`].
    #[error(
        "the canvas would be {width}×{height} pixels ({:.1} megapixels), more than the limit of {:.1} (--max-pixels)",
        f64::from(*.width) * f64::from(*.height) / 1e6,
        *.max_pixels as f64 / 1e6
    )]
    Canvas {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
        /// The limit.
        max_pixels: u64,
    },
    /// Its filters, layers or pattern tiles need more work or memory than rendering may take.
    #[error("refusing to render: it needs about {operations:.1e} pixel operations and {megabytes:.0} MB of layers (at most {:.0e} and {:.0} MB)", MAX_OPERATIONS, MAX_LAYER_BYTES / 1e6)]
    TooCostly {
        /// The estimated pixel operations.
        operations: f64,
        /// The estimated layer memory, in megabytes.
        megabytes: f64,
    },
    /// An elliptical arc so large that usvg would take unbounded time to turn it into curves.
    #[error("refusing to render: an arc of radius {radius:.1e} would become {curves:.1e} curves (at most {:.0e})", MAX_ARC_CURVES)]
    Arc {
        /// Its largest radius, in user units.
        radius: f64,
        /// The curves usvg would make of it.
        curves: f64,
    },
    /// `<use>` elements that would copy content into more elements than parsing may make.
    #[error(
        "refusing to render: its <use> elements would add {elements:.1e} elements (at most {:.0e})",
        MAX_USE_ELEMENTS
    )]
    Uses {
        /// The elements the uses would add.
        elements: f64,
    },
    /// usvg or resvg panicked on it (a bug upstream, contained: see docs/cli.md, "Known limits
    /// (upstream)").
    #[error("the renderer failed on it: {0}")]
    Crashed(String),
}

/// The largest canvas by default: 64 megapixels (256 MB of RGBA), room for a 4000 × 3000 page
/// at scale 2.
pub const DEFAULT_MAX_PIXELS: u64 = 64_000_000;

/// A raster side within this much (pixels) above a whole number is that number: a size in mm or
/// inches (`width="52.9167mm"`, 200 px at 96 dpi) comes back from usvg's f32 arithmetic a hair
/// above the pixel count it was written from, and must not gain a row of pixels.
const SIZE_ROUNDING_SLACK: f32 = 0.01;

/// DECISION: the most pixel operations a render may take, about four seconds on one core of the
/// development machine (an operation is about a nanosecond: a morphology of radius 50 on 200 ×
/// 200 pixels, 4 × 10⁸ operations, took 0.42 s; a blur over 23 megapixels, 1.9 × 10⁹, 2.2 s).
/// Our own SVGs at the largest canvas need about 10⁸.
pub const MAX_OPERATIONS: f64 = 4e9;

/// DECISION: the most memory the layers of a render may hold at once, beyond the canvas: 256 MB,
/// one canvas of the largest size, so that a render stays within about twice its canvas.
pub const MAX_LAYER_BYTES: f64 = 256e6;

/// How to render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// Pixels per SVG pixel.
    pub scale: f32,
    /// The largest canvas accepted, in pixels.
    pub max_pixels: u64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            scale: 1.0,
            max_pixels: DEFAULT_MAX_PIXELS,
        }
    }
}

/// Renders `svg` at `scale` (1 = the document's own pixel size) onto a white background, within
/// the default limits ([`render_svg_with`]).
///
/// # Examples
///
/// ```
/// use crawltrace::render_svg;
///
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10">
///     <path d="M0 5 L20 5" stroke="black" stroke-width="2"/></svg>"#;
/// let image = render_svg(svg, 2.0)?;
/// assert_eq!(image.dimensions(), (40, 20));
/// assert_eq!(image.get_pixel(20, 10).0, [0, 0, 0, 255]);
/// assert_eq!(image.get_pixel(20, 1).0, [255, 255, 255, 255]);
/// # Ok::<(), crawltrace::RenderError>(())
/// ```
///
/// # Errors
///
/// As [`render_svg_with`].
pub fn render_svg(svg: &str, scale: f32) -> Result<RgbaImage, RenderError> {
    render_svg_with(
        svg,
        &RenderOptions {
            scale,
            ..RenderOptions::default()
        },
    )
}

/// Renders `svg` onto a white background. No file is read: `<image>` elements are dropped,
/// whether they point to a file, another SVG or embedded data. [`prepare_render`] then
/// [`PreparedRender::render`].
///
/// # Errors
///
/// As [`prepare_render`].
pub fn render_svg_with(svg: &str, options: &RenderOptions) -> Result<RgbaImage, RenderError> {
    prepare_render(svg, options)?.render()
}

/// A parsed SVG whose canvas and cost were checked, ready to render.
pub struct PreparedRender {
    tree: usvg::Tree,
    width: u32,
    height: u32,
    scale: f32,
    cost: Cost,
}

/// Parses `svg` (reading no file) and checks its canvas size and the cost of rendering it, so
/// that a caller can bound the render itself by what it will take (`crawltrace render` sets its
/// sandbox's time and memory from it).
///
/// Arcs that usvg would turn into more than [`MAX_ARC_CURVES`] curves, and `<use>` elements
/// that would add more than [`MAX_USE_ELEMENTS`] elements, are refused before usvg parses (an
/// arc of radius 10³⁸ never finished; ten levels of ten uses make 10¹⁰ elements). Whatever else
/// usvg might spend unbounded work on while parsing is not seen here (see docs/cli.md, "Known
/// limits (upstream)"); `crawltrace render` runs it in a separate process with time and memory limits.
///
/// # Errors
///
/// [`RenderError::Parse`] when the text is not an SVG document usvg reads,
/// [`RenderError::Arc`] when an arc is too large to parse in bounded time, [`RenderError::Uses`]
/// when `<use>` elements would expand beyond the limit,
/// [`RenderError::Size`] when the raster would be empty or the scale is not a positive number,
/// [`RenderError::Canvas`] when it would have more than [`RenderOptions::max_pixels`], and
/// [`RenderError::TooCostly`] when its layers, filters and pattern tiles would need more than
/// [`MAX_OPERATIONS`] or [`MAX_LAYER_BYTES`].
pub fn prepare_render(svg: &str, options: &RenderOptions) -> Result<PreparedRender, RenderError> {
    let tree = parse(svg)?;
    let (width, height) = canvas_size(&tree, options)?;
    let cost = estimate(&tree, options.scale, width, height);
    check_cost(cost)?;
    Ok(PreparedRender {
        tree,
        width,
        height,
        scale: options.scale,
        cost,
    })
}

impl PreparedRender {
    /// The canvas size in pixels.
    pub fn dimensions(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The estimated pixel operations of the render (at most [`MAX_OPERATIONS`]).
    pub fn operations(&self) -> f64 {
        self.cost.operations
    }

    /// The estimated memory of its layers beyond the canvas, in bytes (at most
    /// [`MAX_LAYER_BYTES`]).
    pub fn layer_bytes(&self) -> f64 {
        self.cost.peak_bytes
    }

    /// Renders onto a white background.
    ///
    /// # Errors
    ///
    /// [`RenderError::Size`] when tiny-skia cannot make a pixmap of this size (a side beyond
    /// what its 32-bit strides hold, with a pixel limit raised that far).
    pub fn render(self) -> Result<RgbaImage, RenderError> {
        let (width, height) = (self.width, self.height);
        let Some(mut pixmap) = resvg::tiny_skia::Pixmap::new(width, height) else {
            return Err(RenderError::Size {
                width,
                height,
                scale: self.scale,
            });
        };
        pixmap.fill(resvg::tiny_skia::Color::WHITE);
        let transform = resvg::tiny_skia::Transform::from_scale(self.scale, self.scale);
        contain(|| resvg::render(&self.tree, transform, &mut pixmap.as_mut()))?;
        // The background is opaque, so premultiplied and straight alpha coincide.
        Ok(RgbaImage::from_raw(width, height, pixmap.take()).expect("pixmap is width×height RGBA"))
    }
}

/// Parses `svg` without reading any file: every `<image>` resolves to nothing. Arcs that usvg
/// would spend unbounded time on are refused first.
fn parse(svg: &str) -> Result<usvg::Tree, RenderError> {
    match parse_hazard(svg) {
        Some(ParseHazard::Arc { radius, curves }) => {
            return Err(RenderError::Arc { radius, curves })
        }
        Some(ParseHazard::Uses { elements }) => return Err(RenderError::Uses { elements }),
        None => {}
    }
    let options = usvg::Options {
        resources_dir: None,
        image_href_resolver: usvg::ImageHrefResolver {
            resolve_data: Box::new(|_, _, _| None),
            resolve_string: Box::new(|_, _| None),
        },
        ..usvg::Options::default()
    };
    contain(|| usvg::Tree::from_str(svg, &options))?.map_err(RenderError::Parse)
}

/// Runs `work`, turning a panic of usvg or resvg into [`RenderError::Crashed`] with its message
/// (tiny-skia 0.12 panics on some huge dashed shapes: `a_huge_dashed_circle_is_an_error`).
fn contain<T>(work: impl FnOnce() -> T) -> Result<T, RenderError> {
    catch_unwind(AssertUnwindSafe(work)).map_err(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|text| text.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic".to_string());
        RenderError::Crashed(message.lines().next().unwrap_or_default().to_string())
    })
}

/// The raster size of `tree` at the options' scale, checked against the limit.
fn canvas_size(tree: &usvg::Tree, options: &RenderOptions) -> Result<(u32, u32), RenderError> {
    let scale = options.scale;
    let size = tree.size();
    let (width, height) = (
        f64::from(size.width()) * f64::from(scale),
        f64::from(size.height()) * f64::from(scale),
    );
    let side = |length: f64| {
        (length - f64::from(SIZE_ROUNDING_SLACK))
            .ceil()
            .min(f64::from(u32::MAX)) as u32
    };
    let (width, height) = (side(width), side(height));
    if !(scale.is_finite() && scale > 0.0) || width == 0 || height == 0 {
        return Err(RenderError::Size {
            width,
            height,
            scale,
        });
    }
    if u64::from(width) * u64::from(height) > options.max_pixels {
        return Err(RenderError::Canvas {
            width,
            height,
            max_pixels: options.max_pixels,
        });
    }
    Ok((width, height))
}

/// Refuses a render that would cost more than the budget.
fn check_cost(cost: Cost) -> Result<(), RenderError> {
    let within = cost.operations <= MAX_OPERATIONS && cost.peak_bytes <= MAX_LAYER_BYTES;
    if within {
        Ok(())
    } else {
        Err(RenderError::TooCostly {
            operations: cost.operations,
            megabytes: cost.peak_bytes / 1e6,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn document(body: &str) -> String {
        format!(r#"<svg xmlns="http://www.w3.org/2000/svg" width="200" height="200">{body}</svg>"#)
    }

    #[test]
    fn rejects_garbage_and_absurd_scales() {
        assert!(matches!(
            render_svg("not svg", 1.0),
            Err(RenderError::Parse(_))
        ));
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10"/>"#;
        for scale in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert!(
                matches!(render_svg(svg, scale), Err(RenderError::Size { .. })),
                "{scale}"
            );
        }
        assert!(matches!(
            render_svg(svg, 1e6),
            Err(RenderError::Canvas { .. })
        ));
    }

    /// Issue 13: a 119-byte SVG of 29 999 × 29 999 pixels took 3.5 GB.
    #[test]
    fn the_canvas_is_limited() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="29999" height="29999"/>"#;
        let error = render_svg(svg, 1.0).unwrap_err();
        assert!(
            matches!(error, RenderError::Canvas { width: 29_999, .. }),
            "{error}"
        );
        let small = RenderOptions {
            scale: 1.0,
            max_pixels: 399,
        };
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="20" height="20"/>"#;
        assert!(render_svg_with(svg, &small).is_err());
        assert!(render_svg_with(
            svg,
            &RenderOptions {
                max_pixels: 400,
                ..small
            }
        )
        .is_ok());
    }

    /// Issue 13: `<image href="/etc/passwd">`, relative paths and other SVGs were read, and
    /// `/dev/zero` was read until memory ran out. Nothing is read; the rest of the drawing is.
    #[test]
    fn images_are_never_loaded() {
        let folder = tempfile::tempdir().unwrap();
        let other = folder.path().join("other.svg");
        std::fs::write(
            &other,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="40" height="40"><rect width="40" height="40"/></svg>"#,
        )
        .unwrap();
        let embedded = "data:image/svg+xml,%3Csvg xmlns='http://www.w3.org/2000/svg' width='40' height='40'%3E%3Crect width='40' height='40'/%3E%3C/svg%3E";
        for href in [
            other.to_str().unwrap(),
            "/etc/passwd",
            "/dev/zero",
            "file:///etc/hostname",
            "other.svg",
            embedded,
        ] {
            let svg = document(&format!(
                r#"<image href="{href}" width="200" height="200"/><rect x="150" y="150" width="10" height="10"/>"#
            ));
            let image = render_svg(&svg, 1.0).unwrap_or_else(|e| panic!("{href}: {e}"));
            assert_eq!(
                image.get_pixel(20, 20).0,
                [255, 255, 255, 255],
                "{href} was drawn"
            );
            assert_eq!(image.get_pixel(155, 155).0, [0, 0, 0, 255], "{href}");
        }
    }

    /// Issue 13: a turbulence of a million octaves and a morphology of radius 10⁶ never finished;
    /// both are refused from their cost. Reasonable filters still render.
    #[test]
    fn costly_filters_are_refused_before_rendering() {
        for body in [
            r#"<filter id="f"><feTurbulence baseFrequency="0.05" numOctaves="1000000"/></filter><rect width="200" height="200" filter="url(#f)"/>"#,
            r#"<filter id="f" x="-1e6" y="-1e6" width="2e6" height="2e6" filterUnits="userSpaceOnUse"><feMorphology radius="1e6"/></filter><rect width="100" height="100" filter="url(#f)"/>"#,
            r#"<pattern id="p" width="1e5" height="1e5" patternUnits="userSpaceOnUse"><rect width="5" height="5"/></pattern><rect width="200" height="200" fill="url(#p)"/>"#,
        ] {
            let error = render_svg(&document(body), 1.0).unwrap_err();
            assert!(
                matches!(error, RenderError::TooCostly { .. }),
                "{body}: {error}"
            );
            assert!(
                error.to_string().starts_with("refusing to render"),
                "{error}"
            );
        }
        for body in [
            r#"<filter id="f"><feTurbulence baseFrequency="0.05" numOctaves="4"/></filter><rect width="200" height="200" filter="url(#f)"/>"#,
            r#"<filter id="f"><feMorphology radius="3"/><feGaussianBlur stdDeviation="1e9"/></filter><rect width="100" height="100" filter="url(#f)"/>"#,
            r#"<pattern id="p" width="10" height="1e-38" patternUnits="userSpaceOnUse"><rect width="5" height="1e-38"/></pattern><rect width="200" height="200" fill="url(#p)"/>"#,
        ] {
            assert!(render_svg(&document(body), 1.0).is_ok(), "{body}");
        }
    }

    /// Found by the fuzz harness's hostile SVGs: tiny-skia 0.12 panics (alpha_runs.rs) on a
    /// circle of radius 10³⁰ with dashes. Its dashes are now counted and refused before
    /// rendering; the panic, were it reached, is an error too (`contain`), never a crash.
    #[test]
    fn a_huge_dashed_circle_is_an_error() {
        let svg =
            document(r#"<circle r="1e30" cx="100" cy="100" stroke="black" stroke-dasharray="1"/>"#);
        match render_svg(&svg, 1.0) {
            Err(RenderError::TooCostly { .. } | RenderError::Crashed(_)) => {}
            other => panic!("{:?}", other.map(|image| image.dimensions())),
        }
    }

    /// Found by the fuzz harness (svg, seed 1, case 182): one arc of radii 65535 and 10³⁸ kept
    /// usvg's parser busy for minutes (its work grows with the square of the curves it makes).
    #[test]
    fn a_huge_arc_is_refused_before_parsing() {
        let svg =
            document(r#"<path d="M10 10 A65535 1e38 0 1 1 190 190" stroke="black" fill="red"/>"#);
        let error = render_svg(&svg, 1.0).unwrap_err();
        assert!(matches!(error, RenderError::Arc { .. }), "{error}");
        let fine = document(r#"<path d="M10 10 A65535 1e6 0 1 1 190 190" fill="red"/>"#);
        assert!(render_svg(&fine, 1.0).is_ok());
    }

    /// Found by the fuzz harness (svg, seed 1, cases 5225 and 5350): strokes dashed every 10⁻⁹
    /// made tiny-skia abort (not a panic: nothing to catch), and a dashed circle of radius 10³⁸
    /// filled memory. The dashes are counted into the cost; ordinary dashes still render.
    #[test]
    fn dashes_are_counted() {
        for body in [
            r#"<path d="M-1 0 L200 200 L0 200 Z" stroke="black" stroke-dasharray="1e-9 1e-9"/>"#,
            r#"<circle cx="50" cy="50" r="1e38" stroke="black" stroke-dasharray="4 2"/>"#,
        ] {
            let error = render_svg(&document(body), 1.0).unwrap_err();
            assert!(
                matches!(error, RenderError::TooCostly { .. }),
                "{body}: {error}"
            );
        }
        let fine =
            document(r#"<circle cx="50" cy="50" r="40" stroke="black" stroke-dasharray="4 2"/>"#);
        assert!(render_svg(&fine, 1.0).is_ok());
    }

    /// Layers nested deeply hold a pixmap each at once: their memory is counted.
    #[test]
    fn deeply_nested_layers_are_counted() {
        let nested = |depth: usize| {
            document(&format!(
                "{}<rect width=\"200\" height=\"200\"/>{}",
                r#"<g opacity="0.5">"#.repeat(depth),
                "</g>".repeat(depth)
            ))
        };
        assert!(render_svg(&nested(20), 1.0).is_ok());
        let error = render_svg(&nested(20), 30.0).unwrap_err();
        assert!(matches!(error, RenderError::TooCostly { .. }), "{error}");
    }

    #[test]
    fn physical_sizes_render_at_their_pixel_count() {
        // 200 × 150 px at 96 dpi, written in mm with four decimals.
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="52.9167mm" height="39.6875mm" viewBox="0 0 200 150"/>"#;
        assert_eq!(render_svg(svg, 1.0).unwrap().dimensions(), (200, 150));
        assert_eq!(render_svg(svg, 2.0).unwrap().dimensions(), (400, 300));
        // A real fraction still rounds up.
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="20.5" height="10"/>"#;
        assert_eq!(render_svg(svg, 1.0).unwrap().dimensions(), (21, 10));
    }
}
