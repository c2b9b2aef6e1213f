//! Shapes for the benchmark's drawings, as dense vertex lists in pixels: polylines built from
//! lines and arcs (with their arc length, so gaps can be placed at known places), ellipses, stars,
//! random blobs, and protrusions inserted into an outline.

use std::f64::consts::{PI, TAU};

use kurbo::{Affine, Point, Vec2};

use super::random::SplitMix64;

/// Arcs are sampled at most this far apart, px.
const ARC_STEP: f64 = 1.0;

/// A true curve before it is laid out on the page.
#[derive(Clone, Debug)]
pub struct Shape {
    /// The vertices; a closed shape does not repeat its first vertex.
    pub points: Vec<Point>,
    /// Whether the curve is closed.
    pub closed: bool,
}

impl Shape {
    /// The shape moved by `transform` (a rigid motion: arc lengths stay as they were).
    pub fn transformed(&self, transform: Affine) -> Shape {
        Shape {
            points: self.points.iter().map(|&p| transform * p).collect(),
            closed: self.closed,
        }
    }

    /// Arc length of the vertex list (closed shapes include the closing segment).
    pub fn length(&self) -> f64 {
        let mut length = polyline_length(&self.points);
        if self.closed {
            length += self.points[self.points.len() - 1].distance(self.points[0]);
        }
        length
    }
}

/// Total length of a vertex chain.
pub fn polyline_length(points: &[Point]) -> f64 {
    points
        .windows(2)
        .map(|pair| pair[0].distance(pair[1]))
        .sum()
}

/// Builds a vertex chain from lines and arcs and tells its arc length as it goes.
#[derive(Clone, Debug, Default)]
pub struct Builder {
    points: Vec<Point>,
    length: f64,
}

impl Builder {
    /// A chain starting at `start`.
    pub fn start(start: Point) -> Builder {
        Builder {
            points: vec![start],
            length: 0.0,
        }
    }

    /// Arc length so far.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The last vertex.
    pub fn end(&self) -> Point {
        *self.points.last().expect("a chain has a start")
    }

    /// A straight line to `to`.
    pub fn line_to(&mut self, to: Point) -> &mut Builder {
        let last = self.end();
        if last.distance(to) > 1e-9 {
            self.length += last.distance(to);
            self.points.push(to);
        }
        self
    }

    /// Straight lines through `vertices`.
    pub fn lines(&mut self, vertices: &[Point]) -> &mut Builder {
        for &vertex in vertices {
            self.line_to(vertex);
        }
        self
    }

    /// An arc of the circle around `centre` with `radius`, from angle `from` to angle `to`
    /// (radians, y down, so increasing angles turn clockwise on screen); a line joins the chain to
    /// the arc's start if needed.
    pub fn arc(&mut self, centre: Point, radius: f64, from: f64, to: f64) -> &mut Builder {
        let steps = ((radius * (to - from).abs()) / ARC_STEP).ceil().max(1.0) as usize;
        for step in 0..=steps {
            let angle = from + (to - from) * step as f64 / steps as f64;
            self.line_to(centre + Vec2::from_angle(angle) * radius);
        }
        self
    }

    /// The chain as an open shape.
    pub fn open(&self) -> Shape {
        Shape {
            points: self.points.clone(),
            closed: false,
        }
    }

    /// The chain as a closed shape (back to its start).
    pub fn closed(&self) -> Shape {
        let mut points = self.points.clone();
        if points.len() > 1 && points[0].distance(*points.last().unwrap()) < 1e-6 {
            points.pop();
        }
        Shape {
            points,
            closed: true,
        }
    }
}

/// An ellipse with semi-axes `rx`, `ry` turned by `rotation`, starting at `start_angle`.
pub fn ellipse(centre: Point, rx: f64, ry: f64, rotation: f64, start_angle: f64) -> Shape {
    let steps = ((PI * (rx + ry)) / ARC_STEP).ceil().max(12.0) as usize;
    let turn = Affine::translate(centre.to_vec2()) * Affine::rotate(rotation);
    let points = (0..steps)
        .map(|i| {
            let angle = start_angle + TAU * i as f64 / steps as f64;
            turn * Point::new(rx * angle.cos(), ry * angle.sin())
        })
        .collect();
    Shape {
        points,
        closed: true,
    }
}

/// A closed polygon through `vertices`.
pub fn polygon(vertices: Vec<Point>) -> Shape {
    Shape {
        points: vertices,
        closed: true,
    }
}

/// An open polyline through `vertices`.
pub fn polyline(vertices: Vec<Point>) -> Shape {
    Shape {
        points: vertices,
        closed: false,
    }
}

