//! The horizon map's shadows, ambient occlusion and bent normals (`bumpmap_math::horizon`)
//! against rays cast at the carved surface itself (`bumpmap_reference::occlusion`,
//! `bumpmap_math::height_trace`).

use glam::{Vec2, Vec3};

use bumpmap_math::height_trace::{TexelRay, surface_height, trace};
use bumpmap_math::horizon::{AZIMUTHS, Horizons, visibility};
use bumpmap_math::{HeightMips, HeightPreset, HorizonMap, Wrap};
use bumpmap_reference::occlusion::occlusion_map;

/// Texels per unit of height: `normalmap`'s default scale.
const DEPTH: f32 = 4.0;

fn heights(preset: HeightPreset, size: usize) -> (HeightMips, HorizonMap) {
    let mips = HeightMips::from_field(&preset.render(size, size)).unwrap();
    let horizons = HorizonMap::from_heights(&mips.levels()[0], Wrap::Repeat).unwrap();
    (mips, horizons)
}

/// GL's LINEAR at texel point (x, y) with REPEAT, as a texture unit filters the horizon map.
fn bilinear(map: &HorizonMap, x: f32, y: f32) -> Horizons {
    let l = &map.levels()[0];
    let (u, v) = (x - 0.5, y - 0.5);
    let (i, j) = (u.floor(), v.floor());
    let (a, b) = (u - i, v - j);
    let at = |di: i64, dj: i64| {
        let c = (i as i64 + di).rem_euclid(l.width as i64) as usize;
        let r = (j as i64 + dj).rem_euclid(l.height as i64) as usize;
        l.texels[r * l.width + c]
    };
    std::array::from_fn(|k| {
        (1.0 - a) * (1.0 - b) * at(0, 0)[k]
            + a * (1.0 - b) * at(1, 0)[k]
            + (1.0 - a) * b * at(0, 1)[k]
            + a * b * at(1, 1)[k]
    })
}

/// A number in [0, 1) from an index and a channel.
fn rand(i: u32, c: u32) -> f32 {
    bumpmap_math::hash::unit(bumpmap_math::hash::hash32(&[i, c]))
}

/// Of points at random on the surface, with the light at a random azimuth `zenith_deg` from the
/// base normal, where the lighting model lights them (the light above the carved surface's
/// tangent plane), the share where the horizon map and an exact shadow ray agree, and the share
/// a shadow ray finds lit (what leaving shadows out agrees on).
fn shadow_agreement(mips: &HeightMips, horizons: &HorizonMap, zenith_deg: f32, points: u32) -> (f64, f64) {
    let level0 = &mips.levels()[0];
    let minmax = mips.minmax().unwrap();
    let (w, h) = (level0.width as f32, level0.height as f32);
    let (mut agree, mut lit, mut counted) = (0u32, 0u32, 0u32);
    for i in 0..points {
        let p = Vec2::new(rand(i, 0) * w, rand(i, 1) * h);
        let phi = std::f32::consts::TAU * rand(i, 2);
        let theta = zenith_deg.to_radians();
        // Toward the light, texel space: across in texels, up in heights.
        let dir = Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos() / DEPTH);
        let height = surface_height(level0, p.x, p.y);
        // Only where the lighting model lights the carved surface (N·L > 0): the light rises
        // above its tangent plane there.
        let g = bumpmap_math::interpolant::sample_texels(level0, Wrap::Repeat, p.x, p.y);
        if dir.z <= g.dx * dir.x + g.dy * dir.y {
            continue;
        }
        counted += 1;
        let ray = TexelRay { origin: Vec3::new(p.x, p.y, (height + 1e-4).min(1.0)), dir };
        let truth = trace(level0, minmax, &ray, f32::INFINITY).is_none();
        let horizon = visibility(&bilinear(horizons, p.x, p.y), dir) >= 0.5;
        agree += u32::from(truth == horizon);
        lit += u32::from(truth);
    }
    (agree as f64 / counted as f64, lit as f64 / counted as f64)
}

#[test]
fn horizon_shadows_agree_with_shadow_rays_on_bricks() {
    // At the preset's own size (256²: bevels two texels wide). At 128² the bevels are one
    // texel, and a texel's horizon says little of points between it and the next across an edge:
    // 98.4, 95.0 and 93.7 % at 45°, 70° and 80° (lit points, same heights and depth).
    let (mips, horizons) = heights(HeightPreset::Bricks, HeightPreset::DEFAULT_SIZE);
    for (zenith, bound) in [(45.0, 0.98), (70.0, 0.98), (80.0, 0.97)] {
        let (agree, lit) = shadow_agreement(&mips, &horizons, zenith, 20_000);
        eprintln!(
            "bricks, light {zenith}° from the normal: horizon agrees {:.2} %, no shadow {:.2} %",
            agree * 100.0,
            lit * 100.0
        );
        assert!(agree >= bound, "{zenith}°: {agree} < {bound}");
        assert!(agree > lit, "{zenith}°: the horizon map must beat leaving shadows out ({agree} vs {lit})");
    }
}

#[test]
fn horizon_occlusion_and_bent_normals_match_256_rays_a_texel() {
    for preset in [HeightPreset::Bricks, HeightPreset::Dimples] {
        let (mips, horizons) = heights(preset, 128);
        let stride = 4;
        let truth = occlusion_map(&mips, DEPTH, 16, stride);
        let ao = horizons.ambient_occlusion(DEPTH);
        let bent = horizons.bent_normals(DEPTH);
        let w = mips.width();
        let points = (0..mips.height()).step_by(stride).flat_map(|y| (0..w).step_by(stride).map(move |x| y * w + x));
        let (mut ao_error, mut angle, mut n) = (0.0f64, 0.0f64, 0usize);
        for (t, i) in truth.iter().zip(points) {
            ao_error += (ao[i] - t.ambient).abs() as f64;
            angle += bent[i].dot(t.bent_normal).clamp(-1.0, 1.0).acos().to_degrees() as f64;
            n += 1;
        }
        let (ao_error, angle) = (ao_error / n as f64, angle / n as f64);
        let mean_ao = truth.iter().map(|t| t.ambient as f64).sum::<f64>() / n as f64;
        eprintln!(
            "{preset:?}: AO mean abs error {ao_error:.4} (truth's mean {mean_ao:.3}), bent normal mean angle {angle:.2}° over {n} texels, {AZIMUTHS} directions"
        );
        assert!(ao_error <= 0.02, "{preset:?}: AO error {ao_error}");
        assert!(angle <= 3.0, "{preset:?}: bent normals off by {angle}°");
        assert!(mean_ao < 0.99, "{preset:?}: the test needs occluded texels to mean anything");
    }
}
