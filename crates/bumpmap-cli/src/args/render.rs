//! The scene, camera, light, material, technique and backend options, in groups shared by
//! `render` and `bench render` (and later `view`). Each group's help heading is what `--help`
//! shows; turning the groups into library values is `crate::setup`'s.

use std::path::PathBuf;

use bumpmap::{ParallaxShadow, TechniqueName};
use clap::builder::PossibleValue;
use clap::{Args, ValueEnum};

use crate::args::{ObjVArg, YArg, parse_counts, parse_f32, parse_pair, parse_repeat, parse_side, parse_vec3};

/// What is drawn: the geometry, its bumps and decal, the texture layout.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Scene")]
pub struct SceneGroup {
    /// torus, wall, floor, wall-floor, patch, sphere, or mesh:FILE (.obj, .gltf, .glb: drawn in its own units and axes, with a glTF's own normal map and base colour unless the options below replace them)
    #[arg(long, default_value = "torus")]
    pub scene: String,
    /// Height field the normal map is made from: image file or preset (bricks, pinwheel, dimples, noise:SEED[@SIZE]) [default: bricks, or a glTF material's normal map]
    #[arg(long = "height-field", conflicts_with = "normal_map")]
    pub height_field: Option<String>,
    /// A normal map to draw as it is (PNG at 8 or 16 bits, other images, DDS or KTX2 with the mip levels it carries, BC5/BC7 included); without stored mips the chain is made with the length in alpha
    #[arg(long = "normal-map")]
    pub normal_map: Option<PathBuf>,
    /// Make --normal-map's smaller levels from its level 0, with the length in alpha, instead of using the file's own (for levels another tool renormalized, which the length factor and --specular-filter toksvig get nothing from)
    #[arg(long = "rebuild-mips", requires = "normal_map")]
    pub rebuild_mips: bool,
    /// Which way --normal-map's green points as the image is displayed: opengl (alias y-up: glTF, Blender, Unity, and what `bumpmap normalmap` writes) or directx (alias y-down: Unreal, 3ds Max)
    #[arg(long = "y-convention", value_enum, default_value = "opengl", requires = "normal_map")]
    pub y_convention: YArg,
    /// Bump strength: a height field's scale (the height of a unit step, in texels) [default: 4]; for a normal map (--normal-map or a glTF's) it multiplies the slopes as glTF's normalTexture.scale does [default: 1, or the material's]
    #[arg(value_parser = parse_f32, long = "bump-scale", allow_negative_numbers = true)]
    pub bump_scale: Option<f32>,
    /// Decal image, or "none" [default: a glTF material's base colour; the brick decal for the bricks preset; none otherwise]
    #[arg(long)]
    pub decal: Option<String>,
    /// Torus radii R,r (hole centre to tube centre, tube)
    #[arg(long = "torus-radii", value_parser = parse_pair, default_value = "2,0.7", allow_hyphen_values = true)]
    pub torus_radii: (f32, f32),
    /// Quads along u and v, each at most 2048 (default: the scene's; torus 128,64)
    #[arg(long, value_parser = parse_counts)]
    pub tessellation: Option<(usize, usize)>,
    /// Texture repeats along s and t (default: the scene's; torus 6,2); negative mirrors; each non-zero, within ±1024
    #[arg(long, value_parser = parse_repeat, allow_hyphen_values = true)]
    pub repeat: Option<(f32, f32)>,
    /// mesh: glTF only: let buffer and image URIs lead outside the glTF's folder (absolute paths, ..); off by default, so a downloaded glTF cannot make bumpmap read other files
    #[arg(long = "allow-outside-paths")]
    pub allow_outside_paths: bool,
    /// OBJ only: flip (v = 0 at the image's bottom, the OBJ convention) or keep the file's v
    #[arg(long = "obj-v", value_enum, default_value = "flip")]
    pub obj_v: ObjVArg,
}

