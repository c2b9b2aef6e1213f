//! Self-tests of the helpers in `tests/support`: curve loading, ground-truth matching (each sample's
//! truth matches itself, and perturbed copies fail for the right reason) and image comparison.

use crate::support;

use std::path::PathBuf;

use crawltrace::Point;
use image::{Rgba, RgbaImage};
use support::{
    compare_images, load_curves, load_stroke_width, match_curves, write_diff, MatchProblem,
    Polyline,
};

/// Every `samples/*.truth.svg` as (name, text), sorted by name.
fn truth_files() -> Vec<(String, String)> {
    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("samples");
    let mut files: Vec<(String, String)> = std::fs::read_dir(&folder)
        .expect("samples/ exists")
        .map(|entry| entry.expect("readable entry").path())
        .filter_map(|path| {
            let name = path.file_name()?.to_str()?.strip_suffix(".truth.svg")?;
            Some((name.to_string(), std::fs::read_to_string(&path).ok()?))
        })
        .collect();
    files.sort();
    assert!(files.len() >= 10, "expected at least ten truth files");
    files
}

/// The tolerance callers use: half the pen plus two pixels.
fn tolerance(svg: &str) -> f64 {
    load_stroke_width(svg).expect("truth files have a stroke width") / 2.0 + 2.0
}

/// The `<path …/>` lines of a truth file.
fn path_lines(svg: &str) -> Vec<&str> {
    svg.lines().filter(|l| l.starts_with("<path ")).collect()
}

/// `svg` with its `index`-th path line replaced by `replacement`.
fn replace_path(svg: &str, index: usize, replacement: &str) -> String {
    let target = path_lines(svg)[index];
    let mut lines: Vec<&str> = svg.lines().collect();
    let position = lines.iter().position(|l| *l == target).unwrap();
    lines[position] = replacement;
    lines.join("\n")
}

#[test]
fn every_truth_file_matches_itself() {
    for (name, svg) in truth_files() {
        let curves = load_curves(&svg);
        assert_eq!(
            curves.len(),
            path_lines(&svg).len(),
            "{name}: one curve per path"
        );
        let closed = curves.iter().filter(|c| c.closed).count();
        assert_eq!(closed, svg.matches(" Z\"").count(), "{name}: closed curves");
        let report = match_curves(&curves, &curves, tolerance(&svg));
        assert!(report.passed(), "{name}:\n{report}");
        for curve in &report.curves {
            assert_eq!(curve.matched, Some(curve.truth), "{name}:\n{report}");
            assert!(curve.nearest.unwrap().distance < 1e-6, "{name}:\n{report}");
        }
    }
}

#[test]
fn a_curve_shifted_by_ten_pixels_is_too_far() {
    for (name, svg) in truth_files() {
        let shifted_line = format!(
            "<g transform=\"translate(10 0)\">{}</g>",
            path_lines(&svg)[0]
        );
        let shifted = replace_path(&svg, 0, &shifted_line);
        let report = match_curves(&load_curves(&svg), &load_curves(&shifted), tolerance(&svg));
        assert!(!report.passed(), "{name}:\n{report}");
        match report.problem(0) {
            Some(MatchProblem::TooFar {
                output: 0,
                distance,
            }) => {
                assert!((distance - 10.0).abs() < 0.01, "{name}:\n{report}")
            }
            other => panic!("{name}: expected curve 0 too far, got {other:?}\n{report}"),
        }
        assert_eq!(report.unmatched_outputs.len(), 1, "{name}:\n{report}");
        assert_eq!(report.unmatched_outputs[0].output, 0, "{name}:\n{report}");
        assert!(report.curves[1..]
            .iter()
            .all(|c| c.matched == Some(c.truth)));
    }
}

#[test]
fn a_closed_curve_written_open_has_the_wrong_closedness() {
    for (name, svg) in truth_files() {
        let truth = load_curves(&svg);
        let Some(index) = truth.iter().position(|c| c.closed) else {
            assert!(
                !svg.contains(" Z\""),
                "{name}: closed paths not loaded as closed"
            );
            continue;
        };
        // Same geometry (the path returns to its start), only the Z is gone.
        let start = truth[index].points[0];
        let line = path_lines(&svg)[index];
        let opened = line.replace(" Z\"", &format!(" L{} {}\"", start.x, start.y));
        assert_ne!(opened, line, "{name}: the path ends with Z");
        let output = load_curves(&replace_path(&svg, index, &opened));
        let report = match_curves(&truth, &output, tolerance(&svg));
        assert!(!report.passed(), "{name}:\n{report}");
        match report.problem(index) {
            Some(MatchProblem::WrongClosedness { output, distance }) => {
                assert_eq!(output, index, "{name}:\n{report}");
                assert!(distance < 0.01, "{name}:\n{report}");
            }
            other => panic!("{name}: expected wrong closedness, got {other:?}\n{report}"),
        }
        assert_eq!(report.unmatched_outputs.len(), 1, "{name}:\n{report}");
    }
}

