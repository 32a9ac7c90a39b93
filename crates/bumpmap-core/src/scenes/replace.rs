//! A scene's bumps or decal replaced by the user's own, a mesh's parts included: what giving a
//! normal map, a height field or a decal of one's own does to a [`SceneSpec`]. What it does not
//! do: load or check the maps (the caller's), or make any technique's maps.

use std::sync::Arc;

use bumpmap_math::Rgba8Mips;

use super::{BumpSource, SceneSpec};

impl SceneSpec {
    /// Draws every surface with `bumps` (a mesh's parts included, their own bumps set aside),
    /// without the default brick decal: what giving a normal map or a height field of one's own
    /// means. `bricks_decal` keeps the brick decal that goes with the brick heights.
    pub fn use_bumps(&mut self, bumps: BumpSource, bricks_decal: bool) {
        self.params.bumps = bumps;
        self.params.default_decal = bricks_decal && self.params.decal.is_none();
        if let Some(parts) = &mut self.params.parts {
            Arc::make_mut(parts).replace_bumps();
        }
    }

    /// Draws every surface with `decal` (`None`: no decal), a mesh's parts' own base colours
    /// set aside.
    pub fn use_decal(&mut self, decal: Option<Arc<Rgba8Mips>>) {
        self.params.decal = decal;
        self.params.default_decal = false;
        if let Some(parts) = &mut self.params.parts {
            Arc::make_mut(parts).replace_decals(self.params.decal.clone());
        }
    }
}
