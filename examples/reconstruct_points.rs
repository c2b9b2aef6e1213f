//! Reconstructs curves from a raw point set with the library, as `crawltrace points` does: a
//! closed curve (a circle), an open one (a "C") and a few stray points, with no parameter.
//! Prints each curve and writes the drawing as SVG.
//!
//! ```sh
//! cargo run --release --example reconstruct_points -- points.svg
//! ```
//!
//! Without an argument the SVG goes to `points.svg` in the temporary folder.

use std::f64::consts::TAU;
use std::path::PathBuf;
use std::process::ExitCode;

use crawltrace::stages::points::write::to_drawing;
use crawltrace::{reconstruct, to_svg, Point};

fn main() -> ExitCode {
    let output = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("points.svg"));

    // A circle of 40 points, a "C" (an open arc of 30 points), and three points far from both.
    let mut points: Vec<Point> = (0..40)
        .map(|k| f64::from(k) * TAU / 40.0)
        .map(|angle| Point::new(50.0 + 30.0 * angle.cos(), 50.0 + 30.0 * angle.sin()))
        .collect();
    points.extend(
        (0..30)
            .map(|k| (40.0 + 280.0 * f64::from(k) / 29.0).to_radians())
            .map(|angle| Point::new(150.0 + 20.0 * angle.cos(), 50.0 + 20.0 * angle.sin())),
    );
    points.extend([
        Point::new(100.0, 120.0),
        Point::new(20.0, 140.0),
        Point::new(180.0, 130.0),
    ]);

    let reconstruction = match reconstruct(&points) {
        Ok(reconstruction) => reconstruction,
        Err(error) => {
            eprintln!("error: {error}");
            return ExitCode::FAILURE;
        }
    };
    for (k, curve) in reconstruction.curves.iter().enumerate() {
        println!(
            "curve {k}: {} points, {}, from point {} to point {}",
            curve.indices.len(),
            if curve.closed { "closed" } else { "open" },
            curve.indices[0],
            curve.indices[curve.indices.len() - 1],
        );
    }
    println!("outliers: {:?}", reconstruction.outliers);

    let svg = to_svg(&to_drawing(&points, &reconstruction, true));
    if let Err(error) = std::fs::write(&output, svg) {
        eprintln!("error: {}: {error}", output.display());
        return ExitCode::FAILURE;
    }
    println!("drawing → {}", output.display());
    ExitCode::SUCCESS
}
