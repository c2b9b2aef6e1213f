//! Clusters of ink parted by spaces: the letters of a word, the objects of a page. A drawing's
//! pieces (strokes joined at their junctions) lie a pen lift apart within a letter and a letter's
//! spacing apart between letters; where the spacings stand clearly apart from the pen lifts, a
//! long bridge between two clusters crosses a space, not a pen lift ([`super::bridges`]).

use kurbo::{Point, Rect};

use super::strokes::StrokeVertices;
use crate::geometry::grid::PointGrid;
use crate::geometry::{FastHashMap, UnionFind};
use std::collections::hash_map::Entry;

/// DECISION: (stop 69, helpers h40 and h42) the pieces of a drawing fall into clusters where the
/// gaps that join them (each piece's nearest gap to another, the single-linkage tree of the
/// pieces' ends) jump by at least this factor above their median: a hand's pen lifts spread within
/// one range (the benchmark's up to 3:1), and the spaces between letters or objects are wider than
/// the longest lift. Thick letters bridged letter to letter across 1.5–2 times the longest pen
/// lift of their word (an "F"'s bar to a "T"'s or an "I"'s top, a "C"'s end to the next letter's
/// stem): the gaps joining their pieces jumped by 1.44–1.57 at the first space (seed 11
/// `letters-thick-006` is the 1.44: a factor of 1.45 or more loses it).
pub(super) const SPACE_MIN_JUMP: f64 = 1.4;

/// ... where the gap below the jump is held to at least this many typical gaps: a jump among gaps
/// much shorter than the hand's pen lifts (4.9 to 7.1 px with lifts of 5.6 px) is no space.
/// Measured (h42, with the other guards): 0.5 and 0.75 read the same on all ten splits (0.95
/// too, with long bridges from 1.6 typical gaps); 1.0 would lose seed 5 `letters-thick-002`,
/// whose space is 1.39 typical gaps (28.3 px against 1.4 × 20.4).
pub(super) const SPACE_JUMP_FLOOR_IN_TYPICAL_GAPS: f64 = 0.75;

/// ... with at least [`SPACE_MIN_LIFTS_BELOW`] gaps below the jump of at least this many typical
/// gaps: fewer pen lifts do not measure the hand.
pub(super) const LIFT_MIN_IN_TYPICAL_GAPS: f64 = 0.5;

/// ... see [`LIFT_MIN_IN_TYPICAL_GAPS`].
pub(super) const SPACE_MIN_LIFTS_BELOW: usize = 5;

/// ... and at least this many gaps at or above the jump (four clusters or more: a word of four
/// letters, a page of four objects): one pen lift longer than the rest (a circle's, a spiral's,
/// a square's side's) parts an outline into two or three pieces, not clusters.
pub(super) const SPACES_MIN: usize = 3;

/// DECISION: (stop 69, helper h42) a cluster is an object (a letter, a shape) only where its
/// extent (its bounding box's diagonal) is at least this many times the space that parts the
/// clusters: a stretch of an outline cut off by one long pen lift can be shorter than the lift
/// (seed 11 `corners-clean-007`: a square's side's last dash, 11 px against a space of 9 px),
/// while the smallest letter of the benchmark's words reads 2.5 spaces (seed 5
/// `letters-thick-002`, a "T"'s bar: so 2.6 would lose it); 1.4–2.0 measure the same.
pub(super) const OBJECT_MIN_EXTENT_IN_SPACES: f64 = 2.0;

