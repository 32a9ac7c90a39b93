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
    Render(Box<RenderArgs>),
    /// Generate tangent frames for a mesh and write glTF with a TANGENT attribute
    Tangents(TangentsArgs),
    /// Run everything on built-in defaults and write the results into a folder
    Demo(DemoArgs),
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
    /// Green = +Y toward the next row (t up): OpenGL, glTF, Blender, Unity
    Opengl,
    /// Green flipped: DirectX, Unreal, 3ds Max
    Directx,
}

impl From<YArg> for YConvention {
    fn from(y: YArg) -> Self {
        match y {
            YArg::Opengl => YConvention::OpenGl,
            YArg::Directx => YConvention::DirectX,
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
    /// Which way green points
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
bumpmap normalmap textures/ -o normals/ --scale 8          # every image in a folder, in parallel\n\n\
IN is an image file (PNG, TGA, BMP, JPEG, TIFF, PNM; 8 or 16 bits), a folder of them, or a \
preset: bricks, pinwheel, dimples, noise:SEED, each optionally @SIZE (default 256).")]
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
    #[command(flatten)]
    pub map: NormalMapOpts,
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
    /// Print the worst angular error of the bilinear lookup for face sizes 8–128, both encodings
    #[arg(long)]
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
        /// Timed runs (after one warm-up)
        #[arg(long, default_value_t = 9, value_parser = clap::value_parser!(u32).range(1..))]
        runs: u32,
        /// Worker threads (default: all cores)
        #[arg(long)]
        threads: Option<usize>,
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
        /// Worker threads (default: all cores)
        #[arg(long)]
        threads: Option<usize>,
        /// Print one JSON line instead of prose
        #[arg(long)]
        json: bool,
    },
    /// Frames per second of a scene, the light orbiting as in the llvmpipe peer
    Render {
        #[arg(long, default_value = "torus")]
        scene: String,
        #[arg(long, value_enum, default_value = "kilgard")]
        technique: TechniqueArg,
        /// Square framebuffer size
        #[arg(long, default_value_t = 1024)]
        size: usize,
        /// Worker threads (default: all cores)
        #[arg(long)]
        threads: Option<usize>,
        /// Frames per timed run
        #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..))]
        frames: u32,
        /// Timed runs (after one warm-up run)
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..))]
        runs: u32,
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

