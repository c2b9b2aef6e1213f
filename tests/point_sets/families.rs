//! The families: each makes one random instance from a generator; spacing 1 unless a family
//! says otherwise. [`FAMILIES`] lists them in the order of the benchmark's table.

use std::f64::consts::{PI, TAU};

use super::geometry::{
    arc, circle, distance, ellipse, local_feature_sizes, parametric, polygon, Path, Xy,
};
use super::{Instance, Scene, SplitMix64};

/// A family: its name in the table, and how to make instance `k` of it.
pub struct Family {
    pub name: &'static str,
    pub what: &'static str,
    pub make: fn(&mut SplitMix64, usize) -> Instance,
}

/// Every family, in table order.
pub const FAMILIES: &[Family] = &[
    Family {
        name: "outliers",
        what: "a circle of 95 samples with 5, 10 or 20 % uniform strays at least 4 spacings off it",
        make: outliers,
    },
    Family {
        name: "stray-cases",
        what: "two strays 0.6 apart 5 outside a circle; three strays in a row 3 apart far from it; an open line with strays 6-7 beyond its ends",
        make: stray_cases,
    },
    Family {
        name: "sectors",
        what: "circular sector of radius 25, apex 15°-90° in 5° steps, apex on a sample or between two",
        make: sectors,
    },
    Family {
        name: "polygons",
        what: "random polygons, corners of 25°-330°, sides of 5-30 spacings",
        make: polygons,
    },
    Family {
        name: "open-ends",
        what: "a circle (r 12) and a 120° arc (r 20, ±2 % spacing) whose end is 3-40 from it; two parallel lines 5 apart, one 3 % denser",
        make: open_ends,
    },
    Family {
        name: "thin",
        what: "a closed 30 × g slot, or two circles (r 10) g apart, g in [0.75, 1.5] spacings",
        make: thin,
    },
    Family {
        name: "thin-narrow",
        what: "the same with g in [0.5, 0.75)",
        make: thin_narrow,
    },
    Family {
        name: "lfs-closed",
        what: "1-3 smooth closed curves sampled at ε × local feature size, ε = 0.2, 0.33, 0.47",
        make: lfs_closed,
    },
    Family {
        name: "lfs-open",
        what: "a smooth open curve sampled at ε × local feature size, ε = 0.2, 0.33, 0.47",
        make: lfs_open,
    },
    Family {
        name: "non-uniform",
        what: "a smooth closed curve whose spacing varies 5-10× along it (at most 0.33 × lfs)",
        make: non_uniform,
    },
    Family {
        name: "noise",
        what: "a smooth closed curve, spacing 1, Gaussian noise of 0.05, 0.1 or 0.15 spacings",
        make: noise,
    },
    Family {
        name: "holes",
        what: "1-3 objects with 0-2 holes each, spacing 1",
        make: holes,
    },
    Family {
        name: "silhouettes",
        what: "animal-like outlines: body, legs, head, pointed ears, tail; spacing 1",
        make: silhouettes,
    },
    Family {
        name: "letters",
        what: "words of 3-5 block letters (outlines, with holes), stroke 2.5-4 spacings",
        make: letters,
    },
];

/// Jitter along the curve, in spacings, for the families sampled at spacing 1.
const JITTER: f64 = 0.15;

/// The radius of a circle of 95 samples at spacing 1.
const STRAY_CIRCLE_RADIUS: f64 = 95.0 / TAU;

/// A circle of 95 samples with `percent` % as many uniform strays, at least 4 spacings off it,
/// in its bounding box grown by 10.
pub fn circle_with_strays(random: &mut SplitMix64, percent: usize) -> Scene {
    let radius = STRAY_CIRCLE_RADIUS;
    let samples = circle((0.0, 0.0), radius).jittered_samples(random, 1.0, JITTER);
    let count = (95.0 * percent as f64 / 100.0).round() as usize;
    let reach = radius + 10.0;
    let mut strays = Vec::new();
    while strays.len() < count {
        let p = (random.range(-reach, reach), random.range(-reach, reach));
        if (p.0.hypot(p.1) - radius).abs() >= 4.0 {
            strays.push(p);
        }
    }
    Scene::default().curve(samples, true).strays(strays)
}

