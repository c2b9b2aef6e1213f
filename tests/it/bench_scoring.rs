//! The benchmark scorer's judgement (`tests/support/bench.rs`) on hand-made traces: a perfect
//! trace passes, and each kind of failure is named for what it is.

use crate::support;

use crawltrace::Point;
use support::bench::{load_bench_truth, score_drawing, BenchTruth, Failure, TrueDot};
use support::Polyline;

fn polyline(points: &[(f64, f64)], closed: bool) -> Polyline {
    Polyline {
        points: points.iter().map(|&(x, y)| Point::new(x, y)).collect(),
        closed,
    }
}

/// A 100 px square, an open line beside it and a dot; pen 3, jitter 0.5: tolerance 4 px.
fn truth() -> BenchTruth {
    BenchTruth {
        family: "test".into(),
        touching: false,
        style: "clean".into(),
        pen: 3.0,
        jitter: 0.5,
        curves: vec![square(0.0), line(0.0)],
        dots: vec![TrueDot {
            centre: Point::new(300.0, 50.0),
            diameter: 6.0,
        }],
    }
}

fn square(shift: f64) -> Polyline {
    polyline(
        &[
            (10.0 + shift, 10.0),
            (110.0 + shift, 10.0),
            (110.0 + shift, 110.0),
            (10.0 + shift, 110.0),
        ],
        true,
    )
}

fn line(shift: f64) -> Polyline {
    polyline(&[(150.0, 10.0 + shift), (250.0, 110.0 + shift)], false)
}

fn dot_path(x: f64, y: f64) -> Polyline {
    polyline(&[(x, y)], false)
}

fn kinds(output: &[Polyline]) -> Vec<Failure> {
    score_drawing(&truth(), output).kinds()
}

#[test]
fn a_perfect_trace_is_exact() {
    let score = score_drawing(&truth(), &[square(0.0), line(0.0), dot_path(300.0, 50.0)]);
    assert!(score.exact(), "{:?}", score.problems);
    assert_eq!((score.matched_curves, score.matched_dots), (2, 1));
    assert!(score.worst_distance < 1e-9);
}

#[test]
fn a_trace_within_the_tolerance_is_exact_and_one_beyond_it_is_too_far() {
    // Tolerance = jitter 0.5 + pen / 2 + 2 = 4 px.
    assert_eq!(truth().tolerance(), 4.0);
    let near = [square(3.9), line(3.9), dot_path(303.0, 52.0)];
    assert!(score_drawing(&truth(), &near).exact());
    let far = [square(0.0), line(6.0), dot_path(300.0, 50.0)];
    assert_eq!(kinds(&far), vec![Failure::TooFarOff, Failure::ExtraPath]);
}

#[test]
fn a_missing_curve_fails_as_missing() {
    assert_eq!(
        kinds(&[square(0.0), dot_path(300.0, 50.0)]),
        vec![Failure::MissingCurve]
    );
}

#[test]
fn an_extra_path_fails_the_drawing() {
    let stray = polyline(&[(400.0, 300.0), (450.0, 320.0)], false);
    let score = score_drawing(
        &truth(),
        &[square(0.0), line(0.0), dot_path(300.0, 50.0), stray],
    );
    assert_eq!(score.kinds(), vec![Failure::ExtraPath]);
    assert!(score.worst_distance > 200.0, "{}", score.worst_distance);
}

#[test]
fn a_closed_curve_left_open_is_wrong_closedness() {
    // The square drawn round as an open path that stops 30 px short of its start.
    let mut open_square = square(0.0);
    open_square.points.push(Point::new(10.0, 40.0));
    open_square.closed = false;
    assert_eq!(
        kinds(&[open_square, line(0.0), dot_path(300.0, 50.0)]),
        vec![Failure::WrongClosedness, Failure::ExtraPath]
    );
    // The same square with its last stretch as a path of its own is split, not left open.
    let mut three_sides = square(0.0);
    three_sides.points.push(Point::new(10.0, 40.0));
    three_sides.closed = false;
    let last_stretch = polyline(&[(10.0, 40.0), (10.0, 10.0)], false);
    assert_eq!(
        kinds(&[three_sides, last_stretch, line(0.0), dot_path(300.0, 50.0)]),
        vec![Failure::TooFarSplit, Failure::ExtraPath]
    );
    // Round the whole square and back to its start, open: the matcher's own closedness check.
    let mut around = square(0.0);
    around.points.push(around.points[0]);
    around.closed = false;
    let score = score_drawing(&truth(), &[around, line(0.0), dot_path(300.0, 50.0)]);
    assert!(score
        .problems
        .iter()
        .any(|p| p.kind == Failure::WrongClosedness && p.detail.contains("curve 0")));
}

