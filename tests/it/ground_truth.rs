//! Ground truth, independent of reference images: every sample in `samples/` is traced, and every
//! true curve of its `<name>.truth.svg` must come out as exactly one output path, open or closed as
//! it should be, within pen width / 2 + 2 px (symmetric Hausdorff distance), with no other paths.

use crate::support;

use std::path::Path;

use crawltrace::stages::decode;
use crawltrace::{to_svg, trace, TraceOptions};

/// Samples that are known to fail today, with the reason. The test fails when one of them starts
/// to pass too, so that this list and the table in `docs/results.md` stay true.
const KNOWN_FAILURES: &[(&str, &str)] = &[];

fn traced_svg(image: &Path) -> String {
    let bytes = std::fs::read(image).unwrap();
    let picture = decode::decode_image(&bytes).unwrap();
    let traced = trace(&picture, &TraceOptions::default())
        .unwrap_or_else(|e| panic!("{}: {e}", image.display()));
    to_svg(&traced.drawing)
}

mod every_true_curve_comes_out_as_exactly_one_path {
    use super::*;

    support::sample_tests!(check);

    /// Fails when `image` fails and is not a known failure, and when a known failure passes (so
    /// that [`KNOWN_FAILURES`] and the table in `docs/results.md` stay true); a known failure is reported on
    /// stderr (`cargo test -- --nocapture` shows it).
    fn check(image: &Path) {
        let name = image.file_name().unwrap().to_string_lossy().into_owned();
        let truth_svg = std::fs::read_to_string(image.with_extension("truth.svg"))
            .unwrap_or_else(|e| panic!("{name} has no truth file: {e}"));
        let truth = support::load_curves(&truth_svg);
        let pen = support::load_stroke_width(&truth_svg).expect("truth has a stroke width");
        let output = support::load_curves(&traced_svg(image));
        let report = support::match_curves(&truth, &output, pen / 2.0 + 2.0);
        let known = KNOWN_FAILURES.iter().find(|(known, _)| *known == name);
        match (report.passed(), known) {
            (true, None) => {}
            (false, Some((_, why))) => eprintln!("{name}: known failure ({why}):\n{report}"),
            (false, None) => panic!("{name} fails:\n{report}"),
            (true, Some((_, why))) => panic!(
                "{name} passes now (listed as known failure: {why}); remove it from \
                 KNOWN_FAILURES and update the table in docs/results.md"
            ),
        }
    }
}

mod traced_svg_is_valid_for_strict_parsers {
    use super::*;

    support::sample_tests!(check);

    /// usvg reads the SVG, its canvas is the image's size, and it holds only our elements.
    fn check(image: &Path) {
        let svg = traced_svg(image);
        let options = usvg::Options::default();
        let tree = usvg::Tree::from_str(&svg, &options)
            .unwrap_or_else(|e| panic!("{}: usvg rejects the SVG: {e}", image.display()));
        let picture = image::open(image).unwrap();
        assert_eq!(
            (tree.size().width() as u32, tree.size().height() as u32),
            (picture.width(), picture.height()),
            "{}: the SVG canvas is the image size",
            image.display()
        );
        // Plain XML: one root, balanced, no text nodes, only the elements we write.
        for element in svg.split('<').skip(1) {
            let tag = element
                .trim_start_matches('/')
                .split([' ', '>', '/'])
                .next()
                .unwrap();
            assert!(
                ["svg", "g", "path"].contains(&tag),
                "unexpected element <{tag}>"
            );
        }
    }
}
