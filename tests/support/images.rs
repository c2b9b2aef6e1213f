//! Image comparison with an explicit tolerance, and the expected | difference | actual picture
//! written to `tests/diffs/` when two images disagree.

use std::fmt;
use std::path::PathBuf;

use image::{Rgba, RgbaImage};

/// The outcome of [`compare_images`].
#[derive(Clone, Debug, PartialEq)]
pub struct ImageComparison {
    /// Size of the expected image.
    pub expected_size: (u32, u32),
    /// Size of the actual image.
    pub actual_size: (u32, u32),
    /// Pixels where some channel differs by more than the tolerance; with different sizes, the
    /// pixels that only one image has count too.
    pub differing_pixels: usize,
    /// The largest channel difference over the common area.
    pub largest_difference: u8,
    /// Channel difference that still counts as equal.
    pub per_pixel_tolerance: u8,
    /// How many differing pixels are accepted.
    pub allowed_differing_pixels: usize,
}

impl ImageComparison {
    /// Same size and no more differing pixels than allowed.
    pub fn passed(&self) -> bool {
        self.expected_size == self.actual_size
            && self.differing_pixels <= self.allowed_differing_pixels
    }

    /// A one-line account for failure messages.
    pub fn summary(&self) -> String {
        self.to_string()
    }
}

impl fmt::Display for ImageComparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.expected_size != self.actual_size {
            write!(
                f,
                "size differs: expected {}×{}, actual {}×{}; ",
                self.expected_size.0, self.expected_size.1, self.actual_size.0, self.actual_size.1
            )?;
        }
        write!(
            f,
            "{} pixels differ by more than {} (allowed: {}); largest difference {}",
            self.differing_pixels,
            self.per_pixel_tolerance,
            self.allowed_differing_pixels,
            self.largest_difference
        )
    }
}

/// Compares two images channel by channel. A size mismatch is a failed comparison, not a panic.
pub fn compare_images(
    expected: &RgbaImage,
    actual: &RgbaImage,
    per_pixel_tolerance: u8,
    allowed_differing_pixels: usize,
) -> ImageComparison {
    let (width, height) = common_size(expected, actual);
    let mut differing_pixels = 0;
    let mut largest_difference = 0;
    for y in 0..height {
        for x in 0..width {
            let difference = pixel_difference(expected.get_pixel(x, y), actual.get_pixel(x, y));
            largest_difference = largest_difference.max(difference);
            if difference > per_pixel_tolerance {
                differing_pixels += 1;
            }
        }
    }
    let area = |image: &RgbaImage| image.width() as usize * image.height() as usize;
    differing_pixels += area(expected) + area(actual) - 2 * (width as usize * height as usize);
    ImageComparison {
        expected_size: expected.dimensions(),
        actual_size: actual.dimensions(),
        differing_pixels,
        largest_difference,
        per_pixel_tolerance,
        allowed_differing_pixels,
    }
}

/// Writes `tests/diffs/<name>.png`: expected, difference and actual side by side. In the middle
/// panel unchanged pixels are a faded copy of the expected image and differing ones red, the
/// stronger the larger the difference; area only one image has is red too.
pub fn write_diff(name: &str, expected: &RgbaImage, actual: &RgbaImage) -> PathBuf {
    const SEPARATOR: u32 = 4;
    let difference_width = expected.width().max(actual.width());
    let difference_height = expected.height().max(actual.height());
    let width = expected.width() + difference_width + actual.width() + 2 * SEPARATOR;
    let height = difference_height;
    let mut picture = RgbaImage::from_pixel(width, height, Rgba([128, 128, 128, 255]));
    image::imageops::replace(&mut picture, expected, 0, 0);
    let difference_left = expected.width() + SEPARATOR;
    for y in 0..difference_height {
        for x in 0..difference_width {
            let inside = |image: &RgbaImage| x < image.width() && y < image.height();
            let pixel = if inside(expected) && inside(actual) {
                let (a, b) = (expected.get_pixel(x, y), actual.get_pixel(x, y));
                let difference = pixel_difference(a, b);
                let faded = 255 - (255 - luminance(a)) / 4;
                if difference == 0 {
                    Rgba([faded, faded, faded, 255])
                } else {
                    // Even a difference of one level is visible.
                    let strength = 96 + u32::from(difference) * 159 / 255;
                    let other = (255 - strength) as u8;
                    Rgba([255, other, other, 255])
                }
            } else {
                Rgba([255, 0, 0, 255])
            };
            picture.put_pixel(difference_left + x, y, pixel);
        }
    }
    let actual_left = i64::from(difference_left + difference_width + SEPARATOR);
    image::imageops::replace(&mut picture, actual, actual_left, 0);

    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/diffs");
    std::fs::create_dir_all(&folder).expect("cannot create tests/diffs");
    let path = folder.join(format!("{name}.png"));
    picture
        .save(&path)
        .unwrap_or_else(|error| panic!("cannot write {}: {error}", path.display()));
    path
}

fn common_size(a: &RgbaImage, b: &RgbaImage) -> (u32, u32) {
    (a.width().min(b.width()), a.height().min(b.height()))
}

fn pixel_difference(a: &Rgba<u8>, b: &Rgba<u8>) -> u8 {
    a.0.iter()
        .zip(b.0.iter())
        .map(|(x, y)| x.abs_diff(*y))
        .max()
        .unwrap_or(0)
}

fn luminance(pixel: &Rgba<u8>) -> u8 {
    let [r, g, b, _] = pixel.0.map(u32::from);
    ((299 * r + 587 * g + 114 * b) / 1000) as u8
}
