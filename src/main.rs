//! The `crawltrace` command: parses arguments, reads and writes files, reports; the work is done
//! by the library.
// The one exception is in `allocator`, where it is allowed and explained.
#![deny(unsafe_code)]

mod allocator;
mod cli;

use std::fs;
use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;
use cli::{Cli, Command, MethodArg, PointsArgs, PointsFormat, PointsMethod, RenderArgs, TraceArgs};
use crawltrace::batch::{self, describe_io, write_atomically, BatchOptions};
use crawltrace::binarize::{BinarizeOptions, ThresholdMethod};
use crawltrace::sketch::Method;
use crawltrace::trace::{trace_file, trace_file_to_svg, TraceOptions};
use crawltrace::{debug, pointfile, pointset, reconstruct, render, svg};

/// A failure to report as `error: <file>: <what>` with an exit code.
struct Failure {
    file: String,
    message: String,
}

impl Failure {
    fn new(file: impl AsRef<Path>, message: impl ToString) -> Self {
        Self {
            file: file.as_ref().display().to_string(),
            message: message.to_string(),
        }
    }
}

fn main() -> ExitCode {
    allocator::keep_freed_memory_for_reuse();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Trace(args) => run_trace(args),
        Command::Points(args) => run_points(args),
        Command::Render(args) => run_render(args),
    };
    match result {
        Ok(code) => code,
        Err(failure) if failure.file.is_empty() => {
            eprintln!("error: {}", failure.message);
            ExitCode::from(2)
        }
        Err(failure) => {
            eprintln!("error: {}: {}", failure.file, failure.message);
            ExitCode::from(2)
        }
    }
}

fn trace_options(args: &TraceArgs) -> TraceOptions {
    TraceOptions {
        binarize: BinarizeOptions {
            method: match (args.threshold, args.adaptive) {
                (Some(level), _) => ThresholdMethod::Fixed(level),
                (None, true) => ThresholdMethod::Adaptive,
                (None, false) => ThresholdMethod::Auto,
            },
            invert: args.invert,
        },
        spacing: args.spacing,
        smooth: !args.no_smooth,
        simplify: args.simplify,
        stroke_width: args.stroke_width,
        color: args.color.clone(),
        method: match args.method {
            MethodArg::Strokes => Method::Strokes,
            MethodArg::Points => Method::Points,
            MethodArg::Paper => Method::Paper,
        },
        keep_stages: args.debug.is_some(),
    }
}

/// Checks the numeric options a user can get wrong, before any work.
fn validate_trace_args(args: &TraceArgs) -> Result<(), Failure> {
    let positive = [
        ("--spacing", args.spacing),
        ("--stroke-width", args.stroke_width),
    ];
    for (name, value) in positive {
        if value.is_some_and(|v| !(v.is_finite() && v > 0.0)) {
            return Err(Failure::new(name, "must be a positive number"));
        }
    }
    if args.simplify.is_some_and(|v| !(v.is_finite() && v >= 0.0)) {
        return Err(Failure::new(
            "--simplify",
            "must be zero or a positive number",
        ));
    }
    if args.color.contains(['"', '<', '>', '&']) || args.color.trim().is_empty() {
        return Err(Failure::new(
            "--color",
            "must be an SVG colour such as black or #1a2b3c",
        ));
    }
    Ok(())
}

/// Writes a whole file (temporary file, then rename) or says why not.
fn save(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    write_atomically(path, bytes).map_err(|e| Failure::new(path, describe_io(&e)))
}

