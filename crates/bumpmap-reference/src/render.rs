//! The reference image: visibility per sample, the exact surface and Blinn's normal at each
//! visible sample, the one lighting model, and the mean of the samples of each pixel.

mod displaced;

pub use displaced::{DisplacedScene, SceneHit, camera_ray};

use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;

use bumpmap_core::Scene;
use bumpmap_core::scene::SceneObject;
use bumpmap_core::shading::{Fragment, LitTerms, SpecularFilter, shade, spot_cone};
use bumpmap_math::lighting::{Light, ObjectLighting, TangentFrame};
use bumpmap_math::{Rgba8Image, Rgba8Mips};

use crate::error::ReferenceError;
use crate::visibility::{Hit, ScreenTriangle, TILE, resolve_tile};
use bumpmap_math::blinn::{displacement_per_unit_height, perturbed_normal};

pub use bumpmap_core::technique::reference::{MAX_SAMPLES_PER_PIXEL, ReferenceOptions};

/// The largest image side.
pub const MAX_SIDE: usize = 16384;

/// A linear RGB image in [0, 1], row 0 at the top of the picture.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearImage {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `width·height` colours, row-major.
    pub pixels: Vec<Vec3>,
}

impl LinearImage {
    /// The image rounded to 8 bits a channel, alpha 255.
    pub fn to_rgba8(&self) -> Rgba8Image {
        let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
        let texels = self.pixels.iter().map(|c| [byte(c.x), byte(c.y), byte(c.z), 255]).collect();
        Rgba8Image::new(self.width, self.height, texels)
    }
}

/// Per-object state the samples share.
struct Prepared<'a> {
    object: &'a SceneObject,
    lighting: Vec<ObjectLighting>,
    /// Object-space displacement per unit height ([`displacement_per_unit_height`]).
    displacement: f32,
}

/// Renders `scene` at `width`×`height` with `options`, calling `progress(done, total)` as tiles
/// of [`TILE`]² pixels finish (from any thread).
pub fn render(
    scene: &Scene,
    width: usize,
    height: usize,
    options: &ReferenceOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<LinearImage, ReferenceError> {
    let spp = options.samples_per_pixel;
    if !(1..=MAX_SAMPLES_PER_PIXEL).contains(&spp) {
        return Err(ReferenceError::SamplesPerPixel { got: spp, max: MAX_SAMPLES_PER_PIXEL });
    }
    if !(1..=MAX_SIDE).contains(&width) || !(1..=MAX_SIDE).contains(&height) {
        return Err(ReferenceError::Size { width, height, max: MAX_SIDE });
    }
    if let Some(light) = scene.lights.iter().position(|l| l.spot.as_ref().is_some_and(|s| s.pattern.is_some())) {
        return Err(ReferenceError::SpotPattern { light });
    }
    if options.displaced {
        return displaced::render(scene, width, height, options, progress);
    }
    let prepared: Vec<Prepared> = scene
        .objects
        .iter()
        .enumerate()
        .map(|(i, object)| {
            let source = object.source.as_ref().ok_or(ReferenceError::NoSurface { object: i })?;
            let heights = source.heights.as_ref().ok_or(ReferenceError::NoHeights { object: i })?;
            let field = &heights.field;
            let lighting = scene
                .lights
                .iter()
                .map(|l| ObjectLighting::new(object.world_from_object, l.light, scene.viewer()))
                .collect();
            let size = (field.width(), field.height());
            let displacement =
                displacement_per_unit_height(&source.surface, source.repeat, size, heights.options.scale);
            Ok(Prepared { object, lighting, displacement })
        })
        .collect::<Result<_, ReferenceError>>()?;

    // Triangles in screen space, and which tiles each may cover.
    let clip_from_world = scene.camera.clip_from_world(width as f32 / height as f32);
    let mut triangles = Vec::new();
    for (o, object) in scene.objects.iter().enumerate() {
        let clip_from_object = clip_from_world * object.world_from_object;
        let mesh = &object.mesh;
        for tri in &mesh.indices {
            let p = tri.map(|i| mesh.positions[i as usize]);
            triangles.extend(ScreenTriangle::project(&clip_from_object, p, (width, height), o as u32, *tri));
        }
    }
    let (tiles_x, tiles_y) = (width.div_ceil(TILE), height.div_ceil(TILE));
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); tiles_x * tiles_y];
    for (i, tri) in triangles.iter().enumerate() {
        let (x0, x1, y0, y1) = tri.pixel_bounds(width, height);
        if x0 >= x1 || y0 >= y1 {
            continue;
        }
        for ty in y0 / TILE..=(y1 - 1) / TILE {
            for tx in x0 / TILE..=(x1 - 1) / TILE {
                bins[ty * tiles_x + tx].push(i as u32);
            }
        }
    }

    let tiles = render_tiles(width, height, progress, |index, (x0, y0, tw, th)| {
        let hits = resolve_tile(&triangles, &bins[index], (x0, y0, tw, th), (spp, options.seed), (width, height));
        hits.chunks(spp)
            .map(|samples| {
                let sum: Vec3 =
                    samples.iter().flatten().map(|hit| shade_sample(scene, &prepared, &triangles, hit, options)).sum();
                sum / spp as f32
            })
            .collect()
    });
    Ok(assemble(&tiles, width, height))
}

