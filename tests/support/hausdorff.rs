//! Symmetric Hausdorff distance between polylines: every point of one, sampled at quarter-pixel
//! steps, against the segments of the other. Segments are grouped in runs with bounding boxes, so
//! most of them are never measured (the early-break idea of Taha & Hanbury, PAMI 2015).

use crawltrace::Point;

use super::Polyline;

/// Points along a polyline are taken at most this far apart, in pixels.
const SAMPLE_STEP: f64 = 0.25;
/// Consecutive segments per bounding box.
const RUN: usize = 16;

/// A polyline prepared for distance queries.
pub struct Indexed {
    samples: Vec<Point>,
    segments: Vec<(Point, Point)>,
    /// Bounding box (low, high) of each run of [`RUN`] segments.
    runs: Vec<(Point, Point)>,
    bounds: (Point, Point),
}

impl Indexed {
    pub fn new(polyline: &Polyline) -> Self {
        Self::union(std::slice::from_ref(polyline))
    }

    /// Several polylines as one set: distances to it are distances to the nearest of them.
    pub fn union(polylines: &[Polyline]) -> Self {
        let mut samples = Vec::new();
        let mut segments: Vec<(Point, Point)> = Vec::new();
        for polyline in polylines {
            let mut vertices = polyline.points.clone();
            if polyline.closed && vertices.len() > 1 {
                vertices.push(vertices[0]);
            }
            if vertices.len() == 1 {
                vertices.push(vertices[0]);
            }
            let first = segments.len();
            segments.extend(vertices.windows(2).map(|pair| (pair[0], pair[1])));
            samples.push(vertices[0]);
            for &(from, to) in &segments[first..] {
                let steps = ((from.distance(to) / SAMPLE_STEP).ceil() as usize).max(1);
                samples.extend((1..=steps).map(|s| from.lerp(to, s as f64 / steps as f64)));
            }
        }
        let runs = segments
            .chunks(RUN)
            .map(|run| bounding_box(run.iter().flat_map(|&(a, b)| [a, b])))
            .collect();
        let bounds = bounding_box(segments.iter().flat_map(|&(a, b)| [a, b]));
        Self {
            samples,
            segments,
            runs,
            bounds,
        }
    }

    /// A cheap lower bound of the Hausdorff distance: the extreme point of one bounding box side is
    /// at least that far from everything in the other.
    pub fn lower_bound(&self, other: &Indexed) -> f64 {
        let (a, b) = (self.bounds, other.bounds);
        [a.0.x - b.0.x, a.0.y - b.0.y, a.1.x - b.1.x, a.1.y - b.1.y]
            .iter()
            .fold(0.0, |bound: f64, difference| bound.max(difference.abs()))
    }

    /// The symmetric Hausdorff distance.
    pub fn hausdorff(&self, other: &Indexed) -> f64 {
        self.directed(other).max(other.directed(self))
    }

    /// The fraction of `self`'s length (its samples) that lies within `tolerance` of `other`.
    pub fn fraction_within(&self, other: &Indexed, tolerance: f64) -> f64 {
        if other.segments.is_empty() || self.samples.is_empty() {
            return 0.0;
        }
        let near = self
            .samples
            .iter()
            .filter(|&&point| {
                (0..other.runs.len()).any(|run| {
                    box_distance(other.runs[run], point) <= tolerance
                        && other.run_distance(run, point) <= tolerance
                })
            })
            .count();
        near as f64 / self.samples.len() as f64
    }

    /// The largest distance from a point of `self` to `other` (directed Hausdorff distance).
    pub fn directed(&self, other: &Indexed) -> f64 {
        self.farthest(other).0
    }

    /// The directed Hausdorff distance and the point of `self` where it is reached (the first
    /// sample when every point lies on `other`).
    pub fn farthest(&self, other: &Indexed) -> (f64, Point) {
        let mut largest: f64 = 0.0;
        let mut where_largest = self
            .samples
            .first()
            .copied()
            .unwrap_or(Point::new(0.0, 0.0));
        // Neighbouring samples are usually nearest to the same run: try it first.
        let mut hint = 0;
        for &point in &self.samples {
            let mut best = other.run_distance(hint, point);
            if best <= largest {
                // This point cannot raise the maximum; how much nearer it really is does not matter.
                continue;
            }
            for run in 0..other.runs.len() {
                if run == hint || box_distance(other.runs[run], point) >= best {
                    continue;
                }
                let distance = other.run_distance(run, point);
                if distance < best {
                    (best, hint) = (distance, run);
                    if best <= largest {
                        break;
                    }
                }
            }
            if best > largest {
                (largest, where_largest) = (best, point);
            }
        }
        (largest, where_largest)
    }

    /// Distance from `point` to the nearest segment of run `run`.
    fn run_distance(&self, run: usize, point: Point) -> f64 {
        let end = (run * RUN + RUN).min(self.segments.len());
        self.segments[run * RUN..end]
            .iter()
            .map(|&(from, to)| segment_distance(point, from, to))
            .fold(f64::INFINITY, f64::min)
    }
}

fn bounding_box(points: impl Iterator<Item = Point>) -> (Point, Point) {
    points.fold(
        (
            Point::new(f64::INFINITY, f64::INFINITY),
            Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        ),
        |(low, high), p| {
            (
                Point::new(low.x.min(p.x), low.y.min(p.y)),
                Point::new(high.x.max(p.x), high.y.max(p.y)),
            )
        },
    )
}

/// Distance from `point` to a box: a lower bound for anything inside it.
fn box_distance((low, high): (Point, Point), point: Point) -> f64 {
    let dx = (low.x - point.x).max(point.x - high.x).max(0.0);
    let dy = (low.y - point.y).max(point.y - high.y).max(0.0);
    dx.hypot(dy)
}

fn segment_distance(point: Point, from: Point, to: Point) -> f64 {
    let along = to - from;
    let squared = along.hypot2();
    if squared == 0.0 {
        return point.distance(from);
    }
    let t = ((point - from).dot(along) / squared).clamp(0.0, 1.0);
    point.distance(from + along * t)
}