#[test]
fn a_curve_split_cut_short_or_joined_to_another_is_told_apart() {
    let half = polyline(&[(150.0, 10.0), (200.0, 60.0)], false);
    let other_half = polyline(&[(200.0, 60.0), (250.0, 110.0)], false);
    assert_eq!(
        kinds(&[square(0.0), half, other_half, dot_path(300.0, 50.0)]),
        vec![Failure::TooFarSplit, Failure::ExtraPath]
    );
    // A corner cut off 6 px along each side: 4.2 px from the truth, the tolerance is 4.
    let mut cut = square(0.0);
    cut.points
        .splice(1..2, [Point::new(104.0, 10.0), Point::new(110.0, 16.0)]);
    assert_eq!(
        kinds(&[cut, line(0.0), dot_path(300.0, 50.0)]),
        vec![Failure::TooFarCut, Failure::ExtraPath]
    );
    // The line runs on into the dot: the line overruns, and the dot is bridged.
    let joined = polyline(&[(150.0, 10.0), (250.0, 110.0), (300.0, 50.0)], false);
    assert_eq!(
        kinds(&[square(0.0), joined]),
        vec![
            Failure::TooFarOverrun,
            Failure::ExtraPath,
            Failure::DotBridged
        ]
    );
}

#[test]
fn a_dot_must_be_kept_and_kept_apart() {
    // Any small path within the dot counts, open or closed.
    let ring = polyline(&[(298.0, 50.0), (300.0, 48.0), (302.0, 50.0)], true);
    assert!(score_drawing(&truth(), &[square(0.0), line(0.0), ring]).exact());
    assert_eq!(kinds(&[square(0.0), line(0.0)]), vec![Failure::DotMissing]);
    let through = polyline(&[(280.0, 50.0), (320.0, 50.0)], false);
    assert_eq!(
        kinds(&[square(0.0), line(0.0), through]),
        vec![Failure::ExtraPath, Failure::DotBridged]
    );
}

#[test]
fn an_overshooting_segment_shows_as_the_worst_distance() {
    let mut overshoot = square(0.0);
    overshoot.points.insert(2, Point::new(140.0, 60.0));
    let score = score_drawing(&truth(), &[overshoot, line(0.0), dot_path(300.0, 50.0)]);
    assert!(
        (score.worst_distance - 30.0).abs() < 0.1,
        "{}",
        score.worst_distance
    );
    assert!(!score.exact());
}

#[test]
fn truth_files_are_read_with_their_dots_and_attributes() {
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100" viewBox="0 0 200 100" data-family="dots" data-touching="false" data-style="thin" data-pen="1.8" data-jitter="0.7">
<g fill="none" stroke="black" stroke-width="1.8" stroke-linecap="round" stroke-linejoin="round">
<path d="M10 10 L90 10 L90 90 Z"/>
</g>
<g data-kind="dots" fill="none" stroke="black" stroke-linecap="round">
<path stroke-width="4.5" d="M150 50 h0"/>
</g>
</svg>
"#;
    let truth = load_bench_truth(svg).expect("a valid truth file");
    assert_eq!(
        (truth.family.as_str(), truth.style.as_str()),
        ("dots", "thin")
    );
    assert_eq!((truth.pen, truth.jitter, truth.touching), (1.8, 0.7, false));
    assert_eq!(truth.curves.len(), 1);
    assert!(truth.curves[0].closed);
    assert_eq!(
        truth.dots,
        vec![TrueDot {
            centre: Point::new(150.0, 50.0),
            diameter: 4.5
        }]
    );
    let no_pen = svg.replace(" data-pen=\"1.8\"", "");
    assert!(load_bench_truth(&no_pen).unwrap_err().contains("data-pen"));
    assert!(load_bench_truth("<svg").unwrap_err().contains("XML"));
}
