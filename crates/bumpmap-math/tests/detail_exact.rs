//! Every detail blend against both exact compositions, from height fields: the base's and the
//! detail's normal maps are made at 16 bits from their heights (`normalmap`, central
//! differences); **added heights**' exact normal is that of the summed heights, in float;
//! **draped detail**'s is the float detail normal turned into the float base normal's frame.
//! Partial derivatives must meet the first and RNM the second within 0.1° on average (what is
//! left is the 16-bit rounding of the inputs); the other methods' errors are printed, the table
//! the README shows.

use bumpmap_math::detail::{BlendMethod, added, blend, draped, with_strength};
use bumpmap_math::normalmap::{normal_map_level0_texels, perturbed_normal};
use bumpmap_math::{Encoding, HeightField, HeightPreset, Kernel, Named, NormalMapOptions, Wrap, YConvention};
use glam::Vec3;

const N: usize = 256;
/// Heights a unit step, in texels (normalmap's --scale): the base's bricks and dimples.
const BASE_SCALE: f32 = 6.0;
/// The detail noise's.
const DETAIL_SCALE: f32 = 3.0;

fn options(scale: f32) -> NormalMapOptions {
    NormalMapOptions {
        kernel: Kernel::Central,
        wrap: Wrap::Repeat,
        scale,
        y_convention: YConvention::TEXTURE_SPACE,
        ..Default::default()
    }
}

/// The 16-bit normal map of `field` at `scale`, decoded.
fn stored(field: &HeightField, scale: f32) -> Vec<Vec3> {
    let map = normal_map_level0_texels::<[u16; 4]>(field, &options(scale)).unwrap();
    let d = |v: u16| Encoding::Unorm.decode16(v);
    map.texels.iter().map(|t| Vec3::new(d(t[0]), d(t[1]), d(t[2])).normalize()).collect()
}

/// The float normals of `field` at `scale`: central differences, wrapping, as `stored` makes
/// them before rounding.
fn exact(field: &HeightField, scale: f32) -> Vec<Vec3> {
    let at = |x: usize, y: usize| field.get(x % N, y % N);
    (0..N * N)
        .map(|k| {
            let (x, y) = (k % N, k / N);
            let a = -scale * (at(x + 1, y) - at(x + N - 1, y)) / 2.0;
            let b = -scale * (at(x, y + 1) - at(x, y + N - 1)) / 2.0;
            perturbed_normal(a, b, 1.0)
        })
        .collect()
}

fn mean_p95(mut degrees: Vec<f32>) -> (f32, f32) {
    degrees.sort_by(f32::total_cmp);
    (degrees.iter().sum::<f32>() / degrees.len() as f32, degrees[degrees.len() * 95 / 100])
}

fn angles(a: &[Vec3], b: &[Vec3]) -> Vec<f32> {
    a.iter().zip(b).map(|(p, q)| p.dot(*q).clamp(-1.0, 1.0).acos().to_degrees()).collect()
}

#[test]
fn every_blend_against_both_exact_compositions() {
    let noise = HeightPreset::Noise(7).render(N, N);
    let mut rows = Vec::new();
    for (base_name, base_preset) in [("bricks", HeightPreset::Bricks), ("dimples", HeightPreset::Dimples)] {
        let base_field = base_preset.render(N, N);
        let (base16, base) = (stored(&base_field, BASE_SCALE), exact(&base_field, BASE_SCALE));
        // Our float normals are the stored map's before rounding: the conventions agree.
        let (check, _) = mean_p95(angles(&base16, &base));
        assert!(check < 0.01, "{check}°");
        for strength in [0.5f32, 1.0, 2.0] {
            let detail16: Vec<Vec3> =
                stored(&noise, DETAIL_SCALE).iter().map(|d| with_strength(*d, strength)).collect();
            let detail = exact(&noise, DETAIL_SCALE * strength);
            // Added heights: the normal of base + strength · detail heights, in float.
            let summed: Vec<f32> = (0..N * N)
                .map(|k| {
                    let (x, y) = (k % N, k / N);
                    base_field.get(x, y) + noise.get(x, y) * DETAIL_SCALE * strength / BASE_SCALE
                })
                .collect();
            let exact_added = exact(&HeightField::new(N, N, summed).unwrap(), BASE_SCALE);
            // The same from the float normals themselves: heights that add are slopes that add.
            let from_normals: Vec<Vec3> = base.iter().zip(&detail).map(|(b, d)| added(*b, *d)).collect();
            assert!(mean_p95(angles(&exact_added, &from_normals)).0 < 0.01);
            let exact_draped: Vec<Vec3> = base.iter().zip(&detail).map(|(b, d)| draped(*b, *d)).collect();
            for &method in BlendMethod::ALL {
                let blended: Vec<Vec3> = base16.iter().zip(&detail16).map(|(b, d)| blend(*b, *d, method)).collect();
                let (added_mean, added_p95) = mean_p95(angles(&blended, &exact_added));
                let (draped_mean, draped_p95) = mean_p95(angles(&blended, &exact_draped));
                rows.push(format!(
                    "| {base_name} + noise | {strength} | {} | {added_mean:.3}° | {added_p95:.3}° | {draped_mean:.3}° | {draped_p95:.3}° |",
                    method.name()
                ));
                if method == BlendMethod::PartialDerivative {
                    assert!(added_mean <= 0.1, "partial derivatives against added heights: {added_mean}°");
                }
                if method == BlendMethod::Rnm {
                    assert!(draped_mean <= 0.1, "RNM against draped detail: {draped_mean}°");
                }
            }
        }
    }
    eprintln!("| base | detail strength | method | added heights: mean | p95 | draped detail: mean | p95 |");
    eprintln!("| --- | --- | --- | --- | --- | --- | --- |");
    for row in rows {
        eprintln!("{row}");
    }
}
