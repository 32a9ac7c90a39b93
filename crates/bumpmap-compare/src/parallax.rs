//! Heights as geometry measured: the brick wall (and the dimples) seen at 30°, 60°, 70°, 75° and
//! 85° from its normal, each technique against the displaced reference.
//!
//! For every pixel whose ray enters the wall, the exact hit is the displaced reference's (the
//! min–max walk of the interpolant, `bumpmap_reference::DisplacedScene`); a technique's hit is
//! its march (`bumpmap_core::parallax::fragment`, what both backends run per fragment) on the
//! same pixel-centre ray, reading the heights the level its footprint picks. The hit error is
//! their distance in texels; normal mapping's "hit" is where the ray enters the polygon. The
//! shadow agreement compares each march's hard shadow at its own hit with the reference's
//! shadow ray at the exact hit, over the pixels whose exact surface faces the light. FLIP and
//! RMSE compare each technique's image (drawn by the chosen backend) with the displaced
//! reference's; each march is drawn a second time with the other normal at its hit (the normal
//! map's, or the heights' own: `--hit-normal`), so the error of the march and the error of the
//! normal it shades with are told apart.
//!
//! What this module does not do: draw the techniques' images (the backends do) or write files.

use std::sync::Arc;
use std::time::Instant;

use bumpmap::{BumpSource, Prepared, Renderer, SceneKind, SceneParams, SceneSpec, TechniqueName, TechniqueOptions};
use bumpmap_core::parallax::{
    FragmentHeights, FragmentRays, HitNormal, HorizonLookup, Parallax, ParallaxOptions, ParallaxShadow, TextureFrame,
    fragment, height_lambda, height_level,
};
use bumpmap_core::scene::SceneLight;
use bumpmap_core::state::Sampler;
use bumpmap_math::lighting::Light;
use bumpmap_math::{HeightPreset, Kernel, NormalMapOptions, Rgba8Image};
use bumpmap_reference::{DisplacedScene, LinearImage, ReferenceOptions, camera_ray};
use glam::{Vec2, Vec3};

use super::metrics;
use crate::error::CompareError;

/// The angles of view from the wall's normal, in degrees.
pub const ANGLES: [f32; 5] = [30.0, 60.0, 70.0, 75.0, 85.0];
/// The height fields, 256² each.
pub const FIELDS: [&str; 2] = ["bricks", "dimples"];
/// The techniques measured: normal mapping, then each march.
pub const TECHNIQUES: [TechniqueName; 6] = [
    TechniqueName::SinglePass,
    TechniqueName::Parallax,
    TechniqueName::SteepParallax,
    TechniqueName::Pom,
    TechniqueName::Relief,
    TechniqueName::HeightExact,
];
/// The light's angle from the normal, in degrees (a directional light from the side).
pub const LIGHT_DEGREES: f32 = 70.0;
/// Image side, samples per pixel of the reference, the eye's distance from the wall's centre and
/// the field of view: about a third of a texel across a pixel at the centre, so the marches read
/// level 0 up to 75° and the distant, minified end of the wall at 85° reads smaller levels.
pub(super) const SIZE: usize = 256;
pub(super) const SPP: usize = 16;
const DISTANCE: f32 = 1.2;
const FOV_DEGREES: f32 = 30.0;

/// One technique on one field at one angle.
#[derive(Clone, Debug, PartialEq)]
pub struct ParallaxRow {
    /// `bricks` or `dimples`.
    pub field: &'static str,
    /// Degrees from the normal.
    pub angle: f32,
    /// The technique.
    pub technique: TechniqueName,
    /// Mean distance of its hit from the exact one, in texels.
    pub hit_mean: f64,
    /// The 95th percentile of that distance.
    pub hit_p95: f64,
    /// Share of the pixels facing the light whose hard shadow agrees with the shadow rays'.
    pub shadow_agreement: f64,
    /// Mean FLIP of its image against the displaced reference's.
    pub flip: f64,
    /// For a march: the mean FLIP with the hit shaded with the normal map's normal, and with
    /// the heights' own (`--hit-normal map` and `heights`; one of them is [`Self::flip`]).
    pub flip_by_hit_normal: Option<(f64, f64)>,
    /// RMSE of its image against the displaced reference's.
    pub rmse: f64,
    /// Milliseconds its image took.
    pub millis: f64,
}