/// Where the scene is seen from. Positions are in world space: for a mesh, the file's own units
/// and axes.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Camera")]
pub struct CameraGroup {
    /// Eye position [default: the scene's; for a mesh, in front of its bounds (glTF's +Z) and above, far enough to see all of it]
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub eye: Option<glam::Vec3>,
    /// Point looked at [default: the scene's; for a mesh, the centre of its bounds]
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub target: Option<glam::Vec3>,
    /// The world's up direction [default: +Z for torus, patch and sphere; +Y for wall, floor and meshes, as glTF and OBJ have it]; looking straight along it takes another up rather than drawing nothing
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub up: Option<glam::Vec3>,
    /// Vertical field of view in degrees
    #[arg(value_parser = parse_f32, long, default_value_t = 45.0, allow_negative_numbers = true)]
    pub fov: f32,
    /// Local or infinite viewer for the half-angle vector
    #[arg(long, value_enum, default_value = "local")]
    pub viewer: ViewerArg,
}

/// The lights.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Lights")]
pub struct LightGroup {
    /// A light, repeatable: [dir:]X,Y,Z[@R,G,B] (default: the scene's)
    #[arg(long = "light", value_parser = parse_light, allow_hyphen_values = true)]
    pub lights: Vec<bumpmap_core::scene::SceneLight>,
    /// single-pass: attenuation with distance: C,L,Q (1/(C + L·d + Q·d²)), exp:D or exp2:D
    #[arg(long, value_parser = parse_attenuation, allow_hyphen_values = true)]
    pub attenuation: Option<bumpmap_core::scene::Attenuation>,
    /// single-pass: make every positional light a spotlight aimed along DX,DY,DZ
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub spot: Option<glam::Vec3>,
    /// Spotlight cone half-angle in degrees, in (0, 90)
    #[arg(value_parser = parse_f32, long = "spot-cutoff", default_value_t = 25.0, allow_negative_numbers = true, requires = "spot")]
    pub spot_cutoff: f32,
    /// Spotlight fall-off exponent (cos^E), ≥ 0
    #[arg(value_parser = parse_f32, long = "spot-exponent", default_value_t = 2.0, allow_negative_numbers = true, requires = "spot")]
    pub spot_exponent: f32,
    /// Pattern projected by the spotlight: an image or a height-field preset (e.g. pinwheel); sampled at up to 2048 a side (a larger one is box-halved)
    #[arg(long = "spot-pattern", requires = "spot")]
    pub spot_pattern: Option<String>,
}

/// The surface's coefficients (Kilgard Eq. 11 and 16).
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Material")]
pub struct MaterialGroup {
    /// Ambient intensity I_ambient
    #[arg(value_parser = parse_f32, long, default_value_t = 0.2, allow_negative_numbers = true)]
    pub ambient: f32,
    /// Diffuse coefficient k_diffuse
    #[arg(value_parser = parse_f32, long, default_value_t = 0.8, allow_negative_numbers = true)]
    pub diffuse: f32,
    /// Specular coefficient (0 drops the specular pass)
    #[arg(value_parser = parse_f32, long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub specular: f32,
    /// Specular exponent (kilgard's combiners are fixed at 8)
    #[arg(value_parser = parse_f32, long, default_value_t = 8.0, allow_negative_numbers = true)]
    pub shininess: f32,
    /// single-pass: gloss map scaling the specular: decal-alpha, bricks (shiny bricks, dull mortar) or an image (red channel, same size as the decal)
    #[arg(long)]
    pub gloss: Option<String>,
    /// With --technique roughness-map (or --specular-filter roughness-map): read this roughness map instead of making one from the normal map's mips — `normalmap --mips --roughness-out`'s file (.ktx2 or .dds with every level, or R.png with R.mip1.png … beside it), at the normal map's size. Its roughness sets the exponent; --shininess stays the brightness of a texel of that roughness
    #[arg(long = "roughness-map", value_name = "FILE")]
    pub roughness_map: Option<std::path::PathBuf>,
    /// Channels --roughness-map holds its roughness in, as `normalmap --roughness-layout` writes them
    #[arg(long = "roughness-layout", value_enum, default_value = "gray", requires = "roughness_map")]
    pub roughness_layout: crate::args::RoughnessLayoutArg,
}

