//! The everyday line-art families of the benchmark (issue 8): single-line capital letters, faces,
//! spirals and waves, nested shapes, pages of several objects, and isolated dots.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use kurbo::{Affine, Point, Vec2};

use super::families::{any_angle, dot, few, fit_on_page, object_spacing, several};
use super::figure::Figure;
use super::pen::Hand;
use super::random::SplitMix64;
use super::shapes::{blob, ellipse, polygon, polyline, star, Builder, Shape};

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

fn line(points: &[(f64, f64)]) -> Shape {
    polyline(points.iter().map(|&(x, y)| p(x, y)).collect())
}

/// An arc of the ellipse around `(cx, cy)` from angle `from` to `to` (y down).
fn elliptic_arc(cx: f64, cy: f64, rx: f64, ry: f64, from: f64, to: f64) -> Vec<Point> {
    // 200 vertices a half turn: about a pixel apart at the sizes drawn.
    let steps = ((to - from).abs() / PI * 200.0).ceil().max(8.0) as usize;
    (0..=steps)
        .map(|i| {
            let t = from + (to - from) * i as f64 / steps as f64;
            p(cx + rx * t.cos(), cy + ry * t.sin())
        })
        .collect()
}

/// Capitals made of straight pen paths, in a box one unit high: letter, width, paths.
type LineGlyph = (char, f64, &'static [&'static [(f64, f64)]]);
const LINE_GLYPHS: &[LineGlyph] = &[
    (
        'A',
        0.7,
        &[
            &[(0.0, 1.0), (0.35, 0.0), (0.7, 1.0)],
            &[(0.14, 0.6), (0.56, 0.6)],
        ],
    ),
    (
        'E',
        0.55,
        &[
            &[(0.55, 0.0), (0.0, 0.0), (0.0, 1.0), (0.55, 1.0)],
            &[(0.0, 0.5), (0.45, 0.5)],
        ],
    ),
    (
        'F',
        0.55,
        &[
            &[(0.55, 0.0), (0.0, 0.0), (0.0, 1.0)],
            &[(0.0, 0.48), (0.42, 0.48)],
        ],
    ),
    (
        'H',
        0.6,
        &[
            &[(0.0, 0.0), (0.0, 1.0)],
            &[(0.6, 0.0), (0.6, 1.0)],
            &[(0.0, 0.5), (0.6, 0.5)],
        ],
    ),
    ('I', 0.05, &[&[(0.0, 0.0), (0.0, 1.0)]]),
    (
        'K',
        0.6,
        &[
            &[(0.0, 0.0), (0.0, 1.0)],
            &[(0.6, 0.0), (0.0, 0.55), (0.6, 1.0)],
        ],
    ),
    ('L', 0.5, &[&[(0.0, 0.0), (0.0, 1.0), (0.5, 1.0)]]),
    (
        'M',
        0.75,
        &[&[
            (0.0, 1.0),
            (0.0, 0.0),
            (0.375, 0.65),
            (0.75, 0.0),
            (0.75, 1.0),
        ]],
    ),
    (
        'N',
        0.6,
        &[&[(0.0, 1.0), (0.0, 0.0), (0.6, 1.0), (0.6, 0.0)]],
    ),
    (
        'T',
        0.7,
        &[&[(0.0, 0.0), (0.7, 0.0)], &[(0.35, 0.0), (0.35, 1.0)]],
    ),
    ('V', 0.7, &[&[(0.0, 0.0), (0.35, 1.0), (0.7, 0.0)]]),
    (
        'W',
        0.9,
        &[&[(0.0, 0.0), (0.2, 1.0), (0.45, 0.35), (0.7, 1.0), (0.9, 0.0)]],
    ),
    (
        'X',
        0.65,
        &[&[(0.0, 0.0), (0.65, 1.0)], &[(0.65, 0.0), (0.0, 1.0)]],
    ),
    (
        'Z',
        0.6,
        &[&[(0.0, 0.0), (0.6, 0.0), (0.0, 1.0), (0.6, 1.0)]],
    ),
];

