//! Runs the `crawltrace` binary in batch mode on a temporary tree of real skip-stroke drawings
//! (PNG and JPEG, nested folders) with broken files among them: mirrored outputs, error lines,
//! summary, exit codes, `--report`, resuming, `--force`, `--shard`, `--glob`, `--quiet`.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;
use std::process::Output;
use std::time::{Duration, SystemTime};

use image::{DynamicImage, GrayImage, ImageFormat, Luma};

use crate::support::cli::{self, describe, stderr_lines};
use crate::support::{files_under, set_modified};

/// Runs the binary in `folder` (no panic: [`cli::run`]) and checks what must hold for every batch
/// run: nothing on standard output (batch results go to files), and no progress bar, since stderr
/// is a pipe here and not a terminal (no carriage returns, no ANSI escapes).
fn run(args: &[&str], folder: &Path) -> Output {
    let output = cli::run(args, folder);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !stderr.contains('\r') && !stderr.contains('\x1b'),
        "a progress bar or escape codes on a stderr that is not a terminal:\n{}",
        describe(args, &output)
    );
    assert!(
        output.stdout.is_empty(),
        "batch mode wrote to stdout:\n{}",
        describe(args, &output)
    );
    output
}

/// Runs the binary as [`run`] does and checks its exit code.
fn run_expecting(code: i32, args: &[&str], folder: &Path) -> Output {
    cli::expect_code(code, args, run(args, folder))
}

/// The drawings of the test tree: what is drawn, and how many paths (closed among them) the
/// tracer must give back.
#[derive(Clone, Copy, Debug)]
enum Drawing {
    /// A dashed circle and a dashed wave.
    CircleAndWave,
    /// A dashed rectangle.
    Rectangle,
    /// Two dashed circles side by side.
    TwoCircles,
}

impl Drawing {
    fn expected_paths(self) -> (usize, usize) {
        match self {
            Drawing::CircleAndWave => (2, 1),
            Drawing::Rectangle => (1, 1),
            Drawing::TwoCircles => (2, 2),
        }
    }

    /// A skip-stroke sketch of the drawing ([`cli::dashed_sketch`]).
    fn render(self) -> GrayImage {
        let shapes = match self {
            Drawing::CircleAndWave => cli::CIRCLE_AND_WAVE,
            Drawing::Rectangle => r#"<rect x="40" y="40" width="150" height="110"/>"#,
            Drawing::TwoCircles => {
                r#"<circle cx="65" cy="100" r="42"/><circle cx="175" cy="100" r="42"/>"#
            }
        };
        cli::dashed_sketch(240, 200, shapes)
    }
}

/// The images of the test tree that trace, by path relative to `in/`.
const GOOD: [(&str, Drawing, ImageFormat); 4] = [
    ("top.png", Drawing::CircleAndWave, ImageFormat::Png),
    ("x/y.png", Drawing::Rectangle, ImageFormat::Png),
    ("x/z.jpg", Drawing::CircleAndWave, ImageFormat::Jpeg),
    ("x/deep/w.png", Drawing::TwoCircles, ImageFormat::Png),
];

/// The files of the test tree that fail, by path relative to `in/`, with a part of their message.
const BAD: [(&str, &str); 3] = [
    ("bad/blank.png", "no drawing found"),
    ("bad/notes.png", "not an image"),
    ("bad/truncated.png", "corrupt or truncated"),
];

fn write_file(path: &Path, bytes: &[u8]) {
    fs::create_dir_all(path.parent().unwrap()).unwrap();
    fs::write(path, bytes).unwrap();
}

fn encode(image: &GrayImage, format: ImageFormat) -> Vec<u8> {
    let mut bytes = Vec::new();
    DynamicImage::ImageLuma8(image.clone())
        .write_to(&mut std::io::Cursor::new(&mut bytes), format)
        .expect("test image encodes");
    bytes
}

