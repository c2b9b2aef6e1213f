//! The pixel density an image file records, in pixels per inch: PNG `pHYs`, JPEG JFIF (APP0) and
//! EXIF (APP1), TIFF `XResolution`/`ResolutionUnit`, BMP pixels per metre. Read from the file's
//! bytes (the `image` crate decodes pixels but does not report densities), so that a 300 dpi scan
//! comes out at its real size. Never panics on any bytes: every read is bounds-checked, and a
//! damaged or missing record is simply no density.
//!
//! Formats: PNG (ISO/IEC 15948, chunk `pHYs`), JFIF 1.02 (APP0 units and densities), EXIF 2.3
//! and TIFF 6.0 (IFD0 tags 282 XResolution, 296 ResolutionUnit), BMP (`BITMAPINFOHEADER`
//! `biXPelsPerMeter`).

use std::ops::RangeInclusive;

/// Metres in an inch.
const METRES_PER_INCH: f64 = 0.0254;
/// Centimetres in an inch.
const CENTIMETRES_PER_INCH: f64 = 2.54;

/// DECISION: densities outside this range are treated as absent. Below one pixel per inch or
/// above 100 000 (a quarter micrometre a pixel) no scan, photo or screen image exists; such values
/// are placeholders or damage, and would give absurd sizes.
const PLAUSIBLE_DPI: RangeInclusive<f64> = 1.0..=100_000.0;

/// A PNG chunk holds 12 bytes besides its data: length, type and CRC, four bytes each.
const PNG_CHUNK_OVERHEAD: usize = 12;

/// The horizontal pixel density recorded in an image file, in pixels per inch, or `None` when the
/// file records none (or only an aspect ratio, or an implausible value).
///
/// DECISION: pixels that are not square (a different vertical density, as fax scans have) are
/// sized by their horizontal density; the outputs keep one scale for both axes.
///
/// DECISION: in a JPEG with both, a JFIF density in real units wins over the EXIF one: JFIF is
/// what scanners write, EXIF is often a camera's 72 dpi placeholder.
///
/// # Examples
///
/// ```
/// use crawltrace::stages::density::image_dpi;
///
/// let png = std::fs::read("samples/face-clean.png").unwrap();
/// // The samples are written without a density.
/// assert_eq!(image_dpi(&png), None);
/// assert_eq!(image_dpi(b"not an image"), None);
/// ```
pub fn image_dpi(bytes: &[u8]) -> Option<f64> {
    let dpi = if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        png_dpi(bytes)
    } else if bytes.starts_with(&[0xFF, 0xD8]) {
        jpeg_dpi(bytes)
    } else if bytes.starts_with(b"II*\0") || bytes.starts_with(b"MM\0*") {
        tiff_dpi(bytes)
    } else if bytes.starts_with(b"BM") {
        bmp_dpi(bytes)
    } else {
        None
    };
    dpi.filter(|dpi| PLAUSIBLE_DPI.contains(dpi))
}

/// The density of `per_unit` pixels per unit, `inch` units long, in pixels per inch.
///
/// DECISION: a whole number of pixels per inch that is stored as exactly this per-metre (or
/// per-centimetre) count is taken as that whole number: PNG cannot hold 300 dpi except as 11 811
/// per metre (299.9994 dpi), and the scanner meant 300.
fn per_inch(per_unit: f64, inch: f64) -> f64 {
    let dpi = per_unit * inch;
    let whole = dpi.round();
    if (whole / inch).round() == per_unit {
        whole
    } else {
        dpi
    }
}

/// `bytes[start..start + length]`, or `None` past the end.
fn slice(bytes: &[u8], start: usize, length: usize) -> Option<&[u8]> {
    bytes.get(start..start.checked_add(length)?)
}

fn u16_be(bytes: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_be_bytes(slice(bytes, at, 2)?.try_into().ok()?))
}

fn u32_be(bytes: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_be_bytes(slice(bytes, at, 4)?.try_into().ok()?))
}

fn i32_le(bytes: &[u8], at: usize) -> Option<i32> {
    Some(i32::from_le_bytes(slice(bytes, at, 4)?.try_into().ok()?))
}

