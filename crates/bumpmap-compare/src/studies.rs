//! The studies `compare` makes of claims the papers make in pictures, each on its own scene:
//! Kilgard §2.4.2's golf ball, §3.1's embossing, Peercy's Figures 5–7, and the specular
//! filtering §2.5.3 leaves open (the golf ball's highlight at a distance).
//!
//! What this module does not do: score images (that is `metrics`) or write files
//! (`report`).

use std::sync::Arc;

use bumpmap::{BumpSource, Renderer, SceneSpec, TechniqueName};
use bumpmap_core::scenes::{self, SceneKind, SceneParams};
use bumpmap_core::technique::{BackFacing, EmbossOptions, SinglePassOptions, SpecularFilter, Technique};
use bumpmap_math::{MipMode, NormalMapOptions, Rgba8Image};
use bumpmap_reference::LinearImage;
use glam::Vec3;

use super::{metrics, reference_image, render_technique};
use crate::error::CompareError;

/// Kilgard §3.1 measured, on the brick wall without specular (embossing is diffuse only), 96²,
/// directional lights.
pub struct EmbossStudy {
    /// `(angle of the light from the normal in degrees, emboss RMSE, emboss bias, single-pass
    /// RMSE, single-pass bias, emboss contrast / reference contrast)`; contrast is the standard
    /// deviation of the wall's brightness.
    pub by_angle: Vec<(f32, f64, f64, f64, f64, f64)>,
    /// `(distance factor, emboss contrast / reference contrast, single-pass contrast / reference
    /// contrast)` with the light at 45°: embossing's shift is one level-0 texel, so at small mip
    /// levels the two fetches agree and the bumps vanish.
    pub by_distance: Vec<(f32, f64, f64)>,
    /// The sphere lit from the side (half of it turned away from the light): the fraction of the
    /// image the reference leaves dark (ambient only), and the fraction of those pixels that
    /// emboss lights with the shift forced to 0 where `L_z ≤ 0`, and without.
    pub facing_away: (f64, f64, f64),
}

/// One distance of [`golf_ball_study`]: `(distance factor, reference, length factor,
/// renormalized)` mean brightness over the ball.
pub type GolfRow = (f32, f64, f64, f64);

/// Kilgard §2.4.2: a dimpled sphere (a golf ball) moving away. Averaging the dimples' normals
/// shortens them; mips that keep the length in alpha dim the ball as the reference does, mips
/// that renormalize stay too bright. The brightness of the whole frame divided by the number of
/// pixels the reference's ball touches: a sum, so the reference's antialiased edge pixels and
/// a rasterizer's all-or-nothing ones count the same area.
///
/// `headlight` puts a directional light behind the eye, where Kilgard's argument holds (few of a
/// footprint's normals face away from the light); otherwise the sphere's own light, from the
/// side, where clamping N·L at 0 makes the length factor a lower bound (the mean of clamped
/// dot products is at least the clamped dot product of the mean) and it comes out too dark.
pub fn golf_ball_study(backend: &mut Renderer, headlight: bool) -> Result<Vec<(f32, f64, f64, f64)>, CompareError> {
    const SIZE: usize = 96;
    let near = Vec3::new(0.0, -5.0, 1.5);
    let lights = if headlight {
        vec![bumpmap_core::scene::SceneLight::white(bumpmap_math::lighting::Light::Directional(near.normalize()))]
    } else {
        Vec::new()
    };
    let base = SceneParams {
        lights,
        bumps: BumpSource::Heights(Arc::new(bumpmap_math::HeightPreset::Dimples.render(256, 256))),
        normal_map: NormalMapOptions { scale: 12.0, ..Default::default() },
        default_decal: false,
        specular: Vec3::ZERO,
        ..Default::default()
    };
    let mut rows = Vec::new();
    for factor in [1.0f32, 2.0, 4.0, 8.0] {
        let params = SceneParams { eye: Some(near * factor), ..base.clone() };
        let scene = scenes::build(&SceneKind::Sphere, &params)?;
        let reference = reference_image(&scene, SIZE, 64)?;
        let covered: Vec<bool> = reference.pixels.iter().map(|c| c.max_element() > 0.0).collect();
        let n = covered.iter().filter(|&&c| c).count().max(1) as f64;
        let mean = |pixels: &[Vec3]| pixels.iter().map(|p| (p.x + p.y + p.z) as f64 / 3.0).sum::<f64>() / n;
        let mut technique_mean = |mode| -> Result<f64, CompareError> {
            let scene = scenes::build(&SceneKind::Sphere, &SceneParams { mip_mode: mode, ..params.clone() })?;
            let frame = draw(backend, &scene, &Technique::SinglePass(SinglePassOptions::default()), SIZE)?;
            Ok(mean(&metrics::linear(&frame)))
        };
        let length = technique_mean(MipMode::LengthInAlpha)?;
        let renormalized = technique_mean(MipMode::Renormalize)?;
        rows.push((factor, mean(&reference.pixels), length, renormalized));
    }
    Ok(rows)
}

