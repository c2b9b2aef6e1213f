//! Binarization: 8-bit gray → ink mask, by Otsu's threshold (N. Otsu, "A threshold selection
//! method from gray-level histograms", IEEE Trans. SMC 9(1), 1979), a fixed level, or Otsu after
//! flat-field correction by a coarse percentile background estimate, for uneven lighting.
//!
//! [`ThresholdMethod::Auto`] (the default) estimates the paper level over coarse blocks and picks
//! Otsu on an evenly lit page and the flat-field method otherwise; every method except
//! [`ThresholdMethod::Fixed`] refuses to invent ink on a page without real contrast.

use image::GrayImage;

use crate::raster::bitmap::Bitmap;

/// How the threshold between ink and paper is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ThresholdMethod {
    /// Otsu on an evenly lit page, [`ThresholdMethod::Adaptive`] when the paper level varies
    /// across the page by more than a quarter of the ink/paper contrast.
    #[default]
    Auto,
    /// One global level chosen by Otsu's method.
    Otsu,
    /// A given level: ink is every pixel at or beyond it on the ink side (≤ level for dark ink,
    /// ≥ level with [`BinarizeOptions::invert`]). Applied as given, even on a blank page.
    Fixed(u8),
    /// Each pixel divided by the smoothly interpolated paper level around it (flat-field
    /// correction), then Otsu on the corrected image. For shadows, vignetting and gradients.
    Adaptive,
}

/// Options for [`binarize`]. The default is automatic, dark ink on light paper.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BinarizeOptions {
    /// How the threshold is chosen.
    pub method: ThresholdMethod,
    /// Light ink on dark paper (chalk on a blackboard, a negative).
    pub invert: bool,
}

/// The method that produced a mask, with the level it used, so the caller can report it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MethodUsed {
    /// Otsu's level, in the input's gray values: ink is at or beyond it on the ink side. (When
    /// ink is too scarce for Otsu, a page with one short stroke, the level is midway between the
    /// paper and the ink found clear of the paper's noise.)
    Otsu {
        /// The level, as in [`ThresholdMethod::Fixed`].
        level: u8,
    },
    /// The caller's level.
    Fixed {
        /// The level, as given.
        level: u8,
    },
    /// Flat-field correction, then Otsu on the corrected image.
    Adaptive,
    /// The page has no real contrast (blank, or nearly uniform): the mask is empty rather than
    /// noise.
    Blank,
}

/// A binarized page.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Binarized {
    /// Ink pixels.
    pub mask: Bitmap,
    /// How the threshold was chosen.
    pub method_used: MethodUsed,
}

/// Blocks along the longer side of the page for the background estimate. Coarse on purpose:
/// a block must be several stroke widths across so that paper dominates it even where the
/// drawing is dense, and lighting varies slowly compared with strokes. 24 blocks make ~170 px
/// blocks on a 4000 px scan (about 14 mm at 300 dpi).
const BLOCKS_ALONG_LONG_SIDE: usize = 24;

/// Smallest block side in pixels, so tiny images still get a meaningful percentile.
const MIN_BLOCK_SIZE: usize = 16;

/// The paper level of a block is this percentile of its pixels (bright side): ink covers far
/// less than 10% of a block of a line drawing, so the 90th percentile is paper, and it is not
/// pulled up by the odd bright speck as the maximum would be.
const BACKGROUND_PERCENTILE: f64 = 0.90;

/// Auto picks the flat-field method when the paper level's range over the page (brightest block
/// minus darkest, inked blocks replaced) exceeds this fraction of the ink/paper contrast
/// (median paper level minus Otsu's mean ink level). Otsu's level sits near the middle of the
/// contrast; paper that dims by a quarter of it still stays a quarter of the contrast clear of
/// the level, enough for noise. Beyond that, dim paper starts to read as ink (or faint ink in
/// bright light as paper).
const UNEVEN_FRACTION: f64 = 0.25;

/// A block whose paper level is below this fraction of its 3×3 neighbourhood's median is taken
/// to be filled with ink. Pen or marker ink reflects a fifth to a third of what paper does, so
/// a block it fills reads well under half its neighbours. Lighting moves a few percent from one
/// block to the next, but in relative terms more where it is dim: a linear gradient down to 6%
/// light steps by 25% between the last blocks, which a tighter fraction would mistake for ink.
const INKED_BLOCK_FRACTION: f32 = 0.5;

/// Flat-field correction maps the paper level to this value, not to 255: paper pixels brighter
/// than the local estimate (noise, the bright side of a block) keep their spread instead of
/// piling up in one clipped bin, which would look to Otsu like a second population.
const CORRECTED_PAPER_LEVEL: f32 = 224.0;

/// Real contrast needs Otsu's two class means at least this many gray levels apart ...
const MIN_SEPARATION: f64 = 10.0;

/// ... and at least this many within-class standard deviations apart. Otsu splits any
/// unimodal histogram somewhere: a Gaussian (sensor noise) split at its mean gives a ratio of
/// 2.65, a uniform one 3.46. Ink gives far more: by our estimate about 16 for pen strokes 3 px
/// wide (190 levels below paper, anti-aliased edges, noise σ 6), and about 7 for faint pencil
/// 60 levels below paper with noise σ 8.
const MIN_SEPARATION_TO_SPREAD: f64 = 4.0;

