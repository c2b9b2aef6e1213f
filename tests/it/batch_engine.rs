//! The batch engine on real folder trees, with a fake processor standing in for the tracer: a file
//! whose content starts with `BAD` fails, any other becomes a tiny SVG quoting that content.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::{mpsc, Mutex};
use std::time::{Duration, SystemTime};

use crawltrace::batch::{
    discover_inputs, run_batch, BatchError, BatchOptions, BatchSummary, Discovery, FileError,
    FileResult, FileStatus, Shard, Unreadable,
};
use crawltrace::files::OutputRefusal;
use tempfile::TempDir;

use crate::support::set_modified;

fn fake_processor(path: &Path) -> Result<FileResult, String> {
    let content = fs::read_to_string(path).map_err(|error| error.to_string())?;
    if content.starts_with("BAD") {
        return Err("bad drawing".to_string());
    }
    Ok(FileResult {
        bytes: fake_svg(&content).into_bytes(),
        curves: 2,
        closed_curves: 1,
    })
}

fn fake_svg(content: &str) -> String {
    format!("<svg xmlns=\"http://www.w3.org/2000/svg\"><!-- {content} --></svg>")
}

/// A temporary folder holding `files` (relative path with `/`, content), parents created.
fn tree(files: &[(&str, &str)]) -> TempDir {
    let root = tempfile::tempdir().unwrap();
    for (relative, content) in files {
        let path = root.path().join(relative);
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(path, content).unwrap();
    }
    root
}

/// Every file under `folder`, as sorted relative paths with `/`.
fn files_under(folder: &Path) -> Vec<String> {
    crate::support::files_under(folder).into_keys().collect()
}

fn quiet() -> BatchOptions {
    BatchOptions {
        quiet: true,
        ..BatchOptions::default()
    }
}

fn recursive() -> BatchOptions {
    BatchOptions {
        recursive: true,
        ..quiet()
    }
}

fn run(inputs: &[&Path], out: &Path, options: &BatchOptions) -> BatchSummary<String> {
    try_run(inputs, out, options).unwrap()
}

/// The batch of `inputs` (which must be found) into `out` with the fake processor: its summary,
/// or the error that stopped it.
fn try_run(
    inputs: &[&Path],
    out: &Path,
    options: &BatchOptions,
) -> Result<BatchSummary<String>, BatchError> {
    let inputs: Vec<PathBuf> = inputs.iter().map(|path| path.to_path_buf()).collect();
    let discovery = discover_inputs(&inputs, options).unwrap();
    run_batch(&discovery, out, options, fake_processor)
}

/// The error of the outcome at `index`, which must have failed.
fn failure(summary: &BatchSummary<String>, index: usize) -> &FileError<String> {
    match &summary.outcomes[index].status {
        FileStatus::Failed { error, .. } => error,
        _ => panic!(
            "outcome {index} did not fail: {:?}",
            summary.outcomes[index]
        ),
    }
}

/// The relative paths of the outcomes with the given status, in outcome order.
fn with_status(summary: &BatchSummary<String>, wanted: &str) -> Vec<String> {
    summary
        .outcomes
        .iter()
        .filter(|outcome| {
            wanted
                == match outcome.status {
                    FileStatus::Done { .. } => "done",
                    FileStatus::Skipped => "skipped",
                    FileStatus::Failed { .. } => "failed",
                }
        })
        .map(|outcome| outcome.relative.to_string_lossy().replace('\\', "/"))
        .collect()
}

#[test]
fn nested_folders_are_mirrored() {
    let input = tree(&[
        ("top.png", "top"),
        ("a/one.jpg", "one"),
        ("a/b/two.PNG", "two"),
    ]);
    let out = tempfile::tempdir().unwrap();
    let summary = run(&[input.path()], out.path(), &recursive());

    assert_eq!(
        files_under(out.path()),
        ["a/b/two.svg", "a/one.svg", "top.svg"]
    );
    assert_eq!(
        fs::read_to_string(out.path().join("a/b/two.svg")).unwrap(),
        fake_svg("two")
    );
    assert_eq!((summary.done, summary.skipped, summary.failed), (3, 0, 0));
    assert_eq!(summary.failed, 0);
}

