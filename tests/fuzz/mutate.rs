//! The cases of the fuzz harness: seeded inputs of each kind, mutated, and how each is run
//! through the library. A case is its bytes alone (an options case carries its option bytes in
//! front of its image), so that a crasher saved to a file replays exactly.

use crawltrace::stages::decode::decode_image;
use crawltrace::{
    parse_points, reconstruct, render_svg_with, to_svg, trace, BinarizeOptions, Method,
    RenderOptions, ThresholdMethod, TraceOptions,
};
use image::{DynamicImage, ImageFormat};

use crate::hostile::{self, SplitMix64};

/// What a case feeds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// Image files: decoded, then traced with the default options.
    Image,
    /// Point files: parsed, then reconstructed.
    Points,
    /// SVG documents: rendered.
    Svg,
    /// Trace options: a small image traced with option values from anywhere in their types.
    Options,
}

impl Kind {
    pub const ALL: [Kind; 4] = [Kind::Image, Kind::Points, Kind::Svg, Kind::Options];

    pub fn name(self) -> &'static str {
        match self {
            Kind::Image => "image",
            Kind::Points => "points",
            Kind::Svg => "svg",
            Kind::Options => "options",
        }
    }

    pub fn parse(name: &str) -> Option<Kind> {
        Kind::ALL.into_iter().find(|kind| kind.name() == name)
    }
}

/// One input.
pub struct Case {
    pub kind: Kind,
    pub bytes: Vec<u8>,
}

/// Bytes of option values in front of an options case's image.
const OPTION_BYTES: usize = 48;

/// DECISION: the fuzz renders at most 1 megapixel: the canvas limit itself is tested apart
/// (`render::tests`), and larger canvases only make cases slower, not different.
const FUZZ_RENDER_PIXELS: u64 = 1_000_000;

