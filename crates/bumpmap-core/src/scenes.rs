//! The built-in scenes: the paper's torus (Figures 11, 12, 14), the Cg Tutorial's wall and
//! floor (Figure 8-4), Peercy's stretched patch (Figure 4), a sphere, and any mesh.

use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3};

use bumpmap_math::blinn::displacement_per_unit_height;
use bumpmap_math::lighting::Light;
use bumpmap_math::mesh::Mesh;
use bumpmap_math::surface::{BicubicPatch, Surface};
use bumpmap_math::tangent::TangentDecode;
use bumpmap_math::{HeightField, HeightMips, MipChain, MipMode, Rgba8Image, Rgba8Mips, bricks_decal};

use crate::bump_maps::{offset_map, surface_material};
use crate::error::CoreError;
pub use crate::spec::{BumpMap, BumpSource, SceneKind, SceneParams, SceneSpec};

mod replace;
use crate::scene::{
    AlphaMode, Camera, Material, NormalSpace, NormalTexels, Scene, SceneLight, SceneObject, SurfaceHeights,
    SurfaceSource,
};

impl SceneSpec {
    /// The scene with the tangent-space normal map (no technique's own maps).
    pub fn build(&self) -> Result<Scene, CoreError> {
        build(&self.kind, &self.params)
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
                        Some(Arc::new(crate::scene::StDerivatives::of(mesh)))
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
        normal_space: match params.decode.unwrap_or(TangentDecode::PerVertex) {
            TangentDecode::PerVertex => NormalSpace::Tangent,
            TangentDecode::MikkTSpace => NormalSpace::TangentPerPixel,
        },
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
