//! What the samples show: each scene is a list of true curves in image pixel coordinates, made of
//! SVG path data, ellipses, polygons and sampled functions.

use std::f64::consts::{PI, TAU};

use kurbo::{Affine, BezPath, Ellipse, ParamCurve, ParamCurveDeriv, Point, Shape};

use super::geometry::TrueCurve;

/// A scene and the canvas it was laid out for.
pub struct Scene {
    /// Canvas width in pixels.
    pub width: u32,
    /// Canvas height in pixels.
    pub height: u32,
    /// The true curves.
    pub curves: Vec<TrueCurve>,
}

fn scene(width: u32, height: u32, curves: Vec<Vec<TrueCurve>>) -> Scene {
    Scene {
        width,
        height,
        curves: curves.into_iter().flatten().collect(),
    }
}

/// Path data moved by `(dx, dy)`.
fn path_at(data: &str, dx: f64, dy: f64) -> Vec<TrueCurve> {
    let mut path = BezPath::from_svg(data).expect("scene path data is valid");
    path.apply_affine(Affine::translate((dx, dy)));
    TrueCurve::from_path(&path)
}

fn ellipse(cx: f64, cy: f64, rx: f64, ry: f64, rotation_degrees: f64) -> Vec<TrueCurve> {
    let shape = Ellipse::new((cx, cy), (rx, ry), rotation_degrees.to_radians());
    let mut path = shape.to_path(0.01);
    // kurbo's ellipse ends back at its start without a ClosePath; the truth needs the Z.
    path.close_path();
    TrueCurve::from_path(&path)
}

fn circle(cx: f64, cy: f64, r: f64) -> Vec<TrueCurve> {
    ellipse(cx, cy, r, r, 0.0)
}

fn polygon(vertices: &[(f64, f64)]) -> Vec<TrueCurve> {
    vec![TrueCurve::from_points(
        vertices.iter().map(|&p| p.into()).collect(),
        true,
    )]
}

fn open_polyline(vertices: &[(f64, f64)]) -> Vec<TrueCurve> {
    vec![TrueCurve::from_points(
        vertices.iter().map(|&p| p.into()).collect(),
        false,
    )]
}

/// A regular polygon or, with `inner_radius`, a star; one vertex points up.
fn star(centre: (f64, f64), outer: f64, inner: Option<f64>, tips: usize) -> Vec<TrueCurve> {
    let count = if inner.is_some() { 2 * tips } else { tips };
    let vertices: Vec<(f64, f64)> = (0..count)
        .map(|i| {
            let radius = if i % 2 == 1 {
                inner.unwrap_or(outer)
            } else {
                outer
            };
            let angle = -PI / 2.0 + TAU * i as f64 / count as f64;
            (
                centre.0 + radius * angle.cos(),
                centre.1 + radius * angle.sin(),
            )
        })
        .collect();
    polygon(&vertices)
}

/// An open curve through `function(t)` for `t` in 0..=1, sampled finely enough to be smooth.
fn sampled(samples: usize, function: impl Fn(f64) -> Point) -> Vec<TrueCurve> {
    let points = (0..=samples)
        .map(|i| function(i as f64 / samples as f64))
        .collect();
    vec![TrueCurve::from_points(points, false)]
}

/// "A", "B" and "O" as outlines with their holes (counters).
pub fn letters() -> Scene {
    let a_outer = "M0 320 L96 0 L144 0 L240 320 L182.4 320 L158.4 236.8 L81.6 236.8 L57.6 320 Z";
    let a_hole = "M96 179.2 L120 83.2 L144 179.2 Z";
    let b_outer = "M0 0 L100 0 C150 0 180 30 180 72 C180 110 155 140 125 150 \
                   C165 160 195 195 195 235 C195 285 160 320 110 320 L0 320 Z";
    let b_upper_hole = "M45 45 L95 45 C120 45 130 58 130 75 C130 92 120 105 95 105 L45 105 Z";
    let b_lower_hole = "M45 190 L105 190 C135 190 150 210 150 240 C150 265 135 280 105 280 \
                        L45 280 Z";
    scene(
        860,
        420,
        vec![
            path_at(a_outer, 40.0, 50.0),
            path_at(a_hole, 40.0, 50.0),
            path_at(b_outer, 345.0, 50.0),
            path_at(b_upper_hole, 345.0, 50.0),
            path_at(b_lower_hole, 345.0, 50.0),
            ellipse(715.0, 210.0, 105.0, 160.0, 0.0),
            ellipse(715.0, 210.0, 55.0, 105.0, 0.0),
        ],
    )
}

