//! Indexed triangle meshes with per-vertex tangent frames: what a surface tessellates into and
//! what a mesh file loads as. Pure data; tangent generation lives in `tangent.rs`.

use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;

mod curvature;
mod parts;

pub use parts::AlphaMode;

/// An indexed triangle mesh. Every per-vertex array has `positions.len()` entries (or is empty
/// where noted). Triangles wind counter-clockwise when seen from the side the normal faces.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals (empty until computed, for a file without them).
    pub normals: Vec<Vec3>,
    /// Texture coordinates (s, t), t growing down the image (empty when the file has none).
    pub texcoords: Vec<Vec2>,
    /// `xyz` = unit tangent T (along increasing s), `w` = ±1 handedness: `B = w · (N × T)`.
    /// Empty until generated or loaded.
    pub tangents: Vec<Vec4>,
    /// RGBA vertex colours multiplying the base colour (the decal), in the decal's encoding
    /// (a glTF's `COLOR_0`, linear in the file, is sRGB-encoded when loaded to draw); empty
    /// when the file has none (white).
    pub colors: Vec<Vec4>,
    /// Triangles as vertex indices.
    pub indices: Vec<[u32; 3]>,
}

/// The largest mesh accepted: 50 million triangles or vertices.
pub const MAX_ELEMENTS: usize = 50_000_000;

/// Why a mesh cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// No triangles.
    #[error("the mesh has no triangles")]
    Empty,
    /// A triangle naming a vertex that does not exist.
    #[error("triangle {triangle} uses vertex {index}, but there are only {vertices} vertices")]
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The index it holds.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
    /// A NaN or infinite value.
    #[error("{what} of vertex {vertex} is not finite ({value})")]
    NonFinite {
        /// Which attribute.
        what: &'static str,
        /// The vertex.
        vertex: usize,
        /// The value, in words.
        value: String,
    },
    /// An attribute with another count than the positions.
    #[error("{what} has {got} entries for {vertices} vertices")]
    CountMismatch {
        /// Which attribute.
        what: &'static str,
        /// Its count.
        got: usize,
        /// The vertices.
        vertices: usize,
    },
    /// Tangents asked of a mesh without texture coordinates.
    #[error("the mesh has no texture coordinates: tangent frames follow them, so there are none to make")]
    NoTexcoords,
    /// Tangents asked of a mesh without normals.
    #[error("the mesh has no normals")]
    NoNormals,
    /// A split angle outside [0, 180] degrees ([`TangentOptions`](crate::tangent::TangentOptions)).
    #[error("the split angle must be in [0, 180] degrees, got {0}")]
    SplitAngle(f32),
    /// The MikkTSpace implementation gave up.
    #[error("MikkTSpace failed: {0}")]
    MikkTSpace(String),
    /// More than [`MAX_ELEMENTS`].
    #[error("{what}: {count} exceeds the limit of {max}")]
    TooLarge {
        /// What is counted.
        what: &'static str,
        /// How many.
        count: u64,
        /// The limit.
        max: usize,
    },
}

impl Mesh {
    /// Checks counts, index ranges and that every value is finite.
    pub fn validate(&self) -> Result<(), MeshError> {
        let n = self.positions.len();
        if self.indices.is_empty() {
            return Err(MeshError::Empty);
        }
        for (what, count) in [("vertices", n), ("triangles", self.indices.len())] {
            if count > MAX_ELEMENTS {
                return Err(MeshError::TooLarge { what, count: count as u64, max: MAX_ELEMENTS });
            }
        }
        for (what, got) in [
            ("normals", self.normals.len()),
            ("texture coordinates", self.texcoords.len()),
            ("tangents", self.tangents.len()),
            ("colours", self.colors.len()),
        ] {
            if got != 0 && got != n {
                return Err(MeshError::CountMismatch { what, got, vertices: n });
            }
        }
        // Each check scans in parallel blocks first (most meshes pass), then finds the first
        // offender serially.
        fn any_in_blocks<T: Sync>(values: &[T], bad: impl Fn(&T) -> bool + Sync) -> bool {
            values.par_chunks(1 << 16).any(|block| block.iter().any(&bad))
        }
        let out_of_range = |t: &[u32; 3]| t.iter().any(|&v| v as usize >= n);
        if any_in_blocks(&self.indices, out_of_range)
            && let Some((triangle, &index)) =
                self.indices.iter().enumerate().find_map(|(i, t)| t.iter().find(|&&v| v as usize >= n).map(|v| (i, v)))
        {
            return Err(MeshError::IndexOutOfRange { triangle, index, vertices: n });
        }
        let bad = |what, vertex, value: String| Err(MeshError::NonFinite { what, vertex, value });
        if any_in_blocks(&self.positions, |p| !p.is_finite())
            && let Some(i) = self.positions.iter().position(|p| !p.is_finite())
        {
            return bad("position", i, self.positions[i].to_string());
        }
        if any_in_blocks(&self.normals, |p| !p.is_finite())
            && let Some(i) = self.normals.iter().position(|p| !p.is_finite())
        {
            return bad("normal", i, self.normals[i].to_string());
        }
        if any_in_blocks(&self.texcoords, |p| !p.is_finite())
            && let Some(i) = self.texcoords.iter().position(|p| !p.is_finite())
        {
            return bad("texture coordinate", i, self.texcoords[i].to_string());
        }
        // A tangent's w is its handedness: NaN there would flip no bump and draw none.
        if any_in_blocks(&self.tangents, |t| !t.is_finite())
            && let Some(i) = self.tangents.iter().position(|t| !t.is_finite())
        {
            return bad("tangent", i, self.tangents[i].to_string());
        }
        if any_in_blocks(&self.colors, |c| !c.is_finite())
            && let Some(i) = self.colors.iter().position(|c| !c.is_finite())
        {
            return bad("colour", i, self.colors[i].to_string());
        }
        Ok(())
    }

