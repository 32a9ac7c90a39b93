//! The lane copy of `bumpmap_core::shading::shade` (`lighting_lanes`), tested equal to it
//! lane by lane; and the whole-exponent power it uses.

use bumpmap_core::lane_math::{clamp_lo, max_lo, min_hi};
use bumpmap_core::shading::{LeanMoments, LitTerms, SpecularFilter, filtered_specular, shininess_is_whole};
use bumpmap_core::technique::{SelfShadow, SpecularShadow};
use glam::Vec3;

use super::Scratch;
use crate::combiners::Lanes;

/// `acc ← x^k` for a whole k ≥ 0 by binary powering, lanes `0..n` (the order of compiler-rt's
/// `__powisf2`, so the result is `powi`'s); `x` is used up.
fn powi_lanes(x: &mut Lanes, k: u32, n: usize, acc: &mut Lanes) {
    acc[..n].fill(1.0);
    let mut e = k;
    loop {
        if e & 1 == 1 {
            for j in 0..n {
                acc[j] *= x[j];
            }
        }
        e >>= 1;
        if e == 0 {
            break;
        }
        for j in 0..n {
            x[j] *= x[j];
        }
    }
}

/// The lane copy of `bumpmap_core::shading::shade` over lanes `0..n` (a multiple of 8): reads
/// `normal`, `decal`, `gloss`, `l`, `h`, `light`, the filter's `moments` or `roughness` and, in
/// object space, `l_n` and `h_n` (in tangent space L_z and H_z); uses the other fields of `sc`
/// as scratch.
pub(super) fn lighting_lanes(terms: &LitTerms, sc: &mut Scratch, object_space: bool, n: usize, out: &mut [Lanes; 4]) {
    let Scratch {
        normal,
        decal,
        gloss,
        moments,
        roughness,
        l,
        h,
        l_n,
        h_n,
        light,
        occlusion,
        s_self,
        n_dot_l,
        h_dot_n,
        gate,
        acc,
        ..
    } = sc;
    let (l_n, h_n) = if object_space { (&*l_n, &*h_n) } else { (&l[2], &h[2]) };
    match terms.self_shadow {
        SelfShadow::Ramp => (0..n).for_each(|j| s_self[j] = clamp_lo(8.0 * l_n[j], 0.0, 1.0)),
        SelfShadow::Step => (0..n).for_each(|j| s_self[j] = (l_n[j] > 0.0) as u8 as f32),
        SelfShadow::Off => s_self.fill(1.0),
    }
    // Eq. 14–15: the filtered normal's direction, expanded as the combiners do; the dot
    // products clamp as the combiners' outputs do.
    for j in 0..n {
        let nv = [normal[0][j] * 2.0 - 1.0, normal[1][j] * 2.0 - 1.0, normal[2][j] * 2.0 - 1.0];
        n_dot_l[j] = clamp_lo(l[0][j] * nv[0] + l[1][j] * nv[1] + l[2][j] * nv[2], -1.0, 1.0);
        h_dot_n[j] = clamp_lo(h[0][j] * nv[0] + h[1][j] * nv[1] + h[2][j] * nv[2], 0.0, 1.0);
    }
    match terms.specular_shadow {
        SpecularShadow::Kilgard => (0..n).for_each(|j| gate[j] = s_self[j] * (h_n[j] >= 0.0) as u8 as f32),
        SpecularShadow::CgTutorial => (0..n).for_each(|j| gate[j] = (n_dot_l[j] > 0.0 && l_n[j] > 0.0) as u8 as f32),
        SpecularShadow::Off => gate.fill(1.0),
    }
    let power: &Lanes = match terms.specular_filter {
        SpecularFilter::None if shininess_is_whole(terms.shininess) => {
            powi_lanes(h_dot_n, terms.shininess as u32, n, acc);
            acc
        }
        SpecularFilter::None => {
            h_dot_n[..n].iter_mut().for_each(|x| *x = x.powf(terms.shininess));
            h_dot_n
        }
        // A per-fragment exponent from the filtered normal's length or the filtered roughness:
        // the scalar model per lane.
        filter @ (SpecularFilter::Toksvig | SpecularFilter::RoughnessMap) => {
            for j in 0..n {
                h_dot_n[j] = filtered_specular(
                    h_dot_n[j],
                    terms.shininess,
                    filter,
                    normal[3][j],
                    roughness[0][j],
                    Vec3::Z,
                    LeanMoments::FLAT,
                );
            }
            h_dot_n
        }
        // LEAN's or CLEAN's lobe from the filtered moments and H: the scalar model per lane.
        filter @ (SpecularFilter::Lean | SpecularFilter::Clean) => {
            for j in 0..n {
                let m = LeanMoments::from_array(std::array::from_fn(|c| moments[c][j]));
                let h = Vec3::new(h[0][j], h[1][j], h[2][j]);
                h_dot_n[j] = filtered_specular(h_dot_n[j], terms.shininess, filter, 1.0, 1.0, h, m);
            }
            h_dot_n
        }
    };
    // Eq. 11 with the filtered (shortened) normal, Eq. 16 with the renormalized one.
    let (ka, kd, ks) = (terms.ambient, terms.diffuse, terms.specular);
    for c in 0..3 {
        for j in 0..n {
            let lit = kd[c] * (light[j] * s_self[j] * max_lo(n_dot_l[j], 0.0) * normal[3][j]);
            let diffuse = min_hi(ka[c] * occlusion[j] + lit, 1.0);
            let specular = ks[c] * (light[j] * gate[j] * gloss[0][j] * power[j]);
            out[c][j] = decal[c][j] * diffuse + specular;
        }
    }
    out[3][..n].fill(1.0);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::combiners::LANES;
    use bumpmap_core::shading::{Fragment, shade};
    use glam::Vec4;
    use proptest::prelude::*;

    fn modes() -> impl Strategy<Value = (SelfShadow, SpecularShadow, f32, SpecularFilter)> {
        (
            prop_oneof![Just(SelfShadow::Ramp), Just(SelfShadow::Step), Just(SelfShadow::Off)],
            prop_oneof![Just(SpecularShadow::Kilgard), Just(SpecularShadow::CgTutorial), Just(SpecularShadow::Off)],
            prop_oneof![Just(8.0f32), Just(1.0), Just(13.0), Just(64.0), Just(7.5), Just(100.0)],
            prop_oneof![
                Just(SpecularFilter::None),
                Just(SpecularFilter::Toksvig),
                Just(SpecularFilter::RoughnessMap),
                Just(SpecularFilter::Lean),
                Just(SpecularFilter::Clean)
            ],
        )
    }

    proptest! {
        /// The lane loops give `shade`'s result bit for bit (the same operations in the same
        /// order; neither side fuses multiply-adds).
        #[test]
        fn lighting_lanes_is_shade(
            (self_shadow, specular_shadow, shininess, specular_filter) in modes(),
            object_space in any::<bool>(),
            seed in any::<u64>(),
            k in (0.0f32..1.0, 0.0f32..1.0, 0.0f32..2.0),
        ) {
            let terms = LitTerms {
                ambient: Vec3::new(k.0, k.0 * 0.5, 0.1),
                diffuse: Vec3::new(k.1, 0.8, k.1 * 0.3),
                specular: Vec3::new(k.2, 1.0, 0.5),
                shininess,
                self_shadow,
                specular_shadow,
                specular_filter,
            };
            let mut rng = seed;
            let mut next = move || {
                rng = rng.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
                ((rng >> 40) as f32) / (1u64 << 24) as f32
            };
            let mut sc = Scratch::zeroed();
            let n = 64;
            for j in 0..n {
                for c in 0..4 {
                    sc.normal[c][j] = next();
                    sc.decal[c][j] = next();
                }
                sc.gloss[0][j] = next();
                sc.roughness[0][j] = next();
                // Slopes in [−2, 2] and second moments at least their squares (a spread).
                let b = [next() * 4.0 - 2.0, next() * 4.0 - 2.0];
                let spread = [next(), next() * 0.2 - 0.1, next()];
                let m = [b[0] * b[0] + spread[0], b[0] * b[1] + spread[1], b[1] * b[1] + spread[2]];
                let jacobian = 1.0 + next() * 10.0;
                for (c, v) in [b[0], b[1], m[0], m[2], m[1], jacobian].into_iter().enumerate() {
                    sc.moments[c][j] = v;
                }
                let l = Vec3::new(next() * 2.0 - 1.0, next() * 2.0 - 1.0, next() * 2.0 - 1.0).normalize_or(Vec3::Z);
                let h = Vec3::new(next() * 2.0 - 1.0, next() * 2.0 - 1.0, next() * 2.0 - 1.0).normalize_or(Vec3::Z);
                for c in 0..3 {
                    sc.l[c][j] = l[c];
                    sc.h[c][j] = h[c];
                }
                sc.l_n[j] = next() * 2.0 - 1.0;
                sc.h_n[j] = next() * 2.0 - 1.0;
                sc.light[j] = next();
                sc.occlusion[j] = next();
            }
            let input = (*sc).clone();
            let mut out = [[0.0; LANES]; 4];
            lighting_lanes(&terms, &mut sc, object_space, n, &mut out);
            for j in 0..n {
                let v3 = |a: &[Lanes; 3]| Vec3::new(a[0][j], a[1][j], a[2][j]);
                let (l, h) = (v3(&input.l), v3(&input.h));
                let f = Fragment {
                    normal: Vec4::new(input.normal[0][j], input.normal[1][j], input.normal[2][j], input.normal[3][j]),
                    decal: Vec3::new(input.decal[0][j], input.decal[1][j], input.decal[2][j]),
                    gloss: input.gloss[0][j],
                    l,
                    h,
                    l_n: if object_space { input.l_n[j] } else { l.z },
                    h_n: if object_space { input.h_n[j] } else { h.z },
                    light: input.light[j],
                    moments: LeanMoments::from_array(std::array::from_fn(|c| input.moments[c][j])),
                    roughness: input.roughness[0][j],
                    occlusion: input.occlusion[j],
                };
                let expected = shade(&terms, &f);
                for c in 0..3 {
                    prop_assert_eq!(out[c][j].to_bits(), expected[c].to_bits(), "lane {} channel {}: {} vs {}", j, c, out[c][j], expected[c]);
                }
                prop_assert_eq!(out[3][j], 1.0);
            }
        }
    }
}
