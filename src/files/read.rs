//! Reading input files: only regular files, opened so that a named pipe cannot block the open,
//! and never more than a size limit, checked before reading.

use std::fs::{self, File, OpenOptions};
use std::io::{self, Read};
use std::path::Path;

use super::describe_io;

/// Why an input file was not read. Its text is one line for a user, without the file's name.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// Opening or reading failed.
    #[error("{}", describe_io(.0))]
    Io(#[from] io::Error),
    /// A folder, a named pipe, a device or a socket: reading one could block forever, never end
    /// (`/dev/zero`) or read what was not meant.
    #[error("not a regular file ({0})")]
    NotAFile(&'static str),
    /// Larger than the caller's limit.
    #[error("file too large: {size} bytes, more than the limit of {limit} bytes")]
    TooLarge {
        /// The file's size.
        size: u64,
        /// The limit.
        limit: u64,
    },
}

/// What kind of file `metadata` describes, in a few words, when it is not a regular file.
pub(crate) fn not_a_file_kind(metadata: &fs::Metadata) -> Option<&'static str> {
    let kind = metadata.file_type();
    if kind.is_file() {
        return None;
    }
    if kind.is_dir() {
        return Some("a folder");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return Some("a named pipe");
        }
        if kind.is_socket() {
            return Some("a socket");
        }
        if kind.is_char_device() || kind.is_block_device() {
            return Some("a device");
        }
    }
    Some("not a file")
}

/// Opens `path` for reading if it is a regular file (symbolic links followed) and gives its
/// size. On Unix the open does not block: a named pipe is opened and refused at once instead of
/// waiting for a writer.
pub fn open_regular_file(path: &Path) -> Result<(File, u64), ReadError> {
    let mut options = OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // Only the open is non-blocking: reading a regular file is unaffected.
        options.custom_flags(rustix::fs::OFlags::NONBLOCK.bits() as i32);
    }
    let file = options.open(path)?;
    // Checked on the opened file, so that it cannot be swapped between the check and the read.
    let metadata = file.metadata()?;
    if let Some(kind) = not_a_file_kind(&metadata) {
        return Err(ReadError::NotAFile(kind));
    }
    Ok((file, metadata.len()))
}

/// Reads a regular file of at most `limit` bytes whole. The size is checked before reading, and
/// reading stops past the limit should the file grow meanwhile.
pub fn read_regular_file(path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
    let (file, size) = open_regular_file(path)?;
    read_within(file, size, limit)
}

/// Reads an opened file of `size` bytes whole, refusing it if it has more than `limit`.
pub(crate) fn read_within(file: File, size: u64, limit: u64) -> Result<Vec<u8>, ReadError> {
    if size > limit {
        return Err(ReadError::TooLarge { size, limit });
    }
    let mut bytes = Vec::with_capacity(usize::try_from(size).unwrap_or(0));
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    let read = bytes.len() as u64;
    if read > limit {
        return Err(ReadError::TooLarge { size: read, limit });
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_regular_file_is_read_whole_within_its_limit() {
        let folder = tempfile::tempdir().unwrap();
        let path = folder.path().join("a.txt");
        fs::write(&path, b"0123456789").unwrap();
        assert_eq!(read_regular_file(&path, 10).unwrap(), b"0123456789");
        assert!(matches!(
            read_regular_file(&path, 9),
            Err(ReadError::TooLarge { size: 10, limit: 9 })
        ));
    }

    #[test]
    fn folders_and_missing_files_are_refused() {
        let folder = tempfile::tempdir().unwrap();
        let error = read_regular_file(folder.path(), 100).unwrap_err();
        // Some systems refuse to open a folder, others open it and the check refuses it.
        assert!(
            matches!(error, ReadError::NotAFile("a folder"))
                || error.to_string() == "is a folder, not a file",
            "{error}"
        );
        let missing = read_regular_file(&folder.path().join("missing"), 100).unwrap_err();
        assert_eq!(missing.to_string(), "no such file");
    }

    #[cfg(unix)]
    #[test]
    fn a_named_pipe_is_refused_without_blocking() {
        let folder = tempfile::tempdir().unwrap();
        let pipe = folder.path().join("pipe.png");
        rustix::fs::mkfifoat(
            rustix::fs::CWD,
            &pipe,
            rustix::fs::Mode::RUSR | rustix::fs::Mode::WUSR,
        )
        .unwrap();
        // Without a writer a blocking open would wait here forever.
        let error = read_regular_file(&pipe, 100).unwrap_err();
        assert!(
            matches!(error, ReadError::NotAFile("a named pipe")),
            "{error}"
        );
        assert_eq!(error.to_string(), "not a regular file (a named pipe)");
    }

    #[cfg(unix)]
    #[test]
    fn a_device_is_refused() {
        let error = read_regular_file(Path::new("/dev/zero"), 100).unwrap_err();
        assert!(matches!(error, ReadError::NotAFile("a device")), "{error}");
    }
}