/// How it is drawn.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Technique")]
pub struct TechniqueGroup {
    /// Any technique of the catalogue (below); one that cannot draw the scene says why
    #[arg(long, value_enum, default_value = "kilgard")]
    pub technique: TechniqueArg,
    /// reference: samples per pixel (stratified); the image converges as it grows
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub spp: u32,
    /// Texture filtering of the normal map and decal
    #[arg(long, value_enum, default_value = "trilinear")]
    pub filter: FilterArg,
    /// Leave out Eq. 12's self-shadowing term (Figure 14, left)
    #[arg(long = "no-self-shadow")]
    pub no_self_shadow: bool,
    /// kilgard: register-combiner arithmetic
    #[arg(long, value_enum, default_value = "float")]
    pub precision: PrecisionArg,
    /// kilgard: specular form of the third pass
    #[arg(long = "specular-mode", value_enum, default_value = "power8")]
    pub specular_mode: SpecularArg,
    /// Face size of the normalization cube map
    #[arg(long = "cube-size", default_value_t = 32, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub cube_size: u32,
    /// single-pass and its variants: how L and H are renormalized per fragment [default: math; the cube map for single-pass-cube and kilgard]
    #[arg(long, value_enum)]
    pub normalize: Option<NormalizeArg>,
    /// single-pass: the self-shadowing factor (kilgard: see --no-self-shadow)
    #[arg(long = "self-shadow", value_enum, default_value = "ramp")]
    pub self_shadow: SelfShadowArg,
    /// single-pass: per-vertex or per-fragment half-angle vector
    #[arg(long = "half-angle", value_enum, default_value = "vertex")]
    pub half_angle: HalfAngleArg,
    /// single-pass: geometric self-shadowing of the specular term
    #[arg(long = "specular-shadow", value_enum, default_value = "kilgard")]
    pub specular_shadow: SpecularShadowArg,
    /// single-pass: how the specular lobe answers the bumps a pixel averages (toksvig: the exponent from the mip chain's |N|; roughness-map: from a roughness map made of it, or --roughness-map FILE; lean and clean: the slopes' moments; a distant bumpy surface's highlight widens and dims; `--technique toksvig` or `lean` sets it)
    #[arg(long = "specular-filter", value_enum, default_value = "none")]
    pub specular_filter: SpecularFilterArg,
}

/// A technique of the catalogue (`bumpmap_core::catalogue`), by its name; `--help` lists each
/// with its description.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TechniqueArg(pub TechniqueName);

impl ValueEnum for TechniqueArg {
    fn value_variants<'a>() -> &'a [Self] {
        const ALL: [TechniqueArg; TechniqueName::ALL.len()] = {
            let mut all = [TechniqueArg(TechniqueName::Kilgard); TechniqueName::ALL.len()];
            let mut i = 0;
            while i < all.len() {
                all[i] = TechniqueArg(TechniqueName::ALL[i]);
                i += 1;
            }
            all
        };
        &ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let needs: Vec<&str> = self.0.requirements().iter().map(|r| r.brief()).collect();
        let help = match needs.as_slice() {
            [] => self.0.description().to_string(),
            needs => format!("{} [needs {}]", self.0.description(), needs.join(" and ")),
        };
        Some(PossibleValue::new(self.0.name()).help(help))
    }
}