/// The cluster of each vertex, where the drawing's pieces fall into clusters parted by spaces
/// ([`SPACE_MIN_JUMP`]); `None` where they do not. A vertex of a cluster too small to be an
/// object ([`OBJECT_MIN_EXTENT_IN_SPACES`]) has no cluster (`None` in the list). Gaps are
/// measured between the pieces' ends (`ends`, vertices) and the nearest vertex of each other
/// piece, rim to rim (less the pen's width `stroke_width`), at most `reach` apart.
pub(super) fn ink_clusters(
    vertices: &StrokeVertices,
    ends: &[u32],
    reach: f64,
    stroke_width: f64,
    typical_gap: f64,
) -> Option<Vec<Option<u32>>> {
    let count = vertices.positions.len();
    if reach <= 0.0 {
        return None;
    }
    // The pieces: strokes that share a vertex (a junction) are one piece.
    let mut pieces = UnionFind::new(count);
    for line in &vertices.of_stroke {
        for pair in line.windows(2) {
            pieces.union(pair[0], pair[1]);
        }
    }
    // Every vertex by position; each end's nearest vertex of each other piece within reach.
    let mut grid: PointGrid<u32> = PointGrid::new(reach);
    for (v, &p) in vertices.positions.iter().enumerate() {
        grid.insert(p, v as u32);
    }
    let mut gaps: Vec<(f64, u32, u32)> = Vec::new();
    let mut nearest: FastHashMap<u32, (f64, u32)> = FastHashMap::default();
    for &end in ends {
        let at: Point = vertices.positions[end as usize];
        let own = pieces.find(end);
        nearest.clear();
        for &other in grid.around(at) {
            let piece = pieces.find(other);
            if piece == own {
                continue;
            }
            let distance = at.distance(vertices.positions[other as usize]);
            if distance > reach {
                continue;
            }
            match nearest.entry(piece) {
                Entry::Occupied(mut e) => {
                    if distance < e.get().0 {
                        e.insert((distance, other));
                    }
                }
                Entry::Vacant(e) => {
                    e.insert((distance, other));
                }
            }
        }
        gaps.extend(
            nearest
                .values()
                .map(|&(distance, other)| ((distance - stroke_width).max(0.0), end, other)),
        );
    }
    gaps.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Kruskal's tree over the pieces, on a copy of the pieces' sets.
    let mut joined = pieces.clone();
    let mut tree: Vec<(f64, u32, u32)> = Vec::new();
    for &(gap, a, b) in &gaps {
        if joined.union(a, b) {
            tree.push((gap, a, b));
        }
    }
    let space = first_space(&tree.iter().map(|t| t.0).collect::<Vec<_>>(), typical_gap)?;
    let mut clusters = pieces;
    for &(gap, a, b) in &tree {
        if gap < space {
            clusters.union(a, b);
        }
    }
    let cluster: Vec<u32> = (0..count as u32).map(|v| clusters.find(v)).collect();
    // Each cluster's bounding box.
    let mut boxes: FastHashMap<u32, Rect> = FastHashMap::default();
    for (&c, &p) in cluster.iter().zip(&vertices.positions) {
        boxes
            .entry(c)
            .and_modify(|r| *r = r.union_pt(p))
            .or_insert_with(|| Rect::from_points(p, p));
    }
    let min_extent = OBJECT_MIN_EXTENT_IN_SPACES * space;
    Some(
        cluster
            .iter()
            .map(|&c| {
                let r = boxes[&c];
                (r.width().hypot(r.height()) >= min_extent).then_some(c)
            })
            .collect(),
    )
}

