//! The single pass's fragment program on the CPU pipeline: [`bumpmap_core::shading`]'s model
//! over a batch's live fragments in structure-of-arrays lanes.
//!
//! The texture lookups (normal map, decal, gloss, cube map, spotlight pattern) run through the
//! batch sampler; the lighting arithmetic (`lighting_lanes`) is the lane copy of
//! `bumpmap_core::shading::shade`, tested equal to it. What to draw and with which state is the
//! core's (`bumpmap_core::technique::single_pass`).

use std::sync::Arc;

use glam::Vec3;

use bumpmap_core::detail::{DetailLayer, detail_normal};
use bumpmap_core::scene::{Attenuation, NormalSpace, NormalTexels};
use bumpmap_core::shading::{blinn_from_derivatives, offset_to_normal, spot_cone};
use bumpmap_core::technique::{Gloss, HalfAngle, LitProgram};
use bumpmap_core::vertex::var;

use crate::combiners::{LANES, Lanes};
use crate::fixed_function::pack_2d_coords;
use crate::raster::{FragmentBatch, FragmentShader};
use crate::texture::{MomentTexture, Sampler, Texture2d, TextureCube, sample_2d, sample_2d_lanes, sample_cube_lanes};

mod lighting;
mod parallax;

use lighting::lighting_lanes;

/// The per-light fragment program.
pub(crate) struct SinglePass<'a> {
    /// What the core asked for.
    pub program: &'a LitProgram,
    /// The normalization cube map, for [`bumpmap_core::technique::Normalize::Cube`].
    pub cube: Option<Arc<TextureCube>>,
    /// The program's textures as texture units hold them.
    pub normal_map: Arc<Texture2d>,
    /// The normal map's LEAN moments, for [`SpecularFilter::Lean`] and [`SpecularFilter::Clean`]
    /// (which reads their Mxx + Myy only: the same texture, not CLEAN's smaller one, which saves
    /// memory traffic a GPU has and this sampler, one lane at a time, does not).
    pub moments: Option<Arc<MomentTexture>>,
    /// The roughness map (perceptual roughness in red, the normal map's size), for
    /// [`SpecularFilter::RoughnessMap`].
    pub roughness: Option<Arc<Texture2d>>,
    pub decal: Option<Arc<Texture2d>>,
    /// The material's occlusion map (what multiplies the ambient term, in red).
    pub occlusion: Option<Arc<Texture2d>>,
    pub gloss: Option<Arc<Texture2d>>,
    pub pattern: Option<Arc<Texture2d>>,
    /// The detail normal map of [`LitProgram::detail`], if any.
    pub detail: Option<Arc<Texture2d>>,
}

/// Per-thread working memory: every per-fragment quantity as packed lanes (lane j is the j-th
/// live fragment of the batch), so each step below is one loop over contiguous arrays.
#[derive(Clone)]
pub struct Scratch {
    /// s, t, λ of the lookup being made.
    coords: [Lanes; 3],
    /// The filtered normal map (RGB range-compressed, A = |N'|), the decal, the gloss texture,
    /// the occlusion map, the detail map.
    normal: [Lanes; 4],
    detail: [Lanes; 4],
    decal: [Lanes; 4],
    gloss: [Lanes; 4],
    occlusion_map: [Lanes; 4],
    /// The filtered LEAN moments (Bx, By, Mxx, Myy, Mxy, J), when the filter reads them.
    moments: [Lanes; 6],
    /// The filtered roughness map (roughness in red), when the filter reads it.
    roughness: [Lanes; 4],
    /// L and H after per-fragment normalization, and vectors being packed or normalized.
    l: [Lanes; 3],
    h: [Lanes; 3],
    v: [Lanes; 3],
    w: [Lanes; 3],
    /// A cube-map lookup's RGBA.
    cube: [Lanes; 4],
    /// L and H against the unperturbed normal (L_z and H_z in tangent space).
    l_n: Lanes,
    h_n: Lanes,
    /// Attenuation × spotlight.
    light: Lanes,
    /// Ambient occlusion, multiplying the ambient term (1 without heights as geometry).
    occlusion: Lanes,
    /// Eq. 12's s_self, N'·L, H·N' (then its power), the specular gate, and a power's partial
    /// product.
    s_self: Lanes,
    n_dot_l: Lanes,
    h_dot_n: Lanes,
    gate: Lanes,
    acc: Lanes,
    /// Heights as geometry (`parallax`): the texture-space varyings (to the eye 3, to the light
    /// 3, the Jacobian 4, the curvature 2), and what the march found: where to read the maps,
    /// L and V there, the light let through, the exact walk's normal, the window depth.
    tex: [Lanes; 12],
    hit: [Lanes; 2],
    par_l: [Lanes; 3],
    par_v: [Lanes; 3],
    par_n: [Lanes; 3],
    par_light: Lanes,
    depth: Lanes,
}