/// Runs `tile(index, (x0, y0, width, height))` for every tile of [`TILE`]² pixels of a
/// `width`×`height` image in parallel (each returning its pixels row-major), calling
/// `progress(done, total)` as each finishes; the tiles in order. A `progress` that panics stops
/// the tiles not yet begun, and its panic goes on ([`bumpmap_math::progress`]).
pub(crate) fn render_tiles(
    width: usize,
    height: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
    tile: impl Fn(usize, (usize, usize, usize, usize)) -> Vec<Vec3> + Sync,
) -> Vec<Vec<Vec3>> {
    let tiles_x = width.div_ceil(TILE);
    let total = tiles_x * height.div_ceil(TILE);
    let told = bumpmap_math::progress::Told::new(progress, total);
    let tiles = (0..total)
        .into_par_iter()
        .map(|index| {
            if told.stopped() {
                return Vec::new();
            }
            let (x0, y0) = ((index % tiles_x) * TILE, (index / tiles_x) * TILE);
            let pixels = tile(index, (x0, y0, TILE.min(width - x0), TILE.min(height - y0)));
            told.step();
            pixels
        })
        .collect();
    told.finish();
    tiles
}

/// The image from its tiles of [`TILE`]² pixels (row-major within a tile, tiles row-major).
pub(crate) fn assemble(tiles: &[Vec<Vec3>], width: usize, height: usize) -> LinearImage {
    let tiles_x = width.div_ceil(TILE);
    let mut pixels = vec![Vec3::ZERO; width * height];
    for (index, tile) in tiles.iter().enumerate() {
        let (x0, y0) = ((index % tiles_x) * TILE, (index / tiles_x) * TILE);
        let tw = TILE.min(width - x0);
        for (i, &c) in tile.iter().enumerate() {
            pixels[(y0 + i / tw) * width + x0 + i % tw] = c;
        }
    }
    LinearImage { width, height, pixels }
}

/// The colour one sample sees on the base surface: Blinn's normal there, lit by [`light`].
fn shade_sample(
    scene: &Scene,
    prepared: &[Prepared],
    triangles: &[ScreenTriangle],
    hit: &Hit,
    options: &ReferenceOptions,
) -> Vec3 {
    let tri = &triangles[hit.triangle as usize];
    let Prepared { object, lighting, displacement } = &prepared[tri.object as usize];
    let source = object.source.as_ref().expect("checked when prepared");
    let heights = source.heights.as_ref().expect("checked when prepared");
    let mesh = &object.mesh;
    let st: Vec2 = (0..3).map(|i| hit.weights[i] * mesh.texcoords[tri.vertices[i] as usize]).sum();
    let (u, v) = (st.x / source.repeat.x, st.y / source.repeat.y);
    let point = source.surface.eval(u, v);

    // Blinn's normal from the interpolant's derivatives: d = k·F(s, t), s = repeat.x·u, and
    // F's derivatives come per texel, so ∂d/∂u = k · repeat.x · width · ∂F/∂x.
    let field = &heights.field;
    let local = st - st.floor();
    let f = bumpmap_math::interpolant::sample(field.as_ref(), heights.options.wrap, local.x, local.y);
    let d_u = displacement * source.repeat.x * field.width() as f32 * f.dx;
    let d_v = displacement * source.repeat.y * field.height() as f32 * f.dy;
    let bumped = perturbed_normal(&point, d_u, d_v);

    // Any orthonormal frame will do: the model reads only dot products and L·N, H·N.
    let (t, b, n) = point.frame();
    let frame = TangentFrame { t, b, n };
    let surfel = Surfel {
        position: point.position,
        frame,
        normal: frame.tangent_from_object(bumped),
        decal: object.material.decal.as_deref().map_or(Vec3::ONE, |d| bilinear_repeat(d, local)),
    };
    light(scene, object, lighting, &surfel, options, |_, _| true)
}