    /// Replaces the normals by area-weighted averages of the incident triangles' normals: the
    /// documented fallback for files without normals.
    pub fn compute_normals(&mut self) {
        let mut sums = vec![Vec3::ZERO; self.positions.len()];
        for t in &self.indices {
            let [a, b, c] = t.map(|i| self.positions[i as usize]);
            let n = (b - a).cross(c - a);
            for &i in t {
                sums[i as usize] += n;
            }
        }
        self.normals = sums.into_iter().map(|n| n.normalize_or(Vec3::Z)).collect();
    }

    /// Whether the vertices carry colours ([`Mesh::colors`]).
    pub fn has_colors(&self) -> bool {
        !self.colors.is_empty()
    }

    /// Vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// The bitangent of vertex `i`: `w · (N × T)`. Panics without tangents.
    pub fn bitangent(&self, i: usize) -> Vec3 {
        let t = self.tangents[i];
        t.w * self.normals[i].cross(t.truncate())
    }

    /// The mean side of a texel of a `width`×`height` texture mapped by the texture
    /// coordinates, in the mesh's units: `√(area / (texture area · width · height))`, the
    /// triangles' areas in space and in texture space summed. `None` without texture
    /// coordinates or where either area is zero.
    pub fn mean_texel_side(&self, (width, height): (usize, usize)) -> Option<f32> {
        if self.texcoords.len() != self.positions.len() {
            return None;
        }
        let (mut area, mut uv_area) = (0.0f64, 0.0f64);
        for t in &self.indices {
            let [a, b, c] = t.map(|i| self.positions[i as usize]);
            let [p, q, r] = t.map(|i| self.texcoords[i as usize]);
            area += 0.5 * (b - a).cross(c - a).length() as f64;
            uv_area += 0.5 * ((q - p).perp_dot(r - p)).abs() as f64;
        }
        let texels = uv_area * width as f64 * height as f64;
        (area > 0.0 && texels > 0.0).then(|| (area / texels).sqrt() as f32)
    }

    /// ∂P/∂s and ∂P/∂t at every vertex: each triangle's (from its positions and texture
    /// coordinates) averaged over the triangles around the vertex, weighted by their area in
    /// texture space; zero at a vertex whose triangles have no texture area. Empty without
    /// texture coordinates.
    pub fn st_derivatives(&self) -> Vec<[Vec3; 2]> {
        if self.texcoords.len() != self.positions.len() {
            return Vec::new();
        }
        let mut sums = vec![[Vec3::ZERO; 2]; self.positions.len()];
        let mut weights = vec![0.0f32; self.positions.len()];
        for t in &self.indices {
            let [a, b, c] = t.map(|i| self.positions[i as usize]);
            let [p, q, r] = t.map(|i| self.texcoords[i as usize]);
            let (e1, e2, d1, d2) = (b - a, c - a, q - p, r - p);
            let det = d1.perp_dot(d2);
            if det == 0.0 || !det.is_finite() {
                continue;
            }
            // Solve [d1 d2]ᵀ-wise: e1 = P_s·d1.x + P_t·d1.y, e2 = P_s·d2.x + P_t·d2.y.
            let p_s = (e1 * d2.y - e2 * d1.y) / det;
            let p_t = (e2 * d1.x - e1 * d2.x) / det;
            let w = 0.5 * det.abs();
            for &i in t {
                let s = &mut sums[i as usize];
                s[0] += p_s * w;
                s[1] += p_t * w;
                weights[i as usize] += w;
            }
        }
        sums.into_iter()
            .zip(weights)
            .map(|(s, w)| if w > 0.0 { [s[0] / w, s[1] / w] } else { [Vec3::ZERO; 2] })
            .collect()
    }
}

