//! Issue 13's hostile inputs through the `crawltrace` binary: each gives a one-line error or a
//! result, in `trace`, in a batch (which finishes, writes its summary and report, exit 1) and in
//! `render`, under an address-space cap and a deadline so that a blow-up or a hang fails the test
//! instead of stalling it. Also kill -9 at several moments of a batch, then a rerun: the output
//! tree is exactly the clean run's, byte for byte.
//!
//! The deadlines catch hangs (the issue's cases ran for minutes), they are not speed targets;
//! speed is measured by `cargo bench`.

use crate::hostile;
use crate::support::cli::{self, stderr_lines};
use crate::support::files_under;

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::thread;
use std::time::{Duration, Instant};

use image::{DynamicImage, ImageFormat};

/// The address space a run may take, in KiB: a blow-up (the issue's 3.5 to 6.9 GB) aborts.
/// DECISION: 2 GiB of address space, not 500 MB, because address space counts thread stacks and
/// allocator arenas that are reserved, not used; resident memory is measured by hand (docs/cli.md, "Hostile input").
const ADDRESS_SPACE_KIB: u64 = 2 << 20;

/// A run that takes longer than this hangs (debug builds on a shared two-core machine).
const DEADLINE: Duration = Duration::from_secs(120);

/// Runs the binary in `folder` with `args` under the address-space cap, killing it past the
/// deadline; checks that it did not hang, crash or panic, and that its standard error is one
/// line per message (no message split over lines).
fn run(args: &[&str], folder: &Path) -> Output {
    run_with_limits(args, folder, "")
}

/// As [`run`], with more `ulimit` settings for the shell that starts the binary.
fn run_with_limits(args: &[&str], folder: &Path, ulimits: &str) -> Output {
    let script = format!("ulimit -v {ADDRESS_SPACE_KIB}; {ulimits} exec \"$0\" \"$@\"");
    let child = Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(cli::binary())
        .args(args)
        .current_dir(folder)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let output = wait_with_deadline(child, args);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        matches!(output.status.code(), Some(0..=3)),
        "crawltrace {args:?} crashed or was killed ({:?}):\n{stderr}",
        output.status
    );
    cli::assert_no_panic(args, &output);
    output
}

