//! Normalization cube maps (Kilgard §4.1, §5.2, Appendix D, Table 1).
//!
//! A cube map indexed by an unnormalized direction returns that direction normalized and
//! range-compressed: the GeForce-era substitute for a per-fragment `normalize`. This module
//! builds the six faces, selects a face and (s, t) for a direction as the cube-map extension's
//! table prescribes, and samples bilinearly with clamp-to-edge within the face. It does not
//! filter across faces (the hardware did not) and knows nothing of mipmaps, which a
//! normalization cube map never has.

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use crate::encoding::{Encoding, expand_normal};

/// The six faces in OpenGL's target order (`GL_TEXTURE_CUBE_MAP_POSITIVE_X` + i).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CubeFace {
    /// +X.
    PosX,
    /// −X.
    NegX,
    /// +Y.
    PosY,
    /// −Y.
    NegY,
    /// +Z.
    PosZ,
    /// −Z.
    NegZ,
}

impl CubeFace {
    /// Every face, in GL order.
    pub const ALL: [CubeFace; 6] =
        [CubeFace::PosX, CubeFace::NegX, CubeFace::PosY, CubeFace::NegY, CubeFace::PosZ, CubeFace::NegZ];

    /// Short file-name stem: `px`, `nx`, `py`, `ny`, `pz`, `nz`.
    pub fn stem(self) -> &'static str {
        ["px", "nx", "py", "ny", "pz", "nz"][self as usize]
    }

    /// The unnormalized direction through face coordinates (sc, tc) ∈ [−1, 1]², the inverse of
    /// Table 1 (Appendix D's `getCubeVector`).
    #[inline]
    pub fn direction(self, sc: f32, tc: f32) -> Vec3 {
        match self {
            CubeFace::PosX => Vec3::new(1.0, -tc, -sc),
            CubeFace::NegX => Vec3::new(-1.0, -tc, sc),
            CubeFace::PosY => Vec3::new(sc, 1.0, tc),
            CubeFace::NegY => Vec3::new(sc, -1.0, -tc),
            CubeFace::PosZ => Vec3::new(sc, -tc, 1.0),
            CubeFace::NegZ => Vec3::new(-sc, -tc, -1.0),
        }
    }

    /// Table 1: the face a direction pierces and its (s, t) in [0, 1]². Ties between axes go to
    /// x before y before z. Returns `None` for the zero vector or a non-finite one.
    #[inline]
    pub fn select(r: Vec3) -> Option<(CubeFace, f32, f32)> {
        let a = r.abs();
        let (face, sc, tc, ma) = if a.x >= a.y && a.x >= a.z {
            if r.x >= 0.0 { (CubeFace::PosX, -r.z, -r.y, a.x) } else { (CubeFace::NegX, r.z, -r.y, a.x) }
        } else if a.y >= a.z {
            if r.y >= 0.0 { (CubeFace::PosY, r.x, r.z, a.y) } else { (CubeFace::NegY, r.x, -r.z, a.y) }
        } else if r.z >= 0.0 {
            (CubeFace::PosZ, r.x, -r.y, a.z)
        } else {
            (CubeFace::NegZ, -r.x, -r.y, a.z)
        };
        (ma > 0.0 && ma.is_finite()).then(|| (face, 0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0)))
    }
}

/// Six square RGB8 faces whose texels hold the range-compressed unit vector through their
/// centre.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NormalizationCubeMap {
    /// Texels along each face's edge.
    pub size: usize,
    /// How the unit vectors are stored.
    pub encoding: Encoding,
    /// Faces in [`CubeFace::ALL`] order; each `size·size` texels, row-major, row 0 = t = 0.
    pub faces: [Vec<[u8; 3]>; 6],
}

/// Appendix D's `getCubeVector`, with C's mix of float and double reproduced so that the
/// `kilgard` encoding equals the paper's (and the Cg Toolkit's) bytes exactly.
pub fn texel_direction(face: CubeFace, size: usize, x: usize, y: usize) -> Vec3 {
    let n = size as f32 as f64;
    let s = ((x as f32 as f64 + 0.5) / n) as f32;
    let t = ((y as f32 as f64 + 0.5) / n) as f32;
    let sc = (s as f64 * 2.0 - 1.0) as f32;
    let tc = (t as f64 * 2.0 - 1.0) as f32;
    let v = face.direction(sc, tc);
    let mag = (1.0 / ((v.x * v.x + v.y * v.y + v.z * v.z) as f64).sqrt()) as f32;
    v * mag
}

impl NormalizationCubeMap {
    /// Builds all six faces. `size` must be positive.
    pub fn new(size: usize, encoding: Encoding) -> Self {
        assert!(size > 0, "cube map face size must be positive");
        let faces = CubeFace::ALL.map(|face| {
            (0..size * size)
                .into_par_iter()
                .map(|i| {
                    let v = texel_direction(face, size, i % size, i / size);
                    [encoding.encode(v.x), encoding.encode(v.y), encoding.encode(v.z)]
                })
                .collect()
        });
        Self { size, encoding, faces }
    }

    /// The texel of `face` at (x, y).
    #[inline]
    pub fn texel(&self, face: CubeFace, x: usize, y: usize) -> [u8; 3] {
        self.faces[face as usize][y * self.size + x]
    }

