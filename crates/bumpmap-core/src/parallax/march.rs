//! The marches, each written once: where a fragment's view ray meets the heights below the
//! polygon, and how much light reaches the hit (`parallax.wgsl` is their copy, tested against
//! them). The heights are sampled through a closure (the backends' texture units). What this
//! module does not do: choose a level, or light the fragment.

use glam::{Vec2, Vec3};

use bumpmap_math::height_mips::{HeightLevel, MinMaxLevel};
use bumpmap_math::height_trace::{TexelRay, trace};

use super::{EXACT_SHADOW_LIFT, ParallaxShadow, RELIEF_BISECTIONS, SHADOW_BIAS, SOFT_SHADOW_SHARPNESS};

/// A fragment's view ray in texture space: from the entry point (s, t, 1) away from the eye.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureRay {
    /// The entry point's texture coordinates.
    pub st: Vec2,
    /// Texture coordinates per unit of height descended: `−v.xy / v.z` for `v` toward the eye.
    pub step: Vec2,
    /// The base surface's fall below its tangent plane in heights per unit of s² and t²
    /// (positive where it curves away from the normal); zero to ignore curvature.
    pub curvature: Vec2,
}

impl TextureRay {
    /// The ray from `st` away from `to_eye` (texture space), or `None` when the eye is not
    /// above the tangent plane.
    #[inline]
    pub fn new(st: Vec2, to_eye: Vec3, curvature: Vec2) -> Option<Self> {
        (to_eye.z > 0.0 && to_eye.is_finite()).then(|| Self {
            st,
            step: Vec2::new(-to_eye.x, -to_eye.y) / to_eye.z,
            curvature,
        })
    }

    /// Texture coordinates after descending `descent` (in heights).
    #[inline]
    pub fn at(&self, descent: f32) -> Vec2 {
        self.st + descent * self.step
    }

    /// The ray's height over the surface after descending `descent`: `1 − descent`, plus how far
    /// a curved surface has fallen away below the tangent plane by then.
    #[inline]
    pub fn height(&self, descent: f32) -> f32 {
        let o = descent * self.step;
        1.0 - descent + (self.curvature.x * o.x * o.x + self.curvature.y * o.y * o.y)
    }
}

/// Where a march met the heights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarchHit {
    /// Texture coordinates of the hit: where the maps are read.
    pub st: Vec2,
    /// Height descended along the straight ray from the entry point (1 − the hit's height).
    pub descent: f32,
}

/// Parallax mapping with offset limiting: the entry point moved by `(1 − h)·cos θ` units of
/// descent along the ray, h the height at the entry point and cos θ (`cos_view`) the view
/// angle's cosine (Welsh's limiting, which keeps grazing offsets from swimming off).
pub fn offset(ray: &TextureRay, cos_view: f32, sample: &mut impl FnMut(Vec2) -> f32) -> MarchHit {
    let descent = (1.0 - sample(ray.st)) * cos_view.clamp(0.0, 1.0);
    MarchHit { st: ray.at(descent), descent }
}

/// The layers' descents: layer i at `i / n`; with curvature a ray may need up to four times
/// as many before it meets the heights or rises out of the slab.
#[inline]
fn layer_descent(i: u32, n: u32) -> f32 {
    i as f32 / n as f32
}

/// The first layer `i` (descending `i/n`) at or below the heights, with the height the ray had
/// one layer earlier and the sample there; `None` where the ray left the slab first.
#[inline]
fn first_layer_below(ray: &TextureRay, n: u32, sample: &mut impl FnMut(Vec2) -> f32) -> Option<(u32, f32, f32)> {
    let (mut prev_ray, mut prev_height) = (1.0f32, 1.0f32);
    for i in 0..=4 * n {
        let d = layer_descent(i, n);
        let r = ray.height(d);
        if i > 0 && r > 1.0 {
            return None;
        }
        let h = sample(ray.at(d));
        if h >= r {
            return Some((i, prev_ray - prev_height, h - r));
        }
        (prev_ray, prev_height) = (r, h);
    }
    None
}

/// Steep parallax mapping: the first of `layers` layers at or below the heights.
pub fn steep(ray: &TextureRay, layers: u32, sample: &mut impl FnMut(Vec2) -> f32) -> Option<MarchHit> {
    let n = layers.max(1);
    first_layer_below(ray, n, sample).map(|(i, _, _)| {
        let descent = layer_descent(i, n);
        MarchHit { st: ray.at(descent), descent }
    })
}

