//! The robust crawl (`crawltrace::reconstruct_robust`) on the cases of issue 10, each a seeded
//! point set at spacing 1 whose exact edge set and outliers are known (`tests/point_sets/`): stray
//! points, acute sectors, open ends near other curves, thin parts, and curves sampled by local
//! feature size. Every set is turned, scaled by a power of two, shifted and shuffled before it is
//! reconstructed, and every test expects exactly the true edges and outliers.

use crate::point_sets;

use crawltrace::reconstruct_robust as reconstruct;
use point_sets::families::{
    circle_and_arc, circle_with_strays, feature_size_closed, feature_size_open,
    line_with_strays_beyond, parallel_lines, sector_samples, slot, stray_pair_outside_circle,
    stray_row_far_from_circle, two_circles,
};
use point_sets::{Instance, Scene, SplitMix64};

/// Reconstructs the scene `make` builds from `seed`, and returns why it is not exact, if it is
/// not.
fn mismatch(
    label: String,
    seed: u64,
    make: impl FnOnce(&mut SplitMix64) -> Scene,
) -> Option<String> {
    let mut random = SplitMix64::new(seed);
    let scene = make(&mut random);
    let instance = Instance::new("test", format!("{label}, seed {seed}"), scene, &mut random);
    let result = reconstruct(&instance.points).expect("generated points are valid");
    instance.mismatch(&result)
}

/// Runs every case and fails listing all that are not exact.
fn assert_all_exact(cases: impl IntoIterator<Item = Option<String>>) {
    let failures: Vec<String> = cases.into_iter().flatten().collect();
    assert!(failures.is_empty(), "not exact:\n{}", failures.join("\n"));
}

#[test]
fn strays_around_a_circle_are_all_outliers() {
    assert_all_exact([5, 10, 20].into_iter().flat_map(|percent| {
        (0..3).map(move |seed| {
            mismatch(format!("{percent} % strays"), seed, |random| {
                circle_with_strays(random, percent)
            })
        })
    }));
}

#[test]
fn two_strays_closer_than_the_spacing_do_not_take_a_circle() {
    assert_all_exact((0..3).map(|seed| {
        mismatch(
            "two strays 0.6 apart".into(),
            seed,
            stray_pair_outside_circle,
        )
    }));
}

#[test]
fn three_strays_in_a_row_far_from_everything_are_outliers() {
    assert_all_exact((0..3).map(|seed| {
        mismatch(
            "three strays in a row".into(),
            seed,
            stray_row_far_from_circle,
        )
    }));
}

#[test]
fn strays_beyond_the_ends_of_an_open_line_stay_outliers() {
    assert_all_exact(
        (0..3).map(|seed| mismatch("line with strays".into(), seed, line_with_strays_beyond)),
    );
}

#[test]
fn acute_sectors_keep_their_apex() {
    assert_all_exact((15..=90).step_by(5).flat_map(|degrees| {
        [true, false].into_iter().map(move |on_sample| {
            let label = format!("sector {degrees}°, apex on a sample: {on_sample}");
            mismatch(label, 0, |_| sector_samples(degrees as f64, on_sample))
        })
    }));
}

#[test]
fn an_open_arc_near_a_circle_stays_apart_from_it() {
    let gaps = [3.0, 4.0, 6.0, 10.0, 20.0, 40.0];
    assert_all_exact(gaps.into_iter().flat_map(|gap| {
        [1.02, 0.98].into_iter().map(move |density| {
            let label = format!("arc end {gap} from the circle, density {density}");
            mismatch(label, 7, |random| circle_and_arc(random, gap, density))
        })
    }));
}

#[test]
fn parallel_open_lines_stay_apart() {
    assert_all_exact((0..5).map(|seed| mismatch("parallel lines".into(), seed, parallel_lines)));
}

/// Gaps g of the thin-part cases, in spacings, from 0.5 to 1.5 by 0.05.
fn gaps(from: f64, to: f64) -> impl Iterator<Item = f64> {
    (0..=20)
        .map(|k| 0.5 + 0.05 * k as f64)
        .filter(move |&g| g >= from - 1e-9 && g < to - 1e-9)
}

#[test]
fn thin_slots_and_touching_circles_are_exact_down_to_three_quarters_of_the_spacing() {
    assert_all_exact(gaps(0.75, 1.55).flat_map(|gap| {
        (0..2).flat_map(move |seed| {
            [
                mismatch(format!("30 × {gap:.2} slot"), seed, |random| {
                    slot(random, gap)
                }),
                mismatch(format!("two circles {gap:.2} apart"), seed, |random| {
                    two_circles(random, gap)
                }),
            ]
        })
    }));
}

/// Below three quarters of the spacing the issue asks only for a report (docs/point-sets.md):
/// these are the cases that fail today. The test fails when one of them starts to pass too, so
/// that this list and the documentation stay true.
const NARROW_FAILURES: &[&str] = &[];

#[test]
fn thinner_parts_fail_only_where_documented() {
    let mut failing = Vec::new();
    for gap in gaps(0.5, 0.75) {
        for seed in 0..2 {
            let slot_label = format!("30 × {gap:.2} slot, seed {seed}");
            if mismatch(slot_label.clone(), seed, |random| slot(random, gap)).is_some() {
                failing.push(slot_label);
            }
            let circles_label = format!("two circles {gap:.2} apart, seed {seed}");
            if mismatch(circles_label.clone(), seed, |random| {
                two_circles(random, gap)
            })
            .is_some()
            {
                failing.push(circles_label);
            }
        }
    }
    assert_eq!(
        failing, NARROW_FAILURES,
        "update NARROW_FAILURES and the docs"
    );
}

#[test]
fn closed_curves_sampled_by_local_feature_size_are_exact() {
    assert_all_exact([0.2, 0.33, 0.47].into_iter().flat_map(|epsilon| {
        (0..4).map(move |seed| {
            let count = 1 + seed as usize % 3;
            let label = format!("{count} closed curve(s), ε = {epsilon}");
            mismatch(label, seed, |random| {
                feature_size_closed(random, epsilon, count)
            })
        })
    }));
}

#[test]
fn open_curves_sampled_by_local_feature_size_are_exact() {
    assert_all_exact([0.2, 0.33, 0.47].into_iter().flat_map(|epsilon| {
        (0..4).map(move |seed| {
            let label = format!("open curve, ε = {epsilon}");
            mismatch(label, seed, |random| feature_size_open(random, epsilon))
        })
    }));
}