#[test]
fn a_square_with_its_z_simply_removed_loses_a_side() {
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">
<path d="M10 10 L90 10 L90 90 L10 90 Z" stroke="black" fill="none"/></svg>"#;
    let truth = load_curves(svg);
    let output = load_curves(&svg.replace(" Z", ""));
    assert!(truth[0].closed && !output[0].closed);
    let report = match_curves(&truth, &output, 3.5);
    match report.problem(0) {
        // The middle of the missing side is 40 px from the rest.
        Some(MatchProblem::TooFar {
            output: 0,
            distance,
        }) => {
            assert!((distance - 40.0).abs() < 1e-9, "{report}")
        }
        other => panic!("expected too far, got {other:?}\n{report}"),
    }
}

#[test]
fn a_curve_split_in_two_matches_nothing() {
    for (name, svg) in truth_files() {
        let truth = load_curves(&svg);
        let whole = &truth[0];
        let middle = whole.points.len() / 2;
        let mut second_half = whole.points[middle..].to_vec();
        if whole.closed {
            second_half.push(whole.points[0]);
        }
        let halves = [whole.points[..=middle].to_vec(), second_half];
        let mut output = truth.clone();
        output.splice(
            0..1,
            halves.map(|points| Polyline {
                points,
                closed: false,
            }),
        );
        let report = match_curves(&truth, &output, tolerance(&svg));
        assert!(!report.passed(), "{name}:\n{report}");
        assert!(
            matches!(report.problem(0), Some(MatchProblem::TooFar { .. })),
            "{name}:\n{report}"
        );
        let unmatched: Vec<usize> = report.unmatched_outputs.iter().map(|u| u.output).collect();
        assert_eq!(unmatched, [0, 1], "{name}:\n{report}");
        assert!(report.curves[1..].iter().all(|c| c.matched.is_some()));
    }
}

#[test]
fn an_extra_path_is_left_over() {
    for (name, svg) in truth_files() {
        let truth = load_curves(&svg);
        let stray = "<path d=\"M2 2 L20 2\"/>\n</g>";
        let with_stray = svg.replacen("</g>", stray, 1);
        let report = match_curves(&truth, &load_curves(&with_stray), tolerance(&svg));
        assert!(!report.passed(), "{name}:\n{report}");
        assert!(report.curves.iter().all(|c| c.matched.is_some()));
        let unmatched: Vec<usize> = report.unmatched_outputs.iter().map(|u| u.output).collect();
        assert_eq!(unmatched, [truth.len()], "{name}:\n{report}");
    }
}

#[test]
fn a_duplicated_curve_counts_once_and_the_copy_is_left_over() {
    let (name, svg) = &truth_files()[0];
    let truth = load_curves(svg);
    let mut output = truth.clone();
    output.push(truth[0].clone());
    let report = match_curves(&truth, &output, tolerance(svg));
    assert!(!report.passed(), "{name}:\n{report}");
    assert_eq!(report.unmatched_outputs.len(), 1, "{name}:\n{report}");
    let copy = &report.unmatched_outputs[0];
    assert_eq!(copy.output, truth.len());
    let nearest = copy.nearest_truth.expect("the copy lies on curve 0");
    assert_eq!(nearest.index, 0, "{report}");
    assert!(nearest.distance < 1e-9, "{report}");
    assert!(
        report.summary().contains("matches no true curve"),
        "{report}"
    );
}

#[test]
fn no_output_at_all_is_reported_per_curve() {
    let (_, svg) = &truth_files()[0];
    let report = match_curves(&load_curves(svg), &[], 3.5);
    assert!(!report.passed());
    assert!(report
        .curves
        .iter()
        .all(|c| c.problem == Some(MatchProblem::NoOutputPaths)));
}

