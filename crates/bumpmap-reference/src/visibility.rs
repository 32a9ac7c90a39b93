//! Which triangle each sample of a pixel sees: sample positions, triangles in screen space, and
//! a depth test per sample, one tile of pixels at a time.
//!
//! Samples are a 2D low-discrepancy sequence (Roberts' R2) of `K` points in the pixel, shifted
//! per pixel by a hash (Cranley–Patterson rotation): stratified for any K, different in every
//! pixel, the same from run to run; a single sample sits at the pixel's centre. Coverage is the edge-function test at the sample itself and
//! depth is GL's `z/w` with `GL_LESS`; attributes come back as perspective-correct barycentric
//! weights. Triangles with a vertex at or behind the eye plane are skipped (the built-in scenes
//! have none). What this module does not do: shade, filter, or reproduce the backends' fixed-point
//! rasterization rules (it is independent of them).

use glam::{Mat4, Vec2, Vec3};

/// Pixels per tile side: the unit of parallel work and of the progress callback.
pub const TILE: usize = 16;

/// Offset in [0, 1)² of sample `k` of `spp` of pixel (x, y): the pixel's centre for a single
/// sample (where a rasterizer samples), else the sequence below, rotated per pixel by a hash of
/// the pixel and `seed` (seed 0 is the pattern the reference has always used).
#[inline]
pub fn sample_offset(k: usize, spp: usize, x: usize, y: usize, seed: u32) -> Vec2 {
    if spp == 1 {
        return Vec2::splat(0.5);
    }
    // R2: the plastic number's powers; a 2D sequence with good stratification for any K.
    const A1: f64 = 0.754_877_666_246_692_8;
    const A2: f64 = 0.569_840_290_998_053_3;
    let h = hash(x as u32, y as u32, seed);
    let (r1, r2) = ((h & 0xffff) as f64 / 65536.0, (h >> 16) as f64 / 65536.0);
    let fx = (0.5 + A1 * k as f64 + r1).fract();
    let fy = (0.5 + A2 * k as f64 + r2).fract();
    Vec2::new(fx as f32, fy as f32)
}

/// A 32-bit integer hash of a pixel and a seed.
fn hash(x: u32, y: u32, seed: u32) -> u32 {
    use bumpmap_math::hash::hash32;
    if seed == 0 { hash32(&[x, y]) } else { hash32(&[x, y, seed]) }
}

/// One triangle in screen space: pixel coordinates with row 0 at the top, `z/w`, `1/w`.
#[derive(Clone, Copy, Debug)]
pub struct ScreenTriangle {
    /// Screen positions in pixels.
    pub xy: [Vec2; 3],
    /// Normalized device depth `z/w` of each vertex.
    pub z: [f32; 3],
    /// `1/w` of each vertex, for perspective-correct weights.
    pub inv_w: [f32; 3],
    /// Which object it belongs to.
    pub object: u32,
    /// The vertex indices into the object's mesh.
    pub vertices: [u32; 3],
}

impl ScreenTriangle {
    /// Projects the object-space triangle `p` with `clip_from_object` onto a `width`×`height`
    /// image, or `None` when a vertex is at or behind the eye plane or the triangle has no area.
    pub fn project(
        clip_from_object: &Mat4,
        p: [Vec3; 3],
        (width, height): (usize, usize),
        object: u32,
        vertices: [u32; 3],
    ) -> Option<Self> {
        let mut xy = [Vec2::ZERO; 3];
        let mut z = [0.0; 3];
        let mut inv_w = [0.0; 3];
        for i in 0..3 {
            let c = *clip_from_object * p[i].extend(1.0);
            if c.w <= 1e-6 {
                return None;
            }
            let iw = 1.0 / c.w;
            xy[i] = Vec2::new((c.x * iw + 1.0) * 0.5 * width as f32, (1.0 - c.y * iw) * 0.5 * height as f32);
            z[i] = c.z * iw;
            inv_w[i] = iw;
        }
        let area = (xy[1] - xy[0]).perp_dot(xy[2] - xy[0]);
        (area.abs() > 1e-12).then_some(Self { xy, z, inv_w, object, vertices })
    }

    /// The pixel rectangle `[x0, x1) × [y0, y1)` its samples can fall in, clipped to the image.
    pub fn pixel_bounds(&self, width: usize, height: usize) -> (usize, usize, usize, usize) {
        let lo = self.xy[0].min(self.xy[1]).min(self.xy[2]);
        let hi = self.xy[0].max(self.xy[1]).max(self.xy[2]);
        let clamp = |v: f32, n: usize| v.clamp(0.0, n as f32) as usize;
        (
            clamp(lo.x.floor(), width),
            clamp(hi.x.floor() + 1.0, width),
            clamp(lo.y.floor(), height),
            clamp(hi.y.floor() + 1.0, height),
        )
    }

