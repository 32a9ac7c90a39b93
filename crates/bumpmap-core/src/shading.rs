//! The lighting model, once: Kilgard Eq. 11 (diffuse with the self-shadowing term of Eq. 12
//! and the mip chain's length factor, Eq. 14–15), Eq. 16 (specular with the paper's or the Cg
//! Tutorial's gating), plus the single pass's extras (light colour, gloss, attenuation and
//! spotlights, applied as one scalar factor).
//!
//! Every fast copy of this model — the CPU backend's lane loops, the GPU backend's WGSL — is
//! tested against [`shade`]. What this module does not do: texture sampling, interpolation
//! and per-fragment renormalization of L and H (the backends' work; their results are the
//! [`Fragment`] fields), and the three-pass technique's 8-bit arithmetic (that is the register
//! combiners' setup data, `setups`).

use std::sync::Arc;

use bumpmap_math::Rgba8Mips;
pub use bumpmap_math::lean::LeanMoments;
use glam::{Vec3, Vec4};

use crate::lane_math::{clamp_lo, max_lo, min_hi};
use crate::scene::Spot;

/// The geometric self-shadowing factor of Eq. 11.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SelfShadow {
    /// Eq. 12: `clamp(8·L_z, 0, 1)`.
    #[default]
    Ramp,
    /// 1 where `L_z > 0`, else 0.
    Step,
    /// Always 1 (Figure 14, left).
    Off,
}

/// Which geometric self-shadowing the specular term gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SpecularShadow {
    /// The paper's: times s_self, and zero where `H_z < 0` (Appendix H's mux).
    #[default]
    Kilgard,
    /// Cg Tutorial §8.5: zero unless `N'·L > 0` and `L_z > 0`.
    CgTutorial,
    /// None.
    Off,
}

/// How the specular term answers the filtered normal's length |Nₐ| (the mip chain's alpha):
/// Kilgard §2.5.3 leaves a distant bumpy surface's highlight as tight as a flat one's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SpecularFilter {
    /// The exponent as given.
    #[default]
    None,
    /// Toksvig 2005 ([`toksvig`]): a shorter filtered normal widens and dims the lobe.
    Toksvig,
    /// A roughness map (the one `bumpmap normalmap --roughness-out` exports, or one made the
    /// same way from the normal map) read as an engine's Blinn–Phong shader reads roughness
    /// ([`roughness_exponent`]); it reads [`Fragment::roughness`], not |Nₐ|.
    RoughnessMap,
    /// LEAN mapping (Olano & Baker 2010): the lobe a Gaussian in slope space whose covariance
    /// is the filtered slopes' spread plus the material's own width
    /// ([`bumpmap_math::lean::LeanMoments::specular`]); it reads [`Fragment::moments`], not
    /// |Nₐ|, and needs a tangent-space map of unit normals.
    Lean,
    /// CLEAN mapping (Olano & Baker 2010, §5): LEAN with the slopes' spread made isotropic
    /// ([`LeanMoments::isotropic`]), what a texture of one channel fewer holds.
    Clean,
}

bumpmap_math::named!(SelfShadow {
    Ramp => "ramp": "Eq. 12: clamp(8·L_z, 0, 1)",
    Step => "step": "1 where L_z > 0",
    Off => "off": "none (Figure 14, left)",
});

bumpmap_math::named!(SpecularShadow {
    Kilgard => "kilgard": "times s_self, zero where H_z < 0 (the paper's mux)",
    CgTutorial => "cg": "zero unless N'·L > 0 and L_z > 0 (Cg Tutorial §8.5)",
    Off => "off": "none",
});

bumpmap_math::named!(SpecularFilter {
    None => "none": "the exponent as given",
    Toksvig => "toksvig": "Toksvig 2005: exponent s·|N|/(|N| + s(1 − |N|)), with its energy factor",
    RoughnessMap => "roughness-map": "a roughness map sampled as an engine samples it, turned into a Blinn–Phong exponent: the one `bumpmap normalmap` exports as its roughness map (Filament's prefilter of each level's |N|), made from the normal map, or a roughness map file",
    Lean => "lean": "LEAN mapping (Olano & Baker 2010): the slopes' first and second moments, filtered, make an anisotropic Gaussian lobe (tangent-space maps of unit normals)",
    Clean => "clean": "CLEAN mapping (Olano & Baker 2010, §5): LEAN with the spread shared out equally in x and y, one moment texture instead of two: a round lobe",
});

