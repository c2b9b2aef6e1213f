//! Writes a large point file for timing `crawltrace points`: `count` points sampled from many
//! closed curves (ellipses of random sizes, each in its own grid cell) with a little jitter.
//!
//! ```sh
//! cargo run --release --example many_curves -- 1000000 > big.txt
//! ```
//!
//! With `--circles N`, the curves are circles of N points each and the lines are shuffled (the
//! point-set timing of `docs/point-sets.md`: 2000 circles of 500 points):
//!
//! ```sh
//! cargo run --release --example many_curves -- 1000000 --circles 500 > circles.txt
//! ```

#[path = "../benches/support/many_curves.rs"]
mod many_curves;
#[path = "../tests/support/random.rs"]
mod random;
use random::SplitMix64;

use std::f64::consts::TAU;
use std::io::{self, BufWriter, Write};

fn main() -> io::Result<()> {
    let count: usize = match std::env::args().nth(1).map(|text| text.parse()) {
        None => 1_000_000,
        Some(Ok(count)) => count,
        Some(Err(_)) => {
            eprintln!("usage: many_curves [POINT_COUNT] > points.txt");
            std::process::exit(2);
        }
    };
    let mut random = SplitMix64::new(7);
    let mut out = BufWriter::new(io::stdout().lock());
    if std::env::args().nth(2).as_deref() == Some("--circles") {
        let per_circle = std::env::args()
            .nth(3)
            .and_then(|text| text.parse().ok())
            .unwrap_or(500);
        for (x, y) in shuffled_circles(count, per_circle, &mut random) {
            writeln!(out, "{x:.6} {y:.6}")?;
        }
        return out.flush();
    }
    for (x, y) in many_curves::ellipse_points(count) {
        writeln!(out, "{x:.6} {y:.6}")?;
    }
    out.flush()
}

/// `count` points on circles of `per_circle` points (spaced about 0.01 apart, each in its own
/// grid cell), in a random order.
fn shuffled_circles(count: usize, per_circle: usize, random: &mut SplitMix64) -> Vec<(f64, f64)> {
    let per_circle = per_circle.max(3);
    let circles = count.div_ceil(per_circle);
    let columns = (circles as f64).sqrt().ceil() as usize;
    let radius = 0.01 * per_circle as f64 / TAU;
    let cell = 2.0 * radius + 0.5;
    let mut points = Vec::with_capacity(count);
    for circle in 0..circles {
        let centre = (
            cell * (circle % columns) as f64 + cell / 2.0,
            cell * (circle / columns) as f64 + cell / 2.0,
        );
        let phase = TAU * random.unit();
        for k in 0..per_circle.min(count - points.len()) {
            let angle = phase + TAU * (k as f64 + 0.3 * random.unit()) / per_circle as f64;
            points.push((
                centre.0 + radius * angle.cos(),
                centre.1 + radius * angle.sin(),
            ));
        }
    }
    // Fisher–Yates with the same generator.
    for i in (1..points.len()).rev() {
        let j = (random.unit() * (i + 1) as f64) as usize;
        points.swap(i, j.min(i));
    }
    points
}