/// Silhouettes with thin parts: a wine glass (16 px stem, 15 px foot) and a key with a bow, a hole
/// and a 22 px shaft with teeth.
pub fn silhouettes() -> Scene {
    let glass = "M140 60 L260 60 C265 150 255 250 208 285 L208 460 C211 480 250 490 290 500 \
                 L290 515 L110 515 L110 500 C150 490 189 480 192 460 L192 285 \
                 C145 250 135 150 140 60 Z";
    let key = "M539.13 289 L760 289 L760 335 L735 335 L735 311 L712 311 L712 330 L690 330 \
               L690 311 L539.13 311 A70 70 0 1 1 539.13 289 Z";
    scene(
        800,
        600,
        vec![
            path_at(glass, 0.0, 0.0),
            path_at(key, 0.0, 0.0),
            circle(455.0, 300.0, 28.0),
        ],
    )
}

/// A five-pointed star and a circle.
pub fn star_and_circle() -> Scene {
    scene(
        700,
        400,
        vec![
            star((190.0, 205.0), 160.0, Some(64.0), 5),
            circle(515.0, 200.0, 150.0),
        ],
    )
}

/// An oval face: closed eyes and head, open brows, nose and smiling mouth.
pub fn face() -> Scene {
    scene(
        500,
        500,
        vec![
            ellipse(250.0, 255.0, 190.0, 215.0, 0.0),
            ellipse(180.0, 200.0, 30.0, 20.0, 0.0),
            ellipse(320.0, 200.0, 30.0, 20.0, 0.0),
            path_at("M140 160 C160 140 200 140 220 152", 0.0, 0.0),
            path_at("M280 152 C300 140 340 140 360 160", 0.0, 0.0),
            path_at(
                "M250 225 C238 262 232 292 252 300 C262 304 272 300 278 294",
                0.0,
                0.0,
            ),
            path_at("M160 350 Q250 420 340 350", 0.0, 0.0),
        ],
    )
}

/// A round face: circle eyes, straight brows, a nose with a sharp bend, a wavy open mouth.
pub fn round_face() -> Scene {
    scene(
        500,
        500,
        vec![
            circle(250.0, 250.0, 205.0),
            circle(175.0, 195.0, 24.0),
            circle(325.0, 195.0, 24.0),
            open_polyline(&[(145.0, 150.0), (205.0, 138.0)]),
            open_polyline(&[(295.0, 138.0), (355.0, 150.0)]),
            open_polyline(&[(250.0, 215.0), (228.0, 290.0), (265.0, 290.0)]),
            path_at("M165 360 C205 330 250 395 335 352", 0.0, 0.0),
        ],
    )
}

/// Open curves: an Archimedean spiral, a sine wave, a damped wave and a zigzag.
pub fn spiral_and_waves() -> Scene {
    let spiral = sampled(8000, |t| {
        let angle = t * 4.5 * TAU;
        let radius = 14.0 + 24.0 * angle / TAU;
        Point::new(200.0 + radius * angle.cos(), 250.0 + radius * angle.sin())
    });
    let sine = sampled(4000, |t| {
        let x = 390.0 + 380.0 * t;
        Point::new(x, 110.0 + 35.0 * (TAU * (x - 390.0) / 95.0).sin())
    });
    let damped = sampled(4000, |t| {
        let x = 390.0 + 380.0 * t;
        let envelope = 50.0 * (-(x - 390.0) / 200.0).exp();
        Point::new(x, 250.0 + envelope * (TAU * (x - 390.0) / 70.0).sin())
    });
    let zigzag: Vec<(f64, f64)> = (0..=12)
        .map(|i| {
            let y = if i % 2 == 0 { 420.0 } else { 360.0 };
            (390.0 + 31.5 * i as f64, y)
        })
        .collect();
    scene(800, 500, vec![spiral, sine, damped, open_polyline(&zigzag)])
}

/// Four nested ellipses and a circle at their centre.
pub fn nested_ellipses() -> Scene {
    let (cx, cy) = (350.0, 250.0);
    scene(
        700,
        500,
        vec![
            ellipse(cx, cy, 310.0, 215.0, 0.0),
            ellipse(cx, cy, 250.0, 165.0, 0.0),
            ellipse(cx, cy, 190.0, 115.0, 0.0),
            ellipse(cx, cy, 130.0, 65.0, 0.0),
            circle(cx, cy, 20.0),
        ],
    )
}

