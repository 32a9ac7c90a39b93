//! `bumpmap bench`: wall-clock medians of the project's hot paths, in prose or one JSON line.
//!
//! Each benchmark builds its input once, runs once to warm up, then times `--runs` runs.
//! Figures for BENCHMARKS.md come from here and from criterion (`cargo bench`).

use std::time::Instant;

use bumpmap_math::{HeightField, HeightPreset, MipChain, MipMode, NormalMapOptions, mip::next_size};
use rayon::prelude::*;

use crate::args::{BenchArgs, BenchRenderArgs, BenchWhat};
use crate::error::CliError;

/// Median, min and max of a set of durations in milliseconds.
pub struct Stats {
    pub median: f64,
    pub min: f64,
    pub max: f64,
}

/// Runs `f` once to warm up, then `runs` times, and returns the timing statistics.
pub fn time_runs(runs: u32, mut f: impl FnMut()) -> Stats {
    f();
    let mut ms: Vec<f64> = (0..runs)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    ms.sort_by(f64::total_cmp);
    Stats { median: ms[ms.len() / 2], min: ms[0], max: ms[ms.len() - 1] }
}

pub fn run(args: &BenchArgs) -> Result<(), CliError> {
    match args.what {
        BenchWhat::Normalmap { size, format, runs, threads, json } => {
            with_threads(threads, || bench_normalmap(size as usize, format, runs, json))
        }
        BenchWhat::Height { size, runs, threads, json } => {
            with_threads(threads, || bench_height(size as usize, runs, json))
        }
        BenchWhat::Tangents { triangles, mode, runs, threads, json } => {
            with_threads(threads, || bench_tangents(triangles as usize, mode, runs, json))
        }
        BenchWhat::Render(ref r) => with_threads(r.threads, || bench_render(r)),
        BenchWhat::Reference { ref scene, size, spp, runs, threads, json } => {
            with_threads(threads, || bench_reference(scene, size, spp as usize, runs, json))
        }
    }
}

/// Normal map → heights on the benchmark's heights made into a 16-bit map (forward kernel,
/// scale 4, green up); making and decoding the map are not timed.
fn bench_height(size: usize, runs: u32, json: bool) -> Result<(), CliError> {
    use bumpmap::heights::{HeightOptions, heights_from_normals};
    use bumpmap_math::integration::{Boundary, Derivative};
    let field = HeightField::from_u8(size, size, &bench_heights(size)).expect("square field");
    let options = NormalMapOptions { y_convention: bumpmap_math::YConvention::YUp, ..Default::default() };
    let level0 = bumpmap_math::normalmap::normal_map_level0_texels::<[u16; 4]>(&field, &options)
        .map_err(|source| CliError::NormalMap { path: "the benchmark's heights".into(), source })?;
    let normals = bumpmap_math::inspect::signed_levels(&[level0]).remove(0);
    let mut failure = None;
    let mut run = |options: &HeightOptions| {
        if let Err(e) = heights_from_normals(&normals, options) {
            failure = Some(e);
        }
    };
    let auto = HeightOptions { scale: 4.0, ..Default::default() };
    let all = time_runs(runs, || run(&auto));
    let given = HeightOptions {
        boundary: Some(Boundary::Periodic),
        derivative: Some(Derivative::Kernel(bumpmap_math::Kernel::Forward)),
        y_convention: Some(bumpmap_math::YConvention::YUp),
        scale: 4.0,
    };
    let solve = time_runs(runs, || run(&given));
    if let Some(e) = failure {
        return Err(CliError::Render(e.to_string()));
    }
    let threads = rayon::current_num_threads();
    if json {
        println!(
            "{{\"bench\":\"height\",\"size\":{size},\"threads\":{threads},\"runs\":{runs},\"median_ms\":{:.3},\"min_ms\":{:.3},\"max_ms\":{:.3},\"solve_median_ms\":{:.3}}}",
            all.median, all.min, all.max, solve.median
        );
    } else {
        println!("normal map → heights, {size}x{size} 16-bit, {threads} threads, {runs} runs");
        println!(
            "  curl and seam tests, kernel fit, solve: median {:.1} ms (min {:.1}, max {:.1})",
            all.median, all.min, all.max
        );
        println!("  the solve alone (kernel, convention and method given): median {:.1} ms", solve.median);
    }
    Ok(())
}