/// Case `index` of `kind` from `seed`: the same bytes on every run and machine.
pub fn case(kind: Kind, seed: u64, index: u64) -> Case {
    let mut random =
        SplitMix64::new(seed ^ ((kind as u64) << 56) ^ index.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let bytes = match kind {
        Kind::Image => mutate_bytes(seed_image(&mut random), &mut random),
        Kind::Points => mutate_text(seed_points(&mut random), &mut random, &POINT_EDITS),
        Kind::Svg => mutate_text(seed_svg(&mut random), &mut random, &SVG_EDITS),
        Kind::Options => {
            let mut bytes: Vec<u8> = (0..OPTION_BYTES).map(|_| random.next_u64() as u8).collect();
            bytes.extend(seed_image(&mut random));
            bytes
        }
    };
    Case { kind, bytes }
}

/// Runs a case through the library; what it answers is described, errors included, as
/// `<outcome>: <detail>`.
pub fn run_case(case: &Case) -> String {
    match case.kind {
        Kind::Image => match decode_image(&case.bytes) {
            Ok(image) => describe_trace(&image, &TraceOptions::default()),
            Err(e) => format!("not decoded: {e}"),
        },
        Kind::Points => match parse_points(&case.bytes) {
            Ok(file) => match reconstruct(&file.points) {
                Ok(result) => format!("reconstructed: {} curves", result.curves.len()),
                Err(e) => format!("not reconstructed: {e}"),
            },
            Err(e) => format!("not parsed: {e}"),
        },
        Kind::Svg => {
            let text = String::from_utf8_lossy(&case.bytes);
            let scale = [1.0, 0.5, 2.0, 0.01][case.bytes.len() % 4];
            let options = RenderOptions {
                scale,
                max_pixels: FUZZ_RENDER_PIXELS,
            };
            match render_svg_with(&text, &options) {
                Ok(image) => format!("rendered: {}×{}", image.width(), image.height()),
                Err(e) => format!("not rendered: {e}"),
            }
        }
        Kind::Options => {
            let split = OPTION_BYTES.min(case.bytes.len());
            let options = options_from(&case.bytes[..split]);
            match decode_image(&case.bytes[split..]) {
                Ok(image) => describe_trace(&image, &options),
                Err(e) => format!("not decoded: {e}"),
            }
        }
    }
}

fn describe_trace(image: &DynamicImage, options: &TraceOptions) -> String {
    match trace(image, options) {
        Ok(traced) => {
            let svg = to_svg(&traced.drawing);
            format!(
                "traced: {} paths, {} bytes",
                traced.drawing.paths.len(),
                svg.len()
            )
        }
        Err(e) => format!("not traced: {e}"),
    }
}

/// Numbers from anywhere in an `f64`: zero, negatives, tiny, huge, NaN, infinities, ordinary.
fn any_number(random: &mut SplitMix64) -> f64 {
    const SPECIAL: [f64; 10] = [
        0.0,
        -1.0,
        1e-300,
        1e-9,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e9,
        f64::MAX,
        0.49,
    ];
    if random.below_u64(2) == 0 {
        SPECIAL[random.below_u64(SPECIAL.len() as u64) as usize]
    } else {
        random.unit() * 20.0
    }
}

/// Trace options read from `bytes` (any bytes give options).
fn options_from(bytes: &[u8]) -> TraceOptions {
    let mut seed = 0u64;
    for &byte in bytes {
        seed = seed.wrapping_mul(0x100_0000_01B3) ^ u64::from(byte);
    }
    let mut random = SplitMix64::new(seed);
    let maybe = |random: &mut SplitMix64| (random.below_u64(3) > 0).then(|| any_number(random));
    let method = match random.below_u64(4) {
        0 => ThresholdMethod::Auto,
        1 => ThresholdMethod::Otsu,
        2 => ThresholdMethod::Adaptive,
        _ => ThresholdMethod::Fixed(random.next_u64() as u8),
    };
    TraceOptions {
        binarize: BinarizeOptions {
            method,
            invert: random.below_u64(4) == 0,
        },
        spacing: maybe(&mut random),
        smooth: random.below_u64(4) > 0,
        simplify: maybe(&mut random),
        stroke_width: maybe(&mut random),
        method: if random.below_u64(3) == 0 {
            Method::Points
        } else {
            Method::Strokes
        },
        keep_stages: random.below_u64(2) == 0,
        max_pixels: [0, 1, 100, 10_000, u64::MAX][random.below_u64(5) as usize],
        ..TraceOptions::default()
    }
}

/// A small image in one of the formats the tracer reads.
fn seed_image(random: &mut SplitMix64) -> Vec<u8> {
    let side = 8 + random.below_u64(88) as u32;
    let picture = match random.below_u64(3) {
        0 => hostile::small_drawing(side),
        1 => hostile::noise_page(side, random.next_u64()),
        _ => hostile::specks_page(
            side.max(4),
            1 + random.below_u64(20) as u32,
            random.next_u64(),
        ),
    };
    const FORMATS: [ImageFormat; 9] = [
        ImageFormat::Png,
        ImageFormat::Jpeg,
        ImageFormat::Gif,
        ImageFormat::Bmp,
        ImageFormat::Tiff,
        ImageFormat::Pnm,
        ImageFormat::Tga,
        ImageFormat::Qoi,
        ImageFormat::Farbfeld,
    ];
    let format = FORMATS[random.below_u64(FORMATS.len() as u64) as usize];
    let gray = DynamicImage::ImageLuma8(picture);
    // The encoders that take no gray pixels get the same picture in the colour type they take.
    let image = match format {
        ImageFormat::Qoi | ImageFormat::Gif => DynamicImage::ImageRgba8(gray.to_rgba8()),
        ImageFormat::Farbfeld => DynamicImage::ImageRgba16(gray.to_rgba16()),
        _ => gray,
    };
    hostile::encode(&image, format)
}

/// Values that break parsers: field extremes in both byte orders.
const INTERESTING: [u32; 10] = [
    0,
    1,
    0x7F,
    0x80,
    0xFF,
    0xFFFF,
    0x7FFF_FFFF,
    0xFFFF_FFFF,
    0x0001_0000,
    65_535,
];

/// One to four edits of binary bytes: header fields, truncation, PNG chunk edits, splices and
/// bit flips.
fn mutate_bytes(mut bytes: Vec<u8>, random: &mut SplitMix64) -> Vec<u8> {
    for _ in 0..1 + random.below_u64(4) {
        if bytes.is_empty() {
            break;
        }
        let len = bytes.len() as u64;
        match random.below_u64(6) {
            0 => {
                // A header field: 1, 2 or 4 bytes among the first 64.
                let at = random.below_u64(len.min(64)) as usize;
                let value = INTERESTING[random.below_u64(INTERESTING.len() as u64) as usize];
                let width = [1, 2, 4][random.below_u64(3) as usize];
                let field = if random.below_u64(2) == 0 {
                    value.to_be_bytes()
                } else {
                    value.to_le_bytes()
                };
                for k in 0..width.min(bytes.len() - at) {
                    bytes[at + k] = field[4 - width + k];
                }
            }
            1 => bytes.truncate(random.below_u64(len) as usize),
            2 => edit_png_chunks(&mut bytes, random),
            3 => {
                // A splice: a range copied over another place.
                let from = random.below_u64(len) as usize;
                let to = random.below_u64(len) as usize;
                let count = (random.below_u64(64) as usize).min(bytes.len() - from.max(to));
                bytes.copy_within(from..from + count, to);
            }
            _ => {
                let at = random.below_u64(len) as usize;
                bytes[at] ^= 1 << random.below_u64(8);
            }
        }
    }
    bytes
}

/// PNG chunks edited as a decoder reads them: a chunk dropped, repeated, or its length field
/// changed, with its checksum fixed half of the time so that the edit gets past the CRC check.
fn edit_png_chunks(bytes: &mut Vec<u8>, random: &mut SplitMix64) {
    let mut chunks = Vec::new();
    let mut at = 8;
    while at + 12 <= bytes.len() && bytes.starts_with(b"\x89PNG") {
        let length = u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        let end = at + 12 + length;
        if end > bytes.len() {
            break;
        }
        chunks.push(at..end);
        at = end;
    }
    if chunks.is_empty() {
        return;
    }
    let chunk = chunks[random.below_u64(chunks.len() as u64) as usize].clone();
    match random.below_u64(3) {
        0 => {
            bytes.drain(chunk);
        }
        1 => {
            let copy = bytes[chunk.clone()].to_vec();
            bytes.splice(chunk.end..chunk.end, copy);
        }
        _ => {
            let value = INTERESTING[random.below_u64(INTERESTING.len() as u64) as usize];
            bytes[chunk.start..chunk.start + 4].copy_from_slice(&value.to_be_bytes());
            if random.below_u64(2) == 0 && chunk.end <= bytes.len() {
                let checksum = hostile::crc32(&bytes[chunk.start + 4..chunk.end - 4]);
                bytes[chunk.end - 4..chunk.end].copy_from_slice(&checksum.to_be_bytes());
            }
        }
    }
}

/// Point files: a curve, a cloud or a grid, in one of the separators the parser reads.
fn seed_points(random: &mut SplitMix64) -> String {
    let count = random.below_u64(400) as usize;
    let separator = [" ", ",", "\t", ", ", ";"][random.below_u64(5) as usize];
    let shape = random.below_u64(3);
    let mut text = String::new();
    if random.below_u64(4) == 0 {
        text += "x y\n";
    }
    for k in 0..count {
        let t = k as f64 / count.max(1) as f64 * std::f64::consts::TAU;
        let (x, y) = match shape {
            0 => (50.0 * t.cos(), 30.0 * t.sin()),
            1 => (random.unit() * 100.0, random.unit() * 100.0),
            _ => ((k % 20) as f64, (k / 20) as f64),
        };
        text += &format!("{x}{separator}{y}\n");
    }
    text
}

/// What point files are edited with: numbers for numbers, and text inserted at line starts.
const POINT_EDITS: Edits = Edits {
    numbers: &[
        "1e308",
        "-1e308",
        "1e-320",
        "NaN",
        "inf",
        "-0",
        "0x10",
        "1,5",
        "999999999999999999999",
        "",
    ],
    markup: &[
        "#",
        "\n",
        "\r\n",
        "1 2 3\n",
        "\u{feff}",
        "x y\n",
        "1e5 1e5\n",
    ],
    boundary: b'\n',
};

/// SVG documents: a hostile one, or a drawing with the elements renderers find hard.
fn seed_svg(random: &mut SplitMix64) -> String {
    let hostile = hostile::hostile_svgs();
    if random.below_u64(3) == 0 {
        return hostile[random.below_u64(hostile.len() as u64) as usize]
            .1
            .clone();
    }
    let side = 20 + random.below_u64(300);
    let mut body = String::new();
    for _ in 0..1 + random.below_u64(6) {
        body += SVG_ELEMENTS[random.below_u64(SVG_ELEMENTS.len() as u64) as usize];
    }
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="{side}" height="{side}">{body}</svg>"#
    )
}