/// The whole study.
pub struct ParallaxStudy {
    /// Image side in pixels.
    pub size: usize,
    /// Samples per pixel of the displaced reference.
    pub spp: usize,
    /// The wall's depth per unit of height, in texels (the bump scale's).
    pub depth_texels: f32,
    /// Every field, angle and technique.
    pub rows: Vec<ParallaxRow>,
    /// The figure: bricks at 75°, `(file stem, caption, image)`.
    pub figure: Vec<(String, String, Rgba8Image)>,
}

impl ParallaxStudy {
    /// The row of `technique` on `field` at `angle`.
    pub fn row(&self, field: &str, angle: f32, technique: TechniqueName) -> Option<&ParallaxRow> {
        self.rows.iter().find(|r| r.field == field && r.angle == angle && r.technique == technique)
    }
}

/// The wall seen `degrees` from its normal, lit from the side at [`LIGHT_DEGREES`], with
/// `field`'s heights (and the brick decal on bricks).
fn spec(field: &'static str, degrees: f32) -> SceneSpec {
    wall(field, degrees, LIGHT_DEGREES)
}

/// The wall seen `degrees` from its normal, lit from the side `light_degrees` from it, with
/// `field`'s heights (and the brick decal on bricks).
pub(super) fn wall(field: &'static str, degrees: f32, light_degrees: f32) -> SceneSpec {
    let (a, l) = (degrees.to_radians(), light_degrees.to_radians());
    let preset = if field == "bricks" { HeightPreset::Bricks } else { HeightPreset::Dimples };
    // The light from the right and a little toward the eye, so shadows fall across the view.
    let light = Vec3::new(l.sin() * 0.8, -l.sin() * 0.6, l.cos());
    let params = SceneParams {
        eye: Some(Vec3::new(0.0, -a.sin(), a.cos()) * DISTANCE),
        target: Some(Vec3::ZERO),
        fov_y_degrees: FOV_DEGREES,
        lights: vec![SceneLight::white(Light::Directional(light))],
        bumps: BumpSource::Heights(Arc::new(preset.render(256, 256))),
        // Central differences: at texel centres the normal map's slope is the interpolant's, so
        // what is left between the images is the hits and filtering, not a half-texel shift.
        normal_map: NormalMapOptions { kernel: Kernel::Central, ..Default::default() },
        default_decal: field == "bricks",
        ..Default::default()
    };
    SceneSpec { kind: SceneKind::Wall, params }
}

/// Per pixel: where the pixel-centre ray enters the wall and what the vertex stage would give
/// it there, and the exact hit; `None` for pixels off the wall.
pub(super) struct PixelRay {
    pub(super) rays: FragmentRays,
    /// λ of the normal map (and heights) at the entry point.
    lambda: f32,
    exact: bumpmap_reference::SceneHit,
    /// Whether the exact surface faces the light there, and whether its shadow ray reaches it.
    pub(super) faces_light: bool,
    pub(super) lit: bool,
}

