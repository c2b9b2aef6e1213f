//! The benchmark's families (issue 8: line art; issue 9: touching parts, in `touching.rs`): the
//! hand of each family, and one random figure of each. Every size, count, position and angle is
//! drawn at random within the ranges the issues give.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use kurbo::{Affine, Point, Vec2};

use super::figure::{arrange, Dot, Figure};
use super::geometry::TrueCurve;
use super::objects;
use super::paper::Style;
use super::pen::{pen_intervals, Corners, Hand, Plan};
use super::random::SplitMix64;
use super::shapes::{blob, ellipse, polygon, polyline, star, Builder, Shape};
use super::touching;

/// Rows of figures on one page are at most this wide, px, and the whole figure at most this big
/// (pages stay within about 300–900 px with their margins).
pub const ROW_WIDTH: f64 = 760.0;
const LARGEST_FIGURE: f64 = 800.0;
/// Largest pen jitter (sideways wobble), px: issue 8.
const MAX_JITTER: f64 = 1.5;
/// Visible gaps of line art, in pen widths: issue 8 ("gaps 1–4 pen widths").
const LINE_ART_GAPS: (f64, f64) = (1.0, 4.0);
/// Strokes of line art are this many times the longest gap, at least (strokes "several times
/// longer" than gaps), and never shorter than 12 px.
const STROKE_TO_GAP: (f64, f64) = (2.0, 3.0);
const SHORTEST_STROKE: f64 = 12.0;
/// DECISION: where lines must not touch (parallel lines, a neck), each stroke wobbles by at most
/// this fraction of the visible space between them (the 0–1.5 px jitter would make lines
/// 2.6 px apart cross); the smaller jitter is the one recorded in the truth.
const TIGHT_JITTER: f64 = 0.25;

/// A family of drawings.
#[derive(Clone, Copy, Debug)]
pub struct Family {
    /// Short name, used in file names and tables.
    pub name: &'static str,
    /// Issue 9's touching-parts families: expected to fail for now, reported in their own rows.
    pub touching: bool,
    /// Draws one figure with `hand`, which it may adjust (corner rule, jitter).
    build: fn(&mut Hand, &mut SplitMix64) -> Figure,
}

impl Family {
    /// One random figure of this family.
    pub fn build(&self, hand: &mut Hand, random: &mut SplitMix64) -> Figure {
        (self.build)(hand, random)
    }
}

/// Every family, in table order.
pub const FAMILIES: &[Family] = &[
    family("stars", false, stars),
    family("corners", false, corners),
    family("closing", false, closing),
    family("open-controls", false, open_controls),
    family("parallel", false, parallel_lines),
    family("finger", false, finger),
    family("dumbbell", false, dumbbell),
    family("figure-eight", false, figure_eights),
    family("letters", false, objects::letters),
    family("faces", false, objects::faces),
    family("spirals-waves", false, objects::spirals_and_waves),
    family("nested", false, objects::nested),
    family("objects", false, objects::objects),
    family("dots", false, objects::dots),
    family("spikes", true, touching::spikes),
    family("arches", true, touching::arches),
    family("meanders", true, touching::meanders),
    family("animals", true, touching::animals),
];

const fn family(
    name: &'static str,
    touching: bool,
    build: fn(&mut Hand, &mut SplitMix64) -> Figure,
) -> Family {
    Family {
        name,
        touching,
        build,
    }
}

/// The four pen styles of the benchmark.
pub const STYLES: &[Style] = &[Style::Clean, Style::Thick, Style::Thin, Style::Scan];

/// The pen width for `style`: issue 8's pens for line art (clean 3, thick 7, thin 1.75–2, scan
/// 3 px). DECISION: issue 9 asks for pens of 2–5 px for touching parts in all four styles; thin
/// takes 2–2.5, clean 3, thick 4–5 and scan 2.5–4.
pub fn pen_width(style: Style, touching: bool, random: &mut SplitMix64) -> f64 {
    match (style, touching) {
        (Style::Thick, false) => 7.0,
        (Style::Thin, false) => random.range(1.75, 2.0),
        (Style::Thick, true) => random.range(4.0, 5.0),
        (Style::Thin, true) => random.range(2.0, 2.5),
        (Style::Scan, true) => random.range(2.5, 4.0),
        _ => 3.0,
    }
}

