//! Dots: the marks a pen leaves when it touches the paper without moving (periods, the dot of an
//! i, dotted lines). A dot is told by its ink, a round piece (its shape from the second moments
//! of its pixels, as in M.-K. Hu, "Visual pattern recognition by moment invariants", IRE Trans.
//! Information Theory 8, 1962), around a skeleton that is a point or a stub; dots are kept as
//! dots, never bridged into a stroke and never dropped as stray marks.

use std::collections::HashSet;

use kurbo::{Point, Vec2};

use super::{Stroke, StrokeEnd};
use crate::geometry::grid::PointGrid;
use crate::geometry::polyline::polyline_length;
use crate::raster::bitmap::{Bitmap, NEIGHBOUR_OFFSETS};

/// A dot: where it is and how wide its ink is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dot {
    /// The centroid of its ink.
    pub centre: Point,
    /// The diameter of a disc of its ink's area, in pixels.
    pub diameter: f64,
}

/// DECISION: a mark is a dot when it is at most 1.5 times as long as it is wide, measured on its
/// ink: the square root of the ratio of the principal second moments of its pixels (each pixel a
/// unit square), which is length / width for a rectangle or an ellipse. A dash drawn with the
/// pen is at least about twice as long as wide. The ink is measured, not the skeleton: thinning
/// a round dot 2–3 px across leaves a stub of up to three pixels, as long as the dot is wide.
const DOT_MAX_ELONGATION: f64 = 1.5;

/// Ties count as round: a 3 × 2 pixel blob, how a round dot 2–3 px across is often binarized,
/// is exactly 1.5 times as long as wide, and its moments must not miss that by a rounding error.
const ELONGATION_TIE: f64 = 1e-9;

/// A mark whose skeleton is longer than this many times its width (the diameter of a disc of
/// its area) is a curled stroke (a tiny "c" or hook, round by its moments), not a dot. A dot's
/// skeleton is a point or a stub within it.
const DOT_MAX_SKELETON_IN_WIDTHS: f64 = 1.0;

/// DECISION: no dot is wider than this (pen widths; a disc of this diameter bounds its area).
/// Dots are 1–3 pen widths wide; a round blot twice that is still written as a dot. The bound
/// keeps the ink of a short stroke from being filled when it belongs to a web of ink over the
/// whole page (a page of noise took 280 s without it, 20 s with it).
const DOT_MAX_DIAMETER_IN_PEN_WIDTHS: f64 = 6.0;

/// Dots are 1–3 pen widths wide: a stroke whose skeleton is longer than this many pen widths is
/// no dot, and its ink is not measured.
const DOT_MAX_SKELETON_IN_PEN_WIDTHS: f64 = 3.0;

/// Takes the dots out of `strokes`: free-ended open strokes whose ink is a round mark
/// (`DOT_MAX_ELONGATION`) around a skeleton no longer than the mark is wide
/// (`DOT_MAX_SKELETON_IN_WIDTHS`). The others are returned in order.
pub fn split_dots(
    strokes: Vec<Stroke>,
    mask: &Bitmap,
    stroke_width: f64,
) -> (Vec<Stroke>, Vec<Dot>) {
    let longest_skeleton = DOT_MAX_SKELETON_IN_PEN_WIDTHS * stroke_width.max(1.0);
    let widest = DOT_MAX_DIAMETER_IN_PEN_WIDTHS * stroke_width.max(1.0);
    let largest_area = std::f64::consts::FRAC_PI_4 * widest * widest;
    let as_dots: Vec<Option<Dot>> = strokes
        .iter()
        .map(|stroke| as_dot(stroke, mask, longest_skeleton, largest_area))
        .collect();
    let tips = pieces_ends_point_at(&strokes, &as_dots, stroke_width);
    let mut kept = Vec::with_capacity(strokes.len());
    let mut dots = Vec::new();
    for ((stroke, dot), tip) in strokes.into_iter().zip(as_dots).zip(tips) {
        match dot {
            Some(dot) if !tip => dots.push(dot),
            _ => kept.push(stroke),
        }
    }
    (kept, dots)
}

