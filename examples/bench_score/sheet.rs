//! Contact sheets of the failing drawings: a grid of cells (30 a page), each the input faded, the
//! truth in thin green, the traced paths over it (closed blue, open red, extras magenta; a dot
//! path as a filled disc), labelled with name, family, style, method and the failure reasons.
//! Overlays are rendered with resvg; labels use the public-domain 8×8 font of `font8x8`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use image::{imageops, Rgba, RgbaImage};

use crate::support::bench::OutputRole;
use crate::support::Polyline;
use crate::{Entry, Outcome};

/// The picture area of a cell, px.
const CELL: u32 = 300;
/// Label lines under each picture, and their height (8 px glyphs with a gap).
const LABEL_LINES: u32 = 4;
const LINE_HEIGHT: u32 = 10;
/// Space around cells, px.
const PADDING: u32 = 8;
const COLUMNS: u32 = 5;
const ROWS: u32 = 6;
/// How much of the input's darkness is kept, so the overlay reads on it.
const INPUT_STRENGTH: f32 = 0.45;

const TRUTH: &str = "#00a000";
const CLOSED: &str = "#1f5fff";
const OPEN: &str = "#e00000";
const EXTRA: &str = "#e000e0";

/// Writes the failures of one method on as many pages as they need; returns the pages written.
pub fn write_sheets(
    path: &Path,
    suffix: Option<&str>,
    method: &str,
    entries: &[Entry],
    outcomes: &[Outcome],
) -> Result<Vec<PathBuf>, String> {
    let failing: Vec<usize> = (0..entries.len())
        .filter(|&i| !outcomes[i].score.exact())
        .collect();
    let per_page = (COLUMNS * ROWS) as usize;
    let stem = path.with_extension("");
    let mut pages = Vec::new();
    for (number, chunk) in failing.chunks(per_page).enumerate() {
        let cell_height = CELL + LABEL_LINES * LINE_HEIGHT + 4;
        let columns = COLUMNS.min(chunk.len() as u32);
        let rows = (chunk.len() as u32).div_ceil(COLUMNS);
        let mut page = RgbaImage::from_pixel(
            columns * (CELL + PADDING) + PADDING,
            rows * (cell_height + PADDING) + PADDING,
            Rgba([200, 200, 200, 255]),
        );
        for (slot, &index) in chunk.iter().enumerate() {
            let cell = cell(&entries[index], &outcomes[index], method)?;
            let (column, row) = (slot as u32 % COLUMNS, slot as u32 / COLUMNS);
            let x = PADDING + column * (CELL + PADDING);
            let y = PADDING + row * (cell_height + PADDING);
            imageops::replace(&mut page, &cell, i64::from(x), i64::from(y));
        }
        let mut name = stem.as_os_str().to_owned();
        if let Some(suffix) = suffix {
            name.push(format!("-{suffix}"));
        }
        name.push(format!("-{}.png", number + 1));
        let page_path = PathBuf::from(name);
        page.save(&page_path)
            .map_err(|e| format!("{}: cannot write: {e}", page_path.display()))?;
        pages.push(page_path);
    }
    Ok(pages)
}

/// One cell: the picture with its overlay, then the label.
fn cell(entry: &Entry, outcome: &Outcome, method: &str) -> Result<RgbaImage, String> {
    let input = image::open(&entry.image)
        .map_err(|e| format!("{}: {e}", entry.image.display()))?
        .to_rgba8();
    let (width, height) = input.dimensions();
    let scale = (CELL as f32 / width as f32).min(CELL as f32 / height as f32);
    let (shown_width, shown_height) = (
        ((width as f32 * scale).round() as u32).max(1),
        ((height as f32 * scale).round() as u32).max(1),
    );
    let mut picture = imageops::resize(
        &input,
        shown_width,
        shown_height,
        imageops::FilterType::Triangle,
    );
    for pixel in picture.pixels_mut() {
        for channel in 0..3 {
            let ink = 255.0 - f32::from(pixel.0[channel]);
            pixel.0[channel] = (255.0 - ink * INPUT_STRENGTH) as u8;
        }
        pixel.0[3] = 255;
    }
    let overlay = overlay_svg(
        entry,
        outcome,
        (width, height),
        (shown_width, shown_height),
        scale,
    );
    draw_over(&mut picture, &overlay)?;

    let label_height = LABEL_LINES * LINE_HEIGHT + 4;
    let mut cell = RgbaImage::from_pixel(CELL, CELL + label_height, Rgba([255, 255, 255, 255]));
    imageops::replace(&mut cell, &picture, 0, 0);
    let kinds: Vec<&str> = outcome.score.kinds().iter().map(|k| k.name()).collect();
    let lines = [
        entry.name.clone(),
        format!("{} / {} / {method}", entry.truth.family, entry.truth.style),
        kinds.join(", "),
        format!(
            "worst {:.1} px, tol {:.1}, {} paths",
            outcome.score.worst_distance,
            outcome.score.tolerance,
            outcome.output.len()
        ),
    ];
    for (number, line) in lines.iter().enumerate() {
        draw_text(&mut cell, 2, CELL + 3 + number as u32 * LINE_HEIGHT, line);
    }
    Ok(cell)
}