/// A capital letter drawn the way a hand writes it, in a box one unit high: its width and its
/// pen paths (bars end on the stems, T-junctions; X crosses).
fn glyph(letter: char) -> (f64, Vec<Shape>) {
    if let Some(&(_, width, paths)) = LINE_GLYPHS.iter().find(|g| g.0 == letter) {
        return (width, paths.iter().map(|path| line(path)).collect());
    }
    let arc = elliptic_arc;
    let (width, mut points, closed) = match letter {
        'O' => {
            let mut points = arc(0.35, 0.5, 0.35, 0.5, -FRAC_PI_2, 1.5 * PI);
            points.pop();
            (0.7, points, true)
        }
        'C' => (0.6, arc(0.35, 0.5, 0.35, 0.5, 0.7, TAU - 0.7), false),
        'U' => {
            let mut points = vec![p(0.0, 0.0)];
            points.extend(arc(0.3, 0.7, 0.3, 0.3, PI, 0.0));
            (0.6, points, false)
        }
        'D' => {
            let mut points = vec![p(0.0, 0.0), p(0.0, 1.0)];
            points.extend(arc(0.2, 0.5, 0.4, 0.5, FRAC_PI_2, -FRAC_PI_2));
            (0.6, points, true)
        }
        'P' => {
            let mut points = vec![p(0.0, 1.0), p(0.0, 0.0)];
            points.extend(arc(0.28, 0.27, 0.27, 0.27, -FRAC_PI_2, FRAC_PI_2));
            (0.55, points, false)
        }
        'J' => {
            let mut points = vec![p(0.5, 0.0)];
            points.extend(arc(0.25, 0.75, 0.25, 0.25, 0.0, PI));
            (0.5, points, false)
        }
        _ => {
            // 'S'
            let mut points = arc(0.28, 0.25, 0.25, 0.25, -PI / 6.0, -1.5 * PI);
            points.extend(arc(0.28, 0.75, 0.25, 0.25, -FRAC_PI_2, 5.0 * PI / 6.0));
            (0.55, points, false)
        }
    };
    // U goes back up its right side; P's bowl ends on its stem.
    match letter {
        'U' => points.push(p(0.6, 0.0)),
        'P' => points.push(p(0.0, 0.54)),
        _ => {}
    }
    let shape = if closed {
        polygon(points)
    } else {
        polyline(points)
    };
    (width, vec![shape])
}

const LETTERS: &[char] = &[
    'A', 'E', 'F', 'H', 'K', 'L', 'M', 'N', 'T', 'V', 'W', 'X', 'Z', 'O', 'C', 'U', 'D', 'P', 'J',
    'S', 'I',
];

/// Words of 2–5 single-line capitals, 50–130 px high, slanted and turned a little.
pub fn letters(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    let hand = *hand;
    several(few(random).min(2), &hand, random, |random| {
        let height = random.range((14.0 * pen).max(50.0), 130.0);
        let slant = random.range(-0.15, 0.15);
        let spacing = (random.range(0.3, 0.5) * height).max(1.5 * (hand.gap.1 + hand.pen));
        let shape_of = Affine::new([height, 0.0, -slant * height, height, 0.0, 0.0]);
        let mut figure = Figure::default();
        let mut x = 0.0;
        for _ in 0..2 + random.index(4) {
            let (width, strokes) = glyph(LETTERS[random.index(LETTERS.len())]);
            let place = Affine::translate((x, 0.0)) * shape_of;
            for stroke in strokes {
                figure.extend(Figure::of(vec![stroke.transformed(place)]));
            }
            x += width * height + spacing;
        }
        figure.rotated(random.range(-0.14, 0.14))
    })
}

