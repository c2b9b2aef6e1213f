//! How the command ends: its exit status, and the failure that stops it, printed as one line.

use std::path::Path;
use std::process::ExitCode;

use crawltrace::batch::BatchSummary;
use crawltrace::files::{printable, printable_text};

/// The exit status of the command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// Everything asked for was done (or was up to date).
    Success = 0,
    /// Some inputs of a batch failed; the others were written.
    SomeFailed = 1,
    /// Nothing ran: bad usage, or an input that cannot be read.
    Usage = 2,
    /// The outputs were written, but the batch report or the `--debug` pictures could not be.
    PartlyWritten = 3,
}

impl Exit {
    /// The status of a finished batch: a report that could not be written outranks failed
    /// files (the report is what lists them).
    pub fn of_batch<E>(summary: &BatchSummary<E>) -> Self {
        if summary.report_error.is_some() {
            Self::PartlyWritten
        } else if summary.failed > 0 {
            Self::SomeFailed
        } else {
            Self::Success
        }
    }
}

impl From<Exit> for ExitCode {
    fn from(exit: Exit) -> Self {
        ExitCode::from(exit as u8)
    }
}

/// A failure that stops the command, reported as `error: <about>: <what>` (or `error: <what>`
/// when the message names its files itself), one printable line, with [`Exit::Usage`] (or the
/// status it was given).
#[derive(Debug)]
pub struct Failure {
    /// What the failure is about: a file, or an option such as `--debug`.
    about: Option<String>,
    /// What went wrong, one line.
    message: String,
    /// The exit status.
    exit: Exit,
}

impl Failure {
    /// A failure about one file (or option).
    pub fn new(about: impl AsRef<Path>, message: impl ToString) -> Self {
        Self {
            about: Some(printable(about.as_ref())),
            message: one_line(&message.to_string()),
            exit: Exit::Usage,
        }
    }

    /// A failure whose message names its files itself (already made printable).
    pub fn general(message: impl ToString) -> Self {
        Self {
            about: None,
            message: one_line(&message.to_string()),
            exit: Exit::Usage,
        }
    }

    /// The same failure, ending the command with `exit` instead.
    pub fn with_exit(self, exit: Exit) -> Self {
        Self { exit, ..self }
    }

    /// Prints the failure on stderr and gives the exit status.
    pub fn report(&self) -> Exit {
        match &self.about {
            Some(about) => eprintln!("error: {about}: {}", self.message),
            None => eprintln!("error: {}", self.message),
        }
        self.exit
    }
}

/// A message on one printable line: line breaks become spaces, control characters are escaped.
fn one_line(message: &str) -> String {
    let joined: String = message
        .trim()
        .chars()
        .map(|c| if c == '\n' || c == '\r' { ' ' } else { c })
        .collect();
    printable_text(&joined)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_batch_exits_with_one_when_a_file_failed_and_three_without_its_report() {
        let mut summary: BatchSummary = BatchSummary {
            done: 3,
            skipped: 2,
            ..BatchSummary::default()
        };
        assert_eq!(Exit::of_batch(&summary), Exit::Success);
        summary.failed = 1;
        assert_eq!(Exit::of_batch(&summary), Exit::SomeFailed);
        // The outputs are written but the report is not: 3, never 2 ("nothing ran").
        summary.report_error = Some(crawltrace::batch::BatchError::NoJobs);
        assert_eq!(Exit::of_batch(&summary), Exit::PartlyWritten);
        assert_eq!(
            [
                Exit::Success,
                Exit::SomeFailed,
                Exit::Usage,
                Exit::PartlyWritten
            ]
            .map(|exit| exit as u8),
            [0, 1, 2, 3]
        );
    }

    #[test]
    fn failures_print_on_one_line() {
        let failure = Failure::new("a\nb.png", "first\nsecond\x1b[0m");
        assert_eq!(failure.about.as_deref(), Some("a\\nb.png"));
        assert_eq!(failure.message, "first second\\u{1b}[0m");
    }
}