/// The truth (thin green) and the traced paths (coloured by role), in image coordinates scaled
/// to the cell.
fn overlay_svg(
    entry: &Entry,
    outcome: &Outcome,
    (width, height): (u32, u32),
    (shown_width, shown_height): (u32, u32),
    scale: f32,
) -> String {
    let unit = 1.0 / f64::from(scale);
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{shown_width}\" \
         height=\"{shown_height}\" viewBox=\"0 0 {width} {height}\">\n\
         <g fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n"
    );
    for curve in &entry.truth.curves {
        path_element(&mut svg, curve, TRUTH, 1.0 * unit);
    }
    for dot in &entry.truth.dots {
        let _ = writeln!(
            svg,
            "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"{:.2}\" stroke=\"{TRUTH}\" stroke-width=\"{:.2}\"/>",
            dot.centre.x,
            dot.centre.y,
            dot.diameter / 2.0,
            unit
        );
    }
    for (path, role) in outcome.output.iter().zip(&outcome.score.roles) {
        let colour = match (role, path.closed) {
            (OutputRole::Extra, _) => EXTRA,
            (_, true) => CLOSED,
            (_, false) => OPEN,
        };
        if path.points.len() == 1 || span(path) < 2.0 * unit {
            let centre = path.points[0];
            let _ = writeln!(
                svg,
                "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"{:.2}\" fill=\"{colour}\"/>",
                centre.x,
                centre.y,
                2.5 * unit
            );
        } else {
            path_element(&mut svg, path, colour, 1.6 * unit);
        }
    }
    svg.push_str("</g>\n</svg>\n");
    svg
}

fn span(path: &Polyline) -> f64 {
    let first = path.points[0];
    path.points
        .iter()
        .map(|p| p.distance(first))
        .fold(0.0, f64::max)
}

fn path_element(svg: &mut String, path: &Polyline, colour: &str, width: f64) {
    let _ = write!(
        svg,
        "<path stroke=\"{colour}\" stroke-width=\"{width:.2}\" d=\""
    );
    for (index, point) in path.points.iter().enumerate() {
        let command = if index == 0 { 'M' } else { 'L' };
        let _ = write!(svg, "{command}{:.2} {:.2} ", point.x, point.y);
    }
    if path.closed {
        svg.push('Z');
    }
    svg.push_str("\"/>\n");
}

/// Renders `svg` (the picture's size) and lays it over `picture`.
fn draw_over(picture: &mut RgbaImage, svg: &str) -> Result<(), String> {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())
        .map_err(|e| format!("overlay: {e}"))?;
    let mut pixmap = resvg::tiny_skia::Pixmap::new(picture.width(), picture.height())
        .ok_or("overlay: empty picture")?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    // The pixmap is premultiplied: out = overlay + picture × (1 − overlay alpha).
    for (pixel, over) in picture.pixels_mut().zip(pixmap.data().chunks_exact(4)) {
        let keep = 1.0 - f32::from(over[3]) / 255.0;
        for (channel, &added) in pixel.0.iter_mut().zip(&over[..3]) {
            let value = f32::from(added) + f32::from(*channel) * keep;
            *channel = value.round().min(255.0) as u8;
        }
    }
    Ok(())
}

/// Writes `text` with its top-left corner at `(x, y)`, one 8×8 glyph per character, clipped to
/// the image.
fn draw_text(image: &mut RgbaImage, x: u32, y: u32, text: &str) {
    for (index, character) in text.chars().enumerate() {
        let code = if character.is_ascii() {
            character as usize
        } else {
            '?' as usize
        };
        let glyph = font8x8::legacy::BASIC_LEGACY[code];
        let left = x + 8 * index as u32;
        for (row, bits) in glyph.iter().enumerate() {
            for column in 0..8 {
                let (px, py) = (left + column, y + row as u32);
                if bits >> column & 1 == 1 && px < image.width() && py < image.height() {
                    image.put_pixel(px, py, Rgba([30, 30, 30, 255]));
                }
            }
        }
    }
}
