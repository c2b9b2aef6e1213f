//! The command's file handling: whole-file writes, standard output, and the rule that an input
//! is never overwritten.

use std::fs;
use std::io::{self, Write};
use std::path::Path;

use crawltrace::files::{describe_io, write_atomically};
use image::{EncodableLayout, ImageBuffer, ImageFormat, PixelWithColorType};

use crate::exit::Failure;

/// Writes a whole file (temporary file, then rename) or says why not.
pub fn save(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    write_atomically(path, bytes).map_err(|e| Failure::new(path, describe_io(&e)))
}

/// Writes `bytes` to standard output.
pub fn write_stdout(bytes: &[u8]) -> Result<(), Failure> {
    io::stdout()
        .lock()
        .write_all(bytes)
        .map_err(|e| Failure::new("<stdout>", e))
}

/// Refuses an output that is one of the inputs (symbolic links resolved).
pub fn refuse_to_overwrite_input(output: &Path, inputs: &[&Path]) -> Result<(), Failure> {
    let Ok(output_real) = fs::canonicalize(output) else {
        return Ok(()); // does not exist yet
    };
    for input in inputs {
        if fs::canonicalize(input).is_ok_and(|input_real| input_real == output_real) {
            return Err(Failure::new(output, "refusing to overwrite the input"));
        }
    }
    Ok(())
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