/// Squares and triangles with sharp corners, one square tilted, one with a square hole.
pub fn squares_and_triangles() -> Scene {
    let tilted: Vec<(f64, f64)> = [(-80.0, -80.0), (80.0, -80.0), (80.0, 80.0), (-80.0, 80.0)]
        .iter()
        .map(|&(x, y)| {
            let rotated = Affine::rotate(25f64.to_radians()) * Point::new(x, y);
            (440.0 + rotated.x, 150.0 + rotated.y)
        })
        .collect();
    scene(
        800,
        500,
        vec![
            polygon(&[(50.0, 50.0), (250.0, 50.0), (250.0, 250.0), (50.0, 250.0)]),
            polygon(&tilted),
            polygon(&[(580.0, 228.0), (780.0, 228.0), (680.0, 55.0)]),
            polygon(&[(60.0, 300.0), (60.0, 460.0), (300.0, 460.0)]),
            polygon(&[(340.0, 460.0), (560.0, 460.0), (600.0, 310.0)]),
            polygon(&[
                (640.0, 290.0),
                (770.0, 290.0),
                (770.0, 470.0),
                (640.0, 470.0),
            ]),
            polygon(&[
                (680.0, 330.0),
                (730.0, 330.0),
                (730.0, 430.0),
                (680.0, 430.0),
            ]),
        ],
    )
}

/// Several separate objects: a house with a window, the sun, a cloud, two birds in one stroke
/// line, a leaf and a heart.
pub fn objects() -> Scene {
    let cloud = "M380 190 A40 40 0 0 1 420 130 A55 55 0 0 1 520 110 A45 45 0 0 1 600 150 \
                 A35 35 0 0 1 590 215 L390 215 A25 25 0 0 1 380 190 Z";
    let leaf = "M360 470 Q470 340 620 430 Q480 540 360 470 Z";
    let heart = "M770 570 C700 520 650 470 660 420 C670 370 740 365 770 415 \
                 C800 365 870 370 880 420 C890 470 840 520 770 570 Z";
    scene(
        900,
        600,
        vec![
            polygon(&[
                (60.0, 560.0),
                (60.0, 330.0),
                (170.0, 220.0),
                (280.0, 330.0),
                (280.0, 560.0),
            ]),
            polygon(&[
                (115.0, 390.0),
                (225.0, 390.0),
                (225.0, 470.0),
                (115.0, 470.0),
            ]),
            circle(800.0, 110.0, 65.0),
            path_at(cloud, 0.0, 0.0),
            path_at("M630 270 Q660 245 690 270 Q720 245 750 270", 0.0, 0.0),
            path_at(leaf, 0.0, 0.0),
            path_at(heart, 0.0, 0.0),
        ],
    )
}

/// A crescent moon, a drop and a lightning bolt: corners at thin tips.
pub fn weather() -> Scene {
    let crescent = "M160 60 A140 140 0 0 0 160 340 A175 175 0 0 1 160 60 Z";
    let drop = "M320 70 C320 70 390 180 390 240 A70 70 0 0 1 250 240 C250 180 320 70 320 70 Z";
    scene(
        600,
        400,
        vec![
            path_at(crescent, 0.0, 0.0),
            path_at(drop, 0.0, 0.0),
            polygon(&[
                (470.0, 40.0),
                (560.0, 40.0),
                (520.0, 150.0),
                (580.0, 150.0),
                (450.0, 360.0),
                (490.0, 200.0),
                (430.0, 200.0),
            ]),
        ],
    )
}

/// A hexagon, a circle, an open S curve and a rounded rectangle (smooth, so no corners).
pub fn shapes() -> Scene {
    let rounded = kurbo::RoundedRect::new(370.0, 350.0, 540.0, 530.0, 30.0);
    scene(
        600,
        600,
        vec![
            star((160.0, 170.0), 110.0, None, 6),
            circle(440.0, 160.0, 110.0),
            path_at(
                "M80 420 C80 340 200 340 200 420 C200 500 320 500 320 420",
                0.0,
                0.0,
            ),
            TrueCurve::from_path(&rounded.to_path(0.01)),
        ],
    )
}

/// Pen width of the clean style, which `touching_parts` is drawn for: its narrow parts are
/// measured in it.
const CLEAN_PEN: f64 = 3.0;

/// Silhouettes whose outline comes back within a pen width of itself (issue 9): a sitting cat
/// whose tail tapers from 3 pen widths at the haunch to a point (on its last third its sides are
/// less than a pen width apart, so their ink is one band), and a fork whose four tines have
/// their sides half a pen width apart (each tine's ink is one band). Not on the benchmark page
/// ([`all`]), so that the page and the speed measured on it stay as they were.
pub fn touching_parts() -> Scene {
    scene(800, 500, vec![sitting_cat(), fork()])
}