/// Toksvig's filtered exponent and energy factor for a filtered normal of length `length` and
/// Blinn-Phong exponent `shininess` (SPECS.md §9): σ² = (1 − |Nₐ|)/|Nₐ|, f = 1/(1 + s·σ²) =
/// |Nₐ|/(|Nₐ| + s(1 − |Nₐ|)), exponent f·s, energy (1 + f·s)/(1 + s). At |Nₐ| = 1 (mip 0, or
/// renormalized mips) it is exactly `(shininess, 1)`.
///
/// ```
/// use bumpmap_core::shading::toksvig;
/// assert_eq!(toksvig(1.0, 8.0), (8.0, 1.0));
/// let (s, e) = toksvig(0.9, 32.0);
/// assert!(s < 32.0 && e < 1.0);
/// ```
#[inline(always)]
pub fn toksvig(length: f32, shininess: f32) -> (f32, f32) {
    let len = clamp_lo(length, 0.0, 1.0);
    let f = len / (len + shininess * (1.0 - len));
    let s = f * shininess;
    (s, (1.0 + s) / (1.0 + shininess))
}

/// The smallest perceptual roughness a roughness map is read as (Filament's
/// `MIN_PERCEPTUAL_ROUGHNESS` for fp32): a texel of 0 would ask for an infinite exponent.
pub const MIN_PERCEPTUAL_ROUGHNESS: f32 = 0.045;

/// The perceptual roughness (glTF's, GGX α^½) of Blinn–Phong exponent `shininess`, by the usual
/// correspondence α² = 2/(s + 2): the surface's own roughness a roughness map starts from.
///
/// ```
/// use bumpmap_core::shading::{perceptual_roughness, roughness_exponent};
/// let r = perceptual_roughness(32.0);
/// assert!((r - (2.0f32 / 34.0).powf(0.25)).abs() < 1e-6);
/// assert!((roughness_exponent(r, 32.0).0 - 32.0).abs() < 1e-3, "and back");
/// ```
pub fn perceptual_roughness(shininess: f32) -> f32 {
    (2.0 / (shininess + 2.0)).sqrt().sqrt()
}

/// The exponent and energy factor a Blinn–Phong shader reads from a roughness map's texel
/// `roughness` (perceptual, as `normalmap --roughness-out` writes it): α² = roughness⁴,
/// exponent s′ = 2/α² − 2, energy (s′ + 2)/(s + 2) — the ratio of the normalized Blinn–Phong
/// lobes, so a texel of the material's own roughness (`shininess` s) draws the model's lobe
/// unchanged and a rougher one a wider, dimmer lobe of the same integral. Roughness is clamped
/// to [[`MIN_PERCEPTUAL_ROUGHNESS`], 1].
///
/// ```
/// use bumpmap_core::shading::{perceptual_roughness, roughness_exponent};
/// let (s, e) = roughness_exponent(perceptual_roughness(32.0), 32.0);
/// assert!((s - 32.0).abs() < 1e-3 && (e - 1.0).abs() < 1e-4);
/// let (s, e) = roughness_exponent(0.6, 32.0);
/// assert!(s < 32.0 && e < 1.0, "rougher: wider and dimmer");
/// assert_eq!(roughness_exponent(1.0, 32.0).0, 0.0, "as rough as it gets: a constant lobe");
/// ```
#[inline(always)]
pub fn roughness_exponent(roughness: f32, shininess: f32) -> (f32, f32) {
    let r = clamp_lo(roughness, MIN_PERCEPTUAL_ROUGHNESS, 1.0);
    let alpha2 = (r * r) * (r * r);
    let s = clamp_lo(2.0 / alpha2 - 2.0, 0.0, f32::MAX);
    (s, (s + 2.0) / (shininess + 2.0))
}

