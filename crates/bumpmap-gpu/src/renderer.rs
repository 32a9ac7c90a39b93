//! The GPU backend's entry point: a technique's passes (`bumpmap_core::technique`) as wgpu
//! render passes into an RGBA8 target, read back as an image.
//!
//! Every pass loads what the previous ones left (8-bit colour, float depth), as the paper's
//! multipass technique needs; the first clears to black, alpha 0, depth 1. The vertex stage is
//! the core's, run on the CPU: the vertex shader only remaps depth and passes the varyings on.

use std::sync::Arc;

use bumpmap_core::Scene;
use bumpmap_core::cache::ArcCache;
use bumpmap_core::technique::{
    Binding, CombinerProgram, Gloss, LitProgram, Normalize, Program, SpecularFilter, Technique,
};
use bumpmap_math::{Rgba8Image, mesh::Mesh};
use wgpu::util::DeviceExt as _;

use crate::combiner_wgsl;
use crate::context::Context;
use crate::error::GpuError;
use crate::lit::{self, LitVariant};
use crate::pipelines::{COLOR_FORMAT, DEPTH_FORMAT, Pipelines, Shader, UNITS, VERTEX_FLOATS};
use crate::textures::Textures;

/// Renders scenes with wgpu, keeping its device, pipelines, textures and target between
/// frames.
pub struct GpuRenderer {
    // Fields drop in order: every resource before the device that made it.
    pipelines: Pipelines,
    textures: Textures,
    target: Option<Target>,
    meshes: ArcCache<Mesh, (wgpu::Buffer, u32)>,
    pub(crate) ctx: Context,
}

impl Drop for GpuRenderer {
    /// Waits for the device to finish before its resources go: tearing down a software
    /// driver (lavapipe) while its threads still run work has crashed processes at exit.
    fn drop(&mut self) {
        let _ = self.ctx.device.poll(wgpu::PollType::wait_indefinitely());
    }
}

/// The colour and depth attachments and the buffer they are read back through.
pub(crate) struct Target {
    width: usize,
    height: usize,
    color: wgpu::Texture,
    pub(crate) color_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
    readback: wgpu::Buffer,
    padded_row: u32,
}

/// What sees the image after each named pass (Kilgard Figure 12).
pub(crate) type SnapshotSink<'a> = &'a mut dyn FnMut(&str, &Rgba8Image);

impl GpuRenderer {
    /// Opens the first adapter wgpu finds (see [`Context::new`]).
    pub fn new() -> Result<Self, GpuError> {
        let ctx = Context::new()?;
        let pipelines = Pipelines::new(&ctx);
        Ok(Self { ctx, pipelines, textures: Textures::default(), target: None, meshes: ArcCache::default() })
    }

    /// The adapter's name and backend, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)`.
    pub fn adapter_name(&self) -> String {
        format!("{} ({:?})", self.ctx.info.name, self.ctx.info.backend)
    }

    /// Whether the adapter is a CPU emulation (lavapipe, llvmpipe, WARP) rather than a GPU.
    pub fn is_software(&self) -> bool {
        self.ctx.info.device_type == wgpu::DeviceType::Cpu
    }

    /// The device and its fault records, for tests of the failure paths.
    pub fn context(&self) -> &Context {
        &self.ctx
    }

    /// Clears the target (black, alpha 0, depth 1), draws `technique`'s passes of `scene` into
    /// it and returns the image (row 0 at the top). `on_snapshot` sees the image after each
    /// pass that has a snapshot name (Kilgard Figure 12).
    pub fn render(
        &mut self,
        scene: &Scene,
        technique: &Technique,
        width: usize,
        height: usize,
        mut on_snapshot: impl FnMut(&str, &Rgba8Image),
    ) -> Result<Rgba8Image, GpuError> {
        let encoder = self.encode(scene, technique, width, height, Some(&mut on_snapshot))?;
        self.read_back(encoder)
    }