/// Minimum depth of ink below its local paper level, in input gray levels, for the flat-field
/// method (see [`flat_field_otsu`]).
const MIN_INK_DEPTH: f32 = 10.0;

/// Background levels are floored at this fraction of the page's median paper level, so that
/// regions which are not paper at all (a scanner's black margin) are not stretched into paper
/// with amplified noise: they stay dark, as Otsu would see them.
const MIN_BACKGROUND_FRACTION: f32 = 0.1;

/// Separates ink from paper. The mask has the image's size; `true` is ink.
pub fn binarize(gray: &GrayImage, options: &BinarizeOptions) -> Binarized {
    let (width, height) = (gray.width() as usize, gray.height() as usize);
    let invert = options.invert;
    if width == 0 || height == 0 {
        return Binarized {
            mask: Bitmap::new(width, height),
            method_used: MethodUsed::Blank,
        };
    }
    // All methods work on "oriented" values where ink is dark, so inverting is one flip.
    let oriented = |value: u8| if invert { 255 - value } else { value };
    let report = |oriented_level: u8| {
        if invert {
            255 - oriented_level
        } else {
            oriented_level
        }
    };
    match options.method {
        ThresholdMethod::Fixed(level) => {
            let mask = threshold(gray, width, height, |value| {
                if invert {
                    value >= level
                } else {
                    value <= level
                }
            });
            Binarized {
                mask,
                method_used: MethodUsed::Fixed { level },
            }
        }
        ThresholdMethod::Otsu => {
            let mut histogram = [0u64; 256];
            for &value in gray.as_raw() {
                histogram[usize::from(oriented(value))] += 1;
            }
            global_otsu(gray, width, height, &histogram, invert, report)
        }
        ThresholdMethod::Adaptive => {
            let background = Background::estimate(gray, invert);
            flat_field_otsu(gray, &background, invert)
        }
        ThresholdMethod::Auto => {
            let background = Background::estimate(gray, invert);
            let uneven = otsu(&background.histogram).is_none_or(|split| {
                let contrast = f64::from(background.median) - split.dark_mean;
                f64::from(background.max - background.min) > UNEVEN_FRACTION * contrast
            });
            if uneven {
                flat_field_otsu(gray, &background, invert)
            } else {
                global_otsu(gray, width, height, &background.histogram, invert, report)
            }
        }
    }
}

/// Otsu on the whole page's histogram (of oriented values).
fn global_otsu(
    gray: &GrayImage,
    width: usize,
    height: usize,
    histogram: &[u64; 256],
    invert: bool,
    report: impl Fn(u8) -> u8,
) -> Binarized {
    match ink_level(histogram) {
        Some(level) => {
            let mask = threshold(gray, width, height, |value| {
                let value = if invert { 255 - value } else { value };
                value <= level
            });
            Binarized {
                mask,
                method_used: MethodUsed::Otsu {
                    level: report(level),
                },
            }
        }
        None => blank(width, height),
    }
}

fn blank(width: usize, height: usize) -> Binarized {
    Binarized {
        mask: Bitmap::new(width, height),
        method_used: MethodUsed::Blank,
    }
}

/// A mask of the pixels for which `is_ink` holds.
/// Each byte is written once: the mask is collected, not zeroed first and then overwritten (on the
/// 12-megapixel page that zeroing was a 12 MB `memset`, a full write pass of its own).
fn threshold(gray: &GrayImage, width: usize, height: usize, is_ink: impl Fn(u8) -> bool) -> Bitmap {
    let pixels = gray.as_raw()[..width * height]
        .iter()
        .map(|&value| u8::from(is_ink(value)))
        .collect();
    Bitmap::from_pixels(width, height, pixels)
}

/// Flat-field correction into the mask's own bytes (no second image buffer), Otsu on the
/// corrected histogram, then thresholding in place.
fn flat_field_otsu(gray: &GrayImage, background: &Background, invert: bool) -> Binarized {
    let (width, height) = (gray.width() as usize, gray.height() as usize);
    // Collected row by row, each byte written once (not zeroed first).
    let mut corrected_levels = Vec::with_capacity(width * height);
    let mut histogram = [0u64; 256];
    let floor = (background.median * MIN_BACKGROUND_FRACTION).max(1.0);
    // Row buffers, so that each step below is a simple loop the compiler vectorizes.
    let mut row_levels = vec![0f32; width];
    let mut row_values = vec![0f32; width];
    let mut row_corrected = vec![0u8; width];
    for (y, row) in gray.as_raw().chunks_exact(width).take(height).enumerate() {
        background.row_levels(y, floor, &mut row_levels);
        for (oriented, &value) in row_values.iter_mut().zip(row) {
            *oriented = f32::from(if invert { 255 - value } else { value });
        }
        for ((corrected, &value), &level) in
            row_corrected.iter_mut().zip(&row_values).zip(&row_levels)
        {
            *corrected = round_to_byte((value * CORRECTED_PAPER_LEVEL / level).min(255.0));
        }
        for &corrected in &row_corrected {
            histogram[usize::from(corrected)] += 1;
        }
        // Ink must also be at least MIN_INK_DEPTH gray levels darker than its local paper in
        // the input: where the paper is very dark, correction magnifies sensor noise into
        // ink-deep dips. Pixels too shallow are stored as 255, which no level reaches.
        corrected_levels.extend(row_corrected.iter().zip(&row_values).zip(&row_levels).map(
            |((&corrected, &value), &level)| {
                if value + MIN_INK_DEPTH <= level {
                    corrected
                } else {
                    255
                }
            },
        ));
    }
    let mut mask = Bitmap::from_pixels(width, height, corrected_levels);
    let Some(level) = ink_level(&histogram) else {
        return blank(width, height);
    };
    let mut ink_found = false;
    for byte in mask.as_bytes_mut() {
        *byte = u8::from(*byte <= level);
        ink_found |= *byte != 0;
    }
    Binarized {
        mask,
        method_used: if ink_found {
            MethodUsed::Adaptive
        } else {
            MethodUsed::Blank
        },
    }
}