/// The roughness map the renderers sample for [`SpecularFilter::RoughnessMap`] when none is
/// given: `normalmap --roughness-out`'s gray map of `normal_map`'s levels (their lengths through
/// Filament's prefilter, [`bumpmap_math::roughness::roughness_mips`]) for a surface of exponent
/// `shininess` ([`perceptual_roughness`]).
pub fn roughness_texture(normal_map: &Rgba8Mips, shininess: f32) -> Rgba8Mips {
    bumpmap_math::roughness::roughness_mips(normal_map, perceptual_roughness(shininess))
}

/// The backends' store of [`roughness_texture`]s, each made once per normal map (`Arc`) and
/// shininess, so a frame after the first makes none and the texture units' caches, keyed by
/// `Arc`, find their copies.
#[derive(Debug, Default)]
pub struct RoughnessTextures {
    /// (normal map, shininess's bits, the roughness texture made of them).
    made: Vec<(Arc<Rgba8Mips>, u32, Arc<Rgba8Mips>)>,
}

impl RoughnessTextures {
    /// Drops what was made of normal maps nothing but this store holds any more.
    pub fn evict_unused(&mut self) {
        self.made.retain(|(m, ..)| Arc::strong_count(m) > 1);
    }

    /// The roughness texture of `normal_map` for exponent `shininess`.
    pub fn get(&mut self, normal_map: &Arc<Rgba8Mips>, shininess: f32) -> Arc<Rgba8Mips> {
        let bits = shininess.to_bits();
        if let Some((_, _, r)) = self.made.iter().find(|(m, s, _)| Arc::ptr_eq(m, normal_map) && *s == bits) {
            return r.clone();
        }
        let r = Arc::new(roughness_texture(normal_map, shininess));
        self.made.push((normal_map.clone(), bits, r.clone()));
        r
    }
}

/// The specular lobe `(H·N')^s` under `filter`: for Toksvig's, at the filtered normal's length
/// `length`; for the roughness map's, at the sampled perceptual `roughness`; for LEAN, the lobe
/// of the filtered `moments` at the half-angle vector `h` (tangent space).
#[inline(always)]
pub fn filtered_specular(
    h_dot_n: f32,
    shininess: f32,
    filter: SpecularFilter,
    length: f32,
    roughness: f32,
    h: Vec3,
    moments: LeanMoments,
) -> f32 {
    match filter {
        SpecularFilter::None => specular_power(h_dot_n, shininess),
        SpecularFilter::Toksvig => {
            let (s, energy) = toksvig(length, shininess);
            specular_power(h_dot_n, s) * energy
        }
        SpecularFilter::RoughnessMap => {
            let (s, energy) = roughness_exponent(roughness, shininess);
            specular_power(h_dot_n, s) * energy
        }
        SpecularFilter::Lean => moments.specular(h, shininess),
        SpecularFilter::Clean => moments.isotropic().specular(h, shininess),
    }
}

/// The coefficients and switches of one lit pass: the material's, times the light's colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LitTerms {
    /// I_ambient (zero on every pass but the first light's).
    pub ambient: Vec3,
    /// k_diffuse · light colour.
    pub diffuse: Vec3,
    /// k_specular · light colour.
    pub specular: Vec3,
    /// The specular exponent, > 0.
    pub shininess: f32,
    /// The geometric self-shadowing factor.
    pub self_shadow: SelfShadow,
    /// How the specular term is gated.
    pub specular_shadow: SpecularShadow,
    /// How the specular exponent answers the filtered normal's length.
    pub specular_filter: SpecularFilter,
}

impl LitTerms {
    /// The terms of `material` lit by `light`: its colour times the material's diffuse and
    /// specular coefficients, and the ambient term only on the first light's (`first`).
    pub fn of(
        material: &crate::scene::Material,
        light: &crate::scene::SceneLight,
        first: bool,
        self_shadow: SelfShadow,
        specular_shadow: SpecularShadow,
        specular_filter: SpecularFilter,
    ) -> Self {
        Self {
            ambient: if first { material.ambient } else { Vec3::ZERO },
            diffuse: material.diffuse * light.color,
            specular: material.specular * light.color,
            shininess: material.shininess,
            self_shadow,
            specular_shadow,
            specular_filter,
        }
    }
}

