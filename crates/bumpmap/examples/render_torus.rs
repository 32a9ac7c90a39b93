//! The paper's torus (Kilgard Figure 11) drawn by its three passes on whatever backend exists,
//! written as a PNG, and held against its screenshot (`examples/screenshots/render_torus.png`,
//! drawn on the CPU) at 40 dB: a GPU's float texture filtering and rasterization rules against
//! the emulated GeForce's (49.6 dB on lavapipe; on the CPU it is exact but for libm).
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
    let image = renderer.render(&SceneSpec::new(SceneKind::Torus), TechniqueName::Kilgard, 256, 256)?;

    // Alpha holds the self-shadowing term the passes blend with, not coverage: write RGB.
    let rgb: Vec<u8> = image.texels.iter().flat_map(|&[r, g, b, _]| [r, g, b]).collect();
    save_png(&out, image.width, image.height, PngLayout::Rgb8, &rgb)?;
    let screenshot = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/screenshots/render_torus.png");
    let reason = "the GPU's float filtering and rasterization against the emulated GeForce's (49.6 dB on lavapipe)";
    bumpmap_testkit::assert_screenshot("render_torus", screenshot.as_ref(), &image, 40.0, reason);
    println!("wrote {} ({})", out.display(), renderer.describe());
    Ok(())
}
