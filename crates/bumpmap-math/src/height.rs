//! Height fields: the scalar function F(u, v) that bump mapping differentiates (Kilgard Eq. 2).
//!
//! A height field is a row-major grid of heights in [0, 1]; row 0 is texture coordinate t = 0
//! (OpenGL's `glTexImage2D` order), so "up" in a normal map is the direction of the next row.
//! The procedural presets tile seamlessly so they can be used with `Wrap::Repeat`. Reading
//! image files belongs to `bumpmap-io`, not here.

/// A row-major grid of heights, nominally in [0, 1].
///
/// 8- and 16-bit fields keep their integer samples and convert a row at a time when read
/// (`h = b/255` in single precision, as Kilgard Appendix E), so a large field is never copied
/// into floats as a whole.
#[derive(Clone, Debug, PartialEq)]
pub struct HeightField {
    width: usize,
    height: usize,
    samples: Samples,
}

#[derive(Clone, Debug, PartialEq)]
enum Samples {
    F32(Vec<f32>),
    U8(Vec<u8>),
    U16(Vec<u16>),
}

/// A field's samples as stored, borrowed ([`HeightField::samples`]): what a reader made them,
/// before any conversion to float.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HeightSamples<'a> {
    /// Heights in float, nominally in [0, 1].
    F32(&'a [f32]),
    /// 8-bit samples, `h = b/255`.
    U8(&'a [u8]),
    /// 16-bit samples, `h = v/65535`.
    U16(&'a [u16]),
}

/// The largest |height| a float field may hold. Slopes are differences of heights times the
/// scale (at most 1e6); beyond about 1e12 their squares overflow single precision and every
/// normal comes out zero (heights of ±1e20 from an OpenEXR file did), so 1e9 keeps three
/// orders of magnitude to spare. Heights are in [0, 1] nominally, or in scene units.
pub const MAX_FLOAT_HEIGHT: f32 = 1e9;

const ONE_OVER_255: f32 = 1.0 / 255.0;
const ONE_OVER_65535: f32 = 1.0 / 65535.0;

impl HeightField {
    fn checked(width: usize, height: usize, len: usize, samples: Samples) -> Option<Self> {
        (width > 0 && height > 0 && len == width.checked_mul(height)?).then_some(Self { width, height, samples })
    }

    /// Wraps `data` (row-major, row 0 first). Returns `None` when the length does not match or a
    /// dimension is zero.
    pub fn new(width: usize, height: usize, data: Vec<f32>) -> Option<Self> {
        Self::checked(width, height, data.len(), Samples::F32(data))
    }

    /// Builds a field by evaluating `f(x, y)` at every texel. Panics if a dimension is zero.
    pub fn from_fn(width: usize, height: usize, mut f: impl FnMut(usize, usize) -> f32) -> Self {
        assert!(width > 0 && height > 0, "height field of {width}x{height}");
        let mut data = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                data.push(f(x, y));
            }
        }
        Self { width, height, samples: Samples::F32(data) }
    }

    /// 8-bit heights, read as `h = b/255`.
    pub fn from_u8(width: usize, height: usize, bytes: &[u8]) -> Option<Self> {
        Self::checked(width, height, bytes.len(), Samples::U8(bytes.to_vec()))
    }

    /// Like [`HeightField::from_u8`], taking ownership of the bytes.
    pub fn from_u8_vec(width: usize, height: usize, bytes: Vec<u8>) -> Option<Self> {
        Self::checked(width, height, bytes.len(), Samples::U8(bytes))
    }

    /// 16-bit heights, read as `h = v/65535`.
    pub fn from_u16(width: usize, height: usize, values: &[u16]) -> Option<Self> {
        Self::checked(width, height, values.len(), Samples::U16(values.to_vec()))
    }

    /// The first float sample that is not finite or beyond ±[`MAX_FLOAT_HEIGHT`], as
    /// `(x, y, value)`, row by row; `None` when every sample can be differentiated (8- and
    /// 16-bit fields always can).
    pub fn first_unusable(&self) -> Option<(usize, usize, f32)> {
        let Samples::F32(d) = &self.samples else { return None };
        d.iter()
            .position(|h| !h.is_finite() || h.abs() > MAX_FLOAT_HEIGHT)
            .map(|i| (i % self.width, i / self.width, d[i]))
    }

    /// The samples as stored, row-major, row 0 first.
    pub fn samples(&self) -> HeightSamples<'_> {
        match &self.samples {
            Samples::F32(d) => HeightSamples::F32(d),
            Samples::U8(d) => HeightSamples::U8(d),
            Samples::U16(d) => HeightSamples::U16(d),
        }
    }

    /// Width in texels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// One row of heights as floats: borrowed when stored as floats, else converted into `buf`.
    /// Panics if `y >= height`.
    #[inline]
    pub fn row<'a>(&'a self, y: usize, buf: &'a mut Vec<f32>) -> &'a [f32] {
        let span = y * self.width..(y + 1) * self.width;
        match &self.samples {
            Samples::F32(d) => &d[span],
            Samples::U8(d) => {
                buf.clear();
                buf.extend(d[span].iter().map(|&b| b as f32 * ONE_OVER_255));
                buf
            }
            Samples::U16(d) => {
                buf.clear();
                buf.extend(d[span].iter().map(|&v| v as f32 * ONE_OVER_65535));
                buf
            }
        }
    }

    /// Row `y` when the field is stored as floats, `None` for integer samples.
    #[inline]
    pub fn float_row(&self, y: usize) -> Option<&[f32]> {
        match &self.samples {
            Samples::F32(d) => Some(&d[y * self.width..(y + 1) * self.width]),
            _ => None,
        }
    }

    /// The height at texel (x, y). Panics when out of range.
    #[inline]
    pub fn get(&self, x: usize, y: usize) -> f32 {
        let i = y * self.width + x;
        match &self.samples {
            Samples::F32(d) => d[i],
            Samples::U8(d) => d[i] as f32 * ONE_OVER_255,
            Samples::U16(d) => d[i] as f32 * ONE_OVER_65535,
        }
    }

    /// All heights as floats, row-major.
    pub fn to_f32(&self) -> Vec<f32> {
        let mut buf = Vec::new();
        (0..self.height).flat_map(|y| self.row(y, &mut buf).to_vec()).collect()
    }

    /// Heights quantized to 8 bits (`round(255·h)`), e.g. to save a preview.
    /// A row at a time: no float copy of the whole field.
    pub fn to_u8(&self) -> Vec<u8> {
        let mut buf = Vec::new();
        let mut out = Vec::with_capacity(self.width * self.height);
        for y in 0..self.height {
            out.extend(self.row(y, &mut buf).iter().map(|&h| (h.clamp(0.0, 1.0) * 255.0 + 0.5) as u8));
        }
        out
    }
}