impl Scratch {
    fn zeroed() -> Box<Self> {
        let z = [0.0; LANES];
        Box::new(Scratch {
            coords: [z; 3],
            normal: [z; 4],
            detail: [z; 4],
            decal: [z; 4],
            gloss: [z; 4],
            occlusion_map: [z; 4],
            moments: [z; 6],
            roughness: [z; 4],
            l: [z; 3],
            h: [z; 3],
            v: [z; 3],
            w: [z; 3],
            cube: [z; 4],
            l_n: z,
            h_n: z,
            light: z,
            occlusion: [1.0; LANES],
            s_self: z,
            n_dot_l: z,
            h_dot_n: z,
            gate: z,
            acc: z,
            tex: [z; 12],
            hit: [z; 2],
            par_l: [z; 3],
            par_v: [z; 3],
            par_n: [z; 3],
            par_light: z,
            depth: z,
        })
    }
}

/// `normalize(v)`, or +Z where v has no direction (glam's `normalize_or`).
#[inline(always)]
fn normalize_or_z(x: f32, y: f32, z: f32) -> [f32; 3] {
    let rcp = 1.0 / (x * x + y * y + z * z).sqrt();
    let ok = rcp.is_finite() && rcp > 0.0;
    [if ok { x * rcp } else { 0.0 }, if ok { y * rcp } else { 0.0 }, if ok { z * rcp } else { 1.0 }]
}

/// `v ← normalize_or_z(v)`, lanes `0..n`.
fn normalize_lanes(v: &mut [Lanes; 3], n: usize) {
    let [x, y, z] = v;
    for j in 0..n {
        [x[j], y[j], z[j]] = normalize_or_z(x[j], y[j], z[j]);
    }
}

/// Dot products of two packed vectors, lanes `0..n`.
fn dot_lanes(a: &[Lanes; 3], b: &[Lanes; 3], n: usize, out: &mut Lanes) {
    for j in 0..n {
        out[j] = a[0][j] * b[0][j] + a[1][j] * b[1][j] + a[2][j] * b[2][j];
    }
}

