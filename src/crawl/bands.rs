//! Lone bands: a narrow protrusion of an outline (a spike, a finger, a tail) whose two sides
//! merged into one band of ink and whose base the pen lifted at stands apart from the outline as
//! a dash of its own. It is spliced back into the outline it stands on, out along its middle and
//! back. Ours (issue 9, "outlines whose parts touch"); the paper has no notion of ink width.

use std::collections::HashSet;

use kurbo::{Line, ParamCurve, ParamCurveNearest, Point, Vec2};

use super::strokes::point_at_length;
use crate::geometry::grid::PointGrid;
use crate::geometry::Polyline;

/// DECISION: a lone band is spliced into a closed outline whose line passes within this many pen
/// widths of one of its ends, the gap a pen lift leaves at the protrusion's base (gaps in a
/// skip-stroke sketch are a few pen widths long; the same reach as a band's next piece across a
/// gap in [`crate::strokes`]). Measured on the benchmark: dev 327 → 329, val 314 → 315 (three
/// fingers and spikes cut off at their base), no drawing lost; a dash one pen wide (a sun's ray
/// drawn short of the sun) is no band and is never spliced.
pub(super) const BASE_GAP_MAX_IN_PEN_WIDTHS: f64 = 5.0;

/// The end must point at the outline: the line from it to its foot on the outline turns at most
/// this much (degrees) from the band's direction there. A protrusion stands on its outline.
pub(super) const BASE_MAX_TURN_DEGREES: f64 = 45.0;

/// The band's direction at an end is measured this many pen widths back along it.
const DIRECTION_REACH_IN_PEN_WIDTHS: f64 = 2.0;

/// A place on a closed curve: the segment from point `segment` to the next, at parameter `t`.
#[derive(Clone, Copy)]
pub(super) struct Foot {
    pub(super) curve: usize,
    pub(super) segment: usize,
    t: f64,
    pub(super) point: Point,
    pub(super) distance: f64,
}

/// Splices every lone band (`curves[k]` with `is_band[k]`, an open curve) that stands on a closed
/// curve into it: from the foot of its base on the outline out to the base, along the band to its
/// tip and back, and on along the outline. Traced once each way along the band's middle, the
/// outline's two sides, merged within a pen width or so, both lie within the tolerance. Bands
/// that stand on nothing are kept as they are.
pub(super) fn splice_lone_bands(
    curves: Vec<Polyline>,
    is_band: &[bool],
    stroke_width: f64,
) -> Vec<Polyline> {
    if !is_band.iter().any(|&band| band) {
        return curves;
    }
    let reach = BASE_GAP_MAX_IN_PEN_WIDTHS * stroke_width;
    let grid = SegmentGrid::new(&curves, reach);
    let mut splices: Vec<(Foot, usize, bool)> = Vec::new();
    for (k, curve) in curves.iter().enumerate() {
        if !is_band[k] || curve.closed || curve.points.len() < 2 {
            continue;
        }
        let base = [false, true]
            .into_iter()
            .filter_map(|at_last| {
                let foot = stands_on(curve, at_last, &curves, &grid, reach, stroke_width)?;
                Some((foot, at_last))
            })
            .min_by(|x, y| x.0.distance.total_cmp(&y.0.distance));
        if let Some((foot, at_last)) = base {
            splices.push((foot, k, at_last));
        }
    }
    if splices.is_empty() {
        return curves;
    }
    // On each curve, later places first, so that the earlier places' indices stay valid.
    splices.sort_by(|x, y| {
        x.0.curve
            .cmp(&y.0.curve)
            .then(y.0.segment.cmp(&x.0.segment))
            .then(y.0.t.total_cmp(&x.0.t))
    });
    let spliced: HashSet<usize> = splices.iter().map(|&(_, k, _)| k).collect();
    let mut curves = curves;
    for (foot, k, at_last) in splices {
        let mut band = curves[k].points.clone();
        if at_last {
            band.reverse();
        }
        // Out from the foot along the band to its tip, and back to the foot.
        let mut excursion = vec![foot.point];
        excursion.extend(band.iter().copied());
        excursion.extend(band.iter().rev().skip(1).copied());
        excursion.push(foot.point);
        let outline = &mut curves[foot.curve].points;
        let at = foot.segment + 1;
        outline.splice(at..at, excursion);
    }
    curves
        .into_iter()
        .enumerate()
        .filter(|(k, _)| !spliced.contains(k))
        .map(|(_, curve)| curve)
        .collect()
}