/// A point to light: where it is (object space), a frame there, the normal in that frame, and
/// the decal's colour.
pub(crate) struct Surfel {
    pub position: Vec3,
    pub frame: TangentFrame,
    pub normal: Vec3,
    pub decal: Vec3,
}

/// Every light's [`shade`] of `surfel` on `object`, each clamped to [0, 1] as a pass into an
/// 8-bit framebuffer is, summed and clamped as additive blending does; light `i` counts where
/// `reaches(i, to_light)` (object space) says it reaches the point.
pub(crate) fn light(
    scene: &Scene,
    object: &SceneObject,
    lighting: &[ObjectLighting],
    surfel: &Surfel,
    options: &ReferenceOptions,
    reaches: impl Fn(usize, Vec3) -> bool,
) -> Vec3 {
    let n = surfel.normal;
    let world = object.world_from_object.transform_point3(surfel.position);
    let mut color = Vec3::ZERO;
    for (i, light) in scene.lights.iter().enumerate() {
        let (l, h) = lighting[i].tangent_space(surfel.position, &surfel.frame);
        let mut factor = 1.0;
        if let Light::Positional(at) = light.light {
            factor *= light.attenuation.factor((at - world).length());
            if let Some(spot) = &light.spot {
                factor *= spot_cone(spot, at - world, spot.direction);
            }
        }
        if factor > 0.0 && !reaches(i, lighting[i].to_light(surfel.position)) {
            factor = 0.0;
        }
        // The reference samples the exact surface: nothing to filter.
        let terms = LitTerms::of(
            &object.material,
            light,
            i == 0,
            options.self_shadow,
            options.specular_shadow,
            SpecularFilter::None,
        );
        let fragment = Fragment {
            normal: Vec4::new(n.x * 0.5 + 0.5, n.y * 0.5 + 0.5, n.z * 0.5 + 0.5, 1.0),
            decal: surfel.decal,
            gloss: 1.0,
            l,
            h,
            l_n: l.z,
            h_n: h.z,
            light: factor,
            moments: bumpmap_core::shading::LeanMoments::FLAT,
            roughness: bumpmap_core::shading::perceptual_roughness(terms.shininess),
            occlusion: 1.0,
        };
        color += shade(&terms, &fragment).clamp(Vec3::ZERO, Vec3::ONE);
    }
    color.min(Vec3::ONE)
}

/// Level 0 of `texture` at (s, t) ∈ [0, 1)², bilinear with repeat: the decal as the surface
/// carries it (the samples of a pixel do the filtering).
pub(crate) fn bilinear_repeat(texture: &Rgba8Mips, st: Vec2) -> Vec3 {
    let level = &texture.levels()[0];
    let (w, h) = (level.width, level.height);
    let x = st.x * w as f32 - 0.5;
    let y = st.y * h as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let texel = |i: i64, j: i64| {
        let c = level.texel(i.rem_euclid(w as i64) as usize, j.rem_euclid(h as i64) as usize);
        Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32) / 255.0
    };
    let (x0, y0) = (x0 as i64, y0 as i64);
    let top = texel(x0, y0).lerp(texel(x0 + 1, y0), fx);
    let bottom = texel(x0, y0 + 1).lerp(texel(x0 + 1, y0 + 1), fx);
    top.lerp(bottom, fy)
}
