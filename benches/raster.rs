//! Raster stages on a synthetic 4000×3000 (12 MP) scan of a skip-stroke drawing: binarize (evenly
//! lit and shaded), estimate_stroke_width, clean and thin. Run with `cargo bench --bench raster`.

#[path = "../tests/support/random.rs"]
mod random;
use random::SplitMix64;

use std::sync::LazyLock;

use crawltrace::stages::binarize::{binarize, BinarizeOptions, ThresholdMethod};
use crawltrace::stages::bitmap::Bitmap;
use crawltrace::stages::clean::{clean, estimate_stroke_width};
use crawltrace::stages::thin::thin;
use divan::{black_box, Bencher};
use image::{GrayImage, Luma};

const WIDTH: u32 = 4000;
const HEIGHT: u32 = 3000;

/// Ink coverage of each pixel (0..=1), drawn stroke by stroke.
struct Canvas {
    coverage: Vec<f32>,
}

impl Canvas {
    /// A thick segment with round caps and a one-pixel anti-aliased edge.
    fn segment(&mut self, from: (f64, f64), to: (f64, f64), stroke_width: f64) {
        let radius = stroke_width / 2.0;
        let (dx, dy) = (to.0 - from.0, to.1 - from.1);
        let length_squared = (dx * dx + dy * dy).max(1e-9);
        let low_x = (from.0.min(to.0) - radius - 1.0).max(0.0) as usize;
        let high_x = ((from.0.max(to.0) + radius + 2.0) as usize).min(WIDTH as usize);
        let low_y = (from.1.min(to.1) - radius - 1.0).max(0.0) as usize;
        let high_y = ((from.1.max(to.1) + radius + 2.0) as usize).min(HEIGHT as usize);
        for y in low_y..high_y {
            for x in low_x..high_x {
                let (px, py) = (x as f64 + 0.5 - from.0, y as f64 + 0.5 - from.1);
                let t = ((px * dx + py * dy) / length_squared).clamp(0.0, 1.0);
                let distance = (px - t * dx).hypot(py - t * dy);
                let cover = (radius + 0.5 - distance).clamp(0.0, 1.0) as f32;
                let cell = &mut self.coverage[y * WIDTH as usize + x];
                *cell = cell.max(cover);
            }
        }
    }

    /// A polyline through `points`.
    fn stroke(&mut self, points: &[(f64, f64)], stroke_width: f64) {
        for pair in points.windows(2) {
            self.segment(pair[0], pair[1], stroke_width);
        }
    }
}

/// A sketch page: circles, ellipses and rectangles, each drawn as short overlapping or gapped
/// strokes with a wobbly hand, as skip-stroke drawings are; then a scan of it (paper 235, ink
/// 35, sensor noise), optionally under uneven light (a side gradient and vignetting).
fn page(shaded: bool) -> GrayImage {
    let mut random = SplitMix64::new(12);
    let mut canvas = Canvas {
        coverage: vec![0.0; (WIDTH * HEIGHT) as usize],
    };
    // Closed shapes traced by a parametric outline point(t), t in 0..1.
    for _ in 0..40 {
        let centre = (random.range(300.0, 3700.0), random.range(300.0, 2700.0));
        let (rx, ry) = (random.range(60.0, 350.0), random.range(60.0, 350.0));
        let square = random.next_u64() % 3 == 0;
        let outline = |t: f64| {
            let angle = t * std::f64::consts::TAU;
            let (c, s) = (angle.cos(), angle.sin());
            if square {
                // A rectangle as a "circle" in the max-norm.
                let scale = c.abs().max(s.abs());
                (centre.0 + rx * c / scale, centre.1 + ry * s / scale)
            } else {
                (centre.0 + rx * c, centre.1 + ry * s)
            }
        };
        let stroke_width = random.range(4.0, 9.0);
        let mut t = random.range(0.0, 1.0);
        let end = t + 1.0;
        while t < end {
            // A stroke covers 3–12% of the outline, starts with a gap or an overlap.
            let span = random.range(0.03, 0.12);
            let wobble = random.range(-3.0, 3.0);
            let points: Vec<(f64, f64)> = (0..=8)
                .map(|i| {
                    let (x, y) = outline(t + span * f64::from(i) / 8.0);
                    let bend = wobble * (f64::from(i) / 8.0 * std::f64::consts::PI).sin();
                    (x + bend, y + bend)
                })
                .collect();
            canvas.stroke(&points, stroke_width);
            t += span + random.range(-0.01, 0.008);
        }
    }
    let mut noise = SplitMix64::new(99);
    let mut gray = GrayImage::new(WIDTH, HEIGHT);
    for (i, pixel) in gray.pixels_mut().enumerate() {
        let (x, y) = ((i as u32 % WIDTH) as f64, (i as u32 / WIDTH) as f64);
        let light = if shaded {
            let (dx, dy) = (x / f64::from(WIDTH) - 0.5, y / f64::from(HEIGHT) - 0.5);
            (1.0 - 0.5 * x / f64::from(WIDTH)) * (1.0 - 0.8 * (dx * dx + dy * dy))
        } else {
            1.0
        };
        let cover = f64::from(canvas.coverage[i]);
        let value = (235.0 - cover * 200.0) * light + (noise.next_u64() % 13) as f64 - 6.0;
        *pixel = Luma([value.round().clamp(0.0, 255.0) as u8]);
    }
    gray
}

