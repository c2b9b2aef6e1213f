//! The scorer's Markdown report (pass rate per family × style with totals, failure reasons, the
//! worst distance of an output path from the truth, time) and its JSON lines.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use crate::support::bench::{Failure, OutputRole};
use crate::{Entry, Outcome};

/// Styles in table order; any other style found is appended.
const STYLE_ORDER: [&str; 4] = ["clean", "thick", "thin", "scan"];

/// Passed and total drawings.
#[derive(Clone, Copy, Default)]
struct Tally {
    passed: usize,
    total: usize,
}

impl Tally {
    fn add(&mut self, passed: bool) {
        self.passed += usize::from(passed);
        self.total += 1;
    }

    fn cell(self, with_percent: bool) -> String {
        if self.total == 0 {
            return "–".into();
        }
        if with_percent {
            let percent = 100.0 * self.passed as f64 / self.total as f64;
            format!("{}/{} ({percent:.0} %)", self.passed, self.total)
        } else {
            format!("{}/{}", self.passed, self.total)
        }
    }
}

/// The whole report for one method.
pub fn report(method: &str, entries: &[Entry], outcomes: &[Outcome], wall: f64) -> String {
    let mut text = String::new();
    let title = match method {
        "points" => "the paper's crawl (`--method points`)",
        _ => "the stroke-aware crawl (default)",
    };
    let _ = writeln!(text, "### {title}\n");
    text.push_str(&pass_table(entries, outcomes));
    text.push('\n');
    text.push_str(&failure_table(outcomes));
    text.push('\n');
    text.push_str(&distance_and_time(entries, outcomes, wall));
    text
}

fn pass_table(entries: &[Entry], outcomes: &[Outcome]) -> String {
    let mut styles: Vec<String> = STYLE_ORDER.iter().map(|s| s.to_string()).collect();
    for entry in entries {
        if !styles.contains(&entry.truth.style) {
            styles.push(entry.truth.style.clone());
        }
    }
    // Families by name (the order of the sorted file names), line art before touching parts.
    let mut families: Vec<(bool, String)> = Vec::new();
    for entry in entries {
        let key = (entry.truth.touching, entry.truth.family.clone());
        if !families.contains(&key) {
            families.push(key);
        }
    }
    families.sort_by_key(|(touching, _)| *touching);
    let mut cells: BTreeMap<(String, String), Tally> = BTreeMap::new();
    for (entry, outcome) in entries.iter().zip(outcomes) {
        let key = (entry.truth.family.clone(), entry.truth.style.clone());
        cells.entry(key).or_default().add(outcome.score.exact());
    }
    let mut text = format!("| family | {} | all |\n|---|", styles.join(" | "));
    text.push_str(&"---:|".repeat(styles.len() + 1));
    text.push('\n');
    let row = |text: &mut String, label: &str, filter: &dyn Fn(&str, bool) -> bool| {
        let mut all = Tally::default();
        let mut line = format!("| {label} |");
        for style in &styles {
            let mut tally = Tally::default();
            for (touching, family) in &families {
                if filter(family, *touching) {
                    if let Some(cell) = cells.get(&(family.clone(), style.clone())) {
                        tally.passed += cell.passed;
                        tally.total += cell.total;
                    }
                }
            }
            all.passed += tally.passed;
            all.total += tally.total;
            let _ = write!(line, " {} |", tally.cell(false));
        }
        let _ = writeln!(line, " {} |", all.cell(true));
        text.push_str(&line);
    };
    for group in [false, true] {
        let members: Vec<&String> = families
            .iter()
            .filter(|(touching, _)| *touching == group)
            .map(|(_, f)| f)
            .collect();
        if members.is_empty() {
            continue;
        }
        for family in &members {
            row(&mut text, family, &|f, _| f == family.as_str());
        }
        let label = if group {
            "**touching parts (issue 9)**"
        } else {
            "**line art (issue 8)**"
        };
        row(&mut text, label, &|_, touching| touching == group);
    }
    row(&mut text, "**all**", &|_, _| true);
    text
}

fn failure_table(outcomes: &[Outcome]) -> String {
    let mut text = String::from("| failure | occurrences | drawings |\n|---|---:|---:|\n");
    for kind in Failure::ALL {
        let occurrences: usize = outcomes
            .iter()
            .map(|o| o.score.problems.iter().filter(|p| p.kind == kind).count())
            .sum();
        let drawings = outcomes
            .iter()
            .filter(|o| o.score.problems.iter().any(|p| p.kind == kind))
            .count();
        let _ = writeln!(text, "| {} | {occurrences} | {drawings} |", kind.name());
    }
    let errors = outcomes.iter().filter(|o| o.error.is_some()).count();
    if errors > 0 {
        let _ = writeln!(text, "| trace error (no output) | {errors} | {errors} |");
    }
    text
}

fn distance_and_time(entries: &[Entry], outcomes: &[Outcome], wall: f64) -> String {
    let worst = entries.iter().zip(outcomes).max_by(|a, b| {
        a.1.score
            .worst_distance
            .total_cmp(&b.1.score.worst_distance)
    });
    let beyond = outcomes
        .iter()
        .filter(|o| o.score.worst_distance > o.score.tolerance)
        .count();
    let mut seconds: Vec<f64> = outcomes.iter().map(|o| o.seconds).collect();
    seconds.sort_by(f64::total_cmp);
    let total: f64 = seconds.iter().sum();
    let median = seconds[seconds.len() / 2];
    let mut text = String::new();
    if let Some((entry, outcome)) = worst {
        let _ = writeln!(
            text,
            "Largest distance of an output path from every true curve and dot: {:.1} px ({}); \
             {beyond} of {} drawings have an output path farther than their tolerance from all \
             of the truth.",
            outcome.score.worst_distance,
            entry.name,
            outcomes.len()
        );
    }
    let _ = writeln!(
        text,
        "Traced and scored {} drawings in {wall:.1} s wall; tracing took {total:.1} s in all, \
         median {:.0} ms a drawing.",
        outcomes.len(),
        median * 1000.0
    );
    text
}

/// One drawing's line of `--json`.
pub fn json_line(method: &str, entry: &Entry, outcome: &Outcome) -> String {
    let score = &outcome.score;
    let extra = score
        .roles
        .iter()
        .filter(|&&r| r == OutputRole::Extra)
        .count();
    serde_json::json!({
        "name": entry.name,
        "family": entry.truth.family,
        "style": entry.truth.style,
        "method": method,
        "exact": score.exact(),
        "curves": score.curves,
        "matched_curves": score.matched_curves,
        "dots": score.dots,
        "matched_dots": score.matched_dots,
        "output_paths": outcome.output.len(),
        "extra_paths": extra,
        "failures": score.problems.iter().map(|p| serde_json::json!({
            "kind": p.kind.name(),
            "detail": p.detail,
        })).collect::<Vec<_>>(),
        "worst_distance": (score.worst_distance * 100.0).round() / 100.0,
        "tolerance": (score.tolerance * 100.0).round() / 100.0,
        "trace_error": outcome.error,
        "seconds": (outcome.seconds * 10000.0).round() / 10000.0,
    })
    .to_string()
}
