//! Heights as geometry on the CPU pipeline: [`bumpmap_core::parallax::fragment`] for each live
//! fragment, its heights read by GL's LINEAR filter from the level of the footprint's shorter
//! side ([`bumpmap_core::parallax::height_lambda`]; the footprint at the entry point, once per
//! quad), the horizon map (where the shadow is the horizon's) from the same level.
//!
//! Not vectorized: each lane runs the core's march as it is written (one home for every march;
//! BENCHMARKS.md says what that costs).

use glam::{Vec2, Vec3};

use bumpmap_core::parallax::{
    FragmentHeights, FragmentRays, HorizonLookup, displaced_depth, fragment, height_lambda, height_level,
};
use bumpmap_core::technique::ParallaxProgram;
use bumpmap_core::vertex::var;
use bumpmap_math::lighting::Light;

use super::{Scratch, SinglePass};
use crate::fixed_function::pack_2d_coords;
use crate::raster::FragmentBatch;

impl SinglePass<'_> {
    /// Marches every live fragment (lanes `0..n`) into the heights: fills the scratch's hit
    /// coordinates, L and V there, the light let through, the heights' normal at the hit and the window
    /// depth (NaN where a silhouette discards the fragment). Leaves the normal map's packed
    /// coordinates and λ of the entry points in `sc.coords`.
    pub(super) fn parallax(&self, p: &ParallaxProgram, batch: &FragmentBatch, sc: &mut Scratch, n: usize) {
        pack_2d_coords(&self.normal_map, batch, [var::S, var::T], [1.0, 1.0], &mut sc.coords);
        let slots = (var::TEX_VIEW..var::TEX_VIEW + 3)
            .chain(var::TEX_LIGHT..var::TEX_LIGHT + 3)
            .chain(var::TANGENT_FROM_TEX..var::TANGENT_FROM_TEX + 4)
            .chain(var::CURVATURE..var::CURVATURE + 2);
        for (k, slot) in slots.enumerate() {
            batch.pack(slot, &mut sc.tex[k]);
        }
        batch.pack_lanes(&batch.depth, &mut sc.depth);
        let levels = p.heights.levels();
        let horizon_levels = p.horizons.as_ref().map_or(&[][..], |h| h.levels());
        let positional = matches!(self.program.light.light, Light::Positional(_));
        let sampler = self.program.sampler;
        let heights = FragmentHeights { level0: &levels[0], minmax: p.heights.minmax() };
        let size = Vec2::new(levels[0].width as f32, levels[0].height as f32);
        let (s, t_) = (&batch.varyings[var::S], &batch.varyings[var::T]);
        let t = &sc.tex;
        for (j, &lane) in batch.live().iter().enumerate().take(n) {
            // The quad's derivatives along x and y (its pixels (1, 0) and (0, 1) from (0, 0)).
            let q = (lane as usize) & !3;
            let at = |k: usize| Vec2::new(s[q + k], t_[q + k]);
            let (dx, dy) = ((at(1) - at(0)) * size, (at(2) - at(0)) * size);
            let lambda = height_lambda(dx.length_squared(), dy.length_squared());
            let k = height_level(&sampler, lambda, levels.len());
            let level = &levels[k];
            let mut sample = |st: Vec2| level.bilinear(st.x, st.y);
            // The horizons from the heights' level: the same footprint.
            let mut sample_horizons = |st: Vec2| horizon_levels[k].bilinear(st.x, st.y);
            let horizons = (!horizon_levels.is_empty())
                .then_some(HorizonLookup { size, sample: &mut sample_horizons as &mut dyn FnMut(Vec2) -> _ });
            let rays = FragmentRays {
                st: Vec2::new(sc.coords[0][j], sc.coords[1][j]),
                to_eye: Vec3::new(t[0][j], t[1][j], t[2][j]),
                to_light: Vec3::new(t[3][j], t[4][j], t[5][j]),
                jacobian: [t[6][j], t[7][j], t[8][j], t[9][j]],
                curvature: Vec2::new(t[10][j], t[11][j]),
            };
            let (hit, l, v, light, normal, depth, occlusion) =
                match fragment(&rays, &p.parallax, p.depth, positional, &mut sample, heights, horizons) {
                    Some(f) => {
                        let depth = if p.parallax.options.write_depth {
                            displaced_depth(sc.depth[j], f.kappa, p.depth_range)
                        } else {
                            sc.depth[j]
                        };
                        (f.st, f.l, f.v, f.light, f.normal.unwrap_or(Vec3::Z), depth, f.occlusion)
                    }
                    None => (rays.st, Vec3::Z, Vec3::Z, 0.0, Vec3::Z, f32::NAN, 1.0),
                };
            (sc.hit[0][j], sc.hit[1][j]) = (hit.x, hit.y);
            for c in 0..3 {
                sc.par_l[c][j] = l[c];
                sc.par_v[c][j] = v[c];
                sc.par_n[c][j] = normal[c];
            }
            sc.par_light[j] = light;
            sc.occlusion[j] = occlusion;
            sc.depth[j] = depth;
        }
    }
}