#[test]
fn hausdorff_distance_sees_offsets_and_overhangs() {
    let line = |x0: f64, y0: f64, x1: f64, y1: f64| Polyline {
        points: vec![Point::new(x0, y0), Point::new(x1, y1)],
        closed: false,
    };
    let truth = [line(0.0, 0.0, 100.0, 0.0)];
    let distance = |output: Polyline| {
        match_curves(&truth, &[output], 1000.0).curves[0]
            .nearest
            .unwrap()
            .distance
    };
    assert!((distance(line(0.0, 3.0, 100.0, 3.0)) - 3.0).abs() < 1e-9);
    // An overhang counts even though every output point is near the truth's line.
    assert!((distance(line(0.0, 0.0, 107.0, 0.0)) - 7.0).abs() < 1e-9);
    // And a missing end counts from the truth's side.
    assert!((distance(line(0.0, 0.0, 60.0, 0.0)) - 40.0).abs() < 1e-9);
}

#[test]
fn load_curves_flattens_shapes_and_applies_the_view_box_and_transforms() {
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100" viewBox="0 0 100 50">
<g transform="translate(10 0)" stroke="black" fill="none">
<path d="M0 5 L10 5"/>
<circle cx="50" cy="25" r="10"/>
<path d="M0 40 Q20 20 40 40"/>
</g></svg>"#;
    let curves = load_curves(svg);
    assert_eq!(curves.len(), 3);
    let line = &curves[0];
    assert!(!line.closed);
    assert_eq!(
        line.points,
        [Point::new(20.0, 10.0), Point::new(40.0, 10.0)]
    );
    let circle = &curves[1];
    assert!(circle.closed);
    for pair in circle.points.windows(2) {
        assert!(pair[0].distance(pair[1]) <= 0.26, "flattened finely");
    }
    for point in &circle.points {
        // Radius 10 user units is 20 canvas pixels around (120, 50).
        assert!((point.distance(Point::new(120.0, 50.0)) - 20.0).abs() < 0.01);
    }
    let quad = &curves[2];
    assert!(!quad.closed);
    assert_eq!(quad.points.first(), Some(&Point::new(20.0, 80.0)));
    assert_eq!(quad.points.last(), Some(&Point::new(100.0, 80.0)));
}

fn checkerboard(width: u32, height: u32) -> RgbaImage {
    RgbaImage::from_fn(width, height, |x, y| {
        let v = if (x / 4 + y / 4) % 2 == 0 { 30 } else { 220 };
        Rgba([v, v, v, 255])
    })
}

#[test]
fn image_comparison_detects_one_changed_pixel_and_writes_the_diff() {
    let expected = checkerboard(40, 30);
    let mut actual = expected.clone();
    actual.put_pixel(7, 5, Rgba([30, 200, 30, 255]));

    assert!(compare_images(&expected, &expected, 0, 0).passed());
    let strict = compare_images(&expected, &actual, 0, 0);
    assert!(!strict.passed(), "{strict}");
    assert_eq!(strict.differing_pixels, 1);
    assert_eq!(strict.largest_difference, 170);
    assert!(compare_images(&expected, &actual, 0, 1).passed());
    assert!(compare_images(&expected, &actual, 170, 0).passed());

    let path = write_diff("selftest-changed-pixel", &expected, &actual);
    assert!(path.ends_with("tests/diffs/selftest-changed-pixel.png"));
    let picture = image::open(&path).expect("diff is a PNG").to_rgba8();
    assert_eq!(picture.dimensions(), (3 * 40 + 8, 30));
    // The middle panel starts after the expected image and a 4-pixel separator.
    let changed = picture.get_pixel(44 + 7, 5).0;
    let unchanged = picture.get_pixel(44 + 8, 5).0;
    assert_eq!((changed[0], changed[1] < 100), (255, true), "{changed:?}");
    assert_eq!(unchanged[0], unchanged[1], "unchanged pixels stay grey");
    assert_eq!(picture.get_pixel(88 + 7, 5).0, [30, 200, 30, 255]);
}

#[test]
fn a_size_mismatch_fails_without_panicking() {
    let expected = checkerboard(10, 10);
    let actual = checkerboard(10, 12);
    let comparison = compare_images(&expected, &actual, 255, 1000);
    assert!(!comparison.passed());
    assert_eq!(comparison.differing_pixels, 20);
    assert!(
        comparison.summary().contains("size differs"),
        "{comparison}"
    );
    let path = write_diff("selftest-size-mismatch", &expected, &actual);
    let picture = image::open(&path).expect("diff is a PNG").to_rgba8();
    assert_eq!(picture.dimensions(), (10 + 10 + 10 + 8, 12));
    assert_eq!(picture.get_pixel(14 + 3, 11).0, [255, 0, 0, 255]);
}
