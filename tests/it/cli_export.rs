//! Runs the `crawltrace` binary where its users work: images through a real pipe (`trace -`),
//! the physical size of the SVG read back with usvg (`--dpi`, `--size`, `--units`, the file's own
//! density), DXF output (one file, standard output, a batch), bad values of the new options, and
//! the completion scripts and manual pages. The DXF itself is read back with ezdxf in
//! `python/tests/test_dxf.py`.

use crate::hostile;
use crate::support;

use std::io::Cursor;
use std::process::{Command, Output};

use image::codecs::jpeg::{JpegEncoder, PixelDensity, PixelDensityUnit};
use image::{DynamicImage, GrayImage, ImageFormat};

use support::cli::{describe, run, run_expecting, run_with_stdin, sketch};

fn png_bytes(image: &GrayImage) -> Vec<u8> {
    let mut bytes = Vec::new();
    DynamicImage::ImageLuma8(image.clone())
        .write_to(&mut Cursor::new(&mut bytes), ImageFormat::Png)
        .unwrap();
    bytes
}

/// `png` with a valid `pHYs` chunk of `dpi` (rounded to whole pixels per metre) after `IHDR`.
fn png_with_dpi(png: &[u8], dpi: f64) -> Vec<u8> {
    let per_metre = (dpi / 0.0254).round() as u32;
    let mut body = b"pHYs".to_vec();
    body.extend_from_slice(&per_metre.to_be_bytes());
    body.extend_from_slice(&per_metre.to_be_bytes());
    body.push(1); // the metre
    let header_end = 8 + 4 + 4 + 13 + 4;
    let mut bytes = png[..header_end].to_vec();
    bytes.extend_from_slice(&9u32.to_be_bytes());
    bytes.extend_from_slice(&body);
    bytes.extend_from_slice(&hostile::crc32(&body).to_be_bytes());
    bytes.extend_from_slice(&png[header_end..]);
    bytes
}

/// A JPEG with a JFIF density of `dpi`.
fn jpeg_with_dpi(image: &GrayImage, dpi: u16) -> Vec<u8> {
    let mut bytes = Vec::new();
    let mut encoder = JpegEncoder::new_with_quality(&mut bytes, 95);
    encoder.set_pixel_density(PixelDensity {
        density: (dpi, dpi),
        unit: PixelDensityUnit::Inches,
    });
    encoder.encode_image(image).unwrap();
    bytes
}

/// The size usvg reads from an SVG, in CSS pixels (96 to the inch).
fn usvg_size(svg: &str) -> (f64, f64) {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default()).expect("usvg parses it");
    (
        f64::from(tree.size().width()),
        f64::from(tree.size().height()),
    )
}

fn assert_close(actual: (f64, f64), expected: (f64, f64), what: &str) {
    let near = |a: f64, b: f64| (a - b).abs() < 0.01;
    assert!(
        near(actual.0, expected.0) && near(actual.1, expected.1),
        "{what}: {actual:?}, expected {expected:?}"
    );
}

/// Runs a command that must be refused with exit code 2 and one line on stderr; the line.
fn refused(args: &[&str], folder: &std::path::Path, stdin: &[u8]) -> String {
    let output = run_expecting(2, args, folder, stdin);
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    stderr
}

fn stdout_text(output: &Output) -> String {
    String::from_utf8(output.stdout.clone()).expect("UTF-8 output")
}

#[test]
fn an_image_on_a_pipe_is_traced_to_standard_output() {
    let folder = tempfile::tempdir().unwrap();
    let png = png_bytes(&sketch(240, 200));
    std::fs::write(folder.path().join("sketch.png"), &png).unwrap();

    let args = ["trace", "-", "-o", "-"];
    let piped = run_with_stdin(&args, folder.path(), &png);
    assert!(piped.status.success(), "{}", describe(&args, &piped));
    let svg = stdout_text(&piped);
    assert_eq!(svg.matches("<path ").count(), 2, "{svg}");
    assert!(String::from_utf8_lossy(&piped.stderr).starts_with("<stdin>: 2 curve(s)"));
    // Without -o, standard input goes to standard output too; the bytes are those of the file.
    let implicit = run_with_stdin(&["trace", "-", "-q"], folder.path(), &png);
    let from_file = run(&["trace", "sketch.png", "-o", "-", "-q"], folder.path());
    assert_eq!(stdout_text(&implicit), svg);
    assert_eq!(stdout_text(&from_file), svg);
    assert!(implicit.stderr.is_empty());

    // Through a shell pipeline, into a file.
    let script = format!(
        "cat sketch.png | '{}' trace - -o piped.svg -q",
        support::cli::binary()
    );
    let status = Command::new("sh")
        .args(["-c", &script])
        .current_dir(folder.path())
        .status()
        .unwrap();
    assert!(status.success());
    assert_eq!(
        std::fs::read_to_string(folder.path().join("piped.svg")).unwrap(),
        svg
    );
}

