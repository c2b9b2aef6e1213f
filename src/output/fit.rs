//! Fits reconstructed polylines with smooth cubic Béziers, or writes them as (optionally
//! Douglas–Peucker simplified) straight segments. Smooth paths follow a Catmull–Rom spline
//! through the lightly smoothed samples, fitted corner to corner (a corner turns by
//! [`CORNER_TURN_DEGREES`] within [`CORNER_STRETCH_IN_PEN_WIDTHS`]) by Schneider's fit-and-split
//! (*An algorithm for automatically fitting digitized curves*, Graphics Gems, 1990). Every cubic
//! is checked against the stretch of polyline it stands for (issue 8: it stays within the
//! tolerance of it, and its control points inside its bounding box grown by the tolerance); one
//! that fails is split, down to one sample interval, which is then drawn straight.

mod corners;

pub use corners::{CORNER_STRETCH_IN_PEN_WIDTHS, CORNER_TURN_DEGREES};

use kurbo::{
    BezPath, CubicBez, Line, ParamCurve, ParamCurveDeriv, ParamCurveNearest, PathSeg, Point, Vec2,
};

use rayon::prelude::*;

use crate::geometry::polyline::simplification_mask;
use crate::geometry::Polyline;
use corners::find_corners;

/// How curves are turned into paths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// Smooth cubic Béziers (true) or straight segments (false).
    pub smooth: bool,
    /// The largest distance the path may stray from the reconstructed polyline, in pixels.
    pub tolerance: f64,
    /// The pen width in pixels: corners are found by the turn over a stretch of
    /// [`CORNER_STRETCH_IN_PEN_WIDTHS`] of it. Not a positive number: by the turn at each vertex.
    pub pen_width: f64,
}

/// One fitted curve: the path that [`super::svg::Drawing`] holds one of per curve.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePath {
    /// The geometry: lines and cubic Béziers, ending in `ClosePath` when closed.
    pub path: BezPath,
    /// Whether the curve is closed.
    pub closed: bool,
    /// The path's own stroke width, when it differs from the drawing's (a dot as wide as its
    /// ink).
    pub stroke_width: Option<f64>,
}

impl CurvePath {
    /// A straight-segment path through `points`, closed back to the first one if `closed`.
    pub fn polyline(points: &[Point], closed: bool) -> Self {
        let mut path = BezPath::new();
        for (i, &p) in points.iter().enumerate() {
            if i == 0 {
                path.move_to(p);
            } else {
                path.line_to(p);
            }
        }
        if closed && points.len() > 2 {
            path.close_path();
        }
        Self {
            path,
            closed: closed && points.len() > 2,
            stroke_width: None,
        }
    }

    /// A dot: a zero-length path at `centre` (drawn by the round cap as a disc `diameter`
    /// wide).
    pub fn dot(centre: Point, diameter: f64) -> Self {
        let mut path = BezPath::new();
        path.move_to(centre);
        path.line_to(centre);
        Self {
            path,
            closed: false,
            stroke_width: Some(diameter),
        }
    }
}

/// One segment of a fitted path and the stretch of its polyline that it stands for: the
/// vertices `first..=last`, counted on past the end of a closed polyline (take them modulo its
/// length). The segment runs from near vertex `first` to near vertex `last`; the segments of a
/// path follow each other, each `first` the `last` before it.
#[derive(Clone, Debug, PartialEq)]
pub struct FittedSegment {
    /// A straight segment or a cubic Bézier.
    pub segment: PathSeg,
    /// The first polyline vertex of the stretch.
    pub first: usize,
    /// The last polyline vertex of the stretch (at least `first + 1`).
    pub last: usize,
}

impl FittedSegment {
    /// The polyline vertices the segment stands for, in order.
    pub fn piece<'a>(&self, curve: &'a Polyline) -> impl Iterator<Item = Point> + 'a {
        let n = curve.points.len();
        (self.first..=self.last).map(move |i| curve.points[i % n])
    }
}

/// Fits every curve into a path and puts the paths in the SVG's stable order (the pipeline's
/// "fit" stage).
pub fn fit_paths(curves: &[Polyline], options: &FitOptions) -> Vec<CurvePath> {
    // Each curve is fitted on its own, on whichever thread is free; `collect` keeps their order.
    let mut paths: Vec<CurvePath> = curves
        .par_iter()
        .map(|curve| CurvePath {
            path: fit_curve(curve, options),
            closed: curve.closed,
            stroke_width: None,
        })
        .collect();
    sort_paths(&mut paths);
    paths
}

