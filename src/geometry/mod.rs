//! Geometry shared by the stages: [`Polyline`] (length, simplification, resampling),
//! [`UnionFind`] and a grid of points for finding what lies near one (`grid::PointGrid`).

pub(crate) mod grid;
pub mod polyline;
pub mod union_find;

pub use polyline::Polyline;
pub use union_find::UnionFind;

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
