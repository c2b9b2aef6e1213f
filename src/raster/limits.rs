//! What an image file may make the decoder do, checked before it does it: at most so many
//! pixels (read from the header, before any pixel is decoded), at most so many bytes of file and
//! of decoder allocations, and for JPEG, at least the data its size needs. The same limits hold
//! for every format (see `docs/design.md`, "Limits").

use image::Limits;

/// The default largest image, in pixels: 250 megapixels, an A0 sheet scanned at 400 dpi
/// (13 244 × 18 724). Larger images are refused from their header unless the limit is raised.
pub const DEFAULT_MAX_PIXELS: u64 = 250_000_000;

/// DECISION: a file may hold, and its decoder allocate, this many bytes for every allowed pixel
/// (an 8-bit RGBA page): 1 GB at the default limit. Deeper pages (16-bit colour, float) are
/// allowed at proportionally fewer pixels. Without it the `image` crate allows 512 MiB whatever
/// the limit, which refuses an A0 colour scan.
pub const BYTES_PER_PIXEL: u64 = 4;

/// DECISION: room beyond the pixels for what files carry besides them (EXIF thumbnails, colour
/// profiles, text chunks) and for the decoders' own buffers.
const ALLOWANCE_BYTES: u64 = 64 << 20;

/// How large an image [`crate::stages::decode`] agrees to decode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DecodeLimits {
    /// The largest width × height accepted.
    pub max_pixels: u64,
}

impl Default for DecodeLimits {
    fn default() -> Self {
        Self {
            max_pixels: DEFAULT_MAX_PIXELS,
        }
    }
}

impl DecodeLimits {
    /// Limits allowing images of up to `max_pixels` pixels.
    pub fn with_max_pixels(max_pixels: u64) -> Self {
        Self { max_pixels }
    }

    /// The largest file read: [`BYTES_PER_PIXEL`] per allowed pixel, plus room for metadata.
    pub fn max_file_bytes(&self) -> u64 {
        self.max_pixels
            .saturating_mul(BYTES_PER_PIXEL)
            .saturating_add(ALLOWANCE_BYTES)
    }

    /// The `image` crate's limits: the same bytes for the decoder's allocations.
    pub(super) fn for_decoder(&self) -> Limits {
        let mut limits = Limits::default();
        limits.max_alloc = Some(self.max_file_bytes());
        limits
    }

    /// Whether a `width` × `height` image is within the limit.
    pub fn allows(&self, width: u32, height: u32) -> bool {
        u64::from(width) * u64::from(height) <= self.max_pixels
    }
}

/// The least number of bytes a JPEG with this frame header needs for `width` × `height` pixels,
/// or `None` when it cannot tell (no frame header before the first scan, arithmetic coding).
///
/// DECISION: a Huffman-coded JPEG spends at least one bit on every 8 × 8 block of every
/// component, progressive or not: each block's DC value is coded, and no Huffman code is shorter
/// than one bit. The `image` crate's JPEG decoder is lenient like a browser and fills whatever
/// the data does not cover with gray, so a 1 kB file whose header was edited to claim
/// 15 000 × 15 000 pixels would otherwise decode (and trace) 225 megapixels of nothing.
pub(super) fn jpeg_minimum_bytes(bytes: &[u8], width: u32, height: u32) -> Option<u64> {
    let frame = jpeg_frame_header(bytes)?;
    // Length (2), precision (1), height (2), width (2), then the component count.
    let components = frame.get(7..)?;
    let count = usize::from(*components.first()?);
    let factors: Vec<(u64, u64)> = components
        .get(1..1 + 3 * count)?
        .chunks_exact(3)
        .map(|component| (u64::from(component[1] >> 4), u64::from(component[1] & 0x0F)))
        .collect();
    let horizontal_max = factors.iter().map(|f| f.0).max()?;
    let vertical_max = factors.iter().map(|f| f.1).max()?;
    if horizontal_max == 0 || vertical_max == 0 {
        return None;
    }
    let (width, height) = (u64::from(width), u64::from(height));
    let blocks: u64 = factors
        .iter()
        .map(|&(horizontal, vertical)| {
            let columns = (width * horizontal).div_ceil(horizontal_max).div_ceil(8);
            let rows = (height * vertical).div_ceil(vertical_max).div_ceil(8);
            columns * rows
        })
        .sum();
    Some(blocks / 8)
}

