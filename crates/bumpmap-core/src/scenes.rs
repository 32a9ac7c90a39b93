//! The built-in scenes: the paper's torus (Figures 11, 12, 14), the Cg Tutorial's wall and
//! floor (Figure 8-4), Peercy's stretched patch (Figure 4), a sphere, and any mesh.

use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3};

use bumpmap_math::blinn::displacement_per_unit_height;
use bumpmap_math::lighting::Light;
use bumpmap_math::mesh::Mesh;
use bumpmap_math::surface::{BicubicPatch, Surface};
use bumpmap_math::{HeightField, HeightMips, MipChain, MipMode, NormalMapOptions, Rgba8Image, Rgba8Mips, bricks_decal};

use crate::bump_maps::{BumpMap, offset_map, surface_material};
use crate::error::CoreError;
use crate::parts::MeshParts;

mod replace;
use crate::scene::{
    AlphaMode, Camera, Material, NormalSpace, NormalTexels, Scene, SceneLight, SceneObject, SurfaceHeights,
    SurfaceSource, ViewerModel,
};

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
/// about it. The technique catalogue ([`crate::catalogue`]) builds a [`Scene`] from it with the
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

    /// The scene with the tangent-space normal map (no technique's own maps).
    pub fn build(&self) -> Result<Scene, CoreError> {
        build(&self.kind, &self.params)
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
    /// another up ([`Camera::view_up`]).
    pub up: Option<Vec3>,
    /// The vertical field of view in degrees.
    pub fov_y_degrees: f32,
    /// The lights; when empty, [`default_light`] as a white light.
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
    /// [`Surface::max_depth`] (a loaded mesh: a tenth of its bounding radius).
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

/// A loaded mesh's frame for its default camera and light: its bounding sphere, and which
/// way is up, toward the front (glTF's +Z: "the front of a glTF asset faces +Z") and right.
struct MeshFrame {
    centre: Vec3,
    radius: f32,
    up: Vec3,
    front: Vec3,
    right: Vec3,
}

impl MeshFrame {
    fn new(mesh: &Mesh, up: Vec3) -> Self {
        let (lo, hi) = mesh.positions.iter().fold((Vec3::MAX, Vec3::MIN), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let (centre, radius) = if lo.cmple(hi).all() {
            ((lo + hi) * 0.5, ((hi - lo).length() * 0.5).max(1e-6))
        } else {
            (Vec3::ZERO, 1.0)
        };
        let up = up.normalize_or(Vec3::Y);
        // +Z made perpendicular to up; with up along ±Z, the front is −Y (Blender's front view).
        let front = (Vec3::Z - up * up.dot(Vec3::Z)).try_normalize().unwrap_or(Vec3::NEG_Y);
        Self { centre, radius, up, front, right: up.cross(front) }
    }

    /// From the front and somewhat above, far enough that the bounding sphere fits a vertical
    /// field of view of `fov_y_degrees`.
    fn eye(&self, fov_y_degrees: f32) -> Vec3 {
        let distance = 1.1 * self.radius / (0.5 * fov_y_degrees.to_radians()).sin();
        self.centre + distance * (self.front + 0.35 * self.up).normalize()
    }

    /// Above, to the left and in front, three radii out.
    fn light(&self) -> Vec3 {
        self.centre + 3.0 * self.radius * (-0.6 * self.right + self.up + 1.2 * self.front).normalize()
    }
}

/// The default light of each scene: the peer's orbit start for the torus, upper left for the
/// flat scenes, and for a mesh above, left and in front of it in its own units and axes
/// (`params.up` says which way is up).
pub fn default_light(kind: &SceneKind, params: &SceneParams) -> Light {
    match kind {
        SceneKind::Torus => {
            let a = -2.2f32;
            Light::Positional(Vec3::new(4.0 * a.cos(), 4.0 * a.sin(), 3.0))
        }
        SceneKind::Wall => Light::Positional(Vec3::new(-2.0, 1.5, 2.0)),
        SceneKind::WallFloor => Light::Positional(Vec3::new(-2.5, 2.8, 0.5)),
        SceneKind::Patch => Light::Positional(Vec3::new(-3.0, -1.0, 1.2)),
        SceneKind::Floor => Light::Positional(Vec3::new(-1.5, 2.5, 1.0)),
        SceneKind::Sphere => Light::Positional(Vec3::new(-3.0, -3.0, 4.0)),
        SceneKind::Mesh(mesh) => Light::Positional(MeshFrame::new(mesh, params.up.unwrap_or(Vec3::Y)).light()),
    }
}

/// The largest side of the default brick decal: a flat colour texture has nothing to show
/// past it, and at the bumps' 16384² it took 1.3 GiB (and as much again in a texture unit).
const MAX_DEFAULT_DECAL: usize = 2048;

/// Builds a scene. Fails when the height field cannot become a normal map, when a map made
/// for a surface is asked of a mesh or one made from heights of a normal map, and when the eye
/// is at the point looked at.
pub fn build(kind: &SceneKind, params: &SceneParams) -> Result<Scene, CoreError> {
    let decal = match (&params.decal, params.default_decal) {
        (Some(d), _) => Some(d.clone()),
        (None, true) => {
            // Drawn at the bumps' size, halved while over MAX_DEFAULT_DECAL: the bricks are defined
            // in texture coordinates, so the mortar still meets the height field's.
            let (mut w, mut h) = params.bumps.size();
            while w.max(h) > MAX_DEFAULT_DECAL {
                (w, h) = (w.div_ceil(2), h.div_ceil(2));
            }
            Some(Arc::new(Rgba8Mips::with_box_mipmaps(Rgba8Image::new(w, h, bricks_decal(w, h)))))
        }
        (None, false) => None,
    };
    let (material, encoding, heights) = material(params, &params.bumps, decal)?;
    let object = |surface: Surface, tess: (usize, usize), repeat: Vec2, world_from_object: Mat4| {
        let repeat = params.repeat.unwrap_or(repeat);
        let mut material = surface_material(params, &material, &surface, repeat, encoding);
        if let Some(h) = &material.heights {
            let made = || {
                displacement_per_unit_height(&surface, repeat, (h.width(), h.height()), params.normal_map.scale.abs())
            };
            // Never zero (a bump scale of 0): a ray's descent per unit of height must be finite.
            let limit = surface.max_depth();
            material.depth = params.depth.unwrap_or_else(made).min(limit).max(limit * 1e-6);
        }
        SceneObject {
            mesh: Arc::new(surface.tessellate(
                params.tessellation.unwrap_or(tess).0,
                params.tessellation.unwrap_or(tess).1,
                repeat,
            )),
            world_from_object,
            material,
            source: Some(SurfaceSource {
                surface,
                repeat,
                heights: heights.map(|field| SurfaceHeights { field: field.clone(), options: params.normal_map }),
            }),
            st_derivatives: None,
        }
    };
    let (objects, eye, target, up) = match kind {
        SceneKind::Torus => {
            let (major, minor) = params.torus_radii;
            let torus = object(Surface::Torus { major, minor }, (128, 64), Vec2::new(6.0, 2.0), Mat4::IDENTITY);
            (vec![torus], Vec3::new(0.0, -5.6, 5.0), Vec3::new(0.0, 0.0, -0.35), Vec3::Z)
        }
        SceneKind::Wall => {
            let wall = object(Surface::Wall { width: 4.0, height: 4.0 }, (8, 8), Vec2::new(2.0, 2.0), Mat4::IDENTITY);
            (vec![wall], Vec3::new(0.0, 0.0, 6.0), Vec3::ZERO, Vec3::Y)
        }
        SceneKind::Floor => {
            let floor = object(Surface::Floor { width: 4.0, depth: 4.0 }, (8, 8), Vec2::new(2.0, 2.0), Mat4::IDENTITY);
            (vec![floor], Vec3::new(0.0, 4.0, 5.0), Vec3::ZERO, Vec3::Y)
        }
        SceneKind::WallFloor => {
            // Figure 8-4: a wall standing on the far edge of a floor, one light for both.
            let wall = object(
                Surface::Wall { width: 4.0, height: 3.0 },
                (8, 8),
                Vec2::new(2.0, 1.5),
                Mat4::from_translation(Vec3::new(0.0, 1.5, -2.0)),
            );
            let floor = object(Surface::Floor { width: 4.0, depth: 4.0 }, (8, 8), Vec2::new(2.0, 2.0), Mat4::IDENTITY);
            (vec![wall, floor], Vec3::new(0.0, 2.2, 5.0), Vec3::new(0.0, 0.8, -1.0), Vec3::Y)
        }
        SceneKind::Patch => {
            // One pinwheel over the whole patch, as in Peercy's Figures 4–7: its texels are
            // stretched four to one and sheared, which is what the surface-independent map
            // gets wrong.
            let patch = object(Surface::Patch(BicubicPatch::stretched()), (8, 8), Vec2::ONE, Mat4::IDENTITY);
            (vec![patch], Vec3::new(0.4, -3.2, 4.0), Vec3::ZERO, Vec3::Z)
        }
        SceneKind::Sphere => {
            let sphere = object(Surface::Sphere { radius: 1.5 }, (64, 32), Vec2::new(4.0, 2.0), Mat4::IDENTITY);
            (vec![sphere], Vec3::new(0.0, -5.0, 1.5), Vec3::ZERO, Vec3::Z)
        }
        SceneKind::Mesh(_) if params.bump_map.needs_surface() => {
            return Err(CoreError::MapNeedsSurface(params.bump_map));
        }
        SceneKind::Mesh(mesh) => {
            // The mesh stays in its own units and axes; the default camera frames its bounds.
            let frame = MeshFrame::new(mesh, params.up.unwrap_or(Vec3::Y));
            let placed = |mesh: &Arc<Mesh>, mut material: Material| {
                let st_derivatives = match &material.heights {
                    Some(h) => {
                        let made = || {
                            let side = mesh.mean_texel_side((h.width(), h.height())).unwrap_or(frame.radius / 1024.0);
                            side * params.normal_map.scale.abs()
                        };
                        material.depth =
                            params.depth.unwrap_or_else(made).min(0.1 * frame.radius).max(frame.radius * 1e-7);
                        Some(Arc::new(mesh.st_derivatives()))
                    }
                    None => None,
                };
                SceneObject {
                    mesh: mesh.clone(),
                    world_from_object: Mat4::IDENTITY,
                    material,
                    source: None,
                    st_derivatives,
                }
            };
            let objects = match &params.parts {
                None => vec![placed(mesh, material.clone())],
                Some(parts) => {
                    // Each part material's maps once, however many parts draw with it.
                    let mut made: Vec<Option<Material>> = vec![None; parts.materials.len()];
                    let mut objects = Vec::with_capacity(parts.parts.len());
                    for part in &parts.parts {
                        let own = parts.materials.get(part.material).ok_or(CoreError::PartMaterial {
                            part: objects.len(),
                            material: part.material,
                            materials: parts.materials.len(),
                        })?;
                        if made[part.material].is_none() {
                            let mut m = match &own.bumps {
                                None => Material { decal: own.decal.clone(), ..material.clone() },
                                Some(bumps) => self::material(params, bumps, own.decal.clone())?.0,
                            };
                            m.sampler = own.sampler;
                            m.alpha = own.alpha;
                            m.occlusion = own.occlusion.clone();
                            m.emission = own.emission.clone();
                            // The file's roughness belongs to its own normal map: where an
                            // explicit one replaced it, the roughness is made from that instead.
                            let size = |t: &Rgba8Mips| (t.width(), t.height());
                            m.roughness_map = own.roughness_map.clone().filter(|r| size(r) == size(&m.normal_map));
                            made[part.material] = Some(m);
                        }
                        let m = made[part.material].clone().expect("made above");
                        objects.push(placed(&part.mesh, m));
                    }
                    objects
                }
            };
            (objects, frame.eye(params.fov_y_degrees), frame.centre, frame.up)
        }
    };
    let lights = if params.lights.is_empty() {
        vec![SceneLight::white(default_light(kind, params))]
    } else {
        params.lights.clone()
    };
    let (eye, target) = (params.eye.unwrap_or(eye), params.target.unwrap_or(target));
    if eye == target {
        return Err(CoreError::EyeAtTarget { eye });
    }
    let (near, far) = clip_planes(&objects, eye);
    Ok(Scene {
        camera: Camera { eye, target, up: params.up.unwrap_or(up), fov_y_degrees: params.fov_y_degrees, near, far },
        viewer: params.viewer,
        lights,
        objects,
    })
}

/// The material `bumps` and `decal` make under `params`: the normal map and its mip chain, the
/// heights as geometry where asked for, the offset map where the bump map is one; with the
/// chain's encoding and the height field behind it, if any.
fn material<'a>(
    params: &SceneParams,
    bumps: &'a BumpSource,
    decal: Option<Arc<Rgba8Mips>>,
) -> Result<(Material, bumpmap_math::Encoding, Option<&'a Arc<HeightField>>), CoreError> {
    let needs_heights = matches!(params.bump_map, BumpMap::Offset | BumpMap::Derivatives | BumpMap::SurfaceDependent);
    let (chain, heights) = match bumps {
        BumpSource::Heights(field) => {
            (Arc::new(MipChain::<[u8; 4]>::from_height(field, &params.normal_map, params.mip_mode)?), Some(field))
        }
        BumpSource::NormalMap(_) if needs_heights => return Err(CoreError::MapNeedsHeights(params.bump_map)),
        BumpSource::NormalMap(chain) if params.mip_mode == MipMode::Renormalize => {
            (Arc::new(chain.with_opaque_alpha()), None)
        }
        BumpSource::NormalMap(chain) => (chain.clone(), None),
    };
    // The chain becomes the material's texture; copied only when the caller still holds it.
    let encoding = chain.encoding;
    let normal_map = Arc::new(Arc::try_unwrap(chain).map_or_else(|shared| shared.to_mips(), MipChain::into_mips));
    let mut material = Material {
        normal_map,
        normal_space: NormalSpace::Tangent,
        normal_texels: NormalTexels::UnitVector,
        decal,
        ambient: params.ambient,
        diffuse: params.diffuse,
        specular: params.specular,
        shininess: params.shininess,
        height_map: heights.filter(|_| params.height_map).map(|field| {
            Arc::new(Rgba8Mips::with_box_mipmaps(Rgba8Image::from_gray(field.width(), field.height(), &field.to_u8())))
        }),
        bump_scale: params.normal_map.scale,
        heights: None,
        depth: 0.0,
        sampler: Default::default(),
        alpha: AlphaMode::Opaque,
        occlusion: None,
        emission: None,
        roughness_map: None,
    };
    if params.displacement {
        if let Some(d) = params.depth
            && !(d.is_finite() && d > 0.0)
        {
            return Err(CoreError::out_of_range("the depth", d, "a positive number of object units"));
        }
        let mut mips = match (&params.height_mips, heights) {
            (Some(given), _) => Some(given.clone()),
            (None, Some(field)) => Some(Arc::new(HeightMips::from_field(field)?)),
            // A normal map given without heights: the catalogue's requirement names what is missing.
            (None, None) => None,
        };
        if let (Some(m), Some(horizons)) = (&mips, &params.horizon_map) {
            mips = Some(Arc::new((**m).clone().with_horizons(horizons.clone())?));
        }
        if let Some(h) = &mips {
            let (hs, ns) = ((h.width(), h.height()), (material.normal_map.width(), material.normal_map.height()));
            if hs != ns {
                return Err(CoreError::HeightsSize { heights: hs, normal_map: ns });
            }
        }
        material.heights = mips;
    }
    if let (BumpMap::Offset | BumpMap::Derivatives, Some(field)) = (params.bump_map, heights) {
        let (map, range) = offset_map(field, &params.normal_map)?;
        material.normal_map = Arc::new(map);
        material.normal_texels = NormalTexels::Offset { range };
    }
    Ok((material, encoding, heights))
}

/// The near and far planes for an eye at `eye`: 0.5 and 50 (the built-in scenes' own) where
/// they hold the objects' bounding sphere, otherwise planes around that sphere — the near one
/// no closer than a thousandth of its radius, for an eye inside it — so that a mesh in any units
/// and a distant eye are neither clipped away nor squeezed into a few depth steps.
fn clip_planes(objects: &[SceneObject], eye: Vec3) -> (f32, f32) {
    let (lo, hi) = objects
        .iter()
        .flat_map(|o| o.mesh.positions.iter().map(|&p| o.world_from_object.transform_point3(p)))
        .fold((Vec3::MAX, Vec3::MIN), |(lo, hi), p| (lo.min(p), hi.max(p)));
    if !lo.cmple(hi).all() {
        return (0.5, 50.0);
    }
    let (centre, radius) = ((lo + hi) * 0.5, (hi - lo).length() * 0.5);
    let distance = eye.distance(centre);
    let (near, far) = ((distance - radius) * 0.95, (distance + radius) * 1.05);
    if near >= 0.5 && far <= 50.0 {
        return (0.5, 50.0);
    }
    (near.max(radius * 1e-3).max(1e-6), far.max(near * 2.0).max(1e-5))
}
