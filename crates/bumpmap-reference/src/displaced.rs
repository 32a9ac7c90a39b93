//! Heights as geometry, exactly: each object's surface carved by its heights,
//! `P′(u, v) = P(u, v) + depth · (h(s, t) − 1) · N(u, v)`, with h the heights' C¹ interpolant
//! clamped to [0, 1] (`bumpmap_math::interpolant`) and (s, t) = repeat ⊙ (u, v), and rays
//! traced to it.
//!
//! - A flat surface (wall, floor) is an affine map of texture space (s, t, h), so a ray stays
//!   a straight line there: it enters the slab through the polygon and walks the min–max levels
//!   of the heights to the interpolant's first crossing (`bumpmap_math::height_trace`, the walk
//!   the `height-exact` technique takes too).
//! - A curved surface (torus, sphere, patch) is micro-tessellated: a vertex at every texel
//!   corner on the carved surface, two triangles per texel, and a quadtree of boxes over them
//!   (its `tessellated` module).
//!
//! Either way a hit is shaded on the smooth carved surface at its (u, v) ([`displaced_normal`]).
//! The heights repeat over the plane beyond a flat surface's edges (a ray entering near an edge
//! at a grazing angle meets them there, as a texture unit's REPEAT reads them). What this
//! module does not do: loaded meshes (no analytic surface), or displacement outward.

use glam::{Mat3, Vec2, Vec3};

use bumpmap_core::scene::SceneObject;
use bumpmap_math::height_trace::{TexelRay, trace};
use bumpmap_math::interpolant::{HeightSample, sample};
use bumpmap_math::surface::{Surface, SurfacePoint};
use bumpmap_math::{HeightMips, Wrap};

use crate::error::ReferenceError;
mod tessellated;

use tessellated::Tessellation;

/// Where a ray met a carved surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplacedHit {
    /// The ray's parameter there (object space, the ray's own direction's units).
    pub t: f32,
    /// Texture coordinates (s, t) of the hit.
    pub st: Vec2,
    /// The height there, in [0, 1].
    pub height: f32,
}

/// One object's carved surface, ready for rays (object space).
#[derive(Debug)]
pub struct Displaced {
    surface: Surface,
    repeat: Vec2,
    depth: f32,
    heights: HeightMips,
    shape: Shape,
}

#[derive(Debug)]
enum Shape {
    /// The affine map `(s, t, h) ↦ origin + s·P_s + t·P_t + depth·(h − 1)·N` and its inverse.
    Flat { origin: Vec3, to_object: Mat3, to_texture: Mat3 },
    /// Triangles over texel corners with their boxes.
    Curved(Box<Tessellation>),
}

/// The carved-surface normal: `∂P′/∂u × ∂P′/∂v` with `P′ = P + d·N`, `∂P′/∂u = P_u + d_u·N +
/// d·N_u` (N's derivatives by central differences; zero on a plane, where this is Blinn's
/// perturbed normal without its approximation), oriented like N.
pub fn displaced_normal(surface: &Surface, u: f32, v: f32, d: f32, d_u: f32, d_v: f32) -> Vec3 {
    let p = surface.eval(u, v);
    let (n_u, n_v) = if d == 0.0 || matches!(surface, Surface::Wall { .. } | Surface::Floor { .. }) {
        (Vec3::ZERO, Vec3::ZERO)
    } else {
        const E: f32 = 1e-3;
        let n = |u: f32, v: f32| surface.eval(u, v).normal;
        ((n(u + E, v) - n(u - E, v)) / (2.0 * E), (n(u, v + E) - n(u, v - E)) / (2.0 * E))
    };
    let pu = p.dp_du + d_u * p.normal + d * n_u;
    let pv = p.dp_dv + d_v * p.normal + d * n_v;
    let n = pu.cross(pv);
    let n = if n.dot(p.normal) < 0.0 { -n } else { n };
    n.normalize_or(p.normal)
}