/// The hand for a drawing of `family` with pen `pen`: gaps and strokes at random within the
/// issue's ranges, jitter 0–1.5 px.
pub fn hand_for(family: &Family, pen: f64, random: &mut SplitMix64) -> Hand {
    let jitter = random.range(0.0, MAX_JITTER);
    if family.touching {
        return touching::hand(pen, jitter, random);
    }
    let low = random.range(LINE_ART_GAPS.0, 2.0);
    let high = (low + random.range(0.5, 2.0)).min(LINE_ART_GAPS.1);
    let shortest =
        (high * pen * random.range(STROKE_TO_GAP.0, STROKE_TO_GAP.1)).max(SHORTEST_STROKE);
    Hand {
        pen,
        jitter,
        stroke: (shortest, shortest * random.range(1.5, 3.0)),
        gap: (low * pen, high * pen),
        corners: Corners::KeepInk {
            tip_gap_chance: 0.0,
        },
    }
}

/// Space between separate objects: well over the longest gap, so an end has no doubt which
/// stroke goes on.
pub fn object_spacing(hand: &Hand, random: &mut SplitMix64) -> f64 {
    random.range(2.5, 4.0) * (hand.gap.1 + hand.pen)
}

/// `count` figures made by `make`, arranged on one page.
pub fn several(
    count: usize,
    hand: &Hand,
    random: &mut SplitMix64,
    mut make: impl FnMut(&mut SplitMix64) -> Figure,
) -> Figure {
    let figures: Vec<Figure> = (0..count).map(|_| make(random)).collect();
    let spacing = object_spacing(hand, random);
    fit_on_page(figures, spacing, random)
}

/// The figures arranged in rows, the last ones left out while the page would be too big.
pub fn fit_on_page(mut figures: Vec<Figure>, spacing: f64, random: &mut SplitMix64) -> Figure {
    loop {
        let page = arrange(figures.clone(), spacing, ROW_WIDTH, random);
        let bounds = page.bounds();
        if figures.len() == 1 || bounds.width().max(bounds.height()) <= LARGEST_FIGURE {
            return page;
        }
        figures.pop();
    }
}

/// 1, 2 or 3, mostly 1 or 2.
pub fn few(random: &mut SplitMix64) -> usize {
    [1, 1, 2, 2, 3][random.index(5)]
}

/// A uniformly random angle.
pub fn any_angle(random: &mut SplitMix64) -> f64 {
    random.range(0.0, TAU)
}

// ---- polygons and stars -------------------------------------------------------------------

/// Stars, isosceles triangles and arrowheads with apex angles of 15°–90° in steps of 15°,
/// rotated 0–45°; a gap lands exactly at a tip with a chance of 15–50 % per tip.
fn stars(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    hand.corners = Corners::KeepInk {
        tip_gap_chance: random.range(0.15, 0.5),
    };
    let pen = hand.pen;
    several(few(random), hand, random, |random| {
        let apex = (15.0 * (1 + random.index(6)) as f64).to_radians();
        let size = random.range((12.0 * pen).max(70.0), 220.0);
        let rotation = random.range(0.0, PI / 4.0);
        let shape = match random.index(3) {
            0 => {
                let tips = 3 + random.index(6);
                star(Point::ORIGIN, size / 2.0, tips, apex, rotation - FRAC_PI_2)
            }
            1 => {
                let half_base = size * (apex / 2.0).tan();
                polygon(vec![
                    Point::new(0.0, 0.0),
                    Point::new(half_base, size),
                    Point::new(-half_base, size),
                ])
                .transformed(Affine::rotate(rotation))
            }
            _ => arrowhead(size, apex).transformed(Affine::rotate(rotation)),
        };
        Figure::of(vec![shape])
    })
}

/// An arrowhead (concave back) or a kite (convex back) with its tip at the origin.
fn arrowhead(size: f64, apex: f64) -> Shape {
    let side = |sign: f64| Point::new(sign * size * (apex / 2.0).sin(), size * (apex / 2.0).cos());
    let depth = size * (apex / 2.0).cos();
    let back = Point::new(0.0, depth * if apex < PI / 3.0 { 0.75 } else { 1.35 });
    polygon(vec![Point::ORIGIN, side(1.0), back, side(-1.0)])
}

