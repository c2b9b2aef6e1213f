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

    /// An empty grid of cells `cell` wide with room for `items` items in about `cells` cells
    /// without growing: a grid of a page's curve points grew through a dozen doublings of its
    /// item vector and its cell table, each copying what it held (docs/performance.md, stop 70).
    pub(crate) fn with_capacity(cell: f64, items: usize, cells: usize) -> Self {
        Self {
            cell,
            cells: HashMap::with_capacity_and_hasher(cells, BuildHasherDefault::default()),
            items: Vec::with_capacity(items),
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
        Around {
            grid: self,
            cx,
            cy,
            // An empty grid looks up no cell.
            next_cell: if self.items.is_empty() { 9 } else { 0 },
            item: NO_NEXT,
        }
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

/// The items of the nine cells around a cell, as [`PointGrid::around`] lists them: one cell at a
/// time, column by column, each cell's list followed to its end.
///
/// DECISION: (stop 70) written out rather than as nested `flat_map`s, whose bookkeeping cost the
/// 12-megapixel page 26 M instructions (4.7 M now; `valgrind --tool=callgrind`,
/// docs/performance.md); the order is the same, so every output is byte-identical.
struct Around<'a, T> {
    grid: &'a PointGrid<T>,
    cx: i64,
    cy: i64,
    /// The next of the nine cells to look up (0 to 8, column-major), 9 when all were.
    next_cell: u8,
    /// The next item of the current cell's list, or [`NO_NEXT`].
    item: u32,
}

impl<'a, T> Iterator for Around<'a, T> {
    type Item = &'a T;

    #[inline]
    fn next(&mut self) -> Option<&'a T> {
        loop {
            if self.item != NO_NEXT {
                let (value, next) = &self.grid.items[self.item as usize];
                self.item = *next;
                return Some(value);
            }
            if self.next_cell >= 9 {
                return None;
            }
            let k = i64::from(self.next_cell);
            self.next_cell += 1;
            let key = (self.cx - 1 + k / 3, self.cy - 1 + k % 3);
            if let Some(&(first, _)) = self.grid.cells.get(&key) {
                self.item = first;
            }
        }
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

    #[test]
    fn around_lists_cells_column_by_column_and_each_cell_in_insertion_order() {
        let mut grid = PointGrid::with_capacity(10.0, 4, 2);
        assert_eq!(grid.around(Point::new(5.0, 5.0)).count(), 0);
        let items = [
            (15.0, 15.0), // cell (1, 1)
            (-5.0, 25.0), // cell (-1, 2)
            (5.0, 5.0),   // cell (0, 0)
            (16.0, 14.0), // cell (1, 1) again
            (-5.0, -5.0), // cell (-1, -1)
            (35.0, 5.0),  // cell (3, 0): two cells off
            (5.0, -22.0), // cell (0, -3): two cells off
        ];
        for (k, &(x, y)) in items.iter().enumerate() {
            grid.insert(Point::new(x, y), k);
        }
        let listed: Vec<usize> = grid.around(Point::new(5.0, 15.0)).copied().collect();
        // Cells (-1, 0), (-1, 1), (-1, 2), (0, 0), (0, 1), (0, 2), (1, 0), (1, 1), (1, 2).
        assert_eq!(listed, vec![1, 2, 0, 3]);
        let by_cells: Vec<usize> = (-1..=1)
            .flat_map(|x| (0..=2).map(move |y| (x, y)))
            .flat_map(|key| grid.in_cell(key))
            .copied()
            .collect();
        assert_eq!(listed, by_cells);
        let corner: Vec<usize> = grid.around(Point::new(-1.0, -1.0)).copied().collect();
        assert_eq!(corner, vec![4, 2]);
    }
}
