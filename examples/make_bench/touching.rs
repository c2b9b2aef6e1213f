//! Issue 9's families: outlines whose parts touch or run within a pen width or two of each
//! other — silhouettes with spikes, fingers and tails; arches and lobes that kiss; meanders and
//! spirals that run parallel then part; animal-like outlines with legs, tail and ears. Pens of
//! 2–5 px, gaps of 5–12 px and strokes of 30–100 px, gaps anywhere (on a spike, at its base, at
//! a contact).

use std::f64::consts::{PI, TAU};

use kurbo::{Affine, Point, Vec2};

use super::families::{any_angle, few, several};
use super::figure::Figure;
use super::pen::{Corners, Hand};
use super::random::SplitMix64;
use super::shapes::{
    arc_length_where, blob, ellipse, insert_chains, insert_protrusions, polygon, polyline,
    rounded_strip, spike, Builder, Chain, Protrusion, Shape,
};

/// Visible gaps, px (issue 9).
const GAPS: (f64, f64) = (5.0, 12.0);
/// Stroke lengths, px (issue 9).
const STROKES: (f64, f64) = (30.0, 100.0);
/// How close the parts come, centre line to centre line, in pen widths (issue 9).
const CONTACTS: [f64; 4] = [0.0, 0.5, 1.0, 1.5];

/// The hand of issue 9: gaps 5–12 px, strokes 30–100 px, gaps anywhere.
pub fn hand(pen: f64, jitter: f64, random: &mut SplitMix64) -> Hand {
    let gap_low = random.range(GAPS.0, 8.0);
    let gap_high = random.range(gap_low + 1.0, GAPS.1);
    let stroke_low = random.range(STROKES.0, 50.0);
    let stroke_high = random.range(stroke_low + 20.0, STROKES.1);
    Hand {
        pen,
        jitter,
        stroke: (stroke_low, stroke_high),
        gap: (gap_low, gap_high),
        corners: Corners::Anywhere,
    }
}

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

/// A body (rectangle or blob, 150–300 px) carrying 2–6 protrusions: triangular spikes 30–60 px
/// long on bases of 3–16 px (apex 3°–20°), rectangular fingers 30–60 px long whose sides are
/// 0.5, 1 or 1.5 pen widths apart, and tails 0.75 pen widths wide with a round end.
pub fn spikes(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    let (body, corners) = if random.chance(0.5) {
        let (w, h) = (random.range(150.0, 300.0), random.range(100.0, 250.0));
        let corners = vec![0.0, w, w + h, 2.0 * w + h];
        (
            polygon(vec![p(0.0, 0.0), p(w, 0.0), p(w, h), p(0.0, h)]),
            corners,
        )
    } else {
        let radius = random.range(75.0, 150.0);
        (blob(Point::ORIGIN, radius, 0.3, random), Vec::new())
    };
    let inside = centroid(&body);
    let count = 2 + random.index(5);
    let protrusions: Vec<Protrusion> = (0..count)
        .map(|_| match random.index(3) {
            0 => {
                let length = random.range(30.0, 60.0);
                let apex = random.range(3.0, 20.0).to_radians();
                let base = (2.0 * length * (apex / 2.0).tan()).clamp(3.0, 16.0);
                spike(0.0, base, length)
            }
            1 => {
                let width = pen * [0.5, 1.0, 1.5][random.index(3)];
                super::shapes::finger(0.0, width, random.range(30.0, 60.0))
            }
            _ => rounded_strip(
                0.0,
                0.75 * pen,
                random.range(30.0, 70.0),
                random.range(-0.8, 0.8),
            ),
        })
        .collect();
    let placed = place_along(&body, &corners, protrusions, random);
    Figure::of(vec![insert_protrusions(&body, inside, &placed)]).rotated(any_angle(random))
}

fn centroid(shape: &Shape) -> Point {
    let sum = shape
        .points
        .iter()
        .fold(Vec2::ZERO, |sum, p| sum + p.to_vec2());
    (sum / shape.points.len() as f64).to_point()
}

/// Puts the protrusions at random places along the outline, at least 20 px apart and clear of
/// the outline's corners; drops those that find no room.
fn place_along(
    outline: &Shape,
    corners: &[f64],
    protrusions: Vec<Protrusion>,
    random: &mut SplitMix64,
) -> Vec<Protrusion> {
    const APART: f64 = 20.0;
    let length = outline.length();
    let mut placed: Vec<Protrusion> = Vec::new();
    for mut protrusion in protrusions {
        let half = protrusion.base / 2.0;
        for _ in 0..100 {
            let at = random.range(half + APART, length - half - APART);
            let clear_of_corners = corners.iter().all(|&c| (c - at).abs() > half + APART);
            let clear_of_others = placed
                .iter()
                .all(|other| (other.at - at).abs() > half + other.base / 2.0 + APART);
            if clear_of_corners && clear_of_others {
                protrusion.at = at;
                placed.push(protrusion);
                break;
            }
        }
    }
    placed
}