    /// [`GpuRenderer::render`] without the snapshots: every pass recorded into one render pass,
    /// nothing read back before the end (a three-pass frame of a hundred parts has 300 named
    /// passes).
    pub fn render_frame(
        &mut self,
        scene: &Scene,
        technique: &Technique,
        width: usize,
        height: usize,
    ) -> Result<Rgba8Image, GpuError> {
        let encoder = self.encode(scene, technique, width, height, None)?;
        self.read_back(encoder)
    }

    /// Draws a frame as [`GpuRenderer::render`] does and waits until the GPU has finished it,
    /// without reading it back (what `glFinish` after a frame measures).
    pub fn draw(&mut self, scene: &Scene, technique: &Technique, width: usize, height: usize) -> Result<(), GpuError> {
        let encoder = self.encode(scene, technique, width, height, None)?;
        let submission = self.ctx.queue.submit([encoder.finish()]);
        let polled = self.ctx.device.poll(wgpu::PollType::Wait { submission_index: Some(submission), timeout: None });
        self.ctx.check()?;
        polled.map(|_| ()).map_err(|e| GpuError::Wgpu(e.to_string()))
    }

    /// Records the frame's passes; with `on_snapshot`, snapshots are read back on the way.
    pub(crate) fn encode(
        &mut self,
        scene: &Scene,
        technique: &Technique,
        width: usize,
        height: usize,
        mut on_snapshot: Option<SnapshotSink<'_>>,
    ) -> Result<wgpu::CommandEncoder, GpuError> {
        self.ctx.check()?;
        let passes = technique.passes(scene)?;
        // What an earlier scene used and nothing holds any more.
        self.textures.evict_unused();
        self.meshes.evict_unused();
        self.ensure_target(width, height)?;
        let aspect = width as f32 / height as f32;
        // Every pass's resources first; then the passes are recorded into as few render passes
        // as possible (one per snapshot), which a tiling software rasterizer such as lavapipe
        // flushes once instead of once per pass.
        let mut draws = Vec::with_capacity(passes.len());
        let mut vertices: Option<((usize, usize), wgpu::Buffer)> = None;
        for pass in &passes {
            let key = (pass.object, pass.light);
            if vertices.as_ref().map(|v| v.0) != Some(key) {
                let v = scene.vertices(&scene.objects[pass.object], &scene.lights[pass.light], aspect)?;
                let floats: Vec<f32> = v.iter().flat_map(|v| v.clip.to_array().into_iter().chain(v.varyings)).collect();
                debug_assert_eq!(floats.len(), v.len() * VERTEX_FLOATS);
                let buffer = self.ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("vertices"),
                    contents: bytes(&floats),
                    usage: wgpu::BufferUsages::VERTEX,
                });
                vertices = Some((key, buffer));
            }
            let (indices, count) = self.indices(&scene.objects[pass.object].mesh);
            let (shader, bind_group) = match &pass.program {
                Program::Lit(p) => (Shader::Lit(LitVariant::of(p)), self.lit_bind_group(p)?),
                Program::Combiners(p) => {
                    (Shader::Combiners(combiner_wgsl::fragment_shader(p)), self.combiner_bind_group(p)?)
                }
            };
            let pipeline = self.pipelines.get(&self.ctx, &shader, &pass.state)?;
            let vertex_buffer = vertices.as_ref().expect("filled above").1.clone();
            draws.push(Draw { pipeline, bind_group, vertex_buffer, indices, count, blend: pass.state.blend.color });
        }
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        let mut first = true;
        let mut start = 0;
        for (i, pass) in passes.iter().enumerate() {
            let snapshot = pass.snapshot.filter(|_| on_snapshot.is_some());
            if snapshot.is_none() && i + 1 < passes.len() {
                continue;
            }
            record(&mut encoder, self.target.as_ref().expect("made above"), first, &draws[start..=i]);
            (first, start) = (false, i + 1);
            if let (Some(name), Some(f)) = (snapshot, on_snapshot.as_mut()) {
                let done = std::mem::replace(&mut encoder, self.ctx.device.create_command_encoder(&Default::default()));
                let image = self.read_back(done)?;
                f(name, &image);
            }
        }
        if first {
            // No passes: the frame is the cleared target.
            record(&mut encoder, self.target.as_ref().expect("made above"), true, &[]);
        }
        Ok(encoder)
    }

    pub(crate) fn ensure_target(&mut self, width: usize, height: usize) -> Result<(), GpuError> {
        if width == 0 || height == 0 {
            return Err(GpuError::EmptyFramebuffer { width, height });
        }
        let max = self.ctx.max_texture_side();
        if width > max as usize || height > max as usize {
            return Err(GpuError::TooLarge { what: "the framebuffer", width, height, max });
        }
        if self.target.as_ref().is_some_and(|t| (t.width, t.height) == (width, height)) {
            return Ok(());
        }
        let size = wgpu::Extent3d { width: width as u32, height: height as u32, depth_or_array_layers: 1 };
        let attachment = |label, format, usage| {
            self.ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | usage,
                view_formats: &[],
            })
        };
        // Read back for an image; read by the window surface's copy (`crate::present`).
        let color =
            attachment("colour", COLOR_FORMAT, wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::TEXTURE_BINDING);
        let depth = attachment("depth", DEPTH_FORMAT, wgpu::TextureUsages::empty());
        let padded_row = (4 * width as u32).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let readback = self.ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read-back"),
            size: padded_row as u64 * height as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.target = Some(Target {
            width,
            height,
            color_view: color.create_view(&Default::default()),
            depth_view: depth.create_view(&Default::default()),
            color,
            readback,
            padded_row,
        });
        Ok(())
    }

    /// The target the last frame was drawn into, if any.
    pub(crate) fn target(&self) -> Option<&Target> {
        self.target.as_ref()
    }

    /// The mesh's index buffer, uploaded once per `Arc`.
    fn indices(&mut self, mesh: &Arc<Mesh>) -> (wgpu::Buffer, u32) {
        let device = &self.ctx.device;
        let made = self.meshes.get_or_try_make(mesh, |mesh| {
            let flat: Vec<u32> = mesh.indices.iter().flatten().copied().collect();
            let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("indices"),
                contents: bytes(&flat),
                usage: wgpu::BufferUsages::INDEX,
            });
            Ok::<_, std::convert::Infallible>((buffer, flat.len() as u32))
        });
        let Ok(made) = made;
        made
    }

    fn lit_bind_group(&mut self, p: &LitProgram) -> Result<wgpu::BindGroup, GpuError> {
        let ctx = &self.ctx;
        let t = &mut self.textures;
        let normal = t.mips(ctx, &p.normal_map)?;
        let decal = match &p.decal {
            Some(d) => t.mips(ctx, d)?,
            None => t.white_2d(ctx),
        };
        let gloss = match &p.gloss {
            Gloss::Map(g) => t.mips(ctx, g)?,
            _ => t.white_2d(ctx),
        };
        let occlusion = match &p.occlusion {
            Some(o) => t.mips(ctx, o)?,
            None => t.white_2d(ctx),
        };
        let detail = match &p.detail {
            Some(d) => t.mips(ctx, &d.map)?,
            None => t.white_2d(ctx),
        };
        let pattern = match p.light.spot.as_ref().and_then(|s| s.pattern.as_ref()) {
            Some(pattern) => t.mips(ctx, pattern)?,
            None => t.white_2d(ctx),
        };
        let cube = match p.normalize {
            Normalize::Cube => t.cube(ctx, p.cube_size, bumpmap_math::Encoding::Unorm),
            Normalize::Math => t.white_cube(ctx),
        };
        let [lean_b_m, lean_m_xy] = match p.terms.specular_filter {
            SpecularFilter::Lean => t.moments(ctx, &p.normal_map)?,
            // CLEAN's one texture where LEAN's first is.
            SpecularFilter::Clean => [t.clean_moments(ctx, &p.normal_map)?, t.white_2d(ctx)],
            _ => [t.white_2d(ctx), t.white_2d(ctx)],
        };
        let roughness = match (p.terms.specular_filter, &p.roughness_map) {
            (SpecularFilter::RoughnessMap, Some(given)) => t.mips(ctx, given)?,
            (SpecularFilter::RoughnessMap, None) => {
                let made = t.roughness.get(&p.normal_map, p.terms.shininess);
                t.mips(ctx, &made)?
            }
            _ => t.white_2d(ctx),
        };
        let [heights, height_bounds] = match &p.parallax {
            Some(x) => t.heights(ctx, &x.heights)?,
            None => t.no_heights(ctx),
        };
        let [horizons_0123, horizons_4567] = match p.parallax.as_ref().and_then(|x| x.horizons.as_ref()) {
            Some(h) => t.horizons(ctx, h)?,
            None => t.no_horizons(ctx),
        };
        let material = t.sampler(ctx, p.sampler);
        let clamp = t.sampler(ctx, bumpmap_core::state::Sampler::LINEAR_CLAMP);
        let uniforms = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("lit"),
            contents: &lit::uniforms(p),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        use wgpu::BindingResource::{Sampler, TextureView};
        let entries = [
            wgpu::BindGroupEntry { binding: 0, resource: uniforms.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: TextureView(&normal) },
            wgpu::BindGroupEntry { binding: 2, resource: TextureView(&decal) },
            wgpu::BindGroupEntry { binding: 3, resource: TextureView(&gloss) },
            wgpu::BindGroupEntry { binding: 4, resource: TextureView(&pattern) },
            wgpu::BindGroupEntry { binding: 5, resource: TextureView(&cube) },
            wgpu::BindGroupEntry { binding: 6, resource: Sampler(&material) },
            wgpu::BindGroupEntry { binding: 7, resource: Sampler(&clamp) },
            wgpu::BindGroupEntry { binding: 8, resource: TextureView(&lean_b_m) },
            wgpu::BindGroupEntry { binding: 9, resource: TextureView(&lean_m_xy) },
            wgpu::BindGroupEntry { binding: 10, resource: TextureView(&roughness) },
            wgpu::BindGroupEntry { binding: 11, resource: TextureView(&heights) },
            wgpu::BindGroupEntry { binding: 12, resource: TextureView(&height_bounds) },
            wgpu::BindGroupEntry { binding: 13, resource: TextureView(&horizons_0123) },
            wgpu::BindGroupEntry { binding: 14, resource: TextureView(&horizons_4567) },
            wgpu::BindGroupEntry { binding: 15, resource: TextureView(&occlusion) },
            wgpu::BindGroupEntry { binding: 16, resource: TextureView(&detail) },
        ];
        Ok(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("lit"),
            layout: &self.pipelines.lit_layout,
            entries: &entries,
        }))
    }

    fn combiner_bind_group(&mut self, p: &CombinerProgram) -> Result<wgpu::BindGroup, GpuError> {
        let ctx = &self.ctx;
        let t = &mut self.textures;
        let mut views = Vec::new();
        for i in 0..UNITS {
            let unit = p.units.get(i);
            let (two_d, cube) = match unit.map(|u| &u.binding) {
                Some(Binding::TwoD { texture, .. }) => (t.mips(ctx, texture)?, t.white_cube(ctx)),
                Some(Binding::NormalizationCube { size, encoding, .. }) => {
                    (t.white_2d(ctx), t.cube(ctx, *size, *encoding))
                }
                None => (t.white_2d(ctx), t.white_cube(ctx)),
            };
            let sampler = t.sampler(ctx, unit.map_or(bumpmap_core::state::Sampler::LINEAR_CLAMP, |u| u.sampler));
            views.push((two_d, cube, sampler));
        }
        let mut entries = Vec::new();
        for (i, (two_d, cube, sampler)) in views.iter().enumerate() {
            let i = i as u32;
            entries.push(wgpu::BindGroupEntry { binding: 3 * i, resource: wgpu::BindingResource::TextureView(two_d) });
            entries
                .push(wgpu::BindGroupEntry { binding: 3 * i + 1, resource: wgpu::BindingResource::TextureView(cube) });
            entries
                .push(wgpu::BindGroupEntry { binding: 3 * i + 2, resource: wgpu::BindingResource::Sampler(sampler) });
        }
        Ok(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("combiners"),
            layout: &self.pipelines.combiner_layout,
            entries: &entries,
        }))
    }

    /// Submits `encoder` with a copy of the target into the read-back buffer, waits, and
    /// returns the image without the rows' padding.
    fn read_back(&mut self, mut encoder: wgpu::CommandEncoder) -> Result<Rgba8Image, GpuError> {
        let target = self.target.as_ref().expect("a target exists while rendering");
        encoder.copy_texture_to_buffer(
            target.color.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &target.readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(target.padded_row),
                    rows_per_image: Some(target.height as u32),
                },
            },
            wgpu::Extent3d { width: target.width as u32, height: target.height as u32, depth_or_array_layers: 1 },
        );
        let submission = self.ctx.queue.submit([encoder.finish()]);
        let slice = target.readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        let polled = self.ctx.device.poll(wgpu::PollType::Wait { submission_index: Some(submission), timeout: None });
        self.ctx.check()?;
        polled.map_err(|e| GpuError::Readback(e.to_string()))?;
        rx.recv().map_err(|e| GpuError::Readback(e.to_string()))?.map_err(|e| GpuError::Readback(e.to_string()))?;
        let mut texels = Vec::with_capacity(target.width * target.height);
        {
            let mapped = slice.get_mapped_range().map_err(|e| GpuError::Readback(e.to_string()))?;
            for row in mapped.chunks_exact(target.padded_row as usize) {
                texels.extend(row[..4 * target.width].chunks_exact(4).map(|p| [p[0], p[1], p[2], p[3]]));
            }
        }
        target.readback.unmap();
        Ok(Rgba8Image::new(target.width, target.height, texels))
    }
}

