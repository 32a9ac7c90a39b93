//! `bumpmap bench`'s subcommands and options.

use clap::{Args, Subcommand};

use bumpmap_math::tangent::TangentMode;

use bumpmap_io::texture_file::TextureFormat;

use crate::args::{BenchRenderArgs, choice, parse_side};

/// `bumpmap bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// What to measure.
    #[command(subcommand)]
    pub what: BenchWhat,
}

/// What `bench` measures.
#[derive(Subcommand, Debug)]
pub enum BenchWhat {
    /// 8-bit height field → normal map + full mip chain, and the read-once/write-once floor
    Normalmap {
        /// Edge length of the square height field
        #[arg(long, default_value_t = 4096, value_parser = clap::value_parser!(u32).range(1..=16384))]
        size: u32,
        /// Also time compressing the chain to this format (bc5, bc7), every level
        #[arg(long, value_parser = choice::<TextureFormat>(), ignore_case = true)]
        format: Option<TextureFormat>,
        /// Timed runs (after one warm-up)
        #[arg(long, default_value_t = 9, value_parser = clap::value_parser!(u32).range(1..))]
        runs: u32,
        /// Worker threads, 1 to 256 (default: all cores)
        #[arg(long, value_parser = clap::value_parser!(u16).range(1..=256))]
        threads: Option<u16>,
        /// Print one JSON line instead of prose
        #[arg(long)]
        json: bool,
    },
    /// 16-bit normal map → heights (what `height` does after decoding): the curl and seam tests,
    /// the kernel fit and the solve, and the solve alone
    Height {
        /// Edge length of the square map
        #[arg(long, default_value_t = 4096, value_parser = clap::value_parser!(u32).range(2..=16384))]
        size: u32,
        /// Timed runs (after one warm-up)
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..))]
        runs: u32,
        /// Worker threads, 1 to 256 (default: all cores)
        #[arg(long, value_parser = clap::value_parser!(u16).range(1..=256))]
        threads: Option<u16>,
        /// Print one JSON line instead of prose
        #[arg(long)]
        json: bool,
    },
    /// Tangents for a wavy textured grid of N triangles (the MikkTSpace peer's mesh)
    Tangents {
        /// Triangles (rounded to a 1000-column grid)
        #[arg(long, default_value_t = 1_000_000, value_parser = clap::value_parser!(u32).range(2000..=50_000_000))]
        triangles: u32,
        /// Which algorithm
        #[arg(long, value_parser = choice::<TangentMode>(), default_value = "ours")]
        mode: TangentMode,
        /// Timed runs (after one warm-up)
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..))]
        runs: u32,
        /// Worker threads, 1 to 256 (default: all cores)
        #[arg(long, value_parser = clap::value_parser!(u16).range(1..=256))]
        threads: Option<u16>,
        /// Print one JSON line instead of prose
        #[arg(long)]
        json: bool,
    },
    /// Frames per second of a scene, the light orbiting as in the llvmpipe peer; takes every
    /// scene, light, material, technique and backend option of `render`
    Render(Box<BenchRenderArgs>),
    /// The reference renderer: one image of a built-in scene at SIZE² with SPP samples per pixel
    Reference {
        /// Built-in scene: torus, wall, floor, wall-floor, patch, sphere
        #[arg(long, default_value = "torus")]
        scene: String,
        /// Square image size
        #[arg(long, default_value_t = 512, value_parser = parse_side)]
        size: usize,
        /// Samples per pixel
        #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=4096))]
        spp: u32,
        /// Timed runs (after one warm-up)
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..))]
        runs: u32,
        /// Worker threads, 1 to 256 (default: all cores)
        #[arg(long, value_parser = clap::value_parser!(u16).range(1..=256))]
        threads: Option<u16>,
        /// Print one JSON line instead of prose
        #[arg(long)]
        json: bool,
    },
}