fn wait_with_deadline(mut child: Child, args: &[&str]) -> Output {
    let started = Instant::now();
    while child.try_wait().expect("waits").is_none() {
        if started.elapsed() > DEADLINE {
            let _ = child.kill();
            let _ = child.wait();
            panic!("crawltrace {args:?} still ran after {DEADLINE:?}: a hang");
        }
        thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("output is collected")
}

fn make_fifo(path: &Path) {
    let status = Command::new("mkfifo").arg(path).status().expect("mkfifo");
    assert!(status.success());
}

/// The hostile images: slow to trace, or lying about their size in their headers.
fn hostile_images() -> Vec<(&'static str, Vec<u8>)> {
    let png = |image| hostile::encode(&DynamicImage::ImageLuma8(image), ImageFormat::Png);
    let pbm = |image| hostile::encode(&DynamicImage::ImageLuma8(image), ImageFormat::Pnm);
    vec![
        ("specks.png", png(hostile::specks_page(600, 5, 1))),
        ("noise.pbm", pbm(hostile::noise_page(200, 2))),
        ("sof-20000.jpg", hostile::jpeg_claiming(20_000, 20_000)),
        ("sof-15000.jpg", hostile::jpeg_claiming(15_000, 15_000)),
        ("sof-65535.jpg", hostile::jpeg_claiming(65_535, 64)),
        ("ihdr-16000.png", hostile::png_claiming(16_000, 16_000)),
        ("ihdr-15000.png", hostile::png_claiming(15_000, 15_000)),
    ]
}

fn write_hostile_images(folder: &Path) {
    for (name, bytes) in hostile_images() {
        fs::write(folder.join(name), bytes).unwrap();
    }
}

#[test]
fn every_hostile_image_gives_a_result_or_one_line_error_in_trace() {
    let folder = tempfile::tempdir().unwrap();
    write_hostile_images(folder.path());
    for (name, _) in hostile_images() {
        // The noise page also with the smallest spacing the options allow.
        let spacing: &[&str] = if name == "noise.pbm" {
            &["--spacing", "0.5"]
        } else {
            &[]
        };
        let mut args = vec!["trace", name, "-o", "out.svg"];
        args.extend_from_slice(spacing);
        let output = run(&args, folder.path());
        let lines = stderr_lines(&output);
        assert_eq!(lines.len(), 1, "{name}: {lines:?}");
        match output.status.code() {
            Some(0) => assert!(lines[0].starts_with(name), "{name}: {lines:?}"),
            Some(2) => assert!(
                lines[0].starts_with(&format!("error: {name}: ")),
                "{lines:?}"
            ),
            other => panic!("{name}: exit {other:?}: {lines:?}"),
        }
    }
    // The headers that lie are refused, not decoded.
    for name in ["sof-20000.jpg", "ihdr-16000.png"] {
        let output = run(&["trace", name, "-o", "out.svg"], folder.path());
        assert_eq!(output.status.code(), Some(2), "{name}");
    }
}

#[test]
fn a_fifo_or_a_device_given_to_trace_is_refused_without_blocking() {
    let folder = tempfile::tempdir().unwrap();
    make_fifo(&folder.path().join("pipe.png"));
    for input in ["pipe.png", "/dev/zero"] {
        let output = run(&["trace", input, "-o", "out.svg"], folder.path());
        assert_eq!(output.status.code(), Some(2), "{input}");
        let lines = stderr_lines(&output);
        assert_eq!(lines.len(), 1, "{lines:?}");
        assert!(lines[0].contains("not a regular file"), "{lines:?}");
    }
}

/// Standard input that never ends and is no image (`cat /dev/zero | crawltrace trace -`) is
/// refused from its first bytes, not read into memory.
#[test]
fn endless_standard_input_is_refused_from_its_first_bytes() {
    let folder = tempfile::tempdir().unwrap();
    let child = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {ADDRESS_SPACE_KIB}; exec \"$0\" trace - -o out.svg"
        ))
        .arg(cli::binary())
        .current_dir(folder.path())
        .stdin(fs::File::open("/dev/zero").unwrap())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let output = wait_with_deadline(child, &["trace", "-"]);
    assert_eq!(output.status.code(), Some(2));
    let lines = stderr_lines(&output);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(
        lines[0].starts_with("error: <stdin>: not an image"),
        "{lines:?}"
    );
}

/// A batch of every hostile image, a FIFO named like an image and one good drawing: it finishes,
/// traces the good one, fails the bad ones alone with a line each, writes its summary and a
/// report line per input, and exits 1.
#[test]
fn a_batch_of_hostile_images_finishes_with_summary_report_and_exit_1() {
    let root = tempfile::tempdir().unwrap();
    let input = root.path().join("in");
    fs::create_dir(&input).unwrap();
    write_hostile_images(&input);
    make_fifo(&input.join("pipe.png"));
    let good = DynamicImage::ImageLuma8(hostile::small_drawing(120));
    fs::write(
        input.join("good.png"),
        hostile::encode(&good, ImageFormat::Png),
    )
    .unwrap();

    let args = ["trace", "in", "-o", "out", "--report", "report.jsonl"];
    let output = run(&args, root.path());
    let lines = stderr_lines(&output);
    assert_eq!(output.status.code(), Some(1), "{lines:?}");
    let inputs = hostile_images().len() + 2;
    // The specks page and the noise page are traced, as is the good drawing; the rest fail,
    // each with one error line.
    let failed = inputs - 3;
    let summary = lines.last().expect("a summary line");
    assert!(
        summary.starts_with(&format!("3 done, 0 skipped (up to date), {failed} failed")),
        "{summary}"
    );
    let errors = lines.iter().filter(|line| line.starts_with("error: in/"));
    assert_eq!(errors.count(), failed, "{lines:?}");
    let report = fs::read_to_string(root.path().join("report.jsonl")).unwrap();
    let entries: BTreeMap<String, serde_json::Value> = report
        .lines()
        .map(|line| {
            let value: serde_json::Value = serde_json::from_str(line).unwrap();
            let path = value["path"].as_str().unwrap().to_string();
            (path.rsplit('/').next().unwrap().to_string(), value)
        })
        .collect();
    assert_eq!(entries.len(), inputs, "{report}");
    assert!(entries.contains_key("pipe.png"), "{report}");
    assert!(root.path().join("out/good.svg").is_file());
    assert!(root.path().join("out/specks.svg").is_file());
    for refused in ["sof-20000.svg", "ihdr-16000.svg", "pipe.svg"] {
        assert!(!root.path().join("out").join(refused).exists(), "{refused}");
    }
}

