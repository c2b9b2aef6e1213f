//! Fits reconstructed polylines with smooth cubic Béziers (a Catmull–Rom spline through the
//! samples, fitted corner to corner by Schneider's fit-and-split, Graphics Gems 1990, within a
//! pixel tolerance that every cubic is checked against), keeping corners sharp; or writes them as
//! (optionally Douglas–Peucker simplified) polylines.

use kurbo::{
    BezPath, CubicBez, Line, ParamCurve, ParamCurveDeriv, ParamCurveNearest, Point, Rect, Vec2,
};

use crate::geometry::polyline::simplify_polyline;
use crate::geometry::Polyline;

/// How curves are turned into paths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// Smooth cubic Béziers (true) or straight segments (false).
    pub smooth: bool,
    /// The largest distance the path may stray from the reconstructed polyline, in pixels.
    pub tolerance: f64,
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

/// Fits every curve into a path and puts the paths in the SVG's stable order (the pipeline's
/// "fit" stage).
pub fn fit_paths(curves: &[Polyline], options: &FitOptions) -> Vec<CurvePath> {
    let mut paths: Vec<CurvePath> = curves
        .iter()
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

/// DECISION: by default a path may stray from the reconstructed polyline by a quarter of the pen
/// width: the polyline's own wobble inside the ink is about that much.
const TOLERANCE_IN_PEN_WIDTHS: f64 = 0.25;
/// The floor of the default tolerance: half a pixel, below which a fit only follows the
/// skeleton's pixel steps.
const TOLERANCE_FLOOR_PX: f64 = 0.5;

/// DECISION: the smallest tolerance a caller may ask for: 0.01 px, the resolution of the SVG's
/// coordinates (two decimals). A smaller one changes no output byte, only the work (each halving
/// of the tolerance splits the curves into more pieces). A smaller tolerance asked for is raised
/// to it.
pub const MIN_TOLERANCE_PX: f64 = 0.01;

/// The default [`FitOptions::tolerance`] for a pen of `stroke_width` pixels: a quarter of the pen
/// width, at least 0.5 px.
pub fn default_tolerance(stroke_width: f64) -> f64 {
    (TOLERANCE_IN_PEN_WIDTHS * stroke_width).max(TOLERANCE_FLOOR_PX)
}

/// DECISION: a vertex is a corner when the curve turns by at least this much there, measured both
/// to its neighbours and to the samples two steps away. Gentle curves sampled every 1.5 pen widths
/// turn by far less; one noisy sample may exceed it at one scale but rarely at both.
const CORNER_TURN_DEGREES: f64 = 50.0;

/// Turns a polyline into a path; closed polylines end with `ClosePath`. A tolerance below
/// [`MIN_TOLERANCE_PX`] (or not a number) is raised to it.
pub fn fit_curve(curve: &Polyline, options: &FitOptions) -> BezPath {
    let options = &FitOptions {
        tolerance: options.tolerance.max(MIN_TOLERANCE_PX),
        ..*options
    };
    let points = &curve.points;
    let closed = curve.closed && points.len() > 2;
    if !options.smooth || points.len() < 3 {
        let simplified = simplify_polyline(points, closed, options.tolerance);
        return CurvePath::polyline(&simplified, closed).path;
    }
    let corners = find_corners(points, closed);
    let mut path = BezPath::new();
    if closed && corners.is_empty() {
        // A smooth loop: one periodic run, its seam as smooth as the rest.
        let smoothed = smooth_interior(points, true, &[]);
        let dense = densify_catmull_rom(&smoothed, true);
        path.move_to(dense[0]);
        fit_run(&dense, true, options.tolerance, &mut path);
        path.close_path();
        return path;
    }
    // Rotate a closed curve to start at a corner, so every run goes corner to corner.
    let mut ordered = points.to_vec();
    let mut corner_indices = corners.clone();
    if closed {
        let start = corners[0];
        ordered.rotate_left(start);
        ordered.push(ordered[0]);
        corner_indices = corners
            .iter()
            .map(|&c| (c + points.len() - start) % points.len())
            .collect();
        corner_indices.push(ordered.len() - 1);
    }
    let smoothed = smooth_interior(&ordered, false, &corner_indices);
    let mut breaks: Vec<usize> = vec![0];
    breaks.extend(corner_indices.iter().copied().filter(|&c| c != 0));
    if *breaks.last().expect("has a start") != smoothed.len() - 1 {
        breaks.push(smoothed.len() - 1);
    }
    breaks.dedup();
    path.move_to(smoothed[0]);
    for run in breaks.windows(2) {
        let dense = densify_catmull_rom(&smoothed[run[0]..=run[1]], false);
        fit_run(&dense, false, options.tolerance, &mut path);
    }
    if closed {
        path.close_path();
    }
    path
}

/// DECISION: the Catmull–Rom spline through the samples is evaluated at this many points per
/// sample interval; the fit follows that dense polyline, so its tolerance holds between samples
/// too, not only at them.
const SPLINE_POINTS_PER_INTERVAL: usize = 4;

/// Points along the uniform Catmull–Rom spline through `points` (ends included; a periodic run
/// ends where it starts).
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

/// Fits the dense polyline `data` with as few cubics as the tolerance allows and appends them to
/// `path` (whose current point is `data[0]`): Schneider's fit-and-split (*An algorithm for
/// automatically fitting digitized curves*, Graphics Gems, 1990). Every accepted cubic stays
/// within `tolerance` of its piece of `data` at the data points and between them, and its
/// control points stay inside the piece's bounding box grown by the tolerance; a piece that no
/// cubic fits is split at its worst point, and a piece of two points is a straight segment. Each
/// split shortens the piece, so the fit always ends; [`FIT_WORK_PER_POINT`] keeps the work
/// O(n log n) whatever the input. This replaces `kurbo::simplify_bezpath`, which
/// loops forever on some inputs (kurbo issue #602) and overshoots on others (#604, #605).
fn fit_run(data: &[Point], periodic: bool, tolerance: f64, path: &mut BezPath) {
    let budget = FIT_WORK_PER_POINT.saturating_mul(data.len());
    fit_run_within(data, periodic, tolerance, budget, path);
}

/// [`fit_run`] with a work budget: fitting a piece costs its length, and once `budget` is spent
/// pieces are halved instead of cut at their worst point.
fn fit_run_within(
    data: &[Point],
    periodic: bool,
    tolerance: f64,
    mut budget: usize,
    path: &mut BezPath,
) {
    let n = data.len();
    if n < 2 {
        return;
    }
    let direction = |from: Point, to: Point| -> Vec2 {
        let d = to - from;
        let length = d.hypot();
        if length > 0.0 {
            d / length
        } else {
            Vec2::ZERO
        }
    };
    // Tangents point into the piece at both ends. A periodic run has one tangent at its seam.
    // Tangents are measured one sample interval away, where the spline's own wobble between two
    // samples averages out.
    let reach = SPLINE_POINTS_PER_INTERVAL.min(n - 1);
    let (start_tangent, end_tangent) = if periodic && n > 2 {
        let reach = reach.min((n - 1) / 2).max(1);
        let seam = direction(data[n - 1 - reach], data[reach]);
        (seam, -seam)
    } else {
        (
            direction(data[0], data[reach]),
            direction(data[n - 1], data[n - 1 - reach]),
        )
    };
    // Pieces waiting to be fitted, last first, so cubics come out in order.
    let mut pending = vec![(0usize, n - 1, start_tangent, end_tangent)];
    while let Some((first, last, t0, t1)) = pending.pop() {
        let piece = &data[first..=last];
        if piece.len() == 2 {
            path.line_to(piece[1]);
            continue;
        }
        budget = budget.saturating_sub(piece.len());
        match fit_cubic(piece, t0, t1, tolerance) {
            Ok(cubic) => path.curve_to(cubic.p1, cubic.p2, cubic.p3),
            Err(worst) => {
                // Past the budget, halve the piece instead of cutting at its worst point.
                let worst = if budget > 0 { worst } else { piece.len() / 2 };
                let split = first + worst.clamp(1, piece.len() - 2);
                let reach = (split - first).min(last - split).min(reach);
                let centre = direction(data[split + reach], data[split - reach]);
                let centre = if centre == Vec2::ZERO {
                    direction(data[split], data[split - 1])
                } else {
                    centre
                };
                pending.push((split, last, -centre, t1));
                pending.push((first, split, t0, centre));
            }
        }
    }
}

/// DECISION: a run's fit may try, on average, this many cubics through each of its points. A
/// split at the worst point can peel a sliver off a long piece at a time and then costs O(n²)
/// (a 4000 × 4000 spiral, one run of 1.8 million points: 7 s); past the budget pieces are halved,
/// so what is left costs O(n log n). The samples and the 12 MP page use at most 9.
const FIT_WORK_PER_POINT: usize = 32;

/// DECISION: reparameterize by Newton's method at most this many times, and only while the error
/// is within this factor of the tolerance (farther off, splitting is the cheaper cure).
const NEWTON_ITERATIONS: usize = 4;
const NEWTON_ERROR_FACTOR: f64 = 4.0;

/// One cubic for `piece` with the given end tangents, or the index of the piece's worst point.
fn fit_cubic(piece: &[Point], t0: Vec2, t1: Vec2, tolerance: f64) -> Result<CubicBez, usize> {
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
    if stays_near_piece(&cubic, piece, &parameters, tolerance) {
        Ok(cubic)
    } else {
        // Near the data but bulging between points or overshooting with its handles: the piece
        // is too long for one cubic, halve it.
        Err(piece.len() / 2)
    }
}

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
    let (mut alpha0, mut alpha1) = if determinant.abs() > 1e-12 * (c00 * c11).max(1e-300) {
        (
            (x0 * c11 - x1 * c01) / determinant,
            (c00 * x1 - c01 * x0) / determinant,
        )
    } else {
        (0.0, 0.0)
    };
    let floor = 1e-6 * chord;
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
    if denominator.abs() < 1e-12 || !denominator.is_finite() {
        return u;
    }
    (u - numerator / denominator).clamp(0.0, 1.0)
}

