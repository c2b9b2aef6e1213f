//! The command's file handling: whole-file writes (after removing what an interrupted run left in
//! the folder), standard output, and the one check of every output ([`OutputPlan`]).

use std::io::{self, Write};
use std::path::Path;

use crawltrace::files::{
    describe_io, parent_folder, remove_stale_temporary_files, write_atomically, OutputPlan,
};
use image::{EncodableLayout, ImageBuffer, ImageFormat, PixelWithColorType};

use crate::exit::Failure;

/// Writes a whole file (temporary file, then rename) or says why not. Temporary files that an
/// interrupted run left in the folder go first.
pub fn save(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    // Not being able to clean up is no reason not to write: the write reports its own errors.
    let _ = remove_stale_temporary_files(parent_folder(path));
    write_atomically(path, bytes).map_err(|e| Failure::new(path, describe_io(&e)))
}

/// Writes `bytes` to standard output.
pub fn write_stdout(bytes: &[u8]) -> Result<(), Failure> {
    io::stdout()
        .lock()
        .write_all(bytes)
        .map_err(|e| Failure::new("<stdout>", e))
}

/// Counts `output` as an output of the run, or refuses it: an input, another output of the same
/// run, or something other than a regular file.
pub fn claim_output(plan: &mut OutputPlan, output: &Path) -> Result<(), Failure> {
    plan.claim(output)
        .map_err(|refusal| Failure::new(output, refusal))
}

/// Whether `path` ends in `.extension`, in any letter case.
pub fn has_extension(path: &Path, extension: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(extension))
}

/// Encodes a picture as PNG bytes; a failure is about `about`, the file it was meant for.
pub fn png_bytes<P>(
    picture: &ImageBuffer<P, Vec<P::Subpixel>>,
    about: &Path,
) -> Result<Vec<u8>, Failure>
where
    P: PixelWithColorType,
    [P::Subpixel]: EncodableLayout,
{
    let mut png = Vec::new();
    picture
        .write_to(&mut io::Cursor::new(&mut png), ImageFormat::Png)
        .map_err(|e| Failure::new(about, e))?;
    Ok(png)
}