static EVEN_PAGE: LazyLock<GrayImage> = LazyLock::new(|| page(false));
static SHADED_PAGE: LazyLock<GrayImage> = LazyLock::new(|| page(true));
static MASK: LazyLock<Bitmap> =
    LazyLock::new(|| binarize(&EVEN_PAGE, &BinarizeOptions::default()).mask);
static STROKE_WIDTH: LazyLock<f64> = LazyLock::new(|| estimate_stroke_width(&MASK));
static CLEANED: LazyLock<Bitmap> = LazyLock::new(|| {
    let mut mask = MASK.clone();
    clean(&mut mask, *STROKE_WIDTH);
    mask
});

fn main() {
    // What is being timed, once, before the timings.
    for (name, page) in [("even", &*EVEN_PAGE), ("shaded", &*SHADED_PAGE)] {
        let result = binarize(page, &BinarizeOptions::default());
        eprintln!(
            "{name} page {WIDTH}×{HEIGHT}: {:?}, {} ink pixels",
            result.method_used,
            result.mask.count_ink()
        );
    }
    let mut cleaned = MASK.clone();
    let report = clean(&mut cleaned, *STROKE_WIDTH);
    let skeleton = thin(&CLEANED);
    let end_points = (0..skeleton.height())
        .flat_map(|y| (0..skeleton.width()).map(move |x| (x, y)))
        .filter(|&(x, y)| skeleton.get(x, y) && skeleton.neighbourhood(x, y).count_ones() == 1)
        .count();
    eprintln!(
        "stroke width {} px; {report:?}; skeleton {} pixels, {end_points} end points",
        *STROKE_WIDTH,
        skeleton.count_ink()
    );
    divan::main();
}

#[divan::bench(sample_count = 20)]
fn binarize_auto_even_light(bencher: Bencher) {
    let page = &*EVEN_PAGE;
    bencher.bench(|| binarize(black_box(page), &BinarizeOptions::default()));
}

#[divan::bench(sample_count = 20)]
fn binarize_auto_shaded(bencher: Bencher) {
    let page = &*SHADED_PAGE;
    bencher.bench(|| binarize(black_box(page), &BinarizeOptions::default()));
}

#[divan::bench(sample_count = 20)]
fn binarize_otsu(bencher: Bencher) {
    let page = &*EVEN_PAGE;
    let options = BinarizeOptions {
        method: ThresholdMethod::Otsu,
        invert: false,
    };
    bencher.bench(|| binarize(black_box(page), &options));
}

#[divan::bench(sample_count = 20)]
fn estimate_stroke_width_12mp(bencher: Bencher) {
    let mask = &*MASK;
    bencher.bench(|| estimate_stroke_width(black_box(mask)));
}

#[divan::bench(sample_count = 20)]
fn clean_12mp(bencher: Bencher) {
    let stroke_width = *STROKE_WIDTH;
    bencher
        .with_inputs(|| MASK.clone())
        .bench_local_refs(|mask| clean(mask, stroke_width));
}

#[divan::bench(sample_count = 20)]
fn thin_12mp(bencher: Bencher) {
    let mask = &*CLEANED;
    bencher.bench(|| thin(black_box(mask)));
}

#[divan::bench(sample_count = 10)]
fn raster_stages_together(bencher: Bencher) {
    let page = &*EVEN_PAGE;
    bencher.bench(|| {
        let mut mask = binarize(black_box(page), &BinarizeOptions::default()).mask;
        let stroke_width = estimate_stroke_width(&mask);
        clean(&mut mask, stroke_width);
        thin(&mask)
    });
}
