//! The backends behind `--backend`: the CPU pipeline and wgpu, as one value the commands hold.
//!
//! Both draw the same `bumpmap_core` passes; this module only owns them, turns their frames
//! into RGBA8 images (row 0 the top of the picture) and their errors into messages that say
//! what to do.

use bumpmap_core::Scene;
use bumpmap_core::technique::Technique;
use bumpmap_cpu::{CpuError, CpuRenderer, Framebuffer};
use bumpmap_gpu::{GpuError, GpuRenderer};
use bumpmap_math::Rgba8Image;

use crate::error::CliError;
use crate::render::core_err;
use crate::render_args::BackendArg;

/// A rendered frame and, when asked for, the framebuffer after each named pass.
pub struct Frame {
    /// The final image.
    pub image: Rgba8Image,
    /// `(pass name, image)` for Kilgard Figure 12.
    pub snapshots: Vec<(String, Rgba8Image)>,
}

/// One backend, kept across frames so that its buffers, textures and pipelines are reused.
pub enum Backend {
    /// The emulated GeForce on the CPU.
    Cpu { renderer: CpuRenderer, fb: Option<Framebuffer> },
    /// wgpu.
    Gpu(Box<GpuRenderer>),
}

/// Refuses a framebuffer no backend accepts, before any work.
pub fn check_size(width: usize, height: usize) -> Result<(), CliError> {
    if width == 0 || height == 0 || width.saturating_mul(height) > bumpmap_cpu::framebuffer::MAX_PIXELS {
        return Err(cpu_err(CpuError::FramebufferSize {
            width,
            height,
            max_pixels: bumpmap_cpu::framebuffer::MAX_PIXELS,
        }));
    }
    Ok(())
}

impl Backend {
    /// Starts the backend `arg` names; for the GPU, finds an adapter and opens a device.
    pub fn new(arg: BackendArg) -> Result<Self, CliError> {
        Ok(match arg {
            BackendArg::Cpu => Backend::Cpu { renderer: CpuRenderer::new(), fb: None },
            BackendArg::Gpu => Backend::Gpu(Box::new(GpuRenderer::new().map_err(gpu_err)?)),
        })
    }

    /// The backend in words, for messages and benchmark output.
    pub fn name(&self) -> String {
        match self {
            Backend::Cpu { .. } => format!("cpu, {} threads", rayon::current_num_threads()),
            Backend::Gpu(g) => format!("gpu: {}", g.adapter_name()),
        }
    }

    /// The short name: `cpu` or `gpu`.
    pub fn kind(&self) -> &'static str {
        match self {
            Backend::Cpu { .. } => "cpu",
            Backend::Gpu(_) => "gpu",
        }
    }

    /// Draws one frame of `width`×`height` and waits for it, without making an image: what a
    /// benchmark times (the GPU's `glFinish`, the CPU's framebuffer left as it is).
    pub fn draw(&mut self, scene: &Scene, technique: &Technique, width: usize, height: usize) -> Result<(), CliError> {
        match self {
            Backend::Cpu { renderer, fb } => {
                let fb = framebuffer(fb, width, height)?;
                renderer.render(scene, technique, fb, |_, _| {}).map_err(cpu_err)
            }
            Backend::Gpu(g) => g.draw(scene, technique, width, height).map_err(gpu_err),
        }
    }

    /// Renders one frame of `width`×`height`; with `snapshots`, also the framebuffer after each
    /// named pass.
    pub fn render(
        &mut self,
        scene: &Scene,
        technique: &Technique,
        width: usize,
        height: usize,
        snapshots: bool,
    ) -> Result<Frame, CliError> {
        let mut shots = Vec::new();
        let image = match self {
            Backend::Cpu { renderer, fb } => {
                let fb = framebuffer(fb, width, height)?;
                renderer
                    .render(scene, technique, fb, |name, fb| {
                        if snapshots {
                            shots.push((name.to_string(), Rgba8Image::new(fb.width, fb.height, fb.to_rgba8())));
                        }
                    })
                    .map_err(cpu_err)?;
                Rgba8Image::new(width, height, fb.to_rgba8())
            }
            Backend::Gpu(g) => g
                .render(scene, technique, width, height, |name, image| {
                    if snapshots {
                        shots.push((name.to_string(), image.clone()));
                    }
                })
                .map_err(gpu_err)?,
        };
        Ok(Frame { image, snapshots: shots })
    }
}

/// The kept framebuffer, made anew when the size changes.
fn framebuffer(fb: &mut Option<Framebuffer>, width: usize, height: usize) -> Result<&mut Framebuffer, CliError> {
    if fb.as_ref().is_none_or(|f| (f.width, f.height) != (width, height)) {
        *fb = Some(Framebuffer::new(width, height).map_err(cpu_err)?);
    }
    Ok(fb.as_mut().expect("made above"))
}

fn cpu_err(e: CpuError) -> CliError {
    match e {
        CpuError::Core(e) => core_err(e),
        other => CliError::Render(other.to_string()),
    }
}

fn gpu_err(e: GpuError) -> CliError {
    match e {
        GpuError::Core(e) => core_err(e),
        GpuError::NoAdapter(reason) => CliError::Render(format!(
            "no GPU adapter found ({reason}): install a Vulkan driver (on Debian without a GPU, \
             `apt-get install mesa-vulkan-drivers libvulkan1` gives Mesa's lavapipe) or use --backend cpu"
        )),
        other => CliError::Render(other.to_string()),
    }
}