/// A point at `distance` from the centre of the strays' circle, in a random direction.
fn around_circle(random: &mut SplitMix64, distance: f64) -> Xy {
    let direction = random.range(0.0, TAU);
    (distance * direction.cos(), distance * direction.sin())
}

/// The circle of [`circle_with_strays`] and two strays 0.6 apart, 5 spacings outside it.
pub fn stray_pair_outside_circle(random: &mut SplitMix64) -> Scene {
    let samples = circle((0.0, 0.0), STRAY_CIRCLE_RADIUS).jittered_samples(random, 1.0, JITTER);
    let middle = around_circle(random, STRAY_CIRCLE_RADIUS + 5.0);
    let turn = random.range(0.0, TAU);
    let half = (0.3 * turn.cos(), 0.3 * turn.sin());
    let strays = vec![
        (middle.0 + half.0, middle.1 + half.1),
        (middle.0 - half.0, middle.1 - half.1),
    ];
    Scene::default().curve(samples, true).strays(strays)
}

/// The circle and three strays in a row, 3 apart, 20 spacings outside it.
pub fn stray_row_far_from_circle(random: &mut SplitMix64) -> Scene {
    let samples = circle((0.0, 0.0), STRAY_CIRCLE_RADIUS).jittered_samples(random, 1.0, JITTER);
    let middle = around_circle(random, STRAY_CIRCLE_RADIUS + 20.0);
    let turn = random.range(0.0, TAU);
    let strays = (-1..=1)
        .map(|i| {
            let along = 3.0 * i as f64;
            (middle.0 + along * turn.cos(), middle.1 + along * turn.sin())
        })
        .collect();
    Scene::default().curve(samples, true).strays(strays)
}

/// An open line of 30 spacings with a stray 6 to 7 spacings beyond each end (within 45° of the
/// line's direction).
pub fn line_with_strays_beyond(random: &mut SplitMix64) -> Scene {
    let line = polygon(&[(0.0, 0.0), (30.0, 0.0)], false);
    let samples = line.jittered_samples(random, 1.0, JITTER);
    let mut strays = Vec::new();
    for (end, outward) in [((0.0, 0.0), PI), ((30.0, 0.0), 0.0)] {
        let reach = random.range(6.0, 7.0);
        let angle = outward + random.range(-PI / 4.0, PI / 4.0);
        strays.push((end.0 + reach * angle.cos(), end.1 + reach * angle.sin()));
    }
    Scene::default().curve(samples, false).strays(strays)
}

fn outliers(random: &mut SplitMix64, k: usize) -> Instance {
    let percent = [5, 10, 20][k % 3];
    let scene = circle_with_strays(random, percent);
    Instance::new("outliers", format!("{percent}% strays"), scene, random)
}

fn stray_cases(random: &mut SplitMix64, k: usize) -> Instance {
    let (label, scene) = match k % 3 {
        0 => (
            "two strays 0.6 apart, 5 outside a circle",
            stray_pair_outside_circle(random),
        ),
        1 => (
            "three strays in a row 3 apart, 20 outside a circle",
            stray_row_far_from_circle(random),
        ),
        _ => (
            "an open line with strays 6-7 beyond its ends",
            line_with_strays_beyond(random),
        ),
    };
    Instance::new("stray-cases", label.to_string(), scene, random)
}

/// A circular sector with its apex at the origin: apex → side → arc → side.
fn sector(radius: f64, apex: f64) -> Path {
    let half = apex / 2.0;
    let mut points = Vec::new();
    let side = polygon(
        &[(0.0, 0.0), (radius * half.cos(), -radius * half.sin())],
        false,
    );
    points.extend_from_slice(&side.fine_points()[..side.fine_points().len() - 1]);
    let rim = arc((0.0, 0.0), radius, -half, half);
    points.extend_from_slice(&rim.fine_points()[..rim.fine_points().len() - 1]);
    let back = polygon(
        &[(radius * half.cos(), radius * half.sin()), (0.0, 0.0)],
        false,
    );
    points.extend_from_slice(&back.fine_points()[..back.fine_points().len() - 1]);
    Path::new(points, true)
}

