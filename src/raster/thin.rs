//! Thinning: ink mask → 1-px, 8-connected skeleton with the same topology, by directional
//! parallel deletion of simple, non-end border pixels (A. Rosenfeld, "A characterization of
//! parallel thinning algorithms", Information and Control 29, 1975), tracking the border instead
//! of rescanning the image.
//!
//! Each pass has four sub-iterations, for the north, south, east and west borders. In each, every
//! ink pixel whose neighbour on that side is background is deleted if it is *simple* (deleting it
//! changes neither the 8-connected ink nor the 4-connected background: a 256-entry table computed
//! from that definition) and not an *end point* (exactly one ink neighbour, so strokes keep their
//! length). All decisions of a sub-iteration are taken on the state before it, then applied
//! together: the result does not depend on scan order, and Rosenfeld showed that deleting simple
//! border points of one side in parallel preserves topology. Zhang–Suen's two sub-iterations
//! erase 2×2 blocks entirely; these four cannot.
//!
//! Speed: only pixels whose 3×3 neighbourhood changed since they were last examined for a side
//! can change their verdict for it, so each side keeps a queue of such pixels, fed by the
//! neighbours of the pixels just deleted. The work follows the ink, not the page.

use crate::raster::bitmap::{Bitmap, NEIGHBOUR_OFFSETS};

/// Whether a pixel with this neighbourhood (the bit layout of [`Bitmap::neighbourhood`]:
/// bit k is neighbour k clockwise from north) is *simple*: its 8 neighbours hold exactly one
/// 8-connected component of ink, and exactly one 4-connected component of background that
/// touches the pixel's edge neighbours. Deleting a simple pixel preserves topology; an isolated
/// pixel and an interior pixel are not simple.
#[inline]
pub fn is_simple(neighbourhood: u8) -> bool {
    SIMPLE[usize::from(neighbourhood)]
}

/// [`is_simple`] for every neighbourhood, computed at compile time from the definition.
static SIMPLE: [bool; 256] = simple_table();

const fn simple_table() -> [bool; 256] {
    let mut table = [false; 256];
    let mut neighbourhood = 0;
    while neighbourhood < 256 {
        let ink = neighbourhood as u8;
        table[neighbourhood] = count_ring_components(ink, true, false) == 1
            && count_ring_components(!ink, false, true) == 1;
        neighbourhood += 1;
    }
    table
}

/// Components formed by the ring cells set in `cells` (the 8 neighbours, centre excluded), with
/// 8-adjacency (`eight`) or 4-adjacency between cells; with `touching_centre`, only components
/// holding an edge neighbour (N, E, S, W: 4-adjacent to the centre) count.
const fn count_ring_components(cells: u8, eight: bool, touching_centre: bool) -> u32 {
    const EDGE_NEIGHBOURS: u8 = 0b0101_0101;
    let mut seen = 0u8;
    let mut count = 0;
    let mut start = 0;
    while start < 8 {
        if cells & (1 << start) != 0 && seen & (1 << start) == 0 {
            // Flood fill from `start` until the component stops growing.
            let mut component = 1u8 << start;
            loop {
                let mut grown = component;
                let mut i = 0;
                while i < 8 {
                    if component & (1 << i) != 0 {
                        let mut j = 0;
                        while j < 8 {
                            if cells & (1 << j) != 0 && adjacent(i, j, eight) {
                                grown |= 1 << j;
                            }
                            j += 1;
                        }
                    }
                    i += 1;
                }
                if grown == component {
                    break;
                }
                component = grown;
            }
            seen |= component;
            if !touching_centre || component & EDGE_NEIGHBOURS != 0 {
                count += 1;
            }
        }
        start += 1;
    }
    count
}

/// Whether ring cells `i` and `j` are adjacent (8- or 4-adjacency, by their coordinates).
const fn adjacent(i: usize, j: usize, eight: bool) -> bool {
    let (xi, yi) = NEIGHBOUR_OFFSETS[i];
    let (xj, yj) = NEIGHBOUR_OFFSETS[j];
    let (dx, dy) = ((xi - xj).abs(), (yi - yj).abs());
    if eight {
        dx <= 1 && dy <= 1 && dx + dy > 0
    } else {
        dx + dy == 1
    }
}