/// PNG: the `pHYs` chunk (pixels per unit, x then y, and a unit byte: 1 is the metre, 0 an
/// aspect ratio only). It must come before the image data, so the walk stops at `IDAT`.
fn png_dpi(bytes: &[u8]) -> Option<f64> {
    /// The 8-byte signature, then chunks of length (4), type (4), data, CRC (4).
    const SIGNATURE_LENGTH: usize = 8;
    const UNIT_METRE: u8 = 1;
    let mut at = SIGNATURE_LENGTH;
    loop {
        let length = usize::try_from(u32_be(bytes, at)?).ok()?;
        let kind = slice(bytes, at + 4, 4)?;
        let data = slice(bytes, at + 8, length)?;
        match kind {
            b"pHYs" => {
                let per_metre = u32_be(data, 0)?;
                return (*data.get(8)? == UNIT_METRE)
                    .then(|| per_inch(f64::from(per_metre), METRES_PER_INCH));
            }
            b"IDAT" | b"IEND" => return None,
            _ => at = at.checked_add(length)?.checked_add(PNG_CHUNK_OVERHEAD)?,
        }
    }
}

/// JPEG: the markers before the first scan; JFIF's APP0 density if in real units, else EXIF's.
fn jpeg_dpi(bytes: &[u8]) -> Option<f64> {
    const APP0: u8 = 0xE0;
    const APP1: u8 = 0xE1;
    const START_OF_SCAN: u8 = 0xDA;
    let mut exif = None;
    let mut at = 2;
    while let (Some(&0xFF), Some(&marker)) = (bytes.get(at), bytes.get(at + 1)) {
        if marker == 0xFF {
            at += 1; // fill byte
            continue;
        }
        if marker == START_OF_SCAN || (0xD0..=0xD9).contains(&marker) {
            break; // image data (or a marker without a length) from here on
        }
        let length = usize::from(u16_be(bytes, at + 2)?);
        let segment = slice(bytes, at + 4, length.checked_sub(2)?)?;
        match marker {
            APP0 => {
                if let Some(dpi) = jfif_dpi(segment) {
                    return Some(dpi);
                }
            }
            APP1 if exif.is_none() => {
                exif = segment.strip_prefix(b"Exif\0\0").and_then(tiff_dpi);
            }
            _ => {}
        }
        at += 2 + length;
    }
    exif
}

/// A JFIF APP0 segment: `JFIF\0`, version (2), units (1: 0 aspect only, 1 per inch, 2 per cm),
/// x density (2), y density (2).
fn jfif_dpi(segment: &[u8]) -> Option<f64> {
    let fields = segment.strip_prefix(b"JFIF\0")?;
    let density = f64::from(u16_be(fields, 3)?);
    match fields.get(2)? {
        1 => Some(density),
        2 => Some(per_inch(density, CENTIMETRES_PER_INCH)),
        _ => None,
    }
}

/// A TIFF structure (a TIFF file, or an EXIF block): the first IFD's XResolution (a rational) in
/// ResolutionUnit (2 inch, the default; 3 centimetre; 1 none).
fn tiff_dpi(tiff: &[u8]) -> Option<f64> {
    const X_RESOLUTION: u16 = 282;
    const RESOLUTION_UNIT: u16 = 296;
    const TYPE_RATIONAL: u16 = 5;
    const ENTRY_LENGTH: usize = 12;
    let little_endian = match slice(tiff, 0, 2)? {
        b"II" => true,
        b"MM" => false,
        _ => return None,
    };
    let read_u16 = |at: usize| {
        let pair: [u8; 2] = slice(tiff, at, 2)?.try_into().ok()?;
        Some(if little_endian {
            u16::from_le_bytes(pair)
        } else {
            u16::from_be_bytes(pair)
        })
    };
    let read_u32 = |at: usize| {
        let quad: [u8; 4] = slice(tiff, at, 4)?.try_into().ok()?;
        Some(if little_endian {
            u32::from_le_bytes(quad)
        } else {
            u32::from_be_bytes(quad)
        })
    };
    let directory = usize::try_from(read_u32(4)?).ok()?;
    let entries = usize::from(read_u16(directory)?);
    let mut resolution = None;
    let mut per_centimetre = false;
    for index in 0..entries {
        let entry = directory + 2 + index * ENTRY_LENGTH;
        match read_u16(entry)? {
            X_RESOLUTION if read_u16(entry + 2)? == TYPE_RATIONAL => {
                let value = usize::try_from(read_u32(entry + 8)?).ok()?;
                let (numerator, denominator) = (read_u32(value)?, read_u32(value + 4)?);
                resolution =
                    (denominator != 0).then(|| f64::from(numerator) / f64::from(denominator));
            }
            // A SHORT held in the entry itself (first two bytes of the value field).
            RESOLUTION_UNIT => match read_u16(entry + 8)? {
                1 => return None,
                3 => per_centimetre = true,
                _ => {}
            },
            _ => {}
        }
    }
    resolution.map(|density| {
        if per_centimetre {
            per_inch(density, CENTIMETRES_PER_INCH)
        } else {
            density
        }
    })
}

