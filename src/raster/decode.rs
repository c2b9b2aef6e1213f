//! Decoding: image file bytes → [`DynamicImage`] → 8-bit gray, with the `image` crate's decoders
//! (format guessed from the content's magic bytes) and Rec. 709 luma weights.
//!
//! The first stage of the pipeline (see `docs/design.md`, "The pipeline"). Two pure functions:
//! [`decode_image`] never panics on any bytes and reports a one-line [`DecodeError`], and [`to_gray`]
//! reduces every colour type the crate produces to the 8-bit luminance the binarizer reads.
//! The size of the image is checked against [`DecodeLimits`] from its header, before any pixel is
//! decoded.

use std::io::Cursor;

use image::{DynamicImage, GrayImage, ImageError, ImageFormat, ImageReader};

use super::limits::jpeg_minimum_bytes;
pub use super::limits::{DecodeLimits, BYTES_PER_PIXEL, DEFAULT_MAX_PIXELS};

/// Why bytes could not be turned into an image. Messages are one line, for a user.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DecodeError {
    /// The input has no bytes at all.
    #[error("empty file (0 bytes)")]
    EmptyInput,
    /// No image format recognised from the content.
    #[error(
        "not an image, or not a format crawltrace reads ({})",
        SUPPORTED_FORMATS
    )]
    NotAnImage,
    /// A format was recognised, but this build cannot read it (or this variant of it).
    #[error("unsupported image format: {0}")]
    Unsupported(String),
    /// The format was recognised but the data is damaged or cut short.
    #[error("corrupt or truncated image data: {0}")]
    Corrupt(String),
    /// Decoding would need more memory than the decoder's safety limits allow.
    #[error("image too large to decode: {0}")]
    TooLarge(String),
    /// The header gives more pixels than [`DecodeLimits::max_pixels`].
    #[error(
        "image too large: {width}×{height} pixels ({:.1} megapixels), more than the limit of {:.1} (--max-pixels)",
        megapixels(u64::from(*.width) * u64::from(*.height)),
        megapixels(*.max_pixels)
    )]
    TooManyPixels {
        /// Width in pixels, from the header.
        width: u32,
        /// Height in pixels, from the header.
        height: u32,
        /// The limit.
        max_pixels: u64,
    },
    /// The image decoded but has no pixels.
    #[error("empty image ({width}×{height} pixels)")]
    EmptyImage {
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
}

/// The formats the enabled `image` features read, for error messages.
const SUPPORTED_FORMATS: &str =
    "PNG, JPEG, GIF, BMP, TIFF, WebP, PNM, TGA, ICO, QOI, HDR, DDS, farbfeld, OpenEXR";

/// Megapixels, for messages.
fn megapixels(pixels: u64) -> f64 {
    pixels as f64 / 1e6
}

/// How much of a file [`identify_format`] needs: TGA, the one format without a signature, is
/// recognised from its header, image ID and colour map (at most 18 + 255 + 65 536 × 4 bytes).
pub const IDENTIFY_BYTES: usize = 18 + 255 + 65_536 * 4;

/// Decodes an image file held in memory, within the default [`DecodeLimits`]. The format is
/// guessed from the content, never from a file name, so a misnamed file still decodes. Never
/// panics on any input.
///
/// TGA is the one enabled format without a signature: when no signature matches, the bytes are
/// tried as TGA, and if that fails too the input is reported as [`DecodeError::NotAnImage`]
/// (not as a corrupt TGA, since TGA was only a guess).
pub fn decode_image(bytes: &[u8]) -> Result<DynamicImage, DecodeError> {
    decode_image_within(bytes, &DecodeLimits::default())
}

/// [`decode_image`] within `limits`: the image's size is read from its header and refused
/// ([`DecodeError::TooManyPixels`]) before any pixel is decoded; the decoder may allocate at most
/// [`BYTES_PER_PIXEL`] per allowed pixel; a JPEG must hold at least the data its size needs
/// (a lenient decoder would invent the rest).
pub fn decode_image_within(
    bytes: &[u8],
    limits: &DecodeLimits,
) -> Result<DynamicImage, DecodeError> {
    let format = identify_format(bytes)?;
    // TGA was only a guess: whatever fails, the bytes are not an image we read.
    let failure = |error: ImageError| match format {
        ImageFormat::Tga => DecodeError::NotAnImage,
        _ => describe(error),
    };
    if format == ImageFormat::Jpeg && !jpeg_has_end(bytes) {
        return Err(DecodeError::Corrupt(
            "JPEG data is cut short (no end-of-image marker)".into(),
        ));
    }
    let (width, height) = reader(bytes, format, limits)
        .into_dimensions()
        .map_err(failure)?;
    if width == 0 || height == 0 {
        return Err(DecodeError::EmptyImage { width, height });
    }
    if !limits.allows(width, height) {
        return Err(DecodeError::TooManyPixels {
            width,
            height,
            max_pixels: limits.max_pixels,
        });
    }
    if format == ImageFormat::Jpeg {
        check_jpeg_data(bytes, width, height)?;
    }
    let image = reader(bytes, format, limits).decode().map_err(failure)?;
    if image.width() == 0 || image.height() == 0 {
        return Err(DecodeError::EmptyImage {
            width: image.width(),
            height: image.height(),
        });
    }
    Ok(image)
}

