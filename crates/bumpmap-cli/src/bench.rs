//! `bumpmap bench`: wall-clock medians of the project's hot paths, in prose or one JSON line.
//!
//! Each benchmark builds its input once, runs once to warm up, then times `--runs` runs.
//! Figures for BENCHMARKS.md come from here and from criterion (`cargo bench`).

use std::time::Instant;

use bumpmap_math::{HeightField, HeightPreset, MipChain, MipMode, NormalMapOptions, mip::next_size};
use rayon::prelude::*;

use crate::args::{BenchArgs, BenchWhat};
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
        BenchWhat::Normalmap { size, runs, threads, json } => {
            with_threads(threads, || bench_normalmap(size as usize, runs, json))
        }
    }
}

/// Runs `f` on a pool of `threads` workers (all cores when `None`).
pub fn with_threads<T: Send>(threads: Option<usize>, f: impl FnOnce() -> T + Send) -> T {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads.unwrap_or(0)).build().expect("thread pool");
    pool.install(f)
}

/// The benchmark's height field: bricks plus 3 bits of seeded noise, like the NumPy peer's.
pub fn bench_heights(size: usize) -> Vec<u8> {
    let bricks = HeightPreset::Bricks.render(size, size);
    let noise = HeightPreset::Noise(7).render(size, size);
    bricks.to_f32().iter().zip(&noise.to_f32()).map(|(b, n)| (b * 247.0 + n * 8.0).clamp(0.0, 255.0) as u8).collect()
}

fn bench_normalmap(size: usize, runs: u32, json: bool) -> Result<(), CliError> {
    let bytes = bench_heights(size);
    let options = NormalMapOptions::default();
    let mut levels = 0;
    let work = time_runs(runs, || {
        let field = HeightField::from_u8(size, size, &bytes).expect("square field");
        let chain = MipChain::from_height(&field, &options, MipMode::LengthInAlpha).expect("valid options");
        levels = chain.len();
    });
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

/// The least any implementation must do: read each height byte once and write every output
/// byte (all levels) once, with the same threads and fresh output buffers.
fn read_once_write_once(bytes: &[u8], size: usize) -> Vec<Vec<[u8; 4]>> {
    let mut out = Vec::new();
    let mut n = size;
    let mut stride = 1;
    loop {
        let mut level = vec![[0u8; 4]; n * n];
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
