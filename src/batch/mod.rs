//! Batch tracing of image folders: finds the inputs, maps each to its output path, runs a per-file
//! processor over them in parallel, and reports (progress bar, error lines, summary, JSON Lines).
//!
//! The engine knows nothing about tracing: it takes any `Fn(&Path) -> Result<FileResult, E>`
//! and keeps each failure's error value, so the real tracer ([`trace_file_to_document`]) and the
//! test and benchmark fakes go through the same code.
//!
//! Rules it keeps (see `docs/design.md`, "Command line"):
//! - the output of `x/y.png` under a folder input is `OUT/x/y.svg` (or `.dxf`, as
//!   [`BatchOptions::format`] says); two inputs with the same output are an error before any work
//!   starts;
//! - an input is never overwritten, and outputs are written whole
//!   ([`crate::files::write_atomically`]);
//! - an output file at least as new as its input is up to date and skipped unless `force`;
//! - a failing file never stops the batch; it is reported and counted, and makes the exit status 1;
//! - [`Shard`]s split the inputs by a stable hash of their relative paths, so several machines can
//!   share one batch without talking to each other.

mod console;
mod discover;
mod engine;
mod report;
mod shard;

use std::io;
use std::path::{Path, PathBuf};

pub use discover::{
    discover_inputs, is_image_path, Discovery, Input, ScanWarning, Unreadable, IMAGE_EXTENSIONS,
};
pub use engine::run_batch;
pub use report::{BatchSummary, FileError, FileOutcome, FileStatus};
pub use shard::{fnv1a_64, Shard, ShardError};

use crate::export::{export, ExportOptions, OutputFormat};
use crate::files::{describe_io, printable, printable_text, OutputRefusal};
use crate::trace::{trace_file, TraceFileError, TraceOptions};

/// What the per-file processor returns for one image.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FileResult {
    /// The document to write (SVG or DXF).
    pub bytes: Vec<u8>,
    /// How many curves it holds.
    pub curves: usize,
    /// How many of them are closed.
    pub closed_curves: usize,
}

/// How a batch runs. `Default` is: top level of folders only, every image, all cores, resumable,
/// progress shown on a terminal, no shard, no report.
#[derive(Clone, Debug, Default)]
pub struct BatchOptions {
    /// Scan folders recursively instead of their top level only.
    pub recursive: bool,
    /// Take only the files of folder inputs that match this glob. A pattern without `/` is
    /// matched against the file name (`scan-*`), one with `/` against the path relative to the
    /// folder given (`**/*.png`, `2024/*.jpg`); `*` never crosses a `/`. Case-sensitive.
    pub glob: Option<String>,
    /// Worker threads; `None` is one per core (or `RAYON_NUM_THREADS`).
    pub jobs: Option<usize>,
    /// Redo files whose output is already up to date.
    pub force: bool,
    /// No progress bar, warnings or summary; failures are still printed.
    pub quiet: bool,
    /// Process only this shard of the inputs.
    pub shard: Option<Shard>,
    /// Write a JSON Lines report here at the end, one object per input.
    pub report: Option<PathBuf>,
    /// The format of the outputs, which gives their extension (`.svg`, `.dxf`).
    pub format: OutputFormat,
}

/// An error that stops a batch before (or, for the report, after) the per-file work. Its text is
/// `<file>: <what>`, to be printed as `error: <file>: <what>` with exit status 2.
#[derive(Debug, thiserror::Error)]
pub enum BatchError {
    /// An input named on the command line cannot be read.
    #[error("{}: {}", printable(path), describe_io(source))]
    Input {
        /// The input as given.
        path: PathBuf,
        /// What went wrong.
        source: io::Error,
    },
    /// The glob does not parse.
    #[error("--glob {}: {}", printable_text(&format!("{pattern:?}")), source.kind())]
    Glob {
        /// The pattern as given.
        pattern: String,
        /// What is wrong with it.
        source: globset::Error,
    },
    /// Two inputs would be written to the same output.
    #[error(
        "{}: both {} and {} would be written to this output",
        printable(output),
        printable(first),
        printable(second)
    )]
    OutputCollision {
        /// The shared output, relative to the output folder.
        output: PathBuf,
        /// The first input, in sorted order.
        first: PathBuf,
        /// The second input.
        second: PathBuf,
    },
    /// `jobs` is 0.
    #[error("--jobs: at least one worker thread is needed")]
    NoJobs,
    /// The worker threads could not be started.
    #[error("worker threads: {0}")]
    ThreadPool(#[from] rayon::ThreadPoolBuildError),
    /// The output folder cannot be created.
    #[error(
        "{}: cannot create the output folder: {}",
        printable(path),
        describe_folder_error(source)
    )]
    OutputFolder {
        /// The output folder.
        path: PathBuf,
        /// Why not.
        source: io::Error,
    },
    /// The report cannot be written.
    #[error("{}: cannot write the report: {problem}", printable(path))]
    Report {
        /// The report file.
        path: PathBuf,
        /// Why not.
        problem: ReportProblem,
    },
}

/// Why a batch's report cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum ReportProblem {
    /// The report's folder does not exist (and is not the output folder, which the run makes).
    #[error("its folder does not exist")]
    NoFolder,
    /// The report may not be written there: an input, another output of the run, or not a
    /// regular file.
    #[error(transparent)]
    Refused(OutputRefusal),
    /// Writing failed.
    #[error("{}", describe_io(.0))]
    Write(#[source] io::Error),
}

/// Why the output folder cannot be created, in a few words.
fn describe_folder_error(error: &io::Error) -> String {
    match error.kind() {
        io::ErrorKind::AlreadyExists => "a file is in the way".to_string(),
        _ => describe_io(error),
    }
}

/// Traces one image file into a document (SVG or DXF, as [`export()`] writes it): the per-file
/// work of `crawltrace trace` on a folder, for [`run_batch`]. Public so that benchmarks and other
/// front ends run exactly what the command runs.
///
/// # Errors
/// As [`trace_file`]: the file cannot be read, is not an image, or has no ink.
pub fn trace_file_to_document(
    path: &Path,
    options: &TraceOptions,
    export_options: &ExportOptions,
) -> Result<FileResult, TraceFileError> {
    let traced = trace_file(path, options)?;
    let paths = &traced.drawing.paths;
    Ok(FileResult {
        bytes: export(&traced, export_options).into_bytes(),
        curves: paths.len(),
        closed_curves: paths.iter().filter(|path| path.closed).count(),
    })
}
