//! One renderer over both backends: a scene and a named technique in, an RGBA8 image out, on
//! the emulated GeForce (CPU) or through wgpu (GPU) — or the reference, which samples the exact
//! surface on the CPU whichever backend is chosen.
//!
//! [`Prepared`] splits the work in two for callers that draw many frames of one scene (a
//! benchmark, a viewer): the maps are made once, the light or the camera may then move between
//! frames. What this module does not do: decide what a technique is (the catalogue,
//! `bumpmap_core::catalogue`) or read files (`crate::assets`).

use std::sync::Arc;

use bumpmap_core::technique::ReferenceOptions;
use bumpmap_core::{BumpSource, CoreError, Scene, SceneSpec, Technique, TechniqueName, TechniqueOptions};
use bumpmap_cpu::{CpuError, CpuRenderer, Framebuffer};
#[cfg(feature = "gpu")]
use bumpmap_gpu::GpuRenderer;
use bumpmap_math::{HeightMips, Rgba8Image};

use crate::error::Error;

/// Which backend a [`Renderer`] should draw with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum BackendChoice {
    /// The emulated GeForce 256 pipeline on every core.
    Cpu,
    /// wgpu on the first adapter found (Vulkan, Metal, DX12 or GL; Mesa's lavapipe on a machine
    /// without a GPU); no adapter is an error.
    Gpu,
    /// The GPU when an adapter exists, else the CPU, with the reason
    /// ([`Renderer::fallback_reason`]).
    #[default]
    Auto,
}

bumpmap_math::named!(BackendChoice {
    Cpu => "cpu": "the emulated GeForce pipeline on the CPU (all cores)",
    Gpu => "gpu": "wgpu on whatever adapter exists (Vulkan, Metal, DX12, GL; lavapipe without a GPU)",
    Auto => "auto": "the GPU when an adapter exists, else the CPU",
});

/// The backend a [`Renderer`] has.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Backend {
    /// The emulated GeForce 256 on the CPU.
    Cpu,
    /// wgpu.
    Gpu,
}

impl Backend {
    /// `cpu` or `gpu`.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Cpu => "cpu",
            Backend::Gpu => "gpu",
        }
    }
}

/// The backend's state, kept between frames so buffers, textures and pipelines are reused.
enum Inner {
    Cpu {
        renderer: Box<CpuRenderer>,
        framebuffer: Option<Framebuffer>,
    },
    #[cfg(feature = "gpu")]
    Gpu(Box<GpuRenderer>),
}

/// Reports a reference's progress: tiles done and in all, from any thread.
pub type Progress = Arc<dyn Fn(usize, usize) + Send + Sync>;

/// A scene with the maps one named technique reads, and the technique that draws it: made once,
/// drawn as often as wanted. Its scene may change between draws (a light orbiting, a camera
/// moving); its maps stay.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// The technique's name.
    pub name: TechniqueName,
    /// The scene with the technique's maps.
    pub scene: Scene,
    /// How it is drawn.
    pub technique: Technique,
}

impl Prepared {
    /// Builds `spec` for `name` with `options`: checks the technique's requirements, makes its
    /// maps and its technique.
    ///
    /// Refuses, before any of them is made, maps that will not fit together
    /// ([`Prepared::bytes_needed`]).
    pub fn new(spec: &SceneSpec, name: TechniqueName, options: &TechniqueOptions) -> Result<Self, Error> {
        Self::new_told(spec, name, options, &|_, _| {})
    }

