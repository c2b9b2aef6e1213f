//! The `crawltrace points` command, run as a user would: the binary in a temporary folder, checked
//! on its exit code, its one-line errors, its output files and its JSON and SVG formats.

use std::f64::consts::TAU;
use std::fmt::Write as _;
use std::fs;
use std::path::Path;

use serde_json::Value;

use crate::support::cli;

/// One finished run of the binary.
struct Run {
    /// The command line, for failure messages.
    command: String,
    code: Option<i32>,
    stdout: Vec<u8>,
    stderr: String,
}

impl Run {
    fn describe(&self) -> String {
        format!(
            "command: {}\nexit code: {:?}\nstderr:\n{}",
            self.command, self.code, self.stderr
        )
    }

    fn succeeded(self) -> Self {
        assert_eq!(self.code, Some(0), "expected success\n{}", self.describe());
        self
    }

    /// Checks exit code 2 and a single `error: <file>: …` line (after warnings, if any), and
    /// returns that line.
    fn failed_with_one_error(self, file: &str) -> String {
        assert_eq!(
            self.code,
            Some(2),
            "expected exit code 2\n{}",
            self.describe()
        );
        let (warnings, errors): (Vec<&str>, Vec<&str>) = self
            .stderr
            .lines()
            .partition(|line| line.starts_with("warning: "));
        assert_eq!(
            errors.len(),
            1,
            "expected one error line\n{}",
            self.describe()
        );
        assert!(
            self.stderr.ends_with(&format!("{}\n", errors[0])),
            "the error is not the last line\n{}",
            self.describe()
        );
        let prefix = format!("error: {file}: ");
        assert!(
            errors[0].starts_with(&prefix),
            "expected {prefix:?}\n{}",
            self.describe()
        );
        let _ = warnings;
        errors[0].to_string()
    }

    fn stdout_text(&self) -> String {
        String::from_utf8(self.stdout.clone())
            .unwrap_or_else(|_| panic!("stdout is not UTF-8\n{}", self.describe()))
    }

    fn json(&self) -> Value {
        serde_json::from_slice(&self.stdout)
            .unwrap_or_else(|e| panic!("stdout is not JSON ({e})\n{}", self.describe()))
    }
}

