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

use glam::{Vec3, Vec4};

use bumpmap_math::{Encoding, NormalizationCubeMap};

use crate::combiners::{LANES, Lanes};
use crate::error::RasterError;
use crate::framebuffer::{Blend, DepthFunc, Framebuffer};
use crate::raster::{DrawState, FragmentBatch, FragmentShader, draw};
use crate::scene::{Attenuation, NormalSpace, Scene, SceneLight, var};
use crate::texture::{Sampler, Texture2d, TextureCube, lambda_2d, sample_2d, sample_cube};

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
            let state = if i == 0 {
                DrawState { varyings: var::COUNT, ..DrawState::OPAQUE }
            } else {
                DrawState {
                    depth_func: DepthFunc::Equal,
                    depth_write: false,
                    blend: Blend::ADD,
                    varyings: var::COUNT,
                    ..DrawState::OPAQUE
                }
            };
            draw(fb, &vertices, &object.mesh.indices, &state, &shader);
        }
    }
    Ok(())
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

impl SinglePass<'_> {
    #[inline(always)]
    fn unit(&self, v: Vec3) -> Vec3 {
        match &self.cube {
            Some(cube) => sample_cube(cube, &Sampler::LINEAR_CLAMP, v, 0.0).truncate() * 2.0 - Vec3::ONE,
            None => v.normalize_or(Vec3::Z),
        }
    }
}

/// Samples a 2D texture at every live lane of a batch at `scale ⊙ (s, t)`, λ once per quad.
fn sample_lanes(tex: &Texture2d, sampler: &Sampler, batch: &FragmentBatch, scale: glam::Vec2, out: &mut [Vec4; LANES]) {
    let (s, t) = (&batch.varyings[var::S], &batch.varyings[var::T]);
    let (ks, kt) = (scale.x, scale.y);
    for q in 0..batch.quads {
        let l = 4 * q;
        if !batch.live[l..l + 4].iter().any(|&x| x) {
            continue;
        }
        let lambda =
            lambda_2d(tex, [ks * s[l], ks * s[l + 1], ks * s[l + 2]], [kt * t[l], kt * t[l + 1], kt * t[l + 2]]);
        for lane in l..l + 4 {
            if batch.live[lane] {
                out[lane] = sample_2d(tex, sampler, ks * s[lane], kt * t[lane], lambda);
            }
        }
    }
}

impl FragmentShader for SinglePass<'_> {
    type Scratch = Box<[[Vec4; LANES]; 3]>;

    fn scratch(&self) -> Self::Scratch {
        Box::new([[Vec4::ZERO; LANES]; 3])
    }

    fn shade(&self, batch: &FragmentBatch, scratch: &mut Self::Scratch, out: &mut [Lanes; 4]) {
        let o = self.options;
        let [normals, decals, gloss] = &mut **scratch;
        let (scale, object_space) = match self.normal_space {
            NormalSpace::Tangent => (glam::Vec2::ONE, false),
            NormalSpace::Object { scale } => (scale, true),
        };
        sample_lanes(&self.normal_map, &o.sampler, batch, scale, normals);
        match &self.decal {
            Some(d) => sample_lanes(d, &o.sampler, batch, glam::Vec2::ONE, decals),
            None => decals[..batch.lanes()].fill(Vec4::ONE),
        }
        match &o.gloss {
            Gloss::None => gloss[..batch.lanes()].fill(Vec4::ONE),
            Gloss::DecalAlpha => (0..batch.lanes()).for_each(|i| gloss[i] = Vec4::splat(decals[i].w)),
            Gloss::Map(g) => sample_lanes(g, &o.sampler, batch, glam::Vec2::ONE, gloss),
        }
        let whole_shininess = self.shininess == self.shininess.trunc() && self.shininess <= 64.0;
        let v3 = |slot: usize, lane: usize| {
            Vec3::new(batch.varyings[slot][lane], batch.varyings[slot + 1][lane], batch.varyings[slot + 2][lane])
        };
        for lane in 0..batch.lanes() {
            if !batch.live[lane] {
                continue;
            }
            // Eq. 14–15: the filtered normal's direction (expanded as the combiners do) and length.
            let t = normals[lane];
            let n = Vec3::new(t.x, t.y, t.z) * 2.0 - Vec3::ONE;
            let len = t.w;
            let l = self.unit(v3(var::L, lane));
            let h = match o.half_angle {
                HalfAngle::Vertex => self.unit(v3(var::H, lane)),
                HalfAngle::Fragment => {
                    let v = v3(var::V, lane).normalize_or(Vec3::Z);
                    self.unit((v3(var::L, lane).normalize_or(Vec3::Z) + v).normalize_or(Vec3::Z))
                }
            };
            // L·N and H·N with the unperturbed normal: L_z and H_z in tangent space.
            let (l_n, h_n) = if object_space {
                let ng = v3(var::N, lane).normalize_or(Vec3::Z);
                (l.dot(ng), h.dot(ng))
            } else {
                (l.z, h.z)
            };
            let s_self = match o.self_shadow {
                SelfShadow::Ramp => (8.0 * l_n).clamp(0.0, 1.0),
                SelfShadow::Step => (l_n > 0.0) as u8 as f32,
                SelfShadow::Off => 1.0,
            };
            // Dot products of the (not exactly unit) expanded vectors clamp to [−1, 1] as the
            // combiners' outputs do, so a quantized normal cannot brighten past the paper's.
            let n_dot_l = l.dot(n).clamp(-1.0, 1.0);
            let spec_gate = match o.specular_shadow {
                SpecularShadow::Kilgard => s_self * (h_n >= 0.0) as u8 as f32,
                SpecularShadow::CgTutorial => (n_dot_l > 0.0 && l_n > 0.0) as u8 as f32,
                SpecularShadow::Off => 1.0,
            };
            let mut light = self.light.attenuation.factor(batch.varyings[var::LIGHT_DISTANCE][lane]);
            if let Some(spot) = &self.light.spot {
                let cos = -(v3(var::L, lane).normalize_or(Vec3::Z)).dot(v3(var::SPOT, lane).normalize_or(Vec3::Z));
                let cutoff = spot.cutoff_degrees.to_radians().cos();
                light *= if cos >= cutoff { cos.max(0.0).powf(spot.exponent) } else { 0.0 };
                if let Some(pattern) = &spot.pattern {
                    let p = v3(var::PROJ, lane);
                    light *= if p.z > 0.0 {
                        sample_2d(pattern, &Sampler::LINEAR_CLAMP, p.x / p.z, p.y / p.z, 0.0).x
                    } else {
                        0.0
                    };
                }
            }
            // Eq. 11 with the filtered (shortened) normal, Eq. 16 with the renormalized one.
            let diffuse = (self.ambient + self.diffuse * (light * s_self * n_dot_l.max(0.0) * len)).min(Vec3::ONE);
            let h_dot_n = h.dot(n).clamp(0.0, 1.0);
            // Whole exponents (the paper's 8 among them) by repeated multiplication.
            let power =
                if whole_shininess { h_dot_n.powi(self.shininess as i32) } else { h_dot_n.powf(self.shininess) };
            let specular = self.specular * (light * spec_gate * gloss[lane].x * power);
            let d = decals[lane];
            let c = Vec3::new(d.x, d.y, d.z) * diffuse + specular;
            out[0][lane] = c.x;
            out[1][lane] = c.y;
            out[2][lane] = c.z;
            out[3][lane] = 1.0;
        }
    }
}