fn write_hostile_svgs(folder: &Path) -> Vec<String> {
    let mut names = Vec::new();
    for (name, text) in hostile::hostile_svgs() {
        fs::write(folder.join(format!("{name}.svg")), text).unwrap();
        names.push(format!("{name}.svg"));
    }
    fs::write(folder.join("canvas-29999.svg"), hostile::svg_canvas(29_999)).unwrap();
    names.push("canvas-29999.svg".into());
    names
}

#[test]
fn every_hostile_svg_renders_or_gives_one_line_error() {
    let folder = tempfile::tempdir().unwrap();
    for name in write_hostile_svgs(folder.path()) {
        let output = run(&["render", &name, "-o", "out.png"], folder.path());
        let lines = stderr_lines(&output);
        match output.status.code() {
            Some(0) => assert!(lines.is_empty(), "{name}: {lines:?}"),
            Some(2) => {
                assert_eq!(lines.len(), 1, "{name}: {lines:?}");
                assert!(
                    lines[0].starts_with(&format!("error: {name}: ")),
                    "{lines:?}"
                );
            }
            other => panic!("{name}: exit {other:?}: {lines:?}"),
        }
    }
    for (name, refusal) in [
        ("canvas-29999.svg", "more than the limit"),
        ("turbulence-million-octaves.svg", "refusing to render"),
        ("uses-ten-levels.svg", "<use> elements would add"),
        ("arc-radius-1e38.svg", "an arc of radius"),
    ] {
        let output = run(&["render", name, "-o", "out.png"], folder.path());
        assert_eq!(output.status.code(), Some(2), "{name}");
        let line = &stderr_lines(&output)[0];
        assert!(line.contains(refusal), "{name}: {line}");
    }
}

/// `render` reads the one file it is given: images pointing at other files are not drawn.
#[test]
fn render_reads_no_file_but_its_input() {
    let folder = tempfile::tempdir().unwrap();
    let black = r#"<svg xmlns="http://www.w3.org/2000/svg" width="40" height="40"><rect width="40" height="40"/></svg>"#;
    fs::write(folder.path().join("black.svg"), black).unwrap();
    let black_png = hostile::encode(
        &DynamicImage::ImageLuma8(image::GrayImage::new(40, 40)),
        ImageFormat::Png,
    );
    fs::write(folder.path().join("black.png"), black_png).unwrap();
    make_fifo(&folder.path().join("pipe.png"));
    let absolute = folder.path().join("black.png");
    for href in [
        "black.svg",
        "black.png",
        absolute.to_str().unwrap(),
        "/dev/zero",
        "pipe.png",
        "/etc/passwd",
    ] {
        fs::write(folder.path().join("doc.svg"), hostile::svg_with_image(href)).unwrap();
        let output = run(&["render", "doc.svg", "-o", "out.png"], folder.path());
        assert_eq!(
            output.status.code(),
            Some(0),
            "{href}: {:?}",
            stderr_lines(&output)
        );
        let picture = image::open(folder.path().join("out.png"))
            .unwrap()
            .to_luma8();
        assert!(
            picture.pixels().all(|pixel| pixel.0[0] == 255),
            "{href} was read and drawn"
        );
    }
    // Nor is its input anything but a regular file.
    for input in ["pipe.png", "/dev/zero"] {
        let output = run(&["render", input, "-o", "out.png"], folder.path());
        assert_eq!(output.status.code(), Some(2), "{input}");
        assert!(stderr_lines(&output)[0].contains("not a regular file"));
    }
}

