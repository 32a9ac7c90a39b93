//! A curved surface carved by its heights, micro-tessellated: a vertex at every texel corner
//! of the repeated texture (so at least one per texel), each on the carved surface
//! `P + depth · (h − 1) · N`, two triangles per texel, and a quadtree of bounding boxes over
//! them (level 0 a box per texel, each level above the union of up to four below) that a ray
//! descends nearest box first.
//!
//! What this module does not do: shade (the hit's (u, v) goes back to the smooth surface,
//! `crate::displaced`), or build anything finer than a texel: between texel corners the
//! triangles are flat, where the interpolant bends.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use bumpmap_math::interpolant::sample;
use bumpmap_math::surface::Surface;
use bumpmap_math::{HeightMips, Wrap};

use super::DisplacedHit;

/// Texels a tessellation may have (about 48 bytes each): beyond it the reference is refused
/// with the memory it would need.
pub const MAX_TEXELS: usize = 16 << 20;

/// Bytes a tessellation of `texels` texels holds: a vertex (position, height) and a box per
/// texel, and the boxes above (a third more).
pub fn bytes_for(texels: usize) -> u64 {
    texels as u64 * (16 + 24 * 4 / 3)
}

const _: () = assert!(MAX_TEXELS < u32::MAX as usize, "cell indices fit the quadtree's arithmetic");

/// One level of boxes.
#[derive(Debug)]
struct BoxLevel {
    width: usize,
    height: usize,
    boxes: Vec<[Vec3; 2]>,
}

/// The triangles and their boxes.
#[derive(Debug)]
pub struct Tessellation {
    /// Texels (cells) along u and v.
    nx: usize,
    ny: usize,
    repeat: Vec2,
    /// `(nx + 1)·(ny + 1)` vertices, row-major along u.
    positions: Vec<Vec3>,
    /// Their heights.
    heights: Vec<f32>,
    /// Level 0: a box per cell.
    levels: Vec<BoxLevel>,
}

/// The cells of `surface` with `heights` repeated `repeat` times: one per texel.
pub fn cells(repeat: Vec2, heights: &HeightMips) -> (usize, usize) {
    let cells = |r: f32, n: usize| ((r.abs() * n as f32).ceil() as usize).max(1);
    (cells(repeat.x, heights.width()), cells(repeat.y, heights.height()))
}

impl Tessellation {
    /// The carved `surface` (texture repeated `repeat` times, heights `depth` deep).
    pub fn new(surface: &Surface, repeat: Vec2, depth: f32, heights: &HeightMips) -> Self {
        let (nx, ny) = cells(repeat, heights);
        let level0 = &heights.levels()[0];
        let vertices: Vec<(Vec3, f32)> = (0..(nx + 1) * (ny + 1))
            .into_par_iter()
            .map(|k| {
                let (i, j) = (k % (nx + 1), k / (nx + 1));
                let (u, v) = (i as f32 / nx as f32, j as f32 / ny as f32);
                let (s, t) = (repeat.x * u, repeat.y * v);
                let h = sample(level0, Wrap::Repeat, s - s.floor(), t - t.floor()).value.clamp(0.0, 1.0);
                let p = surface.eval(u, v);
                (p.position + depth * (h - 1.0) * p.normal, h)
            })
            .collect();
        let (positions, heights): (Vec<Vec3>, Vec<f32>) = vertices.into_iter().unzip();
        let corner = |i: usize, j: usize| positions[j * (nx + 1) + i];
        let boxes = (0..nx * ny)
            .into_par_iter()
            .map(|c| {
                let (i, j) = (c % nx, c / nx);
                let q = [corner(i, j), corner(i + 1, j), corner(i, j + 1), corner(i + 1, j + 1)];
                [q[0].min(q[1]).min(q[2]).min(q[3]), q[0].max(q[1]).max(q[2]).max(q[3])]
            })
            .collect();
        let mut levels = vec![BoxLevel { width: nx, height: ny, boxes }];
        while let Some(last) = levels.last().filter(|l| (l.width, l.height) != (1, 1)) {
            let (w, h) = (last.width.div_ceil(2), last.height.div_ceil(2));
            let boxes = (0..w * h)
                .map(|c| {
                    let (i, j) = (c % w, c / w);
                    let mut b = [Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)];
                    for (ci, cj) in [(2 * i, 2 * j), (2 * i + 1, 2 * j), (2 * i, 2 * j + 1), (2 * i + 1, 2 * j + 1)] {
                        if ci < last.width && cj < last.height {
                            let child = last.boxes[cj * last.width + ci];
                            b = [b[0].min(child[0]), b[1].max(child[1])];
                        }
                    }
                    b
                })
                .collect();
            levels.push(BoxLevel { width: w, height: h, boxes });
        }
        Self { nx, ny, repeat, positions, heights, levels }
    }

    /// The nearest hit of `origin + t·dir` with `t` in (0, `t_max`].
    pub fn trace(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<DisplacedHit> {
        let inv = dir.recip();
        let mut best: Option<(f32, usize, usize, f32, f32, bool)> = None;
        let mut limit = t_max;
        let top = self.levels.len() - 1;
        let mut stack: Vec<(usize, usize, usize)> = Vec::with_capacity(4 * self.levels.len());
        stack.push((top, 0, 0));
        while let Some((k, i, j)) = stack.pop() {
            let level = &self.levels[k];
            let b = level.boxes[j * level.width + i];
            if slab(b, origin, inv, limit).is_none() {
                continue;
            }
            if k == 0 {
                let v = |di: usize, dj: usize| self.positions[(j + dj) * (self.nx + 1) + i + di];
                let (a, b, c, d) = (v(0, 0), v(1, 0), v(1, 1), v(0, 1));
                for (tri, second) in [([a, b, c], false), ([a, c, d], true)] {
                    if let Some((t, b1, b2)) = triangle(origin, dir, tri)
                        && t > 0.0
                        && t <= limit
                    {
                        limit = t;
                        best = Some((t, i, j, b1, b2, second));
                    }
                }
                continue;
            }
            // Children, nearest last (popped first).
            let below = &self.levels[k - 1];
            let mut children: Vec<(f32, usize, usize)> =
                [(2 * i, 2 * j), (2 * i + 1, 2 * j), (2 * i, 2 * j + 1), (2 * i + 1, 2 * j + 1)]
                    .into_iter()
                    .filter(|&(ci, cj)| ci < below.width && cj < below.height)
                    .filter_map(|(ci, cj)| {
                        slab(below.boxes[cj * below.width + ci], origin, inv, limit).map(|t| (t, ci, cj))
                    })
                    .collect();
            children.sort_by(|x, y| y.0.total_cmp(&x.0));
            stack.extend(children.into_iter().map(|(_, ci, cj)| (k - 1, ci, cj)));
        }
        let (t, i, j, b1, b2, second) = best?;
        // Corner weights of the triangle (a, b, c) or (a, c, d) in cell (i, j).
        let (corners, w) = if second {
            ([(0, 0), (1, 1), (0, 1)], [1.0 - b1 - b2, b1, b2])
        } else {
            ([(0, 0), (1, 0), (1, 1)], [1.0 - b1 - b2, b1, b2])
        };
        let (mut uv, mut height) = (Vec2::ZERO, 0.0);
        for ((di, dj), w) in corners.into_iter().zip(w) {
            let (ci, cj) = (i + di, j + dj);
            uv += w * Vec2::new(ci as f32 / self.nx as f32, cj as f32 / self.ny as f32);
            height += w * self.heights[cj * (self.nx + 1) + ci];
        }
        Some(DisplacedHit { t, st: self.repeat * uv, height })
    }
}