/// Puts paths in the SVG's stable order: by the path's first point, top to bottom, then left to
/// right.
pub fn sort_paths(paths: &mut [CurvePath]) {
    paths.sort_by(|a, b| {
        let key = |p: &CurvePath| {
            p.path
                .elements()
                .first()
                .and_then(|e| e.end_point())
                .unwrap_or(Point::ZERO)
        };
        let (ka, kb) = (key(a), key(b));
        ka.y.total_cmp(&kb.y).then(ka.x.total_cmp(&kb.x))
    });
}

/// DECISION: by default a path may stray from the reconstructed polyline by 0.4 pen widths. The
/// samples wobble on the skeleton by about a quarter pen width; a band wider than that lets the
/// cubics run smoothly through the wobble, and it stays inside the ink's half width (0.5). At
/// 0.25, with every cubic held to it (issue 8), the paths of the benchmark's development split
/// turn 39 % more than the true curves at the pen-width scale, against 18 % at 0.4 (15 % before
/// the cubics were held to the polyline, when they followed the smoothed spline), with the same
/// distance to the truth.
const TOLERANCE_IN_PEN_WIDTHS: f64 = 0.4;
/// The floor of the default tolerance: half a pixel, below which a fit only follows the
/// skeleton's pixel steps.
const TOLERANCE_FLOOR_PX: f64 = 0.5;

/// DECISION: the smallest tolerance a caller may ask for: 0.01 px, the resolution of the SVG's
/// coordinates (two decimals). A smaller one changes no output byte, only the work (each halving
/// of the tolerance splits the curves into more pieces). A smaller tolerance asked for is raised
/// to it.
pub const MIN_TOLERANCE_PX: f64 = 0.01;

/// The default [`FitOptions::tolerance`] for a pen of `stroke_width` pixels: 0.4 pen widths, at
/// least 0.5 px.
pub fn default_tolerance(stroke_width: f64) -> f64 {
    (TOLERANCE_IN_PEN_WIDTHS * stroke_width).max(TOLERANCE_FLOOR_PX)
}

/// DECISION: smoothing may move a sample by at most this share of the tolerance. The cubics
/// follow the smoothed samples and are checked against the unsmoothed polyline; a sample moved
/// farther would leave them too little room, and a straight segment between two samples
/// (the last resort) stays within this share of the polyline.
const SMOOTHING_SHIFT_IN_TOLERANCES: f64 = 0.5;

/// Turns a polyline into a path; closed polylines end with `ClosePath`. A tolerance below
/// [`MIN_TOLERANCE_PX`] (or not a number) is raised to it.
pub fn fit_curve(curve: &Polyline, options: &FitOptions) -> BezPath {
    let segments = fit_segments(curve, options);
    let Some(first) = segments.first() else {
        // One point or none: nothing to fit.
        return CurvePath::polyline(&curve.points, false).path;
    };
    let mut path = BezPath::new();
    path.move_to(first.segment.start());
    let closed = curve.closed && curve.points.len() > 2;
    for (k, fitted) in segments.iter().enumerate() {
        match fitted.segment {
            // `ClosePath` draws a closed path's last straight segment.
            PathSeg::Line(_) if closed && k + 1 == segments.len() => {}
            PathSeg::Line(line) => path.line_to(line.p1),
            PathSeg::Quad(quad) => path.quad_to(quad.p1, quad.p2),
            PathSeg::Cubic(cubic) => path.curve_to(cubic.p1, cubic.p2, cubic.p3),
        }
    }
    if closed {
        path.close_path();
    }
    path
}

/// The segments of [`fit_curve`]'s path, each with the stretch of polyline it stands for
/// (a closed path's closing segment included). Empty for fewer than two points.
pub fn fit_segments(curve: &Polyline, options: &FitOptions) -> Vec<FittedSegment> {
    let tolerance = options.tolerance.max(MIN_TOLERANCE_PX);
    let points = &curve.points;
    let closed = curve.closed && points.len() > 2;
    if points.len() < 2 {
        Vec::new()
    } else if !options.smooth || points.len() < 3 {
        straight_segments(points, closed, tolerance)
    } else {
        smooth_segments(points, closed, tolerance, options.pen_width)
    }
}

/// Douglas–Peucker simplification within `tolerance`, as straight segments.
fn straight_segments(points: &[Point], closed: bool, tolerance: f64) -> Vec<FittedSegment> {
    let n = points.len();
    let mut kept: Vec<usize> = if n <= 2 {
        (0..n).collect()
    } else {
        let mask = simplification_mask(points, closed, tolerance);
        (0..n).filter(|&i| mask[i]).collect()
    };
    if closed {
        kept.push(n);
    }
    kept.windows(2)
        .map(|pair| FittedSegment {
            segment: PathSeg::Line(Line::new(points[pair[0]], points[pair[1] % n])),
            first: pair[0],
            last: pair[1],
        })
        .collect()
}