/// Arches and lobes whose inner sides come within 0, 0.5, 1 or 1.5 pen widths of each other at
/// one point (radius of curvature about 20 px there).
pub fn arches(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    several(few(random).min(2), hand, random, |random| {
        let contact = pen * CONTACTS[random.index(CONTACTS.len())];
        let shape = if random.chance(0.5) {
            lobes(contact, random)
        } else {
            arch(pen, contact, 0.0, random)
        };
        Figure::of(vec![shape]).rotated(any_angle(random))
    })
}

/// Two round lobes side by side on a base, `contact` apart where they come closest.
fn lobes(contact: f64, random: &mut SplitMix64) -> Shape {
    let r1 = random.range(15.0, 35.0);
    let r2 = r1 * random.range(0.8, 1.25);
    let c1 = p(-r1 - contact / 2.0, 0.0);
    let c2 = p(r2 + contact / 2.0, 0.0);
    let base_top = random.range(0.3, 0.8) * r1.min(r2);
    let base_bottom = base_top + random.range(20.0, 60.0);
    let left = c1.x - r1 - random.range(10.0, 40.0);
    let right = c2.x + r2 + random.range(10.0, 40.0);
    let (s1, s2) = (
        (r1 * r1 - base_top * base_top).sqrt(),
        (r2 * r2 - base_top * base_top).sqrt(),
    );
    let mut builder = Builder::start(p(left, base_top));
    for (centre, radius, half) in [(c1, r1, s1), (c2, r2, s2)] {
        let from = base_top.atan2(-half);
        let to = TAU + base_top.atan2(half);
        builder.line_to(p(centre.x - half, base_top));
        builder.arc(centre, radius, from, to);
    }
    builder.lines(&[
        p(right, base_top),
        p(right, base_bottom),
        p(left, base_bottom),
    ]);
    builder.closed()
}

/// An arch (an Ω): a band over a round hole whose inner sides meet `contact` apart below the
/// hole, run on parallel for `parallel` px, then part at 30°–60° down to the feet.
fn arch(pen: f64, contact: f64, parallel: f64, random: &mut SplitMix64) -> Shape {
    let r = random.range(15.0, 30.0);
    let band = random.range((3.0 * pen).max(12.0), 30.0);
    let outer = r + band;
    let pinch_y = (r * r - contact * contact / 4.0).sqrt();
    let outer_x = (outer * outer - pinch_y * pinch_y).sqrt();
    let half_split = random.range(15.0, 30.0).to_radians();
    let feet = random.range(20.0, 50.0);
    let down = |sign: f64| Vec2::new(sign * half_split.sin(), half_split.cos()) * feet;
    let straight = Vec2::new(0.0, parallel);
    let (inner_left, inner_right) = (p(-contact / 2.0, pinch_y), p(contact / 2.0, pinch_y));
    let (outer_left, outer_right) = (p(-outer_x, pinch_y), p(outer_x, pinch_y));
    let mut builder = Builder::start(inner_right);
    let from = pinch_y.atan2(contact / 2.0);
    let to = pinch_y.atan2(-contact / 2.0) - TAU;
    builder.arc(Point::ORIGIN, r, from, to);
    builder.lines(&[
        inner_left + straight,
        inner_left + straight + down(-1.0),
        outer_left + straight + down(-1.0),
        outer_left + straight,
        outer_left,
    ]);
    builder.arc(
        Point::ORIGIN,
        outer,
        pinch_y.atan2(-outer_x),
        TAU + pinch_y.atan2(outer_x),
    );
    builder.lines(&[
        outer_right + straight,
        outer_right + straight + down(1.0),
        inner_right + straight + down(1.0),
        inner_right + straight,
    ]);
    builder.closed()
}

/// Outlines whose non-adjacent parts run parallel 0.5–1.5 pen widths apart for 20–80 px, then
/// part at 30°–60°: a slot under an arch, a looped hairpin, and a spiral whose last turn closes
/// in on the one before.
pub fn meanders(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    let hand = *hand;
    several(few(random).min(2), &hand, random, |random| {
        let apart = pen * random.range(0.5, 1.5);
        let parallel = random.range(20.0, 80.0);
        let shape = match random.index(3) {
            0 => arch(pen, apart, parallel, random),
            1 => looped_hairpin(apart, parallel, random),
            _ => closing_spiral(&hand, apart, parallel, random),
        };
        Figure::of(vec![shape]).rotated(any_angle(random))
    })
}

