//! Writing outputs whole: into a temporary file beside the output, flushed, then renamed over it,
//! so that no reader and no interrupted run ever sees a part; and removing the temporary files
//! that a killed run left behind. While it is written, a temporary file is locked (an advisory
//! `flock` on Unix), which the kernel releases when its writer dies: an unlocked temporary file is
//! stale, a locked one belongs to a run still going (another shard writing into the same folder).

use std::fs;
use std::io::{self, Write};
use std::path::Path;

use super::parent_folder;

/// The names of this tool's temporary files: hidden, and ending in `.tmp`, so that nothing takes
/// them for an output or an input.
const TEMPORARY_PREFIX: &str = ".crawltrace-";
const TEMPORARY_SUFFIX: &str = ".tmp";

/// DECISION: a write whose temporary file was removed by another run's clean-up before it was
/// locked (a window of one system call) starts again with a new one, at most this many times.
const WRITE_ATTEMPTS: usize = 3;

/// Writes `bytes` to `path` whole: into a temporary file in the same folder, locked, flushed to
/// disk, then renamed over `path`. A reader, or a run interrupted at any point, sees the old file
/// or the new one, never a part; an interrupted run may leave a hidden `.crawltrace-*.tmp` file,
/// never a truncated file under the real name, and [`remove_stale_temporary_files`] removes it
/// later. The folder must exist.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut attempt = 1;
    loop {
        match write_once(path, bytes) {
            Err(error) if attempt < WRITE_ATTEMPTS && lost_to_a_clean_up(&error) => attempt += 1,
            result => return result,
        }
    }
}

/// Whether a write failed because another run's clean-up took its temporary file: it was locked
/// by the clean-up, or gone at the rename.
fn lost_to_a_clean_up(error: &io::Error) -> bool {
    matches!(
        error.kind(),
        io::ErrorKind::WouldBlock | io::ErrorKind::NotFound
    )
}

fn write_once(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let mut temporary = temporary_file_beside(path)?;
    lock(temporary.as_file())?;
    temporary.write_all(bytes)?;
    // Without this a crash soon after the rename can leave an empty file under the real name,
    // which a resumed batch would then take for an up-to-date output.
    temporary.as_file().sync_all()?;
    // The lock goes with the file handle, once the file has its real name.
    temporary.persist(path).map_err(|error| error.error)?;
    Ok(())
}

/// A new temporary file in the folder of `path`.
fn temporary_file_beside(path: &Path) -> io::Result<tempfile::NamedTempFile> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(TEMPORARY_PREFIX).suffix(TEMPORARY_SUFFIX);
    // tempfile creates files readable by the owner only; an output should get the usual
    // permissions, as from `File::create` (the umask still applies).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(parent_folder(path))
}

/// Takes the exclusive advisory lock of `file` without waiting (fails with `WouldBlock` if it is
/// held).
#[cfg(unix)]
fn lock(file: &fs::File) -> io::Result<()> {
    rustix::fs::flock(file, rustix::fs::FlockOperation::NonBlockingLockExclusive)
        .map_err(io::Error::from)
}

/// Elsewhere there is no lock, and [`remove_stale_temporary_files`] removes nothing.
#[cfg(not(unix))]
fn lock(_file: &fs::File) -> io::Result<()> {
    Ok(())
}

/// Removes this tool's stale temporary files from `folder` (not its subfolders): those named
/// `.crawltrace-*.tmp` whose writer is gone (their lock is free). Files of a run still writing are
/// left alone. Returns how many were removed; a folder that does not exist has none. Does nothing
/// where there are no locks (outside Unix).
pub fn remove_stale_temporary_files(folder: &Path) -> io::Result<usize> {
    let entries = match fs::read_dir(folder) {
        Ok(entries) => entries,
        Err(error) if error.kind() == io::ErrorKind::NotFound => return Ok(0),
        Err(error) => return Err(error),
    };
    let mut removed = 0;
    for entry in entries {
        let entry = entry?;
        let name = entry.file_name();
        let name = name.to_string_lossy();
        let ours = name.starts_with(TEMPORARY_PREFIX) && name.ends_with(TEMPORARY_SUFFIX);
        // `file_type` does not follow links: a link named like ours is left alone.
        if ours && entry.file_type()?.is_file() && remove_if_stale(&entry.path())? {
            removed += 1;
        }
    }
    Ok(removed)
}

#[cfg(unix)]
fn remove_if_stale(path: &Path) -> io::Result<bool> {
    use std::os::unix::fs::OpenOptionsExt;
    let file = match fs::OpenOptions::new()
        .read(true)
        .custom_flags((rustix::fs::OFlags::NOFOLLOW | rustix::fs::OFlags::NONBLOCK).bits() as i32)
        .open(path)
    {
        Ok(file) => file,
        // Renamed or removed by its writer meanwhile.
        Err(error) if error.kind() == io::ErrorKind::NotFound => return Ok(false),
        Err(error) => return Err(error),
    };
    match lock(&file) {
        Ok(()) => match fs::remove_file(path) {
            Ok(()) => Ok(true),
            Err(error) if error.kind() == io::ErrorKind::NotFound => Ok(false),
            Err(error) => Err(error),
        },
        Err(error) if error.kind() == io::ErrorKind::WouldBlock => Ok(false),
        Err(error) => Err(error),
    }
}

#[cfg(not(unix))]
fn remove_if_stale(_path: &Path) -> io::Result<bool> {
    Ok(false)
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

    /// A killed run's temporary file is removed by the next run; one still being written (its
    /// lock held) is not, nor is anything else in the folder.
    #[cfg(unix)]
    #[test]
    fn only_stale_temporary_files_are_removed() {
        let folder = tempfile::tempdir().unwrap();
        let output = folder.path().join("drawing.svg");
        let stale = temporary_file_beside(&output).unwrap();
        let (_, stale_path) = stale.keep().unwrap(); // its writer is gone: no lock
        let live = temporary_file_beside(&output).unwrap();
        lock(live.as_file()).unwrap(); // a writer still at work
        let others = ["drawing.svg", ".crawltrace-notes.txt", "crawltrace-1.tmp"];
        for name in others {
            fs::write(folder.path().join(name), b"keep").unwrap();
        }
        std::os::unix::fs::symlink(&output, folder.path().join(".crawltrace-link.tmp")).unwrap();

        assert_eq!(remove_stale_temporary_files(folder.path()).unwrap(), 1);
        assert!(!stale_path.exists());
        assert!(live.path().exists());
        for name in others {
            assert!(folder.path().join(name).exists(), "{name}");
        }
        assert!(fs::symlink_metadata(folder.path().join(".crawltrace-link.tmp")).is_ok());
        // The live writer finishes normally.
        live.persist(&output).unwrap();
        assert_eq!(remove_stale_temporary_files(folder.path()).unwrap(), 0);
        assert_eq!(
            remove_stale_temporary_files(&folder.path().join("missing")).unwrap(),
            0
        );
    }
}
