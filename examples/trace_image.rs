//! Traces one image with the library, as `crawltrace trace` does: decode, trace with the default
//! options (nothing to tune), write the SVG, and say what was found.
//!
//! ```sh
//! cargo run --release --example trace_image -- samples/face-scan.jpg face.svg
//! ```
//!
//! Without arguments it traces `samples/face-scan.jpg` into `face-scan.svg` in the temporary
//! folder.

use std::path::PathBuf;
use std::process::ExitCode;

use crawltrace::{to_svg, trace_file, TraceOptions};

fn main() -> ExitCode {
    let mut args = std::env::args_os().skip(1).map(PathBuf::from);
    let input = args
        .next()
        .unwrap_or_else(|| PathBuf::from("samples/face-scan.jpg"));
    let output = args
        .next()
        .unwrap_or_else(|| std::env::temp_dir().join("face-scan.svg"));

    let traced = match trace_file(&input, &TraceOptions::default()) {
        Ok(traced) => traced,
        Err(error) => {
            eprintln!("error: {}: {error}", input.display());
            return ExitCode::FAILURE;
        }
    };
    if let Err(error) = std::fs::write(&output, to_svg(&traced.drawing)) {
        eprintln!("error: {}: {error}", output.display());
        return ExitCode::FAILURE;
    }

    let paths = &traced.drawing.paths;
    let closed = paths.iter().filter(|path| path.closed).count();
    let report = &traced.report;
    println!(
        "{}: {} curve(s), {closed} closed; pen {:.1} px, {} strokes, {} samples → {}",
        input.display(),
        paths.len(),
        report.stroke_width,
        report.strokes,
        report.samples,
        output.display()
    );
    for (stage, time) in &report.timings {
        println!("  {stage:<16} {:6.1} ms", time.as_secs_f64() * 1e3);
    }
    ExitCode::SUCCESS
}