/// Two strands `apart` apart for `parallel` px, joined at one end by a round loop and parting at
/// the other at 30°–60°.
fn looped_hairpin(apart: f64, parallel: f64, random: &mut SplitMix64) -> Shape {
    let radius = random.range(12.0, 35.0);
    let half_split = random.range(15.0, 30.0).to_radians();
    let lead = random.range(30.0, 90.0);
    let centre = p(
        parallel + (radius * radius - apart * apart / 4.0).sqrt(),
        0.0,
    );
    let away = |sign: f64| {
        p(
            -lead * half_split.cos(),
            sign * (apart / 2.0 + lead * half_split.sin()),
        )
    };
    let mut builder = Builder::start(away(-1.0));
    builder.lines(&[p(0.0, -apart / 2.0), p(parallel, -apart / 2.0)]);
    let from = (p(parallel, -apart / 2.0) - centre).atan2();
    let to = (p(parallel, apart / 2.0) - centre).atan2();
    // The long way round the far side of the loop.
    builder.arc(centre, radius, from, if to > from { to } else { to + TAU });
    builder.lines(&[p(0.0, apart / 2.0), away(1.0)]);
    builder.open()
}

/// An Archimedean spiral whose spacing closes in from its own to `apart` over a quarter turn,
/// runs parallel to the previous turn for `parallel` px, then leaves at 30°–60°.
fn closing_spiral(hand: &Hand, apart: f64, parallel: f64, random: &mut SplitMix64) -> Shape {
    const STEPS_PER_TURN: usize = 720;
    let spacing = (2.5 * (hand.gap.1 + hand.pen)).max(25.0);
    let inner = random.range(8.0, 20.0);
    let turns_before = random.range(1.25, 1.75);
    let step = TAU / STEPS_PER_TURN as f64;
    let squeeze_from = (turns_before * STEPS_PER_TURN as f64) as usize;
    let squeeze = STEPS_PER_TURN / 4;
    let mut radii: Vec<f64> = Vec::new();
    let mut points: Vec<Point> = Vec::new();
    let mut along_parallel = 0.0;
    let mut index = 0;
    loop {
        let angle = index as f64 * step;
        let radius = if index < STEPS_PER_TURN {
            inner + spacing * angle / TAU
        } else {
            let t = (index.saturating_sub(squeeze_from) as f64 / squeeze as f64).min(1.0);
            let smooth = t * t * (3.0 - 2.0 * t);
            radii[index - STEPS_PER_TURN] + spacing + (apart - spacing) * smooth
        };
        let point = Point::ORIGIN + Vec2::from_angle(angle) * radius;
        if index > squeeze_from + squeeze {
            along_parallel += point.distance(points[index - 1]);
        }
        radii.push(radius);
        points.push(point);
        if along_parallel >= parallel {
            break;
        }
        index += 1;
    }
    // Leave outward at 30°–60° from the tangent.
    let last = points.len() - 1;
    let tangent = (points[last] - points[last - 1]).normalize();
    let outward = -random.range(30.0, 60.0).to_radians();
    let direction = Affine::rotate(outward) * tangent.to_point();
    let end = points[last] + direction.to_vec2() * random.range(30.0, 70.0);
    points.push(end);
    polyline(points)
}

/// An animal-like outline: a body with 2–6 legs 0.5–3 pen widths wide (feet sometimes touching
/// the next leg), a tail and a head with ears.
pub fn animals(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    let (rx, ry) = (random.range(75.0, 150.0), random.range(40.0, 80.0));
    let body = ellipse(Point::ORIGIN, rx, ry, 0.0, 0.0);
    let ground = ry + random.range(25.0, 70.0);
    let mut chains = legs(&body, rx, ground, pen, random);
    // The head on the front top (angle about -40°), the tail on the back top.
    let head = head_with_ears(pen, random);
    let tail_width = pen * random.range(0.75, 2.0);
    let tail = rounded_strip(
        0.0,
        tail_width,
        random.range(30.0, 80.0),
        random.range(-1.2, 1.2),
    );
    for (angle, protrusion) in [
        (-random.range(0.5, 0.9), head),
        (PI + random.range(0.15, 0.5), tail),
    ] {
        let target = Point::ORIGIN + Vec2::new(rx * angle.cos(), ry * angle.sin());
        let at = nearest_arc_length(&body, target).clamp(
            protrusion.base / 2.0 + 1.0,
            body.length() - protrusion.base / 2.0 - 1.0,
        );
        let placed = Protrusion { at, ..protrusion };
        chains.push(placed.chain(&body, Point::ORIGIN));
    }
    let outline = insert_chains(&body, &chains);
    let facing = if random.chance(0.5) { 1.0 } else { -1.0 };
    Figure::of(vec![
        outline.transformed(Affine::scale_non_uniform(facing, 1.0))
    ])
    .rotated(random.range(-0.25, 0.25))
}