/// DECISION: between two data points the cubic is checked at this many points.
const CHECKS_PER_INTERVAL: usize = 4;

/// Whether the cubic stays near its piece everywhere: its control points inside the piece's
/// bounding box grown by the tolerance (a cubic whose handles leave it is overshooting), and its
/// points between data points within the tolerance of the nearby stretch of the polyline.
fn stays_near_piece(cubic: &CubicBez, piece: &[Point], parameters: &[f64], tolerance: f64) -> bool {
    let mut bounds = Rect::from_points(piece[0], piece[0]);
    for &p in piece {
        bounds = bounds.union_pt(p);
    }
    let grown = bounds.inflate(tolerance, tolerance);
    if !grown.contains(cubic.p1) || !grown.contains(cubic.p2) {
        return false;
    }
    let last = piece.len() - 1;
    for k in 0..last {
        // The stretch of polyline the cubic may be near between parameters k and k + 1.
        let (from, to) = (k.saturating_sub(1), (k + 2).min(last));
        for step in 1..CHECKS_PER_INTERVAL {
            let t = step as f64 / CHECKS_PER_INTERVAL as f64;
            let u = parameters[k] + t * (parameters[k + 1] - parameters[k]);
            let q = cubic.eval(u);
            let near = (from..to)
                .map(|i| {
                    Line::new(piece[i], piece[i + 1])
                        .nearest(q, 1e-9)
                        .distance_sq
                })
                .fold(f64::INFINITY, f64::min);
            if near > tolerance * tolerance {
                return false;
            }
        }
    }
    true
}

