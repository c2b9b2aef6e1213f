//! The batch engine: runs a per-file processor over the discovered inputs in parallel, writes
//! each result whole beside its mirror path in the output folder, skips what is up to date, and
//! never lets one failing file stop the others.

use std::collections::BTreeSet;
use std::fmt;
use std::fs;
use std::panic::{self, AssertUnwindSafe};
use std::path::{Component, Path, PathBuf};
use std::time::Instant;

use rayon::prelude::*;

use super::console::{failure_line, Console};
use super::discover::{Discovery, Input};
use super::report::{BatchSummary, FileError, FileOutcome, FileStatus};
use super::{BatchError, BatchOptions, FileResult, ReportProblem};
use crate::files::{
    parent_folder, printable, remove_stale_temporary_files, write_atomically, OutputPlan,
    OutputRefusal,
};

/// Runs `process` over the inputs of `discovery` on `options.jobs` threads and writes each result
/// to `out_dir`, mirroring the relative paths (folders are created as needed).
///
/// Before any work every output goes through one [`OutputPlan`]: an output that would land on an
/// input, on another output of the run or on something other than a regular file fails its
/// input; a report that would is an error. Stale temporary files of an interrupted run are
/// removed from the folders the run writes to. Then, per file: an output file at least as new as
/// its input is skipped unless `options.force`; otherwise `process` runs (a panic in it is caught
/// and counted as a failure) and its SVG is written with [`write_atomically`]. Failures are printed
/// as `error: <input>: <message>` as they happen and never stop the batch. A progress bar is drawn
/// on stderr when it is a terminal and not `options.quiet`; a summary line ends the run unless
/// quiet. The report, if asked for, is written at the end; if that fails, the error is kept in
/// [`BatchSummary::report_error`] (the outputs are written by then).
///
/// Errors (before any work): `jobs` of 0, an output folder that cannot be created, a report whose
/// folder does not exist (other than `out_dir`, which the run makes) or that the plan refuses.
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
    let refusals = plan_outputs(discovery, out_dir, options)?;
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
    clean_up_interrupted_writes(discovery, out_dir, options, &console);
    // An indexed parallel iterator collects in input order, whatever order the files finish in.
    let outcomes: Vec<FileOutcome<E>> = pool.install(|| {
        discovery
            .inputs
            .par_iter()
            .zip(refusals.into_par_iter())
            .map(|(input, refusal)| {
                let outcome = process_one(input, out_dir, options, refusal, &process);
                if let FileStatus::Failed { error, .. } = &outcome.status {
                    console.line(&failure_line(&outcome.source, &error.to_string()));
                }
                console.advance();
                outcome
            })
            .collect()
    });
    console.finish();

    let mut summary = BatchSummary::of(outcomes, discovery);
    if let Some(report) = &options.report {
        if let Err(error) = write_atomically(report, summary.report_json_lines().as_bytes()) {
            summary.report_error = Some(BatchError::Report {
                path: report.to_path_buf(),
                problem: ReportProblem::Write(error),
            });
        }
    }
    summary.elapsed = started.elapsed();
    if !options.quiet {
        eprintln!("{summary}");
    }
    Ok(summary)
}

/// Checks every output of the run with one [`OutputPlan`] before any is written: this shard's
/// outputs (a refusal fails that input alone), the other shards' outputs (reserved, so that the
/// report cannot land on one) and the report (a refusal stops the run).
fn plan_outputs(
    discovery: &Discovery,
    out_dir: &Path,
    options: &BatchOptions,
) -> Result<Vec<Option<OutputRefusal>>, BatchError> {
    let report = options.report.as_deref();
    let mut plan = OutputPlan::with_resolved_inputs(discovery.protected.clone());
    let refusals = discovery
        .inputs
        .iter()
        .map(|input| match input.unreadable {
            Some(_) => None,
            None => plan
                .claim(&out_dir.join(input.output_relative(options.format)))
                .err(),
        })
        .collect();
    for relative in &discovery.other_shard_outputs {
        // Another shard checks its own outputs; here they only keep the report off them.
        let _ = plan.claim(&out_dir.join(relative));
    }
    if let Some(report) = report {
        let refuse = |problem: ReportProblem| BatchError::Report {
            path: report.to_path_buf(),
            problem,
        };
        let folder = parent_folder(report);
        // The output folder is the natural place for the report, and the run creates it; a
        // first run must not refuse what every later run accepts.
        let in_out_dir = without_current_dir(folder).eq(without_current_dir(out_dir));
        if !folder.is_dir() && !in_out_dir {
            return Err(refuse(ReportProblem::NoFolder));
        }
        plan.claim(report)
            .map_err(|refusal| refuse(ReportProblem::Refused(refusal)))?;
    }
    Ok(refusals)
}

/// Removes the temporary files an interrupted run left in the folders this run writes to (the
/// output folders of its inputs and the report's), so that a rerun leaves only whole outputs.
/// A folder that cannot be cleaned is reported as a warning; the run goes on.
fn clean_up_interrupted_writes(
    discovery: &Discovery,
    out_dir: &Path,
    options: &BatchOptions,
    console: &Console,
) {
    let report = options.report.as_deref();
    let mut folders: BTreeSet<PathBuf> = discovery
        .inputs
        .iter()
        .map(|input| out_dir.join(input.output_relative(options.format)))
        .map(|output| parent_folder(&output).to_path_buf())
        .collect();
    folders.extend(report.map(|report| parent_folder(report).to_path_buf()));
    for folder in folders {
        if let Err(error) = remove_stale_temporary_files(&folder) {
            console.line(&format!(
                "warning: {}: cannot remove temporary files left by an interrupted run: {}",
                printable(&folder),
                crate::files::describe_io(&error)
            ));
        }
    }
}

/// The components of `path` without its `.`s, so that `./out` and `out` compare equal.
fn without_current_dir(path: &Path) -> impl Iterator<Item = Component<'_>> {
    path.components()
        .filter(|component| *component != Component::CurDir)
}

fn process_one<F, E>(
    input: &Input,
    out_dir: &Path,
    options: &BatchOptions,
    refusal: Option<OutputRefusal>,
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
            let status = match refusal {
                Some(refusal) => FileStatus::Failed {
                    error: FileError::OutputRefused {
                        output: output.clone(),
                        refusal,
                    },
                    seconds: None,
                },
                None => trace_one(input, &output, options.force, process),
            };
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

fn trace_one<F, E>(input: &Input, output: &Path, force: bool, process: &F) -> FileStatus<E>
where
    F: Fn(&Path) -> Result<FileResult, E> + Sync,
{
    let failed = |error: FileError<E>, seconds: Option<f64>| FileStatus::Failed { error, seconds };
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
