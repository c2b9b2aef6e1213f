//! What a batch did: each input's outcome, the counts, the summary line and the JSON Lines report.

use std::fmt;
use std::path::PathBuf;
use std::time::Duration;

/// What happened to one input.
#[derive(Clone, Debug, PartialEq)]
pub enum FileStatus {
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
        /// Why, on one line.
        message: String,
        /// Time spent processing it, when the processor ran.
        seconds: Option<f64>,
    },
}

/// One input and what happened to it.
#[derive(Clone, Debug, PartialEq)]
pub struct FileOutcome {
    /// The input file.
    pub source: PathBuf,
    /// Its path relative to the folder given.
    pub relative: PathBuf,
    /// Its output, `None` for an entry the folder scan could not read.
    pub output: Option<PathBuf>,
    /// What happened.
    pub status: FileStatus,
}

/// The result of [`run_batch`].
#[derive(Clone, Debug, Default)]
pub struct BatchSummary {
    /// One outcome per input, in the order of [`Discovery::inputs`] (sorted by relative path).
    pub outcomes: Vec<FileOutcome>,
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
}

impl BatchSummary {
    /// The process exit status: 1 if any input failed, else 0.
    pub fn exit_code(&self) -> u8 {
        u8::from(self.failed > 0)
    }

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
                FileStatus::Failed { message, seconds } => {
                    ("failed", None, None, *seconds, Some(message.as_str()))
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

impl fmt::Display for BatchSummary {
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
    error: Option<&'a str>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exit_code_is_one_only_with_failures() {
        let mut summary = BatchSummary {
            done: 3,
            skipped: 2,
            ..BatchSummary::default()
        };
        assert_eq!(summary.exit_code(), 0);
        summary.failed = 1;
        assert_eq!(summary.exit_code(), 1);
    }

    #[test]
    fn summary_line_counts_everything() {
        let summary = BatchSummary {
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