#[test]
fn without_recursive_only_the_top_level_is_taken() {
    let input = tree(&[("top.png", "top"), ("a/one.png", "one")]);
    let out = tempfile::tempdir().unwrap();
    let summary = run(&[input.path()], out.path(), &quiet());

    assert_eq!(files_under(out.path()), ["top.svg"]);
    assert_eq!(summary.done, 1);
}

/// The relative paths of what discovery found, in its order.
fn relatives(discovery: &Discovery) -> Vec<PathBuf> {
    discovery
        .inputs
        .iter()
        .map(|input| input.relative.clone())
        .collect()
}

#[test]
fn the_glob_filters_folder_contents() {
    let input = tree(&[
        ("scan-1.png", "1"),
        ("photo.png", "p"),
        ("sub/scan-2.png", "2"),
        ("sub/other.jpg", "o"),
    ]);
    // By file name in any folder, or by path inside the given folder.
    for (glob, expected, excluded) in [
        ("scan-*", ["scan-1.png", "sub/scan-2.png"], 2),
        ("sub/*", ["sub/other.jpg", "sub/scan-2.png"], 2),
    ] {
        let options = BatchOptions {
            glob: Some(glob.to_string()),
            ..recursive()
        };
        let discovery = discover_inputs(&[input.path().to_path_buf()], &options).unwrap();
        let expected: Vec<PathBuf> = expected
            .iter()
            .map(|path| path.split('/').collect())
            .collect();
        assert_eq!(relatives(&discovery), expected, "{glob}");
        assert_eq!(discovery.excluded_by_glob, excluded, "{glob}");
    }
}

#[test]
fn files_without_an_image_extension_are_counted_and_left_alone() {
    let input = tree(&[
        ("a.png", "a"),
        ("notes.txt", "BAD notes"),
        ("drawing.svg", "<svg/>"),
        ("README", "read me"),
    ]);
    let out = tempfile::tempdir().unwrap();
    let summary = run(&[input.path()], out.path(), &quiet());

    assert_eq!(files_under(out.path()), ["a.svg"]);
    assert_eq!(summary.not_images, 3);
    assert_eq!(summary.outcomes.len(), 1);
    assert_eq!(summary.failed, 0);
}

#[test]
fn files_named_directly_are_always_taken() {
    let input = tree(&[("notes.txt", "not an image"), ("skipped.txt", "x")]);
    let out = tempfile::tempdir().unwrap();
    let options = BatchOptions {
        glob: Some("*.png".to_string()),
        ..quiet()
    };
    let summary = run(&[&input.path().join("notes.txt")], out.path(), &options);

    assert_eq!(files_under(out.path()), ["notes.svg"]);
    assert_eq!(summary.done, 1);
}

#[test]
fn a_failing_file_is_reported_and_the_others_are_still_written() {
    let input = tree(&[("a.png", "a"), ("b.png", "BAD b"), ("c.png", "c")]);
    let out = tempfile::tempdir().unwrap();
    let summary = run(&[input.path()], out.path(), &quiet());

    assert_eq!(files_under(out.path()), ["a.svg", "c.svg"]);
    assert_eq!((summary.done, summary.skipped, summary.failed), (2, 0, 1));
    assert!(summary.failed > 0);
    assert_eq!(with_status(&summary, "failed"), ["b.png"]);
    let error = failure(&summary, 1);
    assert!(
        matches!(error, FileError::Process(message) if message == "bad drawing"),
        "the processor's own error is kept: {error:?}"
    );
}