    /// [`Prepared::new`], telling `progress(rows done, rows)` while the horizon map is made where
    /// the technique reads one (`horizon`, a march's horizon shadow or occlusion) and the scene's
    /// heights are a height field: the long part of preparing (minutes for 8192²). Other
    /// techniques prepare without a word.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use std::sync::atomic::{AtomicUsize, Ordering};
    /// use bumpmap::{BackendChoice, BumpSource, HeightPreset, Prepared, Renderer, SceneKind, SceneSpec};
    /// use bumpmap::{TechniqueName, TechniqueOptions};
    ///
    /// let mut spec = SceneSpec::new(SceneKind::Wall);
    /// spec.params.bumps = BumpSource::Heights(Arc::new(HeightPreset::Bricks.render(64, 64)));
    /// let (options, rows) = (TechniqueOptions::default(), AtomicUsize::new(0));
    /// let told = Prepared::new_told(&spec, TechniqueName::Horizon, &options, &|done, total| {
    ///     assert!(done <= total && total == 64);
    ///     rows.fetch_max(done, Ordering::Relaxed);
    /// })
    /// .unwrap();
    /// assert_eq!(rows.load(Ordering::Relaxed), 64, "every row of the horizon map told");
    /// // The same maps as prepared without a word: the same frame.
    /// let quiet = Prepared::new(&spec, TechniqueName::Horizon, &options).unwrap();
    /// let mut renderer = Renderer::new(BackendChoice::Cpu).unwrap();
    /// let frame = renderer.draw(&told, 48, 48).unwrap();
    /// assert_eq!(frame.texels, renderer.draw(&quiet, 48, 48).unwrap().texels);
    /// // A technique that reads no horizon map tells nothing.
    /// Prepared::new_told(&spec, TechniqueName::Pom, &options, &|_, _| panic!("told")).unwrap();
    /// ```
    pub fn new_told(
        spec: &SceneSpec,
        name: TechniqueName,
        options: &TechniqueOptions,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Self, Error> {
        bumpmap_math::buffer::ensure_available(Self::bytes_needed(spec, name), "making its maps")
            .map_err(|source| Error::OutOfMemory { what: format!("preparing {name}"), source })?;
        let reads_horizons = matches!(
            name.technique(options),
            Technique::SinglePass(bumpmap_core::technique::SinglePassOptions { parallax: Some(p), .. })
                if p.reads_horizons()
        );
        let params = &spec.params;
        let (scene, technique) = match &params.bumps {
            // The heights the scene would make, made here with their horizon map told (one
            // surface's: a model's parts make their own, untold).
            BumpSource::Heights(field)
                if reads_horizons
                    && params.height_mips.is_none()
                    && params.horizon_map.is_none()
                    && params.parts.is_none() =>
            {
                let heights = HeightMips::from_field(field).map_err(CoreError::from)?;
                heights.horizons_told(progress).map_err(CoreError::from)?;
                let mut spec = spec.clone();
                spec.params.height_mips = Some(Arc::new(heights));
                name.prepare(&spec, options)?
            }
            _ => name.prepare(spec, options)?,
        };
        Ok(Self { name, scene, technique })
    }

    /// What preparing `spec` for `name` asks for, in bytes: the normal map and its mips made
    /// from heights, or a given map's copy in the scene (4/3 of level 0's RGBA8), a texture
    /// unit's copy of it (and of the height
    /// map, for embossing), the heights and their bounds for the techniques that march them, and
    /// a tessellation's mesh and vertex-stage output. Maps already loaded are not counted.
    /// Within about 5% of the peaks measured in BENCHMARKS.md; each buffer is also asked for
    /// fallibly, so an estimate too low still ends in an error rather than an abort.
    pub fn bytes_needed(spec: &SceneSpec, name: TechniqueName) -> u64 {
        let (w, h) = spec.params.bumps.size();
        // Every bump source: the scene's, and a model's parts' own.
        let texels = spec.params.bump_sources().map(|b| b.size().0 as u64 * b.size().1 as u64).sum::<u64>() * 4 / 3;
        let embossed = matches!(name, TechniqueName::Emboss | TechniqueName::EmbossUnforced);
        // Made from heights, or copied from a map the spec shares into the scene's material.
        let mut bytes = texels * 4;
        if !name.is_reference() {
            bytes += bumpmap_cpu::texture_unit_bytes(texels);
        }
        if name.parallax_method().is_some() || name == TechniqueName::ReferenceDisplaced {
            // Heights as geometry: the heights and their bounds, every level (a given file's are
            // already loaded, but a texture unit or the GPU reads them as they are).
            bytes += bumpmap_math::HeightMips::bytes_for(w, h);
        }
        if embossed {
            bytes += texels * 4 + bumpmap_cpu::texture_unit_bytes(texels);
        }
        if let (Some(decal), false) = (&spec.params.decal, name.is_reference()) {
            let level0 = &decal.levels()[0];
            bytes += bumpmap_cpu::texture_unit_bytes((level0.width as u64 * level0.height as u64) * 4 / 3);
        }
        if let Some((u, v)) = spec.params.tessellation {
            let vertices = (u as u64 + 1) * (v as u64 + 1);
            let per_vertex = (std::mem::size_of::<bumpmap_core::vertex::Vertex>() + 48) as u64;
            bytes += vertices * per_vertex + u as u64 * v as u64 * 24;
        }
        bytes
    }
}

/// What sees the framebuffer after each named pass ([`Renderer::draw_scene`]).
pub type OnPass<'a> = &'a mut dyn FnMut(&str, &Rgba8Image);

/// Draws scenes on one backend.
///
/// ```
/// use bumpmap::{BackendChoice, Renderer, SceneSpec, TechniqueName};
///
/// let mut renderer = Renderer::new(BackendChoice::Cpu)?;
/// let image = renderer.render(&SceneSpec::default(), TechniqueName::SinglePass, 64, 48)?;
/// assert_eq!((image.width, image.height), (64, 48));
/// # Ok::<(), bumpmap::Error>(())
/// ```
pub struct Renderer {
    inner: Inner,
    fallback: Option<String>,
    progress: Option<Progress>,
}

impl Renderer {
    /// Opens the backend `choice` names. [`BackendChoice::Gpu`] without an adapter is an error;
    /// [`BackendChoice::Auto`] falls back to the CPU and keeps the reason.
    pub fn new(choice: BackendChoice) -> Result<Self, Error> {
        let cpu = || Inner::Cpu { renderer: Box::new(CpuRenderer::new()), framebuffer: None };
        #[cfg(feature = "gpu")]
        let (inner, fallback) = match choice {
            BackendChoice::Cpu => (cpu(), None),
            BackendChoice::Gpu => (Inner::Gpu(Box::new(GpuRenderer::new()?)), None),
            BackendChoice::Auto => match GpuRenderer::new() {
                Ok(gpu) => (Inner::Gpu(Box::new(gpu)), None),
                Err(e) => (cpu(), Some(e.to_string())),
            },
        };
        #[cfg(not(feature = "gpu"))]
        let (inner, fallback) = match choice {
            BackendChoice::Cpu => (cpu(), None),
            BackendChoice::Gpu => return Err(Error::NoGpuBackend),
            BackendChoice::Auto => (cpu(), Some(Error::NoGpuBackend.to_string())),
        };
        Ok(Self { inner, fallback, progress: None })
    }

