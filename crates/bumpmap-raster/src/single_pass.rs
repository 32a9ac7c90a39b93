//! One float pass per light (Kilgard §6's prediction; the Cg Tutorial's fragment programs):
//! the whole lighting model of the papers evaluated per fragment.
//!
//! Per light: the normal map's N' and length |N'| (Eq. 14–15, the same mip chain as the three
//! passes), L and H normalized per fragment by math or by the normalization cube map, Eq. 11's
//! diffuse with the Eq. 12 ramp (or a step, or none), Eq. 16's specular with any shininess,
//! gated as the paper's mux does or as the Cg Tutorial §8.5 suggests, a gloss map, light and
//! material colours, attenuation, a spotlight cone and a projected spotlight pattern. The first
//! light's pass draws with depth LESS and adds the ambient term; each further light adds its
//! own pass with `glBlendFunc(GL_ONE, GL_ONE)` and depth EQUAL, so the framebuffer is 8-bit
//! between lights as on the hardware.

use std::sync::Arc;

use glam::Vec3;

use bumpmap_math::{Encoding, NormalizationCubeMap};

use crate::combiners::{LANES, Lanes};
use crate::error::RasterError;
use crate::fixed_function::pack_2d_coords;
use crate::framebuffer::{Blend, DepthFunc, Framebuffer};
use crate::lane_math::{clamp_lo, max_lo, min_hi};
use crate::raster::{DrawState, FragmentBatch, FragmentShader, draw};
use crate::scene::{Attenuation, NormalSpace, Scene, SceneLight, var};
use crate::texture::{Sampler, Texture2d, TextureCube, sample_2d, sample_2d_lanes, sample_cube_lanes};

/// How the interpolated L and H are renormalized per fragment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Normalize {
    /// `normalize()` in float.
    #[default]
    Math,
    /// A lookup in the normalization cube map, expanded as `2x − 1` (the paper's way).
    Cube,
}

/// The geometric self-shadowing factor of Eq. 11.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SelfShadow {
    /// Eq. 12: `clamp(8·L_z, 0, 1)`.
    #[default]
    Ramp,
    /// 1 where `L_z > 0`, else 0.
    Step,
    /// Always 1 (Figure 14, left).
    Off,
}

/// Where the half-angle vector comes from (Cg Tutorial §8.1.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum HalfAngle {
    /// Computed per vertex (Appendix C) and interpolated.
    #[default]
    Vertex,
    /// `normalize(L̂ + V̂)` from the interpolated L and V.
    Fragment,
}

/// Which geometric self-shadowing the specular term gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SpecularShadow {
    /// The paper's: times s_self, and zero where `H_z < 0` (Appendix H's mux).
    #[default]
    Kilgard,
    /// Cg Tutorial §8.5: zero unless `N'·L > 0` and `L_z > 0`.
    CgTutorial,
    /// None.
    Off,
}

/// Where the gloss (specular scale) comes from (Cg Tutorial §8.5.2).
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Gloss {
    #[default]
    None,
    /// The decal's alpha channel.
    DecalAlpha,
    /// The red channel of a gloss map with the decal's texture coordinates.
    Map(Arc<Texture2d>),
}

/// Options of the single-pass technique. The defaults are the paper's settings except for the
/// math normalization.
#[derive(Clone, Debug, PartialEq)]
pub struct SinglePassOptions {
    pub sampler: Sampler,
    pub normalize: Normalize,
    pub self_shadow: SelfShadow,
    pub half_angle: HalfAngle,
    pub specular_shadow: SpecularShadow,
    pub gloss: Gloss,
    pub cube_size: usize,
}

impl Default for SinglePassOptions {
    fn default() -> Self {
        Self {
            sampler: Sampler::TRILINEAR_REPEAT,
            normalize: Normalize::Math,
            self_shadow: SelfShadow::Ramp,
            half_angle: HalfAngle::Vertex,
            specular_shadow: SpecularShadow::Kilgard,
            gloss: Gloss::None,
            cube_size: 32,
        }
    }
}