/// Runs `crawltrace <args>` in `folder`, feeding `stdin` (empty if `None`).
fn crawltrace(folder: &Path, args: &[&str], stdin: Option<&[u8]>) -> Run {
    let output = cli::run_with_stdin(args, folder, stdin.unwrap_or_default());
    Run {
        command: format!("crawltrace {}", args.join(" ")),
        code: output.status.code(),
        stdout: output.stdout,
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

fn folder() -> tempfile::TempDir {
    tempfile::tempdir().expect("a temporary folder")
}

/// `count` points on a circle, as `x y` lines.
fn circle_text(count: usize, centre: (f64, f64), radius: f64) -> String {
    let mut text = String::new();
    for k in 0..count {
        let angle = TAU * k as f64 / count as f64;
        let _ = writeln!(
            text,
            "{} {}",
            centre.0 + radius * angle.cos(),
            centre.1 + radius * angle.sin()
        );
    }
    text
}

/// A circle of 24 points, a far outlier, and a repeat of the first point.
fn scene_text() -> String {
    let mut text = circle_text(24, (5.0, 5.0), 4.0);
    text.push_str("40 40\n");
    let first = text.lines().next().unwrap().to_string();
    text.push_str(&first);
    text.push('\n');
    text
}

fn keys(value: &Value) -> Vec<&str> {
    let mut keys: Vec<&str> = value
        .as_object()
        .unwrap_or_else(|| panic!("not an object: {value}"))
        .keys()
        .map(String::as_str)
        .collect();
    keys.sort_unstable();
    keys
}

fn as_indices(value: &Value) -> Vec<usize> {
    value
        .as_array()
        .unwrap_or_else(|| panic!("not an array: {value}"))
        .iter()
        .map(|v| v.as_u64().unwrap_or_else(|| panic!("not an index: {v}")) as usize)
        .collect()
}

fn parse_input(text: &str) -> Vec<(f64, f64)> {
    text.lines()
        .map(|line| {
            let mut fields = line.split_whitespace().map(|f| f.parse::<f64>().unwrap());
            (fields.next().unwrap(), fields.next().unwrap())
        })
        .collect()
}

#[test]
fn json_output_has_the_documented_shape() {
    let folder = folder();
    let text = scene_text();
    fs::write(folder.path().join("scene.txt"), &text).unwrap();
    let run = crawltrace(folder.path(), &["points", "scene.txt"], None).succeeded();
    assert!(run.stdout_text().ends_with('\n'), "{}", run.describe());
    let json = run.json();
    assert_eq!(keys(&json), ["curves", "duplicates", "outliers"]);
    let input = parse_input(&text);
    let curves = json["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 1, "{json}");
    let curve = &curves[0];
    assert_eq!(keys(curve), ["closed", "indices", "points"]);
    assert_eq!(curve["closed"], Value::Bool(true));
    let indices = as_indices(&curve["indices"]);
    let mut sorted = indices.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, (0..24).collect::<Vec<_>>(), "{json}");
    let points = curve["points"].as_array().unwrap();
    assert_eq!(points.len(), indices.len());
    for (&index, point) in indices.iter().zip(points) {
        let xy: Vec<f64> = point
            .as_array()
            .unwrap_or_else(|| panic!("point is not [x, y]: {point}"))
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        // The coordinates are the input's own, exactly.
        assert_eq!(xy, [input[index].0, input[index].1], "point {index}");
    }
    assert_eq!(as_indices(&json["outliers"]), [24]);
    let duplicates = json["duplicates"].as_array().unwrap();
    assert_eq!(duplicates.len(), 1);
    assert_eq!(as_indices(&duplicates[0]), [25, 0], "[dropped, kept]");
}

#[test]
fn format_follows_the_output_extension_unless_given() {
    let folder = folder();
    fs::write(folder.path().join("scene.txt"), scene_text()).unwrap();
    let json_on_stdout = crawltrace(folder.path(), &["points", "scene.txt"], None)
        .succeeded()
        .stdout;
    let cases: [(&[&str], &str, bool); 7] = [
        (&[], "out.svg", true),
        (&[], "OUT.SVG", true),
        (&[], "out.json", false),
        (&[], "out.txt", false),
        (&[], "out", false),
        (&["--format", "svg"], "out2.json", true),
        (&["--format", "json"], "out2.svg", false),
    ];
    for (options, output, is_svg) in cases {
        let mut args = vec!["points", "scene.txt", "-o", output];
        args.extend_from_slice(options);
        let run = crawltrace(folder.path(), &args, None).succeeded();
        assert!(run.stdout.is_empty(), "{}", run.describe());
        let written = fs::read(folder.path().join(output)).unwrap();
        if is_svg {
            let svg = String::from_utf8(written).unwrap();
            assert!(svg.starts_with("<svg "), "{}\n{svg}", run.describe());
        } else {
            assert_eq!(written, json_on_stdout, "{}", run.describe());
        }
    }
    let svg_on_stdout = crawltrace(
        folder.path(),
        &["points", "scene.txt", "--format", "svg"],
        None,
    )
    .succeeded();
    assert_eq!(
        svg_on_stdout.stdout,
        fs::read(folder.path().join("out.svg")).unwrap()
    );
}

#[test]
fn dash_reads_stdin_and_writes_stdout() {
    let folder = folder();
    let text = scene_text();
    fs::write(folder.path().join("scene.txt"), &text).unwrap();
    let from_file = crawltrace(folder.path(), &["points", "scene.txt"], None).succeeded();
    let piped = crawltrace(
        folder.path(),
        &["points", "-", "-o", "-"],
        Some(text.as_bytes()),
    )
    .succeeded();
    assert_eq!(piped.stdout, from_file.stdout, "{}", piped.describe());
    // Nothing named "-" is created.
    assert!(!folder.path().join("-").exists());
    assert!(
        piped.stderr.starts_with("warning: <stdin>: "),
        "{}",
        piped.describe()
    );
}

#[test]
fn every_line_ending_comment_and_separator_gives_the_same_result() {
    let folder = folder();
    let plain = circle_text(30, (0.0, 0.0), 10.0);
    let expected = crawltrace(folder.path(), &["points", "-"], Some(plain.as_bytes()))
        .succeeded()
        .stdout;
    let lines: Vec<&str> = plain.lines().collect();
    let commented = {
        let mut text = String::from("# a circle\n\n");
        for (k, line) in lines.iter().enumerate() {
            let (x, y) = line.split_once(' ').unwrap();
            let separator = [" ", "\t", ",", " , ", ";"][k % 5];
            let _ = writeln!(text, "  {x}{separator}{y}  extra columns # point {k}");
        }
        text
    };
    let variants = [
        ("\\r\\n", lines.join("\r\n") + "\r\n"),
        ("\\r", lines.join("\r") + "\r"),
        ("no final newline", lines.join("\n")),
        ("mixed", {
            let mut text = String::new();
            for (k, line) in lines.iter().enumerate() {
                text.push_str(line);
                text.push_str(["\n", "\r\n", "\r"][k % 3]);
            }
            text
        }),
        ("comments, separators and extra columns", commented),
        ("a header", format!("x y\n{plain}")),
        (
            "a spreadsheet header",
            format!("\u{feff}\"x\",\"y\"\r\n{plain}"),
        ),
    ];
    for (what, text) in variants {
        let name = format!("points-{}.txt", what.replace(['\\', ' ', ','], "_"));
        fs::write(folder.path().join(&name), &text).unwrap();
        let run = crawltrace(folder.path(), &["points", &name], None).succeeded();
        assert_eq!(run.stdout, expected, "{what}\n{}", run.describe());
        assert_eq!(run.stderr, "", "{what}\n{}", run.describe());
    }
}

#[test]
fn a_coordinate_that_is_not_finite_is_a_one_line_error_naming_the_line() {
    let folder = folder();
    for bad in ["nan", "NaN", "inf", "-inf", "infinity", "1e999"] {
        for line_ending in ["\n", "\r\n", "\r"] {
            let text =
                ["# header comment", "1 2", "3 4", &format!("5 {bad}"), "7 8"].join(line_ending);
            fs::write(folder.path().join("bad.txt"), &text).unwrap();
            let line = crawltrace(folder.path(), &["points", "bad.txt"], None)
                .failed_with_one_error("bad.txt");
            assert!(line.starts_with("error: bad.txt: line 4: "), "{line}");
            let line = crawltrace(folder.path(), &["points", "-"], Some(text.as_bytes()))
                .failed_with_one_error("<stdin>");
            assert!(line.starts_with("error: <stdin>: line 4: "), "{line}");
        }
    }
}

#[test]
fn unreadable_input_is_a_one_line_error() {
    let folder = folder();
    let line = crawltrace(folder.path(), &["points", "missing.txt"], None)
        .failed_with_one_error("missing.txt");
    assert_eq!(line, "error: missing.txt: no such file");
    fs::create_dir(folder.path().join("a folder")).unwrap();
    crawltrace(folder.path(), &["points", "a folder"], None).failed_with_one_error("a folder");
    for (text, line_number) in [
        (&b"1 2\n3 apples\n"[..], 2),
        (b"1 2\n3\n", 2),
        (b"1 2\n\xff\xfe 3\n", 2),
        (b"1 2\n4 5\n1e300 0\n", 3),
    ] {
        fs::write(folder.path().join("bad.txt"), text).unwrap();
        let line = crawltrace(folder.path(), &["points", "bad.txt"], None)
            .failed_with_one_error("bad.txt");
        assert!(
            line.starts_with(&format!("error: bad.txt: line {line_number}: ")),
            "{line}"
        );
    }
}

#[test]
fn tiny_and_collinear_inputs_work() {
    let folder = folder();
    let mut cases: Vec<(&str, String)> = vec![
        ("empty", String::new()),
        ("only comments", "# nothing\n\n".to_string()),
        ("one point", "1 1\n".to_string()),
        ("two points", "1 1\n2 3\n".to_string()),
        ("three points", "0 0\n1 0\n0 1\n".to_string()),
        ("one point many times", "2 2\n".repeat(50)),
    ];
    let collinear: String = (0..500)
        .map(|k| format!("{} {}\n", (k * 37) % 500, 2 * ((k * 37) % 500)))
        .collect();
    cases.push(("collinear", collinear));
    let even_collinear: String = (0..500).map(|k| format!("{k} 7\n")).collect();
    cases.push(("evenly spaced collinear", even_collinear));
    for (what, text) in cases {
        let count = text
            .lines()
            .filter(|l| !l.starts_with('#') && !l.is_empty())
            .count();
        let run = crawltrace(folder.path(), &["points", "-"], Some(text.as_bytes())).succeeded();
        let json = run.json();
        // Every input point is on a curve, an outlier or a merged duplicate, exactly once.
        let mut seen: Vec<usize> = as_indices(&json["outliers"]);
        for curve in json["curves"].as_array().unwrap() {
            seen.extend(as_indices(&curve["indices"]));
        }
        for duplicate in json["duplicates"].as_array().unwrap() {
            seen.push(as_indices(duplicate)[0]);
        }
        seen.sort_unstable();
        assert_eq!(seen, (0..count).collect::<Vec<_>>(), "{what}\n{json}");
        let svg = crawltrace(
            folder.path(),
            &["points", "-", "--format", "svg"],
            Some(text.as_bytes()),
        )
        .succeeded()
        .stdout_text();
        usvg::Tree::from_str(&svg, &usvg::Options::default())
            .unwrap_or_else(|e| panic!("{what}: SVG does not parse: {e}\n{svg}"));
    }
}

#[test]
fn duplicates_are_merged_with_a_warning() {
    let folder = folder();
    let mut text = circle_text(20, (0.0, 0.0), 5.0);
    let lines: Vec<String> = text.lines().map(str::to_string).collect();
    // Line 21 repeats line 4, line 22 repeats line 8, line 23 repeats line 4 again.
    for k in [3, 7, 3] {
        text.push_str(&lines[k]);
        text.push('\n');
    }
    fs::write(folder.path().join("twice.txt"), &text).unwrap();
    let run = crawltrace(folder.path(), &["points", "twice.txt"], None).succeeded();
    assert_eq!(
        run.stderr,
        "warning: twice.txt: merged 3 duplicate point(s) (line 21 repeats line 4)\n",
        "{}",
        run.describe()
    );
    let json = run.json();
    let duplicates: Vec<Vec<usize>> = json["duplicates"]
        .as_array()
        .unwrap()
        .iter()
        .map(as_indices)
        .collect();
    assert_eq!(duplicates, [[20, 3], [21, 7], [22, 3]]);
    let curves = json["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 1);
    assert_eq!(curves[0]["closed"], Value::Bool(true));
    assert_eq!(as_indices(&curves[0]["indices"]).len(), 20);
}

#[test]
fn the_input_is_never_overwritten() {
    let folder = folder();
    let text = scene_text();
    fs::create_dir(folder.path().join("sub")).unwrap();
    fs::write(folder.path().join("scene.txt"), &text).unwrap();
    let mut spellings = vec!["scene.txt", "./scene.txt", "sub/../scene.txt"];
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("scene.txt", folder.path().join("link.txt")).unwrap();
        spellings.push("link.txt");
    }
    for output in spellings {
        for format in ["json", "svg"] {
            let run = crawltrace(
                folder.path(),
                &["points", "scene.txt", "-o", output, "--format", format],
                None,
            );
            // Refused before reading the input: no duplicate warning either.
            assert!(!run.stderr.contains("warning"), "{}", run.describe());
            let line = run.failed_with_one_error(output);
            assert!(line.contains("input"), "{line}");
            assert_eq!(
                fs::read_to_string(folder.path().join("scene.txt")).unwrap(),
                text,
                "the input changed after -o {output}"
            );
        }
    }
    // A failed run leaves no temporary file behind.
    let mut names: Vec<String> = fs::read_dir(folder.path())
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort_unstable();
    let mut expected = vec!["scene.txt", "sub"];
    if cfg!(unix) {
        expected.insert(0, "link.txt");
    }
    assert_eq!(names, expected);
}

#[test]
fn an_existing_output_is_replaced_whole() {
    let folder = folder();
    fs::write(folder.path().join("scene.txt"), scene_text()).unwrap();
    fs::write(folder.path().join("out.json"), "x".repeat(100_000)).unwrap();
    let run = crawltrace(
        folder.path(),
        &["points", "scene.txt", "-o", "out.json"],
        None,
    )
    .succeeded();
    let written = fs::read(folder.path().join("out.json")).unwrap();
    let expected = crawltrace(folder.path(), &["points", "scene.txt"], None)
        .succeeded()
        .stdout;
    assert_eq!(written, expected, "{}", run.describe());
    let line = crawltrace(
        folder.path(),
        &["points", "scene.txt", "-o", "no such folder/out.json"],
        None,
    )
    .failed_with_one_error("no such folder/out.json");
    assert!(!line.contains("os error"), "{line}");
}

#[cfg(unix)]
#[test]
fn output_files_get_the_usual_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let folder = folder();
    fs::write(folder.path().join("scene.txt"), scene_text()).unwrap();
    // std::fs::write creates files with 0666 less the umask, as any program would.
    fs::write(folder.path().join("plain"), "").unwrap();
    let usual = fs::metadata(folder.path().join("plain"))
        .unwrap()
        .permissions()
        .mode()
        & 0o777;
    for output in ["out.json", "out.svg"] {
        crawltrace(folder.path(), &["points", "scene.txt", "-o", output], None).succeeded();
        let mode = fs::metadata(folder.path().join(output))
            .unwrap()
            .permissions()
            .mode()
            & 0o777;
        assert_eq!(mode, usual, "{output}: {mode:o} instead of {usual:o}");
    }
}

/// All `usvg` path nodes under `group`, recursively.
fn path_count(group: &usvg::Group) -> usize {
    group
        .children()
        .iter()
        .map(|node| match node {
            usvg::Node::Group(inner) => path_count(inner),
            usvg::Node::Path(_) => 1,
            _ => 0,
        })
        .sum()
}

#[test]
fn svg_output_parses_with_usvg() {
    let folder = folder();
    // Two circles, an open arc and two outliers.
    let mut text = circle_text(30, (0.0, 0.0), 10.0);
    text.push_str(&circle_text(20, (30.0, 0.0), 5.0));
    for k in 0..15 {
        let angle = 0.1 * k as f64;
        let _ = writeln!(text, "{} {}", 60.0 * angle.cos(), 60.0 * angle.sin() - 40.0);
    }
    text.push_str("100 100\n-50 80\n");
    fs::write(folder.path().join("scene.txt"), &text).unwrap();
    let run = crawltrace(
        folder.path(),
        &["points", "scene.txt", "-o", "scene.svg"],
        None,
    )
    .succeeded();
    let svg = fs::read_to_string(folder.path().join("scene.svg")).unwrap();
    let tree = usvg::Tree::from_str(&svg, &usvg::Options::default())
        .unwrap_or_else(|e| panic!("{e}\n{}\n{svg}", run.describe()));
    assert!(tree.size().width() > 0.0 && tree.size().height() > 0.0);
    // Three curves and two outlier dots (usvg turns circles into paths).
    assert_eq!(path_count(tree.root()), 5, "{svg}");
    assert_eq!(svg.matches(" Z\"").count(), 2, "two closed curves\n{svg}");
}

#[test]
fn the_sample_point_set_comes_back_as_documented() {
    // samples/points/shapes.txt: a ring (two closed curves), a circle, a square and a house
    // (closed), an open wave, and five outliers (examples/make_point_set.rs).
    let sample = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/points/shapes.txt");
    let sample = sample.to_str().unwrap();
    let place = folder();
    let run = crawltrace(place.path(), &["points", sample], None);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    let json = run.json();
    let curves = json["curves"].as_array().unwrap();
    let closed = curves
        .iter()
        .filter(|c| c["closed"] == Value::Bool(true))
        .count();
    assert_eq!((curves.len(), closed), (6, 5), "{}", run.describe());
    assert_eq!(json["outliers"].as_array().unwrap().len(), 5);

    let run = crawltrace(
        place.path(),
        &["points", sample, "--format", "svg", "--show-points"],
        None,
    );
    assert_eq!(run.code, Some(0), "{}", run.describe());
    let svg = String::from_utf8(run.stdout.clone()).unwrap();
    let point_count = fs::read_to_string(sample)
        .unwrap()
        .lines()
        .filter(|line| !line.starts_with('#') && !line.trim().is_empty())
        .count();
    // Every point as a blue dot, and the outliers once more in red.
    assert_eq!(svg.matches("<circle ").count(), point_count + 5, "{svg}");
    let plain = crawltrace(place.path(), &["points", sample, "--format", "svg"], None);
    let plain = String::from_utf8(plain.stdout).unwrap();
    assert_eq!(plain.matches("<circle ").count(), 5);
}

/// A circle at spacing 1 and two stray points 0.6 apart, 5 spacings outside it: the robust crawl
/// (the default) reports the strays as outliers; the paper's crawl (`--method paper`) takes them
/// into a curve, as issue 10 describes.
#[test]
fn method_chooses_the_robust_crawl_by_default_or_the_papers() {
    let folder = folder();
    let count = 48;
    let radius = count as f64 / TAU;
    let mut text = circle_text(count, (0.0, 0.0), radius);
    let _ = writeln!(text, "{} 0.3", radius + 5.0);
    let _ = writeln!(text, "{} -0.3", radius + 5.0);
    fs::write(folder.path().join("strays.txt"), &text).unwrap();
    let robust = crawltrace(folder.path(), &["points", "strays.txt"], None)
        .succeeded()
        .json();
    let curves = robust["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 1, "{robust}");
    assert_eq!(curves[0]["closed"], Value::Bool(true), "{robust}");
    let mut on_circle = as_indices(&curves[0]["indices"]);
    on_circle.sort_unstable();
    assert_eq!(on_circle, (0..count).collect::<Vec<_>>(), "{robust}");
    assert_eq!(as_indices(&robust["outliers"]), [count, count + 1]);
    let explicit = crawltrace(
        folder.path(),
        &["points", "strays.txt", "--method", "robust"],
        None,
    )
    .succeeded()
    .json();
    assert_eq!(explicit, robust);
    let paper = crawltrace(
        folder.path(),
        &["points", "strays.txt", "--method", "paper"],
        None,
    )
    .succeeded()
    .json();
    assert_ne!(
        as_indices(&paper["outliers"]),
        [count, count + 1],
        "the paper's crawl takes the stray pair into a curve: {paper}"
    );
    let run = crawltrace(
        folder.path(),
        &["points", "strays.txt", "--method", "nearest"],
        None,
    );
    assert_eq!(run.code, Some(2), "{}", run.describe());
    assert!(run.stderr.contains("--method"), "{}", run.describe());
}