#[test]
fn a_panicking_processor_fails_one_file_only() {
    let input = tree(&[("a.png", "a"), ("b.png", "b")]);
    let out = tempfile::tempdir().unwrap();
    let discovery = discover_inputs(&[input.path().to_path_buf()], &quiet()).unwrap();
    let summary = run_batch(&discovery, out.path(), &quiet(), |path| {
        if path.ends_with("a.png") {
            panic!("index out of bounds");
        }
        fake_processor(path)
    })
    .unwrap();

    assert_eq!(files_under(out.path()), ["b.svg"]);
    let error = failure(&summary, 0);
    assert!(matches!(error, FileError::Panic(_)), "{error:?}");
    assert_eq!(error.to_string(), "internal error: index out of bounds");
    assert!(summary.failed > 0);
}

#[test]
fn an_output_subfolder_blocked_by_a_file_gives_per_file_errors() {
    let input = tree(&[("a/one.png", "1"), ("b/two.png", "2")]);
    let out = tree(&[("a", "a file where the folder `a` should go")]);
    let summary = run(&[input.path()], out.path(), &recursive());

    assert_eq!(with_status(&summary, "failed"), ["a/one.png"]);
    assert_eq!(with_status(&summary, "done"), ["b/two.png"]);
    let error = failure(&summary, 0);
    assert!(matches!(error, FileError::CreateFolder { .. }), "{error:?}");
    let message = error.to_string();
    assert!(message.starts_with("cannot create the folder"), "{message}");
}

#[test]
fn a_folder_in_place_of_an_output_is_not_up_to_date() {
    let input = tree(&[("a.png", "a"), ("b.png", "b")]);
    // Made after the inputs, so newer than them, as a finished output would be.
    let out = tempfile::tempdir().unwrap();
    fs::create_dir(out.path().join("a.svg")).unwrap();
    let summary = run(&[input.path()], out.path(), &quiet());

    assert_eq!(with_status(&summary, "failed"), ["a.png"]);
    assert_eq!(with_status(&summary, "done"), ["b.png"]);
    let error = failure(&summary, 0);
    assert!(
        matches!(
            error,
            FileError::OutputRefused {
                refusal: OutputRefusal::NotAFile("a folder"),
                ..
            }
        ),
        "{error:?}"
    );
    let message = error.to_string();
    assert!(
        message.starts_with("refusing to replace a folder with a file"),
        "{message}"
    );
    assert!(out.path().join("a.svg").is_dir());
}

#[cfg(unix)]
#[test]
fn a_read_only_output_folder_gives_per_file_errors() {
    use std::os::unix::fs::PermissionsExt;
    let input = tree(&[("a.png", "a"), ("b.png", "b")]);
    let out = tempfile::tempdir().unwrap();
    fs::set_permissions(out.path(), fs::Permissions::from_mode(0o555)).unwrap();
    // Root (and some sandboxes) write anywhere: then there is nothing to test.
    let probe = out.path().join("probe");
    if fs::write(&probe, "").is_ok() {
        eprintln!("skipped: permissions are not enforced for this user");
        return;
    }
    let summary = run(&[input.path()], out.path(), &quiet());
    fs::set_permissions(out.path(), fs::Permissions::from_mode(0o755)).unwrap();

    assert_eq!(with_status(&summary, "failed"), ["a.png", "b.png"]);
    let error = failure(&summary, 0);
    let message = error.to_string();
    assert!(message.ends_with("permission denied"), "{message}");
    assert!(summary.failed > 0);
}

#[test]
fn a_second_run_skips_everything_and_force_redoes_it() {
    let input = tree(&[("a.png", "a"), ("sub/b.png", "b")]);
    let out = tempfile::tempdir().unwrap();
    let first = run(&[input.path()], out.path(), &recursive());
    assert_eq!(first.done, 2);

    let second = run(&[input.path()], out.path(), &recursive());
    assert_eq!((second.done, second.skipped, second.failed), (0, 2, 0));
    assert_eq!(second.failed, 0);

    // Mark the outputs so that a rewrite shows.
    for name in ["a.svg", "sub/b.svg"] {
        fs::write(out.path().join(name), "stale").unwrap();
    }
    let forced = BatchOptions {
        force: true,
        ..recursive()
    };
    let third = run(&[input.path()], out.path(), &forced);
    assert_eq!((third.done, third.skipped), (2, 0));
    assert_eq!(
        fs::read_to_string(out.path().join("a.svg")).unwrap(),
        fake_svg("a")
    );
    assert_eq!(
        fs::read_to_string(out.path().join("sub/b.svg")).unwrap(),
        fake_svg("b")
    );
}