    /// The backend in use.
    pub fn backend(&self) -> Backend {
        match self.inner {
            Inner::Cpu { .. } => Backend::Cpu,
            #[cfg(feature = "gpu")]
            Inner::Gpu(_) => Backend::Gpu,
        }
    }

    /// The backend in words: `cpu, 2 threads` or `gpu: llvmpipe (LLVM 15.0.7, 256 bits) (Vulkan)`.
    pub fn describe(&self) -> String {
        match &self.inner {
            Inner::Cpu { .. } => format!("cpu, {} threads", rayon::current_num_threads()),
            #[cfg(feature = "gpu")]
            Inner::Gpu(g) => format!("gpu: {}", g.adapter_name()),
        }
    }

    /// Why [`BackendChoice::Auto`] drew on the CPU (no adapter, or one that would not open).
    pub fn fallback_reason(&self) -> Option<&str> {
        self.fallback.as_deref()
    }

    /// Calls `progress` as the reference's tiles finish (`None`: no reports).
    pub fn set_reference_progress(&mut self, progress: Option<Progress>) {
        self.progress = progress;
    }

    /// Refuses a framebuffer no backend accepts (empty, or more than [`bumpmap_cpu::MAX_PIXELS`]),
    /// before any work.
    pub fn check_size(width: usize, height: usize) -> Result<(), Error> {
        let max_pixels = bumpmap_cpu::MAX_PIXELS;
        if width == 0 || height == 0 || width.saturating_mul(height) > max_pixels {
            return Err(Error::Cpu(CpuError::FramebufferSize { width, height, max_pixels }));
        }
        Ok(())
    }

