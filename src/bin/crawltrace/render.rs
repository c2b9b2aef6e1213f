//! `crawltrace render`: an SVG file rasterized to PNG with resvg, in a sandbox
//! ([`crate::sandbox`]): only the given file is read, and the render runs in a child process
//! with limits on its time and memory.

use crawltrace::files::{read_regular_file, OutputPlan};
use crawltrace::RenderOptions;

use crate::cli::RenderArgs;
use crate::exit::{Exit, Failure};
use crate::files::{claim_output, save};
use crate::sandbox::{render_sandboxed, serve};

/// DECISION: the largest SVG file rendered, 256 MiB: parsing takes about ten times its size in
/// memory, and the traced SVG of a 250-megapixel page of noise is far smaller.
const MAX_SVG_BYTES: u64 = 256 << 20;

pub fn run(args: RenderArgs) -> Result<Exit, Failure> {
    let options = RenderOptions {
        scale: args.scale,
        max_pixels: args.max_pixels,
    };
    if args.in_sandbox {
        return serve(&options)
            .map(|()| Exit::Success)
            .map_err(Failure::general);
    }
    claim_output(&mut OutputPlan::new([args.input.as_path()]), &args.output)?;
    let svg =
        read_regular_file(&args.input, MAX_SVG_BYTES).map_err(|e| Failure::new(&args.input, e))?;
    let png = render_sandboxed(&svg, &args.input, &options)?;
    save(&args.output, &png)?;
    Ok(Exit::Success)
}