/// Checks what the options and the scene's lights and materials allow.
pub fn validate(scene: &Scene, options: &SinglePassOptions) -> Result<(), RasterError> {
    let bad = |m: String| Err(RasterError::Scene(m));
    for object in &scene.objects {
        let m = &object.material;
        if !(m.shininess > 0.0 && m.shininess.is_finite()) {
            return bad(format!("shininess must be a positive number, got {}", m.shininess));
        }
        if let Gloss::Map(g) = &options.gloss {
            match &m.decal {
                Some(d) if (d.width(), d.height()) != (g.width(), g.height()) => {
                    return bad(format!(
                        "the gloss map is {}x{} but the decal is {}x{}: they share texture coordinates and must be the same size",
                        g.width(),
                        g.height(),
                        d.width(),
                        d.height()
                    ));
                }
                _ => {}
            }
        }
        if options.gloss == Gloss::DecalAlpha && m.decal.is_none() {
            return bad("--gloss decal-alpha needs a decal".into());
        }
    }
    for light in &scene.lights {
        validate_light(light)?;
    }
    Ok(())
}

/// Checks one light's parameters.
pub fn validate_light(light: &SceneLight) -> Result<(), RasterError> {
    let bad = |m: String| Err(RasterError::Scene(m));
    if !light.color.is_finite() || light.color.min_element() < 0.0 {
        return bad(format!("light colour must be finite and not negative, got {}", light.color));
    }
    match light.attenuation {
        Attenuation::Polynomial { constant, linear, quadratic } => {
            if [constant, linear, quadratic].iter().any(|c| !(c.is_finite() && *c >= 0.0))
                || constant + linear + quadratic == 0.0
            {
                return bad(format!(
                    "attenuation coefficients must be ≥ 0 and not all zero, got {constant},{linear},{quadratic}"
                ));
            }
        }
        Attenuation::Exponential { density } | Attenuation::ExponentialSquared { density } => {
            if !(density.is_finite() && density >= 0.0) {
                return bad(format!("attenuation density must be ≥ 0, got {density}"));
            }
        }
        Attenuation::None => {}
    }
    if let Some(spot) = &light.spot {
        if !(spot.cutoff_degrees > 0.0 && spot.cutoff_degrees < 90.0) {
            return bad(format!("spotlight cutoff must be in (0, 90) degrees, got {}", spot.cutoff_degrees));
        }
        if !(spot.exponent.is_finite() && spot.exponent >= 0.0) {
            return bad(format!("spotlight exponent must be ≥ 0, got {}", spot.exponent));
        }
        if !(spot.direction.length() > 0.0 && spot.direction.is_finite()) {
            return bad("spotlight direction must be a non-zero vector".into());
        }
        if matches!(light.light, bumpmap_math::lighting::Light::Directional(_)) {
            return bad("a spotlight needs a positional light".into());
        }
    }
    Ok(())
}

/// Renders `scene` into `fb` (cleared first).
pub fn render(scene: &Scene, options: &SinglePassOptions, fb: &mut Framebuffer) -> Result<(), RasterError> {
    validate(scene, options)?;
    fb.clear([0, 0, 0, 0], 1.0);
    let cube = (options.normalize == Normalize::Cube).then(|| {
        Arc::new(TextureCube::from_normalization(&NormalizationCubeMap::new(options.cube_size, Encoding::Unorm)))
    });
    let aspect = fb.width as f32 / fb.height as f32;
    for object in &scene.objects {
        for (i, light) in scene.lights.iter().enumerate() {
            let vertices = scene.vertices(object, light, aspect);
            let m = &object.material;
            let shader = SinglePass {
                options,
                cube: cube.clone(),
                normal_map: m.normal_map.clone(),
                normal_space: m.normal_space,
                decal: m.decal.clone(),
                ambient: if i == 0 { m.ambient } else { Vec3::ZERO },
                diffuse: m.diffuse * light.color,
                specular: m.specular * light.color,
                shininess: m.shininess,
                light: light.clone(),
            };
            let varyings = varyings_read(options, light, m.normal_space);
            let state = if i == 0 {
                DrawState { varyings, ..DrawState::OPAQUE }
            } else {
                DrawState {
                    depth_func: DepthFunc::Equal,
                    depth_write: false,
                    blend: Blend::ADD,
                    varyings,
                    ..DrawState::OPAQUE
                }
            };
            draw(fb, &vertices, &object.mesh.indices, &state, &shader);
        }
    }
    Ok(())
}

/// How many varyings (from slot 0) the fragment program reads: the rest are not interpolated.
fn varyings_read(options: &SinglePassOptions, light: &SceneLight, space: NormalSpace) -> usize {
    if matches!(space, NormalSpace::Object { .. }) {
        var::N + 3
    } else if light.spot.is_some() {
        var::PROJ + 3
    } else if light.attenuation != Attenuation::None {
        var::LIGHT_DISTANCE + 1
    } else if options.half_angle == HalfAngle::Fragment {
        var::V + 3
    } else {
        var::H + 3
    }
}

