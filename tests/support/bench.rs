//! The generalization benchmark's ground truth and scoring (issue 8): reading a drawing's
//! `NAME.truth.svg` (curves, dots, and the family, style, pen width and jitter on its root), and
//! judging a trace against it. A true curve counts when exactly one output path has its
//! closedness and lies within jitter + pen / 2 + 2 px of it (symmetric Hausdorff distance, the
//! matcher of `matching.rs`); a dot counts when one output path lies wholly within that tolerance
//! of the dot's disc; every other output path is an extra. A drawing is exact when every curve and
//! dot is matched and nothing is extra. Each failure gets a reason.

use std::fmt;

use crawltrace::Point;

use super::hausdorff::Indexed;
use super::{load_curves, match_curves, MatchProblem, Polyline};

/// An isolated dot of the truth: its centre is its true position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrueDot {
    pub centre: Point,
    pub diameter: f64,
}

/// A benchmark drawing's ground truth.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchTruth {
    pub family: String,
    /// Whether the family is one of issue 9's touching-parts families (reported apart).
    pub touching: bool,
    pub style: String,
    /// Nominal pen width, px.
    pub pen: f64,
    /// Largest sideways wobble of a stroke, px.
    pub jitter: f64,
    /// The true curves (dots not included).
    pub curves: Vec<Polyline>,
    pub dots: Vec<TrueDot>,
}

impl BenchTruth {
    /// How far an output path may lie from its true curve: jitter + pen / 2 + 2 px.
    pub fn tolerance(&self) -> f64 {
        self.jitter + self.pen / 2.0 + 2.0
    }
}

/// Reads a benchmark truth file; the error names what is wrong.
pub fn load_bench_truth(svg: &str) -> Result<BenchTruth, String> {
    let document = roxmltree::Document::parse(svg).map_err(|e| format!("not valid XML: {e}"))?;
    let root = document.root_element();
    let text = |name: &str| {
        root.attribute(name)
            .ok_or_else(|| format!("the root has no {name} attribute (not a benchmark truth file)"))
    };
    let number = |name: &str| -> Result<f64, String> {
        let value = text(name)?;
        value
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && *v >= 0.0)
            .ok_or_else(|| format!("{name}=\"{value}\" is not a non-negative number"))
    };
    let mut dots = Vec::new();
    for group in root
        .children()
        .filter(|n| n.attribute("data-kind") == Some("dots"))
    {
        for path in group.children().filter(|n| n.has_tag_name("path")) {
            dots.push(parse_dot(path)?);
        }
    }
    usvg::Tree::from_str(svg, &usvg::Options::default())
        .map_err(|e| format!("usvg rejects the SVG: {e}"))?;
    let curves = load_curves(svg);
    // Dots come back from usvg as single points; they are kept apart.
    let curves: Vec<Polyline> = curves.into_iter().filter(|c| c.points.len() > 1).collect();
    Ok(BenchTruth {
        family: text("data-family")?.to_string(),
        touching: root.attribute("data-touching") == Some("true"),
        style: text("data-style")?.to_string(),
        pen: number("data-pen")?,
        jitter: number("data-jitter")?,
        curves,
        dots,
    })
}

/// A dot is written as `<path stroke-width="D" d="MX Y h0"/>`.
fn parse_dot(path: roxmltree::Node) -> Result<TrueDot, String> {
    let data = path.attribute("d").unwrap_or("");
    let coordinates: Vec<f64> = data
        .trim_start_matches('M')
        .trim_end_matches("h0")
        .split_whitespace()
        .filter_map(|word| word.parse().ok())
        .collect();
    let diameter = path
        .attribute("stroke-width")
        .and_then(|w| w.parse::<f64>().ok());
    match (coordinates.as_slice(), diameter) {
        ([x, y], Some(diameter)) if diameter > 0.0 => Ok(TrueDot {
            centre: Point::new(*x, *y),
            diameter,
        }),
        _ => Err(format!(
            "dot path d=\"{data}\" is not \"MX Y h0\" with a stroke width"
        )),
    }
}

/// Why a drawing is not exact.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Failure {
    /// No output path of its own follows the curve (nothing there, or the only near path is
    /// another curve's).
    MissingCurve,
    /// A path follows the curve within the tolerance but is open where the curve is closed, or
    /// the other way round.
    WrongClosedness,
    /// The nearest path lies on the curve but does not reach all of it, by at most
    /// `CUT_REACH` tolerances: a tip, corner or end cut off.
    TooFarCut,
    /// The nearest path lies on the curve but leaves a longer stretch of it out: the curve is
    /// split into several paths (or a piece is missing).
    TooFarSplit,
    /// The nearest path covers the curve but runs on beyond it: joined to another curve, bridged
    /// across, or overshooting.
    TooFarOverrun,
    /// The nearest path neither lies on the curve nor covers it.
    TooFarOff,
    /// An output path that matches nothing.
    ExtraPath,
    /// No output path at the dot.
    DotMissing,
    /// A path passes through the dot but is not confined to it (bridged into a stroke).
    DotBridged,
}