    /// Renders `spec` with `technique` and its default options at `width`×`height`.
    pub fn render(
        &mut self,
        spec: &SceneSpec,
        technique: TechniqueName,
        width: usize,
        height: usize,
    ) -> Result<Rgba8Image, Error> {
        let prepared = Prepared::new(spec, technique, &TechniqueOptions::default())?;
        self.draw(&prepared, width, height)
    }

    /// Draws a prepared scene: the image, row 0 the top of the picture (alpha is whatever the
    /// technique left there: the three-pass technique's s_self, not coverage).
    pub fn draw(&mut self, prepared: &Prepared, width: usize, height: usize) -> Result<Rgba8Image, Error> {
        self.draw_scene(&prepared.scene, &prepared.technique, width, height, None)
    }

    /// Draws `technique`'s passes of `scene` (or the reference); with `on_pass`, calls it with
    /// the framebuffer after each pass that has a name (Kilgard Figure 12: `decal`, `diffuse`,
    /// `specular`, once per object; the reference has no passes). What [`Renderer::draw`] does
    /// with a [`Prepared`]; for a scene and technique made by hand. Without `on_pass` no pass
    /// image is made (the GPU records the frame in one go).
    pub fn draw_scene(
        &mut self,
        scene: &Scene,
        technique: &Technique,
        width: usize,
        height: usize,
        mut on_pass: Option<OnPass<'_>>,
    ) -> Result<Rgba8Image, Error> {
        Self::check_size(width, height)?;
        if let Technique::Reference(options) = technique {
            return self.reference(scene, options, width, height);
        }
        match &mut self.inner {
            Inner::Cpu { renderer, framebuffer } => {
                let fb = framebuffer_of(framebuffer, width, height)?;
                renderer.render(scene, technique, fb, |name, fb| {
                    if let Some(f) = on_pass.as_mut() {
                        f(name, &Rgba8Image::new(fb.width, fb.height, fb.to_rgba8()));
                    }
                })?;
                Ok(Rgba8Image::new(width, height, fb.to_rgba8()))
            }
            #[cfg(feature = "gpu")]
            Inner::Gpu(g) => Ok(match on_pass {
                Some(f) => g.render(scene, technique, width, height, f)?,
                None => g.render_frame(scene, technique, width, height)?,
            }),
        }
    }

    /// Draws a frame and waits for it without making an image: what a benchmark times (the
    /// GPU's `glFinish`; the CPU's framebuffer is left as it is).
    pub fn draw_unread(&mut self, prepared: &Prepared, width: usize, height: usize) -> Result<(), Error> {
        Self::check_size(width, height)?;
        let (scene, technique) = (&prepared.scene, &prepared.technique);
        if let Technique::Reference(options) = technique {
            return self.reference(scene, options, width, height).map(|_| ());
        }
        match &mut self.inner {
            Inner::Cpu { renderer, framebuffer } => {
                let fb = framebuffer_of(framebuffer, width, height)?;
                Ok(renderer.render(scene, technique, fb, |_, _| {})?)
            }
            #[cfg(feature = "gpu")]
            Inner::Gpu(g) => Ok(g.draw(scene, technique, width, height)?),
        }
    }