/// The reference renderer's time for one image; scene setup is not timed.
fn bench_reference(scene: &str, size: usize, spp: usize, runs: u32, json: bool) -> Result<(), CliError> {
    use bumpmap_core::scenes::{self, SceneKind, SceneParams};
    let kind = SceneKind::parse(scene)
        .ok_or_else(|| CliError::Usage(format!("unknown scene '{scene}': use {}", SceneKind::built_in_names())))?;
    // The framebuffer limit `render` and `compare` apply, before any work.
    bumpmap::Renderer::check_size(size, size).map_err(bumpmap_words::frame::lib_err)?;
    let scene_value = scenes::build(&kind, &SceneParams::default()).map_err(bumpmap_words::frame::core_err)?;
    let options = bumpmap_reference::ReferenceOptions { samples_per_pixel: spp, ..Default::default() };
    let mut failure = None;
    let stats = time_runs(runs, || {
        if let Err(e) = bumpmap_reference::render(&scene_value, size, size, &options, &|_, _| {}) {
            failure = Some(e);
        }
    });
    if let Some(e) = failure {
        return Err(CliError::Render(bumpmap_words::frame::reference_err(e)));
    }
    let threads = rayon::current_num_threads();
    let msamples = (size * size * spp) as f64 / stats.median / 1e3;
    if json {
        println!(
            "{{\"bench\":\"reference\",\"scene\":\"{scene}\",\"size\":{size},\"spp\":{spp},\"threads\":{threads},\"runs\":{runs},\"median_ms\":{:.3},\"min_ms\":{:.3},\"max_ms\":{:.3},\"msamples_per_s\":{msamples:.1}}}",
            stats.median, stats.min, stats.max
        );
    } else {
        println!(
            "reference {scene} {size}² at {spp} samples per pixel on {threads} threads: median {:.1} ms ({msamples:.1} M samples/s; min {:.1}, max {:.1})",
            stats.median, stats.min, stats.max
        );
    }
    Ok(())
}

/// Runs `f` on a pool of `threads` workers (all cores when `None`).
pub fn with_threads<T: Send>(threads: Option<u16>, f: impl FnOnce() -> T + Send) -> T {
    let pool =
        rayon::ThreadPoolBuilder::new().num_threads(threads.map_or(0, usize::from)).build().expect("thread pool");
    pool.install(f)
}

/// The benchmark's height field: bricks plus 3 bits of seeded noise, like the NumPy peer's.
pub fn bench_heights(size: usize) -> Vec<u8> {
    let bricks = HeightPreset::Bricks.render(size, size);
    let noise = HeightPreset::Noise(7).render(size, size);
    bricks.to_f32().iter().zip(&noise.to_f32()).map(|(b, n)| (b * 247.0 + n * 8.0).clamp(0.0, 255.0) as u8).collect()
}

fn bench_normalmap(
    size: usize,
    format: Option<bumpmap_io::texture_file::TextureFormat>,
    runs: u32,
    json: bool,
) -> Result<(), CliError> {
    let bytes = bench_heights(size);
    let options = NormalMapOptions::default();
    let mut levels = 0;
    let mut last = None;
    let work = time_runs(runs, || {
        let field = HeightField::from_u8(size, size, &bytes).expect("square field");
        let chain = MipChain::<[u8; 4]>::from_height(&field, &options, MipMode::LengthInAlpha).expect("valid options");
        levels = chain.len();
        last = Some(chain);
    });
    if let Some(format) = format {
        return bench_compression(size, &last.expect("ran"), format, runs, json);
    }
    let floor = time_runs(runs, || {
        std::hint::black_box(read_once_write_once(&bytes, size));
    });
    let threads = rayon::current_num_threads();
    let mpix = (size * size) as f64 / 1e6;
    if json {
        println!(
            "{{\"bench\":\"normalmap\",\"size\":{size},\"levels\":{levels},\"threads\":{threads},\"runs\":{runs},\"median_ms\":{:.3},\"min_ms\":{:.3},\"max_ms\":{:.3},\"floor_median_ms\":{:.3},\"ratio_to_floor\":{:.3},\"mpix_per_s\":{:.1}}}",
            work.median,
            work.min,
            work.max,
            floor.median,
            work.median / floor.median,
            mpix / (work.median / 1e3)
        );
    } else {
        println!("normal map + {levels}-level mip chain, {size}x{size} 8-bit heights, {threads} threads, {runs} runs");
        println!(
            "  median {:.2} ms (min {:.2}, max {:.2}): {:.0} MPix/s",
            work.median,
            work.min,
            work.max,
            mpix / (work.median / 1e3)
        );
        println!("  floor (read the input once, write every output byte once): median {:.2} ms", floor.median);
        println!("  ratio to the floor: {:.2}x", work.median / floor.median);
    }
    Ok(())
}