/// The built-in procedural height fields, usable wherever a height-field file is accepted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HeightPreset {
    /// The Cg Tutorial's brick wall (Figure 8-1): raised bricks, recessed mortar, some bricks
    /// rough. 4 bricks across and 8 rows per tile, alternate rows offset by half a brick.
    Bricks,
    /// Peercy Figure 4's pinwheel: eight raised blades around the centre, soft-edged.
    Pinwheel,
    /// A golf ball: spherical dimples on a hexagonal grid.
    Dimples,
    /// Tileable fractal value noise from a seed.
    Noise(u64),
}

/// The name [`HeightPreset::parse`] reads back: `bricks`, `noise:7`, …
impl std::fmt::Display for HeightPreset {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            HeightPreset::Bricks => f.write_str("bricks"),
            HeightPreset::Pinwheel => f.write_str("pinwheel"),
            HeightPreset::Dimples => f.write_str("dimples"),
            HeightPreset::Noise(seed) => write!(f, "noise:{seed}"),
        }
    }
}

impl HeightPreset {
    /// Default edge length of a preset rendered without an explicit size.
    pub const DEFAULT_SIZE: usize = 256;

    /// Parses `bricks`, `pinwheel`, `dimples` or `noise:SEED` (case-insensitive).
    pub fn parse(spec: &str) -> Option<Self> {
        let lower = spec.to_ascii_lowercase();
        match lower.as_str() {
            "bricks" => Some(Self::Bricks),
            "pinwheel" => Some(Self::Pinwheel),
            "dimples" => Some(Self::Dimples),
            "noise" => Some(Self::Noise(1)),
            other => other.strip_prefix("noise:")?.parse().ok().map(Self::Noise),
        }
    }