/// A face: head, eyes (circles, ellipses or dots), maybe brows, maybe a nose, a mouth.
pub fn faces(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let pen = hand.pen;
    let rx = random.range((25.0 * pen).max(80.0), 190.0);
    let ry = rx * random.range(0.9, 1.25);
    let mut figure = Figure::of(vec![ellipse(
        Point::ORIGIN,
        rx,
        ry,
        random.range(-0.1, 0.1),
        any_angle(random),
    )]);
    let eye_y = -ry * random.range(0.1, 0.3);
    let eye_x = rx * random.range(0.3, 0.42);
    let eye_r = (rx * random.range(0.08, 0.15)).max(4.0 * pen);
    let eye_kind = random.index(5);
    for sign in [-1.0, 1.0] {
        let centre = p(sign * eye_x, eye_y);
        match eye_kind {
            0 => figure.dots.push(dot(centre, pen, random)),
            1 | 2 => figure.extend(Figure::of(vec![ellipse(
                centre,
                eye_r,
                eye_r * random.range(0.6, 0.9),
                0.0,
                any_angle(random),
            )])),
            _ => figure.extend(Figure::of(vec![ellipse(
                centre,
                eye_r,
                eye_r,
                0.0,
                any_angle(random),
            )])),
        }
    }
    let clear = 2.0 * (hand.gap.1 + pen);
    if random.chance(0.6) {
        let brow_y = eye_y - eye_r - clear.max(0.12 * ry);
        let lift = random.range(0.0, 0.5) * eye_r;
        for sign in [-1.0, 1.0] {
            let brow = (0..=30)
                .map(|i| {
                    let t = i as f64 / 15.0 - 1.0;
                    p(
                        sign * eye_x + 1.2 * eye_r * t,
                        brow_y - lift * (1.0 - t * t),
                    )
                })
                .collect();
            figure.extend(Figure::of(vec![polyline(brow)]));
        }
    }
    if random.chance(0.8) {
        let top = eye_y + eye_r * 0.5;
        let tip = p(
            random.range(-0.12, 0.12) * rx,
            ry * random.range(0.15, 0.25),
        );
        figure.extend(Figure::of(vec![polyline(vec![
            p(0.0, top),
            tip,
            p(
                random.range(0.05, 0.15) * rx,
                tip.y + random.range(0.0, 0.05) * ry,
            ),
        ])]));
    }
    let mouth_y = ry * random.range(0.42, 0.6);
    let half = rx * random.range(0.2, 0.4);
    let curve = random.range(-0.5, 1.0) * half * 0.6;
    let mouth = (0..=60)
        .map(|i| {
            let t = i as f64 / 60.0 * 2.0 - 1.0;
            p(t * half, mouth_y + curve * (1.0 - t * t) - curve / 2.0)
        })
        .collect();
    figure.extend(Figure::of(vec![polyline(mouth)]));
    figure.rotated(random.range(-0.2, 0.2))
}

/// Open curves: Archimedean spirals, sine and damped waves, zigzags and square waves.
pub fn spirals_and_waves(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let hand = *hand;
    several(few(random), &hand, random, |random| {
        let shape = match random.index(5) {
            0 => spiral(&hand, random),
            1 | 2 => wave(&hand, random),
            3 => zigzag(&hand, random),
            _ => square_wave(&hand, random),
        };
        Figure::of(vec![shape]).rotated(any_angle(random))
    })
}

fn spiral(hand: &Hand, random: &mut SplitMix64) -> Shape {
    let spacing = (random.range(2.0, 3.0) * (hand.gap.1 + hand.pen)).max(14.0);
    let inner = random.range(4.0, 15.0);
    let turns = random
        .range(1.5, 3.5)
        .min((200.0 - inner) / spacing)
        .max(1.2);
    let steps = (turns * 400.0) as usize;
    let direction = if random.chance(0.5) { 1.0 } else { -1.0 };
    polyline(
        (0..=steps)
            .map(|i| {
                let angle = TAU * turns * i as f64 / steps as f64;
                let radius = inner + spacing * angle / TAU;
                Point::ORIGIN + Vec2::from_angle(direction * angle) * radius
            })
            .collect(),
    )
}

