//! The bump textures the compared techniques read, and the material each one makes for a
//! surface: the tangent-space normal map (Kilgard; Peercy's surface-independent map), Peercy's
//! object-space and surface-dependent maps, Kilgard's offset map and the derivative texture of
//! Peercy's Figure 2.
//!
//! What this module does not do: make the tangent-space normal map and its mip chain (that is
//! `bumpmap_math`), light anything (`shading`), or choose a scene's geometry (`scenes`).

use std::sync::Arc;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use bumpmap_math::blinn::{displacement_per_unit_height, perturbed_normal};
use bumpmap_math::surface::Surface;
use bumpmap_math::{Encoding, HeightField, MipChain, MipMode, NormalMapOptions, Rgba8Image, Rgba8Mips};

use crate::error::CoreError;
use crate::scene::{Material, NormalSpace, NormalTexels};
pub use crate::spec::BumpMap;
use crate::spec::SceneParams;

/// The material `base` (whose normal map is the tangent-space map of `params`' height field,
/// its texels encoded as `encoding` says) with the bump texture `params.bump_map` for `surface` covered `repeat` times. The
/// offset map of [`BumpMap::Offset`] and [`BumpMap::Derivatives`] is already in `base`, made
/// once per scene by [`offset_map`].
pub fn surface_material(
    params: &SceneParams,
    base: &Material,
    surface: &Surface,
    repeat: Vec2,
    encoding: Encoding,
) -> Material {
    let mut material = base.clone();
    match (params.bump_map, base.normal_texels) {
        (BumpMap::Derivatives, NormalTexels::Offset { range }) => {
            let size = (base.normal_map.width(), base.normal_map.height());
            let scale = displacement_per_slope(surface, repeat, size);
            material.normal_texels = NormalTexels::Derivatives { range, scale };
        }
        (BumpMap::ObjectSpace, _) => {
            let map = object_space_normal_map(surface, repeat, &base.normal_map.levels()[0], encoding, params.mip_mode);
            material.normal_map = Arc::new(map.into_mips());
            material.normal_texels = NormalTexels::UnitVector;
            material.normal_space = NormalSpace::Object { scale: Vec2::ONE / repeat };
        }
        (BumpMap::SurfaceDependent, _) => {
            // The same field and options already made `chain`, so they cannot fail here; `build`
            // refuses this map for a normal map given without heights.
            let crate::spec::BumpSource::Heights(field) = &params.bumps else {
                unreachable!("a surface-dependent map is made from heights")
            };
            let options = &params.normal_map;
            let dependent = surface_dependent_normal_map(surface, repeat, field, options, params.mip_mode)
                .expect("the field and options made the tangent-space chain");
            material.normal_map = Arc::new(dependent.into_mips());
            material.normal_texels = NormalTexels::UnitVector;
            material.normal_space = NormalSpace::SurfaceTangent { scale: Vec2::ONE / repeat };
        }
        _ => {}
    }
    material
}

/// ∂d/∂u and ∂d/∂v of the displacement per unit of a `size` map's slope (per texel), the map
/// repeated `repeat` times over `surface`: `ℓ · repeat · size` (`bumpmap_math::blinn`).
fn displacement_per_slope(surface: &Surface, repeat: Vec2, size: (usize, usize)) -> Vec2 {
    let texel_side = displacement_per_unit_height(surface, repeat, size, 1.0);
    texel_side * repeat * Vec2::new(size.0 as f32, size.1 as f32)
}

/// The size of a map that covers `surface` once where the texture repeats `repeat` times: one
/// texel per texel of the repeated `width`×`height` map, at most 4096 a side.
fn covering_size(width: usize, height: usize, repeat: Vec2) -> (usize, usize) {
    (
        ((width as f32 * repeat.x.abs()).round() as usize).clamp(1, 4096),
        ((height as f32 * repeat.y.abs()).round() as usize).clamp(1, 4096),
    )
}

