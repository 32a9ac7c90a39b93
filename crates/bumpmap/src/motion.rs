//! Moving a prepared scene between frames: the first light orbiting the point looked at, and
//! the camera turned about it and moved toward it. What a benchmark's frames and a viewer's
//! animation and mouse do to a [`Scene`], in one place.
//!
//! What this module does not do: keep time or read input (the caller says how far round), or
//! rebuild any map (a move never changes what a technique samples, only where it is seen from
//! and lit from).

use bumpmap_core::Scene;
use bumpmap_core::scene::Camera;
use bumpmap_math::lighting::Light;
use glam::{Quat, Vec3};

/// The first light of a scene carried round the point looked at, about the view's up axis: on
/// the torus, the llvmpipe peer's orbit (`(4 cos a, 4 sin a, 3)`).
///
/// ```
/// use bumpmap::motion::LightOrbit;
/// use bumpmap::{SceneKind, SceneSpec};
///
/// let mut scene = SceneSpec::new(SceneKind::Torus).build()?;
/// let orbit = LightOrbit::of(&scene);
/// let start = scene.lights[0].light;
/// orbit.place(&mut scene, 0.5, 0.0);
/// assert_ne!(scene.lights[0].light, start, "half a turn moves the light");
/// orbit.place(&mut scene, 1.0, 0.0);
/// let (bumpmap::Light::Positional(a), bumpmap::Light::Positional(b)) = (scene.lights[0].light, start) else {
///     unreachable!("the torus's light is positional")
/// };
/// assert!((a - b).length() < 1e-4, "a whole turn brings it back");
/// # Ok::<(), bumpmap::CoreError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightOrbit {
    axis: Vec3,
    centre: Vec3,
    start: Option<Light>,
}

/// The most a light or the eye is tilted toward the up axis, in radians: short of the pole,
/// where the turn about the axis would stop moving it.
pub const MAX_TILT: f32 = 1.45;

impl LightOrbit {
    /// The orbit of `scene`'s first light as it is now (none when the scene has no light).
    pub fn of(scene: &Scene) -> Self {
        let camera = scene.camera;
        Self {
            axis: camera.view_up().normalize_or(Vec3::Z),
            centre: camera.target,
            start: scene.lights.first().map(|l| l.light),
        }
    }

    /// Puts the first light `turns` of a full turn round the axis from where it started, and
    /// `tilt` radians from there toward the up axis (clamped to ±[`MAX_TILT`] from the plane
    /// of the orbit; a light already along the axis only turns).
    pub fn place(&self, scene: &mut Scene, turns: f32, tilt: f32) {
        let (Some(start), Some(light)) = (self.start, scene.lights.first_mut()) else { return };
        let turn = Quat::from_axis_angle(self.axis, std::f32::consts::TAU * turns);
        let lift = |v: Vec3| tilted(v, self.axis, tilt);
        light.light = match start {
            Light::Positional(p) => Light::Positional(self.centre + lift(turn * (p - self.centre))),
            Light::Directional(d) => Light::Directional(lift(turn * d)),
        };
    }
}

/// Moves the first light of `scene` to `at` (world space): a positional light is put there, a
/// directional one turned to shine from `at`'s direction (as seen from the origin). A scene
/// without lights is left as it is; a zero `at` leaves a directional light's direction.
///
/// ```
/// use bumpmap::motion::move_first_light;
/// use bumpmap::{Light, SceneKind, SceneSpec};
///
/// let mut scene = SceneSpec::new(SceneKind::Torus).build()?;
/// move_first_light(&mut scene, glam::Vec3::new(0.0, 0.0, 5.0));
/// assert_eq!(scene.lights[0].light, Light::Positional(glam::Vec3::new(0.0, 0.0, 5.0)));
/// # Ok::<(), bumpmap::CoreError>(())
/// ```
pub fn move_first_light(scene: &mut Scene, at: Vec3) {
    let Some(light) = scene.lights.first_mut() else { return };
    light.light = match light.light {
        Light::Positional(_) => Light::Positional(at),
        Light::Directional(d) => Light::Directional(at.try_normalize().unwrap_or(d)),
    };
}

/// The camera moved to `eye`, still looking at its target; refused where the eye is at the
/// target or so close that no direction is left between them (the frame would be black).
///
/// ```
/// use bumpmap::motion::move_eye;
/// use bumpmap::{SceneKind, SceneSpec};
///
/// let mut scene = SceneSpec::new(SceneKind::Torus).build()?;
/// move_eye(&mut scene, glam::Vec3::new(0.0, -6.0, 3.0))?;
/// let target = scene.camera.target;
/// assert!(move_eye(&mut scene, target).is_err(), "nowhere to look");
/// assert_eq!(scene.camera.eye, glam::Vec3::new(0.0, -6.0, 3.0), "a refused move leaves the camera");
/// # Ok::<(), bumpmap::CoreError>(())
/// ```
pub fn move_eye(scene: &mut Scene, eye: Vec3) -> Result<(), bumpmap_core::CoreError> {
    if !eye.is_finite() || (eye - scene.camera.target).try_normalize().is_none() {
        return Err(bumpmap_core::CoreError::EyeAtTarget { eye });
    }
    scene.camera.eye = eye;
    Ok(())
}

/// `v` rotated by `tilt` radians toward `axis` within the plane they span, its elevation above
/// the plane perpendicular to `axis` kept within ±[`MAX_TILT`]; `v` along `axis` is kept.
fn tilted(v: Vec3, axis: Vec3, tilt: f32) -> Vec3 {
    let side = axis.cross(v);
    if tilt == 0.0 || side.length_squared() < 1e-12 {
        return v;
    }
    let elevation = (v.normalize().dot(axis)).clamp(-1.0, 1.0).asin();
    let wanted = (elevation + tilt).clamp(-MAX_TILT, MAX_TILT);
    Quat::from_axis_angle(side.normalize(), -(wanted - elevation)) * v
}

/// `camera` turned `yaw` radians about its up direction and `pitch` radians toward it, round
/// the point looked at, at `distance_scale` times its distance (the near plane comes closer as
/// the eye does, the far plane goes out as it does, so the object stays between them).
///
/// ```
/// use bumpmap::motion::orbit_camera;
/// use bumpmap::{SceneKind, SceneSpec};
///
/// let camera = SceneSpec::new(SceneKind::Torus).build()?.camera;
/// let moved = orbit_camera(&camera, 1.0, 0.3, 2.0);
/// let d = |c: &bumpmap::Camera| (c.eye - c.target).length();
/// assert!((d(&moved) - 2.0 * d(&camera)).abs() < 1e-3);
/// assert_eq!(moved.target, camera.target);
/// # Ok::<(), bumpmap::CoreError>(())
/// ```
pub fn orbit_camera(camera: &Camera, yaw: f32, pitch: f32, distance_scale: f32) -> Camera {
    let up = camera.view_up().normalize_or(Vec3::Z);
    let offset = Quat::from_axis_angle(up, yaw) * (camera.eye - camera.target);
    let offset = tilted(offset, up, pitch) * distance_scale;
    Camera {
        eye: camera.target + offset,
        near: camera.near * distance_scale.min(1.0),
        far: camera.far * distance_scale.max(1.0),
        ..*camera
    }
}
