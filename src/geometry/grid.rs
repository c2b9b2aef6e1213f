//! Items bucketed by position in square cells, so that what lies near a point is found by looking
//! at nine cells instead of at every item (a page of noise has hundreds of thousands of ends,
//! corners and samples): the uniform grid of Bentley and Friedman, "Data structures for range
//! searching", ACM Computing Surveys 11(4), 1979.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use kurbo::Point;

/// A hasher for cell coordinates: a multiply and a rotate per coordinate. The standard library's
/// SipHash guards against keys chosen to collide, which a grid of pixel cells need not fear, and
/// cost a fifth of the crawl's time on a page of noise. The cells' order never shows: `around`
/// visits cells in a fixed order, whatever the map's.
#[derive(Default)]
struct CellHasher(u64);

impl Hasher for CellHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            self.write_u64(u64::from(byte));
        }
    }

    fn write_u64(&mut self, value: u64) {
        // The multiplier is 2^64 over the golden ratio (Fibonacci hashing, Knuth, TAOCP vol. 3).
        self.0 = (self.0.rotate_left(5) ^ value).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }

    fn write_i64(&mut self, value: i64) {
        self.write_u64(value as u64);
    }
}

/// Items placed at points, in square cells of a fixed size.
#[derive(Clone, Debug)]
pub(crate) struct PointGrid<T> {
    cell: f64,
    cells: HashMap<(i64, i64), Vec<T>, BuildHasherDefault<CellHasher>>,
}

impl<T> PointGrid<T> {
    /// An empty grid of cells `cell` wide (positive; callers check their own widths).
    pub(crate) fn new(cell: f64) -> Self {
        Self {
            cell,
            cells: HashMap::default(),
        }
    }

    /// The cell `p` lies in.
    pub(crate) fn cell_of(&self, p: Point) -> (i64, i64) {
        (
            (p.x / self.cell).floor() as i64,
            (p.y / self.cell).floor() as i64,
        )
    }

    /// Puts `item` in the cell of `p`.
    pub(crate) fn insert(&mut self, p: Point, item: T) {
        self.cells.entry(self.cell_of(p)).or_default().push(item);
    }

    /// The items in the cell of `p` and in the eight cells around it: every item placed within a
    /// cell's width of `p`, and some farther. Cell by cell (column-major), each cell's items in
    /// the order they were put in.
    pub(crate) fn around(&self, p: Point) -> impl Iterator<Item = &T> + '_ {
        let (cx, cy) = self.cell_of(p);
        (cx - 1..=cx + 1)
            .flat_map(move |x| (cy - 1..=cy + 1).map(move |y| (x, y)))
            .filter_map(|key| self.cells.get(&key))
            .flatten()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn around_finds_every_item_within_a_cell_and_none_two_cells_off() {
        let mut grid = PointGrid::new(10.0);
        let items = [
            (0.0, 0.0),
            (9.9, -9.9),
            (-9.5, 3.0),
            (25.0, 0.0),
            (0.0, -21.0),
        ];
        for (k, &(x, y)) in items.iter().enumerate() {
            grid.insert(Point::new(x, y), k);
        }
        let mut near: Vec<usize> = grid.around(Point::new(1.0, 1.0)).copied().collect();
        near.sort_unstable();
        assert_eq!(near, vec![0, 1, 2]);
    }
}