/// A circular sector of radius 25 with an apex of `degrees`, sampled at spacing about 1 along
/// its outline, the apex on a sample or halfway between two.
pub fn sector_samples(degrees: f64, apex_on_sample: bool) -> Scene {
    let path = sector(25.0, degrees.to_radians());
    let count = path.length().round() as usize;
    let samples = path.even_samples(count, if apex_on_sample { 0.0 } else { 0.5 });
    Scene::default().curve(samples, true)
}

fn sectors(random: &mut SplitMix64, k: usize) -> Instance {
    let degrees = 15 + 5 * ((k / 2) % 14);
    let on_sample = k % 2 == 0;
    let label = format!(
        "apex {degrees}°, {}",
        if on_sample {
            "on a sample"
        } else {
            "between samples"
        }
    );
    let scene = sector_samples(degrees as f64, on_sample);
    Instance::new("sectors", label, scene, random)
}

/// The interior angle at each corner of a closed polygon, in degrees (counter-clockwise order).
fn interior_angles(corners: &[Xy]) -> Vec<f64> {
    let n = corners.len();
    (0..n)
        .map(|i| {
            let (a, b, c) = (corners[(i + n - 1) % n], corners[i], corners[(i + 1) % n]);
            let incoming = (b.1 - a.1).atan2(b.0 - a.0);
            let outgoing = (c.1 - b.1).atan2(c.0 - b.0);
            let turn = (outgoing - incoming + PI).rem_euclid(TAU) - PI;
            180.0 - turn.to_degrees()
        })
        .collect()
}

fn polygons(random: &mut SplitMix64, _k: usize) -> Instance {
    loop {
        let n = 3 + random.below(6);
        let mut angles: Vec<f64> = (0..n).map(|_| random.range(0.0, TAU)).collect();
        angles.sort_by(f64::total_cmp);
        let corners: Vec<Xy> = angles
            .iter()
            .map(|&a| {
                let r = random.range(6.0, 16.0);
                (r * a.cos(), r * a.sin())
            })
            .collect();
        let sides_ok = (0..n).all(|i| {
            let side = distance(corners[i], corners[(i + 1) % n]);
            (5.0..=30.0).contains(&side)
        });
        let interior = interior_angles(&corners);
        let angles_ok = interior.iter().all(|&a| (25.0..=330.0).contains(&a));
        // Corners must stay well apart from the sides they are not on.
        let clear = (0..n).all(|i| {
            (0..n).all(|j| {
                if j == i || (j + 1) % n == i {
                    return true;
                }
                segment_distance(corners[i], corners[j], corners[(j + 1) % n]) >= 3.0
            })
        });
        if !(sides_ok && angles_ok && clear) {
            continue;
        }
        let path = polygon(&corners, true);
        let samples = path.jittered_samples(random, 1.0, JITTER);
        let sharpest = interior.iter().copied().fold(f64::INFINITY, f64::min);
        let label = format!("{n} corners, sharpest {sharpest:.0}°");
        return Instance::new(
            "polygons",
            label,
            Scene::default().curve(samples, true),
            random,
        );
    }
}

fn segment_distance(p: Xy, a: Xy, b: Xy) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let t = (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    distance(p, (a.0 + t * dx, a.1 + t * dy))
}

/// Two parallel open lines of 30 spacings, 5 apart, the second 3 % denser and shifted along
/// by up to 10.
pub fn parallel_lines(random: &mut SplitMix64) -> Scene {
    let first = polygon(&[(0.0, 0.0), (30.0, 0.0)], false);
    let shift = random.range(-10.0, 10.0);
    let second = polygon(&[(shift, 5.0), (shift + 30.0, 5.0)], false);
    Scene::default()
        .curve(first.jittered_samples(random, 1.0, JITTER), false)
        .curve(second.jittered_samples(random, 0.97, JITTER), false)
}

