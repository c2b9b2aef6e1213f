//! Golden round trip: every sample is traced, its SVG rasterized with resvg and compared with the
//! reference PNG in `tests/golden/`. See `tests/README.md`; `BLESS=1 cargo test --test it golden::`
//! rewrites the references. One test per sample (`golden::face_scan`, ...).

use crate::support;

use std::path::Path;

use crawltrace::stages::decode;
use crawltrace::{render_svg, to_svg, trace, TraceOptions};

/// A channel may differ by this much and still count as equal: anti-aliasing of the same path can
/// shift by a few levels between platforms' float rounding.
const PER_PIXEL_TOLERANCE: u8 = 48;
/// How many pixels may differ beyond the tolerance, per million pixels of the image: a curve that
/// moves by one pixel over a few pen widths stays under it, a missing or extra curve does not.
const ALLOWED_DIFFERING_PER_MILLION: usize = 2_000;

support::sample_tests!(traces_like_its_reference);

/// Traces `image`, rasterizes the SVG and compares it with its reference; with `BLESS=1`, writes
/// the reference instead.
fn traces_like_its_reference(image: &Path) {
    let bless = std::env::var_os("BLESS").is_some_and(|v| v != "0");
    let golden = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("golden");
    let stem = image.file_stem().unwrap().to_string_lossy().into_owned();
    let picture = decode::decode_image(&std::fs::read(image).unwrap()).unwrap();
    let traced = trace(&picture, &TraceOptions::default()).unwrap();
    let actual = render_svg(&to_svg(&traced.drawing), 1.0).unwrap();
    let reference = golden.join(format!("{stem}.png"));
    if bless {
        std::fs::create_dir_all(&golden).unwrap();
        actual.save(&reference).unwrap();
        return;
    }
    let expected = match image::open(&reference) {
        Ok(expected) => expected.to_rgba8(),
        Err(e) => panic!(
            "{stem}: no reference {} ({e}); run BLESS=1 cargo test --test it golden::",
            reference.display()
        ),
    };
    let allowed =
        actual.width() as usize * actual.height() as usize * ALLOWED_DIFFERING_PER_MILLION
            / 1_000_000;
    let comparison = support::compare_images(&expected, &actual, PER_PIXEL_TOLERANCE, allowed);
    if !comparison.passed() {
        let diff = support::write_diff(&stem, &expected, &actual);
        panic!(
            "{stem}: {comparison}; expected | difference | actual written to {}",
            diff.display()
        );
    }
}
