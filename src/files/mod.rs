//! File handling shared by the library and the command: short texts for I/O errors, names that
//! print on one line, reading only regular files within a size limit ([`read`]), writing whole
//! files and cleaning up after interrupted writes ([`write`](mod@write)), and the one check every
//! output goes through before anything is written ([`outputs`]).

pub mod outputs;
pub mod read;
pub mod write;

use std::fmt::Write as _;
use std::io;
use std::path::Path;

pub use outputs::{OutputPlan, OutputRefusal};
pub use read::{open_regular_file, read_regular_file, ReadError};
pub use write::{remove_stale_temporary_files, write_atomically};

/// A short description of an I/O error, without Rust's `(os error N)` suffix.
pub fn describe_io(error: &io::Error) -> String {
    match error.kind() {
        io::ErrorKind::NotFound => "no such file".to_string(),
        io::ErrorKind::PermissionDenied => "permission denied".to_string(),
        io::ErrorKind::IsADirectory => "is a folder, not a file".to_string(),
        _ => {
            let text = error.to_string();
            match text.find(" (os error") {
                Some(cut) => text[..cut].to_string(),
                None => text,
            }
        }
    }
}

/// A path as one printable line: control characters (newlines, tabs, escape sequences), the
/// invisible characters that reorder text (bidirectional overrides) and line separators are
/// written as `\n`, `\t` or `\u{…}`, and bytes that are not UTF-8 as `\x..`, so that a file name
/// can neither split an error line nor colour or rewrite a terminal.
pub fn printable(path: &Path) -> String {
    printable_bytes_of(path)
}

/// [`printable`] for text: a message that may quote a file name or a decoder's detail.
pub fn printable_text(text: &str) -> String {
    let mut line = String::with_capacity(text.len());
    for c in text.chars() {
        push_printable(&mut line, c);
    }
    line
}

fn push_printable(line: &mut String, c: char) {
    match c {
        '\n' => line.push_str("\\n"),
        '\r' => line.push_str("\\r"),
        '\t' => line.push_str("\\t"),
        c if c.is_control() || is_invisible_format(c) => {
            let _ = write!(line, "\\u{{{:x}}}", u32::from(c));
        }
        c => line.push(c),
    }
}

/// Characters that are not controls but change how a terminal shows the line: bidirectional
/// marks, embeddings, overrides and isolates, and the line and paragraph separators.
fn is_invisible_format(c: char) -> bool {
    matches!(
        c,
        '\u{200E}' | '\u{200F}' | '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}' | '\u{2028}' | '\u{2029}'
    )
}

#[cfg(unix)]
fn printable_bytes_of(path: &Path) -> String {
    use std::os::unix::ffi::OsStrExt;
    let mut line = String::new();
    for chunk in path.as_os_str().as_bytes().utf8_chunks() {
        line.push_str(&printable_text(chunk.valid()));
        for byte in chunk.invalid() {
            let _ = write!(line, "\\x{byte:02x}");
        }
    }
    line
}

#[cfg(not(unix))]
fn printable_bytes_of(path: &Path) -> String {
    printable_text(&path.to_string_lossy())
}

/// The folder a file path lives in; `.` for a bare file name.
pub fn parent_folder(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_print_on_one_line_without_terminal_controls() {
        assert_eq!(printable(Path::new("scans/a b.png")), "scans/a b.png");
        assert_eq!(
            printable(Path::new("a\nerror: fake.png")),
            "a\\nerror: fake.png"
        );
        assert_eq!(
            printable(Path::new("\x1b[31mred\x1b[0m.png")),
            "\\u{1b}[31mred\\u{1b}[0m.png"
        );
        assert_eq!(printable(Path::new("tab\there\r")), "tab\\there\\r");
        assert_eq!(printable(Path::new("gnp.\u{202E}exe")), "gnp.\\u{202e}exe");
        assert_eq!(printable_text("été ✓"), "été ✓");
    }

    #[cfg(unix)]
    #[test]
    fn bytes_that_are_not_utf8_are_shown_as_hex() {
        use std::ffi::OsStr;
        use std::os::unix::ffi::OsStrExt;
        let name = Path::new(OsStr::from_bytes(b"bad\xff\xfe.png"));
        assert_eq!(printable(name), "bad\\xff\\xfe.png");
    }
}
