//! What setting a scene up from options can refuse, and what it notes, each naming the option
//! as a [`SceneOption`] and the file as given. A skin (the command line, the Python package)
//! words the option its own way; [`SceneOption::name`] is the name Rust and Python share.

use std::fmt;
use std::path::PathBuf;

use bumpmap_core::TechniqueName;
use bumpmap_core::technique::SpecularFilter;
use bumpmap_io::IoError;
use bumpmap_io::error::shown;
use bumpmap_math::buffer::OutOfMemory;
use glam::Vec3;

/// An option of [`super::SceneOptions`] that a message names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneOption {
    /// [`super::SceneOptions::height_field`].
    HeightField,
    /// [`super::SceneOptions::normal_map`].
    NormalMap,
    /// [`super::SceneOptions::bump_scale`].
    BumpScale,
    /// [`super::SceneOptions::decal`].
    Decal,
    /// [`super::SceneOptions::torus_radii`].
    TorusRadii,
    /// [`super::CameraOptions::up`].
    Up,
    /// [`super::CameraOptions::fov_y_degrees`].
    Fov,
    /// [`super::MaterialOptions::ambient`].
    Ambient,
    /// [`super::MaterialOptions::diffuse`].
    Diffuse,
    /// [`super::MaterialOptions::specular`].
    Specular,
    /// [`super::MaterialOptions::shininess`].
    Shininess,
    /// [`super::MaterialOptions::roughness_map`].
    RoughnessMap,
    /// [`super::TechniqueChoice::precision`].
    Precision,
    /// [`super::TechniqueChoice::specular_mode`].
    SpecularMode,
    /// [`super::TechniqueChoice::specular_filter`].
    SpecularFilter,
    /// [`super::TechniqueChoice::filter`].
    Filter,
    /// [`super::SceneOptions::tessellation`].
    Tessellation,
    /// [`super::SceneOptions::repeat`].
    Repeat,
    /// [`super::CameraOptions::eye`].
    Eye,
    /// [`super::CameraOptions::target`].
    Target,
    /// [`super::LightOptions::spot`].
    Spot,
    /// [`super::TechniqueChoice::samples_per_pixel`].
    Spp,
    /// [`super::TechniqueChoice::cube_size`].
    CubeSize,
    /// [`super::HeightsOptions::depth`].
    Depth,
    /// [`super::HeightsOptions::layers`].
    Layers,
}

impl SceneOption {
    /// Every option a message may name.
    pub const ALL: [SceneOption; 25] = [
        SceneOption::HeightField,
        SceneOption::NormalMap,
        SceneOption::BumpScale,
        SceneOption::Decal,
        SceneOption::TorusRadii,
        SceneOption::Up,
        SceneOption::Fov,
        SceneOption::Ambient,
        SceneOption::Diffuse,
        SceneOption::Specular,
        SceneOption::Shininess,
        SceneOption::RoughnessMap,
        SceneOption::Precision,
        SceneOption::SpecularMode,
        SceneOption::SpecularFilter,
        SceneOption::Filter,
        SceneOption::Tessellation,
        SceneOption::Repeat,
        SceneOption::Eye,
        SceneOption::Target,
        SceneOption::Spot,
        SceneOption::Spp,
        SceneOption::CubeSize,
        SceneOption::Depth,
        SceneOption::Layers,
    ];

    /// Its name in snake case, as Python's keyword has it (the command line's flag is the same
    /// with dashes).
    pub const fn name(self) -> &'static str {
        match self {
            SceneOption::HeightField => "height_field",
            SceneOption::NormalMap => "normal_map",
            SceneOption::BumpScale => "bump_scale",
            SceneOption::Decal => "decal",
            SceneOption::TorusRadii => "torus_radii",
            SceneOption::Up => "up",
            SceneOption::Fov => "fov",
            SceneOption::Ambient => "ambient",
            SceneOption::Diffuse => "diffuse",
            SceneOption::Specular => "specular",
            SceneOption::Shininess => "shininess",
            SceneOption::RoughnessMap => "roughness_map",
            SceneOption::Precision => "precision",
            SceneOption::SpecularMode => "specular_mode",
            SceneOption::SpecularFilter => "specular_filter",
            SceneOption::Filter => "filter",
            SceneOption::Tessellation => "tessellation",
            SceneOption::Repeat => "repeat",
            SceneOption::Eye => "eye",
            SceneOption::Target => "target",
            SceneOption::Spot => "spot",
            SceneOption::Spp => "spp",
            SceneOption::CubeSize => "cube_size",
            SceneOption::Depth => "depth",
            SceneOption::Layers => "layers",
        }
    }
}

impl fmt::Display for SceneOption {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A map read beside the normal map that must have its size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BesideMap {
    /// The heights as geometry.
    Heights,
    /// The horizon map.
    Horizons,
}

impl BesideMap {
    /// What it holds, plural.
    pub const fn what(self) -> &'static str {
        match self {
            BesideMap::Heights => "heights",
            BesideMap::Horizons => "horizons",
        }
    }
}

