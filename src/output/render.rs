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
    let width = (size.width() * scale).ceil() as u32;
    let height = (size.height() * scale).ceil() as u32;
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
}
