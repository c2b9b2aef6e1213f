//! Polylines: ordered chains of points, open or closed, with their length, Ramer–Douglas–Peucker
//! simplification (U. Ramer, Computer Graphics and Image Processing 1(3), 1972; D. Douglas and
//! T. Peucker, The Canadian Cartographer 10(2), 1973) and resampling at a spacing.

use kurbo::{Point, Rect, Vec2};

/// An ordered chain of points; a closed one joins its last point back to its first, which it does
/// not repeat.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Polyline {
    /// The points in order.
    pub points: Vec<Point>,
    /// Whether the last point joins the first.
    pub closed: bool,
}

impl Polyline {
    /// A polyline through `points`, closed or open.
    pub fn new(points: Vec<Point>, closed: bool) -> Self {
        Self { points, closed }
    }

    /// The length, the closing segment included when closed.
    pub fn length(&self) -> f64 {
        polyline_length(&self.points, self.closed)
    }

    /// Ramer–Douglas–Peucker simplification: a subset of the points (always including both ends
    /// of an open polyline) within `tolerance` of the original.
    pub fn simplify(&self, tolerance: f64) -> Self {
        Self::new(
            simplify_polyline(&self.points, self.closed, tolerance),
            self.closed,
        )
    }

    /// The polyline with evenly spaced points inserted into every segment longer than
    /// `spacing`, so that no two consecutive points are farther apart.
    pub fn resample(&self, spacing: f64) -> Self {
        Self::new(subdivide(&self.points, self.closed, spacing), self.closed)
    }
}

/// Twice the signed area of the closed polygon through `points` (positive counter-clockwise in
/// y-up axes; the shoelace formula).
pub fn signed_area(points: &[Point]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|k| {
            let (a, b) = (points[k], points[(k + 1) % n]);
            a.x * b.y - b.x * a.y
        })
        .sum()
}

/// Whether `p` lies within `reach` of the chain `points` (of its segments, not only its points).
pub(crate) fn within_of_chain(p: Point, points: &[Point], reach: f64) -> bool {
    points
        .windows(2)
        .any(|pair| distance_to_segment(p, kurbo::Line::new(pair[0], pair[1])) <= reach)
}

/// The box of `points` grown by `reach` on every side; an empty box for no points.
pub(crate) fn grown_bounding_box(points: &[Point], reach: f64) -> Rect {
    if points.is_empty() {
        Rect::ZERO
    } else {
        bounding_box(points).inflate(reach, reach)
    }
}

/// Whether `p` lies inside the closed polygon `ring` (even-odd rule).
pub(crate) fn polygon_contains(ring: &[Point], p: Point) -> bool {
    let n = ring.len();
    let mut inside = false;
    for k in 0..n {
        let (u, v) = (ring[k], ring[(k + 1) % n]);
        if (u.y > p.y) != (v.y > p.y) && p.x < u.x + (p.y - u.y) / (v.y - u.y) * (v.x - u.x) {
            inside = !inside;
        }
    }
    inside
}

/// The bounding box of `points` (at least one).
pub(crate) fn bounding_box(points: &[Point]) -> Rect {
    points
        .iter()
        .fold(Rect::from_points(points[0], points[0]), |r, &p| {
            r.union_pt(p)
        })
}

/// The distance along the chain `points` from its first point to each of its points (0 for the
/// first).
pub fn distances_along(points: &[Point]) -> Vec<f64> {
    let mut along = vec![0.0; points.len()];
    for k in 1..points.len() {
        along[k] = along[k - 1] + points[k - 1].distance(points[k]);
    }
    along
}

/// The length of an ordered chain of points, including the closing segment if `closed`
/// ([`Polyline::length`] for points held elsewhere).
pub fn polyline_length(points: &[Point], closed: bool) -> f64 {
    let open: f64 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
    match (closed, points.first(), points.last()) {
        (true, Some(&first), Some(&last)) => open + first.distance(last),
        _ => open,
    }
}