    /// Whether the point is inside (either winding) and, if so, its depth and perspective-correct
    /// barycentric weights.
    #[inline]
    pub fn hit(&self, q: Vec2) -> Option<(f32, [f32; 3])> {
        let [a, b, c] = self.xy;
        let area = (b - a).perp_dot(c - a);
        let l0 = (c - b).perp_dot(q - b) / area;
        let l1 = (a - c).perp_dot(q - c) / area;
        let l2 = 1.0 - l0 - l1;
        if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
            return None;
        }
        let depth = l0 * self.z[0] + l1 * self.z[1] + l2 * self.z[2];
        if !(-1.0..=1.0).contains(&depth) {
            return None;
        }
        let p = [l0 * self.inv_w[0], l1 * self.inv_w[1], l2 * self.inv_w[2]];
        let sum = p[0] + p[1] + p[2];
        Some((depth, p.map(|v| v / sum)))
    }
}

/// What one sample sees: a triangle (index into the triangle list) and its weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Index of the triangle.
    pub triangle: u32,
    /// Perspective-correct barycentric weights of its three vertices.
    pub weights: [f32; 3],
}

/// The nearest hit of every sample of the tile at pixel (`x0`, `y0`) (`tw`×`th` pixels, `spp`
/// samples each of the pattern `seed` picks, pixel-major), among the `candidates` triangles of
/// `triangles`.
pub fn resolve_tile(
    triangles: &[ScreenTriangle],
    candidates: &[u32],
    (x0, y0, tw, th): (usize, usize, usize, usize),
    (spp, seed): (usize, u32),
    (width, height): (usize, usize),
) -> Vec<Option<Hit>> {
    let mut depth = vec![f32::INFINITY; tw * th * spp];
    let mut hits = vec![None; tw * th * spp];
    for &index in candidates {
        let tri = &triangles[index as usize];
        let (bx0, bx1, by0, by1) = tri.pixel_bounds(width, height);
        for y in by0.max(y0)..by1.min(y0 + th) {
            for x in bx0.max(x0)..bx1.min(x0 + tw) {
                let base = ((y - y0) * tw + (x - x0)) * spp;
                for k in 0..spp {
                    let q = Vec2::new(x as f32, y as f32) + sample_offset(k, spp, x, y, seed);
                    if let Some((z, weights)) = tri.hit(q)
                        && z < depth[base + k]
                    {
                        depth[base + k] = z;
                        hits[base + k] = Some(Hit { triangle: index, weights });
                    }
                }
            }
        }
    }
    hits
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_fill_the_pixel_evenly() {
        // 64 samples: every 4×4 stratum of the pixel gets between 2 and 6 of them.
        for (x, y, seed) in [(0, 0, 0), (17, 3, 0), (400, 311, 0), (17, 3, 9)] {
            let mut strata = [0; 16];
            for k in 0..64 {
                let o = sample_offset(k, 64, x, y, seed);
                assert!((0.0..1.0).contains(&o.x) && (0.0..1.0).contains(&o.y));
                strata[(o.y * 4.0) as usize * 4 + (o.x * 4.0) as usize] += 1;
            }
            assert!(strata.iter().all(|&n| (2..=6).contains(&n)), "{strata:?}");
        }
        assert_ne!(sample_offset(0, 4, 1, 0, 0), sample_offset(0, 4, 0, 1, 0), "rotated per pixel");
        assert_ne!(sample_offset(0, 4, 1, 0, 0), sample_offset(0, 4, 1, 0, 1), "rotated per seed");
        assert_eq!(sample_offset(0, 1, 7, 9, 3), Vec2::splat(0.5), "one sample: the centre, whatever the seed");
    }

    #[test]
    fn the_nearer_of_two_overlapping_triangles_wins_and_weights_sum_to_one() {
        let clip = Mat4::perspective_rh_gl(1.0, 1.0, 0.5, 50.0) * Mat4::look_at_rh(Vec3::Z * 5.0, Vec3::ZERO, Vec3::Y);
        let tri = |z: f32| [Vec3::new(-2.0, -2.0, z), Vec3::new(2.0, -2.0, z), Vec3::new(0.0, 2.0, z)];
        let far = ScreenTriangle::project(&clip, tri(-1.0), (32, 32), 0, [0, 1, 2]).unwrap();
        let near = ScreenTriangle::project(&clip, tri(1.0), (32, 32), 1, [0, 1, 2]).unwrap();
        let tris = [far, near];
        for order in [[0u32, 1], [1, 0]] {
            let hits = resolve_tile(&tris, &order, (8, 8, 16, 16), (4, 0), (32, 32));
            let centre = hits[((16 - 8) * 16 + (16 - 8)) * 4].expect("the centre is covered");
            assert_eq!(centre.triangle, 1, "order {order:?}");
            assert!((centre.weights.iter().sum::<f32>() - 1.0).abs() < 1e-5);
        }
    }
}
