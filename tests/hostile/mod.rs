//! The hostile inputs of issue 13, made in code so that tests, the fuzz harness and
//! `examples/hostile_inputs.rs` share them: images that are slow to trace or that lie about their
//! size, point files, and SVGs that make a renderer read other files, loop or allocate without
//! bound. Files that are not bytes (a FIFO, a sparse 3 GB file, a device) are made by the tests
//! themselves, where they are used.
// Each user takes what it needs.
#![allow(dead_code)]

#[path = "../support/random.rs"]
mod random;

use std::io::Cursor;

use image::{DynamicImage, GrayImage, ImageFormat, Luma};
pub use random::SplitMix64;

/// Encodes `image` in `format`.
pub fn encode(image: &DynamicImage, format: ImageFormat) -> Vec<u8> {
    let mut bytes = Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, format)
        .expect("the image crate encodes its own images");
    bytes.into_inner()
}

/// A `side`² white page with 2 × 2 px black specks covering `percent` % of it: the page on which
/// `kurbo::simplify_bezpath` never returned (kurbo issue #602).
pub fn specks_page(side: u32, percent: u32, seed: u64) -> GrayImage {
    let mut page = GrayImage::from_pixel(side, side, Luma([255]));
    let mut random = SplitMix64::new(seed);
    let specks = u64::from(side) * u64::from(side) * u64::from(percent) / 100 / 4;
    for _ in 0..specks {
        let x = random.below_u64(u64::from(side - 2)) as u32;
        let y = random.below_u64(u64::from(side - 2)) as u32;
        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            page.put_pixel(x + dx, y + dy, Luma([0]));
        }
    }
    page
}

/// A `side`² page of black and white pixels at random, half of each.
pub fn noise_page(side: u32, seed: u64) -> GrayImage {
    let mut random = SplitMix64::new(seed);
    GrayImage::from_fn(side, side, |_, _| {
        Luma([if random.below_u64(2) == 0 { 0 } else { 255 }])
    })
}

/// A small drawing (a ring and a bar), the start of the header edits.
pub fn small_drawing(side: u32) -> GrayImage {
    let centre = f64::from(side) / 2.0;
    GrayImage::from_fn(side, side, |x, y| {
        let radius = (f64::from(x) - centre).hypot(f64::from(y) - centre);
        let ring = (radius - centre * 0.6).abs() < 1.5;
        let bar = y == side / 5 && x > side / 5 && x < side * 4 / 5;
        Luma([if ring || bar { 0 } else { 255 }])
    })
}

/// A gray JPEG of [`small_drawing`] whose frame header (SOF0) claims `width` × `height`: a few
/// kilobytes that a lenient decoder expands to the claimed size.
pub fn jpeg_claiming(width: u16, height: u16) -> Vec<u8> {
    let mut bytes = encode(
        &DynamicImage::ImageLuma8(small_drawing(64)),
        ImageFormat::Jpeg,
    );
    let sof = bytes
        .windows(2)
        .position(|pair| pair == [0xFF, 0xC0])
        .expect("a baseline JPEG has a SOF0 marker");
    // FF C0, length (2), precision (1), then height and width, big-endian.
    bytes[sof + 5..sof + 7].copy_from_slice(&height.to_be_bytes());
    bytes[sof + 7..sof + 9].copy_from_slice(&width.to_be_bytes());
    bytes
}

/// A gray PNG of [`small_drawing`] whose header (IHDR) claims `width` × `height`, its checksum
/// fixed so that the decoder believes it.
pub fn png_claiming(width: u32, height: u32) -> Vec<u8> {
    let mut bytes = encode(
        &DynamicImage::ImageLuma8(small_drawing(64)),
        ImageFormat::Png,
    );
    // Signature (8), length (4), "IHDR" (4), then width and height, big-endian.
    bytes[16..20].copy_from_slice(&width.to_be_bytes());
    bytes[20..24].copy_from_slice(&height.to_be_bytes());
    let checksum = crc32(&bytes[12..29]);
    bytes[29..33].copy_from_slice(&checksum.to_be_bytes());
    bytes
}

/// The CRC-32 of PNG chunks (ISO 3309, reflected, polynomial 0xEDB88320).
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// An SVG that draws the file at `href` (absolute, relative, `file:` URL, another SVG, a device,
/// a FIFO) over a small canvas.
pub fn svg_with_image(href: &str) -> String {
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="40" height="40"><image href="{href}" xlink:href="{href}" width="40" height="40"/></svg>"#
    )
}