/// Compressing a finished chain (every level, in parallel) to `format`; the chain itself is
/// made once, untimed.
fn bench_compression(
    size: usize,
    chain: &MipChain,
    format: bumpmap_io::texture_file::TextureFormat,
    runs: u32,
    json: bool,
) -> Result<(), CliError> {
    let layout = bumpmap_io::texture_file::TextureLayout { faces: vec![chain.levels.iter().map(Into::into).collect()] };
    let mut failed = None;
    let stats = time_runs(runs, || {
        if let Err(e) = bumpmap_io::texture_file::encode(std::path::Path::new("bench"), &layout, format) {
            failed = Some(e);
        }
    });
    if let Some(e) = failed {
        return Err(e.into());
    }
    let threads = rayon::current_num_threads();
    let texels: usize = chain.levels.iter().map(|l| l.width * l.height).sum();
    let mpix = texels as f64 / 1e6;
    if json {
        println!(
            "{{\"bench\":\"compress\",\"format\":\"{}\",\"size\":{size},\"levels\":{},\"threads\":{threads},\"runs\":{runs},\"median_ms\":{:.3},\"min_ms\":{:.3},\"max_ms\":{:.3},\"mpix_per_s\":{:.1}}}",
            format.dxgi_name(),
            chain.len(),
            stats.median,
            stats.min,
            stats.max,
            mpix / (stats.median / 1e3)
        );
    } else {
        println!(
            "{} compression of a {size}x{size} normal map and its {} levels, {threads} threads, {runs} runs",
            format.dxgi_name(),
            chain.len()
        );
        println!(
            "  median {:.1} ms (min {:.1}, max {:.1}): {:.0} MPix/s",
            stats.median,
            stats.min,
            stats.max,
            mpix / (stats.median / 1e3)
        );
    }
    Ok(())
}

/// Tangents for the peer's wavy grid (`bumpmap_math::mesh::wavy_grid`); the timed region is
/// `generate_tangents` alone, validation included, as the peer times `genTangSpaceDefault`.
fn bench_tangents(
    triangles: usize,
    mode: bumpmap_math::tangent::TangentMode,
    runs: u32,
    json: bool,
) -> Result<(), CliError> {
    use bumpmap_math::tangent::{TangentOptions, generate_tangents};
    let nx = 1000;
    let ny = (triangles / (2 * nx)).max(1);
    let mesh = bumpmap_math::mesh::wavy_grid(nx, ny);
    let options = TangentOptions { mode, ..Default::default() };
    let mut result = None;
    let stats = time_runs(runs, || {
        result = Some(generate_tangents(&mesh, &options));
    });
    let (out, _) = result.expect("ran").map_err(|e| CliError::Render(e.to_string()))?;
    let threads = rayon::current_num_threads();
    let name = bumpmap::Named::name(mode);
    let tris = mesh.triangle_count();
    if json {
        println!(
            "{{\"bench\":\"tangents\",\"mode\":\"{name}\",\"triangles\":{tris},\"vertices_out\":{},\"threads\":{threads},\"runs\":{runs},\"median_ms\":{:.3},\"min_ms\":{:.3},\"max_ms\":{:.3}}}",
            out.vertex_count(),
            stats.median,
            stats.min,
            stats.max
        );
    } else {
        println!("tangents ({name}) for a {tris}-triangle wavy grid, {threads} threads, {runs} runs");
        println!(
            "  median {:.1} ms (min {:.1}, max {:.1}): {:.2} M triangles/s",
            stats.median,
            stats.min,
            stats.max,
            tris as f64 / stats.median / 1e3
        );
    }
    Ok(())
}

