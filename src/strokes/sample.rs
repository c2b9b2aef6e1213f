//! Sampling pen strokes into points for the crawl: each stroke is simplified (Ramer–Douglas–Peucker,
//! so corners and stroke ends are kept exactly), then points are inserted so that no two
//! consecutive samples are farther apart than the spacing.

use super::Stroke;

/// The sample spacing for a pen of `stroke_width` pixels.
///
/// DECISION: one and a half pen widths. Closer samples than about a pen width only resample the
/// skeleton's pixel staircase; much sparser ones cut across curves whose radius is a few pen
/// widths. The floor of 2 px keeps hairlines from producing a point per pixel.
pub fn default_spacing(stroke_width: f64) -> f64 {
    (1.5 * stroke_width).max(2.0)
}

/// The deviation from the skeleton that simplification may introduce, for a pen of
/// `stroke_width` pixels.
///
/// DECISION: a quarter of the pen width, at least 0.7 px: the skeleton of a hand-drawn stroke
/// wobbles by about that much inside the ink, so finer detail is noise, not drawing.
pub fn simplification_tolerance(stroke_width: f64) -> f64 {
    (0.25 * stroke_width).max(0.7)
}

/// Samples every stroke every `spacing` pixels after simplifying it within `tolerance` (the
/// pipeline's "sample" stage).
pub fn sample_strokes(strokes: &[Stroke], spacing: f64, tolerance: f64) -> Vec<Stroke> {
    strokes
        .iter()
        .map(|stroke| {
            // A loop needs at least four samples to be closable (the paper's "more than two
            // edges"); small loops are sampled more densely.
            let stroke_spacing = if stroke.line.closed {
                spacing.min(stroke.line.length() / 4.0)
            } else {
                spacing
            };
            Stroke {
                line: stroke.line.simplify(tolerance).resample(stroke_spacing),
                ends: stroke.ends,
            }
        })
        .collect()
}
