//! A scene set up from typed options: what the command line's `render`, `bench render` and
//! `view` take and the Python package's keywords, as one Rust value with its defaults, turned
//! into a [`SceneSpec`] (the user's files loaded), a technique's options and what was read.
//!
//! ```
//! use bumpmap::options::{SceneChoice, SceneOptions};
//! use bumpmap::{Prepared, Renderer, BackendChoice, SceneKind, TechniqueName};
//!
//! let mut options = SceneOptions::default();
//! options.scene = SceneChoice::BuiltIn(SceneKind::Wall);
//! options.technique.technique = TechniqueName::Pom;
//! options.camera.eye = Some(glam::Vec3::new(0.0, -3.0, 1.2));
//! let set_up = options.set_up()?;
//! let prepared = Prepared::new(&set_up.spec, options.technique.technique, &set_up.options)?;
//! let image = Renderer::new(BackendChoice::Cpu)?.draw(&prepared, 64, 64)?;
//! assert!(image.texels.iter().any(|t| t[0] > 40), "the wall is lit");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Every value is checked here (ranges, an option another technique's family owns, a file the
//! normal map's size does not match) and refused with a [`SetupError`] that names the option as
//! a [`SceneOption`]; a skin words it (a flag, a keyword).
//!
//! What this module does not do: parse text (the command line's values, Python's keywords), or
//! draw ([`crate::Renderer`]); the backend is the renderer's choice, not a scene's.

use std::path::PathBuf;

use bumpmap_core::combiners::Precision;
use bumpmap_core::detail::BlendMethod;
use bumpmap_core::parallax::{DEFAULT_LAYERS, HitNormal, ParallaxShadow};
use bumpmap_core::scene::{Attenuation, SceneLight, ViewerModel};
use bumpmap_core::state::Sampler;
use bumpmap_core::technique::{HalfAngle, Normalize, SelfShadow, SpecularFilter, SpecularMode, SpecularShadow};
use bumpmap_core::{SceneKind, SceneSpec, TechniqueName, TechniqueOptions};
use bumpmap_io::{HeightSource, ObjTexcoords};
use bumpmap_math::YConvention;
use glam::{Vec2, Vec3};

mod build;
mod detail;
mod error;
mod files;
mod roughness;
mod technique;

pub use error::{SceneOption, SetupError, SetupNote};
pub use roughness::{RoughnessLayout, roughness_map};
pub use technique::{MAX_CUBE_SIZE, MAX_SAMPLES_PER_PIXEL, MAX_TESSELLATION};

/// Every option that says what is drawn and how, in the command line's groups. The defaults
/// are the command line's (a test holds the two together).
#[derive(Clone, Debug)]
pub struct SceneOptions {
    /// The geometry, its bumps and decal.
    pub scene: SceneChoice,
    /// Where the height field comes from (`None`: the bricks, or a glTF material's normal map).
    pub height_field: Option<HeightSource>,
    /// A normal map file drawn as it is, in place of a height field's.
    pub normal_map: Option<PathBuf>,
    /// Make the normal map's smaller levels from its level 0 instead of using the file's own.
    pub rebuild_mips: bool,
    /// Which way the normal map's green points as the image is displayed.
    pub y_convention: YConvention,
    /// A height field's scale (default 4), or what a normal map's slopes are multiplied by
    /// (default 1, or a glTF material's).
    pub bump_scale: Option<f32>,
    /// The decal (`None`: a glTF material's base colour, the brick decal for the bricks, or none).
    pub decal: Option<DecalChoice>,
    /// The torus's radii (hole centre to tube centre, tube).
    pub torus_radii: (f32, f32),
    /// Quads along u and v (`None`: the scene's).
    pub tessellation: Option<(usize, usize)>,
    /// Texture repeats along s and t (`None`: the scene's).
    pub repeat: Option<Vec2>,
    /// Let a glTF's buffer and image URIs lead outside its folder.
    pub allow_outside_paths: bool,
    /// How an OBJ file's v is read.
    pub obj_texcoords: ObjTexcoords,
    /// Where it is seen from.
    pub camera: CameraOptions,
    /// The lights.
    pub lights: LightOptions,
    /// The surface's coefficients and maps.
    pub material: MaterialOptions,
    /// The technique and how it draws.
    pub technique: TechniqueChoice,
    /// Heights as geometry.
    pub heights: HeightsOptions,
    /// A detail normal map laid over the normal map at render time.
    pub detail: DetailOptions,
}