/// Renders `frames` frames per run with the first light orbiting the point looked at, about the
/// view's up axis, once per run: on the torus, the llvmpipe peer's orbit (`(4 cos a, 4 sin a,
/// 3)`, a from −2.2 around the circle). Scene setup (normal map, decal,
/// tessellation, the GPU's device and pipelines) is not timed; per frame: the vertex stage,
/// clearing and every pass are, and on the GPU the wait for the frame to finish (as the peer's
/// `glFinish`; neither reads the frame back).
fn bench_render(args: &BenchRenderArgs) -> Result<(), CliError> {
    use bumpmap_words::frame::lib_err;
    let (size, frames, runs) = (args.size, args.frames, args.runs);
    bumpmap::Renderer::check_size(size, size).map_err(lib_err)?;
    let name = args.setup.0.options.technique.technique;
    if name.is_reference() {
        return Err(CliError::Usage(format!(
            "bench render times frames of the pass-drawing techniques; {name} has its own: bench reference"
        )));
    }
    let setup = crate::setup::setup(&args.setup)?;
    for note in &setup.notes {
        eprintln!("{note}");
    }
    let mut prepared = bumpmap::Prepared::new(&setup.spec, name, &setup.options).map_err(lib_err)?;
    let mut renderer = crate::render::renderer(args.setup.0.backend)?;
    let orbit = bumpmap::motion::LightOrbit::of(&prepared.scene);
    let mut frame = |k: u32| -> Result<(), CliError> {
        orbit.place(&mut prepared.scene, k as f32 / frames as f32, 0.0);
        renderer.draw_unread(&prepared, size, size).map_err(lib_err)
    };
    let mut err = None;
    let stats = time_runs(runs, || {
        for k in 0..frames {
            if let Err(e) = frame(k) {
                err.get_or_insert(e);
            }
        }
    });
    if let Some(e) = err {
        return Err(e);
    }
    let threads = rayon::current_num_threads();
    let fps = frames as f64 / (stats.median / 1e3);
    let scene_name = args.setup.0.options.scene.to_string();
    let (kind, device) = (renderer.backend().name(), renderer.describe());
    if args.json {
        println!(
            "{{\"bench\":\"render\",\"scene\":\"{scene_name}\",\"technique\":\"{name}\",\"backend\":\"{kind}\",\"device\":\"{}\",\"size\":{size},\"threads\":{threads},\"frames\":{frames},\"runs\":{runs},\"fps\":{fps:.2},\"ms_per_frame\":{:.3},\"fps_min\":{:.2},\"fps_max\":{:.2}}}",
            device.replace('"', "'"),
            stats.median / frames as f64,
            frames as f64 / (stats.max / 1e3),
            frames as f64 / (stats.min / 1e3)
        );
    } else {
        println!("render {scene_name} with {name} on {device}, {size}x{size}, {runs} runs of {frames} frames");
        println!(
            "  {fps:.1} frames/s ({:.2} ms/frame; slowest run {:.1} fps, fastest {:.1})",
            stats.median / frames as f64,
            frames as f64 / (stats.max / 1e3),
            frames as f64 / (stats.min / 1e3)
        );
    }
    Ok(())
}

/// The least any implementation must do: read each height byte once and write every output
/// byte (all levels) once, with the same threads and fresh output buffers.
fn read_once_write_once(bytes: &[u8], size: usize) -> Vec<Vec<[u8; 4]>> {
    let mut out = Vec::new();
    let mut n = size;
    let mut stride = 1;
    loop {
        // The same allocation as the real work's, so the floor pays the same page costs.
        let mut level = bumpmap_math::buffer::zeroed_rgba8(n * n);
        level.par_chunks_mut(n).enumerate().for_each(|(y, row)| {
            let src = &bytes[y * stride * size..];
            for (x, t) in row.iter_mut().enumerate() {
                let h = src[x * stride];
                *t = [h, h, h, 255];
            }
        });
        out.push(level);
        if n == 1 {
            break;
        }
        n = next_size(n);
        stride *= 2;
    }
    out
}
