//! Bumps that shadow each other and hold ambient light, measured: the brick wall and the
//! dimples seen head-on, lit 45°, 70° and 80° from the normal, every way of shadowing the bumps
//! against the displaced reference's shadow rays, and the horizon map's ambient occlusion and
//! bent normals against 256 occlusion rays a texel.
//!
//! The shadow masks are compared per pixel over the pixels whose exact surface faces the light
//! (where shadowing decides anything), each method at its own hit (`parallax::hits`): no
//! shadow; Kilgard's Eq. 12, which darkens only where the *base* surface turns from the light
//! (on a flat wall: nowhere); the horizon map at the entry point (`horizon`); POM's hard march
//! toward the light; POM's hit shadowed by the horizon map; the exact hit shadowed by the
//! horizon map (the map's own error). Head-on, a pixel's entry point and its exact hit are the
//! same texture point up to the perspective's slant (15° at the image's edges, which moves the
//! entry point up to a texel from the hit at the foot of a 4-texel brick), so the flat horizon
//! technique carries some hit error too. FLIP compares each technique's image with the displaced
//! reference drawn with its shadow rays.
//!
//! What this module does not do: draw the techniques (the backends do) or write files.

use bumpmap::{Prepared, Renderer, TechniqueName, TechniqueOptions};
use bumpmap_core::parallax::{Parallax, ParallaxMethod, ParallaxOptions, ParallaxShadow};
use bumpmap_reference::ReferenceOptions;
use bumpmap_reference::occlusion::occlusion_map;

use super::metrics;
use super::parallax::{SIZE, SPP, hits, pixel_rays, wall};
use crate::error::CompareError;

/// The lights' angles from the wall's normal, in degrees.
pub const LIGHTS: [f32; 3] = [45.0, 70.0, 80.0];
/// The height fields, 256² each.
pub const FIELDS: [&str; 2] = ["bricks", "dimples"];
/// Occlusion rays a texel, and every how many texels along each axis they are cast.
pub const OCCLUSION_RAYS: usize = 256;
const OCCLUSION_STRIDE: usize = 4;

/// A way of shadowing the bumps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadowMethod {
    /// None.
    NoShadow,
    /// Kilgard's Eq. 12: dark only where the base surface turns from the light.
    Eq12,
    /// The horizon map at the entry point (`--technique horizon`).
    Horizon,
    /// POM's hit and a hard march toward the light (`pom --parallax-shadow hard`).
    PomMarch,
    /// POM's hit and the horizon map there (`pom --parallax-shadow horizon`).
    PomHorizon,
    /// The exact hit and the horizon map there (`height-exact --parallax-shadow horizon`): the
    /// horizon map's own error, without a march's.
    ExactHorizon,
}

impl ShadowMethod {
    /// Every method, in the table's order.
    pub const ALL: [ShadowMethod; 6] =
        [Self::NoShadow, Self::Eq12, Self::Horizon, Self::PomMarch, Self::PomHorizon, Self::ExactHorizon];

    /// Its name in the table, the plots and `results.json`.
    pub fn name(self) -> &'static str {
        match self {
            ShadowMethod::NoShadow => "no shadow",
            ShadowMethod::Eq12 => "Eq. 12",
            ShadowMethod::Horizon => "horizon",
            ShadowMethod::PomMarch => "pom + march",
            ShadowMethod::PomHorizon => "pom + horizon",
            ShadowMethod::ExactHorizon => "exact hit + horizon",
        }
    }

    /// The technique and shadow that draw it.
    fn drawn_by(self) -> (TechniqueName, ParallaxShadow) {
        match self {
            ShadowMethod::NoShadow | ShadowMethod::Eq12 => (TechniqueName::SinglePass, ParallaxShadow::Off),
            ShadowMethod::Horizon => (TechniqueName::Horizon, ParallaxShadow::Horizon),
            ShadowMethod::PomMarch => (TechniqueName::Pom, ParallaxShadow::Hard),
            ShadowMethod::PomHorizon => (TechniqueName::Pom, ParallaxShadow::Horizon),
            ShadowMethod::ExactHorizon => (TechniqueName::HeightExact, ParallaxShadow::Horizon),
        }
    }

    /// The march and shadow its mask is made with (`None`: the entry point, lit).
    fn parallax(self) -> Option<Parallax> {
        let method = match self {
            ShadowMethod::NoShadow | ShadowMethod::Eq12 => return None,
            ShadowMethod::Horizon => ParallaxMethod::Flat,
            ShadowMethod::PomMarch | ShadowMethod::PomHorizon => ParallaxMethod::Occlusion,
            ShadowMethod::ExactHorizon => ParallaxMethod::Exact,
        };
        Some(Parallax { method, options: ParallaxOptions { shadow: self.drawn_by().1, ..Default::default() } })
    }
}

/// One method on one field under one light.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowRow {
    /// `bricks` or `dimples`.
    pub field: &'static str,
    /// The light's degrees from the normal.
    pub light: f32,
    /// The method.
    pub method: ShadowMethod,
    /// Share of the pixels facing the light whose mask agrees with the shadow rays'.
    pub agreement: f64,
    /// Mean FLIP of its image against the displaced reference with shadow rays. Eq. 12 is the
    /// single pass's own self-shadowing, so its image is "no shadow"'s.
    pub flip: f64,
}

