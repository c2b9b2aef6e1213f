//! The fuzz harness of issue 13, on the stable toolchain: seeded mutations of images (header
//! fields, truncation, chunk edits, splices, bit flips), point files, SVGs and trace options, run
//! through the library's entry points (`decode_image` → `trace` → `to_svg`, `parse_points` →
//! `reconstruct`, `render_svg_with`). Every case runs in a worker process (this same binary with
//! `--worker`) under an address-space limit, and the parent is its watchdog: a case that panics,
//! aborts (a blow-up past the memory budget) or outlives its time budget is reported with its
//! kind, seed and index, its input saved under `target/fuzz-crashers/`, and the run goes on with a
//! fresh worker. Errors returned by the library are the expected answer to bad input.
//!
//! ```sh
//! cargo test --test fuzz                                     # the quick run (CI)
//! cargo test --release --test fuzz -- --cases 10000          # the long run (docs/fuzzing.md)
//! cargo test --release --test fuzz -- --cases 500 --kind svg --seed 7
//! cargo test --release --test fuzz -- --replay svg target/fuzz-crashers/svg-1-42.bin
//! cargo test --release --test fuzz -- --dump svg 1 42 > case.svg   # a case's input
//! ```
//!
//! `FUZZ_VERBOSE=1` prints every case's answer on standard error.
//!
//! A crasher, once understood, is kept as a named regression test beside the code it broke, and
//! its input in `tests/fuzz/regressions/` (replayed by every run).

#[path = "../hostile/mod.rs"]
mod hostile;
mod mutate;

use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitCode, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use mutate::{Case, Kind};

/// Cases per kind of the quick run, about a minute for all four kinds in a debug build on two
/// shared cores.
const QUICK_CASES: u64 = 1000;

/// DECISION: the time budget of one case, in processor time of its worker: 10 s, 60 s in a debug
/// build. The costliest render the library accepts takes about 4 s of one core
/// (`MAX_OPERATIONS`). Processor time, not wall-clock time, so that a loaded machine does not
/// report slow cases as hangs (a first long run with a 10 s wall-clock budget, next to two
/// builds, reported a dozen).
const CASE_CPU_BUDGET: Duration = if cfg!(debug_assertions) {
    Duration::from_secs(60)
} else {
    Duration::from_secs(10)
};

/// A worker that uses no processor time but does not answer (blocked on something) is stopped
/// after this much wall-clock time.
const CASE_WALL_BUDGET: Duration = Duration::from_secs(600);

/// DECISION: the worker's address space: 1 GiB. The issue's promise is 500 MB resident; address
/// space also counts what the allocator and the thread stacks reserve without using.
const MEMORY_BUDGET_BYTES: u64 = 1 << 30;

struct Settings {
    cases: u64,
    seed: u64,
    kinds: Vec<Kind>,
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--worker") {
        return worker(&args[1..]);
    }
    if let Some(at) = args.iter().position(|a| a == "--dump") {
        let kind = Kind::parse(&args[at + 1]).expect("a kind: image, points, svg, options");
        let number = |k: usize| args[at + k].parse::<u64>().expect("--dump KIND SEED INDEX");
        let case = mutate::case(kind, number(2), number(3));
        std::io::stdout().write_all(&case.bytes).expect("stdout");
        return ExitCode::SUCCESS;
    }
    if let Some(at) = args.iter().position(|a| a == "--replay") {
        let kind = Kind::parse(&args[at + 1]).expect("a kind: image, points, svg, options");
        let bytes = std::fs::read(&args[at + 2]).expect("the crasher's file");
        println!("{:?}", mutate::run_case(&Case { kind, bytes }));
        return ExitCode::SUCCESS;
    }
    // `cargo test` passes its own flags (`--quiet`, a name filter): only ours are read.
    let value = |flag: &str| {
        let at = args.iter().position(|a| a == flag)?;
        args.get(at + 1).cloned()
    };
    let settings = Settings {
        cases: value("--cases").map_or(QUICK_CASES, |n| n.parse().expect("--cases N")),
        seed: value("--seed").map_or(1, |n| n.parse().expect("--seed N")),
        kinds: value("--kind").map_or(Kind::ALL.to_vec(), |k| {
            vec![Kind::parse(&k).expect("--kind image|points|svg|options")]
        }),
    };
    let mut failures = replay_regressions();
    for &kind in &settings.kinds {
        let started = Instant::now();
        let tally = fuzz_kind(kind, settings.seed, settings.cases);
        println!(
            "fuzz {kind:?}: {} cases (seed {}) in {:.1} s, slowest {:.2} s, {} failing; outcomes {:?}",
            settings.cases,
            settings.seed,
            started.elapsed().as_secs_f64(),
            tally.slowest.as_secs_f64(),
            tally.failures.len(),
            tally.outcomes
        );
        // A harness whose mutations never get past the first check tests nothing: a tenth of the
        // cases at least must go all the way through (traced, reconstructed, rendered).
        let through = tally
            .outcomes
            .iter()
            .filter(|(outcome, _)| !outcome.starts_with("not "))
            .map(|(_, count)| count)
            .sum::<u64>();
        if through * 10 < settings.cases {
            failures.push(format!(
                "{kind:?}: only {through} of {} cases went all the way through",
                settings.cases
            ));
        }
        failures.extend(tally.failures);
    }
    for failure in &failures {
        println!("FAILED {failure}");
    }
    if failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// The saved inputs of past crashers, `tests/fuzz/regressions/<name>.<kind>` (kind: image,