/// For texel `i` of a `w`-wide, `h`-tall map covering the surface once: the surface
/// parameters (u, v) of its centre and the texel of the repeated `mw`×`mh` map there.
fn covering_texel(i: usize, (w, h): (usize, usize), repeat: Vec2, (mw, mh): (usize, usize)) -> (Vec2, usize, usize) {
    let (u, v) = (((i % w) as f32 + 0.5) / w as f32, ((i / w) as f32 + 0.5) / h as f32);
    let (s, t) = (repeat.x * u, repeat.y * v);
    let x = ((s - s.floor()) * mw as f32) as usize % mw;
    let y = ((t - t.floor()) * mh as f32) as usize % mh;
    (Vec2::new(u, v), x, y)
}

/// An object-space normal map for `surface` (Peercy §2.1): the tangent-space map's level 0
/// (texels encoded as `enc` says), repeated `repeat` times as the surface's texture is, with each normal rotated by the
/// surface's frame at that point. One texel per texel of the repeated tangent-space map (at
/// most 4096 along each side), with its own mip chain made as `mode` says.
pub fn object_space_normal_map(
    surface: &Surface,
    repeat: Vec2,
    tangent_level0: &Rgba8Image,
    enc: Encoding,
    mode: MipMode,
) -> MipChain {
    let level = tangent_level0;
    let (w, h) = covering_size(level.width, level.height, repeat);
    let normals: Vec<Vec3> = (0..w * h)
        .into_par_iter()
        .map(|i| {
            let (uv, x, y) = covering_texel(i, (w, h), repeat, (level.width, level.height));
            let (n, _) = level.decode(x, y, enc);
            let (t, b, nn) = surface.eval(uv.x, uv.y).texture_frame(repeat);
            (t * n.x + b * n.y + nn * n.z).normalize_or(nn)
        })
        .collect();
    MipChain::from_normals(w, h, &normals, enc, mode)
}

/// Peercy's surface-dependent map (Eq. 3–6): for each texel of a map covering `surface` once,
/// Blinn's perturbed normal (`bumpmap_math::blinn`) from the surface's exact ∂P/∂u, ∂P/∂v at its
/// centre and the height field's slopes as `options`' kernel measures them, in that texel's
/// tangent frame (T = ∂P/∂u / |∂P/∂u|, B = N × T, as the vertex stage's), so that it is lit
/// exactly as the surface-independent map is. One texel per texel of the repeated map (at most
/// 4096 a side), with its own mip chain made as `mode` says.
pub fn surface_dependent_normal_map(
    surface: &Surface,
    repeat: Vec2,
    field: &HeightField,
    options: &NormalMapOptions,
    mode: MipMode,
) -> Result<MipChain, CoreError> {
    // The slopes at 16 bits, so quantizing them is far below the 8-bit map's own step.
    let slopes = bumpmap_math::normalmap::normal_map_level0_texels::<[u16; 4]>(field, options)?;
    let (mw, mh) = (slopes.width, slopes.height);
    let (w, h) = covering_size(mw, mh, repeat);
    // d = ℓ·(scale·F), and the map's texel holds n ∝ (−scale·F_x, −scale·F_y, 1).
    let per_slope = displacement_per_slope(surface, repeat, (mw, mh));
    let normals: Vec<Vec3> = (0..w * h)
        .into_par_iter()
        .map(|i| {
            let (uv, x, y) = covering_texel(i, (w, h), repeat, (mw, mh));
            let (n, _) = slopes.decode(x, y, options.encoding);
            let (a, b) = (-n.x / n.z.max(1e-4), -n.y / n.z.max(1e-4));
            let p = surface.eval(uv.x, uv.y);
            let perturbed = perturbed_normal(&p, per_slope.x * a, per_slope.y * b);
            let (t, b, nn) = p.texture_frame(repeat);
            Vec3::new(perturbed.dot(t), perturbed.dot(b), perturbed.dot(nn))
        })
        .collect();
    Ok(MipChain::from_normals(w, h, &normals, options.encoding, mode))
}