fn turn_degrees(incoming: Vec2, outgoing: Vec2) -> f64 {
    if incoming.hypot2() == 0.0 || outgoing.hypot2() == 0.0 {
        return 0.0;
    }
    incoming
        .cross(outgoing)
        .atan2(incoming.dot(outgoing))
        .abs()
        .to_degrees()
}

/// Indices of the corner vertices, with non-maximum suppression between neighbours.
fn find_corners(points: &[Point], closed: bool) -> Vec<usize> {
    let n = points.len();
    let at = |i: isize| -> Option<Point> {
        if closed {
            Some(points[i.rem_euclid(n as isize) as usize])
        } else if (0..n as isize).contains(&i) {
            Some(points[i as usize])
        } else {
            None
        }
    };
    let turn_at_scale = |i: usize, step: isize| -> Option<f64> {
        let (before, here, after) = (at(i as isize - step)?, points[i], at(i as isize + step)?);
        Some(turn_degrees(here - before, after - here))
    };
    let turns: Vec<f64> = (0..n)
        .map(|i| {
            let near = turn_at_scale(i, 1).unwrap_or(0.0);
            // Near an open end there is no second scale: trust the first.
            let far = turn_at_scale(i, 2).unwrap_or(near);
            near.min(far)
        })
        .collect();
    (0..n)
        .filter(|&i| turns[i] >= CORNER_TURN_DEGREES)
        .filter(|&i| {
            // A rounded corner turns at two neighbouring samples: keep the sharper (ties go to
            // the earlier one).
            let previous = if closed || i > 0 {
                turns[(i + n - 1) % n]
            } else {
                0.0
            };
            let next = if closed || i + 1 < n {
                turns[(i + 1) % n]
            } else {
                0.0
            };
            turns[i] > previous && turns[i] >= next
        })
        .filter(|&i| closed || (i > 0 && i + 1 < n))
        .collect()
}

