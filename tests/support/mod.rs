//! Shared helpers for the integration tests: curves out of any SVG, ground-truth matching by
//! Hausdorff distance, the benchmark's truth files and scoring (`bench`), tolerant image
//! comparison with a visual diff in `tests/diffs/`, running the binary ([`cli`]) and the seeded
//! generator ([`random`]).
// Each test binary includes this module and uses only part of it.
#![allow(dead_code, unused_imports)]

pub mod bench;
pub mod cli;
mod hausdorff;
mod images;
mod matching;
pub mod random;

use crawltrace::Point;
use kurbo::ParamCurve;
use usvg::tiny_skia_path::PathSegment;

pub use images::{compare_images, write_diff, ImageComparison};
pub use matching::{match_curves, CurveMatch, MatchProblem, MatchReport, Nearest, UnmatchedOutput};

/// Largest step, in pixels, when Béziers are flattened.
const FLATTEN_STEP: f64 = 0.25;

/// One subpath of an SVG, flattened to straight segments in canvas pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    /// The vertices; a closed polyline does not repeat its first vertex at the end.
    pub points: Vec<Point>,
    /// Whether the subpath ended with a close (`Z`).
    pub closed: bool,
}

/// One `#[test]` per sample drawing, named after it, each calling `$check(&path)`, so that a
/// failing sample runs alone: `cargo test --test it golden::face_scan`. Use inside a test module
/// as `support::sample_tests!(check);` with `fn check(image: &Path)`. The list leaves out the
/// benchmark page (`page-4000x3000.png`, too slow for debug-build tests); the generated
/// `every_sample_has_a_test` fails when it and the folder ([`sample_images`]) disagree.
#[allow(unused_macros)]
macro_rules! sample_tests {
    ($check:path) => {
        $crate::support::sample_tests!(@each $check,
            cat_fork_clean => "cat-fork-clean.png",
            face_clean => "face-clean.png",
            face_scan => "face-scan.jpg",
            letters_clean => "letters-clean.png",
            letters_scan => "letters-scan.jpg",
            nested_ellipses_thick => "nested-ellipses-thick.png",
            objects_clean => "objects-clean.png",
            shapes_16bit => "shapes-16bit.png",
            silhouettes_clean => "silhouettes-clean.png",
            silhouettes_scan => "silhouettes-scan.jpg",
            spiral_waves_thin => "spiral-waves-thin.png",
            squares_triangles_thick => "squares-triangles-thick.png",
            star_circle_thin => "star-circle-thin.png",
            weather_alpha => "weather-alpha.png",
        );
    };
    (@each $check:path, $($test:ident => $file:literal),* $(,)?) => {
        $(
            #[test]
            fn $test() {
                $check(&$crate::support::sample_path($file));
            }
        )*

        #[test]
        fn every_sample_has_a_test() {
            let listed: Vec<std::path::PathBuf> =
                [$($file),*].iter().map(|file| $crate::support::sample_path(file)).collect();
            assert_eq!(
                listed,
                $crate::support::sample_images(),
                "the samples in sample_tests! (tests/support/mod.rs) are not those in samples/"
            );
        }
    };
}
#[allow(unused_imports)]
pub(crate) use sample_tests;

/// The path of `file` in `samples/`.
pub fn sample_path(file: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("samples")
        .join(file)
}

/// The sample drawings in `samples/` (every image file), sorted, without the 12-megapixel
/// benchmark page, which is too slow for debug-build tests.
pub fn sample_images() -> Vec<std::path::PathBuf> {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("samples");
    let mut images: Vec<std::path::PathBuf> = std::fs::read_dir(&folder)
        .unwrap_or_else(|e| panic!("{}: {e}", folder.display()))
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|path| crawltrace::batch::is_image_path(path))
        .filter(|path| {
            !path
                .file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("page-")
        })
        .collect();
    images.sort();
    images
}

/// Every file under `folder` with its bytes, by relative path with `/`, sorted.
pub fn files_under(folder: &std::path::Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    let mut files = std::collections::BTreeMap::new();
    for entry in walkdir::WalkDir::new(folder).min_depth(1) {
        let entry = entry.unwrap_or_else(|e| panic!("{}: {e}", folder.display()));
        if entry.file_type().is_file() {
            let relative = entry.path().strip_prefix(folder).unwrap();
            let parts: Vec<_> = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            let bytes = std::fs::read(entry.path())
                .unwrap_or_else(|e| panic!("{}: {e}", entry.path().display()));
            files.insert(parts.join("/"), bytes);
        }
    }
    files
}