/// Parallax occlusion mapping's layer count: `layers` at grazing angles down to a quarter of it
/// looking straight on, linear in `cos_view` (Tatarchuk's `lerp(max, min, N·V)`).
#[inline]
pub fn occlusion_layers(layers: u32, cos_view: f32) -> u32 {
    let max = layers.max(1) as f32;
    let min = (layers.max(1) as f32 / 4.0).ceil();
    // Rounded half up (floor(x + ½)), as WGSL can say it too.
    (max + (min - max) * cos_view.clamp(0.0, 1.0) + 0.5).floor().max(1.0) as u32
}

/// Parallax occlusion mapping: [`occlusion_layers`] layers, the hit where the straight line
/// between the last sample above and the first below crosses the ray.
pub fn occlusion(
    ray: &TextureRay,
    layers: u32,
    cos_view: f32,
    sample: &mut impl FnMut(Vec2) -> f32,
) -> Option<MarchHit> {
    let n = occlusion_layers(layers, cos_view);
    first_layer_below(ray, n, sample).map(|(i, above, below)| {
        let at = if i == 0 {
            0.0
        } else {
            // `above` the ray over the heights one layer back, `below` the heights over the ray now.
            let w = above / (above + below);
            (i as f32 - 1.0 + if w.is_finite() { w } else { 1.0 }) / n as f32
        };
        MarchHit { st: ray.at(at), descent: at }
    })
}

/// Relief mapping: the linear search of [`steep`] with `layers` layers, then
/// [`RELIEF_BISECTIONS`] halvings of the layer it ended in; the hit at the last interval's middle.
pub fn relief(ray: &TextureRay, layers: u32, sample: &mut impl FnMut(Vec2) -> f32) -> Option<MarchHit> {
    let n = layers.max(1);
    let (i, _, _) = first_layer_below(ray, n, sample)?;
    if i == 0 {
        return Some(MarchHit { st: ray.st, descent: 0.0 });
    }
    let (mut a, mut b) = (layer_descent(i - 1, n), layer_descent(i, n));
    for _ in 0..RELIEF_BISECTIONS {
        let mid = 0.5 * (a + b);
        if sample(ray.at(mid)) >= ray.height(mid) {
            b = mid;
        } else {
            a = mid;
        }
    }
    let descent = 0.5 * (a + b);
    Some(MarchHit { st: ray.at(descent), descent })
}

/// The exact hit: the straight ray walked through `minmax` over `level0`'s interpolant
/// (`bumpmap_math::height_trace::trace`). With curvature, a ray whose curved path has risen out
/// of the slab by the time the straight one meets the heights misses (`None`).
pub fn exact(ray: &TextureRay, level0: &HeightLevel, minmax: &[MinMaxLevel]) -> Option<MarchHit> {
    let (w, h) = (level0.width as f32, level0.height as f32);
    let texel = TexelRay {
        origin: Vec3::new(ray.st.x * w, ray.st.y * h, 1.0),
        dir: Vec3::new(ray.step.x * w, ray.step.y * h, -1.0),
    };
    let descent = trace(level0, minmax, &texel, f32::INFINITY).unwrap_or(1.0);
    (ray.height(descent) <= 1.0 || descent == 0.0).then(|| MarchHit { st: ray.at(descent), descent })
}

/// How much light reaches the hit (`st`, `height`) from `to_light` (texture space, toward the
/// light), by a march of up to `layers` steps over the height left above it: 1 lit, 0 in shadow.
/// A light at or below the tangent plane is the lighting model's business: 1.
pub fn shadow(
    st: Vec2,
    height: f32,
    to_light: Vec3,
    layers: u32,
    mode: ParallaxShadow,
    sample: &mut impl FnMut(Vec2) -> f32,
) -> f32 {
    if mode == ParallaxShadow::Off || to_light.z <= 0.0 || height >= 1.0 || !to_light.is_finite() {
        return 1.0;
    }
    let rise = 1.0 - height;
    let step = Vec2::new(to_light.x, to_light.y) / to_light.z;
    let n = ((layers.max(1) as f32 * rise).ceil() as u32).max(1);
    let mut worst = 0.0f32;
    for i in 1..=n {
        let r = rise * i as f32 / n as f32;
        let above = sample(st + r * step) - (height + r);
        match mode {
            ParallaxShadow::Hard if above > SHADOW_BIAS => return 0.0,
            ParallaxShadow::Soft => worst = worst.max((above - SHADOW_BIAS) * (1.0 - i as f32 / n as f32)),
            _ => {}
        }
    }
    1.0 - (worst * SOFT_SHADOW_SHARPNESS).clamp(0.0, 1.0)
}