/// A circle of radius 12 and an open 120° arc of radius 20 sampled `density` times as densely,
/// whose nearest end is `gap` from the circle, heading off at a random angle.
pub fn circle_and_arc(random: &mut SplitMix64, gap: f64, density: f64) -> Scene {
    let circle_samples = circle((0.0, 0.0), 12.0).jittered_samples(random, 1.0, JITTER);
    loop {
        // Kept only when the first end is the arc's nearest point to the circle.
        let out = random.range(0.0, TAU);
        let end = ((12.0 + gap) * out.cos(), (12.0 + gap) * out.sin());
        let start = random.range(0.0, TAU);
        let centre = (end.0 - 20.0 * start.cos(), end.1 - 20.0 * start.sin());
        let path = if random.below(2) == 0 {
            arc(centre, 20.0, start, start + TAU / 3.0)
        } else {
            arc(centre, 20.0, start - TAU / 3.0, start)
        };
        let clear = path
            .fine_points()
            .iter()
            .all(|p| p.0.hypot(p.1) - 12.0 >= gap - 1e-6);
        if clear {
            let arc_samples = path.jittered_samples(random, 1.0 / density, JITTER);
            return Scene::default()
                .curve(circle_samples, true)
                .curve(arc_samples, false);
        }
    }
}

fn open_ends(random: &mut SplitMix64, k: usize) -> Instance {
    if k % 3 == 2 {
        let label = "two parallel lines 5 apart, one 3 % denser".to_string();
        let scene = parallel_lines(random);
        return Instance::new("open-ends", label, scene, random);
    }
    let density = if k % 3 == 0 { 1.02 } else { 0.98 };
    let gap = random.range(3.0, 40.0);
    let label = format!(
        "arc end {gap:.1} from the circle, arc {}",
        if density > 1.0 {
            "2 % denser"
        } else {
            "2 % sparser"
        }
    );
    let scene = circle_and_arc(random, gap, density);
    Instance::new("open-ends", label, scene, random)
}

/// A closed 30 × `gap` slot (a thin rectangle), spacing 1.
pub fn slot(random: &mut SplitMix64, gap: f64) -> Scene {
    let slot = polygon(&[(0.0, 0.0), (30.0, 0.0), (30.0, gap), (0.0, gap)], true);
    Scene::default().curve(slot.jittered_samples(random, 1.0, 0.1), true)
}

/// Two circles of radius 10, `gap` apart, spacing 1.
pub fn two_circles(random: &mut SplitMix64, gap: f64) -> Scene {
    let a = circle((0.0, 0.0), 10.0).jittered_samples(random, 1.0, 0.1);
    let b = circle((20.0 + gap, 0.0), 10.0).jittered_samples(random, 1.0, 0.1);
    Scene::default().curve(a, true).curve(b, true)
}

fn thin_scene(random: &mut SplitMix64, k: usize, gap: f64) -> (String, Scene) {
    if k % 2 == 0 {
        (format!("30 × {gap:.2} slot"), slot(random, gap))
    } else {
        (
            format!("two circles {gap:.2} apart"),
            two_circles(random, gap),
        )
    }
}

fn thin(random: &mut SplitMix64, k: usize) -> Instance {
    let gap = random.range(0.75, 1.5);
    let (label, scene) = thin_scene(random, k, gap);
    Instance::new("thin", label, scene, random)
}

fn thin_narrow(random: &mut SplitMix64, k: usize) -> Instance {
    let gap = random.range(0.5, 0.75);
    let (label, scene) = thin_scene(random, k, gap);
    Instance::new("thin-narrow", label, scene, random)
}

/// A random smooth closed shape of size about 1 around the origin: an ellipse (aspect 1.5-8),
/// a blob with a few harmonics, or a peanut with a narrow waist; as a polar or parametric
/// function of t ∈ [0, 2π).
fn smooth_shape(random: &mut SplitMix64) -> Box<dyn Fn(f64) -> Xy> {
    let turn = random.range(0.0, TAU);
    let (c, s) = (turn.cos(), turn.sin());
    let rotate = move |(x, y): Xy| (c * x - s * y, s * x + c * y);
    match random.below(3) {
        0 => {
            let aspect = random.range(1.5, 8.0);
            Box::new(move |t: f64| rotate((t.cos(), t.sin() / aspect)))
        }
        1 => {
            let harmonics: Vec<(f64, f64, f64)> = (0..2 + random.below(3))
                .map(|_| {
                    let order = (2 + random.below(4)) as f64;
                    (
                        order,
                        random.range(0.05, 0.35) / order,
                        random.range(0.0, TAU),
                    )
                })
                .collect();
            Box::new(move |t: f64| {
                let r = 1.0
                    + harmonics
                        .iter()
                        .map(|&(order, amplitude, phase)| amplitude * (order * t + phase).cos())
                        .sum::<f64>();
                rotate((r * t.cos(), r * t.sin()))
            })
        }
        _ => {
            let waist = random.range(0.3, 0.6);
            Box::new(move |t: f64| {
                let r = 1.0 + waist * (2.0 * t).cos();
                rotate((r * t.cos(), r * t.sin()))
            })
        }
    }
}

