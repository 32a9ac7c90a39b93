//! Frames shown in a window: the technique's passes drawn into the offscreen target exactly as
//! for an image, then copied onto the window's surface by a full-screen triangle that lays an
//! overlay (text, a wireframe: straight alpha, the same size) over them. The frame never comes
//! back to the CPU.
//!
//! What this module does not do: make the window (the caller hands over anything with a
//! window and display handle, a winit window for one), draw the overlay's contents, or scale:
//! the surface is the frame's size.

use bumpmap_core::Scene;
use bumpmap_core::technique::Technique;
use bumpmap_math::Rgba8Image;

use crate::error::GpuError;
use crate::pipelines::{COLOR_FORMAT, unfiltered_entry};
use crate::renderer::GpuRenderer;

/// The copy: each pixel of the frame, with the overlay mixed over it by its alpha. The frame's
/// alpha (the three-pass technique's s_self, not coverage) is not shown.
const PRESENT_WGSL: &str = r#"
@group(0) @binding(0) var frame: texture_2d<f32>;
@group(0) @binding(1) var overlay: texture_2d<f32>;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let at = vec2<i32>(p.xy);
    let c = textureLoad(frame, at, 0);
    let o = textureLoad(overlay, at, 0);
    return vec4<f32>(mix(c.rgb, o.rgb, o.a), 1.0);
}
"#;

/// A window's surface, configured for frames of one size, with the copy's pipeline and the
/// overlay texture.
pub struct WindowSurface {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    view_format: wgpu::TextureFormat,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    overlay: Option<wgpu::Texture>,
    /// The overlay's bytes as last uploaded: an unchanged overlay is not sent again.
    uploaded: Vec<u8>,
}

impl WindowSurface {
    /// The surface's size.
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// The texture format frames are written in (the surface's, without sRGB encoding: the
    /// frame's bytes are already what the screen should show).
    pub fn format(&self) -> wgpu::TextureFormat {
        self.view_format
    }
}

impl GpuRenderer {
    /// A surface on `window` (anything with window and display handles, such as an
    /// `Arc<winit::window::Window>`) for frames of `width`×`height`.
    pub fn window_surface(
        &self,
        window: impl wgpu::DisplayAndWindowHandle + 'static,
        width: u32,
        height: u32,
    ) -> Result<WindowSurface, GpuError> {
        let ctx = &self.ctx;
        let surface = ctx.instance.create_surface(window).map_err(|e| GpuError::Surface(e.to_string()))?;
        let caps = surface.get_capabilities(&ctx.adapter);
        // A format without sRGB encoding, or an sRGB one viewed without it.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| !f.is_srgb())
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| GpuError::Surface(format!("{} cannot present to this window", ctx.info.name)))?;
        let view_format = format.remove_srgb_suffix();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            color_space: wgpu::SurfaceColorSpace::Auto,
            width: width.max(1),
            height: height.max(1),
            desired_maximum_frame_latency: 2,
            present_mode: wgpu::PresentMode::AutoVsync,
            alpha_mode: wgpu::CompositeAlphaMode::Auto,
            view_formats: if view_format == format { vec![] } else { vec![view_format] },
        };
        surface.configure(&ctx.device, &config);
        let layout = ctx.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("present"),
            entries: &[unfiltered_entry(0), unfiltered_entry(1)],
        });
        let pipeline_layout = ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("present"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = ctx.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("present"),
            source: wgpu::ShaderSource::Wgsl(PRESENT_WGSL.into()),
        });
        let pipeline = ctx.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("present"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(view_format.into())],
            }),
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        });
        ctx.check()?;
        Ok(WindowSurface { surface, config, view_format, pipeline, layout, overlay: None, uploaded: Vec::new() })
    }

    /// Draws `technique`'s passes of `scene` at the surface's size and shows them with
    /// `overlay` (straight alpha, the surface's size) over them. A surface that has gone out of
    /// date (a resize under way) is configured again and the frame skipped.
    pub fn present(
        &mut self,
        surface: &mut WindowSurface,
        scene: &Scene,
        technique: &Technique,
        overlay: &Rgba8Image,
    ) -> Result<(), GpuError> {
        let (width, height) = (surface.config.width as usize, surface.config.height as usize);
        if (overlay.width, overlay.height) != (width, height) {
            return Err(GpuError::Surface(format!(
                "the overlay is {}x{}, the window {width}x{height}",
                overlay.width, overlay.height
            )));
        }
        let encoder = self.encode(scene, technique, width, height, None)?;
        self.show(surface, encoder, overlay)
    }

    /// Shows `image` (the surface's size) on `surface` as it is: a frame drawn elsewhere (the
    /// reference, on the CPU).
    pub fn present_image(&mut self, surface: &mut WindowSurface, image: &Rgba8Image) -> Result<(), GpuError> {
        let (width, height) = (surface.config.width as usize, surface.config.height as usize);
        if (image.width, image.height) != (width, height) {
            return Err(GpuError::Surface(format!(
                "the image is {}x{}, the window {width}x{height}",
                image.width, image.height
            )));
        }
        self.ensure_target(width, height)?;
        let encoder = self.ctx.device.create_command_encoder(&Default::default());
        let opaque = Rgba8Image::new(width, height, image.texels.iter().map(|&[r, g, b, _]| [r, g, b, 255]).collect());
        self.show(surface, encoder, &opaque)
    }

    /// Finishes `encoder` (a frame drawn into the target) with the copy onto the surface and
    /// presents it.
    fn show(
        &mut self,
        surface: &mut WindowSurface,
        mut encoder: wgpu::CommandEncoder,
        overlay: &Rgba8Image,
    ) -> Result<(), GpuError> {
        let (width, height) = (surface.config.width as usize, surface.config.height as usize);
        let ctx = &self.ctx;
        let size = wgpu::Extent3d { width: width as u32, height: height as u32, depth_or_array_layers: 1 };
        if surface.overlay.as_ref().is_none_or(|t| t.size() != size) {
            surface.uploaded.clear();
            surface.overlay = Some(ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("overlay"),
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: COLOR_FORMAT,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            }));
        }
        let overlay_texture = surface.overlay.as_ref().expect("made above");
        let bytes = overlay.texels.as_flattened();
        if surface.uploaded != bytes {
            ctx.queue.write_texture(
                overlay_texture.as_image_copy(),
                bytes,
                wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4 * width as u32), rows_per_image: None },
                size,
            );
            surface.uploaded.clear();
            surface.uploaded.extend_from_slice(bytes);
        }
        let frame = match surface.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t) | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => return Ok(()),
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                surface.surface.configure(&ctx.device, &surface.config);
                return Ok(());
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                ctx.check()?;
                return Err(GpuError::Surface("the window's next image could not be had".into()));
            }
        };
        let view = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor { format: Some(surface.view_format), ..Default::default() });
        let target = self.target().expect("encode made the target");
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("present"),
            layout: &surface.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&target.color_view) },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&overlay_texture.create_view(&Default::default())),
                },
            ],
        });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("present"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&surface.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
        ctx.queue.submit([encoder.finish()]);
        ctx.queue.present(frame);
        ctx.check()
    }

    /// Sizes `surface` for frames of `width`×`height` (both at least 1).
    pub fn resize(&self, surface: &mut WindowSurface, width: u32, height: u32) {
        let (width, height) = (width.max(1), height.max(1));
        if (surface.config.width, surface.config.height) != (width, height) {
            surface.config.width = width;
            surface.config.height = height;
            surface.surface.configure(&self.ctx.device, &surface.config);
        }
    }
}
