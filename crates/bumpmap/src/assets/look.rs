//! A glTF material's other textures made into the maps the renderers read: the occlusion with
//! its strength folded in, the emission with its factor, the roughness at the normal map's
//! size (glTF 2.0 §3.9.2–3.9.5).
//!
//! What this module does not do: decode images (that is `bumpmap-io`) or decide which texture
//! coordinates they are read with (every map of a part is read with the part's one set).

use std::sync::Arc;

use bumpmap_io::{MaterialTexture, StoredLevels};
use bumpmap_math::{Rgba8Image, Rgba8Mips};

use super::{srgb_decode, srgb_encode};
use crate::error::Error;

/// Level 0 of `t` as RGBA8 (16-bit texels rounded), refused when it and its mipmaps would not
/// fit in memory.
fn level0(t: &MaterialTexture, what: &'static str) -> Result<Rgba8Image, Error> {
    let level = match &t.texture.levels {
        StoredLevels::Rgba8(levels) => levels[0].clone(),
        StoredLevels::Rgba16(_) => {
            let levels: Vec<Rgba8Image> = (&t.texture.levels).into();
            levels.into_iter().next().expect("a texture has a level 0")
        }
    };
    let texels = level.width as u64 * level.height as u64;
    bumpmap_math::buffer::ensure_available(texels * 4 * 4 / 3, what)
        .map_err(|source| Error::OutOfMemory { what: t.source.display().to_string(), source })?;
    Ok(level)
}

/// What multiplies the ambient term, grey in RGB: `1 + strength · (red − 1)` of an
/// `occlusionTexture` (linear, not sRGB), with box-filtered mipmaps.
pub(super) fn occlusion_map(t: &MaterialTexture) -> Result<Arc<Rgba8Mips>, Error> {
    let mut image = level0(t, "the occlusion map and its mipmaps")?;
    let strength = t.scale;
    for texel in &mut image.texels {
        let v = 1.0 + strength * (texel[0] as f32 / 255.0 - 1.0);
        let b = (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        *texel = [b, b, b, 255];
    }
    Ok(Arc::new(Rgba8Mips::with_box_mipmaps(image)))
}

/// `emissiveTexture · emissiveFactor`, sRGB-encoded as the decal is (a one-texel map of the
/// factor where there is no texture), or `None` where the factor is black: glTF's default,
/// which turns a texture off.
pub(super) fn emission_map(t: Option<&MaterialTexture>, factor: [f32; 3]) -> Result<Option<Arc<Rgba8Mips>>, Error> {
    if factor.iter().all(|&f| f <= 0.0) {
        return Ok(None);
    }
    let tint = |texel: [u8; 4]| {
        let c = |i: usize| srgb_encode(srgb_decode(texel[i]) * factor[i]);
        [c(0), c(1), c(2), 255]
    };
    Ok(Some(Arc::new(match t {
        Some(t) => {
            let mut image = level0(t, "the emission map and its mipmaps")?;
            image.texels.iter_mut().for_each(|texel| *texel = tint(*texel));
            Rgba8Mips::with_box_mipmaps(image)
        }
        None => Rgba8Mips::single(Rgba8Image::new(1, 1, vec![tint([255; 4])])),
    })))
}

/// Perceptual roughness in red: a `metallicRoughnessTexture`'s green times `roughnessFactor`,
/// resampled (bilinearly) to `size`, the normal map's, as the roughness-map filter reads it
/// with the normal map's coordinates and levels; box-filtered mipmaps.
pub(super) fn roughness_map(t: &MaterialTexture, factor: f32, size: (usize, usize)) -> Result<Arc<Rgba8Mips>, Error> {
    let image = level0(t, "the roughness map and its mipmaps")?;
    let green: Vec<u8> = image
        .texels
        .iter()
        .map(|texel| ((texel[1] as f32 / 255.0 * factor).clamp(0.0, 1.0) * 255.0).round() as u8)
        .collect();
    let gray = image::GrayImage::from_raw(image.width as u32, image.height as u32, green)
        .expect("one byte per texel of the level");
    let (w, h) = (size.0.max(1), size.1.max(1));
    let resized = if (image.width, image.height) == (w, h) {
        gray
    } else {
        image::imageops::resize(&gray, w as u32, h as u32, image::imageops::FilterType::Triangle)
    };
    let texels = resized.pixels().map(|p| [p.0[0], 0, 0, 255]).collect();
    Ok(Arc::new(Rgba8Mips::with_box_mipmaps(Rgba8Image::new(w, h, texels))))
}
