//! `crawltrace render`: an SVG file rasterized to PNG with resvg.

use crawltrace::files::{read_regular_file, OutputPlan};
use crawltrace::render_svg;

use crate::cli::RenderArgs;
use crate::exit::{Exit, Failure};
use crate::files::{claim_output, png_bytes, save};

/// DECISION: the largest SVG file rendered, 256 MiB: parsing takes about ten times its size in
/// memory, and the traced SVG of a 250-megapixel page of noise is far smaller.
const MAX_SVG_BYTES: u64 = 256 << 20;

pub fn run(args: RenderArgs) -> Result<Exit, Failure> {
    claim_output(&mut OutputPlan::new([args.input.as_path()]), &args.output)?;
    let svg =
        read_regular_file(&args.input, MAX_SVG_BYTES).map_err(|e| Failure::new(&args.input, e))?;
    let svg = String::from_utf8(svg).map_err(|_| Failure::new(&args.input, "not UTF-8 text"))?;
    let image = render_svg(&svg, args.scale).map_err(|e| Failure::new(&args.input, e))?;
    let png = png_bytes(&image, &args.output)?;
    save(&args.output, &png)?;
    Ok(Exit::Success)
}
