//! Command-line arguments. The help texts are the user manual: they say what each option
//! means in the papers' terms and what the default is.

use std::path::PathBuf;

use bumpmap_io::Channel;
use bumpmap_math::{Encoding, Kernel, MipMode, Wrap, YConvention};
use clap::{Args, Parser, Subcommand, ValueEnum};

#[derive(Parser, Debug)]
#[command(
    name = "bumpmap",
    version,
    about = "Bump mapping toolkit and renderer after Kilgard (2000), the Cg Tutorial ch. 8 and Peercy et al. (1997)",
    long_about = "Bump mapping toolkit and renderer.\n\n\
Makes tangent-space normal maps from height fields, with mip chains that keep the length of the \
averaged normal in alpha so bumpy surfaces dim correctly at a distance (Kilgard 2000, §2.4.2); \
builds normalization cube maps; and renders bump-mapped objects.\n\n\
Start with `bumpmap demo`, which writes example outputs into ./out/demo.\n\n\
Texture convention: the first row of an image file is texture coordinate t = 0 (OpenGL's \
glTexImage2D order), so the normal map's +Y (green) points toward the next row."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Height field → normal map (and its mip chain)
    Normalmap(NormalmapArgs),
    /// Write a normalization cube map, or measure the accuracy of its lookup
    Cubemap(CubemapArgs),
    /// Measure speed (median of several runs); --json prints one machine-readable line
    Bench(BenchArgs),
    /// Render a bump-mapped scene
    Render(Box<crate::render_args::RenderArgs>),
    /// Generate tangent frames for a mesh and write glTF with a TANGENT attribute
    Tangents(TangentsArgs),
    /// Run everything on built-in defaults and write the results into a folder
    Demo(DemoArgs),
    /// Render every technique on one scene, measure each against the reference, write a report
    Compare(CompareArgs),
}

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap compare                                    # the torus, out/compare/report.html\n  \
bumpmap compare --scene patch --height-field pinwheel --spp 256\n  \
bumpmap compare --techniques kilgard,single-pass --backend gpu\n\n\
Writes OUT/results.json (every score), OUT/report.html (images, FLIP heat maps, the table and \
plots; relative links only, so the folder can be copied), one PNG per technique and its \
FLIP heat map, and the plots as SVG. A technique that cannot render the scene is skipped, with \
its reason on stderr and in the report.\n\n\
Whatever the scene, the report also measures three claims the papers make in pictures, each on \
its own scene: Kilgard §2.4.2's golf ball at a distance (the length factor against renormalized \
mips), §3.1's embossing (flat head-on, lost at a distance, lit where the light is behind), and \
Peercy's Figures 5–7 on his stretched patch (per-pixel Blinn, the surface-dependent and the \
surface-independent map, at bump scales 1, 2 and 4).")]
pub struct CompareArgs {
    /// Built-in scene: torus, wall, floor, wall-floor, patch, sphere (the reference needs an exact surface)
    #[arg(long, default_value = "torus")]
    pub scene: String,
    /// Height field: image file or preset (bricks, pinwheel, dimples, noise:SEED[@SIZE])
    #[arg(long = "height-field", default_value = "bricks")]
    pub height_field: String,
    /// Bump scale: the height of a unit step, in texels
    #[arg(long = "bump-scale", default_value_t = 4.0)]
    pub bump_scale: f32,
    /// Square image size in pixels
    #[arg(long, default_value_t = 256, value_parser = parse_side)]
    pub size: usize,
    /// The reference's samples per pixel (stratified); the convergence plot uses 1, 4, 16, … up to it
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub spp: u32,
    /// What draws the techniques (the reference always runs on the CPU)
    #[arg(long, value_enum, default_value = "cpu")]
    pub backend: crate::render_args::BackendArg,
    /// Comma-separated techniques to run (default: all of kilgard, single-pass, single-pass-cube, object-space, mip-renormalized, no-bump, peercy-independent, peercy-dependent, emboss, emboss-unforced, offset-map, peercy-blinn)
    #[arg(long, value_delimiter = ',')]
    pub techniques: Vec<String>,
    /// Output folder
    #[arg(short, long, default_value = "out/compare")]
    pub output: PathBuf,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum KernelArg {
    /// F(u+1) − F(u): the paper's right/up differences (Kilgard Appendix E)
    Forward,
    /// (F(u+1) − F(u−1)) / 2
    Central,
    /// 3×3 Sobel
    Sobel3,
    /// 5×5 Sobel
    Sobel5,
    /// 3×3 Prewitt (what DirectXTex uses)
    Prewitt3,
    /// 3×3 Scharr
    Scharr3,
    /// 7×7 derivative of a Gaussian, σ = 1 (Peercy et al.)
    Gaussian7,
}

impl From<KernelArg> for Kernel {
    fn from(k: KernelArg) -> Self {
        match k {
            KernelArg::Forward => Kernel::Forward,
            KernelArg::Central => Kernel::Central,
            KernelArg::Sobel3 => Kernel::Sobel3,
            KernelArg::Sobel5 => Kernel::Sobel5,
            KernelArg::Prewitt3 => Kernel::Prewitt3,
            KernelArg::Scharr3 => Kernel::Scharr3,
            KernelArg::Gaussian7 => Kernel::Gaussian7,
        }
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum WrapArg {
    /// The field tiles: edges read the opposite edge
    Repeat,
    /// Edges repeat the last texel
    Clamp,
    /// Kilgard's border case: the input is one texel wider and taller than the output
    Border,
}

impl From<WrapArg> for Wrap {
    fn from(w: WrapArg) -> Self {
        match w {
            WrapArg::Repeat => Wrap::Repeat,
            WrapArg::Clamp => Wrap::Clamp,
            WrapArg::Border => Wrap::Border,
        }
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum EncodingArg {
    /// round(127.5·n + 127.5): symmetric, what modern tools write
    Unorm,
    /// (byte)(128 + 127·n), truncated: the paper's Appendices D–F, byte for byte
    Kilgard,
}

impl From<EncodingArg> for Encoding {
    fn from(e: EncodingArg) -> Self {
        match e {
            EncodingArg::Unorm => Encoding::Unorm,
            EncodingArg::Kilgard => Encoding::Kilgard,
        }
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum YArg {
    /// Green up: +Y toward the top of the image as displayed (glTF, OpenGL, Blender, Maya, Unity)
    #[value(alias = "y-up")]
    Opengl,
    /// Green down: +Y toward the bottom of the image as displayed (DirectX, Unreal, 3ds Max)
    #[value(alias = "y-down")]
    Directx,
}

impl From<YArg> for YConvention {
    fn from(y: YArg) -> Self {
        match y {
            YArg::Opengl => YConvention::YUp,
            YArg::Directx => YConvention::YDown,
        }
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum MipModeArg {
    /// RGB = normalized mean of the covered normals, A = its length (Kilgard §5.3)
    LengthInAlpha,
    /// RGB = normalized mean, A = 255: what most tools do (too bright at a distance)
    Renormalize,
}

impl From<MipModeArg> for MipMode {
    fn from(m: MipModeArg) -> Self {
        match m {
            MipModeArg::LengthInAlpha => MipMode::LengthInAlpha,
            MipModeArg::Renormalize => MipMode::Renormalize,
        }
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ChannelArg {
    Luminance,
    Red,
    Green,
    Blue,
    Alpha,
}

impl From<ChannelArg> for Channel {
    fn from(c: ChannelArg) -> Self {
        match c {
            ChannelArg::Luminance => Channel::Luminance,
            ChannelArg::Red => Channel::Red,
            ChannelArg::Green => Channel::Green,
            ChannelArg::Blue => Channel::Blue,
            ChannelArg::Alpha => Channel::Alpha,
        }
    }
}

/// Options that decide how heights become normals; shared by every command that makes one.
#[derive(Args, Debug, Clone)]
pub struct NormalMapOpts {
    /// Finite-difference kernel for ∂F/∂u and ∂F/∂v
    #[arg(long, value_enum, default_value = "forward")]
    pub kernel: KernelArg,
    /// Bump height: heights are in [0,1], derivatives per texel, n ∝ (−scale·∂F/∂u, −scale·∂F/∂v, 1)
    #[arg(long, default_value_t = 4.0, allow_negative_numbers = true)]
    pub scale: f32,
    /// What the kernel reads beyond the edges
    #[arg(long, value_enum, default_value = "repeat")]
    pub wrap: WrapArg,
    /// Byte encoding of the normal's components
    #[arg(long, value_enum, default_value = "unorm")]
    pub encoding: EncodingArg,
    /// Which way green points in the file, as the image is displayed: opengl (alias y-up: glTF, Blender, Unity) or directx (alias y-down: Unreal)
    #[arg(long = "y-convention", value_enum, default_value = "opengl")]
    pub y_convention: YArg,
    /// Which channel of a colour image holds the heights (greyscale images: their grey value)
    #[arg(long, value_enum, default_value = "luminance")]
    pub channel: ChannelArg,
}

impl NormalMapOpts {
    pub fn options(&self) -> bumpmap_math::NormalMapOptions {
        bumpmap_math::NormalMapOptions {
            kernel: self.kernel.into(),
            scale: self.scale,
            wrap: self.wrap.into(),
            y_convention: self.y_convention.into(),
            encoding: self.encoding.into(),
        }
    }
}

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap normalmap heights.png -o normals.png --mips        # normals.png, normals.mip1.png, …\n  \
bumpmap normalmap bricks@512 -o bricks.ktx2 --mips         # a preset, all levels in one file\n  \
bumpmap normalmap textures/ -o normals/ --scale 8          # every image in a folder, in parallel\n  \
bumpmap normalmap rock.png -o rock.dds --mips --format bc5  # BC5 for an engine (Z rebuilt in the shader)\n  \
bumpmap normalmap scan16.png -o rock.png --bits 16         # 16-bit PNG, no banding on gentle slopes\n\n\
IN is an image file (PNG, TGA, BMP, JPEG, TIFF, PNM at 8 or 16 bits; OpenEXR in float), a folder of them, or a \
preset: bricks, pinwheel, dimples, noise:SEED, each optionally @SIZE (default 256). Green points \
up the image as displayed (glTF, Blender, Unity) unless --y-convention directx.")]
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
    #[arg(long = "mip-mode", value_enum, default_value = "length-in-alpha")]
    pub mip_mode: MipModeArg,
    /// Texel format of .dds and .ktx2 outputs: rgba8 (uncompressed), bc5 (red and green, Z rebuilt in the shader; drops the length factor in alpha), bc7 (all four channels). texconv's names work too (BC5_UNORM, …); a folder run with bc5/bc7 writes .dds files
    #[arg(long, value_enum, default_value = "rgba8", ignore_case = true)]
    pub format: FormatArg,
    /// Bits per channel of uncompressed outputs: 8, or 16 (16-bit PNG, R16G16B16A16_UNORM in .dds and .ktx2)
    #[arg(long, default_value_t = 8, value_parser = parse_bits)]
    pub bits: u8,
    #[command(flatten)]
    pub map: NormalMapOpts,
}

fn parse_bits(s: &str) -> Result<u8, String> {
    match s {
        "8" => Ok(8),
        "16" => Ok(16),
        _ => Err(format!("'{s}' is not 8 or 16")),
    }
}

/// Texel formats of DDS and KTX2 outputs.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormatArg {
    /// Uncompressed 8-bit RGBA (16-bit with --bits 16)
    #[value(alias = "r8g8b8a8_unorm")]
    Rgba8,
    /// Uncompressed 16-bit RGBA (the same as --bits 16)
    #[value(alias = "r16g16b16a16_unorm")]
    Rgba16,
    /// BC5: two channels (X, Y), 8 bits per texel
    #[value(alias = "bc5_unorm")]
    Bc5,
    /// BC7: four channels, 8 bits per texel
    #[value(alias = "bc7_unorm")]
    Bc7,
}

impl From<FormatArg> for bumpmap_io::texture_file::TextureFormat {
    fn from(f: FormatArg) -> Self {
        use bumpmap_io::texture_file::TextureFormat;
        match f {
            FormatArg::Rgba8 => TextureFormat::Rgba8,
            FormatArg::Rgba16 => TextureFormat::Rgba16,
            FormatArg::Bc5 => TextureFormat::Bc5,
            FormatArg::Bc7 => TextureFormat::Bc7,
        }
    }
}

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
    #[arg(long, value_enum, default_value = "unorm")]
    pub encoding: EncodingArg,
    /// A folder (six PNG faces), or a .dds / .ktx2 cube-map file
    #[arg(short, long, required_unless_present = "accuracy")]
    pub output: Option<PathBuf>,
    /// Print the worst angular error of the bilinear lookup for face sizes 8–128, both encodings (writes nothing; takes no other option)
    #[arg(long, conflicts_with_all = ["output", "size", "encoding"])]
    pub accuracy: bool,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    #[command(subcommand)]
    pub what: BenchWhat,
}

#[derive(Subcommand, Debug)]
pub enum BenchWhat {
    /// 8-bit height field → normal map + full mip chain, and the read-once/write-once floor
    Normalmap {
        /// Edge length of the square height field
        #[arg(long, default_value_t = 4096, value_parser = clap::value_parser!(u32).range(1..=16384))]
        size: u32,
        /// Also time compressing the chain to this format (bc5, bc7), every level
        #[arg(long, value_enum, ignore_case = true)]
        format: Option<FormatArg>,
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
    /// Tangents for a wavy textured grid of N triangles (the MikkTSpace peer's mesh)
    Tangents {
        /// Triangles (rounded to a 1000-column grid)
        #[arg(long, default_value_t = 1_000_000, value_parser = clap::value_parser!(u32).range(2000..=50_000_000))]
        triangles: u32,
        #[arg(long, value_enum, default_value = "ours")]
        mode: TangentModeArg,
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
    Render(Box<crate::render_args::BenchRenderArgs>),
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

#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Folder to write into (created if missing)
    #[arg(short, long, default_value = "out/demo")]
    pub output: PathBuf,
    /// Also render the figures on the GPU (wgpu); `auto` does when an adapter exists and says so
    /// when none does
    #[arg(long, value_enum, default_value = "auto")]
    pub gpu: DemoGpuArg,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum DemoGpuArg {
    /// GPU images when an adapter exists
    Auto,
    /// GPU images, and an error when no adapter exists
    Always,
    /// CPU images only
    Never,
}

/// Three numbers, `X,Y,Z`.
pub fn parse_vec3(s: &str) -> Result<glam::Vec3, String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|p| p.trim().parse::<f32>().map_err(|_| format!("'{p}' is not a number")))
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(glam::Vec3::new(*x, *y, *z)),
        _ => Err(format!("expected X,Y,Z (three finite numbers), got '{s}'")),
    }
}

/// Two numbers, `A,B`.
pub fn parse_pair(s: &str) -> Result<(f32, f32), String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|p| p.trim().parse::<f32>().map_err(|_| format!("'{p}' is not a number")))
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [a, b] if a.is_finite() && b.is_finite() => Ok((*a, *b)),
        _ => Err(format!("expected A,B (two finite numbers), got '{s}'")),
    }
}

/// Texture repeats `S,T`: two finite numbers, neither 0 (a map made for the surface is addressed
/// with 1/repeat) and neither beyond ±1024 (texture coordinates stay well inside single
/// precision's whole numbers).
pub fn parse_repeat(s: &str) -> Result<(f32, f32), String> {
    let (a, b) = parse_pair(s)?;
    let ok = |v: f32| v != 0.0 && v.abs() <= 1024.0;
    if ok(a) && ok(b) { Ok((a, b)) } else { Err(format!("repeats must be non-zero and within ±1024, got '{s}'")) }
}

/// The largest image side `render` and `bench render` take (the CPU framebuffer's limit on
/// the pixel count applies as well).
pub const MAX_SIDE: usize = 16384;

/// An image side in pixels, 1..=[`MAX_SIDE`].
pub fn parse_side(s: &str) -> Result<usize, String> {
    s.trim()
        .parse::<usize>()
        .ok()
        .filter(|n| (1..=MAX_SIDE).contains(n))
        .ok_or_else(|| format!("'{s}' is not a size in 1..={MAX_SIDE} pixels"))
}

/// Two positive integers, `U,V`.
pub fn parse_counts(s: &str) -> Result<(usize, usize), String> {
    let (a, b) = s.split_once(',').ok_or_else(|| format!("expected U,V, got '{s}'"))?;
    let p = |x: &str| {
        x.trim()
            .parse::<usize>()
            .ok()
            .filter(|&n| (1..=4096).contains(&n))
            .ok_or_else(|| format!("'{x}' is not a count in 1..=4096"))
    };
    Ok((p(a)?, p(b)?))
}

/// How an OBJ's `vt` map to the image.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ObjVArg {
    /// v = 0 is the image's bottom row, as Blender, Maya and OBJ exporters write it
    #[default]
    Flip,
    /// v = 0 is the image's top row (OBJ files from tools that write glTF's convention)
    Keep,
}

impl From<ObjVArg> for bumpmap_io::ObjTexcoords {
    fn from(v: ObjVArg) -> Self {
        match v {
            ObjVArg::Flip => bumpmap_io::ObjTexcoords::FlipV,
            ObjVArg::Keep => bumpmap_io::ObjTexcoords::Keep,
        }
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum TangentModeArg {
    /// Per-triangle ∂P/∂s blended at vertices, split at mirror seams (Cg Tutorial §8.4); parallel
    Ours,
    /// The reference MikkTSpace algorithm (what Blender, Substance and glTF viewers use)
    Mikktspace,
}

#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap tangents model.obj -o model.glb\n  \
bumpmap tangents scan.gltf -o scan_tangents.gltf --mode mikktspace\n  \
bumpmap tangents model.obj --normal-map n.png -o model.glb   # a ready-to-view asset\n\n\
Reads OBJ, glTF or GLB (positions, normals, texture coordinates; normals are computed when \
missing; glTF node transforms applied; OBJ v flipped, see --obj-v). Writes positions, normals, \
TEXCOORD_0, TANGENT (VEC4, glTF's w = ±1 handedness) and indices, repairs normals and tangents \
glTF would call invalid, and reports degenerate, mirrored, split and repaired geometry.\n\n\
Limits: files and glTF buffers up to 1 GiB each, buffers read only from data: URIs, the GLB \
chunk or files inside the glTF's folder (see --allow-outside-paths), at most byteLength bytes; \
50,000,000 vertices, triangles or accessor elements.")]
pub struct TangentsArgs {
    /// Mesh file: .obj, .gltf or .glb
    pub input: PathBuf,
    /// Output: .gltf (with a .bin beside it) or .glb
    #[arg(short, long)]
    pub output: PathBuf,
    #[arg(long, value_enum, default_value = "ours")]
    pub mode: TangentModeArg,
    /// Ours: tangents further apart than this many degrees split a vertex
    #[arg(long = "split-angle", default_value_t = 60.0)]
    pub split_angle: f32,
    /// glTF only: let buffer URIs lead outside the glTF's folder (absolute paths, ..); off by default, so a downloaded glTF cannot make bumpmap read other files
    #[arg(long = "allow-outside-paths")]
    pub allow_outside_paths: bool,
    /// OBJ only: flip (v = 0 at the image's bottom, the OBJ convention) or keep the file's v
    #[arg(long = "obj-v", value_enum, default_value = "flip")]
    pub obj_v: ObjVArg,
    /// A PNG normal map (green up, as `normalmap` writes by default) to pack into the output as the material's normalTexture: a ready-to-view asset
    #[arg(long = "normal-map")]
    pub normal_map: Option<PathBuf>,
}
