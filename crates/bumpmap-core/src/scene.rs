//! What is rendered, independent of how: camera, lights, objects with their meshes and
//! materials. Textures are plain RGBA8 data ([`Rgba8Mips`]); how they are sampled is the
//! backend's business.
//!
//! A technique turns a `Scene` into passes (`technique`); the vertex stage (`vertex`) turns an
//! object and a light into per-vertex inputs; a backend draws them.

use std::sync::Arc;

use glam::{Mat4, Vec3};

use bumpmap_math::lighting::Light;
pub use bumpmap_math::mesh::AlphaMode;
use bumpmap_math::mesh::Mesh;
use bumpmap_math::surface::Surface;
use bumpmap_math::{HeightField, HeightMips, NormalMapOptions, Rgba8Mips};

/// A perspective camera (`gluLookAt` + `gluPerspective`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The eye position in world space (`gluLookAt`'s eye).
    pub eye: Vec3,
    /// The point looked at, in world space.
    pub target: Vec3,
    /// The up direction in world space. Where it is parallel to `target − eye` (looking straight
    /// down on a scene, say), another is taken ([`Camera::view_up`]).
    pub up: Vec3,
    /// The vertical field of view in degrees (`gluPerspective`'s fovy).
    pub fov_y_degrees: f32,
    /// Distance to the near clipping plane, > 0.
    pub near: f32,
    /// Distance to the far clipping plane, > `near`.
    pub far: f32,
}

impl Camera {
    /// `clip_from_world` for an image of the given aspect ratio (width / height).
    pub fn clip_from_world(&self, aspect: f32) -> Mat4 {
        Mat4::perspective_rh_gl(self.fov_y_degrees.to_radians(), aspect, self.near, self.far)
            * Mat4::look_at_rh(self.eye, self.target, self.view_up())
    }

    /// The up direction the view is built with: [`Camera::up`], or where the view runs along
    /// it, −Z (+Y when `up` is itself along Z), so that looking straight down on a +Y-up scene
    /// shows its back at the top of the image, as a top view does.
    pub fn view_up(&self) -> Vec3 {
        let forward = (self.target - self.eye).normalize_or_zero();
        let up = self.up.normalize_or_zero();
        if forward.cross(up).length_squared() > 1e-8 {
            return self.up;
        }
        if up.z.abs() > 0.9 { Vec3::Y } else { Vec3::NEG_Z }
    }
}

/// Local or infinite viewer for the half-angle vector (Kilgard §6).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ViewerModel {
    #[default]
    /// H from the direction to the eye at each vertex (`GL_LIGHT_MODEL_LOCAL_VIEWER` true).
    Local,
    /// H from one view direction for the whole object, `eye − target`.
    Infinite,
}

bumpmap_math::named!(ViewerModel {
    Local => "local": "the half-angle from each vertex toward the eye",
    Infinite => "infinite": "one half-angle direction for the whole image (toward the eye from the target)",
});

/// A light, its colour, its fall-off with distance and an optional spotlight cone.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneLight {
    /// Where the light is: positional or directional, in world space.
    pub light: Light,
    /// Linear RGB colour; multiplies the material's diffuse and specular coefficients.
    pub color: Vec3,
    /// Fall-off with the distance to the light.
    pub attenuation: Attenuation,
    /// A spotlight cone (positional lights only), or `None`.
    pub spot: Option<Spot>,
}

impl SceneLight {
    /// A white light with no attenuation and no cone.
    pub fn white(light: Light) -> Self {
        Self { light, color: Vec3::ONE, attenuation: Attenuation::None, spot: None }
    }

