//! A traced drawing as the file a user asked for: SVG or DXF ([`OutputFormat`]), at the physical
//! size the options and the image's own density give ([`SizeRequest`]). The one place where the
//! command, the batch engine and the Python package turn a [`Traced`] into bytes.

use std::path::Path;

use crate::output::dxf::to_dxf;
use crate::output::svg::to_svg_with_size;
use crate::output::units::{PhysicalSize, SizeRequest};
use crate::trace::Traced;

/// The file formats a traced drawing is written in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum OutputFormat {
    /// SVG: one `<path>` per curve, smooth Béziers; `width`/`height` in mm or inches.
    #[default]
    Svg,
    /// DXF R2000: one `LWPOLYLINE` per curve, for CAD/CAM and laser software.
    Dxf,
}

impl OutputFormat {
    /// The file extension of the format, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            OutputFormat::Svg => "svg",
            OutputFormat::Dxf => "dxf",
        }
    }

    /// The format a file name asks for by its extension (`.dxf`, any letter case), if any.
    pub fn from_path(path: &Path) -> Option<Self> {
        let extension = path.extension()?.to_str()?;
        [OutputFormat::Svg, OutputFormat::Dxf]
            .into_iter()
            .find(|format| format.extension().eq_ignore_ascii_case(extension))
    }
}

/// How a traced drawing is written. `Default` is SVG in millimetres at the image's own density
/// (else 96 pixels per inch).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ExportOptions {
    /// The file format.
    pub format: OutputFormat,
    /// The physical size asked for (`--dpi`, `--size`, `--units`).
    pub size: SizeRequest,
}

impl ExportOptions {
    /// The physical size `traced` is written at.
    pub fn physical_size(&self, traced: &Traced) -> PhysicalSize {
        let drawing = &traced.drawing;
        self.size
            .resolve(drawing.width, drawing.height, traced.image_dpi)
    }
}

/// Writes `traced` in `options.format` at its physical size: SVG with `width`/`height` in units
/// and the `viewBox` in pixels, or DXF with the paths flattened within the trace's fitting
/// tolerance (`--simplify`).
///
/// # Examples
///
/// ```
/// use std::path::Path;
///
/// use crawltrace::{export, trace_file, ExportOptions, OutputFormat, TraceOptions};
///
/// let traced = trace_file(Path::new("samples/face-clean.png"), &TraceOptions::default())?;
/// let dxf = export(&traced, &ExportOptions { format: OutputFormat::Dxf, ..ExportOptions::default() });
/// assert_eq!(dxf.matches("LWPOLYLINE").count(), traced.drawing.paths.len());
/// # Ok::<(), crawltrace::TraceFileError>(())
/// ```
pub fn export(traced: &Traced, options: &ExportOptions) -> String {
    let size = options.physical_size(traced);
    match options.format {
        OutputFormat::Svg => to_svg_with_size(&traced.drawing, &size),
        OutputFormat::Dxf => to_dxf(&traced.drawing, &size, traced.report.tolerance),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_follow_the_extension() {
        assert_eq!(
            OutputFormat::from_path(Path::new("a/b.DXF")),
            Some(OutputFormat::Dxf)
        );
        assert_eq!(
            OutputFormat::from_path(Path::new("b.svg")),
            Some(OutputFormat::Svg)
        );
        assert_eq!(OutputFormat::from_path(Path::new("b.png")), None);
        assert_eq!(OutputFormat::from_path(Path::new("dxf")), None);
    }
}
