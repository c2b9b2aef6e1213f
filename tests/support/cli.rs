//! Running the `crawltrace` binary in the command-line tests: with standard input on a real pipe,
//! checked for panics, described on failure; and the skip-stroke sketch they trace. The one
//! runner of the command-line tests (`cli_*`); `cli_hostile` adds resource limits around it.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};

use image::{DynamicImage, GrayImage};

/// The binary Cargo built for the integration tests (the examples that share this module have
/// none).
pub fn binary() -> &'static str {
    match option_env!("CARGO_BIN_EXE_crawltrace") {
        Some(path) => path,
        None => panic!("Cargo names the binary to integration tests only"),
    }
}

/// Runs the binary in `folder` with `stdin` on a pipe (empty for most commands); checks that it
/// did not panic.
pub fn run_with_stdin(args: &[&str], folder: &Path, stdin: &[u8]) -> Output {
    let mut child = Command::new(binary())
        .args(args)
        .current_dir(folder)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    let mut pipe = child.stdin.take().expect("stdin is piped");
    let bytes = stdin.to_vec();
    // Written from another thread: a large input could otherwise fill the pipe while the child
    // fills its output pipe. The binary may stop reading early (a usage error); a broken pipe is
    // then expected.
    let writer = std::thread::spawn(move || {
        let _ = pipe.write_all(&bytes);
    });
    let output = child.wait_with_output().expect("the binary runs");
    writer.join().expect("the stdin writer finishes");
    assert_no_panic(args, &output);
    output
}

/// Runs the binary in `folder` with nothing on standard input.
pub fn run(args: &[&str], folder: &Path) -> Output {
    run_with_stdin(args, folder, b"")
}

/// Runs the binary as [`run_with_stdin`] does and checks its exit code.
pub fn run_expecting(code: i32, args: &[&str], folder: &Path, stdin: &[u8]) -> Output {
    expect_code(code, args, run_with_stdin(args, folder, stdin))
}

/// Checks that `output` (of `crawltrace ARGS`) exited with `code`, showing the command and its
/// stderr otherwise.
pub fn expect_code(code: i32, args: &[&str], output: Output) -> Output {
    assert_eq!(
        output.status.code(),
        Some(code),
        "{}",
        describe(args, &output)
    );
    output
}

/// Checks that `crawltrace ARGS` did not panic (its stderr holds no panic message or backtrace
/// hint).
pub fn assert_no_panic(args: &[&str], output: &Output) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    for marker in ["panicked", "RUST_BACKTRACE", "stack backtrace"] {
        assert!(
            !stderr.contains(marker),
            "{marker:?}: a panic\n{}",
            describe(args, output)
        );
    }
}

/// The command, its exit code and its stderr, for failure messages.
pub fn describe(args: &[&str], output: &Output) -> String {
    format!(
        "crawltrace {}\nexit: {:?}\nstderr:\n{}",
        args.join(" "),
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    )
}

/// Standard error, one string a line.
pub fn stderr_lines(output: &Output) -> Vec<String> {
    String::from_utf8_lossy(&output.stderr)
        .lines()
        .map(str::to_string)
        .collect()
}

/// The shapes of [`sketch`]: a circle (closed) and a wave (open).
pub const CIRCLE_AND_WAVE: &str = r#"<circle cx="70" cy="70" r="45"/>
    <path d="M20 160 C60 130 100 190 140 160 S 200 130 220 160"/>"#;

/// A skip-stroke sketch of `width` × `height` pixels: a dashed circle (closed) and a dashed wave
/// (open), as a gray image.
pub fn sketch(width: u32, height: u32) -> GrayImage {
    dashed_sketch(width, height, CIRCLE_AND_WAVE)
}

/// A skip-stroke sketch of the SVG `shapes` on a white `width` × `height` page: strokes with
/// small gaps (a 3 px pen, 22 px dashes, 7 px gaps), rendered with resvg, as a gray image.
pub fn dashed_sketch(width: u32, height: u32, shapes: &str) -> GrayImage {
    let svg = format!(
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}">
        <rect width="100%" height="100%" fill="white"/>
        <g fill="none" stroke="black" stroke-width="3" stroke-linecap="round" stroke-dasharray="22 7">
        {shapes}</g></svg>"##
    );
    let rgba = crawltrace::render_svg(&svg, 1.0).expect("test SVG renders");
    DynamicImage::ImageRgba8(rgba).to_luma8()
}