/// `[dir:]X,Y,Z[@R,G,B]`: a positional light (or a direction toward a directional one) and its
/// colour.
pub fn parse_light(s: &str) -> Result<bumpmap_raster::scene::SceneLight, String> {
    use bumpmap_math::lighting::Light;
    let (pos, color) = match s.split_once('@') {
        Some((p, c)) => (p, parse_vec3(c)?),
        None => (s, glam::Vec3::ONE),
    };
    if color.min_element() < 0.0 {
        return Err(format!("light colour must not be negative, got '{s}'"));
    }
    let light = match pos.strip_prefix("dir:") {
        Some(d) => {
            let d = parse_vec3(d)?;
            if d.length() == 0.0 {
                return Err("a directional light needs a non-zero direction".into());
            }
            Light::Directional(d.normalize())
        }
        None => Light::Positional(parse_vec3(pos)?),
    };
    Ok(bumpmap_raster::scene::SceneLight { color, ..bumpmap_raster::scene::SceneLight::white(light) })
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum TechniqueArg {
    /// The paper's three passes on the emulated GeForce 256 (register combiners, cube map)
    Kilgard,
    /// One float pass per light with the full lighting model (Kilgard §6, Cg Tutorial)
    SinglePass,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalizeArg {
    /// normalize() in float
    Math,
    /// the normalization cube map, as the paper does
    Cube,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SelfShadowArg {
    /// Eq. 12: clamp(8·L_z, 0, 1)
    Ramp,
    /// 1 where L_z > 0
    Step,
    /// none (Figure 14, left)
    Off,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum HalfAngleArg {
    /// per vertex, interpolated (Appendix C)
    Vertex,
    /// normalize(L̂ + V̂) per fragment (Cg Tutorial §8.1.4)
    Fragment,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecularShadowArg {
    /// times s_self, zero where H_z < 0 (the paper's mux)
    Kilgard,
    /// zero unless N'·L > 0 and L_z > 0 (Cg Tutorial §8.5)
    Cg,
    /// none
    Off,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilterArg {
    /// GL_NEAREST: blocky, no mipmaps
    Nearest,
    /// GL_LINEAR: bilinear, no mipmaps (shimmers at a distance)
    Linear,
    /// GL_LINEAR_MIPMAP_LINEAR: the paper's choice
    Trilinear,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrecisionArg {
    /// Single-precision combiners
    Float,
    /// The GeForce 256's 9-bit signed fixed point
    Fixed9,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecularArg {
    /// max(0, H·N')^8 by repeated squaring (Appendix H)
    Power8,
    /// max(0, 4·(H·N' − ¾))² (§5.5), a tighter highlight
    Ramp,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewerArg {
    Local,
    Infinite,
}

#[derive(Args, Debug, Clone)]
#[command(after_help = "Examples:\n  \
bumpmap render                                         # the paper's torus, out/render.png\n  \
bumpmap render --passes -o torus.png                   # also torus.decal.png, .diffuse.png, .specular.png\n  \
bumpmap render --scene wall-floor --light -1,2,3        # the Cg Tutorial's Figure 8-4\n  \
bumpmap render --height-field dimples --bump-scale 8 --decal none\n  \
bumpmap render --light 4,0,3@1,0.6,0.4 --light dir:-1,0,1@0.3,0.3,0.6\n\n\
Lights are [dir:]X,Y,Z[@R,G,B] in world space: a point light's position, or with dir: the \
direction toward a light at infinity.")]
pub struct RenderArgs {
    /// torus, wall, floor, wall-floor, patch, sphere, or mesh:FILE (.obj, .gltf, .glb)
    #[arg(long, default_value = "torus")]
    pub scene: String,
    #[arg(long, value_enum, default_value = "kilgard")]
    pub technique: TechniqueArg,
    /// Output PNG
    #[arg(short, long, default_value = "out/render.png")]
    pub output: PathBuf,
    /// Square image size (pixels)
    #[arg(long, default_value_t = 512, conflicts_with_all = ["width", "height"])]
    pub size: usize,
    /// Image width in pixels (with --height, instead of --size)
    #[arg(long, requires = "height")]
    pub width: Option<usize>,
    /// Image height in pixels (with --width)
    #[arg(long, requires = "width")]
    pub height: Option<usize>,
    /// Eye position (default: the scene's)
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub eye: Option<glam::Vec3>,
    /// Point looked at (default: the scene's)
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub target: Option<glam::Vec3>,
    /// Vertical field of view in degrees
    #[arg(long, default_value_t = 45.0)]
    pub fov: f32,
    /// A light, repeatable: [dir:]X,Y,Z[@R,G,B] (default: the scene's)
    #[arg(long = "light", value_parser = parse_light, allow_hyphen_values = true)]
    pub lights: Vec<bumpmap_raster::scene::SceneLight>,
    /// Local or infinite viewer for the half-angle vector
    #[arg(long, value_enum, default_value = "local")]
    pub viewer: ViewerArg,
    /// Height field: image file or preset (bricks, pinwheel, dimples, noise:SEED[@SIZE])
    #[arg(long = "height-field", default_value = "bricks")]
    pub height_field: String,
    /// Bump height (the normal map's --scale)
    #[arg(long = "bump-scale", default_value_t = 4.0, allow_negative_numbers = true)]
    pub bump_scale: f32,
    /// Decal image, or "none" (default: brick decal for the bricks preset, none otherwise)
    #[arg(long)]
    pub decal: Option<String>,
    /// Ambient intensity I_ambient
    #[arg(long, default_value_t = 0.2)]
    pub ambient: f32,
    /// Diffuse coefficient k_diffuse
    #[arg(long, default_value_t = 0.8)]
    pub diffuse: f32,
    /// Specular coefficient (0 drops the specular pass)
    #[arg(long, default_value_t = 1.0)]
    pub specular: f32,
    /// Torus radii R,r (hole centre to tube centre, tube)
    #[arg(long = "torus-radii", value_parser = parse_pair, default_value = "2,0.7")]
    pub torus_radii: (f32, f32),
    /// Quads along u and v (default: the scene's; torus 128,64)
    #[arg(long, value_parser = parse_counts)]
    pub tessellation: Option<(usize, usize)>,
    /// Texture repeats along s and t (default: the scene's; torus 6,2)
    #[arg(long, value_parser = parse_pair)]
    pub repeat: Option<(f32, f32)>,
    /// Texture filtering of the normal map and decal
    #[arg(long, value_enum, default_value = "trilinear")]
    pub filter: FilterArg,
    /// Also write the framebuffer after each pass (Figure 12): OUT.decal.png, OUT.diffuse.png, …
    #[arg(long)]
    pub passes: bool,
    /// Leave out Eq. 12's self-shadowing term (Figure 14, left)
    #[arg(long = "no-self-shadow")]
    pub no_self_shadow: bool,
    /// Register-combiner arithmetic
    #[arg(long, value_enum, default_value = "float")]
    pub precision: PrecisionArg,
    /// Specular form of the third pass
    #[arg(long = "specular-mode", value_enum, default_value = "power8")]
    pub specular_mode: SpecularArg,
    /// Face size of the normalization cube map
    #[arg(long = "cube-size", default_value_t = 32, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub cube_size: u32,
    /// single-pass: how L and H are renormalized per fragment
    #[arg(long, value_enum, default_value = "math")]
    pub normalize: NormalizeArg,
    /// single-pass: the self-shadowing factor (kilgard: see --no-self-shadow)
    #[arg(long = "self-shadow", value_enum, default_value = "ramp")]
    pub self_shadow: SelfShadowArg,
    /// single-pass: per-vertex or per-fragment half-angle vector
    #[arg(long = "half-angle", value_enum, default_value = "vertex")]
    pub half_angle: HalfAngleArg,
    /// Specular exponent (kilgard's combiners are fixed at 8)
    #[arg(long, default_value_t = 8.0)]
    pub shininess: f32,
    /// single-pass: geometric self-shadowing of the specular term
    #[arg(long = "specular-shadow", value_enum, default_value = "kilgard")]
    pub specular_shadow: SpecularShadowArg,
    /// single-pass: gloss map scaling the specular: decal-alpha, bricks (shiny bricks, dull mortar) or an image (red channel, same size as the decal)
    #[arg(long)]
    pub gloss: Option<String>,
    /// single-pass: attenuation with distance: C,L,Q (1/(C + L·d + Q·d²)), exp:D or exp2:D
    #[arg(long, value_parser = parse_attenuation)]
    pub attenuation: Option<bumpmap_raster::scene::Attenuation>,
    /// single-pass: make every positional light a spotlight aimed along DX,DY,DZ
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub spot: Option<glam::Vec3>,
    /// Spotlight cone half-angle in degrees, in (0, 90)
    #[arg(long = "spot-cutoff", default_value_t = 25.0)]
    pub spot_cutoff: f32,
    /// Spotlight fall-off exponent (cos^E), ≥ 0
    #[arg(long = "spot-exponent", default_value_t = 2.0)]
    pub spot_exponent: f32,
    /// Pattern projected by the spotlight: an image or a height-field preset (e.g. pinwheel)
    #[arg(long = "spot-pattern")]
    pub spot_pattern: Option<String>,
    /// single-pass: light in tangent space, or in object space with an object-space normal map made for the surface (built-in surfaces only)
    #[arg(long, value_enum, default_value = "tangent")]
    pub space: SpaceArg,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpaceArg {
    /// tangent-space normal map, L and H rotated into each vertex's frame
    Tangent,
    /// object-space normal map baked for the surface, L and H in object space (Peercy §2.1)
    Object,
}

/// `C,L,Q`, `exp:D` or `exp2:D`.
pub fn parse_attenuation(s: &str) -> Result<bumpmap_raster::scene::Attenuation, String> {
    use bumpmap_raster::scene::Attenuation;
    let num = |x: &str| x.trim().parse::<f32>().map_err(|_| format!("'{x}' is not a number"));
    if s == "none" {
        return Ok(Attenuation::None);
    }
    if let Some(d) = s.strip_prefix("exp2:") {
        return Ok(Attenuation::ExponentialSquared { density: num(d)? });
    }
    if let Some(d) = s.strip_prefix("exp:") {
        return Ok(Attenuation::Exponential { density: num(d)? });
    }
    let v: Vec<f32> = s.split(',').map(num).collect::<Result<_, _>>()?;
    match v.as_slice() {
        [c, l, q] => Ok(Attenuation::Polynomial { constant: *c, linear: *l, quadratic: *q }),
        _ => Err(format!("expected none, C,L,Q, exp:D or exp2:D, got '{s}'")),
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
bumpmap tangents scan.gltf -o scan_tangents.gltf --mode mikktspace\n\n\
Reads OBJ, glTF or GLB (positions, normals, texture coordinates; normals are computed when \
missing). Writes positions, normals, TEXCOORD_0, TANGENT (VEC4, w = ±1 handedness) and indices, \
and reports degenerate, mirrored and split geometry.")]
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
}
