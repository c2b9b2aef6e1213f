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

/// resvg clips layers and filter regions to the canvas grown by this many times its size on
/// every side.
const LAYER_GROWTH: f32 = 2.0;

/// An SVG arc command takes seven arguments: rx, ry, rotation, the two flags, x, y.
const ARC_ARGUMENTS: usize = 7;

/// The estimate of rendering `tree` at `scale` onto a `width` × `height` canvas.
pub(super) fn estimate(tree: &usvg::Tree, scale: f32, width: u32, height: u32) -> Cost {
    let (w, h) = (width as f32, height as f32);
    let model = Model {
        scale: Transform::from_scale(scale, scale),
        largest_layer: Rect::from_xywh(
            -LAYER_GROWTH * w,
            -LAYER_GROWTH * h,
            (1.0 + 2.0 * LAYER_GROWTH) * w,
            (1.0 + 2.0 * LAYER_GROWTH) * h,
        ),
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
        let segments = path.data().len() as f64 + dashes(path);
        let mut cost = Cost {
            operations: segments * OPERATIONS_PER_SEGMENT + area,
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

    /// The area in canvas pixels of `rect` (in user units), clipped as resvg clips layers and
    /// rounded out to whole pixels as its pixmaps are (a layer of 2.4 pixels is 3 × 3).
    fn pixels(&self, rect: Rect) -> f64 {
        let Some(largest) = self.largest_layer else {
            return 0.0;
        };
        let whole = |low: f32, high: f32| f64::from(high.ceil() - low.floor());
        rect.transform(self.scale)
            .and_then(|r| r.intersect(&largest))
            .map_or(0.0, |r| {
                whole(r.left(), r.right()) * whole(r.top(), r.bottom())
            })
    }
}

/// How many dashes the stroke of `path` is cut into: its length (that of its control polygon,
/// an upper bound) over the dash pattern's period. Dashes as fine as 10⁻⁹ over a whole drawing,
/// or ordinary ones around a circle of radius 10³⁸, made tiny-skia abort or fill memory.
fn dashes(path: &Path) -> f64 {
    let Some(period) = path
        .stroke()
        .and_then(|stroke| stroke.dasharray())
        .map(|array| array.iter().map(|&d| f64::from(d)).sum::<f64>())
    else {
        return 0.0;
    };
    let points = path.data().points();
    let length: f64 = points
        .windows(2)
        .map(|pair| f64::from(pair[0].distance(pair[1])))
        .sum();
    let count = length / period;
    if count.is_finite() {
        count
    } else {
        f64::INFINITY
    }
}

/// DECISION: the most cubic curves usvg may make of one elliptical arc: 10 000. usvg 0.49 turns
/// an arc into kurbo's curves at a tolerance of 0.1 and its work grows with the square of their
/// number (an arc of 32 000 curves took 0.7 s to parse, one of 150 000 took 13 s, and one of
/// radius 10³⁸ never finished). 10 000 curves is an arc of radius about 10²³, far beyond any
/// drawing, and parses in 0.1 s.
pub const MAX_ARC_CURVES: f64 = 10_000.0;

/// The tolerance usvg 0.49 gives kurbo for arcs (`parser/shapes.rs`).
const USVG_ARC_TOLERANCE: f64 = 0.1;

/// DECISION: the most elements that `<use>` may add to a document beyond its own: 100 000, the
/// size of a large drawing. usvg copies the referenced content for every `<use>`, so ten levels of
/// ten uses each make 10¹⁰ elements from 3 kB of text; each costs about a kilobyte once parsed.
pub const MAX_USE_ELEMENTS: f64 = 100_000.0;

/// What makes usvg's parse itself unbounded, found before it runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum ParseHazard {
    /// An arc of this largest radius would become this many curves (over [`MAX_ARC_CURVES`]).
    Arc { radius: f64, curves: f64 },
    /// `<use>` elements would add this many elements (over [`MAX_USE_ELEMENTS`]).
    Uses { elements: f64 },
}

/// Reads `svg` with roxmltree (as usvg will) and finds what usvg would spend unbounded time or
/// memory on: an elliptical arc it would turn into too many curves, or `<use>` elements that
/// copy content into too many elements. Checked before usvg parses anything, because the parse
/// is what does not end; `None` also when the text is not XML (usvg then says why).
pub(super) fn parse_hazard(svg: &str) -> Option<ParseHazard> {
    let options = usvg::roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let document = usvg::roxmltree::Document::parse_with_options(svg, options).ok()?;
    let radius = document
        .descendants()
        .filter_map(|node| node.attribute("d"))
        .map(largest_arc_radius)
        .fold(0.0, f64::max);
    let curves = arc_curves(radius);
    if curves > MAX_ARC_CURVES {
        return Some(ParseHazard::Arc { radius, curves });
    }
    let own = document.descendants().filter(|n| n.is_element()).count() as f64;
    let elements = expanded_elements(&document) - own;
    (elements > MAX_USE_ELEMENTS).then_some(ParseHazard::Uses { elements })
}

/// The elements of `document` once every `<use>` is replaced by a copy of what it references
/// (recursive references count once, as usvg drops them), counted without expanding: each
/// element's count is computed once, children and use targets first, on an explicit stack (use
/// chains may be longer than the call stack is deep).
fn expanded_elements(document: &usvg::roxmltree::Document) -> f64 {
    use std::collections::{HashMap, HashSet};
    const XLINK: &str = "http://www.w3.org/1999/xlink";
    let by_id: HashMap<&str, usvg::roxmltree::Node> = document
        .descendants()
        .filter_map(|node| Some((node.attribute("id")?, node)))
        .collect();
    let parts = |node: usvg::roxmltree::Node| -> Vec<usvg::roxmltree::NodeId> {
        let href = node.attribute((XLINK, "href")).or(node.attribute("href"));
        let target = href
            .filter(|_| node.has_tag_name("use"))
            .and_then(|href| by_id.get(href.strip_prefix('#')?).copied());
        let children = node.children().filter(|child| child.is_element());
        children.chain(target).map(|part| part.id()).collect()
    };
    let mut counts: HashMap<usvg::roxmltree::NodeId, f64> = HashMap::new();
    let mut open = HashSet::new();
    let root = document.root_element().id();
    let mut stack = vec![(root, false)];
    while let Some((id, parts_done)) = stack.pop() {
        if counts.contains_key(&id) {
            continue;
        }
        let node = document.get_node(id).expect("ids come from this document");
        if parts_done {
            let total: f64 = parts(node).iter().filter_map(|part| counts.get(part)).sum();
            counts.insert(id, 1.0 + total);
            open.remove(&id);
        } else if open.insert(id) {
            stack.push((id, true));
            let pending = parts(node).into_iter().filter(|part| !open.contains(part));
            stack.extend(pending.map(|part| (part, false)));
        }
    }
    counts.get(&root).copied().unwrap_or(0.0)
}

/// kurbo 0.13's number of cubic curves for a whole ellipse of largest radius `radius`
/// (`Arc::append_iter`).
fn arc_curves(radius: f64) -> f64 {
    (1.1163 * radius / USVG_ARC_TOLERANCE)
        .powf(1.0 / 6.0)
        .max(4.0)
}

/// The largest radius (rx or ry) of the arc commands in path data `d`, 0 when it has none. The
/// path grammar of SVG 1.1 (section 8.3.9), read just enough to know which numbers are radii:
/// an arc takes seven arguments, the fourth and fifth one-character flags.
fn largest_arc_radius(d: &str) -> f64 {
    let bytes = d.as_bytes();
    let (mut at, mut command, mut argument) = (0, b' ', 0usize);
    let mut largest: f64 = 0.0;
    while at < bytes.len() {
        let byte = bytes[at];
        if byte.is_ascii_alphabetic() && !matches!(byte, b'e' | b'E') {
            (command, argument) = (byte.to_ascii_uppercase(), 0);
            at += 1;
        } else if byte.is_ascii_whitespace() || byte == b',' {
            at += 1;
        } else if command == b'A' && matches!(argument % ARC_ARGUMENTS, 3 | 4) {
            // A flag: one character, with or without a separator after it.
            at += 1;
            argument += 1;
        } else {
            let end = number_end(bytes, at);
            if end == at {
                at += 1;
                continue;
            }
            if command == b'A' && argument % ARC_ARGUMENTS < 2 {
                let value: f64 = d[at..end].parse().unwrap_or(0.0);
                largest = largest.max(value.abs());
            }
            at = end;
            argument += 1;
        }
    }
    largest
}

/// Where the number starting at `start` ends (`start` itself when none starts there): a sign,
/// digits with at most one point, then an exponent.
fn number_end(bytes: &[u8], start: usize) -> usize {
    let digits = |mut at: usize| {
        while at < bytes.len() && bytes[at].is_ascii_digit() {
            at += 1;
        }
        at
    };
    let mut at = start + usize::from(matches!(bytes[start], b'+' | b'-'));
    let integer_end = digits(at);
    let mut end = integer_end;
    if end < bytes.len() && bytes[end] == b'.' {
        end = digits(end + 1);
    }
    // A number needs a digit before or after its point.
    if integer_end == at && end <= integer_end + 1 {
        return start;
    }
    at = end;
    if at < bytes.len() && matches!(bytes[at], b'e' | b'E') {
        let mut exponent = at + 1;
        exponent += usize::from(exponent < bytes.len() && matches!(bytes[exponent], b'+' | b'-'));
        let exponent_end = digits(exponent);
        if exponent_end > exponent {
            end = exponent_end;
        }
    }
    end
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arc_radii_are_read_from_path_data() {
        assert_eq!(largest_arc_radius("M10 10 A65535 1e38 0 1 1 190 190"), 1e38);
        assert_eq!(largest_arc_radius("M0,0a5,7,0,1,0,3,4"), 7.0);
        // Flags without separators, relative arcs repeated, other commands' numbers ignored.
        assert_eq!(largest_arc_radius("M1e30 0 a2 3 0 11.5.5 4 1 0 015 6"), 4.0);
        assert_eq!(largest_arc_radius("M0 0 L1e38 1e38 C1 2 3 4 5 6"), 0.0);
        assert_eq!(largest_arc_radius("garbage A -1.5e2 .5"), 150.0);
    }

    #[test]
    fn only_arcs_beyond_the_curve_limit_are_hazards() {
        let svg = |radius: &str| {
            format!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" width="9" height="9"><path d="M1 1 A{radius} 2 0 1 1 5 5"/></svg>"#
            )
        };
        assert_eq!(parse_hazard(&svg("1e6")), None);
        assert_eq!(parse_hazard(&svg("1e20")), None);
        let Some(ParseHazard::Arc { radius, curves }) = parse_hazard(&svg("1e30")) else {
            panic!("an arc of radius 1e30 is a hazard");
        };
        assert_eq!(radius, 1e30);
        assert!(curves > MAX_ARC_CURVES);
        assert_eq!(parse_hazard("not xml"), None);
    }

    /// `levels` levels of ten `<use>` of the level below, each level's group referenced by the
    /// next: 10^levels rectangles.
    fn nested_uses(levels: usize) -> String {
        let mut svg = String::from(
            r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink"><rect id="l0" width="1" height="1"/>"#,
        );
        for level in 1..=levels {
            svg += &format!(r#"<g id="l{level}">"#);
            for _ in 0..10 {
                svg += &format!(r##"<use xlink:href="#l{}"/>"##, level - 1);
            }
            svg += "</g>";
        }
        svg + "</svg>"
    }

    #[test]
    fn use_expansion_is_counted_without_expanding() {
        // Level k's group holds 10 uses of level k - 1: it expands to 1 + 10 (1 + size(k - 1)).
        assert_eq!(parse_hazard(&nested_uses(3)), None);
        let Some(ParseHazard::Uses { elements }) = parse_hazard(&nested_uses(6)) else {
            panic!("a million rectangles from uses are a hazard");
        };
        assert!(elements > 2e6, "{elements}");
        // Fifty levels: 10^50, still counted at once.
        assert!(parse_hazard(&nested_uses(50)).is_some());
        // A use of itself, or of its own parent, counts once.
        let cycle = r##"<svg xmlns="http://www.w3.org/2000/svg"><g id="g"><use href="#g"/><use href="#u"/><use id="u" href="#u"/></g></svg>"##;
        assert_eq!(parse_hazard(cycle), None);
    }
}
