//! Curves to sample from: fine polylines of exact primitives (segments, arcs, parametric curves),
//! sampled by arc length at a given spacing, or at a spacing proportional to the local feature
//! size (Amenta, Bern & Eppstein 1998) measured on the Voronoi vertices of a dense sampling.

use std::f64::consts::TAU;

use spade::{DelaunayTriangulation, Point2, Triangulation};

/// A point as a pair, the generators' working type.
pub type Xy = (f64, f64);

pub fn distance(a: Xy, b: Xy) -> f64 {
    (a.0 - b.0).hypot(a.1 - b.1)
}

/// A curve as a fine polyline with its arc lengths; a closed one does not repeat its first point.
#[derive(Clone, Debug)]
pub struct Path {
    points: Vec<Xy>,
    closed: bool,
    /// Arc length at each fine point, and for a closed path the total length last.
    lengths: Vec<f64>,
}

/// Fine polyline steps per unit of arc length are at least this many (arcs and parametric
/// curves); the sampled points are interpolated on the fine polyline, within 1e-4 of the curve.
const FINE_STEPS_PER_UNIT: f64 = 8.0;

impl Path {
    pub fn new(points: Vec<Xy>, closed: bool) -> Self {
        let mut lengths = vec![0.0];
        let count = points.len();
        let pairs = if closed { count } else { count - 1 };
        for k in 0..pairs {
            let step = distance(points[k], points[(k + 1) % count]);
            lengths.push(lengths[k] + step);
        }
        Self {
            points,
            closed,
            lengths,
        }
    }

    pub fn closed(&self) -> bool {
        self.closed
    }

    pub fn length(&self) -> f64 {
        *self.lengths.last().expect("a path has a point")
    }

