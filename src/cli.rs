//! Command-line types (clap derive) for the `crawltrace` binary; no behaviour lives here.

use std::path::PathBuf;

use clap::{Parser, Subcommand, ValueEnum};

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
    /// Reconstruct curves from a point set (one `x y` point a line) and write them as JSON or SVG.
    Points(PointsArgs),
    /// Rasterize an SVG file to PNG with resvg.
    Render(RenderArgs),
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