/// A temporary folder holding `in/`: the [`GOOD`] drawings, the [`BAD`] files (a blank white
/// page, a text file named `.png`, a PNG cut in half) and a text file that is not an image.
fn test_tree() -> tempfile::TempDir {
    let root = tempfile::tempdir().unwrap();
    let input = root.path().join("in");
    for (relative, drawing, format) in GOOD {
        write_file(&input.join(relative), &encode(&drawing.render(), format));
    }
    let blank = GrayImage::from_pixel(120, 90, Luma([255]));
    write_file(
        &input.join("bad/blank.png"),
        &encode(&blank, ImageFormat::Png),
    );
    write_file(&input.join("bad/notes.png"), b"this is text, not a picture");
    let png = encode(&Drawing::Rectangle.render(), ImageFormat::Png);
    write_file(&input.join("bad/truncated.png"), &png[..png.len() / 2]);
    write_file(&input.join("readme.txt"), b"not an image");
    root
}

/// The `.svg` files under `folder`, by relative path with `/`.
fn svgs_under(folder: &Path) -> BTreeSet<String> {
    files_under(folder)
        .into_keys()
        .filter(|name| name.ends_with(".svg"))
        .collect()
}

fn modified(path: &Path) -> SystemTime {
    fs::metadata(path).unwrap().modified().unwrap()
}

/// The output of `relative` (an input path with `/`): the same path with the extension `svg`.
fn svg_name(relative: &str) -> String {
    Path::new(relative)
        .with_extension("svg")
        .to_string_lossy()
        .replace('\\', "/")
}

/// Parses `svg` with usvg and returns its number of paths, and of closed ones (ending in `Z`).
fn count_paths(name: &str, svg: &[u8]) -> (usize, usize) {
    let text = std::str::from_utf8(svg).unwrap_or_else(|_| panic!("{name}: not UTF-8"));
    let tree = usvg::Tree::from_str(text, &usvg::Options::default())
        .unwrap_or_else(|error| panic!("{name}: usvg refuses it: {error}\n{text}"));
    fn parsed_paths(group: &usvg::Group) -> usize {
        group
            .children()
            .iter()
            .map(|node| match node {
                usvg::Node::Path(_) => 1,
                usvg::Node::Group(group) => parsed_paths(group),
                _ => 0,
            })
            .sum()
    }
    let paths = text.matches("<path ").count();
    assert_eq!(parsed_paths(tree.root()), paths, "{name}: usvg lost paths");
    let closed = text
        .lines()
        .filter(|line| line.starts_with("<path") && line.contains('Z'))
        .count();
    (paths, closed)
}

/// Checks that `out` holds exactly the outputs of `relatives` (good inputs, paths under the
/// input folder given) and that each has the paths of its drawing; `run` (the command and its
/// stderr) is shown on failure.
fn assert_outputs(out: &Path, relatives: &[(&str, Drawing)], run: &str) {
    let files = files_under(out);
    let svgs: BTreeSet<String> = files
        .keys()
        .filter(|name| name.ends_with(".svg"))
        .cloned()
        .collect();
    let expected: BTreeSet<String> = relatives.iter().map(|(r, _)| svg_name(r)).collect();
    assert_eq!(svgs, expected, "outputs in {}\n{run}", out.display());
    for (relative, drawing) in relatives {
        let name = svg_name(relative);
        assert_eq!(
            count_paths(&name, &files[&name]),
            drawing.expected_paths(),
            "{name}:\n{}\n{run}",
            String::from_utf8_lossy(&files[&name])
        );
    }
}

fn good_under(prefix: &str) -> Vec<(&'static str, Drawing)> {
    GOOD.iter()
        .filter(|(relative, _, _)| relative.starts_with(prefix))
        .map(|&(relative, drawing, _)| (relative, drawing))
        .collect()
}

/// The summary line without its trailing `(N.N s)`, which is the one part that varies.
fn summary_without_time(line: &str) -> &str {
    let cut = line
        .rfind(" (")
        .unwrap_or_else(|| panic!("no time in {line:?}"));
    assert!(line.ends_with(" s)"), "{line:?}");
    &line[..cut]
}

/// Checks that `lines` hold one error line for each of the [`BAD`] files, with its message.
fn assert_failure_lines(lines: &[String], input_folder: &str) {
    let errors: Vec<&String> = lines
        .iter()
        .filter(|line| line.starts_with("error: "))
        .collect();
    assert_eq!(errors.len(), BAD.len(), "{lines:#?}");
    // Workers finish in any order, so the lines are matched by file, not by position.
    for (relative, message) in BAD {
        let prefix = format!("error: {input_folder}/{relative}: ");
        let line = errors
            .iter()
            .find(|line| line.starts_with(&prefix))
            .unwrap_or_else(|| panic!("no line starting {prefix:?} in {lines:#?}"));
        assert!(line.contains(message), "{line:?} should say {message:?}");
    }
}

