//! The ground truth describes its picture: every sample in `samples/` has a truth file of its
//! size, nearly all of the sample's ink lies near a true curve, and every true curve has ink
//! along most of its length.

use crate::support;

use std::path::{Path, PathBuf};

use crawltrace::{render_svg, to_svg, CurvePath, Drawing, Point};
use image::{DynamicImage, GrayImage};
use support::{load_curves, load_stroke_width, Polyline};

/// Ink may stray this far beyond the pen width from a true curve (jitter, blur, round caps).
const INK_MARGIN: f64 = 3.0;
/// At most this fraction of the dark pixels may lie farther than that.
const STRAY_INK_ALLOWED: f64 = 0.001;
/// Every true curve must have ink along at least this fraction of its length; gaps are at most
/// 3 pen widths between strokes of at least 4.
const INKED_LENGTH_REQUIRED: f64 = 0.7;

fn samples_folder() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("samples")
}

/// Every sample image, sorted.
fn sample_images() -> Vec<PathBuf> {
    let mut images: Vec<PathBuf> = std::fs::read_dir(samples_folder())
        .expect("samples/ exists")
        .map(|entry| entry.expect("readable entry").path())
        .filter(|path| {
            matches!(
                path.extension().and_then(|e| e.to_str()),
                Some("png" | "jpg")
            )
        })
        .collect();
    images.sort();
    images
}

fn truth_path(image: &Path) -> PathBuf {
    let stem = image.file_stem().unwrap().to_str().unwrap();
    image.with_file_name(format!("{stem}.truth.svg"))
}

#[test]
fn every_sample_has_a_truth_file_and_every_truth_file_a_sample() {
    let images = sample_images();
    assert!(images.len() >= 10, "expected at least ten samples");
    for image in &images {
        assert!(
            truth_path(image).is_file(),
            "{} has no truth",
            image.display()
        );
    }
    let truth_count = std::fs::read_dir(samples_folder())
        .unwrap()
        .filter(|e| {
            let name = e.as_ref().unwrap().file_name();
            name.to_string_lossy().ends_with(".truth.svg")
        })
        .count();
    assert_eq!(truth_count, images.len(), "a truth file without a sample");
}

