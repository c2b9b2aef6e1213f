//! Times each stage of `crawltrace points` on a point file (a profiling aid, not a benchmark):
//! read, parse, triangulate, crawl, the whole `reconstruct`, and JSON writing. With a repeat
//! count, each stage's fastest time over that many runs is shown (the machine is shared).
//!
//! ```sh
//! cargo run --release --example stage_times -- big.txt 5
//! ```

use std::time::Instant;

use crawltrace::stages::crawl::algorithm::crawl;
use crawltrace::stages::crawl::neighbours::NeighbourGraph;
use crawltrace::stages::crawl::reconstruct::paper_closable;
use crawltrace::stages::points::write as pointset;
use crawltrace::{parse_points, reconstruct, Point};

fn main() {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: stage_times POINT_FILE [REPEAT]");
        std::process::exit(2);
    };
    let repeat: usize = std::env::args()
        .nth(2)
        .map_or(1, |text| text.parse().expect("REPEAT is a count"));
    let mut fastest = [f64::INFINITY; 7];
    for _ in 0..repeat {
        for (best, time) in fastest.iter_mut().zip(run(&path)) {
            *best = best.min(time);
        }
    }
    for (stage, time) in STAGES.iter().zip(fastest) {
        println!("{stage:>18}: {:8.1} ms", time * 1e3);
    }
}

const STAGES: [&str; 7] = [
    "read",
    "parse",
    "sort + dedup",
    "triangulate",
    "crawl",
    "reconstruct (all)",
    "write JSON",
];

/// One run; returns each stage's time in seconds.
fn run(path: &str) -> [f64; 7] {
    let clock = Instant::now();
    let bytes = std::fs::read(path).expect("readable point file");
    let read = clock.elapsed();

    let clock = Instant::now();
    let file = parse_points(&bytes).expect("a valid point file");
    let parse = clock.elapsed();

    // The distinct points in lexicographic order, as `reconstruct` triangulates them.
    let clock = Instant::now();
    let mut positions: Vec<Point> = file.points.clone();
    positions.sort_unstable_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    positions.dedup();
    let sort = clock.elapsed();

    let clock = Instant::now();
    let graph = NeighbourGraph::delaunay(&positions).expect("triangulable points");
    let triangulate = clock.elapsed();

    let clock = Instant::now();
    let chains = crawl(&positions, &graph, |chain| {
        paper_closable(&positions, &graph, chain)
    });
    let crawling = clock.elapsed();

    let clock = Instant::now();
    let reconstruction = reconstruct(&file.points).expect("reconstructible points");
    let whole = clock.elapsed();

    let clock = Instant::now();
    let mut json = Vec::new();
    pointset::write_json(&mut json, &file.points, &reconstruction).expect("JSON in memory");
    let write = clock.elapsed();

    eprintln!(
        "{} points, {} distinct, {} chains, {} curves",
        file.points.len(),
        positions.len(),
        chains.len(),
        reconstruction.curves.len()
    );
    [read, parse, sort, triangulate, crawling, whole, write].map(|time| time.as_secs_f64())
}
