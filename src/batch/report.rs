//! What a batch did: each input's outcome, the counts, the summary line and the JSON Lines report.

use std::fmt;
use std::io;
use std::path::PathBuf;
use std::time::Duration;

use super::discover::{Discovery, Unreadable};
use super::BatchError;
use crate::files::{describe_io, printable, OutputRefusal};
use crate::trace::TraceFileError;

/// What happened to one input. `E` is the per-file processor's error.
#[derive(Debug)]
pub enum FileStatus<E = TraceFileError> {
    /// Traced and written.
    Done {
        /// Curves in the output.
        curves: usize,
        /// Closed curves among them.
        closed_curves: usize,
        /// Time spent processing it, writing included.
        seconds: f64,
    },
    /// The output was already up to date.
    Skipped,
    /// Not done; the batch went on.
    Failed {
        /// Why.
        error: FileError<E>,
        /// Time spent processing it, when the processor ran.
        seconds: Option<f64>,
    },
}

/// Why one input of a batch failed. Its text is one line for a user, without the input's name.
#[derive(Debug, thiserror::Error)]
pub enum FileError<E = TraceFileError> {
    /// The folder scan could not read the entry.
    #[error(transparent)]
    Unreadable(#[from] Unreadable),
    /// The output may not be written: it is one of the batch's inputs, another output of the
    /// run, or something other than a regular file (see [`crate::files::OutputPlan`]).
    #[error("{refusal}: {}", printable(output))]
    OutputRefused {
        /// The output that was not written.
        output: PathBuf,
        /// Why not.
        refusal: OutputRefusal,
    },
    /// The input's modification time could not be read.
    #[error("{}", describe_io(.0))]
    Input(#[source] io::Error),
    /// The processor (the tracer) failed on the input.
    #[error("{0}")]
    Process(E),
    /// The processor panicked; the message is the panic's.
    #[error("internal error: {0}")]
    Panic(String),
    /// The output's folder could not be created.
    #[error(
        "cannot create the folder {}: {}",
        printable(folder),
        describe_io(source)
    )]
    CreateFolder {
        /// The folder.
        folder: PathBuf,
        /// Why not.
        source: io::Error,
    },
    /// The output could not be written.
    #[error("cannot write {}: {}", printable(output), describe_io(source))]
    Write {
        /// The output.
        output: PathBuf,
        /// Why not.
        source: io::Error,
    },
}

/// One input and what happened to it.
#[derive(Debug)]
pub struct FileOutcome<E = TraceFileError> {
    /// The input file.
    pub source: PathBuf,
    /// Its path relative to the folder given.
    pub relative: PathBuf,
    /// Its output, `None` for an entry the folder scan could not read.
    pub output: Option<PathBuf>,
    /// What happened.
    pub status: FileStatus<E>,
}

/// The result of [`super::run_batch`].
#[derive(Debug)]
pub struct BatchSummary<E = TraceFileError> {
    /// One outcome per input, in the order of [`super::Discovery::inputs`] (sorted by relative
    /// path).
    pub outcomes: Vec<FileOutcome<E>>,
    /// Inputs traced and written.
    pub done: usize,
    /// Inputs skipped because their output was up to date.
    pub skipped: usize,
    /// Inputs that failed.
    pub failed: usize,
    /// Files in the folders without an image extension.
    pub not_images: usize,
    /// Inputs left to other shards.
    pub in_other_shards: usize,
    /// Wall-clock time of the whole run.
    pub elapsed: Duration,
    /// Why the report could not be written, if it was asked for and could not be. The outputs
    /// were written by then, so this is not a failure to run (exit status 3 in the command).
    pub report_error: Option<BatchError>,
}

impl<E> Default for BatchSummary<E> {
    fn default() -> Self {
        Self {
            outcomes: Vec::new(),
            done: 0,
            skipped: 0,
            failed: 0,
            not_images: 0,
            in_other_shards: 0,
            elapsed: Duration::ZERO,
            report_error: None,
        }
    }
}