/// [`Polyline::simplify`] on points held elsewhere.
pub fn simplify_polyline(points: &[Point], closed: bool, tolerance: f64) -> Vec<Point> {
    if points.len() <= 2 {
        return points.to_vec();
    }
    let kept = simplification_mask(points, closed, tolerance);
    points
        .iter()
        .zip(&kept)
        .filter(|(_, &k)| k)
        .map(|(&p, _)| p)
        .collect()
}

/// Which points Ramer–Douglas–Peucker keeps; a closed chain is split at the point farthest
/// from its first point and both halves are simplified.
pub(crate) fn simplification_mask(points: &[Point], closed: bool, tolerance: f64) -> Vec<bool> {
    if closed {
        // Split the loop at the point farthest from the first one, and simplify both halves.
        let far = (1..points.len())
            .max_by(|&a, &b| {
                points[0]
                    .distance_squared(points[a])
                    .total_cmp(&points[0].distance_squared(points[b]))
                    .then(b.cmp(&a))
            })
            .expect("more than two points");
        let mut keep = vec![false; points.len()];
        keep[0] = true;
        keep[far] = true;
        douglas_peucker(points, 0, far, tolerance, &mut keep);
        let mut wrapped: Vec<Point> = points[far..].to_vec();
        wrapped.push(points[0]);
        let mut keep_wrapped = vec![false; wrapped.len()];
        douglas_peucker(&wrapped, 0, wrapped.len() - 1, tolerance, &mut keep_wrapped);
        for (k, &kept) in keep_wrapped.iter().enumerate().take(wrapped.len() - 1) {
            keep[far + k] |= kept;
        }
        keep
    } else {
        let mut keep = vec![false; points.len()];
        keep[0] = true;
        keep[points.len() - 1] = true;
        douglas_peucker(points, 0, points.len() - 1, tolerance, &mut keep);
        keep
    }
}

/// DECISION: Douglas–Peucker may measure, on average, this many distances per point. It splits
/// a range at its farthest point, which on a spiral peels off a sliver at a time and costs
/// O(n²) (a 4000 × 4000 spiral: 3.4 s); past the budget the remaining ranges are split in the
/// middle, which halves them (O(n log n) for the rest) and still drops only points within the
/// tolerance. The samples and the 12 MP page use at most 7.
const SIMPLIFY_WORK_PER_POINT: usize = 32;

/// Marks the points of `points[first..=last]` that Ramer–Douglas–Peucker keeps at `tolerance`;
/// the work is bounded by [`SIMPLIFY_WORK_PER_POINT`].
fn douglas_peucker(points: &[Point], first: usize, last: usize, tolerance: f64, keep: &mut [bool]) {
    let mut budget = SIMPLIFY_WORK_PER_POINT.saturating_mul(last - first + 1);
    // An explicit stack: skeleton branches can be thousands of pixels long.
    let mut stack = vec![(first, last)];
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let line = kurbo::Line::new(points[a], points[b]);
        let (mut farthest, mut distance) = (a, -1.0);
        for (k, &p) in points.iter().enumerate().take(b).skip(a + 1) {
            let d = distance_to_segment(p, line);
            if d > distance {
                farthest = k;
                distance = d;
            }
        }
        budget = budget.saturating_sub(b - a);
        if distance > tolerance {
            let split = if budget > 0 {
                farthest
            } else {
                a + (b - a) / 2
            };
            keep[split] = true;
            stack.push((a, split));
            stack.push((split, b));
        }
    }
}

/// The signed turn (radians, counter-clockwise positive, in -π..π) from the direction `incoming`
/// to the direction `outgoing`: how much a path going along one turns to go along the other.
pub(crate) fn signed_turn(incoming: Vec2, outgoing: Vec2) -> f64 {
    incoming.cross(outgoing).atan2(incoming.dot(outgoing))
}

/// Whether the segments `a0`–`a1` and `b0`–`b1` cross at a point inside both (touching or
/// overlapping is no crossing).
pub(crate) fn segments_cross(a0: Point, a1: Point, b0: Point, b1: Point) -> bool {
    let side = |p: Point, q0: Point, q1: Point| (q1 - q0).cross(p - q0);
    side(b0, a0, a1) * side(b1, a0, a1) < 0.0 && side(a0, b0, b1) * side(a1, b0, b1) < 0.0
}

