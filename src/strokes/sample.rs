//! Sampling pen strokes into points for the crawl: each stroke is simplified (Ramer–Douglas–Peucker,
//! so corners and stroke ends are kept exactly), then points are inserted so that no two
//! consecutive samples are farther apart than the spacing.

use super::Stroke;

/// DECISION: samples one and a half pen widths apart. Closer samples than about a pen width only
/// resample the skeleton's pixel staircase; much sparser ones cut across curves whose radius is a
/// few pen widths.
const SPACING_IN_PEN_WIDTHS: f64 = 1.5;
/// The floor of the spacing, which keeps hairlines from producing a point per pixel.
const SPACING_FLOOR_PX: f64 = 2.0;

/// DECISION: the densest sampling a caller may ask for: samples half a pixel apart (the
/// skeleton's own resolution is a pixel) and a quarter of a pen width apart (the skeleton wobbles
/// that much inside the ink). Denser samples add no shape, only work: samples, triangles and
/// crawl steps all grow as 1 / spacing (`--spacing 1e-4` once took 40 s and 4.3 GB on 500 × 500
/// pixels).
pub const MIN_SPACING_PX: f64 = 0.5;
const MIN_SPACING_IN_PEN_WIDTHS: f64 = 0.25;

/// DECISION: simplification may move the skeleton by a quarter of the pen width: the skeleton of
/// a hand-drawn stroke wobbles by about that much inside the ink, so finer detail is noise, not
/// drawing.
const SIMPLIFICATION_IN_PEN_WIDTHS: f64 = 0.25;
/// The floor of the tolerance: the skeleton's pixel staircase alone deviates by about 0.7 px.
const SIMPLIFICATION_FLOOR_PX: f64 = 0.7;

/// A loop needs at least this many samples to be closable (the paper's "more than two edges"
/// before closing), so small loops are sampled more densely.
pub(crate) const MIN_LOOP_SAMPLES: usize = 4;

/// The sample spacing for a pen of `stroke_width` pixels: one and a half pen widths, at least
/// 2 px.
pub fn default_spacing(stroke_width: f64) -> f64 {
    (SPACING_IN_PEN_WIDTHS * stroke_width).max(SPACING_FLOOR_PX)
}

/// The smallest sample spacing for a pen of `stroke_width` pixels: a quarter of the pen width,
/// at least [`MIN_SPACING_PX`]. A smaller spacing asked for is raised to it.
pub fn minimum_spacing(stroke_width: f64) -> f64 {
    (MIN_SPACING_IN_PEN_WIDTHS * stroke_width).max(MIN_SPACING_PX)
}

/// The deviation from the skeleton that simplification may introduce, for a pen of
/// `stroke_width` pixels: a quarter of the pen width, at least 0.7 px.
pub fn simplification_tolerance(stroke_width: f64) -> f64 {
    (SIMPLIFICATION_IN_PEN_WIDTHS * stroke_width).max(SIMPLIFICATION_FLOOR_PX)
}

/// Samples every stroke every `spacing` pixels after simplifying it within `tolerance` (the
/// pipeline's "sample" stage). A spacing below [`MIN_SPACING_PX`] (or not a number) is raised to
/// it, so that no spacing can make the samples outgrow memory.
pub fn sample_strokes(strokes: &[Stroke], spacing: f64, tolerance: f64) -> Vec<Stroke> {
    let spacing = spacing.max(MIN_SPACING_PX);
    strokes
        .iter()
        .map(|stroke| {
            let stroke_spacing = if stroke.line.closed {
                spacing.min(stroke.line.length() / MIN_LOOP_SAMPLES as f64)
            } else {
                spacing
            };
            Stroke {
                line: stroke.line.simplify(tolerance).resample(stroke_spacing),
                ends: stroke.ends,
                wide: stroke.wide,
                contacts: stroke.contacts.clone(),
            }
        })
        .collect()
}
