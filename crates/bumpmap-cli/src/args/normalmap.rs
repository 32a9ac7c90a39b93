//! `bumpmap normalmap`'s options, and the kernel, wrap, encoding, mip-mode and channel choices
//! every command that makes a normal map shares.

use std::path::PathBuf;

use bumpmap_io::Channel;
use bumpmap_math::{Encoding, Kernel, MipMode, Wrap};
use clap::Args;

use bumpmap::YConvention;
use bumpmap::options::RoughnessLayout;

use bumpmap_io::texture_file::TextureFormat;

use crate::args::{choice, parse_f32};

/// Options that decide how heights become normals; shared by every command that makes one.
#[derive(Args, Debug, Clone)]
pub struct NormalMapOpts {
    /// Finite-difference kernel for ∂F/∂u and ∂F/∂v
    #[arg(long, value_parser = choice::<Kernel>(), default_value = "forward")]
    pub kernel: Kernel,
    /// Bump height: heights are in [0,1], derivatives per texel, n ∝ (−scale·∂F/∂u, −scale·∂F/∂v, 1)
    #[arg(value_parser = parse_f32, long, default_value_t = 4.0, allow_negative_numbers = true)]
    pub scale: f32,
    /// What the kernel reads beyond the edges
    #[arg(long, value_parser = choice::<Wrap>(), default_value = "repeat")]
    pub wrap: Wrap,
    /// Byte encoding of the normal's components
    #[arg(long, value_parser = choice::<Encoding>(), default_value = "unorm")]
    pub encoding: Encoding,
    /// Which way green points in the file, as the image is displayed: opengl (alias y-up: glTF, Blender, Unity) or directx (alias y-down: Unreal)
    #[arg(long = "y-convention", value_parser = choice::<YConvention>(), default_value = "opengl")]
    pub y_convention: YConvention,
    /// Which channel of a colour image holds the heights (greyscale images: their grey value)
    #[arg(long, value_parser = choice::<Channel>(), default_value = "luminance")]
    pub channel: Channel,
}

impl NormalMapOpts {
    /// The options as the library takes them.
    pub fn options(&self) -> bumpmap_math::NormalMapOptions {
        bumpmap_math::NormalMapOptions {
            kernel: self.kernel,
            scale: self.scale,
            wrap: self.wrap,
            y_convention: self.y_convention,
            encoding: self.encoding,
        }
    }
}

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap normalmap heights.png -o normals.png --mips        # normals.png, normals.mip1.png, …\n  \
bumpmap normalmap bricks@512 -o bricks.ktx2 --mips         # a preset, all levels in one file\n  \
bumpmap normalmap textures/ -o normals/ --scale 8          # every image in a folder, in parallel\n  \
bumpmap normalmap rock.png -o rock.dds --mips --format bc5  # BC5 for an engine (Z rebuilt in the shader)\n  \
bumpmap normalmap scan16.png -o rock.png --bits 16         # 16-bit PNG, no banding on gentle slopes\n  \
bumpmap normalmap bricks -o n.png --mips --height-out h.png --bits 16   # + heights for --technique pom\n  \
bumpmap normalmap bricks -o n.png --horizon-out hz.png --ao-out ao.png --bent-normals-out bent.png   # shadows, AO\n\n\
IN is an image file (PNG, TGA, BMP, JPEG, TIFF, PNM at 8 or 16 bits; OpenEXR in float), a folder of them, or a \
preset: bricks, pinwheel, dimples, noise:SEED, each optionally @SIZE (default 256). Green points \
up the image as displayed (glTF, Blender, Unity) unless --y-convention directx.")]
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
    /// What the smaller levels store
    #[arg(long = "mip-mode", value_parser = choice::<MipMode>(), default_value = "length-in-alpha")]
    pub mip_mode: MipMode,
    /// Texel format of .dds and .ktx2 outputs: rgba8 (uncompressed), bc5 (red and green, Z rebuilt in the shader; drops the length factor in alpha), bc7 (all four channels). texconv's names work too (BC5_UNORM, …); a folder run with bc5/bc7 writes .dds files
    #[arg(long, value_parser = choice::<TextureFormat>(), default_value = "rgba8", ignore_case = true)]
    pub format: TextureFormat,
    /// Bits per channel of uncompressed outputs: 8, or 16 (16-bit PNG, R16G16B16A16_UNORM in .dds and .ktx2)
    #[arg(long, default_value_t = 8, value_parser = parse_bits)]
    pub bits: u8,
    /// How heights become normals.
    #[command(flatten)]
    pub map: NormalMapOpts,
    /// Also write a roughness map with a level for each normal-map level (.png: R.png, R.mip1.png, …; .dds or .ktx2: all levels, RGBA8): each texel the --roughness of the surface made rougher by the spread of the normals it averages (Filament's prefilter: α′ = √(α² + 2/κ), κ from the mean normal's length), what GGX shaders in engines read in place of the length factor
    #[arg(long = "roughness-out", requires = "mips")]
    pub roughness_out: Option<PathBuf>,
    /// The surface's own perceptual roughness (glTF's roughnessFactor), in [0, 1]: level 0's value wherever its normal is one
    #[arg(long, default_value_t = 0.5, value_parser = parse_unit, requires = "roughness_out")]
    pub roughness: f32,
    /// Channels of --roughness-out: gray (roughness in RGB), gloss (1 − roughness in RGB), gltf (glTF's metallicRoughness and Unreal's ORM: G roughness, B metallic 0, R 1, or with --ao-out the occlusion, every level its mean), unity (Unity's metallic-smoothness: R metallic 0, A smoothness)
    #[arg(long = "roughness-layout", value_parser = choice::<RoughnessLayout>(), default_value = "gray", requires = "roughness_out")]
    pub roughness_layout: RoughnessLayout,
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

/// A number in [0, 1].
fn parse_unit(s: &str) -> Result<f32, String> {
    let v = parse_f32(s)?;
    if (0.0..=1.0).contains(&v) { Ok(v) } else { Err(format!("'{s}' is not in [0, 1]")) }
}

pub(super) fn parse_bits(s: &str) -> Result<u8, String> {
    match s {
        "8" => Ok(8),
        "16" => Ok(16),
        _ => Err(format!("'{s}' is not 8 or 16")),
    }
}
