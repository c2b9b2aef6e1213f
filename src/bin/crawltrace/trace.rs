//! `crawltrace trace`: one image (a file, or standard input) to one SVG or DXF file, or folders
//! and several images with the batch engine.

use std::fs;
use std::io::{self, Read};
use std::path::{Path, PathBuf};
use std::time::Instant;

use crawltrace::batch::{self, trace_file_to_document, BatchOptions};
use crawltrace::files::{describe_io, printable, OutputPlan};
use crawltrace::stages::debug::{debug_images, PICTURE_NAMES};
use crawltrace::stages::decode::{identify_format, DecodeLimits, IDENTIFY_BYTES};
use crawltrace::{export, to_svg, trace_bytes, trace_file, ExportOptions, TraceOptions, Traced};

use crate::cli::TraceArgs;
use crate::exit::{Exit, Failure};
use crate::files::{claim_output, png_bytes, save, write_stdout};

/// How errors name standard input.
const STDIN_NAME: &str = "<stdin>";

pub fn run(args: TraceArgs) -> Result<Exit, Failure> {
    let options = args.trace_options();
    let export_options = args.export_options();
    let input = &args.inputs[0];
    if args.inputs.len() > 1 && args.inputs.iter().any(|input| is_stdin(input)) {
        return Err(Failure::new(
            "-",
            "standard input can only be traced alone, as the one input",
        ));
    }
    let batch_mode =
        args.inputs.len() > 1 || input.is_dir() || args.output.as_deref().is_some_and(Path::is_dir);
    if batch_mode {
        run_batch(&args, &options, &export_options)
    } else {
        run_one(&args, input, &options, &export_options)
    }
}

/// Whether an input names standard input.
fn is_stdin(input: &Path) -> bool {
    input.as_os_str() == "-"
}

/// Traces one image (a file, or standard input for `-`) into one SVG or DXF file (or standard
/// output). Every output (the document and the `--debug` pictures) is checked before the work
/// starts.
fn run_one(
    args: &TraceArgs,
    input: &Path,
    options: &TraceOptions,
    export_options: &ExportOptions,
) -> Result<Exit, Failure> {
    let started = Instant::now();
    let from_stdin = is_stdin(input);
    let input_name = if from_stdin {
        Path::new(STDIN_NAME)
    } else {
        input
    };
    let output = match &args.output {
        Some(path) if path.as_os_str() == "-" => None,
        Some(path) => Some(path.clone()),
        None if from_stdin => None,
        None => Some(input.with_extension(export_options.format.extension())),
    };
    let inputs: &[&Path] = if from_stdin { &[] } else { &[input] };
    let mut plan = OutputPlan::new(inputs.iter().copied());
    if let Some(path) = &output {
        claim_output(&mut plan, path)?;
    }
    if let Some(folder) = &args.debug {
        for name in PICTURE_NAMES {
            claim_output(&mut plan, &folder.join(name))?;
        }
    }
    let traced = if from_stdin {
        trace_bytes(read_stdin(options)?, options)
    } else {
        trace_file(input, options)
    }
    .map_err(|e| Failure::new(input_name, e))?;
    let text = export(&traced, export_options);
    match &output {
        Some(path) => save(path, text.as_bytes())?,
        None => write_stdout(text.as_bytes())?,
    }
    if let Some(folder) = &args.debug {
        // The output is written: a failure now is not "nothing ran". The pictures are in
        // pixels, whatever the output's format and size.
        write_debug_pictures(folder, &traced, &to_svg(&traced.drawing))
            .map_err(|failure| failure.with_exit(Exit::PartlyWritten))?;
    }
    if !args.quiet {
        let curves = &traced.drawing.paths;
        let closed = curves.iter().filter(|c| c.closed).count();
        eprintln!(
            "{}: {} curve(s), {} closed, pen {:.1} px, {:.2} s{}",
            printable(input_name),
            curves.len(),
            closed,
            traced.report.stroke_width,
            started.elapsed().as_secs_f64(),
            output
                .as_ref()
                .map(|o| format!(" → {}", printable(o)))
                .unwrap_or_default(),
        );
    }
    Ok(Exit::Success)
}

/// Writes the picture of every stage into `folder` (for `--debug`).
fn write_debug_pictures(folder: &Path, traced: &Traced, svg: &str) -> Result<(), Failure> {
    let Some(stages) = &traced.stages else {
        return Ok(());
    };
    fs::create_dir_all(folder).map_err(|e| Failure::new(folder, describe_io(&e)))?;
    for (name, picture) in debug_images(stages, svg) {
        let path = folder.join(name);
        save(&path, &png_bytes(&picture, &path)?)?;
    }
    Ok(())
}

/// Reads all of standard input: the bytes of one image file. Its first bytes must be an image's
/// (`cat /dev/zero |` stops there), and it is read up to the largest file an image within the
/// pixel limit can be.
fn read_stdin(options: &TraceOptions) -> Result<Vec<u8>, Failure> {
    let limit = DecodeLimits::with_max_pixels(options.max_pixels).max_file_bytes();
    let failure = |e: io::Error| Failure::new(STDIN_NAME, describe_io(&e));
    let mut reader = io::stdin().lock().take(limit.saturating_add(1));
    let mut bytes = Vec::new();
    (&mut reader)
        .take(IDENTIFY_BYTES as u64)
        .read_to_end(&mut bytes)
        .map_err(failure)?;
    identify_format(&bytes).map_err(|e| Failure::new(STDIN_NAME, e))?;
    reader.read_to_end(&mut bytes).map_err(failure)?;
    if bytes.len() as u64 > limit {
        return Err(Failure::new(
            STDIN_NAME,
            format!("more than {limit} bytes, larger than an image within the pixel limit can be (--max-pixels)"),
        ));
    }
    Ok(bytes)
}

/// Traces folders or several images into an output folder with the batch engine.
fn run_batch(
    args: &TraceArgs,
    options: &TraceOptions,
    export_options: &ExportOptions,
) -> Result<Exit, Failure> {
    if args.debug.is_some() {
        return Err(Failure::new("--debug", "works with one image at a time"));
    }
    let out_dir = batch_output_folder(args)?;
    let batch_options = BatchOptions {
        recursive: args.recursive,
        glob: args.glob.clone(),
        jobs: args.jobs,
        force: args.force,
        quiet: args.quiet,
        shard: args.shard,
        report: args.report.clone(),
        format: export_options.format,
    };
    let discovery =
        batch::discover_inputs(&args.inputs, &batch_options).map_err(Failure::general)?;
    let summary = batch::run_batch(&discovery, &out_dir, &batch_options, |path| {
        trace_file_to_document(path, options, export_options)
    })
    .map_err(Failure::general)?;
    if let Some(error) = &summary.report_error {
        // After the summary line: the outputs are written, only the report is missing.
        Failure::general(error).report();
    }
    Ok(Exit::of_batch(&summary))
}

/// The folder the SVGs of a batch go to: `-o`, or the one folder given.
fn batch_output_folder(args: &TraceArgs) -> Result<PathBuf, Failure> {
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
    Ok(out_dir)
}
