//! File helpers shared by the library and the command: a short text for an I/O error, and
//! writing a file whole (temporary file, flushed, renamed) so that no reader ever sees a part.

use std::fs;
use std::io::{self, Write};
use std::path::Path;

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

/// Writes `bytes` to `path` whole: into a temporary file in the same folder, flushed to disk,
/// then renamed over `path`. A reader, or a run interrupted at any point, sees the old file or
/// the new one, never a part; an interrupted run may leave a hidden `.crawltrace-*.tmp` file, never
/// a truncated file under the real name. The folder must exist.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut temporary = temporary_file_beside(path)?;
    temporary.write_all(bytes)?;
    // Without this a crash soon after the rename can leave an empty file under the real name,
    // which a resumed batch would then take for an up-to-date output.
    temporary.as_file().sync_all()?;
    temporary.persist(path).map_err(|error| error.error)?;
    Ok(())
}

/// A new temporary file in the folder of `path`, named so that nothing mistakes it for an output
/// or an input: hidden, ending in `.tmp`.
fn temporary_file_beside(path: &Path) -> io::Result<tempfile::NamedTempFile> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(".crawltrace-").suffix(".tmp");
    // tempfile creates files readable by the owner only; an output should get the usual
    // permissions, as from `File::create` (the umask still applies).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(parent_folder(path))
}

/// The folder a file path lives in; `.` for a bare file name.
pub(crate) fn parent_folder(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::batch::is_image_path;

    /// A run killed between creating the temporary file and renaming it leaves the temporary
    /// file behind (nothing gets to delete it); it must not look like an output or an input.
    #[test]
    fn an_interrupted_write_leaves_no_svg() {
        let folder = tempfile::tempdir().unwrap();
        let output = folder.path().join("drawing.svg");
        let mut temporary = temporary_file_beside(&output).unwrap();
        temporary.write_all(b"<svg xmlns=").unwrap(); // cut short
        let (_, left_behind) = temporary.keep().unwrap(); // as if killed before the rename

        assert!(!output.exists());
        let names: Vec<String> = fs::read_dir(folder.path())
            .unwrap()
            .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names.len(), 1, "{names:?}");
        assert!(!names[0].ends_with(".svg"), "{names:?}");
        assert!(!is_image_path(&left_behind), "{names:?}");

        // The next attempt writes the whole file under the real name.
        write_atomically(&output, b"<svg xmlns=\"http://www.w3.org/2000/svg\"/>").unwrap();
        assert_eq!(
            fs::read(&output).unwrap(),
            b"<svg xmlns=\"http://www.w3.org/2000/svg\"/>"
        );
    }

    #[test]
    fn write_atomically_replaces_a_file_whole() {
        let folder = tempfile::tempdir().unwrap();
        let output = folder.path().join("a.svg");
        fs::write(&output, "old and longer than the new content").unwrap();
        write_atomically(&output, b"new").unwrap();
        assert_eq!(fs::read(&output).unwrap(), b"new");
        assert_eq!(
            fs::read_dir(folder.path()).unwrap().count(),
            1,
            "a temporary file was left"
        );
    }

    #[cfg(unix)]
    #[test]
    fn write_atomically_gives_the_usual_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let folder = tempfile::tempdir().unwrap();
        let reference = folder.path().join("reference");
        fs::File::create(&reference).unwrap();
        let output = folder.path().join("a.svg");
        write_atomically(&output, b"<svg/>").unwrap();
        let mode = |path: &Path| fs::metadata(path).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&output), mode(&reference));
    }
}