/// Rounds a float in 0.0..=255.0 to the nearest byte (ties to even). Adding 1.5 × 2²³ leaves the
/// rounded integer in the low mantissa bits, read with a bit cast: unlike `as u8` (saturating,
/// NaN-checking), this compiles to a few vector instructions, which matters 12 million times.
#[inline]
fn round_to_byte(value: f32) -> u8 {
    const ROUNDING: f32 = 12_582_912.0;
    (value + ROUNDING).to_bits() as u8
}

/// The level separating ink (≤ level) from paper in a histogram of oriented values, or `None`
/// when there is no real ink: Otsu's level when its classes are really two populations, else
/// the level of a small dark population standing clear of the paper's noise (see
/// [`dark_tail_level`]).
fn ink_level(histogram: &[u64; 256]) -> Option<u8> {
    match otsu(histogram) {
        Some(split) if split.has_real_contrast() => Some(split.level),
        _ => dark_tail_level(histogram),
    }
}

/// Otsu fails when ink is a tiny fraction of the page (one short stroke on a big scan): the
/// between-class variance is then larger for a cut through the paper's noise than for the cut
/// isolating the ink, and [`Split::has_real_contrast`] rightly rejects that cut. This looks for
/// the ink directly: the paper's median M and noise σ, estimated from the bright half of the
/// histogram (ink never reaches it), and the pixels more than [`TAIL_SIGMAS`]·σ (and at least
/// [`MIN_SEPARATION`] levels) below M. If there are at least [`MIN_TAIL_PIXELS`] of them (and a
/// millionth of the page), they are ink, and the level is midway between M and their mean, but
/// at least 4σ below M so that paper noise stays out.
fn dark_tail_level(histogram: &[u64; 256]) -> Option<u8> {
    let total: u64 = histogram.iter().sum();
    let quantile = |fraction: f64| {
        let wanted = (fraction * total as f64).ceil().max(1.0) as u64;
        let mut seen = 0;
        histogram
            .iter()
            .position(|&count| {
                seen += count;
                seen >= wanted
            })
            .unwrap_or(255) as f64
    };
    let median = quantile(0.5);
    let deviation = ((quantile(0.75) - median) / GAUSSIAN_UPPER_QUARTILE).max(MIN_PAPER_DEVIATION);
    let cut = median - (TAIL_SIGMAS * deviation).max(MIN_SEPARATION);
    if cut < 0.0 {
        return None;
    }
    let cut = cut.floor() as usize;
    let (count, sum) = histogram[..=cut]
        .iter()
        .enumerate()
        .fold((0u64, 0f64), |(count, sum), (value, &n)| {
            (count + n, sum + value as f64 * n as f64)
        });
    if count < MIN_TAIL_PIXELS.max(total / PAGE_PIXELS_PER_TAIL_PIXEL) {
        return None;
    }
    let ink_mean = sum / count as f64;
    let level = ((median + ink_mean) / 2.0).min(median - LEVEL_SIGMAS * deviation);
    Some(level.clamp(0.0, 254.0) as u8)
}

/// The upper quartile of a Gaussian lies this many σ above its median: (quartile − median) / it
/// estimates the paper's noise σ from the bright half of the histogram, which ink never reaches.
const GAUSSIAN_UPPER_QUARTILE: f64 = 0.674;

/// The paper's σ is at least half a gray level: levels are quantized, so a perfectly flat paper
/// still spreads by that much.
const MIN_PAPER_DEVIATION: f64 = 0.5;

/// The dark tail must also hold one pixel in a million of the page, so that on a huge scan a few
/// dust pixels are not taken for the drawing.
const PAGE_PIXELS_PER_TAIL_PIXEL: u64 = 1_000_000;

/// The tail's level is at least this many σ below the paper's median, so that paper noise stays
/// on the paper's side of it.
const LEVEL_SIGMAS: f64 = 4.0;

/// See [`dark_tail_level`]: paper noise essentially never reaches 6σ below the median (a
/// Gaussian: two pixels in a billion; uniform noise: never beyond 1.8σ).
const TAIL_SIGMAS: f64 = 6.0;

/// See [`dark_tail_level`]: the fewest pixels that make ink rather than a speck of dust (which
/// [`crate::raster::clean`] would remove anyway): a stroke 16 px long and 2 px wide.
const MIN_TAIL_PIXELS: u64 = 32;

/// Otsu's two classes of a histogram.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Split {
    /// The dark class is every value ≤ level.
    level: u8,
    dark_mean: f64,
    light_mean: f64,
    /// Square root of the weighted mean of the two class variances.
    within_deviation: f64,
}