impl Failure {
    /// Every failure kind, in table order.
    pub const ALL: [Failure; 9] = [
        Failure::MissingCurve,
        Failure::WrongClosedness,
        Failure::TooFarCut,
        Failure::TooFarSplit,
        Failure::TooFarOverrun,
        Failure::TooFarOff,
        Failure::ExtraPath,
        Failure::DotMissing,
        Failure::DotBridged,
    ];

    /// Short name for tables and labels.
    pub fn name(self) -> &'static str {
        match self {
            Failure::MissingCurve => "missing curve",
            Failure::WrongClosedness => "wrong closedness",
            Failure::TooFarCut => "too far: cut short",
            Failure::TooFarSplit => "too far: split",
            Failure::TooFarOverrun => "too far: runs past",
            Failure::TooFarOff => "too far: off curve",
            Failure::ExtraPath => "extra path",
            Failure::DotMissing => "dot missing",
            Failure::DotBridged => "dot bridged",
        }
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One failure of a drawing: its kind and what it concerns.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    pub kind: Failure,
    /// "curve 2 (closed): nearest path 5 at 7.3 px", "path 4 (open): 12.0 px from the truth", ...
    pub detail: String,
}

/// How one output path was judged.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputRole {
    /// Matched to a true curve.
    Curve,
    /// Matched to a dot.
    Dot,
    /// Matched to nothing.
    Extra,
}

/// The judgement of one trace against its truth.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawingScore {
    pub tolerance: f64,
    pub curves: usize,
    pub matched_curves: usize,
    pub dots: usize,
    pub matched_dots: usize,
    /// One entry per output path.
    pub roles: Vec<OutputRole>,
    pub problems: Vec<Problem>,
    /// The largest distance of any point of any output path from the nearest true curve or dot:
    /// overshoots of fitted segments show here.
    pub worst_distance: f64,
}

impl DrawingScore {
    /// Every curve and dot matched, nothing extra.
    pub fn exact(&self) -> bool {
        self.problems.is_empty()
    }

    /// The distinct failure kinds, in table order.
    pub fn kinds(&self) -> Vec<Failure> {
        let mut kinds: Vec<Failure> = self.problems.iter().map(|p| p.kind).collect();
        kinds.sort();
        kinds.dedup();
        kinds
    }
}

/// A curve counts as missing (rather than traced too far off) when less than this share of it
/// has any output path within `MISSING_REACH` tolerances.
const COVERED_SHARE: f64 = 0.5;
const MISSING_REACH: f64 = 3.0;
/// A path of the other closedness that shares this much of its length with the curve (and lies
/// on it, or covers it) is the curve left open or sealed.
const SAME_BUT_A_GAP: f64 = 0.75;
/// A path on the curve that misses it by at most this many tolerances has cut a tip, a corner or
/// an end; one that misses more has left a piece out.
const CUT_REACH: f64 = 3.0;
/// Other paths covering more than this share of the curve make it split, not left open.
const OTHER_PATHS_SHARE: f64 = 0.02;

/// Judges `output` (the traced paths, flattened) against `truth`.
pub fn score_drawing(truth: &BenchTruth, output: &[Polyline]) -> DrawingScore {
    let tolerance = truth.tolerance();
    let report = match_curves(&truth.curves, output, tolerance);
    let mut roles = vec![OutputRole::Extra; output.len()];
    for curve in &report.curves {
        if let Some(o) = curve.matched {
            roles[o] = OutputRole::Curve;
        }
    }
    let indexed: Vec<Indexed> = output.iter().map(Indexed::new).collect();
    let mut problems = Vec::new();
    let matched_dots = match_dots(
        truth,
        output,
        &indexed,
        tolerance,
        &mut roles,
        &mut problems,
    );
    let all_output = Indexed::union(output);
    for curve in report.curves.iter().filter(|c| c.matched.is_none()) {
        problems.push(curve_problem(
            truth,
            curve,
            output,
            &indexed,
            &all_output,
            tolerance,
        ));
    }
    let mut truth_polylines = truth.curves.clone();
    truth_polylines.extend(truth.dots.iter().map(|dot| Polyline {
        points: vec![dot.centre],
        closed: false,
    }));
    let all_truth = Indexed::union(&truth_polylines);
    let mut worst_distance: f64 = 0.0;
    for (index, path) in indexed.iter().enumerate() {
        let distance = path.directed(&all_truth);
        worst_distance = worst_distance.max(distance);
        if roles[index] == OutputRole::Extra {
            problems.push(Problem {
                kind: Failure::ExtraPath,
                detail: format!(
                    "path {index} ({}): {distance:.1} px from the truth at worst",
                    closedness(output[index].closed)
                ),
            });
        }
    }
    DrawingScore {
        tolerance,
        curves: truth.curves.len(),
        matched_curves: report.curves.iter().filter(|c| c.matched.is_some()).count(),
        dots: truth.dots.len(),
        matched_dots,
        roles,
        problems,
        worst_distance,
    }
}

