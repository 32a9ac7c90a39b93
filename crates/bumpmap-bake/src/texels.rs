//! LOW's UV layout over the texels: which triangle a sample point of a texel falls in, and its
//! barycentric weights there. Texture coordinates are the renderer's (`s` across, `t` down the
//! rows, texel `(x, y)` covering `[x, x+1) × [y, y+1)` of `(s·width, t·height)`); a triangle is
//! listed in every row its UV bounds touch, so a row's lookups see a few triangles, not all.
//! Where islands overlap (mirrored or stacked UVs) the first triangle in LOW's order that holds
//! the sample wins: the texel is one texel, and the renderer reads the same one for both.
//!
//! What this module does not do: cast rays or interpolate attributes (the baker does).

use bumpmap_math::mesh::Mesh;
use glam::Vec2;

/// A sample's triangle and weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Covered {
    /// The triangle of LOW.
    pub triangle: u32,
    /// Barycentric weights of its three vertices.
    pub weights: [f32; 3],
}

/// LOW's triangles in texel space, binned by row.
pub struct Layout {
    /// Each triangle's three corners in texel units.
    corners: Vec<[Vec2; 3]>,
    /// For each row, the triangles whose bounds touch it.
    rows: Vec<Vec<u32>>,
}

/// How far outside a triangle (in barycentric weight) a sample still counts as in: seams where
/// two triangles share an edge must not leave a crack of texels in neither.
const EDGE: f32 = 1e-5;

impl Layout {
    /// Bins `mesh`'s triangles over `width`×`height` texels.
    pub fn new(mesh: &Mesh, width: usize, height: usize) -> Self {
        let scale = Vec2::new(width as f32, height as f32);
        let corners: Vec<[Vec2; 3]> =
            mesh.indices.iter().map(|t| t.map(|i| mesh.texcoords[i as usize] * scale)).collect();
        let mut rows = vec![Vec::new(); height];
        for (k, c) in corners.iter().enumerate() {
            let (lo, hi) = (c[0].y.min(c[1].y).min(c[2].y), c[0].y.max(c[1].y).max(c[2].y));
            // Texture coordinates beyond [0, 1] (tiling) are not baked: a texel is one place.
            let first = lo.floor().max(0.0) as usize;
            let last = (hi.floor() as i64).min(height as i64 - 1);
            if last < 0 || first >= height {
                continue;
            }
            for row in &mut rows[first..=last as usize] {
                row.push(k as u32);
            }
        }
        Layout { corners, rows }
    }

    /// The triangle holding point `p` (texel units) of row `row`, if any.
    pub fn at(&self, row: usize, p: Vec2) -> Option<Covered> {
        self.rows[row].iter().find_map(|&k| {
            let [a, b, c] = self.corners[k as usize];
            let area = (b - a).perp_dot(c - a);
            if area == 0.0 {
                return None;
            }
            let w1 = (p - a).perp_dot(c - a) / area;
            let w2 = (b - a).perp_dot(p - a) / area;
            let w0 = 1.0 - w1 - w2;
            (w0 >= -EDGE && w1 >= -EDGE && w2 >= -EDGE).then_some(Covered { triangle: k, weights: [w0, w1, w2] })
        })
    }
}

/// Offset in [0, 1)² of sample `k` of `count` in a texel: the centre for one sample, else a
/// `n`×`n` grid of stratum centres (`n = ⌈√count⌉`, the first `count` strata in a fixed
/// scrambled order, so 4 samples are the four quadrants' centres).
pub fn sample_offset(k: usize, count: usize) -> Vec2 {
    if count <= 1 {
        return Vec2::splat(0.5);
    }
    let n = (count as f64).sqrt().ceil() as usize;
    // Strata visited by a stride coprime with n², so a partial grid spreads over the texel.
    let cells = n * n;
    let stride = (1..cells).rev().find(|s| gcd(*s, cells) == 1 && *s * 2 < cells + 2).unwrap_or(1);
    let cell = (k * stride) % cells;
    Vec2::new(((cell % n) as f32 + 0.5) / n as f32, ((cell / n) as f32 + 0.5) / n as f32)
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 { a } else { gcd(b, a % b) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_are_distinct_strata_inside_the_texel() {
        for count in [1, 2, 4, 5, 9, 16] {
            let points: Vec<Vec2> = (0..count).map(|k| sample_offset(k, count)).collect();
            for (i, p) in points.iter().enumerate() {
                assert!((0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y), "{count}: {p}");
                assert!(points[..i].iter().all(|q| q.distance(*p) > 0.1), "{count}: {points:?}");
            }
        }
        let four: Vec<Vec2> = (0..4).map(|k| sample_offset(k, 4)).collect();
        for q in [Vec2::new(0.25, 0.25), Vec2::new(0.75, 0.25), Vec2::new(0.25, 0.75), Vec2::new(0.75, 0.75)] {
            assert!(four.contains(&q), "{four:?}");
        }
    }

    #[test]
    fn two_triangles_of_a_quad_cover_every_texel_once_with_weights_that_sum_to_one() {
        let mesh = Mesh {
            positions: vec![glam::Vec3::ZERO; 4],
            texcoords: vec![Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(1.0, 1.0), Vec2::new(0.0, 1.0)],
            indices: vec![[0, 1, 2], [0, 2, 3]],
            ..Default::default()
        };
        let layout = Layout::new(&mesh, 8, 8);
        for y in 0..8 {
            for x in 0..8 {
                let c = layout.at(y, Vec2::new(x as f32 + 0.5, y as f32 + 0.5)).expect("covered");
                assert!((c.weights.iter().sum::<f32>() - 1.0).abs() < 1e-5);
            }
        }
        assert_eq!(layout.at(0, Vec2::new(8.5, 0.5)), None, "outside the layout");
    }
}