/// The study: every field, angle and technique.
pub fn parallax_study(backend: &mut Renderer) -> Result<ParallaxStudy, CompareError> {
    let mut rows = Vec::new();
    let mut figure = Vec::new();
    let mut depth_texels = 0.0;
    for field in FIELDS {
        for angle in ANGLES {
            let spec = spec(field, angle);
            let options = TechniqueOptions::default();
            let reference = Prepared::new(&spec, TechniqueName::ReferenceDisplaced, &options)?;
            let scene = &reference.scene;
            let object = &scene.objects[0];
            let heights = object.material.heights.clone().expect("the displaced reference carries heights");
            let texel = object.texel_side((heights.width(), heights.height())).expect("the wall has area");
            depth_texels = object.material.depth / texel;
            let ref_options = ReferenceOptions { samples_per_pixel: SPP, displaced: true, ..Default::default() };
            let image = bumpmap_reference::render(scene, SIZE, SIZE, &ref_options, &|_, _| {})?;
            let ref_rgb = metrics::reference_rgb8(&image);
            let pixels = pixel_rays(scene)?;
            let show = field == "bricks" && angle == 75.0;
            if show {
                figure.push((
                    "parallax_reference".to_string(),
                    format!("the displaced reference, bricks at {angle}° ({SPP} samples per pixel)"),
                    image.to_rgba8(),
                ));
            }
            for technique in TECHNIQUES {
                let prepared = Prepared::new(&spec, technique, &options)?;
                let t = Instant::now();
                let drawn = backend.draw(&prepared, SIZE, SIZE)?;
                let millis = t.elapsed().as_secs_f64() * 1e3;
                let (scores, _) = metrics::score(&image, &ref_rgb, &drawn);
                // The same technique with the other normal at the hit.
                let flip_by_hit_normal = match technique.parallax_method() {
                    Some(method) => {
                        let own = HitNormal::default_for(method);
                        let other = if own == HitNormal::Map { HitNormal::Heights } else { HitNormal::Map };
                        let mut with_other = options.clone();
                        with_other.parallax.hit_normal = Some(other);
                        let drawn = backend.draw(&Prepared::new(&spec, technique, &with_other)?, SIZE, SIZE)?;
                        let other_flip = metrics::score(&image, &ref_rgb, &drawn).0.flip_mean;
                        Some(if own == HitNormal::Map {
                            (scores.flip_mean, other_flip)
                        } else {
                            (other_flip, scores.flip_mean)
                        })
                    }
                    None => None,
                };
                let parallax = technique.parallax_method().map(|method| Parallax {
                    method,
                    options: ParallaxOptions { shadow: ParallaxShadow::Hard, ..Default::default() },
                });
                let (hit_mean, hit_p95, shadow_agreement) =
                    hits(parallax, &pixels, &heights, object.material.depth).map_err(bumpmap_core::CoreError::from)?;
                if show
                    && matches!(technique, TechniqueName::SinglePass | TechniqueName::Pom | TechniqueName::HeightExact)
                {
                    figure.push((
                        format!("parallax_{}", technique.name()),
                        format!("{}, bricks at {angle}°", technique.name()),
                        drawn,
                    ));
                }
                rows.push(ParallaxRow {
                    field,
                    angle,
                    technique,
                    hit_mean,
                    hit_p95,
                    shadow_agreement,
                    flip: scores.flip_mean,
                    flip_by_hit_normal,
                    rmse: scores.rmse,
                    millis,
                });
            }
        }
    }
    Ok(ParallaxStudy { size: SIZE, spp: SPP, depth_texels, rows, figure })
}

/// Every pixel of the wall: its entry point, texture-space vectors, footprint and exact hit.
pub(super) fn pixel_rays(scene: &bumpmap_core::Scene) -> Result<Vec<PixelRay>, CompareError> {
    let displaced = DisplacedScene::new(scene)?;
    let object = &scene.objects[0];
    let source = object.source.as_ref().expect("a built-in wall");
    let depth = object.material.depth;
    let clip = scene.camera.clip_from_world(1.0);
    let eye = scene.camera.eye;
    let Light::Directional(light) = scene.lights[0].light else { unreachable!("the study's light is directional") };
    // The wall is flat: one frame everywhere, T along +s, B along +t, N = +z (object = world).
    let p = source.surface.eval(0.5, 0.5);
    let (t, b, n) = p.texture_frame(source.repeat);
    let frame = bumpmap_math::lighting::TangentFrame { t, b, n };
    let tex = TextureFrame::new(p.dp_du / source.repeat.x, p.dp_dv / source.repeat.y, &frame, depth);
    let origin = source.surface.eval(0.0, 0.0).position;
    // Texture coordinates where the ray through image point (x, y) meets the wall's plane.
    let entry = |x: f32, y: f32| -> Option<(Vec2, Vec3)> {
        let (o, d) = camera_ray(&clip, eye, (SIZE, SIZE), x, y);
        let along = (origin - o).dot(n) / d.dot(n);
        (along > 0.0).then(|| {
            let q = o + along * d;
            let st = Vec2::new((q - origin).dot(t), (q - origin).dot(b))
                / Vec2::new(p.dp_du.length(), p.dp_dv.length())
                * source.repeat;
            (st, q)
        })
    };
    let heights = object.material.heights.as_ref().expect("the displaced reference carries heights");
    let size = Vec2::new(heights.width() as f32, heights.height() as f32);
    let mut out = Vec::new();
    for y in 0..SIZE {
        for x in 0..SIZE {
            let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
            let Some((st, point)) = entry(cx, cy) else { continue };
            let inside = |v: f32, r: f32| (0.0..=r).contains(&v);
            if !inside(st.x, source.repeat.x) || !inside(st.y, source.repeat.y) {
                continue;
            }
            let (o, d) = camera_ray(&clip, eye, (SIZE, SIZE), cx, cy);
            let Some(exact) = displaced.trace(o, d) else { continue };
            // The footprint from the neighbouring pixels' entry points, as a quad's derivatives
            // give it, and the heights' level of detail from it.
            let lambda = match (entry(cx + 1.0, cy), entry(cx, cy + 1.0)) {
                (Some((sx, _)), Some((sy, _))) => {
                    let (dx, dy) = ((sx - st) * size, (sy - st) * size);
                    height_lambda(dx.length_squared(), dy.length_squared())
                }
                _ => 0.0,
            };
            let surface = displaced.object(0);
            let faces_light = surface.normal(&exact.hit).dot(light) > 0.0;
            out.push(PixelRay {
                rays: FragmentRays {
                    st,
                    to_eye: tex.to_texture(frame.tangent_from_object(eye - point)),
                    to_light: tex.to_texture(frame.tangent_from_object(light)),
                    jacobian: tex.jacobian,
                    curvature: Vec2::ZERO,
                },
                lambda,
                exact,
                faces_light,
                lit: displaced.lit(&exact, 0),
            });
        }
    }
    if out.is_empty() {
        return Err(bumpmap_core::CoreError::out_of_range("the parallax study's view", "empty", "the wall").into());
    }
    Ok(out)
}