#[test]
fn a_folder_is_mirrored_recursively_and_failures_are_reported() {
    let root = test_tree();
    let args = ["trace", "in", "-o", "out", "-r"];
    let output = run_expecting(1, &args, root.path());

    assert_outputs(
        &root.path().join("out"),
        &good_under(""),
        &describe(&args, &output),
    );
    let lines = stderr_lines(&output);
    assert_failure_lines(&lines, "in");
    assert_eq!(lines.len(), BAD.len() + 1, "{}", describe(&args, &output));
    assert_eq!(
        summary_without_time(lines.last().unwrap()),
        "4 done, 0 skipped (up to date), 3 failed, 1 not images"
    );
    // No temporary file is left behind, and nothing but SVGs is written.
    let written = files_under(&root.path().join("out"));
    assert!(
        written.keys().all(|name| name.ends_with(".svg")),
        "{:?}",
        written.keys()
    );
}

#[test]
fn without_recursive_only_the_top_level_is_traced() {
    let root = test_tree();
    let args = ["trace", "in", "-o", "out"];
    let output = run_expecting(0, &args, root.path());
    assert_outputs(
        &root.path().join("out"),
        &good_under("top"),
        &describe(&args, &output),
    );
    assert_eq!(
        summary_without_time(&stderr_lines(&output)[0]),
        "1 done, 0 skipped (up to date), 0 failed, 1 not images"
    );

    // A subfolder given as the input is the root of the mirrored layout.
    let args = ["trace", "in/x", "-o", "out-x"];
    let output = run_expecting(0, &args, root.path());
    assert_outputs(
        &root.path().join("out-x"),
        &[
            ("y.png", Drawing::Rectangle),
            ("z.jpg", Drawing::CircleAndWave),
        ],
        &describe(&args, &output),
    );

    // Files named on the command line land at the top of the output folder.
    let args = ["trace", "in/x/deep/w.png", "in/top.png", "-o", "out-files"];
    let output = run_expecting(0, &args, root.path());
    assert_outputs(
        &root.path().join("out-files"),
        &[
            ("w.png", Drawing::TwoCircles),
            ("top.png", Drawing::CircleAndWave),
        ],
        &describe(&args, &output),
    );
}

#[test]
fn one_folder_without_output_gets_the_svgs_beside_its_images() {
    let root = test_tree();
    let before = files_under(&root.path().join("in"));
    run_expecting(1, &["trace", "in", "-r", "-q"], root.path());
    let after = files_under(&root.path().join("in"));
    for (name, bytes) in &before {
        assert!(after[name] == *bytes, "the input {name} changed");
    }
    let expected: BTreeSet<String> = GOOD.iter().map(|(r, _, _)| svg_name(r)).collect();
    assert_eq!(svgs_under(&root.path().join("in")), expected);
}

#[test]
fn usage_errors_exit_with_2_before_any_work() {
    let root = test_tree();
    let cases: [(&[&str], &str); 6] = [
        (&["trace", "in/top.png", "in/x/y.png"], "needs -o OUTDIR"),
        (&["trace", "in", "-o", "-"], "standard output"),
        (&["trace", "in", "-o", "out", "--shard", "4/3"], "4/3"),
        (&["trace", "in", "-o", "out", "--shard", "two"], "K/N"),
        (&["trace", "in", "-o", "out", "--jobs", "0"], "--jobs"),
        (
            &["trace", "in", "missing", "-o", "out"],
            "missing: no such file",
        ),
    ];
    for (args, expected) in cases {
        let output = run_expecting(2, args, root.path());
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.starts_with("error: ") && stderr.contains(expected),
            "should say {expected:?}:\n{}",
            describe(args, &output)
        );
        assert!(
            !root.path().join("out").exists(),
            "an output folder was made:\n{}",
            describe(args, &output)
        );
        assert!(
            svgs_under(root.path()).is_empty(),
            "{}",
            describe(args, &output)
        );
    }
}

