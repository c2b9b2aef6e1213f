//! What rendering a parsed SVG will cost, estimated from the usvg tree before resvg runs, so that
//! a small document that would make the renderer loop or allocate far beyond its size is refused
//! with a message instead: filters (a turbulence of a million octaves, a morphology of radius
//! 10⁶, huge convolution matrices), pattern tiles, and groups drawn on layers of their own (each
//! up to 25 times the canvas, as resvg allows) nested deeply. The model follows what resvg 0.49
//! allocates and loops over (`resvg/src/render.rs`, `filter/`, `path.rs`); it is an upper bound,
//! not a prediction. What it cannot see (usvg turning an arc of radius 10³⁸ into millions of
//! curves) is bounded by the command's sandbox (`src/bin/crawltrace/render.rs`).

use usvg::filter::Kind;
use usvg::tiny_skia_path::{Rect, Transform};
use usvg::{Group, Node, Paint, Path};

/// Bytes of a pixel in resvg's RGBA pixmaps.
const BYTES_PER_PIXEL: f64 = 4.0;

/// DECISION: a curve segment of a path costs as much as this many pixels: tiny-skia flattens a
/// cubic into at most 64 lines (its `MAX_COEFF_SHIFT` of 6), each clipped and turned into edges.
const OPERATIONS_PER_SEGMENT: f64 = 64.0;

/// DECISION: per-pixel costs of the filter primitives, in pixel operations of about a
/// nanosecond each, measured with `crawltrace render` (release) on a 2000² rectangle whose filter
/// region is 5.8 MP: a blur of any deviation took 78 ns a pixel (resvg converts to linear RGB and
/// back, then runs three box passes each way or an IIR filter), a turbulence 52 ns a pixel per
/// octave, lighting 14 ns, an offset 2 ns. A morphology looks at its whole (2rx + 1) × (2ry + 1)
/// window and a convolution at its whole matrix for every pixel (a 5 × 5 morphology: 28 ns).
const TURBULENCE_PER_OCTAVE: f64 = 56.0;
const LIGHTING: f64 = 16.0;
const BLUR: f64 = 80.0;
const SIMPLE_PRIMITIVE: f64 = 4.0;

/// What rendering a tree needs: pixel operations, and the most bytes held at once.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Cost {
    /// Pixel operations (pixels touched, times the work per pixel).
    pub(super) operations: f64,
    /// Bytes of pixmaps alive at the same time, the canvas excluded.
    pub(super) peak_bytes: f64,
}

impl Cost {
    /// `self` followed by `other`: the work adds up, the memory does not.
    fn then(self, other: Cost) -> Cost {
        Cost {
            operations: self.operations + other.operations,
            peak_bytes: self.peak_bytes.max(other.peak_bytes),
        }
    }

    /// `other` done while `self`'s pixmaps are held.
    fn inside(self, other: Cost) -> Cost {
        Cost {
            operations: self.operations + other.operations,
            peak_bytes: self.peak_bytes + other.peak_bytes,
        }
    }
}

/// The estimate of rendering `tree` at `scale` onto a `width` × `height` canvas.
pub(super) fn estimate(tree: &usvg::Tree, scale: f32, width: u32, height: u32) -> Cost {
    let (w, h) = (width as f32, height as f32);
    let model = Model {
        scale: Transform::from_scale(scale, scale),
        // resvg clips layers and filter regions to this: the canvas grown by twice its size
        // on every side.
        largest_layer: Rect::from_xywh(-2.0 * w, -2.0 * h, 5.0 * w, 5.0 * h),
    };
    model.group(tree.root())
}

struct Model {
    /// From the document's user units to canvas pixels.
    scale: Transform,
    /// The largest area a layer covers, in canvas pixels.
    largest_layer: Option<Rect>,
}

impl Model {
    fn group(&self, group: &Group) -> Cost {
        let children = group
            .children()
            .iter()
            .map(|node| self.node(node))
            .fold(Cost::default(), Cost::then);
        if !group.should_isolate() {
            return children;
        }
        let layer = self.pixels(group.abs_layer_bounding_box().to_rect());
        let mut own = Cost {
            operations: layer,
            peak_bytes: layer * BYTES_PER_PIXEL,
        };
        let pixel_scale = self.pixel_scale(group.abs_transform());
        for filter in group.filters() {
            let primitives = filter.primitives();
            let per_pixel: f64 = primitives
                .iter()
                .map(|primitive| self.primitive(primitive.kind(), pixel_scale, layer))
                .sum();
            own.operations += layer * per_pixel;
            // The source, the result, and every named intermediate result.
            own.peak_bytes += layer * BYTES_PER_PIXEL * (primitives.len() as f64 + 2.0);
        }
        if let Some(mask) = group.mask() {
            own = own.then(self.mask(mask, layer));
        }
        if let Some(clip) = group.clip_path() {
            let clip_layer = Cost {
                operations: layer,
                peak_bytes: layer * BYTES_PER_PIXEL,
            };
            own = own.then(clip_layer.inside(self.group(clip.root())));
        }
        own.inside(children)
    }

