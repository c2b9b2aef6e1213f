//! Mask cleaning: stroke width from run lengths, then speck removal and pinhole filling by
//! run-length connected-component labelling (union–find over runs, as in K. Wu, E. Otoo and
//! K. Suzuki, "Optimizing two-pass connected-component labeling algorithms", Pattern Analysis
//! and Applications 12, 2009), with size limits derived from the stroke width.
//!
//! Everything here works on runs (maximal horizontal stretches of equal pixels), so time and
//! memory follow the number of runs, not of pixels: a 12 MP page of line art has a few hundred
//! thousand runs, and no full-image buffer is allocated besides the mask itself.

use crate::geometry::UnionFind;
use crate::raster::bitmap::Bitmap;

/// What [`clean`] changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CleanReport {
    /// Ink components removed as specks.
    pub specks_removed: usize,
    /// Background components filled as pinholes.
    pub holes_filled: usize,
}

/// A speck is an ink component smaller than this fraction of the area of a disk one stroke
/// width across: a disk half a pen width across. DECISION: a dot drawn on purpose is at least a
/// pen width across, but on a page of nothing but dots the pen is measured on the dots
/// themselves, up to twice too wide (a disc of diameter D reads D/√2 at its middle row, and dots
/// are 1–3 pen widths), and a small dot binarizes thin: on the benchmark such dots keep 0.39–0.46
/// of the measured pen's disk, and half of it erased them. Paper texture, dust and JPEG ringing
/// leave specks of a pixel or a few; the benchmark's 216 JPEG scans and the samples' three leave
/// none at all after thresholding (no ink component away from the drawing).
const SPECK_DISK_FRACTION: f64 = 0.25;

/// A pinhole is an enclosed background component smaller than this fraction of the same disk.
/// Pinholes come from pen skips, paper texture and strokes that nearly touch; they would thin
/// into tiny loops. A hole drawn on purpose (the inside of a small "o") is at least about a pen
/// width across, so a full disk or more, and is kept.
const PINHOLE_DISK_FRACTION: f64 = 0.5;

/// Lower bound of both limits, in pixels: whatever the stroke width, lone pixels of ink and
/// one-pixel holes are noise (a limit of 2 removes components of area 1).
const MIN_LIMIT_AREA: f64 = 2.0;

/// Bins per pixel of the stroke width histogram: the estimate's resolution is 1/8 px.
const WIDTH_BINS_PER_PIXEL: f64 = 8.0;

/// Widths beyond this many pixels share the last bin (no line drawing has wider strokes).
const MAX_MEASURED_WIDTH: f64 = 512.0;

/// The vertical walk from a run's middle stops after this many times the run's length: the
/// local width h·v/√(h² + v²) is then within 1% of h, and the walk along a long vertical stroke
/// stays proportional to its width instead of its length.
const VERTICAL_WALK_LIMIT: usize = 8;

/// The typical pen width in pixels, or 0.0 for an empty mask.
///
/// For every horizontal ink run (length h), the vertical run through its middle pixel (length
/// v) is measured, and h·v/√(h² + v²) is the width of a straight band crossing the run: a band
/// of width w at angle θ has h = w/sin θ and v = w/cos θ, so the formula gives w at every
/// angle (the shorter of h and v alone would read up to √2·w on diagonals). The result is the
/// median of these local widths weighted by h, that is over ink pixels, so horizontal and
/// vertical strokes count alike, and specks, junctions and stroke ends (a minority of the ink)
/// do not move it. Only ink is touched: one pass over each row's runs plus short vertical walks.
pub fn estimate_stroke_width(mask: &Bitmap) -> f64 {
    let (width, height) = (mask.width(), mask.height());
    let pixels = mask.as_bytes();
    let bins = (MAX_MEASURED_WIDTH * WIDTH_BINS_PER_PIXEL) as usize + 1;
    let mut histogram = vec![0u64; bins];
    let mut total = 0u64;
    for y in 0..height {
        let row = &pixels[y * width..(y + 1) * width];
        for_each_run(row, true, |start, end| {
            let across = end - start;
            let middle = start + across / 2;
            let limit = VERTICAL_WALK_LIMIT * across;
            let ink = |y: usize| pixels[y * width + middle] != 0;
            let up = (1..=limit.min(y)).take_while(|&step| ink(y - step)).count();
            let down = (1..=limit.min(height - 1 - y))
                .take_while(|&step| ink(y + step))
                .count();
            let (h, v) = (across as f64, (1 + up + down) as f64);
            let local_width = h * v / (h * h + v * v).sqrt();
            let bin = ((local_width * WIDTH_BINS_PER_PIXEL).round() as usize).min(bins - 1);
            histogram[bin] += across as u64;
            total += across as u64;
        });
    }
    if total == 0 {
        return 0.0;
    }
    // The weighted median: the first bin holding the middle ink pixel.
    let middle = total.div_ceil(2);
    let mut seen = 0;
    for (bin, &count) in histogram.iter().enumerate() {
        seen += count;
        if seen >= middle {
            return bin as f64 / WIDTH_BINS_PER_PIXEL;
        }
    }
    unreachable!("the histogram holds `total` pixels")
}