/// Smooth cubics from corner to corner (a closed curve without corners as one periodic run).
fn smooth_segments(
    points: &[Point],
    closed: bool,
    tolerance: f64,
    pen_width: f64,
) -> Vec<FittedSegment> {
    let n = points.len();
    let corners = find_corners(points, closed, CORNER_STRETCH_IN_PEN_WIDTHS * pen_width);
    let max_shift = SMOOTHING_SHIFT_IN_TOLERANCES * tolerance;
    let shifted = |fits: Vec<(PathSeg, usize, usize)>, offset: usize| {
        fits.into_iter()
            .map(move |(segment, first, last)| FittedSegment {
                segment,
                first: first + offset,
                last: last + offset,
            })
    };
    if closed && corners.is_empty() {
        // A smooth loop: one periodic run, its seam as smooth as the rest.
        let smoothed = smooth_interior(points, true, &[], max_shift);
        let dense = densify_catmull_rom(&smoothed, true);
        let mut polyline = points.to_vec();
        polyline.push(points[0]);
        return shifted(fit_run(&dense, &polyline, true, tolerance), 0).collect();
    }
    // The vertices in path order: a closed curve starts and ends at its first corner, so every
    // run goes corner to corner.
    let start = if closed { corners[0] } else { 0 };
    let end = if closed { start + n } else { n - 1 };
    let ordered: Vec<Point> = (start..=end).map(|i| points[i % n]).collect();
    let mut breaks: Vec<usize> = corners
        .iter()
        .map(|&c| (c + n - start) % n)
        .chain([0, end - start])
        .collect();
    breaks.sort_unstable();
    breaks.dedup();
    let smoothed = smooth_interior(&ordered, false, &breaks, max_shift);
    let mut segments = Vec::new();
    for run in breaks.windows(2) {
        let dense = densify_catmull_rom(&smoothed[run[0]..=run[1]], false);
        let fits = fit_run(&dense, &ordered[run[0]..=run[1]], false, tolerance);
        segments.extend(shifted(fits, start + run[0]));
    }
    segments
}

/// DECISION: the Catmull–Rom spline through the samples is evaluated at this many points per
/// sample interval; the fit follows that dense polyline, so its tolerance holds between samples
/// too, not only at them.
const SPLINE_POINTS_PER_INTERVAL: usize = 4;

/// Points along the uniform Catmull–Rom spline through `points` (ends included; a periodic run
/// ends where it starts): point `k` × [`SPLINE_POINTS_PER_INTERVAL`] is sample `k`.
fn densify_catmull_rom(points: &[Point], periodic: bool) -> Vec<Point> {
    let spline = catmull_rom(points, periodic);
    let mut dense = vec![points[0]];
    for segment in spline.segments() {
        for k in 1..=SPLINE_POINTS_PER_INTERVAL {
            dense.push(segment.eval(k as f64 / SPLINE_POINTS_PER_INTERVAL as f64));
        }
    }
    dense
}

/// Fits the dense polyline `data` (the spline through the smoothed samples of `polyline`, one
/// run of it) with as few cubics as the tolerance allows: Schneider's fit-and-split. A cubic is
/// accepted when it stays within `tolerance` of its piece of `data` and of its stretch of
/// `polyline`, with its control points inside that stretch's bounding box grown by the
/// tolerance; a piece that no cubic fits is split at the sample nearest its worst point, and a
/// piece of one sample interval that no cubic fits is a straight segment. Each split shortens
/// the piece, so the fit always ends; [`FIT_WORK_PER_POINT`] keeps the work O(n log n) whatever
/// the input. Returns the segments with the first and last `polyline` vertex of each.
///
/// This replaces `kurbo::simplify_bezpath`, which loops forever on some inputs (kurbo issue
/// #602) and overshoots on others (#604, #605).
fn fit_run(
    data: &[Point],
    polyline: &[Point],
    periodic: bool,
    tolerance: f64,
) -> Vec<(PathSeg, usize, usize)> {
    let budget = FIT_WORK_PER_POINT.saturating_mul(data.len());
    fit_run_within(data, polyline, periodic, tolerance, budget)
}

/// The unit vector from `from` to `to`; zero when they coincide.
fn direction(from: Point, to: Point) -> Vec2 {
    let d = to - from;
    let length = d.hypot();
    if length > 0.0 {
        d / length
    } else {
        Vec2::ZERO
    }
}

