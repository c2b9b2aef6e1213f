//! `crawltrace trace`: one image to one SVG, or folders and several images with the batch engine.

use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crawltrace::batch::{self, trace_file_to_svg, BatchOptions};
use crawltrace::files::{describe_io, printable, OutputPlan};
use crawltrace::stages::debug::{debug_images, PICTURE_NAMES};
use crawltrace::{to_svg, trace_file, TraceOptions, Traced};

use crate::cli::TraceArgs;
use crate::exit::{Exit, Failure};
use crate::files::{claim_output, png_bytes, save, write_stdout};

pub fn run(args: TraceArgs) -> Result<Exit, Failure> {
    let options = args.trace_options();
    let input = &args.inputs[0];
    let batch_mode =
        args.inputs.len() > 1 || input.is_dir() || args.output.as_deref().is_some_and(Path::is_dir);
    if batch_mode {
        run_batch(&args, &options)
    } else {
        run_one(&args, input, &options)
    }
}

/// Traces one image into one SVG file (or standard output). Every output (the SVG and the
/// `--debug` pictures) is checked before the work starts.
fn run_one(args: &TraceArgs, input: &Path, options: &TraceOptions) -> Result<Exit, Failure> {
    let started = Instant::now();
    let output = match &args.output {
        Some(path) if path.as_os_str() == "-" => None,
        Some(path) => Some(path.clone()),
        None => Some(input.with_extension("svg")),
    };
    let mut plan = OutputPlan::new([input]);
    if let Some(path) = &output {
        claim_output(&mut plan, path)?;
    }
    if let Some(folder) = &args.debug {
        for name in PICTURE_NAMES {
            claim_output(&mut plan, &folder.join(name))?;
        }
    }
    let traced = trace_file(input, options).map_err(|e| Failure::new(input, e))?;
    let text = to_svg(&traced.drawing);
    match &output {
        Some(path) => save(path, text.as_bytes())?,
        None => write_stdout(text.as_bytes())?,
    }
    if let Some(folder) = &args.debug {
        // The SVG is written: a failure now is not "nothing ran".
        write_debug_pictures(folder, &traced, &text)
            .map_err(|failure| failure.with_exit(Exit::PartlyWritten))?;
    }
    if !args.quiet {
        let curves = &traced.drawing.paths;
        let closed = curves.iter().filter(|c| c.closed).count();
        eprintln!(
            "{}: {} curve(s), {} closed, pen {:.1} px, {:.2} s{}",
            printable(input),
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

/// Traces folders or several images into an output folder with the batch engine.
fn run_batch(args: &TraceArgs, options: &TraceOptions) -> Result<Exit, Failure> {
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
    };
    let discovery =
        batch::discover_inputs(&args.inputs, &batch_options).map_err(Failure::general)?;
    let summary = batch::run_batch(&discovery, &out_dir, &batch_options, |path| {
        trace_file_to_svg(path, options)
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
