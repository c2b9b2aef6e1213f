//! The many-curves point set: `count` points on closed curves (ellipses of 100 to 1000 points,
//! about 0.01 apart, each in its own cell of a grid), from a fixed seed. Shared by
//! `benches/reconstruct.rs` (in memory) and `examples/many_curves.rs` (as a point file) through
//! `#[path]`, so the benchmark measures the scenes the example writes.

use crate::random::SplitMix64;

use std::f64::consts::{PI, TAU};

/// The seed of every many-curves point set.
const SEED: u64 = 7;

/// `count` points on ellipses, in file order.
pub fn ellipse_points(count: usize) -> Vec<(f64, f64)> {
    let mut random = SplitMix64::new(SEED);
    // Curves of 100 to 1000 points (550 on average), spaced about 0.01 apart, fit in cells 4
    // units wide.
    let columns = ((count as f64 / 550.0).sqrt().ceil() as usize).max(1);
    let mut points = Vec::with_capacity(count);
    let mut cell = 0;
    while points.len() < count {
        let size = ((100.0 + 900.0 * random.unit()) as usize).min(count - points.len());
        let aspect = 1.0 + random.unit();
        // The ellipse's perimeter is about π(a + b) = 0.01 · size.
        let a = 0.01 * size as f64 / (PI * (1.0 + 1.0 / aspect));
        let centre = (
            4.0 * (cell % columns) as f64 + 2.0,
            4.0 * (cell / columns) as f64 + 2.0,
        );
        let phase = TAU * random.unit();
        for k in 0..size {
            let angle = phase + TAU * (k as f64 + 0.3 * random.unit()) / size as f64;
            points.push((
                centre.0 + a * angle.cos(),
                centre.1 + a / aspect * angle.sin(),
            ));
        }
        cell += 1;
    }
    points
}