#[test]
fn truth_curves_describe_the_ink_of_every_sample() {
    let mut failures = Vec::new();
    for image_path in sample_images() {
        let name = image_path
            .file_name()
            .unwrap()
            .to_string_lossy()
            .to_string();
        let svg = std::fs::read_to_string(truth_path(&image_path)).expect("truth file");
        let image = image::open(&image_path).expect("sample decodes");
        let tree = usvg::Tree::from_str(&svg, &usvg::Options::default()).expect("truth parses");
        let size = (tree.size().width() as u32, tree.size().height() as u32);
        assert_eq!(size, (image.width(), image.height()), "{name}: truth size");

        let pen = load_stroke_width(&svg).expect("truth has the pen width");
        let curves = load_curves(&svg);
        let ink = dark_pixels(&luminance_on_white(&image));
        let near_truth = band_around(&curves, size, pen + INK_MARGIN);

        let dark = ink.iter().filter(|&&d| d).count();
        let stray = ink
            .iter()
            .zip(&near_truth)
            .filter(|&(&dark, &near)| dark && !near)
            .count();
        let stray_fraction = stray as f64 / dark.max(1) as f64;
        if dark == 0 || stray_fraction > STRAY_INK_ALLOWED {
            failures.push(format!(
                "{name}: {stray} of {dark} dark pixels lie farther than {} px from every true curve",
                pen + INK_MARGIN
            ));
        }

        let mut least_inked: f64 = 1.0;
        for (index, curve) in curves.iter().enumerate() {
            let inked = inked_fraction(curve, &ink, size, pen / 2.0 + 1.5);
            least_inked = least_inked.min(inked);
            if inked < INKED_LENGTH_REQUIRED {
                failures.push(format!(
                    "{name}: true curve {index} has ink along only {:.0} % of its length",
                    inked * 100.0
                ));
            }
        }
        println!(
            "{name}: {dark} dark pixels, {stray} far from the truth; \
             least inked curve {:.0} %",
            least_inked * 100.0
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Grey levels with any alpha composited on white, 16-bit reduced to 8.
fn luminance_on_white(image: &DynamicImage) -> GrayImage {
    let rgba = image.to_rgba8();
    GrayImage::from_fn(rgba.width(), rgba.height(), |x, y| {
        let [r, g, b, a] = rgba.get_pixel(x, y).0.map(f64::from);
        let luma = 0.299 * r + 0.587 * g + 0.114 * b;
        let alpha = a / 255.0;
        image::Luma([(luma * alpha + 255.0 * (1.0 - alpha)).round() as u8])
    })
}

/// Ink: pixels much darker than their surroundings (the mean of a 41×41 window), so uneven
/// lighting on the scans does not count as ink.
fn dark_pixels(gray: &GrayImage) -> Vec<bool> {
    const RADIUS: i64 = 20;
    let (width, height) = (gray.width() as i64, gray.height() as i64);
    // Summed-area table with a zero row and column in front.
    let stride = width + 1;
    let mut sums = vec![0u64; (stride * (height + 1)) as usize];
    for y in 0..height {
        for x in 0..width {
            let value = u64::from(gray.get_pixel(x as u32, y as u32).0[0]);
            let at = ((y + 1) * stride + x + 1) as usize;
            sums[at] =
                value + sums[at - 1] + sums[at - stride as usize] - sums[at - stride as usize - 1];
        }
    }
    let mut dark = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let (x0, y0) = ((x - RADIUS).max(0), (y - RADIUS).max(0));
            let (x1, y1) = ((x + RADIUS + 1).min(width), (y + RADIUS + 1).min(height));
            let sum = sums[(y1 * stride + x1) as usize] + sums[(y0 * stride + x0) as usize]
                - sums[(y0 * stride + x1) as usize]
                - sums[(y1 * stride + x0) as usize];
            let mean = sum as f64 / ((x1 - x0) * (y1 - y0)) as f64;
            let value = f64::from(gray.get_pixel(x as u32, y as u32).0[0]);
            dark.push(value < 0.6 * mean);
        }
    }
    dark
}

/// Pixels within `reach` of some curve, by drawing the curves with resvg at twice that width.
fn band_around(curves: &[Polyline], size: (u32, u32), reach: f64) -> Vec<bool> {
    let drawing = Drawing {
        width: f64::from(size.0),
        height: f64::from(size.1),
        paths: curves
            .iter()
            .map(|c| CurvePath::polyline(&c.points, c.closed))
            .collect(),
        stroke_width: 2.0 * reach,
        color: "black".into(),
        dots: Vec::new(),
        points: Vec::new(),
    };
    let band = render_svg(&to_svg(&drawing), 1.0).expect("band renders");
    band.pixels().map(|p| p.0[0] < 255).collect()
}

/// The fraction of the curve's length, sampled every pixel, that has a dark pixel within `reach`.
fn inked_fraction(curve: &Polyline, ink: &[bool], size: (u32, u32), reach: f64) -> f64 {
    let mut vertices = curve.points.clone();
    if curve.closed {
        vertices.push(vertices[0]);
    }
    let samples: Vec<Point> = vertices
        .windows(2)
        .flat_map(|pair| {
            let steps = pair[0].distance(pair[1]).ceil().max(1.0) as usize;
            (0..steps).map(move |s| pair[0].lerp(pair[1], s as f64 / steps as f64))
        })
        .collect();
    let has_ink_near = |point: Point| {
        let span = reach.ceil() as i64;
        let (cx, cy) = (point.x.floor() as i64, point.y.floor() as i64);
        (cy - span..=cy + span).any(|y| {
            (cx - span..=cx + span).any(|x| {
                let inside = x >= 0 && y >= 0 && x < size.0 as i64 && y < size.1 as i64;
                let centre = Point::new(x as f64 + 0.5, y as f64 + 0.5);
                inside && centre.distance(point) <= reach && ink[(y * size.0 as i64 + x) as usize]
            })
        })
    };
    let inked = samples.iter().filter(|&&p| has_ink_near(p)).count();
    inked as f64 / samples.len().max(1) as f64
}