/// [`fit_run`] with a work budget: fitting a piece costs its length, and once `budget` is spent
/// pieces are halved instead of cut at their worst point.
fn fit_run_within(
    data: &[Point],
    polyline: &[Point],
    periodic: bool,
    tolerance: f64,
    mut budget: usize,
) -> Vec<(PathSeg, usize, usize)> {
    const STEP: usize = SPLINE_POINTS_PER_INTERVAL;
    let n = data.len();
    debug_assert_eq!(n, STEP * (polyline.len() - 1) + 1, "dense data per sample");
    // Tangents point into the piece at both ends. A periodic run has one tangent at its seam.
    // Tangents are measured one sample interval away, where the spline's own wobble between two
    // samples averages out.
    let reach = STEP.min(n - 1);
    let (start_tangent, end_tangent) = if periodic {
        let seam = direction(data[n - 1 - reach], data[reach]);
        (seam, -seam)
    } else {
        (
            direction(data[0], data[reach]),
            direction(data[n - 1], data[n - 1 - reach]),
        )
    };
    let mut fitted = Vec::new();
    // Pieces waiting to be fitted, last first, so segments come out in order. Pieces start and
    // end at samples (multiples of STEP), whose stretch of polyline is known.
    let mut pending = vec![(0usize, n - 1, start_tangent, end_tangent)];
    while let Some((first, last, t0, t1)) = pending.pop() {
        let piece = &data[first..=last];
        let stretch = &polyline[first / STEP..=last / STEP];
        budget = budget.saturating_sub(piece.len());
        let worst = match fit_cubic(piece, stretch, t0, t1, tolerance) {
            Ok(cubic) => {
                fitted.push((PathSeg::Cubic(cubic), first / STEP, last / STEP));
                continue;
            }
            Err(worst) => worst,
        };
        let intervals = (last - first) / STEP;
        if intervals <= 1 {
            // Both ends are smoothed samples, each within the smoothing's shift of its vertex,
            // so the straight segment between them stays that close to the polyline.
            let line = Line::new(piece[0], piece[piece.len() - 1]);
            fitted.push((PathSeg::Line(line), first / STEP, last / STEP));
            continue;
        }
        // Past the budget, halve the piece instead of cutting at its worst point.
        let worst = if budget > 0 { worst } else { piece.len() / 2 };
        let sample = (worst + STEP / 2) / STEP;
        let split = first + STEP * sample.clamp(1, intervals - 1);
        let centre = direction(data[split + reach], data[split - reach]);
        let centre = if centre == Vec2::ZERO {
            direction(data[split], data[split - 1])
        } else {
            centre
        };
        pending.push((split, last, -centre, t1));
        pending.push((first, split, t0, centre));
    }
    fitted
}

/// DECISION: a run's fit may try, on average, this many cubics through each of its points. A
/// split at the worst point can peel a sliver off a long piece at a time and then costs O(n²)
/// (a 4000 × 4000 spiral, one run of 1.8 million points: 7 s); past the budget pieces are halved,
/// so what is left costs O(n log n). The samples and the 12 MP page use at most 9.
const FIT_WORK_PER_POINT: usize = 32;

/// DECISION: reparameterize by Newton's method at most this many times, and only while the error
/// is within [`NEWTON_ERROR_FACTOR`] of the tolerance (farther off, splitting is the cheaper cure).
const NEWTON_ITERATIONS: usize = 4;
/// Newton's method is tried only on a cubic whose error is at most this many tolerances: nearer
/// fits a few steps usually bring within the tolerance.
const NEWTON_ERROR_FACTOR: f64 = 4.0;

/// One cubic for `piece` (of the dense data) with the given end tangents that stays near the
/// piece and its `stretch` of polyline, or the index in `piece` of the point to split at.
fn fit_cubic(
    piece: &[Point],
    stretch: &[Point],
    t0: Vec2,
    t1: Vec2,
    tolerance: f64,
) -> Result<CubicBez, usize> {
    let mut parameters = chord_length_parameters(piece);
    let mut cubic = least_squares_cubic(piece, &parameters, t0, t1);
    let (mut error, mut worst) = parameter_error(&cubic, piece, &parameters);
    for _ in 0..NEWTON_ITERATIONS {
        if error <= tolerance || error > NEWTON_ERROR_FACTOR * tolerance {
            break;
        }
        for (u, p) in parameters.iter_mut().zip(piece) {
            *u = newton_step(&cubic, *p, *u);
        }
        cubic = least_squares_cubic(piece, &parameters, t0, t1);
        (error, worst) = parameter_error(&cubic, piece, &parameters);
    }
    if error > tolerance {
        return Err(worst);
    }
    if stays_near_stretch(&cubic, stretch, &parameters, tolerance) {
        Ok(cubic)
    } else {
        // Near the data but bulging between points, overshooting with its handles or off the
        // polyline: the piece is too long for one cubic, halve it.
        Err(piece.len() / 2)
    }
}