/// A render that outlives its processor-time budget is stopped and refused in one line (the
/// budget is forced down with `ulimit -t`, standing in for a construct that loops upstream).
#[test]
fn a_render_past_its_time_budget_is_refused() {
    let folder = tempfile::tempdir().unwrap();
    // Turbulence over a large canvas, within the cost budget: about three seconds of processor
    // time in a release build.
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="3000" height="3000"><filter id="f"><feTurbulence baseFrequency="0.05" numOctaves="4"/></filter><rect width="3000" height="3000" filter="url(#f)"/></svg>"#;
    fs::write(folder.path().join("slow.svg"), svg).unwrap();
    let output = run_with_limits(
        &["render", "slow.svg", "-o", "out.png"],
        folder.path(),
        "ulimit -t 1;",
    );
    assert_eq!(output.status.code(), Some(2));
    let lines = stderr_lines(&output);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(lines[0].contains("time budget"), "{lines:?}");
    assert!(!folder.path().join("out.png").exists());
}

/// A render that needs more memory than the sandbox allows is stopped and refused in one line
/// (the address space is forced down with `ulimit -v`, standing in for a construct that
/// allocates without bound upstream).
#[test]
fn a_render_past_its_memory_budget_is_refused() {
    let folder = tempfile::tempdir().unwrap();
    // A 9-megapixel canvas and a blurred layer: several hundred megabytes.
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="3000" height="3000"><filter id="f"><feGaussianBlur stdDeviation="20"/></filter><rect width="3000" height="3000" filter="url(#f)"/></svg>"#;
    fs::write(folder.path().join("big.svg"), svg).unwrap();
    let output = run_with_limits(
        &["render", "big.svg", "-o", "out.png"],
        folder.path(),
        "ulimit -v 100000;",
    );
    assert_eq!(output.status.code(), Some(2));
    let lines = stderr_lines(&output);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(
        lines[0].contains("more memory than its budget"),
        "{lines:?}"
    );
    assert!(!folder.path().join("out.png").exists());
}

/// Drawings in the kill -9 batch.
const KILL_BATCH_FILES: usize = 12;

/// Side of the batch's last drawing, px: about five times the area of the others, so that once
/// the other eleven SVGs are written the batch still runs for the whole of its trace, and a kill
/// after eleven outputs finds it running even when the test is slow to look.
const LAST_DRAWING_SIDE: u32 = 2000;

/// The drawings of the kill -9 batch: rings and bars of different sizes, enough work that the
/// kills land at different moments of the run. The largest is last in the batch's order.
fn kill_batch_inputs(folder: &Path) {
    for k in 0..KILL_BATCH_FILES {
        let side = if k == KILL_BATCH_FILES - 1 {
            LAST_DRAWING_SIDE
        } else {
            500 + 40 * k as u32
        };
        let drawing = DynamicImage::ImageLuma8(hostile::small_drawing(side));
        let format = if k % 3 == 0 {
            ImageFormat::Jpeg
        } else {
            ImageFormat::Png
        };
        let extension = if k % 3 == 0 { "jpg" } else { "png" };
        let sub = folder.join(if k % 2 == 0 { "a" } else { "b" });
        fs::create_dir_all(&sub).unwrap();
        let bytes = hostile::encode(&drawing, format);
        fs::write(sub.join(format!("d{k:02}.{extension}")), bytes).unwrap();
    }
}

/// Every file under `folder` (none while the batch has not made it yet).
fn tree(folder: &Path) -> BTreeMap<String, Vec<u8>> {
    if folder.exists() {
        files_under(folder)
    } else {
        BTreeMap::new()
    }
}

/// The SVGs in place under `folder` while a batch writes there. Names only: a temporary file
/// listed here may be renamed before it could be read, and an entry that goes away between the
/// listing and its look is skipped, not an error.
fn count_svgs(folder: &Path) -> usize {
    walkdir::WalkDir::new(folder)
        .into_iter()
        .filter_map(Result::ok)
        .filter(|entry| entry.file_type().is_file())
        .filter(|entry| entry.file_name().to_string_lossy().ends_with(".svg"))
        .count()
}

/// When a round kills the batch.
#[derive(Clone, Copy, Debug)]
enum Moment {
    /// Once this many SVGs are in place.
    AfterOutputs(usize),
    /// This long after the start.
    After(Duration),
}

impl Moment {
    /// An earlier moment, for the next attempt of a round whose kill came after the batch had
    /// finished (the machine was faster than the clean run, or the test slow to look).
    fn earlier(self) -> Moment {
        match self {
            Moment::AfterOutputs(count) => Moment::AfterOutputs(count.saturating_sub(1)),
            Moment::After(delay) => Moment::After(delay / 2),
        }
    }
}

