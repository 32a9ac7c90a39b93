//! The built-in scenes: the paper's torus (Figures 11, 12, 14), the Cg Tutorial's wall and
//! floor (Figure 8-4), Peercy's stretched patch (Figure 4), a sphere, and any mesh.

use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3};

use bumpmap_math::lighting::Light;
use bumpmap_math::mesh::Mesh;
use bumpmap_math::surface::{BicubicPatch, Surface};
use bumpmap_math::{HeightField, MipChain, MipMode, NormalMapOptions, Rgba8Image, Rgba8Mips, bricks_decal};

use crate::bump_maps::{BumpMap, offset_map, surface_material};
use crate::error::CoreError;
use crate::scene::{
    Camera, Material, NormalSpace, NormalTexels, Scene, SceneLight, SceneObject, SurfaceSource, ViewerModel,
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
    /// A loaded mesh (with normals, texture coordinates and tangents), centred and scaled to
    /// fit a unit-radius ball.
    Mesh(Arc<Mesh>),
}

impl SceneKind {
    /// Parses the built-in names (`mesh:FILE` is the CLI's business).
    pub fn parse(name: &str) -> Option<Self> {
        Some(match name {
            "torus" => SceneKind::Torus,
            "wall" => SceneKind::Wall,
            "floor" => SceneKind::Floor,
            "wall-floor" => SceneKind::WallFloor,
            "patch" => SceneKind::Patch,
            "sphere" => SceneKind::Sphere,
            _ => return None,
        })
    }
}

/// Everything adjustable about a built-in scene; `None` picks the scene's own default.
#[derive(Clone, Debug)]
pub struct SceneParams {
    /// The eye position in world space, or the scene's default.
    pub eye: Option<Vec3>,
    /// The point looked at, or the scene's default.
    pub target: Option<Vec3>,
    /// The vertical field of view in degrees.
    pub fov_y_degrees: f32,
    /// The lights; when empty, [`default_light`] as a white light.
    pub lights: Vec<SceneLight>,
    /// Local or infinite viewer for the half-angle vector.
    pub viewer: ViewerModel,
    /// The height field the normal map is made from.
    pub height_field: HeightField,
    /// How the height field becomes a normal map (kernel, bump scale, wrap, encoding).
    pub normal_map: NormalMapOptions,
    /// A decal image, box-filtered into its mipmaps.
    pub decal: Option<Rgba8Image>,
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
    /// renormalized normals.
    pub mip_mode: MipMode,
}

impl Default for SceneParams {
    /// The llvmpipe peer's settings: ambient 0.2, k_d 0.8, bump scale 4, bricks 256².
    fn default() -> Self {
        Self {
            eye: None,
            target: None,
            fov_y_degrees: 45.0,
            lights: Vec::new(),
            viewer: ViewerModel::Local,
            height_field: bumpmap_math::HeightPreset::Bricks.render(256, 256),
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
        }
    }
}

/// The default light of each scene: the peer's orbit start for the torus, upper left for the
/// flat scenes.
pub fn default_light(kind: &SceneKind) -> Light {
    match kind {
        SceneKind::Torus => {
            let a = -2.2f32;
            Light::Positional(Vec3::new(4.0 * a.cos(), 4.0 * a.sin(), 3.0))
        }
        SceneKind::Wall => Light::Positional(Vec3::new(-2.0, 1.5, 2.0)),
        SceneKind::WallFloor => Light::Positional(Vec3::new(-2.5, 2.8, 0.5)),
        SceneKind::Patch => Light::Positional(Vec3::new(-3.0, -1.0, 1.2)),
        SceneKind::Floor => Light::Positional(Vec3::new(-1.5, 2.5, 1.0)),
        _ => Light::Positional(Vec3::new(-3.0, -3.0, 4.0)),
    }
}

/// Builds a scene. Fails when the height field cannot become a normal map, or when a map made
/// for a surface is asked of a mesh.
pub fn build(kind: &SceneKind, params: &SceneParams) -> Result<Scene, CoreError> {
    let chain = MipChain::<[u8; 4]>::from_height(&params.height_field, &params.normal_map, params.mip_mode)?;
    let normal_map = Arc::new(chain.to_mips());
    let decal = match (&params.decal, params.default_decal) {
        (Some(d), _) => Some(Arc::new(Rgba8Mips::with_box_mipmaps(d.clone()))),
        (None, true) => {
            let (w, h) = (params.height_field.width(), params.height_field.height());
            Some(Arc::new(Rgba8Mips::with_box_mipmaps(Rgba8Image::new(w, h, bricks_decal(w, h)))))
        }
        (None, false) => None,
    };
    let material = Material {
        normal_map,
        normal_space: NormalSpace::Tangent,
        normal_texels: NormalTexels::UnitVector,
        decal,
        ambient: params.ambient,
        diffuse: params.diffuse,
        specular: params.specular,
        shininess: params.shininess,
        height_map: Some(Arc::new(Rgba8Mips::with_box_mipmaps(Rgba8Image::from_gray(
            params.height_field.width(),
            params.height_field.height(),
            &params.height_field.to_u8(),
        )))),
        bump_scale: params.normal_map.scale,
    };
    let mut material = material;
    if matches!(params.bump_map, BumpMap::Offset | BumpMap::Derivatives) {
        let (map, range) = offset_map(&params.height_field, &params.normal_map)?;
        material.normal_map = Arc::new(map);
        material.normal_texels = NormalTexels::Offset { range };
    }
    let heights = Arc::new(params.height_field.clone());
    let object = |surface: Surface, tess: (usize, usize), repeat: Vec2, world_from_object: Mat4| {
        let repeat = params.repeat.unwrap_or(repeat);
        let material = surface_material(params, &material, &surface, repeat, &chain);
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
                height_field: heights.clone(),
                normal_map: params.normal_map,
            }),
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
            let (lo, hi) = mesh.positions.iter().fold((Vec3::MAX, Vec3::MIN), |(lo, hi), &p| (lo.min(p), hi.max(p)));
            let centre = (lo + hi) * 0.5;
            let radius = ((hi - lo).length() * 0.5).max(1e-6);
            let world_from_object = Mat4::from_scale(Vec3::splat(1.5 / radius)) * Mat4::from_translation(-centre);
            let object =
                SceneObject { mesh: mesh.clone(), world_from_object, material: material.clone(), source: None };
            (vec![object], Vec3::new(0.0, -2.5, 3.5), Vec3::ZERO, Vec3::Z)
        }
    };
    let lights =
        if params.lights.is_empty() { vec![SceneLight::white(default_light(kind))] } else { params.lights.clone() };
    Ok(Scene {
        camera: Camera {
            eye: params.eye.unwrap_or(eye),
            target: params.target.unwrap_or(target),
            up,
            fov_y_degrees: params.fov_y_degrees,
            near: 0.5,
            far: 50.0,
        },
        viewer: params.viewer,
        lights,
        objects,
    })
}