impl Default for SceneOptions {
    fn default() -> Self {
        SceneOptions {
            scene: SceneChoice::default(),
            height_field: None,
            normal_map: None,
            rebuild_mips: false,
            y_convention: YConvention::YUp,
            bump_scale: None,
            decal: None,
            torus_radii: (2.0, 0.7),
            tessellation: None,
            repeat: None,
            allow_outside_paths: false,
            obj_texcoords: ObjTexcoords::FlipV,
            camera: CameraOptions::default(),
            lights: LightOptions::default(),
            material: MaterialOptions::default(),
            technique: TechniqueChoice::default(),
            heights: HeightsOptions::default(),
            detail: DetailOptions::default(),
        }
    }
}

/// The geometry drawn.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneChoice {
    /// A built-in surface.
    BuiltIn(SceneKind),
    /// A mesh file (.obj, .gltf, .glb), or the name of a [`Given::mesh`].
    Mesh(PathBuf),
}

impl Default for SceneChoice {
    fn default() -> Self {
        SceneChoice::BuiltIn(SceneKind::Torus)
    }
}

impl SceneChoice {
    /// `torus`, `wall`, … or `mesh:FILE`; `None` for any other name.
    pub fn parse(name: &str) -> Option<Self> {
        match name.strip_prefix("mesh:") {
            Some(path) => Some(SceneChoice::Mesh(PathBuf::from(path))),
            None => SceneKind::parse(name).map(SceneChoice::BuiltIn),
        }
    }

    /// Whether it is a glTF file (.gltf, .glb), whose material may bring a normal map.
    pub fn is_gltf(&self) -> bool {
        match self {
            SceneChoice::Mesh(path) => {
                let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
                matches!(ext.as_deref(), Some("gltf" | "glb"))
            }
            SceneChoice::BuiltIn(_) => false,
        }
    }
}

/// What [`SceneChoice::parse`] reads back: `torus`, or `mesh:FILE`.
impl std::fmt::Display for SceneChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SceneChoice::BuiltIn(kind) => write!(f, "{}", kind.name()),
            SceneChoice::Mesh(path) => write!(f, "mesh:{}", path.display()),
        }
    }
}

/// The decal asked for.
#[derive(Clone, Debug, PartialEq)]
pub enum DecalChoice {
    /// No decal, whatever the scene has.
    None,
    /// An image file (or the name of a [`Given::decal`]).
    File(PathBuf),
}

impl DecalChoice {
    /// `none`, or an image file.
    pub fn parse(text: &str) -> Self {
        match text {
            "none" => DecalChoice::None,
            path => DecalChoice::File(PathBuf::from(path)),
        }
    }
}

/// What [`DecalChoice::parse`] reads back.
impl std::fmt::Display for DecalChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DecalChoice::None => write!(f, "none"),
            DecalChoice::File(path) => write!(f, "{}", path.display()),
        }
    }
}

/// Where the camera is.
#[derive(Clone, Debug)]
pub struct CameraOptions {
    /// The eye (`None`: the scene's; for a mesh, in front of its bounds and above).
    pub eye: Option<Vec3>,
    /// The point looked at (`None`: the scene's; for a mesh, its bounds' centre).
    pub target: Option<Vec3>,
    /// The world's up (`None`: the scene's).
    pub up: Option<Vec3>,
    /// Vertical field of view, degrees in [1, 170].
    pub fov_y_degrees: f32,
    /// Local or infinite viewer for the half-angle vector.
    pub viewer: ViewerModel,
}

impl Default for CameraOptions {
    fn default() -> Self {
        CameraOptions { eye: None, target: None, up: None, fov_y_degrees: 45.0, viewer: ViewerModel::Local }
    }
}

/// The lights.
#[derive(Clone, Debug)]
pub struct LightOptions {
    /// The lights (empty: the scene's own).
    pub lights: Vec<SceneLight>,
    /// Attenuation with distance for every light.
    pub attenuation: Option<Attenuation>,
    /// Make every positional light a spotlight aimed this way.
    pub spot: Option<Vec3>,
    /// The spotlight's cone half-angle, degrees in (0, 90).
    pub spot_cutoff_degrees: f32,
    /// The spotlight's fall-off exponent (cos^E), ≥ 0.
    pub spot_exponent: f32,
    /// A pattern the spotlight projects, sampled at up to 2048 texels a side.
    pub spot_pattern: Option<HeightSource>,
}

impl Default for LightOptions {
    fn default() -> Self {
        LightOptions {
            lights: Vec::new(),
            attenuation: None,
            spot: None,
            spot_cutoff_degrees: 25.0,
            spot_exponent: 2.0,
            spot_pattern: None,
        }
    }
}