/// A free end points at a round mark when the mark's centre lies within this many pen widths of
/// the end, beyond the mark's rim ([`pieces_ends_point_at`]).
const TIP_PIECE_REACH_IN_PEN_WIDTHS: f64 = 4.0;

/// ... and within this angle (degrees) of the way the end points.
const TIP_PIECE_AIM_MAX_DEGREES: f64 = 30.0;

/// ... and two such ends lie at least this many pen widths apart: two lines, not the forked top
/// of one (an "i"'s stem whose top split into two spurs both pointing at its dot).
const TIP_PIECE_MIN_ENDS_APART_IN_PEN_WIDTHS: f64 = 2.0;

/// An end's way is read over this many pen widths of its stroke.
const END_WAY_IN_PEN_WIDTHS: f64 = 2.0;

/// DECISION: (stop 60) a round mark that free ends of two lines point at
/// ([`TIP_PIECE_REACH_IN_PEN_WIDTHS`], [`TIP_PIECE_AIM_MAX_DEGREES`],
/// [`TIP_PIECE_MIN_ENDS_APART_IN_PEN_WIDTHS`]) is no dot but the piece of a corner between two
/// pen lifts: the tip of an "A" whose pen lifts fell on both legs just below it left a wedge of
/// ink 8 px across, round by its moments, and as a dot it stood apart while the legs were
/// bridged flat beneath it. Kept as a stroke, the legs go on through it. A dot stands alone: at
/// most one line points at it (an "i"'s stem, a word before its period). Measured on the
/// benchmark (exact of 432): no development drawing gained or lost (that "A" is mended, its page
/// fails on a "P"; it is the only development output that changes), validation +1, seed 4
/// unchanged; within 3 pen widths validation is unchanged, within 6 the same as 4, at 20° and
/// 45° the same as 30°; without the ends' distance apart, seed 7 loses an "i" whose stem's top
/// forked.
fn pieces_ends_point_at(
    strokes: &[Stroke],
    as_dots: &[Option<Dot>],
    stroke_width: f64,
) -> Vec<bool> {
    let pen = stroke_width.max(1.0);
    let aim = TIP_PIECE_AIM_MAX_DEGREES.to_radians().cos();
    let apart = TIP_PIECE_MIN_ENDS_APART_IN_PEN_WIDTHS * pen;
    // The free ends of the strokes that are no dots, in cells as wide as the farthest reach (a
    // dot is at most [`DOT_MAX_DIAMETER_IN_PEN_WIDTHS`] wide), so that each dot looks only at
    // those around it: a page of noise has thousands of dots and hundreds of thousands of ends.
    let mut grid = PointGrid::new(
        (TIP_PIECE_REACH_IN_PEN_WIDTHS + DOT_MAX_DIAMETER_IN_PEN_WIDTHS / 2.0) * pen,
    );
    let ends = strokes
        .iter()
        .zip(as_dots)
        .filter(|(stroke, dot)| dot.is_none() && !stroke.line.closed)
        .flat_map(|(stroke, _)| free_end_ways(stroke, END_WAY_IN_PEN_WIDTHS * pen));
    for (at, way) in ends {
        grid.insert(at, (at, way));
    }
    as_dots
        .iter()
        .map(|dot| {
            let Some(dot) = dot else { return false };
            let reach = TIP_PIECE_REACH_IN_PEN_WIDTHS * pen + dot.diameter / 2.0;
            let aiming: Vec<Point> = grid
                .around(dot.centre)
                .filter(|&&(at, way)| {
                    let to = dot.centre - at;
                    let distance = to.hypot();
                    distance > 0.0 && distance <= reach && way.dot(to / distance) >= aim
                })
                .map(|&(at, _)| at)
                .collect();
            aiming
                .iter()
                .any(|a| aiming.iter().any(|b| a.distance(*b) >= apart))
        })
        .collect()
}