    /// The names accepted by [`HeightPreset::parse`], for help texts and error messages.
    pub const NAMES: &'static str = "bricks, pinwheel, dimples, noise:SEED";

    /// Renders the preset at `width`×`height` texels. Panics if a dimension is zero.
    pub fn render(self, width: usize, height: usize) -> HeightField {
        let (w, h) = (width as f32, height as f32);
        match self {
            Self::Bricks => {
                let rough = ValueNoise::new(0xb51c, 32);
                HeightField::from_fn(width, height, |x, y| {
                    let (u, v) = ((x as f32 + 0.5) / w, (y as f32 + 0.5) / h);
                    bricks(u, v, w, h, &rough)
                })
            }
            Self::Pinwheel => HeightField::from_fn(width, height, |x, y| {
                let (u, v) = ((x as f32 + 0.5) / w - 0.5, (y as f32 + 0.5) / h - 0.5);
                pinwheel(u, v, w.min(h))
            }),
            Self::Dimples => {
                HeightField::from_fn(width, height, |x, y| dimples((x as f32 + 0.5) / w, (y as f32 + 0.5) / h))
            }
            Self::Noise(seed) => {
                let noise = ValueNoise::new(seed, 8);
                HeightField::from_fn(width, height, |x, y| noise.fractal((x as f32 + 0.5) / w, (y as f32 + 0.5) / h, 5))
            }
        }
    }
}

/// Where (u, v) ∈ [0, 1)² falls in the brick layout: distance to the nearest mortar joint in
/// texels (negative inside the mortar) for a `w`×`h` texture, and the brick's row and column.
fn brick_cell(u: f32, v: f32, w: f32, h: f32) -> (f32, u64, u64) {
    const ACROSS: f32 = 4.0;
    const ROWS: f32 = 8.0;
    let row = (v * ROWS).floor();
    let shift = if row as i32 % 2 == 1 { 0.5 } else { 0.0 };
    let bu = (u * ACROSS + shift).rem_euclid(ACROSS);
    let col = bu.floor();
    // The mortar joint is 1/16 of a brick row tall and as wide in texels.
    let (fu, fv) = (bu.fract(), (v * ROWS).fract());
    let mortar = 1.0 / 16.0;
    let du = (fu.min(1.0 - fu) - mortar * 0.5 * h * ACROSS / (ROWS * w)) * w / ACROSS;
    let dv = (fv.min(1.0 - fv) - mortar * 0.5) * h / ROWS;
    (du.min(dv), row as u64, col as u64)
}

/// Brick height at (u, v) in [0, 1)²; `w`, `h` give the texel size for the bevel width.
fn bricks(u: f32, v: f32, w: f32, h: f32, rough: &ValueNoise) -> f32 {
    let (edge, row, col) = brick_cell(u, v, w, h);
    let bevel = (w / 128.0).max(1.0);
    let face = (edge / bevel).clamp(0.0, 1.0);
    // Every third brick (by a hash of its cell) is rough.
    let roughness = if hash(row * 31 + col, 7).is_multiple_of(3) { 0.2 } else { 0.0 };
    let grain = rough.fractal(u, v, 3) - 0.5;
    0.2 + 0.8 * face * (1.0 - roughness * 0.5 + roughness * grain)
}