/// The four sides, in the order of the sub-iterations: north, south, east, west. Opposite sides
/// alternate so that a thick stroke is pared evenly towards its centre line.
const SIDES: [usize; 4] = [0, 4, 2, 6];

/// Bit of a work byte that holds the pixel (the others are queue flags).
const INK: u8 = 1;

/// Bit of a work byte saying the pixel is in the queue of side `side` (0..4, as in [`SIDES`]).
const fn queued(side: usize) -> u8 {
    2 << side
}

/// The skeleton of `mask`: a subset of it, 1 pixel wide (no pixel is simple with more than one
/// ink neighbour), 8-connected, with the same ink components and holes. A stroke of width w
/// thins to its centre line, shortened by about w/2 at each end. See the module documentation.
pub fn thin(mask: &Bitmap) -> Bitmap {
    let (width, height) = (mask.width(), mask.height());
    if width == 0 || height == 0 {
        return mask.clone();
    }
    let (mut work, mut queues) = Work::framed(mask);
    let mut deletions = Vec::new();
    let mut spare = Vec::new();
    while queues.iter().any(|queue| !queue.is_empty()) {
        for side in 0..4 {
            // Decide on the state before this sub-iteration ...
            let candidates = std::mem::replace(&mut queues[side], std::mem::take(&mut spare));
            work.find_deletions(side, &candidates, &mut deletions);
            spare = candidates;
            spare.clear();
            // ... then delete all at once, and queue the neighbours whose verdicts may change.
            work.delete(&deletions, &mut queues);
        }
    }
    work.unframed()
}

/// The image being thinned: a copy of the mask framed by one pixel of background, so that
/// neighbours never need bounds checks. Bit 0 of a byte is ink ([`INK`]); bits 1..=4 are the
/// queue flags ([`queued`]), kept in the same bytes so that no further image-sized buffer is
/// needed.
struct Work {
    bytes: Vec<u8>,
    width: usize,
    height: usize,
    /// The length of a framed row: `width + 2`.
    stride: usize,
    /// The index offsets of the 8 neighbours, in [`NEIGHBOUR_OFFSETS`] order.
    offsets: [isize; 8],
    /// The index offsets of the neighbour on each side, in [`SIDES`] order.
    side_offsets: [isize; 4],
}

impl Work {
    /// The framed copy of `mask`, and every border pixel in the queue of each side it faces,
    /// flagged as queued.
    fn framed(mask: &Bitmap) -> (Self, [Vec<usize>; 4]) {
        let (width, height) = (mask.width(), mask.height());
        let stride = width + 2;
        let offsets = NEIGHBOUR_OFFSETS.map(|(dx, dy)| dx + dy * stride as isize);
        let mut work = Self {
            bytes: Vec::with_capacity(stride * (height + 2)),
            width,
            height,
            stride,
            offsets,
            side_offsets: SIDES.map(|k| offsets[k]),
        };
        // One pass over the page, each byte written once (zeroing the page first and then
        // copying the mask in wrote it twice, and the border was looked for in a pass of its
        // own): the top frame row and the first row's left frame byte, then each row with its
        // right frame byte and the next row's left one, then the bottom frame row. A row's
        // border pixels are queued once the row below it is in place.
        let mut queues: [Vec<usize>; 4] = Default::default();
        work.bytes.resize(stride + 1, 0);
        for (y, row) in mask.as_bytes().chunks_exact(width).enumerate() {
            let start = work.bytes.len();
            work.bytes.extend_from_slice(row);
            for cell in &mut work.bytes[start..] {
                *cell = u8::from(*cell != 0);
            }
            work.bytes.extend_from_slice(&[0, 0]);
            if y > 0 {
                work.queue_border(y, &mut queues);
            }
        }
        work.bytes.resize(stride * (height + 2), 0);
        work.queue_border(height, &mut queues);
        for (side, queue) in queues.iter().enumerate() {
            for &index in queue {
                work.bytes[index] |= queued(side);
            }
        }
        (work, queues)
    }

