//! The detail-normal study (`--studies detail`): every blend of `bumpmap_math::detail` laid a
//! noise detail over bricks and over dimples at several strengths, both maps stored at 16 bits
//! as `normalmap` makes them, and measured against the two exact compositions computed in float
//! from the heights — **added heights** (the normal of the base's heights plus the detail's) and
//! **draped detail** (the float detail normal turned into the float base normal's frame).
//!
//! What this module does not do: tile or filter the detail (both maps are the same size, one
//! texel of detail a texel of base), or render anything (the blends are per texel).

use bumpmap_math::detail::{BlendMethod, blend, draped, with_strength};
use bumpmap_math::normalmap::{normal_map_level0_texels, perturbed_normal};
use bumpmap_math::{Encoding, HeightField, HeightPreset, Kernel, Named, NormalMapOptions, Wrap, YConvention};
use glam::Vec3;

/// Texels a side of both maps.
pub const SIZE: usize = 256;
/// The bases, each under the same noise detail.
pub const BASES: [&str; 2] = ["bricks", "dimples"];
/// What the detail's slopes are multiplied by.
pub const STRENGTHS: [f32; 3] = [0.5, 1.0, 2.0];
/// The base's `normalmap --scale` (a unit step of height, in texels).
pub const BASE_SCALE: f32 = 6.0;
/// The detail's.
pub const DETAIL_SCALE: f32 = 3.0;
/// The detail's noise seed.
const NOISE_SEED: u64 = 7;

/// One blend on one base at one strength against both exact compositions, in degrees.
#[derive(Clone, Debug, PartialEq)]
pub struct DetailRow {
    /// The base ([`BASES`]).
    pub base: &'static str,
    /// The detail's strength.
    pub strength: f32,
    /// The blend.
    pub method: BlendMethod,
    /// Mean and 95th percentile of the angle to added heights' normal.
    pub added: (f64, f64),
    /// The same to draped detail's.
    pub draped: (f64, f64),
}

/// Every blend on every base at every strength.
#[derive(Clone, Debug, PartialEq)]
pub struct DetailStudy {
    /// Its rows, base by base, strength by strength, in [`BlendMethod`]'s order.
    pub rows: Vec<DetailRow>,
}

impl DetailStudy {
    /// The row of `method` on `base` at `strength`.
    pub fn row(&self, base: &str, strength: f32, method: BlendMethod) -> Option<&DetailRow> {
        self.rows.iter().find(|r| r.base == base && r.strength == strength && r.method == method)
    }
}

/// The normal-map options both maps are made with: central differences, wrapping, in texture
/// space.
fn options(scale: f32) -> NormalMapOptions {
    NormalMapOptions {
        kernel: Kernel::Central,
        wrap: Wrap::Repeat,
        scale,
        y_convention: YConvention::TEXTURE_SPACE,
        ..Default::default()
    }
}

/// `field`'s normal map at `scale` as a 16-bit file holds it, decoded.
fn stored(field: &HeightField, scale: f32) -> Vec<Vec3> {
    let map = normal_map_level0_texels::<[u16; 4]>(field, &options(scale)).expect("a preset's heights make a map");
    let d = |v: u16| Encoding::Unorm.decode16(v);
    map.texels.iter().map(|t| Vec3::new(d(t[0]), d(t[1]), d(t[2])).normalize()).collect()
}

/// `field`'s normals at `scale` in float: what a 16-bit normal map of it rounds (central
/// differences, wrapping, in texture space).
pub fn exact_normals(field: &HeightField, scale: f32) -> Vec<Vec3> {
    let (w, h) = (field.width(), field.height());
    let at = |x: usize, y: usize| field.get(x % w, y % h);
    (0..w * h)
        .map(|k| {
            let (x, y) = (k % w, k / w);
            let a = -scale * (at(x + 1, y) - at(x + w - 1, y)) / 2.0;
            let b = -scale * (at(x, y + 1) - at(x, y + h - 1)) / 2.0;
            perturbed_normal(a, b, 1.0)
        })
        .collect()
}

/// The mean and 95th percentile of the angles between `a` and `b`, in degrees.
pub fn mean_p95(a: &[Vec3], b: &[Vec3]) -> (f64, f64) {
    let mut degrees: Vec<f64> =
        a.iter().zip(b).map(|(p, q)| (p.dot(*q).clamp(-1.0, 1.0) as f64).acos().to_degrees()).collect();
    degrees.sort_by(f64::total_cmp);
    (degrees.iter().sum::<f64>() / degrees.len() as f64, degrees[degrees.len() * 95 / 100])
}

/// The preset a base is.
fn preset(base: &str) -> HeightPreset {
    match base {
        "bricks" => HeightPreset::Bricks,
        _ => HeightPreset::Dimples,
    }
}

/// Runs the study.
pub fn detail_study() -> DetailStudy {
    let noise = HeightPreset::Noise(NOISE_SEED).render(SIZE, SIZE);
    let detail_stored = stored(&noise, DETAIL_SCALE);
    let mut rows = Vec::new();
    for base_name in BASES {
        let base_field = preset(base_name).render(SIZE, SIZE);
        let (base16, base) = (stored(&base_field, BASE_SCALE), exact_normals(&base_field, BASE_SCALE));
        for strength in STRENGTHS {
            let detail16: Vec<Vec3> = detail_stored.iter().map(|d| with_strength(*d, strength)).collect();
            let detail = exact_normals(&noise, DETAIL_SCALE * strength);
            // Added heights: base + the detail's heights scaled to the base's scale.
            let ratio = DETAIL_SCALE * strength / BASE_SCALE;
            let summed: Vec<f32> = base_field.to_f32().iter().zip(noise.to_f32()).map(|(b, d)| b + d * ratio).collect();
            let added = exact_normals(&HeightField::new(SIZE, SIZE, summed).expect("finite heights"), BASE_SCALE);
            let draped: Vec<Vec3> = base.iter().zip(&detail).map(|(b, d)| draped(*b, *d)).collect();
            for &method in BlendMethod::ALL {
                let blended: Vec<Vec3> = base16.iter().zip(&detail16).map(|(b, d)| blend(*b, *d, method)).collect();
                rows.push(DetailRow {
                    base: base_name,
                    strength,
                    method,
                    added: mean_p95(&blended, &added),
                    draped: mean_p95(&blended, &draped),
                });
            }
        }
    }
    DetailStudy { rows }
}