fn wave(hand: &Hand, random: &mut SplitMix64) -> Shape {
    let amplitude = random.range((2.0 * hand.pen).max(10.0), 60.0);
    let wavelength = random.range((3.0 * amplitude).max(50.0), (5.0 * amplitude).max(180.0));
    let length = (wavelength * random.range(1.5, 4.0)).min(650.0);
    let damping = if random.chance(0.4) {
        random.range(1.0, 3.0) / length
    } else {
        0.0
    };
    let phase = any_angle(random);
    let steps = (length * 2.0) as usize;
    polyline(
        (0..=steps)
            .map(|i| {
                let x = length * i as f64 / steps as f64;
                let envelope = amplitude * (-damping * x).exp();
                p(x, envelope * (TAU * x / wavelength + phase).sin())
            })
            .collect(),
    )
}

fn zigzag(hand: &Hand, random: &mut SplitMix64) -> Shape {
    let height = random.range((4.0 * hand.pen).max(20.0), 80.0);
    // Teeth no sharper than 40°.
    let step = random.range(height * 2.0 * 20f64.to_radians().tan(), height * 1.5);
    let teeth = (3 + random.index(6))
        .min((650.0 / (2.0 * step)) as usize)
        .max(2);
    polyline(
        (0..=2 * teeth)
            .map(|i| p(step * i as f64, if i % 2 == 0 { height } else { 0.0 }))
            .collect(),
    )
}

fn square_wave(hand: &Hand, random: &mut SplitMix64) -> Shape {
    let height = random.range((5.0 * hand.pen).max(20.0), 70.0);
    let width = random.range((5.0 * hand.pen).max(20.0), 70.0);
    let periods = 2 + random.index(4);
    let mut points = vec![p(0.0, 0.0)];
    for i in 0..periods {
        let x = 2.0 * width * i as f64;
        points.extend([p(x, height), p(x + width, height), p(x + width, 0.0)]);
        points.push(p(x + 2.0 * width, 0.0));
    }
    polyline(points)
}

/// 2–5 shapes of one kind inside each other, 1.5–3 (gap + pen) apart, sometimes off centre.
pub fn nested(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let spacing = (random.range(1.5, 3.0) * (hand.gap.1 + hand.pen)).max(10.0);
    // As many as fit within a radius of 300 px (a square of that size turned 45° still fits).
    let count = (2 + random.index(4)).min(((270.0 / spacing) as usize).max(2));
    let outer = random
        .range(
            (count as f64 * spacing + 25.0).max(60.0),
            (count as f64 * spacing + 60.0).max(220.0),
        )
        .min(300.0);
    let aspect = random.range(0.55, 1.0);
    let kind = random.index(5);
    let sides = 3 + random.index(4);
    let off_centre = random.chance(0.4);
    let bumps = blob(Point::ORIGIN, outer, 0.15, random);
    let mut shapes = Vec::new();
    let mut centre = Point::ORIGIN;
    for index in 0..count {
        let r = outer - spacing * index as f64;
        if r < 12.0 {
            break;
        }
        if off_centre && index > 0 {
            // Drift by at most a third of the spacing, so neighbours stay apart.
            centre += Vec2::from_angle(any_angle(random)) * (spacing / 3.0);
        }
        let at = Affine::translate(centre.to_vec2());
        let shape = match kind {
            0 => ellipse(
                centre,
                r,
                (outer * aspect - spacing * index as f64).max(8.0),
                0.0,
                any_angle(random),
            ),
            1 => {
                let (w, h) = (r, outer * aspect - spacing * index as f64);
                polygon(vec![p(-w, -h), p(w, -h), p(w, h), p(-w, h)]).transformed(at)
            }
            2 => {
                // A regular polygon whose sides stay `spacing` apart: the circumradius shrinks
                // by spacing / cos(π / sides).
                let radius = outer - spacing * index as f64 / (PI / sides as f64).cos();
                star(centre, radius, sides, PI - TAU / sides as f64, -FRAC_PI_2)
            }
            3 => rounded_rectangle(r, outer * aspect - spacing * index as f64, 0.3 * r)
                .transformed(at),
            _ => bumps.transformed(at * Affine::scale(r / outer)),
        };
        shapes.push(shape);
    }
    Figure::of(shapes).rotated(any_angle(random))
}

