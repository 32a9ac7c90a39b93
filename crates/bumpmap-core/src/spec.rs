//! A scene before any technique has made its maps: which geometry ([`SceneKind`]), where the
//! bumps come from ([`BumpSource`]), which bump texture the surface reads ([`BumpMap`]), a
//! loaded model's parts with their materials ([`parts`]), and everything adjustable
//! ([`SceneParams`]); [`SceneSpec`] is the geometry and its parameters together.
//!
//! What this module does not do: build a scene (`crate::scenes` does, and the technique
//! catalogue with each technique's maps), or make any map (`crate::bump_maps`).

use std::sync::Arc;

use glam::{Vec2, Vec3};

use bumpmap_math::mesh::Mesh;
use bumpmap_math::tangent::TangentDecode;
use bumpmap_math::{HeightField, HeightMips, MipChain, MipMode, NormalMapOptions, Rgba8Mips};

use crate::scene::{SceneLight, ViewerModel};

pub mod parts;

pub use parts::{MeshPart, MeshParts, PartMaterial};

/// What a material's bump texture holds and how the surface reads it. The techniques the papers
/// compare differ here; the lighting is the same for all.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum BumpMap {
    /// The tangent-space normal map of the height field, usable on any surface (Kilgard;
    /// Peercy's surface-independent map, Eq. 8–11).
    #[default]
    Tangent,
    /// That map's normals rotated by the surface's frame at each texel (Peercy §2.1): object
    /// space, lit with object-space L and H. Made for one surface.
    ObjectSpace,
    /// Peercy's surface-dependent map (Eq. 3–6, Figure 6): per texel, Blinn's perturbed normal
    /// from the surface's exact ∂P/∂u, ∂P/∂v in that texel's tangent frame, lit with tangent-space
    /// L and H exactly as [`BumpMap::Tangent`] is. Made for one surface.
    SurfaceDependent,
    /// An offset map (Kilgard §2.2, Eq. 6–7): the filtered offset added to the unperturbed
    /// normal and renormalized per pixel.
    Offset,
    /// Peercy Figure 2's hardware: the offset map read as the height derivatives, and Blinn's
    /// normal made per pixel from them and the interpolated ∂P/∂u, ∂P/∂v. Needs a surface.
    Derivatives,
}

impl BumpMap {
    /// Whether the map is made from, or read with, a surface's exact derivatives, so that a
    /// mesh cannot have it.
    pub fn needs_surface(self) -> bool {
        matches!(self, BumpMap::ObjectSpace | BumpMap::SurfaceDependent | BumpMap::Derivatives)
    }

    /// The map in words, for messages.
    pub fn describe(self) -> &'static str {
        match self {
            BumpMap::Tangent => "a tangent-space normal map",
            BumpMap::ObjectSpace => "an object-space normal map",
            BumpMap::SurfaceDependent => "a surface-dependent normal map",
            BumpMap::Offset => "an offset map",
            BumpMap::Derivatives => "a height-derivative map",
        }
    }
}

/// Which geometry a scene shows.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneKind {
    /// The paper's torus (Figures 11, 12, 14), radii [`SceneParams::torus_radii`].
    Torus,
    /// The Cg Tutorial's wall: a rectangle in the x–y plane facing +z.
    Wall,
    /// The Cg Tutorial's floor: a rectangle in the x–z plane facing +y.
    Floor,
    /// The wall standing on the far edge of the floor, one light for both (Cg Tutorial Figure 8-4).
    WallFloor,
    /// Peercy's highly stretched bicubic patch (Figure 4).
    Patch,
    /// A sphere of radius 1.5.
    Sphere,
    /// A loaded mesh (with normals, texture coordinates and tangents), drawn in its own units
    /// and axes; the default camera frames its bounds.
    Mesh(Arc<Mesh>),
}

impl SceneKind {
    /// The built-in scenes (every kind but a mesh), in the order the help texts list them.
    pub const BUILT_IN: [SceneKind; 6] = [
        SceneKind::Torus,
        SceneKind::Wall,
        SceneKind::Floor,
        SceneKind::WallFloor,
        SceneKind::Patch,
        SceneKind::Sphere,
    ];

