//! The demo's detail normals: a noise detail laid over the bricks' normal map by RNM, partial
//! derivatives and linear blending (`bumpmap blend`), and the figure of the wall lit from the
//! side with each — the bricks alone, then each blend.

use std::path::Path;

use bumpmap::assets::load_normal_map;
use bumpmap::maps::{BlendOptions, blend_files};
use bumpmap::{ImportOptions, Light, Prepared, Renderer, SceneLight, SceneSpec, TechniqueName, TechniqueOptions};
use bumpmap_core::scenes::SceneKind;
use bumpmap_io::image_file::{PngLayout, save_png};
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_math::detail::BlendMethod;
use bumpmap_math::{HeightPreset, MipMode, Named, NormalMapOptions, YConvention};
use bumpmap_words::Error;
use bumpmap_words::frame::lib_err;
use bumpmap_words::maps::{blend_error, save_error, scale_err};
use glam::Vec3;

/// The figure (the README shows one like it).
pub const BLEND_FIGURE: &str = "blend_figure.png";

/// Each panel's side in pixels.
const SIDE: usize = 256;

/// The blends the figure shows, after the bricks alone.
const METHODS: [BlendMethod; 3] = [BlendMethod::Rnm, BlendMethod::PartialDerivative, BlendMethod::Linear];

/// Writes `blend/` (the detail and each blend) and the figure into `out`, over `base` (the
/// bricks' normal map, green up); returns the index's lines.
pub fn write(out: &Path, base: &Path, renderer: &mut Renderer) -> Result<String, Error> {
    let dir = out.join("blend");
    std::fs::create_dir_all(&dir).map_err(|source| bumpmap_io::IoError::Write { path: dir.clone(), source })?;
    let detail = dir.join("noise_detail.png");
    let options = NormalMapOptions { y_convention: YConvention::YUp, scale: 3.0, ..Default::default() };
    let chain =
        bumpmap::maps::normal_chain(&HeightPreset::Noise(7).render(128, 128), &options, false, MipMode::LengthInAlpha)
            .map_err(|source| scale_err(source, "noise"))?;
    bumpmap::maps::write_chain(&detail, &bumpmap::maps::Chain::Rgba8(chain), TextureFormat::Rgba8, &[])
        .map_err(save_error)?;
    let mut maps = vec![base.to_path_buf()];
    for method in METHODS {
        let file = dir.join(format!("bricks_{}.png", method.name()));
        let options = BlendOptions { method, strength: 1.5, repeat: 4, ..Default::default() };
        blend_files(base, &detail, &file, &options).map_err(blend_error)?;
        maps.push(file);
    }
    let mut rgb = vec![0u8; maps.len() * SIDE * SIDE * 3];
    for (k, map) in maps.iter().enumerate() {
        let image = lit_wall(renderer, map)?;
        for y in 0..SIDE {
            for x in 0..SIDE {
                let t = image.texels[y * SIDE + x];
                let at = (y * maps.len() * SIDE + k * SIDE + x) * 3;
                rgb[at..at + 3].copy_from_slice(&t[..3]);
            }
        }
    }
    save_png(&out.join(BLEND_FIGURE), maps.len() * SIDE, SIDE, PngLayout::Rgb8, &rgb)?;
    Ok(format!(
        "- `blend/noise_detail.png`, `blend/bricks_rnm.png`, `blend/bricks_partial-derivative.png`, `blend/bricks_linear.png`: a noise \
detail laid over `bricks_normal.png` 4 times across at strength 1.5 by each blend (`bumpmap blend bricks_normal.png blend/noise_detail.png \
-o … --detail-repeat 4 --detail-strength 1.5 --method …`)\n\
- `{BLEND_FIGURE}`: the wall lit from the side with the bricks alone, then with each blend: RNM and partial derivatives keep the \
bricks' edges and add the detail; linear blending washes both out\n"
    ))
}

/// The wall seen head-on, lit from the left at a grazing angle, with `map` as its normal map.
fn lit_wall(renderer: &mut Renderer, map: &Path) -> Result<bumpmap::Rgba8Image, Error> {
    let normal_map = load_normal_map(map, &ImportOptions::default()).map_err(lib_err)?;
    let mut spec = SceneSpec::new(SceneKind::Wall);
    spec.params.bumps = normal_map.bumps();
    spec.params.default_decal = false;
    spec.params.eye = Some(Vec3::new(0.0, 0.0, 2.2));
    spec.params.lights = vec![SceneLight::white(Light::Directional(Vec3::new(-1.0, 0.4, 0.45).normalize()))];
    spec.params.specular = Vec3::splat(0.2);
    let prepared = Prepared::new(&spec, TechniqueName::SinglePass, &TechniqueOptions::default()).map_err(lib_err)?;
    let frame = bumpmap::frame::draw_passes(renderer, &prepared.scene, &prepared.technique, SIDE, SIDE, false)
        .map_err(lib_err)?;
    Ok(frame.image)
}
