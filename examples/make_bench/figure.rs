//! What one benchmark drawing shows before it is drawn: true curves with the plan of how each is
//! to be sketched, and dots; arranging several figures on one page.

use kurbo::{Affine, Point, Rect, Vec2};

use super::pen::Plan;
use super::random::SplitMix64;
use super::shapes::Shape;

/// One true curve and how it is drawn.
#[derive(Clone, Debug)]
pub struct Part {
    pub shape: Shape,
    pub plan: Plan,
}

/// An isolated dot: its true position is its centre.
#[derive(Clone, Copy, Debug)]
pub struct Dot {
    pub centre: Point,
    pub diameter: f64,
}

/// True curves and dots in pixels.
#[derive(Clone, Debug, Default)]
pub struct Figure {
    pub parts: Vec<Part>,
    pub dots: Vec<Dot>,
}

impl Figure {
    /// A figure of curves drawn with random strokes and gaps.
    pub fn of(shapes: Vec<Shape>) -> Figure {
        Figure {
            parts: shapes
                .into_iter()
                .map(|shape| Part {
                    shape,
                    plan: Plan::auto(),
                })
                .collect(),
            dots: Vec::new(),
        }
    }

    /// Adds a curve with its plan.
    pub fn push(&mut self, shape: Shape, plan: Plan) {
        self.parts.push(Part { shape, plan });
    }

    /// Adds everything of `other`.
    pub fn extend(&mut self, other: Figure) {
        self.parts.extend(other.parts);
        self.dots.extend(other.dots);
    }

    /// The bounding box of every vertex and dot (dots with their size).
    pub fn bounds(&self) -> Rect {
        let mut bounds: Option<Rect> = None;
        let mut grow = |rect: Rect| {
            bounds = Some(bounds.map_or(rect, |b| b.union(rect)));
        };
        for part in &self.parts {
            for &point in &part.shape.points {
                grow(Rect::from_points(point, point));
            }
        }
        for dot in &self.dots {
            grow(Rect::from_center_size(
                dot.centre,
                (dot.diameter, dot.diameter),
            ));
        }
        bounds.unwrap_or(Rect::ZERO)
    }

    /// The figure moved by a rigid motion; arc-length plans stay valid.
    pub fn transformed(&self, transform: Affine) -> Figure {
        Figure {
            parts: self
                .parts
                .iter()
                .map(|part| Part {
                    shape: part.shape.transformed(transform),
                    plan: part.plan.clone(),
                })
                .collect(),
            dots: self
                .dots
                .iter()
                .map(|dot| Dot {
                    centre: transform * dot.centre,
                    diameter: dot.diameter,
                })
                .collect(),
        }
    }

    /// The figure turned by `angle` radians around the centre of its bounding box.
    pub fn rotated(&self, angle: f64) -> Figure {
        let centre = self.bounds().center();
        self.transformed(Affine::rotate_about(angle, centre))
    }
}

/// Figures side by side in rows no wider than `max_width` (shelf packing in the given order),
/// `spacing` apart, each nudged by up to `spacing / 2` so the page is no grid.
pub fn arrange(
    figures: Vec<Figure>,
    spacing: f64,
    max_width: f64,
    random: &mut SplitMix64,
) -> Figure {
    let mut page = Figure::default();
    let (mut x, mut y, mut row_height) = (0.0, 0.0, 0.0_f64);
    for figure in figures {
        let bounds = figure.bounds();
        if x > 0.0 && x + bounds.width() > max_width {
            x = 0.0;
            y += row_height + spacing;
            row_height = 0.0;
        }
        let nudge = Vec2::new(0.0, random.range(0.0, spacing / 2.0));
        let offset = Vec2::new(x - bounds.x0, y - bounds.y0) + nudge;
        page.extend(figure.transformed(Affine::translate(offset)));
        x += bounds.width() + spacing * random.range(1.0, 1.5);
        row_height = row_height.max(bounds.height() + nudge.y);
    }
    page
}
