//! `bumpmap normalmap`'s options: the library's map, channel and format tables, and the files
//! the command writes.

use std::path::PathBuf;

use bumpmap::maps::MapOptions;
use bumpmap::option_table::{CHANNEL, FORMAT, MAPS};
use bumpmap_io::Channel;
use bumpmap_io::texture_file::TextureFormat;
use clap::Args;

use crate::args::table::{Table, rows};

rows!(
    /// How heights become normals and what else is made: the library's [`MAPS`] table.
    Maps: MapOptions = MAPS
);
rows!(
    /// Which channel holds the heights: the library's [`CHANNEL`] table.
    Channels: Channel = CHANNEL
);
rows!(
    /// A texture file's texel format: the library's [`FORMAT`] table.
    Formats: TextureFormat = FORMAT
);

#[derive(Args, Debug)]
#[command(
    mut_arg("format", |a| a.ignore_case(true)),
    mut_arg("roughness", |a| a.requires("roughness_out")),
    mut_arg("roughness-layout", |a| a.requires("roughness_out")),
    after_help = "Examples:\n  \
bumpmap normalmap heights.png -o normals.png --mips        # normals.png, normals.mip1.png, …\n  \
bumpmap normalmap bricks@512 -o bricks.ktx2 --mips         # a preset, all levels in one file\n  \
bumpmap normalmap textures/ -o normals/ --scale 8          # every image in a folder, in parallel\n  \
bumpmap normalmap rock.png -o rock.dds --mips --format bc5  # BC5 for an engine (Z rebuilt in the shader)\n  \
bumpmap normalmap scan16.png -o rock.png --bits 16         # 16-bit PNG, no banding on gentle slopes\n  \
bumpmap normalmap bricks -o n.png --mips --height-out h.png --bits 16   # + heights for --technique pom\n  \
bumpmap normalmap bricks -o n.png --horizon-out hz.png --ao-out ao.png --bent-normals-out bent.png   # shadows, AO\n\n\
IN is an image file (PNG, TGA, BMP, JPEG, TIFF, PNM at 8 or 16 bits; OpenEXR in float), a folder of them, or a \
preset: bricks, pinwheel, dimples, noise:SEED, each optionally @SIZE (default 256). Green points \
up the image as displayed (glTF, Blender, Unity) unless --y-convention directx."
)]
/// `bumpmap normalmap`.
pub struct NormalmapArgs {
    /// Height field: image file, folder, or preset (bricks, pinwheel, dimples, noise:SEED[@SIZE])
    pub input: String,
    /// Output: .png (level 0; with --mips also OUT.mip1.png, …), .dds or .ktx2 (all levels), or a folder
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also make every smaller level down to 1×1
    #[arg(long)]
    pub mips: bool,
    /// Texel format of .dds and .ktx2 outputs (the library's [`FORMAT`] table).
    #[command(flatten)]
    pub format: Table<Formats>,
    /// How heights become normals, the chain, the bits and the roughness (the library's [`MAPS`]).
    #[command(flatten)]
    pub maps: Table<Maps>,
    /// Which channel holds the heights (the library's [`CHANNEL`] table).
    #[command(flatten)]
    pub channel: Table<Channels>,
    /// Also write a roughness map with a level for each normal-map level (.png: R.png, R.mip1.png, …; .dds or .ktx2: all levels, RGBA8): each texel the --roughness of the surface made rougher by the spread of the normals it averages (Filament's prefilter: α′ = √(α² + 2/κ), κ from the mean normal's length), what GGX shaders in engines read in place of the length factor
    #[arg(long = "roughness-out", requires = "mips")]
    pub roughness_out: Option<PathBuf>,
    /// Also write LEAN mapping's moments (Olano & Baker 2010) for every level, as 32-bit floats in .ktx2 or .dds: L.ktx2 holds (Bx, By, Mxx, Myy), L.mxy-j.ktx2 holds (Mxy, J, 0, 0), with B = (Nx/Nz, Ny/Nz), M = (Bx², BxBy, By²), J = 1/Nz³, each level the mean over the level-0 texels it covers of the 8-bit normal map's; what `--specular-filter lean` renders from
    #[arg(long = "lean-out", requires = "mips")]
    pub lean_out: Option<PathBuf>,
    /// Also write the heights as the parallax techniques read them (`render --height-map`), every level at --bits, with the min–max levels the exact walk reads: .png: H.png, H.mip1.png, … and H.minmax.png, H.minmax.mip1.png, … (16-bit RGB, R the lower bound, G the upper); .ktx2 or .dds: H (R8 or R16_UNORM) and H.minmax (R16G16_UNORM). Heights are clamped to [0, 1], 1 the surface
    #[arg(long = "height-out", value_name = "H")]
    pub height_out: Option<PathBuf>,
    /// Also write the horizon map (Max 1988; Sloan & Cohen 2000): per texel, how high the heights around it rise in 8 directions, k·45° from +s toward +t (down the image), as two RGBA textures at --bits: .png: H.png (directions 0–3 in R, G, B, A) and H.dirs4-7.png (4–7), with H.mip1.png, … under --mips; .ktx2 or .dds: H and H.dirs4-7, every level under --mips. A channel is atan(rise)/90°, the rise in heights per texel: the same map serves every --scale
    #[arg(long = "horizon-out", value_name = "H")]
    pub horizon_out: Option<PathBuf>,
    /// Also write ambient occlusion from the horizons at --scale: the cosine-weighted share of the sky each texel sees past the heights around it (1 open, 0 closed), one gray level at --bits (.png, or R8/R16 .ktx2/.dds)
    #[arg(long = "ao-out", value_name = "A")]
    pub ao_out: Option<PathBuf>,
    /// Also write bent normals from the horizons at --scale: the mean direction of the open sky, as a tangent-space normal map in the same conventions as the normal map (--y-convention, --encoding, --bits), level 0 (.png, .ktx2, .dds); for the ambient term in engines that read them (Godot, Unreal)
    #[arg(long = "bent-normals-out", value_name = "B")]
    pub bent_normals_out: Option<PathBuf>,
}

pub(super) fn parse_bits(s: &str) -> Result<u8, String> {
    match s {
        "8" => Ok(8),
        "16" => Ok(16),
        _ => Err(format!("'{s}' is not 8 or 16")),
    }
}
