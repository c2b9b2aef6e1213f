//! The `crawltrace` command: parses arguments, reads and writes files, reports; the work is done
//! by the library.

mod cli;

use std::fs;
use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;
use cli::{Cli, Command, PointsArgs, PointsFormat, RenderArgs};
use crawltrace::{pointfile, pointset, reconstruct, render};

/// A failure to report as `error: <file>: <what>` with an exit code.
struct Failure {
    file: String,
    message: String,
}

impl Failure {
    fn new(file: impl AsRef<Path>, message: impl ToString) -> Self {
        Self {
            file: file.as_ref().display().to_string(),
            message: message.to_string(),
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Points(args) => run_points(args),
        Command::Render(args) => run_render(args),
    };
    match result {
        Ok(code) => code,
        Err(failure) => {
            eprintln!("error: {}: {}", failure.file, failure.message);
            ExitCode::from(2)
        }
    }
}

fn run_points(args: PointsArgs) -> Result<ExitCode, Failure> {
    let from_stdin = args.input.as_os_str() == "-";
    let input_name = if from_stdin {
        PathBuf::from("<stdin>")
    } else {
        args.input.clone()
    };
    let output = args.output.filter(|o| o.as_os_str() != "-");
    // Refuse before doing any work: a large input takes a while to reconstruct.
    if let Some(path) = &output {
        refuse_to_overwrite_input(path, &[&args.input])?;
    }
    let bytes = if from_stdin {
        let mut bytes = Vec::new();
        io::stdin()
            .read_to_end(&mut bytes)
            .map_err(|e| Failure::new(&input_name, e))?;
        bytes
    } else {
        fs::read(&args.input).map_err(|e| Failure::new(&input_name, describe_io(&e)))?
    };
    let file = pointfile::parse_points(&bytes).map_err(|e| Failure::new(&input_name, e))?;
    drop(bytes); // The text of a large file is no longer needed: keep the peak memory down.
    let reconstruction = reconstruct(&file.points).map_err(|e| {
        let line = match e {
            reconstruct::ReconstructError::NotFinite { index }
            | reconstruct::ReconstructError::OutOfRange { index, .. } => file.lines[index],
        };
        Failure::new(&input_name, format!("line {line}: {e}"))
    })?;
    if !reconstruction.merged_duplicates.is_empty() {
        let first = reconstruction.merged_duplicates[0];
        eprintln!(
            "warning: {}: merged {} duplicate point(s) (line {} repeats line {})",
            input_name.display(),
            reconstruction.merged_duplicates.len(),
            file.lines[first.dropped],
            file.lines[first.kept],
        );
    }
    let format = args.format.unwrap_or(match &output {
        Some(path) if has_extension(path, "svg") => PointsFormat::Svg,
        _ => PointsFormat::Json,
    });
    let mut text = Vec::new();
    match format {
        PointsFormat::Json => pointset::write_json(&mut text, &file.points, &reconstruction)
            .map_err(|e| Failure::new(&input_name, e))?,
        PointsFormat::Svg => text.extend_from_slice(
            crawltrace::svg::to_svg(&pointset::to_drawing(&file.points, &reconstruction))
                .as_bytes(),
        ),
    }
    match output {
        Some(path) => write_atomically(&path, &text)?,
        None => io::stdout()
            .lock()
            .write_all(&text)
            .map_err(|e| Failure::new("<stdout>", e))?,
    }
    Ok(ExitCode::SUCCESS)
}

fn run_render(args: RenderArgs) -> Result<ExitCode, Failure> {
    let svg = fs::read(&args.input).map_err(|e| Failure::new(&args.input, describe_io(&e)))?;
    let svg = String::from_utf8(svg).map_err(|_| Failure::new(&args.input, "not UTF-8 text"))?;
    let image = render::render_svg(&svg, args.scale).map_err(|e| Failure::new(&args.input, e))?;
    refuse_to_overwrite_input(&args.output, &[&args.input])?;
    let mut png = Vec::new();
    image
        .write_to(&mut io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| Failure::new(&args.output, e))?;
    write_atomically(&args.output, &png)?;
    Ok(ExitCode::SUCCESS)
}

fn has_extension(path: &Path, extension: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(extension))
}

/// A short description of an I/O error, without Rust's `(os error N)` suffix.
fn describe_io(error: &io::Error) -> String {
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

fn refuse_to_overwrite_input(output: &Path, inputs: &[&Path]) -> Result<(), Failure> {
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

/// Writes `bytes` to a temporary file beside `path`, then renames it over `path`, so a reader
/// never sees a half-written file.
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    let folder = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    // A temporary file is private (0600) by default; the result should get the permissions any
    // new file gets (0666 less the umask), as if written directly.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let mut temporary = builder
        .tempfile_in(folder)
        .map_err(|e| Failure::new(path, describe_io(&e)))?;
    temporary
        .write_all(bytes)
        .map_err(|e| Failure::new(path, describe_io(&e)))?;
    temporary
        .persist(path)
        .map_err(|e| Failure::new(path, describe_io(&e.error)))?;
    Ok(())
}