/// The distances (× the nearest) of the specular study: five over a 16× range.
pub const SPECULAR_DISTANCES: [f32; 5] = [1.0, 2.0, 4.0, 8.0, 16.0];

/// The specular filters the study measures, in its columns' order: renormalized mips, the
/// length in alpha (which the single pass's specular does not read), Toksvig's filter, the
/// exported roughness map read by a Blinn–Phong shader, LEAN mapping and CLEAN mapping.
pub const SPECULAR_FILTERS: [&str; 6] =
    ["renormalized mips", "length factor", "Toksvig", "roughness map", "LEAN", "CLEAN"];

/// One distance of [`specular_study`]: the reference's and each filter's `(energy, width)`.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecularRow {
    /// Distance from the ball, × the nearest.
    pub distance: f32,
    /// The reference.
    pub reference: (f64, f64),
    /// Each of [`SPECULAR_FILTERS`].
    pub filters: [(f64, f64); 6],
}

impl SpecularRow {
    /// Each filter's energy error against the reference, relative (−0.1: 10 % too little).
    pub fn energy_errors(&self) -> [f64; 6] {
        self.filters.map(|(e, _)| e / self.reference.0 - 1.0)
    }
}

/// Kilgard §2.5.3 measured: the golf ball's highlight as it moves away, specular alone
/// (ambient and diffuse 0, k_s 1, shininess 32), a directional light behind the eye. Averaging
/// the dimples' normals in the mips leaves one normal where the footprint had many: the
/// reference's highlight spreads and dims, the unfiltered single pass keeps it tight; Toksvig's
/// filter widens the lobe by the length the mips keep, LEAN by the slopes' covariance. With k_s 1 and no other term no pixel
/// passes 1, so the 8-bit frames clip nothing.
///
/// Energy: the frame's summed brightness over the number of pixels the reference's ball
/// touches (as the golf ball study counts). Width: the brightness-weighted RMS distance from
/// the highlight's centroid, over the ball's radius in pixels (√(pixels/π)).
pub fn specular_study(backend: &mut Renderer) -> Result<Vec<SpecularRow>, CompareError> {
    const SIZE: usize = 160;
    let near = Vec3::new(0.0, -5.0, 1.5);
    let light = bumpmap_core::scene::SceneLight::white(bumpmap_math::lighting::Light::Directional(near.normalize()));
    let base = SceneParams {
        lights: vec![light],
        bumps: BumpSource::Heights(Arc::new(bumpmap_math::HeightPreset::Dimples.render(256, 256))),
        normal_map: NormalMapOptions { scale: 12.0, ..Default::default() },
        default_decal: false,
        ambient: Vec3::ZERO,
        diffuse: Vec3::ZERO,
        specular: Vec3::ONE,
        shininess: 32.0,
        ..Default::default()
    };
    // The roughness column reads the map `normalmap --mips --roughness-out` writes for this ball
    // (gray layout, 8 bits, every level), at the roughness of shininess 32.
    let exported = {
        let BumpSource::Heights(field) = &base.bumps else { unreachable!("the ball's bumps are heights") };
        let perceptual = bumpmap_core::shading::perceptual_roughness(base.shininess);
        let chain = bumpmap::options::roughness_map(
            field,
            &base.normal_map,
            perceptual,
            bumpmap::options::RoughnessLayout::Gray,
        )
        .map_err(|source| CompareError::NormalMap { name: "dimples", source })?;
        Arc::new(bumpmap_math::Rgba8Mips::from_levels(chain.levels))
    };
    let mut rows = Vec::new();
    for distance in SPECULAR_DISTANCES {
        let params = SceneParams { eye: Some(near * distance), ..base.clone() };
        let scene = scenes::build(&SceneKind::Sphere, &params)?;
        let reference = reference_image(&scene, SIZE, 64)?;
        let n = reference.pixels.iter().filter(|c| c.max_element() > 0.0).count().max(1) as f64;
        let measure = |pixels: &[Vec3]| highlight(pixels, SIZE, n);
        let mut filtered = |mode, filter| -> Result<(f64, f64), CompareError> {
            let scene = scenes::build(&SceneKind::Sphere, &SceneParams { mip_mode: mode, ..params.clone() })?;
            let roughness_map = (filter == SpecularFilter::RoughnessMap).then(|| exported.clone());
            let technique = Technique::SinglePass(SinglePassOptions {
                specular_filter: filter,
                roughness_map,
                ..Default::default()
            });
            let frame = draw(backend, &scene, &technique, SIZE)?;
            Ok(measure(&metrics::linear(&frame)))
        };
        let filters = [
            filtered(MipMode::Renormalize, SpecularFilter::None)?,
            filtered(MipMode::LengthInAlpha, SpecularFilter::None)?,
            filtered(MipMode::LengthInAlpha, SpecularFilter::Toksvig)?,
            filtered(MipMode::LengthInAlpha, SpecularFilter::RoughnessMap)?,
            filtered(MipMode::LengthInAlpha, SpecularFilter::Lean)?,
            filtered(MipMode::LengthInAlpha, SpecularFilter::Clean)?,
        ];
        rows.push(SpecularRow { distance, reference: measure(&reference.pixels), filters });
    }
    Ok(rows)
}