#[test]
fn touching_an_input_redoes_only_it() {
    let input = tree(&[("a.png", "a"), ("b.png", "b"), ("c.png", "c")]);
    let out = tempfile::tempdir().unwrap();
    run(&[input.path()], out.path(), &quiet());

    // An hour ahead rather than "now": no dependence on the clock's resolution.
    set_modified(
        &input.path().join("b.png"),
        SystemTime::now() + Duration::from_secs(3600),
    );
    let summary = run(&[input.path()], out.path(), &quiet());
    assert_eq!(with_status(&summary, "done"), ["b.png"]);
    assert_eq!(with_status(&summary, "skipped"), ["a.png", "c.png"]);
}

#[test]
fn an_output_as_new_as_its_input_is_up_to_date() {
    let input = tree(&[("a.png", "a")]);
    let out = tree(&[("a.svg", "existing")]);
    let time = SystemTime::UNIX_EPOCH + Duration::from_secs(1_700_000_000);
    set_modified(&input.path().join("a.png"), time);
    set_modified(&out.path().join("a.svg"), time);

    let summary = run(&[input.path()], out.path(), &quiet());
    assert_eq!(with_status(&summary, "skipped"), ["a.png"]);
    assert_eq!(
        fs::read_to_string(out.path().join("a.svg")).unwrap(),
        "existing"
    );
}

#[test]
fn shards_cover_every_input_exactly_once() {
    let files: Vec<(String, String)> = (0..40)
        .map(|number| {
            (
                format!("f{}/scan-{number}.png", number % 4),
                number.to_string(),
            )
        })
        .collect();
    let borrowed: Vec<(&str, &str)> = files
        .iter()
        .map(|(path, content)| (path.as_str(), content.as_str()))
        .collect();
    let input = tree(&borrowed);
    let everything = discover_inputs(&[input.path().to_path_buf()], &recursive()).unwrap();
    assert_eq!(everything.inputs.len(), 40);

    let out = tempfile::tempdir().unwrap();
    let mut seen = Vec::new();
    for index in 1..=3 {
        let options = BatchOptions {
            shard: Some(Shard::new(index, 3).unwrap()),
            ..recursive()
        };
        let summary = run(&[input.path()], out.path(), &options);
        assert!(
            summary.done > 0,
            "shard {index}/3 is empty: a poor split of 40 files"
        );
        assert_eq!(summary.done + summary.in_other_shards, 40);
        seen.extend(with_status(&summary, "done"));
    }
    let distinct: BTreeSet<_> = seen.iter().cloned().collect();
    assert_eq!(seen.len(), 40, "some input was in two shards");
    assert_eq!(distinct.len(), 40);
    assert_eq!(files_under(out.path()).len(), 40);
}

#[test]
fn output_folder_equal_to_the_input_folder_keeps_the_inputs() {
    let input = tree(&[("a.png", "a"), ("sub/b.jpg", "b")]);
    let summary = run(&[input.path()], input.path(), &recursive());

    assert_eq!(summary.done, 2);
    assert_eq!(
        files_under(input.path()),
        ["a.png", "a.svg", "sub/b.jpg", "sub/b.svg"]
    );
    assert_eq!(fs::read_to_string(input.path().join("a.png")).unwrap(), "a");
    assert_eq!(
        fs::read_to_string(input.path().join("sub/b.jpg")).unwrap(),
        "b"
    );

    // The outputs are not images: a second run sees the same two inputs, up to date.
    let again = run(&[input.path()], input.path(), &recursive());
    assert_eq!((again.skipped, again.outcomes.len()), (2, 2));
}

