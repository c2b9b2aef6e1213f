//! The `crawltrace` command: parses arguments, reads and writes files, reports; the work is done
//! by the library. One module per command ([`trace`], [`points`], [`render`], [`help_files`] for
//! completions and the manual page).
// The one exception is in `allocator`, where it is allowed and explained.
#![deny(unsafe_code)]

mod allocator;
mod cli;
mod exit;
mod files;
mod help_files;
mod points;
mod render;
mod sandbox;
mod trace;

use std::error::Error as _;
use std::process::ExitCode;

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::Parser;

use cli::{Cli, Command, ValueError};
use exit::Exit;

fn main() -> ExitCode {
    allocator::keep_freed_memory_for_reuse();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => return report_usage_error(error),
    };
    let result = match cli.command {
        Command::Trace(args) => trace::run(*args),
        Command::Points(args) => points::run(args),
        Command::Render(args) => render::run(args),
        Command::Completions(args) => help_files::completions(args),
        Command::Manpage(args) => help_files::manpage(args),
    };
    match result {
        Ok(exit) => exit,
        Err(failure) => failure.report(),
    }
    .into()
}

/// Prints a command-line error. A value refused by one of our own checks ([`cli::OptionCheck`]) is
/// one line, `error: --option: what`, like every other error of the command; everything else
/// (help, version, clap's own errors) is clap's.
fn report_usage_error(error: clap::Error) -> ExitCode {
    if error.kind() == ErrorKind::ValueValidation {
        let check = error
            .source()
            .and_then(|source| match source.downcast_ref::<ValueError>() {
                Some(ValueError::Check(check)) => Some(check),
                _ => None,
            });
        let option = match error.get(ContextKind::InvalidArg) {
            Some(ContextValue::String(option)) => option.split(' ').next(),
            _ => None,
        };
        if let (Some(check), Some(option)) = (check, option) {
            eprintln!("error: {option}: {check}");
            return Exit::Usage.into();
        }
    }
    error.exit()
}
