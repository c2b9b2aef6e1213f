//! The keyword options of `crawltrace.trace`, checked as the command line checks its options
//! (`src/bin/crawltrace/cli.rs`) and turned into the library's [`TraceOptions`] and
//! [`ExportOptions`]. Messages are one line, `option: problem`, as on the command line.

use crawltrace::{
    BinarizeOptions, ExportOptions, Length, Method, SizeRequest, ThresholdMethod, TraceOptions,
    Units,
};

/// The options as Python passed them.
pub struct TraceArguments<'a> {
    pub threshold: Option<i64>,
    pub adaptive: bool,
    pub invert: bool,
    pub spacing: Option<f64>,
    pub method: &'a str,
    pub smooth: bool,
    pub simplify: Option<f64>,
    pub stroke_width: Option<f64>,
    pub color: &'a str,
    pub dpi: Option<f64>,
    pub size: Option<&'a str>,
    pub units: Option<&'a str>,
}

/// A number that must be finite and above zero (`spacing`, `stroke_width`, `dpi`).
fn positive(name: &str, value: Option<f64>) -> Result<Option<f64>, String> {
    match value {
        Some(v) if !(v.is_finite() && v > 0.0) => Err(format!("{name}: must be a positive number")),
        _ => Ok(value),
    }
}

impl TraceArguments<'_> {
    /// The library's options, or the first problem found.
    pub fn check(&self) -> Result<(TraceOptions, ExportOptions), String> {
        let method = match self.threshold {
            Some(_) if self.adaptive => {
                return Err("threshold: cannot be used with adaptive=True".into())
            }
            Some(level) => ThresholdMethod::Fixed(
                u8::try_from(level)
                    .map_err(|_| "threshold: must be a gray level from 0 to 255".to_string())?,
            ),
            None if self.adaptive => ThresholdMethod::Adaptive,
            None => ThresholdMethod::Auto,
        };
        if self.simplify.is_some_and(|t| !(t.is_finite() && t >= 0.0)) {
            return Err("simplify: must be zero or a positive number".into());
        }
        if self.color.trim().is_empty() || self.color.contains(['"', '<', '>', '&']) {
            return Err("color: must be an SVG colour such as black or #1a2b3c".into());
        }
        let trace_options = TraceOptions {
            binarize: BinarizeOptions {
                method,
                invert: self.invert,
            },
            spacing: positive("spacing", self.spacing)?,
            smooth: self.smooth,
            simplify: self.simplify,
            stroke_width: positive("stroke_width", self.stroke_width)?,
            color: self.color.to_string(),
            method: match self.method {
                "strokes" => Method::Strokes,
                "points" => Method::Points,
                "paper" => Method::Paper,
                _ => return Err("method: must be \"strokes\", \"points\" or \"paper\"".into()),
            },
            keep_stages: false,
            // The library's pixel limit for files (250 megapixels).
            ..TraceOptions::default()
        };
        Ok((trace_options, self.export_options()?))
    }

    /// `dpi`, `size` and `units`.
    fn export_options(&self) -> Result<ExportOptions, String> {
        if self.dpi.is_some() && self.size.is_some() {
            return Err("size: cannot be used with dpi (it sets the density itself)".into());
        }
        let size = self
            .size
            .map(|text| text.parse::<Length>().map_err(|e| format!("size: {e}")))
            .transpose()?;
        let units = self
            .units
            .map(|text| text.parse::<Units>().map_err(|e| format!("units: {e}")))
            .transpose()?;
        Ok(ExportOptions {
            size: SizeRequest {
                dpi: positive("dpi", self.dpi)?,
                size,
                units,
            },
            ..ExportOptions::default()
        })
    }
}