// ---- sharp corners that fall between samples ----------------------------------------------

/// Squares, rectangles and triangles at any angle whose corners are cut by 0.5–2 px (a right
/// angle becomes two 45° turns), and open hairpins of 20°–40°.
fn corners(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    several(few(random), hand, random, |random| {
        let small = (8.0 * pen).max(40.0);
        let shape = match random.index(4) {
            0 => {
                let side = random.range(small, 220.0);
                rectangle(side, side)
            }
            1 => {
                let width = random.range(small, 260.0);
                let height = (width * random.range(0.2, 0.8)).max(small);
                rectangle(width, height)
            }
            2 => triangle(random.range(small.max(50.0), 140.0), random),
            _ => hairpin(pen, random),
        };
        let cut = chamfered(&shape, random);
        Figure::of(vec![cut.transformed(Affine::rotate(any_angle(random)))])
    })
}

fn rectangle(width: f64, height: f64) -> Shape {
    polygon(vec![
        Point::new(0.0, 0.0),
        Point::new(width, 0.0),
        Point::new(width, height),
        Point::new(0.0, height),
    ])
}

/// A triangle on a circle of `radius` with no angle under 25°.
fn triangle(radius: f64, random: &mut SplitMix64) -> Shape {
    loop {
        let mut angles: Vec<f64> = (0..3).map(|_| random.range(0.0, TAU)).collect();
        angles.sort_by(f64::total_cmp);
        // Inscribed angles are half the arcs opposite them.
        let arcs = [
            angles[1] - angles[0],
            angles[2] - angles[1],
            TAU - angles[2] + angles[0],
        ];
        if arcs.iter().all(|&arc| arc / 2.0 >= 25f64.to_radians()) {
            let vertices = angles
                .iter()
                .map(|&a| Point::ORIGIN + Vec2::from_angle(a) * radius)
                .collect();
            return polygon(vertices);
        }
    }
}

/// An open V whose arms meet at 20°–40°.
fn hairpin(pen: f64, random: &mut SplitMix64) -> Shape {
    let apex = random.range(20.0, 40.0).to_radians();
    let arm = |random: &mut SplitMix64| random.range((10.0 * pen).max(50.0), 160.0);
    let (a, b) = (arm(random), arm(random));
    polyline(vec![
        Point::ORIGIN + Vec2::from_angle(FRAC_PI_2 - apex / 2.0) * a,
        Point::ORIGIN,
        Point::ORIGIN + Vec2::from_angle(FRAC_PI_2 + apex / 2.0) * b,
    ])
}

/// The shape with most corners cut by 0.5–2 px along both edges.
fn chamfered(shape: &Shape, random: &mut SplitMix64) -> Shape {
    let count = shape.points.len();
    let mut points = Vec::with_capacity(2 * count);
    for index in 0..count {
        let vertex = shape.points[index];
        let is_end = !shape.closed && (index == 0 || index == count - 1);
        if is_end || random.chance(0.25) {
            points.push(vertex);
            continue;
        }
        let before = shape.points[(index + count - 1) % count];
        let after = shape.points[(index + 1) % count];
        let cut = random.range(0.5, 2.0);
        points.push(vertex + (before - vertex).normalize() * cut);
        points.push(vertex + (after - vertex).normalize() * cut);
    }
    Shape {
        points,
        closed: shape.closed,
    }
}

// ---- closing the loop ------------------------------------------------------------------------

/// DECISION: the widest closing gap is at most this share of the loop (issue 8: a loop-closing
/// bridge is at most 10–15 % of the loop); the open controls' openings are 25 % and more.
const CLOSING_GAP_SHARE: f64 = 0.12;

