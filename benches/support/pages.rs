//! The 4000×3000 test pages of the `trace` benchmark and of `scripts/compare-tracers.sh`: the
//! committed `samples/page-4000x3000.png` when present, otherwise a comparable page drawn here
//! deterministically; and a scan-like JPEG of it (uneven light, sensor noise, warm paper).
//!
//! Shared by `benches/trace.rs` and `examples/bench_pages.rs` through `#[path]`, so the benchmark
//! and the comparison script trace the very same bytes.

#![allow(dead_code)] // each includer uses a different part

#[path = "../../tests/support/random.rs"]
mod random;
use random::SplitMix64;

use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use crawltrace::stages::bitmap::Bitmap;
use image::codecs::jpeg::JpegEncoder;
use image::{GrayImage, ImageFormat, Rgb, RgbImage};

pub const WIDTH: u32 = 4000;
pub const HEIGHT: u32 = 3000;

/// The committed page, relative to the crate root.
pub const SAMPLE_PAGE: &str = "samples/page-4000x3000.png";

/// Where the page comes from, for the benchmark's header line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PageSource {
    /// `samples/page-4000x3000.png`.
    Sample,
    /// Drawn by [`generate_page`] (fresh clone without the sample).
    Generated,
}

/// The PNG bytes of the page: the committed sample if present, else the generated page.
pub fn page_png() -> (Vec<u8>, PageSource) {
    let sample = Path::new(env!("CARGO_MANIFEST_DIR")).join(SAMPLE_PAGE);
    match std::fs::read(&sample) {
        Ok(bytes) => (bytes, PageSource::Sample),
        Err(_) => (encode_png(&generate_page()), PageSource::Generated),
    }
}

/// The path of the committed sample page, if present.
pub fn sample_path() -> Option<PathBuf> {
    let sample = Path::new(env!("CARGO_MANIFEST_DIR")).join(SAMPLE_PAGE);
    sample.is_file().then_some(sample)
}

pub fn encode_png(gray: &GrayImage) -> Vec<u8> {
    let mut bytes = Vec::new();
    gray.write_to(&mut Cursor::new(&mut bytes), ImageFormat::Png)
        .expect("PNG encoding to memory");
    bytes
}

/// A page like the sample: a 4×4 grid of cells, each holding one to three shapes (circles,
/// ellipses, rectangles, polygons, stars, concentric rings, spirals and waves), every one drawn
/// as a skip-stroke sketch — short dashes with small gaps, a 3 px pen — and rendered with resvg.
pub fn generate_page() -> GrayImage {
    let mut random = SplitMix64::new(2026);
    let mut svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" viewBox="0 0 {WIDTH} {HEIGHT}"><g fill="none" stroke="black" stroke-width="3" stroke-linecap="round">"#
    );
    let (cell_w, cell_h) = (f64::from(WIDTH) / 4.0, f64::from(HEIGHT) / 4.0);
    for row in 0..4 {
        for column in 0..4 {
            let shapes = 1 + random.next_u64() % 3;
            for k in 0..shapes {
                // Shapes side by side in their cell, none touching.
                let slot_w = cell_w / shapes as f64;
                let centre = (
                    f64::from(column) * cell_w + (k as f64 + 0.5) * slot_w,
                    f64::from(row) * cell_h + 0.5 * cell_h,
                );
                let size = (0.5 * slot_w).min(0.5 * cell_h) * random.range(0.55, 0.8);
                let points = shape(&mut random, centre, size);
                let closed = points.first() == points.last();
                let mut d = String::new();
                for (i, (x, y)) in points.iter().enumerate() {
                    let _ = write!(d, "{}{x:.2} {y:.2} ", if i == 0 { "M" } else { "L" });
                }
                // The skip strokes: dashes of 25–70 px with gaps of 3–9 px, starting anywhere.
                let (dash, gap) = (random.range(25.0, 70.0), random.range(3.0, 9.0));
                let offset = random.range(0.0, dash + gap);
                let _ = write!(
                    svg,
                    r#"<path d="{}{}" stroke-dasharray="{dash:.1} {gap:.1}" stroke-dashoffset="{offset:.1}"/>"#,
                    d.trim_end(),
                    if closed { " Z" } else { "" }
                );
            }
        }
    }
    svg.push_str("</g></svg>");
    let rgba = crawltrace::render_svg(&svg, 1.0).expect("the generated SVG renders");
    image::DynamicImage::ImageRgba8(rgba).to_luma8()
}

