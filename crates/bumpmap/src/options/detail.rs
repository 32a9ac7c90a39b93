//! The detail normal map of [`super::DetailOptions`]: its file read as a normal map file is (the
//! Y convention applied, its own levels or a chain made with the length in alpha), and refused
//! for the techniques that cannot read a second normal map.
//!
//! What this module does not do: blend anything (`bumpmap_core::detail`, the backends) or
//! write a blended map (`crate::maps::blend`).

use std::sync::Arc;

use bumpmap_core::detail::DetailLayer;
use bumpmap_core::{Technique, TechniqueName, TechniqueOptions};
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_math::MipMode;
use bumpmap_math::imported::ImportOptions;

use super::{Given, SceneOptions, SetupError, SetupNote};
use crate::assets::{given_or_load_normal_map, green_way};

/// The detail layer `o` asks for, or `None`; a technique outside the single pass's family
/// refuses one.
pub(super) fn detail_layer(
    o: &SceneOptions,
    given: &Given,
    notes: &mut Vec<SetupNote>,
) -> Result<Option<DetailLayer>, SetupError> {
    let d = &o.detail;
    let Some(path) = &d.map else { return Ok(None) };
    let name = o.technique.technique;
    if !draws_detail(name) {
        return Err(SetupError::DetailNotDrawn { technique: name });
    }
    let y_convention = d.y_convention.unwrap_or(o.y_convention);
    let options = ImportOptions { y_convention, scale: 1.0, mip_mode: MipMode::LengthInAlpha, rebuild_mips: false };
    let map = given_or_load_normal_map(path, given.detail_map.as_ref(), &options)?;
    notes.push(SetupNote::About {
        path: path.clone(),
        line: format!(
            "{} as the detail map (green {}), {} times over the normal map by {}, strength {}{}",
            map.describe(),
            green_way(y_convention),
            d.repeat,
            bumpmap_math::Named::name(d.method),
            d.strength,
            if finer_than_8_bits(map.format) {
                "; read at 8 bits a channel, as every texture unit holds them"
            } else {
                ""
            },
        ),
    });
    notes.extend(map.warnings().iter().map(|w| SetupNote::Warning(w.to_string())));
    Ok(Some(DetailLayer {
        map: Arc::new(map.chain.to_mips()),
        repeat: d.repeat,
        method: d.method,
        strength: d.strength,
    }))
}

/// Whether the file held more than 8 bits a channel (the renderers' texture units hold 8).
fn finer_than_8_bits(format: TextureFormat) -> bool {
    matches!(format, TextureFormat::Rgba16 | TextureFormat::Rgba32Float)
}

/// Whether `name` draws a detail map (the single pass and its variants).
fn draws_detail(name: TechniqueName) -> bool {
    matches!(name.technique(&TechniqueOptions::default()), Technique::SinglePass(_))
}
