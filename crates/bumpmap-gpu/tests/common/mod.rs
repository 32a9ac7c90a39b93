//! What the GPU tests share: an adapter or a reasoned skip, and a compute-shader runner for
//! testing WGSL functions against their Rust definitions.

#![allow(dead_code)]

use bumpmap_gpu::Context;
use bumpmap_gpu::GpuRenderer;
use wgpu::util::DeviceExt as _;

/// The parity tests' random numbers: a 64-bit LCG (Knuth's MMIX constants), its high 24 bits as
/// a float in [0, 1).
pub struct Rng(pub u64);

impl Rng {
    /// The next number in [0, 1).
    pub fn unit(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// `v` as a WGSL expression of exactly its bits.
pub fn wgsl_literal(v: f32) -> String {
    format!("bitcast<f32>({:#010x}u)", v.to_bits())
}

/// Whether a missing adapter must fail the test (CI installs lavapipe, so there it must).
fn adapter_required() -> bool {
    std::env::var_os("CI").is_some() || std::env::var_os("BUMPMAP_REQUIRE_GPU").is_some()
}

/// `Some` of an opened adapter; `None` (with a note on stderr) where none exists and CI is
/// not set. Under CI a missing adapter fails the test.
fn or_skip<T>(opened: Result<T, bumpmap_gpu::GpuError>) -> Option<T> {
    match opened {
        Ok(v) => Some(v),
        Err(e) if !adapter_required() => {
            eprintln!("SKIPPED: no GPU adapter ({e}); install mesa-vulkan-drivers for lavapipe");
            None
        }
        Err(e) => panic!("no GPU adapter under CI: {e}"),
    }
}

/// A GPU renderer, on the terms of [`or_skip`].
pub fn renderer() -> Option<GpuRenderer> {
    or_skip(GpuRenderer::new())
}

/// A device for compute tests, on the terms of [`or_skip`].
pub fn context() -> Option<Context> {
    or_skip(Context::new())
}

/// Plain f32/u32 data as bytes.
pub fn bytes<T: Copy>(v: &[T]) -> &[u8] {
    // SAFETY: only called with f32/u32 arrays (no padding, every byte initialized).
    unsafe { std::slice::from_raw_parts(v.as_ptr().cast::<u8>(), std::mem::size_of_val(v)) }
}

/// Runs `wgsl`'s compute entry `main` (workgroup size 64, one invocation per output) with
/// `input` at binding 0 (read-only storage) and `n` vec4 outputs at binding 1; returns them.
pub fn run_compute(ctx: &Context, wgsl: &str, input: &[u8], n: usize) -> Result<Vec<[f32; 4]>, String> {
    run_compute_with(ctx, wgsl, input, n, &[])
}

/// [`run_compute`] with the pipeline's override constants set.
pub fn run_compute_with(
    ctx: &Context,
    wgsl: &str,
    input: &[u8],
    n: usize,
    constants: &[(&str, f64)],
) -> Result<Vec<[f32; 4]>, String> {
    let d = &ctx.device;
    let scope = d.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(wgsl.into()),
    });
    let pipeline = d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: None,
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: wgpu::PipelineCompilationOptions { constants, ..Default::default() },
        cache: None,
    });
    if let Some(e) = pollster::block_on(scope.pop()) {
        return Err(format!("{e}\n--- shader ---\n{wgsl}"));
    }
    let input = d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: input,
        usage: wgpu::BufferUsages::STORAGE,
    });
    let size = (n * 16) as u64;
    let output = d.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let readback = d.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let entries = [
        wgpu::BindGroupEntry { binding: 0, resource: input.as_entire_binding() },
        wgpu::BindGroupEntry { binding: 1, resource: output.as_entire_binding() },
    ];
    let bind = d.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    });
    let mut enc = d.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
    {
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups(n.div_ceil(64) as u32, 1, 1);
    }
    enc.copy_buffer_to_buffer(&output, 0, &readback, 0, size);
    ctx.queue.submit([enc.finish()]);
    let (tx, rx) = std::sync::mpsc::channel();
    readback.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = tx.send(r);
    });
    d.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| e.to_string())?;
    rx.recv().map_err(|e| e.to_string())?.map_err(|e| e.to_string())?;
    let view = readback.get_mapped_range(..).map_err(|e| format!("{e:?}"))?;
    let out = view
        .chunks_exact(16)
        .map(|c| std::array::from_fn(|k| f32::from_le_bytes(c[4 * k..4 * k + 4].try_into().unwrap())))
        .collect();
    drop(view);
    readback.unmap();
    Ok(out)
}
