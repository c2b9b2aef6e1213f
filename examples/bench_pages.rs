//! Writes the inputs of `scripts/compare-tracers.sh` into a folder: the benchmark's 4000×3000 page
//! (`page.png`, the committed sample or the generated stand-in), its scan-like JPEG
//! (`page-scan.jpg`), and both binarized by crawltrace as 1-bit PBM for potrace (`page.pbm`,
//! `page-scan.pbm`). Run: `cargo run --release --example bench_pages -- OUTDIR`.

#[path = "../benches/support/pages.rs"]
mod pages;

use std::fs;
use std::path::PathBuf;

use crawltrace::stages::binarize::{binarize, BinarizeOptions};
use crawltrace::stages::clean::{clean, estimate_stroke_width};
use crawltrace::stages::decode::{decode_image, to_gray};

fn main() {
    let Some(folder) = std::env::args_os().nth(1).map(PathBuf::from) else {
        eprintln!("usage: bench_pages OUTDIR");
        std::process::exit(2);
    };
    fs::create_dir_all(&folder).expect("the output folder can be made");
    let (png, source) = pages::page_png();
    let page = decode_image(&png).expect("the page decodes").to_luma8();
    let jpeg = pages::scan_jpeg(&page);
    for (name, bytes) in [("page.png", &png), ("page-scan.jpg", &jpeg)] {
        fs::write(folder.join(name), bytes).expect("the page can be written");
        // potrace's input: crawltrace's own binarization (automatic method) and speck/pinhole
        // cleaning, the ink mask that crawltrace itself thins, so both tracers see the same ink.
        let gray = to_gray(&decode_image(bytes).expect("the page decodes"));
        let mut mask = binarize(&gray, &BinarizeOptions::default()).mask;
        let stroke_width = estimate_stroke_width(&mask);
        clean(&mut mask, stroke_width);
        let pbm = folder.join(name).with_extension("pbm");
        fs::write(&pbm, pages::pbm(&mask)).expect("the PBM can be written");
    }
    eprintln!(
        "{}: page.png ({source:?}), page-scan.jpg, page.pbm, page-scan.pbm",
        folder.display()
    );
}