    /// The light notation the command line and the Python package take: `[dir:]X,Y,Z[@R,G,B]`,
    /// a positional light's position (or, with `dir:`, the direction toward a light at
    /// infinity) and its colour (white when left out).
    ///
    /// ```
    /// use bumpmap_core::scene::SceneLight;
    /// use bumpmap_math::lighting::Light;
    /// let warm = SceneLight::parse("4,0,3@1,0.6,0.4").unwrap();
    /// assert_eq!(warm.light, Light::Positional(glam::Vec3::new(4.0, 0.0, 3.0)));
    /// assert!(SceneLight::parse("dir:0,0,0").is_err(), "a direction must not be zero");
    /// ```
    pub fn parse(spec: &str) -> Result<Self, String> {
        let (at, color) = match spec.split_once('@') {
            Some((p, c)) => (p, parse_vec3(c)?),
            None => (spec, Vec3::ONE),
        };
        match at.strip_prefix("dir:") {
            Some(d) => SceneLight::directional(parse_vec3(d)?, color),
            None => SceneLight::positional(parse_vec3(at)?, color),
        }
    }

    /// A point light at `position` of `color`; a position not finite or a colour negative or
    /// not finite is refused.
    pub fn positional(position: Vec3, color: Vec3) -> Result<Self, String> {
        if !position.is_finite() {
            return Err(format!("a light's position must be finite, got {position}"));
        }
        Ok(SceneLight { color: checked_color(color)?, ..SceneLight::white(Light::Positional(position)) })
    }

    /// A light at infinity toward `direction` (normalized) of `color`; a zero direction is refused.
    pub fn directional(direction: Vec3, color: Vec3) -> Result<Self, String> {
        let d = direction.normalize_or_zero();
        if d == Vec3::ZERO {
            return Err(format!("a directional light needs a finite, non-zero direction, got {direction}"));
        }
        Ok(SceneLight { color: checked_color(color)?, ..SceneLight::white(Light::Directional(d)) })
    }
}

/// A light's colour: finite and not negative.
fn checked_color(color: Vec3) -> Result<Vec3, String> {
    if !(color.is_finite() && color.min_element() >= 0.0) {
        return Err(format!("a light's colour must be finite and not negative, got {color}"));
    }
    Ok(color)
}

/// Three finite numbers, `X,Y,Z`.
fn parse_vec3(s: &str) -> Result<Vec3, String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|p| p.trim().parse::<f32>().map_err(|_| format!("'{p}' is not a number")))
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(Vec3::new(*x, *y, *z)),
        _ => Err(format!("expected X,Y,Z (three finite numbers), got '{s}'")),
    }
}

/// Fall-off with the distance d to a positional light (Kilgard §5.6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Attenuation {
    /// No fall-off: the factor is 1.
    None,
    /// OpenGL's `1 / (constant + linear·d + quadratic·d²)`.
    Polynomial {
        /// `GL_CONSTANT_ATTENUATION`.
        constant: f32,
        /// `GL_LINEAR_ATTENUATION`.
        linear: f32,
        /// `GL_QUADRATIC_ATTENUATION`.
        quadratic: f32,
    },
    /// The fog-coordinate style `exp(−density·d)`.
    Exponential {
        /// The density per unit distance, ≥ 0.
        density: f32,
    },
    /// `exp(−(density·d)²)`.
    ExponentialSquared {
        /// The density per unit distance, ≥ 0.
        density: f32,
    },
}

