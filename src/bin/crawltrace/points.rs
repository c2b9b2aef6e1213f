//! `crawltrace points`: a point file reconstructed into curves, written as JSON or SVG.

use std::io::{self, Read};
use std::path::{Path, PathBuf};

use crawltrace::files::{read_regular_file, OutputPlan};
use crawltrace::stages::points::write::{to_drawing, write_json};
use crawltrace::{
    parse_points, reconstruct, reconstruct_robust, to_svg, PointFile, ReconstructError,
    Reconstruction,
};

use crate::cli::{PointsArgs, PointsFormat, PointsMethod};
use crate::exit::{Exit, Failure};
use crate::files::{claim_output, has_extension, save, write_stdout};

pub fn run(args: PointsArgs) -> Result<Exit, Failure> {
    let from_stdin = args.input.as_os_str() == "-";
    let input_name = if from_stdin {
        PathBuf::from("<stdin>")
    } else {
        args.input.clone()
    };
    let output = args.output.filter(|o| o.as_os_str() != "-");
    // Refuse before doing any work: a large input takes a while to reconstruct.
    if let Some(path) = &output {
        claim_output(&mut OutputPlan::new([args.input.as_path()]), path)?;
    }
    let file = read_point_file(&args.input, from_stdin, &input_name)?;
    let reconstruction = match args.method {
        PointsMethod::Robust => reconstruct_robust(&file.points),
        PointsMethod::Paper => reconstruct(&file.points),
    };
    let reconstruction = reconstruction.map_err(|e| {
        let line = match e {
            ReconstructError::NotFinite { index } | ReconstructError::OutOfRange { index, .. } => {
                file.lines[index]
            }
        };
        Failure::new(&input_name, format!("line {line}: {e}"))
    })?;
    warn_about_duplicates(&input_name, &file, &reconstruction);
    let format = args.format.unwrap_or(match &output {
        Some(path) if has_extension(path, "svg") => PointsFormat::Svg,
        _ => PointsFormat::Json,
    });
    let mut text = Vec::new();
    match format {
        PointsFormat::Json => write_json(&mut text, &file.points, &reconstruction)
            .map_err(|e| Failure::new(&input_name, e))?,
        PointsFormat::Svg => text.extend_from_slice(
            to_svg(&to_drawing(&file.points, &reconstruction, args.show_points)).as_bytes(),
        ),
    }
    match output {
        // Checked against the input before reading it, above.
        Some(path) => save(&path, &text),
        None => write_stdout(&text),
    }?;
    Ok(Exit::Success)
}

/// Reads and parses the point file (or standard input); errors name `input_name`.
fn read_point_file(
    input: &Path,
    from_stdin: bool,
    input_name: &Path,
) -> Result<PointFile, Failure> {
    let bytes = if from_stdin {
        let mut bytes = Vec::new();
        io::stdin()
            .read_to_end(&mut bytes)
            .map_err(|e| Failure::new(input_name, e))?;
        bytes
    } else {
        // Only a regular file: a named pipe or a device (`/dev/zero`) could block or never end;
        // pipes come through standard input (`-`).
        read_regular_file(input, u64::MAX).map_err(|e| Failure::new(input_name, e))?
    };
    // The text of a large file is dropped on return: only the points stay, keeping the peak
    // memory down.
    parse_points(&bytes).map_err(|e| Failure::new(input_name, e))
}

/// One warning line when exact duplicates were merged, naming the first pair.
fn warn_about_duplicates(input_name: &Path, file: &PointFile, reconstruction: &Reconstruction) {
    let Some(first) = reconstruction.merged_duplicates.first() else {
        return;
    };
    eprintln!(
        "warning: {}: merged {} duplicate point(s) (line {} repeats line {})",
        input_name.display(),
        reconstruction.merged_duplicates.len(),
        file.lines[first.dropped],
        file.lines[first.kept],
    );
}