#[test]
fn an_output_that_is_an_input_is_refused() {
    let input = tree(&[("drawing.svg", "the user's own drawing"), ("a.png", "a")]);
    let named = input.path().join("drawing.svg");
    let summary = run(
        &[&named, &input.path().join("a.png")],
        input.path(),
        &quiet(),
    );

    assert_eq!(
        fs::read_to_string(&named).unwrap(),
        "the user's own drawing"
    );
    assert_eq!(with_status(&summary, "failed"), ["drawing.svg"]);
    assert_eq!(with_status(&summary, "done"), ["a.png"]);
    let error = failure(&summary, 1);
    assert!(
        matches!(
            error,
            FileError::OutputRefused {
                refusal: OutputRefusal::Input,
                ..
            }
        ),
        "{error:?}"
    );
    let message = error.to_string();
    assert!(
        message.starts_with("refusing to overwrite an input"),
        "{message}"
    );
}

#[test]
fn two_inputs_with_the_same_output_are_an_error_before_any_work() {
    let input = tree(&[("a.png", "a"), ("a.jpg", "a too"), ("b.png", "b")]);
    let error = discover_inputs(&[input.path().to_path_buf()], &quiet()).unwrap_err();

    let BatchError::OutputCollision {
        output,
        first,
        second,
    } = &error
    else {
        panic!("{error:?}");
    };
    assert_eq!(output, Path::new("a.svg"));
    assert_eq!(first, &input.path().join("a.jpg"));
    assert_eq!(second, &input.path().join("a.png"));
    let text = error.to_string();
    assert!(text.contains("a.jpg") && text.contains("a.png"), "{text}");
}

#[test]
fn colliding_inputs_in_different_shards_are_still_an_error() {
    let input = tree(&[("x/a.png", "a")]);
    let other = tree(&[("x/a.gif", "a")]);
    for index in 1..=2 {
        let options = BatchOptions {
            shard: Some(Shard::new(index, 2).unwrap()),
            ..recursive()
        };
        let inputs = [input.path().to_path_buf(), other.path().to_path_buf()];
        assert!(matches!(
            discover_inputs(&inputs, &options),
            Err(BatchError::OutputCollision { .. })
        ));
    }
}

#[test]
fn the_same_file_reached_twice_is_traced_once() {
    let input = tree(&[("a.png", "a"), ("b.png", "b")]);
    let inputs = [
        input.path().to_path_buf(),
        input.path().join("a.png"),
        input.path().to_path_buf(),
    ];
    let discovery = discover_inputs(&inputs, &quiet()).unwrap();
    assert_eq!(discovery.inputs.len(), 2);
}

#[test]
fn results_come_in_input_order_whatever_order_they_finish_in() {
    let input = tree(&[
        ("a.png", "a"),
        ("b.png", "b"),
        ("c.png", "c"),
        ("d.png", "d"),
    ]);
    let out = tempfile::tempdir().unwrap();
    let options = BatchOptions {
        jobs: Some(2),
        ..quiet()
    };
    let discovery = discover_inputs(&[input.path().to_path_buf()], &options).unwrap();
    let finished = Mutex::new(Vec::new());
    let (last_done, wait_for_last) = mpsc::channel::<()>();
    let wait_for_last = Mutex::new(wait_for_last);
    let summary = run_batch(&discovery, out.path(), &options, |path| {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name == "a.png" {
            // Hold the first file until the last one is finished. The timeout only guards
            // against a hang; the order is asserted below.
            let _ = wait_for_last
                .lock()
                .unwrap()
                .recv_timeout(Duration::from_secs(60));
        }
        let result = fake_processor(path);
        finished.lock().unwrap().push(name.clone());
        if name == "d.png" {
            let _ = last_done.send(());
        }
        result
    })
    .unwrap();

    let finished = finished.into_inner().unwrap();
    let position = |name: &str| finished.iter().position(|n| n == name).unwrap();
    assert!(position("d.png") < position("a.png"), "{finished:?}");
    assert_eq!(
        with_status(&summary, "done"),
        ["a.png", "b.png", "c.png", "d.png"]
    );
}