/// The decal that goes with [`HeightPreset::Bricks`]: red bricks, each tinted a little
/// differently, in light grey mortar. RGBA8 (A = 255), row-major, row 0 = t = 0.
pub fn bricks_decal(width: usize, height: usize) -> Vec<[u8; 4]> {
    let (w, h) = (width as f32, height as f32);
    let mut out = Vec::with_capacity(width * height);
    for y in 0..height {
        for x in 0..width {
            let (edge, row, col) = brick_cell((x as f32 + 0.5) / w, (y as f32 + 0.5) / h, w, h);
            let tint = 0.75 + 0.35 * (hash(row * 31 + col, 11) >> 40) as f32 / (1u64 << 24) as f32;
            let brick = [0.72 * tint, 0.28 * tint, 0.18 * tint];
            let mortar = [0.78, 0.76, 0.72];
            let k = edge.clamp(0.0, 1.0);
            let c = [0, 1, 2].map(|i| ((k * brick[i] + (1.0 - k) * mortar[i]).clamp(0.0, 1.0) * 255.0 + 0.5) as u8);
            out.push([c[0], c[1], c[2], 255]);
        }
    }
    out
}

/// A gloss map for [`HeightPreset::Bricks`]: 255 on brick faces, 40 in the mortar, with the
/// same soft edge as the height field.
pub fn bricks_gloss(width: usize, height: usize) -> Vec<u8> {
    let (w, h) = (width as f32, height as f32);
    let bevel = (w / 128.0).max(1.0);
    let mut out = Vec::with_capacity(width * height);
    for y in 0..height {
        for x in 0..width {
            let (edge, _, _) = brick_cell((x as f32 + 0.5) / w, (y as f32 + 0.5) / h, w, h);
            let face = (edge / bevel).clamp(0.0, 1.0);
            out.push((40.0 + 215.0 * face + 0.5) as u8);
        }
    }
    out
}

fn pinwheel(u: f32, v: f32, texels: f32) -> f32 {
    const BLADES: f32 = 8.0;
    let r = (u * u + v * v).sqrt();
    let theta = v.atan2(u);
    // Blades curl with the radius, like a child's pinwheel; soft edges about a texel wide.
    let phase = (theta * BLADES / 2.0 + r * 6.0).sin();
    let edge_px = (texels * r * std::f32::consts::PI / BLADES).max(1.0);
    let blade = (phase * edge_px * 0.5 + 0.5).clamp(0.0, 1.0);
    let disc = ((0.45 - r) * texels * 0.5 + 0.5).clamp(0.0, 1.0);
    blade * disc
}

fn dimples(u: f32, v: f32) -> f32 {
    // A hexagonal lattice with 8 columns and 8 rows per tile: rows are √3/2 apart only
    // approximately, which keeps the lattice periodic in both directions.
    const COLS: f32 = 8.0;
    const ROWS: f32 = 8.0;
    let radius = 0.45 / COLS;
    let mut best = f32::MAX;
    let row = (v * ROWS).floor();
    for dr in -1..=1 {
        let r = row + dr as f32;
        let shift = if (r as i32).rem_euclid(2) == 1 { 0.5 } else { 0.0 };
        let cy = (r + 0.5) / ROWS;
        let col = (u * COLS - shift).floor();
        for dc in -1..=1 {
            let cx = (col + dc as f32 + shift + 0.5) / COLS;
            let d2 = (u - cx).powi(2) + ((v - cy) * COLS / ROWS).powi(2);
            best = best.min(d2);
        }
    }
    let d = best.sqrt() / radius;
    if d >= 1.0 { 1.0 } else { 1.0 - 0.6 * (1.0 - d * d).sqrt() }
}

