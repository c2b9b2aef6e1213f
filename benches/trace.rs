//! The whole `trace` on a 4000×3000 skip-stroke page, end to end (file bytes → SVG text) and stage
//! by stage, on the PNG page and on a scan-like colour JPEG of it. Run with
//! `cargo bench --bench trace`; before the timings it prints each stage's share of one trace.
//!
//! The page is `samples/page-4000x3000.png` when present, otherwise a comparable page drawn
//! deterministically (see `benches/support/pages.rs`).

#[path = "support/pages.rs"]
mod pages;

use std::fmt;
use std::sync::LazyLock;
use std::time::{Duration, Instant};

use crawltrace::stages::binarize::{binarize, BinarizeOptions};
use crawltrace::stages::bitmap::Bitmap;
use crawltrace::stages::clean::{clean, estimate_stroke_width};
use crawltrace::stages::crawl::strokes::{connect, Method};
use crawltrace::stages::crawl::tips::restore_tips;
use crawltrace::stages::decode::{decode_image, to_gray};
use crawltrace::stages::fit::{default_tolerance, fit_paths, sort_paths, FitOptions};
use crawltrace::stages::geometry::Polyline;
use crawltrace::stages::strokes::{
    default_spacing, extract_strokes, sample_strokes, simplification_tolerance, split_dots, Stroke,
};
use crawltrace::stages::thin::thin;
use crawltrace::{to_svg, CurvePath, Drawing, TraceOptions};
use divan::{black_box, Bencher};
use image::{DynamicImage, GrayImage};

/// The two inputs every benchmark runs on.
#[derive(Clone, Copy, Debug)]
enum Page {
    /// The 8-bit gray PNG page.
    Png,
    /// The scan-like colour JPEG of the same page.
    Jpeg,
}

impl fmt::Display for Page {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Page::Png => "png",
            Page::Jpeg => "jpeg",
        })
    }
}

const PAGES: [Page; 2] = [Page::Png, Page::Jpeg];

/// Every stage's input, computed once with the same calls and defaults as `trace()`, so that
/// each stage can be timed on its own.
struct Pipeline {
    bytes: Vec<u8>,
    image: DynamicImage,
    gray: GrayImage,
    binarized: Bitmap,
    stroke_width: f64,
    cleaned: Bitmap,
    skeleton: Bitmap,
    strokes: Vec<Stroke>,
    spacing: f64,
    sampled: Vec<Stroke>,
    curves: Vec<Polyline>,
    fit_options: FitOptions,
    drawing: Drawing,
}

impl Pipeline {
    fn new(bytes: Vec<u8>) -> Self {
        let image = decode_image(&bytes).expect("the page decodes");
        let gray = to_gray(&image);
        let binarized = binarize(&gray, &BinarizeOptions::default()).mask;
        let stroke_width = estimate_stroke_width(&binarized);
        let mut cleaned = binarized.clone();
        clean(&mut cleaned, stroke_width);
        let skeleton = thin(&cleaned);
        let (strokes, dots) = split_dots(
            extract_strokes(&skeleton, &cleaned, stroke_width),
            &cleaned,
            stroke_width,
        );
        let spacing = default_spacing(stroke_width);
        let sampled = sample_strokes(&strokes, spacing, simplification_tolerance(stroke_width));
        let mut curves = connect(&sampled, Method::Strokes, spacing, stroke_width);
        restore_tips(&mut curves, &cleaned, stroke_width);
        let fit_options = FitOptions {
            smooth: true,
            tolerance: default_tolerance(stroke_width),
            pen_width: stroke_width,
        };
        let traced = crawltrace::trace(&image, &TraceOptions::default()).expect("the page traces");
        let drawing = traced.drawing;
        // The stage benchmarks are only meaningful if they replay what trace() does.
        let mut paths = fit_paths(&curves, &fit_options);
        paths.extend(dots.iter().map(|d| CurvePath::dot(d.centre, d.diameter)));
        sort_paths(&mut paths);
        assert_eq!(
            paths, drawing.paths,
            "the stage-by-stage pipeline differs from trace()"
        );
        Self {
            bytes,
            image,
            gray,
            binarized,
            stroke_width,
            cleaned,
            skeleton,
            strokes,
            spacing,
            sampled,
            curves,
            fit_options,
            drawing,
        }
    }
}