/// Where the band `curve` stands on a closed curve at its first (or last) point: the nearest
/// point of another closed curve within `reach`, which the band's end points at and its other end
/// lies farther from.
fn stands_on(
    curve: &Polyline,
    at_last: bool,
    curves: &[Polyline],
    grid: &SegmentGrid,
    reach: f64,
    stroke_width: f64,
) -> Option<Foot> {
    let points = &curve.points;
    let (end, far_end) = if at_last {
        (points[points.len() - 1], points[0])
    } else {
        (points[0], points[points.len() - 1])
    };
    let outward = end_direction(
        points,
        at_last,
        DIRECTION_REACH_IN_PEN_WIDTHS * stroke_width,
    )?;
    let foot = grid.nearest(end, curves, reach)?;
    let towards = foot.point - end;
    let max_turn = BASE_MAX_TURN_DEGREES.to_radians().cos();
    let points_at = towards.hypot() == 0.0 || outward.dot(towards / towards.hypot()) >= max_turn;
    let sticks_out = grid
        .nearest(far_end, curves, foot.distance + stroke_width)
        .is_none();
    (points_at && sticks_out).then_some(foot)
}

/// The unit direction in which the curve `points` leaves its first (or last) point, measured
/// from the point `reach` back along it; none where the two coincide.
pub(super) fn end_direction(points: &[Point], at_last: bool, reach: f64) -> Option<Vec2> {
    let end = if at_last {
        points[points.len() - 1]
    } else {
        points[0]
    };
    let way = end - point_back_from(points, at_last, reach);
    let length = way.hypot();
    (length > 0.0).then(|| way / length)
}

/// The point `distance` back along `points` from its first (or last) point.
pub(super) fn point_back_from(points: &[Point], from_last: bool, distance: f64) -> Point {
    if from_last {
        let reversed: Vec<Point> = points.iter().rev().copied().collect();
        point_at_length(&reversed, distance)
    } else {
        point_at_length(points, distance)
    }
}

/// The segments of the closed curves in square cells, for the nearest one to a point.
pub(super) struct SegmentGrid {
    grid: PointGrid<(usize, usize)>,
}

impl SegmentGrid {
    pub(super) fn new(curves: &[Polyline], cell: f64) -> Self {
        let mut grid = PointGrid::new(cell);
        for (c, curve) in curves.iter().enumerate() {
            if !curve.closed {
                continue;
            }
            let n = curve.points.len();
            for s in 0..n {
                let (a, b) = (curve.points[s], curve.points[(s + 1) % n]);
                let (ka, kb) = (grid.cell_of(a), grid.cell_of(b));
                for x in ka.0.min(kb.0)..=ka.0.max(kb.0) {
                    for y in ka.1.min(kb.1)..=ka.1.max(kb.1) {
                        grid.insert_in_cell((x, y), (c, s));
                    }
                }
            }
        }
        Self { grid }
    }

    /// The nearest point of a closed curve's segment to `p` within `reach`.
    pub(super) fn nearest(&self, p: Point, curves: &[Polyline], reach: f64) -> Option<Foot> {
        self.nearest_except(p, curves, reach, usize::MAX)
    }

    /// [`Self::nearest`], on any closed curve but curve `except`.
    pub(super) fn nearest_except(
        &self,
        p: Point,
        curves: &[Polyline],
        reach: f64,
        except: usize,
    ) -> Option<Foot> {
        let key = self.grid.cell_of(p);
        let span = (reach / self.grid.cell()).ceil() as i64;
        let mut best: Option<Foot> = None;
        for x in key.0 - span..=key.0 + span {
            for y in key.1 - span..=key.1 + span {
                for &(c, s) in self.grid.in_cell((x, y)) {
                    if c == except {
                        continue;
                    }
                    let curve = &curves[c];
                    let n = curve.points.len();
                    let line = Line::new(curve.points[s], curve.points[(s + 1) % n]);
                    let nearest = line.nearest(p, 1e-9);
                    let distance = nearest.distance_sq.sqrt();
                    if distance <= reach && best.is_none_or(|b| distance < b.distance) {
                        best = Some(Foot {
                            curve: c,
                            segment: s,
                            t: nearest.t,
                            point: line.eval(nearest.t),
                            distance,
                        });
                    }
                }
            }
        }
        best
    }
}