#[test]
fn the_report_has_one_json_object_per_input_in_order() {
    let input = tree(&[
        ("a.png", "a"),
        ("b.png", "BAD"),
        ("c.png", "c"),
        ("x.txt", ""),
    ]);
    let out = tempfile::tempdir().unwrap();
    // c is already up to date.
    fs::write(out.path().join("c.svg"), fake_svg("c")).unwrap();
    set_modified(
        &out.path().join("c.svg"),
        SystemTime::now() + Duration::from_secs(3600),
    );
    let report = out.path().join("report.jsonl");
    let options = BatchOptions {
        report: Some(report.clone()),
        ..quiet()
    };
    run(&[input.path()], out.path(), &options);

    let text = fs::read_to_string(&report).unwrap();
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|line| serde_json::from_str(line).unwrap())
        .collect();
    assert_eq!(lines.len(), 3, "{text}");
    let path = |name: &str| input.path().join(name).to_string_lossy().into_owned();

    assert_eq!(lines[0]["path"], path("a.png"));
    assert_eq!(lines[0]["status"], "done");
    assert_eq!(lines[0]["curves"], 2);
    assert_eq!(lines[0]["closed_curves"], 1);
    assert!(lines[0]["seconds"].as_f64().is_some_and(|s| s >= 0.0));
    assert!(lines[0]["error"].is_null());
    assert_eq!(
        lines[0]["output"],
        out.path().join("a.svg").to_string_lossy().as_ref()
    );

    assert_eq!(lines[1]["path"], path("b.png"));
    assert_eq!(lines[1]["status"], "failed");
    assert!(lines[1]["curves"].is_null());
    assert!(lines[1]["closed_curves"].is_null());
    assert!(lines[1]["seconds"].is_f64());
    assert_eq!(lines[1]["error"], "bad drawing");

    assert_eq!(lines[2]["path"], path("c.png"));
    assert_eq!(lines[2]["status"], "skipped");
    for field in ["curves", "closed_curves", "seconds", "error"] {
        assert!(lines[2][field].is_null(), "{field}");
    }
}

#[test]
fn a_report_in_a_missing_folder_is_an_error_before_any_work() {
    let input = tree(&[("a.png", "a")]);
    let out = tempfile::tempdir().unwrap();
    let options = BatchOptions {
        report: Some(out.path().join("missing").join("report.jsonl")),
        ..quiet()
    };
    let result = try_run(&[input.path()], out.path(), &options);

    assert!(
        matches!(result, Err(BatchError::Report { .. })),
        "{result:?}"
    );
    assert!(files_under(out.path()).is_empty());
}

#[test]
fn a_report_in_the_output_folder_the_run_makes_is_written() {
    let input = tree(&[("a.png", "a")]);
    let parent = tempfile::tempdir().unwrap();
    // `./out` and `out/…`: the same folder spelled two ways.
    let out = parent.path().join(".").join("out");
    let options = BatchOptions {
        report: Some(parent.path().join("out").join("report.jsonl")),
        ..quiet()
    };
    run(&[input.path()], &out, &options);

    assert_eq!(files_under(&out), ["a.svg", "report.jsonl"]);
}

#[test]
fn a_report_over_an_input_is_refused() {
    let input = tree(&[("a.png", "a")]);
    let out = tempfile::tempdir().unwrap();
    let options = BatchOptions {
        report: Some(input.path().join("a.png")),
        ..quiet()
    };
    let result = try_run(&[input.path()], out.path(), &options);

    assert!(
        matches!(result, Err(BatchError::Report { .. })),
        "{result:?}"
    );
    assert_eq!(fs::read_to_string(input.path().join("a.png")).unwrap(), "a");
}

