//! The paper's torus (Kilgard Figure 11) drawn by its three passes on whatever backend exists,
//! written as a PNG.
//!
//! `cargo run --release -p bumpmap --example render_torus [OUT.png]`

use std::path::PathBuf;

use bumpmap::bumpmap_io::image_file::{PngLayout, save_png};
use bumpmap::{BackendChoice, Renderer, SceneKind, SceneSpec, TechniqueName};

fn main() -> Result<(), bumpmap::Error> {
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("out/examples/torus.png"), PathBuf::from);
    // The GPU when an adapter exists, else the CPU, with the reason.
    let mut renderer = Renderer::new(BackendChoice::Auto)?;
    if let Some(why) = renderer.fallback_reason() {
        eprintln!("no GPU ({why}): drawing on the CPU");
    }
    let image = renderer.render(&SceneSpec::new(SceneKind::Torus), TechniqueName::Kilgard, 512, 512)?;

    // Alpha holds the self-shadowing term the passes blend with, not coverage: write RGB.
    let rgb: Vec<u8> = image.texels.iter().flat_map(|&[r, g, b, _]| [r, g, b]).collect();
    save_png(&out, image.width, image.height, PngLayout::Rgb8, &rgb)?;
    let lit = image.texels.iter().filter(|t| t[0].max(t[1]) > 40).count();
    assert!(lit > image.texels.len() / 5, "the torus should fill much of the frame, {lit} pixels are lit");
    println!("wrote {} ({})", out.display(), renderer.describe());
    Ok(())
}
