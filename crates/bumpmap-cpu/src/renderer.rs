//! The CPU backend's entry point: a technique's passes (`bumpmap_core::technique`) executed in
//! order on the emulated pipeline.
//!
//! [`CpuRenderer`] keeps what is worth keeping between frames: the rasterizer's vectors, the
//! texture units' copies of the scene's textures (keyed by the scene's `Arc`s) and the
//! normalization cube maps. It decides nothing about what is drawn.

use std::sync::Arc;

use bumpmap_core::shading::RoughnessTextures;
use bumpmap_core::technique::{Binding as CoreBinding, Gloss, Normalize, Program, SpecularFilter, Technique};
use bumpmap_core::{Scene, vertex::Vertex};
use bumpmap_math::{Encoding, LeanMips, NormalizationCubeMap, Rgba8Mips};

use bumpmap_core::cache::ArcCache;

use crate::combiners::Combiners;
use crate::error::CpuError;
use crate::fixed_function::{Binding, FixedFunction, TextureUnit};
use crate::framebuffer::Framebuffer;
use crate::raster::{DrawState, Rasterizer};
use crate::single_pass::SinglePass;
use crate::texture::{MomentTexture, Texture2d, TextureCube};

/// Renders scenes on the CPU pipeline, reusing its buffers and textures from frame to frame.
#[derive(Debug, Default)]
pub struct CpuRenderer {
    raster: Rasterizer,
    textures: ArcCache<Rgba8Mips, Arc<Texture2d>>,
    /// LEAN moments, keyed by the normal map they were made from.
    moments: ArcCache<Rgba8Mips, Arc<MomentTexture>>,
    /// Roughness maps made for the roughness-map filter.
    roughness: RoughnessTextures,
    cubes: Vec<((usize, Encoding), Arc<TextureCube>)>,
}

impl CpuRenderer {
    /// A renderer with nothing cached.
    pub fn new() -> Self {
        Self::default()
    }

    /// Clears `fb` (black, alpha 0, depth 1) and draws `technique`'s passes of `scene`.
    /// `on_snapshot` sees the framebuffer after each pass that has a snapshot name (the first
    /// light's passes of the three-pass technique, Kilgard Figure 12).
    pub fn render(
        &mut self,
        scene: &Scene,
        technique: &Technique,
        fb: &mut Framebuffer,
        mut on_snapshot: impl FnMut(&str, &Framebuffer),
    ) -> Result<(), CpuError> {
        let passes = technique.passes(scene)?;
        // What an earlier scene used and nothing holds any more.
        self.textures.evict_unused();
        self.moments.evict_unused();
        self.roughness.evict_unused();
        fb.clear([0, 0, 0, 0], 1.0);
        let aspect = fb.width as f32 / fb.height as f32;
        // The vertex stage of the (object, light) the last pass drew: the passes of one light
        // share it.
        let mut vertices: Option<((usize, usize), Vec<Vertex>)> = None;
        for pass in &passes {
            let key = (pass.object, pass.light);
            if vertices.as_ref().map(|v| v.0) != Some(key) {
                let v = scene.vertices(&scene.objects[pass.object], &scene.lights[pass.light], aspect)?;
                vertices = Some((key, v));
            }
            let verts = &vertices.as_ref().expect("filled above").1;
            let indices = &scene.objects[pass.object].mesh.indices;
            let state = DrawState::new(pass.state, pass.program.varyings_read());
            match &pass.program {
                Program::Combiners(program) => {
                    let units = program
                        .units
                        .iter()
                        .map(|u| Ok(TextureUnit { binding: self.binding(&u.binding)?, sampler: u.sampler }))
                        .collect::<Result<_, CpuError>>()?;
                    let combiners = Combiners::new(program.setup.clone(), program.precision)?;
                    let primary_color = program.vertex_color.then_some(bumpmap_core::vertex::var::COLOR);
                    let shader = FixedFunction { units, combiners, primary_color };
                    self.raster.draw(fb, verts, indices, &state, &shader);
                }
                Program::Lit(program) => {
                    let shader = SinglePass {
                        program,
                        cube: (program.normalize == Normalize::Cube)
                            .then(|| self.cube(program.cube_size, Encoding::Unorm)),
                        normal_map: self.texture(&program.normal_map)?,
                        moments: matches!(program.terms.specular_filter, SpecularFilter::Lean | SpecularFilter::Clean)
                            .then(|| self.moments(&program.normal_map))
                            .transpose()?,
                        roughness: match (program.terms.specular_filter, &program.roughness_map) {
                            (SpecularFilter::RoughnessMap, Some(given)) => Some(self.texture(given)?),
                            (SpecularFilter::RoughnessMap, None) => {
                                let made = self.roughness.get(&program.normal_map, program.terms.shininess);
                                Some(self.texture(&made)?)
                            }
                            _ => None,
                        },
                        decal: program.decal.as_ref().map(|d| self.texture(d)).transpose()?,
                        occlusion: program.occlusion.as_ref().map(|d| self.texture(d)).transpose()?,
                        detail: program.detail.as_ref().map(|d| self.texture(&d.map)).transpose()?,
                        gloss: match &program.gloss {
                            Gloss::Map(g) => Some(self.texture(g)?),
                            _ => None,
                        },
                        pattern: program
                            .light
                            .spot
                            .as_ref()
                            .and_then(|s| s.pattern.as_ref())
                            .map(|p| self.texture(p))
                            .transpose()?,
                    };
                    self.raster.draw(fb, verts, indices, &state, &shader);
                }
            }
            if let Some(name) = pass.snapshot {
                on_snapshot(name, fb);
            }
        }
        Ok(())
    }

    fn binding(&mut self, binding: &CoreBinding) -> Result<Binding, CpuError> {
        Ok(match binding {
            CoreBinding::TwoD { texture, s, t } => Binding::TwoD { texture: self.texture(texture)?, s: *s, t: *t },
            CoreBinding::NormalizationCube { size, encoding, r } => {
                Binding::Cube { texture: self.cube(*size, *encoding), r: *r }
            }
        })
    }

    /// The texture unit's copy of `mips`, made once per `Arc`.
    fn texture(&mut self, mips: &Arc<Rgba8Mips>) -> Result<Arc<Texture2d>, CpuError> {
        self.textures.get_or_try_make(mips, |m| Ok(Arc::new(Texture2d::try_from_mips(m)?)))
    }

    /// The LEAN moments of `normal_map`'s level 0 (unorm texels, as a material's are), made
    /// once per `Arc`.
    fn moments(&mut self, normal_map: &Arc<Rgba8Mips>) -> Result<Arc<MomentTexture>, CpuError> {
        self.moments.get_or_try_make(normal_map, |m| {
            let lean = LeanMips::from_normal_map(m, Encoding::Unorm)?;
            Ok(Arc::new(MomentTexture::try_from_mips(&lean)?))
        })
    }

    /// The normalization cube map of face size `size`, built once.
    fn cube(&mut self, size: usize, encoding: Encoding) -> Arc<TextureCube> {
        if let Some((_, c)) = self.cubes.iter().find(|(k, _)| *k == (size, encoding)) {
            return c.clone();
        }
        let c = Arc::new(TextureCube::from_normalization(&NormalizationCubeMap::new(size, encoding)));
        self.cubes.push(((size, encoding), c.clone()));
        c
    }
}

/// Renders one frame with a fresh [`CpuRenderer`] (see [`CpuRenderer::render`]).
pub fn render(scene: &Scene, technique: &Technique, fb: &mut Framebuffer) -> Result<(), CpuError> {
    CpuRenderer::new().render(scene, technique, fb, |_, _| {})
}