    fn mask(&self, mask: &usvg::Mask, layer: f64) -> Cost {
        let own = Cost {
            operations: layer,
            peak_bytes: layer * BYTES_PER_PIXEL,
        };
        let nested = mask.mask().map_or(Cost::default(), |m| self.mask(m, layer));
        own.inside(self.group(mask.root()).then(nested))
    }

    fn node(&self, node: &Node) -> Cost {
        match node {
            Node::Group(group) => self.group(group),
            Node::Path(path) => self.path(path),
            // Images are not loaded (see `render`); text is not built in.
            Node::Image(_) | Node::Text(_) => Cost::default(),
        }
    }

    fn path(&self, path: &Path) -> Cost {
        let area = self.pixels(path.abs_stroke_bounding_box());
        let mut cost = Cost {
            operations: path.data().len() as f64 * OPERATIONS_PER_SEGMENT + area,
            peak_bytes: 0.0,
        };
        let paints = [
            path.fill().map(|fill| fill.paint()),
            path.stroke().map(|stroke| stroke.paint()),
        ];
        for paint in paints.into_iter().flatten() {
            if let Paint::Pattern(pattern) = paint {
                cost = cost.then(self.pattern(pattern, path.abs_transform(), area));
            }
        }
        cost
    }

    /// A pattern's tile is rendered into a pixmap of its own size in pixels (unclipped), then
    /// repeated over the path.
    fn pattern(&self, pattern: &usvg::Pattern, transform: Transform, area: f64) -> Cost {
        let (sx, sy) = self
            .scale
            .pre_concat(transform)
            .pre_concat(pattern.transform())
            .get_scale();
        let rect = pattern.rect();
        let tile = f64::from(rect.width() * sx).round() * f64::from(rect.height() * sy).round();
        let tile = if tile.is_finite() {
            tile
        } else {
            f64::INFINITY
        };
        Cost {
            operations: tile + area,
            peak_bytes: tile * BYTES_PER_PIXEL,
        }
        .inside(self.group(pattern.root()))
    }

    /// Pixel operations per pixel of a filter primitive on a layer of `layer` pixels.
    fn primitive(&self, kind: &Kind, pixel_scale: f64, layer: f64) -> f64 {
        let side = layer.sqrt();
        match kind {
            Kind::Turbulence(turbulence) => {
                TURBULENCE_PER_OCTAVE * f64::from(turbulence.num_octaves())
            }
            Kind::Morphology(morphology) => {
                // resvg clips the radius to the region's size.
                let window = |radius: f32| 2.0 * (f64::from(radius) * pixel_scale).min(side) + 1.0;
                window(morphology.radius_x().get()) * window(morphology.radius_y().get())
            }
            Kind::ConvolveMatrix(convolve) => {
                f64::from(convolve.matrix().columns()) * f64::from(convolve.matrix().rows())
            }
            Kind::DiffuseLighting(_) | Kind::SpecularLighting(_) => LIGHTING,
            Kind::GaussianBlur(_) | Kind::DropShadow(_) => BLUR,
            Kind::Image(image) => {
                SIMPLE_PRIMITIVE + self.group(image.root()).operations / layer.max(1.0)
            }
            _ => SIMPLE_PRIMITIVE,
        }
    }

    /// How many canvas pixels a unit of `transform`'s space spans, at most.
    fn pixel_scale(&self, transform: Transform) -> f64 {
        let (sx, sy) = self.scale.pre_concat(transform).get_scale();
        f64::from(sx.max(sy))
    }

    /// The area in canvas pixels of `rect` (in user units), clipped as resvg clips layers.
    fn pixels(&self, rect: Rect) -> f64 {
        let Some(largest) = self.largest_layer else {
            return 0.0;
        };
        rect.transform(self.scale)
            .and_then(|r| r.intersect(&largest))
            .map_or(0.0, |r| f64::from(r.width()) * f64::from(r.height()))
    }
}