/// The horizon map's occlusion on one field.
#[derive(Clone, Debug, PartialEq)]
pub struct OcclusionRow {
    /// `bricks` or `dimples`.
    pub field: &'static str,
    /// Mean absolute error of ambient occlusion against the rays.
    pub ao_error: f64,
    /// The rays' mean occlusion (how much there is to get right).
    pub ao_mean: f64,
    /// Mean angle between the bent normals and the rays' mean open direction, degrees.
    pub bent_degrees: f64,
    /// Texels measured.
    pub texels: usize,
}

/// The whole study.
pub struct ShadowStudy {
    /// The wall's depth per unit of height, in texels.
    pub depth_texels: f32,
    /// Every field, light and method.
    pub rows: Vec<ShadowRow>,
    /// Ambient occlusion and bent normals per field.
    pub occlusion: Vec<OcclusionRow>,
}

impl ShadowStudy {
    /// The row of `method` on `field` under `light`.
    pub fn row(&self, field: &str, light: f32, method: ShadowMethod) -> Option<&ShadowRow> {
        self.rows.iter().find(|r| r.field == field && r.light == light && r.method == method)
    }
}

/// The study: every field, light and method, then occlusion per field.
pub fn shadow_study(backend: &mut Renderer) -> Result<ShadowStudy, CompareError> {
    let (mut rows, mut occlusion) = (Vec::new(), Vec::new());
    let mut depth_texels = 0.0;
    for field in FIELDS {
        for light in LIGHTS {
            let spec = wall(field, 0.0, light);
            let shadowed = TechniqueOptions {
                parallax: ParallaxOptions { shadow: ParallaxShadow::Hard, ..Default::default() },
                ..Default::default()
            };
            let reference = Prepared::new(&spec, TechniqueName::ReferenceDisplaced, &shadowed)?;
            let scene = &reference.scene;
            let object = &scene.objects[0];
            let heights = object.material.heights.clone().expect("the displaced reference carries heights");
            let texel = object.texel_side((heights.width(), heights.height())).expect("the wall has area");
            depth_texels = object.material.depth / texel;
            let ref_options =
                ReferenceOptions { samples_per_pixel: SPP, displaced: true, shadow_rays: true, ..Default::default() };
            let image = bumpmap_reference::render(scene, SIZE, SIZE, &ref_options, &|_, _| {})?;
            let ref_rgb = metrics::reference_rgb8(&image);
            let pixels = pixel_rays(scene)?;
            for method in ShadowMethod::ALL {
                let agreement = match method {
                    // Eq. 12 darkens where the base normal turns from the light: L·N ≤ 0 in the
                    // flat wall's tangent frame.
                    ShadowMethod::Eq12 => {
                        let facing: Vec<_> = pixels.iter().filter(|p| p.faces_light).collect();
                        let agree = facing.iter().filter(|p| (p.rays.to_light.z > 0.0) == p.lit).count();
                        agree as f64 / facing.len().max(1) as f64
                    }
                    _ => {
                        hits(method.parallax(), &pixels, &heights, object.material.depth)
                            .map_err(bumpmap_core::CoreError::from)?
                            .2
                    }
                };
                let (technique, shadow) = method.drawn_by();
                let options = TechniqueOptions {
                    parallax: ParallaxOptions { shadow, ..Default::default() },
                    ..Default::default()
                };
                let prepared = Prepared::new(&spec, technique, &options)?;
                let drawn = backend.draw(&prepared, SIZE, SIZE)?;
                let (scores, _) = metrics::score(&image, &ref_rgb, &drawn);
                rows.push(ShadowRow { field, light, method, agreement, flip: scores.flip_mean });
            }
            if light == LIGHTS[0] {
                let horizons = heights.horizons().map_err(bumpmap_core::CoreError::from)?;
                let truth = occlusion_map(&heights, depth_texels, OCCLUSION_RAYS.isqrt(), OCCLUSION_STRIDE);
                let ao = horizons.ambient_occlusion(depth_texels);
                let bent = horizons.bent_normals(depth_texels);
                let w = heights.width();
                let texels: Vec<usize> = (0..heights.height())
                    .step_by(OCCLUSION_STRIDE)
                    .flat_map(|y| (0..w).step_by(OCCLUSION_STRIDE).map(move |x| y * w + x))
                    .collect();
                let n = texels.len().max(1) as f64;
                let pairs = || truth.iter().zip(&texels);
                occlusion.push(OcclusionRow {
                    field,
                    ao_error: pairs().map(|(t, &i)| (ao[i] - t.ambient).abs() as f64).sum::<f64>() / n,
                    ao_mean: truth.iter().map(|t| t.ambient as f64).sum::<f64>() / n,
                    bent_degrees: pairs()
                        .map(|(t, &i)| bent[i].dot(t.bent_normal).clamp(-1.0, 1.0).acos().to_degrees() as f64)
                        .sum::<f64>()
                        / n,
                    texels: texels.len(),
                });
            }
        }
    }
    Ok(ShadowStudy { depth_texels, rows, occlusion })
}