/// The body of a JPEG's Huffman-coded frame header (SOF0–3, 5–7: length, precision, height,
/// width, components), found by walking the marker segments from the start of the file.
fn jpeg_frame_header(bytes: &[u8]) -> Option<&[u8]> {
    let mut at = 2; // after the start-of-image marker
    loop {
        if *bytes.get(at)? != 0xFF {
            return None;
        }
        let marker = *bytes.get(at + 1)?;
        match marker {
            // Fill bytes before a marker.
            0xFF => at += 1,
            // Markers without a segment: restart markers, TEM.
            0x01 | 0xD0..=0xD7 => at += 2,
            // Start of scan or end of image before any frame header.
            0xDA | 0xD9 => return None,
            _ => {
                let length = usize::from(u16::from_be_bytes([
                    *bytes.get(at + 2)?,
                    *bytes.get(at + 3)?,
                ]));
                let segment = bytes.get(at + 2..at + 2 + length)?;
                match marker {
                    0xC0..=0xC3 | 0xC5..=0xC7 => return Some(segment),
                    // Arithmetic coding: far denser, and not decoded by the `image` crate.
                    0xC9..=0xCB | 0xCD..=0xCF => return None,
                    _ => at += 2 + length,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{DynamicImage, GrayImage, ImageFormat, Luma, RgbImage};
    use std::io::Cursor;

    fn encode(image: &DynamicImage) -> Vec<u8> {
        let mut bytes = Cursor::new(Vec::new());
        image.write_to(&mut bytes, ImageFormat::Jpeg).unwrap();
        bytes.into_inner()
    }

    /// Real JPEGs, even blank ones (the best compression there is), have at least the data the
    /// bound asks for; a header edited to claim more pixels does not.
    #[test]
    fn real_jpegs_have_the_data_their_size_needs() {
        let blank_gray = DynamicImage::ImageLuma8(GrayImage::from_pixel(800, 600, Luma([255])));
        let blank_colour =
            DynamicImage::ImageRgb8(RgbImage::from_pixel(640, 480, image::Rgb([255, 255, 255])));
        for image in [blank_gray, blank_colour] {
            let bytes = encode(&image);
            let needed = jpeg_minimum_bytes(&bytes, image.width(), image.height()).unwrap();
            assert!(needed > 0);
            assert!(bytes.len() as u64 >= needed, "{} < {needed}", bytes.len());
            let claimed = jpeg_minimum_bytes(&bytes, 15_000, 15_000).unwrap();
            assert!(
                bytes.len() as u64 * 50 < claimed,
                "{} vs {claimed}",
                bytes.len()
            );
        }
    }

    #[test]
    fn gray_needs_a_bit_per_block_and_subsampled_colour_more() {
        let gray = encode(&DynamicImage::ImageLuma8(GrayImage::new(64, 64)));
        // 8 × 8 blocks of one component: 64 bits.
        assert_eq!(jpeg_minimum_bytes(&gray, 64, 64), Some(8));
        assert_eq!(jpeg_minimum_bytes(&gray, 65, 64), Some(9));
        assert_eq!(jpeg_minimum_bytes(b"\xFF\xD8\xFF\xDA", 64, 64), None);
        assert_eq!(jpeg_minimum_bytes(b"not a jpeg", 64, 64), None);
    }

    #[test]
    fn limits_scale_with_the_pixels_allowed() {
        let limits = DecodeLimits::default();
        assert!(limits.allows(13_244, 18_724));
        assert!(!limits.allows(20_000, 20_000));
        assert!(!limits.allows(65_535, 65_535));
        let small = DecodeLimits::with_max_pixels(1000);
        assert!(small.allows(10, 100) && !small.allows(10, 101));
        assert_eq!(small.max_file_bytes(), 4000 + ALLOWANCE_BYTES);
        assert_eq!(
            DecodeLimits::with_max_pixels(u64::MAX).max_file_bytes(),
            u64::MAX
        );
    }
}
