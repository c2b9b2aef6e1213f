//! The integration tests, linked into one binary so that `cargo test` links once, not once per
//! file. Each module was a test file of its own; run one with `cargo test --test it MODULE::`,
//! one test with `cargo test --test it MODULE::NAME`. The fuzz harness (`tests/fuzz/`) stays a
//! target of its own: it has its own `main`.

// The seeded generator `tests/support/random.rs` is one file, included by `#[path]` in each shared
// module that needs it (`support`, `hostile`, `point_sets`, the sample generator), because those
// modules are also included alone by the fuzz harness, benches and examples. Here they meet, so
// the file is compiled more than once; the copies are identical.
#![allow(clippy::duplicate_mod)]

#[path = "../hostile/mod.rs"]
mod hostile;
#[path = "../point_sets/mod.rs"]
mod point_sets;
#[path = "../support/mod.rs"]
mod support;

mod batch_engine;
mod bench_generator;
mod bench_regressions;
mod bench_scoring;
mod cli_batch;
mod cli_export;
#[cfg(unix)]
mod cli_hostile;
mod cli_points;
mod cli_trace;
mod fit_property;
mod golden;
mod ground_truth;
mod large_inputs;
mod reconstruct_properties;
mod robust_points;
mod samples_truth;
mod support_selftest;
