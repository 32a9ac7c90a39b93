//! Is it a normal map, and does it tile? Level 0's texels, counted.
//!
//! A tangent-space normal map holds unit vectors (to within its encoding) that lean away from
//! the surface (`z > 0`), in colours that differ channel by channel. A height, roughness or mask
//! map stored as an image has equal channels; a colour photograph's texels, decoded as vectors,
//! have any length. Whether a map tiles is read from its edges: the angle between the normals on
//! either side of the wrap against the angle between interior neighbours.
//!
//! What this module does not do: decide the Y convention (`convention`) or judge the mips
//! (`mips`).

use glam::{Vec3, Vec4, Vec4Swizzles};

use crate::image::Image;
use crate::imported::UNIT_TOLERANCE;

/// Level 0's texels, counted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexelStats {
    /// Texels counted.
    pub texels: usize,
    /// The mean length of the stored vectors.
    pub mean_length: f32,
    /// The root-mean-square of `|n| − 1`.
    pub length_rms_error: f32,
    /// The fraction whose length is more than [`UNIT_TOLERANCE`] from 1, or not a number at
    /// all (NaN or infinite).
    pub off_unit: f32,
    /// The fraction with `z ≤ 0`: facing into the surface, which no height field makes.
    pub facing_away: f32,
    /// The fraction whose three channels are equal (to 1.5 steps of 8 bits).
    pub gray: f32,
    /// The mean vector.
    pub mean: Vec3,
}

/// What the texels say the file is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapKind {
    /// Vectors of unit length leaning away from the surface.
    NormalMap,
    /// Equal channels: a height, roughness, occlusion or mask map.
    Gray,
    /// Vectors of every length: a colour image (a photograph, a base colour, a packed ORM map).
    NotUnitVectors,
    /// Unit vectors, but most lean into the surface or lie in it.
    FacingAway,
}

impl MapKind {
    /// Whether the file reads as a normal map.
    pub fn is_normal_map(self) -> bool {
        self == MapKind::NormalMap
    }

    /// In words.
    pub fn describe(self) -> &'static str {
        match self {
            MapKind::NormalMap => "a normal map",
            MapKind::Gray => "not a normal map: its channels are equal (a height, roughness or mask map?)",
            MapKind::NotUnitVectors => {
                "not a normal map: its texels are vectors of every length (a colour image or a packed ORM map?)"
            }
            MapKind::FacingAway => "not a tangent-space normal map: most texels point into the surface",
        }
    }
}

/// The fraction of gray texels beyond which a map is gray.
const GRAY_ABOVE: f32 = 0.9;
/// The fraction of off-unit texels beyond which a map is not made of unit vectors.
const NOT_UNIT_ABOVE: f32 = 0.25;
/// The fraction of texels facing away beyond which a map is not a tangent-space normal map.
const FACING_AWAY_ABOVE: f32 = 0.5;

impl TexelStats {
    /// The texels of `level` (signed xyz; w not read).
    pub fn of(level: &Image<Vec4>) -> Self {
        use rayon::prelude::*;
        let n = level.texels.len().max(1) as f64;
        let step = 1.5 * 2.0 / 255.0;
        // Per chunk: length sum, squared length error, off unit, facing away, gray, mean.
        type Sums = (f64, f64, usize, usize, usize, glam::DVec3);
        let zero: Sums = (0.0, 0.0, 0, 0, 0, glam::DVec3::ZERO);
        let add = |a: Sums, b: Sums| (a.0 + b.0, a.1 + b.1, a.2 + b.2, a.3 + b.3, a.4 + b.4, a.5 + b.5);
        let (len_sum, len_sq_err, off, away, gray, mean) = level
            .texels
            .par_chunks(1 << 14)
            .map(|chunk| {
                let mut s = zero;
                let mut mean = glam::Vec3::ZERO;
                for t in chunk {
                    let v = t.xyz();
                    let l = v.length();
                    s.0 += l as f64;
                    s.1 += ((l - 1.0) as f64).powi(2);
                    s.2 += usize::from(!l.is_finite() || (l - 1.0).abs() > UNIT_TOLERANCE);
                    s.3 += usize::from(v.z <= 0.0);
                    s.4 += usize::from((v.x - v.y).abs() <= step && (v.y - v.z).abs() <= step);
                    mean += v;
                }
                s.5 = mean.as_dvec3();
                s
            })
            .reduce(|| zero, add);
        Self {
            texels: level.texels.len(),
            mean_length: (len_sum / n) as f32,
            length_rms_error: (len_sq_err / n).sqrt() as f32,
            off_unit: off as f32 / n as f32,
            facing_away: away as f32 / n as f32,
            gray: gray as f32 / n as f32,
            mean: (mean / n).as_vec3(),
        }
    }

