//! The project's hot paths timed as `bumpmap bench` times them, for BENCHMARKS.md and
//! `scripts/compare_peers.sh`: each benchmark builds its input once, runs once to warm up, then
//! times `runs` runs and keeps their median, fastest and slowest ([`Stats`], milliseconds).
//!
//! ```
//! use bumpmap::bench;
//! let (times, _chain) = bench::normal_map(64, 3);
//! assert_eq!(times.levels, 7);
//! assert!(times.work.min <= times.work.median && times.work.median <= times.work.max);
//! assert!(bench::floor(64, 3).median > 0.0);
//! ```
//!
//! What this module does not do: say anything (each benchmark returns its figures, for a
//! command to print as prose or JSON), or choose threads (run it inside [`with_threads`]).

use std::time::Instant;

use bumpmap_io::IoError;
use bumpmap_io::texture_file::{TextureFormat, TextureLayout};
use bumpmap_math::integration::IntegrationError;
use bumpmap_math::mesh::MeshError;
use bumpmap_math::mip::next_size;
use bumpmap_math::normalmap::NormalMapError;
use bumpmap_math::tangent::TangentMode;
use bumpmap_reference::ReferenceError;
use rayon::prelude::*;

use crate::{Error, HeightField, HeightPreset, MipChain, MipMode, NormalMapOptions, Prepared, Renderer, Scene};

/// Median, fastest and slowest of a set of runs, in milliseconds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stats {
    /// The median run.
    pub median: f64,
    /// The fastest run.
    pub min: f64,
    /// The slowest run.
    pub max: f64,
}

/// Runs `f` once to warm up, then `runs` times (at least once), and returns the timings.
pub fn time_runs(runs: u32, mut f: impl FnMut()) -> Stats {
    f();
    let mut ms: Vec<f64> = (0..runs.max(1))
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    ms.sort_by(f64::total_cmp);
    Stats { median: ms[ms.len() / 2], min: ms[0], max: ms[ms.len() - 1] }
}

/// Runs `f` on a pool of `threads` workers (all cores when `None`).
pub fn with_threads<T: Send>(threads: Option<u16>, f: impl FnOnce() -> T + Send) -> T {
    let pool =
        rayon::ThreadPoolBuilder::new().num_threads(threads.map_or(0, usize::from)).build().expect("thread pool");
    pool.install(f)
}

/// The benchmarks' height field, `size`² bytes: bricks plus 3 bits of seeded noise, like the
/// NumPy peer's.
pub fn heights(size: usize) -> Vec<u8> {
    let bricks = HeightPreset::Bricks.render(size, size);
    let noise = HeightPreset::Noise(7).render(size, size);
    bricks.to_f32().iter().zip(&noise.to_f32()).map(|(b, n)| (b * 247.0 + n * 8.0).clamp(0.0, 255.0) as u8).collect()
}

/// [`normal_map`]'s figures.
#[derive(Clone, Copy, Debug)]
pub struct NormalMapTimes {
    /// Levels of the chain (`size`² down to 1²).
    pub levels: usize,
    /// Worker threads.
    pub threads: usize,
    /// Heights → normal map and its chain.
    pub work: Stats,
}

/// The [`heights`] of `size`² into a normal map and its whole chain (8 bits, the length in
/// alpha); returns the last chain made too.
pub fn normal_map(size: usize, runs: u32) -> (NormalMapTimes, MipChain) {
    let bytes = heights(size);
    let options = NormalMapOptions::default();
    let mut last = None;
    let work = time_runs(runs, || {
        let field = HeightField::from_u8(size, size, &bytes).expect("a square field of its own bytes");
        last = Some(MipChain::<[u8; 4]>::from_height(&field, &options, MipMode::LengthInAlpha).expect("valid options"));
    });
    let chain = last.expect("ran at least once");
    (NormalMapTimes { levels: chain.len(), threads: rayon::current_num_threads(), work }, chain)
}

/// The floor beside [`normal_map`]: the least any implementation must do, reading each height
/// byte once and writing every output byte (all levels) once, with the same threads and fresh
/// buffers.
pub fn floor(size: usize, runs: u32) -> Stats {
    let bytes = heights(size);
    time_runs(runs, || {
        std::hint::black_box(read_once_write_once(&bytes, size));
    })
}

/// [`compression`]'s figures.
#[derive(Clone, Copy, Debug)]
pub struct CompressionTimes {
    /// Texels of every level together.
    pub texels: usize,
    /// Worker threads.
    pub threads: usize,
    /// The chain's levels compressed.
    pub stats: Stats,
}

/// Compressing a finished `chain` (every level, in parallel) to `format`.
pub fn compression(chain: &MipChain, format: TextureFormat, runs: u32) -> Result<CompressionTimes, IoError> {
    let layout = TextureLayout { faces: vec![chain.levels.iter().map(Into::into).collect()] };
    let mut failed = None;
    let stats = time_runs(runs, || {
        if let Err(e) = bumpmap_io::texture_file::encode(std::path::Path::new("bench"), &layout, format) {
            failed = Some(e);
        }
    });
    match failed {
        Some(e) => Err(e),
        None => Ok(CompressionTimes {
            texels: chain.levels.iter().map(|l| l.width * l.height).sum(),
            threads: rayon::current_num_threads(),
            stats,
        }),
    }
}