/// An offset map (Kilgard §2.2, Eq. 6–7): each texel's offset `D = (−s·∂F/∂x, −s·∂F/∂y)` (the
/// normal map's slopes) range-compressed as `D / range` in RG, `range` the largest component
/// over the map; the smaller levels box-filter the offsets (what the hardware's mipmapping
/// would do to them). Returns the texture and `range`.
pub fn offset_map(field: &HeightField, options: &NormalMapOptions) -> Result<(Rgba8Mips, f32), CoreError> {
    // The slopes at 16 bits, as for the surface-dependent map.
    let slopes = bumpmap_math::normalmap::normal_map_level0_texels::<[u16; 4]>(field, options)?;
    let offsets: Vec<Vec2> = (0..slopes.width * slopes.height)
        .map(|i| {
            let (n, _) = slopes.decode(i % slopes.width, i / slopes.width, options.encoding);
            Vec2::new(n.x, n.y) / n.z.max(1e-4)
        })
        .collect();
    let range = offsets.iter().fold(1e-6f32, |m, d| m.max(d.x.abs()).max(d.y.abs()));
    let texels = offsets
        .iter()
        .map(|d| [options.encoding.encode(d.x / range), options.encoding.encode(d.y / range), 128, 255])
        .collect();
    let level0 = Rgba8Image::new(slopes.width, slopes.height, texels);
    Ok((Rgba8Mips::with_box_mipmaps(level0), range))
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpmap_math::surface::BicubicPatch;

    fn options() -> NormalMapOptions {
        NormalMapOptions { scale: 2.0, ..Default::default() }
    }

    #[test]
    fn on_the_square_wall_the_surface_dependent_map_is_the_tangent_space_map_repeated() {
        // The wall's texels are squares of the mean side and its frame is the texture's, so
        // Eq. 3–6 reduce to Eq. 8–11: the same normals, one byte step apart at most (the two
        // maps round the same vector through different arithmetic).
        let field = bumpmap_math::HeightPreset::Bricks.render(32, 32);
        let wall = Surface::Wall { width: 4.0, height: 4.0 };
        let repeat = Vec2::new(2.0, 2.0);
        let tangent = MipChain::<[u8; 4]>::from_height(&field, &options(), MipMode::LengthInAlpha).unwrap();
        let dependent =
            surface_dependent_normal_map(&wall, repeat, &field, &options(), MipMode::LengthInAlpha).unwrap();
        let (level, t) = (&dependent.levels[0], &tangent.levels[0]);
        assert_eq!((level.width, level.height), (64, 64));
        for y in 0..64 {
            for x in 0..64 {
                let (a, b) = (level.texel(x, y), t.texel(x % 32, y % 32));
                assert!(a.iter().zip(b).all(|(p, q)| p.abs_diff(q) <= 1), "({x}, {y}): {a:?} vs {b:?}");
            }
        }
    }

    #[test]
    fn on_the_stretched_patch_slopes_along_the_long_texels_are_gentler() {
        // Peercy's patch is about 4 × 1 with one map over it: a texel is twice the mean side
        // along u and half of it along v. A ramp along x rises half as steeply on the surface as
        // the surface-independent map assumes, a ramp along y twice as steeply.
        let patch = Surface::Patch(BicubicPatch::stretched());
        let tilt = |ramp_along_x: bool| {
            let field = HeightField::from_fn(64, 64, |x, y| 0.01 * if ramp_along_x { x } else { y } as f32);
            let o = NormalMapOptions { wrap: bumpmap_math::Wrap::Clamp, ..options() };
            let map = surface_dependent_normal_map(&patch, Vec2::ONE, &field, &o, MipMode::LengthInAlpha).unwrap();
            let (n, _) = map.levels[0].decode(32, 32, o.encoding);
            if ramp_along_x { -n.x / n.z } else { -n.y / n.z }
        };
        // The independent map's slope is scale · 0.01 = 0.02 per texel (measured here: 0.0118
        // along u, 0.0431 along v; the 8-bit map's step in n is 1/127.5 ≈ 0.008).
        let (along_u, along_v) = (tilt(true), tilt(false));
        assert!(along_u > 0.25 * 0.02 && along_u < 0.75 * 0.02, "along u: {along_u}");
        assert!(along_v > 1.5 * 0.02, "along v: {along_v}");
    }

    #[test]
    fn maps_made_for_a_surface_say_so() {
        for map in [BumpMap::ObjectSpace, BumpMap::SurfaceDependent, BumpMap::Derivatives] {
            assert!(map.needs_surface(), "{map:?}");
        }
        assert!(!BumpMap::Tangent.needs_surface() && !BumpMap::Offset.needs_surface());
    }
}