impl Displaced {
    /// The carved surface of `object` (number `index` in its scene), which needs an analytic
    /// surface and heights as geometry. A curved surface's tessellation holds about 48 bytes per
    /// texel it covers, and more than `tessellated::MAX_TEXELS` (16 Mi) is refused.
    pub fn new(object: &SceneObject, index: usize) -> Result<Self, ReferenceError> {
        let source = object.source.as_ref().ok_or(ReferenceError::NoSurface { object: index })?;
        let heights = object.material.heights.as_ref().ok_or(ReferenceError::NoDisplacement { object: index })?;
        let heights = match heights.minmax() {
            Some(_) => (**heights).clone(),
            None => {
                (**heights).clone().with_minmax().map_err(|error| ReferenceError::Heights { object: index, error })?
            }
        };
        let (surface, repeat, depth) = (source.surface.clone(), source.repeat, object.material.depth);
        let shape = match surface {
            Surface::Wall { .. } | Surface::Floor { .. } => {
                let p = surface.eval(0.0, 0.0);
                let to_object = Mat3::from_cols(p.dp_du / repeat.x, p.dp_dv / repeat.y, depth * p.normal);
                Shape::Flat { origin: p.position - depth * p.normal, to_object, to_texture: to_object.inverse() }
            }
            _ => {
                let (nx, ny) = tessellated::cells(repeat, &heights);
                let texels = nx as u64 * ny as u64;
                if texels > tessellated::MAX_TEXELS as u64 {
                    return Err(ReferenceError::Tessellation {
                        object: index,
                        texels,
                        bytes: tessellated::bytes_for(texels as usize),
                        max: tessellated::MAX_TEXELS,
                    });
                }
                Shape::Curved(Box::new(Tessellation::new(&surface, repeat, depth, &heights)))
            }
        };
        Ok(Self { surface, repeat, depth, heights, shape })
    }

    /// The heights this surface is carved by.
    pub fn heights(&self) -> &HeightMips {
        &self.heights
    }

    /// The surface point under texture coordinates `st`, (u, v) = st / repeat.
    pub fn base(&self, st: Vec2) -> (f32, f32, SurfacePoint) {
        let (u, v) = (st.x / self.repeat.x, st.y / self.repeat.y);
        (u, v, self.surface.eval(u, v))
    }

    /// The interpolant at texture coordinates `st` (one repeat = [0, 1]).
    fn height_at(&self, st: Vec2) -> HeightSample {
        let local = st - st.floor();
        sample(&self.heights.levels()[0], Wrap::Repeat, local.x, local.y)
    }

    /// The first hit of the ray `origin + t·dir` (object space) with the carved surface.
    pub fn trace(&self, origin: Vec3, dir: Vec3) -> Option<DisplacedHit> {
        match &self.shape {
            Shape::Flat { origin: o, to_texture, .. } => {
                let (p, d) = (*to_texture * (origin - *o), *to_texture * dir);
                // Into the slab through its top, from above, inside the polygon.
                if d.z >= 0.0 || p.z < 1.0 {
                    return None;
                }
                let t_top = (p.z - 1.0) / -d.z;
                let entry = p + t_top * d;
                let inside = |x: f32, r: f32| (0.0..=r.abs()).contains(&(x * r.signum()));
                if !inside(entry.x, self.repeat.x) || !inside(entry.y, self.repeat.y) {
                    return None;
                }
                let level0 = &self.heights.levels()[0];
                let (w, h) = (level0.width as f32, level0.height as f32);
                let ray = TexelRay {
                    origin: Vec3::new(entry.x * w, entry.y * h, 1.0),
                    dir: Vec3::new(d.x * w, d.y * h, d.z),
                };
                let minmax = self.heights.minmax().expect("made with min–max levels");
                let tau = trace(level0, minmax, &ray, f32::INFINITY)?;
                let q = entry + tau * d;
                Some(DisplacedHit { t: t_top + tau, st: Vec2::new(q.x, q.y), height: q.z })
            }
            Shape::Curved(mesh) => mesh.trace(origin, dir, f32::INFINITY),
        }
    }

    /// The carved surface's point at a hit, object space.
    pub fn position(&self, hit: &DisplacedHit) -> Vec3 {
        match &self.shape {
            Shape::Flat { origin, to_object, .. } => *origin + *to_object * Vec3::new(hit.st.x, hit.st.y, hit.height),
            Shape::Curved(_) => {
                let (_, _, p) = self.base(hit.st);
                p.position + self.depth * (hit.height - 1.0) * p.normal
            }
        }
    }

    /// The carved surface's unit normal at a hit, object space.
    pub fn normal(&self, hit: &DisplacedHit) -> Vec3 {
        let (u, v, _) = self.base(hit.st);
        let f = self.height_at(hit.st);
        let level0 = &self.heights.levels()[0];
        // Flat where the interpolant is clamped to the slab; ∂h/∂u = ∂h/∂x · width · repeat.x.
        let (d_u, d_v) = if (0.0..=1.0).contains(&f.value) {
            (
                self.depth * f.dx * level0.width as f32 * self.repeat.x,
                self.depth * f.dy * level0.height as f32 * self.repeat.y,
            )
        } else {
            (0.0, 0.0)
        };
        displaced_normal(&self.surface, u, v, self.depth * (hit.height - 1.0), d_u, d_v)
    }