/// Where the line through `a0 → a1` meets the line through `b0 → b1`; none for lines whose
/// angle's sine is below `min_sine` (near-parallel), or where either is a single point.
pub(crate) fn lines_meet(
    a0: Point,
    a1: Point,
    b0: Point,
    b1: Point,
    min_sine: f64,
) -> Option<Point> {
    let (da, db) = (a1 - a0, b1 - b0);
    let denominator = da.cross(db);
    if da.hypot() == 0.0
        || db.hypot() == 0.0
        || denominator.abs() < min_sine * da.hypot() * db.hypot()
    {
        return None;
    }
    let t = (b0 - a0).cross(db) / denominator;
    Some(a0 + da * t)
}

/// The index of the point of `points` nearest to `to` (the first of equally near ones); `None`
/// for no points.
pub(crate) fn nearest_point_index(points: &[Point], to: Point) -> Option<usize> {
    (0..points.len()).min_by(|&a, &b| points[a].distance(to).total_cmp(&points[b].distance(to)))
}

/// The points of a closed curve after `points[from]` up to and including `points[to]`, going on
/// round past the last point to the first.
pub(crate) fn points_round_after(points: &[Point], from: usize, to: usize) -> Vec<Point> {
    let n = points.len();
    let mut stretch = Vec::new();
    let mut k = (from + 1) % n;
    loop {
        stretch.push(points[k]);
        if k == to {
            return stretch;
        }
        k = (k + 1) % n;
    }
}

/// The point `length` along the curve `points` from `points[k]`, forwards or backwards (round
/// from the last point to the first where the curve is `closed`, at most once round); none where
/// the curve is shorter than that.
pub(crate) fn point_along(
    points: &[Point],
    closed: bool,
    k: usize,
    length: f64,
    forwards: bool,
) -> Option<Point> {
    let n = points.len();
    let mut walked = 0.0;
    let mut at = k;
    for _ in 0..n {
        let next = match (closed, forwards) {
            (false, true) => (at + 1 < n).then_some(at + 1)?,
            (false, false) => at.checked_sub(1)?,
            (true, true) => (at + 1) % n,
            (true, false) => (at + n - 1) % n,
        };
        let step = points[at].distance(points[next]);
        if walked + step >= length {
            // Within this segment: a long one (a bridge) holds the point wherever it falls.
            let t = if step > 0.0 {
                (length - walked) / step
            } else {
                0.0
            };
            return Some(points[at].lerp(points[next], t));
        }
        walked += step;
        at = next;
    }
    None
}

/// The distance from `p` to the nearest point of the segment `line`.
pub(crate) fn distance_to_segment(p: Point, line: kurbo::Line) -> f64 {
    use kurbo::ParamCurveNearest;
    // The accuracy argument is for curves: a line's nearest point is computed exactly.
    line.nearest(p, 1e-9).distance_sq.sqrt()
}