impl Split {
    /// Whether the classes are two real populations (ink and paper) rather than one population
    /// cut in two: see [`MIN_SEPARATION`] and [`MIN_SEPARATION_TO_SPREAD`].
    fn has_real_contrast(&self) -> bool {
        let separation = self.light_mean - self.dark_mean;
        separation >= MIN_SEPARATION
            && separation >= MIN_SEPARATION_TO_SPREAD * self.within_deviation
    }
}

/// Otsu's method: the level maximising the between-class variance. `None` when all pixels
/// share one value (no split exists).
fn otsu(histogram: &[u64; 256]) -> Option<Split> {
    let total: u64 = histogram.iter().sum();
    let sum: f64 = histogram
        .iter()
        .enumerate()
        .map(|(value, &count)| value as f64 * count as f64)
        .sum();
    let (mut dark_count, mut dark_sum) = (0u64, 0f64);
    // The best between-class variance and the run of consecutive levels reaching it: when ink
    // and paper are separated by an empty gap, every level in the gap ties, and the middle of
    // the gap is the natural level (the first would put ink lighter by one level on the paper
    // side).
    let mut best: Option<(f64, u8, u8)> = None;
    for level in 0..255u8 {
        let count = histogram[usize::from(level)];
        dark_count += count;
        dark_sum += f64::from(level) * count as f64;
        let light_count = total - dark_count;
        if dark_count == 0 || light_count == 0 {
            continue;
        }
        let dark_mean = dark_sum / dark_count as f64;
        let light_mean = (sum - dark_sum) / light_count as f64;
        let between = dark_count as f64 * light_count as f64 * (light_mean - dark_mean).powi(2);
        match best {
            Some((best_between, first, last)) if between == best_between && last + 1 == level => {
                best = Some((best_between, first, level));
            }
            Some((best_between, ..)) if between <= best_between => {}
            _ => best = Some((between, level, level)),
        }
    }
    let (_, first, last) = best?;
    let level = ((u16::from(first) + u16::from(last)) / 2) as u8;
    let moments = |range: std::ops::RangeInclusive<usize>| {
        let (mut count, mut sum, mut squares) = (0f64, 0f64, 0f64);
        for value in range {
            let n = histogram[value] as f64;
            count += n;
            sum += n * value as f64;
            squares += n * (value * value) as f64;
        }
        let mean = sum / count;
        (count, mean, (squares / count - mean * mean).max(0.0))
    };
    let (dark_count, dark_mean, dark_variance) = moments(0..=usize::from(level));
    let (light_count, light_mean, light_variance) = moments(usize::from(level) + 1..=255);
    let within =
        (dark_count * dark_variance + light_count * light_variance) / (dark_count + light_count);
    Some(Split {
        level,
        dark_mean,
        light_mean,
        within_deviation: within.sqrt(),
    })
}

/// The paper level over a coarse grid of blocks, smoothed, for flat-field correction and for
/// Auto's decision. Built in one pass over the image, with one 256-bin histogram per block of a
/// single block row alive at a time.
struct Background {
    /// Block columns.
    columns: usize,
    /// Centres of the block columns (x) and rows (y), in pixel coordinates.
    column_centres: Vec<f32>,
    row_centres: Vec<f32>,
    /// Paper level of each block, row by row, inked blocks replaced (see
    /// [`replace_inked_blocks`]).
    levels: Vec<f32>,
    /// Median, minimum and maximum of `levels`.
    median: f32,
    min: f32,
    max: f32,
    /// Histogram of the whole page's oriented values, a by-product for Otsu.
    histogram: [u64; 256],
}

/// The histograms a block's pixels are counted in by turns ([`Background::estimate`]).
const HISTOGRAM_LANES: usize = 4;

/// Pixels are counted this many at a time, a span of one level at once ([`count_span`]).
const UNIFORM_SPAN: usize = 16;

/// Counts the pixels of `span` (at most [`UNIFORM_SPAN`] of them, values `^ flip`) in a block's
/// `lanes`. Paper is one level over most of a clean page: a span all of one level is counted in
/// one addition (16 pixels compared as one 128-bit word), the others pixel by pixel, lane by lane.
/// On the 12-megapixel page the background's instructions fell from 63 M to 31 M (callgrind); on
/// its scan-like JPEG, whose noise leaves few spans of one level, they rose from 63 M to 72 M.
#[inline]
fn count_span(span: &[u8], flip: u8, lanes: &mut [[u32; 256]; HISTOGRAM_LANES]) {
    if let Ok(bytes) = <[u8; UNIFORM_SPAN]>::try_from(span) {
        let first = bytes[0];
        if u128::from_ne_bytes(bytes) == u128::from_ne_bytes([first; UNIFORM_SPAN]) {
            lanes[0][usize::from(first ^ flip)] += UNIFORM_SPAN as u32;
            return;
        }
    }
    let mut groups = span.chunks_exact(HISTOGRAM_LANES);
    for group in &mut groups {
        for (lane, &value) in lanes.iter_mut().zip(group) {
            lane[usize::from(value ^ flip)] += 1;
        }
    }
    for &value in groups.remainder() {
        lanes[0][usize::from(value ^ flip)] += 1;
    }
}