fn rounded_rectangle(half_width: f64, half_height: f64, radius: f64) -> Shape {
    let r = radius.min(half_width).min(half_height.max(1.0));
    let (w, h) = (half_width - r, half_height.max(r) - r);
    let mut builder = Builder::start(p(-w, -h - r));
    builder.line_to(p(w, -h - r));
    builder.arc(p(w, -h), r, -FRAC_PI_2, 0.0);
    builder.line_to(p(w + r, h));
    builder.arc(p(w, h), r, 0.0, FRAC_PI_2);
    builder.line_to(p(-w, h + r));
    builder.arc(p(-w, h), r, FRAC_PI_2, PI);
    builder.line_to(p(-w - r, -h));
    builder.arc(p(-w, -h), r, PI, 1.5 * PI);
    builder.closed()
}

/// A page of 3–7 everyday objects: houses, suns with rays, clouds, hearts, leaves, moons,
/// fish, balloons, mountains, stars, blobs and waves.
pub fn objects(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let hand = *hand;
    let count = 3 + random.index(5);
    let figures = (0..count)
        .map(|_| {
            let size = random.range((12.0 * hand.pen).max(60.0), 170.0);
            let figure = match random.index(11) {
                0 => house(size, random),
                1 => sun(size, &hand, random),
                2 => cloud(size, random),
                3 => heart(size),
                4 => leaf(size, random),
                5 => moon(size, random),
                6 => fish(size, random),
                7 => balloon(size, random),
                8 => Figure::of(vec![line(&[
                    (0.0, size * 0.6),
                    (size * 0.35, 0.0),
                    (size * 0.55, size * 0.3),
                    (size * 0.75, size * 0.1),
                    (size * 1.2, size * 0.6),
                ])]),
                9 => Figure::of(vec![star(Point::ORIGIN, size / 2.0, 5, 0.6, -FRAC_PI_2)]),
                _ => Figure::of(vec![blob(Point::ORIGIN, size / 2.0, 0.3, random)]),
            };
            figure.rotated(random.range(-0.3, 0.3))
        })
        .collect();
    let spacing = object_spacing(&hand, random);
    fit_on_page(figures, spacing, random)
}

fn house(size: f64, random: &mut SplitMix64) -> Figure {
    let (w, h) = (size, size * random.range(0.6, 0.9));
    let roof = size * random.range(0.3, 0.6);
    let mut figure = Figure::of(vec![polygon(vec![
        p(0.0, h),
        p(0.0, 0.0),
        p(w / 2.0, -roof),
        p(w, 0.0),
        p(w, h),
    ])]);
    if size > 80.0 {
        let (x, y, s) = (w * 0.15, h * 0.2, w * 0.25);
        figure.extend(Figure::of(vec![polygon(vec![
            p(x, y),
            p(x + s, y),
            p(x + s, y + s),
            p(x, y + s),
        ])]));
        if random.chance(0.6) {
            // A door standing on the floor line: its ends touch the wall (T-junctions).
            let (x0, x1) = (w * 0.6, w * 0.82);
            figure.extend(Figure::of(vec![line(&[
                (x0, h),
                (x0, h * 0.45),
                (x1, h * 0.45),
                (x1, h),
            ])]));
        }
    }
    figure
}

fn sun(size: f64, hand: &Hand, random: &mut SplitMix64) -> Figure {
    let r = size * 0.3;
    let mut figure = Figure::of(vec![ellipse(Point::ORIGIN, r, r, 0.0, any_angle(random))]);
    let rays = 6 + random.index(5);
    let start = r + 2.0 * (hand.gap.1 + hand.pen);
    let length = (size * 0.5 - start).max(3.0 * hand.pen + 12.0);
    let turn = any_angle(random);
    for i in 0..rays {
        let direction = Vec2::from_angle(turn + TAU * i as f64 / rays as f64);
        figure.extend(Figure::of(vec![polyline(vec![
            Point::ORIGIN + direction * start,
            Point::ORIGIN + direction * (start + length),
        ])]));
    }
    figure
}

