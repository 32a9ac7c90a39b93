//! `bumpmap blend`'s options: the library's [`BLEND`] table, and the files.

use std::path::PathBuf;

use bumpmap::maps::BlendOptions;
use bumpmap::option_table::BLEND;
use clap::Args;

use crate::args::table::{Table, rows};

rows!(
    /// How the detail is laid over the base and the result stored: the library's [`BLEND`] table.
    Blend: BlendOptions = BLEND
);

/// `bumpmap blend`.
#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap blend rock_normal.png pores_normal.png -o rock_detailed.png --detail-repeat 8\n  \
bumpmap blend base.png detail.png -o out.png --method partial-derivative --detail-strength 0.5\n  \
bumpmap blend base.png unreal_detail.png -o out.ktx2 --detail-y-convention directx --mips\n\n\
Each texel of BASE gets DETAIL's normal at its place (DETAIL repeated --detail-repeat times \
across, bilinear, wrapping), its slopes times --detail-strength, laid over BASE's normal by \
--method. Which is right depends on what the detail is: rnm turns the detail into the base's \
frame, exact for a detail draped over the base's bumps (fabric on a sculpted form); \
partial-derivative adds slopes, exact for heights that add (pores in a rock). whiteout and udn \
come close to both, linear and overlay flatten the result. The result has BASE's size; a DETAIL \
of other bits, or green the other way (--detail-y-convention), is converted and said.")]
pub struct BlendArgs {
    /// The base normal map: PNG (8/16-bit), TGA, TIFF, JPEG, OpenEXR, DDS or KTX2 (level 0 is used)
    pub base: PathBuf,
    /// The detail normal map, in any of the same formats
    pub detail: PathBuf,
    /// Output: .png (with .mipN.png beside it with --mips), .dds or .ktx2
    #[arg(short, long)]
    pub output: PathBuf,
    /// How the detail is laid over the base and the result stored.
    #[command(flatten)]
    pub blend: Table<Blend>,
}