impl SinglePass<'_> {
    /// `out ← unit(v)`: per-fragment normalization by math or the cube map (expanded 2x − 1).
    fn unit(&self, v: &[Lanes; 3], cube: &mut [Lanes; 4], n: usize, out: &mut [Lanes; 3]) {
        match &self.cube {
            Some(map) => {
                sample_cube_lanes(map, &Sampler::LINEAR_CLAMP, [&v[0], &v[1], &v[2]], n, cube);
                for c in 0..3 {
                    for j in 0..n {
                        out[c][j] = cube[c][j] * 2.0 - 1.0;
                    }
                }
            }
            None => {
                let [x, y, z] = out;
                for j in 0..n {
                    [x[j], y[j], z[j]] = normalize_or_z(v[0][j], v[1][j], v[2][j]);
                }
            }
        }
    }

    /// MikkTSpace's per-pixel decode of the normal in `sc.normal` (range-compressed, its length
    /// kept): to object space in the interpolated, unnormalized tangent and normal, as
    /// `bumpmap_math::tangent::decode_per_pixel` says. Runs after every lookup, so the packed
    /// coordinates and the vectors of L and H are free.
    fn decode_per_pixel(&self, batch: &FragmentBatch, sc: &mut Scratch, n: usize) {
        for k in 0..3 {
            batch.pack(var::TANGENT + k, &mut sc.v[k]);
            batch.pack(var::N + k, &mut sc.w[k]);
        }
        batch.pack(var::TANGENT + 3, &mut sc.coords[0]);
        let (nm, t, nv, sign) = (&mut sc.normal, &sc.v, &sc.w, &sc.coords[0]);
        for j in 0..n {
            let v = Vec3::new(nm[0][j], nm[1][j], nm[2][j]) * 2.0 - 1.0;
            let frame_t = Vec3::new(t[0][j], t[1][j], t[2][j]);
            let frame_n = Vec3::new(nv[0][j], nv[1][j], nv[2][j]);
            let d = bumpmap_math::tangent::decode_per_pixel(v, frame_t, sign[j], frame_n) * 0.5 + 0.5;
            (nm[0][j], nm[1][j], nm[2][j]) = (d.x, d.y, d.z);
        }
    }

    /// Samples a 2D texture at the live lanes at `scale ⊙ (s, t)`, λ once per quad. With
    /// `same_coords` the coordinates packed for the previous lookup are reused (same texture
    /// size and scale: same s, t and λ).
    fn sample(
        &self,
        tex: &Texture2d,
        batch: &FragmentBatch,
        scale: [f32; 2],
        sc: &mut Scratch,
        n: usize,
        which: Tex,
        same_coords: bool,
    ) {
        if !same_coords {
            pack_2d_coords(tex, batch, [var::S, var::T], scale, &mut sc.coords);
            if self.program.parallax.is_some() {
                // Where the view ray met the heights, at the footprint where it entered (as
                // `textureGrad` reads a texture with the entry point's derivatives).
                let m = n.next_multiple_of(8).min(LANES);
                for c in 0..2 {
                    sc.coords[c][..m].copy_from_slice(&sc.hit[c][..m]);
                }
            }
        }
        let out = match which {
            Tex::Normal => &mut sc.normal,
            Tex::Decal => &mut sc.decal,
            Tex::Gloss => &mut sc.gloss,
            Tex::Occlusion => &mut sc.occlusion_map,
        };
        let [s, t, lambda] = &sc.coords;
        sample_2d_lanes(tex, &self.program.sampler, s, t, lambda, n, out);
    }

    /// Lays the detail map over the filtered normal in `sc.normal` ([`detail_normal`] per lane):
    /// the detail read at `repeat` times the normal map's coordinates, with its own λ.
    fn detail(
        &self,
        layer: &DetailLayer,
        d: &Texture2d,
        batch: &FragmentBatch,
        scale: [f32; 2],
        sc: &mut Scratch,
        n: usize,
    ) {
        let scale = scale.map(|k| k * layer.repeat);
        pack_2d_coords(d, batch, [var::S, var::T], scale, &mut sc.coords);
        if self.program.parallax.is_some() {
            // At the hit, with the entry point's footprint (as `sample` reads the normal map).
            let m = n.next_multiple_of(8).min(LANES);
            for c in 0..2 {
                for j in 0..m {
                    sc.coords[c][j] = sc.hit[c][j] * scale[c];
                }
            }
        }
        let [s, t, lambda] = &sc.coords;
        sample_2d_lanes(d, &self.program.sampler, s, t, lambda, n, &mut sc.detail);
        let (nm, dm) = (&mut sc.normal, &sc.detail);
        for j in 0..n {
            let base = glam::Vec4::new(nm[0][j], nm[1][j], nm[2][j], nm[3][j]);
            let texel = glam::Vec4::new(dm[0][j], dm[1][j], dm[2][j], dm[3][j]);
            let v = detail_normal(base, texel, layer.method, layer.strength);
            (nm[0][j], nm[1][j], nm[2][j], nm[3][j]) = (v.x, v.y, v.z, v.w);
        }
    }

    /// Attenuation and the spotlight's cone and pattern, per live lane.
    fn light_factor(&self, batch: &FragmentBatch, sc: &mut Scratch, n: usize) {
        let live = batch.live();
        let light = &self.program.light;
        match light.attenuation {
            Attenuation::None => sc.light[..n].fill(1.0),
            attenuation => {
                batch.pack(var::LIGHT_DISTANCE, &mut sc.light);
                sc.light[..n].iter_mut().for_each(|d| *d = attenuation.factor(*d));
            }
        }
        let Some(spot) = &light.spot else { return };
        let v3 = |slot: usize, lane: usize| {
            Vec3::new(batch.varyings[slot][lane], batch.varyings[slot + 1][lane], batch.varyings[slot + 2][lane])
        };
        for (j, &lane) in live.iter().enumerate() {
            let lane = lane as usize;
            let mut f = spot_cone(spot, v3(var::L, lane), v3(var::SPOT, lane));
            if let Some(pattern) = &self.pattern {
                f *= pattern_factor(pattern, v3(var::PROJ, lane));
            }
            sc.light[j] *= f;
        }
    }
}