    /// Queues the border pixels of framed row `y` (1..=height) for each side they face; the rows
    /// above and below it must be in place.
    fn queue_border(&self, y: usize, queues: &mut [Vec<usize>; 4]) {
        let (width, side_offsets, work) = (self.width, self.side_offsets, &self.bytes);
        let row = y * self.stride;
        crate::raster::clean::for_each_run(&work[row + 1..row + 1 + width], true, |start, end| {
            for index in row + 1 + start..row + 1 + end {
                for (side, queue) in queues.iter_mut().enumerate() {
                    if work[index.wrapping_add_signed(side_offsets[side])] & INK == 0 {
                        queue.push(index);
                    }
                }
            }
        });
    }

    /// The candidates of sub-iteration `side` that are deleted: ink, facing that side, not an
    /// end point, and simple. Unflags them as queued for that side.
    fn find_deletions(&mut self, side: usize, candidates: &[usize], deletions: &mut Vec<usize>) {
        deletions.clear();
        for &index in candidates {
            self.bytes[index] &= !queued(side);
            if self.bytes[index] & INK == 0 {
                continue;
            }
            let neighbourhood = neighbourhood_at(&self.bytes, index, &self.offsets);
            let faces_side = neighbourhood & (1 << SIDES[side]) == 0;
            let end_point = neighbourhood.count_ones() <= 1;
            if faces_side && !end_point && is_simple(neighbourhood) {
                deletions.push(index);
            }
        }
    }

    /// Deletes `deletions` together, then queues their remaining ink neighbours, whose verdicts
    /// may have changed, for every side they now face.
    fn delete(&mut self, deletions: &[usize], queues: &mut [Vec<usize>; 4]) {
        let work = &mut self.bytes;
        for &index in deletions {
            work[index] &= !INK;
        }
        for &index in deletions {
            for &offset in &self.offsets {
                let neighbour = index.wrapping_add_signed(offset);
                if work[neighbour] & INK == 0 {
                    continue;
                }
                for (other_side, queue) in queues.iter_mut().enumerate() {
                    let open = work[neighbour.wrapping_add_signed(self.side_offsets[other_side])]
                        & INK
                        == 0;
                    if open && work[neighbour] & queued(other_side) == 0 {
                        work[neighbour] |= queued(other_side);
                        queue.push(neighbour);
                    }
                }
            }
        }
    }

    /// The ink without the frame and the flags, in the work's own buffer: each row moves down
    /// to its place in the unframed image, which never lies after its place in the framed one.
    /// A second page-sized buffer would cost as much again in fresh pages as the thinning.
    fn unframed(self) -> Bitmap {
        let (width, height, stride) = (self.width, self.height, self.stride);
        let mut bytes = self.bytes;
        // One pass over the page: each row moved to its place and its flags cleared there while
        // it is in the cache, instead of moving all rows and then masking the page. (A loop
        // doing both at once compiles to byte-by-byte code; a copy and a mask are vector code.)
        for y in 0..height {
            let (from, to) = ((y + 1) * stride + 1, y * width);
            bytes.copy_within(from..from + width, to);
            for cell in &mut bytes[to..to + width] {
                *cell &= INK;
            }
        }
        bytes.truncate(width * height);
        Bitmap::from_pixels(width, height, bytes)
    }
}

/// The neighbourhood bits of the work pixel at `index` (its frame keeps indices in bounds).
#[inline]
fn neighbourhood_at(work: &[u8], index: usize, offsets: &[isize; 8]) -> u8 {
    let mut neighbourhood = 0;
    for (bit, &offset) in offsets.iter().enumerate() {
        neighbourhood |= (work[index.wrapping_add_signed(offset)] & INK) << bit;
    }
    neighbourhood
}

/// Invariant checkers for skeletons, used by the tests and available to callers' tests.
pub mod checks {
    use crate::raster::bitmap::Bitmap;
    use crate::raster::clean::{count_components, count_holes, Connectivity};

    /// Whether every ink pixel of `skeleton` is ink in `mask` (same size required).
    pub fn is_subset(skeleton: &Bitmap, mask: &Bitmap) -> bool {
        skeleton.width() == mask.width()
            && skeleton.height() == mask.height()
            && skeleton
                .as_bytes()
                .iter()
                .zip(mask.as_bytes())
                .all(|(&s, &m)| s == 0 || m != 0)
    }

