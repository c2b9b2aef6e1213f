//! Runs the `crawltrace` binary on images made in the test (skip-stroke drawings rendered from
//! dashed SVG strokes) in a temporary folder: formats, outputs, errors, determinism, `--debug`,
//! `render`.

use crate::support;

use std::path::{Path, PathBuf};

use image::{DynamicImage, GrayImage, ImageFormat, Luma};

use support::cli::{run, run_expecting, sketch};

fn write_image(folder: &Path, name: &str, image: DynamicImage, format: ImageFormat) -> PathBuf {
    let path = folder.join(name);
    image
        .save_with_format(&path, format)
        .expect("test image saves");
    path
}

/// The test sketch ([`sketch`], 240 × 200) as a PNG named `name` in `folder`.
fn write_sketch(folder: &Path, name: &str) -> PathBuf {
    write_image(folder, name, sketch(240, 200).into(), ImageFormat::Png)
}

fn path_count(svg: &str) -> (usize, usize) {
    let paths = svg.matches("<path ").count();
    let closed = svg
        .lines()
        .filter(|l| l.starts_with("<path") && l.contains('Z'))
        .count();
    (paths, closed)
}

#[test]
fn traces_a_png_beside_the_input_with_one_path_per_shape() {
    let folder = tempfile::tempdir().unwrap();
    write_sketch(folder.path(), "sketch.png");
    let args = ["trace", "sketch.png"];
    run_expecting(0, &args, folder.path(), b"");
    let svg =
        std::fs::read_to_string(folder.path().join("sketch.svg")).expect("sketch.svg written");
    assert!(svg.contains(r#"viewBox="0 0 240 200""#), "{svg}");
    assert_eq!(path_count(&svg), (2, 1), "{svg}");
    usvg::Tree::from_str(&svg, &usvg::Options::default()).expect("valid SVG");
}

#[test]
fn every_common_format_and_pixel_type_traces_the_same_shapes() {
    let folder = tempfile::tempdir().unwrap();
    let gray = sketch(240, 200);
    let rgb = DynamicImage::ImageLuma8(gray.clone()).to_rgb8();
    let sixteen_bit = DynamicImage::ImageLuma16(DynamicImage::ImageLuma8(gray.clone()).to_luma16());
    // Gray ink on a transparent background: alpha must be composited over white.
    let with_alpha = image::GrayAlphaImage::from_fn(240, 200, |x, y| {
        let ink = 255 - gray.get_pixel(x, y).0[0];
        image::LumaA([0, ink])
    });
    let cases: Vec<(&str, DynamicImage, ImageFormat)> = vec![
        ("a.png", rgb.clone().into(), ImageFormat::Png),
        ("b.jpg", rgb.clone().into(), ImageFormat::Jpeg),
        ("c.gif", rgb.clone().into(), ImageFormat::Gif),
        ("d.bmp", rgb.clone().into(), ImageFormat::Bmp),
        ("e.tiff", rgb.clone().into(), ImageFormat::Tiff),
        (
            "f.webp",
            DynamicImage::ImageRgb8(rgb.clone()).to_rgba8().into(),
            ImageFormat::WebP,
        ),
        ("g.pgm", gray.clone().into(), ImageFormat::Pnm),
        ("h16.png", sixteen_bit, ImageFormat::Png),
        ("i-alpha.png", with_alpha.into(), ImageFormat::Png),
    ];
    for (name, picture, format) in cases {
        write_image(folder.path(), name, picture, format);
        let args = ["trace", name, "-o", "-"];
        let output = run_expecting(0, &args, folder.path(), b"");
        let svg = String::from_utf8(output.stdout).unwrap();
        assert_eq!(path_count(&svg), (2, 1), "{name}:\n{svg}");
    }
}

#[test]
fn output_is_byte_identical_across_runs() {
    let folder = tempfile::tempdir().unwrap();
    write_sketch(folder.path(), "s.png");
    let first = run(&["trace", "s.png", "-o", "-"], folder.path()).stdout;
    let second = run(&["trace", "s.png", "-o", "-"], folder.path()).stdout;
    assert!(!first.is_empty());
    assert_eq!(first, second);
}

#[test]
fn bad_inputs_are_one_line_errors_with_exit_code_2() {
    let folder = tempfile::tempdir().unwrap();
    std::fs::write(
        folder.path().join("notes.png"),
        "this is text, not a picture",
    )
    .unwrap();
    let mut png = Vec::new();
    DynamicImage::ImageLuma8(sketch(240, 200))
        .write_to(&mut std::io::Cursor::new(&mut png), ImageFormat::Png)
        .unwrap();
    std::fs::write(folder.path().join("truncated.png"), &png[..png.len() / 2]).unwrap();
    std::fs::write(folder.path().join("empty.png"), b"").unwrap();
    write_image(
        folder.path(),
        "blank.png",
        GrayImage::from_pixel(100, 80, Luma([255])).into(),
        ImageFormat::Png,
    );
    for (name, expected) in [
        ("notes.png", "notes.png"),
        ("truncated.png", "truncated.png"),
        ("empty.png", "empty.png"),
        ("blank.png", "no drawing found"),
        ("missing.png", "no such file"),
    ] {
        let args = ["trace", name];
        let output = run_expecting(2, &args, folder.path(), b"");
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert_eq!(stderr.lines().count(), 1, "{}", stderr);
        assert!(stderr.starts_with(&format!("error: {name}: ")), "{stderr}");
        assert!(stderr.contains(expected), "{stderr}");
        let svg_path = folder.path().join(name).with_extension("svg");
        assert!(!svg_path.exists(), "no output for a failed input");
    }
}

#[test]
fn never_overwrites_the_input() {
    let folder = tempfile::tempdir().unwrap();
    let input = write_sketch(folder.path(), "s.png");
    let before = std::fs::read(&input).unwrap();
    let args = ["trace", "s.png", "-o", "s.png"];
    run_expecting(2, &args, folder.path(), b"");
    assert_eq!(std::fs::read(&input).unwrap(), before);
}

#[test]
fn light_ink_on_dark_paper_needs_invert() {
    let folder = tempfile::tempdir().unwrap();
    let mut negative = sketch(240, 200);
    image::imageops::invert(&mut negative);
    write_image(folder.path(), "neg.png", negative.into(), ImageFormat::Png);
    let args = ["trace", "neg.png", "--invert", "-o", "-"];
    let output = run_expecting(0, &args, folder.path(), b"");
    assert_eq!(
        path_count(&String::from_utf8(output.stdout).unwrap()),
        (2, 1)
    );
}

#[test]
fn options_change_the_output_as_documented() {
    let folder = tempfile::tempdir().unwrap();
    write_sketch(folder.path(), "s.png");
    let polyline = run(&["trace", "s.png", "--no-smooth", "-o", "-"], folder.path());
    let polyline = String::from_utf8(polyline.stdout).unwrap();
    assert!(
        polyline.contains(" L") && !polyline.contains(" C"),
        "{polyline}"
    );
    let smooth =
        String::from_utf8(run(&["trace", "s.png", "-o", "-"], folder.path()).stdout).unwrap();
    assert!(smooth.contains(" C"), "{smooth}");
    let styled = run(
        &[
            "trace",
            "s.png",
            "--stroke-width",
            "5",
            "--color",
            "#ff0000",
            "-o",
            "-",
        ],
        folder.path(),
    );
    let styled = String::from_utf8(styled.stdout).unwrap();
    assert!(
        styled.contains(r##"stroke="#ff0000" stroke-width="5""##),
        "{styled}"
    );
    let args = ["trace", "s.png", "--spacing", "-3"];
    run_expecting(2, &args, folder.path(), b"");
}

#[test]
fn debug_writes_a_picture_of_every_stage() {
    let folder = tempfile::tempdir().unwrap();
    write_sketch(folder.path(), "s.png");
    let args = ["trace", "s.png", "--debug", "stages", "-q"];
    run_expecting(0, &args, folder.path(), b"");
    for name in [
        "1-mask",
        "2-skeleton",
        "3-samples",
        "4-delaunay",
        "5-result",
    ] {
        let picture = image::open(folder.path().join("stages").join(format!("{name}.png")))
            .unwrap_or_else(|e| panic!("{name}.png: {e}"));
        assert_eq!((picture.width(), picture.height()), (240, 200));
    }
}

#[test]
fn render_rasterizes_the_traced_svg() {
    let folder = tempfile::tempdir().unwrap();
    write_sketch(folder.path(), "s.png");
    assert!(run(&["trace", "s.png"], folder.path()).status.success());
    let args = ["render", "s.svg", "-o", "s-preview.png", "--scale", "2"];
    run_expecting(0, &args, folder.path(), b"");
    let preview = image::open(folder.path().join("s-preview.png"))
        .unwrap()
        .to_luma8();
    assert_eq!(preview.dimensions(), (480, 400));
    let dark = preview.pixels().filter(|p| p.0[0] < 128).count();
    assert!(
        dark > 1000,
        "the preview shows the curves ({dark} dark pixels)"
    );
}

/// `--method` picks how samples are connected: the stroke-aware crawl (default, one path per
/// drawn shape), or one of the point-set crawls on all samples, `points` (robust) and `paper`;
/// every choice traces, and each point-set crawl differs from the default on a skip-stroke sketch.
#[test]
fn method_picks_the_crawl() {
    let folder = tempfile::tempdir().unwrap();
    write_sketch(folder.path(), "s.png");
    let trace = |method: &str| {
        let args = ["trace", "s.png", "--method", method, "-o", "-"];
        let output = run_expecting(0, &args, folder.path(), b"");
        String::from_utf8(output.stdout).unwrap()
    };
    let strokes = trace("strokes");
    assert_eq!(path_count(&strokes), (2, 1), "{strokes}");
    let default = String::from_utf8(run(&["trace", "s.png", "-o", "-"], folder.path()).stdout);
    assert_eq!(default.unwrap(), strokes);
    for method in ["points", "paper"] {
        let svg = trace(method);
        assert!(path_count(&svg).0 >= 1, "--method {method}: {svg}");
        assert_ne!(svg, strokes, "--method {method}");
    }
}
