//! Command-line types (clap derive) for the `crawltrace` binary, the checks of option values
//! (clap value parsers), and the library options they make.

use std::num::ParseFloatError;
use std::path::PathBuf;

use clap::{Parser, Subcommand, ValueEnum};
use clap_complete::Shell;
use crawltrace::{
    BinarizeOptions, ExportOptions, Length, Method, OutputFormat, SizeRequest, ThresholdMethod,
    TraceOptions, Units, UnitsError,
};

/// Turn scanned skip-stroke line drawings and 2D point sets into clean SVG curves.
#[derive(Debug, Parser)]
#[command(name = "crawltrace", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Trace scanned line drawings (image files, standard input or folders of them) into SVG or
    /// DXF.
    Trace(Box<TraceArgs>),
    /// Reconstruct curves from a point set (one `x y` point a line) and write them as JSON or SVG.
    Points(PointsArgs),
    /// Rasterize an SVG file to PNG with resvg.
    Render(RenderArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell) on standard output.
    Completions(CompletionsArgs),
    /// Print the manual page (roff) on standard output, or write one page per command into a
    /// folder.
    Manpage(ManpageArgs),
}

/// Arguments of `crawltrace completions`.
#[derive(Debug, clap::Args)]
pub struct CompletionsArgs {
    /// The shell to complete in.
    #[arg(value_enum)]
    pub shell: Shell,
}

/// Arguments of `crawltrace manpage`.
#[derive(Debug, clap::Args)]
pub struct ManpageArgs {
    /// Write `crawltrace.1` and one page per command (`crawltrace-trace.1`, …) into DIR instead.
    #[arg(long, value_name = "DIR")]
    pub dir: Option<PathBuf>,
}

/// Arguments of `crawltrace points`.
#[derive(Debug, clap::Args)]
pub struct PointsArgs {
    /// The point file, or `-` for standard input.
    pub input: PathBuf,
    /// Where to write the result (`-` is standard output, the default).
    #[arg(short, long, value_name = "OUT")]
    pub output: Option<PathBuf>,
    /// Output format; by default taken from the extension of `-o` (`.svg` → svg), else json.
    #[arg(long, value_enum)]
    pub format: Option<PointsFormat>,
    /// In SVG output, draw every input point as a dot over the curves.
    #[arg(long)]
    pub show_points: bool,
    /// How points are connected: `robust` (default) handles stray points, sharp corners, open
    /// ends and thin parts; `paper` is the paper's crawl as published.
    #[arg(long, value_enum, default_value_t = PointsMethod::Robust)]
    pub method: PointsMethod,
}

/// `--method` values of `crawltrace points`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PointsMethod {
    /// The robust crawl (`docs/point-sets.md`).
    Robust,
    /// The paper's crawl (Parakkat & Muthuganapathy 2016, Algorithm 1).
    Paper,
}

/// Output formats of `crawltrace points`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PointsFormat {
    /// `{"curves":[{"closed":…,"indices":[…],"points":[[x,y],…]}],"outliers":[…]}`
    Json,
    /// One path per curve, outliers as red dots.
    Svg,
}

/// Arguments of `crawltrace render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// The SVG file to rasterize.
    pub input: PathBuf,
    /// The PNG file to write.
    #[arg(short, long, value_name = "PNG")]
    pub output: PathBuf,
    /// Pixels per SVG pixel.
    #[arg(long, default_value_t = 1.0)]
    pub scale: f32,
}

/// Arguments of `crawltrace trace`.
#[derive(Debug, clap::Args)]
pub struct TraceArgs {
    /// Image files (any format the `image` crate reads) or folders of them; `-` reads one image
    /// from standard input.
    #[arg(required = true, value_name = "INPUT")]
    pub inputs: Vec<PathBuf>,
    /// Output: for one image, the SVG or DXF file (`-` for standard output, the default for
    /// standard input; else `<stem>.svg` beside the input); for several images or a folder, the
    /// output folder.
    #[arg(short, long, value_name = "OUT")]
    pub output: Option<PathBuf>,
    /// Output format (default: from the extension of `-o`, `.dxf` → dxf; else svg).
    #[arg(long, value_enum)]
    pub format: Option<FormatArg>,