    /// What the counts say the map is. `two_channel`: Z was rebuilt, so lengths are 1 by
    /// construction and not judged.
    pub fn kind(&self, two_channel: bool) -> MapKind {
        if self.gray > GRAY_ABOVE {
            MapKind::Gray
        } else if !two_channel && self.off_unit > NOT_UNIT_ABOVE {
            MapKind::NotUnitVectors
        } else if self.facing_away > FACING_AWAY_ABOVE {
            MapKind::FacingAway
        } else {
            MapKind::NormalMap
        }
    }
}

/// How the map meets itself when it repeats, along each axis: the mean angle between the
/// normals on either side of the wrap (last column and first; last row and first) against the
/// largest mean angle between any two neighbouring interior columns (rows). A map that tiles
/// has a seam like any other column pair; measuring against the worst pair rather than the
/// average keeps a tile whose edge runs along a feature (bricks' mortar joints) from reading as
/// broken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seam {
    /// Across the vertical seam (last column to first): the seam's mean angle and the worst
    /// interior column pair's, in degrees.
    pub columns: [f32; 2],
    /// Across the horizontal seam (last row to first), the same.
    pub rows: [f32; 2],
    /// The mean slope `(−n_x/n_z, −n_y/n_z)` per texel, green as stored: a map can tile while the
    /// heights it holds cannot — a tilted plane's normals are all alike, but its heights climb
    /// by `width × slope` from one edge to the other.
    pub mean_slope: [f32; 2],
}

/// The largest mean slope (per texel, either way) of heights that tile: twice what 8-bit unorm's
/// missing zero leaves on a flat map (a stored 128 decodes to 0.004).
pub const MEAN_SLOPE_TILES: f32 = 0.008;

/// The most rows (columns) a seam's pairs are averaged over.
pub const SEAM_SAMPLES: usize = 512;

impl Seam {
    /// The larger of the two seams' mean angles, in degrees.
    pub fn seam_degrees(&self) -> f32 {
        self.columns[0].max(self.rows[0])
    }

    /// The larger of the two worst interior pairs, in degrees.
    pub fn interior_degrees(&self) -> f32 {
        self.columns[1].max(self.rows[1])
    }

    /// Whether both seams are within a quarter (and a quarter degree) of the worst interior
    /// pair along the same axis: the map tiles.
    pub fn tiles(&self) -> bool {
        [self.columns, self.rows].iter().all(|[seam, worst]| *seam <= 1.25 * worst + 0.25)
    }

    /// Whether the heights the map holds tile too: the map tiles and its mean slope is under
    /// [`MEAN_SLOPE_TILES`] each way.
    pub fn heights_tile(&self) -> bool {
        self.tiles() && self.mean_slope.iter().all(|m| m.abs() <= MEAN_SLOPE_TILES)
    }

    /// The seams of `level` (signed xyz; w not read). A side of one or two texels has no
    /// interior pair: its seam is compared with 0. Pairs are averaged over at most
    /// [`SEAM_SAMPLES`] evenly spaced rows (columns): the seam of a 4096² map costs what a 512²
    /// map's does.
    pub fn of(level: &Image<Vec4>) -> Self {
        use rayon::prelude::*;
        let (w, h) = (level.width, level.height);
        let dir = |x: usize, y: usize| level.texel(x, y).xyz().normalize_or_zero();
        let angle = |a: Vec3, b: Vec3| a.dot(b).clamp(-1.0, 1.0).acos().to_degrees() as f64;
        // Mean angle of each pair (i, i+1 mod n) along one axis, over m lines.
        let pairs = |n: usize, m: usize, at: &(dyn Fn(usize, usize) -> Vec3 + Sync)| -> [f32; 2] {
            if n < 2 || m == 0 {
                return [0.0, 0.0];
            }
            let step = m.div_ceil(SEAM_SAMPLES);
            let lines: Vec<usize> = (0..m).step_by(step).collect();
            let means: Vec<f64> = (0..n)
                .into_par_iter()
                .map(|i| lines.iter().map(|&j| angle(at(i, j), at((i + 1) % n, j))).sum::<f64>() / lines.len() as f64)
                .collect();
            let worst = means[..n - 1].iter().cloned().fold(0.0, f64::max);
            [means[n - 1] as f32, worst as f32]
        };
        let (sum_p, sum_q, n) = level
            .texels
            .par_iter()
            .filter(|t| t.z > 0.1)
            .map(|t| ((-t.x / t.z) as f64, (-t.y / t.z) as f64, 1usize))
            .reduce(|| (0.0, 0.0, 0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2));
        let n = n.max(1) as f64;
        Self {
            columns: pairs(w, h, &|x, y| dir(x, y)),
            rows: pairs(h, w, &|y, x| dir(x, y)),
            mean_slope: [(sum_p / n) as f32, (sum_q / n) as f32],
        }
    }
}
