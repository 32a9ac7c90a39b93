//! `bumpmap bench`: the library's timings (`bumpmap::bench`) in prose or one JSON line.
//! Figures for BENCHMARKS.md come from here and from criterion (`cargo bench`).

use bumpmap::bench::{self, BenchError, Stats, with_threads};
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_math::tangent::TangentMode;
use bumpmap_words::frame::{core_err, lib_err};

use crate::args::{BenchArgs, BenchRenderArgs, BenchWhat};
use crate::error::CliError;

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

/// A benchmark's refusal in the command line's words.
fn bench_err(e: BenchError) -> CliError {
    match e {
        BenchError::NormalMap(source) => CliError::NormalMap { path: "the benchmark's heights".into(), source },
        BenchError::Reference(e) => CliError::Render(bumpmap_words::frame::reference_err(e)),
        other => CliError::Render(other.to_string()),
    }
}

/// `"median_ms":…,"min_ms":…,"max_ms":…` of one JSON line.
fn json_stats(s: &Stats) -> String {
    format!("\"median_ms\":{:.3},\"min_ms\":{:.3},\"max_ms\":{:.3}", s.median, s.min, s.max)
}

fn bench_height(size: usize, runs: u32, json: bool) -> Result<(), CliError> {
    let t = bench::height(size, runs).map_err(bench_err)?;
    let (threads, all, solve) = (t.threads, t.all, t.solve);
    if json {
        println!(
            "{{\"bench\":\"height\",\"size\":{size},\"threads\":{threads},\"runs\":{runs},{},\"solve_median_ms\":{:.3}}}",
            json_stats(&all),
            solve.median
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

fn bench_reference(scene: &str, size: usize, spp: usize, runs: u32, json: bool) -> Result<(), CliError> {
    use bumpmap_core::scenes::{self, SceneKind, SceneParams};
    let kind = SceneKind::parse(scene)
        .ok_or_else(|| CliError::Usage(format!("unknown scene '{scene}': use {}", SceneKind::built_in_names())))?;
    // The framebuffer limit `render` and `compare` apply, before any work.
    bumpmap::Renderer::check_size(size, size).map_err(lib_err)?;
    let built = scenes::build(&kind, &SceneParams::default()).map_err(core_err)?;
    let stats = bench::reference(&built, size, spp, runs).map_err(bench_err)?;
    let threads = rayon::current_num_threads();
    let msamples = (size * size * spp) as f64 / stats.median / 1e3;
    if json {
        println!(
            "{{\"bench\":\"reference\",\"scene\":\"{scene}\",\"size\":{size},\"spp\":{spp},\"threads\":{threads},\"runs\":{runs},{},\"msamples_per_s\":{msamples:.1}}}",
            json_stats(&stats)
        );
    } else {
        println!(
            "reference {scene} {size}² at {spp} samples per pixel on {threads} threads: median {:.1} ms ({msamples:.1} M samples/s; min {:.1}, max {:.1})",
            stats.median, stats.min, stats.max
        );
    }
    Ok(())
}

fn bench_normalmap(size: usize, format: Option<TextureFormat>, runs: u32, json: bool) -> Result<(), CliError> {
    let (t, chain) = bench::normal_map(size, runs);
    let (levels, threads, work) = (t.levels, t.threads, t.work);
    if let Some(format) = format {
        let c = bench::compression(&chain, format, runs)?;
        let mpix = c.texels as f64 / 1e6 / (c.stats.median / 1e3);
        let name = format.dxgi_name();
        if json {
            println!(
                "{{\"bench\":\"compress\",\"format\":\"{name}\",\"size\":{size},\"levels\":{levels},\"threads\":{threads},\"runs\":{runs},{},\"mpix_per_s\":{mpix:.1}}}",
                json_stats(&c.stats)
            );
        } else {
            println!(
                "{name} compression of a {size}x{size} normal map and its {levels} levels, {threads} threads, {runs} runs"
            );
            println!(
                "  median {:.1} ms (min {:.1}, max {:.1}): {mpix:.0} MPix/s",
                c.stats.median, c.stats.min, c.stats.max
            );
        }
        return Ok(());
    }
    let floor = bench::floor(size, runs);
    let mpix = (size * size) as f64 / 1e6 / (work.median / 1e3);
    let ratio = work.median / floor.median;
    if json {
        println!(
            "{{\"bench\":\"normalmap\",\"size\":{size},\"levels\":{levels},\"threads\":{threads},\"runs\":{runs},{},\"floor_median_ms\":{:.3},\"ratio_to_floor\":{ratio:.3},\"mpix_per_s\":{mpix:.1}}}",
            json_stats(&work),
            floor.median
        );
    } else {
        println!("normal map + {levels}-level mip chain, {size}x{size} 8-bit heights, {threads} threads, {runs} runs");
        println!("  median {:.2} ms (min {:.2}, max {:.2}): {mpix:.0} MPix/s", work.median, work.min, work.max);
        println!("  floor (read the input once, write every output byte once): median {:.2} ms", floor.median);
        println!("  ratio to the floor: {ratio:.2}x");
    }
    Ok(())
}

fn bench_tangents(triangles: usize, mode: TangentMode, runs: u32, json: bool) -> Result<(), CliError> {
    let t = bench::tangents(triangles, mode, runs).map_err(bench_err)?;
    let (name, tris, threads, stats) = (bumpmap::Named::name(mode), t.triangles, t.threads, t.stats);
    if json {
        println!(
            "{{\"bench\":\"tangents\",\"mode\":\"{name}\",\"triangles\":{tris},\"vertices_out\":{},\"threads\":{threads},\"runs\":{runs},{}}}",
            t.vertices_out,
            json_stats(&stats)
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

/// `bench render`: the scene set up as `render` sets it up, then `bumpmap::bench::render`.
fn bench_render(args: &BenchRenderArgs) -> Result<(), CliError> {
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
    let stats = bench::render(&mut renderer, &mut prepared, size, frames, runs).map_err(lib_err)?;
    let threads = rayon::current_num_threads();
    let fps = frames as f64 / (stats.median / 1e3);
    let (slowest, fastest) = (frames as f64 / (stats.max / 1e3), frames as f64 / (stats.min / 1e3));
    let per_frame = stats.median / frames as f64;
    let scene_name = args.setup.0.options.scene.to_string();
    let (kind, device) = (renderer.backend().name(), renderer.describe());
    if args.json {
        println!(
            "{{\"bench\":\"render\",\"scene\":\"{scene_name}\",\"technique\":\"{name}\",\"backend\":\"{kind}\",\"device\":\"{}\",\"size\":{size},\"threads\":{threads},\"frames\":{frames},\"runs\":{runs},\"fps\":{fps:.2},\"ms_per_frame\":{per_frame:.3},\"fps_min\":{slowest:.2},\"fps_max\":{fastest:.2}}}",
            device.replace('"', "'")
        );
    } else {
        println!("render {scene_name} with {name} on {device}, {size}x{size}, {runs} runs of {frames} frames");
        println!("  {fps:.1} frames/s ({per_frame:.2} ms/frame; slowest run {slowest:.1} fps, fastest {fastest:.1})");
    }
    Ok(())
}