/// points, svg or options), each run once in a worker like any case.
fn replay_regressions() -> Vec<String> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz/regressions");
    let Ok(entries) = std::fs::read_dir(&folder) else {
        return Vec::new();
    };
    let mut paths: Vec<PathBuf> = entries.map(|entry| entry.unwrap().path()).collect();
    paths.sort();
    let mut failures = Vec::new();
    println!("fuzz regressions: {} saved inputs replayed", paths.len());
    for path in paths {
        let kind = path
            .extension()
            .and_then(|extension| Kind::parse(extension.to_str()?));
        let Some(kind) = kind else { continue };
        let mut worker = Worker::start(&["--file", kind.name(), path.to_str().unwrap()]);
        if let Err(problem) = worker.next_case(0) {
            failures.push(format!("regression {}: {problem}", path.display()));
        }
        worker.finish();
    }
    failures
}

/// What a run of one kind saw.
#[derive(Default)]
struct Tally {
    slowest: Duration,
    /// How many cases ended in each outcome (`traced`, `not decoded`, ...).
    outcomes: BTreeMap<String, u64>,
    failures: Vec<String>,
}

/// Runs `cases` cases of `kind` from `seed`, restarting the worker after each failure.
fn fuzz_kind(kind: Kind, seed: u64, cases: u64) -> Tally {
    let mut tally = Tally::default();
    let mut next = 0;
    while next < cases {
        let range = [next.to_string(), cases.to_string()];
        let seed_text = seed.to_string();
        let mut worker = Worker::start(&["--cases", kind.name(), &seed_text, &range[0], &range[1]]);
        while next < cases {
            let started = Instant::now();
            let result = worker.next_case(next);
            tally.slowest = tally.slowest.max(started.elapsed());
            next += 1;
            match result {
                Ok(outcome) => *tally.outcomes.entry(outcome).or_default() += 1,
                Err(problem) => {
                    let saved = save_crasher(kind, seed, next - 1);
                    tally.failures.push(format!(
                        "{kind:?} seed {seed} case {}: {problem}; input {saved}; replay: cargo test --release --test fuzz -- --replay {} {saved}",
                        next - 1,
                        kind.name()
                    ));
                    break;
                }
            }
        }
        worker.finish();
    }
    tally
}

/// Writes the input of a failing case where it can be replayed from, and returns the path.
fn save_crasher(kind: Kind, seed: u64, index: u64) -> String {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/fuzz-crashers");
    let path = folder.join(format!("{}-{seed}-{index}.bin", kind.name()));
    let case = mutate::case(kind, seed, index);
    let saved = std::fs::create_dir_all(&folder).and_then(|()| std::fs::write(&path, &case.bytes));
    match saved {
        Ok(()) => path.display().to_string(),
        Err(e) => format!("(not saved: {e})"),
    }
}

/// A worker process and the lines it writes: `start N`, then `ok N <outcome>` or
/// `panic N <message>`.
struct Worker {
    child: Child,
    lines: mpsc::Receiver<String>,
}

