//! The batch engine: runs a per-file processor over the discovered inputs in parallel, writes
//! each result whole beside its mirror path in the output folder, skips what is up to date, and
//! never lets one failing file stop the others.

use std::collections::HashSet;
use std::fmt;
use std::fs;
use std::panic::{self, AssertUnwindSafe};
use std::path::{Component, Path, PathBuf};
use std::time::{Duration, Instant};

use rayon::prelude::*;

use super::console::{failure_line, Console};
use super::discover::{Discovery, Input};
use super::report::{BatchSummary, FileError, FileOutcome, FileStatus};
use super::{BatchError, BatchOptions, FileResult, ReportProblem};
use crate::files::{parent_folder, write_atomically};

/// Runs `process` over the inputs of `discovery` on `options.jobs` threads and writes each result
/// to `out_dir`, mirroring the relative paths (folders are created as needed).
///
/// Per file, in order: an output that would land on an input is refused; an output file at least
/// as new as its input is skipped unless `options.force`; otherwise `process` runs (a panic in it is
/// caught and counted as a failure) and its SVG is written with [`write_atomically`]. Failures are
/// printed as `error: <input>: <message>` as they happen and never stop the batch. A progress bar
/// is drawn on stderr when it is a terminal and not `options.quiet`; a summary line ends the run
/// unless quiet. The report, if asked for, is written at the end.
///
/// Errors (before any work): `jobs` of 0, an output folder that cannot be created, a report whose
/// folder does not exist (other than `out_dir`, which the run makes) or that would overwrite an
/// input; (after the work) a report that cannot
/// be written.
pub fn run_batch<F, E>(
    discovery: &Discovery,
    out_dir: &Path,
    options: &BatchOptions,
    process: F,
) -> Result<BatchSummary<E>, BatchError>
where
    F: Fn(&Path) -> Result<FileResult, E> + Sync,
    E: fmt::Display + Send,
{
    let started = Instant::now();
    if options.jobs == Some(0) {
        return Err(BatchError::NoJobs);
    }
    if let Some(report) = &options.report {
        check_report_path(report, out_dir, &discovery.protected)?;
    }
    fs::create_dir_all(out_dir).map_err(|source| BatchError::OutputFolder {
        path: out_dir.to_path_buf(),
        source,
    })?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.unwrap_or(0))
        .build()?;

    let console = Console::new(discovery.inputs.len(), options.quiet);
    if !options.quiet {
        for warning in &discovery.warnings {
            console.line(&format!("warning: {warning}"));
        }
    }
    // An indexed parallel iterator collects in input order, whatever order the files finish in.
    let outcomes: Vec<FileOutcome<E>> = pool.install(|| {
        discovery
            .inputs
            .par_iter()
            .map(|input| {
                let outcome = process_one(input, out_dir, options, discovery, &process);
                if let FileStatus::Failed { error, .. } = &outcome.status {
                    console.line(&failure_line(&outcome.source, &error.to_string()));
                }
                console.advance();
                outcome
            })
            .collect()
    });
    console.finish();

    let count = |wanted: fn(&FileStatus<E>) -> bool| {
        outcomes
            .iter()
            .filter(|outcome| wanted(&outcome.status))
            .count()
    };
    let mut summary = BatchSummary {
        done: count(|status| matches!(status, FileStatus::Done { .. })),
        skipped: count(|status| matches!(status, FileStatus::Skipped)),
        failed: count(|status| matches!(status, FileStatus::Failed { .. })),
        not_images: discovery.not_images,
        in_other_shards: discovery.in_other_shards,
        outcomes,
        elapsed: Duration::ZERO,
    };
    if let Some(report) = &options.report {
        write_atomically(report, summary.report_json_lines().as_bytes()).map_err(|error| {
            BatchError::Report {
                path: report.clone(),
                problem: ReportProblem::Write(error),
            }
        })?;
    }
    summary.elapsed = started.elapsed();
    if !options.quiet {
        eprintln!("{summary}");
    }
    Ok(summary)
}