/// Heights as geometry: how deep, from which file, and how the marches run.
#[derive(Args, Debug, Clone)]
#[command(
    next_help_heading = "Heights as geometry (parallax, steep-parallax, pom, relief, height-exact, reference-displaced)"
)]
pub struct HeightsGroup {
    /// How deep the heights carve below the surface, in the scene's units per unit of height (heights are 1 on the surface, 0 at this depth) [default: what --bump-scale stands for: that many texels of the surface's mean texel side, so the normal map's slopes are the geometry's]. Clamped to a quarter of a wall's or floor's shorter side, half a torus's tube radius or a sphere's radius, a quarter of the patch's narrower side
    #[arg(long, value_parser = parse_depth, allow_negative_numbers = true)]
    pub depth: Option<f32>,
    /// The heights as a file, the normal map's size: what `normalmap --height-out` writes (H.png with H.mip1.png … and H.minmax.png …, or H.ktx2 / H.dds with H.minmax.ktx2 / .dds beside it); what a --normal-map needs for these techniques. height-exact needs the min–max files
    #[arg(long = "height-map", value_name = "FILE")]
    pub height_map: Option<PathBuf>,
    /// The heights' horizon map as a file, the normal map's size: what `normalmap --horizon-out` writes (H.png and H.dirs4-7.png with their .mipK.png levels, or H.ktx2 / H.dds and H.dirs4-7 beside it), read by --parallax-shadow horizon, --technique horizon and --ambient-occlusion instead of the one made from the heights
    #[arg(long = "horizon-map", value_name = "FILE")]
    pub horizon_map: Option<PathBuf>,
    /// Layers of a march: steep-parallax and relief step through this many, pom through a quarter of it looking straight on up to all of it at grazing angles; a shadow march steps this many over the depth
    #[arg(long, default_value_t = bumpmap::bumpmap_core::parallax::DEFAULT_LAYERS, value_parser = clap::value_parser!(u32).range(1..=bumpmap::bumpmap_core::parallax::MAX_LAYERS as i64), allow_negative_numbers = true)]
    pub layers: u32,
    /// Self-shadowing by the heights (soft is Tatarchuk's engine-style penumbra). height-exact and reference-displaced cast exact shadow rays for hard and soft alike
    #[arg(long = "parallax-shadow", value_enum, default_value = "off")]
    pub parallax_shadow: ParallaxShadowArg,
    /// On curved surfaces, drop pixels whose ray leaves the surface without meeting the heights, so bumps cut the silhouette (the surface's curvature bends the ray, Oliveira & Policarpo 2005)
    #[arg(long)]
    pub silhouettes: bool,
    /// Write the depth where the ray met the heights instead of the polygon's, so two bumpy surfaces intersect where their bumps do
    #[arg(long = "write-depth")]
    pub write_depth: bool,
    /// Multiply the ambient term by the ambient occlusion of the heights' horizon map (Sloan & Cohen 2000): the share of the sky each point sees past the bumps around it, at the depth drawn
    #[arg(long = "ambient-occlusion")]
    pub ambient_occlusion: bool,
}

/// A parallax shadow mode (`bumpmap_core::parallax::ParallaxShadow`), by its name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParallaxShadowArg(pub ParallaxShadow);

impl ValueEnum for ParallaxShadowArg {
    fn value_variants<'a>() -> &'a [Self] {
        const ALL: [ParallaxShadowArg; ParallaxShadow::ALL.len()] = {
            let mut all = [ParallaxShadowArg(ParallaxShadow::Off); ParallaxShadow::ALL.len()];
            let mut i = 0;
            while i < all.len() {
                all[i] = ParallaxShadowArg(ParallaxShadow::ALL[i]);
                i += 1;
            }
            all
        };
        &ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        Some(PossibleValue::new(self.0.name()).help(self.0.description()))
    }
}

/// A depth: a positive, finite number of the scene's units.
pub fn parse_depth(s: &str) -> Result<f32, String> {
    let v = parse_f32(s)?;
    if !(v.is_finite() && v > 0.0) {
        return Err(format!("'{s}' is not a depth: give a positive number of the scene's units"));
    }
    Ok(v)
}

/// What draws it.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Backend")]
pub struct BackendGroup {
    /// cpu: the emulated GeForce on all cores; gpu: wgpu (Vulkan, Metal, DX12 or GL; on a
    /// machine without a GPU, Mesa's lavapipe: Debian's mesa-vulkan-drivers); auto: the GPU when
    /// an adapter exists, else the CPU (and says why). The reference always runs on the CPU
    #[arg(long, value_enum, default_value = "cpu")]
    pub backend: BackendArg,
}

/// Every option that says what is drawn and how: what `render`, `bench render` (and later
/// `view`) share.
#[derive(Args, Debug, Clone)]
pub struct SceneSetup {
    /// What is drawn.
    #[command(flatten)]
    pub scene: SceneGroup,
    /// From where.
    #[command(flatten)]
    pub camera: CameraGroup,
    /// The lights.
    #[command(flatten)]
    pub lights: LightGroup,
    /// The material's coefficients.
    #[command(flatten)]
    pub material: MaterialGroup,
    /// How it is drawn.
    #[command(flatten)]
    pub technique: TechniqueGroup,
    /// Heights as geometry.
    #[command(flatten)]
    pub heights: HeightsGroup,
    /// What draws it.
    #[command(flatten)]
    pub backend: BackendGroup,
}