/// Circles, ellipses and blobs (r = 25–60 px) drawn in 5–8 strokes with exactly one gap
/// 1.8–2.4× the largest other gap: each must come out closed.
fn closing(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    let hand = *hand;
    several(few(random), &hand, random, |random| {
        // DECISION: with the 7 px pen a 25 px circle leaves strokes of one pen width; radii
        // start at 5 pen widths there.
        let smallest = 25f64.max(5.0 * pen);
        let radius = |random: &mut SplitMix64| random.range(smallest, 60.0);
        let shape = match random.index(3) {
            0 => {
                let r = radius(random);
                ellipse(Point::ORIGIN, r, r, 0.0, any_angle(random))
            }
            1 => {
                let (rx, ry) = (radius(random), radius(random));
                ellipse(Point::ORIGIN, rx, ry, any_angle(random), any_angle(random))
            }
            _ => blob(Point::ORIGIN, radius(random), 0.25, random),
        };
        let intervals = closing_intervals(shape.length(), &hand, random);
        let mut figure = Figure::default();
        figure.push(shape, Plan::Intervals(intervals));
        figure
    })
}

/// 5–8 strokes around a loop of `length`, one gap `1.8–2.4×` the largest of the others.
fn closing_intervals(length: f64, hand: &Hand, random: &mut SplitMix64) -> Vec<(f64, f64)> {
    let ratio = random.range(1.8, 2.4);
    let high = hand.gap.1.min(CLOSING_GAP_SHARE * length / ratio);
    let low = hand.gap.0.min(0.8 * high);
    let mut strokes = 5 + random.index(4);
    let gaps = loop {
        let mut gaps: Vec<f64> = (1..strokes).map(|_| random.range(low, high)).collect();
        let widest = gaps.iter().copied().fold(0.0, f64::max);
        gaps.insert(random.index(strokes), ratio * widest);
        let lifted: f64 = gaps.iter().map(|&g| hand.lifted(g)).sum();
        // Fewer strokes when they would be shorter than 2.5 mean gaps.
        let mean_stroke = (length - lifted) / strokes as f64;
        if strokes == 5 || mean_stroke >= 2.5 * lifted / strokes as f64 {
            break gaps;
        }
        strokes -= 1;
    };
    let lifted: f64 = gaps.iter().map(|&g| hand.lifted(g)).sum();
    let weights: Vec<f64> = (0..strokes).map(|_| random.range(0.6, 1.4)).collect();
    let total: f64 = weights.iter().sum();
    let mut position = random.range(0.0, length);
    let mut intervals = Vec::with_capacity(strokes);
    for (weight, gap) in weights.iter().zip(&gaps) {
        let stroke = (length - lifted) * weight / total;
        intervals.push((position, position + stroke));
        position += stroke + hand.lifted(*gap);
    }
    intervals
}

/// Controls that must stay open: an arc whose opening is 25–45 % of its perimeter, and two
/// facing arcs "( )" whose ends are 2.5× the drawing's typical gap apart.
fn open_controls(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let hand = *hand;
    several(1 + random.index(2), &hand, random, |random| {
        if random.chance(0.5) {
            open_arc(&hand, random)
        } else {
            facing_arcs(&hand, random)
        }
    })
}

fn open_arc(hand: &Hand, random: &mut SplitMix64) -> Figure {
    let smallest = (6.0 * hand.pen).max(30.0);
    let (rx, ry) = (random.range(smallest, 100.0), random.range(smallest, 100.0));
    let full = ellipse(Point::ORIGIN, rx, ry, any_angle(random), any_angle(random));
    let opening = random.range(0.25, 0.45);
    let keep = full.length() * (1.0 - opening);
    let mut builder = Builder::start(full.points[0]);
    for &point in &full.points[1..] {
        if builder.length() + builder.end().distance(point) > keep {
            break;
        }
        builder.line_to(point);
    }
    Figure::of(vec![builder.open()])
}