/// The format of an image file from its first bytes ([`IDENTIFY_BYTES`] are enough), so that a
/// large file that is no image is refused before it is read whole.
pub fn identify_format(head: &[u8]) -> Result<ImageFormat, DecodeError> {
    if head.is_empty() {
        return Err(DecodeError::EmptyInput);
    }
    if let Ok(format) = image::guess_format(head) {
        return Ok(format);
    }
    let tga_header =
        ImageReader::with_format(Cursor::new(head), ImageFormat::Tga).into_dimensions();
    match tga_header {
        Ok(_) => Ok(ImageFormat::Tga),
        Err(_) => Err(DecodeError::NotAnImage),
    }
}

/// A reader of `bytes` as `format` within `limits`.
fn reader<'a>(
    bytes: &'a [u8],
    format: ImageFormat,
    limits: &DecodeLimits,
) -> ImageReader<Cursor<&'a [u8]>> {
    let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
    reader.limits(limits.for_decoder());
    reader
}

/// Refuses a JPEG with less data than its size needs ([`jpeg_minimum_bytes`]).
fn check_jpeg_data(bytes: &[u8], width: u32, height: u32) -> Result<(), DecodeError> {
    match jpeg_minimum_bytes(bytes, width, height) {
        Some(needed) if (bytes.len() as u64) < needed => Err(DecodeError::Corrupt(format!(
            "JPEG data too short for its {width}×{height} pixels: {} bytes, at least {needed} needed",
            bytes.len()
        ))),
        _ => Ok(()),
    }
}

/// Whether JPEG data has an end-of-image marker (FF D9) after its last start-of-scan (FF DA).
///
/// The JPEG decoder is lenient on purpose, like a browser: a file cut short decodes with the
/// missing rows filled in gray, which would trace as a huge ink block. Entropy-coded data never
/// holds a bare FF D9 (an FF byte there is stuffed as FF 00), so a cut file has no EOI after its
/// last scan header; bytes after the EOI (camera trailers) are fine.
fn jpeg_has_end(bytes: &[u8]) -> bool {
    let last_scan = bytes.windows(2).rposition(|pair| pair == [0xFF, 0xDA]);
    last_scan.is_some_and(|start| bytes[start..].windows(2).any(|pair| pair == [0xFF, 0xD9]))
}

/// Maps the `image` crate's error to ours, keeping its detail on one line.
fn describe(error: ImageError) -> DecodeError {
    let detail = one_line(&error.to_string());
    match error {
        ImageError::Unsupported(_) => DecodeError::Unsupported(detail),
        ImageError::Limits(_) => DecodeError::TooLarge(format!(
            "it needs more memory than the limit ({BYTES_PER_PIXEL} bytes a pixel of --max-pixels)"
        )),
        // With an in-memory reader an I/O error can only be the data ending early.
        ImageError::IoError(_) => DecodeError::Corrupt(detail),
        ImageError::Decoding(_) | ImageError::Parameter(_) | ImageError::Encoding(_) => {
            DecodeError::Corrupt(detail)
        }
    }
}