    /// The scene's name as the command line spells it (`mesh` for a loaded mesh).
    pub fn name(&self) -> &'static str {
        match self {
            SceneKind::Torus => "torus",
            SceneKind::Wall => "wall",
            SceneKind::Floor => "floor",
            SceneKind::WallFloor => "wall-floor",
            SceneKind::Patch => "patch",
            SceneKind::Sphere => "sphere",
            SceneKind::Mesh(_) => "mesh",
        }
    }

    /// The built-in scenes' names, comma-separated, for messages.
    pub fn built_in_names() -> String {
        Self::BUILT_IN.iter().map(SceneKind::name).collect::<Vec<_>>().join(", ")
    }

    /// Parses a built-in scene's name (`mesh:FILE` is the caller's business: files are not
    /// this crate's).
    pub fn parse(name: &str) -> Option<Self> {
        Self::BUILT_IN.into_iter().find(|k| k.name() == name)
    }

    /// Whether the scene is an analytic surface (every built-in one), which the reference and the
    /// maps made for a surface need.
    pub fn is_surface(&self) -> bool {
        !matches!(self, SceneKind::Mesh(_))
    }
}

/// Where a material's bumps come from.
#[derive(Clone, Debug)]
pub enum BumpSource {
    /// A height field, made into a tangent-space normal map and its mip chain with the scene's
    /// [`SceneParams::normal_map`] options and [`SceneParams::mip_mode`]. Every technique can
    /// draw it.
    Heights(Arc<HeightField>),
    /// A tangent-space normal map given as it is (a file's, a glTF material's): Y along +t, its
    /// mip chain already made. [`SceneParams::normal_map`]'s kernel and scale do not apply;
    /// techniques that differentiate heights (embossing, offset maps, Peercy's maps, the
    /// reference) cannot draw it.
    NormalMap(Arc<MipChain>),
}

impl BumpSource {
    /// The size of level 0 of the normal map it makes.
    pub fn size(&self) -> (usize, usize) {
        match self {
            BumpSource::Heights(f) => (f.width(), f.height()),
            BumpSource::NormalMap(c) => (c.levels[0].width, c.levels[0].height),
        }
    }

    /// The same source without bumps: a flat field (or map) of the same size.
    pub fn flat(&self) -> Self {
        let (w, h) = self.size();
        match self {
            BumpSource::Heights(_) => BumpSource::Heights(Arc::new(HeightField::from_fn(w, h, |_, _| 0.5))),
            BumpSource::NormalMap(_) => BumpSource::flat_map(w, h),
        }
    }

    /// A `width`×`height` normal map of unperturbed normals: no bumps.
    pub fn flat_map(width: usize, height: usize) -> Self {
        let normals = vec![Vec3::Z; width * height];
        BumpSource::NormalMap(Arc::new(MipChain::from_normals(
            width,
            height,
            &normals,
            bumpmap_math::Encoding::Unorm,
            MipMode::LengthInAlpha,
        )))
    }
}

/// A scene before any technique has made its maps: which geometry, and everything adjustable
/// about it. The technique catalogue ([`crate::catalogue`]) builds a [`crate::Scene`] from it with the
/// maps each technique reads.
#[derive(Clone, Debug, Default)]
pub struct SceneSpec {
    /// The geometry.
    pub kind: SceneKind,
    /// Camera, lights, material, bumps.
    pub params: SceneParams,
}

impl Default for SceneKind {
    /// The paper's torus.
    fn default() -> Self {
        SceneKind::Torus
    }
}

impl SceneSpec {
    /// The scene `kind` with every parameter at its default (the paper's bricks, one light).
    pub fn new(kind: SceneKind) -> Self {
        Self { kind, params: SceneParams::default() }
    }
}

