//! Ground-truth matching: every true curve must come out as exactly one output path with the same
//! closedness within a Hausdorff tolerance, and no output path may be left over.

use std::fmt;

use super::hausdorff::Indexed;
use super::Polyline;

/// An output path (or a true curve) and how far it is, by symmetric Hausdorff distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest {
    /// Its index in its list.
    pub index: usize,
    /// The distance in pixels.
    pub distance: f64,
    /// Whether it is closed.
    pub closed: bool,
}

/// Why a true curve has no output path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MatchProblem {
    /// There are no output paths at all.
    NoOutputPaths,
    /// Even the nearest output path is farther than the tolerance.
    TooFar { output: usize, distance: f64 },
    /// An output path lies within the tolerance, but it is open where the curve is closed or the
    /// other way round.
    WrongClosedness { output: usize, distance: f64 },
    /// The only output paths within the tolerance were matched to other true curves.
    Taken { output: usize, by_truth: usize },
}

/// One true curve in a [`MatchReport`].
#[derive(Clone, Debug, PartialEq)]
pub struct CurveMatch {
    /// Index of the true curve.
    pub truth: usize,
    /// Whether the true curve is closed.
    pub closed: bool,
    /// The nearest output path, whatever its closedness.
    pub nearest: Option<Nearest>,
    /// The output path matched to this curve.
    pub matched: Option<usize>,
    /// Why there is none, when there is none.
    pub problem: Option<MatchProblem>,
}

/// An output path that matched no true curve.
#[derive(Clone, Debug, PartialEq)]
pub struct UnmatchedOutput {
    /// Index of the output path.
    pub output: usize,
    /// Whether it is closed.
    pub closed: bool,
    /// The nearest true curve, whatever its closedness.
    pub nearest_truth: Option<Nearest>,
}

/// The result of [`match_curves`].
#[derive(Clone, Debug, PartialEq)]
pub struct MatchReport {
    /// The Hausdorff tolerance in pixels.
    pub tolerance: f64,
    /// One entry per true curve, in order.
    pub curves: Vec<CurveMatch>,
    /// Output paths matched to no true curve, in order.
    pub unmatched_outputs: Vec<UnmatchedOutput>,
}

impl MatchReport {
    /// Every true curve matched and nothing left over.
    pub fn passed(&self) -> bool {
        self.unmatched_outputs.is_empty() && self.curves.iter().all(|c| c.matched.is_some())
    }

    /// The problem of true curve `truth`, if it has one.
    pub fn problem(&self, truth: usize) -> Option<MatchProblem> {
        self.curves[truth].problem
    }

    /// A human-readable account for failure messages: one line per true curve, then the
    /// unmatched output paths.
    pub fn summary(&self) -> String {
        self.to_string()
    }
}

impl fmt::Display for MatchReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let matched = self.curves.iter().filter(|c| c.matched.is_some()).count();
        writeln!(
            f,
            "{} of {} true curves matched within {:.2} px; {} output paths unmatched",
            matched,
            self.curves.len(),
            self.tolerance,
            self.unmatched_outputs.len()
        )?;
        for curve in &self.curves {
            let kind = closedness(curve.closed);
            write!(f, "  true curve {} ({kind}): ", curve.truth)?;
            match (curve.matched, curve.problem, curve.nearest) {
                (Some(output), _, Some(nearest)) => {
                    write!(f, "ok, output path {output} at {:.2} px", nearest.distance)?
                }
                (_, Some(MatchProblem::NoOutputPaths), _) => write!(f, "FAIL, no output paths")?,
                (_, Some(MatchProblem::TooFar { output, distance }), _) => write!(
                    f,
                    "FAIL, nearest output path {output} is {distance:.2} px away"
                )?,
                (_, Some(MatchProblem::WrongClosedness { output, distance }), _) => write!(
                    f,
                    "FAIL, output path {output} lies within {distance:.2} px but is {}",
                    closedness(!curve.closed)
                )?,
                (_, Some(MatchProblem::Taken { output, by_truth }), _) => write!(
                    f,
                    "FAIL, output path {output} is near but was matched to true curve {by_truth}"
                )?,
                _ => write!(f, "?")?,
            }
            writeln!(f)?;
        }
        for output in &self.unmatched_outputs {
            write!(
                f,
                "  output path {} ({}): FAIL, matches no true curve",
                output.output,
                closedness(output.closed)
            )?;
            if let Some(nearest) = output.nearest_truth {
                write!(
                    f,
                    "; nearest is true curve {} ({}) at {:.2} px",
                    nearest.index,
                    closedness(nearest.closed),
                    nearest.distance
                )?;
            }
            writeln!(f)?;
        }
        Ok(())
    }
}