/// `bumpmap render`.
#[derive(Args, Debug, Clone)]
#[command(after_help = "Examples:\n  \
bumpmap render                                         # the paper's torus, out/render.png\n  \
bumpmap render --passes -o torus.png                   # also torus.decal.png, .diffuse.png, .specular.png\n  \
bumpmap render --scene wall-floor --light -1,2,3        # the Cg Tutorial's Figure 8-4\n  \
bumpmap render --height-field dimples --bump-scale 8 --decal none\n  \
bumpmap render --light 4,0,3@1,0.6,0.4 --light dir:-1,0,1@0.3,0.3,0.6\n  \
bumpmap render --backend gpu --technique single-pass   # the same on the GPU (wgpu)\n  \
bumpmap render --technique peercy-blinn --scene patch --height-field pinwheel\n  \
bumpmap render --normal-map rock.png --scene sphere    # your own normal map (green up)\n  \
bumpmap render --normal-map rock.dds --y-convention directx   # …one made for Unreal\n  \
bumpmap render --scene mesh:model.glb                  # a glTF with its own material\n  \
bumpmap render --technique pom --scene wall --eye 0,-3,1.2   # parallax occlusion mapping, grazing\n  \
bumpmap render --technique reference-displaced --scene wall --eye 0,-3,1.2 --spp 16   # its ground truth\n  \
bumpmap render --technique relief --parallax-shadow hard --layers 64 --light 3,0,0.6\n  \
bumpmap render --normal-map n.png --height-map h.png --technique height-exact   # normalmap --height-out's files\n\n\
Lights are [dir:]X,Y,Z[@R,G,B] in world space (a mesh's own units and axes): a point light's \
position, or with dir: the direction toward a light at infinity.")]
pub struct RenderArgs {
    /// What is drawn and how.
    #[command(flatten)]
    pub setup: SceneSetup,
    /// Output PNG
    #[arg(short, long, default_value = "out/render.png")]
    pub output: PathBuf,
    /// Square image size (pixels)
    #[arg(long, default_value_t = 512, value_parser = parse_side, conflicts_with_all = ["width", "height"])]
    pub size: usize,
    /// Image width in pixels (with --height, instead of --size)
    #[arg(long, value_parser = parse_side, requires = "height")]
    pub width: Option<usize>,
    /// Image height in pixels (with --width)
    #[arg(long, value_parser = parse_side, requires = "width")]
    pub height: Option<usize>,
    /// Also write the framebuffer after each pass (Figure 12): OUT.decal.png, OUT.diffuse.png, …
    #[arg(long)]
    pub passes: bool,
}

/// `bumpmap bench render`.
#[derive(Args, Debug, Clone)]
#[command(after_help = "Examples:\n  \
bumpmap bench render --technique kilgard --threads 2 --json\n  \
bumpmap bench render --technique single-pass --normalize cube\n  \
bumpmap bench render --backend gpu --frames 100            # on the GPU (or lavapipe)\n\n\
The first light (the scene's own, or the first --light) orbits the point looked at about the \
view's up axis once per run — on the torus, the llvmpipe peer's orbit. Scene setup is not \
timed; every frame's vertex stage, clear, passes and (GPU) wait for the frame are. Every \
technique but the reference (see `bench reference`).")]
pub struct BenchRenderArgs {
    /// What is drawn and how.
    #[command(flatten)]
    pub setup: SceneSetup,
    /// Square framebuffer size
    #[arg(long, default_value_t = 1024, value_parser = parse_side)]
    pub size: usize,
    /// Worker threads, 1 to 256 (default: all cores)
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=256))]
    pub threads: Option<u16>,
    /// Frames per timed run
    #[arg(long, default_value_t = 30, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: u32,
    /// Timed runs (after one warm-up run)
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..))]
    pub runs: u32,
    /// Print one JSON line instead of prose
    #[arg(long)]
    pub json: bool,
}

/// `[dir:]X,Y,Z[@R,G,B]`: a positional light (or a direction toward a directional one) and its
/// colour.
pub fn parse_light(s: &str) -> Result<bumpmap_core::scene::SceneLight, String> {
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
    Ok(bumpmap_core::scene::SceneLight { color, ..bumpmap_core::scene::SceneLight::white(light) })
}