/// One pass of [1/4, 1/2, 1/4] smoothing on every vertex except the ends of an open chain and
/// the `fixed` ones (corners): it takes out the skeleton's pixel jitter without moving corners.
fn smooth_interior(points: &[Point], closed: bool, fixed: &[usize]) -> Vec<Point> {
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
            Point::new(
                0.25 * before.x + 0.5 * points[i].x + 0.25 * after.x,
                0.25 * before.y + 0.5 * points[i].y + 0.25 * after.y,
            )
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
    /// `kurbo::simplify_bezpath` never returned): every fit returns, and every cubic stays near
    /// its chain with its control points near the chain's bounding box.
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
            let closed = case % 2 == 0;
            let tolerance = [0.0, 0.1, 0.5, 1.75][case % 4];
            let path = fit_curve(
                &Polyline::new(points.clone(), closed),
                &FitOptions {
                    smooth: true,
                    tolerance,
                },
            );
            let longest_step = 3.0;
            let allowed = tolerance + longest_step;
            let bounds = points
                .iter()
                .fold(Rect::from_points(points[0], points[0]), |r, &q| {
                    r.union_pt(q)
                })
                .inflate(allowed, allowed);
            for element in path.elements() {
                if let PathEl::CurveTo(a, b, _) = element {
                    assert!(
                        bounds.contains(*a) && bounds.contains(*b),
                        "case {case}: a control point leaves the chain: {element:?}"
                    );
                }
            }
            let worst = path
                .segments()
                .flat_map(|segment| (0..=16).map(move |k| segment.eval(k as f64 / 16.0)))
                .map(|q| distance_to_chain(q, &points, closed))
                .fold(0.0, f64::max);
            assert!(
                worst <= allowed,
                "case {case}: the path strays {worst:.2} px"
            );
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
            let mut path = BezPath::new();
            path.move_to(dense[0]);
            fit_run_within(&dense, false, tolerance, budget, &mut path);
            let worst = path
                .segments()
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
        };
        let path = fit_curve(&Polyline::new(points.clone(), false), &options);
        assert_eq!(path.elements().len(), 2, "{path:?}");
        assert!(path
            .elements()
            .iter()
            .all(|e| !matches!(e, PathEl::CurveTo(..))));
    }
}