    /// Fixed gray level (0–255) below which a pixel is ink, instead of the automatic threshold.
    #[arg(
        long,
        value_name = "N",
        conflicts_with = "adaptive",
        help_heading = "Thresholding"
    )]
    pub threshold: Option<u8>,
    /// Always use the adaptive threshold (for uneven lighting; chosen automatically when needed).
    #[arg(long, help_heading = "Thresholding")]
    pub adaptive: bool,
    /// Light ink on dark paper.
    #[arg(long, help_heading = "Thresholding")]
    pub invert: bool,

    /// Sample spacing along strokes in pixels (default: 1.5 × the measured pen width).
    #[arg(long, value_name = "PX", value_parser = positive_number, help_heading = "Reconstruction")]
    pub spacing: Option<f64>,
    /// How samples are connected: `strokes` (default) knows which samples the pen drew together;
    /// `points` is the robust point-set crawl on all samples; `paper` the paper's plain crawl.
    #[arg(long, value_enum, default_value_t = MethodArg::Strokes, help_heading = "Reconstruction")]
    pub method: MethodArg,

    /// Smooth cubic Béziers with sharp corners kept (the default).
    #[arg(long, overrides_with = "no_smooth", help_heading = "Output")]
    pub smooth: bool,
    /// Write straight segments instead of smooth cubic Béziers.
    #[arg(long, overrides_with = "smooth", help_heading = "Output")]
    pub no_smooth: bool,
    /// Largest deviation of a path from the reconstructed curve, in pixels (default: a quarter of
    /// the pen width, at least 0.5).
    #[arg(long, value_name = "TOL", value_parser = zero_or_positive_number, help_heading = "Output")]
    pub simplify: Option<f64>,
    /// Pixels per inch of the image, for the output's physical size (default: the density the
    /// image file records, else 96).
    #[arg(
        long,
        value_name = "N",
        value_parser = positive_number,
        allow_negative_numbers = true,
        conflicts_with = "size",
        help_heading = "Size"
    )]
    pub dpi: Option<f64>,
    /// The length of the drawing's longer side (`210mm`, `21cm`, `8in`), instead of a density.
    #[arg(
        long,
        value_name = "LENGTH",
        value_parser = physical_length,
        allow_hyphen_values = true,
        help_heading = "Size"
    )]
    pub size: Option<Length>,
    /// Units of the output's size and DXF coordinates (default: those of `--size`, else mm).
    #[arg(long, value_enum, help_heading = "Size")]
    pub units: Option<UnitsArg>,

    /// Stroke width of the SVG paths (default: the measured pen width).
    #[arg(long, value_name = "PX", value_parser = positive_number, help_heading = "Output")]
    pub stroke_width: Option<f64>,
    /// Stroke colour of the SVG paths.
    #[arg(long, default_value = "#000000", value_parser = svg_colour, help_heading = "Output")]
    pub color: String,
    /// Write pictures of each stage (mask, skeleton, samples, triangulation, result) into DIR.
    #[arg(long, value_name = "DIR", help_heading = "Output")]
    pub debug: Option<PathBuf>,
    /// Print nothing but errors.
    #[arg(short, long)]
    pub quiet: bool,

    /// Scan folders recursively.
    #[arg(short, long, help_heading = "Folders and batches")]
    pub recursive: bool,
    /// Only trace files matching this pattern (`scan-*`, or `**/*.png` against the path inside
    /// the folder).
    #[arg(long, value_name = "PATTERN", help_heading = "Folders and batches")]
    pub glob: Option<String>,
    /// Number of images traced at once (default: all cores).
    #[arg(short, long, value_name = "N", help_heading = "Folders and batches")]
    pub jobs: Option<usize>,
    /// Trace again even when the output is newer than the input.
    #[arg(long, help_heading = "Folders and batches")]
    pub force: bool,
    /// Write one JSON line per input (path, status, curves, closed curves, seconds, error).
    #[arg(long, value_name = "FILE", help_heading = "Folders and batches")]
    pub report: Option<PathBuf>,
    /// Take only shard K of N (`--shard 2/8`): a fixed share of the inputs chosen by path, for
    /// splitting a folder across machines.
    #[arg(long, value_name = "K/N", help_heading = "Folders and batches")]
    pub shard: Option<crawltrace::batch::Shard>,
}

/// `--format` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FormatArg {
    /// SVG: one path per curve, width and height in mm or inches, viewBox in pixels.
    Svg,
    /// DXF R2000: one LWPOLYLINE per curve, closed flag set on closed curves.
    Dxf,
}

/// `--units` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum UnitsArg {
    /// Millimetres.
    Mm,
    /// Inches.
    In,
}

/// `--method` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Crawl on stroke edges and gap bridges (default).
    Strokes,
    /// The robust point-set crawl on the Delaunay triangulation of all samples.
    Points,
    /// The paper's crawl on the Delaunay triangulation of all samples.
    Paper,
}

impl TraceArgs {
    /// The library's options for these arguments.
    pub fn trace_options(&self) -> TraceOptions {
        TraceOptions {
            binarize: BinarizeOptions {
                method: match (self.threshold, self.adaptive) {
                    (Some(level), _) => ThresholdMethod::Fixed(level),
                    (None, true) => ThresholdMethod::Adaptive,
                    (None, false) => ThresholdMethod::Auto,
                },
                invert: self.invert,
            },
            spacing: self.spacing,
            smooth: !self.no_smooth,
            simplify: self.simplify,
            stroke_width: self.stroke_width,
            color: self.color.clone(),
            method: match self.method {
                MethodArg::Strokes => Method::Strokes,
                MethodArg::Points => Method::Points,
                MethodArg::Paper => Method::Paper,
            },
            keep_stages: self.debug.is_some(),
        }
    }

