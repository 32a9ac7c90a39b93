//! `bumpmap cubemap`'s options.

use std::path::PathBuf;

use clap::Args;

use bumpmap_math::Encoding;

use crate::args::choice;

/// `bumpmap cubemap`.
#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap cubemap --size 32 --encoding kilgard -o cube/   # cube/px.png … cube/nz.png\n  \
bumpmap cubemap --size 64 -o normcube.dds\n  \
bumpmap cubemap --accuracy                               # worst angular error table\n\n\
Faces are +X, −X, +Y, −Y, +Z, −Z with Kilgard Table 1 addressing; rows in memory order.")]
pub struct CubemapArgs {
    /// Texels along each face's edge
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub size: u32,
    /// Byte encoding of the vectors
    #[arg(long, value_parser = choice::<Encoding>(), default_value = "unorm")]
    pub encoding: Encoding,
    /// A folder (six PNG faces), or a .dds / .ktx2 cube-map file
    #[arg(short, long, required_unless_present = "accuracy")]
    pub output: Option<PathBuf>,
    /// Print the worst angular error of the bilinear lookup for face sizes 8–128, both encodings (writes nothing; takes no other option)
    #[arg(long, conflicts_with_all = ["output", "size", "encoding"])]
    pub accuracy: bool,
}