/// The surface's coefficients (Kilgard Eq. 11 and 16) and maps.
#[derive(Clone, Debug)]
pub struct MaterialOptions {
    /// Ambient intensity, in [0, 1].
    pub ambient: f32,
    /// Diffuse coefficient, in [0, 1].
    pub diffuse: f32,
    /// Specular coefficient, in [0, 1] (0 drops the specular pass).
    pub specular: f32,
    /// Specular exponent, positive.
    pub shininess: f32,
    /// A gloss map scaling the specular (single pass).
    pub gloss: GlossChoice,
    /// A roughness map file read by the roughness-map specular filter.
    pub roughness_map: Option<PathBuf>,
    /// The channels the roughness map holds its roughness in.
    pub roughness_layout: RoughnessLayout,
}

impl Default for MaterialOptions {
    fn default() -> Self {
        MaterialOptions {
            ambient: 0.2,
            diffuse: 0.8,
            specular: 1.0,
            shininess: 8.0,
            gloss: GlossChoice::None,
            roughness_map: None,
            roughness_layout: RoughnessLayout::Gray,
        }
    }
}

/// A gloss map.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum GlossChoice {
    /// None: the specular everywhere.
    #[default]
    None,
    /// The decal's alpha.
    DecalAlpha,
    /// The bricks' own: shiny bricks, dull mortar.
    Bricks,
    /// An image file's red channel, the decal's size.
    File(PathBuf),
}

impl GlossChoice {
    /// `none`, `decal-alpha`, `bricks`, or an image file.
    pub fn parse(text: &str) -> Self {
        match text {
            "none" => GlossChoice::None,
            "decal-alpha" => GlossChoice::DecalAlpha,
            "bricks" => GlossChoice::Bricks,
            path => GlossChoice::File(PathBuf::from(path)),
        }
    }
}

/// What [`GlossChoice::parse`] reads back.
impl std::fmt::Display for GlossChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            GlossChoice::None => write!(f, "none"),
            GlossChoice::DecalAlpha => write!(f, "decal-alpha"),
            GlossChoice::Bricks => write!(f, "bricks"),
            GlossChoice::File(path) => write!(f, "{}", path.display()),
        }
    }
}

/// Texture filtering of the normal map and decal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Filter {
    /// GL_NEAREST, no mipmaps.
    Nearest,
    /// GL_LINEAR, no mipmaps.
    Linear,
    /// GL_LINEAR_MIPMAP_LINEAR: the paper's choice.
    #[default]
    Trilinear,
}

bumpmap_math::named!(Filter {
    Nearest => "nearest": "GL_NEAREST: blocky, no mipmaps",
    Linear => "linear": "GL_LINEAR: bilinear, no mipmaps (shimmers at a distance)",
    Trilinear => "trilinear": "GL_LINEAR_MIPMAP_LINEAR: the paper's choice",
});

impl Filter {
    /// The sampler state, repeating.
    pub fn sampler(self) -> Sampler {
        match self {
            Filter::Nearest => Sampler::NEAREST_REPEAT,
            Filter::Linear => Sampler::LINEAR_REPEAT,
            Filter::Trilinear => Sampler::TRILINEAR_REPEAT,
        }
    }
}

/// The technique and the options of every family (each refused where another family owns it).
#[derive(Clone, Debug)]
pub struct TechniqueChoice {
    /// The technique of the catalogue.
    pub technique: TechniqueName,
    /// The reference's samples per pixel, 1 to 4096.
    pub samples_per_pixel: u32,
    /// The reference's sample pattern (0 is the default one).
    pub seed: u32,
    /// Texture filtering (`None`: a glTF material's sampler where it names filters, else
    /// trilinear); one given replaces every material's.
    pub filter: Option<Filter>,
    /// The self-shadowing factor (kilgard: the ramp or off).
    pub self_shadow: SelfShadow,
    /// kilgard: the register combiners' arithmetic.
    pub precision: Precision,
    /// kilgard: the third pass's specular form.
    pub specular_mode: SpecularMode,
    /// The normalization cube map's face size, 1 to 1024.
    pub cube_size: u32,
    /// How the single pass renormalizes L and H (`None`: by math; the cube map for
    /// single-pass-cube).
    pub normalize: Option<Normalize>,
    /// Per-vertex or per-fragment half-angle (single pass).
    pub half_angle: HalfAngle,
    /// The specular term's geometric self-shadowing (single pass).
    pub specular_shadow: SpecularShadow,
    /// How the specular lobe answers the bumps a pixel averages (single pass).
    pub specular_filter: SpecularFilter,
    /// How a tangent-space map is decoded (`None`: `TechniqueName::default_decode`'s choice,
    /// per pixel on meshes where the technique can).
    pub decode: Option<bumpmap_math::tangent::TangentDecode>,
}

