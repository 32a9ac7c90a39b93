//! What the viewer's choices make: the scene and technique prepared from the scene's setup with
//! each choice applied (technique, scene, bump scale, shininess, depth, the toggles, the
//! sampler), the heights as geometry made once per height field and kept.
//!
//! What this module does not do: decide what a key chooses (`super::Viewer::apply`) or keep a
//! choice that fails (the caller keeps the old scene).

use std::sync::Arc;

use bumpmap::bumpmap_core::state::Sampler;
use bumpmap::{
    BumpSource, HeightField, HeightMips, MipMode, Normalize, Prepared, SceneKind, SelfShadow, TechniqueName,
    TechniqueOptions,
};
use glam::Vec3;

use super::{Choices, Mips};
use crate::setup::Setup;

/// A height field and the heights as geometry made from it.
pub(super) type HeightsCache = Option<(Arc<HeightField>, Arc<HeightMips>)>;

/// The scene and technique `choices` describe, on `base`; the heights as geometry from
/// `heights` when they were made from the same field, else made and kept there.
pub(super) fn prepare(
    base: &Setup,
    scenes: &[SceneKind],
    c: &Choices,
    heights: &mut HeightsCache,
) -> Result<Prepared, bumpmap::Error> {
    let mut spec = base.spec.clone();
    spec.kind = scenes[c.scene].clone();
    let params = &mut spec.params;
    let name = TechniqueName::ALL[c.technique];
    let takes_heights = name.parallax_method().is_some() || name == TechniqueName::ReferenceDisplaced;
    if let (true, None, BumpSource::Heights(field)) = (takes_heights, &params.height_mips, &params.bumps) {
        let mips = match heights {
            Some((made_from, mips)) if Arc::ptr_eq(made_from, field) => mips.clone(),
            _ => {
                let mips = Arc::new(HeightMips::from_field(field).map_err(bumpmap::CoreError::from)?);
                *heights = Some((field.clone(), mips.clone()));
                mips
            }
        };
        params.height_mips = Some(mips);
    }
    if let BumpSource::Heights(_) = params.bumps {
        params.normal_map.scale = c.bump_scale;
    }
    params.shininess = c.shininess;
    params.depth = c.depth;
    if !c.decal {
        params.decal = None;
        params.default_decal = false;
        if let Some(parts) = &mut params.parts {
            Arc::make_mut(parts).replace_decals(None);
        }
    }
    if !c.diffuse {
        params.diffuse = Vec3::ZERO;
    }
    if !c.specular {
        params.specular = Vec3::ZERO;
    }
    params.mip_mode = if c.mips == Mips::Renormalized { MipMode::Renormalize } else { MipMode::LengthInAlpha };
    let sampler = match (c.nearest, c.mips) {
        (true, _) => Sampler::NEAREST_REPEAT,
        (false, Mips::None) => Sampler::LINEAR_REPEAT,
        (false, _) => Sampler::TRILINEAR_REPEAT,
    };
    let mut options: TechniqueOptions = base.options.clone();
    options.parallax.layers = c.layers;
    options.parallax.shadow = c.parallax_shadow;
    options.kilgard.self_shadow = c.self_shadow;
    options.kilgard.sampler = sampler;
    options.emboss.sampler = sampler;
    let sp = &mut options.single_pass;
    sp.sampler = sampler;
    sp.normalize = if c.cube { Normalize::Cube } else { Normalize::Math };
    sp.specular_filter = c.specular_filter;
    sp.detail = match (&base.options.single_pass.detail, c.detail) {
        (Some(d), Some(method)) => Some(bumpmap::bumpmap_core::detail::DetailLayer { method, ..d.clone() }),
        _ => None,
    };
    if !c.self_shadow {
        sp.self_shadow = SelfShadow::Off;
        options.reference.self_shadow = SelfShadow::Off;
    } else if sp.self_shadow == SelfShadow::Off {
        sp.self_shadow = SelfShadow::Ramp;
        options.reference.self_shadow = SelfShadow::Ramp;
    }
    let prepared = Prepared::new(&spec, name, &options)?;
    // What the technique cannot draw is refused here, so the choice is undone, rather than
    // when the frame is drawn.
    if !name.is_reference() {
        prepared.technique.passes(&prepared.scene)?;
    }
    Ok(prepared)
}
