//! True curves of the samples: dense polylines in image pixel coordinates with their arc length,
//! their sharp corners, and the simplified form written to the ground-truth SVG.

use kurbo::{Affine, BezPath, PathEl, Point, Vec2};

/// Flattening tolerance for Béziers and arcs, in pixels: far below anything visible.
const FLATTEN_TOLERANCE: f64 = 0.01;
/// Longest segment of a dense curve, in pixels.
const MAX_STEP: f64 = 0.5;
/// A vertex where the direction turns by more than this is a sharp corner.
const CORNER_TURN_DEGREES: f64 = 30.0;

/// One true curve: the geometry the sketch is drawn from and the tracer should give back.
#[derive(Clone, Debug)]
pub struct TrueCurve {
    /// Dense vertices, at most [`MAX_STEP`] apart; closed curves repeat the first at the end.
    points: Vec<Point>,
    /// Arc length from the start to each vertex.
    lengths: Vec<f64>,
    /// Whether the curve is closed.
    pub closed: bool,
    /// Arc-length positions of the sharp corners.
    pub corners: Vec<f64>,
}

impl TrueCurve {
    /// One curve per subpath of `path`; a subpath is closed when it ends with `Z`.
    pub fn from_path(path: &BezPath) -> Vec<TrueCurve> {
        let mut curves = Vec::new();
        let mut points: Vec<Point> = Vec::new();
        let mut finish = |points: &mut Vec<Point>, closed: bool| {
            if points.len() > 1 {
                curves.push(TrueCurve::from_points(std::mem::take(points), closed));
            }
            points.clear();
        };
        kurbo::flatten(path, FLATTEN_TOLERANCE, |element| match element {
            PathEl::MoveTo(point) => {
                finish(&mut points, false);
                points.push(point);
            }
            PathEl::LineTo(point) => points.push(point),
            PathEl::ClosePath => finish(&mut points, true),
            // `flatten` only emits lines.
            PathEl::QuadTo(..) | PathEl::CurveTo(..) => unreachable!(),
        });
        finish(&mut points, false);
        curves
    }

    /// A curve through `vertices` (open, or closed back to the first one).
    pub fn from_points(vertices: Vec<Point>, closed: bool) -> TrueCurve {
        // Drop repeated vertices: they have no direction and would fake corners.
        let mut distinct: Vec<Point> = Vec::with_capacity(vertices.len() + 1);
        for vertex in vertices {
            if distinct
                .last()
                .is_none_or(|last| last.distance(vertex) > 0.05)
            {
                distinct.push(vertex);
            }
        }
        if closed && distinct.len() > 1 && distinct[0].distance(*distinct.last().unwrap()) <= 0.05 {
            distinct.pop();
        }
        if closed {
            distinct.push(distinct[0]);
        }
        let corner_vertices = corner_vertices(&distinct, closed);
        let mut points = vec![distinct[0]];
        let mut lengths = vec![0.0];
        let mut corners = Vec::new();
        if corner_vertices.contains(&0) {
            corners.push(0.0);
        }
        for (index, pair) in distinct.windows(2).enumerate() {
            let steps = (pair[0].distance(pair[1]) / MAX_STEP).ceil().max(1.0) as usize;
            for step in 1..=steps {
                let point = pair[0].lerp(pair[1], step as f64 / steps as f64);
                let length = lengths.last().unwrap() + points.last().unwrap().distance(point);
                points.push(point);
                lengths.push(length);
            }
            let vertex = index + 1;
            if corner_vertices.contains(&vertex) && !(closed && vertex == distinct.len() - 1) {
                corners.push(*lengths.last().unwrap());
            }
        }
        TrueCurve {
            points,
            lengths,
            closed,
            corners,
        }
    }

    /// The same curve moved by `transform` (a similarity, so corners stay corners).
    pub fn transformed(&self, transform: Affine) -> TrueCurve {
        let mut vertices: Vec<Point> = self.points.iter().map(|&p| transform * p).collect();
        if self.closed {
            vertices.pop();
        }
        TrueCurve::from_points(vertices, self.closed)
    }

    /// Total arc length (closed curves include the closing segment).
    pub fn length(&self) -> f64 {
        *self.lengths.last().unwrap()
    }

