//! LOW's UV layout over the texels: which triangle a sample point of a texel falls in, and its
//! barycentric weights there. Texture coordinates are the renderer's (`s` across, `t` down the
//! rows, texel `(x, y)` covering `[x, x+1) × [y, y+1)` of `(s·width, t·height)`); a triangle is
//! listed in every square cell of texels its UV bounds touch, so a lookup sees a few triangles,
//! not all.
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

/// LOW's triangles in texel space, binned in square cells of texels.
pub struct Layout {
    /// Each triangle's three corners in texel units.
    corners: Vec<[Vec2; 3]>,
    /// Cells across and down.
    cells: (usize, usize),
    /// Texels a cell's side.
    cell: usize,
    /// Where each cell's triangles start in [`Self::binned`] (one more than cells: the end).
    starts: Vec<u32>,
    /// The triangles whose bounds touch each cell, in LOW's order, cell after cell.
    binned: Vec<u32>,
}

/// How far outside a triangle (in barycentric weight) a sample still counts as in: seams where
/// two triangles share an edge must not leave a crack of texels in neither.
const EDGE: f32 = 1e-5;

/// The most entries the bins may hold before the cells grow: a layout of large overlapping
/// triangles (every one over the whole square) must not bin each into millions of cells.
const MAX_BINNED: u64 = 1 << 25;

impl Layout {
    /// The most bytes the bins of a `width`×`height` layout take: the cells' starts and the
    /// entries.
    pub fn max_bytes(width: usize, height: usize) -> u64 {
        4 * ((width.div_ceil(8) * height.div_ceil(8)) as u64 + 1 + MAX_BINNED)
    }

    /// Bins `mesh`'s triangles over `width`×`height` texels.
    pub fn new(mesh: &Mesh, width: usize, height: usize) -> Self {
        let scale = Vec2::new(width as f32, height as f32);
        let corners: Vec<[Vec2; 3]> =
            mesh.indices.iter().map(|t| t.map(|i| mesh.texcoords[i as usize] * scale)).collect();
        // Each triangle's texel bounds, clipped to the layout (texture coordinates beyond
        // [0, 1], tiling, are not baked: a texel is one place); `None` where it lies outside.
        let bounds: Vec<Option<[usize; 4]>> = corners
            .iter()
            .map(|c| {
                let lo = c[0].min(c[1]).min(c[2]);
                let hi = c[0].max(c[1]).max(c[2]);
                let first = |v: f32| v.floor().max(0.0) as usize;
                let last = |v: f32, n: usize| (v.floor() as i64).min(n as i64 - 1);
                let (x1, y1) = (last(hi.x, width), last(hi.y, height));
                let (x0, y0) = (first(lo.x), first(lo.y));
                let inside = x1 >= 0 && y1 >= 0 && x0 < width && y0 < height && lo.is_finite() && hi.is_finite();
                inside.then_some([x0, y0, x1 as usize, y1 as usize])
            })
            .collect();
        // Cells of 8 texels, larger where that would bin too much.
        let mut cell = 8;
        loop {
            let entries: u64 = bounds
                .iter()
                .flatten()
                .map(|&[x0, y0, x1, y1]| ((x1 / cell - x0 / cell + 1) * (y1 / cell - y0 / cell + 1)) as u64)
                .sum();
            if entries <= MAX_BINNED || cell >= width.max(height) {
                break;
            }
            cell *= 2;
        }
        let cells = (width.div_ceil(cell), height.div_ceil(cell));
        let mut counts = vec![0u32; cells.0 * cells.1 + 1];
        let each_cell = |[x0, y0, x1, y1]: [usize; 4], f: &mut dyn FnMut(usize)| {
            for cy in y0 / cell..=y1 / cell {
                for cx in x0 / cell..=x1 / cell {
                    f(cy * cells.0 + cx);
                }
            }
        };
        for b in bounds.iter().flatten() {
            each_cell(*b, &mut |c| counts[c + 1] += 1);
        }
        for k in 1..counts.len() {
            counts[k] += counts[k - 1];
        }
        let starts = counts;
        let mut next = starts.clone();
        let mut binned = vec![0u32; *starts.last().unwrap_or(&0) as usize];
        for (k, b) in bounds.iter().enumerate() {
            if let Some(b) = b {
                each_cell(*b, &mut |c| {
                    binned[next[c] as usize] = k as u32;
                    next[c] += 1;
                });
            }
        }
        Layout { corners, cells, cell, starts, binned }
    }

    /// The triangle holding point `p` (texel units) of texel `(x, y)`, if any.
    pub fn at(&self, x: usize, y: usize, p: Vec2) -> Option<Covered> {
        let c = (y / self.cell) * self.cells.0 + x / self.cell;
        let list = &self.binned[self.starts[c] as usize..self.starts[c + 1] as usize];
        list.iter().find_map(|&k| {
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
                let c = layout.at(x, y, Vec2::new(x as f32 + 0.5, y as f32 + 0.5)).expect("covered");
                assert!((c.weights.iter().sum::<f32>() - 1.0).abs() < 1e-5);
            }
        }
        assert_eq!(layout.at(7, 0, Vec2::new(8.5, 0.5)), None, "outside the layout");
    }

    /// Every triangle in LOW's order: what the bins must agree with.
    fn first_of_all(mesh: &Mesh, width: usize, height: usize, p: Vec2) -> Option<u32> {
        let scale = Vec2::new(width as f32, height as f32);
        mesh.indices
            .iter()
            .position(|t| {
                let [a, b, c] = t.map(|i| mesh.texcoords[i as usize] * scale);
                let area = (b - a).perp_dot(c - a);
                let w1 = (p - a).perp_dot(c - a) / area;
                let w2 = (b - a).perp_dot(p - a) / area;
                area != 0.0 && w1 >= -EDGE && w2 >= -EDGE && 1.0 - w1 - w2 >= -EDGE
            })
            .map(|k| k as u32)
    }

    proptest::proptest! {
        /// Overlapping, mirrored, tiny and square-wide triangles, some beyond [0, 1]: the binned
        /// lookup finds the first triangle in LOW's order that holds each sample, as a search
        /// over every triangle does.
        #[test]
        fn the_bins_find_the_first_triangle_that_holds_a_sample(
            uvs in proptest::collection::vec((-0.2f32..1.2, -0.2f32..1.2), 3..60),
            width in 1usize..70,
            height in 1usize..70,
        ) {
            let texcoords: Vec<Vec2> = uvs.iter().map(|&(s, t)| Vec2::new(s, t)).collect();
            let indices = (0..texcoords.len() as u32 / 3).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
            let mesh = Mesh { positions: vec![glam::Vec3::ZERO; texcoords.len()], texcoords, indices, ..Default::default() };
            let layout = Layout::new(&mesh, width, height);
            for y in 0..height {
                for x in 0..width {
                    for k in 0..4 {
                        let p = Vec2::new(x as f32, y as f32) + sample_offset(k, 4);
                        let found = layout.at(x, y, p).map(|c| c.triangle);
                        proptest::prop_assert_eq!(found, first_of_all(&mesh, width, height, p), "texel ({}, {})", x, y);
                    }
                }
            }
        }
    }
}