/// `(energy, width)` of a `size`² frame's highlight, for a ball covering `n` pixels.
fn highlight(pixels: &[Vec3], size: usize, n: f64) -> (f64, f64) {
    let value = |p: &Vec3| (p.x + p.y + p.z) as f64 / 3.0;
    let total: f64 = pixels.iter().map(value).sum();
    if total <= 0.0 {
        return (0.0, 0.0);
    }
    let at = |i: usize| ((i % size) as f64 + 0.5, (i / size) as f64 + 0.5);
    let (mut cx, mut cy) = (0.0, 0.0);
    for (i, p) in pixels.iter().enumerate() {
        let (x, y) = at(i);
        cx += value(p) * x;
        cy += value(p) * y;
    }
    (cx, cy) = (cx / total, cy / total);
    let spread: f64 = pixels
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let (x, y) = at(i);
            value(p) * ((x - cx).powi(2) + (y - cy).powi(2))
        })
        .sum();
    (total / n, (spread / total).sqrt() / (n / std::f64::consts::PI).sqrt())
}

/// The pixels the reference covers whose eight neighbours it covers too: the surface without
/// its antialiased edge.
fn interior(reference: &LinearImage) -> Vec<bool> {
    let (w, h) = (reference.width, reference.height);
    let covered = |x: usize, y: usize| reference.pixels[y * w + x].max_element() > 0.0;
    (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            x > 0 && y > 0 && x + 1 < w && y + 1 < h && (0..9).all(|k| covered(x + k % 3 - 1, y + k / 3 - 1))
        })
        .collect()
}