impl Background {
    fn estimate(gray: &GrayImage, invert: bool) -> Self {
        let (width, height) = (gray.width() as usize, gray.height() as usize);
        let block_size = width
            .max(height)
            .div_ceil(BLOCKS_ALONG_LONG_SIDE)
            .max(MIN_BLOCK_SIZE);
        let columns = width.div_ceil(block_size);
        let rows = height.div_ceil(block_size);
        let centres = |count: usize, extent: usize| -> Vec<f32> {
            (0..count)
                .map(|i| {
                    let end = ((i + 1) * block_size).min(extent);
                    (i * block_size + end) as f32 / 2.0
                })
                .collect()
        };
        let mut raw_levels = Vec::with_capacity(columns * rows);
        let mut histogram = [0u64; 256];
        // Each block counts its pixels in HISTOGRAM_LANES histograms, a pixel's lane its place in
        // the row modulo the lanes, summed once the block is done: paper is one level over most
        // of a page, and a single histogram then waits on the last pixel's count before it can
        // add the next (a store forwarded to the next load, several cycles a pixel).
        let mut block_histograms = vec![[[0u32; 256]; HISTOGRAM_LANES]; columns];
        let mut block = [0u32; 256];
        // 255 - value for a byte.
        let flip = if invert { u8::MAX } else { 0 };
        let pixels = gray.as_raw();
        for block_row in 0..rows {
            for lanes in &mut block_histograms {
                for lane in lanes.iter_mut() {
                    lane.fill(0);
                }
            }
            let (top, bottom) = (
                block_row * block_size,
                ((block_row + 1) * block_size).min(height),
            );
            for y in top..bottom {
                let row = &pixels[y * width..(y + 1) * width];
                for (segment, lanes) in row.chunks(block_size).zip(&mut block_histograms) {
                    let mut spans = segment.chunks_exact(UNIFORM_SPAN);
                    for span in &mut spans {
                        count_span(span, flip, lanes);
                    }
                    count_span(spans.remainder(), flip, lanes);
                }
            }
            for lanes in &block_histograms {
                for (level, count) in block.iter_mut().enumerate() {
                    *count = lanes.iter().map(|lane| lane[level]).sum();
                }
                for (total, &count) in histogram.iter_mut().zip(block.iter()) {
                    *total += u64::from(count);
                }
                raw_levels.push(percentile(&block, BACKGROUND_PERCENTILE));
            }
        }
        let levels = replace_inked_blocks(&raw_levels, columns, rows);
        let mut sorted = levels.clone();
        sorted.sort_by(f32::total_cmp);
        Self {
            columns,
            column_centres: centres(columns, width),
            row_centres: centres(rows, height),
            median: sorted[sorted.len() / 2],
            min: sorted[0],
            max: sorted[sorted.len() - 1],
            levels,
            histogram,
        }
    }

    /// The paper level of every pixel of row `y`: interpolated bilinearly between block
    /// centres (see [`segment`]) and floored at `floor`. Walks the column segments in order, so
    /// the cost is a multiply-add a pixel.
    fn row_levels(&self, y: usize, floor: f32, levels: &mut [f32]) {
        let (upper, lower, vertical) = segment(&self.row_centres, y as f32 + 0.5);
        let level_at = |column: usize| {
            let a = self.levels[upper * self.columns + column];
            let b = self.levels[lower * self.columns + column];
            a + (b - a) * vertical
        };
        if self.columns < 2 {
            levels.fill(level_at(0).max(floor));
            return;
        }
        let mut x = 0;
        for first in 0..self.columns - 1 {
            let (left, right) = (self.column_centres[first], self.column_centres[first + 1]);
            let (left_level, right_level) = (level_at(first), level_at(first + 1));
            let slope = (right_level - left_level) / (right - left);
            // This segment serves the pixels whose centre is left of the next centre (the last
            // one serves the rest of the row), as `segment` would pick.
            let end = if first + 2 == self.columns {
                levels.len()
            } else {
                ((right - 0.5).ceil().max(0.0) as usize).min(levels.len())
            };
            let start = x.min(end);
            let start_level = left_level + slope * (start as f32 + 0.5 - left);
            for (offset, level) in levels[start..end].iter_mut().enumerate() {
                // Through i32: integer → float conversion only vectorizes from 32-bit signed.
                *level = (start_level + slope * (offset as i32 as f32)).max(floor);
            }
            x = x.max(end);
        }
    }
}

/// The pair of consecutive centres used for `position` and its weight on the second: the pair
/// around it, or the outermost pair, extrapolated linearly, for the half block beyond the outer
/// centres (so a gradient keeps its slope up to the page edge). One centre: weight 0.
fn segment(centres: &[f32], position: f32) -> (usize, usize, f32) {
    if centres.len() < 2 {
        return (0, 0, 0.0);
    }
    let first = centres
        .iter()
        .rposition(|&centre| centre <= position)
        .unwrap_or(0)
        .min(centres.len() - 2);
    let t = (position - centres[first]) / (centres[first + 1] - centres[first]);
    (first, first + 1, t)
}

/// The smallest value with at least `fraction` of the counts at or below it.
fn percentile(histogram: &[u32; 256], fraction: f64) -> f32 {
    let total: u64 = histogram.iter().map(|&count| u64::from(count)).sum();
    let wanted = (fraction * total as f64).ceil().max(1.0) as u64;
    let mut seen = 0u64;
    for (value, &count) in histogram.iter().enumerate() {
        seen += u64::from(count);
        if seen >= wanted {
            return value as f32;
        }
    }
    255.0
}