/// Matches dots to output paths not taken by curves, nearest first: a path qualifies when all of
/// it lies within the tolerance of the dot's disc. Returns how many dots matched; records a
/// problem for each that did not.
fn match_dots(
    truth: &BenchTruth,
    output: &[Polyline],
    indexed: &[Indexed],
    tolerance: f64,
    roles: &mut [OutputRole],
    problems: &mut Vec<Problem>,
) -> usize {
    let dot_indexed: Vec<Indexed> = truth
        .dots
        .iter()
        .map(|dot| {
            Indexed::new(&Polyline {
                points: vec![dot.centre],
                closed: false,
            })
        })
        .collect();
    let mut pairs = Vec::new();
    for (d, dot) in truth.dots.iter().enumerate() {
        let reach = tolerance + dot.diameter / 2.0;
        for (o, path) in indexed.iter().enumerate() {
            if roles[o] != OutputRole::Extra || path.lower_bound(&dot_indexed[d]) > reach {
                continue;
            }
            let distance = path.directed(&dot_indexed[d]);
            if distance <= reach {
                pairs.push((distance, d, o));
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut dot_matched = vec![false; truth.dots.len()];
    for (_, d, o) in pairs {
        if !dot_matched[d] && roles[o] == OutputRole::Extra {
            dot_matched[d] = true;
            roles[o] = OutputRole::Dot;
        }
    }
    for (d, dot) in truth.dots.iter().enumerate() {
        if dot_matched[d] {
            continue;
        }
        let reach = tolerance + dot.diameter / 2.0;
        let through = output
            .iter()
            .enumerate()
            .map(|(o, _)| (o, dot_indexed[d].directed(&indexed[o])))
            .find(|&(_, distance)| distance <= reach);
        let at = format!("dot {d} at ({:.0}, {:.0})", dot.centre.x, dot.centre.y);
        problems.push(match through {
            Some((o, _)) => Problem {
                kind: Failure::DotBridged,
                detail: format!("{at}: path {o} runs through it"),
            },
            None => Problem {
                kind: Failure::DotMissing,
                detail: format!("{at}: no path there"),
            },
        });
    }
    dot_matched.iter().filter(|&&m| m).count()
}

/// Why true curve `curve` has no path.
fn curve_problem(
    truth: &BenchTruth,
    curve: &super::CurveMatch,
    paths: &[Polyline],
    indexed: &[Indexed],
    all_output: &Indexed,
    tolerance: f64,
) -> Problem {
    let name = format!("curve {} ({})", curve.truth, closedness(curve.closed));
    let true_curve = Indexed::new(&truth.curves[curve.truth]);
    let covered = true_curve.fraction_within(all_output, MISSING_REACH * tolerance);
    match curve.problem {
        Some(MatchProblem::WrongClosedness { output, distance }) => Problem {
            kind: Failure::WrongClosedness,
            detail: format!(
                "{name}: path {output} follows it within {distance:.1} px but is {}",
                closedness(!curve.closed)
            ),
        },
        Some(MatchProblem::Taken { output, by_truth }) => Problem {
            kind: Failure::MissingCurve,
            detail: format!("{name}: its only near path {output} is curve {by_truth}'s"),
        },
        Some(MatchProblem::TooFar { output, distance }) if covered >= COVERED_SHARE => {
            let (along, worst) = true_curve.farthest(&indexed[output]);
            let off = indexed[output].directed(&true_curve);
            // A loop left open at a gap wider than the tolerance, or an open curve sealed by a
            // long closing segment, is a closedness failure, not a distance one: the path and
            // the curve are the same but for a stretch of at most a quarter of either.
            let closedness_differs = curve.closed != paths[output].closed;
            // Left open, not split: no other path lies on the stretch this one leaves out.
            let own_cover = true_curve.fraction_within(&indexed[output], tolerance);
            let all_cover = true_curve.fraction_within(all_output, tolerance);
            let left_open = off <= tolerance
                && own_cover >= SAME_BUT_A_GAP
                && all_cover - own_cover < OTHER_PATHS_SHARE;
            let sealed = along <= tolerance
                && indexed[output].fraction_within(&true_curve, tolerance) >= SAME_BUT_A_GAP;
            let kind = if closedness_differs && (left_open || sealed) {
                Failure::WrongClosedness
            } else if off <= tolerance && along <= CUT_REACH * tolerance {
                Failure::TooFarCut
            } else if off <= tolerance {
                Failure::TooFarSplit
            } else if along <= tolerance {
                Failure::TooFarOverrun
            } else {
                Failure::TooFarOff
            };
            Problem {
                kind,
                detail: format!(
                    "{name}: nearest path {output} at {distance:.1} px \
                     (curve to path {along:.1} at {:.0},{:.0}; path to curve {off:.1})",
                    worst.x, worst.y
                ),
            }
        }
        _ => Problem {
            kind: Failure::MissingCurve,
            detail: format!(
                "{name}: only {:.0} % of it has a path within {:.1} px",
                covered * 100.0,
                MISSING_REACH * tolerance
            ),
        },
    }
}

fn closedness(closed: bool) -> &'static str {
    if closed {
        "closed"
    } else {
        "open"
    }
}