/// One pass's pipeline and bindings, ready to record.
struct Draw {
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
    vertex_buffer: wgpu::Buffer,
    indices: wgpu::Buffer,
    count: u32,
    blend: [f32; 4],
}

/// Records `draws` in order into one render pass on the target, cleared first when `clear`.
fn record(encoder: &mut wgpu::CommandEncoder, target: &Target, clear: bool, draws: &[Draw]) {
    let mut rp = begin(encoder, target, clear);
    for d in draws {
        rp.set_pipeline(&d.pipeline);
        rp.set_bind_group(0, &d.bind_group, &[]);
        let c = d.blend;
        rp.set_blend_constant(wgpu::Color { r: c[0] as f64, g: c[1] as f64, b: c[2] as f64, a: c[3] as f64 });
        rp.set_vertex_buffer(0, d.vertex_buffer.slice(..));
        rp.set_index_buffer(d.indices.slice(..), wgpu::IndexFormat::Uint32);
        rp.draw_indexed(0..d.count, 0, 0..1);
    }
}

/// A render pass on the target: cleared (black, alpha 0, depth 1) or loading what is there.
fn begin<'e>(encoder: &'e mut wgpu::CommandEncoder, target: &Target, clear: bool) -> wgpu::RenderPass<'e> {
    let (color, depth) = if clear {
        (wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), wgpu::LoadOp::Clear(1.0))
    } else {
        (wgpu::LoadOp::Load, wgpu::LoadOp::Load)
    };
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("pass"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: &target.color_view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations { load: color, store: wgpu::StoreOp::Store },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &target.depth_view,
            depth_ops: Some(wgpu::Operations { load: depth, store: wgpu::StoreOp::Store }),
            stencil_ops: None,
        }),
        ..Default::default()
    })
}

/// Plain data as bytes.
fn bytes<T: Copy>(v: &[T]) -> &[u8] {
    // SAFETY: T is f32 or u32 here (plain data, no padding, every bit pattern valid as bytes);
    // the slice covers exactly the vector's initialized elements.
    unsafe { std::slice::from_raw_parts(v.as_ptr().cast::<u8>(), std::mem::size_of_val(v)) }
}