impl Worker {
    fn start(args: &[&str]) -> Worker {
        let mut child = Command::new(std::env::current_exe().expect("the harness knows itself"))
            .arg("--worker")
            .args(args)
            // One thread: less address space reserved, and the same work on every machine.
            .env("RAYON_NUM_THREADS", "1")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("the worker starts");
        let stdout = child.stdout.take().expect("piped");
        let (sender, lines) = mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                if sender.send(line).is_err() {
                    break;
                }
            }
        });
        Worker { child, lines }
    }

    /// Waits for case `index` to finish within the budget; returns its outcome (`traced`,
    /// `not decoded`, ...).
    fn next_case(&mut self, index: u64) -> Result<String, String> {
        let started = Instant::now();
        let cpu_at_start = cpu_time(self.child.id());
        loop {
            match self.lines.recv_timeout(Duration::from_millis(500)) {
                Ok(line) if line.starts_with(&format!("ok {index} ")) => {
                    return Ok(line[4 + index.to_string().len()..].to_string())
                }
                Ok(line) if line.starts_with(&format!("panic {index} ")) => {
                    return Err(format!(
                        "panicked: {}",
                        &line[7 + index.to_string().len()..]
                    ))
                }
                Ok(_) => continue,
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    let used = cpu_time(self.child.id())
                        .zip(cpu_at_start)
                        .map(|(now, start)| now.saturating_sub(start));
                    let over_cpu = used.is_some_and(|used| used > CASE_CPU_BUDGET);
                    // Without /proc, the processor budget stands for wall-clock time.
                    let over_wall = started.elapsed()
                        > if used.is_some() {
                            CASE_WALL_BUDGET
                        } else {
                            CASE_CPU_BUDGET
                        };
                    if over_cpu || over_wall {
                        let _ = self.child.kill();
                        let _ = self.child.wait();
                        return Err(format!(
                            "hung: {:?} of processor time, {:?} in all",
                            used.unwrap_or_default(),
                            started.elapsed()
                        ));
                    }
                }
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    let status = self.child.wait().expect("the worker is waited for");
                    return Err(format!(
                        "the worker died ({status}): an abort, most likely memory past {} MiB",
                        MEMORY_BUDGET_BYTES >> 20
                    ));
                }
            }
        }
    }

    fn finish(mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The processor time (user and system) process `pid` has used so far, from `/proc` (Linux);
/// `None` elsewhere. DECISION: `/proc` counts in USER_HZ, 100 a second on every Linux platform.
fn cpu_time(pid: u32) -> Option<Duration> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name, in parentheses, may hold spaces: count fields after it. The state is
    // field 3 of the line, utime and stime fields 14 and 15.
    let fields: Vec<&str> = stat.get(stat.rfind(')')? + 2..)?.split(' ').collect();
    let ticks = |at: usize| fields.get(at)?.parse::<u64>().ok();
    Some(Duration::from_millis((ticks(11)? + ticks(12)?) * 10))
}

/// The worker: limits its own memory, then runs its cases, reporting each on standard output.
fn worker(args: &[String]) -> ExitCode {
    limit_memory(MEMORY_BUDGET_BYTES);
    // The panic message goes to the parent with the case number, not to standard error.
    let message = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
    let hook_message = message.clone();
    std::panic::set_hook(Box::new(move |info| {
        let location = info.location().map(|l| l.to_string()).unwrap_or_default();
        let payload = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        *hook_message.lock().unwrap() = format!("{payload} at {location}").replace('\n', " ");
    }));
    let cases: Box<dyn Iterator<Item = (u64, Case)>> = match args[0].as_str() {
        "--file" => {
            let kind = Kind::parse(&args[1]).expect("kind");
            let bytes = std::fs::read(&args[2]).expect("regression file");
            Box::new(std::iter::once((0, Case { kind, bytes })))
        }
        _ => {
            let kind = Kind::parse(&args[1]).expect("kind");
            let number = |at: usize| args[at].parse::<u64>().expect("a number");
            let (seed, from, to) = (number(2), number(3), number(4));
            Box::new((from..to).map(move |index| (index, mutate::case(kind, seed, index))))
        }
    };
    let mut stdout = std::io::stdout();
    for (index, case) in cases {
        let _ = writeln!(stdout, "start {index}");
        let _ = stdout.flush();
        let started = Instant::now();
        let outcome = std::panic::catch_unwind(|| mutate::run_case(&case));
        let line = match outcome {
            Ok(answer) => {
                if std::env::var_os("FUZZ_VERBOSE").is_some() {
                    eprintln!(
                        "{} {index}: {answer} ({:.2} s)",
                        case.kind.name(),
                        started.elapsed().as_secs_f64()
                    );
                }
                let outcome = answer.split(':').next().unwrap_or_default().to_string();
                format!("ok {index} {outcome}")
            }
            Err(_) => format!("panic {index} {}", message.lock().unwrap()),
        };
        let _ = writeln!(stdout, "{line}");
        let _ = stdout.flush();
    }
    ExitCode::SUCCESS
}

#[cfg(unix)]
fn limit_memory(bytes: u64) {
    use rustix::process::{getrlimit, setrlimit, Resource, Rlimit};
    let hard = getrlimit(Resource::As).maximum;
    let wanted = hard.map_or(bytes, |hard| hard.min(bytes));
    let _ = setrlimit(
        Resource::As,
        Rlimit {
            current: Some(wanted),
            maximum: hard,
        },
    );
}

#[cfg(not(unix))]
fn limit_memory(_bytes: u64) {}
