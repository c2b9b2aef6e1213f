//! Benchmarks of point-set reconstruction (divan): the Delaunay triangulation, the crawls on it
//! (the paper's and the robust one), the whole reconstruction by each, and the file stages of
//! `crawltrace points` (parsing, JSON), on 10k, 100k and 1M points sampled from many closed curves.
//!
//! ```sh
//! cargo bench --bench reconstruct
//! ```

#[path = "support/many_curves.rs"]
mod many_curves;
#[path = "../tests/support/random.rs"]
mod random;

use crawltrace::stages::crawl::algorithm::crawl;
use crawltrace::stages::crawl::neighbours::NeighbourGraph;
use crawltrace::stages::crawl::reconstruct::paper_closable;
use crawltrace::stages::crawl::robust;
use crawltrace::stages::points::write as pointset;
use crawltrace::{parse_points, reconstruct, reconstruct_robust, Point};
use divan::{black_box, Bencher};

fn main() {
    divan::main();
}

const SIZES: [usize; 3] = [10_000, 100_000, 1_000_000];

/// `count` points on many closed curves ([`many_curves::ellipse_points`]), rounded to 6 decimals
/// as in the file `examples/many_curves.rs` writes.
fn curve_points(count: usize) -> Vec<Point> {
    let round = |value: f64| (value * 1e6).round() / 1e6;
    many_curves::ellipse_points(count)
        .into_iter()
        .map(|(x, y)| Point::new(round(x), round(y)))
        .collect()
}

/// The distinct points in lexicographic order: what `reconstruct` triangulates.
fn canonical(points: &[Point]) -> Vec<Point> {
    let mut positions = points.to_vec();
    positions.sort_unstable_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    positions.dedup();
    positions
}

#[divan::bench(args = SIZES, sample_count = 5, sample_size = 1)]
fn triangulation(bencher: Bencher, count: usize) {
    let positions = canonical(&curve_points(count));
    bencher.bench(|| NeighbourGraph::delaunay(black_box(&positions)).unwrap());
}

#[divan::bench(args = SIZES, sample_count = 5, sample_size = 1)]
fn crawl_on_triangulation(bencher: Bencher, count: usize) {
    let positions = canonical(&curve_points(count));
    let graph = NeighbourGraph::delaunay(&positions).unwrap();
    bencher.bench(|| {
        crawl(black_box(&positions), black_box(&graph), |chain| {
            paper_closable(&positions, &graph, chain)
        })
    });
}

#[divan::bench(args = SIZES, sample_count = 5, sample_size = 1)]
fn robust_crawl_on_triangulation(bencher: Bencher, count: usize) {
    let positions = canonical(&curve_points(count));
    let graph = NeighbourGraph::delaunay(&positions).unwrap();
    bencher.bench(|| robust::crawl(black_box(&positions), black_box(&graph)));
}

#[divan::bench(args = SIZES, sample_count = 5, sample_size = 1)]
fn reconstruct_whole(bencher: Bencher, count: usize) {
    let points = curve_points(count);
    bencher.bench(|| reconstruct(black_box(&points)).unwrap());
}

#[divan::bench(args = SIZES, sample_count = 5, sample_size = 1)]
fn reconstruct_robust_whole(bencher: Bencher, count: usize) {
    let points = curve_points(count);
    bencher.bench(|| reconstruct_robust(black_box(&points)).unwrap());
}

/// The point file `crawltrace points` would read for `count` points.
fn point_file(count: usize) -> Vec<u8> {
    let mut text = String::new();
    for p in curve_points(count) {
        text.push_str(&format!("{} {}\n", p.x, p.y));
    }
    text.into_bytes()
}

#[divan::bench(args = SIZES, sample_count = 5, sample_size = 1)]
fn parse_point_file(bencher: Bencher, count: usize) {
    let bytes = point_file(count);
    bencher.bench(|| parse_points(black_box(&bytes)).unwrap());
}

#[divan::bench(args = SIZES, sample_count = 5, sample_size = 1)]
fn write_json(bencher: Bencher, count: usize) {
    let points = curve_points(count);
    let reconstruction = reconstruct(&points).unwrap();
    bencher.bench(|| {
        let mut out = Vec::new();
        pointset::write_json(&mut out, black_box(&points), &reconstruction).unwrap();
        out
    });
}