/// Where the ray enters the box within (0, `limit`], if it does.
#[inline]
fn slab(b: [Vec3; 2], origin: Vec3, inv: Vec3, limit: f32) -> Option<f32> {
    let t1 = (b[0] - origin) * inv;
    let t2 = (b[1] - origin) * inv;
    // NaN (a ray along a face) is ignored by f32::min and max.
    let near = t1.min(t2);
    let far = t1.max(t2);
    let enter = near.x.max(near.y).max(near.z).max(0.0);
    let exit = far.x.min(far.y).min(far.z).min(limit);
    // A hair of slack so that a ray grazing a flat box (a plane's cell) still enters it.
    (enter <= exit * (1.0 + 1e-6) + 1e-9).then_some(enter)
}

/// Möller–Trumbore: the ray parameter and the barycentric weights of vertices 1 and 2.
#[inline]
fn triangle(origin: Vec3, dir: Vec3, [a, b, c]: [Vec3; 3]) -> Option<(f32, f32, f32)> {
    let (e1, e2) = (b - a, c - a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-20 {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - a;
    let b1 = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&b1) {
        return None;
    }
    let q = s.cross(e1);
    let b2 = dir.dot(q) * inv;
    if b2 < 0.0 || b1 + b2 > 1.0 {
        return None;
    }
    Some((e2.dot(q) * inv, b1, b2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quadtree_finds_the_nearest_of_all_triangles() {
        // Rays from outside at a sphere carved by noise: the descent's hit is the nearest over
        // every triangle tested one by one.
        let heights = HeightMips::from_field(&bumpmap_math::HeightPreset::Noise(5).render(16, 16)).unwrap();
        let sphere = Surface::Sphere { radius: 1.5 };
        let mesh = Tessellation::new(&sphere, Vec2::new(2.0, 1.0), 0.1, &heights);
        for k in 0..60 {
            let a = k as f32 * 0.7;
            let origin = Vec3::new(4.0 * a.cos(), 4.0 * a.sin(), (k as f32 * 0.37).sin() * 2.0);
            let dir = (Vec3::new(0.1 * (k as f32).sin(), 0.2, 0.1) - origin).normalize();
            let got = mesh.trace(origin, dir, f32::INFINITY).map(|h| h.t);
            let mut want: Option<f32> = None;
            for j in 0..mesh.ny {
                for i in 0..mesh.nx {
                    let v = |di: usize, dj: usize| mesh.positions[(j + dj) * (mesh.nx + 1) + i + di];
                    for tri in [[v(0, 0), v(1, 0), v(1, 1)], [v(0, 0), v(1, 1), v(0, 1)]] {
                        if let Some((t, ..)) = triangle(origin, dir, tri).filter(|h| h.0 > 0.0) {
                            want = Some(want.map_or(t, |w: f32| w.min(t)));
                        }
                    }
                }
            }
            assert_eq!(got, want, "ray {k}");
        }
        assert_eq!(cells(Vec2::new(2.0, 1.0), &heights), (32, 16));
    }
}