/// How L and H are renormalized per fragment.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalizeArg {
    /// normalize() in float
    Math,
    /// the normalization cube map, as the paper does
    Cube,
}

/// The self-shadowing factor.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SelfShadowArg {
    /// Eq. 12: clamp(8·L_z, 0, 1)
    Ramp,
    /// 1 where L_z > 0
    Step,
    /// none (Figure 14, left)
    Off,
}

/// Where the half-angle vector comes from.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum HalfAngleArg {
    /// per vertex, interpolated (Appendix C)
    Vertex,
    /// normalize(L̂ + V̂) per fragment (Cg Tutorial §8.1.4)
    Fragment,
}

/// The specular term's gating.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecularShadowArg {
    /// times s_self, zero where H_z < 0 (the paper's mux)
    Kilgard,
    /// zero unless N'·L > 0 and L_z > 0 (Cg Tutorial §8.5)
    Cg,
    /// none
    Off,
}

/// How the specular exponent answers the filtered normal's length.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecularFilterArg {
    /// the exponent as given
    None,
    /// Toksvig 2005: exponent s·|N|/(|N| + s(1 − |N|)), with its energy factor
    Toksvig,
    /// a roughness map sampled as an engine samples it, turned into a Blinn–Phong exponent: the one `normalmap --roughness-out` exports (Filament's prefilter of each level's |N|), made from the normal map, or --roughness-map FILE
    RoughnessMap,
    /// LEAN mapping (Olano & Baker 2010): the slopes' first and second moments, filtered, make an anisotropic Gaussian lobe (tangent-space maps of unit normals)
    Lean,
    /// CLEAN mapping (Olano & Baker 2010, §5): LEAN with the spread shared out equally in x and y, one moment texture instead of two: a round lobe
    Clean,
}

impl From<SpecularFilterArg> for bumpmap::SpecularFilter {
    fn from(f: SpecularFilterArg) -> Self {
        match f {
            SpecularFilterArg::None => bumpmap::SpecularFilter::None,
            SpecularFilterArg::Toksvig => bumpmap::SpecularFilter::Toksvig,
            SpecularFilterArg::RoughnessMap => bumpmap::SpecularFilter::RoughnessMap,
            SpecularFilterArg::Lean => bumpmap::SpecularFilter::Lean,
            SpecularFilterArg::Clean => bumpmap::SpecularFilter::Clean,
        }
    }
}

/// Texture filtering.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilterArg {
    /// GL_NEAREST: blocky, no mipmaps
    Nearest,
    /// GL_LINEAR: bilinear, no mipmaps (shimmers at a distance)
    Linear,
    /// GL_LINEAR_MIPMAP_LINEAR: the paper's choice
    Trilinear,
}

/// The register combiners' arithmetic.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrecisionArg {
    /// Single-precision combiners
    Float,
    /// The GeForce 256's 9-bit signed fixed point
    Fixed9,
}

/// The specular form of kilgard's third pass.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecularArg {
    /// max(0, H·N')^8 by repeated squaring (Appendix H)
    Power8,
    /// max(0, 4·(H·N' − ¾))² (§5.5), a tighter highlight
    Ramp,
}

/// Local or infinite viewer.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewerArg {
    /// the half-angle from each vertex toward the eye
    Local,
    /// one half-angle direction for the whole image (toward the eye from the target)
    Infinite,
}

/// What draws.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackendArg {
    /// the emulated GeForce pipeline on the CPU (all cores)
    Cpu,
    /// wgpu on whatever adapter exists (Vulkan, Metal, DX12, GL; lavapipe without a GPU)
    Gpu,
    /// the GPU when an adapter exists, else the CPU
    Auto,
}

impl From<BackendArg> for bumpmap::BackendChoice {
    fn from(b: BackendArg) -> Self {
        match b {
            BackendArg::Cpu => bumpmap::BackendChoice::Cpu,
            BackendArg::Gpu => bumpmap::BackendChoice::Gpu,
            BackendArg::Auto => bumpmap::BackendChoice::Auto,
        }
    }
}

/// `C,L,Q`, `exp:D` or `exp2:D`.
pub fn parse_attenuation(s: &str) -> Result<bumpmap_core::scene::Attenuation, String> {
    use bumpmap_core::scene::Attenuation;
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