/// One shape's outline around `centre`, at most `size` from it; closed outlines repeat their
/// first point at the end.
fn shape(random: &mut SplitMix64, centre: (f64, f64), size: f64) -> Vec<(f64, f64)> {
    let (cx, cy) = centre;
    let around = |n: usize, radius: &dyn Fn(f64) -> (f64, f64)| -> Vec<(f64, f64)> {
        (0..=n)
            .map(|i| {
                let t = TAU * (i % n) as f64 / n as f64;
                let (rx, ry) = radius(t);
                (cx + rx * t.cos(), cy + ry * t.sin())
            })
            .collect()
    };
    match random.next_u64() % 7 {
        0 => around(180, &|_| (size, size)),
        1 => {
            let squash = random.range(0.45, 0.8);
            around(180, &|_| (size, size * squash))
        }
        2 | 3 => {
            // A polygon of 3–6 corners, turned at random.
            let corners = 3 + (random.next_u64() % 4) as usize;
            let turn = random.range(0.0, TAU);
            (0..=corners)
                .map(|i| {
                    let t = turn + TAU * (i % corners) as f64 / corners as f64;
                    (cx + size * t.cos(), cy + size * t.sin())
                })
                .collect()
        }
        4 => {
            // A five-pointed star.
            (0..=10)
                .map(|i| {
                    let t = -PI / 2.0 + PI * (i % 10) as f64 / 5.0;
                    let r = if i % 2 == 0 { size } else { 0.42 * size };
                    (cx + r * t.cos(), cy + r * t.sin())
                })
                .collect()
        }
        5 => {
            // An open spiral of three turns.
            (0..=540)
                .map(|i| {
                    let t = 3.0 * TAU * f64::from(i) / 540.0;
                    let r = size * (0.12 + 0.88 * f64::from(i) / 540.0);
                    (cx + r * t.cos(), cy + r * t.sin())
                })
                .collect()
        }
        _ => {
            // An open wave.
            (0..=240)
                .map(|i| {
                    let s = f64::from(i) / 240.0;
                    (
                        cx - size + 2.0 * size * s,
                        cy + 0.25 * size * (4.0 * TAU * s).sin(),
                    )
                })
                .collect()
        }
    }
}

/// A phone-scan-like colour JPEG of `page` (quality 85): warm paper, light falling off to one
/// side and to the corners, and sensor noise; ink stays dark but not black.
pub fn scan_jpeg(page: &GrayImage) -> Vec<u8> {
    let mut noise = SplitMix64::new(99);
    let (width, height) = page.dimensions();
    let mut rgb = RgbImage::new(width, height);
    for (x, y, pixel) in rgb.enumerate_pixels_mut() {
        let (u, v) = (
            f64::from(x) / f64::from(width),
            f64::from(y) / f64::from(height),
        );
        let (du, dv) = (u - 0.5, v - 0.5);
        let light = (1.0 - 0.45 * u) * (1.0 - 0.7 * (du * du + dv * dv));
        let ink = 1.0 - f64::from(page.get_pixel(x, y)[0]) / 255.0;
        let base = 238.0 - ink * 190.0;
        let grain = (noise.next_u64() % 17) as f64 - 8.0;
        let channel = |tint: f64| (base * tint * light + grain).round().clamp(0.0, 255.0) as u8;
        *pixel = Rgb([channel(1.0), channel(0.97), channel(0.9)]);
    }
    let mut bytes = Vec::new();
    JpegEncoder::new_with_quality(&mut bytes, 85)
        .encode_image(&rgb)
        .expect("JPEG encoding to memory");
    bytes
}

/// A binary PBM (P4) of an ink mask, ink black, as potrace reads it.
pub fn pbm(mask: &Bitmap) -> Vec<u8> {
    let (width, height) = (mask.width(), mask.height());
    let mut bytes = format!("P4\n{width} {height}\n").into_bytes();
    for row in mask.as_bytes().chunks_exact(width) {
        for eight in row.chunks(8) {
            let byte = eight.iter().enumerate().fold(0u8, |byte, (i, &ink)| {
                byte | (u8::from(ink != 0) << (7 - i))
            });
            bytes.push(byte);
        }
    }
    bytes
}