    /// Whether the straight path from the hit toward `to_light` (object space: a vector to a
    /// point light, whose end is the light, or a direction) meets the carved surface first.
    pub fn shadowed(&self, hit: &DisplacedHit, to_light: Vec3, positional: bool) -> bool {
        match &self.shape {
            Shape::Flat { to_texture, .. } => {
                let d = *to_texture * to_light;
                if d.z <= 0.0 {
                    // Toward or along the floor: the lighting model's own terms darken it.
                    return false;
                }
                let level0 = &self.heights.levels()[0];
                let (w, h) = (level0.width as f32, level0.height as f32);
                let ray = TexelRay {
                    origin: Vec3::new(hit.st.x * w, hit.st.y * h, (hit.height + LIFT).min(1.0)),
                    dir: Vec3::new(d.x * w, d.y * h, d.z),
                };
                let limit = if positional { 1.0 } else { f32::INFINITY };
                let minmax = self.heights.minmax().expect("made with min–max levels");
                trace(level0, minmax, &ray, limit).is_some()
            }
            Shape::Curved(mesh) => {
                let from = self.position(hit) + self.normal(hit) * (LIFT * self.depth);
                let limit = if positional { 1.0 } else { f32::INFINITY };
                mesh.trace(from, to_light, limit).is_some()
            }
        }
    }
}

/// How far above the surface a shadow ray starts, in heights (and, on a curved surface, the
/// same fraction of the depth along the normal): past the rounding of the hit it starts from.
const LIFT: f32 = 1e-4;

#[cfg(test)]
mod tests {
    use super::*;
    use bumpmap_core::scenes::{SceneKind, SceneParams, build};

    fn displaced(kind: SceneKind, depth: f32) -> Displaced {
        let params = SceneParams { displacement: true, depth: Some(depth), ..Default::default() };
        let scene = build(&kind, &params).unwrap();
        Displaced::new(&scene.objects[0], 0).unwrap()
    }

    #[test]
    fn a_ray_straight_down_the_wall_meets_the_height_under_it() {
        let wall = displaced(SceneKind::Wall, 0.05);
        for st in [Vec2::new(0.3, 0.7), Vec2::new(1.1, 0.2), Vec2::new(1.9, 1.9)] {
            let (_, _, p) = wall.base(st);
            let hit = wall.trace(p.position + Vec3::Z * 3.0, -Vec3::Z).unwrap();
            assert!((hit.st - st).length() < 1e-4, "{} vs {st}", hit.st);
            let want = wall.height_at(st).value.clamp(0.0, 1.0);
            assert!((hit.height - want).abs() < 1e-4, "{} vs {want}", hit.height);
            // The point is that far below the wall.
            let q = wall.position(&hit);
            assert!((q.z - 0.05 * (want - 1.0)).abs() < 1e-5, "{q}");
        }
        // Beside the wall: nothing.
        assert!(wall.trace(Vec3::new(5.0, 0.0, 3.0), -Vec3::Z).is_none());
    }

    #[test]
    fn the_torus_tessellation_meets_a_ray_where_the_flat_formula_says() {
        // Straight down onto the torus's top (v = 1/4, where N = +z): the hit lies depth·(h − 1)
        // below the base surface, h the interpolant there within the tessellation's error.
        let torus = displaced(SceneKind::Torus, 0.03);
        let (_, _, p) = torus.base(Vec2::new(0.3 * 6.0, 0.25 * 2.0));
        let hit = torus.trace(p.position + Vec3::Z * 2.0, -Vec3::Z).unwrap();
        let want = torus.height_at(hit.st).value.clamp(0.0, 1.0);
        let q = torus.position(&hit);
        assert!((q.z - (p.position.z + 0.03 * (want - 1.0))).abs() < 0.03 * 0.1, "{q} vs h {want}");
        let n = torus.normal(&hit);
        assert!((n.length() - 1.0).abs() < 1e-5 && n.z > 0.5, "{n}");
    }

    #[test]
    fn the_carved_normal_is_blinns_on_a_plane_and_n_where_flat() {
        let wall = Surface::Wall { width: 4.0, height: 4.0 };
        let p = wall.eval(0.3, 0.4);
        let want = bumpmap_math::blinn::perturbed_normal(&p, 0.2, -0.1);
        assert!((displaced_normal(&wall, 0.3, 0.4, -0.02, 0.2, -0.1) - want).length() < 1e-6);
        let sphere = Surface::Sphere { radius: 1.5 };
        let n = displaced_normal(&sphere, 0.3, 0.4, -0.02, 0.0, 0.0);
        assert!((n - sphere.eval(0.3, 0.4).normal).length() < 1e-3, "{n}");
    }
}
