//! Rasterizes SVG with usvg + resvg (<https://github.com/linebender/resvg>), for previews and for
//! the golden-image round-trip tests.

use image::RgbaImage;

/// Why an SVG could not be rasterized.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// usvg rejected the document.
    #[error("not a valid SVG: {0}")]
    Parse(#[from] usvg::Error),
    /// The requested raster is empty or too large.
    #[error("cannot make a {width}×{height} raster (scale {scale})")]
    Size {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
        /// The scale that led to it.
        scale: f32,
    },
}

/// The largest raster side we agree to allocate, in pixels.
const MAX_SIDE: u32 = 30_000;

/// A raster side within this much (pixels) above a whole number is that number: a size in mm or
/// inches (`width="52.9167mm"`, 200 px at 96 dpi) comes back from usvg's f32 arithmetic a hair
/// above the pixel count it was written from, and must not gain a row of pixels.
const SIZE_ROUNDING_SLACK: f32 = 0.01;

/// Renders `svg` at `scale` (1 = the document's own pixel size) onto a white background.
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
/// [`RenderError::Parse`] when the text is not an SVG document usvg reads, and
/// [`RenderError::Size`] when the raster would be empty or larger than 30 000 pixels a side.
pub fn render_svg(svg: &str, scale: f32) -> Result<RgbaImage, RenderError> {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())?;
    let size = tree.size();
    let whole_pixels = |length: f32| (length * scale - SIZE_ROUNDING_SLACK).ceil() as u32;
    let (width, height) = (whole_pixels(size.width()), whole_pixels(size.height()));
    let too_big = !(scale.is_finite() && scale > 0.0) || width > MAX_SIDE || height > MAX_SIDE;
    let pixmap = if too_big {
        None
    } else {
        resvg::tiny_skia::Pixmap::new(width, height)
    };
    let mut pixmap = match pixmap {
        Some(pixmap) => pixmap,
        None => {
            return Err(RenderError::Size {
                width,
                height,
                scale,
            })
        }
    };
    pixmap.fill(resvg::tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    // The background is opaque, so premultiplied and straight alpha coincide.
    Ok(RgbaImage::from_raw(width, height, pixmap.take()).expect("pixmap is width×height RGBA"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_garbage_and_absurd_scales() {
        assert!(matches!(
            render_svg("not svg", 1.0),
            Err(RenderError::Parse(_))
        ));
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10"/>"#;
        assert!(matches!(
            render_svg(svg, 0.0),
            Err(RenderError::Size { .. })
        ));
        assert!(matches!(
            render_svg(svg, 1e6),
            Err(RenderError::Size { .. })
        ));
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
