//! Specular roughness from the spread of the normals a mip texel averages: what engines read
//! where this crate's chains keep the length of the averaged normal (Kilgard §5.3).
//!
//! The formula is Filament's roughness prefilter (`tools/roughness-prefilter`): the normals
//! under a texel are taken as a von Mises–Fisher distribution whose mean resultant length is
//! the stored length `r`; its concentration is κ = (3r − r³)/(1 − r²), and its variance, 2/κ,
//! is added to the GGX α² of the surface's own roughness: α′ = √(α² + 2/κ), α = roughness²
//! (perceptual). We use Filament's rather than Unreal's composite-texture formula because it
//! reads the quantity our chains store (the mean length, not a variance rebuilt from it), and
//! is stated for GGX with the perceptual roughness glTF and most engines take; Unreal's
//! (Toksvig's variance folded into a Blinn–Phong power) gives nearly the same roughness for
//! small variances.
//!
//! What this module does not do: pick the texels (any chain with the length in alpha will do),
//! lay the roughness out in an engine's channels (a file convention: the command line's; the
//! one layout here, [`roughness_mips`]'s gray, is the form the renderers sample), or turn
//! roughness into a shader's exponent (`bumpmap_core::shading::roughness_exponent`).

use crate::encoding::{Encoding, Texel};
use crate::image::{Image, Rgba8Image, Rgba8Mips};

/// The roughness a surface of perceptual roughness `perceptual` (in [0, 1]) takes on where the
/// normals it averages have mean length `length` (in [0, 1]): Filament's prefilter, clamped to
/// [0, 1].
///
/// ```
/// use bumpmap_math::roughness::filament_roughness;
///
/// assert_eq!(filament_roughness(0.4, 1.0), 0.4, "one normal: no spread to add");
/// let r = filament_roughness(0.4, 0.9);
/// assert!(r > 0.4 && r < 1.0, "spread normals look rougher: {r}");
/// assert_eq!(filament_roughness(0.4, 0.0), 1.0, "normals cancelling out: as rough as it gets");
/// ```
pub fn filament_roughness(perceptual: f32, length: f32) -> f32 {
    let alpha = perceptual.clamp(0.0, 1.0).powi(2);
    let r = length.clamp(0.0, 1.0);
    let variance = if r >= 1.0 {
        0.0
    } else {
        // κ = (3r − r³)/(1 − r²); 2/κ, written so that r = 0 gives infinity rather than NaN.
        2.0 * (1.0 - r * r) / (3.0 * r - r * r * r)
    };
    (alpha * alpha + variance).sqrt().sqrt().min(1.0)
}

/// The perceptual roughness of every texel of every level of a chain (`levels`, whose alpha is
/// the length of the averaged normal), for a surface of roughness `perceptual`.
pub fn roughness_levels<T: Texel>(levels: &[Image<T>], perceptual: f32) -> Vec<Image<f32>> {
    levels
        .iter()
        .map(|level| Image {
            width: level.width,
            height: level.height,
            texels: level.texels.iter().map(|t| filament_roughness(perceptual, t.unpack(Encoding::Unorm)[3])).collect(),
        })
        .collect()
}

/// `v` in [0, 1] as an 8-bit unorm channel (rounded to nearest; outside [0, 1] clamped).
///
/// ```
/// use bumpmap_math::roughness::unorm8;
/// assert_eq!((unorm8(0.0), unorm8(0.5), unorm8(1.0), unorm8(2.0)), (0, 128, 255, 255));
/// ```
pub fn unorm8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The roughness map of an 8-bit normal-map chain (alpha the averaged normal's length), every
/// level its own (not box-filtered from level 0: a level's roughness is its own normals'
/// spread), gray: the perceptual roughness in R, G and B, A 255 — what `bumpmap normalmap
/// --roughness-out` writes for the default layout, and what the renderers sample.
///
/// ```
/// use bumpmap_math::{Rgba8Image, Rgba8Mips, roughness::roughness_mips};
/// // A flat level 0 over a level whose normals averaged to length 0.8 (alpha 204).
/// let normal = Rgba8Mips::from_levels(vec![
///     Rgba8Image::new(2, 1, vec![[128, 128, 255, 255]; 2]),
///     Rgba8Image::new(1, 1, vec![[128, 128, 230, 204]]),
/// ]);
/// let rough = roughness_mips(&normal, 0.5);
/// assert_eq!(rough.levels()[0].texels[0], [128, 128, 128, 255], "level 0: the surface's own");
/// assert!(rough.levels()[1].texels[0][0] > 128, "the spread makes level 1 rougher");
/// ```
pub fn roughness_mips(normal_map: &Rgba8Mips, perceptual: f32) -> Rgba8Mips {
    let levels = roughness_levels(normal_map.levels(), perceptual)
        .into_iter()
        .map(|level| {
            let texels = level.texels.iter().map(|&r| [unorm8(r), unorm8(r), unorm8(r), 255]).collect();
            Rgba8Image::new(level.width, level.height, texels)
        })
        .collect();
    Rgba8Mips::from_levels(levels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_prefilter_adds_the_spread_as_variance() {
        // Small spreads: 2/κ ≈ 1 − r, so α′⁴ ≈ α⁴ + (1 − r)… in α² terms.
        for base in [0.1f32, 0.3, 0.6] {
            let mut last = base;
            for r in [0.999f32, 0.99, 0.95, 0.8, 0.5, 0.2] {
                let rough = filament_roughness(base, r);
                assert!(rough >= last, "more spread is rougher: base {base}, r {r}");
                let kappa = (3.0 * r - r.powi(3)) / (1.0 - r * r);
                let want = (base.powi(4) + 2.0 / kappa).sqrt().sqrt().min(1.0);
                assert!((rough - want).abs() < 1e-6, "{rough} vs {want}");
                last = rough;
            }
        }
        assert_eq!(filament_roughness(1.0, 0.5), 1.0);
    }
}
