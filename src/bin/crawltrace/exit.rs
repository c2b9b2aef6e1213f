//! How the command ends: its exit status, and the failure that stops it, printed as one line.

use std::path::Path;
use std::process::ExitCode;

use crawltrace::batch::BatchSummary;

/// The exit status of the command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// Everything asked for was done (or was up to date).
    Success = 0,
    /// Some inputs of a batch failed; the others were written.
    SomeFailed = 1,
    /// Nothing ran: bad usage, or an input that cannot be read.
    Usage = 2,
}

impl Exit {
    /// The status of a finished batch.
    pub fn of_batch<E>(summary: &BatchSummary<E>) -> Self {
        if summary.failed > 0 {
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
/// when the message names its files itself) with [`Exit::Usage`].
#[derive(Debug)]
pub struct Failure {
    /// What the failure is about: a file, or an option such as `--debug`.
    about: Option<String>,
    /// What went wrong, one line.
    message: String,
}

impl Failure {
    /// A failure about one file (or option).
    pub fn new(about: impl AsRef<Path>, message: impl ToString) -> Self {
        Self {
            about: Some(about.as_ref().display().to_string()),
            message: message.to_string(),
        }
    }

    /// A failure whose message names its files itself.
    pub fn general(message: impl ToString) -> Self {
        Self {
            about: None,
            message: message.to_string(),
        }
    }

    /// Prints the failure on stderr and gives the exit status.
    pub fn report(&self) -> Exit {
        match &self.about {
            Some(about) => eprintln!("error: {about}: {}", self.message),
            None => eprintln!("error: {}", self.message),
        }
        Exit::Usage
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_batch_exits_with_one_only_when_a_file_failed() {
        let mut summary: BatchSummary = BatchSummary {
            done: 3,
            skipped: 2,
            ..BatchSummary::default()
        };
        assert_eq!(Exit::of_batch(&summary), Exit::Success);
        summary.failed = 1;
        assert_eq!(Exit::of_batch(&summary), Exit::SomeFailed);
        assert_eq!(
            [Exit::Success, Exit::SomeFailed, Exit::Usage].map(|exit| exit as u8),
            [0, 1, 2]
        );
    }
}