/// Each point's share of the arc length from the piece's first point (0) to its last (1); evenly
/// spread when all points coincide.
fn chord_length_parameters(piece: &[Point]) -> Vec<f64> {
    let mut parameters = Vec::with_capacity(piece.len());
    let mut total = 0.0;
    parameters.push(0.0);
    for pair in piece.windows(2) {
        total += pair[0].distance(pair[1]);
        parameters.push(total);
    }
    let last = piece.len() - 1;
    for (k, u) in parameters.iter_mut().enumerate() {
        *u = if total > 0.0 {
            *u / total
        } else {
            k as f64 / last as f64
        };
    }
    parameters
}

/// The least-squares system is singular when its determinant is below this share of the
/// product of its diagonal terms (the tangents' terms parallel, or one of them empty): its
/// solution would be rounding noise.
const SINGULAR_DETERMINANT: f64 = 1e-12;

/// Handles shorter than this share of the chord are degenerate (Schneider's `1.0e-6 *
/// segLength`): the least-squares solution is replaced by handles a third of the chord long.
const MIN_HANDLE_IN_CHORDS: f64 = 1e-6;

/// The cubic from the piece's first to last point along the tangents whose handle lengths
/// minimise the squared distance to the data at the given parameters (Schneider's
/// `GenerateBezier`), with his fallback of a third of the chord when that is degenerate.
fn least_squares_cubic(piece: &[Point], parameters: &[f64], t0: Vec2, t1: Vec2) -> CubicBez {
    let (start, end) = (piece[0], piece[piece.len() - 1]);
    let (mut c00, mut c01, mut c11, mut x0, mut x1) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (&u, &p) in parameters.iter().zip(piece) {
        let v = 1.0 - u;
        let (b0, b1, b2, b3) = (v * v * v, 3.0 * u * v * v, 3.0 * u * u * v, u * u * u);
        let (a0, a1) = (t0 * b1, t1 * b2);
        c00 += a0.dot(a0);
        c01 += a0.dot(a1);
        c11 += a1.dot(a1);
        let rest = p.to_vec2() - (start.to_vec2() * (b0 + b1) + end.to_vec2() * (b2 + b3));
        x0 += a0.dot(rest);
        x1 += a1.dot(rest);
    }
    let determinant = c00 * c11 - c01 * c01;
    let chord = start.distance(end);
    // The floor makes a zero determinant singular even when the diagonal terms vanish.
    let singular = SINGULAR_DETERMINANT * (c00 * c11).max(1e-300);
    let (mut alpha0, mut alpha1) = if determinant.abs() > singular {
        (
            (x0 * c11 - x1 * c01) / determinant,
            (c00 * x1 - c01 * x0) / determinant,
        )
    } else {
        (0.0, 0.0)
    };
    let floor = MIN_HANDLE_IN_CHORDS * chord;
    if !(alpha0.is_finite() && alpha1.is_finite()) || alpha0 < floor || alpha1 < floor {
        alpha0 = chord / 3.0;
        alpha1 = chord / 3.0;
    }
    CubicBez::new(start, start + t0 * alpha0, end + t1 * alpha1, end)
}

/// The largest distance between a data point and the cubic at that point's parameter, and where.
fn parameter_error(cubic: &CubicBez, piece: &[Point], parameters: &[f64]) -> (f64, usize) {
    let mut worst = (0.0, piece.len() / 2);
    for (k, (&u, &p)) in parameters.iter().zip(piece).enumerate() {
        let distance = cubic.eval(u).distance(p);
        if distance > worst.0 {
            worst = (distance, k);
        }
    }
    worst
}

/// One Newton–Raphson step towards the parameter of the point of `cubic` nearest `p`.
fn newton_step(cubic: &CubicBez, p: Point, u: f64) -> f64 {
    let d1 = cubic.deriv();
    let d2 = d1.deriv();
    let offset = cubic.eval(u) - p;
    let first = d1.eval(u).to_vec2();
    let numerator = offset.dot(first);
    let denominator = first.dot(first) + offset.dot(d2.eval(u).to_vec2());
    // A flat denominator (an inflection at the nearest point) would send the step off the curve.
    if denominator.abs() < 1e-12 || !denominator.is_finite() {
        return u;
    }
    (u - numerator / denominator).clamp(0.0, 1.0)
}

