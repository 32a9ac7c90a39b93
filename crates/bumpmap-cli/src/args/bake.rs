//! `bumpmap bake`'s options: the library's [`BAKE`] table, and the files.

use std::path::PathBuf;

use bumpmap::bake::{BakeMap, BakeRequest};
use bumpmap::option_table::BAKE;
use clap::Args;

use crate::args::table::{Table, rows};

rows!(
    /// How the bake is made and its map stored: the library's [`BAKE`] table.
    Bake: BakeRequest = BAKE
);

/// `--maps`' values: the library's [`BakeMap`] names.
fn bake_maps() -> impl clap::builder::TypedValueParser<Value = BakeMap> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(BakeMap::ALL.map(BakeMap::name))
        .map(|name: String| BakeMap::parse(&name).expect("one of the names listed"))
}

/// `bumpmap bake`.
#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap bake sculpt.glb game.glb -o game_normal.png\n  \
bumpmap bake sculpt.obj game.obj -o n.png --size 2048 --spp 4 --extrude 0.05 --max-distance 0.05\n  \
bumpmap bake high.glb low.glb -o n.png --low-out low_baked.glb --mask-out missed.png\n  \
bumpmap bake high.glb low.glb -o n.png --maps ao,height,mask   # also n_ao.png, n_height.png, n_mask.png\n  \
bumpmap render --scene mesh:low_baked.glb --technique single-pass   # the low-poly with its bake\n\n\
Each texel of LOW's UV layout casts rays from the low-poly surface into the high-poly one: \
from --extrude in front of LOW (the cage) inward as far as --max-distance behind it, the \
first hit from the cage inward winning (as xNormal and Marmoset do), along LOW's averaged \
normals by default (--ray explicit: its own, split at hard edges). The hit's normal is \
stored in LOW's tangent frame, inverted exactly for the decode the map is made for \
(--decode): the renderer then shows the high-poly's shading on the low-poly. A bake where \
most rays meet nothing is an error, never a flat map.")]
pub struct BakeArgs {
    /// The high-poly mesh (.obj, .gltf, .glb): what the map records
    pub high: PathBuf,
    /// The low-poly mesh (.obj, .gltf, .glb), with texture coordinates: what the map is drawn on
    pub low: PathBuf,
    /// The tangent-space normal map: .png (with .mipN.png beside it with --mips), .dds or .ktx2
    #[arg(short, long)]
    pub output: PathBuf,
    /// How the bake is made and stored.
    #[command(flatten)]
    pub bake: Table<Bake>,
    /// Also write these maps, each beside the normal map as STEM_MAP.png (-o n.png --maps ao,low: n_ao.png, n_low.glb); an --*-out flag below names a map's file instead. Comma-separated
    #[arg(long, value_delimiter = ',', value_name = "MAP,...", value_parser = bake_maps())]
    pub maps: Vec<BakeMap>,
    /// Also write the object-space normals (8-bit RGB PNG)
    #[arg(long = "object-out")]
    pub object_out: Option<PathBuf>,
    /// Also write HIGH's ambient occlusion (gray PNG, 8 or 16 bits as --bits: 1 unoccluded), --ao-rays rays a sample
    #[arg(long = "ao-out")]
    pub ao_out: Option<PathBuf>,
    /// Also write the displacement: the signed distance from LOW to HIGH along each ray, 16-bit gray mapped from its range (.exr: the distances themselves, 32-bit float), the range beside it as STEM.range.json
    #[arg(long = "height-out")]
    pub height_out: Option<PathBuf>,
    /// Also write HIGH's mean curvature: 16-bit gray, mid-gray flat, lighter where convex, darker in creases, mapped from ±its 99th percentile (.exr: the values themselves, 32-bit float), the range beside it as STEM.range.json
    #[arg(long = "curvature-out")]
    pub curvature_out: Option<PathBuf>,
    /// Also write which texels' rays met HIGH (8-bit gray PNG: 255 hit, 0 missed or outside the UVs)
    #[arg(long = "mask-out")]
    pub mask_out: Option<PathBuf>,
    /// Also write LOW as baked for (.glb or .gltf): its normals and tangents as the map was made for them, the map as its normalTexture (needs a .png map, green up)
    #[arg(long = "low-out")]
    pub low_out: Option<PathBuf>,
}