fn run_trace(args: TraceArgs) -> Result<ExitCode, Failure> {
    validate_trace_args(&args)?;
    let input = args.inputs[0].clone();
    let batch_mode =
        args.inputs.len() > 1 || input.is_dir() || args.output.as_deref().is_some_and(Path::is_dir);
    if batch_mode {
        return run_trace_batch(args);
    }
    let options = trace_options(&args);
    let started = std::time::Instant::now();
    let traced = trace_file(&input, &options).map_err(|e| Failure::new(&input, e))?;
    let text = svg::to_svg(&traced.drawing);
    let output = match &args.output {
        Some(path) if path.as_os_str() == "-" => None,
        Some(path) => Some(path.clone()),
        None => Some(input.with_extension("svg")),
    };
    match &output {
        Some(path) => {
            refuse_to_overwrite_input(path, &[&input])?;
            save(path, text.as_bytes())?;
        }
        None => io::stdout()
            .lock()
            .write_all(text.as_bytes())
            .map_err(|e| Failure::new("<stdout>", e))?,
    }
    if let (Some(folder), Some(stages)) = (&args.debug, &traced.stages) {
        fs::create_dir_all(folder).map_err(|e| Failure::new(folder, describe_io(&e)))?;
        for (name, picture) in debug::debug_images(stages, &text) {
            let path = folder.join(name);
            let mut png = Vec::new();
            picture
                .write_to(&mut io::Cursor::new(&mut png), image::ImageFormat::Png)
                .map_err(|e| Failure::new(&path, e))?;
            save(&path, &png)?;
        }
    }
    if !args.quiet {
        let curves = &traced.drawing.paths;
        let closed = curves.iter().filter(|c| c.closed).count();
        eprintln!(
            "{}: {} curve(s), {} closed, pen {:.1} px, {:.2} s{}",
            input.display(),
            curves.len(),
            closed,
            traced.report.stroke_width,
            started.elapsed().as_secs_f64(),
            output
                .as_ref()
                .map(|o| format!(" → {}", o.display()))
                .unwrap_or_default(),
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// Traces folders or several images into an output folder with the batch engine.
fn run_trace_batch(args: TraceArgs) -> Result<ExitCode, Failure> {
    if args.debug.is_some() {
        return Err(Failure::new("--debug", "works with one image at a time"));
    }
    let out_dir = match (&args.output, args.inputs.as_slice()) {
        (Some(out), _) if out.as_os_str() == "-" => {
            return Err(Failure::new(
                "-o -",
                "several images cannot go to standard output",
            ));
        }
        (Some(out), _) => out.clone(),
        // One folder and no -o: the SVGs go beside the images.
        (None, [folder]) if folder.is_dir() => folder.clone(),
        (None, _) => {
            return Err(Failure::new(
                &args.inputs[0],
                "tracing several images needs -o OUTDIR, the folder for the SVGs",
            ));
        }
    };
    if out_dir.exists() && !out_dir.is_dir() {
        return Err(Failure::new(
            &out_dir,
            "is a file; -o must name a folder when tracing several images",
        ));
    }
    let batch_options = BatchOptions {
        recursive: args.recursive,
        glob: args.glob.clone(),
        jobs: args.jobs,
        force: args.force,
        quiet: args.quiet,
        shard: args.shard,
        report: args.report.clone(),
    };
    let options = trace_options(&args);
    let fail = |e: batch::BatchError| Failure {
        file: String::new(),
        message: e.to_string(),
    };
    let discovery = batch::discover_inputs(&args.inputs, &batch_options).map_err(fail)?;
    let summary = batch::run_batch(&discovery, &out_dir, &batch_options, |path| {
        trace_file_to_svg(path, &options)
    })
    .map_err(fail)?;
    Ok(ExitCode::from(summary.exit_code()))
}

fn run_points(args: PointsArgs) -> Result<ExitCode, Failure> {
    let from_stdin = args.input.as_os_str() == "-";
    let input_name = if from_stdin {
        PathBuf::from("<stdin>")
    } else {
        args.input.clone()
    };
    let output = args.output.filter(|o| o.as_os_str() != "-");
    // Refuse before doing any work: a large input takes a while to reconstruct.
    if let Some(path) = &output {
        refuse_to_overwrite_input(path, &[&args.input])?;
    }
    let bytes = if from_stdin {
        let mut bytes = Vec::new();
        io::stdin()
            .read_to_end(&mut bytes)
            .map_err(|e| Failure::new(&input_name, e))?;
        bytes
    } else {
        fs::read(&args.input).map_err(|e| Failure::new(&input_name, describe_io(&e)))?
    };
    let file = pointfile::parse_points(&bytes).map_err(|e| Failure::new(&input_name, e))?;
    drop(bytes); // The text of a large file is no longer needed: keep the peak memory down.
    let reconstruction = match args.method {
        PointsMethod::Robust => crawltrace::robust_crawl::reconstruct(&file.points),
        PointsMethod::Paper => reconstruct(&file.points),
    };
    let reconstruction = reconstruction.map_err(|e| {
        let line = match e {
            reconstruct::ReconstructError::NotFinite { index }
            | reconstruct::ReconstructError::OutOfRange { index, .. } => file.lines[index],
        };
        Failure::new(&input_name, format!("line {line}: {e}"))
    })?;
    if !reconstruction.merged_duplicates.is_empty() {
        let first = reconstruction.merged_duplicates[0];
        eprintln!(
            "warning: {}: merged {} duplicate point(s) (line {} repeats line {})",
            input_name.display(),
            reconstruction.merged_duplicates.len(),
            file.lines[first.dropped],
            file.lines[first.kept],
        );
    }
    let format = args.format.unwrap_or(match &output {
        Some(path) if has_extension(path, "svg") => PointsFormat::Svg,
        _ => PointsFormat::Json,
    });
    let mut text = Vec::new();
    match format {
        PointsFormat::Json => pointset::write_json(&mut text, &file.points, &reconstruction)
            .map_err(|e| Failure::new(&input_name, e))?,
        PointsFormat::Svg => text.extend_from_slice(
            crawltrace::svg::to_svg(&pointset::to_drawing(
                &file.points,
                &reconstruction,
                args.show_points,
            ))
            .as_bytes(),
        ),
    }
    match output {
        // Checked against the input before reading it, above.
        Some(path) => save(&path, &text)?,
        None => io::stdout()
            .lock()
            .write_all(&text)
            .map_err(|e| Failure::new("<stdout>", e))?,
    }
    Ok(ExitCode::SUCCESS)
}

fn run_render(args: RenderArgs) -> Result<ExitCode, Failure> {
    let svg = fs::read(&args.input).map_err(|e| Failure::new(&args.input, describe_io(&e)))?;
    let svg = String::from_utf8(svg).map_err(|_| Failure::new(&args.input, "not UTF-8 text"))?;
    let image = render::render_svg(&svg, args.scale).map_err(|e| Failure::new(&args.input, e))?;
    refuse_to_overwrite_input(&args.output, &[&args.input])?;
    let mut png = Vec::new();
    image
        .write_to(&mut io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| Failure::new(&args.output, e))?;
    write_atomically(&args.output, &png)
        .map_err(|e| Failure::new(&args.output, describe_io(&e)))?;
    Ok(ExitCode::SUCCESS)
}

fn has_extension(path: &Path, extension: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(extension))
}

fn refuse_to_overwrite_input(output: &Path, inputs: &[&Path]) -> Result<(), Failure> {
    let Ok(output_real) = fs::canonicalize(output) else {
        return Ok(()); // does not exist yet
    };
    for input in inputs {
        if fs::canonicalize(input).is_ok_and(|input_real| input_real == output_real) {
            return Err(Failure::new(output, "refusing to overwrite the input"));
        }
    }
    Ok(())
}
