//! Where a batch's progress and messages go: a progress bar on stderr when it is a terminal, and
//! one line per failure, printed through the bar so that lines do not tear it.

use std::io::{self, IsTerminal};
use std::path::Path;

use indicatif::{ProgressBar, ProgressStyle};

use crate::files::{printable, printable_text};

/// `error: <path>: <message>`, on a single printable line whatever the name and the message hold
/// (line breaks in a message become spaces; control characters are escaped).
pub(super) fn failure_line(path: &Path, message: &str) -> String {
    let message: String = message
        .trim()
        .chars()
        .map(|c| if c == '\n' || c == '\r' { ' ' } else { c })
        .collect();
    format!("error: {}: {}", printable(path), printable_text(&message))
}

/// Where progress and messages go: through the bar while it is drawn, so lines do not tear it.
pub(super) struct Console {
    bar: Option<ProgressBar>,
}

impl Console {
    pub(super) fn new(total: usize, quiet: bool) -> Self {
        if quiet || !io::stderr().is_terminal() {
            return Self { bar: None };
        }
        let bar = ProgressBar::new(total as u64);
        if let Ok(style) = ProgressStyle::with_template(
            // `per_sec:1`: one decimal (the width field sets the precision for rates).
            "{wide_bar} {pos}/{len} files  {per_sec:1}  {elapsed} elapsed, ETA {eta}",
        ) {
            bar.set_style(style);
        }
        Self { bar: Some(bar) }
    }

    pub(super) fn line(&self, text: &str) {
        match &self.bar {
            Some(bar) => bar.println(text),
            None => eprintln!("{text}"),
        }
    }

    pub(super) fn advance(&self) {
        if let Some(bar) = &self.bar {
            bar.inc(1);
        }
    }

    pub(super) fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failure_lines_are_single_lines() {
        let line = failure_line(Path::new("in/a.png"), "first\nsecond\r\nthird\n");
        assert_eq!(line, "error: in/a.png: first second  third");
        let line = failure_line(Path::new("in/a\nerror: b\x1b[2J.png"), "bad\x07");
        assert_eq!(line, "error: in/a\\nerror: b\\u{1b}[2J.png: bad\\u{7}");
    }
}