fn facing_arcs(hand: &Hand, random: &mut SplitMix64) -> Figure {
    let radius = random.range((6.0 * hand.pen).max(30.0), 90.0);
    let half_span = random.range(50.0, 75.0).to_radians();
    let template = |from: f64| {
        let mut builder = Builder::start(Point::ORIGIN + Vec2::from_angle(from) * radius);
        builder.arc(Point::ORIGIN, radius, from, from + 2.0 * half_span);
        builder.open()
    };
    let left = template(PI - half_span);
    let right = template(-half_span);
    let plans: Vec<Vec<(f64, f64)>> = [&left, &right]
        .iter()
        .map(|shape| {
            let curve = TrueCurve::from_points(shape.points.clone(), false);
            pen_intervals(&curve, &Plan::auto(), hand, random)
        })
        .collect();
    let mut gaps: Vec<f64> = plans
        .iter()
        .flat_map(|intervals| intervals.windows(2).map(|w| w[1].0 - w[0].1 - hand.pen))
        .collect();
    gaps.sort_by(f64::total_cmp);
    let typical = if gaps.is_empty() {
        (hand.gap.0 + hand.gap.1) / 2.0
    } else {
        gaps[gaps.len() / 2]
    };
    // Ends `2.5 × typical` apart, ink to ink.
    let centres = 2.5 * typical + hand.pen;
    let shift = (centres - 2.0 * radius * half_span.cos()) / 2.0;
    let mut figure = Figure::default();
    for ((shape, intervals), sign) in [left, right].into_iter().zip(plans).zip([-1.0, 1.0]) {
        let moved = shape.transformed(Affine::translate((sign * shift, 0.0)));
        figure.push(moved, Plan::Intervals(intervals));
    }
    figure.transformed(Affine::rotate(any_angle(random)))
}

// ---- lines side by side --------------------------------------------------------------------

/// Two straight lines 150 px long, 1.5–2 pen widths apart, each with 10–14 px gaps, the gaps of
/// the second staggered by 2–8 px from those of the first: two straight paths expected.
fn parallel_lines(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    let apart = random.range(1.5, 2.0) * pen;
    hand.jitter = hand.jitter.min(TIGHT_JITTER * (apart - pen));
    let hand = *hand;
    several(1 + random.index(2), &hand, random, |random| {
        const LENGTH: f64 = 150.0;
        let mut centres = Vec::new();
        let mut position = 0.0;
        loop {
            let stroke = random.range(22.0, 45.0);
            let lifted = hand.lifted(random.range(10.0, 14.0));
            if position + stroke + lifted + 22.0 > LENGTH {
                break;
            }
            centres.push(position + stroke + lifted / 2.0);
            position += stroke + lifted;
        }
        let staggered: Vec<f64> = centres
            .iter()
            .map(|c| c + random.range(2.0, 8.0) * if random.chance(0.5) { 1.0 } else { -1.0 })
            .collect();
        let mut figure = Figure::default();
        for (y, gap_centres) in [(0.0, centres), (apart, staggered)] {
            let (start, end) = (random.range(-3.0, 3.0), LENGTH + random.range(-3.0, 3.0));
            let line = polyline(vec![Point::new(start, y), Point::new(end, y)]);
            let gaps = gap_centres
                .iter()
                .map(|&c| (c - start, random.range(10.0, 14.0)))
                .collect();
            figure.push(
                line,
                Plan::Auto {
                    forced_gaps: gaps,
                    solid: vec![(0.0, end - start)],
                },
            );
        }
        figure.transformed(Affine::rotate(any_angle(random)))
    })
}