/// A star with `tips` tips whose apex angle is `apex` (radians), outer radius `outer`, one tip
/// pointing along `rotation`.
pub fn star(centre: Point, outer: f64, tips: usize, apex: f64, rotation: f64) -> Shape {
    let half_step = PI / tips as f64;
    let tangent = (apex / 2.0).tan();
    // The inner vertex at ±half_step whose edge to the tip makes half the apex angle with the axis.
    let inner = outer * tangent / (half_step.sin() + tangent * half_step.cos());
    let vertices = (0..2 * tips)
        .map(|i| {
            let radius = if i % 2 == 0 { outer } else { inner };
            let angle = rotation + half_step * i as f64;
            centre + Vec2::from_angle(angle) * radius
        })
        .collect();
    polygon(vertices)
}

/// A random smooth blob around `centre`: a circle of `radius` whose radius varies by a few low
/// harmonics (at most `bumpiness` of the radius in all), so it stays star-shaped and smooth.
pub fn blob(centre: Point, radius: f64, bumpiness: f64, random: &mut SplitMix64) -> Shape {
    let harmonics: Vec<(f64, f64, f64)> = (2..=5)
        .map(|k| {
            let weight = random.range(0.3, 1.0) / k as f64;
            (k as f64, weight, random.range(0.0, TAU))
        })
        .collect();
    let total: f64 = harmonics.iter().map(|h| h.1).sum();
    let steps = ((TAU * radius) / ARC_STEP).ceil().max(24.0) as usize;
    let points = (0..steps)
        .map(|i| {
            let angle = TAU * i as f64 / steps as f64;
            let wave: f64 = harmonics
                .iter()
                .map(|&(k, weight, phase)| weight * (k * angle + phase).cos())
                .sum();
            let r = radius * (1.0 + bumpiness * wave / total);
            centre + Vec2::from_angle(angle) * r
        })
        .collect();
    Shape {
        points,
        closed: true,
    }
}

/// The point, unit tangent and arc length at arc length `position` along a closed or open chain.
pub fn point_at(shape: &Shape, position: f64) -> (Point, Vec2) {
    let mut vertices = shape.points.clone();
    if shape.closed {
        vertices.push(vertices[0]);
    }
    let total = polyline_length(&vertices);
    let mut left = if shape.closed {
        position.rem_euclid(total)
    } else {
        position.clamp(0.0, total)
    };
    for pair in vertices.windows(2) {
        let segment = pair[0].distance(pair[1]);
        if left <= segment && segment > 0.0 {
            let direction = (pair[1] - pair[0]) / segment;
            return (pair[0] + direction * left, direction);
        }
        left -= segment;
    }
    let last = vertices.len() - 1;
    let direction = (vertices[last] - vertices[last - 1]).normalize();
    (vertices[last], direction)
}

/// A protrusion to insert into an outline: a chain in a local frame whose x axis runs along the
/// outline's direction of travel and whose y axis points outward (away from `inside`), from
/// `(-base/2, 0)` to `(base/2, 0)`.
#[derive(Clone, Debug)]
pub struct Protrusion {
    /// Arc length of its middle on the outline.
    pub at: f64,
    /// Width of the stretch of outline it replaces.
    pub base: f64,
    /// The chain in the local frame, from the base's start to its end.
    pub local: Vec<Point>,
}

/// `outline` with each protrusion put in place of the stretch of outline under its base; the
/// local frame's y axis points away from `inside`. Protrusions must not overlap.
pub fn insert_protrusions(outline: &Shape, inside: Point, protrusions: &[Protrusion]) -> Shape {
    let chains: Vec<Chain> = protrusions
        .iter()
        .map(|protrusion| protrusion.chain(outline, inside))
        .collect();
    insert_chains(outline, &chains)
}

impl Protrusion {
    /// The protrusion in page coordinates, as the chain that replaces the outline under its base;
    /// its local y axis points away from `inside`.
    pub fn chain(&self, outline: &Shape, inside: Point) -> Chain {
        let (middle, tangent) = point_at(outline, self.at);
        let mut normal = Vec2::new(-tangent.y, tangent.x);
        if normal.dot(middle - inside) < 0.0 {
            normal = -normal;
        }
        Chain {
            from: self.at - self.base / 2.0,
            to: self.at + self.base / 2.0,
            points: self
                .local
                .iter()
                .map(|local| middle + tangent * local.x + normal * local.y)
                .collect(),
        }
    }
}