/// Removes specks and fills pinholes, in place, with limits derived from `stroke_width` (as
/// measured by [`estimate_stroke_width`]; a non-finite or negative width counts as 0):
///
/// - ink components (8-connected) smaller than a quarter of the area of a disk one stroke width
///   across (π·w²/16; at least 2 px, so lone pixels always go) are erased;
/// - then background components (4-connected, the complement of 8-connected ink) that do not
///   touch the image border and are smaller than half that disk (π·w²/8) are filled.
///
/// Specks go first so that a speck inside a hole does not split it into smaller "holes".
pub fn clean(mask: &mut Bitmap, stroke_width: f64) -> CleanReport {
    let stroke_width = if stroke_width.is_finite() {
        stroke_width.max(0.0)
    } else {
        0.0
    };
    let disk = std::f64::consts::PI / 4.0 * stroke_width * stroke_width;
    let speck_limit = (SPECK_DISK_FRACTION * disk).max(MIN_LIMIT_AREA);
    let pinhole_limit = (PINHOLE_DISK_FRACTION * disk).max(MIN_LIMIT_AREA);
    let specks_removed = replace_small_components(mask, true, speck_limit);
    let holes_filled = replace_small_components(mask, false, pinhole_limit);
    CleanReport {
        specks_removed,
        holes_filled,
    }
}

/// Flips every component of `ink` pixels smaller than `limit` (background components touching
/// the border are never flipped) and returns how many were flipped.
fn replace_small_components(mask: &mut Bitmap, ink: bool, limit: f64) -> usize {
    let connectivity = if ink {
        Connectivity::Eight
    } else {
        Connectivity::Four
    };
    let mut labels = RunLabels::new(mask, ink, connectivity);
    // A border component is never small, whatever the limit (an absurd pen width makes it
    // infinite).
    let is_small = |area: u32| area != TOUCHES_BORDER && f64::from(area) < limit;
    let flipped = labels.roots().filter(|&(_, area)| is_small(area)).count();
    if flipped == 0 || mask.width() == 0 {
        return flipped;
    }
    // Runs are enumerated again in the same order, so the k-th run is run k of the labelling.
    let width = mask.width();
    let mut run = 0;
    let mut runs = Vec::new();
    for row in mask.as_bytes_mut().chunks_exact_mut(width) {
        runs.clear();
        for_each_run(row, ink, |start, end| runs.push((start, end)));
        for &(start, end) in &runs {
            if is_small(labels.area(run)) {
                row[start..end].fill(u8::from(!ink));
            }
            run += 1;
        }
    }
    flipped
}

/// Pixel adjacency for components.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Connectivity {
    /// Edge neighbours only.
    Four,
    /// Edge and corner neighbours.
    Eight,
}

/// Connected components of the runs of one pixel value, by union–find over run indices (runs
/// numbered row by row, left to right).
pub(crate) struct RunLabels {
    /// The components: one set of runs each.
    sets: UnionFind,
    /// At a root, the component's area in pixels; [`TOUCHES_BORDER`] for a background
    /// component that reaches the image border (never a hole).
    area: Vec<u32>,
}

/// The area of a component that touches the image border (saturating: it stays so).
const TOUCHES_BORDER: u32 = u32::MAX;