#[test]
fn a_missing_input_is_an_error() {
    let input = tempfile::tempdir().unwrap();
    let missing = input.path().join("nowhere");
    let error = discover_inputs(std::slice::from_ref(&missing), &quiet()).unwrap_err();
    assert!(matches!(&error, BatchError::Input { path, .. } if *path == missing));
    assert_eq!(
        error.to_string(),
        format!("{}: no such file", missing.display())
    );
}

#[test]
fn zero_jobs_is_an_error() {
    let input = tree(&[("a.png", "a")]);
    let out = tempfile::tempdir().unwrap();
    let options = BatchOptions {
        jobs: Some(0),
        ..quiet()
    };
    let result = try_run(&[input.path()], out.path(), &options);
    assert!(matches!(result, Err(BatchError::NoJobs)), "{result:?}");
}

#[test]
fn an_empty_folder_is_an_empty_batch() {
    let input = tempfile::tempdir().unwrap();
    let out = tempfile::tempdir().unwrap();
    let summary = run(&[input.path()], out.path(), &quiet());
    assert!(summary.outcomes.is_empty());
    assert_eq!(summary.failed, 0);
}

#[cfg(unix)]
#[test]
fn a_symbolic_link_loop_does_not_hang() {
    let input = tree(&[("a.png", "a"), ("sub/b.png", "b")]);
    std::os::unix::fs::symlink(input.path(), input.path().join("sub/back-to-top")).unwrap();
    let discovery = discover_inputs(&[input.path().to_path_buf()], &recursive()).unwrap();

    let taken = relatives(&discovery);
    assert_eq!(
        taken,
        [PathBuf::from("a.png"), Path::new("sub").join("b.png")]
    );
    assert_eq!(discovery.warnings.len(), 1, "{:?}", discovery.warnings);
    assert!(discovery.warnings[0].to_string().contains("loop"));
}

#[cfg(unix)]
#[test]
fn a_broken_link_to_an_image_is_a_failure() {
    let input = tree(&[("a.png", "a")]);
    std::os::unix::fs::symlink("nowhere.png", input.path().join("ghost.png")).unwrap();
    std::os::unix::fs::symlink("nowhere.txt", input.path().join("ghost.txt")).unwrap();
    let out = tempfile::tempdir().unwrap();
    let summary = run(&[input.path()], out.path(), &quiet());

    assert_eq!(with_status(&summary, "done"), ["a.png"]);
    assert_eq!(with_status(&summary, "failed"), ["ghost.png"]);
    assert!(
        matches!(
            summary.outcomes[1].status,
            FileStatus::Failed {
                error: FileError::Unreadable(Unreadable::BrokenLink),
                seconds: None
            }
        ),
        "{:?}",
        summary.outcomes[1].status
    );
    if let FileStatus::Failed { error, .. } = &summary.outcomes[1].status {
        assert_eq!(error.to_string(), "broken symbolic link");
    }
    assert_eq!(summary.not_images, 1);
}

/// Issue 13: `--report` naming one of the batch's own SVGs replaced it and a rerun called it up to
/// date. The report is an output like the SVGs and may not be one of them, in this shard or
/// another.
#[test]
fn a_report_over_an_output_of_the_run_is_refused_before_any_work() {
    let input = tree(&[("a.png", "a"), ("b.png", "b"), ("c.png", "c")]);
    let out = tempfile::tempdir().unwrap();
    for shard in [
        None,
        Some(Shard::new(1, 3).unwrap()),
        Some(Shard::new(2, 3).unwrap()),
    ] {
        for svg in ["a.svg", "b.svg", "c.svg"] {
            let options = BatchOptions {
                report: Some(out.path().join(svg)),
                shard,
                ..quiet()
            };
            let result = try_run(&[input.path()], out.path(), &options);
            let Err(error @ BatchError::Report { .. }) = result else {
                panic!("{svg} in {shard:?}: {result:?}");
            };
            let message = error.to_string();
            assert!(
                message.contains("refusing to write it twice: it is also the output"),
                "{message}"
            );
            assert!(files_under(out.path()).is_empty(), "{svg}: work was done");
        }
    }
}

