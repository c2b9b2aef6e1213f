//! Items bucketed by position in square cells, so that what lies near a point is found by looking
//! at nine cells instead of at every item (a page of noise has hundreds of thousands of ends,
//! corners and samples): the uniform grid of Bentley and Friedman, "Data structures for range
//! searching", ACM Computing Surveys 11(4), 1979.

use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;

use kurbo::Point;

use super::{floor_to_i64, FastHasher};

/// Items placed at points, in square cells of a fixed size.
///
/// The items live in one vector, each cell holding the first and last of its items and each item
/// the next of its cell (a linked list in insertion order): a vector per cell cost an allocation
/// and its regrowths per cell, a tenth of the reconstruction's time on a page (docs/performance.md).
#[derive(Clone, Debug)]
pub(crate) struct PointGrid<T> {
    cell: f64,
    cells: HashMap<(i64, i64), (u32, u32), BuildHasherDefault<FastHasher>>,
    items: Vec<(T, u32)>,
}

/// The end of a cell's list of items.
const NO_NEXT: u32 = u32::MAX;

impl<T> PointGrid<T> {
    /// An empty grid of cells `cell` wide (positive; callers check their own widths).
    pub(crate) fn new(cell: f64) -> Self {
        Self {
            cell,
            cells: HashMap::default(),
            items: Vec::new(),
        }
    }

    /// The width of a cell.
    pub(crate) fn cell(&self) -> f64 {
        self.cell
    }

    /// The cell `p` lies in.
    pub(crate) fn cell_of(&self, p: Point) -> (i64, i64) {
        (floor_to_i64(p.x / self.cell), floor_to_i64(p.y / self.cell))
    }

    /// Puts `item` in the cell of `p`.
    pub(crate) fn insert(&mut self, p: Point, item: T) {
        self.insert_in_cell(self.cell_of(p), item);
    }

    /// Puts `item` in the cell `key` (for items spanning several cells, such as segments).
    pub(crate) fn insert_in_cell(&mut self, key: (i64, i64), item: T) {
        let index = u32::try_from(self.items.len()).expect("fewer than 2^32 items in a grid");
        self.items.push((item, NO_NEXT));
        match self.cells.entry(key) {
            Entry::Occupied(mut cell) => {
                let (_, last) = cell.get_mut();
                self.items[*last as usize].1 = index;
                *last = index;
            }
            Entry::Vacant(cell) => {
                cell.insert((index, index));
            }
        }
    }

    /// The items in the cell of `p` and in the eight cells around it: every item placed within a
    /// cell's width of `p`, and some farther. Cell by cell (column-major), each cell's items in
    /// the order they were put in.
    pub(crate) fn around(&self, p: Point) -> impl Iterator<Item = &T> + '_ {
        let (cx, cy) = self.cell_of(p);
        (cx - 1..=cx + 1)
            .flat_map(move |x| (cy - 1..=cy + 1).map(move |y| (x, y)))
            .flat_map(|key| self.in_cell(key))
    }

    /// The items in the cell `key`, in the order they were put in.
    pub(crate) fn in_cell(&self, key: (i64, i64)) -> impl Iterator<Item = &T> + '_ {
        let first = self.cells.get(&key).map(|&(first, _)| first);
        std::iter::successors(first, |&k| {
            let next = self.items[k as usize].1;
            (next != NO_NEXT).then_some(next)
        })
        .map(|k| &self.items[k as usize].0)
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
