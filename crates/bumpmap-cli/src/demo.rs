//! `bumpmap demo`: everything on built-in defaults, written into one folder.

use bumpmap_io::image_file::{PngLayout, save_png};
use bumpmap_math::{Encoding, HeightPreset, MipMode, NormalMapOptions, NormalizationCubeMap};
use indicatif::{ProgressBar, ProgressStyle};

use crate::args::DemoArgs;
use crate::error::CliError;

pub fn run(args: &DemoArgs) -> Result<(), CliError> {
    let out = &args.output;
    std::fs::create_dir_all(out).map_err(|e| CliError::Path { path: out.clone(), reason: e.to_string() })?;
    let presets = [
        ("bricks", HeightPreset::Bricks),
        ("pinwheel", HeightPreset::Pinwheel),
        ("dimples", HeightPreset::Dimples),
        ("noise", HeightPreset::Noise(1)),
    ];
    let bar = ProgressBar::new(presets.len() as u64 + 1)
        .with_style(ProgressStyle::with_template("{bar:40} {pos}/{len} {wide_msg}").expect("valid template"));
    for (name, preset) in presets {
        bar.set_message(format!("normal map: {name}"));
        let field = preset.render(256, 256);
        save_png(&out.join(format!("{name}_height.png")), 256, 256, PngLayout::Gray8, &field.to_u8())?;
        let chain = crate::normalmap::make(&field, &NormalMapOptions::default(), true, MipMode::LengthInAlpha, name)?;
        crate::normalmap::write(&out.join(format!("{name}_normal.png")), &chain)?;
        bar.inc(1);
    }
    bar.set_message("normalization cube map");
    crate::cubemap::write(&out.join("cubemap"), &NormalizationCubeMap::new(32, Encoding::Unorm))?;
    bar.finish_and_clear();
    eprintln!("wrote height fields, normal maps with mip chains, and a cube map into {}", out.display());
    Ok(())
}