/// Attempts per round: each later attempt kills earlier, and `After(0)` always hits.
const KILL_ATTEMPTS: usize = 4;

/// Starts the batch `args` in `folder` and kills it (SIGKILL) at `moment`: whether the kill found
/// it still running.
fn kill_at(moment: Moment, args: &[&str], folder: &Path, out_path: &Path) -> bool {
    let mut child = Command::new(cli::binary())
        .args(args)
        .current_dir(folder)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let started = Instant::now();
    loop {
        let due = match moment {
            Moment::After(delay) => started.elapsed() >= delay,
            Moment::AfterOutputs(count) => count_svgs(out_path) >= count,
        };
        let finished = child.try_wait().unwrap().is_some();
        if due || finished || started.elapsed() > DEADLINE {
            break;
        }
        thread::sleep(Duration::from_millis(2));
    }
    let running = child.try_wait().unwrap().is_none();
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    eprintln!(
        "{moment:?}: killed after {:?} {} with {} of {KILL_BATCH_FILES} SVGs written",
        started.elapsed(),
        if running { "while running" } else { "too late" },
        count_svgs(out_path)
    );
    running
}

/// Reruns the batch `args` after a kill: it succeeds, and `out_path` holds exactly the clean
/// run's files, byte for byte.
fn assert_rerun_restores(
    args: &[&str],
    folder: &Path,
    out_path: &Path,
    clean: &BTreeMap<String, Vec<u8>>,
) {
    let rerun = run(args, folder);
    assert_eq!(
        rerun.status.code(),
        Some(0),
        "{args:?}: {:?}",
        stderr_lines(&rerun)
    );
    let after = tree(out_path);
    assert_eq!(
        after.keys().collect::<Vec<_>>(),
        clean.keys().collect::<Vec<_>>(),
        "{args:?}: other files than the clean run's"
    );
    for (path, bytes) in &after {
        assert!(bytes == &clean[path], "{args:?}: {path:?} differs");
    }
}

/// Issue 13: kill -9 at any moment of a batch, then a rerun: the output tree holds exactly the
/// SVGs of a clean run, byte-identical, and nothing else (no temporary file, no truncated SVG).
/// The kills land before any output, after the first, halfway, near the end, and at fractions of
/// the clean run's time (which fall inside writes now and then). Every round must hit a running
/// batch, or the test would test nothing: a round whose kill came too late is checked all the
/// same and tried again a little earlier, in a fresh output folder.
#[test]
fn kill_9_at_several_moments_then_a_rerun_leaves_exactly_the_clean_outputs() {
    let root = tempfile::tempdir().unwrap();
    kill_batch_inputs(&root.path().join("in"));
    let args = ["trace", "in", "-o", "clean", "-r", "-q", "--jobs", "2"];
    let started = Instant::now();
    let clean_run = run(&args, root.path());
    let clean_time = started.elapsed();
    assert_eq!(
        clean_run.status.code(),
        Some(0),
        "{:?}",
        stderr_lines(&clean_run)
    );
    let clean = tree(&root.path().join("clean"));
    assert_eq!(clean.len(), KILL_BATCH_FILES);
    assert!(clean.keys().all(|path| path.ends_with(".svg")));

    let moments = [
        Moment::After(Duration::ZERO),
        Moment::AfterOutputs(1),
        Moment::AfterOutputs(KILL_BATCH_FILES / 2),
        Moment::AfterOutputs(KILL_BATCH_FILES - 1),
        Moment::After(clean_time / 4),
        Moment::After(clean_time * 2 / 3),
    ];
    for (round, &first) in moments.iter().enumerate() {
        let mut moment = first;
        let hit = (0..KILL_ATTEMPTS).any(|attempt| {
            let out = format!("out{round}-{attempt}");
            let out_path = root.path().join(&out);
            let args = ["trace", "in", "-o", &out, "-r", "-q", "--jobs", "2"];
            let running = kill_at(moment, &args, root.path(), &out_path);
            assert_rerun_restores(&args, root.path(), &out_path, &clean);
            moment = moment.earlier();
            running
        });
        assert!(
            hit,
            "round {round} ({first:?}): no kill in {KILL_ATTEMPTS} attempts hit a running batch"
        );
    }
}