const SVG_ELEMENTS: [&str; 10] = [
    r#"<path d="M10 10 C 40 0 60 80 90 30 S 120 90 150 40" fill="none" stroke="blue" stroke-width="2"/>"#,
    r#"<circle cx="50" cy="50" r="30" stroke="black" stroke-dasharray="4 2"/>"#,
    r#"<filter id="f"><feGaussianBlur stdDeviation="3"/><feMorphology radius="2"/></filter><rect width="60" height="60" filter="url(#f)"/>"#,
    r#"<pattern id="p" width="8" height="8" patternUnits="userSpaceOnUse"><rect width="4" height="4"/></pattern><rect width="80" height="80" fill="url(#p)"/>"#,
    r#"<g opacity="0.5"><g opacity="0.5"><rect x="5" y="5" width="50" height="50"/></g></g>"#,
    r#"<mask id="m"><rect width="40" height="40" fill="white"/></mask><rect width="90" height="90" mask="url(#m)"/>"#,
    r#"<clipPath id="c"><circle cx="30" cy="30" r="20"/></clipPath><rect width="90" height="90" clip-path="url(#c)"/>"#,
    r##"<defs><rect id="r" width="3" height="3"/></defs><use xlink:href="#r" x="10"/><use xlink:href="#r" x="20"/>"##,
    r#"<image href="/etc/passwd" width="40" height="40"/>"#,
    r#"<filter id="t"><feTurbulence baseFrequency="0.05" numOctaves="3"/><feConvolveMatrix order="3" kernelMatrix="0 1 0 1 -4 1 0 1 0"/></filter><rect width="50" height="50" filter="url(#t)"/>"#,
];

