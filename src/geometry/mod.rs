//! Geometry shared by the stages: [`Polyline`] (length, simplification, resampling),
//! [`UnionFind`], a grid of points for finding what lies near one (`grid::PointGrid`), and two
//! speed helpers: a hasher for small integer keys and a floor without a library call.

pub(crate) mod grid;
pub mod polyline;
pub mod union_find;

pub use polyline::Polyline;
pub use union_find::UnionFind;

use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// A hasher for small integer keys (grid cells, vertex and curve numbers): a multiply and a
/// rotate per word. The standard library's SipHash guards against keys chosen to collide, which
/// cells and vertex numbers need not fear, and cost a fifth of the crawl's time on a page of noise
/// in the grids, and 4 % of a page's instructions in the bridges' maps. No output depends on a
/// map's order: the standard maps' order was already random from run to run.
#[derive(Default)]
pub(crate) struct FastHasher(u64);

impl Hasher for FastHasher {
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

    fn write_u32(&mut self, value: u32) {
        self.write_u64(u64::from(value));
    }

    fn write_usize(&mut self, value: usize) {
        self.write_u64(value as u64);
    }

    fn write_i64(&mut self, value: i64) {
        self.write_u64(value as u64);
    }
}

/// A hash map keyed by small integers, with [`FastHasher`].
pub(crate) type FastHashMap<K, V> = HashMap<K, V, BuildHasherDefault<FastHasher>>;

/// A hash set of small integers, with [`FastHasher`].
pub(crate) type FastHashSet<K> = HashSet<K, BuildHasherDefault<FastHasher>>;

/// `x.floor() as i64`, without the call: Rust's `floor` is a library call on x86-64 without
/// SSE4.1, about fifty instructions, and the grids and the ink measurements take the cell or
/// pixel of millions of points on a page (6 % of a page's instructions, docs/performance.md).
/// Equal to `x.floor() as i64` for every `f64`, NaN (0) and the saturated ends included.
#[inline]
pub(crate) fn floor_to_i64(x: f64) -> i64 {
    let truncated = x as i64;
    // Truncation rounds toward zero: a negative value with a fraction lies one below it.
    if (truncated as f64) > x {
        truncated.saturating_sub(1)
    } else {
        truncated
    }
}

#[cfg(test)]
mod tests {
    use super::floor_to_i64;

    #[test]
    fn floor_to_i64_is_floor_then_cast_everywhere() {
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            -1.0000001,
            2.9999999,
            -2.9999999,
            1e18,
            -1e18,
            9.3e18,
            -9.3e18,
            1e300,
            -1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
        ];
        values.extend((-4000..4000).map(|k| f64::from(k) * 0.37));
        for x in values {
            assert_eq!(floor_to_i64(x), x.floor() as i64, "at {x}");
        }
    }
}