impl Attenuation {
    /// The notation the command line and the Python package take: `none`, `C,L,Q` (1/(C + L·d +
    /// Q·d²)), `exp:D` or `exp2:D`.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let num = |x: &str| x.trim().parse::<f32>().map_err(|_| format!("'{x}' is not a number"));
        if spec == "none" {
            return Ok(Attenuation::None);
        }
        if let Some(d) = spec.strip_prefix("exp2:") {
            return Ok(Attenuation::ExponentialSquared { density: num(d)? });
        }
        if let Some(d) = spec.strip_prefix("exp:") {
            return Ok(Attenuation::Exponential { density: num(d)? });
        }
        let v: Vec<f32> = spec.split(',').map(num).collect::<Result<_, _>>()?;
        match v.as_slice() {
            [c, l, q] => Ok(Attenuation::Polynomial { constant: *c, linear: *l, quadratic: *q }),
            _ => Err(format!("expected none, C,L,Q, exp:D or exp2:D, got '{spec}'")),
        }
    }

    /// The factor at distance `d`, in [0, 1] for valid parameters.
    #[inline]
    pub fn factor(&self, d: f32) -> f32 {
        match *self {
            Attenuation::None => 1.0,
            Attenuation::Polynomial { constant, linear, quadratic } => {
                (1.0 / (constant + linear * d + quadratic * d * d)).clamp(0.0, 1.0)
            }
            Attenuation::Exponential { density } => (-density * d).exp(),
            Attenuation::ExponentialSquared { density } => (-(density * d).powi(2)).exp(),
        }
    }
}

/// A spotlight: a cone around `direction` (world space, pointing away from the light) with
/// GL's `cos^exponent` fall-off, and optionally a pattern projected from the light (Segal et
/// al., Kilgard §5.6) through a square frustum whose half-angle is the cutoff.
#[derive(Clone, Debug, PartialEq)]
pub struct Spot {
    /// The cone's axis (`GL_SPOT_DIRECTION`) in world space: finite and non-zero, not necessarily unit.
    pub direction: Vec3,
    /// Half-angle of the cone in degrees, in (0, 90).
    pub cutoff_degrees: f32,
    /// `GL_SPOT_EXPONENT`: the exponent of the cosine to the axis, ≥ 0.
    pub exponent: f32,
    /// A texture projected from the light that multiplies the cone factor, or `None`.
    pub pattern: Option<Arc<Rgba8Mips>>,
}

impl Spot {
    /// The light's `clip_from_world` for projecting the pattern from `position`.
    pub fn clip_from_world(&self, position: Vec3) -> Mat4 {
        let d = self.direction.normalize();
        let up = if d.cross(Vec3::Z).length() > 1e-3 { Vec3::Z } else { Vec3::Y };
        Mat4::perspective_rh_gl(2.0 * self.cutoff_degrees.to_radians(), 1.0, 0.05, 1000.0)
            * Mat4::look_at_rh(position, position + d, up)
    }
}

/// The space a normal map's vectors live in (Peercy §2, Kilgard §5).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum NormalSpace {
    /// Tangent space: usable on any surface, lit with tangent-space L and H.
    #[default]
    Tangent,
    /// Tangent space, made for one surface (Peercy's surface-dependent map, Eq. 3–6): lit with
    /// tangent-space L and H as [`NormalSpace::Tangent`] is. The map covers the surface once; it
    /// is addressed with the texture coordinates times `scale`.
    SurfaceTangent {
        /// Multiplies the texture coordinates to address the map (1 / the texture's repeat).
        scale: glam::Vec2,
    },
    /// Object space, made for one surface: lit with object-space L and H. The map covers the
    /// surface once; it is addressed with the texture coordinates times `scale`.
    Object {
        /// Multiplies the texture coordinates to address the map (1 / the texture's repeat).
        scale: glam::Vec2,
    },
    /// Tangent space decoded per pixel as MikkTSpace's header says
    /// (`bumpmap_math::tangent::decode_per_pixel`): each fragment takes the map's normal to
    /// object space with the interpolated, unnormalized T and N and B = sign · N × T, and is lit
    /// with object-space L and H. What `bumpmap bake` inverts by default, and what glTF viewers
    /// do; [`NormalSpace::Tangent`] is the papers' per-vertex frame.
    TangentPerPixel,
}

impl NormalSpace {
    /// What the texture coordinates are multiplied by to address the map: 1 for a map that
    /// repeats with the texture.
    pub fn texcoord_scale(self) -> glam::Vec2 {
        match self {
            NormalSpace::Tangent | NormalSpace::TangentPerPixel => glam::Vec2::ONE,
            NormalSpace::SurfaceTangent { scale } | NormalSpace::Object { scale } => scale,
        }
    }

