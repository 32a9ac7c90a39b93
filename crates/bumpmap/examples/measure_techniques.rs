//! Two techniques measured against the reference (Blinn's perturbed normal on the exact
//! surface, many samples per pixel): the paper's three 8-bit passes and the float single pass,
//! with the surface without bumps as the control. The reference image is held against its
//! screenshot (`examples/screenshots/measure_techniques.png`) at 60 dB: its samples' jitter is
//! a hash of the pixel, the same on every machine, and the slack covers libm's sin and cos
//! differing between machines.
//!
//! `cargo run --release -p bumpmap --example measure_techniques`

use bumpmap::{BackendChoice, Prepared, Renderer, SceneKind, SceneSpec, TechniqueName, TechniqueOptions};

/// Root-mean-square difference of two images' RGB in [0, 1].
fn rmse(a: &bumpmap::Rgba8Image, b: &bumpmap::Rgba8Image) -> f64 {
    let sum: f64 = a
        .texels
        .iter()
        .zip(&b.texels)
        .flat_map(|(p, q)| (0..3).map(move |c| (p[c] as f64 - q[c] as f64) / 255.0))
        .map(|d| d * d)
        .sum();
    (sum / (3 * a.texels.len()) as f64).sqrt()
}

fn main() -> Result<(), bumpmap::Error> {
    let spec = SceneSpec::new(SceneKind::Torus);
    let size = 128;
    let mut renderer = Renderer::new(BackendChoice::Cpu)?;
    let mut options = TechniqueOptions::default();
    options.reference.samples_per_pixel = 16;
    let draw = |renderer: &mut Renderer, name| renderer.draw(&Prepared::new(&spec, name, &options)?, size, size);
    let reference = draw(&mut renderer, TechniqueName::Reference)?;
    let screenshot = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/screenshots/measure_techniques.png");
    bumpmap_testkit::assert_screenshot(
        "measure_techniques",
        screenshot.as_ref(),
        &reference,
        60.0,
        "deterministic but for libm's sin and cos",
    );
    let control = rmse(&draw(&mut renderer, TechniqueName::NoBump)?, &reference);
    for name in [TechniqueName::Kilgard, TechniqueName::SinglePass] {
        let error = rmse(&draw(&mut renderer, name)?, &reference);
        println!("{name:>12}: RMSE {error:.4} against the reference ({})", name.description());
        assert!(error < control, "{name} should be closer to the reference than no bumps at all ({control:.4})");
    }
    println!("{:>12}: RMSE {control:.4} (the control: the surface without bumps)", TechniqueName::NoBump);
    Ok(())
}
