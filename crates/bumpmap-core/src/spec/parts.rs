//! A loaded model as parts, each drawn with its own material: a glTF's primitives, placed and
//! split by `bumpmap::assets`. `crate::scenes::build` makes one [`crate::scene::SceneObject`]
//! per part, its normal map and decal the part material's; the lighting coefficients, the
//! camera and the lights stay the scene's.
//!
//! What this module does not do: read files, or decide which of a file's materials an explicit
//! option replaces (the caller does, with [`MeshParts::replace_bumps`] and
//! [`MeshParts::replace_decals`]).

use std::sync::Arc;

use bumpmap_math::Rgba8Mips;
use bumpmap_math::mesh::Mesh;

use super::BumpSource;

/// A model's parts and the materials they draw with.
#[derive(Clone, Debug, Default)]
pub struct MeshParts {
    /// The materials, each once; [`MeshPart::material`] indexes them.
    pub materials: Vec<PartMaterial>,
    /// The parts, in the order they are drawn.
    pub parts: Vec<MeshPart>,
}

/// What a part's material gives the renderers.
#[derive(Clone, Debug)]
pub struct PartMaterial {
    /// Its name, for messages.
    pub name: String,
    /// Its own bumps (a normal map; a flat one for a material without), or `None` for the
    /// scene's ([`crate::SceneParams::bumps`]).
    pub bumps: Option<BumpSource>,
    /// Its decal (the base colour), or `None` for none.
    pub decal: Option<Arc<Rgba8Mips>>,
    /// Its textures' wrap modes and filters (a glTF sampler's).
    pub sampler: crate::state::MaterialSampler,
    /// Opaque, cut out or blended by the decal's alpha.
    pub alpha: crate::scene::AlphaMode,
    /// What multiplies the ambient term, in red ([`crate::scene::Material::occlusion`]).
    pub occlusion: Option<Arc<Rgba8Mips>>,
    /// Light given off, added ([`crate::scene::Material::emission`]).
    pub emission: Option<Arc<Rgba8Mips>>,
    /// Perceptual roughness in red, at its normal map's size
    /// ([`crate::scene::Material::roughness_map`]).
    pub roughness_map: Option<Arc<Rgba8Mips>>,
}

/// One part: its geometry (with normals, texture coordinates and tangents) and its material.
#[derive(Clone, Debug)]
pub struct MeshPart {
    /// The geometry, in the model's space.
    pub mesh: Arc<Mesh>,
    /// An index into [`MeshParts::materials`].
    pub material: usize,
}

impl MeshParts {
    /// Every material drawn with the scene's bumps instead of its own (an explicit height
    /// field or normal map replaces the file's, or a technique draws no bumps).
    pub fn replace_bumps(&mut self) {
        for m in &mut self.materials {
            m.bumps = None;
        }
    }

    /// Every material drawn with `decal` instead of its own base colour.
    pub fn replace_decals(&mut self, decal: Option<Arc<Rgba8Mips>>) {
        for m in &mut self.materials {
            m.decal = decal.clone();
        }
    }

    /// Every material's textures filtered as the technique says, whatever filters its sampler
    /// names (its wrap modes stay): what a filter the user chose asks.
    pub fn replace_filters(&mut self) {
        for m in &mut self.materials {
            (m.sampler.min, m.sampler.mag) = (None, None);
        }
    }

    /// The bumps of the materials that have their own.
    pub fn own_bumps(&self) -> impl Iterator<Item = &BumpSource> {
        self.materials.iter().filter_map(|m| m.bumps.as_ref())
    }
}
