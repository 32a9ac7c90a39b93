//! Roughness maps as engines read them: the channel layouts a file keeps its roughness in, and
//! a height field's roughness levels laid out in one. What this module does not do: the formula
//! that makes roughness from a mip texel's length (`bumpmap_math::roughness`).

use bumpmap_math::normalmap::NormalMapError;
use bumpmap_math::{HeightField, MipChain, MipMode, NormalMapOptions};

/// The channels a roughness map holds its perceptual roughness in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RoughnessLayout {
    /// Roughness in R, G and B; A 1.
    #[default]
    Gray,
    /// 1 − roughness (gloss, smoothness) in R, G and B; A 1.
    Gloss,
    /// glTF metallicRoughness / Unreal ORM: R 1 (no occlusion), G roughness, B metallic 0, A 1.
    Gltf,
    /// Unity metallic-smoothness: R metallic 0, G and B 0, A smoothness (1 − roughness).
    Unity,
}

bumpmap_math::named!(RoughnessLayout {
    Gray => "gray": "Roughness in R, G and B; A 1",
    Gloss => "gloss": "1 − roughness (gloss, smoothness) in R, G and B; A 1",
    Gltf => "gltf": "glTF metallicRoughness / Unreal ORM: R 1 (no occlusion; where ambient occlusion is written beside it, the occlusion), G roughness, B metallic 0, A 1",
    Unity => "unity": "Unity metallic-smoothness: R metallic 0, G and B 0, A smoothness (1 − roughness)",
});

impl RoughnessLayout {
    /// The RGBA8 texel for perceptual roughness `r` in [0, 1].
    ///
    /// ```
    /// use bumpmap::options::RoughnessLayout;
    /// assert_eq!(RoughnessLayout::Gltf.texel(1.0), [255, 255, 0, 255]);
    /// assert_eq!(RoughnessLayout::Unity.texel(1.0), [0, 0, 0, 0]);
    /// ```
    pub fn texel(self, r: f32) -> [u8; 4] {
        let byte = bumpmap_math::roughness::unorm8;
        let (rough, gloss) = (byte(r), byte(1.0 - r));
        match self {
            RoughnessLayout::Gray => [rough, rough, rough, 255],
            RoughnessLayout::Gloss => [gloss, gloss, gloss, 255],
            RoughnessLayout::Gltf => [255, rough, 0, 255],
            RoughnessLayout::Unity => [0, 0, 0, gloss],
        }
    }

    /// The perceptual roughness in [0, 1] a texel of this layout holds ([`Self::texel`]'s
    /// inverse on its byte).
    pub fn read(self, texel: [u8; 4]) -> f32 {
        let unit = |b: u8| b as f32 / 255.0;
        match self {
            RoughnessLayout::Gray => unit(texel[0]),
            RoughnessLayout::Gloss => 1.0 - unit(texel[0]),
            RoughnessLayout::Gltf => unit(texel[1]),
            RoughnessLayout::Unity => 1.0 - unit(texel[3]),
        }
    }
}

/// A roughness map's levels for a surface of perceptual roughness `perceptual` under the bumps
/// of `field`: the lengths of the averaged normals of a 16-bit chain with the length in alpha
/// (whatever the caller's normal map keeps), made into roughness by
/// [`filament_roughness`](bumpmap_math::roughness::filament_roughness) and laid out in RGBA8 as
/// `layout` says. What `normalmap --roughness-out` writes and `compare`'s specular study reads.
pub fn roughness_map(
    field: &HeightField,
    options: &NormalMapOptions,
    perceptual: f32,
    layout: RoughnessLayout,
) -> Result<MipChain, NormalMapError> {
    let lengths: MipChain<[u16; 4]> = MipChain::from_height(field, options, MipMode::LengthInAlpha)?;
    let levels = bumpmap_math::roughness::roughness_levels(&lengths.levels, perceptual)
        .into_iter()
        .map(|level| bumpmap_math::Image {
            width: level.width,
            height: level.height,
            texels: level.texels.into_iter().map(|r| layout.texel(r)).collect(),
        })
        .collect();
    Ok(MipChain { levels, encoding: bumpmap_math::Encoding::Unorm })
}

#[cfg(test)]
mod tests {
    use super::RoughnessLayout;

    #[test]
    fn every_layout_reads_back_what_it_writes() {
        for layout in [RoughnessLayout::Gray, RoughnessLayout::Gloss, RoughnessLayout::Gltf, RoughnessLayout::Unity] {
            for byte in 0..=255u8 {
                let r = byte as f32 / 255.0;
                // One byte of rounding either way: the texel stores the value at 8 bits.
                let back = layout.read(layout.texel(r));
                assert!((back - r).abs() <= 0.5 / 255.0 + 1e-6, "{layout:?}: {r} came back {back}");
            }
        }
    }
}