/// BMP: `biXPelsPerMeter` of a `BITMAPINFOHEADER` (or a later header of 40 bytes or more);
/// 0 means unset. The old 12-byte core header has no density.
fn bmp_dpi(bytes: &[u8]) -> Option<f64> {
    const FILE_HEADER_LENGTH: usize = 14;
    const INFO_HEADER_LENGTH: i32 = 40;
    const X_PER_METRE_OFFSET: usize = FILE_HEADER_LENGTH + 24;
    if i32_le(bytes, FILE_HEADER_LENGTH)? < INFO_HEADER_LENGTH {
        return None;
    }
    let per_metre = i32_le(bytes, X_PER_METRE_OFFSET)?;
    (per_metre > 0).then(|| per_inch(f64::from(per_metre), METRES_PER_INCH))
}

#[cfg(test)]
mod tests {
    use std::io::Cursor;

    use image::{DynamicImage, GrayImage, ImageFormat};

    use super::*;

    fn encoded(format: ImageFormat) -> Vec<u8> {
        let image = DynamicImage::ImageLuma8(GrayImage::new(4, 3));
        let mut bytes = Vec::new();
        image
            .write_to(&mut Cursor::new(&mut bytes), format)
            .unwrap();
        bytes
    }

    /// A PNG chunk with a (not checked here) zero CRC.
    fn png_chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
        let mut chunk = (data.len() as u32).to_be_bytes().to_vec();
        chunk.extend_from_slice(kind);
        chunk.extend_from_slice(data);
        chunk.extend_from_slice(&[0; 4]);
        chunk
    }

    /// `png` with a `pHYs` chunk inserted after the header chunk.
    fn with_phys(png: &[u8], per_metre: u32, unit: u8) -> Vec<u8> {
        let header_end = 8 + 4 + 4 + 13 + 4;
        let mut data = per_metre.to_be_bytes().to_vec();
        data.extend_from_slice(&per_metre.to_be_bytes());
        data.push(unit);
        let mut bytes = png[..header_end].to_vec();
        bytes.extend(png_chunk(b"pHYs", &data));
        bytes.extend_from_slice(&png[header_end..]);
        bytes
    }

    #[test]
    fn png_density_comes_from_phys_in_metres_only() {
        let png = encoded(ImageFormat::Png);
        assert_eq!(image_dpi(&png), None);
        // 300 dpi is stored as 11 811 per metre (299.9994 dpi), and read back as 300.
        assert_eq!(image_dpi(&with_phys(&png, 11811, 1)), Some(300.0));
        // A count that no whole dpi is stored as stays as it is.
        let dpi = image_dpi(&with_phys(&png, 10_020, 1)).unwrap();
        assert!((dpi - 254.508).abs() < 1e-9, "{dpi}");
        assert_eq!(image_dpi(&with_phys(&png, 11811, 0)), None); // aspect ratio only
                                                                 // A pHYs after the image data does not count.
        let mut late = png[..png.len() - 12].to_vec();
        late.extend(png_chunk(b"pHYs", &[0, 0, 46, 35, 0, 0, 46, 35, 1]));
        assert_eq!(image_dpi(&late), None);
    }

    /// A JPEG of `segments` (marker, payload) and an end marker: enough for the density reader.
    fn jpeg(segments: &[(u8, Vec<u8>)]) -> Vec<u8> {
        let mut bytes = vec![0xFF, 0xD8];
        for (marker, payload) in segments {
            bytes.extend_from_slice(&[0xFF, *marker]);
            bytes.extend_from_slice(&((payload.len() + 2) as u16).to_be_bytes());
            bytes.extend_from_slice(payload);
        }
        bytes.extend_from_slice(&[0xFF, 0xDA, 0, 2, 0xFF, 0xD9]);
        bytes
    }

    fn jfif(units: u8, density: u16) -> (u8, Vec<u8>) {
        let mut payload = b"JFIF\0\x01\x02".to_vec();
        payload.push(units);
        payload.extend_from_slice(&density.to_be_bytes());
        payload.extend_from_slice(&density.to_be_bytes());
        payload.extend_from_slice(&[0, 0]);
        (0xE0, payload)
    }

    /// A little-endian TIFF structure with XResolution `numerator/denominator` and `unit`.
    fn tiff(numerator: u32, denominator: u32, unit: u16) -> Vec<u8> {
        let mut bytes = b"II*\0".to_vec();
        bytes.extend_from_slice(&8u32.to_le_bytes());
        bytes.extend_from_slice(&2u16.to_le_bytes());
        let rational_at = 8 + 2 + 2 * 12 + 4;
        for (tag, kind, value) in [
            (282u16, 5u16, rational_at as u32),
            (296, 3, u32::from(unit)),
        ] {
            bytes.extend_from_slice(&tag.to_le_bytes());
            bytes.extend_from_slice(&kind.to_le_bytes());
            bytes.extend_from_slice(&1u32.to_le_bytes());
            bytes.extend_from_slice(&value.to_le_bytes());
        }
        bytes.extend_from_slice(&0u32.to_le_bytes()); // no next IFD
        bytes.extend_from_slice(&numerator.to_le_bytes());
        bytes.extend_from_slice(&denominator.to_le_bytes());
        bytes
    }

    fn exif(tiff: Vec<u8>) -> (u8, Vec<u8>) {
        let mut payload = b"Exif\0\0".to_vec();
        payload.extend(tiff);
        (0xE1, payload)
    }

    #[test]
    fn jpeg_density_comes_from_jfif_then_exif() {
        assert_eq!(image_dpi(&jpeg(&[jfif(1, 300)])), Some(300.0));
        assert_eq!(image_dpi(&jpeg(&[jfif(2, 100)])), Some(254.0)); // per cm
        assert_eq!(image_dpi(&jpeg(&[jfif(2, 118)])), Some(300.0)); // 299.72: how 300 dpi is stored
        assert_eq!(image_dpi(&jpeg(&[jfif(0, 1)])), None); // aspect only
        let both = jpeg(&[jfif(1, 600), exif(tiff(72, 1, 2))]);
        assert_eq!(image_dpi(&both), Some(600.0));
        let exif_only = jpeg(&[jfif(0, 1), exif(tiff(600, 2, 2))]);
        assert_eq!(image_dpi(&exif_only), Some(300.0));
        // The image crate's own JPEG writes JFIF with an aspect ratio only.
        assert_eq!(image_dpi(&encoded(ImageFormat::Jpeg)), None);
    }

    #[test]
    fn tiff_density_follows_its_unit() {
        assert_eq!(image_dpi(&tiff(300, 1, 2)), Some(300.0));
        assert_eq!(image_dpi(&tiff(100, 1, 3)), Some(254.0));
        assert_eq!(image_dpi(&tiff(300, 1, 1)), None); // no unit
        assert_eq!(image_dpi(&tiff(300, 0, 2)), None); // division by zero
        assert_eq!(image_dpi(&tiff(0, 1, 2)), None); // implausible
    }

    #[test]
    fn bmp_density_is_in_pixels_per_metre() {
        let mut bmp = encoded(ImageFormat::Bmp);
        bmp[38..42].copy_from_slice(&3780i32.to_le_bytes());
        assert_eq!(image_dpi(&bmp), Some(96.0)); // 3780 per metre: how 96 dpi is stored
        bmp[38..42].copy_from_slice(&0i32.to_le_bytes());
        assert_eq!(image_dpi(&bmp), None);
    }

    /// Every prefix of every file, and every file with one byte changed, reads without a panic.
    #[test]
    fn damaged_files_never_panic_and_give_a_usable_density_or_none() {
        let files = [
            with_phys(&encoded(ImageFormat::Png), 11811, 1),
            jpeg(&[jfif(0, 1), exif(tiff(600, 2, 2))]),
            tiff(300, 1, 2),
            encoded(ImageFormat::Bmp),
        ];
        // Whatever is read from a damaged file is a density the output can use, or none.
        let usable = |dpi: Option<f64>| dpi.is_none_or(|dpi| PLAUSIBLE_DPI.contains(&dpi));
        for file in &files {
            for end in 0..file.len() {
                assert!(usable(image_dpi(&file[..end])), "cut at {end}");
            }
            for at in 0..file.len() {
                for value in [0x00, 0x7F, 0xFF] {
                    let mut damaged = file.clone();
                    damaged[at] = value;
                    assert!(usable(image_dpi(&damaged)), "byte {at} set to {value}");
                }
            }
        }
    }
}