/// Mean and standard deviation of the brightness of `pixels` where `mask` is set.
fn brightness_stats(pixels: &[Vec3], mask: &[bool]) -> (f64, f64) {
    let values: Vec<f64> =
        pixels.iter().zip(mask).filter(|(_, m)| **m).map(|(p, _)| (p.x + p.y + p.z) as f64 / 3.0).collect();
    let n = values.len().max(1) as f64;
    let mean = values.iter().sum::<f64>() / n;
    (mean, (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt())
}

/// [`EmbossStudy`]: the wall at six light angles and four distances, the sphere lit from the side.
pub fn emboss_study(backend: &mut Renderer) -> Result<EmbossStudy, CompareError> {
    use bumpmap_core::scene::SceneLight;
    use bumpmap_math::lighting::Light;
    const SIZE: usize = 96;
    let directional = |degrees: f32| {
        let a = degrees.to_radians();
        vec![SceneLight::white(Light::Directional(Vec3::new(a.sin(), 0.0, a.cos())))]
    };
    // No decal, so brightness varies with the bumps alone.
    let base = SceneParams { specular: Vec3::ZERO, default_decal: false, ..Default::default() };
    let forced = Technique::Emboss(EmbossOptions::default());
    let single = Technique::SinglePass(SinglePassOptions::default());
    // Renders the reference and the techniques of `params` on `kind`: the reference, then each.
    let mut run = |kind: &SceneKind, params: &SceneParams, techniques: &[&Technique]| {
        let scene = scenes::build(kind, params)?;
        let reference = reference_image(&scene, SIZE, 16)?;
        let mut images = Vec::new();
        for t in techniques {
            images.push(metrics::linear(&draw(backend, &scene, t, SIZE)?));
        }
        Ok::<_, CompareError>((reference, images))
    };
    let mut by_angle = Vec::new();
    for degrees in [0.0f32, 15.0, 30.0, 45.0, 60.0, 75.0] {
        let params = SceneParams { lights: directional(degrees), ..base.clone() };
        let (reference, images) = run(&SceneKind::Wall, &params, &[&forced, &single])?;
        let mask = interior(&reference);
        let (emboss_rmse, _, emboss_bias) = metrics::pixel_errors(&reference.pixels, &images[0]);
        let (single_rmse, _, single_bias) = metrics::pixel_errors(&reference.pixels, &images[1]);
        let contrast = brightness_stats(&images[0], &mask).1 / brightness_stats(&reference.pixels, &mask).1.max(1e-9);
        by_angle.push((degrees, emboss_rmse, emboss_bias, single_rmse, single_bias, contrast));
    }
    let mut by_distance = Vec::new();
    for factor in [1.0f32, 2.0, 4.0, 8.0] {
        let params =
            SceneParams { lights: directional(45.0), eye: Some(Vec3::new(0.0, 0.0, 6.0 * factor)), ..base.clone() };
        let (reference, images) = run(&SceneKind::Wall, &params, &[&forced, &single])?;
        let mask = interior(&reference);
        let reference_contrast = brightness_stats(&reference.pixels, &mask).1.max(1e-9);
        by_distance.push((
            factor,
            brightness_stats(&images[0], &mask).1 / reference_contrast,
            brightness_stats(&images[1], &mask).1 / reference_contrast,
        ));
    }
    let unforced = Technique::Emboss(EmbossOptions { back_facing: BackFacing::Unforced, ..Default::default() });
    let params = SceneParams { lights: directional(90.0), default_decal: false, ..base.clone() };
    let (reference, images) = run(&SceneKind::Sphere, &params, &[&forced, &unforced])?;
    // The dark side: pixels the reference leaves at the ambient term (0.2, white surface). A
    // pixel there is wrongly lit when it is more than 5 steps of 8 bits brighter.
    let dark: Vec<bool> =
        reference.pixels.iter().map(|c| c.max_element() > 0.0 && c.max_element() < 0.2 + 1.5 / 255.0).collect();
    let lit = |image: &[Vec3]| {
        let n = dark.iter().filter(|&&d| d).count().max(1) as f64;
        image.iter().zip(&dark).filter(|(c, d)| **d && c.max_element() > 0.2 + 5.0 / 255.0).count() as f64 / n
    };
    let facing_away =
        (dark.iter().filter(|&&d| d).count() as f64 / (SIZE * SIZE) as f64, lit(&images[0]), lit(&images[1]));
    Ok(EmbossStudy { by_angle, by_distance, facing_away })
}

/// Peercy's three implementations, in the report's order: Figure 7's surface-independent map,
/// Figure 6's surface-dependent map, Figure 5's per-pixel Blinn.
pub const PEERCY: [TechniqueName; 3] =
    [TechniqueName::PeercyIndependent, TechniqueName::PeercyDependent, TechniqueName::PeercyBlinn];

/// Peercy Figures 5–7 measured, on his scene: the stretched bicubic patch with the pinwheel
/// over it once, the 7×7 derivative of a Gaussian for every map.
pub struct PeercyStudy {
    /// Image side in pixels.
    pub size: usize,
    /// One row per bump scale.
    pub rows: Vec<PeercyRow>,
    /// The bump scale whose images the report shows.
    pub shown_scale: f32,
    /// At that scale: the reference with the kernel's heights, then the [`PEERCY`] images, each
    /// with its file stem and a caption.
    pub images: Vec<(&'static str, &'static str, Rgba8Image)>,
}

/// [`PeercyStudy`] at one bump scale; the arrays follow [`PEERCY`].
pub struct PeercyRow {
    /// The bump scale (height of a unit step, in texels).
    pub bump_scale: f32,
    /// RMSE against the reference made from the heights as the 7×7 kernel sees them
    /// (`bumpmap_math::kernel::gaussian7_smoothed`): the same f_u, f_v for every implementation,
    /// as the paper's comparison holds them, so what is left is how each one applies them.
    pub rmse_same_slopes: [f64; 3],
    /// RMSE against the reference from the raw heights, which adds the kernel's own smoothing
    /// (a one-texel blade edge spread over seven) to every technique alike.
    pub rmse_raw_heights: [f64; 3],
    /// Mean FLIP between the surface-dependent image and each [`PEERCY`] image: how visible
    /// the difference between the figures is ("almost imperceptible" between 5 and 6).
    pub flip_from_dependent: [f64; 3],
}

/// [`PeercyStudy`]: the patch at `SIZE`², its references at 16 samples per pixel, bump scales
/// 1, 2 and 4 (slopes up to about 20°, 36° and 56°), the images of scale 2 kept.
pub fn peercy_study(backend: &mut Renderer) -> Result<PeercyStudy, CompareError> {
    const SIZE: usize = 256;
    const SHOWN: f32 = 2.0;
    let field = bumpmap_math::HeightPreset::Pinwheel.render(256, 256);
    let smoothed = bumpmap_math::kernel::gaussian7_smoothed(&field, bumpmap_math::Wrap::Repeat);
    let mut rows = Vec::new();
    let mut images = Vec::new();
    for bump_scale in [1.0f32, 2.0, 4.0] {
        let params = SceneParams {
            bumps: BumpSource::Heights(Arc::new(field.clone())),
            normal_map: NormalMapOptions { scale: bump_scale, ..Default::default() },
            default_decal: false,
            ..Default::default()
        };
        let reference = |field| {
            let bumps = BumpSource::Heights(Arc::new(field));
            let scene = scenes::build(&SceneKind::Patch, &SceneParams { bumps, ..params.clone() })?;
            reference_image(&scene, SIZE, 16)
        };
        let (same_slopes, raw_heights) = (reference(smoothed.clone())?, reference(field.clone())?);
        let rendered: Vec<Rgba8Image> = PEERCY
            .iter()
            .map(|&name| {
                let spec = SceneSpec { kind: SceneKind::Patch, params: params.clone() };
                render_technique(name, &spec, backend, SIZE).map(|(image, _)| image)
            })
            .collect::<Result<_, _>>()
            .map_err(|reason| CompareError::Study { study: "Peercy's figures on the patch", reason })?;
        let rmse = |reference: &LinearImage| -> [f64; 3] {
            std::array::from_fn(|i| metrics::pixel_errors(&reference.pixels, &metrics::linear(&rendered[i])).0)
        };
        let flip_from_dependent = std::array::from_fn(|i| metrics::flip_mean(&rendered[1], &rendered[i]));
        rows.push(PeercyRow {
            bump_scale,
            rmse_same_slopes: rmse(&same_slopes),
            rmse_raw_heights: rmse(&raw_heights),
            flip_from_dependent,
        });
        if bump_scale == SHOWN {
            images.push(("peercy_reference", "reference, the kernel's f_u, f_v", same_slopes.to_rgba8()));
            let names = [
                ("peercy_fig7_independent", "Figure 7: surface-independent map"),
                ("peercy_fig6_dependent", "Figure 6: surface-dependent map"),
                ("peercy_fig5_blinn", "Figure 5: per-pixel Blinn"),
            ];
            images.extend(names.into_iter().zip(rendered).map(|((stem, caption), image)| (stem, caption, image)));
        }
    }
    Ok(PeercyStudy { size: SIZE, rows, shown_scale: SHOWN, images })
}

/// `technique`'s image of `scene`, `size` pixels square.
fn draw(
    backend: &mut Renderer,
    scene: &bumpmap_core::Scene,
    technique: &Technique,
    size: usize,
) -> Result<Rgba8Image, CompareError> {
    Ok(backend.draw_scene(scene, technique, size, size, None)?)
}