fn placed(shape: Box<dyn Fn(f64) -> Xy>, centre: Xy, scale: f64) -> impl Fn(f64) -> Xy {
    move |t| {
        let (x, y) = shape(t);
        (centre.0 + scale * x, centre.1 + scale * y)
    }
}

/// A random smooth closed curve around the origin, of a size drawn from `sizes` (smallest,
/// largest), with its smallest local feature size.
fn smooth_loop(random: &mut SplitMix64, sizes: (f64, f64)) -> (Path, f64) {
    let scale = random.range(sizes.0, sizes.1);
    let path = parametric(
        placed(smooth_shape(random), (0.0, 0.0), scale),
        0.0,
        TAU,
        true,
    );
    let feature_sizes = local_feature_sizes(&[&path]).remove(0);
    let smallest = feature_sizes.iter().copied().fold(f64::INFINITY, f64::min);
    (path, smallest)
}

const EPSILONS: [f64; 3] = [0.2, 0.33, 0.47];

/// Samples each path at `epsilon` × its local feature size (measured on all paths together).
fn feature_size_samples(paths: &[Path], epsilon: f64, random: &mut SplitMix64) -> Vec<Vec<Xy>> {
    let references: Vec<&Path> = paths.iter().collect();
    let sizes = local_feature_sizes(&references);
    paths
        .iter()
        .zip(&sizes)
        .map(|(path, size)| {
            let spacing = |i: usize| epsilon * size[i];
            path.samples_with_spacing(&spacing, random.unit())
        })
        .collect()
}

