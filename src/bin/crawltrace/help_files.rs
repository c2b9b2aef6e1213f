//! `crawltrace completions SHELL` and `crawltrace manpage`: shell completion scripts
//! (clap_complete) and roff manual pages (clap_mangen), both generated from the clap definitions
//! in `cli.rs`, so they always match the options.

use std::fs;
use std::path::Path;

use clap::CommandFactory;
use clap_mangen::Man;
use crawltrace::files::{describe_io, OutputPlan};

use crate::cli::{Cli, CompletionsArgs, ManpageArgs};
use crate::exit::{Exit, Failure};
use crate::files::{claim_output, save, write_stdout};

/// The name the scripts complete and the pages describe.
const BINARY_NAME: &str = "crawltrace";

/// Prints the completion script for `args.shell`.
pub fn completions(args: CompletionsArgs) -> Result<Exit, Failure> {
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut Cli::command(), BINARY_NAME, &mut script);
    write_stdout(&script)?;
    Ok(Exit::Success)
}

/// Prints the main manual page, or writes it and one page per command into `args.dir`.
pub fn manpage(args: ManpageArgs) -> Result<Exit, Failure> {
    let mut command = Cli::command().disable_help_subcommand(true);
    // Building gives every command its display name (`crawltrace-trace`), which names its page.
    command.build();
    let Some(folder) = args.dir else {
        write_stdout(&render(&Man::new(command), Path::new("<stdout>"))?)?;
        return Ok(Exit::Success);
    };
    fs::create_dir_all(&folder).map_err(|e| Failure::new(&folder, describe_io(&e)))?;
    let subcommands: Vec<clap::Command> = command.get_subcommands().cloned().collect();
    let pages: Vec<Man> = std::iter::once(command)
        .chain(subcommands)
        .map(Man::new)
        .collect();
    // Every page is checked like any output before one is written (a FIFO or a device named
    // like a page is refused).
    let mut plan = OutputPlan::new([]);
    for page in &pages {
        claim_output(&mut plan, &folder.join(page.get_filename()))?;
    }
    for page in pages {
        let path = folder.join(page.get_filename());
        save(&path, &render(&page, &path)?)?;
    }
    Ok(Exit::Success)
}

/// The roff text of `page`; a failure is about `about`.
fn render(page: &Man, about: &Path) -> Result<Vec<u8>, Failure> {
    let mut text = Vec::new();
    page.render(&mut text)
        .map_err(|e| Failure::new(about, describe_io(&e)))?;
    Ok(text)
}