/// What one fragment brings to the model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fragment {
    /// The filtered normal-map texel in [0, 1]: RGB the range-compressed N', A = |N'|.
    pub normal: Vec4,
    /// The decal's RGB in [0, 1] (white without a decal).
    pub decal: Vec3,
    /// The gloss factor in [0, 1] (1 without gloss).
    pub gloss: f32,
    /// The unit light vector in the lighting space, renormalized per fragment.
    pub l: Vec3,
    /// The unit half-angle vector, likewise.
    pub h: Vec3,
    /// L·N with the unperturbed normal (L_z in tangent space).
    pub l_n: f32,
    /// H·N with the unperturbed normal (H_z in tangent space).
    pub h_n: f32,
    /// Attenuation × spotlight, in [0, 1].
    pub light: f32,
    /// The filtered LEAN moments of the slopes (read only by [`SpecularFilter::Lean`] and
    /// [`SpecularFilter::Clean`], which reads only their Mxx + Myy of the second moments;
    /// [`LeanMoments::FLAT`] otherwise).
    pub moments: LeanMoments,
    /// The filtered roughness map's perceptual roughness in [0, 1] (read only by
    /// [`SpecularFilter::RoughnessMap`]).
    pub roughness: f32,
    /// Ambient occlusion in [0, 1], multiplying the ambient term (1: none).
    pub occlusion: f32,
}

/// The self-shadowing factor s_self of Eq. 11 for L·N = `l_n`.
#[inline(always)]
pub fn self_shadow(mode: SelfShadow, l_n: f32) -> f32 {
    match mode {
        // Eq. 12 (`bumpmap_math::lighting::s_self`, NaN taking 0 as the lane loops do).
        SelfShadow::Ramp => clamp_lo(8.0 * l_n, 0.0, 1.0),
        SelfShadow::Step => (l_n > 0.0) as u8 as f32,
        SelfShadow::Off => 1.0,
    }
}

/// The specular gate: which geometric self-shadowing the specular term gets, given s_self,
/// N'·L and the unperturbed L·N and H·N.
#[inline(always)]
pub fn specular_gate(mode: SpecularShadow, s_self: f32, n_dot_l: f32, l_n: f32, h_n: f32) -> f32 {
    match mode {
        // Appendix H's mux: zero where H_z < 0, and times s_self (pass 3 reads it from alpha).
        SpecularShadow::Kilgard => s_self * (h_n >= 0.0) as u8 as f32,
        // Cg Tutorial §8.5: only where the bumped and the geometric normal face the light.
        SpecularShadow::CgTutorial => (n_dot_l > 0.0 && l_n > 0.0) as u8 as f32,
        SpecularShadow::Off => 1.0,
    }
}

/// Whether `shininess` is raised by repeated multiplication (`powi`) rather than `powf`:
/// whole exponents up to 64, the paper's 8 among them.
#[inline(always)]
pub fn shininess_is_whole(shininess: f32) -> bool {
    shininess == shininess.trunc() && shininess <= 64.0
}

/// `x^shininess`, by [`f32::powi`] for whole exponents up to 64 and [`f32::powf`] otherwise.
#[inline(always)]
pub fn specular_power(x: f32, shininess: f32) -> f32 {
    if shininess_is_whole(shininess) { x.powi(shininess as i32) } else { x.powf(shininess) }
}

/// The range-compressed vector `c` in [0, 1]³ expanded as `2c − 1` (EXPAND_NORMAL).
#[inline(always)]
pub fn expand(c: [f32; 3]) -> [f32; 3] {
    c.map(|v| v * 2.0 - 1.0)
}