impl<E> BatchSummary<E> {
    /// The summary of `outcomes`, the inputs of `discovery` in order.
    pub(super) fn of(outcomes: Vec<FileOutcome<E>>, discovery: &Discovery) -> Self {
        let count = |wanted: fn(&FileStatus<E>) -> bool| {
            outcomes
                .iter()
                .filter(|outcome| wanted(&outcome.status))
                .count()
        };
        Self {
            done: count(|status| matches!(status, FileStatus::Done { .. })),
            skipped: count(|status| matches!(status, FileStatus::Skipped)),
            failed: count(|status| matches!(status, FileStatus::Failed { .. })),
            not_images: discovery.not_images,
            in_other_shards: discovery.in_other_shards,
            outcomes,
            ..Self::default()
        }
    }
}

impl<E: fmt::Display> BatchSummary<E> {
    /// The report: one JSON object a line per input, in input order, with the fields `path`,
    /// `output`, `status` (`done`, `skipped` or `failed`), `curves`, `closed_curves`, `seconds`
    /// and `error`; fields that do not apply are `null`.
    pub fn report_json_lines(&self) -> String {
        let mut text = String::new();
        for outcome in &self.outcomes {
            let (status, curves, closed_curves, seconds, error) = match &outcome.status {
                FileStatus::Done {
                    curves,
                    closed_curves,
                    seconds,
                } => (
                    "done",
                    Some(*curves),
                    Some(*closed_curves),
                    Some(*seconds),
                    None,
                ),
                FileStatus::Skipped => ("skipped", None, None, None, None),
                FileStatus::Failed { error, seconds } => {
                    ("failed", None, None, *seconds, Some(error.to_string()))
                }
            };
            let line = ReportLine {
                path: outcome.source.to_string_lossy(),
                output: outcome.output.as_ref().map(|path| path.to_string_lossy()),
                status,
                curves,
                closed_curves,
                seconds,
                error,
            };
            // Serialising strings, numbers and nulls cannot fail.
            if let Ok(json) = serde_json::to_string(&line) {
                text.push_str(&json);
                text.push('\n');
            }
        }
        text
    }
}

impl<E> fmt::Display for BatchSummary<E> {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            formatter,
            "{} done, {} skipped (up to date), {} failed",
            self.done, self.skipped, self.failed
        )?;
        if self.not_images > 0 {
            write!(formatter, ", {} not images", self.not_images)?;
        }
        if self.in_other_shards > 0 {
            write!(formatter, ", {} in other shards", self.in_other_shards)?;
        }
        write!(formatter, " ({:.1} s)", self.elapsed.as_secs_f64())
    }
}

#[derive(serde::Serialize)]
struct ReportLine<'a> {
    path: std::borrow::Cow<'a, str>,
    output: Option<std::borrow::Cow<'a, str>>,
    status: &'static str,
    curves: Option<usize>,
    closed_curves: Option<usize>,
    seconds: Option<f64>,
    error: Option<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failure_keeps_its_error_and_reports_its_text() {
        let summary: BatchSummary<String> = BatchSummary {
            outcomes: vec![FileOutcome {
                source: PathBuf::from("in/a.png"),
                relative: PathBuf::from("a.png"),
                output: Some(PathBuf::from("out/a.svg")),
                status: FileStatus::Failed {
                    error: FileError::Process("bad drawing".to_string()),
                    seconds: Some(0.5),
                },
            }],
            failed: 1,
            ..BatchSummary::default()
        };
        assert!(matches!(
            &summary.outcomes[0].status,
            FileStatus::Failed { error: FileError::Process(text), .. } if text == "bad drawing"
        ));
        assert_eq!(
            summary.report_json_lines(),
            "{\"path\":\"in/a.png\",\"output\":\"out/a.svg\",\"status\":\"failed\",\"curves\":null,\"closed_curves\":null,\"seconds\":0.5,\"error\":\"bad drawing\"}\n"
        );
    }

    #[test]
    fn summary_line_counts_everything() {
        let summary: BatchSummary = BatchSummary {
            done: 3,
            skipped: 2,
            failed: 1,
            not_images: 4,
            in_other_shards: 5,
            ..BatchSummary::default()
        };
        assert_eq!(
            summary.to_string(),
            "3 done, 2 skipped (up to date), 1 failed, 4 not images, 5 in other shards (0.0 s)"
        );
    }
}