static PNG_BYTES: LazyLock<(Vec<u8>, pages::PageSource)> = LazyLock::new(pages::page_png);
static PNG: LazyLock<Pipeline> = LazyLock::new(|| Pipeline::new(PNG_BYTES.0.clone()));
static JPEG: LazyLock<Pipeline> = LazyLock::new(|| {
    let gray = decode_image(&PNG_BYTES.0)
        .expect("the page decodes")
        .to_luma8();
    Pipeline::new(pages::scan_jpeg(&gray))
});

fn pipeline(page: Page) -> &'static Pipeline {
    match page {
        Page::Png => &PNG,
        Page::Jpeg => &JPEG,
    }
}

/// File bytes → SVG text, as `crawltrace trace` does between reading and writing the file.
fn trace_bytes(bytes: &[u8]) -> String {
    let image = decode_image(bytes).expect("the page decodes");
    let traced = crawltrace::trace(&image, &TraceOptions::default()).expect("the page traces");
    to_svg(&traced.drawing)
}

/// Traces `page` a few times and prints the median wall time of each stage and its share of
/// the total, from `TraceReport::timings` plus decode and SVG writing around it.
fn print_shares(page: Page) {
    const RUNS: usize = 7;
    let bytes = &pipeline(page).bytes;
    let mut runs: Vec<Vec<(&'static str, Duration)>> = Vec::new();
    for _ in 0..RUNS {
        let started = Instant::now();
        let image = decode_image(bytes).expect("the page decodes");
        let mut stages = vec![("decode", started.elapsed())];
        let traced = crawltrace::trace(&image, &TraceOptions::default()).expect("the page traces");
        stages.extend(traced.report.timings.iter().copied());
        let started = Instant::now();
        black_box(to_svg(&traced.drawing));
        stages.push(("svg", started.elapsed()));
        runs.push(stages);
    }
    let median = |i: usize| {
        let mut times: Vec<Duration> = runs.iter().map(|run| run[i].1).collect();
        times.sort();
        times[RUNS / 2]
    };
    let medians: Vec<(&str, Duration)> = (0..runs[0].len())
        .map(|i| (runs[0][i].0, median(i)))
        .collect();
    let total: Duration = medians.iter().map(|(_, time)| *time).sum();
    let p = pipeline(page);
    eprintln!(
        "\n{page} page, {} bytes: pen {} px, {} strokes, {} samples, {} curves",
        p.bytes.len(),
        p.stroke_width,
        p.strokes.len(),
        p.sampled.iter().map(|s| s.line.points.len()).sum::<usize>(),
        p.drawing.paths.len(),
    );
    eprintln!("| stage | median ms | share |\n|---|---:|---:|");
    for (stage, time) in &medians {
        eprintln!(
            "| {stage} | {:.1} | {:.0}% |",
            time.as_secs_f64() * 1e3,
            100.0 * time.as_secs_f64() / total.as_secs_f64()
        );
    }
    eprintln!("| **sum** | **{:.1}** | 100% |", total.as_secs_f64() * 1e3);
}

fn main() {
    match PNG_BYTES.1 {
        pages::PageSource::Sample => eprintln!("page: {}", pages::SAMPLE_PAGE),
        pages::PageSource::Generated => eprintln!(
            "page: generated stand-in ({} is missing)",
            pages::SAMPLE_PAGE
        ),
    }
    for page in PAGES {
        print_shares(page);
    }
    eprintln!();
    divan::main();
}

#[divan::bench(args = PAGES, sample_count = 10)]
fn end_to_end(bencher: Bencher, page: Page) {
    let bytes = &pipeline(page).bytes;
    bencher.bench(|| trace_bytes(black_box(bytes)));
}

#[divan::bench(args = PAGES, sample_count = 10)]
fn stage_1_decode(bencher: Bencher, page: Page) {
    let bytes = &pipeline(page).bytes;
    bencher.bench(|| decode_image(black_box(bytes)));
}

#[divan::bench(args = PAGES, sample_count = 10)]
fn stage_2_to_gray(bencher: Bencher, page: Page) {
    let image = &pipeline(page).image;
    bencher.bench(|| to_gray(black_box(image)));
}

#[divan::bench(args = PAGES, sample_count = 10)]
fn stage_3_binarize(bencher: Bencher, page: Page) {
    let gray = &pipeline(page).gray;
    bencher.bench(|| binarize(black_box(gray), &BinarizeOptions::default()));
}

#[divan::bench(args = PAGES, sample_count = 10)]
fn stage_4_stroke_width_and_clean(bencher: Bencher, page: Page) {
    let binarized = &pipeline(page).binarized;
    bencher
        .with_inputs(|| binarized.clone())
        .bench_local_refs(|mask| {
            let stroke_width = estimate_stroke_width(mask);
            clean(mask, stroke_width)
        });
}

#[divan::bench(args = PAGES, sample_count = 10)]
fn stage_5_thin(bencher: Bencher, page: Page) {
    let cleaned = &pipeline(page).cleaned;
    bencher.bench(|| thin(black_box(cleaned)));
}

#[divan::bench(args = PAGES, sample_count = 10)]
fn stage_6_strokes_and_sample(bencher: Bencher, page: Page) {
    let p = pipeline(page);
    let tolerance = simplification_tolerance(p.stroke_width);
    bencher.bench(|| {
        let (strokes, _dots) = split_dots(
            extract_strokes(black_box(&p.skeleton), &p.cleaned, p.stroke_width),
            &p.cleaned,
            p.stroke_width,
        );
        sample_strokes(&strokes, p.spacing, tolerance)
    });
}

#[divan::bench(args = PAGES, sample_count = 10)]
fn stage_7_reconstruct(bencher: Bencher, page: Page) {
    let p = pipeline(page);
    bencher.bench(|| {
        let mut curves = connect(
            black_box(&p.sampled),
            Method::Strokes,
            p.spacing,
            p.stroke_width,
        );
        restore_tips(&mut curves, &p.cleaned, p.stroke_width);
        curves
    });
}

#[divan::bench(args = PAGES, sample_count = 10)]
fn stage_8_fit(bencher: Bencher, page: Page) {
    let p = pipeline(page);
    bencher.bench(|| fit_paths(black_box(&p.curves), &p.fit_options));
}

#[divan::bench(args = PAGES, sample_count = 10)]
fn stage_9_svg(bencher: Bencher, page: Page) {
    let drawing = &pipeline(page).drawing;
    bencher.bench(|| to_svg(black_box(drawing)));
}

/// A 1500×1500 page of black and white pixels at random, half of each, as PNG bytes: the worst
/// page there is for every stage after binarizing (a web of ink everywhere, hundreds of thousands
/// of strokes and bridges). A stage whose work grows faster than the page shows here first: the
/// dot test once filled a page-wide web of ink once per short stroke, 280 s on a 4000×3000 page.
static NOISE_PNG: LazyLock<Vec<u8>> = LazyLock::new(|| {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let page = image::GrayImage::from_fn(1500, 1500, |_, _| {
        // xorshift64: any fixed sequence of fair bits will do.
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        image::Luma([if state & 1 == 0 { 0 } else { 255 }])
    });
    let mut bytes = Vec::new();
    DynamicImage::ImageLuma8(page)
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .expect("the noise page encodes");
    bytes
});

#[divan::bench(sample_count = 3)]
fn noise_page_end_to_end(bencher: Bencher) {
    let bytes = &*NOISE_PNG;
    bencher.bench(|| trace_bytes(black_box(bytes)));
}