fn cloud(size: f64, random: &mut SplitMix64) -> Figure {
    let bumps = 3 + random.index(3);
    let width = size * 1.3;
    let mut builder = Builder::start(p(0.0, 0.0));
    let step = width / bumps as f64;
    for i in 0..bumps {
        let centre = p(step * (i as f64 + 0.5), 0.0);
        builder.arc(centre, step / 2.0 * random.range(1.0, 1.15), PI, TAU);
    }
    builder.line_to(p(width, size * 0.1));
    builder.line_to(p(0.0, size * 0.1));
    Figure::of(vec![builder.closed()])
}

fn heart(size: f64) -> Figure {
    let points = (0..600)
        .map(|i| {
            let t = TAU * i as f64 / 600.0;
            let x = 16.0 * t.sin().powi(3);
            let y =
                13.0 * t.cos() - 5.0 * (2.0 * t).cos() - 2.0 * (3.0 * t).cos() - (4.0 * t).cos();
            p(x * size / 34.0, -y * size / 34.0)
        })
        .collect();
    Figure::of(vec![polygon(points)])
}

fn leaf(size: f64, random: &mut SplitMix64) -> Figure {
    let bulge = size * random.range(0.2, 0.35);
    let mut points: Vec<Point> = (0..=100)
        .map(|i| {
            let t = i as f64 / 100.0;
            p(size * t, -bulge * 4.0 * t * (1.0 - t))
        })
        .collect();
    points.extend((1..100).rev().map(|i| {
        let t = i as f64 / 100.0;
        p(size * t, bulge * 4.0 * t * (1.0 - t))
    }));
    Figure::of(vec![polygon(points)])
}

fn moon(size: f64, random: &mut SplitMix64) -> Figure {
    let r = size / 2.0;
    let inner = r * random.range(1.1, 1.5);
    let offset = r * random.range(0.45, 0.7);
    // The outer circle's arc outside the inner one, and the inner arc back: two sharp tips.
    let (top, bottom) = circle_crossings(r, inner, offset);
    let mut builder = Builder::start(p(r * top.cos(), r * top.sin()));
    builder.arc(Point::ORIGIN, r, top, bottom + TAU);
    let centre = p(offset, 0.0);
    let from = (p(r * bottom.cos(), r * bottom.sin()) - centre).atan2();
    let to = (p(r * top.cos(), r * top.sin()) - centre).atan2();
    builder.arc(centre, inner, from, if to < from { to + TAU } else { to });
    Figure::of(vec![builder.closed()])
}

/// Angles on the circle of radius `r` around the origin where it meets the circle of radius
/// `other` around `(offset, 0)`: (upper, lower).
fn circle_crossings(r: f64, other: f64, offset: f64) -> (f64, f64) {
    let x = (r * r - other * other + offset * offset) / (2.0 * offset);
    let angle = (x / r).clamp(-1.0, 1.0).acos();
    (angle, -angle)
}

fn fish(size: f64, random: &mut SplitMix64) -> Figure {
    let (rx, ry) = (size * 0.5, size * random.range(0.22, 0.32));
    let tail = size * random.range(0.25, 0.4);
    // Body from the back (the tail's root) round the front, then the tail triangle.
    let root = PI * 0.85;
    // From the lower back round the front to the upper back, then out to the tail and back.
    let mut points = elliptic_arc(0.0, 0.0, rx, ry, root, -root);
    let tail_x = -rx - tail;
    let spread = tail * random.range(0.5, 0.8);
    points.extend([p(tail_x, -spread), p(tail_x, spread)]);
    Figure::of(vec![polygon(points)])
}

fn balloon(size: f64, random: &mut SplitMix64) -> Figure {
    let (rx, ry) = (size * 0.3, size * 0.38);
    let mut figure = Figure::of(vec![ellipse(Point::ORIGIN, rx, ry, 0.0, any_angle(random))]);
    // The string hangs from the balloon's bottom (one end touches the outline).
    let sway = size * random.range(-0.15, 0.15);
    let string: Vec<Point> = (0..=40)
        .map(|i| {
            let t = i as f64 / 40.0;
            p(sway * (PI * t).sin(), ry + size * 0.6 * t)
        })
        .collect();
    figure.extend(Figure::of(vec![polyline(string)]));
    figure
}