/// `count` random smooth closed curves in a row, each 10-30 across, 1-15 apart (so that they
/// shape each other's local feature size), sampled at `epsilon` × local feature size.
pub fn feature_size_closed(random: &mut SplitMix64, epsilon: f64, count: usize) -> Scene {
    let mut paths = Vec::new();
    let mut cursor = 0.0;
    for _ in 0..count {
        let scale = random.range(10.0, 30.0);
        let shape = smooth_shape(random);
        let xs: Vec<f64> = (0..512)
            .map(|i| scale * shape(TAU * i as f64 / 512.0).0)
            .collect();
        let (left, right) = (
            xs.iter().copied().fold(f64::INFINITY, f64::min),
            xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        let centre = (cursor - left, random.range(-5.0, 5.0));
        cursor = centre.0 + right + random.range(1.0, 15.0);
        paths.push(parametric(placed(shape, centre, scale), 0.0, TAU, true));
    }
    let mut scene = Scene::default();
    for samples in feature_size_samples(&paths, epsilon, random) {
        scene = scene.curve(samples, true);
    }
    scene
}

/// A random part (20-75 %) of a random smooth closed curve, sampled at `epsilon` × its local
/// feature size (as an open curve: the missing part does not count).
pub fn feature_size_open(random: &mut SplitMix64, epsilon: f64) -> Scene {
    let scale = random.range(10.0, 30.0);
    let shape = placed(smooth_shape(random), (0.0, 0.0), scale);
    let start = random.range(0.0, TAU);
    let fraction = random.range(0.2, 0.75);
    let path = parametric(shape, start, start + fraction * TAU, false);
    let samples = feature_size_samples(&[path], epsilon, random).remove(0);
    Scene::default().curve(samples, false)
}

fn lfs_closed(random: &mut SplitMix64, k: usize) -> Instance {
    let epsilon = EPSILONS[k % 3];
    let count = 1 + random.below(3);
    let scene = feature_size_closed(random, epsilon, count);
    let label = format!("{count} curve(s), ε = {epsilon}");
    Instance::new("lfs-closed", label, scene, random)
}

fn lfs_open(random: &mut SplitMix64, k: usize) -> Instance {
    let epsilon = EPSILONS[k % 3];
    let scene = feature_size_open(random, epsilon);
    Instance::new("lfs-open", format!("ε = {epsilon}"), scene, random)
}

fn non_uniform(random: &mut SplitMix64, _k: usize) -> Instance {
    let (path, smallest) = smooth_loop(random, (15.0, 40.0));
    let widest = 0.33 * smallest;
    let ratio = random.range(5.0, 10.0);
    let waves = (1 + random.below(3)) as f64;
    let phase = random.range(0.0, TAU);
    let fine = path.fine_points().len() as f64;
    let spacing = |i: usize| {
        let wave = 0.5 + 0.5 * (TAU * waves * i as f64 / fine + phase).sin();
        widest * (1.0 / ratio + (1.0 - 1.0 / ratio) * wave)
    };
    let samples = path.samples_with_spacing(&spacing, random.unit());
    Instance::new(
        "non-uniform",
        format!("spacing varies {ratio:.1}×, {waves} wave(s)"),
        Scene::default().curve(samples, true),
        random,
    )
}

fn noise(random: &mut SplitMix64, k: usize) -> Instance {
    let sigma = [0.05, 0.1, 0.15][k % 3];
    loop {
        let (path, smallest) = smooth_loop(random, (12.0, 30.0));
        // Noise must stay small against the curve's feature size, or the true order is moot.
        if smallest < 3.0 {
            continue;
        }
        let samples: Vec<Xy> = path
            .jittered_samples(random, 1.0, 0.1)
            .into_iter()
            .map(|(x, y)| (x + sigma * random.gaussian(), y + sigma * random.gaussian()))
            .collect();
        return Instance::new(
            "noise",
            format!("noise σ = {sigma}"),
            Scene::default().curve(samples, true),
            random,
        );
    }
}

/// Whether every sample of `paths` is at least `clearance` from every other path.
fn apart(paths: &[Path], clearance: f64) -> bool {
    for (i, a) in paths.iter().enumerate() {
        for b in &paths[i + 1..] {
            let coarse_b: Vec<Xy> = b.fine_points().iter().step_by(4).copied().collect();
            for p in a.fine_points().iter().step_by(4) {
                if coarse_b.iter().any(|&q| distance(*p, q) < clearance) {
                    return false;
                }
            }
        }
    }
    true
}

fn holes(random: &mut SplitMix64, _k: usize) -> Instance {
    loop {
        let hosts = 1 + random.below(3);
        let mut paths = Vec::new();
        for h in 0..hosts {
            let scale = random.range(10.0, 22.0);
            let centre = (h as f64 * 60.0, random.range(-5.0, 5.0));
            paths.push(parametric(
                placed(smooth_shape(random), centre, scale),
                0.0,
                TAU,
                true,
            ));
            for _ in 0..random.below(3) {
                let inner = random.range(0.2, 0.45) * scale;
                let offset = (
                    random.range(-0.3, 0.3) * scale,
                    random.range(-0.3, 0.3) * scale,
                );
                paths.push(parametric(
                    placed(
                        smooth_shape(random),
                        (centre.0 + offset.0, centre.1 + offset.1),
                        inner,
                    ),
                    0.0,
                    TAU,
                    true,
                ));
            }
        }
        if !apart(&paths, 3.0) {
            continue;
        }
        let references: Vec<&Path> = paths.iter().collect();
        let smallest = local_feature_sizes(&references)
            .iter()
            .flatten()
            .copied()
            .fold(f64::INFINITY, f64::min);
        if smallest < 2.0 {
            continue;
        }
        let mut scene = Scene::default();
        for path in &paths {
            scene = scene.curve(path.jittered_samples(random, 1.0, JITTER), true);
        }
        return Instance::new("holes", format!("{} curves", paths.len()), scene, random);
    }
}

/// How far a plateau part at `centre` (angular half-width `half`, sides `ramp` radians steep)
/// reaches out at angle `t`, from 0 to 1.
fn plateau(t: f64, centre: f64, half: f64, ramp: f64) -> f64 {
    let off = (t - centre + PI).rem_euclid(TAU) - PI;
    ((half - off.abs()) / ramp).clamp(0.0, 1.0)
}

/// How far a spike at `centre` (angular half-width `half`) reaches out at angle `t`, 0 to 1.
fn spike(t: f64, centre: f64, half: f64) -> f64 {
    let off = (t - centre + PI).rem_euclid(TAU) - PI;
    (1.0 - off.abs() / half).max(0.0)
}

/// Whether `path` folds back on itself anywhere: two of its points closer than 1.5 (spacings) and
/// closer than a sixth of their distance along it (a sliver, or a tip sharper than about 20°).
fn folds(path: &Path) -> bool {
    let step = 0.25;
    let count = (path.length() / step) as usize;
    let points: Vec<Xy> = (0..count).map(|i| path.at(i as f64 * step)).collect();
    for i in 0..count {
        for j in i + 1..count {
            let along = ((j - i).min(count - (j - i))) as f64 * step;
            let apart = distance(points[i], points[j]);
            if apart < 1.5 && apart < along / 6.0 {
                return true;
            }
        }
    }
    false
}

fn silhouettes(random: &mut SplitMix64, k: usize) -> Instance {
    loop {
        let instance = silhouette(random, k);
        if let Some(instance) = instance {
            return instance;
        }
    }
}

fn silhouette(random: &mut SplitMix64, _k: usize) -> Option<Instance> {
    // An outline r(θ) around the body's centre: an oval body; legs and a tail as plateaus with
    // steep (radial) sides; a round head with two pointed ears as spikes. Parts never fold over,
    // and the gaps between legs stay at least 2.5 spacings wide.
    let body = (random.range(12.0, 20.0), random.range(8.0, 12.0));
    let rim = move |t: f64| 1.0 / ((t.cos() / body.0).powi(2) + (t.sin() / body.1).powi(2)).sqrt();
    let ramp = 0.01;
    let mut legs = Vec::new();
    let count = 2 + random.below(3);
    let widest = 5.0;
    let spread = (widest + random.range(2.5, 5.0)) / body.1;
    for i in 0..count {
        let angle = -PI / 2.0 + (i as f64 - (count - 1) as f64 / 2.0) * spread;
        let half = random.range(3.0, widest) / 2.0 / rim(angle);
        legs.push((angle, half, random.range(6.0, 12.0)));
    }
    let head_angle = if random.below(2) == 0 { 0.0 } else { PI } + random.range(0.3, 0.6);
    let head = (head_angle, random.range(0.3, 0.45), random.range(4.0, 7.0));
    let ears: Vec<(f64, f64, f64)> = [-1.0, 1.0]
        .iter()
        .map(|side| {
            let angle = head.0 + side * random.range(0.1, 0.18);
            let height = random.range(4.0, 7.0);
            let tip = random.range(25.0f64, 60.0).to_radians();
            let radius = rim(angle) + head.2;
            (angle, height * (tip / 2.0).tan() / radius, height)
        })
        .collect();
    let tail_angle = PI - head.0 + random.range(-0.2, 0.2);
    let tail = (
        tail_angle,
        random.range(2.5, 3.5) / 2.0 / rim(tail_angle),
        random.range(5.0, 10.0),
    );
    let outline = parametric(
        move |t| {
            let mut r = rim(t);
            for &(angle, half, length) in legs.iter().chain([&tail]) {
                r += length * plateau(t, angle, half, ramp);
            }
            let off = (t - head.0 + PI).rem_euclid(TAU) - PI;
            r += head.2 * (1.0 - (off / head.1).powi(2)).max(0.0).sqrt();
            for &(angle, half, height) in &ears {
                r += height * spike(t, angle, half);
            }
            (r * t.cos(), r * t.sin())
        },
        0.0,
        TAU,
        true,
    );
    if folds(&outline) {
        return None;
    }
    let samples = outline.jittered_samples(random, 1.0, JITTER);
    Some(Instance::new(
        "silhouettes",
        format!("{count} legs"),
        Scene::default().curve(samples, true),
        random,
    ))
}

/// Block letters as closed outlines (outer boundaries and holes) on a grid of stroke widths:
/// 3 wide, 5 high.
fn glyph(letter: char, stroke: f64, origin: Xy) -> Vec<Path> {
    let at = |x: f64, y: f64| (origin.0 + x * stroke, origin.1 + y * stroke);
    let poly = |corners: &[(f64, f64)]| {
        let points: Vec<Xy> = corners.iter().map(|&(x, y)| at(x, y)).collect();
        polygon(&points, true)
    };
    match letter {
        'L' => vec![poly(&[
            (0.0, 0.0),
            (3.0, 0.0),
            (3.0, 1.0),
            (1.0, 1.0),
            (1.0, 5.0),
            (0.0, 5.0),
        ])],
        'T' => vec![poly(&[
            (1.0, 0.0),
            (2.0, 0.0),
            (2.0, 4.0),
            (3.0, 4.0),
            (3.0, 5.0),
            (0.0, 5.0),
            (0.0, 4.0),
            (1.0, 4.0),
        ])],
        'E' => vec![poly(&[
            (0.0, 0.0),
            (3.0, 0.0),
            (3.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (2.5, 2.0),
            (2.5, 3.0),
            (1.0, 3.0),
            (1.0, 4.0),
            (3.0, 4.0),
            (3.0, 5.0),
            (0.0, 5.0),
        ])],
        'H' => vec![poly(&[
            (0.0, 0.0),
            (1.0, 0.0),
            (1.0, 2.0),
            (2.0, 2.0),
            (2.0, 0.0),
            (3.0, 0.0),
            (3.0, 5.0),
            (2.0, 5.0),
            (2.0, 3.0),
            (1.0, 3.0),
            (1.0, 5.0),
            (0.0, 5.0),
        ])],
        'O' => {
            let centre = at(1.5, 2.5);
            vec![
                ellipse(centre, (1.5 * stroke, 2.5 * stroke), 0.0),
                ellipse(centre, (0.5 * stroke, 1.5 * stroke), 0.0),
            ]
        }
        'P' => vec![
            poly(&[
                (0.0, 0.0),
                (1.0, 0.0),
                (1.0, 2.0),
                (3.0, 2.0),
                (3.0, 5.0),
                (0.0, 5.0),
            ]),
            poly(&[(1.0, 3.0), (2.0, 3.0), (2.0, 4.0), (1.0, 4.0)]),
        ],
        'D' => {
            let mut outer = vec![at(0.0, 0.0), at(1.5, 0.0)];
            outer.extend((1..24).map(|i| {
                let t = -PI / 2.0 + PI * i as f64 / 24.0;
                at(1.5 + 1.5 * t.cos(), 2.5 + 2.5 * t.sin())
            }));
            outer.extend([at(1.5, 5.0), at(0.0, 5.0)]);
            let mut inner = vec![at(1.0, 1.0), at(1.5, 1.0)];
            inner.extend((1..24).map(|i| {
                let t = -PI / 2.0 + PI * i as f64 / 24.0;
                at(1.5 + 0.5 * t.cos(), 2.5 + 1.5 * t.sin())
            }));
            inner.extend([at(1.5, 4.0), at(1.0, 4.0)]);
            vec![polygon(&outer, true), polygon(&inner, true)]
        }
        _ => vec![poly(&[(1.0, 0.0), (2.0, 0.0), (2.0, 5.0), (1.0, 5.0)])], // 'I'
    }
}

fn letters(random: &mut SplitMix64, _k: usize) -> Instance {
    const ALPHABET: [char; 8] = ['L', 'T', 'E', 'H', 'O', 'P', 'D', 'I'];
    let stroke = random.range(2.5, 4.0);
    let count = 3 + random.below(3);
    let mut x = 0.0;
    let mut word = String::new();
    let mut scene = Scene::default();
    for _ in 0..count {
        let letter = ALPHABET[random.below(ALPHABET.len())];
        word.push(letter);
        for path in glyph(letter, stroke, (x, 0.0)) {
            scene = scene.curve(path.jittered_samples(random, 1.0, JITTER), true);
        }
        x += stroke * random.range(4.0, 5.0);
    }
    Instance::new(
        "letters",
        format!("\"{word}\", stroke {stroke:.1}"),
        scene,
        random,
    )
}