    /// Bilinear `GL_LINEAR` sample with `GL_CLAMP_TO_EDGE` inside the selected face, in texel
    /// units [0, 1] per channel (as a texture unit hands it to the combiners).
    pub fn sample(&self, r: Vec3) -> Option<Vec3> {
        let (face, s, t) = CubeFace::select(r)?;
        let n = self.size as f32;
        // Clamp-to-edge: s ∈ [1/2N, 1 − 1/2N] so the filter never leaves the face.
        let u = (s * n - 0.5).clamp(0.0, n - 1.0);
        let v = (t * n - 0.5).clamp(0.0, n - 1.0);
        let (i0, j0) = (u.floor() as usize, v.floor() as usize);
        let (i1, j1) = ((i0 + 1).min(self.size - 1), (j0 + 1).min(self.size - 1));
        let (a, b) = (u - i0 as f32, v - j0 as f32);
        let px = |i, j| {
            let [r, g, b] = self.texel(face, i, j);
            Vec3::new(r as f32, g as f32, b as f32) / 255.0
        };
        let top = px(i0, j0) * (1.0 - a) + px(i1, j0) * a;
        let bottom = px(i0, j1) * (1.0 - a) + px(i1, j1) * a;
        Some(top * (1.0 - b) + bottom * b)
    }

    /// The normalized direction as the register combiners see it: the bilinear sample expanded
    /// with `EXPAND_NORMAL_NV` (2x − 1). Not exactly unit length; that is the point of measuring.
    pub fn lookup(&self, r: Vec3) -> Option<Vec3> {
        self.sample(r).map(|c| c * 2.0 - Vec3::ONE)
    }

    /// All faces as one buffer, +X first, each face row-major (the Cg Toolkit's layout).
    pub fn to_bytes(&self) -> Vec<u8> {
        self.faces.iter().flat_map(|f| f.as_flattened().iter().copied()).collect()
    }
}

/// Expands an RGB byte triple as `EXPAND_NORMAL_NV` does.
pub fn expand_rgb(t: [u8; 3]) -> Vec3 {
    Vec3::new(expand_normal(t[0]), expand_normal(t[1]), expand_normal(t[2]))
}

/// The worst angle, in degrees, between a direction and the cube map's expanded bilinear lookup
/// of it, over a grid of `4·size + 1` points per face edge: every texel centre, every point
/// between them, and every face edge and corner.
pub fn worst_angular_error_degrees(map: &NormalizationCubeMap) -> f64 {
    let steps = 4 * map.size;
    CubeFace::ALL
        .par_iter()
        .map(|&face| {
            let mut worst = 0.0f64;
            for j in 0..=steps {
                for i in 0..=steps {
                    let sc = 2.0 * i as f32 / steps as f32 - 1.0;
                    let tc = 2.0 * j as f32 / steps as f32 - 1.0;
                    let dir = face.direction(sc, tc);
                    let got = map.lookup(dir).expect("face directions are never zero");
                    let (a, b) = (DVec3::from(dir.normalize()), DVec3::from(got).normalize());
                    worst = worst.max(a.dot(b).clamp(-1.0, 1.0).acos().to_degrees());
                }
            }
            worst
        })
        .reduce(|| 0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cg_tutorial_known_answer() {
        // Cg Tutorial §8.1.3: (3, 1.5, 0.9) pierces +X and normalizes to about (0.93, 0.72, 0.63)
        // once range-compressed.
        let r = Vec3::new(3.0, 1.5, 0.9);
        assert_eq!(CubeFace::select(r).unwrap().0, CubeFace::PosX);
        let map = NormalizationCubeMap::new(32, Encoding::Unorm);
        let c = map.sample(r).unwrap();
        let want = Vec3::new(0.93, 0.72, 0.63);
        // The book rounds to two digits; bilinear filtering of 8-bit texels adds < 0.01.
        assert!((c - want).abs().max_element() < 0.01, "{c} vs {want}");
    }

    #[test]
    fn select_inverts_direction_on_every_face() {
        for face in CubeFace::ALL {
            for (sc, tc) in [(0.0, 0.0), (0.5, -0.25), (-0.9, 0.9), (0.99, 0.99)] {
                let (f, s, t) = CubeFace::select(face.direction(sc, tc) * 3.0).unwrap();
                assert_eq!(f, face);
                // Two divisions and a few additions in f32: 1e-6 absolute.
                assert!((s - (sc + 1.0) / 2.0).abs() < 1e-6 && (t - (tc + 1.0) / 2.0).abs() < 1e-6);
            }
        }
        assert_eq!(CubeFace::select(Vec3::ZERO), None);
        assert_eq!(CubeFace::select(Vec3::new(f32::NAN, 0.0, 0.0)), None);
    }

    #[test]
    fn lookup_is_close_to_normalize() {
        let map = NormalizationCubeMap::new(64, Encoding::Unorm);
        let err = worst_angular_error_degrees(&map);
        // 8-bit components alone allow ~0.5°; bilinear chords across a 64² face add a little.
        assert!(err > 0.0 && err < 1.5, "worst error {err}°");
    }
}
