//! The reference image of heights as geometry: for each sample, the camera's ray through it
//! traced to every object's carved surface (`crate::displaced`), the nearest hit shaded there
//! by the same lighting as the base-surface reference, with shadow rays toward each light when
//! asked, and the mean of a pixel's samples.
//!
//! Visibility here is the rays' own, not the rasterized base mesh's: the carved surface lies
//! inside the base one, so silhouettes shrink where bumps are cut by them.

use glam::{Mat4, Vec2, Vec3};

use bumpmap_core::Scene;
use bumpmap_core::technique::reference::ReferenceOptions;
use bumpmap_math::lighting::{Light, ObjectLighting, TangentFrame};

use super::{LinearImage, Surfel, assemble, bilinear_repeat, light, render_tiles};
use crate::displaced::{Displaced, DisplacedHit};
use crate::error::ReferenceError;
use crate::visibility::sample_offset;

/// The world-space ray from the eye through the image point (`x`, `y`) (pixels, row 0 at the
/// top) of a `width`×`height` image seen through `clip_from_world`: the eye and a direction
/// reaching the far plane at `t = 1`.
pub fn camera_ray(clip_from_world: &Mat4, eye: Vec3, (width, height): (usize, usize), x: f32, y: f32) -> (Vec3, Vec3) {
    let ndc = Vec2::new(2.0 * x / width as f32 - 1.0, 1.0 - 2.0 * y / height as f32);
    let far = clip_from_world.inverse().project_point3(ndc.extend(1.0));
    (eye, far - eye)
}

/// Every object's carved surface, with the lighting in its space.
pub struct DisplacedScene<'a> {
    scene: &'a Scene,
    objects: Vec<(Displaced, Vec<ObjectLighting>, Mat4)>,
}

/// What a camera ray met: the object, and where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneHit {
    /// Index into the scene's objects.
    pub object: usize,
    /// The hit on its carved surface.
    pub hit: DisplacedHit,
}

impl<'a> DisplacedScene<'a> {
    /// The carved surfaces of `scene`'s objects (each needs an analytic surface and heights).
    pub fn new(scene: &'a Scene) -> Result<Self, ReferenceError> {
        let objects = scene
            .objects
            .iter()
            .enumerate()
            .map(|(i, object)| {
                let displaced = Displaced::new(object, i)?;
                let lighting = scene
                    .lights
                    .iter()
                    .map(|l| ObjectLighting::new(object.world_from_object, l.light, scene.viewer()))
                    .collect();
                Ok((displaced, lighting, object.world_from_object.inverse()))
            })
            .collect::<Result<_, ReferenceError>>()?;
        Ok(Self { scene, objects })
    }

    /// Object `i`'s carved surface.
    pub fn object(&self, i: usize) -> &Displaced {
        &self.objects[i].0
    }

    /// The nearest hit of the world-space ray `origin + t·dir`.
    pub fn trace(&self, origin: Vec3, dir: Vec3) -> Option<SceneHit> {
        let mut best: Option<SceneHit> = None;
        for (i, (displaced, _, object_from_world)) in self.objects.iter().enumerate() {
            let (o, d) = (object_from_world.transform_point3(origin), object_from_world.transform_vector3(dir));
            if let Some(hit) = displaced.trace(o, d)
                && hit.t > 0.0
                && best.is_none_or(|b| hit.t < b.hit.t)
            {
                best = Some(SceneHit { object: i, hit });
            }
        }
        best
    }

    /// Whether light `light` reaches `hit` past the carved surface it lies on.
    pub fn lit(&self, hit: &SceneHit, light: usize) -> bool {
        let (displaced, lighting, _) = &self.objects[hit.object];
        let position = displaced.position(&hit.hit);
        let positional = matches!(self.scene.lights[light].light, Light::Positional(_));
        !displaced.shadowed(&hit.hit, lighting[light].to_light(position), positional)
    }

    /// The colour at `hit`, lit as the base-surface reference lights, with shadow rays when
    /// `options.shadow_rays`.
    pub fn shade(&self, hit: &SceneHit, options: &ReferenceOptions) -> Vec3 {
        let (displaced, lighting, _) = &self.objects[hit.object];
        let object = &self.scene.objects[hit.object];
        let (_, _, base) = displaced.base(hit.hit.st);
        let (t, b, n) = base.frame();
        let frame = TangentFrame { t, b, n };
        let local = hit.hit.st - hit.hit.st.floor();
        let surfel = Surfel {
            position: displaced.position(&hit.hit),
            frame,
            normal: frame.tangent_from_object(displaced.normal(&hit.hit)),
            decal: object.material.decal.as_deref().map_or(Vec3::ONE, |d| bilinear_repeat(d, local)),
        };
        light(self.scene, object, lighting, &surfel, options, |i, _| !options.shadow_rays || self.lit(hit, i))
    }
}

/// The displaced reference image: `options.samples_per_pixel` rays a pixel, progress per tile.
pub fn render(
    scene: &Scene,
    width: usize,
    height: usize,
    options: &ReferenceOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<LinearImage, ReferenceError> {
    let displaced = DisplacedScene::new(scene)?;
    let clip_from_world = scene.camera.clip_from_world(width as f32 / height as f32);
    let spp = options.samples_per_pixel;
    let tiles = render_tiles(width, height, progress, |_, (x0, y0, tw, th)| {
        let mut pixels = Vec::with_capacity(tw * th);
        for y in y0..y0 + th {
            for x in x0..x0 + tw {
                let mut sum = Vec3::ZERO;
                for k in 0..spp {
                    let q = Vec2::new(x as f32, y as f32) + sample_offset(k, spp, x, y, options.seed);
                    let (origin, dir) = camera_ray(&clip_from_world, scene.camera.eye, (width, height), q.x, q.y);
                    if let Some(hit) = displaced.trace(origin, dir) {
                        sum += displaced.shade(&hit, options);
                    }
                }
                pixels.push(sum / spp as f32);
            }
        }
        pixels
    });
    Ok(assemble(&tiles, width, height))
}