/// Replaces the blocks that ink fills (a dense hatch, a large dot) by the median of their 3×3
/// neighbourhood. Such a block reads far darker than its neighbours; lighting varies smoothly, so
/// a block darker than [`INKED_BLOCK_FRACTION`] of its neighbourhood's median is not paper.
/// Other blocks keep their own level: a blanket median filter would bend gradients at the page
/// edges, where the window is one-sided.
fn replace_inked_blocks(levels: &[f32], columns: usize, rows: usize) -> Vec<f32> {
    let mut filtered = Vec::with_capacity(levels.len());
    let mut window = Vec::with_capacity(9);
    for row in 0..rows {
        for column in 0..columns {
            window.clear();
            for r in row.saturating_sub(1)..=(row + 1).min(rows - 1) {
                for c in column.saturating_sub(1)..=(column + 1).min(columns - 1) {
                    window.push(levels[r * columns + c]);
                }
            }
            window.sort_by(f32::total_cmp);
            // The upper median for an even count: paper is the bright side.
            let median = window[window.len() / 2];
            let level = levels[row * columns + column];
            filtered.push(if level < INKED_BLOCK_FRACTION * median {
                median
            } else {
                level
            });
        }
    }
    filtered
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::test_random::SplitMix64;
    use image::Luma;

    /// Uniform noise in -amplitude..=amplitude.
    fn noise(random: &mut SplitMix64, amplitude: i32) -> i32 {
        (random.next_u64() % (2 * amplitude as u64 + 1)) as i32 - amplitude
    }

    /// A page of `reflectance` (paper 0.9, ink 0.15 where `ink` holds) under `illumination`, with
    /// a little sensor noise.
    fn photograph(
        width: u32,
        height: u32,
        ink: &Bitmap,
        illumination: impl Fn(u32, u32) -> f64,
        seed: u64,
    ) -> GrayImage {
        let mut random = SplitMix64::new(seed);
        GrayImage::from_fn(width, height, |x, y| {
            let reflectance = if ink.get(x as usize, y as usize) {
                0.15
            } else {
                0.9
            };
            let value = 255.0 * reflectance * illumination(x, y);
            Luma([(value.round() as i32 + noise(&mut random, 3)).clamp(0, 255) as u8])
        })
    }

    /// Options for dark ink on light paper, thresholded by `method`.
    fn not_inverted(method: ThresholdMethod) -> BinarizeOptions {
        BinarizeOptions {
            method,
            invert: false,
        }
    }

    /// Options for light ink on dark paper, thresholded by `method`.
    fn inverted(method: ThresholdMethod) -> BinarizeOptions {
        BinarizeOptions {
            method,
            invert: true,
        }
    }

    /// A 3 px horizontal stroke and a 2 px diagonal one.
    fn drawing(width: u32, height: u32) -> Bitmap {
        let mut ink = Bitmap::new(width as usize, height as usize);
        for x in 8..width as usize - 8 {
            for y in 30..33 {
                ink.set(x, y, true);
            }
            let y = 10 + x * (height as usize - 20) / width as usize;
            ink.set(x, y, true);
            ink.set(x, y + 1, true);
        }
        ink
    }

    #[test]
    fn otsu_separates_two_levels() {
        let gray = GrayImage::from_fn(20, 10, |x, _| Luma([if x < 5 { 40 } else { 200 }]));
        let result = binarize(&gray, &not_inverted(ThresholdMethod::Otsu));
        let MethodUsed::Otsu { level } = result.method_used else {
            panic!("{:?}", result.method_used)
        };
        assert!((40..200).contains(&level), "level {level}");
        for y in 0..10 {
            for x in 0..20 {
                assert_eq!(result.mask.get(x, y), x < 5, "({x}, {y})");
            }
        }
        // The level is in the middle of the empty gap between the two levels.
        assert_eq!(level, (40 + 199) / 2);
        // Evenly lit: Auto takes the same decision.
        let auto = binarize(&gray, &BinarizeOptions::default());
        assert_eq!(auto, result);
    }

    #[test]
    fn auto_recovers_a_drawing_under_a_strong_gradient_where_otsu_fails() {
        let (width, height) = (256, 96);
        let ink = drawing(width, height);
        // Light falls from full on the left to a quarter on the right: the paper on the right
        // (≈ 57) ends up darker than the ink on the left (≈ 38 … 60).
        let gray = photograph(
            width,
            height,
            &ink,
            |x, _| 1.0 - 0.75 * f64::from(x) / f64::from(width),
            1,
        );
        let auto = binarize(&gray, &BinarizeOptions::default());
        assert_eq!(auto.method_used, MethodUsed::Adaptive);
        assert_eq!(auto.mask, ink, "Auto missed ink or took paper for ink");

        let otsu = binarize(&gray, &not_inverted(ThresholdMethod::Otsu));
        let wrong = otsu
            .mask
            .as_bytes()
            .iter()
            .zip(ink.as_bytes())
            .filter(|(a, b)| a != b)
            .count();
        assert!(
            wrong > 1000,
            "Otsu alone should fail here, but only {wrong} pixels are wrong"
        );
    }

    #[test]
    fn vignetting_is_corrected_too() {
        let (width, height) = (200, 160);
        let ink = drawing(width, height);
        let vignette = |x: u32, y: u32| {
            let dx = f64::from(x) / f64::from(width) - 0.5;
            let dy = f64::from(y) / f64::from(height) - 0.5;
            // Corners at 45% of the centre's light, as in a phone photograph.
            1.0 - 1.1 * (dx * dx + dy * dy)
        };
        let gray = photograph(width, height, &ink, vignette, 2);
        let auto = binarize(&gray, &BinarizeOptions::default());
        assert_eq!(auto.method_used, MethodUsed::Adaptive);
        assert_eq!(auto.mask, ink);
    }

    #[test]
    fn an_evenly_lit_drawing_uses_otsu_and_adaptive_agrees() {
        let (width, height) = (200, 80);
        let ink = drawing(width, height);
        let gray = photograph(width, height, &ink, |_, _| 1.0, 3);
        let auto = binarize(&gray, &BinarizeOptions::default());
        assert!(
            matches!(auto.method_used, MethodUsed::Otsu { .. }),
            "{:?}",
            auto.method_used
        );
        assert_eq!(auto.mask, ink);
        let adaptive = binarize(&gray, &not_inverted(ThresholdMethod::Adaptive));
        assert_eq!(adaptive.method_used, MethodUsed::Adaptive);
        assert_eq!(adaptive.mask, ink);
    }

    #[test]
    fn blank_pages_give_an_empty_mask_not_noise() {
        let mut random = SplitMix64::new(4);
        let flat = GrayImage::from_pixel(120, 90, Luma([235]));
        let noisy = GrayImage::from_fn(120, 90, |_, _| Luma([(230 + noise(&mut random, 6)) as u8]));
        let shaded = GrayImage::from_fn(300, 90, |x, _| {
            Luma([(240.0 - 0.5 * f64::from(x)) as u8 + noise(&mut random, 3).unsigned_abs() as u8])
        });
        let black = GrayImage::from_pixel(40, 30, Luma([0]));
        for (name, gray) in [
            ("flat", &flat),
            ("noisy", &noisy),
            ("shaded", &shaded),
            ("black", &black),
        ] {
            for method in [
                ThresholdMethod::Auto,
                ThresholdMethod::Otsu,
                ThresholdMethod::Adaptive,
            ] {
                for invert in [false, true] {
                    let result = binarize(gray, &BinarizeOptions { method, invert });
                    assert_eq!(
                        result.mask.count_ink(),
                        0,
                        "{name} {method:?} invert {invert}"
                    );
                    assert_eq!(result.method_used, MethodUsed::Blank, "{name} {method:?}");
                }
            }
        }
        // A fixed level is applied as given, even on a blank page.
        let fixed = binarize(&flat, &not_inverted(ThresholdMethod::Fixed(240)));
        assert_eq!(fixed.mask.count_ink(), 120 * 90);
        // No pixels at all.
        let empty = binarize(&GrayImage::new(0, 5), &BinarizeOptions::default());
        assert_eq!((empty.mask.width(), empty.mask.height()), (0, 5));
    }

    #[test]
    fn a_single_short_stroke_on_a_large_page_is_found() {
        // 150 ink pixels in 800 000: Otsu alone cuts through the paper noise instead.
        let (width, height) = (1000, 800);
        let mut ink = Bitmap::new(width as usize, height as usize);
        for x in 300..350 {
            for y in 400..403 {
                ink.set(x, y, true);
            }
        }
        // Paper 230 and ink 40, with noise of ±6 levels.
        let mut random = SplitMix64::new(8);
        let gray = GrayImage::from_fn(width, height, |x, y| {
            let value = if ink.get(x as usize, y as usize) {
                40
            } else {
                230
            };
            Luma([(value + noise(&mut random, 6)) as u8])
        });
        let mut histogram = [0u64; 256];
        for pixel in gray.pixels() {
            histogram[usize::from(pixel[0])] += 1;
        }
        assert!(
            !otsu(&histogram).unwrap().has_real_contrast(),
            "Otsu alone should fail here"
        );
        for method in [
            ThresholdMethod::Auto,
            ThresholdMethod::Otsu,
            ThresholdMethod::Adaptive,
        ] {
            let result = binarize(&gray, &not_inverted(method));
            assert_eq!(result.mask, ink, "{method:?}");
        }
        // A couple of dust specks on a blank page are not ink.
        let mut dust = Bitmap::new(width as usize, height as usize);
        dust.set(10, 10, true);
        dust.set(500, 20, true);
        let gray = photograph(width, height, &dust, |_, _| 1.0, 9);
        let result = binarize(&gray, &BinarizeOptions::default());
        assert_eq!(result.method_used, MethodUsed::Blank);
    }

    #[test]
    fn invert_reads_light_ink_on_dark_paper() {
        let (width, height) = (256, 96);
        let ink = drawing(width, height);
        let dark_on_light = photograph(width, height, &ink, |_, _| 1.0, 5);
        let mut light_on_dark = dark_on_light.clone();
        for pixel in light_on_dark.pixels_mut() {
            pixel[0] = 255 - pixel[0];
        }
        for method in [
            ThresholdMethod::Auto,
            ThresholdMethod::Otsu,
            ThresholdMethod::Adaptive,
        ] {
            let options = inverted(method);
            let result = binarize(&light_on_dark, &options);
            assert_eq!(result.mask, ink, "{method:?}");
            // Without invert, the paper would be the ink.
            let wrong = binarize(&light_on_dark, &not_inverted(method));
            assert_ne!(wrong.mask, ink, "{method:?}");
        }
        // Levels are reported in the input's gray values.
        let otsu = binarize(&light_on_dark, &inverted(ThresholdMethod::Otsu));
        let MethodUsed::Otsu { level } = otsu.method_used else {
            panic!()
        };
        assert!(level > 60 && level < 200, "level {level}");
        let fixed = binarize(&light_on_dark, &inverted(ThresholdMethod::Fixed(128)));
        assert_eq!(fixed.mask, ink);
        assert_eq!(fixed.method_used, MethodUsed::Fixed { level: 128 });
    }

    #[test]
    fn a_block_filled_with_ink_does_not_fool_the_background() {
        // A solid square covering 2×2 whole blocks, on an evenly lit page: the median filter keeps the
        // paper estimate, Auto stays with Otsu and the square stays ink.
        let (width, height) = (384, 256);
        let mut ink = drawing(width, height);
        for y in 96..136 {
            for x in 192..232 {
                ink.set(x, y, true);
            }
        }
        let gray = photograph(width, height, &ink, |_, _| 1.0, 6);
        for method in [ThresholdMethod::Auto, ThresholdMethod::Adaptive] {
            let result = binarize(&gray, &not_inverted(method));
            assert_eq!(result.mask, ink, "{method:?}");
        }
    }

    #[test]
    fn row_levels_interpolate_between_block_centres() {
        // Irregular sizes: a partial last block in both directions.
        let gray = GrayImage::from_fn(150, 70, |x, y| Luma([(60 + x + y / 2) as u8]));
        let background = Background::estimate(&gray, false);
        assert_eq!(background.column_centres.len(), 10);
        let mut levels = vec![0f32; 150];
        for y in [0, 9, 35, 69] {
            background.row_levels(y, 1.0, &mut levels);
            let (upper, lower, vertical) = segment(&background.row_centres, y as f32 + 0.5);
            for (x, &level) in levels.iter().enumerate() {
                let (left, right, t) = segment(&background.column_centres, x as f32 + 0.5);
                let at = |column: usize| {
                    let a = background.levels[upper * background.columns + column];
                    let b = background.levels[lower * background.columns + column];
                    a + (b - a) * vertical
                };
                let expected = at(left) + (at(right) - at(left)) * t;
                assert!(
                    (level - expected).abs() < 1e-3,
                    "({x}, {y}): {level} vs {expected}"
                );
            }
        }
        // The estimate follows the gradient (the 90th percentile sits on the bright side of
        // each block, a constant few levels up for a linear gradient).
        background.row_levels(35, 1.0, &mut levels);
        for (x, &level) in levels.iter().enumerate() {
            let truth = (60 + x + 35 / 2) as f32;
            assert!(
                (level - truth - 6.0).abs() <= 4.0,
                "x {x}: {level} vs {truth}"
            );
        }
    }

    #[test]
    fn spans_are_counted_as_pixel_by_pixel() {
        let uniform = [200u8; UNIFORM_SPAN];
        let mut mixed = uniform;
        mixed[9] = 7;
        let short = [1u8, 2, 3, 200, 200];
        for flip in [0, u8::MAX] {
            let mut lanes = [[0u32; 256]; HISTOGRAM_LANES];
            let mut expected = [0u32; 256];
            for span in [&uniform[..], &mixed[..], &short[..]] {
                count_span(span, flip, &mut lanes);
                for &value in span {
                    expected[usize::from(value ^ flip)] += 1;
                }
            }
            let counted: Vec<u32> = (0..256)
                .map(|level| lanes.iter().map(|lane| lane[level]).sum())
                .collect();
            assert_eq!(counted, expected.to_vec());
        }
    }

    #[test]
    fn bytes_round_to_nearest() {
        for (value, byte) in [
            (0.0, 0),
            (0.49, 0),
            (0.51, 1),
            (1.5, 2),
            (2.5, 2),
            (127.3, 127),
            (254.6, 255),
            (255.0, 255),
        ] {
            assert_eq!(round_to_byte(value), byte, "{value}");
        }
    }

    #[test]
    fn percentile_and_median_filter() {
        let mut histogram = [0u32; 256];
        histogram[10] = 5;
        histogram[200] = 95;
        assert_eq!(percentile(&histogram, 0.9), 200.0);
        assert_eq!(percentile(&histogram, 0.05), 10.0);
        assert_eq!(percentile(&[0; 256], 0.9), 255.0);
        // One dark block among paper is replaced; a gradient passes through, edges included.
        let levels = [200.0, 200.0, 200.0, 200.0, 20.0, 200.0, 200.0, 200.0, 200.0];
        assert_eq!(replace_inked_blocks(&levels, 3, 3)[4], 200.0);
        let gradient = [
            100.0, 110.0, 120.0, 100.0, 110.0, 120.0, 100.0, 110.0, 120.0,
        ];
        assert_eq!(replace_inked_blocks(&gradient, 3, 3), gradient);
        // Interpolation segments, with linear extrapolation beyond the outer centres.
        let centres = [8.0, 24.0, 36.0];
        assert_eq!(segment(&centres, 16.0), (0, 1, 0.5));
        assert_eq!(segment(&centres, 0.5), (0, 1, -0.46875));
        assert_eq!(segment(&centres, 39.5), (1, 2, 1.2916666));
        assert_eq!(segment(&[5.0], 3.0), (0, 0, 0.0));
    }
}