/// A chain of vertices in page coordinates that replaces the outline between two arc lengths.
#[derive(Clone, Debug)]
pub struct Chain {
    pub from: f64,
    pub to: f64,
    pub points: Vec<Point>,
}

/// `outline` with the stretch from each chain's `from` to its `to` replaced by the chain.
/// Chains must not overlap, and must lie inside an open outline's ends.
pub fn insert_chains(outline: &Shape, chains: &[Chain]) -> Shape {
    let mut sorted = chains.to_vec();
    sorted.sort_by(|a, b| a.from.total_cmp(&b.from));
    let mut vertices = outline.points.clone();
    if outline.closed {
        vertices.push(vertices[0]);
    }
    let covered = |position: f64| sorted.iter().any(|c| position > c.from && position < c.to);
    let mut result: Vec<Point> = Vec::new();
    let mut travelled = 0.0;
    let mut next = 0;
    for pair in vertices.windows(2) {
        if !covered(travelled) {
            result.push(pair[0]);
        }
        let segment = pair[0].distance(pair[1]);
        // Every chain whose stretch starts on this segment goes in after its first vertex.
        while next < sorted.len() && sorted[next].from < travelled + segment {
            result.extend(sorted[next].points.iter().copied());
            next += 1;
        }
        travelled += segment;
    }
    if !outline.closed {
        result.push(*vertices.last().unwrap());
    }
    Shape {
        points: result,
        closed: outline.closed,
    }
}

/// Arc length of the first place on `outline` where `crosses` changes sign between two vertices
/// (linear between them), searching from arc length `from`.
pub fn arc_length_where(outline: &Shape, from: f64, crosses: impl Fn(Point) -> f64) -> Option<f64> {
    let mut vertices = outline.points.clone();
    if outline.closed {
        vertices.push(vertices[0]);
    }
    let mut travelled = 0.0;
    for pair in vertices.windows(2) {
        let segment = pair[0].distance(pair[1]);
        let (a, b) = (crosses(pair[0]), crosses(pair[1]));
        if travelled + segment >= from && a * b <= 0.0 && a != b {
            let t = a / (a - b);
            let position = travelled + t * segment;
            if position >= from {
                return Some(position);
            }
        }
        travelled += segment;
    }
    None
}

/// A triangular spike `length` long on a base `base` wide.
pub fn spike(at: f64, base: f64, length: f64) -> Protrusion {
    Protrusion {
        at,
        base,
        local: vec![
            Point::new(-base / 2.0, 0.0),
            Point::new(0.0, length),
            Point::new(base / 2.0, 0.0),
        ],
    }
}

/// A rectangular finger `length` long whose sides are `width` apart, flat at its end.
pub fn finger(at: f64, width: f64, length: f64) -> Protrusion {
    Protrusion {
        at,
        base: width,
        local: vec![
            Point::new(-width / 2.0, 0.0),
            Point::new(-width / 2.0, length),
            Point::new(width / 2.0, length),
            Point::new(width / 2.0, 0.0),
        ],
    }
}

/// A strip `width` wide and `length` long with a round end, its centre line bending by
/// `bend` radians over its length.
pub fn rounded_strip(at: f64, width: f64, length: f64, bend: f64) -> Protrusion {
    let steps = (length / ARC_STEP).ceil().max(4.0) as usize;
    // The centre line: starts along +y, turns steadily by `bend`.
    let mut centre = vec![Point::ORIGIN];
    let mut directions = vec![Vec2::new(0.0, 1.0)];
    for step in 1..=steps {
        let heading = PI / 2.0 + bend * step as f64 / steps as f64;
        let direction = Vec2::from_angle(heading);
        centre.push(centre[step - 1] + direction * (length / steps as f64));
        directions.push(direction);
    }
    let half = width / 2.0;
    // Local x runs along the outline, so the strip's side at -x comes first.
    let side = |index: usize, sign: f64| {
        let d = directions[index];
        centre[index] + Vec2::new(d.y, -d.x) * (sign * half)
    };
    let mut local: Vec<Point> = (0..=steps).map(|i| side(i, -1.0)).collect();
    let tip = centre[steps];
    let heading = directions[steps].atan2();
    let cap_steps = ((PI * half) / 0.5).ceil().max(6.0) as usize;
    for step in 1..cap_steps {
        // Around the end from the -x side to the +x side through the tip.
        let angle = heading + PI / 2.0 - PI * step as f64 / cap_steps as f64;
        local.push(tip + Vec2::from_angle(angle) * half);
    }
    local.extend((0..=steps).rev().map(|i| side(i, 1.0)));
    Protrusion {
        at,
        base: width,
        local,
    }
}