impl RunLabels {
    /// Labels the runs of `ink` (or background) pixels. Background components touching the
    /// border get the area [`TOUCHES_BORDER`].
    pub(crate) fn new(mask: &Bitmap, ink: bool, connectivity: Connectivity) -> Self {
        let (width, height) = (mask.width(), mask.height());
        // Two runs in consecutive rows touch when their column ranges overlap, or, with
        // 8-connectivity, when they meet at a corner.
        let reach = match connectivity {
            Connectivity::Four => 0,
            Connectivity::Eight => 1,
        };
        let mut labels = Self {
            sets: UnionFind::default(),
            area: Vec::new(),
        };
        // (start, end, run index) of the previous and the current row.
        let mut previous: Vec<(usize, usize, u32)> = Vec::new();
        let mut current: Vec<(usize, usize, u32)> = Vec::new();
        for (y, row) in mask
            .as_bytes()
            .chunks_exact(width.max(1))
            .take(height)
            .enumerate()
        {
            current.clear();
            let mut first_candidate = 0;
            for_each_run(row, ink, |start, end| {
                let index = labels
                    .sets
                    .push()
                    .expect("fewer than 2³² runs (a bitmap under 8 gigapixels)");
                let on_border = !ink && (y == 0 || y + 1 == height || start == 0 || end == width);
                labels.area.push(if on_border {
                    TOUCHES_BORDER
                } else {
                    (end - start) as u32
                });
                // Runs of the previous row ending before this one (and so before every later
                // one) can be skipped for good; the last overlapping one may overlap the next
                // run too, so the scan restarts from it.
                while first_candidate < previous.len()
                    && previous[first_candidate].1 + reach <= start
                {
                    first_candidate += 1;
                }
                for &(above_start, _, above) in &previous[first_candidate..] {
                    if above_start >= end + reach {
                        break;
                    }
                    labels.union(index, above);
                }
                current.push((start, end, index));
            });
            std::mem::swap(&mut previous, &mut current);
        }
        labels
    }

    /// Merges the components of two runs; the root with the lower index stays root, so roots are
    /// the first run of their component in scan order (deterministic).
    fn union(&mut self, a: u32, b: u32) {
        let (a, b) = (self.sets.find(a), self.sets.find(b));
        if a == b {
            return;
        }
        let (root, child) = (a.min(b), a.max(b));
        self.sets.attach(child, root);
        self.area[root as usize] =
            self.area[root as usize].saturating_add(self.area[child as usize]);
    }

    /// The area of the component of run `run` ([`TOUCHES_BORDER`] for a border background
    /// component).
    pub(crate) fn area(&mut self, run: usize) -> u32 {
        let root = self.sets.find(run as u32);
        self.area[root as usize]
    }

    /// Every component, as (root run, area).
    pub(crate) fn roots(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        (0..self.sets.len() as u32)
            .filter(|&run| self.sets.is_root(run))
            .map(|run| (run, self.area[run as usize]))
    }
}

/// Number of connected components of ink (`ink`) or background pixels. Background components
/// touching the border are counted too; see [`count_holes`] for the enclosed ones.
pub(crate) fn count_components(mask: &Bitmap, ink: bool, connectivity: Connectivity) -> usize {
    RunLabels::new(mask, ink, connectivity).roots().count()
}

/// Number of holes: 4-connected background components not touching the image border.
pub(crate) fn count_holes(mask: &Bitmap) -> usize {
    RunLabels::new(mask, false, Connectivity::Four)
        .roots()
        .filter(|&(_, area)| area != TOUCHES_BORDER)
        .count()
}

/// Calls `visit(start, end)` for each maximal run of ink (nonzero) bytes, or of background
/// (zero) bytes when `ink` is false, left to right; `end` is exclusive.
#[inline]
pub(crate) fn for_each_run(row: &[u8], ink: bool, mut visit: impl FnMut(usize, usize)) {
    let mut position = 0;
    while position < row.len() {
        let Some(start) = find_byte(row, position, ink) else {
            return;
        };
        let end = find_byte(row, start + 1, !ink).unwrap_or(row.len());
        visit(start, end);
        position = end;
    }
}