/// Inserts evenly spaced points into every segment longer than `spacing`.
fn subdivide(vertices: &[Point], closed: bool, spacing: f64) -> Vec<Point> {
    let mut samples = Vec::with_capacity(vertices.len());
    let segment_count = if closed {
        vertices.len()
    } else {
        vertices.len().saturating_sub(1)
    };
    if vertices.len() == 1 || segment_count == 0 {
        return vertices.to_vec();
    }
    for k in 0..segment_count {
        let (a, b) = (vertices[k], vertices[(k + 1) % vertices.len()]);
        samples.push(a);
        let pieces = (a.distance(b) / spacing).ceil().max(1.0) as usize;
        for step in 1..pieces {
            samples.push(a.lerp(b, step as f64 / pieces as f64));
        }
    }
    if !closed {
        samples.push(vertices[vertices.len() - 1]);
    }
    samples
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Simplified within `tolerance`, then resampled every `spacing`: how strokes are sampled.
    fn sample_polyline(points: &[Point], closed: bool, spacing: f64, tolerance: f64) -> Vec<Point> {
        Polyline::new(points.to_vec(), closed)
            .simplify(tolerance)
            .resample(spacing)
            .points
    }

    #[test]
    fn a_corner_and_both_ends_are_kept() {
        // An L of pixel centres: 10 right, then 10 down.
        let mut points: Vec<Point> = (0..=10).map(|x| Point::new(x as f64, 0.0)).collect();
        points.extend((1..=10).map(|y| Point::new(10.0, y as f64)));
        let samples = sample_polyline(&points, false, 3.0, 0.7);
        assert_eq!(samples.first(), Some(&Point::new(0.0, 0.0)));
        assert_eq!(samples.last(), Some(&Point::new(10.0, 10.0)));
        assert!(samples.contains(&Point::new(10.0, 0.0)), "{samples:?}");
        for pair in samples.windows(2) {
            let d = pair[0].distance(pair[1]);
            assert!(d <= 3.0 + 1e-9 && d > 1.0, "{samples:?}");
        }
    }

    #[test]
    fn a_loop_is_sampled_all_round_without_repeating_its_start() {
        let points: Vec<Point> = (0..64)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 64.0;
                Point::new(20.0 * a.cos(), 20.0 * a.sin())
            })
            .collect();
        let samples = sample_polyline(&points, true, 4.0, 0.5);
        assert_ne!(samples.first(), samples.last());
        let perimeter: f64 = (0..samples.len())
            .map(|k| samples[k].distance(samples[(k + 1) % samples.len()]))
            .sum();
        assert!(
            (perimeter - std::f64::consts::TAU * 20.0).abs() < 2.0,
            "{perimeter}"
        );
        for k in 0..samples.len() {
            let d = samples[k].distance(samples[(k + 1) % samples.len()]);
            assert!(d <= 4.0 + 1e-9, "gap {d} at {k}");
        }
    }

    #[test]
    fn wobble_below_the_tolerance_is_removed() {
        let points: Vec<Point> = (0..40)
            .map(|x| Point::new(x as f64, if x % 2 == 0 { 0.0 } else { 0.5 }))
            .collect();
        let samples = sample_polyline(&points, false, 100.0, 0.7);
        assert_eq!(samples.len(), 2, "{samples:?}");
    }

    #[test]
    fn tiny_inputs_pass_through() {
        assert!(sample_polyline(&[], false, 3.0, 0.7).is_empty());
        let dot = [Point::new(1.0, 1.0)];
        assert_eq!(sample_polyline(&dot, false, 3.0, 0.7), dot.to_vec());
        let pair = [Point::new(0.0, 0.0), Point::new(7.0, 0.0)];
        assert_eq!(sample_polyline(&pair, false, 3.0, 0.7).len(), 4);
    }

    /// A spiral of many turns makes plain Douglas–Peucker peel one sliver at a time (quadratic);
    /// past its work budget the simplification splits in the middle instead. Either way every
    /// dropped point must stay within the tolerance of the kept polyline.
    #[test]
    fn a_long_spiral_is_simplified_within_the_tolerance() {
        let points: Vec<Point> = (0..40_000)
            .map(|k| {
                let angle = k as f64 * 0.01;
                let radius = 2.0 + 1.5 * angle;
                Point::new(radius * angle.cos(), radius * angle.sin())
            })
            .collect();
        let tolerance = 0.7;
        let keep = simplification_mask(&points, false, tolerance);
        let kept: Vec<usize> = (0..points.len()).filter(|&k| keep[k]).collect();
        assert!(
            kept.len() > 100 && kept.len() < points.len() / 4,
            "{}",
            kept.len()
        );
        for pair in kept.windows(2) {
            let line = kurbo::Line::new(points[pair[0]], points[pair[1]]);
            for (k, &p) in points.iter().enumerate().take(pair[1]).skip(pair[0] + 1) {
                let distance = distance_to_segment(p, line);
                assert!(distance <= tolerance, "point {k} is {distance} px off");
            }
        }
    }
}
