//! Command-line types (clap derive) for the `crawltrace` binary, the checks of option values
//! (clap value parsers), and the library options they make.

use std::num::{ParseFloatError, ParseIntError};
use std::path::PathBuf;

use clap::{Parser, Subcommand, ValueEnum};
use clap_complete::Shell;
use crawltrace::stages::decode::DEFAULT_MAX_PIXELS;
use crawltrace::stages::fit::MIN_TOLERANCE_PX;
use crawltrace::stages::render::DEFAULT_MAX_PIXELS as DEFAULT_RENDER_PIXELS;
use crawltrace::stages::strokes::MIN_SPACING_PX;
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
    #[arg(long, default_value_t = 1.0, value_parser = render_scale)]
    pub scale: f32,
    /// Refuse canvases with more pixels than this (default: 64000000, a 4000 × 3000 page at
    /// scale 2).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_RENDER_PIXELS, value_parser = pixel_count)]
    pub max_pixels: u64,
    /// Internal: be the sandboxed renderer (SVG on standard input, PNG on standard output).
    #[arg(long, hide = true)]
    pub in_sandbox: bool,
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

    /// Sample spacing along strokes in pixels (default: 1.5 × the measured pen width; at least
    /// 0.5, and a spacing below a quarter of the pen width is raised to it).
    #[arg(long, value_name = "PX", value_parser = spacing, help_heading = "Reconstruction")]
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
    /// Largest deviation of a path from the reconstructed curve, in pixels (default: 0.4 pen
    /// widths, at least 0.5; at least 0.01, the SVG's resolution).
    #[arg(long, value_name = "TOL", value_parser = tolerance, help_heading = "Output")]
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
    /// Refuse images with more pixels than this, from their header, before decoding them; files
    /// larger than such an image can be (4 bytes a pixel) are not read (default: 250000000, an A0
    /// sheet at 400 dpi).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_PIXELS, value_parser = pixel_count)]
    pub max_pixels: u64,

    /// Scan folders recursively.
    #[arg(short, long, help_heading = "Folders and batches")]
    pub recursive: bool,
    /// Only trace files matching this pattern (`scan-*`, or `**/*.png` against the path inside
    /// the folder).
    #[arg(long, value_name = "PATTERN", help_heading = "Folders and batches")]
    pub glob: Option<String>,
    /// Number of images traced at once, 1 to 1024 (default: all cores).
    #[arg(short, long, value_name = "N", value_parser = job_count, help_heading = "Folders and batches")]
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
            max_pixels: self.max_pixels,
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
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum OptionCheck {
    /// Zero, negative, infinite or NaN where a size is wanted.
    #[error("must be a positive number")]
    NotPositive,
    /// Below the smallest value that changes the result (or not a finite number).
    #[error("must be a number of at least {0}")]
    AtLeast(f64),
    /// A count outside its range.
    #[error("must be between {0} and {1}")]
    Between(u64, u64),
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
    /// Not a whole number.
    #[error(transparent)]
    NotAWholeNumber(#[from] ParseIntError),
    /// A number (or text) out of range.
    #[error(transparent)]
    Check(#[from] OptionCheck),
}

/// A finite number greater than zero (`--stroke-width`).
fn positive_number(text: &str) -> Result<f64, ValueError> {
    let value: f64 = text.parse()?;
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(OptionCheck::NotPositive.into())
    }
}

/// `--scale`: a finite number greater than zero.
fn render_scale(text: &str) -> Result<f32, ValueError> {
    positive_number(text).map(|scale| scale as f32)
}

/// A finite number of at least `minimum`.
fn at_least(text: &str, minimum: f64) -> Result<f64, ValueError> {
    let value: f64 = text.parse()?;
    if value.is_finite() && value >= minimum {
        Ok(value)
    } else {
        Err(OptionCheck::AtLeast(minimum).into())
    }
}

/// `--spacing`: at least [`MIN_SPACING_PX`] (the library raises it further for thick pens).
fn spacing(text: &str) -> Result<f64, ValueError> {
    at_least(text, MIN_SPACING_PX)
}

/// `--simplify`: at least [`MIN_TOLERANCE_PX`].
fn tolerance(text: &str) -> Result<f64, ValueError> {
    at_least(text, MIN_TOLERANCE_PX)
}

/// A whole number from `minimum` to `maximum`.
fn whole_number_between(text: &str, minimum: u64, maximum: u64) -> Result<u64, ValueError> {
    let value: u64 = text.parse()?;
    if (minimum..=maximum).contains(&value) {
        Ok(value)
    } else {
        Err(OptionCheck::Between(minimum, maximum).into())
    }
}

/// `--max-pixels`: at least one pixel.
fn pixel_count(text: &str) -> Result<u64, ValueError> {
    whole_number_between(text, 1, u64::MAX)
}

/// DECISION: at most 1024 worker threads: more than any machine we know has cores, and each
/// thread holds an image's worth of memory while it traces.
const MAX_JOBS: u64 = 1024;

/// `--jobs`: 1 to [`MAX_JOBS`].
fn job_count(text: &str) -> Result<usize, ValueError> {
    whole_number_between(text, 1, MAX_JOBS).map(|jobs| jobs as usize)
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
    }

    /// Values that would make a trace spin or outgrow memory are refused with their range.
    #[test]
    fn work_bounding_options_have_floors_and_ranges() {
        assert_eq!(spacing("0.5").ok(), Some(0.5));
        assert_eq!(tolerance("0.01").ok(), Some(0.01));
        for text in ["0.49", "1e-4", "1e-300", "0", "-1", "NaN", "inf"] {
            assert!(
                matches!(spacing(text), Err(ValueError::Check(OptionCheck::AtLeast(m))) if m == 0.5),
                "{text}"
            );
        }
        for text in ["0", "0.009", "-0.5", "NaN"] {
            assert!(
                matches!(
                    tolerance(text),
                    Err(ValueError::Check(OptionCheck::AtLeast(_)))
                ),
                "{text}"
            );
        }
        assert_eq!(
            OptionCheck::AtLeast(0.5).to_string(),
            "must be a number of at least 0.5"
        );
        assert_eq!(job_count("1").ok(), Some(1));
        assert_eq!(job_count("1024").ok(), Some(1024));
        for text in ["0", "1025", "100000000"] {
            assert!(
                matches!(
                    job_count(text),
                    Err(ValueError::Check(OptionCheck::Between(1, 1024)))
                ),
                "{text}"
            );
        }
        assert!(matches!(
            job_count("-1"),
            Err(ValueError::NotAWholeNumber(_))
        ));
        assert_eq!(pixel_count("1").ok(), Some(1));
        assert!(matches!(pixel_count("0"), Err(ValueError::Check(_))));
        assert!(matches!(
            pixel_count("2.5e8"),
            Err(ValueError::NotAWholeNumber(_))
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
