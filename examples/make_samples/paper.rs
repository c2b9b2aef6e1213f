//! The look of a sample: pen width and ink per style, and the step from the rendered sketch (black
//! strokes on white) to the file a user would have: clean PNG, 16-bit or grey+alpha PNG, or a JPEG
//! "scan" on grey, unevenly lit, noisy paper.

use std::io::Cursor;

use image::{
    codecs::jpeg::JpegEncoder, DynamicImage, GrayAlphaImage, ImageBuffer, ImageFormat, Luma, LumaA,
    Rgb, RgbImage, RgbaImage,
};

use super::random::{smoothstep, value_noise, SplitMix64};

/// How a sample is drawn and stored.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Style {
    /// Pen 3 px, black ink on white, 8-bit grey PNG.
    Clean,
    /// Pen 7 px, 8-bit grey PNG.
    Thick,
    /// Pen 1.75 px, 8-bit grey PNG.
    Thin,
    /// Pen 3 px on grey paper under uneven light, with paper noise and blur: colour JPEG, quality 75.
    Scan,
    /// Pen 3 px on white with a faint paper gradient, 16-bit grey PNG.
    Gray16,
    /// Pen 3 px, ink as opacity on transparent paper: grey+alpha PNG.
    GrayAlpha,
}

impl Style {
    /// The style's name in `samples/README.md`.
    pub fn name(self) -> &'static str {
        match self {
            Style::Clean => "clean",
            Style::Thick => "thick",
            Style::Thin => "thin",
            Style::Scan => "scan",
            Style::Gray16 => "clean, 16-bit",
            Style::GrayAlpha => "clean, grey+alpha",
        }
    }

    /// Nominal pen width in pixels; each stroke varies by up to 8 %.
    pub fn pen(self) -> f64 {
        match self {
            Style::Thick => 7.0,
            Style::Thin => 1.75,
            _ => 3.0,
        }
    }

    /// The lightest grey a stroke may have (0 = black): pencils and pens vary a little.
    pub fn lightest_ink(self) -> u8 {
        match self {
            Style::Scan => 50,
            _ => 30,
        }
    }

    /// File name extension.
    pub fn extension(self) -> &'static str {
        match self {
            Style::Scan => "jpg",
            _ => "png",
        }
    }

    /// The file bytes for the rendered `sketch` (strokes on white).
    pub fn encode(self, sketch: &RgbaImage, seed: u64) -> Vec<u8> {
        let gray = ImageBuffer::from_fn(sketch.width(), sketch.height(), |x, y| {
            Luma([sketch.get_pixel(x, y).0[0]])
        });
        match self {
            Style::Clean | Style::Thick | Style::Thin => png(DynamicImage::ImageLuma8(gray)),
            Style::Gray16 => png(DynamicImage::ImageLuma16(sixteen_bit(&gray))),
            Style::GrayAlpha => png(DynamicImage::ImageLumaA8(ink_as_alpha(&gray))),
            Style::Scan => {
                let mut bytes = Vec::new();
                JpegEncoder::new_with_quality(&mut bytes, 75)
                    .encode_image(&scanned(&gray, seed))
                    .expect("JPEG encoding into memory cannot fail");
                bytes
            }
        }
    }
}

fn png(image: DynamicImage) -> Vec<u8> {
    let mut bytes = Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, ImageFormat::Png)
        .expect("PNG encoding into memory cannot fail");
    bytes.into_inner()
}

/// 16 bits with a faint left-to-right paper gradient, so the low byte carries real information.
fn sixteen_bit(gray: &ImageBuffer<Luma<u8>, Vec<u8>>) -> ImageBuffer<Luma<u16>, Vec<u16>> {
    let width = f64::from(gray.width());
    ImageBuffer::from_fn(gray.width(), gray.height(), |x, y| {
        let paper = 65535.0 - 3000.0 * f64::from(x) / width;
        let reflectance = f64::from(gray.get_pixel(x, y).0[0]) / 255.0;
        Luma([(paper * reflectance).round() as u16])
    })
}

/// Ink as opacity of dark grey on transparent paper; composited on white it gives the sketch back.
fn ink_as_alpha(gray: &ImageBuffer<Luma<u8>, Vec<u8>>) -> GrayAlphaImage {
    ImageBuffer::from_fn(gray.width(), gray.height(), |x, y| {
        LumaA([20, 255 - gray.get_pixel(x, y).0[0]])
    })
}

/// The sketch as a phone or a cheap scanner would give it: slightly blurred, on warm grey paper
/// with fibres, lit unevenly (a gradient, a vignette and a soft shadow along one edge), with
/// sensor noise.
fn scanned(gray: &ImageBuffer<Luma<u8>, Vec<u8>>, seed: u64) -> RgbImage {
    let (width, height) = gray.dimensions();
    let (w, h) = (f64::from(width), f64::from(height));
    let mut random = SplitMix64::new(seed ^ 0x5CA1_AB1E);
    let light_angle = random.range(0.0, std::f64::consts::TAU);
    let (light_x, light_y) = (light_angle.cos(), light_angle.sin());
    let vignette_centre = (w * random.range(0.3, 0.7), h * random.range(0.3, 0.7));
    let shadow_from_left = random.chance(0.5);
    let shadow_width = w * random.range(0.12, 0.2);
    let blurred = blur(gray);
    RgbImage::from_fn(width, height, |x, y| {
        let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
        // Light falls off across the sheet from 1.05 to 0.7 ...
        let along = ((px / w - 0.5) * light_x + (py / h - 0.5) * light_y) / 1.42 + 0.5;
        let gradient = 1.05 - 0.35 * along;
        // ... darker towards the corners ...
        let corner = ((px - vignette_centre.0) / w).hypot((py - vignette_centre.1) / h);
        let vignette = 1.0 - 0.45 * corner * corner;
        // ... and a soft shadow (a hand, a book's gutter) along one side.
        let edge = if shadow_from_left { px } else { w - px };
        let shadow = 1.0 - 0.4 * (1.0 - smoothstep(edge / shadow_width));
        let light = gradient * vignette * shadow;
        let fibres = 1.0
            + 0.025 * value_noise(seed, px / 5.0, py / 5.0)
            + 0.02 * value_noise(seed ^ 1, px / 40.0, py / 40.0);
        let reflectance = 0.84 * fibres * blurred[(y * width + x) as usize];
        let value = 255.0 * light * reflectance;
        let noise = 3.5 * random.gaussian();
        let channel = |tint: f64, own_noise: f64| (value * tint + noise + own_noise).round();
        let pixel = [
            channel(1.0, random.gaussian()),
            channel(0.97, random.gaussian()),
            channel(0.9, random.gaussian()),
        ];
        Rgb(pixel.map(|v| v.clamp(0.0, 255.0) as u8))
    })
}

/// Reflectance (0 = ink, 1 = paper) after a 3×3 binomial blur, row-major.
fn blur(gray: &ImageBuffer<Luma<u8>, Vec<u8>>) -> Vec<f64> {
    let (width, height) = (gray.width() as i64, gray.height() as i64);
    let at = |x: i64, y: i64| {
        let (x, y) = (x.clamp(0, width - 1), y.clamp(0, height - 1));
        f64::from(gray.get_pixel(x as u32, y as u32).0[0]) / 255.0
    };
    let weights = [1.0, 2.0, 1.0];
    let mut result = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let mut sum = 0.0;
            for (dy, wy) in (-1..=1).zip(weights) {
                for (dx, wx) in (-1..=1).zip(weights) {
                    sum += wx * wy * at(x + dx, y + dy);
                }
            }
            result.push(sum / 16.0);
        }
    }
    result
}