/// The projected pattern's red channel at the projective coordinates (s, t, q), 0 behind the
/// light (Segal et al.); LINEAR, CLAMP_TO_EDGE, level 0.
fn pattern_factor(pattern: &Texture2d, p: Vec3) -> f32 {
    if p.z > 0.0 { sample_2d(pattern, &Sampler::LINEAR_CLAMP, p.x / p.z, p.y / p.z, 0.0).x } else { 0.0 }
}

/// Which texture [`SinglePass::sample`] fills.
#[derive(Clone, Copy)]
enum Tex {
    Normal,
    Decal,
    Gloss,
    Occlusion,
}

impl FragmentShader for SinglePass<'_> {
    type Scratch = Box<Scratch>;

    fn scratch(&self) -> Self::Scratch {
        Scratch::zeroed()
    }

    fn shade(&self, batch: &FragmentBatch, sc: &mut Self::Scratch, out: &mut [Lanes; 4]) {
        let o = self.program;
        let live_n = batch.live().len();
        // Every loop runs over whole 8-lane vectors; the lanes past live_n are never written out.
        let n = live_n.next_multiple_of(8);
        let (scale, object_space) = (o.normal_space.texcoord_scale().to_array(), o.normal_space.lit_in_object_space());
        let size = |t: &Texture2d| (t.width(), t.height());
        if let Some(p) = &o.parallax {
            self.parallax(p, batch, sc, live_n);
        }
        self.sample(&self.normal_map, batch, scale, sc, live_n, Tex::Normal, false);
        if let Some(moments) = &self.moments {
            // Same size and levels as the normal map: the coordinates just packed.
            moments.sample_lanes(&self.program.sampler, &sc.coords, live_n, &mut sc.moments);
        }
        if let Some(roughness) = &self.roughness {
            // Same size as the normal map (the core checks a given one): the same coordinates.
            let [s, t, lambda] = &sc.coords;
            sample_2d_lanes(roughness, &self.program.sampler, s, t, lambda, live_n, &mut sc.roughness);
        }
        match o.normal_texels {
            NormalTexels::UnitVector => {}
            NormalTexels::Offset { range } => {
                // Kilgard Eq. 7 per fragment, after filtering the offsets.
                let nm = &mut sc.normal;
                for j in 0..n {
                    let v = offset_to_normal(glam::Vec4::new(nm[0][j], nm[1][j], nm[2][j], nm[3][j]), range);
                    (nm[0][j], nm[1][j], nm[2][j], nm[3][j]) = (v.x, v.y, v.z, v.w);
                }
            }
            NormalTexels::Derivatives { range, scale } => {
                // Peercy Figure 2: Blinn per fragment from the interpolated surface derivatives.
                for k in 0..3 {
                    batch.pack(var::PARAM_FRAME + k, &mut sc.v[k]);
                }
                let (nm, f) = (&mut sc.normal, &sc.v);
                for j in 0..n {
                    let texel = glam::Vec4::new(nm[0][j], nm[1][j], nm[2][j], nm[3][j]);
                    let v = blinn_from_derivatives(texel, range, scale, glam::Vec3::new(f[0][j], f[1][j], f[2][j]));
                    (nm[0][j], nm[1][j], nm[2][j], nm[3][j]) = (v.x, v.y, v.z, v.w);
                }
            }
        }
        if o.parallax.as_ref().is_some_and(|p| p.parallax.hit_normal() == bumpmap_core::parallax::HitNormal::Heights) {
            // The heights' own normal at the hit, from their interpolant (A = 1: one surface).
            for c in 0..3 {
                for j in 0..n {
                    sc.normal[c][j] = sc.par_n[c][j] * 0.5 + 0.5;
                }
            }
            sc.normal[3][..n].fill(1.0);
        }
        if let (Some(layer), Some(d)) = (&o.detail, &self.detail) {
            self.detail(layer, d, batch, scale, sc, live_n);
        }
        // The coordinates packed last (the detail's, which no other texture shares, or none).
        let mut last = if self.detail.is_some() { ((0, 0), scale) } else { (size(&self.normal_map), scale) };
        match &self.decal {
            Some(d) => {
                self.sample(d, batch, [1.0, 1.0], sc, live_n, Tex::Decal, last == (size(d), [1.0, 1.0]));
                last = (size(d), [1.0, 1.0]);
            }
            None => sc.decal.iter_mut().for_each(|c| c.fill(1.0)),
        }
        match (&o.gloss, &self.gloss) {
            (Gloss::Map(_), Some(g)) => {
                self.sample(g, batch, [1.0, 1.0], sc, live_n, Tex::Gloss, last == (size(g), [1.0, 1.0]));
                last = (size(g), [1.0, 1.0]);
            }
            (Gloss::DecalAlpha, _) => sc.gloss[0] = sc.decal[3],
            _ => sc.gloss[0].fill(1.0),
        }
        if let Some(occlusion) = &self.occlusion {
            let same = last == (size(occlusion), [1.0, 1.0]);
            self.sample(occlusion, batch, [1.0, 1.0], sc, live_n, Tex::Occlusion, same);
        }
        if o.parallax.is_some() {
            // L and V where the ray met the heights; H from them per fragment.
            normalize_lanes(&mut sc.par_l, n);
            normalize_lanes(&mut sc.par_v, n);
            for k in 0..3 {
                sc.l[k][..n].copy_from_slice(&sc.par_l[k][..n]);
                for j in 0..n {
                    sc.v[k][j] = sc.par_l[k][j] + sc.par_v[k][j];
                }
            }
            normalize_lanes(&mut sc.v, n);
            for k in 0..3 {
                sc.h[k][..n].copy_from_slice(&sc.v[k][..n]);
            }
        } else {
            // L, and H per vertex or per fragment (Cg Tutorial §8.1.4).
            for k in 0..3 {
                batch.pack(var::L + k, &mut sc.v[k]);
            }
            self.unit(&sc.v, &mut sc.cube, n, &mut sc.l);
            match o.half_angle {
                HalfAngle::Vertex => {
                    for k in 0..3 {
                        batch.pack(var::H + k, &mut sc.v[k]);
                    }
                }
                HalfAngle::Fragment => {
                    // v = normalize(normalize(L) + normalize(V)); v still holds L.
                    normalize_lanes(&mut sc.v, n);
                    for k in 0..3 {
                        batch.pack(var::V + k, &mut sc.w[k]);
                    }
                    normalize_lanes(&mut sc.w, n);
                    for k in 0..3 {
                        for j in 0..n {
                            sc.v[k][j] += sc.w[k][j];
                        }
                    }
                    normalize_lanes(&mut sc.v, n);
                }
            }
            self.unit(&sc.v, &mut sc.cube, n, &mut sc.h);
        }
        // L·N and H·N with the unperturbed normal: L_z and H_z in tangent space.
        if object_space {
            for k in 0..3 {
                batch.pack(var::N + k, &mut sc.v[k]);
            }
            normalize_lanes(&mut sc.v, n);
            dot_lanes(&sc.l, &sc.v, n, &mut sc.l_n);
            dot_lanes(&sc.h, &sc.v, n, &mut sc.h_n);
        }
        self.light_factor(batch, sc, live_n);
        if o.parallax.is_some() {
            for j in 0..n {
                sc.light[j] *= sc.par_light[j];
            }
        } else {
            sc.occlusion[..n].fill(1.0);
        }
        if self.occlusion.is_some() {
            for j in 0..n {
                sc.occlusion[j] *= sc.occlusion_map[0][j];
            }
        }
        if o.vertex_color {
            // The base colour, alpha too, times the interpolated vertex colour (after every
            // lookup: the packed coordinates are free).
            for c in 0..4 {
                batch.pack(var::COLOR + c, &mut sc.coords[0]);
                for j in 0..n {
                    sc.decal[c][j] *= sc.coords[0][j];
                }
            }
        }
        if o.normal_space == NormalSpace::TangentPerPixel {
            self.decode_per_pixel(batch, sc, n);
        }
        lighting_lanes(&o.terms, sc, object_space, n, out);
        if o.decal_alpha {
            // A blended material's pass: the decal's alpha weighs it against what is behind.
            out[3][..n].copy_from_slice(&sc.decal[3][..n]);
        }
    }

    fn writes_depth(&self) -> bool {
        self.program.parallax.as_ref().is_some_and(|p| p.parallax.options.write_depth || p.parallax.options.silhouettes)
    }

    fn depth<'a>(&self, sc: &'a Self::Scratch) -> Option<&'a Lanes> {
        self.writes_depth().then_some(&sc.depth)
    }
}