/// The tangent benchmark's mesh, the same as the MikkTSpace peer's: an `nx`×`ny`-quad grid over
/// [0, 20]×[0, 10] with heights `0.2·sin x·cos y`, analytic normals and UVs repeating every 2
/// units (1000×500 quads = 1,000,000 triangles).
pub fn wavy_grid(nx: usize, ny: usize) -> Mesh {
    let mut m = Mesh::default();
    for i in 0..=nx {
        for j in 0..=ny {
            let (x, y) = (20.0 * i as f32 / nx as f32, 10.0 * j as f32 / ny as f32);
            m.positions.push(Vec3::new(x, y, 0.2 * x.sin() * y.cos()));
            m.normals.push(Vec3::new(-0.2 * x.cos() * y.cos(), 0.2 * x.sin() * y.sin(), 1.0).normalize());
            m.texcoords.push(Vec2::new(x / 2.0, y / 2.0));
        }
    }
    let row = ny as u32 + 1;
    for i in 0..nx as u32 {
        for j in 0..ny as u32 {
            let (a, b) = (i * row + j, (i + 1) * row + j);
            m.indices.push([a, b, b + 1]);
            m.indices.push([a, b + 1, a + 1]);
        }
    }
    m
}

/// A cube of half-size 1 whose edges and corners are rounded to `radius` (0: the plain cube
/// with hard edges), each face an `n`×`n`-quad grid with its own vertices and its own island of
/// texture coordinates (a 3×2 atlas, a margin of 4 % of a cell around each), exact normals and
/// no tangents: the baking demo's and tests' pair (a rounded HIGH, a hard-edged LOW with split
/// UVs). Faces run so that `s × t` points out (t runs down the image, as the renderer has it).
pub fn rounded_cube(n: usize, radius: f32) -> Mesh {
    let faces = [
        (Vec3::X, Vec3::NEG_Y, Vec3::NEG_Z),
        (Vec3::NEG_X, Vec3::Y, Vec3::NEG_Z),
        (Vec3::Y, Vec3::X, Vec3::NEG_Z),
        (Vec3::NEG_Y, Vec3::NEG_X, Vec3::NEG_Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (Vec3::NEG_Z, Vec3::X, Vec3::NEG_Y),
    ];
    let n = n.max(1);
    let inner = Vec3::splat(1.0 - radius.clamp(0.0, 1.0));
    let mut mesh = Mesh::default();
    for (face, (axis, u, v)) in faces.into_iter().enumerate() {
        let base = mesh.positions.len() as u32;
        let cell = Vec2::new((face % 3) as f32 / 3.0, (face / 3) as f32 / 2.0);
        for j in 0..=n {
            for i in 0..=n {
                let st = Vec2::new(i as f32 / n as f32, j as f32 / n as f32);
                let q = axis + u * (2.0 * st.x - 1.0) + v * (2.0 * st.y - 1.0);
                let c = q.clamp(-inner, inner);
                let normal = (q - c).normalize_or(axis);
                mesh.positions.push(c + normal * radius);
                mesh.normals.push(normal);
                mesh.texcoords.push(cell + (Vec2::splat(0.04) + st * 0.92) * Vec2::new(1.0 / 3.0, 0.5));
            }
        }
        let at = |i: usize, j: usize| base + (j * (n + 1) + i) as u32;
        for j in 0..n {
            for i in 0..n {
                mesh.indices.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                mesh.indices.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::Surface;

    #[test]
    fn a_tessellated_surface_has_its_texture_derivatives_and_texel_side() {
        // A 4×4 wall with the texture twice along each side: ∂P/∂s = 2·X, ∂P/∂t = 2·Y, and a
        // 256² texture's texels are 1/128 a side.
        let wall = Surface::Wall { width: 4.0, height: 4.0 }.tessellate(3, 2, Vec2::splat(2.0));
        assert!((wall.mean_texel_side((256, 256)).unwrap() - 1.0 / 128.0).abs() < 1e-7);
        for [p_s, p_t] in wall.st_derivatives() {
            assert!((p_s - 2.0 * Vec3::X).length() < 1e-5 && (p_t - 2.0 * Vec3::Y).length() < 1e-5, "{p_s} {p_t}");
        }
        // The torus: ∂P/∂s along its rings, its length 2π(R + r cos v)/6 at vertex rows.
        let torus = Surface::default_torus();
        let mesh = torus.tessellate(64, 32, Vec2::new(6.0, 2.0));
        let d = mesh.st_derivatives();
        let p = torus.eval(0.25, 0.0);
        let i = 16; // row 0, u = 16/64
        let want = p.dp_du / 6.0;
        // Chords of a 64-gon and triangles that lean across the row: within 3 %.
        assert!((d[i][0] - want).length() < 0.03 * want.length(), "{} vs {want}", d[i][0]);
        let mut no_uv = mesh.clone();
        no_uv.texcoords.clear();
        assert!(no_uv.st_derivatives().is_empty() && no_uv.mean_texel_side((8, 8)).is_none());
    }
}