fn closedness(closed: bool) -> &'static str {
    if closed {
        "closed"
    } else {
        "open"
    }
}

/// Matches the `output` paths to the `truth` curves. A pair qualifies when both are closed or both
/// open and their symmetric Hausdorff distance is at most `tolerance` pixels; qualifying pairs are
/// taken nearest first, each curve and each path at most once.
pub fn match_curves(truth: &[Polyline], output: &[Polyline], tolerance: f64) -> MatchReport {
    let truth_index: Vec<Indexed> = truth.iter().map(Indexed::new).collect();
    let output_index: Vec<Indexed> = output.iter().map(Indexed::new).collect();

    // For each true curve: the nearest output path and every one within the tolerance.
    let mut nearest_output = Vec::with_capacity(truth.len());
    let mut pairs = Vec::new();
    let mut close_other_kind = vec![None; truth.len()];
    for (t, curve) in truth_index.iter().enumerate() {
        let (nearest, within) = search(curve, &output_index, output, tolerance);
        for candidate in within {
            if candidate.closed == truth[t].closed {
                pairs.push((candidate.distance, t, candidate.index));
            } else if close_other_kind[t].is_none() {
                close_other_kind[t] = Some(candidate);
            }
        }
        nearest_output.push(nearest);
    }

    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut truth_to_output: Vec<Option<usize>> = vec![None; truth.len()];
    let mut output_to_truth: Vec<Option<usize>> = vec![None; output.len()];
    for &(_, t, o) in &pairs {
        if truth_to_output[t].is_none() && output_to_truth[o].is_none() {
            truth_to_output[t] = Some(o);
            output_to_truth[o] = Some(t);
        }
    }

    let curves = (0..truth.len())
        .map(|t| {
            let matched = truth_to_output[t];
            let taken = pairs
                .iter()
                .find(|&&(_, pair_truth, _)| pair_truth == t)
                .map(|&(_, _, o)| MatchProblem::Taken {
                    output: o,
                    by_truth: output_to_truth[o].expect("a qualifying path left free is matched"),
                });
            let problem = match (matched, nearest_output[t]) {
                (Some(_), _) => None,
                (None, None) => Some(MatchProblem::NoOutputPaths),
                (None, Some(nearest)) => taken
                    .or(close_other_kind[t].map(|c| MatchProblem::WrongClosedness {
                        output: c.index,
                        distance: c.distance,
                    }))
                    .or(Some(MatchProblem::TooFar {
                        output: nearest.index,
                        distance: nearest.distance,
                    })),
            };
            // Report the matched path as "nearest" when it is the one that counts.
            let nearest = match matched {
                Some(o) => pairs.iter().find(|&&(_, pt, po)| pt == t && po == o).map(
                    |&(distance, _, _)| Nearest {
                        index: o,
                        distance,
                        closed: output[o].closed,
                    },
                ),
                None => nearest_output[t],
            };
            CurveMatch {
                truth: t,
                closed: truth[t].closed,
                nearest,
                matched,
                problem,
            }
        })
        .collect();

    let unmatched_outputs = (0..output.len())
        .filter(|&o| output_to_truth[o].is_none())
        .map(|o| UnmatchedOutput {
            output: o,
            closed: output[o].closed,
            nearest_truth: search(&output_index[o], &truth_index, truth, tolerance).0,
        })
        .collect();

    MatchReport {
        tolerance,
        curves,
        unmatched_outputs,
    }
}

/// The nearest of `others` to `curve`, and all of them within `tolerance`. Candidates are tried in
/// order of a cheap lower bound, so far-away ones are never measured exactly.
fn search(
    curve: &Indexed,
    others: &[Indexed],
    polylines: &[Polyline],
    tolerance: f64,
) -> (Option<Nearest>, Vec<Nearest>) {
    let mut order: Vec<(f64, usize)> = others
        .iter()
        .enumerate()
        .map(|(index, other)| (curve.lower_bound(other), index))
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut nearest: Option<Nearest> = None;
    let mut within = Vec::new();
    for (bound, index) in order {
        let best = nearest.map_or(f64::INFINITY, |n| n.distance);
        if bound > best && bound > tolerance {
            break;
        }
        let candidate = Nearest {
            index,
            distance: curve.hausdorff(&others[index]),
            closed: polylines[index].closed,
        };
        if candidate.distance < best {
            nearest = Some(candidate);
        }
        if candidate.distance <= tolerance {
            within.push(candidate);
        }
    }
    (nearest, within)
}