    /// How the drawing is written: `--format` (or the extension of `-o`), `--dpi`, `--size`,
    /// `--units`.
    pub fn export_options(&self) -> ExportOptions {
        let from_output = self.output.as_deref().and_then(OutputFormat::from_path);
        ExportOptions {
            format: match self.format {
                Some(FormatArg::Svg) => OutputFormat::Svg,
                Some(FormatArg::Dxf) => OutputFormat::Dxf,
                None => from_output.unwrap_or_default(),
            },
            size: SizeRequest {
                dpi: self.dpi,
                size: self.size,
                units: self.units.map(|units| match units {
                    UnitsArg::Mm => Units::Mm,
                    UnitsArg::In => Units::In,
                }),
            },
        }
    }
}

/// An option value that parses but is out of range.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum OptionCheck {
    /// Zero, negative, infinite or NaN where a size is wanted.
    #[error("must be a positive number")]
    NotPositive,
    /// Negative, infinite or NaN where a tolerance is wanted.
    #[error("must be zero or a positive number")]
    Negative,
    /// Empty, or a character that would break the SVG attribute.
    #[error("must be an SVG colour such as black or #1a2b3c")]
    NotAColour,
    /// Not a positive length with a unit.
    #[error(transparent)]
    NotALength(#[from] UnitsError),
}

/// Why an option value was refused. `main` reports a failed [`OptionCheck`] as
/// `error: <option>: <check>`, one line like every other error of the command; a value that is no
/// number at all gets clap's usual message.
#[derive(Debug, thiserror::Error)]
pub enum ValueError {
    /// Not a number.
    #[error(transparent)]
    NotANumber(#[from] ParseFloatError),
    /// A number (or text) out of range.
    #[error(transparent)]
    Check(#[from] OptionCheck),
}

/// A finite number greater than zero (`--spacing`, `--stroke-width`).
fn positive_number(text: &str) -> Result<f64, ValueError> {
    let value: f64 = text.parse()?;
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(OptionCheck::NotPositive.into())
    }
}

/// A finite number, zero or greater (`--simplify`).
fn zero_or_positive_number(text: &str) -> Result<f64, ValueError> {
    let value: f64 = text.parse()?;
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(OptionCheck::Negative.into())
    }
}

/// A positive length with a unit (`--size`).
fn physical_length(text: &str) -> Result<Length, ValueError> {
    text.parse()
        .map_err(|error: UnitsError| OptionCheck::from(error).into())
}

/// Anything that can stand in an SVG attribute as a colour (`--color`); the SVG renderer judges
/// the colour itself.
fn svg_colour(text: &str) -> Result<String, ValueError> {
    if text.contains(['"', '<', '>', '&']) || text.trim().is_empty() {
        Err(OptionCheck::NotAColour.into())
    } else {
        Ok(text.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_must_be_positive_and_finite() {
        assert_eq!(positive_number("2.5").ok(), Some(2.5));
        for text in ["0", "-1", "inf", "NaN"] {
            assert!(
                matches!(
                    positive_number(text),
                    Err(ValueError::Check(OptionCheck::NotPositive))
                ),
                "{text}"
            );
        }
        assert!(matches!(
            positive_number("px"),
            Err(ValueError::NotANumber(_))
        ));
        assert_eq!(zero_or_positive_number("0").ok(), Some(0.0));
        assert!(matches!(
            zero_or_positive_number("-0.5"),
            Err(ValueError::Check(OptionCheck::Negative))
        ));
    }

    #[test]
    fn sizes_need_a_unit() {
        let length = physical_length("210mm").ok().unwrap();
        assert!((length.inches - 210.0 / 25.4).abs() < 1e-12);
        for text in ["banana", "210", "-3in", "0mm"] {
            assert!(
                matches!(
                    physical_length(text),
                    Err(ValueError::Check(OptionCheck::NotALength(_)))
                ),
                "{text:?}"
            );
        }
    }

    #[test]
    fn colours_must_fit_in_an_attribute() {
        assert_eq!(svg_colour("#1a2b3c").ok().as_deref(), Some("#1a2b3c"));
        assert_eq!(svg_colour("black").ok().as_deref(), Some("black"));
        for text in ["", "  ", "red\"", "a<b", "a&b"] {
            assert!(
                matches!(
                    svg_colour(text),
                    Err(ValueError::Check(OptionCheck::NotAColour))
                ),
                "{text:?}"
            );
        }
    }

    #[test]
    fn the_command_line_definition_is_consistent() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }
}
