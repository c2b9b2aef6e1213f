//! Writes the hostile inputs of issue 13 into a folder, to try them on the command line:
//! images that lie about their size or are slow to trace, SVGs that make a renderer read other
//! files, loop or allocate without bound, and odd point files. The tests make the same inputs
//! (`tests/hostile/mod.rs`) and check what each gives.
//!
//! ```sh
//! cargo run --release --example hostile_inputs -- /tmp/hostile
//! for f in /tmp/hostile/*.{png,jpg,pbm}; do crawltrace trace "$f" -o /tmp/out.svg; done
//! for f in /tmp/hostile/*.svg; do crawltrace render "$f" -o /tmp/out.png; done
//! ```

#[path = "../tests/hostile/mod.rs"]
mod hostile;

use std::fs;
use std::path::PathBuf;

use image::{DynamicImage, ImageFormat};

fn main() -> std::io::Result<()> {
    let folder = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("crawltrace-hostile"));
    fs::create_dir_all(&folder)?;
    let png = |image| hostile::encode(&DynamicImage::ImageLuma8(image), ImageFormat::Png);
    let pbm = |image| hostile::encode(&DynamicImage::ImageLuma8(image), ImageFormat::Pnm);
    let files: Vec<(String, Vec<u8>)> = vec![
        (
            "specks-1000.png".into(),
            png(hostile::specks_page(1000, 5, 1)),
        ),
        ("noise-200.pbm".into(), pbm(hostile::noise_page(200, 2))),
        ("noise-500.pbm".into(), pbm(hostile::noise_page(500, 3))),
        (
            "sof-20000x20000.jpg".into(),
            hostile::jpeg_claiming(20_000, 20_000),
        ),
        (
            "sof-15000x15000.jpg".into(),
            hostile::jpeg_claiming(15_000, 15_000),
        ),
        (
            "sof-width-65535.jpg".into(),
            hostile::jpeg_claiming(65_535, 64),
        ),
        (
            "ihdr-16000x16000.png".into(),
            hostile::png_claiming(16_000, 16_000),
        ),
        (
            "ihdr-15000x15000.png".into(),
            hostile::png_claiming(15_000, 15_000),
        ),
    ];
    for (name, bytes) in files {
        fs::write(folder.join(name), bytes)?;
    }
    for (name, text) in hostile::hostile_svgs() {
        fs::write(folder.join(format!("{name}.svg")), text)?;
    }
    fs::write(folder.join("canvas-29999.svg"), hostile::svg_canvas(29_999))?;
    for (name, href) in [
        ("image-etc-passwd", "/etc/passwd"),
        ("image-file-url", "file:///etc/hostname"),
        ("image-relative-svg", "canvas-29999.svg"),
        ("image-dev-zero", "/dev/zero"),
    ] {
        fs::write(
            folder.join(format!("{name}.svg")),
            hostile::svg_with_image(href),
        )?;
    }
    for (name, bytes) in hostile::hostile_point_files() {
        fs::write(folder.join(name), bytes)?;
    }
    println!("{}", folder.display());
    Ok(())
}
