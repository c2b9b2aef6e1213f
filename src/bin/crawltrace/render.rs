//! `crawltrace render`: an SVG file rasterized to PNG with resvg.

use std::fs;

use crawltrace::files::describe_io;
use crawltrace::render_svg;

use crate::cli::RenderArgs;
use crate::exit::{Exit, Failure};
use crate::files::{png_bytes, refuse_to_overwrite_input, save};

pub fn run(args: RenderArgs) -> Result<Exit, Failure> {
    let svg = fs::read(&args.input).map_err(|e| Failure::new(&args.input, describe_io(&e)))?;
    let svg = String::from_utf8(svg).map_err(|_| Failure::new(&args.input, "not UTF-8 text"))?;
    let image = render_svg(&svg, args.scale).map_err(|e| Failure::new(&args.input, e))?;
    refuse_to_overwrite_input(&args.output, &[&args.input])?;
    let png = png_bytes(&image, &args.output)?;
    save(&args.output, &png)?;
    Ok(Exit::Success)
}