/// Joins a possibly multi-line message into one line.
fn one_line(message: &str) -> String {
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Reduces any decoded image to 8-bit gray.
///
/// - Luminance uses the `image` crate's weights, which are Rec. 709's (0.2126 R + 0.7152 G +
///   0.0722 B), applied to the stored (gamma-encoded) values as the crate does, rounded to nearest.
/// - Transparent pixels are composited over white paper: a transparent background must read as
///   paper, not as black ink (which is what dropping the alpha channel would give).
/// - 16-bit values are rounded to 8 bits; float values (HDR, OpenEXR) are clamped to 0..=1 and
///   scaled, as the crate's own float → 8-bit conversion does.
pub fn to_gray(image: &DynamicImage) -> GrayImage {
    let (width, height) = (image.width(), image.height());
    let pixels: Vec<u8> = match image {
        DynamicImage::ImageLuma8(gray) => return gray.clone(),
        DynamicImage::ImageLumaA8(buffer) => buffer
            .pixels()
            .map(|p| over_white(u32::from(p[0]), u32::from(p[1]), 255) as u8)
            .collect(),
        DynamicImage::ImageRgb8(buffer) => buffer
            .pixels()
            .map(|p| luma(u32::from(p[0]), u32::from(p[1]), u32::from(p[2])) as u8)
            .collect(),
        DynamicImage::ImageRgba8(buffer) => buffer
            .pixels()
            .map(|p| {
                let value = luma(u32::from(p[0]), u32::from(p[1]), u32::from(p[2]));
                over_white(value, u32::from(p[3]), 255) as u8
            })
            .collect(),
        DynamicImage::ImageLuma16(buffer) => {
            buffer.pixels().map(|p| to_8_bits(p[0].into())).collect()
        }
        DynamicImage::ImageLumaA16(buffer) => buffer
            .pixels()
            .map(|p| to_8_bits(over_white(u32::from(p[0]), u32::from(p[1]), 65535)))
            .collect(),
        DynamicImage::ImageRgb16(buffer) => buffer
            .pixels()
            .map(|p| to_8_bits(luma(u32::from(p[0]), u32::from(p[1]), u32::from(p[2]))))
            .collect(),
        DynamicImage::ImageRgba16(buffer) => buffer
            .pixels()
            .map(|p| {
                let value = luma(u32::from(p[0]), u32::from(p[1]), u32::from(p[2]));
                to_8_bits(over_white(value, u32::from(p[3]), 65535))
            })
            .collect(),
        DynamicImage::ImageRgb32F(buffer) => buffer
            .pixels()
            .map(|p| float_to_8_bits(luma_float(p[0], p[1], p[2])))
            .collect(),
        DynamicImage::ImageRgba32F(buffer) => buffer
            .pixels()
            .map(|p| {
                let alpha = unit(p[3]);
                float_to_8_bits(unit(luma_float(p[0], p[1], p[2])) * alpha + (1.0 - alpha))
            })
            .collect(),
        // `DynamicImage` is non-exhaustive: a future colour type goes through the crate's RGBA.
        other => {
            return to_gray(&DynamicImage::ImageRgba8(other.to_rgba8()));
        }
    };
    GrayImage::from_raw(width, height, pixels).expect("one gray byte for each pixel")
}

/// Rec. 709 luma weights, in ten-thousandths (the `image` crate's `SRGB_LUMA`).
const LUMA_WEIGHTS: [u32; 3] = [2126, 7152, 722];

/// Luma of integer RGB (any bit depth up to 16), rounded to nearest.
#[inline]
fn luma(red: u32, green: u32, blue: u32) -> u32 {
    (LUMA_WEIGHTS[0] * red + LUMA_WEIGHTS[1] * green + LUMA_WEIGHTS[2] * blue + 5_000) / 10_000
}

/// Luma of float RGB.
#[inline]
fn luma_float(red: f32, green: f32, blue: f32) -> f32 {
    (LUMA_WEIGHTS[0] as f32 * red + LUMA_WEIGHTS[1] as f32 * green + LUMA_WEIGHTS[2] as f32 * blue)
        / 10_000.0
}

/// `value` with coverage `alpha` (both out of `full`) over white paper, rounded to nearest.
#[inline]
fn over_white(value: u32, alpha: u32, full: u32) -> u32 {
    // u64: 16-bit products reach 65535² and would overflow u32 with the rounding term.
    let (value, alpha, full) = (u64::from(value), u64::from(alpha), u64::from(full));
    ((value * alpha + full * (full - alpha) + full / 2) / full) as u32
}

/// A 16-bit value rounded to 8 bits.
#[inline]
fn to_8_bits(value: u32) -> u8 {
    ((value * 255 + 32_767) / 65_535) as u8
}

/// A float clamped to 0..=1; NaN counts as 0.
#[inline]
fn unit(value: f32) -> f32 {
    if value.is_nan() {
        0.0
    } else {
        value.clamp(0.0, 1.0)
    }
}

/// A float of 0..=1 (clamped) to 8 bits, rounded to nearest.
#[inline]
fn float_to_8_bits(value: f32) -> u8 {
    (unit(value) * 255.0 + 0.5) as u8
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::test_random::SplitMix64;
    use image::{ImageBuffer, Luma, LumaA, Rgb, Rgba};

    /// A small deterministic drawing: dark strokes on light paper.
    fn sample_gray(width: u32, height: u32) -> GrayImage {
        GrayImage::from_fn(width, height, |x, y| {
            Luma([if (x + y) % 7 == 0 || x == width / 2 {
                20
            } else {
                230
            }])
        })
    }

    /// The formats scanners, phones and drawing programs write most: damage to each of them must
    /// be an error, never a panic.
    const SCANNER_FORMATS: [ImageFormat; 5] = [
        ImageFormat::Png,
        ImageFormat::Jpeg,
        ImageFormat::Gif,
        ImageFormat::Bmp,
        ImageFormat::Tiff,
    ];

    fn encode(image: &DynamicImage, format: ImageFormat) -> Vec<u8> {
        let mut bytes = Cursor::new(Vec::new());
        image.write_to(&mut bytes, format).expect("encode fixture");
        bytes.into_inner()
    }

    #[test]
    fn every_encodable_format_round_trips_whatever_the_name() {
        let gray = sample_gray(37, 23);
        let rgb = DynamicImage::ImageRgb8(DynamicImage::ImageLuma8(gray.clone()).to_rgb8());
        for (format, source) in [
            (ImageFormat::Png, DynamicImage::ImageLuma8(gray.clone())),
            (ImageFormat::Bmp, rgb.clone()),
            (ImageFormat::Tiff, rgb.clone()),
            (ImageFormat::Pnm, DynamicImage::ImageLuma8(gray.clone())),
            (ImageFormat::Tga, rgb.clone()),
            (ImageFormat::Qoi, DynamicImage::ImageRgba8(rgb.to_rgba8())),
            (ImageFormat::Gif, DynamicImage::ImageRgba8(rgb.to_rgba8())),
            (ImageFormat::WebP, DynamicImage::ImageRgba8(rgb.to_rgba8())),
            (ImageFormat::Ico, DynamicImage::ImageRgba8(rgb.to_rgba8())),
            (
                ImageFormat::Farbfeld,
                DynamicImage::ImageRgba16(rgb.to_rgba16()),
            ),
        ] {
            let bytes = encode(&source, format);
            let decoded = decode_image(&bytes).unwrap_or_else(|e| panic!("{format:?}: {e}"));
            assert_eq!(to_gray(&decoded), gray, "{format:?}");
        }
        // JPEG is lossy: compare within a tolerance.
        let decoded = decode_image(&encode(&rgb, ImageFormat::Jpeg)).expect("jpeg");
        let decoded = to_gray(&decoded);
        let worst = decoded
            .pixels()
            .zip(gray.pixels())
            .map(|(a, b)| a[0].abs_diff(b[0]))
            .max();
        assert!(worst < Some(80), "JPEG too far off: {worst:?}");
        assert_eq!(decoded.dimensions(), gray.dimensions());
    }

    #[test]
    fn truncated_files_are_errors_not_panics() {
        let image = DynamicImage::ImageLuma8(sample_gray(64, 48));
        for format in SCANNER_FORMATS {
            let source = if format == ImageFormat::Png {
                image.clone()
            } else {
                DynamicImage::ImageRgb8(image.to_rgb8())
            };
            let bytes = encode(&source, format);
            // Every prefix through the headers, then every 37th byte to the end.
            let lengths = (0..bytes.len().min(600)).chain((600..bytes.len()).step_by(37));
            for length in lengths {
                // Some formats decode a prefix missing only trailing metadata: that is fine, as
                // long as nothing panics, what decodes is the whole picture's size, and an error
                // is one line.
                match decode_image(&bytes[..length]) {
                    Ok(decoded) => assert_eq!(
                        (decoded.width(), decoded.height()),
                        (64, 48),
                        "{format:?} cut at {length}"
                    ),
                    Err(error) => assert_one_line(&error, &bytes[..length]),
                }
            }
            // A cut in the middle of the pixel data is reported as corrupt or truncated.
            match decode_image(&bytes[..bytes.len() / 2]) {
                Err(DecodeError::Corrupt(message)) => assert!(!message.contains('\n')),
                other => panic!("{format:?} cut in half: {other:?}"),
            }
        }
    }

    #[test]
    fn damaged_and_random_bytes_are_errors_not_panics() {
        let mut random = SplitMix64::new(7);
        // Random bytes with no signature.
        for length in [1, 2, 17, 18, 100, 5000] {
            let bytes: Vec<u8> = (0..length).map(|_| random.next_u64() as u8).collect();
            let error = decode_image(&bytes).expect_err("random bytes are not an image");
            assert_one_line(&error, &bytes);
        }
        // Valid signatures followed by garbage, and valid files with bytes flipped.
        let image =
            DynamicImage::ImageRgb8(DynamicImage::ImageLuma8(sample_gray(40, 30)).to_rgb8());
        let other_formats = [
            ImageFormat::WebP,
            ImageFormat::Qoi,
            ImageFormat::Pnm,
            ImageFormat::Ico,
        ];
        for format in SCANNER_FORMATS.into_iter().chain(other_formats) {
            let source = match format {
                ImageFormat::Qoi | ImageFormat::Ico | ImageFormat::WebP | ImageFormat::Gif => {
                    DynamicImage::ImageRgba8(image.to_rgba8())
                }
                _ => image.clone(),
            };
            let bytes = encode(&source, format);
            let mut garbage = bytes[..16.min(bytes.len())].to_vec();
            garbage.extend((0..200).map(|_| random.next_u64() as u8));
            let error = decode_image(&garbage).expect_err("a header and garbage is not an image");
            assert_one_line(&error, &garbage);
            for _ in 0..150 {
                let mut damaged = bytes.clone();
                for _ in 0..1 + random.next_u64() % 4 {
                    let at = (random.next_u64() % damaged.len() as u64) as usize;
                    damaged[at] = random.next_u64() as u8;
                }
                // A flipped pixel byte may still decode; whatever fails says so in one line.
                match decode_image(&damaged) {
                    Ok(decoded) => assert!(decoded.width() > 0 && decoded.height() > 0),
                    Err(error) => assert_one_line(&error, &damaged),
                }
            }
        }
    }

    /// A decode error is one non-empty line (it ends up after a file name on the console).
    fn assert_one_line(error: &DecodeError, bytes: &[u8]) {
        let message = error.to_string();
        assert!(
            !message.is_empty() && !message.contains('\n'),
            "{message:?} for {} bytes starting {:02x?}",
            bytes.len(),
            &bytes[..bytes.len().min(16)]
        );
    }

    #[test]
    fn errors_say_what_is_wrong_in_one_line() {
        assert_eq!(decode_image(&[]), Err(DecodeError::EmptyInput));
        assert_eq!(
            decode_image(b"hello, world\n"),
            Err(DecodeError::NotAnImage)
        );
        let message = DecodeError::NotAnImage.to_string();
        assert!(message.starts_with("not an image") && !message.contains('\n'));
        // A recognised signature (AVIF) whose decoder is not built in.
        let avif = b"\0\0\0\x20ftypavif\0\0\0\0avifmif1miaf";
        assert!(
            matches!(decode_image(avif), Err(DecodeError::Unsupported(_))),
            "{:?}",
            decode_image(avif)
        );
        // A PGM header declaring zero width.
        let empty = b"P5\n0 5\n255\n";
        assert!(
            matches!(
                decode_image(empty),
                Err(DecodeError::EmptyImage { .. } | DecodeError::Corrupt(_))
            ),
            "{:?}",
            decode_image(empty)
        );
        // A PGM declaring an absurd size is refused from its header, not allocated.
        let huge = b"P5\n1000000 1000000\n255\n\0\0\0";
        assert_eq!(
            decode_image(huge),
            Err(DecodeError::TooManyPixels {
                width: 1_000_000,
                height: 1_000_000,
                max_pixels: DEFAULT_MAX_PIXELS
            })
        );
        assert_eq!(
            decode_image(huge).unwrap_err().to_string(),
            "image too large: 1000000×1000000 pixels (1000000.0 megapixels), more than the limit of 250.0 (--max-pixels)"
        );
    }

    #[test]
    fn sizes_are_checked_from_the_header_before_decoding() {
        let png = encode(
            &DynamicImage::ImageLuma8(sample_gray(40, 30)),
            ImageFormat::Png,
        );
        assert!(decode_image_within(&png, &DecodeLimits::with_max_pixels(1200)).is_ok());
        assert_eq!(
            decode_image_within(&png, &DecodeLimits::with_max_pixels(1199)),
            Err(DecodeError::TooManyPixels {
                width: 40,
                height: 30,
                max_pixels: 1199
            })
        );
        // A JPEG whose frame header was edited to claim far more pixels than its data holds: the
        // lenient decoder would fill 225 megapixels with gray.
        let mut jpeg = encode(
            &DynamicImage::ImageLuma8(sample_gray(64, 64)),
            ImageFormat::Jpeg,
        );
        let sof = jpeg
            .windows(2)
            .position(|pair| pair == [0xFF, 0xC0])
            .unwrap();
        jpeg[sof + 5..sof + 9].copy_from_slice(&[0x3A, 0x98, 0x3A, 0x98]); // 15 000 × 15 000
        match decode_image(&jpeg) {
            Err(DecodeError::Corrupt(message)) => {
                assert!(
                    message.starts_with("JPEG data too short for its 15000×15000 pixels"),
                    "{message}"
                )
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_file_that_is_no_image_is_known_from_its_first_bytes() {
        assert_eq!(identify_format(b"\x89PNG\r\n\x1a\n"), Ok(ImageFormat::Png));
        assert_eq!(identify_format(&[0u8; 4096]), Err(DecodeError::NotAnImage));
        assert_eq!(identify_format(b"hello"), Err(DecodeError::NotAnImage));
        assert_eq!(identify_format(&[]), Err(DecodeError::EmptyInput));
        let tga = encode(
            &DynamicImage::ImageLuma8(sample_gray(40, 30)),
            ImageFormat::Tga,
        );
        assert_eq!(identify_format(&tga[..18]), Ok(ImageFormat::Tga));
    }

    #[test]
    fn transparency_is_composited_over_white() {
        let rgba = ImageBuffer::from_fn(4, 1, |x, _| match x {
            0 => Rgba([0u8, 0, 0, 0]),   // transparent: paper
            1 => Rgba([0, 0, 0, 255]),   // opaque black: ink
            2 => Rgba([0, 0, 0, 128]),   // half-covered black: mid gray
            _ => Rgba([255, 0, 0, 255]), // opaque red: its luma
        });
        let gray = to_gray(&DynamicImage::ImageRgba8(rgba));
        assert_eq!(gray.as_raw(), &[255, 0, 127, 54]);

        let gray_alpha =
            ImageBuffer::from_fn(2, 1, |x, _| LumaA([0u8, if x == 0 { 0 } else { 255 }]));
        assert_eq!(
            to_gray(&DynamicImage::ImageLumaA8(gray_alpha)).as_raw(),
            &[255, 0]
        );

        let rgba16 = ImageBuffer::from_fn(2, 1, |x, _| {
            Rgba([0u16, 0, 0, if x == 0 { 0 } else { 65535 }])
        });
        assert_eq!(
            to_gray(&DynamicImage::ImageRgba16(rgba16)).as_raw(),
            &[255, 0]
        );

        let rgba_float = ImageBuffer::from_fn(2, 1, |x, _| {
            Rgba([0f32, 0.0, 0.0, if x == 0 { 0.0 } else { 1.0 }])
        });
        assert_eq!(
            to_gray(&DynamicImage::ImageRgba32F(rgba_float)).as_raw(),
            &[255, 0]
        );
    }

    #[test]
    fn deep_and_colour_images_reduce_to_8_bit_luma() {
        let luma16 = ImageBuffer::from_fn(3, 1, |x, _| Luma([[0u16, 32_896, 65_535][x as usize]]));
        assert_eq!(
            to_gray(&DynamicImage::ImageLuma16(luma16)).as_raw(),
            &[0, 128, 255]
        );

        // Rec. 709: pure green is much brighter than pure blue.
        let rgb = ImageBuffer::from_fn(3, 1, |x, _| match x {
            0 => Rgb([0u8, 255, 0]),
            1 => Rgb([0, 0, 255]),
            _ => Rgb([200, 200, 200]),
        });
        assert_eq!(
            to_gray(&DynamicImage::ImageRgb8(rgb)).as_raw(),
            &[182, 18, 200]
        );

        let rgb16 = ImageBuffer::from_fn(1, 1, |_, _| Rgb([0u16, 65_535, 0]));
        assert_eq!(to_gray(&DynamicImage::ImageRgb16(rgb16)).as_raw(), &[182]);

        // Floats outside 0..=1 (HDR) and NaN are clamped, never wrapped.
        let float = ImageBuffer::from_fn(3, 1, |x, _| {
            let v = [4.0f32, -1.0, f32::NAN][x as usize];
            Rgb([v, v, v])
        });
        assert_eq!(
            to_gray(&DynamicImage::ImageRgb32F(float)).as_raw(),
            &[255, 0, 0]
        );
    }
}