/// The vertices of `path` flattened, in order (one subpath, no `Z`).
fn flattened(data: &str) -> Vec<Point> {
    let path = BezPath::from_svg(data).expect("scene path data is valid");
    let mut points = Vec::new();
    kurbo::flatten(&path, 0.01, |element| match element {
        kurbo::PathEl::MoveTo(point) | kurbo::PathEl::LineTo(point) => points.push(point),
        _ => unreachable!("one open subpath flattens to lines"),
    });
    points
}

/// A cat sitting on the ground, facing left, with pointed ears; its tail leaves the haunch just
/// above the ground and curls up, tapering to a point.
fn sitting_cat() -> Vec<TrueCurve> {
    let tail_base = Point::new(322.0, 424.5);
    let tail_base_half_width = 1.5 * CLEAN_PEN;
    let tail = kurbo::CubicBez::new(
        tail_base,
        Point::new(380.0, 436.0),
        Point::new(440.0, 442.0),
        Point::new(468.0, 398.0),
    );
    let head_and_back = flattened(&format!(
        "M100 60 L138 108 Q165 100 190 108 L222 66 L228 130 \
         C240 165 235 195 218 215 C265 235 305 285 318 345 \
         C326 380 330 405 {} {}",
        tail_base.x,
        tail_base.y - tail_base_half_width
    ));
    let front = flattened(&format!(
        "M{} {} C322 434 321 438 316 440 L112 440 C100 400 112 300 138 242 \
         C108 232 92 195 96 150",
        tail_base.x,
        tail_base.y + tail_base_half_width
    ));
    // The tail's sides, out along its upper side and back along its lower one.
    const TAIL_SAMPLES: usize = 400;
    let side = |t: f64, sign: f64| {
        let tangent = tail.deriv().eval(t).to_vec2().normalize();
        let up = kurbo::Vec2::new(tangent.y, -tangent.x);
        tail.eval(t) + up * (sign * tail_base_half_width * (1.0 - t))
    };
    let upper = (1..TAIL_SAMPLES).map(|k| side(k as f64 / TAIL_SAMPLES as f64, 1.0));
    let lower = (1..TAIL_SAMPLES)
        .rev()
        .map(|k| side(k as f64 / TAIL_SAMPLES as f64, -1.0));
    let outline: Vec<Point> = head_and_back
        .into_iter()
        .chain(upper)
        .chain(std::iter::once(tail.p3))
        .chain(lower)
        .chain(front)
        .collect();
    vec![TrueCurve::from_points(outline, true)]
}

/// A fork standing on its handle's rounded end, four tines up: each tine's sides are half a pen
/// width apart (centre to centre) with a round tip; the slots between tines end in half circles.
fn fork() -> Vec<TrueCurve> {
    let half_tine = CLEAN_PEN / 4.0;
    let tine_centres = [570.0, 593.0, 616.0, 639.0];
    let (tips_y, slots_y) = (70.0, 165.0);
    let mut outline = format!("M{} 190", tine_centres[0] - half_tine);
    for (k, &x) in tine_centres.iter().enumerate() {
        let (left, right) = (x - half_tine, x + half_tine);
        outline += &format!(" L{left} {tips_y} A{half_tine} {half_tine} 0 0 1 {right} {tips_y}");
        if let Some(&next) = tine_centres.get(k + 1) {
            let slot_radius = (next - half_tine - right) / 2.0;
            outline += &format!(
                " L{right} {slots_y} A{slot_radius} {slot_radius} 0 0 0 {} {slots_y}",
                next - half_tine
            );
        }
    }
    let right_edge = tine_centres[3] + half_tine;
    let left_edge = tine_centres[0] - half_tine;
    outline += &format!(
        " L{right_edge} 190 C{right_edge} 225 616 232 614 260 L614 430 \
         A10 10 0 0 1 594 430 L594 260 C592 232 {left_edge} 225 {left_edge} 190 Z"
    );
    path_at(&outline, 0.0, 0.0)
}

/// Every scene, for the large page.
pub fn all() -> Vec<Scene> {
    vec![
        letters(),
        silhouettes(),
        star_and_circle(),
        face(),
        round_face(),
        spiral_and_waves(),
        nested_ellipses(),
        squares_and_triangles(),
        objects(),
        weather(),
        shapes(),
    ]
}
