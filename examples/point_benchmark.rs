//! Measures point-set reconstruction on seeded families of generated point sets with known
//! curves (`tests/point_sets/`): for each family, the share of sets the paper's crawl and the
//! robust crawl reconstruct exactly (every true edge, no other edge, exactly the true outliers).
//!
//! Two seeds: the development seed, on which the robust crawl's rules were worked out, and the
//! validation seed, only ever measured. Both are printed, as the table in `docs/point-sets.md`.
//!
//! ```sh
//! cargo run --release --example point_benchmark                  # both seeds, 100 sets a family
//! cargo run --release --example point_benchmark -- --sets 20     # a quicker look
//! cargo run --release --example point_benchmark -- --seed development --family sectors --failures
//! cargo run --release --example point_benchmark -- --write DIR   # the point files, to look at
//! ```

#[path = "../tests/point_sets/mod.rs"]
mod point_sets;

use std::fmt::Write as _;
use std::path::PathBuf;

use crawltrace::{reconstruct, reconstruct_robust};
use point_sets::families::FAMILIES;
use point_sets::{Instance, SplitMix64};
use rayon::prelude::*;

/// The seed the rules were developed on.
const DEVELOPMENT_SEED: u64 = 0x2016_0001;
/// The seed only measured, never tuned on.
const VALIDATION_SEED: u64 = 0x2016_0002;

struct Options {
    sets: usize,
    seeds: Vec<(&'static str, u64)>,
    family: Option<String>,
    failures: bool,
    write: Option<PathBuf>,
}

fn options() -> Options {
    let mut options = Options {
        sets: 100,
        seeds: vec![
            ("development", DEVELOPMENT_SEED),
            ("validation", VALIDATION_SEED),
        ],
        family: None,
        failures: false,
        write: None,
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--sets" => options.sets = args.next().and_then(|v| v.parse().ok()).unwrap_or(100),
            "--seed" => {
                let which = args.next().unwrap_or_default();
                options.seeds.retain(|(name, _)| *name == which);
            }
            "--family" => options.family = args.next(),
            "--failures" => options.failures = true,
            "--write" => options.write = args.next().map(PathBuf::from),
            _ => {
                eprintln!(
                    "usage: point_benchmark [--sets N] [--seed development|validation] [--family NAME] [--failures] [--write DIR]"
                );
                std::process::exit(2);
            }
        }
    }
    options
}

/// The instance's own seed: the run's seed, the family and the set's number mixed.
fn instance_seed(seed: u64, family: &str, k: usize) -> u64 {
    let mut mixed = seed;
    for byte in family.bytes() {
        mixed = (mixed ^ u64::from(byte)).wrapping_mul(0x100_0000_01B3);
    }
    let mut random = SplitMix64::new(mixed ^ (k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    random.next_u64()
}

/// Exact or not, by each method, with the robust crawl's mismatch.
struct Outcome {
    paper: bool,
    robust: bool,
    robust_mismatch: Option<String>,
}

fn run(instance: &Instance) -> Outcome {
    let paper = reconstruct(&instance.points).expect("generated points are valid");
    let robust = reconstruct_robust(&instance.points).expect("generated points are valid");
    let robust_mismatch = instance.mismatch(&robust);
    Outcome {
        paper: instance.mismatch(&paper).is_none(),
        robust: robust_mismatch.is_none(),
        robust_mismatch,
    }
}

fn write_instance(folder: &std::path::Path, seed_name: &str, k: usize, instance: &Instance) {
    let mut text = format!("# {} {}: {}\n", instance.family, k, instance.label);
    for p in &instance.points {
        let _ = writeln!(text, "{} {}", p.x, p.y);
    }
    let name = format!("{}-{seed_name}-{k:03}.txt", instance.family);
    std::fs::create_dir_all(folder).expect("output folder");
    std::fs::write(folder.join(name), text).expect("point file written");
}

fn main() {
    let options = options();
    let mut table = String::from("| family | sets |");
    for (name, _) in &options.seeds {
        let _ = write!(table, " paper, {name} | robust, {name} |");
    }
    table.push_str("\n|---|---:|");
    for _ in &options.seeds {
        table.push_str("---:|---:|");
    }
    table.push('\n');
    let mut totals = vec![(0usize, 0usize, 0usize); options.seeds.len()];
    for family in FAMILIES {
        if options.family.as_deref().is_some_and(|f| f != family.name) {
            continue;
        }
        let _ = write!(table, "| {} | {} |", family.name, options.sets);
        for (s, &(seed_name, seed)) in options.seeds.iter().enumerate() {
            let outcomes: Vec<(usize, Instance, Outcome)> = (0..options.sets)
                .into_par_iter()
                .map(|k| {
                    let mut random = SplitMix64::new(instance_seed(seed, family.name, k));
                    let instance = (family.make)(&mut random, k);
                    let outcome = run(&instance);
                    (k, instance, outcome)
                })
                .collect();
            let paper = outcomes.iter().filter(|(_, _, o)| o.paper).count();
            let robust = outcomes.iter().filter(|(_, _, o)| o.robust).count();
            for (k, instance, outcome) in &outcomes {
                if let Some(folder) = &options.write {
                    write_instance(folder, seed_name, *k, instance);
                }
                if options.failures {
                    if let Some(why) = &outcome.robust_mismatch {
                        eprintln!("{seed_name} #{k}: {why}");
                    }
                }
            }
            let rate = |count: usize| 100.0 * count as f64 / options.sets as f64;
            let _ = write!(table, " {:.0} % | {:.0} % |", rate(paper), rate(robust));
            totals[s].0 += options.sets;
            totals[s].1 += paper;
            totals[s].2 += robust;
        }
        table.push('\n');
    }
    let _ = write!(table, "| **all** | {} |", totals.first().map_or(0, |t| t.0));
    for &(sets, paper, robust) in &totals {
        let rate = |count: usize| 100.0 * count as f64 / sets.max(1) as f64;
        let _ = write!(
            table,
            " **{:.0} %** ({paper}) | **{:.0} %** ({robust}) |",
            rate(paper),
            rate(robust)
        );
    }
    println!("{table}");
    for family in FAMILIES {
        if options.family.as_deref().is_none_or(|f| f == family.name) {
            println!("- **{}**: {}", family.name, family.what);
        }
    }
}