fn check_report_path(
    report: &Path,
    out_dir: &Path,
    protected: &HashSet<PathBuf>,
) -> Result<(), BatchError> {
    let refuse = |problem: ReportProblem| BatchError::Report {
        path: report.to_path_buf(),
        problem,
    };
    let folder = parent_folder(report);
    // The output folder is the natural place for the report, and the run creates it; a first
    // run must not refuse what every later run accepts.
    let in_out_dir = without_current_dir(folder).eq(without_current_dir(out_dir));
    if !folder.is_dir() && !in_out_dir {
        return Err(refuse(ReportProblem::NoFolder));
    }
    if lands_on_protected(report, protected) {
        return Err(refuse(ReportProblem::OverwritesInput));
    }
    Ok(())
}

/// The components of `path` without its `.`s, so that `./out` and `out` compare equal.
fn without_current_dir(path: &Path) -> impl Iterator<Item = Component<'_>> {
    path.components()
        .filter(|component| *component != Component::CurDir)
}

/// Whether writing `path` would replace one of the `protected` files, symbolic links resolved.
fn lands_on_protected(path: &Path, protected: &HashSet<PathBuf>) -> bool {
    let resolved = fs::canonicalize(path).ok().or_else(|| {
        // Not there yet: it can only land on an input through a linked folder.
        let folder = fs::canonicalize(parent_folder(path)).ok()?;
        Some(folder.join(path.file_name()?))
    });
    resolved.is_some_and(|resolved| protected.contains(&resolved))
}

fn process_one<F, E>(
    input: &Input,
    out_dir: &Path,
    options: &BatchOptions,
    discovery: &Discovery,
    process: &F,
) -> FileOutcome<E>
where
    F: Fn(&Path) -> Result<FileResult, E> + Sync,
{
    let (output, status) = match &input.unreadable {
        Some(unreadable) => (
            None,
            FileStatus::Failed {
                error: FileError::Unreadable(unreadable.clone()),
                seconds: None,
            },
        ),
        None => {
            let output = out_dir.join(input.output_relative(options.format));
            let status = trace_one(input, &output, options.force, discovery, process);
            (Some(output), status)
        }
    };
    FileOutcome {
        source: input.source.clone(),
        relative: input.relative.clone(),
        output,
        status,
    }
}

fn trace_one<F, E>(
    input: &Input,
    output: &Path,
    force: bool,
    discovery: &Discovery,
    process: &F,
) -> FileStatus<E>
where
    F: Fn(&Path) -> Result<FileResult, E> + Sync,
{
    let failed = |error: FileError<E>, seconds: Option<f64>| FileStatus::Failed { error, seconds };
    // Checked before the up-to-date test: an output that *is* its input always looks up to date.
    if lands_on_protected(output, &discovery.protected) {
        let output = output.to_path_buf();
        return failed(FileError::OverwritesInput { output }, None);
    }
    let input_modified = match fs::metadata(&input.source).and_then(|m| m.modified()) {
        Ok(modified) => modified,
        Err(error) => return failed(FileError::Input(error), None),
    };
    if !force {
        // Only a file is an output: a folder (or anything else) in its place is not up to date,
        // and writing there then fails with a message instead of the file being skipped quietly.
        let output_modified = fs::metadata(output)
            .ok()
            .filter(|metadata| metadata.is_file())
            .and_then(|metadata| metadata.modified().ok());
        if output_modified.is_some_and(|modified| modified >= input_modified) {
            return FileStatus::Skipped;
        }
    }

    let started = Instant::now();
    let seconds = || started.elapsed().as_secs_f64();
    // A bug in the processor on one odd file must not take the other thousands down with it.
    let result = match panic::catch_unwind(AssertUnwindSafe(|| process(&input.source))) {
        Ok(Ok(result)) => result,
        Ok(Err(error)) => return failed(FileError::Process(error), Some(seconds())),
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|text| text.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown cause".to_string());
            return failed(FileError::Panic(what), Some(seconds()));
        }
    };
    let folder = parent_folder(output);
    if let Err(source) = fs::create_dir_all(folder) {
        let folder = folder.to_path_buf();
        return failed(FileError::CreateFolder { folder, source }, Some(seconds()));
    }
    if let Err(source) = write_atomically(output, &result.bytes) {
        let output = output.to_path_buf();
        return failed(FileError::Write { output, source }, Some(seconds()));
    }
    FileStatus::Done {
        curves: result.curves,
        closed_curves: result.closed_curves,
        seconds: seconds(),
    }
}