/// A named pipe (or a device) where an output should go is never replaced by a file: that input
/// fails, the others are written.
#[cfg(unix)]
#[test]
fn an_output_that_is_a_named_pipe_fails_its_input_alone() {
    let input = tree(&[("a.png", "a"), ("b.png", "b")]);
    let out = tempfile::tempdir().unwrap();
    let pipe = out.path().join("a.svg");
    make_fifo(&pipe);
    let summary = run(&[input.path()], out.path(), &quiet());
    assert_eq!(with_status(&summary, "failed"), ["a.png"]);
    assert_eq!(with_status(&summary, "done"), ["b.png"]);
    assert!(fs::symlink_metadata(&pipe).unwrap().file_type().is_fifo());
    let error = failure(&summary, 0);
    assert!(
        error
            .to_string()
            .starts_with("refusing to replace a named pipe with a file"),
        "{error}"
    );
}

/// Issue 13: a FIFO named like an image in an input folder hung the whole batch. It is never
/// opened: it fails alone, with its report line, and the batch finishes.
#[cfg(unix)]
#[test]
fn a_named_pipe_named_like_an_image_fails_alone_without_blocking() {
    let input = tree(&[("a.png", "a"), ("c.png", "c")]);
    make_fifo(&input.path().join("b.png"));
    let out = tempfile::tempdir().unwrap();
    let report = out.path().join("report.jsonl");
    let options = BatchOptions {
        report: Some(report.clone()),
        ..quiet()
    };
    let summary = run(&[input.path()], out.path(), &options);
    assert_eq!(with_status(&summary, "failed"), ["b.png"]);
    assert_eq!(with_status(&summary, "done"), ["a.png", "c.png"]);
    let error = failure(&summary, 1);
    assert!(matches!(
        error,
        FileError::Unreadable(Unreadable::NotAFile("a named pipe"))
    ));
    let text = fs::read_to_string(&report).unwrap();
    assert_eq!(text.lines().count(), 3, "{text}");
    assert!(text.contains("not a regular file (a named pipe)"), "{text}");
}

/// Temporary files left by a killed run are removed from the folders the next run writes to;
/// nothing else is touched.
#[test]
fn a_rerun_removes_what_an_interrupted_run_left() {
    let input = tree(&[("a.png", "a"), ("sub/b.png", "b")]);
    let out = tree(&[
        (".crawltrace-AbCd12.tmp", "<svg cut sh"),
        ("sub/.crawltrace-XyZ789.tmp", "<sv"),
        ("notes.txt", "the user's"),
    ]);
    run(&[input.path()], out.path(), &recursive());
    assert_eq!(files_under(out.path()), ["a.svg", "notes.txt", "sub/b.svg"]);
}

/// The report is written after the SVGs; if that fails the SVGs stay and the failure is kept
/// apart (the command exits 3, not 2, which means nothing ran).
#[test]
fn a_report_that_cannot_be_written_after_the_work_is_kept_apart() {
    let input = tree(&[("a.png", "a"), ("b.png", "b")]);
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let report_folder = reports.path().join("reports");
    fs::create_dir(&report_folder).unwrap();
    let options = BatchOptions {
        report: Some(report_folder.join("report.jsonl")),
        jobs: Some(1),
        ..quiet()
    };
    let discovery = discover_inputs(&[input.path().to_path_buf()], &options).unwrap();
    // The report's folder disappears while the batch runs.
    let summary = run_batch(&discovery, out.path(), &options, |path| {
        let _ = fs::remove_dir_all(&report_folder);
        fake_processor(path)
    })
    .unwrap();
    assert_eq!(summary.done, 2);
    assert_eq!(files_under(out.path()), ["a.svg", "b.svg"]);
    assert!(
        matches!(&summary.report_error, Some(BatchError::Report { .. })),
        "{:?}",
        summary.report_error
    );
}

#[cfg(unix)]
fn make_fifo(path: &Path) {
    let status = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success());
}

#[cfg(unix)]
use std::os::unix::fs::FileTypeExt;