#[test]
fn garbage_or_nothing_on_standard_input_is_a_one_line_error() {
    let folder = tempfile::tempdir().unwrap();
    for (stdin, problem) in [
        (&b"hello, not an image"[..], "not an image"),
        (&b""[..], "empty file"),
        (
            &b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR"[..],
            "corrupt or truncated",
        ),
    ] {
        let stderr = refused(&["trace", "-", "-o", "out.svg"], folder.path(), stdin);
        assert!(
            stderr.starts_with("error: <stdin>: ") && stderr.contains(problem),
            "{stderr}"
        );
        assert!(!folder.path().join("out.svg").exists());
    }
    std::fs::write(folder.path().join("a.png"), png_bytes(&sketch(240, 200))).unwrap();
    let stderr = refused(&["trace", "-", "a.png", "-o", "out"], folder.path(), b"");
    assert!(stderr.contains("standard input can only be traced alone"));
}

#[test]
fn the_svg_has_the_physical_size_asked_for_or_recorded_in_the_file() {
    let folder = tempfile::tempdir().unwrap();
    let image = sketch(300, 200);
    let png = png_bytes(&image);
    std::fs::write(folder.path().join("plain.png"), &png).unwrap();
    std::fs::write(folder.path().join("scan300.png"), png_with_dpi(&png, 300.0)).unwrap();
    std::fs::write(
        folder.path().join("scan200.jpg"),
        jpeg_with_dpi(&image, 200),
    )
    .unwrap();

    // (arguments, expected usvg size in CSS pixels, expected width attribute)
    let cases: [(&[&str], (f64, f64), &str); 7] = [
        (&["plain.png"], (300.0, 200.0), "79.375mm"),
        (&["scan300.png"], (96.0, 64.0), "25.4mm"),
        (&["scan200.jpg"], (144.0, 96.0), "38.1mm"),
        (&["scan300.png", "--dpi", "150"], (192.0, 128.0), "50.8mm"),
        (&["scan300.png", "--units", "in"], (96.0, 64.0), "1in"),
        (&["plain.png", "--size", "8in"], (768.0, 512.0), "8in"),
        (
            &["plain.png", "--size", "150mm", "--units", "in"],
            (566.93, 377.95),
            "5.9055in",
        ),
    ];
    for (extra, expected, width) in cases {
        let mut args = vec!["trace", "-q", "-o", "-"];
        args.extend_from_slice(extra);
        let output = run(&args, folder.path());
        assert!(output.status.success(), "{}", describe(&args, &output));
        let svg = stdout_text(&output);
        assert!(svg.contains(r#"viewBox="0 0 300 200""#), "{svg}");
        assert!(
            svg.contains(&format!(r#"width="{width}""#)),
            "{args:?}: {svg}"
        );
        assert_close(usvg_size(&svg), expected, &format!("{args:?}"));
    }

    // The --debug pictures stay in the image's pixels whatever the physical size.
    let args = [
        "trace",
        "scan300.png",
        "--size",
        "2in",
        "--debug",
        "stages",
        "-q",
    ];
    assert!(run(&args, folder.path()).status.success());
    let result = image::open(folder.path().join("stages").join("5-result.png")).unwrap();
    assert_eq!((result.width(), result.height()), (300, 200));
}

#[test]
fn bad_sizes_are_one_line_errors_before_any_work() {
    let folder = tempfile::tempdir().unwrap();
    std::fs::write(folder.path().join("a.png"), png_bytes(&sketch(240, 200))).unwrap();
    for (extra, message) in [
        (
            &["--dpi", "0"][..],
            "error: --dpi: must be a positive number",
        ),
        (
            &["--dpi", "-300"][..],
            "error: --dpi: must be a positive number",
        ),
        (
            &["--dpi", "inf"][..],
            "error: --dpi: must be a positive number",
        ),
        (
            &["--size", "banana"][..],
            "error: --size: must be a positive length with a unit",
        ),
        (
            &["--size", "210"][..],
            "error: --size: must be a positive length with a unit",
        ),
        (
            &["--size", "-2in"][..],
            "error: --size: must be a positive length with a unit",
        ),
    ] {
        let args = [&["trace", "a.png", "-o", "a.svg"][..], extra].concat();
        let stderr = refused(&args, folder.path(), b"");
        assert!(stderr.starts_with(message), "{args:?}: {stderr}");
        assert!(!folder.path().join("a.svg").exists());
    }
    // clap's own errors for values that are no option value at all, and conflicts.
    for extra in [
        &["--units", "cm"][..],
        &["--format", "pdf"][..],
        &["--dpi", "300", "--size", "8in"][..],
    ] {
        let args = [&["trace", "a.png", "-o", "a.svg"][..], extra].concat();
        run_expecting(2, &args, folder.path(), b"");
        assert!(!folder.path().join("a.svg").exists());
    }
}

/// The entity kinds in a DXF's ENTITIES section, and the closed flag (code 70) of each
/// LWPOLYLINE.
fn dxf_entities(dxf: &str) -> (Vec<String>, Vec<bool>) {
    let lines: Vec<&str> = dxf.lines().map(str::trim).collect();
    let pairs: Vec<(&str, &str)> = lines.chunks(2).map(|pair| (pair[0], pair[1])).collect();
    let start = pairs.iter().position(|p| *p == ("2", "ENTITIES")).unwrap();
    let end = start
        + pairs[start..]
            .iter()
            .position(|p| *p == ("0", "ENDSEC"))
            .unwrap();
    let section = &pairs[start + 1..end];
    let kinds = section
        .iter()
        .filter(|(code, _)| *code == "0")
        .map(|(_, kind)| kind.to_string())
        .collect();
    let closed = section
        .windows(3)
        .filter(|w| w[0] == ("100", "AcDbPolyline"))
        .map(|w| w[2] == ("70", "1"))
        .collect();
    (kinds, closed)
}

#[test]
fn dxf_output_has_one_polyline_per_curve() {
    let folder = tempfile::tempdir().unwrap();
    let png = png_bytes(&sketch(240, 200));
    std::fs::write(folder.path().join("a.png"), &png).unwrap();
    assert!(run(&["trace", "a.png", "-q"], folder.path())
        .status
        .success());
    let svg = std::fs::read_to_string(folder.path().join("a.svg")).unwrap();
    let svg_closed: Vec<bool> = svg
        .lines()
        .filter(|l| l.starts_with("<path"))
        .map(|l| l.contains('Z'))
        .collect();

    let args = ["trace", "a.png", "-o", "a.dxf", "-q"];
    let output = run(&args, folder.path());
    assert!(output.status.success(), "{}", describe(&args, &output));
    let dxf = std::fs::read_to_string(folder.path().join("a.dxf")).unwrap();
    let (kinds, closed) = dxf_entities(&dxf);
    assert_eq!(kinds, vec!["LWPOLYLINE"; svg_closed.len()]);
    assert_eq!(closed, svg_closed);
    assert!(dxf.contains("$INSUNITS\n 70\n4\n"));

    // --format wins over the extension; standard input and output work too.
    let args = ["trace", "-", "--format", "dxf", "--units", "in", "-q"];
    let piped = run_with_stdin(&args, folder.path(), &png);
    assert!(piped.status.success(), "{}", describe(&args, &piped));
    let piped = stdout_text(&piped);
    assert_eq!(dxf_entities(&piped), (kinds, closed));
    assert!(piped.contains("$INSUNITS\n 70\n1\n"));
}

#[test]
fn a_batch_writes_dxf_files_when_asked() {
    let folder = tempfile::tempdir().unwrap();
    let scans = folder.path().join("scans");
    std::fs::create_dir(&scans).unwrap();
    for name in ["one.png", "two.png"] {
        std::fs::write(scans.join(name), png_bytes(&sketch(240, 200))).unwrap();
    }
    let args = ["trace", "scans", "-o", "out", "--format", "dxf", "-q"];
    let output = run(&args, folder.path());
    assert!(output.status.success(), "{}", describe(&args, &output));
    let mut names: Vec<String> = std::fs::read_dir(folder.path().join("out"))
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["one.dxf", "two.dxf"]);
    let dxf = std::fs::read_to_string(folder.path().join("out").join("one.dxf")).unwrap();
    assert_eq!(dxf_entities(&dxf).0.len(), 2);
}

#[test]
fn bash_loads_the_completion_script() {
    let folder = tempfile::tempdir().unwrap();
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let output = run(&["completions", shell], folder.path());
        assert!(output.status.success(), "{shell}");
        let script = stdout_text(&output);
        assert!(
            script.contains("dpi") && script.contains("size"),
            "{shell}: {script}"
        );
    }
    let script = stdout_text(&run(&["completions", "bash"], folder.path()));
    std::fs::write(folder.path().join("crawltrace.bash"), script).unwrap();
    let loaded = Command::new("bash")
        .args(["-c", "source ./crawltrace.bash && complete -p crawltrace"])
        .current_dir(folder.path())
        .output()
        .expect("bash runs");
    assert!(
        loaded.status.success(),
        "{}",
        String::from_utf8_lossy(&loaded.stderr)
    );
    assert!(
        stdout_text(&loaded).contains("_crawltrace"),
        "{}",
        stdout_text(&loaded)
    );
}

#[test]
fn manual_pages_describe_every_command() {
    let folder = tempfile::tempdir().unwrap();
    let page = stdout_text(&run(&["manpage"], folder.path()));
    assert!(page.contains(".TH crawltrace 1"), "{page}");
    assert!(
        page.contains("crawltrace\\-trace(1)"),
        "the page lists the commands: {page}"
    );
    let output = run(&["manpage", "--dir", "man"], folder.path());
    assert!(
        output.status.success(),
        "{}",
        describe(&["manpage"], &output)
    );
    for name in [
        "crawltrace",
        "crawltrace-trace",
        "crawltrace-points",
        "crawltrace-render",
    ] {
        let page = std::fs::read_to_string(folder.path().join("man").join(format!("{name}.1")))
            .unwrap_or_else(|e| panic!("{name}.1: {e}"));
        assert!(page.contains(&format!(".TH {name} 1")), "{page}");
    }
    let trace_page =
        std::fs::read_to_string(folder.path().join("man").join("crawltrace-trace.1")).unwrap();
    assert!(trace_page.contains("\\-\\-dpi") && trace_page.contains("\\-\\-format"));
}