impl Default for TechniqueChoice {
    fn default() -> Self {
        TechniqueChoice {
            technique: TechniqueName::Kilgard,
            samples_per_pixel: 64,
            seed: 0,
            filter: None,
            self_shadow: SelfShadow::Ramp,
            precision: Precision::Float,
            specular_mode: SpecularMode::EighthPower,
            cube_size: 32,
            normalize: None,
            half_angle: HalfAngle::Vertex,
            specular_shadow: SpecularShadow::Kilgard,
            specular_filter: SpecularFilter::None,
            decode: None,
        }
    }
}

/// Heights as geometry.
#[derive(Clone, Debug)]
pub struct HeightsOptions {
    /// How deep the heights carve, in the scene's units (`None`: what the bump scale stands for).
    pub depth: Option<f32>,
    /// The heights as a file (`normalmap --height-out`'s).
    pub height_map: Option<PathBuf>,
    /// The horizon map as a file (`normalmap --horizon-out`'s).
    pub horizon_map: Option<PathBuf>,
    /// Layers of a march.
    pub layers: u32,
    /// Self-shadowing by the heights.
    pub parallax_shadow: ParallaxShadow,
    /// Bumps cut the silhouette of curved surfaces.
    pub silhouettes: bool,
    /// Write the depth where the ray met the heights.
    pub write_depth: bool,
    /// Multiply the ambient term by the heights' ambient occlusion.
    pub ambient_occlusion: bool,
    /// The normal the hit is shaded with (`None`: the technique's own).
    pub hit_normal: Option<HitNormal>,
}

impl Default for HeightsOptions {
    fn default() -> Self {
        HeightsOptions {
            depth: None,
            height_map: None,
            horizon_map: None,
            layers: DEFAULT_LAYERS,
            parallax_shadow: ParallaxShadow::Off,
            silhouettes: false,
            write_depth: false,
            ambient_occlusion: false,
            hit_normal: None,
        }
    }
}

/// A detail normal map laid over the normal map per pixel ([`bumpmap_core::detail`]).
#[derive(Clone, Debug)]
pub struct DetailOptions {
    /// The detail's file (`None`: no detail), read as a normal map file is.
    pub map: Option<PathBuf>,
    /// How many times it repeats over one repeat of the normal map, each way.
    pub repeat: f32,
    /// How it is laid over the normal map.
    pub method: BlendMethod,
    /// What its slopes are multiplied by.
    pub strength: f32,
    /// Which way its green points (`None`: as [`SceneOptions::y_convention`] says).
    pub y_convention: Option<YConvention>,
}

impl Default for DetailOptions {
    fn default() -> Self {
        DetailOptions { map: None, repeat: 8.0, method: BlendMethod::Rnm, strength: 1.0, y_convention: None }
    }
}

/// Inputs given in memory instead of read from files (arrays from Python, say): each stands
/// where the file its option names would, used exactly as that file's contents would be. The
/// option must still be given: its path names the input in messages.
#[derive(Clone, Debug, Default)]
pub struct Given {
    /// [`SceneOptions::normal_map`]'s texture, as the file would load.
    pub normal_map: Option<bumpmap_io::StoredTexture>,
    /// [`SceneOptions::height_field`]'s heights.
    pub height_field: Option<bumpmap_math::HeightField>,
    /// [`SceneOptions::decal`]'s image.
    pub decal: Option<bumpmap_math::Rgba8Image>,
    /// [`DetailOptions::map`]'s texture, as the file would load.
    pub detail_map: Option<bumpmap_io::StoredTexture>,
    /// The mesh [`SceneChoice::Mesh`] names, in place of reading the file (no material: the
    /// scene's bumps and decal, as for an OBJ). Its normals are made from the faces where it
    /// has none, its tangents where it has none.
    pub mesh: Option<bumpmap_io::LoadedMesh>,
}

/// What the options describe, set up.
pub struct SetUp {
    /// The scene, with the user's assets in it.
    pub spec: SceneSpec,
    /// The options of every technique family, at the values the options give.
    pub options: TechniqueOptions,
    /// Every file read (found by name beside those given too): no output may replace one.
    pub inputs: Vec<PathBuf>,
    /// What the assets brought and left out, and what the options replaced.
    pub notes: Vec<SetupNote>,
}

impl SceneOptions {
    /// Checks the options, loads the files they name and builds the scene, the technique's
    /// options and the list of files read.
    pub fn set_up(&self) -> Result<SetUp, SetupError> {
        self.set_up_given(&Given::default())
    }

    /// [`Self::set_up`], with the inputs `given` in memory in place of their options' files.
    pub fn set_up_given(&self, given: &Given) -> Result<SetUp, SetupError> {
        build::set_up(self, given)
    }

    /// The files the options name, before anything is read (an output must replace none).
    pub fn named_inputs(&self) -> Vec<PathBuf> {
        files::named_inputs(self)
    }
}
