//! What a material's alpha and emission add to a technique's passes, the same for every
//! technique, applied to the pass list after the technique made it:
//!
//! - **cut out** ([`AlphaMode::Mask`]): a first pass lays the depth of the texels whose decal
//!   alpha passes `glAlphaFunc(GL_GEQUAL, cutoff)`, colour writes off; the technique's own first
//!   pass then draws with depth EQUAL like its later ones, so every pass covers the same texels
//!   (how a multipass renderer cuts out: the alpha test once, in the pass that writes depth);
//! - **emission**: one more pass adds the emission map's colour, depth EQUAL;
//! - **blended** ([`AlphaMode::Blend`]), for a technique that [blends](super::Technique::blends):
//!   the objects are drawn after the opaque ones, the farthest first (by the centre of each
//!   object's bounds: whole primitives are sorted, not triangles).
//!
//! What this module does not do: decide how a blended material's own passes blend (the
//! technique does, as only it knows which of its passes carries the surface's colour), or read
//! the occlusion map (the ambient term is the technique's).

use glam::Vec3;

use crate::combiners::Precision;
use crate::error::{CoreError, Feature};
use crate::scene::{AlphaMode, Scene, SceneObject};
use crate::setups;
use crate::state::{Blend, BlendFactor, DepthFunc, PassState, Sampler};
use crate::technique::{Binding, CombinerProgram, Pass, Program, TextureUnit};
use crate::vertex::var;

/// `technique`'s `passes` (each object's passes together, as every technique makes them) with each
/// material's cut, emission and order applied; `sampler` is the technique's for the decal and
/// the emission map, `blends` whether it draws blended materials blended.
pub(super) fn finish(
    technique: &'static str,
    scene: &Scene,
    passes: Vec<Pass>,
    sampler: Sampler,
    blends: bool,
) -> Result<Vec<Pass>, CoreError> {
    // Most scenes have nothing to add or reorder: their pass list is returned as it is.
    let plain = |m: &crate::scene::Material| m.alpha == AlphaMode::Opaque && m.emission.is_none();
    if scene.objects.iter().all(|o| plain(&o.material)) {
        return Ok(passes);
    }
    let mut groups: Vec<(usize, Vec<Pass>)> = Vec::new();
    for pass in passes {
        match groups.last_mut() {
            Some((object, group)) if *object == pass.object => group.push(pass),
            _ => groups.push((pass.object, vec![pass])),
        }
    }
    for (o, group) in &mut groups {
        let m = &scene.objects[*o].material;
        let unit = |texture| TextureUnit {
            binding: Binding::TwoD { texture, s: var::S, t: var::T },
            sampler: sampler.for_material(&m.sampler),
        };
        let colored = scene.objects[*o].mesh.has_colors();
        let combiners = |units, setup: crate::combiners::CombinerSetup| {
            let vertex_color = colored && setup.reads(crate::combiners::Register::PrimaryColor);
            Program::Combiners(CombinerProgram { units, setup, precision: Precision::Float, vertex_color })
        };
        // Without a decal or vertex colours the alpha is the factor's, already 1 (the texel's
        // product): nothing to cut.
        if let AlphaMode::Mask { cutoff } = m.alpha
            && (m.decal.is_some() || colored)
        {
            if group.iter().any(writes_depth) {
                return Err(CoreError::Unsupported { technique, feature: Feature::MaskWithDepth });
            }
            for pass in group.iter_mut().filter(|p| p.state.depth_write) {
                pass.state.depth_func = DepthFunc::Equal;
                pass.state.depth_write = false;
            }
            let state = PassState { color_mask: [false; 4], alpha_test: Some(cutoff), ..PassState::OPAQUE };
            let units: Vec<TextureUnit> = m.decal.iter().map(|d| unit(d.clone())).collect();
            let setup = if colored { setups::vertex_colored_decal(m.decal.is_some()) } else { setups::decal() };
            let program = combiners(units, setup);
            group.insert(0, Pass { object: *o, light: 0, snapshot: None, state, program });
        }
        if let Some(emission) = &m.emission {
            let blended = blends && m.alpha == AlphaMode::Blend;
            let mut units = vec![unit(emission.clone())];
            if blended {
                units.extend(m.decal.clone().map(unit));
            }
            let setup = setups::emission(units.len() == 2);
            let blend = if blended { Blend::new(BlendFactor::SrcAlpha, BlendFactor::One) } else { Blend::ADD };
            let program = combiners(units, setup);
            group.push(Pass { object: *o, light: 0, snapshot: None, state: PassState::equal(blend), program });
        }
    }
    if blends {
        // Opaque first in their own order, then blended ones from the farthest.
        let eye = scene.camera.eye;
        let key = |o: usize| {
            let object = &scene.objects[o];
            match object.material.alpha {
                AlphaMode::Blend => (1, -centre(object).distance(eye)),
                _ => (0, 0.0),
            }
        };
        groups.sort_by(|a, b| key(a.0).partial_cmp(&key(b.0)).unwrap_or(std::cmp::Ordering::Equal));
    }
    Ok(groups.into_iter().flat_map(|(_, group)| group).collect())
}

/// Whether a pass's program writes a depth of its own (heights as geometry moving the surface).
fn writes_depth(pass: &Pass) -> bool {
    match &pass.program {
        Program::Lit(l) => {
            l.parallax.as_ref().is_some_and(|p| p.parallax.options.write_depth || p.parallax.options.silhouettes)
        }
        Program::Combiners(_) => false,
    }
}

/// The centre of an object's bounds in world space.
fn centre(object: &SceneObject) -> Vec3 {
    let (lo, hi) = object
        .mesh
        .positions
        .iter()
        .map(|&p| object.world_from_object.transform_point3(p))
        .fold((Vec3::MAX, Vec3::MIN), |(lo, hi), p| (lo.min(p), hi.max(p)));
    (lo + hi) * 0.5
}