/// Sets the modification time of the file at `path` (to make an output look older or newer than
/// its input).
pub fn set_modified(path: &std::path::Path, time: std::time::SystemTime) {
    std::fs::File::options()
        .write(true)
        .open(path)
        .and_then(|file| file.set_modified(time))
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

/// Every subpath of every path in `svg_text`, flattened finely and moved by the path's absolute
/// transform (viewBox included), in document order. Paths usvg drops as invisible (no fill and
/// no stroke) are not seen.
///
/// Panics when usvg rejects the document: tests feed it SVG they expect to be valid.
pub fn load_curves(svg_text: &str) -> Vec<Polyline> {
    let tree = usvg::Tree::from_str(svg_text, &usvg::Options::default())
        .unwrap_or_else(|error| panic!("usvg rejects the SVG: {error}"));
    let mut curves = Vec::new();
    collect_group(tree.root(), &mut curves);
    curves
}

/// The stroke width of the first stroked path (the truth files put the pen width there).
pub fn load_stroke_width(svg_text: &str) -> Option<f64> {
    let tree = usvg::Tree::from_str(svg_text, &usvg::Options::default()).ok()?;
    first_stroke_width(tree.root())
}

fn first_stroke_width(group: &usvg::Group) -> Option<f64> {
    group.children().iter().find_map(|node| match node {
        usvg::Node::Group(child) => first_stroke_width(child),
        usvg::Node::Path(path) => path.stroke().map(|s| f64::from(s.width().get())),
        _ => None,
    })
}

fn collect_group(group: &usvg::Group, curves: &mut Vec<Polyline>) {
    for node in group.children() {
        match node {
            usvg::Node::Group(child) => collect_group(child, curves),
            usvg::Node::Path(path) => collect_path(path, curves),
            usvg::Node::Image(_) | usvg::Node::Text(_) => {}
        }
    }
}

fn collect_path(path: &usvg::Path, curves: &mut Vec<Polyline>) {
    let transform = path.abs_transform();
    let to_canvas = |point: usvg::tiny_skia_path::Point| {
        let (x, y) = (f64::from(point.x), f64::from(point.y));
        Point::new(
            f64::from(transform.sx) * x + f64::from(transform.kx) * y + f64::from(transform.tx),
            f64::from(transform.ky) * x + f64::from(transform.sy) * y + f64::from(transform.ty),
        )
    };
    let mut current: Vec<Point> = Vec::new();
    let mut subpath_start = Point::ORIGIN;
    let mut finish = |points: &mut Vec<Point>, closed: bool| {
        if closed && points.len() > 1 && points.first() == points.last() {
            points.pop();
        }
        if !points.is_empty() {
            curves.push(Polyline {
                points: std::mem::take(points),
                closed,
            });
        }
    };
    for segment in path.data().segments() {
        // Flattening happens in user space; the transform is applied to every point after.
        let last = current.last().copied().unwrap_or(subpath_start);
        match segment {
            PathSegment::MoveTo(point) => {
                finish(&mut current, false);
                subpath_start = to_canvas(point);
                current.push(subpath_start);
            }
            PathSegment::LineTo(point) => {
                if current.is_empty() {
                    current.push(subpath_start);
                }
                push_distinct(&mut current, to_canvas(point));
            }
            PathSegment::QuadTo(control, end) => {
                let curve = kurbo::QuadBez::new(last, to_canvas(control), to_canvas(end));
                let polygon = [curve.p0, curve.p1, curve.p2];
                flatten_into(&mut current, &polygon, |t| curve.eval(t));
            }
            PathSegment::CubicTo(first, second, end) => {
                let curve =
                    kurbo::CubicBez::new(last, to_canvas(first), to_canvas(second), to_canvas(end));
                let polygon = [curve.p0, curve.p1, curve.p2, curve.p3];
                flatten_into(&mut current, &polygon, |t| curve.eval(t));
            }
            PathSegment::Close => finish(&mut current, true),
        }
    }
    finish(&mut current, false);
}

/// Appends points of a Bézier at steps no longer than [`FLATTEN_STEP`]. Control points are mapped
/// to the canvas first (evaluation commutes with affine maps), and the control polygon is at least
/// as long as the curve.
fn flatten_into(points: &mut Vec<Point>, control_polygon: &[Point], eval: impl Fn(f64) -> Point) {
    if points.is_empty() {
        points.push(control_polygon[0]);
    }
    let polygon_length: f64 = control_polygon
        .windows(2)
        .map(|pair| pair[0].distance(pair[1]))
        .sum();
    let steps = ((polygon_length / FLATTEN_STEP).ceil() as usize).max(1);
    for step in 1..=steps {
        push_distinct(points, eval(step as f64 / steps as f64));
    }
}

fn push_distinct(points: &mut Vec<Point>, point: Point) {
    if points.last() != Some(&point) {
        points.push(point);
    }
}
