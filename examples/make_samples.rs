//! Writes the sample drawings and their ground truth into `samples/` (or the folder given as the
//! only argument): skip-stroke sketches of known curves, rendered with resvg, byte-identical on
//! every run. Run as `cargo run --release --example make_samples [FOLDER]`; see `samples/README.md`.

#[path = "make_samples/geometry.rs"]
mod geometry;
#[path = "make_samples/paper.rs"]
mod paper;
#[path = "make_samples/random.rs"]
mod random;
#[path = "make_samples/scenes.rs"]
mod scenes;
#[path = "make_samples/sketch.rs"]
mod sketch;

use std::path::{Path, PathBuf};

use crawltrace::{to_svg, CurvePath, Drawing};
use kurbo::Affine;

use geometry::TrueCurve;
use paper::Style;
use random::SplitMix64;
use scenes::Scene;

/// Truth polylines stay this close to the dense true curves, in pixels.
const TRUTH_TOLERANCE: f64 = 0.05;

/// One sample file: its name, how it looks, its seed and what it shows.
struct Sample {
    name: &'static str,
    style: Style,
    seed: u64,
    scene: fn() -> Scene,
}

const SAMPLES: &[Sample] = &[
    sample("letters-clean", Style::Clean, 1, scenes::letters),
    sample("letters-scan", Style::Scan, 2, scenes::letters),
    sample("silhouettes-clean", Style::Clean, 3, scenes::silhouettes),
    sample("silhouettes-scan", Style::Scan, 4, scenes::silhouettes),
    sample("star-circle-thin", Style::Thin, 5, scenes::star_and_circle),
    sample("face-clean", Style::Clean, 6, scenes::face),
    sample("face-scan", Style::Scan, 7, scenes::round_face),
    sample(
        "spiral-waves-thin",
        Style::Thin,
        8,
        scenes::spiral_and_waves,
    ),
    sample(
        "nested-ellipses-thick",
        Style::Thick,
        9,
        scenes::nested_ellipses,
    ),
    sample(
        "squares-triangles-thick",
        Style::Thick,
        10,
        scenes::squares_and_triangles,
    ),
    sample("objects-clean", Style::Clean, 11, scenes::objects),
    sample("weather-alpha", Style::GrayAlpha, 12, scenes::weather),
    sample("shapes-16bit", Style::Gray16, 13, scenes::shapes),
    sample("cat-fork-clean", Style::Clean, 14, scenes::touching_parts),
];

const fn sample(name: &'static str, style: Style, seed: u64, scene: fn() -> Scene) -> Sample {
    Sample {
        name,
        style,
        seed,
        scene,
    }
}

fn main() {
    let folder = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("samples"));
    std::fs::create_dir_all(&folder).expect("cannot create the output folder");
    for sample in SAMPLES {
        let scene = (sample.scene)();
        write_sample(&folder, sample.name, sample.style, sample.seed, &scene);
    }
    write_sample(&folder, "page-4000x3000", Style::Clean, 100, &page());
}

/// Sketches `scene`, writes `<name>.<ext>` and `<name>.truth.svg` into `folder`.
fn write_sample(folder: &Path, name: &str, style: Style, seed: u64, scene: &Scene) {
    let mut random = SplitMix64::new(seed);
    let mut strokes: Vec<sketch::Stroke> = scene
        .curves
        .iter()
        .flat_map(|curve| {
            sketch::sketch_curve(curve, style.pen(), style.lightest_ink(), &mut random)
        })
        .collect();
    // People start anywhere and draw in any order.
    random.shuffle_by_index(&mut strokes);
    let sketch_svg = sketch::strokes_to_svg(scene.width, scene.height, &strokes);
    let rendered = crawltrace::render_svg(&sketch_svg, 1.0).expect("sketch renders");
    let image_path = folder.join(format!("{name}.{}", style.extension()));
    std::fs::write(&image_path, style.encode(&rendered, seed)).expect("cannot write the image");
    let truth_path = folder.join(format!("{name}.truth.svg"));
    std::fs::write(&truth_path, truth_svg(name, style, seed, scene)).expect("cannot write truth");
    println!(
        "{}: {} curves, {} strokes",
        image_path.display(),
        scene.curves.len(),
        strokes.len()
    );
}

/// The ground truth: one `<path>` per true curve, pen width as the group's stroke width.
fn truth_svg(name: &str, style: Style, seed: u64, scene: &Scene) -> String {
    let drawing = Drawing {
        width: f64::from(scene.width),
        height: f64::from(scene.height),
        paths: scene
            .curves
            .iter()
            .map(|curve| CurvePath::polyline(&curve.simplified(TRUTH_TOLERANCE), curve.closed))
            .collect(),
        stroke_width: style.pen(),
        color: "black".into(),
        dots: Vec::new(),
        points: Vec::new(),
    };
    let svg = to_svg(&drawing);
    // A note after the root element's start tag says where the file comes from.
    let (root, rest) = svg.split_once('\n').expect("to_svg writes lines");
    format!(
        "{root}\n<!-- ground truth of sample {name}: style {}, pen {} px, seed {seed}; \
         made by examples/make_samples.rs, see samples/README.md -->\n{rest}",
        style.name(),
        style.pen()
    )
}

/// A 4000×3000 page with every scene laid out on a 4×4 grid, some twice.
fn page() -> Scene {
    let (cell_width, cell_height) = (1000.0, 750.0);
    let scenes = scenes::all();
    let mut curves: Vec<TrueCurve> = Vec::new();
    for cell in 0..16 {
        let scene = &scenes[cell % scenes.len()];
        let (column, row) = ((cell % 4) as f64, (cell / 4) as f64);
        // Centre the scene in its cell.
        let offset = (
            column * cell_width + ((cell_width - f64::from(scene.width)) / 2.0).round(),
            row * cell_height + ((cell_height - f64::from(scene.height)) / 2.0).round(),
        );
        let transform = Affine::translate(offset);
        curves.extend(scene.curves.iter().map(|c| c.transformed(transform)));
    }
    Scene {
        width: 4000,
        height: 3000,
        curves,
    }
}