/// The free ends of an open stroke, each with the unit way it points: from the point `arm` back
/// along the stroke to the end (none where the stroke is shorter).
fn free_end_ways(stroke: &Stroke, arm: f64) -> Vec<(Point, Vec2)> {
    let points = &stroke.line.points;
    let mut ways = Vec::new();
    for (k, end) in stroke.ends.iter().enumerate() {
        if *end != StrokeEnd::Free {
            continue;
        }
        let tip = if k == 0 {
            points[0]
        } else {
            points[points.len() - 1]
        };
        let back = if k == 0 {
            points.iter().find(|p| p.distance(tip) >= arm)
        } else {
            points.iter().rev().find(|p| p.distance(tip) >= arm)
        };
        if let Some(&back) = back {
            let way = tip - back;
            ways.push((tip, way / way.hypot()));
        }
    }
    ways
}

fn as_dot(stroke: &Stroke, mask: &Bitmap, longest_skeleton: f64, largest_area: f64) -> Option<Dot> {
    let points = &stroke.line.points;
    if stroke.line.closed || stroke.ends != [StrokeEnd::Free, StrokeEnd::Free] {
        return None;
    }
    let skeleton_length = polyline_length(points, false);
    // Cheap first: a stroke longer than the widest dot is no dot.
    if skeleton_length > longest_skeleton {
        return None;
    }
    // A stroke with two free ends is the whole skeleton of its piece of ink.
    let ink = InkMoments::of_component(mask, *points.first()?, largest_area)?;
    let width = ink.equivalent_diameter();
    // Thinning shrinks a mark to one pixel only when it has no long axis at the pixel grid's
    // resolution (a blob of five pixels in an L is as round as a pixel grid draws a dot 2 px
    // across, though its moments say 1.55).
    let round = points.len() == 1
        || (ink.elongation() <= DOT_MAX_ELONGATION + ELONGATION_TIE
            && skeleton_length <= DOT_MAX_SKELETON_IN_WIDTHS * width);
    round.then(|| Dot {
        centre: ink.centroid(),
        diameter: width,
    })
}

/// The area, centroid and second moments of a piece of ink (an 8-connected component of the
/// mask), each pixel a unit square.
struct InkMoments {
    area: f64,
    sum: Vec2,
    /// Sums of x², y² and x·y over the pixel centres.
    sum_xx: f64,
    sum_yy: f64,
    sum_xy: f64,
}

impl InkMoments {
    /// The moments of the component holding the pixel under `seed`; `None` when it is paper or
    /// has more than `largest_area` pixels (no dot, and not worth filling: a short stroke may be
    /// a piece of a web of ink over the whole page).
    fn of_component(mask: &Bitmap, seed: Point, largest_area: f64) -> Option<Self> {
        let start = (seed.x.floor() as isize, seed.y.floor() as isize);
        if !mask.get_signed(start.0, start.1) {
            return None;
        }
        let mut moments = Self {
            area: 0.0,
            sum: Vec2::ZERO,
            sum_xx: 0.0,
            sum_yy: 0.0,
            sum_xy: 0.0,
        };
        let mut seen = HashSet::from([start]);
        let mut to_visit = vec![start];
        while let Some((x, y)) = to_visit.pop() {
            let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
            moments.area += 1.0;
            if moments.area > largest_area {
                return None;
            }
            moments.sum += Vec2::new(cx, cy);
            moments.sum_xx += cx * cx;
            moments.sum_yy += cy * cy;
            moments.sum_xy += cx * cy;
            for (dx, dy) in NEIGHBOUR_OFFSETS {
                let next = (x + dx, y + dy);
                if mask.get_signed(next.0, next.1) && seen.insert(next) {
                    to_visit.push(next);
                }
            }
        }
        Some(moments)
    }

    fn centroid(&self) -> Point {
        (self.sum / self.area).to_point()
    }

    /// The diameter of a disc of the same area.
    fn equivalent_diameter(&self) -> f64 {
        2.0 * (self.area / std::f64::consts::PI).sqrt()
    }

