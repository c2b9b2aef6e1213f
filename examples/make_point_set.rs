//! Writes `samples/points/shapes.txt`, the sample point set of `docs/point-sets.md`: the cases the paper
//! shows (an object with a hole, several objects, sharp corners, an open curve, sparse samples,
//! outliers), sampled with a little jitter by a seeded generator, so the file is the same on
//! every run. Run: `cargo run --example make_point_set [OUT_FILE]`.

#[path = "../tests/support/random.rs"]
mod random;
use random::SplitMix64;

use std::f64::consts::TAU;
use std::fmt::Write as _;

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "samples/points/shapes.txt".to_string());
    let mut random = SplitMix64::new(2016);
    let mut points: Vec<(f64, f64)> = Vec::new();
    let mut ellipse = |points: &mut Vec<(f64, f64)>, c: (f64, f64), r: (f64, f64), n: usize| {
        for i in 0..n {
            let a = TAU * (i as f64 + random.jitter(0.15)) / n as f64;
            points.push((c.0 + r.0 * a.cos(), c.1 + r.1 * a.sin()));
        }
    };
    // A ring: an object with a hole.
    ellipse(&mut points, (120.0, 115.0), (90.0, 70.0), 66);
    ellipse(&mut points, (120.0, 115.0), (45.0, 30.0), 34);
    // A sparse circle.
    ellipse(&mut points, (330.0, 90.0), (40.0, 40.0), 18);
    let mut random = SplitMix64::new(7);
    // A square and a house: sharp corners.
    let mut polygon = |points: &mut Vec<(f64, f64)>, corners: &[(f64, f64)], step: f64| {
        for k in 0..corners.len() {
            let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
            let length = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
            let count = (length / step).round() as usize;
            for i in 0..count {
                let t = i as f64 / count as f64;
                let wobble = if i == 0 { 0.0 } else { random.jitter(0.6) };
                points.push((
                    a.0 + t * (b.0 - a.0) + wobble,
                    a.1 + t * (b.1 - a.1) + wobble,
                ));
            }
        }
    };
    polygon(
        &mut points,
        &[
            (260.0, 180.0),
            (400.0, 180.0),
            (400.0, 300.0),
            (260.0, 300.0),
        ],
        8.0,
    );
    polygon(
        &mut points,
        &[
            (40.0, 345.0),
            (200.0, 345.0),
            (200.0, 270.0),
            (120.0, 215.0),
            (40.0, 270.0),
        ],
        8.0,
    );
    // An open wave, sampled more sparsely than the rest: the crawl seeds the shortest edges
    // first, so the other curves are done before it starts and its ends find nothing to join.
    for i in 0..25 {
        let x = 30.0 + i as f64 * 16.0;
        points.push((x, 400.0 + 18.0 * (x / 30.0).sin()));
    }
    // Outliers, away from the curves and enclosed by them: an outlier within reach of an open
    // curve's end is taken by it (the paper's own limit with open curves).
    for &p in &[
        (120.0, 115.0),
        (330.0, 90.0),
        (330.0, 240.0),
        (300.0, 270.0),
        (120.0, 300.0),
    ] {
        points.push(p);
    }
    let mut text = String::from(
        "# crawltrace sample point set: a ring, a sparse circle, a square, a house, an open wave\n\
         # and five outliers; made by examples/make_point_set.rs\n",
    );
    for (x, y) in points {
        let _ = writeln!(text, "{x:.3} {y:.3}");
    }
    std::fs::write(&out, text).unwrap_or_else(|e| panic!("{out}: {e}"));
    eprintln!("wrote {out}");
}