/// Tileable value noise: a `period`×`period` lattice of hashed values, bicubically smoothed.
#[derive(Clone, Copy, Debug)]
struct ValueNoise {
    seed: u64,
    period: u32,
}

impl ValueNoise {
    fn new(seed: u64, period: u32) -> Self {
        Self { seed, period }
    }

    fn lattice(&self, x: i64, y: i64, octave: u32) -> f32 {
        let p = (self.period << octave) as i64;
        let (x, y) = (x.rem_euclid(p) as u64, y.rem_euclid(p) as u64);
        (hash(x | (y << 24) | ((octave as u64) << 48), self.seed) >> 40) as f32 / (1u64 << 24) as f32
    }

    fn at(&self, u: f32, v: f32, octave: u32) -> f32 {
        let scale = (self.period << octave) as f32;
        let (x, y) = (u * scale, v * scale);
        let (x0, y0) = (x.floor(), y.floor());
        let smooth = |t: f32| t * t * (3.0 - 2.0 * t);
        let (sx, sy) = (smooth(x - x0), smooth(y - y0));
        let (ix, iy) = (x0 as i64, y0 as i64);
        let a = self.lattice(ix, iy, octave);
        let b = self.lattice(ix + 1, iy, octave);
        let c = self.lattice(ix, iy + 1, octave);
        let d = self.lattice(ix + 1, iy + 1, octave);
        let top = a + (b - a) * sx;
        let bottom = c + (d - c) * sx;
        top + (bottom - top) * sy
    }

    /// Sum of `octaves` octaves with halving amplitude, normalized to [0, 1].
    fn fractal(&self, u: f32, v: f32, octaves: u32) -> f32 {
        let (mut sum, mut amp, mut total) = (0.0, 1.0, 0.0);
        for o in 0..octaves {
            sum += amp * self.at(u, v, o);
            total += amp;
            amp *= 0.5;
        }
        sum / total
    }
}

/// SplitMix64 of `x` mixed with `seed` ([`crate::hash::splitmix64`]).
fn hash(x: u64, seed: u64) -> u64 {
    crate::hash::splitmix64(x.wrapping_add(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_parse_and_stay_in_range() {
        for spec in ["bricks", "PINWHEEL", "dimples", "noise:42", "noise"] {
            let preset = HeightPreset::parse(spec).unwrap_or_else(|| panic!("{spec} did not parse"));
            let field = preset.render(64, 48);
            let (lo, hi) = field.to_f32().iter().fold((f32::MAX, f32::MIN), |(lo, hi), &h| (lo.min(h), hi.max(h)));
            assert!(lo >= 0.0 && hi <= 1.0, "{spec}: heights must be in [0,1], got [{lo}, {hi}]");
            assert!(hi - lo > 0.1, "{spec}: a preset must not be flat, range {lo}..{hi}");
        }
        assert_eq!(HeightPreset::parse("noise:x"), None);
        assert_eq!(HeightPreset::parse("brick"), None);
    }

    #[test]
    fn bricks_have_recessed_mortar() {
        let f = HeightPreset::Bricks.render(256, 256);
        // Row 0 lies in the mortar joint between brick rows; the middle of a brick row is raised.
        let mortar = f.get(40, 0);
        let brick = f.get(40, 16);
        assert!(mortar + 0.4 < brick, "mortar {mortar} must be well below brick {brick}");
    }

    #[test]
    fn noise_depends_on_the_seed_and_tiles() {
        let a = HeightPreset::Noise(1).render(32, 32);
        let b = HeightPreset::Noise(2).render(32, 32);
        assert_ne!(a, b);
        // Tiling: the noise lattice has an integer period, so the value at u and u+1 agree.
        let n = ValueNoise::new(5, 8);
        assert!((n.fractal(0.1, 0.3, 4) - n.fractal(1.1, 1.3, 4)).abs() < 1e-5);
    }
}