/// DECISION: the cubic is checked at points at most this share of the tolerance apart along it.
/// Distance changes no faster than arc length, so a point between two checks is at most half
/// that farther off than the nearer check: the checks hold the cubic to the tolerance less a
/// tenth of it, and then every point of the cubic is within the tolerance.
const CHECK_SPACING_IN_TOLERANCES: f64 = 0.2;

/// Whether the cubic stays near its stretch of polyline everywhere: its control points inside
/// the stretch's bounding box grown by the tolerance (a cubic whose handles leave it is
/// overshooting), and every point of it within the tolerance of the polyline near it (the
/// sample interval its parameter falls in, among the data's `parameters`, and its neighbours).
fn stays_near_stretch(
    cubic: &CubicBez,
    stretch: &[Point],
    parameters: &[f64],
    tolerance: f64,
) -> bool {
    if !within_grown_bounds(stretch, tolerance, &[cubic.p1, cubic.p2]) {
        return false;
    }
    // The cubic's speed is at most 3 × its longest control leg, so `checks` steps in parameter
    // are at most `spacing` apart along it.
    let longest_leg = [cubic.p0, cubic.p1, cubic.p2, cubic.p3]
        .windows(2)
        .map(|leg| leg[0].distance(leg[1]))
        .fold(0.0, f64::max);
    let checks = ((3.0 * longest_leg / (CHECK_SPACING_IN_TOLERANCES * tolerance)).ceil() as usize)
        .max(parameters.len());
    let spacing = 3.0 * longest_leg / checks as f64;
    let allowed = tolerance - 0.5 * spacing;
    let intervals = stretch.len() - 1;
    // Newton's steps may leave the parameters slightly out of order: follow their running
    // maximum.
    let mut data_index = 0;
    let mut reached = 0.0f64;
    for j in 0..=checks {
        let u = j as f64 / checks as f64;
        while data_index + 1 < parameters.len() && reached.max(parameters[data_index + 1]) <= u {
            data_index += 1;
            reached = reached.max(parameters[data_index]);
        }
        let interval = (data_index / SPLINE_POINTS_PER_INTERVAL).min(intervals - 1);
        let q = cubic.eval(u);
        // Near when one of the intervals lies within `limit`, looked at only until one does: the
        // same as their least distance within it (a NaN distance is never near, and a NaN or
        // infinite limit passes every point, as the least distance compared with it did).
        let limit = allowed * allowed;
        let near = limit.is_nan()
            || limit == f64::INFINITY
            || (interval.saturating_sub(1)..(interval + 2).min(intervals)).any(|i| {
                // The accuracy argument is for curves: a line's nearest point is exact.
                Line::new(stretch[i], stretch[i + 1])
                    .nearest(q, 1e-9)
                    .distance_sq
                    <= limit
            });
        if !near {
            return false;
        }
    }
    true
}

/// Whether every point of `inside` lies in the bounding box of `stretch` grown by `margin`
/// (edges included).
pub fn within_grown_bounds(stretch: &[Point], margin: f64, inside: &[Point]) -> bool {
    let (mut low, mut high) = (stretch[0], stretch[0]);
    for p in stretch {
        low = Point::new(low.x.min(p.x), low.y.min(p.y));
        high = Point::new(high.x.max(p.x), high.y.max(p.y));
    }
    inside.iter().all(|q| {
        q.x >= low.x - margin
            && q.x <= high.x + margin
            && q.y >= low.y - margin
            && q.y <= high.y + margin
    })
}

/// Smoothing moves a vertex this share of the way to its neighbours' midpoint: half, the
/// [1/4, 1/2, 1/4] binomial kernel, which takes out a zig-zag from sample to sample entirely and
/// leaves a bend spread over several samples nearly as it is.
const SMOOTHING_PULL: f64 = 0.5;

/// One pass of [1/4, 1/2, 1/4] smoothing on every vertex except the ends of an open chain and
/// the `fixed` ones (corners): it takes out the skeleton's pixel jitter without moving corners.
/// No vertex moves farther than `max_shift`.
fn smooth_interior(points: &[Point], closed: bool, fixed: &[usize], max_shift: f64) -> Vec<Point> {
    let n = points.len();
    // A mask, not a search of `fixed` per vertex: a jagged curve has corners all along it.
    let mut is_fixed = vec![false; n];
    for &i in fixed {
        is_fixed[i] = true;
    }
    (0..n)
        .map(|i| {
            let is_end = !closed && (i == 0 || i + 1 == n);
            if is_end || is_fixed[i] || n < 3 {
                return points[i];
            }
            let (before, after) = (points[(i + n - 1) % n], points[(i + 1) % n]);
            let midpoint = (before.to_vec2() + after.to_vec2()) * 0.5;
            let shift = (midpoint - points[i].to_vec2()) * SMOOTHING_PULL;
            let length = shift.hypot();
            if length > max_shift {
                points[i] + shift * (max_shift / length)
            } else {
                points[i] + shift
            }
        })
        .collect()
}