/// The per-light fragment program.
struct SinglePass<'a> {
    options: &'a SinglePassOptions,
    cube: Option<Arc<TextureCube>>,
    normal_map: Arc<Texture2d>,
    normal_space: NormalSpace,
    decal: Option<Arc<Texture2d>>,
    ambient: Vec3,
    diffuse: Vec3,
    specular: Vec3,
    shininess: f32,
    light: SceneLight,
}

/// Per-thread working memory: every per-fragment quantity as packed lanes (lane j is the j-th
/// live fragment of the batch), so each step below is one loop over contiguous arrays.
pub struct Scratch {
    /// s, t, λ of the lookup being made.
    coords: [Lanes; 3],
    /// The filtered normal map (RGB range-compressed, A = |N'|), the decal, the gloss texture.
    normal: [Lanes; 4],
    decal: [Lanes; 4],
    gloss: [Lanes; 4],
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
    /// Eq. 12's s_self, N'·L, H·N' (then its power), the specular gate, and a power's partial
    /// product.
    s_self: Lanes,
    n_dot_l: Lanes,
    h_dot_n: Lanes,
    gate: Lanes,
    acc: Lanes,
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
        }
        let out = match which {
            Tex::Normal => &mut sc.normal,
            Tex::Decal => &mut sc.decal,
            Tex::Gloss => &mut sc.gloss,
        };
        let [s, t, lambda] = &sc.coords;
        sample_2d_lanes(tex, &self.options.sampler, s, t, lambda, n, out);
    }

    /// Attenuation and the spotlight's cone and pattern, per live lane.
    fn light_factor(&self, batch: &FragmentBatch, sc: &mut Scratch, n: usize) {
        let live = batch.live();
        match self.light.attenuation {
            Attenuation::None => sc.light[..n].fill(1.0),
            attenuation => {
                batch.pack(var::LIGHT_DISTANCE, &mut sc.light);
                sc.light[..n].iter_mut().for_each(|d| *d = attenuation.factor(*d));
            }
        }
        let Some(spot) = &self.light.spot else { return };
        let v3 = |slot: usize, lane: usize| {
            Vec3::new(batch.varyings[slot][lane], batch.varyings[slot + 1][lane], batch.varyings[slot + 2][lane])
        };
        let cutoff = spot.cutoff_degrees.to_radians().cos();
        for (j, &lane) in live.iter().enumerate() {
            let lane = lane as usize;
            let cos = -(v3(var::L, lane).normalize_or(Vec3::Z)).dot(v3(var::SPOT, lane).normalize_or(Vec3::Z));
            let mut f = if cos >= cutoff { cos.max(0.0).powf(spot.exponent) } else { 0.0 };
            if let Some(pattern) = &spot.pattern {
                let p = v3(var::PROJ, lane);
                f *= if p.z > 0.0 {
                    sample_2d(pattern, &Sampler::LINEAR_CLAMP, p.x / p.z, p.y / p.z, 0.0).x
                } else {
                    0.0
                };
            }
            sc.light[j] *= f;
        }
    }
}

/// Which texture [`SinglePass::sample`] fills.
#[derive(Clone, Copy)]
enum Tex {
    Normal,
    Decal,
    Gloss,
}

/// `acc ← x^k` for a whole k ≥ 0 by binary powering, lanes `0..n` (the order of compiler-rt's
/// `__powisf2`, so the result is `powi`'s); `x` is used up.
fn powi_lanes(x: &mut Lanes, k: u32, n: usize, acc: &mut Lanes) {
    acc[..n].fill(1.0);
    let mut e = k;
    loop {
        if e & 1 == 1 {
            for j in 0..n {
                acc[j] *= x[j];
            }
        }
        e >>= 1;
        if e == 0 {
            break;
        }
        for j in 0..n {
            x[j] *= x[j];
        }
    }
}