fn nearest_arc_length(shape: &Shape, target: Point) -> f64 {
    let mut travelled = 0.0;
    let mut best = (f64::INFINITY, 0.0);
    let count = shape.points.len();
    for index in 0..count {
        let point = shape.points[index];
        if point.distance(target) < best.0 {
            best = (point.distance(target), travelled);
        }
        travelled += point.distance(shape.points[(index + 1) % count]);
    }
    best.1
}

/// A round head 30–55 px wide and 25–50 px high with one or two pointed or round ears.
fn head_with_ears(pen: f64, random: &mut SplitMix64) -> Protrusion {
    let width = random.range(30.0, 55.0);
    let height = random.range(25.0, 50.0);
    let outline: Vec<Point> = (0..=80)
        .map(|i| {
            let phi = PI - PI * i as f64 / 80.0;
            p(width / 2.0 * phi.cos(), height * phi.sin())
        })
        .collect();
    let head = polyline(outline);
    let length = head.length();
    let ears: Vec<Protrusion> = (0..1 + random.index(2))
        .map(|index| {
            let at = length * (0.3 + 0.3 * index as f64 + random.range(-0.05, 0.05));
            if random.chance(0.5) {
                spike(at, random.range(6.0, 14.0), random.range(10.0, 25.0))
            } else {
                rounded_strip(
                    at,
                    pen * random.range(1.5, 3.0),
                    random.range(8.0, 20.0),
                    random.range(-0.5, 0.5),
                )
            }
        })
        .collect();
    // The head's inside is below its outline in the local frame (towards the body).
    let with_ears = insert_protrusions(&head, p(0.0, 0.0), &ears);
    Protrusion {
        at: 0.0,
        base: width,
        local: with_ears.points,
    }
}

/// 2–6 vertical legs from the bottom of the body down to `ground`, each 0.5–3 pen widths wide,
/// with a foot pointing forward that sometimes touches the next leg.
fn legs(body: &Shape, rx: f64, ground: f64, pen: f64, random: &mut SplitMix64) -> Vec<Chain> {
    let count = 2 + random.index(5);
    let widths: Vec<f64> = (0..count).map(|_| pen * random.range(0.5, 3.0)).collect();
    let span = rx * random.range(1.0, 1.4);
    let slot = span / count as f64;
    let xs: Vec<f64> = (0..count)
        .map(|i| -span / 2.0 + slot * (i as f64 + random.range(0.3, 0.7)))
        .collect();
    let mut chains = Vec::new();
    for (i, (&x, &width)) in xs.iter().zip(&widths).enumerate() {
        let (left, right) = (x - width / 2.0, x + width / 2.0);
        // The ellipse runs clockwise from its right end: along the bottom x decreases.
        let (Some(from), Some(to)) = (
            arc_length_where(body, 0.0, |q| q.x - right),
            arc_length_where(body, 0.0, |q| q.x - left),
        ) else {
            continue;
        };
        let y_of = |s: f64| super::shapes::point_at(body, s).0.y;
        let foot = match xs.get(i + 1) {
            Some(&next) if random.chance(0.25) => {
                // Touching: the foot ends 0–1 pen widths (centre lines) from the next leg.
                next - widths[i + 1] / 2.0 - right - pen * random.range(0.0, 1.0)
            }
            _ => pen * random.range(0.0, 4.0),
        };
        let foot_height = (1.5 * pen).max(width).min(ground - y_of(from) - pen);
        let mut points = vec![p(right, y_of(from))];
        if foot > pen {
            points.extend([
                p(right, ground - foot_height),
                p(right + foot, ground - foot_height),
                p(right + foot, ground),
            ]);
        } else {
            points.push(p(right, ground));
        }
        points.extend([p(left, ground), p(left, y_of(to))]);
        chains.push(Chain { from, to, points });
    }
    chains
}
