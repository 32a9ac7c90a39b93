//! Ground truth for ambient occlusion and bent normals: rays cast from a texel's centre on the
//! carved surface over the cosine-weighted hemisphere of the base normal, each traced to the
//! heights' interpolant (`bumpmap_math::height_trace`, the surface the displaced reference
//! draws). Occlusion is the fraction that leaves the slab unblocked; the bent normal is the mean
//! of their directions. The rays are stratified (a `side`×`side` grid over the unit square, one
//! jittered ray per cell, mapped to the hemisphere by Malley's method), so 256 of them (side 16)
//! have far less noise than 256 independent ones.
//!
//! What this module does not do: use the horizon map (`bumpmap_math::horizon` is what it
//! measures), or cast rays from anywhere but texel centres.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use bumpmap_math::HeightMips;
use bumpmap_math::height_trace::{TexelRay, trace};

/// How far above the surface an occlusion ray starts, in heights.
const LIFT: f32 = 1e-4;

/// A texel's ground truth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexelOcclusion {
    /// The cosine-weighted fraction of the hemisphere open to the sky.
    pub ambient: f32,
    /// The mean open direction (tangent frame: x along +s, y along +t, z the base normal),
    /// unit; the base normal where no ray is open.
    pub bent_normal: Vec3,
}

/// The ground truth at texel (`x`, `y`) of `heights` (level 0, wrapped around) drawn `depth`
/// texels deep per unit of height, from `side`² rays.
pub fn texel_occlusion(heights: &HeightMips, depth: f32, x: usize, y: usize, side: usize) -> TexelOcclusion {
    let level0 = &heights.levels()[0];
    let minmax = heights.minmax().expect("HeightMips made from heights carry min–max levels");
    let h0 = level0.texels[y * level0.width + x];
    let origin = Vec3::new(x as f32 + 0.5, y as f32 + 0.5, (h0 + LIFT).min(1.0));
    let (mut open, mut sum) = (0usize, Vec3::ZERO);
    for j in 0..side {
        for i in 0..side {
            let jitter = Vec2::new(hash01(x, y, i, j, 0), hash01(x, y, i, j, 1));
            let u = (Vec2::new(i as f32, j as f32) + jitter) / side as f32;
            // Malley: a uniform point on the disc lifted to the hemisphere is cosine-weighted.
            let (r, phi) = (u.x.sqrt(), std::f32::consts::TAU * u.y);
            let dir = Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt());
            let ray = TexelRay { origin, dir: Vec3::new(dir.x, dir.y, dir.z / depth) };
            if trace(level0, minmax, &ray, f32::INFINITY).is_none() {
                open += 1;
                sum += dir;
            }
        }
    }
    TexelOcclusion { ambient: open as f32 / (side * side) as f32, bent_normal: sum.normalize_or(Vec3::Z) }
}

/// [`texel_occlusion`] at every `stride`-th texel along each axis (row-major, rows of
/// `ceil(width / stride)`), in parallel.
pub fn occlusion_map(heights: &HeightMips, depth: f32, side: usize, stride: usize) -> Vec<TexelOcclusion> {
    let stride = stride.max(1);
    let (w, h) = (heights.width(), heights.height());
    let points: Vec<(usize, usize)> =
        (0..h).step_by(stride).flat_map(|y| (0..w).step_by(stride).map(move |x| (x, y))).collect();
    points.par_iter().map(|&(x, y)| texel_occlusion(heights, depth, x, y, side)).collect()
}

/// A number in [0, 1) from a texel, a cell and a channel: the same rays every run.
fn hash01(x: usize, y: usize, i: usize, j: usize, c: u32) -> f32 {
    use bumpmap_math::hash::{hash32, unit};
    unit(hash32(&[x as u32, y as u32, i as u32, j as u32, c]))
}