impl FragmentShader for SinglePass<'_> {
    type Scratch = Box<Scratch>;

    fn scratch(&self) -> Self::Scratch {
        let z = [0.0; LANES];
        Box::new(Scratch {
            coords: [z; 3],
            normal: [z; 4],
            decal: [z; 4],
            gloss: [z; 4],
            l: [z; 3],
            h: [z; 3],
            v: [z; 3],
            w: [z; 3],
            cube: [z; 4],
            l_n: z,
            h_n: z,
            light: z,
            s_self: z,
            n_dot_l: z,
            h_dot_n: z,
            gate: z,
            acc: z,
        })
    }

    fn shade(&self, batch: &FragmentBatch, sc: &mut Self::Scratch, out: &mut [Lanes; 4]) {
        let o = self.options;
        let live_n = batch.live().len();
        // Every loop runs over whole 8-lane vectors; the lanes past live_n are never written out.
        let n = live_n.next_multiple_of(8);
        let (scale, object_space) = match self.normal_space {
            NormalSpace::Tangent => ([1.0, 1.0], false),
            NormalSpace::Object { scale } => ([scale.x, scale.y], true),
        };
        let size = |t: &Texture2d| (t.width(), t.height());
        self.sample(&self.normal_map, batch, scale, sc, live_n, Tex::Normal, false);
        let mut last = (size(&self.normal_map), scale);
        match &self.decal {
            Some(d) => {
                self.sample(d, batch, [1.0, 1.0], sc, live_n, Tex::Decal, last == (size(d), [1.0, 1.0]));
                last = (size(d), [1.0, 1.0]);
            }
            None => sc.decal.iter_mut().for_each(|c| c.fill(1.0)),
        }
        match &o.gloss {
            Gloss::None => sc.gloss[0].fill(1.0),
            Gloss::DecalAlpha => sc.gloss[0] = sc.decal[3],
            Gloss::Map(g) => self.sample(g, batch, [1.0, 1.0], sc, live_n, Tex::Gloss, last == (size(g), [1.0, 1.0])),
        }
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
        let Scratch { normal, decal, gloss, l, h, l_n, h_n, light, s_self, n_dot_l, h_dot_n, gate, acc, .. } =
            &mut **sc;
        let (l_n, h_n) = if object_space { (&*l_n, &*h_n) } else { (&l[2], &h[2]) };
        match o.self_shadow {
            SelfShadow::Ramp => (0..n).for_each(|j| s_self[j] = clamp_lo(8.0 * l_n[j], 0.0, 1.0)),
            SelfShadow::Step => (0..n).for_each(|j| s_self[j] = (l_n[j] > 0.0) as u8 as f32),
            SelfShadow::Off => s_self.fill(1.0),
        }
        // Eq. 14–15: the filtered normal's direction, expanded as the combiners do. Dot
        // products of the (not exactly unit) expanded vectors clamp to [−1, 1] as the
        // combiners' outputs do, so a quantized normal cannot brighten past the paper's.
        for j in 0..n {
            let nv = [normal[0][j] * 2.0 - 1.0, normal[1][j] * 2.0 - 1.0, normal[2][j] * 2.0 - 1.0];
            n_dot_l[j] = clamp_lo(l[0][j] * nv[0] + l[1][j] * nv[1] + l[2][j] * nv[2], -1.0, 1.0);
            h_dot_n[j] = clamp_lo(h[0][j] * nv[0] + h[1][j] * nv[1] + h[2][j] * nv[2], 0.0, 1.0);
        }
        match o.specular_shadow {
            SpecularShadow::Kilgard => (0..n).for_each(|j| gate[j] = s_self[j] * (h_n[j] >= 0.0) as u8 as f32),
            SpecularShadow::CgTutorial => {
                (0..n).for_each(|j| gate[j] = (n_dot_l[j] > 0.0 && l_n[j] > 0.0) as u8 as f32)
            }
            SpecularShadow::Off => gate.fill(1.0),
        }
        // Whole exponents (the paper's 8 among them) by repeated multiplication.
        let power: &Lanes = if self.shininess == self.shininess.trunc() && self.shininess <= 64.0 {
            powi_lanes(h_dot_n, self.shininess as u32, n, acc);
            acc
        } else {
            h_dot_n[..n].iter_mut().for_each(|x| *x = x.powf(self.shininess));
            h_dot_n
        };
        // Eq. 11 with the filtered (shortened) normal, Eq. 16 with the renormalized one.
        let (ka, kd, ks) = (self.ambient, self.diffuse, self.specular);
        for c in 0..3 {
            for j in 0..n {
                let diffuse =
                    min_hi(ka[c] + kd[c] * (light[j] * s_self[j] * max_lo(n_dot_l[j], 0.0) * normal[3][j]), 1.0);
                let specular = ks[c] * (light[j] * gate[j] * gloss[0][j] * power[j]);
                out[c][j] = decal[c][j] * diffuse + specular;
            }
        }
        out[3][..n].fill(1.0);
    }
}