/// The mean and 95th-percentile hit error in texels over `pixels` of `parallax`'s march (normal
/// mapping's entry point for `None`), and its shadow's agreement with the shadow rays over the
/// pixels facing the light (all lit for `None`).
pub(super) fn hits(
    parallax: Option<Parallax>,
    pixels: &[PixelRay],
    heights: &bumpmap_math::HeightMips,
    depth: f32,
) -> Result<(f64, f64, f64), bumpmap_math::HorizonError> {
    let levels = heights.levels();
    let exact = FragmentHeights { level0: &levels[0], minmax: heights.minmax() };
    let texels = Vec2::new(heights.width() as f32, heights.height() as f32);
    let horizons = heights.horizons()?;
    let mut errors = Vec::with_capacity(pixels.len());
    let (mut facing, mut agree) = (0usize, 0usize);
    for px in pixels {
        let (st, lit) = match parallax {
            None => (px.rays.st, true),
            Some(parallax) => {
                let k = height_level(&Sampler::TRILINEAR_REPEAT, px.lambda, levels.len());
                let level = &levels[k];
                let mut sample = |st: Vec2| level.bilinear(st.x, st.y);
                let mut sample_horizons = |st: Vec2| horizons.levels()[k].bilinear(st.x, st.y);
                let lookup = HorizonLookup { size: texels, sample: &mut sample_horizons };
                match fragment(&px.rays, &parallax, depth, false, &mut sample, exact, Some(lookup)) {
                    Some(f) => (f.st, f.light > 0.5),
                    None => continue,
                }
            }
        };
        errors.push(((st - px.exact.hit.st) * texels).length() as f64);
        if px.faces_light {
            facing += 1;
            agree += (lit == px.lit) as usize;
        }
    }
    errors.sort_by(f64::total_cmp);
    let n = errors.len().max(1);
    let mean = errors.iter().sum::<f64>() / n as f64;
    let p95 = errors.get((0.95 * (n - 1) as f64).round() as usize).copied().unwrap_or(0.0);
    Ok((mean, p95, agree as f64 / facing.max(1) as f64))
}

/// The displaced reference of `scene` at `spp`, for the main table's second column.
pub fn displaced_reference(scene: &bumpmap_core::Scene, size: usize, spp: usize) -> Result<LinearImage, String> {
    let options = ReferenceOptions { samples_per_pixel: spp, displaced: true, ..Default::default() };
    bumpmap_reference::render(scene, size, size, &options, &|_, _| {}).map_err(|e| e.to_string())
}