    /// Length over width: the square root of the ratio of the covariance's eigenvalues, with a
    /// pixel's own spread (1/12 along each axis) added, so that one pixel is round.
    fn elongation(&self) -> f64 {
        let mean = self.sum / self.area;
        let pixel_spread = 1.0 / 12.0;
        let xx = self.sum_xx / self.area - mean.x * mean.x + pixel_spread;
        let yy = self.sum_yy / self.area - mean.y * mean.y + pixel_spread;
        let xy = self.sum_xy / self.area - mean.x * mean.y;
        let half_trace = 0.5 * (xx + yy);
        let spread = (0.25 * (xx - yy).powi(2) + xy * xy).sqrt();
        ((half_trace + spread) / (half_trace - spread).max(f64::MIN_POSITIVE)).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::thin::thin;
    use crate::strokes::extract_strokes;

    fn dots_and_strokes(grid: &str, stroke_width: f64) -> (Vec<Stroke>, Vec<Dot>) {
        let mask = Bitmap::from_grid(grid);
        let strokes = extract_strokes(&thin(&mask), &mask, stroke_width);
        split_dots(strokes, &mask, stroke_width)
    }

    #[test]
    fn a_round_blob_is_a_dot_and_a_dash_is_not() {
        let (strokes, dots) = dots_and_strokes(
            "
            ....................
            ..###...............
            .#####..##########..
            .#####..##########..
            .#####..##########..
            ..###...............
            ....................",
            3.0,
        );
        assert_eq!(dots.len(), 1, "{dots:?}");
        assert!(
            dots[0].centre.distance(Point::new(3.5, 3.5)) < 1.0,
            "{dots:?}"
        );
        assert!((4.0..=6.0).contains(&dots[0].diameter), "{dots:?}");
        assert_eq!(strokes.len(), 1, "{strokes:?}");
    }

    /// The dots and strokes of a 100 × 100 mask holding a round mark 6 px across at (50, 24)
    /// and, for each of `legs`, a line 3 px wide from its foot up towards (50, 20), ending at
    /// y = 35: the legs of an "A" whose pen lifts fell just below its tip.
    fn tip_piece_and_legs(legs: &[f64]) -> (Vec<Stroke>, Vec<Dot>) {
        let mut mask = Bitmap::new(100, 100);
        for y in 0..100 {
            for x in 0..100 {
                let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
                let mark = p.distance(Point::new(50.0, 24.0)) <= 3.0;
                let on_leg = legs.iter().any(|&foot| {
                    let (from, to) = (Point::new(foot, 80.0), Point::new(50.0, 20.0));
                    let t = (p - from).dot(to - from) / (to - from).hypot2();
                    p.y >= 35.0 && (0.0..=1.0).contains(&t) && p.distance(from.lerp(to, t)) <= 1.5
                });
                mask.set(x, y, mark || on_leg);
            }
        }
        let strokes = extract_strokes(&thin(&mask), &mask, 3.0);
        split_dots(strokes, &mask, 3.0)
    }

    #[test]
    fn a_round_mark_two_lines_point_at_is_a_tip_not_a_dot() {
        let (strokes, dots) = tip_piece_and_legs(&[30.0, 70.0]);
        assert!(dots.is_empty(), "{dots:?}");
        assert_eq!(strokes.len(), 3, "{strokes:?}");
        // One line pointing at it (an "i"'s stem) leaves it a dot.
        let (strokes, dots) = tip_piece_and_legs(&[30.0]);
        assert_eq!(dots.len(), 1, "{dots:?}");
        assert_eq!(strokes.len(), 1, "{strokes:?}");
    }

    #[test]
    fn a_single_pixel_is_a_dot() {
        let (strokes, dots) = dots_and_strokes("...\n.#.\n...", 1.0);
        assert!(strokes.is_empty());
        assert_eq!(dots.len(), 1);
        assert_eq!(dots[0].centre, Point::new(1.5, 1.5));
    }

    #[test]
    fn a_three_by_two_blob_is_a_dot_though_it_thins_to_a_stub() {
        // A round dot 2.3–2.6 px across drawn with a 1.8 px pen binarizes like this; its skeleton
        // is three pixels long, longer than the ink's radius, and it used to be dropped.
        let mask = Bitmap::from_grid(".....\n.###.\n.###.\n.....");
        let strokes = extract_strokes(&thin(&mask), &mask, 2.0);
        assert_eq!(strokes.len(), 1);
        assert!(strokes[0].line.points.len() > 1, "{strokes:?}");
        let (strokes, dots) = split_dots(strokes, &mask, 2.0);
        assert!(strokes.is_empty(), "{strokes:?}");
        assert_eq!(dots.len(), 1);
        assert!(
            dots[0].centre.distance(Point::new(2.5, 2.0)) < 1e-9,
            "{dots:?}"
        );
        let area_diameter = 2.0 * (6.0 / std::f64::consts::PI).sqrt();
        assert!((dots[0].diameter - area_diameter).abs() < 1e-9, "{dots:?}");
    }

    #[test]
    fn a_mark_twice_as_long_as_wide_is_a_dash() {
        let (strokes, dots) = dots_and_strokes("......\n.####.\n.####.\n......", 2.0);
        assert!(dots.is_empty(), "{dots:?}");
        assert_eq!(strokes.len(), 1);
    }

    #[test]
    fn a_mark_thinned_to_one_pixel_is_a_dot_whatever_its_moments() {
        // Five pixels in an L: 1.55 times as long as wide by its moments, but as round as a pixel
        // grid draws a dot 2 px across.
        let (strokes, dots) = dots_and_strokes("....\n.#..\n.##.\n.##.\n....", 2.0);
        assert!(strokes.is_empty(), "{strokes:?}");
        assert_eq!(dots.len(), 1);
    }

    const HOOK: &str = "
        .........
        ..#####..
        .##...##.
        .##......
        .##......
        .##...##.
        ..#####..
        .........";

    #[test]
    fn a_small_hook_is_no_dot_though_round_by_its_moments() {
        // A "c" as wide as it is tall: its skeleton runs around it, longer than the mark is wide.
        let (strokes, dots) = dots_and_strokes(HOOK, 5.0);
        assert!(dots.is_empty(), "{dots:?}");
        assert_eq!(strokes.len(), 1);
        // The guard is what rejects it: its skeleton is within the widest dot's, and its ink is
        // round.
        let length = polyline_length(&strokes[0].line.points, false);
        assert!(length <= DOT_MAX_SKELETON_IN_PEN_WIDTHS * 5.0, "{length}");
        let mask = Bitmap::from_grid(HOOK);
        let ink =
            InkMoments::of_component(&mask, strokes[0].line.points[0], f64::INFINITY).expect("ink");
        assert!(
            ink.elongation() <= DOT_MAX_ELONGATION,
            "{}",
            ink.elongation()
        );
    }

    #[test]
    fn ink_wider_than_any_dot_is_not_filled() {
        // A 12 × 12 blot with a pen of 1 px: far wider than the widest dot (6 pen widths); its
        // ink is not measured, and its skeleton, a stub, stays a stroke.
        let mut grid = String::new();
        for y in 0..14 {
            for x in 0..14 {
                grid.push(if (1..13).contains(&x) && (1..13).contains(&y) {
                    '#'
                } else {
                    '.'
                });
            }
            grid.push('\n');
        }
        let mask = Bitmap::from_grid(&grid);
        assert!(InkMoments::of_component(&mask, Point::new(6.5, 6.5), 100.0).is_none());
        assert!(InkMoments::of_component(&mask, Point::new(6.5, 6.5), 144.0).is_some());
        let (_, dots) = dots_and_strokes(&grid, 1.0);
        assert!(dots.is_empty(), "{dots:?}");
        let (_, dots) = dots_and_strokes(&grid, 4.0);
        assert_eq!(dots.len(), 1, "a blot 3 pen widths across is a dot");
    }

    #[test]
    fn elongation_is_length_over_width() {
        let moments = |grid: &str| {
            let mask = Bitmap::from_grid(grid);
            InkMoments::of_component(&mask, Point::new(1.5, 1.5), f64::INFINITY)
                .expect("ink at the seed")
        };
        assert!((moments("...\n.#.\n...").elongation() - 1.0).abs() < 1e-9);
        let dash = moments("........\n.######.\n.######.\n........");
        assert!((dash.elongation() - 3.0).abs() < 1e-9);
        assert!(
            InkMoments::of_component(&Bitmap::from_grid("..\n.."), Point::new(0.5, 0.5), 1.0)
                .is_none()
        );
    }
}