/// The exact shadow: 0 where a ray from just above the hit toward the light meets the heights
/// before leaving the slab, 1 otherwise (hard: the reference's point light).
pub fn exact_shadow(st: Vec2, height: f32, to_light: Vec3, level0: &HeightLevel, minmax: &[MinMaxLevel]) -> f32 {
    if to_light.z <= 0.0 || !to_light.is_finite() {
        return 1.0;
    }
    let (w, h) = (level0.width as f32, level0.height as f32);
    let step = Vec2::new(to_light.x, to_light.y) / to_light.z;
    let ray = TexelRay {
        origin: Vec3::new(st.x * w, st.y * h, (height + EXACT_SHADOW_LIFT).min(1.0)),
        dir: Vec3::new(step.x * w, step.y * h, 1.0),
    };
    if trace(level0, minmax, &ray, f32::INFINITY).is_some() { 0.0 } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parallax::TextureFrame;
    use bumpmap_math::HeightMips;

    fn bricks() -> HeightMips {
        HeightMips::from_field(&bumpmap_math::HeightPreset::Bricks.render(64, 64)).unwrap()
    }

    /// A ray entering at `st` seen from `theta` degrees off the normal toward azimuth `phi`,
    /// over a surface where a texel is `texel` object units and a unit of height `depth`.
    fn ray_at(st: Vec2, theta: f32, phi: f32, texel: f32, size: f32, depth: f32) -> TextureRay {
        let (t, p) = (theta.to_radians(), phi.to_radians());
        let v = Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
        let frame = TextureFrame { jacobian: [texel * size, 0.0, 0.0, texel * size], depth };
        TextureRay::new(st, frame.to_texture(v), Vec2::ZERO).unwrap()
    }

    /// The first point of `ray` at or below the bilinear heights: steps of 1/4096 of the depth,
    /// then bisection. Slow and simple.
    fn brute_force(ray: &TextureRay, sample: &mut impl FnMut(Vec2) -> f32) -> Vec2 {
        let below = |d: f32, sample: &mut dyn FnMut(Vec2) -> f32| sample(ray.at(d)) >= ray.height(d);
        let mut d = 0.0;
        while d < 1.0 && !below(d + 1.0 / 4096.0, sample) {
            d += 1.0 / 4096.0;
        }
        let (mut a, mut b) = (d, (d + 1.0 / 4096.0).min(1.0));
        for _ in 0..30 {
            let m = 0.5 * (a + b);
            if below(m, sample) { b = m } else { a = m }
        }
        ray.at(b)
    }

    #[test]
    fn the_marches_converge_on_the_first_crossing_of_the_heights_they_sample_as_layers_grow() {
        // Bricks 64², a texel 1/64 of a unit, 4 texels deep: seen at 70°. The marches sample the
        // bilinear heights, so their limit is the bilinear surface's first crossing.
        let m = bricks();
        let level0 = &m.levels()[0];
        let mut sample = |st: Vec2| level0.bilinear(st.x, st.y);
        let mut errors = [[0f32; 3]; 3];
        let n = 200;
        for i in 0..n {
            let st = Vec2::new(i as f32 * 0.137 % 1.0, i as f32 * 0.291 % 1.0);
            let ray = ray_at(st, 70.0, i as f32 * 7.0, 1.0 / 64.0, 64.0, 4.0 / 64.0);
            let truth = brute_force(&ray, &mut sample);
            for (k, layers) in [8, 32, 128].into_iter().enumerate() {
                for (j, hit) in [
                    steep(&ray, layers, &mut sample),
                    occlusion(&ray, layers, 0.0, &mut sample),
                    relief(&ray, layers, &mut sample),
                ]
                .into_iter()
                .enumerate()
                {
                    errors[j][k] += (hit.unwrap().st - truth).length() * 64.0 / n as f32;
                }
            }
        }
        for (j, name) in ["steep", "occlusion", "relief"].iter().enumerate() {
            let e = errors[j];
            // Each fourfold increase in layers must cut the mean error (texels) clearly.
            assert!(e[1] < 0.75 * e[0] && e[2] < 0.75 * e[1], "{name}: {e:?}");
        }
        // POM and relief refine within a layer; steep does not.
        assert!(errors[1][1] < errors[0][1] && errors[2][1] < errors[0][1], "{errors:?}");
    }

    #[test]
    fn looking_straight_down_every_march_stays_put() {
        let m = bricks();
        let level0 = &m.levels()[0];
        let mut sample = |st: Vec2| level0.bilinear(st.x, st.y);
        let ray = TextureRay::new(Vec2::new(0.3, 0.7), Vec3::new(0.0, 0.0, 5.0), Vec2::ZERO).unwrap();
        for hit in [
            Some(offset(&ray, 1.0, &mut sample)),
            steep(&ray, 16, &mut sample),
            occlusion(&ray, 16, 1.0, &mut sample),
            relief(&ray, 16, &mut sample),
            exact(&ray, level0, m.minmax().unwrap()),
        ] {
            assert_eq!(hit.unwrap().st, ray.st);
        }
        assert_eq!(occlusion_layers(32, 1.0), 8);
        assert_eq!(occlusion_layers(32, 0.0), 32);
        assert_eq!(occlusion_layers(1, 0.5), 1);
    }

    #[test]
    fn a_curved_surface_lets_a_grazing_ray_escape() {
        // Flat heights at 0.5: a straight ray meets them; on a surface curving away fast enough
        // the ray rises out of the slab first.
        let flat = HeightMips::from_field(&bumpmap_math::HeightField::from_fn(16, 16, |_, _| 0.5)).unwrap();
        let level0 = &flat.levels()[0];
        let mut sample = |st: Vec2| level0.bilinear(st.x, st.y);
        let straight = TextureRay { st: Vec2::ZERO, step: Vec2::new(1.0, 0.0), curvature: Vec2::ZERO };
        let curved = TextureRay { curvature: Vec2::new(3.0, 0.0), ..straight };
        assert!(steep(&straight, 16, &mut sample).is_some());
        assert!(steep(&curved, 16, &mut sample).is_none());
        assert!(occlusion(&curved, 16, 0.2, &mut sample).is_none());
        assert!(exact(&straight, level0, flat.minmax().unwrap()).is_some());
        assert!(exact(&curved, level0, flat.minmax().unwrap()).is_none());
    }

    #[test]
    fn a_ridge_shadows_what_lies_behind_it_from_a_low_light() {
        let ridge = bumpmap_math::HeightField::from_fn(32, 4, |x, _| if (16..18).contains(&x) { 1.0 } else { 0.2 });
        let m = HeightMips::from_field(&ridge).unwrap();
        let (level0, minmax) = (&m.levels()[0], m.minmax().unwrap());
        let mut sample = |st: Vec2| level0.bilinear(st.x, st.y);
        // A point on the floor at x = 12 texels; the light low toward +x (over the ridge) or −x.
        // Texture space: a texel is 1/32 of s; the light rises 0.1 of the depth per texel.
        let st = Vec2::new(12.5 / 32.0, 0.5);
        let toward = Vec3::new(1.0 / 32.0, 0.0, 0.1);
        let away = Vec3::new(-1.0 / 32.0, 0.0, 0.1);
        for mode in [ParallaxShadow::Hard, ParallaxShadow::Soft] {
            assert!(shadow(st, 0.2, toward, 32, mode, &mut sample) < 0.5, "{mode:?}");
            assert_eq!(shadow(st, 0.2, away, 32, mode, &mut sample), 1.0, "{mode:?}");
        }
        assert_eq!(shadow(st, 0.2, toward, 32, ParallaxShadow::Off, &mut sample), 1.0);
        assert_eq!(exact_shadow(st, 0.2, toward, level0, minmax), 0.0);
        assert_eq!(exact_shadow(st, 0.2, away, level0, minmax), 1.0);
        // High light: over the ridge.
        assert_eq!(exact_shadow(st, 0.2, Vec3::new(1.0, 0.0, 10.0), level0, minmax), 1.0);
    }
}