/// The first space among the gaps of a single-linkage tree (in any order): the first gap, from
/// the median up, at least [`SPACE_MIN_JUMP`] times the one before it (held to at least
/// [`SPACE_JUMP_FLOOR_IN_TYPICAL_GAPS`]), with at least [`SPACE_MIN_LIFTS_BELOW`] pen lifts below
/// it and at least [`SPACES_MIN`] gaps at or above it.
pub(super) fn first_space(gaps: &[f64], typical_gap: f64) -> Option<f64> {
    let floor = SPACE_JUMP_FLOOR_IN_TYPICAL_GAPS * typical_gap;
    let lift = LIFT_MIN_IN_TYPICAL_GAPS * typical_gap;
    let mut sorted = gaps.to_vec();
    sorted.sort_by(f64::total_cmp);
    let from = (sorted.len() / 2).max(1);
    (from..sorted.len())
        .find(|&i| {
            sorted[i] >= SPACE_MIN_JUMP * sorted[i - 1].max(floor)
                && sorted[..i].iter().filter(|&&g| g >= lift).count() >= SPACE_MIN_LIFTS_BELOW
        })
        .filter(|&i| sorted.len() - i >= SPACES_MIN)
        .map(|i| sorted[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_space_is_the_first_jump_above_the_median_over_enough_pen_lifts() {
        // Pen lifts of 10–18 px and the spaces between letters of 30 px and more.
        let gaps = [12.0, 10.0, 14.0, 16.0, 18.0, 31.0, 15.0, 40.0, 30.0];
        assert_eq!(
            first_space(&gaps[..8], 12.0),
            None,
            "two spaces part no word"
        );
        assert_eq!(first_space(&gaps, 12.0), Some(30.0));
        // A spread-out hand with no space clearly wider than its lifts.
        let even = [10.0, 12.0, 14.0, 16.0, 19.0, 22.0, 26.0, 30.0];
        assert_eq!(first_space(&even, 12.0), None);
        // Too few lifts below the jump to measure the hand.
        assert_eq!(first_space(&[10.0, 11.0, 12.0, 30.0, 31.0], 12.0), None);
        // A jump below the median (a few gaps of nothing) is no space.
        let low = [0.0, 0.0, 10.0, 11.0, 12.0, 12.5, 13.0, 14.0];
        assert_eq!(first_space(&low, 12.0), None);
        // A jump from gaps shorter than the hand's lifts (3 px with lifts of 5) is held to the
        // floor: 4.5 px is no space.
        let short = [3.0, 3.0, 3.0, 3.0, 3.0, 3.0, 4.5, 4.6, 4.7];
        assert_eq!(first_space(&short, 5.0), None);
        assert_eq!(first_space(&short.map(|g| g * 2.0), 5.0), Some(9.0));
    }

    #[test]
    fn pieces_a_space_apart_fall_into_clusters() {
        // Four "letters" of three dashes each along a line: dashes 20 px long, pen lifts of
        // 10 px (7 rim to rim with a 3 px pen) and spaces of 30 px between the letters.
        let mut vertices = StrokeVertices::default();
        let mut ends = Vec::new();
        for letter in 0..4 {
            for dash in 0..3 {
                let x0 = f64::from(letter) * 110.0 + f64::from(dash) * 30.0;
                let first = vertices.positions.len() as u32;
                let line: Vec<u32> = (0..=4)
                    .map(|k| {
                        vertices
                            .positions
                            .push(Point::new(x0 + 5.0 * f64::from(k), 0.0));
                        first + k
                    })
                    .collect();
                ends.extend([line[0], line[4]]);
                vertices.of_stroke.push(line);
                vertices.closed.push(false);
            }
        }
        let cluster =
            ink_clusters(&vertices, &ends, 60.0, 3.0, 7.0).expect("spaces part the letters");
        // Each letter's 15 vertices are one cluster, and no two letters share one.
        for letter in 0..4 {
            let first = letter * 15;
            assert!(cluster[first].is_some());
            assert!((first..first + 15).all(|v| cluster[v] == cluster[first]));
            assert!((0..first).all(|v| cluster[v] != cluster[first]));
        }
        // A fifth "letter" of one short dash a space after the fourth is too small to be an
        // object: 5 px against a space of 27.
        let first = vertices.positions.len() as u32;
        vertices.positions.push(Point::new(440.0, 0.0));
        vertices.positions.push(Point::new(445.0, 0.0));
        vertices.of_stroke.push(vec![first, first + 1]);
        vertices.closed.push(false);
        ends.extend([first, first + 1]);
        let cluster =
            ink_clusters(&vertices, &ends, 60.0, 3.0, 7.0).expect("spaces part the letters");
        assert!(cluster[..60].iter().all(Option::is_some));
        assert_eq!(cluster[first as usize], None);
        assert_eq!(cluster[first as usize + 1], None);
        // Evenly spaced dashes have no space to part them.
        for v in 15..60 {
            vertices.positions[v].x -= 20.0 * (v / 15) as f64;
        }
        assert_eq!(ink_clusters(&vertices, &ends, 60.0, 3.0, 7.0), None);
    }
}