/// Isolated dots of 1–3 pen widths: periods after words, dotted i's, dotted lines and loose dots.
pub fn dots(hand: &mut Hand, random: &mut SplitMix64) -> Figure {
    let hand = *hand;
    several(2 + random.index(2), &hand, random, |random| {
        match random.index(4) {
            0 => words_with_periods(&hand, random),
            1 => dotted_is(&hand, random),
            2 => dotted_line(&hand, random),
            _ => loose_dots(&hand, random),
        }
    })
}

fn words_with_periods(hand: &Hand, random: &mut SplitMix64) -> Figure {
    let mut figure = Figure::default();
    let mut x = 0.0;
    for _ in 0..2 + random.index(3) {
        let length = random.range(35.0, 100.0);
        let height = random.range(6.0, 14.0).max(2.0 * hand.pen);
        let wavelength = random.range(12.0, 25.0).max(4.0 * hand.pen);
        let steps = (length * 2.0) as usize;
        let word: Vec<Point> = (0..=steps)
            .map(|i| {
                let u = length * i as f64 / steps as f64;
                p(
                    x + u,
                    -height / 2.0 - height / 2.0 * (TAU * u / wavelength).cos(),
                )
            })
            .collect();
        figure.extend(Figure::of(vec![polyline(word)]));
        x += length;
        let period = dot(p(0.0, 0.0), hand.pen, random);
        let away = period.diameter / 2.0 + hand.pen / 2.0 + random.range(1.0, 3.0) * hand.pen;
        if random.chance(0.6) {
            figure.dots.push(super::figure::Dot {
                centre: p(x + away, -period.diameter / 2.0 + hand.pen / 2.0),
                ..period
            });
        }
        x += away + period.diameter + 2.5 * (hand.gap.1 + hand.pen);
    }
    figure
}

fn dotted_is(hand: &Hand, random: &mut SplitMix64) -> Figure {
    let mut figure = Figure::default();
    let mut x = 0.0;
    for _ in 0..2 + random.index(4) {
        let stem = random.range(20.0, 50.0).max(6.0 * hand.pen);
        figure.extend(Figure::of(vec![line(&[(x, 0.0), (x, -stem)])]));
        let mut i_dot = dot(Point::ORIGIN, hand.pen, random);
        let away = i_dot.diameter / 2.0 + hand.pen / 2.0 + random.range(1.5, 3.5) * hand.pen;
        i_dot.centre = p(x + random.range(-0.5, 0.5) * hand.pen, -stem - away);
        figure.dots.push(i_dot);
        x += random.range(2.5, 4.0) * (hand.gap.1 + hand.pen) + i_dot.diameter;
    }
    figure
}

fn dotted_line(hand: &Hand, random: &mut SplitMix64) -> Figure {
    let mut figure = Figure::default();
    let diameter = hand.pen * random.range(1.0, 3.0);
    let spacing = diameter + random.range((1.5 * diameter).max(2.0 * hand.pen), 5.0 * diameter);
    let count = 5 + random.index(8);
    let bend = random.range(-0.4, 0.4) / (spacing * count as f64);
    let mut position = Point::ORIGIN;
    let mut heading: f64 = 0.0;
    for _ in 0..count {
        figure.dots.push(super::figure::Dot {
            centre: position,
            diameter: diameter * random.range(0.85, 1.15),
        });
        position += Vec2::from_angle(heading) * spacing;
        heading += bend * spacing;
    }
    figure
}

fn loose_dots(hand: &Hand, random: &mut SplitMix64) -> Figure {
    let mut figure = Figure::default();
    let apart = 4.0 * (hand.gap.1 + hand.pen);
    let count = 3 + random.index(6);
    let columns = 3;
    for i in 0..count {
        let cell = p((i % columns) as f64 * apart, (i / columns) as f64 * apart);
        let wiggle = Vec2::new(random.range(0.0, 0.3), random.range(0.0, 0.3)) * apart;
        figure.dots.push(dot(cell + wiggle, hand.pen, random));
    }
    figure
}
