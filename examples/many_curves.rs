//! Writes a large point file for timing `crawltrace points`: `count` points sampled from many
//! closed curves (ellipses of random sizes, each in its own grid cell) with a little jitter.
//!
//! ```sh
//! cargo run --release --example many_curves -- 1000000 > big.txt
//! ```

use std::f64::consts::TAU;
use std::io::{self, BufWriter, Write};

/// SplitMix64: a tiny deterministic generator, so the file is the same on every run.
struct SplitMix64(u64);

impl SplitMix64 {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn main() -> io::Result<()> {
    let count: usize = match std::env::args().nth(1).map(|text| text.parse()) {
        None => 1_000_000,
        Some(Ok(count)) => count,
        Some(Err(_)) => {
            eprintln!("usage: many_curves [POINT_COUNT] > points.txt");
            std::process::exit(2);
        }
    };
    let mut random = SplitMix64(7);
    let mut out = BufWriter::new(io::stdout().lock());
    // Curves of 100 to 1000 points, spaced about 0.01 apart, fit in cells 4 units wide.
    let columns = ((count as f64 / 550.0).sqrt().ceil() as usize).max(1);
    let mut written = 0;
    let mut cell = 0;
    while written < count {
        let points = ((100.0 + 900.0 * random.unit()) as usize).min(count - written);
        let aspect = 1.0 + random.unit();
        // The ellipse's perimeter is about π(a + b) = 0.01 · points.
        let a = 0.01 * points as f64 / (std::f64::consts::PI * (1.0 + 1.0 / aspect));
        let centre = (
            4.0 * (cell % columns) as f64 + 2.0,
            4.0 * (cell / columns) as f64 + 2.0,
        );
        let phase = TAU * random.unit();
        for k in 0..points {
            let angle = phase + TAU * (k as f64 + 0.3 * random.unit()) / points as f64;
            writeln!(
                out,
                "{:.6} {:.6}",
                centre.0 + a * angle.cos(),
                centre.1 + a / aspect * angle.sin()
            )?;
        }
        written += points;
        cell += 1;
    }
    out.flush()
}