    /// The reference at 8 bits; `bumpmap_reference::render` gives it in float.
    fn reference(
        &self,
        scene: &Scene,
        options: &ReferenceOptions,
        width: usize,
        height: usize,
    ) -> Result<Rgba8Image, Error> {
        let progress = self.progress.clone();
        let report = move |done: usize, total: usize| {
            if let Some(p) = &progress {
                p(done, total);
            }
        };
        Ok(bumpmap_reference::render(scene, width, height, options, &report)?.to_rgba8())
    }
}

/// A window the GPU backend draws into (a swap chain): frames go to the screen without coming
/// back to the CPU. Made by [`Renderer::window_surface`].
#[cfg(feature = "gpu")]
pub struct WindowSurface(bumpmap_gpu::WindowSurface);

#[cfg(feature = "gpu")]
impl WindowSurface {
    /// The size frames are drawn at.
    pub fn size(&self) -> (usize, usize) {
        let (w, h) = self.0.size();
        (w as usize, h as usize)
    }
}

#[cfg(feature = "gpu")]
impl Renderer {
    /// A surface on `window` (a winit window, say, behind an `Arc`) for frames of
    /// `width`×`height`, on the GPU backend; `None` on the CPU's, whose frames a caller shows
    /// itself (with softbuffer, say).
    pub fn window_surface(
        &self,
        window: impl bumpmap_gpu::DisplayAndWindowHandle + 'static,
        width: usize,
        height: usize,
    ) -> Result<Option<WindowSurface>, Error> {
        match &self.inner {
            Inner::Cpu { .. } => Ok(None),
            Inner::Gpu(g) => Ok(Some(WindowSurface(g.window_surface(window, width as u32, height as u32)?))),
        }
    }

    /// Sizes `surface` for frames of `width`×`height`.
    pub fn resize_surface(&self, surface: &mut WindowSurface, width: usize, height: usize) {
        if let Inner::Gpu(g) = &self.inner {
            g.resize(&mut surface.0, width as u32, height as u32);
        }
    }

    /// Draws `prepared` into `surface` at its size with `overlay` (straight alpha, the same
    /// size; see [`Rgba8Image::overlay`]) over it, and shows it. The reference is drawn on the
    /// CPU and shown through the surface. A surface of another backend's is an error.
    pub fn present(
        &mut self,
        surface: &mut WindowSurface,
        prepared: &Prepared,
        overlay: &Rgba8Image,
    ) -> Result<(), Error> {
        let (width, height) = surface.size();
        Self::check_size(width, height)?;
        if let Technique::Reference(options) = &prepared.technique {
            let mut image = self.reference(&prepared.scene, options, width, height)?;
            image.overlay(overlay);
            return match &mut self.inner {
                Inner::Gpu(g) => Ok(g.present_image(&mut surface.0, &image)?),
                Inner::Cpu { .. } => {
                    Err(Error::Gpu(bumpmap_gpu::GpuError::Surface("a CPU renderer has no surface".into())))
                }
            };
        }
        match &mut self.inner {
            Inner::Gpu(g) => Ok(g.present(&mut surface.0, &prepared.scene, &prepared.technique, overlay)?),
            Inner::Cpu { .. } => {
                Err(Error::Gpu(bumpmap_gpu::GpuError::Surface("a CPU renderer has no surface".into())))
            }
        }
    }
}

/// The kept framebuffer, made anew when the size changes.
fn framebuffer_of(fb: &mut Option<Framebuffer>, width: usize, height: usize) -> Result<&mut Framebuffer, CpuError> {
    if fb.as_ref().is_none_or(|f| (f.width, f.height) != (width, height)) {
        *fb = Some(Framebuffer::new(width, height)?);
    }
    Ok(fb.as_mut().expect("made above"))
}