/// A palm with one or two fingers 7 px wide (7/3 pen widths for pens over 3.5 px) whose round
/// tip is one U-stroke, with a gap on both sides just below it: the U must not be sealed.
fn finger(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    // DECISION: the 7 px finger is for a 3 px pen; a thick pen would fill it.
    let width = if pen <= 3.5 { 7.0 } else { 7.0 / 3.0 * pen };
    let palm_width = random.range(80.0, 170.0);
    let palm_height = random.range(50.0, 120.0);
    let fingers = 1 + random.index(2);
    let mut builder = Builder::start(Point::new(0.0, palm_height));
    builder.line_to(Point::new(0.0, 0.0));
    let mut forced_gaps = Vec::new();
    let mut solid = Vec::new();
    for index in 0..fingers {
        let slot = palm_width / fingers as f64;
        let x = slot * (index as f64 + random.range(0.35, 0.65));
        let length = random.range(30f64.max(4.0 * width), 60f64.max(6.0 * width));
        let tip_centre = Point::new(x, -(length - width / 2.0));
        builder.line_to(Point::new(x - width / 2.0, 0.0));
        builder.line_to(Point::new(x - width / 2.0, tip_centre.y));
        let tip_start = builder.length();
        builder.arc(tip_centre, width / 2.0, PI, TAU);
        let tip = (tip_start + builder.length()) / 2.0;
        // From the tip's middle to either end of the round tip.
        let reach = tip - tip_start;
        builder.line_to(Point::new(x + width / 2.0, 0.0));
        // The U-stroke runs 0.3–1.5 finger widths down each side, then the pen lifts.
        let down = (reach + width * random.range(0.3, 1.5)).min(length - width);
        let side = length - width / 2.0 - (down - reach);
        let visible = hand.random_gap(random).min(0.6 * side - pen).max(0.5 * pen);
        solid.push((tip - down, tip + down));
        for sign in [-1.0, 1.0] {
            forced_gaps.push((tip + sign * (down + hand.lifted(visible) / 2.0), visible));
        }
    }
    builder.lines(&[
        Point::new(palm_width, 0.0),
        Point::new(palm_width, palm_height),
    ]);
    let mut figure = Figure::default();
    figure.push(builder.closed(), Plan::Auto { forced_gaps, solid });
    figure.rotated(any_angle(random))
}

/// Two circles joined by a neck whose sides are 1.25–2 pen widths apart, with a gap on both
/// sides of the neck at the same place.
fn dumbbell(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    let apart = random.range(1.25, 2.0) * pen;
    hand.jitter = hand.jitter.min(TIGHT_JITTER * (apart - pen));
    let hand = *hand;
    several(few(random), &hand, random, |random| {
        let smallest = (5.0 * pen).max(25.0);
        let (r1, r2) = (random.range(smallest, 60.0), random.range(smallest, 60.0));
        let visible = hand.random_gap(random);
        // The neck keeps some ink on both sides of its gaps.
        let lifted = hand.lifted(visible);
        let neck = random.range(25f64.max(3.0 * lifted), 70f64.max(5.0 * lifted));
        let half = apart / 2.0;
        let (a1, a2) = ((half / r1).asin(), (half / r2).asin());
        let x1 = r1 * a1.cos();
        let centre2 = Point::new(r1 + neck + r2, 0.0);
        let x2 = centre2.x - r2 * a2.cos();
        let mut builder = Builder::start(Point::new(x1, half));
        builder.arc(Point::ORIGIN, r1, a1, TAU - a1);
        let top_start = builder.length();
        builder.line_to(Point::new(x2, -half));
        builder.arc(centre2, r2, PI + a2, 3.0 * PI - a2);
        let bottom_start = builder.length();
        builder.line_to(Point::new(x1, half));
        let at = random.range(x1 + hand.lifted(visible), x2 - hand.lifted(visible));
        let forced_gaps = vec![
            (top_start + (at - x1), visible),
            (bottom_start + (x2 - at), visible),
        ];
        let mut figure = Figure::default();
        figure.push(
            builder.closed(),
            Plan::Auto {
                forced_gaps,
                solid: Vec::new(),
            },
        );
        figure.rotated(any_angle(random))
    })
}

/// Figure-eights: one closed curve crossing itself once, lobes of random and unequal size.
fn figure_eights(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    several(few(random), hand, random, |random| {
        let half_width = random.range((10.0 * pen).max(50.0), 170.0);
        let half_height = half_width * random.range(0.35, 0.8);
        let skew = random.range(-0.3, 0.3);
        const STEPS: usize = 2000;
        let points = (0..STEPS)
            .map(|i| {
                let t = TAU * i as f64 / STEPS as f64;
                Point::new(
                    half_width * t.cos(),
                    half_height * (2.0 * t).sin() * (1.0 + skew * t.cos()),
                )
            })
            .collect();
        Figure::of(vec![Shape {
            points,
            closed: true,
        }])
        .rotated(any_angle(random))
    })
}

/// A dot of 1–3 pen widths.
pub fn dot(centre: Point, pen: f64, random: &mut SplitMix64) -> Dot {
    Dot {
        centre,
        diameter: pen * random.range(1.0, 3.0),
    }
}