#[test]
fn the_report_has_one_json_line_per_input() {
    let root = test_tree();
    let args = [
        "trace",
        "in",
        "-o",
        "out",
        "-r",
        "-q",
        "--report",
        "report.jsonl",
    ];
    run_expecting(1, &args, root.path());
    let text = fs::read_to_string(root.path().join("report.jsonl")).unwrap();
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|line| serde_json::from_str(line).unwrap_or_else(|e| panic!("{e}: {line}")))
        .collect();
    assert_eq!(lines.len(), GOOD.len() + BAD.len(), "{text}");

    let by_path: BTreeMap<String, &serde_json::Value> = lines
        .iter()
        .map(|line| (line["path"].as_str().unwrap().replace('\\', "/"), line))
        .collect();
    for (relative, drawing, _) in GOOD {
        let line = by_path[&format!("in/{relative}")];
        let (curves, closed) = drawing.expected_paths();
        assert_eq!(line["status"], "done", "{line}");
        assert_eq!(line["curves"], curves, "{line}");
        assert_eq!(line["closed_curves"], closed, "{line}");
        assert!(line["seconds"].as_f64().is_some_and(|s| s >= 0.0), "{line}");
        assert!(line["error"].is_null(), "{line}");
    }
    for (relative, message) in BAD {
        let line = by_path[&format!("in/{relative}")];
        assert_eq!(line["status"], "failed", "{line}");
        assert!(
            line["curves"].is_null() && line["closed_curves"].is_null(),
            "{line}"
        );
        assert!(
            line["error"].as_str().is_some_and(|e| e.contains(message)),
            "{line}"
        );
    }

    // On the next run the traced files are reported as skipped, and the broken ones again.
    run_expecting(1, &args, root.path());
    let text = fs::read_to_string(root.path().join("report.jsonl")).unwrap();
    let statuses: Vec<String> = text
        .lines()
        .map(|line| {
            let line: serde_json::Value = serde_json::from_str(line).unwrap();
            line["status"].as_str().unwrap().to_string()
        })
        .collect();
    assert_eq!(
        statuses.iter().filter(|s| *s == "skipped").count(),
        GOOD.len()
    );
    assert_eq!(
        statuses.iter().filter(|s| *s == "failed").count(),
        BAD.len()
    );
}

#[test]
fn the_report_can_go_into_the_output_folder_the_run_makes() {
    let root = test_tree();
    let args = ["trace", "in/x", "-o", "out", "--report", "out/report.jsonl"];
    let output = run_expecting(0, &args, root.path());
    let report = fs::read_to_string(root.path().join("out/report.jsonl")).unwrap();
    assert_eq!(report.lines().count(), 2, "{report}");
    assert_outputs(
        &root.path().join("out"),
        &[
            ("y.png", Drawing::Rectangle),
            ("z.jpg", Drawing::CircleAndWave),
        ],
        &describe(&args, &output),
    );

    // A report in a folder that nothing makes is still refused before any work.
    let args = [
        "trace",
        "in/x",
        "-o",
        "out-2",
        "--report",
        "missing/report.jsonl",
    ];
    let output = run_expecting(2, &args, root.path());
    assert!(
        stderr_lines(&output)[0].contains("its folder does not exist"),
        "{}",
        describe(&args, &output)
    );
    assert!(!root.path().join("out-2").exists());
}

#[test]
fn a_second_run_skips_everything_and_force_redoes_it() {
    let root = test_tree();
    let out = root.path().join("out");
    let args = ["trace", "in", "-o", "out", "-r"];
    run_expecting(1, &args, root.path());
    let first = files_under(&out);
    let first_times: BTreeMap<&String, SystemTime> = first
        .keys()
        .map(|name| (name, modified(&out.join(name))))
        .collect();

    let output = run_expecting(1, &args, root.path());
    let lines = stderr_lines(&output);
    assert_failure_lines(&lines, "in");
    assert_eq!(
        summary_without_time(lines.last().unwrap()),
        "0 done, 4 skipped (up to date), 3 failed, 1 not images"
    );
    assert_eq!(files_under(&out), first, "a skipped output changed");
    for (name, time) in &first_times {
        assert_eq!(modified(&out.join(name)), *time, "{name} was rewritten");
    }

    // A skipped output is not even read: spoil one and date it after its input; only `--force`
    // puts it right.
    let spoiled = out.join("x/y.svg");
    fs::write(&spoiled, "spoiled").unwrap();
    set_modified(&spoiled, SystemTime::now() + Duration::from_secs(3600));
    run_expecting(1, &args, root.path());
    assert_eq!(fs::read(&spoiled).unwrap(), b"spoiled");

    let forced = ["trace", "in", "-o", "out", "-r", "--force"];
    let output = run_expecting(1, &forced, root.path());
    assert_eq!(
        summary_without_time(stderr_lines(&output).last().unwrap()),
        "4 done, 0 skipped (up to date), 3 failed, 1 not images"
    );
    assert_eq!(files_under(&out), first, "--force did not redo the output");
}