    /// The point at arc length `s` (wrapped around a closed path, clamped on an open one).
    pub fn at(&self, s: f64) -> Xy {
        let length = self.length();
        let s = if self.closed {
            s.rem_euclid(length)
        } else {
            s.clamp(0.0, length)
        };
        let i = self
            .lengths
            .partition_point(|&l| l <= s)
            .clamp(1, self.lengths.len() - 1);
        let (s0, s1) = (self.lengths[i - 1], self.lengths[i]);
        let t = if s1 > s0 { (s - s0) / (s1 - s0) } else { 0.0 };
        let a = self.points[i - 1];
        let b = self.points[i % self.points.len()];
        (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
    }

    /// `count` samples evenly spaced by arc length, the first at `phase` spacings from the start;
    /// an open path gets `count + 1` samples from end to end (phase ignored).
    pub fn even_samples(&self, count: usize, phase: f64) -> Vec<Xy> {
        let length = self.length();
        if self.closed {
            let step = length / count as f64;
            (0..count)
                .map(|k| self.at((k as f64 + phase) * step))
                .collect()
        } else {
            let step = length / count as f64;
            (0..=count).map(|k| self.at(k as f64 * step)).collect()
        }
    }

    /// Samples about `spacing` apart, each moved along the curve by up to `jitter` spacings
    /// (below 0.5, so the order along the curve is kept).
    pub fn jittered_samples(
        &self,
        random: &mut super::SplitMix64,
        spacing: f64,
        jitter: f64,
    ) -> Vec<Xy> {
        let count = ((self.length() / spacing).round() as usize).max(3);
        let step = self.length() / count as f64;
        let phase = random.unit();
        let last = if self.closed { count } else { count + 1 };
        (0..last)
            .map(|k| {
                let inner = self.closed || (k > 0 && k < count);
                let wobble = if inner {
                    random.range(-jitter, jitter)
                } else {
                    0.0
                };
                let base = if self.closed {
                    k as f64 + phase
                } else {
                    k as f64
                };
                self.at((base + wobble) * step)
            })
            .collect()
    }

    /// Samples whose spacing at arc length s is `spacing(s)`: the k-th sample sits where
    /// ∫ ds / spacing reaches k (times a factor that makes the count whole), so neighbouring
    /// spacings follow the function smoothly.
    pub fn samples_with_spacing(&self, spacing: &dyn Fn(usize) -> f64, phase: f64) -> Vec<Xy> {
        // The integral of 1 / spacing over the fine polyline, by the trapezoid rule.
        let count = self.points.len();
        let segments = if self.closed { count } else { count - 1 };
        let mut integral = vec![0.0];
        for k in 0..segments {
            let step = self.lengths[k + 1] - self.lengths[k];
            let density = 0.5 * (1.0 / spacing(k) + 1.0 / spacing((k + 1) % count));
            integral.push(integral[k] + step * density);
        }
        let total = *integral.last().expect("non-empty");
        let samples = if self.closed {
            (total.round() as usize).max(4)
        } else {
            (total.round() as usize).max(2)
        };
        let scale = samples as f64 / total;
        let at_level = |level: f64| {
            let i = integral
                .partition_point(|&v| v * scale <= level)
                .clamp(1, integral.len() - 1);
            let (v0, v1) = (integral[i - 1] * scale, integral[i] * scale);
            let t = if v1 > v0 {
                (level - v0) / (v1 - v0)
            } else {
                0.0
            };
            self.at(self.lengths[i - 1] + t * (self.lengths[i] - self.lengths[i - 1]))
        };
        if self.closed {
            (0..samples).map(|k| at_level(k as f64 + phase)).collect()
        } else {
            (0..=samples).map(|k| at_level(k as f64)).collect()
        }
    }

    /// The fine polyline's points.
    pub fn fine_points(&self) -> &[Xy] {
        &self.points
    }
}

/// A parametric curve γ(t), t ∈ [t0, t1], as a fine path.
pub fn parametric(f: impl Fn(f64) -> Xy, t0: f64, t1: f64, closed: bool) -> Path {
    // A rough length first, to choose the resolution.
    let rough: f64 = (0..256)
        .map(|k| {
            let a = t0 + (t1 - t0) * k as f64 / 256.0;
            let b = t0 + (t1 - t0) * (k + 1) as f64 / 256.0;
            distance(f(a), f(b))
        })
        .sum();
    let steps = ((rough * FINE_STEPS_PER_UNIT) as usize).clamp(512, 200_000);
    let last = if closed { steps } else { steps + 1 };
    let points = (0..last)
        .map(|k| f(t0 + (t1 - t0) * k as f64 / steps as f64))
        .collect();
    Path::new(points, closed)
}

pub fn circle(centre: Xy, radius: f64) -> Path {
    ellipse(centre, (radius, radius), 0.0)
}

pub fn ellipse(centre: Xy, radii: Xy, turn: f64) -> Path {
    let (c, s) = (turn.cos(), turn.sin());
    parametric(
        move |t| {
            let (x, y) = (radii.0 * t.cos(), radii.1 * t.sin());
            (centre.0 + c * x - s * y, centre.1 + s * x + c * y)
        },
        0.0,
        TAU,
        true,
    )
}

/// The arc of a circle from angle `from` to angle `to` (radians, counter-clockwise if to > from).
pub fn arc(centre: Xy, radius: f64, from: f64, to: f64) -> Path {
    parametric(
        move |t| (centre.0 + radius * t.cos(), centre.1 + radius * t.sin()),
        from,
        to,
        false,
    )
}

/// A polygon (closed) or polyline (open) through `corners`, with exact straight sides.
pub fn polygon(corners: &[Xy], closed: bool) -> Path {
    let mut points = Vec::new();
    let sides = if closed {
        corners.len()
    } else {
        corners.len() - 1
    };
    for k in 0..sides {
        let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
        // Corners are fine points; intermediate fine points keep `at` exact on straight sides.
        let steps = ((distance(a, b) * FINE_STEPS_PER_UNIT) as usize).max(1);
        for i in 0..steps {
            let t = i as f64 / steps as f64;
            points.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
        }
    }
    if !closed {
        points.push(*corners.last().expect("corners"));
    }
    Path::new(points, closed)
}

/// The local feature size at every fine point of every path: the distance to the nearest Voronoi
/// vertex of all the paths' fine points together, which approximates the medial axis of the
/// curves (Amenta, Bern & Eppstein 1998). Vertices of triangles spanning no curve (on the hull)
/// lie far out and do not matter.
pub fn local_feature_sizes(paths: &[&Path]) -> Vec<Vec<f64>> {
    let mut triangulation: DelaunayTriangulation<Point2<f64>> = DelaunayTriangulation::new();
    let all: Vec<Point2<f64>> = paths
        .iter()
        .flat_map(|p| p.fine_points().iter().map(|&(x, y)| Point2::new(x, y)))
        .collect();
    let triangulation_points = all.clone();
    for p in triangulation_points {
        let _ = triangulation.insert(p);
    }
    let centres: Vec<Xy> = triangulation
        .inner_faces()
        .map(|face| {
            let c = face.circumcenter();
            (c.x, c.y)
        })
        .collect();
    // A grid over the Voronoi vertices for nearest look-ups.
    let grid = Grid::new(&centres);
    paths
        .iter()
        .map(|path| {
            path.fine_points()
                .iter()
                .map(|&p| grid.nearest_distance(p))
                .collect()
        })
        .collect()
}

/// Uniform grid of points for nearest-point queries.
struct Grid {
    origin: Xy,
    cell: f64,
    columns: usize,
    rows: usize,
    cells: Vec<Vec<Xy>>,
}

impl Grid {
    fn new(points: &[Xy]) -> Self {
        let finite: Vec<Xy> = points
            .iter()
            .copied()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .collect();
        let (mut low, mut high) = ((f64::MAX, f64::MAX), (f64::MIN, f64::MIN));
        for &(x, y) in &finite {
            low = (low.0.min(x), low.1.min(y));
            high = (high.0.max(x), high.1.max(y));
        }
        let extent = (high.0 - low.0).max(high.1 - low.1).max(1e-9);
        let side = (finite.len() as f64).sqrt().ceil().max(1.0);
        let cell = extent / side;
        let columns = ((high.0 - low.0) / cell) as usize + 1;
        let rows = ((high.1 - low.1) / cell) as usize + 1;
        let mut cells = vec![Vec::new(); columns * rows];
        for &p in &finite {
            let (i, j) = (
                ((p.0 - low.0) / cell) as usize,
                ((p.1 - low.1) / cell) as usize,
            );
            cells[j.min(rows - 1) * columns + i.min(columns - 1)].push(p);
        }
        Self {
            origin: low,
            cell,
            columns,
            rows,
            cells,
        }
    }

    fn nearest_distance(&self, p: Xy) -> f64 {
        let ci = ((p.0 - self.origin.0) / self.cell).floor() as i64;
        let cj = ((p.1 - self.origin.1) / self.cell).floor() as i64;
        let mut best = f64::INFINITY;
        // Far enough to cover the whole grid from wherever the query cell is.
        let (columns, rows) = (self.columns as i64, self.rows as i64);
        let reach = ci
            .abs()
            .max(cj.abs())
            .max((ci - columns).abs())
            .max((cj - rows).abs())
            + 1;
        for ring in 0..=reach {
            // Every point in ring r+1 or beyond is at least r cells away.
            if best <= (ring as f64 - 1.0).max(0.0) * self.cell {
                break;
            }
            for j in cj - ring..=cj + ring {
                for i in ci - ring..=ci + ring {
                    let on_ring = (i - ci).abs() == ring || (j - cj).abs() == ring;
                    if !on_ring
                        || i < 0
                        || j < 0
                        || i >= self.columns as i64
                        || j >= self.rows as i64
                    {
                        continue;
                    }
                    for &q in &self.cells[j as usize * self.columns + i as usize] {
                        best = best.min(distance(p, q));
                    }
                }
            }
        }
        best
    }
}