    /// The point at arc length `position`, wrapping around closed curves, with the unit normal there
    /// (normals are averaged at vertices, so an offset curve stays joined at corners).
    pub fn point_and_normal(&self, position: f64) -> (Point, Vec2) {
        let length = self.length();
        let position = if self.closed {
            position.rem_euclid(length)
        } else {
            position.clamp(0.0, length)
        };
        let next = self.lengths.partition_point(|&l| l <= position);
        let index = next.clamp(1, self.points.len() - 1) - 1;
        let segment = self.lengths[index + 1] - self.lengths[index];
        let t = if segment > 0.0 {
            ((position - self.lengths[index]) / segment).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let point = self.points[index].lerp(self.points[index + 1], t);
        let normal = self
            .vertex_normal(index)
            .lerp(self.vertex_normal(index + 1), t);
        (point, normal.normalize())
    }

    /// Arc-length positions of the vertices strictly between `start` and `end` (`end` may exceed
    /// the length of a closed curve: positions then continue on the next lap).
    pub fn vertex_positions_between(&self, start: f64, end: f64) -> Vec<f64> {
        let length = self.length();
        let laps = if self.closed { 3 } else { 1 };
        let mut positions = Vec::new();
        for lap in 0..laps {
            let offset = lap as f64 * length;
            // On a closed curve the last vertex is the first one again.
            let count = self.lengths.len() - usize::from(self.closed);
            for &vertex_length in &self.lengths[..count] {
                let position = vertex_length + offset;
                if position > start && position < end {
                    positions.push(position);
                }
            }
        }
        positions
    }

    /// The curve with as few vertices as keep it within `tolerance` pixels
    /// (Ramer–Douglas–Peucker); closed curves do not repeat the first vertex.
    pub fn simplified(&self, tolerance: f64) -> Vec<Point> {
        if !self.closed {
            return simplify(&self.points, tolerance);
        }
        // Split the loop at the vertex farthest from the start, so both halves are proper chains.
        let start = self.points[0];
        let far = (0..self.points.len())
            .max_by(|&a, &b| {
                start
                    .distance(self.points[a])
                    .total_cmp(&start.distance(self.points[b]))
            })
            .unwrap();
        let mut result = simplify(&self.points[..=far], tolerance);
        result.pop();
        result.extend(simplify(&self.points[far..], tolerance));
        result.pop();
        result
    }

    fn vertex_normal(&self, index: usize) -> Vec2 {
        let last = self.points.len() - 1;
        let direction = |from: usize, to: usize| (self.points[to] - self.points[from]).normalize();
        let incoming = if index > 0 {
            Some(direction(index - 1, index))
        } else if self.closed {
            Some(direction(last - 1, last))
        } else {
            None
        };
        let outgoing = if index < last {
            Some(direction(index, index + 1))
        } else if self.closed {
            Some(direction(0, 1))
        } else {
            None
        };
        let tangent = match (incoming, outgoing) {
            (Some(a), Some(b)) if (a + b).hypot() > 1e-6 => (a + b).normalize(),
            (Some(a), _) => a,
            (None, Some(b)) => b,
            (None, None) => Vec2::new(1.0, 0.0),
        };
        Vec2::new(-tangent.y, tangent.x)
    }
}

/// Indices of the vertices where the polyline turns sharply.
fn corner_vertices(vertices: &[Point], closed: bool) -> Vec<usize> {
    let last = vertices.len() - 1;
    let threshold = CORNER_TURN_DEGREES.to_radians();
    let mut corners = Vec::new();
    for index in 0..=last {
        let (before, after) = match index {
            0 if closed => (last - 1, 1),
            i if i == last || i == 0 => continue,
            i => (i - 1, i + 1),
        };
        let incoming = vertices[index] - vertices[before];
        let outgoing = vertices[after] - vertices[index];
        let turn = incoming.cross(outgoing).atan2(incoming.dot(outgoing)).abs();
        if turn > threshold {
            corners.push(index);
        }
    }
    corners
}

/// Ramer–Douglas–Peucker on an open chain, keeping both ends.
fn simplify(points: &[Point], tolerance: f64) -> Vec<Point> {
    let mut keep = vec![false; points.len()];
    keep[0] = true;
    keep[points.len() - 1] = true;
    let mut pending = vec![(0, points.len() - 1)];
    while let Some((first, last)) = pending.pop() {
        let (mut farthest, mut distance) = (first, 0.0);
        for index in first + 1..last {
            let d = segment_distance(points[index], points[first], points[last]);
            if d > distance {
                (farthest, distance) = (index, d);
            }
        }
        if distance > tolerance {
            keep[farthest] = true;
            pending.push((first, farthest));
            pending.push((farthest, last));
        }
    }
    points
        .iter()
        .zip(keep)
        .filter_map(|(&point, kept)| kept.then_some(point))
        .collect()
}

fn segment_distance(point: Point, a: Point, b: Point) -> f64 {
    let along = b - a;
    let squared = along.hypot2();
    if squared == 0.0 {
        return point.distance(a);
    }
    let t = ((point - a).dot(along) / squared).clamp(0.0, 1.0);
    point.distance(a + along * t)
}