#[test]
fn an_input_newer_than_its_output_is_traced_again() {
    let root = test_tree();
    let out = root.path().join("out");
    run_expecting(0, &["trace", "in/x", "-o", "out"], root.path());
    // Date the outputs in the past rather than waiting for the clock to move.
    let past = SystemTime::now() - Duration::from_secs(3600);
    set_modified(&out.join("y.svg"), past);
    let untouched = modified(&out.join("z.svg"));
    let output = run_expecting(0, &["trace", "in/x", "-o", "out"], root.path());
    assert_eq!(
        summary_without_time(&stderr_lines(&output)[0]),
        "1 done, 1 skipped (up to date), 0 failed"
    );
    assert!(modified(&out.join("y.svg")) > past);
    assert_eq!(modified(&out.join("z.svg")), untouched);
}

#[test]
fn shards_together_produce_every_output_exactly_once() {
    let root = test_tree();
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut error_lines = Vec::new();
    for index in 1..=3 {
        let shard = format!("{index}/3");
        let out = format!("out-{index}");
        let args = ["trace", "in", "-o", &out, "-r", "--shard", &shard];
        let output = run(&args, root.path());
        let lines = stderr_lines(&output);
        let failed = lines.iter().filter(|l| l.starts_with("error: ")).count();
        assert_eq!(
            output.status.code(),
            Some(i32::from(failed > 0)),
            "{}",
            describe(&args, &output)
        );
        error_lines.extend(lines.iter().filter(|l| l.starts_with("error: ")).cloned());
        for name in svgs_under(&root.path().join(&out)) {
            *seen.entry(name).or_default() += 1;
        }
    }
    let expected: BTreeMap<String, usize> = GOOD.iter().map(|(r, _, _)| (svg_name(r), 1)).collect();
    assert_eq!(seen, expected);
    assert_failure_lines(&error_lines, "in");

    // Into one shared folder, one shard after another: the same set, each written by one shard.
    let mut runs = String::new();
    for index in 1..=3 {
        let shard = format!("{index}/3");
        let args = ["trace", "in", "-o", "shared", "-r", "--shard", &shard];
        runs += &describe(&args, &run(&args, root.path()));
    }
    assert_outputs(&root.path().join("shared"), &good_under(""), &runs);
}

#[test]
fn the_input_folder_as_output_never_overwrites_an_input() {
    let root = test_tree();
    // A PNG named `.svg` given by name lands at the top of the output folder, which is its own
    // folder: its output would be itself.
    fs::copy(
        root.path().join("in/top.png"),
        root.path().join("in/copy.svg"),
    )
    .unwrap();
    let before = files_under(&root.path().join("in"));

    let args = ["trace", "in", "in/copy.svg", "-o", "in", "-r"];
    let output = run_expecting(1, &args, root.path());
    let lines = stderr_lines(&output);
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with("error: in/copy.svg: refusing to overwrite an input")),
        "{}",
        describe(&args, &output)
    );
    let after = files_under(&root.path().join("in"));
    for (name, bytes) in &before {
        assert!(after[name] == *bytes, "the input {name} changed");
    }
    let expected: BTreeSet<String> = GOOD
        .iter()
        .map(|(r, _, _)| svg_name(r))
        .chain(["copy.svg".to_string()])
        .collect();
    assert_eq!(svgs_under(&root.path().join("in")), expected);

    // Run again: the SVGs now in the folder are not images and are left alone.
    run_expecting(1, &args, root.path());
    let again = files_under(&root.path().join("in"));
    assert_eq!(again, after);
}