    /// Whether the map's vectors are in object space.
    pub fn is_object(self) -> bool {
        matches!(self, NormalSpace::Object { .. })
    }

    /// Whether L and H are in object space: an object-space map's, or a tangent-space one's
    /// decoded per pixel.
    pub fn lit_in_object_space(self) -> bool {
        matches!(self, NormalSpace::Object { .. } | NormalSpace::TangentPerPixel)
    }
}

/// What a normal map's texels hold.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum NormalTexels {
    /// RGB the range-compressed unit normal, A its length after filtering (Kilgard §5.3).
    #[default]
    UnitVector,
    /// An offset map (Kilgard §2.2, Eq. 6–7): RG the range-compressed offset `D / range`, the
    /// normal rebuilt per pixel as `normalize(N + D)`; B and A unused.
    Offset {
        /// The largest offset component the map stores, > 0.
        range: f32,
    },
    /// Peercy Figure 2's hardware: the same texels read as the height derivatives, and Blinn's
    /// normal made per pixel from them and the interpolated ∂P/∂u, ∂P/∂v of the surface
    /// (`var::PARAM_FRAME`).
    Derivatives {
        /// The largest offset component the map stores, > 0.
        range: f32,
        /// ∂d/∂u and ∂d/∂v of the displacement per unit of the stored slope
        /// (`bumpmap_math::blinn`: ℓ · repeat · size).
        scale: glam::Vec2,
    },
}

/// Surface appearance: a normal map with its mip chain, an optional decal and the lighting
/// coefficients of Kilgard Eq. 11 and 16.
#[derive(Clone, Debug)]
pub struct Material {
    /// RGB = range-compressed normal (unorm encoding), A = length of the filtered normal.
    pub normal_map: Arc<Rgba8Mips>,
    /// The space the normal map's vectors are in.
    pub normal_space: NormalSpace,
    /// What the normal map's texels hold.
    pub normal_texels: NormalTexels,
    /// A decal whose RGB multiplies the diffuse term (white when `None`).
    pub decal: Option<Arc<Rgba8Mips>>,
    /// The ambient term of Eq. 11, added once rather than per light.
    pub ambient: Vec3,
    /// k_diffuse of Eq. 11, per RGB channel.
    pub diffuse: Vec3,
    /// k_specular of Eq. 16, per RGB channel.
    pub specular: Vec3,
    /// The specular exponent of Eq. 16, > 0.
    pub shininess: f32,
    /// The height field itself as a gray texture with box mipmaps, for embossing (Kilgard
    /// §3.1), or `None`.
    pub height_map: Option<Arc<Rgba8Mips>>,
    /// The bump scale the normal map was made with (the height of a unit step, in texels).
    pub bump_scale: f32,
    /// The heights as geometry, carved below the surface (the parallax techniques and the
    /// displaced reference read them), or `None` where no technique asked for them.
    pub heights: Option<Arc<HeightMips>>,
    /// Object units along the normal per unit of height: how deep the heights carve
    /// ([`crate::scenes::SceneParams::depth`]).
    pub depth: f32,
    /// The material's own wrap modes (and filters, where it names them) for its normal map
    /// and decal: a glTF sampler's; repeating otherwise.
    pub sampler: crate::state::MaterialSampler,
    /// Opaque, cut out by the decal's alpha, or blended over what is behind by it.
    pub alpha: AlphaMode,
    /// What multiplies the ambient term per texel, in red (a glTF `occlusionTexture` with its
    /// strength folded in), read with the decal's coordinates; `None`: 1.
    pub occlusion: Option<Arc<Rgba8Mips>>,
    /// Light the surface gives off, added to the lit colour (a glTF `emissiveTexture` times
    /// `emissiveFactor`), read with the decal's coordinates; `None`: none.
    pub emission: Option<Arc<Rgba8Mips>>,
    /// Perceptual roughness in red at the normal map's size (a glTF `metallicRoughnessTexture`'s
    /// green times `roughnessFactor`), read by `SpecularFilter::RoughnessMap` in place of the one
    /// made from the normal map; `None`: made from the normal map.
    pub roughness_map: Option<Arc<Rgba8Mips>>,
}