/// What SVGs are edited with: numbers for numbers, elements after a tag, attributes.
const SVG_EDITS: Edits = Edits {
    numbers: &[
        "1e38", "-1e38", "1e-38", "0", "NaN", "65535", "1e6", "-1", "1e-9", "3e38",
    ],
    markup: &[
        r#"<g opacity="0.3"><rect width="1e38" height="5"/></g>"#,
        r##"<use xlink:href="#f"/>"##,
        r##"<use xlink:href="#p"/>"##,
        r#"<rect width="100%" height="100%" filter="url(#f)"/>"#,
        r#"<rect width="100%" height="100%" fill="url(#p)" mask="url(#m)"/>"#,
        r#"<path d="M0 0 A1e38 1e38 0 1 1 5 5" stroke="black" stroke-dasharray="1e-9"/>"#,
        r#"<image href="data:image/png;base64,iVBORw0KGgo=" width="10" height="10"/>"#,
        r#"<text>text</text>"#,
        r#"<g transform="scale(1e20)"><circle r="1"/></g>"#,
    ],
    boundary: b'>',
};

/// How a kind of text is edited.
struct Edits {
    /// Replacements for a number.
    numbers: &'static [&'static str],
    /// Text inserted after a boundary.
    markup: &'static [&'static str],
    /// Where markup may go: after a line (points) or a tag (SVG).
    boundary: u8,
}

/// One to four edits of text that mostly keep it well-formed, so that they reach the code
/// past the parser: a number replaced, markup inserted after a boundary, a line or an empty
/// element repeated; and now and then the text cut or a byte flipped.
fn mutate_text(text: String, random: &mut SplitMix64, edits: &Edits) -> Vec<u8> {
    let mut bytes = text.into_bytes();
    for _ in 0..1 + random.below_u64(4) {
        if bytes.is_empty() {
            break;
        }
        let at = random.below_u64(bytes.len() as u64) as usize;
        let pick = |random: &mut SplitMix64, list: &[&'static str]| {
            list[random.below_u64(list.len() as u64) as usize].as_bytes()
        };
        match random.below_u64(10) {
            0..=3 => {
                let Some(start) = (at..bytes.len()).find(|&k| bytes[k].is_ascii_digit()) else {
                    continue;
                };
                let is_numeric = |b: u8| b.is_ascii_digit() || b".-+eE".contains(&b);
                let end = (start..bytes.len())
                    .find(|&k| !is_numeric(bytes[k]))
                    .unwrap_or(bytes.len());
                bytes.splice(start..end, pick(random, edits.numbers).iter().copied());
            }
            4 | 5 => {
                let Some(after) = (at..bytes.len()).find(|&k| bytes[k] == edits.boundary) else {
                    continue;
                };
                bytes.splice(
                    after + 1..after + 1,
                    pick(random, edits.markup).iter().copied(),
                );
            }
            6 | 7 => repeat_unit(
                &mut bytes,
                at,
                edits.boundary,
                1 + random.below_u64(64) as usize,
            ),
            8 => bytes.truncate(at),
            _ => bytes[at] ^= 1 << random.below_u64(8),
        }
    }
    bytes
}

/// Repeats `times` times the unit after `at`: a line for points, an empty element (`<.../>`) for
/// SVG.
fn repeat_unit(bytes: &mut Vec<u8>, at: usize, boundary: u8, times: usize) {
    let start = if boundary == b'>' {
        (at..bytes.len()).find(|&k| bytes[k] == b'<' && bytes.get(k + 1) != Some(&b'/'))
    } else {
        (at..bytes.len())
            .find(|&k| bytes[k] == b'\n')
            .map(|k| k + 1)
    };
    let Some(start) = start else { return };
    let Some(end) = (start..bytes.len()).find(|&k| bytes[k] == boundary) else {
        return;
    };
    if boundary == b'>' && bytes[end - 1] != b'/' {
        return;
    }
    let unit = bytes[start..=end].to_vec();
    for _ in 0..times {
        bytes.splice(end + 1..end + 1, unit.iter().copied());
    }
}