/// `a · b`, summed in the order x, y, z (the lane loops' order, so results are the same bits).
#[inline(always)]
pub fn dot3(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The colour of one fragment (alpha is 1): `decal · min(ambient · occlusion + diffuse · light · s_self ·
/// max(0, N'·L) · |N'|, 1) + specular · light · gate · gloss · (H·N')^shininess` (the lobe
/// filtered as [`filtered_specular`] says).
///
/// N'·L and H·N' use the expanded, not renormalized, normal-map vector and are clamped to
/// [−1, 1] and [0, 1] as the combiners' outputs are, so a quantized normal cannot brighten past
/// the three-pass technique's.
pub fn shade(terms: &LitTerms, f: &Fragment) -> Vec3 {
    let n = expand([f.normal.x, f.normal.y, f.normal.z]);
    let n_dot_l = clamp_lo(dot3(f.l.to_array(), n), -1.0, 1.0);
    let h_dot_n = clamp_lo(dot3(f.h.to_array(), n), 0.0, 1.0);
    let s_self = self_shadow(terms.self_shadow, f.l_n);
    let gate = specular_gate(terms.specular_shadow, s_self, n_dot_l, f.l_n, f.h_n);
    let power =
        filtered_specular(h_dot_n, terms.shininess, terms.specular_filter, f.normal.w, f.roughness, f.h, f.moments);
    let (ka, kd, ks, decal) = (terms.ambient.to_array(), terms.diffuse.to_array(), terms.specular.to_array(), f.decal);
    Vec3::from_array(std::array::from_fn(|c| {
        let diffuse = min_hi(ka[c] * f.occlusion + kd[c] * (f.light * s_self * max_lo(n_dot_l, 0.0) * f.normal.w), 1.0);
        let specular = ks[c] * (f.light * gate * f.gloss * power);
        decal[c] * diffuse + specular
    }))
}

/// An offset-map texel (Kilgard §2.2, Eq. 6–7) as the normal-map texel [`shade`] takes: the
/// offset `D = range · (2·rg − 1)` added to the unperturbed normal (0, 0, 1) and renormalized,
/// range-compressed, with A = 1 (an offset map keeps no length: filtering averages the offsets
/// and renormalizing forgets how much they disagreed).
#[inline(always)]
pub fn offset_to_normal(texel: Vec4, range: f32) -> Vec4 {
    let (dx, dy) = ((texel.x * 2.0 - 1.0) * range, (texel.y * 2.0 - 1.0) * range);
    let inv = 1.0 / (dx * dx + dy * dy + 1.0).sqrt();
    Vec4::new(dx * inv * 0.5 + 0.5, dy * inv * 0.5 + 0.5, inv * 0.5 + 0.5, 1.0)
}

/// Peercy Figure 2 per pixel: Blinn's normal (`bumpmap_math::blinn::perturbed_normal`) in the
/// tangent frame from an offset-map texel read as the slopes (`d_u = −scale.x · D_x`,
/// `d_v = −scale.y · D_y`, `D = range · (2·rg − 1)`) and the interpolated surface derivatives
/// `param_frame = (|∂P/∂u|, ∂P/∂v · T, ∂P/∂v · B)`. With `T = ∂P/∂u / |∂P/∂u|` and n̂ = +z,
/// `N' = |P_u × P_v| n̂ + σ·(d_u (n̂ × P_v) − d_v (n̂ × P_u))`, σ the sign of `P_v · B`.
/// Range-compressed, A = 1.
#[inline(always)]
pub fn blinn_from_derivatives(texel: Vec4, range: f32, scale: glam::Vec2, param_frame: Vec3) -> Vec4 {
    let d_u = -scale.x * (texel.x * 2.0 - 1.0) * range;
    let d_v = -scale.y * (texel.y * 2.0 - 1.0) * range;
    let (pu, pvt, pvb) = (param_frame.x, param_frame.y, param_frame.z);
    let sigma = if pvb >= 0.0 { 1.0 } else { -1.0 };
    let n = Vec3::new(sigma * (-d_u * pvb), sigma * (d_u * pvt - d_v * pu), (pu * pvb).abs()).normalize_or(Vec3::Z);
    Vec4::new(n.x * 0.5 + 0.5, n.y * 0.5 + 0.5, n.z * 0.5 + 0.5, 1.0)
}

/// A spotlight's cone factor: GL's `max(0, cos)^exponent` inside the cutoff, 0 outside, where
/// `to_light` is the (unnormalized) vector from the fragment to the light and `axis` the spot
/// direction, both in the lighting space. The pattern, if any, multiplies this.
pub fn spot_cone(spot: &Spot, to_light: Vec3, axis: Vec3) -> f32 {
    let cos = -(to_light.normalize_or(Vec3::Z)).dot(axis.normalize_or(Vec3::Z));
    if cos >= spot.cutoff_degrees.to_radians().cos() { cos.max(0.0).powf(spot.exponent) } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn terms() -> LitTerms {
        LitTerms {
            ambient: Vec3::splat(0.2),
            diffuse: Vec3::splat(0.8),
            specular: Vec3::ONE,
            shininess: 8.0,
            self_shadow: SelfShadow::Ramp,
            specular_shadow: SpecularShadow::Kilgard,
            specular_filter: SpecularFilter::None,
        }
    }

    #[test]
    fn toksvig_widens_and_dims_the_lobe_as_the_normal_shortens_and_is_exact_at_length_1() {
        for s in [1.0f32, 8.0, 32.0, 100.0] {
            assert_eq!(toksvig(1.0, s), (s, 1.0));
            let mut last = (s, 1.0);
            for k in 1..=100 {
                let len = 1.0 - k as f32 * 0.0099;
                let (e, energy) = toksvig(len, s);
                assert!(e < last.0 && energy < last.1, "length {len}, s {s}: {e}, {energy} after {last:?}");
                assert!(e > 0.0 && energy > 1.0 / (1.0 + s) - 1e-6);
                // σ² = (1 − |Nₐ|)/|Nₐ| and exponent s/(1 + s·σ²): the same number another way.
                let sigma2 = (1.0 - len) / len;
                assert!((e - s / (1.0 + s * sigma2)).abs() <= 1e-4 * s, "{e} vs {}", s / (1.0 + s * sigma2));
                last = (e, energy);
            }
        }
        // A shortened normal spreads the highlight: dimmer at its peak, brighter off it.
        let short = Vec4::new(0.5, 0.5, 1.0, 0.9); // the mean direction (unit) and its length
        let f = |h: Vec3| Fragment { normal: short, h, ..flat(Vec3::Z, h) };
        let toksvig_terms = LitTerms { specular_filter: SpecularFilter::Toksvig, shininess: 64.0, ..terms() };
        let plain = LitTerms { shininess: 64.0, ..terms() };
        let peak = Vec3::new(0.0, 0.0, 1.0);
        let off = Vec3::new(0.35, 0.0, 1.0).normalize();
        assert!(shade(&toksvig_terms, &f(peak)).x < shade(&plain, &f(peak)).x);
        assert!(shade(&toksvig_terms, &f(off)).x > shade(&plain, &f(off)).x);
    }

    fn flat(l: Vec3, h: Vec3) -> Fragment {
        Fragment {
            normal: Vec4::new(0.5, 0.5, 1.0, 1.0),
            decal: Vec3::ONE,
            gloss: 1.0,
            l,
            h,
            l_n: l.z,
            h_n: h.z,
            light: 1.0,
            moments: LeanMoments::FLAT,
            roughness: perceptual_roughness(8.0),
            occlusion: 1.0,
        }
    }

    #[test]
    fn a_roughness_texel_of_the_materials_own_roughness_draws_the_plain_lobe() {
        let rough = LitTerms { specular_filter: SpecularFilter::RoughnessMap, ..terms() };
        for h in [Vec3::Z, Vec3::new(0.3, 0.1, 1.0).normalize(), Vec3::new(0.6, -0.2, 0.8).normalize()] {
            let (a, b) = (shade(&rough, &flat(Vec3::Z, h)), shade(&terms(), &flat(Vec3::Z, h)));
            assert!((a - b).abs().max_element() < 1e-4, "{a} vs {b}");
        }
        // A rougher texel: dimmer at the peak, brighter off it; the |N| the texel also holds is
        // not what this filter reads.
        let f = |h: Vec3, r: f32| Fragment { roughness: r, normal: Vec4::new(0.5, 0.5, 1.0, 0.5), ..flat(Vec3::Z, h) };
        let off = Vec3::new(1.0, 0.0, 1.0).normalize();
        let own = perceptual_roughness(8.0);
        assert!(shade(&rough, &f(Vec3::Z, 0.8)).x < shade(&rough, &f(Vec3::Z, own)).x);
        assert!(shade(&rough, &f(off, 0.8)).x > shade(&rough, &f(off, own)).x);
        let specular_only = LitTerms { ambient: Vec3::ZERO, diffuse: Vec3::ZERO, ..rough };
        assert_eq!(shade(&specular_only, &f(off, own)), shade(&specular_only, &flat(Vec3::Z, off)));
    }

    #[test]
    fn the_made_roughness_texture_holds_the_surfaces_own_roughness_where_the_normals_agree() {
        use bumpmap_math::{Rgba8Image, Rgba8Mips};
        let flat_map = Rgba8Mips::with_box_mipmaps(Rgba8Image::new(4, 4, vec![[128, 128, 255, 255]; 16]));
        let rough = roughness_texture(&flat_map, 32.0);
        assert_eq!(rough.levels().len(), flat_map.levels().len());
        let own = bumpmap_math::roughness::unorm8(perceptual_roughness(32.0));
        assert!(rough.levels().iter().all(|l| l.texels.iter().all(|&t| t == [own, own, own, 255])));
    }

    #[test]
    fn head_on_light_gives_ambient_plus_diffuse_plus_specular() {
        let c = shade(&terms(), &flat(Vec3::Z, Vec3::Z));
        // min(0.2 + 0.8, 1) + 1 · 1^8 = 2 (clamped later by the framebuffer).
        assert_eq!(c, Vec3::splat(2.0));
    }

    #[test]
    fn eq12_ramp_darkens_grazing_light() {
        let l = Vec3::new(0.995, 0.0, 0.05).normalize();
        let c = shade(&LitTerms { specular: Vec3::ZERO, ..terms() }, &flat(l, Vec3::Z));
        let s = (8.0 * l.z).clamp(0.0, 1.0);
        let expected = 0.2 + 0.8 * s * l.z;
        assert!((c.x - expected).abs() < 1e-6, "{c} vs {expected}");
        assert_eq!(self_shadow(SelfShadow::Ramp, l.z), bumpmap_math::lighting::s_self(l.z));
    }

    #[test]
    fn light_below_the_surface_leaves_ambient_only() {
        let c = shade(&terms(), &flat(-Vec3::Z, -Vec3::Z));
        assert_eq!(c, Vec3::splat(0.2));
    }

    #[test]
    fn offset_texels_rebuild_the_normal_of_eq_7() {
        // No offset: straight up. D = (range, 0) with range 1: 45° toward +x.
        assert_eq!(offset_to_normal(Vec4::new(0.5, 0.5, 0.0, 0.0), 3.0), Vec4::new(0.5, 0.5, 1.0, 1.0));
        let n = offset_to_normal(Vec4::new(1.0, 0.5, 0.0, 0.0), 1.0);
        let h = 0.5f32.sqrt();
        assert!((n - Vec4::new(h * 0.5 + 0.5, 0.5, h * 0.5 + 0.5, 1.0)).length() < 1e-6, "{n}");
    }

    #[test]
    fn per_pixel_blinn_agrees_with_the_math_crates_blinn() {
        // The patch's frame at one point, a slope, and the same normal two ways.
        use bumpmap_math::surface::{BicubicPatch, Surface};
        let p = Surface::Patch(BicubicPatch::stretched()).eval(0.3, 0.6);
        let (t, b, n) = p.frame();
        let (range, scale, texel) = (2.0, glam::Vec2::new(3.0, 5.0), Vec4::new(0.7, 0.35, 0.0, 0.0));
        let got =
            blinn_from_derivatives(texel, range, scale, Vec3::new(p.dp_du.length(), p.dp_dv.dot(t), p.dp_dv.dot(b)));
        let (d_u, d_v) = (-scale.x * 0.4 * range, -scale.y * -0.3 * range);
        let want = bumpmap_math::blinn::perturbed_normal(&p, d_u, d_v);
        let want = Vec3::new(want.dot(t), want.dot(b), want.dot(n)) * 0.5 + Vec3::splat(0.5);
        assert!((got.truncate() - want).length() < 1e-5, "{got} vs {want}");
    }

    #[test]
    fn powi_for_whole_exponents_powf_otherwise() {
        assert_eq!(specular_power(0.5, 8.0), 0.5f32.powi(8));
        assert_eq!(specular_power(0.5, 8.5), 0.5f32.powf(8.5));
        assert_eq!(specular_power(0.5, 100.0), 0.5f32.powf(100.0));
    }
}