/// Everything adjustable about a scene; `None` picks the scene's own default.
#[derive(Clone, Debug)]
pub struct SceneParams {
    /// The eye position in world space, or the scene's default (for a mesh: one that frames
    /// its bounds from the front and above).
    pub eye: Option<Vec3>,
    /// The point looked at, or the scene's default (for a mesh: the centre of its bounds).
    pub target: Option<Vec3>,
    /// The world's up direction, or the scene's own (+Z for the torus, patch and sphere, +Y for
    /// the wall and floor and for meshes, as glTF and OBJ have it). A view along it picks
    /// another up ([`crate::scene::Camera::view_up`]).
    pub up: Option<Vec3>,
    /// The vertical field of view in degrees.
    pub fov_y_degrees: f32,
    /// The lights; when empty, [`crate::scenes::default_light`] as a white light.
    pub lights: Vec<SceneLight>,
    /// Local or infinite viewer for the half-angle vector.
    pub viewer: ViewerModel,
    /// Where the bumps come from: a height field, or a normal map given as it is.
    pub bumps: BumpSource,
    /// How a height field becomes a normal map (kernel, bump scale, wrap, encoding).
    pub normal_map: NormalMapOptions,
    /// A decal with its mipmaps (`Rgba8Mips::with_box_mipmaps`).
    pub decal: Option<Arc<Rgba8Mips>>,
    /// Use the brick decal that matches the brick height field when no decal is given.
    pub default_decal: bool,
    /// The material's ambient term.
    pub ambient: Vec3,
    /// The material's k_diffuse.
    pub diffuse: Vec3,
    /// The material's k_specular.
    pub specular: Vec3,
    /// The material's specular exponent, > 0.
    pub shininess: f32,
    /// The torus's (major, minor) radii.
    pub torus_radii: (f32, f32),
    /// Quads along u and v, both > 0, instead of the scene's own; ignored for a mesh.
    pub tessellation: Option<(usize, usize)>,
    /// Texture repeats along s and t instead of the scene's own (non-zero with a map made for the surface); ignored for a mesh.
    pub repeat: Option<Vec2>,
    /// The bump texture and how the surface reads it; the tangent-space normal map by default.
    pub bump_map: BumpMap,
    /// How a tangent-space map ([`BumpMap::Tangent`]) is decoded: in the papers' per-vertex
    /// frame, or per pixel as MikkTSpace's header says
    /// ([`crate::scene::NormalSpace::TangentPerPixel`]). `None`: as the technique drawing the
    /// scene decodes by default (`TechniqueName::default_decode`); a scene built without one is
    /// decoded per vertex.
    pub decode: Option<TangentDecode>,
    /// What the normal map's smaller levels store: the length factor (Kilgard §5.3) or
    /// renormalized normals. A [`BumpSource::NormalMap`] keeps its own levels, with A = 1 under
    /// [`MipMode::Renormalize`].
    pub mip_mode: MipMode,
    /// Whether the material also carries the height field as a texture (RGBA8 with its mips,
    /// four bytes a texel: 1.3 GiB for a 16384² field), which only embossing reads. On by
    /// default; the technique catalogue turns it off for every other technique.
    pub height_map: bool,
    /// How deep the heights carve below the surface where they are geometry, in object units per
    /// unit of height (finite, > 0). `None`: the depth the bump scale stands for, `normal_map.scale`
    /// texels of the object's mean texel side (`bumpmap_math::blinn::displacement_per_unit_height`),
    /// so the normal map's slopes are the geometry's. Clamped to the surface's
    /// [`bumpmap_math::surface::Surface::max_depth`] (a loaded mesh: a tenth of its bounding radius).
    pub depth: Option<f32>,
    /// Heights as geometry given as they are (the file `normalmap --height-out` writes), the
    /// normal map's size, instead of the height field's: what a normal map given as it is needs
    /// for the parallax techniques.
    pub height_mips: Option<Arc<HeightMips>>,
    /// The heights' horizon map given as it is (the files `normalmap --horizon-out` writes),
    /// instead of the one made from the heights when a technique reads it; level 0's size.
    pub horizon_map: Option<Arc<bumpmap_math::HorizonMap>>,
    /// Whether the material carries the heights as geometry ([`crate::scene::Material::heights`]);
    /// the technique catalogue turns it on for the techniques that read them.
    pub displacement: bool,
    /// A loaded mesh's parts with their own materials (a glTF's primitives), drawn instead of
    /// [`SceneKind::Mesh`]'s mesh as one object, which then only frames the camera and light.
    pub parts: Option<Arc<MeshParts>>,
}

impl SceneParams {
    /// Every bump source the scene draws: [`SceneParams::bumps`] and the parts' own.
    pub fn bump_sources(&self) -> impl Iterator<Item = &BumpSource> {
        std::iter::once(&self.bumps).chain(self.parts.iter().flat_map(|p| p.own_bumps()))
    }
}

impl Default for SceneParams {
    /// The llvmpipe peer's settings: ambient 0.2, k_d 0.8, bump scale 4, bricks 256².
    fn default() -> Self {
        Self {
            eye: None,
            target: None,
            up: None,
            fov_y_degrees: 45.0,
            lights: Vec::new(),
            viewer: ViewerModel::Local,
            bumps: BumpSource::Heights(Arc::new(bumpmap_math::HeightPreset::Bricks.render(256, 256))),
            normal_map: NormalMapOptions::default(),
            decal: None,
            default_decal: true,
            ambient: Vec3::splat(0.2),
            diffuse: Vec3::splat(0.8),
            specular: Vec3::ONE,
            shininess: 8.0,
            torus_radii: (2.0, 0.7),
            tessellation: None,
            repeat: None,
            bump_map: BumpMap::Tangent,
            decode: None,
            mip_mode: MipMode::LengthInAlpha,
            height_map: true,
            depth: None,
            height_mips: None,
            horizon_map: None,
            displacement: false,
            parts: None,
        }
    }
}