/// An SVG whose whole canvas is `side` × `side` pixels (119 bytes for 29 999).
pub fn svg_canvas(side: u32) -> String {
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{side}" height="{side}"><rect width="9" height="9"/></svg>"#
    )
}

/// Small SVGs that make a renderer loop, or allocate, far beyond their size: an arc of radius
/// 1e38, ten levels of ten `<use>` of the level below (10¹⁰ elements), a huge blur, a turbulence of a million octaves, a pattern tile 1e-38 high, a filter
/// region far beyond the canvas, a stroke dashed in steps of 1e-9, and paths with coordinates
/// near the largest float.
pub fn hostile_svgs() -> Vec<(&'static str, String)> {
    let document = |body: &str| {
        format!(r#"<svg xmlns="http://www.w3.org/2000/svg" width="200" height="200">{body}</svg>"#)
    };
    vec![
        (
            "arc-radius-1e38",
            document(r#"<path d="M10 10 A1e38 1e38 0 1 1 190 190" stroke="black" fill="red"/>"#),
        ),
        (
            "blur-huge",
            document(
                r#"<filter id="f" x="-1e9" y="-1e9" width="2e9" height="2e9" filterUnits="userSpaceOnUse"><feGaussianBlur stdDeviation="1e9"/></filter><rect width="100" height="100" filter="url(#f)"/>"#,
            ),
        ),
        (
            "turbulence-million-octaves",
            document(
                r#"<filter id="f"><feTurbulence baseFrequency="0.05" numOctaves="1000000"/></filter><rect width="200" height="200" filter="url(#f)"/>"#,
            ),
        ),
        (
            "pattern-tile-1e-38",
            document(
                r#"<pattern id="p" width="10" height="1e-38" patternUnits="userSpaceOnUse"><rect width="5" height="1e-38"/></pattern><rect width="200" height="200" fill="url(#p)"/>"#,
            ),
        ),
        (
            "filter-region-1e6",
            document(
                r#"<filter id="f" x="-1e6" y="-1e6" width="2e6" height="2e6" filterUnits="userSpaceOnUse"><feMorphology radius="1e6"/><feConvolveMatrix order="3" kernelMatrix="1 1 1 1 1 1 1 1 1"/></filter><rect width="100" height="100" filter="url(#f)"/>"#,
            ),
        ),
        (
            "dashes-1e-9",
            document(
                r#"<path d="M0 0 L200 200 L0 200 Z" stroke="black" stroke-dasharray="1e-9 1e-9"/>"#,
            ),
        ),
        (
            "coordinates-3e38",
            document(
                r#"<path d="M-3e38 -3e38 L3e38 3e38 L-3e38 3e38 Z" stroke="black" stroke-width="3e38"/>"#,
            ),
        ),
        ("uses-ten-levels", nested_uses(10)),
        (
            "nested-groups-and-filters",
            document(&format!(
                r#"<filter id="f"><feGaussianBlur stdDeviation="2"/></filter>{}<rect width="200" height="200"/>{}"#,
                r#"<g filter="url(#f)" opacity="0.5">"#.repeat(200),
                "</g>".repeat(200)
            )),
        ),
    ]
}

/// `<use>` of ten `<use>` of ten ... `levels` deep: 10^levels rectangles from 3 kB of text.
pub fn nested_uses(levels: usize) -> String {
    let mut svg = String::from(
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="200" height="200"><defs><rect id="l0" width="1" height="1"/>"#,
    );
    for level in 1..=levels {
        svg += &format!(r#"<g id="l{level}">"#);
        for k in 0..10 {
            svg += &format!(r##"<use xlink:href="#l{}" x="{k}"/>"##, level - 1);
        }
        svg += "</g>";
    }
    svg + &format!(r##"</defs><use xlink:href="#l{levels}"/></svg>"##)
}

/// Point files: many points on a tiny grid, huge coordinates, long lines without newlines.
pub fn hostile_point_files() -> Vec<(&'static str, Vec<u8>)> {
    let mut random = SplitMix64::new(13);
    let noise: String = (0..20_000)
        .map(|_| format!("{} {}\n", random.unit() * 100.0, random.unit() * 100.0))
        .collect();
    let grid: String = (0..40_000)
        .map(|k| format!("{} {}\n", k % 200, k / 200))
        .collect();
    vec![
        ("noise-20000.txt", noise.into_bytes()),
        ("grid-40000.txt", grid.into_bytes()),
        ("one-long-line.txt", vec![b'1'; 1 << 20]),
        (
            "extremes.txt",
            b"1e60 1e60\n-1e60 -1e60\n1e-42 0\n0 1e-42\n1 1\n".to_vec(),
        ),
    ]
}