/// A uniform Catmull–Rom spline through `points` as cubic Béziers; open runs use one-sided
/// tangents at their ends.
fn catmull_rom(points: &[Point], closed: bool) -> BezPath {
    let n = points.len();
    let mut path = BezPath::new();
    if n == 0 {
        return path;
    }
    path.move_to(points[0]);
    if n == 1 {
        return path;
    }
    let at = |i: isize| -> Point {
        if closed {
            points[i.rem_euclid(n as isize) as usize]
        } else {
            points[i.clamp(0, n as isize - 1) as usize]
        }
    };
    let segments = if closed { n } else { n - 1 };
    for k in 0..segments as isize {
        let (p0, p1, p2, p3) = (at(k - 1), at(k), at(k + 1), at(k + 2));
        // The uniform spline's tangent at p1 is (p2 − p0) / 2; a Bézier handle is a third of it.
        let c1 = p1 + (p2 - p0) / 6.0;
        let c2 = p2 - (p3 - p1) / 6.0;
        path.curve_to(c1, c2, p2);
    }
    if closed {
        path.close_path();
    }
    path
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{ParamCurve, PathEl, Shape};

    fn smooth() -> FitOptions {
        FitOptions {
            smooth: true,
            tolerance: 0.5,
            pen_width: 2.0,
        }
    }

    /// The largest distance from any point of `points` to the path.
    fn deviation(path: &BezPath, points: &[Point]) -> f64 {
        let mut flattened = Vec::new();
        for segment in path.segments() {
            for k in 0..=32 {
                flattened.push(segment.eval(k as f64 / 32.0));
            }
        }
        points
            .iter()
            .map(|p| {
                flattened
                    .iter()
                    .map(|q| p.distance(*q))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_circle_becomes_a_few_closed_cubics_close_to_it() {
        let points: Vec<Point> = (0..40)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 40.0;
                Point::new(50.0 + 30.0 * a.cos(), 50.0 + 30.0 * a.sin())
            })
            .collect();
        let path = fit_curve(&Polyline::new(points.clone(), true), &smooth());
        assert!(matches!(path.elements().last(), Some(PathEl::ClosePath)));
        let cubics = path
            .elements()
            .iter()
            .filter(|e| matches!(e, PathEl::CurveTo(..)))
            .count();
        assert!((2..=12).contains(&cubics), "{cubics} cubics");
        assert!(deviation(&path, &points) < 1.0);
        assert!((path.area().abs() - std::f64::consts::PI * 900.0).abs() < 60.0);
    }

    #[test]
    fn a_square_keeps_its_four_corners() {
        let mut points = Vec::new();
        let corners = [(0.0, 0.0), (40.0, 0.0), (40.0, 40.0), (0.0, 40.0)];
        for k in 0..4 {
            let (a, b) = (corners[k], corners[(k + 1) % 4]);
            for step in 0..8 {
                let t = step as f64 / 8.0;
                points.push(Point::new(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            }
        }
        let path = fit_curve(&Polyline::new(points.clone(), true), &smooth());
        for (x, y) in corners {
            let corner = Point::new(x, y);
            let nearest = path
                .elements()
                .iter()
                .filter_map(|e| e.end_point())
                .map(|p| p.distance(corner))
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest < 0.01,
                "corner {corner:?} is not a path vertex: {path:?}"
            );
        }
        assert!(deviation(&path, &points) < 0.6);
    }

    #[test]
    fn open_curves_stay_open_and_keep_their_ends() {
        let points: Vec<Point> = (0..30)
            .map(|i| Point::new(i as f64 * 3.0, 20.0 * (i as f64 * 0.2).sin()))
            .collect();
        let path = fit_curve(&Polyline::new(points.clone(), false), &smooth());
        assert!(!matches!(path.elements().last(), Some(PathEl::ClosePath)));
        let first = path.elements()[0].end_point().unwrap();
        let last = path.elements().last().unwrap().end_point().unwrap();
        assert_eq!((first, last), (points[0], points[29]));
        assert!(deviation(&path, &points) < 1.5);
    }

    /// Random jagged chains, like the skeletons of specks and noise (the inputs on which
    /// `kurbo::simplify_bezpath` never returned): every fit returns, and every segment stays
    /// within the tolerance of its stretch of the chain with its control points inside the
    /// stretch's bounding box grown by the tolerance.
    #[test]
    fn jagged_chains_fit_without_leaving_them() {
        let mut state = 0x5EED_u64;
        let mut unit = move || {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..600 {
            let count = 3 + (unit() * 120.0) as usize;
            let mut p = Point::new(50.0, 50.0);
            let mut points = vec![p];
            for _ in 1..count {
                // Steps of 0 to 3 px in any direction, duplicates included.
                let step = (unit() * 4.0).floor() * 0.75;
                let angle = unit() * std::f64::consts::TAU;
                p += Vec2::new(step * angle.cos(), step * angle.sin());
                points.push(p);
            }
            let curve = Polyline::new(points, case % 2 == 0);
            let tolerance = [0.0, 0.1, 0.5, 1.75][case % 4];
            let options = FitOptions {
                smooth: true,
                tolerance,
                pen_width: [0.0, 1.0, 2.0, 7.0][case % 4],
            };
            let fitted = fit_segments(&curve, &options);
            let tolerance = tolerance.max(MIN_TOLERANCE_PX);
            for (k, piece) in fitted.iter().enumerate() {
                let stretch: Vec<Point> = piece.piece(&curve).collect();
                let controls: Vec<Point> = match piece.segment {
                    PathSeg::Cubic(c) => vec![c.p1, c.p2],
                    _ => Vec::new(),
                };
                assert!(
                    within_grown_bounds(&stretch, tolerance, &controls),
                    "case {case}, segment {k}: a control point leaves the stretch"
                );
                let worst = (0..=64)
                    .map(|j| piece.segment.eval(j as f64 / 64.0))
                    .map(|q| distance_to_chain(q, &stretch, false))
                    .fold(0.0, f64::max);
                assert!(
                    worst <= tolerance + 1e-9,
                    "{piece:?} {stretch:?} case {case}, segment {k}: strays {worst:.3} px (tolerance {tolerance})"
                );
            }
        }
    }

    fn distance_to_chain(q: Point, points: &[Point], closed: bool) -> f64 {
        let n = points.len();
        let segments = if closed { n } else { n - 1 };
        (0..segments)
            .map(|i| {
                Line::new(points[i], points[(i + 1) % n])
                    .nearest(q, 1e-9)
                    .distance_sq
                    .sqrt()
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// A spiral is one long run without corners, on which cutting at the worst point can peel a
    /// sliver at a time; past the work budget the fit halves its pieces instead. With the budget
    /// and with none at all, the path must stay near the spiral.
    #[test]
    fn a_long_spiral_run_is_fitted_near_the_data_within_any_budget() {
        // An Archimedean spiral, r = 4 + 2θ (turns 4π px apart), sampled about every 2.5 px.
        const TURN_SPACING: f64 = 2.0 * std::f64::consts::TAU;
        let radius_at = |angle: f64| 4.0 + 2.0 * angle;
        let points: Vec<Point> = (0..5_000)
            .map(|k| {
                let angle = (k as f64 * 1.25).sqrt();
                let radius = radius_at(angle);
                Point::new(radius * angle.cos(), radius * angle.sin())
            })
            .collect();
        let dense = densify_catmull_rom(&points, false);
        // The distance to the nearest turn along the radius: at least the distance to the spiral.
        let off_spiral = |q: Point| {
            let (radius, angle) = (q.to_vec2().hypot(), q.y.atan2(q.x));
            let turns = ((radius - radius_at(angle)) / TURN_SPACING).round();
            (radius - radius_at(angle + turns * std::f64::consts::TAU)).abs()
        };
        let tolerance = 0.5;
        for budget in [0, FIT_WORK_PER_POINT * dense.len()] {
            let fitted = fit_run_within(&dense, &points, false, tolerance, budget);
            let worst = fitted
                .iter()
                .map(|&(segment, _, _)| segment)
                .flat_map(|segment| (0..=8).map(move |k| segment.eval(k as f64 / 8.0)))
                .filter(|q| q.to_vec2().hypot() > 20.0)
                .map(off_spiral)
                .fold(0.0, f64::max);
            assert!(
                worst <= 2.0 * tolerance,
                "budget {budget}: strays {worst:.2} px"
            );
        }
    }

    #[test]
    fn polylines_are_simplified_within_the_tolerance() {
        let points: Vec<Point> = (0..50)
            .map(|i| Point::new(i as f64, 0.2 * (i % 2) as f64))
            .collect();
        let options = FitOptions {
            smooth: false,
            tolerance: 0.5,
            pen_width: 2.0,
        };
        let path = fit_curve(&Polyline::new(points.clone(), false), &options);
        assert_eq!(path.elements().len(), 2, "{path:?}");
        assert!(path
            .elements()
            .iter()
            .all(|e| !matches!(e, PathEl::CurveTo(..))));
    }
}