/// [`height`]'s figures.
#[derive(Clone, Copy, Debug)]
pub struct HeightTimes {
    /// Worker threads.
    pub threads: usize,
    /// The curl and seam tests, the kernel fit and the solve.
    pub all: Stats,
    /// The solve alone (kernel, convention and method given).
    pub solve: Stats,
}

/// Why a benchmark could not run.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// The benchmark's normal map could not be made.
    #[error(transparent)]
    NormalMap(#[from] NormalMapError),
    /// The heights could not be integrated.
    #[error(transparent)]
    Integration(#[from] IntegrationError),
    /// The tangents could not be made.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The reference could not render.
    #[error(transparent)]
    Reference(#[from] ReferenceError),
}

/// Normal map → heights on the [`heights`] of `size`² made into a 16-bit map (forward kernel,
/// scale 4, green up); making and decoding the map are not timed.
pub fn height(size: usize, runs: u32) -> Result<HeightTimes, BenchError> {
    use crate::heights::{HeightOptions, heights_from_normals};
    use bumpmap_math::integration::{Boundary, Derivative};
    let field = HeightField::from_u8(size, size, &heights(size)).expect("a square field of its own bytes");
    let options = NormalMapOptions { y_convention: bumpmap_math::YConvention::YUp, ..Default::default() };
    let level0 = bumpmap_math::normalmap::normal_map_level0_texels::<[u16; 4]>(&field, &options)?;
    let normals = bumpmap_math::inspect::signed_levels(&[level0]).remove(0);
    let mut failure = None;
    let mut run = |options: &HeightOptions| {
        if let Err(e) = heights_from_normals(&normals, options) {
            failure = Some(e);
        }
    };
    let all = time_runs(runs, || run(&HeightOptions { scale: 4.0, ..Default::default() }));
    let given = HeightOptions {
        boundary: Some(Boundary::Periodic),
        derivative: Some(Derivative::Kernel(bumpmap_math::Kernel::Forward)),
        y_convention: Some(bumpmap_math::YConvention::YUp),
        scale: 4.0,
    };
    let solve = time_runs(runs, || run(&given));
    match failure {
        Some(e) => Err(e.into()),
        None => Ok(HeightTimes { threads: rayon::current_num_threads(), all, solve }),
    }
}

/// [`tangents`]' figures.
#[derive(Clone, Copy, Debug)]
pub struct TangentTimes {
    /// Triangles of the grid.
    pub triangles: usize,
    /// Vertices of the mesh made (split where frames differ).
    pub vertices_out: usize,
    /// Worker threads.
    pub threads: usize,
    /// `generate_tangents`, validation included.
    pub stats: Stats,
}

/// Tangents by `mode` for the MikkTSpace peer's wavy grid of about `triangles` triangles
/// (`bumpmap_math::mesh::wavy_grid`, 1000 columns); the timed region is `generate_tangents`
/// alone, as the peer times `genTangSpaceDefault`.
pub fn tangents(triangles: usize, mode: TangentMode, runs: u32) -> Result<TangentTimes, BenchError> {
    use bumpmap_math::tangent::{TangentOptions, generate_tangents};
    let nx = 1000;
    let mesh = bumpmap_math::mesh::wavy_grid(nx, (triangles / (2 * nx)).max(1));
    let options = TangentOptions { mode, ..Default::default() };
    let mut result = None;
    let stats = time_runs(runs, || result = Some(generate_tangents(&mesh, &options)));
    let (out, _) = result.expect("ran at least once")?;
    Ok(TangentTimes {
        triangles: mesh.triangle_count(),
        vertices_out: out.vertex_count(),
        threads: rayon::current_num_threads(),
        stats,
    })
}

/// `frames` frames of `prepared` at `size`² by `renderer` a run, the first light orbiting the
/// point looked at about the view's up axis once per run (on the torus, the llvmpipe peer's
/// orbit: `(4 cos a, 4 sin a, 3)`, a from −2.2 around the circle). Per frame, the vertex
/// stage, clearing and every pass are timed, and on the GPU the wait for the frame to finish
/// (as the peer's `glFinish`; neither reads the frame back); setting the scene up is not.
pub fn render(
    renderer: &mut Renderer,
    prepared: &mut Prepared,
    size: usize,
    frames: u32,
    runs: u32,
) -> Result<Stats, Error> {
    Renderer::check_size(size, size)?;
    let orbit = crate::motion::LightOrbit::of(&prepared.scene);
    let mut err = None;
    let stats = time_runs(runs, || {
        for k in 0..frames {
            orbit.place(&mut prepared.scene, k as f32 / frames as f32, 0.0);
            if let Err(e) = renderer.draw_unread(prepared, size, size) {
                err.get_or_insert(e);
            }
        }
    });
    match err {
        Some(e) => Err(e),
        None => Ok(stats),
    }
}

/// The reference renderer's time for one `size`² image of `scene` at `spp` samples a pixel;
/// setting the scene up is not timed.
pub fn reference(scene: &Scene, size: usize, spp: usize, runs: u32) -> Result<Stats, BenchError> {
    let options = bumpmap_reference::ReferenceOptions { samples_per_pixel: spp, ..Default::default() };
    let mut failure = None;
    let stats = time_runs(runs, || {
        if let Err(e) = bumpmap_reference::render(scene, size, size, &options, &|_, _| {}) {
            failure = Some(e);
        }
    });
    match failure {
        Some(e) => Err(e.into()),
        None => Ok(stats),
    }
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