/// A mesh placed in the world. The mesh must have normals, texture coordinates and tangents.
#[derive(Clone, Debug)]
pub struct SceneObject {
    /// The geometry in object space, with normals, texture coordinates and tangents.
    pub mesh: Arc<Mesh>,
    /// The object's model transform.
    pub world_from_object: Mat4,
    /// The surface appearance.
    pub material: Material,
    /// What the mesh and the normal map were made from, where they were made from an analytic
    /// surface: what a reference renderer evaluates instead. `None` for a loaded mesh.
    pub source: Option<SurfaceSource>,
    /// A loaded mesh's texture-space derivatives per vertex, where its material has heights as
    /// geometry; a built-in surface's come from the surface itself.
    pub st_derivatives: Option<Arc<StDerivatives>>,
}

/// A mesh's texture-space derivatives at each vertex: what a ray through its heights is
/// marched and bent with.
#[derive(Clone, Debug, PartialEq)]
pub struct StDerivatives {
    /// ∂P/∂s and ∂P/∂t (`Mesh::st_derivatives`).
    pub first: Vec<[glam::Vec3; 2]>,
    /// N·∂²P/∂s² and N·∂²P/∂t² (`Mesh::st_normal_curvature`): how the surface falls away from
    /// its tangent plane along s and t, so silhouettes can be cut on any mesh.
    pub second: Vec<glam::Vec2>,
}

impl StDerivatives {
    /// Both, of `mesh`.
    pub fn of(mesh: &bumpmap_math::mesh::Mesh) -> Self {
        let first = mesh.st_derivatives();
        let second = mesh.st_normal_curvature(&first);
        StDerivatives { first, second }
    }
}

impl SceneObject {
    /// The mean side of a texel of a `size` map on this object, in object units: the depth a
    /// bump scale of 1 stands for (`bumpmap_math::blinn::displacement_per_unit_height`). `None`
    /// for a mesh without texture coordinates or area.
    pub fn texel_side(&self, size: (usize, usize)) -> Option<f32> {
        match &self.source {
            Some(s) => Some(bumpmap_math::blinn::displacement_per_unit_height(&s.surface, s.repeat, size, 1.0)),
            None => self.mesh.mean_texel_side(size),
        }
    }
}

/// The exact surface and height field behind a built-in object (Peercy §2, Kilgard Eq. 5).
///
/// The mesh is `surface` tessellated with texture coordinates `repeat ⊙ (u, v)`; the normal
/// map is [`SurfaceHeights::field`] differentiated with its options' kernel and scale.
#[derive(Clone, Debug)]
pub struct SurfaceSource {
    /// The analytic surface, in object space.
    pub surface: Surface,
    /// Texture repeats along s and t.
    pub repeat: glam::Vec2,
    /// The heights the normal map was made from, or `None` for a normal map given as it is
    /// (a file's), which has no heights to differentiate.
    pub heights: Option<SurfaceHeights>,
}

/// A height field and the options that made the normal map from it.
#[derive(Clone, Debug)]
pub struct SurfaceHeights {
    /// The heights.
    pub field: Arc<HeightField>,
    /// The options the normal map was made with (its scale and wrap matter here).
    pub options: NormalMapOptions,
}

/// Everything a technique renders.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The camera the image is seen from.
    pub camera: Camera,
    /// Local or infinite viewer for the half-angle vector H.
    pub viewer: ViewerModel,
    /// The lights, each adding its own diffuse and specular terms.
    pub lights: Vec<SceneLight>,
    /// The objects drawn.
    pub objects: Vec<SceneObject>,
}