/// Why options could not be set up.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// A value outside its range.
    #[error("{option} must be {expected}, got {got}")]
    OutOfRange {
        /// The option.
        option: SceneOption,
        /// What it must be ("in [0, 1]").
        expected: String,
        /// The value, as given.
        got: String,
    },
    /// An option the technique asked for does not take.
    #[error("{option} belongs to kilgard's register combiners; {technique} takes shininess and computes in float")]
    KilgardOnly {
        /// The kilgard option.
        option: SceneOption,
        /// The technique asked for.
        technique: TechniqueName,
    },
    /// A specular filter on a technique that does not draw the single pass's specular.
    #[error("specular_filter shapes the single pass's float specular; {technique} does not draw with it")]
    SpecularFilterNotDrawn {
        /// The technique asked for.
        technique: TechniqueName,
    },
    /// single-pass-cube asked to normalize by math.
    #[error("single-pass-cube normalizes by the cube map, not by math")]
    CubeNormalizes,
    /// A roughness map given to a technique and filter that do not read one.
    #[error("roughness_map is read by the roughness-map specular filter, not by {technique} with {specular_filter:?}")]
    RoughnessMapUnread {
        /// The technique asked for.
        technique: TechniqueName,
        /// The specular filter asked for.
        specular_filter: SpecularFilter,
    },
    /// A detail map given to a technique that does not read one.
    #[error(
        "detail_map is laid over the normal map by the single pass and its variants, not by {technique}: the paper's combiners have both texture units taken (the normal map, the normalization cube map), emboss reads no normal map and the reference draws the heights as a surface. Blend the detail into the normal map first (`bumpmap blend`, Python's blend_normals), as a GeForce 256 title would have"
    )]
    DetailNotDrawn {
        /// The technique asked for.
        technique: TechniqueName,
    },
    /// A mesh given in memory whose values cannot be drawn.
    #[error("{}: {reason}", shown(.path))]
    MeshValues {
        /// The name it was given under.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// A mesh whose vertices are all at one point.
    #[error("{}: every vertex is at {at}: the mesh has no extent, so there is nothing to draw", shown(.path))]
    NoExtent {
        /// The mesh.
        path: PathBuf,
        /// Where every vertex is.
        at: Vec3,
    },
    /// An image whose mipmaps would not fit in memory.
    #[error("{}: {source}; a smaller image needs less", shown(.path))]
    TooBig {
        /// The image.
        path: PathBuf,
        /// What would not fit.
        source: OutOfMemory,
    },
    /// A map read beside the normal map whose size is not the normal map's.
    #[error(
        "{}: is {}x{}, but the normal map is {}x{}: {} are read at the normal map's texture coordinates and levels",
        shown(.path), .size.0, .size.1, .normal_map.0, .normal_map.1, .map.what()
    )]
    SizeMismatch {
        /// The file.
        path: PathBuf,
        /// What it holds.
        map: BesideMap,
        /// Its size.
        size: (usize, usize),
        /// The normal map's.
        normal_map: (usize, usize),
    },
    /// Heights without the min–max levels an exact walk needs.
    #[error("{}: has no min–max levels beside it ({} not found), and {technique} walks them", shown(.path), shown(.minmax))]
    NoMinMax {
        /// The heights file.
        path: PathBuf,
        /// Where the min–max levels were looked for.
        minmax: PathBuf,
        /// The technique asked for.
        technique: TechniqueName,
    },
    /// A roughness map's level of the wrong size.
    #[error(
        "{}: is {}x{}, but level {level} comes after a {}x{} level, so it is {}x{}",
        shown(.path), .size.0, .size.1, .base.0, .base.1, .want.0, .want.1
    )]
    LevelSize {
        /// The level's file.
        path: PathBuf,
        /// Its level.
        level: usize,
        /// Its size.
        size: (usize, usize),
        /// The level before it.
        base: (usize, usize),
        /// The size it should have.
        want: (usize, usize),
    },
    /// A file could not be read.
    #[error(transparent)]
    Io(#[from] IoError),
    /// An asset, light or technique option the library refuses.
    #[error(transparent)]
    Library(#[from] crate::Error),
}

impl From<bumpmap_core::CoreError> for SetupError {
    fn from(e: bumpmap_core::CoreError) -> Self {
        SetupError::Library(crate::Error::Core(e))
    }
}

/// What setting up noted: what the assets brought or left out, what an option replaced.
#[derive(Clone, Debug, PartialEq)]
pub enum SetupNote {
    /// A line about a file (what a glTF's material gave, what a normal map is).
    About {
        /// The file.
        path: PathBuf,
        /// What it is or brought.
        line: String,
    },
    /// Something the caller may want to change.
    Warning(String),
    /// An option replaces what a mesh's material has.
    Replaces {
        /// The mesh.
        path: PathBuf,
        /// The option: the height field or normal map (the bumps), or the decal (base colour).
        option: SceneOption,
    },
    /// A bump scale given for a mesh whose material has no normal texture.
    NothingToScale {
        /// The mesh.
        path: PathBuf,
    },
    /// A roughness map of one level: its smaller levels are box-filtered and keep no spread.
    OneRoughnessLevel {
        /// The file.
        path: PathBuf,
    },
}

impl SetupNote {
    /// What `option` replaces of a mesh's material, in [`SetupNote::Replaces`].
    pub const fn replaced(option: SceneOption) -> &'static str {
        match option {
            SceneOption::Decal => "base colour",
            SceneOption::NormalMap => "normal map",
            SceneOption::Filter => "samplers' filters",
            _ => "bumps",
        }
    }

    /// Whether it is a warning rather than a note for the record.
    pub fn is_warning(&self) -> bool {
        matches!(self, SetupNote::Warning(_) | SetupNote::OneRoughnessLevel { .. })
    }
}

impl fmt::Display for SetupNote {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SetupNote::About { path, line } => write!(f, "{}: {line}", path.display()),
            SetupNote::Warning(w) => f.write_str(w),
            SetupNote::Replaces { path, option } => {
                write!(f, "{}: {option} replaces the material's {}", path.display(), SetupNote::replaced(*option))
            }
            SetupNote::NothingToScale { path } => {
                write!(f, "{}: bump_scale has nothing to scale: the material has no normalTexture", path.display())
            }
            SetupNote::OneRoughnessLevel { path } => write!(
                f,
                "{}: one level, so its smaller levels are box-filtered and hold no spread of the normals",
                shown(path)
            ),
        }
    }
}
