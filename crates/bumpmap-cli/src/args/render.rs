//! The scene, camera, light, material, technique and backend options, in groups shared by
//! `render` and `bench render` (and later `view`). Each group's help heading is what `--help`
//! shows; turning the groups into library values is `crate::setup`'s.

use std::path::PathBuf;

use bumpmap::bumpmap_core::combiners::Precision;
use bumpmap::options::{Filter, RoughnessLayout};
use bumpmap::{
    BackendChoice, HalfAngle, Normalize, ParallaxShadow, SelfShadow, SpecularFilter, SpecularMode, SpecularShadow,
    TechniqueName, ViewerModel, YConvention,
};
use bumpmap_io::ObjTexcoords;
use clap::builder::PossibleValue;
use clap::{Args, ValueEnum};

use crate::args::{choice, parse_counts, parse_f32, parse_pair, parse_repeat, parse_side, parse_vec3};

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
    #[arg(long = "y-convention", value_parser = choice::<YConvention>(), default_value = "opengl", requires = "normal_map")]
    pub y_convention: YConvention,
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
    #[arg(long = "obj-v", value_parser = choice::<ObjTexcoords>(), default_value = "flip")]
    pub obj_v: ObjTexcoords,
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
    #[arg(long, value_parser = choice::<ViewerModel>(), default_value = "local")]
    pub viewer: ViewerModel,
}

/// The lights.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Lights")]
pub struct LightGroup {
    /// A light, repeatable: [dir:]X,Y,Z[@R,G,B] (default: the scene's)
    #[arg(long = "light", value_parser = bumpmap::SceneLight::parse, allow_hyphen_values = true)]
    pub lights: Vec<bumpmap_core::scene::SceneLight>,
    /// single-pass: attenuation with distance: C,L,Q (1/(C + L·d + Q·d²)), exp:D or exp2:D
    #[arg(long, value_parser = bumpmap::Attenuation::parse, allow_hyphen_values = true)]
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
    #[arg(long = "roughness-layout", value_parser = choice::<RoughnessLayout>(), default_value = "gray", requires = "roughness_map")]
    pub roughness_layout: RoughnessLayout,
}

/// How it is drawn.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Technique")]
pub struct TechniqueGroup {
    /// Any technique of the catalogue (below); one that cannot draw the scene says why
    #[arg(long, value_enum, default_value = "kilgard")]
    pub technique: TechniqueArg,
    /// reference: samples per pixel (stratified); the image converges as it grows
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=bumpmap::options::MAX_SAMPLES_PER_PIXEL as i64))]
    pub spp: u32,
    /// Texture filtering of the normal map and decal
    #[arg(long, value_parser = choice::<Filter>(), default_value = "trilinear")]
    pub filter: Filter,
    /// Leave out Eq. 12's self-shadowing term (Figure 14, left)
    #[arg(long = "no-self-shadow")]
    pub no_self_shadow: bool,
    /// kilgard: register-combiner arithmetic
    #[arg(long, value_parser = choice::<Precision>(), default_value = "float")]
    pub precision: Precision,
    /// kilgard: specular form of the third pass
    #[arg(long = "specular-mode", value_parser = choice::<SpecularMode>(), default_value = "power8")]
    pub specular_mode: SpecularMode,
    /// Face size of the normalization cube map
    #[arg(long = "cube-size", default_value_t = 32, value_parser = clap::value_parser!(u32).range(1..=bumpmap::options::MAX_CUBE_SIZE as i64))]
    pub cube_size: u32,
    /// single-pass and its variants: how L and H are renormalized per fragment [default: math; the cube map for single-pass-cube and kilgard]
    #[arg(long, value_parser = choice::<Normalize>())]
    pub normalize: Option<Normalize>,
    /// single-pass: the self-shadowing factor (kilgard: see --no-self-shadow)
    #[arg(long = "self-shadow", value_parser = choice::<SelfShadow>(), default_value = "ramp")]
    pub self_shadow: SelfShadow,
    /// single-pass: per-vertex or per-fragment half-angle vector
    #[arg(long = "half-angle", value_parser = choice::<HalfAngle>(), default_value = "vertex")]
    pub half_angle: HalfAngle,
    /// single-pass: geometric self-shadowing of the specular term
    #[arg(long = "specular-shadow", value_parser = choice::<SpecularShadow>(), default_value = "kilgard")]
    pub specular_shadow: SpecularShadow,
    /// single-pass: how the specular lobe answers the bumps a pixel averages (toksvig: the exponent from the mip chain's |N|; roughness-map: from a roughness map made of it, or --roughness-map FILE; lean and clean: the slopes' moments; a distant bumpy surface's highlight widens and dims; `--technique toksvig` or `lean` sets it)
    #[arg(long = "specular-filter", value_parser = choice::<SpecularFilter>(), default_value = "none")]
    pub specular_filter: SpecularFilter,
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
    #[arg(long = "parallax-shadow", value_parser = choice::<ParallaxShadow>(), default_value = "off")]
    pub parallax_shadow: ParallaxShadow,
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
    #[arg(long, value_parser = choice::<BackendChoice>(), default_value = "cpu")]
    pub backend: BackendChoice,
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
    #[arg(long, default_value_t = crate::render::DEFAULT_SIZE, value_parser = parse_side, conflicts_with_all = ["width", "height"])]
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