#[test]
fn the_glob_selects_by_file_name_or_by_relative_path() {
    let root = test_tree();
    let args = ["trace", "in", "-o", "jpegs", "-r", "--glob", "*.jpg"];
    let output = run_expecting(0, &args, root.path());
    assert_outputs(
        &root.path().join("jpegs"),
        &good_under("x/z"),
        &describe(&args, &output),
    );

    // With a `/` the pattern is matched against the path inside the folder, and `*` stays in
    // one folder: x/deep/w.png is not taken.
    let args = ["trace", "in", "-o", "x-png", "-r", "--glob", "x/*.png"];
    let output = run_expecting(0, &args, root.path());
    assert_outputs(
        &root.path().join("x-png"),
        &good_under("x/y"),
        &describe(&args, &output),
    );

    run_expecting(
        1,
        &["trace", "in", "-o", "bad", "-r", "--glob", "bad/*"],
        root.path(),
    );
    assert!(svgs_under(&root.path().join("bad")).is_empty());
}

#[test]
fn quiet_prints_only_errors() {
    let root = test_tree();
    let args = ["trace", "in", "-o", "out", "-r", "-q"];
    let output = run_expecting(1, &args, root.path());
    let lines = stderr_lines(&output);
    assert_eq!(lines.len(), BAD.len(), "{}", describe(&args, &output));
    assert_failure_lines(&lines, "in");
    assert_outputs(
        &root.path().join("out"),
        &good_under(""),
        &describe(&args, &output),
    );

    let output = run_expecting(0, &["trace", "in/x", "-o", "out-x", "-q"], root.path());
    assert!(
        output.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

#[test]
fn a_folder_where_an_output_should_go_fails_that_file_only() {
    let root = test_tree();
    // Made after the inputs, so it is newer than `in/x/y.png`: it must still not pass for an
    // up-to-date output.
    fs::create_dir_all(root.path().join("out/x/y.svg")).unwrap();
    let args = ["trace", "in/x", "-o", "out/x"];
    let output = run_expecting(1, &args, root.path());
    let lines = stderr_lines(&output);
    assert!(
        lines[0].starts_with("error: in/x/y.png: ") && lines[0].contains("out/x/y.svg"),
        "{}",
        describe(&args, &output)
    );
    assert_eq!(
        summary_without_time(&lines[1]),
        "1 done, 0 skipped (up to date), 1 failed"
    );
    assert!(root.path().join("out/x/y.svg").is_dir());
    assert!(root.path().join("out/x/z.svg").is_file());
}

#[cfg(unix)]
#[test]
fn a_read_only_output_folder_fails_each_file() {
    use std::os::unix::fs::PermissionsExt;
    let root = test_tree();
    let out = root.path().join("out");
    fs::create_dir(&out).unwrap();
    fs::set_permissions(&out, fs::Permissions::from_mode(0o555)).unwrap();
    // Root writes anywhere: then this case cannot be made (the test above covers an output
    // that cannot be written).
    if fs::write(out.join("probe"), "").is_ok() {
        eprintln!("skipped: permissions are not enforced for this user");
        return;
    }
    let args = ["trace", "in/x", "-o", "out"];
    let output = run(&args, root.path());
    fs::set_permissions(&out, fs::Permissions::from_mode(0o755)).unwrap();
    assert_eq!(
        output.status.code(),
        Some(1),
        "{}",
        describe(&args, &output)
    );
    let lines = stderr_lines(&output);
    for name in ["in/x/y.png", "in/x/z.jpg"] {
        assert!(
            lines
                .iter()
                .any(|l| l.starts_with(&format!("error: {name}: "))
                    && l.ends_with("permission denied")),
            "{}",
            describe(&args, &output)
        );
    }
}

#[test]
fn forced_runs_write_the_same_bytes_whatever_the_number_of_jobs() {
    let root = test_tree();
    run_expecting(
        1,
        &["trace", "in", "-o", "out", "-r", "-j", "2"],
        root.path(),
    );
    let first = files_under(&root.path().join("out"));
    run_expecting(
        1,
        &["trace", "in", "-o", "out", "-r", "-j", "2", "--force"],
        root.path(),
    );
    assert_eq!(files_under(&root.path().join("out")), first);
    run_expecting(
        1,
        &["trace", "in", "-o", "one-job", "-r", "-j", "1"],
        root.path(),
    );
    assert_eq!(files_under(&root.path().join("one-job")), first);
}
