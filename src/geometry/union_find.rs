//! Union–find (disjoint sets) over indices, with path halving (R. E. Tarjan and J. van Leeuwen,
//! "Worst-case analysis of set union algorithms", JACM 31(2), 1984). The caller chooses which of
//! two roots stays root, so that it can keep per-set data (an area, a length) at the roots and
//! merge it in an order of its own.

/// A forest of sets over the indices `0..len()`; every index starts as its own set.
#[derive(Clone, Debug, Default)]
pub struct UnionFind {
    /// The parent of each index; roots are their own parent.
    parent: Vec<u32>,
}

impl UnionFind {
    /// `count` singleton sets.
    ///
    /// # Panics
    /// If `count` exceeds `u32::MAX + 1` (indices are stored as `u32` to halve the memory).
    pub fn new(count: usize) -> Self {
        let count = u32::try_from(count).expect("at most 2³² elements");
        Self {
            parent: (0..count).collect(),
        }
    }

    /// Adds a singleton set and returns its index, or `None` when the indices would overflow
    /// `u32`.
    pub fn push(&mut self) -> Option<u32> {
        let index = u32::try_from(self.parent.len()).ok()?;
        self.parent.push(index);
        Some(index)
    }

    /// The number of elements.
    pub fn len(&self) -> usize {
        self.parent.len()
    }

    /// Whether there are no elements.
    pub fn is_empty(&self) -> bool {
        self.parent.is_empty()
    }

    /// The root of the set of `element`, halving the path on the way.
    pub fn find(&mut self, mut element: u32) -> u32 {
        while self.parent[element as usize] != element {
            let grandparent = self.parent[self.parent[element as usize] as usize];
            self.parent[element as usize] = grandparent;
            element = grandparent;
        }
        element
    }

    /// Whether `element` is the root of its set.
    pub fn is_root(&self, element: u32) -> bool {
        self.parent[element as usize] == element
    }

    /// Puts the set of root `child` under root `root`. Both must be roots, and distinct.
    pub fn attach(&mut self, child: u32, root: u32) {
        debug_assert!(self.is_root(child) && self.is_root(root) && child != root);
        self.parent[child as usize] = root;
    }

    /// Joins the sets of `a` and `b`, the set of `a` going under the root of `b`'s; returns
    /// whether they were apart. For callers that keep no data at the roots.
    pub fn union(&mut self, a: u32, b: u32) -> bool {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.attach(a, b);
        }
        a != b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sets_join_and_roots_are_chosen_by_the_caller() {
        let mut sets = UnionFind::new(5);
        assert_eq!(sets.len(), 5);
        assert!((0..5).all(|element| sets.find(element) == element));
        sets.attach(3, 1);
        let (a, b) = (sets.find(4), sets.find(3));
        sets.attach(a, b);
        assert_eq!(sets.find(4), 1, "4 joined 3's set, whose root is 1");
        assert_eq!(sets.find(0), 0);
        assert!(sets.is_root(1) && !sets.is_root(3) && !sets.is_root(4));
        assert_eq!(sets.push(), Some(5));
        assert_eq!(sets.find(5), 5);
    }

    #[test]
    fn union_puts_the_first_set_under_the_second_s_root_once() {
        let mut sets = UnionFind::new(4);
        assert!(sets.union(0, 1));
        assert!(sets.union(2, 0), "2 joins 0's set, whose root is 1");
        assert_eq!(sets.find(2), 1);
        assert!(!sets.union(0, 2), "already one set");
        assert_eq!(sets.find(3), 3);
    }

    #[test]
    fn find_halves_long_paths() {
        // A chain 0 ← 1 ← 2 ← … ← 9 (each attached under the previous one, the last first, so
        // that both are roots when attached).
        let mut sets = UnionFind::new(10);
        for element in (1..10).rev() {
            sets.attach(element, element - 1);
        }
        assert_eq!(sets.find(9), 0);
        // Path halving pointed every other element on the path at its grandparent.
        assert_eq!(sets.parent[9], 7);
        assert_eq!(sets.find(9), 0);
    }
}