    /// Number of 8-connected ink components.
    pub fn ink_components(bitmap: &Bitmap) -> usize {
        count_components(bitmap, true, Connectivity::Eight)
    }

    /// Number of holes: 4-connected background components not touching the border.
    pub fn holes(bitmap: &Bitmap) -> usize {
        count_holes(bitmap)
    }

    /// Pixels that make a skeleton thicker than needed: simple, with more than one ink
    /// neighbour (deleting them would neither change topology nor shorten a stroke).
    pub fn removable_pixels(skeleton: &Bitmap) -> Vec<(usize, usize)> {
        let mut removable = Vec::new();
        for y in 0..skeleton.height() {
            for x in 0..skeleton.width() {
                if skeleton.get(x, y) {
                    let neighbourhood = skeleton.neighbourhood(x, y);
                    if neighbourhood.count_ones() > 1 && super::is_simple(neighbourhood) {
                        removable.push((x, y));
                    }
                }
            }
        }
        removable
    }

    /// Checks that `skeleton` is a valid thinning of `mask`: a subset, with the same numbers of
    /// ink components and holes, and 1 pixel wide. Describes the first violation.
    pub fn check_skeleton(mask: &Bitmap, skeleton: &Bitmap) -> Result<(), String> {
        if !is_subset(skeleton, mask) {
            return Err("the skeleton is not a subset of the mask".into());
        }
        let (before, after) = (ink_components(mask), ink_components(skeleton));
        if before != after {
            return Err(format!(
                "ink components: {before} in the mask, {after} in the skeleton"
            ));
        }
        let (before, after) = (holes(mask), holes(skeleton));
        if before != after {
            return Err(format!(
                "holes: {before} in the mask, {after} in the skeleton"
            ));
        }
        let removable = removable_pixels(skeleton);
        if let Some(first) = removable.first() {
            return Err(format!(
                "not 1 px wide: {} removable pixels, the first at {first:?}",
                removable.len()
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::checks::*;
    use super::*;
    use crate::raster::clean::tests::draw_line;
    use crate::raster::test_random::SplitMix64;

    /// Thins and checks the invariants, with both pictures in the failure message.
    fn thin_checked(mask: &Bitmap) -> Bitmap {
        let skeleton = thin(mask);
        if let Err(problem) = check_skeleton(mask, &skeleton) {
            panic!(
                "{problem}\nmask:\n{}\nskeleton:\n{}",
                mask.to_grid(),
                skeleton.to_grid()
            );
        }
        skeleton
    }

    /// The same thinning by full rescans, straight from the definition: the reference the
    /// border-tracking version must match exactly.
    fn thin_by_rescanning(mask: &Bitmap) -> Bitmap {
        let mut skeleton = mask.clone();
        loop {
            let mut changed = false;
            for side in SIDES {
                let mut deletions = Vec::new();
                for y in 0..skeleton.height() {
                    for x in 0..skeleton.width() {
                        let neighbourhood = skeleton.neighbourhood(x, y);
                        if skeleton.get(x, y)
                            && neighbourhood & (1 << side) == 0
                            && neighbourhood.count_ones() > 1
                            && is_simple(neighbourhood)
                        {
                            deletions.push((x, y));
                        }
                    }
                }
                for &(x, y) in &deletions {
                    skeleton.set(x, y, false);
                }
                changed |= !deletions.is_empty();
            }
            if !changed {
                return skeleton;
            }
        }
    }

    /// A random blob: thick strokes and discs, with discs cut out (holes, notches) and salt
    /// noise on top.
    fn random_blob(random: &mut SplitMix64, width: usize, height: usize) -> Bitmap {
        let mut mask = Bitmap::new(width, height);
        let point =
            |random: &mut SplitMix64| (random.unit() * width as f64, random.unit() * height as f64);
        for _ in 0..1 + random.below(5) {
            let (from, to) = (point(random), point(random));
            draw_line(&mut mask, from, to, 1.0 + random.unit() * 9.0);
        }
        for _ in 0..random.below(4) {
            let centre = point(random);
            draw_line(&mut mask, centre, centre, 4.0 + random.unit() * 14.0);
        }
        let mut cut = Bitmap::new(width, height);
        for _ in 0..random.below(6) {
            let centre = point(random);
            draw_line(&mut cut, centre, centre, 1.0 + random.unit() * 6.0);
        }
        for _ in 0..random.below(width * height / 20) {
            let (x, y) = (random.below(width), random.below(height));
            cut.set(x, y, !cut.get(x, y));
        }
        for (pixel, &cut) in mask.as_bytes_mut().iter_mut().zip(cut.as_bytes()) {
            *pixel ^= cut;
        }
        mask
    }

    /// Yokoi's connectivity number for 8-connected ink (S. Yokoi, J. Toriwaki, T. Fukumura,
    /// 1975): an independent formula; a pixel is simple exactly when it equals 1.
    fn yokoi_number(neighbourhood: u8) -> u32 {
        let background = |k: usize| u32::from(neighbourhood & (1 << (k % 8)) == 0);
        [0, 2, 4, 6]
            .iter()
            .map(|&k| background(k) - background(k) * background(k + 1) * background(k + 2))
            .sum()
    }

    #[test]
    fn simple_table_matches_yokoi_and_known_cases() {
        for neighbourhood in 0..=255u8 {
            assert_eq!(
                is_simple(neighbourhood),
                yokoi_number(neighbourhood) == 1,
                "neighbourhood {neighbourhood:08b}"
            );
        }
        assert!(!is_simple(0), "an isolated pixel");
        assert!(!is_simple(0xFF), "an interior pixel");
        assert!(is_simple(0b0000_0001), "an end point");
        assert!(!is_simple(0b0001_0001), "the middle of a vertical line");
        assert!(!is_simple(0b1000_1000), "the middle of a diagonal line");
        assert!(is_simple(0b0000_0111), "a corner of a block");
        assert!(!is_simple(0b0101_0101), "the middle of a plus");
    }

    #[test]
    fn small_fixtures() {
        // A 2×2 block survives as something.
        let block = thin_checked(&Bitmap::from_grid("....\n.##.\n.##.\n...."));
        assert!(
            block.count_ink() >= 1 && block.count_ink() <= 2,
            "{block:?}"
        );
        // A 1-px line is already a skeleton.
        let line = Bitmap::from_grid("......\n.####.\n......");
        assert_eq!(thin_checked(&line), line);
        // So is a diagonal, and a lone pixel.
        let diagonal = Bitmap::from_grid("#...\n.#..\n..#.\n...#");
        assert_eq!(thin_checked(&diagonal), diagonal);
        let dot = Bitmap::from_grid("...\n.#.\n...");
        assert_eq!(thin_checked(&dot), dot);
        // An L of width 2 keeps its corner and its arms, less about a pixel at each end.
        let l_shape = Bitmap::from_grid(
            "
            ##......
            ##......
            ##......
            ########
            ########
            ",
        );
        let skeleton = thin_checked(&l_shape);
        assert!(
            (0..2).any(|y| skeleton.get(0, y) || skeleton.get(1, y)),
            "{skeleton:?}"
        );
        assert!(
            (3..5).any(|y| skeleton.get(6, y) || skeleton.get(7, y)),
            "{skeleton:?}"
        );
        assert!(
            skeleton.get(0, 2) || skeleton.get(1, 3),
            "no corner: {skeleton:?}"
        );
        // Ink touching the image border thins like any other.
        let full = Bitmap::from_grid("#####\n#####\n#####");
        // (North and south go first, so the ends of the last row are end points by the time east
        // and west come.)
        assert_eq!(thin_checked(&full).to_grid(), ".....\n#####\n.....\n");
        for empty in [Bitmap::new(0, 0), Bitmap::new(0, 3), Bitmap::new(4, 4)] {
            assert_eq!(thin(&empty), empty);
        }
    }

    #[test]
    fn a_ring_thins_to_a_closed_loop() {
        let mut ring = Bitmap::new(40, 40);
        for y in 0..40 {
            for x in 0..40 {
                let r = ((x as f64 - 19.5).powi(2) + (y as f64 - 19.5).powi(2)).sqrt();
                ring.set(x, y, (9.0..=15.0).contains(&r));
            }
        }
        let skeleton = thin_checked(&ring);
        assert_eq!(holes(&skeleton), 1);
        // A closed loop has no end points, and it runs near the middle radius.
        for y in 0..40 {
            for x in 0..40 {
                if skeleton.get(x, y) {
                    assert!(
                        skeleton.neighbourhood(x, y).count_ones() >= 2,
                        "end at ({x}, {y})"
                    );
                    let r = ((x as f64 - 19.5).powi(2) + (y as f64 - 19.5).powi(2)).sqrt();
                    assert!((r - 12.0).abs() <= 1.5, "({x}, {y}) at radius {r}");
                }
            }
        }
    }

    #[test]
    fn a_cross_thins_to_four_arms() {
        let mut cross = Bitmap::new(41, 41);
        draw_line(&mut cross, (5.5, 20.5), (35.5, 20.5), 5.0);
        draw_line(&mut cross, (20.5, 5.5), (20.5, 35.5), 5.0);
        let skeleton = thin_checked(&cross);
        let ends: Vec<(usize, usize)> = (0..41)
            .flat_map(|y| (0..41).map(move |x| (x, y)))
            .filter(|&(x, y)| skeleton.get(x, y) && skeleton.neighbourhood(x, y).count_ones() == 1)
            .collect();
        assert_eq!(ends.len(), 4, "{skeleton:?}");
        for (x, y) in ends {
            let reach = (x.abs_diff(20)).max(y.abs_diff(20));
            assert!(reach >= 15 - 3, "arm end ({x}, {y}) too short");
        }
    }

    #[test]
    fn a_filled_disk_thins_to_a_point_or_so() {
        for diameter in [3.0, 6.0, 11.0, 20.0, 31.0] {
            let mut disk = Bitmap::new(40, 40);
            draw_line(&mut disk, (20.2, 19.9), (20.2, 19.9), diameter);
            let skeleton = thin_checked(&disk);
            assert!(
                skeleton.count_ink() <= 3,
                "diameter {diameter}: {skeleton:?}"
            );
        }
    }

    #[test]
    fn thick_lines_thin_to_their_centre_line() {
        let angles: [f64; 6] = [0.0, 90.0, 45.0, 30.0, -60.0, 12.0];
        for stroke_width in 1..=7 {
            for angle in angles {
                let (size, length) = (90usize, 60.0);
                let direction = (angle.to_radians().cos(), angle.to_radians().sin());
                let centre = (45.123, 45.123);
                let half = length / 2.0;
                let from = (centre.0 - direction.0 * half, centre.1 - direction.1 * half);
                let to = (centre.0 + direction.0 * half, centre.1 + direction.1 * half);
                let mut mask = Bitmap::new(size, size);
                draw_line(&mut mask, from, to, f64::from(stroke_width));
                let skeleton = thin_checked(&mask);
                let context = format!("width {stroke_width} at {angle}°");
                // Along (t) and across (d) the line, for each skeleton pixel centre.
                let (mut lowest, mut highest) = (f64::MAX, f64::MIN);
                for y in 0..size {
                    for x in 0..size {
                        if skeleton.get(x, y) {
                            let (px, py) = (x as f64 + 0.5 - centre.0, y as f64 + 0.5 - centre.1);
                            let along = px * direction.0 + py * direction.1;
                            let across = -px * direction.1 + py * direction.0;
                            assert!(across.abs() <= 1.0, "{context}: ({x}, {y}) is {across} off");
                            lowest = lowest.min(along);
                            highest = highest.max(along);
                        }
                    }
                }
                // The segment ends at ±half (the round caps reach w/2 further); thinning may eat
                // back up to w/2 of the segment at each end, plus a pixel for digitization.
                let allowed = half - f64::from(stroke_width) / 2.0 - 1.0;
                assert!(
                    lowest <= -allowed && highest >= allowed,
                    "{context}: spans {lowest}..{highest}"
                );
                // One stroke, no spurs: exactly two end points.
                let ends = (0..size * size)
                    .filter(|&i| {
                        let (x, y) = (i % size, i / size);
                        skeleton.get(x, y) && skeleton.neighbourhood(x, y).count_ones() == 1
                    })
                    .count();
                assert_eq!(ends, 2, "{context}: {skeleton:?}");
            }
        }
    }

    #[test]
    fn random_blobs_keep_their_topology_and_match_the_rescanning_reference() {
        let mut random = SplitMix64::new(2024);
        for round in 0..300 {
            let (width, height) = (8 + random.below(56), 8 + random.below(56));
            let mask = random_blob(&mut random, width, height);
            let skeleton = thin(&mask);
            if let Err(problem) = check_skeleton(&mask, &skeleton) {
                panic!(
                    "round {round}: {problem}\nmask:\n{}\nskeleton:\n{}",
                    mask.to_grid(),
                    skeleton.to_grid()
                );
            }
            assert_eq!(
                skeleton,
                thin_by_rescanning(&mask),
                "round {round}: differs from the reference"
            );
            // Thinning a skeleton changes nothing.
            assert_eq!(thin(&skeleton), skeleton, "round {round}: not idempotent");
        }
    }

    #[test]
    fn a_photographed_ring_comes_out_as_one_closed_loop() {
        // The raster stages in a chain: a ring 7 px wide, photographed under a side light with
        // noise, specks and pinholes, saved as PNG.
        use crate::raster::binarize::{binarize, BinarizeOptions, MethodUsed};
        use crate::raster::clean::{clean, estimate_stroke_width};
        use crate::raster::decode::{decode_image, to_gray};
        let mut random = SplitMix64::new(5);
        let (width, height) = (160u32, 120u32);
        let gray = image::GrayImage::from_fn(width, height, |x, y| {
            let (dx, dy) = (f64::from(x) + 0.5 - 80.0, f64::from(y) + 0.5 - 60.0);
            let radius = (dx * dx + dy * dy).sqrt();
            let on_ring = (36.5..43.5).contains(&radius);
            // Specks on the paper, pinholes in the ink.
            let flipped = random.below(if on_ring { 150 } else { 1500 }) == 0;
            let reflectance = if on_ring != flipped { 0.15 } else { 0.9 };
            let light = 1.0 - 0.7 * f64::from(x) / f64::from(width);
            let value = 255.0 * reflectance * light + random.unit() * 8.0 - 4.0;
            image::Luma([value.round().clamp(0.0, 255.0) as u8])
        });
        let mut png = std::io::Cursor::new(Vec::new());
        gray.write_to(&mut png, image::ImageFormat::Png).unwrap();
        let decoded = to_gray(&decode_image(png.get_ref()).unwrap());
        let binarized = binarize(&decoded, &BinarizeOptions::default());
        assert_eq!(binarized.method_used, MethodUsed::Adaptive);
        let mut mask = binarized.mask;
        let stroke_width = estimate_stroke_width(&mask);
        assert!(
            (stroke_width - 7.0).abs() <= 1.0,
            "stroke width {stroke_width}"
        );
        let report = clean(&mut mask, stroke_width);
        assert!(
            report.specks_removed > 0 && report.holes_filled > 0,
            "{report:?}"
        );
        assert_eq!((ink_components(&mask), holes(&mask)), (1, 1));
        let skeleton = thin_checked(&mask);
        let ends = (0..height as usize)
            .flat_map(|y| (0..width as usize).map(move |x| (x, y)))
            .filter(|&(x, y)| skeleton.get(x, y) && skeleton.neighbourhood(x, y).count_ones() < 2)
            .count();
        assert_eq!(ends, 0, "{skeleton:?}");
    }

    #[test]
    fn the_checkers_catch_bad_skeletons() {
        let mask = Bitmap::from_grid("......\n.####.\n.####.\n......");
        assert!(check_skeleton(&mask, &mask)
            .unwrap_err()
            .contains("1 px wide"));
        let split = Bitmap::from_grid("......\n.#..#.\n......\n......");
        assert!(check_skeleton(&mask, &split)
            .unwrap_err()
            .contains("components"));
        let outside = Bitmap::from_grid("#.....\n......\n......\n......");
        assert!(check_skeleton(&mask, &outside)
            .unwrap_err()
            .contains("subset"));
        // (A rectangle's corners would be removable: 8-connectivity closes the ring without.)
        let ring = Bitmap::from_grid(".###.\n#...#\n.###.");
        let broken = Bitmap::from_grid(".#.#.\n#...#\n.###.");
        assert!(check_skeleton(&ring, &broken)
            .unwrap_err()
            .contains("holes"));
        assert_eq!(check_skeleton(&ring, &ring), Ok(()));
    }
}