/// The first position at or after `from` holding ink (nonzero) when `ink`, background (zero)
/// otherwise. Skips 16 bytes at a time: rows are mostly long runs of one value.
#[inline]
fn find_byte(row: &[u8], from: usize, ink: bool) -> Option<usize> {
    const ONES: u128 = u128::from_ne_bytes([0x01; 16]);
    const HIGHS: u128 = u128::from_ne_bytes([0x80; 16]);
    let mut position = from;
    while let Some(chunk) = row.get(position..position + 16) {
        let word = u128::from_ne_bytes(chunk.try_into().expect("16 bytes"));
        // Any nonzero byte: the word is nonzero. Any zero byte: the classic "has a zero byte"
        // test, (w − 0x01…01) & !w & 0x80…80 ≠ 0.
        let found = if ink {
            word != 0
        } else {
            word.wrapping_sub(ONES) & !word & HIGHS != 0
        };
        if found {
            break;
        }
        position += 16;
    }
    row.get(position..)?
        .iter()
        .position(|&byte| (byte != 0) == ink)
        .map(|offset| position + offset)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Sets the pixels whose centre is within `stroke_width / 2` of the segment from `from` to
    /// `to` (a stroke with round caps).
    pub(crate) fn draw_line(
        mask: &mut Bitmap,
        from: (f64, f64),
        to: (f64, f64),
        stroke_width: f64,
    ) {
        let (dx, dy) = (to.0 - from.0, to.1 - from.1);
        let length_squared = dx * dx + dy * dy;
        for y in 0..mask.height() {
            for x in 0..mask.width() {
                let (px, py) = (x as f64 + 0.5 - from.0, y as f64 + 0.5 - from.1);
                let t = ((px * dx + py * dy) / length_squared).clamp(0.0, 1.0);
                let (ex, ey) = (px - t * dx, py - t * dy);
                if (ex * ex + ey * ey).sqrt() <= stroke_width / 2.0 {
                    mask.set(x, y, true);
                }
            }
        }
    }

    #[test]
    fn runs_are_found_across_chunk_boundaries() {
        let mut row = vec![0u8; 70];
        for range in [3..5, 15..17, 31..33, 40..64, 69..70] {
            row[range].fill(1);
        }
        let mut ink = Vec::new();
        for_each_run(&row, true, |start, end| ink.push((start, end)));
        assert_eq!(ink, [(3, 5), (15, 17), (31, 33), (40, 64), (69, 70)]);
        let mut background = Vec::new();
        for_each_run(&row, false, |start, end| background.push((start, end)));
        assert_eq!(background, [(0, 3), (5, 15), (17, 31), (33, 40), (64, 69)]);
        let mut none = Vec::new();
        for_each_run(&[], true, |start, end| none.push((start, end)));
        assert!(none.is_empty());
    }

    #[test]
    fn components_follow_the_connectivity() {
        let mask = Bitmap::from_grid(
            "
            #.#....
            .#...#.
            ....#.#
            ##...#.
            .......
            ",
        );
        assert_eq!(count_components(&mask, true, Connectivity::Eight), 3);
        assert_eq!(count_components(&mask, true, Connectivity::Four), 8);
        // The pixel at (1, 0) is cut off, but on the border; the one inside the diamond is a hole.
        assert_eq!(count_components(&mask, false, Connectivity::Four), 3);
        assert_eq!(count_holes(&mask), 1);
        let ring = Bitmap::from_grid(
            "
            .....
            .###.
            .#.#.
            .###.
            ",
        );
        assert_eq!(count_holes(&ring), 1);
        assert_eq!(count_components(&ring, false, Connectivity::Four), 2);
    }

    #[test]
    fn specks_go_and_short_strokes_stay() {
        let mut mask = Bitmap::from_grid(
            "
            ..............
            .#.........#..
            ..........##..
            ..####........
            ..####.....#..
            ..####........
            ........#.....
            .......##.....
            ",
        );
        // Stroke width 5: a speck is under a quarter of a 5-px disk, 4.9 px: areas 1, 3, 1, 3
        // go, the 12-px stroke stays.
        let report = clean(&mut mask, 5.0);
        assert_eq!(report.specks_removed, 4);
        assert_eq!(report.holes_filled, 0);
        assert_eq!(
            mask,
            Bitmap::from_grid(
                "
                ..............
                ..............
                ..............
                ..####........
                ..####........
                ..####........
                ..............
                ..............
                ",
            )
        );
    }

    #[test]
    fn a_small_dot_stays_where_the_pen_is_measured_on_bigger_dots() {
        // A page of nothing but dots, 1–3 pen widths across: the pen reads 3.12 px where it was
        // 1.95, and the smallest dot (2 px across) binarizes as 3 pixels (benchmark drawing
        // dots-thin-003 of seed 1). Half a disk (3.8 px) erased it; lone pixels still go.
        let mut mask = Bitmap::from_grid(
            "
            .........
            .##...#..
            ..#......
            .........",
        );
        let report = clean(&mut mask, 3.12);
        assert_eq!(report.specks_removed, 1);
        assert_eq!(mask.count_ink(), 3);
        assert!(mask.get(1, 1) && mask.get(2, 1) && mask.get(2, 2));
    }

    #[test]
    fn pinholes_are_filled_and_drawn_holes_kept() {
        let mut mask = Bitmap::from_grid(
            "
            ...................
            .#######...#######.
            .##.####...#.....#.
            .#######...#.....#.
            .###..##...#.....#.
            .#######...#######.
            ...................
            ",
        );
        // Stroke width 4: pinholes under half of a 4-px disk, 6.3 px, are filled; the ring's
        // 15-px hole stays, and so does the outside.
        let report = clean(&mut mask, 4.0);
        assert_eq!(report.holes_filled, 2);
        assert_eq!(report.specks_removed, 0);
        assert_eq!(
            mask,
            Bitmap::from_grid(
                "
                ...................
                .#######...#######.
                .#######...#.....#.
                .#######...#.....#.
                .#######...#.....#.
                .#######...#######.
                ...................
                ",
            )
        );
        // A notch open to the border is not a hole.
        let mut notched = Bitmap::from_grid(
            "
            #.###
            #####
            ",
        );
        let before = notched.clone();
        assert_eq!(clean(&mut notched, 4.0).holes_filled, 0);
        assert_eq!(notched, before);
    }

    #[test]
    fn a_bubble_closed_only_at_diagonal_corners_is_filled() {
        // Ink is 8-connected and paper 4-connected: the ring's two open corners touch only
        // diagonally, so they close it, and the 4-px bubble inside (under the 6.3-px limit of a
        // 4-px pen) is filled. The 10-px ring itself is no speck.
        let mut mask = Bitmap::from_grid(
            "
            ......
            .###..
            .#..#.
            .#..#.
            ..###.
            ......
            ",
        );
        let report = clean(&mut mask, 4.0);
        assert_eq!((report.specks_removed, report.holes_filled), (0, 1));
        assert_eq!(
            mask,
            Bitmap::from_grid(
                "
                ......
                .###..
                .####.
                .####.
                ..###.
                ......
                ",
            )
        );
    }

    #[test]
    fn a_speck_in_a_drawn_hole_goes_before_the_hole_is_measured() {
        // With a 4.6-px pen both limits are π·4.6²/8 = 8.3 px. The hole is 9 px, 8 around the
        // speck: measured with the speck it would be a pinhole and the whole "o" a blob.
        let mut mask = Bitmap::from_grid(
            "
            .......
            .#####.
            .#...#.
            .#.#.#.
            .#...#.
            .#####.
            .......
            ",
        );
        let report = clean(&mut mask, 4.6);
        assert_eq!((report.specks_removed, report.holes_filled), (1, 0));
        assert_eq!(
            mask,
            Bitmap::from_grid(
                "
                .......
                .#####.
                .#...#.
                .#...#.
                .#...#.
                .#####.
                .......
                ",
            )
        );
    }

    #[test]
    fn a_filled_corner_keeps_its_ink_and_loses_its_pinhole() {
        // Two 3-px strokes meeting at a corner, the corner blotted with ink and a 2-px pinhole
        // in the blot (a pen skip): the pinhole is filled, no ink is taken off the corner, and
        // the corner's open side (touching the border) is never a hole.
        let mut mask = Bitmap::from_grid(
            "
            ........
            .######.
            .######.
            .##..##.
            .######.
            .###....
            .###....
            .###....
            ",
        );
        let report = clean(&mut mask, 3.0);
        assert_eq!((report.specks_removed, report.holes_filled), (0, 1));
        assert_eq!(
            mask,
            Bitmap::from_grid(
                "
                ........
                .######.
                .######.
                .######.
                .######.
                .###....
                .###....
                .###....
                ",
            )
        );
    }

    #[test]
    fn degenerate_widths_and_masks_do_not_panic() {
        // A width that is no width is taken as 0: the diagonal pair (2 px) is no lone pixel and
        // stays. An absurdly wide pen makes it a speck.
        for (width, kept) in [
            (0.0, true),
            (-3.0, true),
            (f64::NAN, true),
            (f64::INFINITY, true),
            (1e300, false),
        ] {
            let mut mask = Bitmap::from_grid("#.\n.#");
            let report = clean(&mut mask, width);
            assert_eq!(report.specks_removed, usize::from(!kept), "width {width}");
            assert_eq!(mask.get(0, 0), kept, "width {width}");
        }
        let mut empty = Bitmap::new(0, 0);
        assert_eq!(clean(&mut empty, 3.0), CleanReport::default());
        assert_eq!(estimate_stroke_width(&empty), 0.0);
        assert_eq!(estimate_stroke_width(&Bitmap::new(10, 10)), 0.0);
        // Width 0: only lone pixels go.
        let mut mask = Bitmap::from_grid("#..##\n.....\n..#..");
        assert_eq!(clean(&mut mask, 0.0).specks_removed, 2);
        assert_eq!(mask, Bitmap::from_grid("...##\n.....\n....."));
    }

    #[test]
    fn stroke_width_is_measured_at_every_angle() {
        for stroke_width in [1.0, 2.0, 3.0, 5.0, 8.0, 13.0] {
            for (name, from, to) in [
                ("0°", (10.0, 60.0), (110.0, 60.0)),
                ("90°", (60.0, 10.0), (60.0, 110.0)),
                ("45°", (15.0, 15.0), (105.0, 105.0)),
                ("-30°", (10.0, 90.0), (110.0, 32.0)),
                ("70°", (40.0, 110.0), (76.0, 10.0)),
            ] {
                // Off the pixel grid, so that a band of integer width covers that many pixel
                // centres across instead of one more at exact ties.
                let off_grid = |(x, y): (f64, f64)| (x + 0.123, y + 0.123);
                let mut mask = Bitmap::new(120, 120);
                draw_line(&mut mask, off_grid(from), off_grid(to), stroke_width);
                let measured = estimate_stroke_width(&mask);
                assert!(
                    (measured - stroke_width).abs() <= 1.0,
                    "width {stroke_width} at {name}: measured {measured}"
                );
            }
        }
    }

    #[test]
    fn stroke_width_ignores_specks_and_mixed_orientations() {
        let mut mask = Bitmap::new(200, 200);
        draw_line(&mut mask, (20.0, 20.0), (180.0, 30.0), 6.0);
        draw_line(&mut mask, (30.0, 40.0), (40.0, 190.0), 6.0);
        draw_line(&mut mask, (60.0, 60.0), (190.0, 180.0), 6.0);
        // Noise: one lone pixel in every 7×7 cell away from the strokes.
        let mut specks = 0;
        for y in (3..200usize).step_by(7) {
            for x in (3..200usize).step_by(7) {
                let clear = (y.saturating_sub(1)..=y + 1)
                    .all(|j| (x - 1..=x + 1).all(|i| j >= 200 || i >= 200 || !mask.get(i, j)));
                if clear {
                    mask.set(x, y, true);
                    specks += 1;
                }
            }
        }
        assert!(specks > 500);
        let measured = estimate_stroke_width(&mask);
        assert!((measured - 6.0).abs() <= 1.0, "measured {measured}");
        let report = clean(&mut mask, measured);
        assert_eq!(report.specks_removed, specks);
        assert_eq!(count_components(&mask, true, Connectivity::Eight), 3);
    }
}
