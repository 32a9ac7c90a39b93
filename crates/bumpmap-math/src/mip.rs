//! Normal-map mip chains that stay correct at a distance (Kilgard §2.4.2, §2.6.3, §5.3, App. F).
//!
//! Every texel of level k holds, in RGB, the normalized mean of the level-0 unit normals it
//! covers (Eq. 14 renormalized) and, in A, the length of that mean: the "descaling factor" that
//! brings back the dimming of bumpy surfaces for diffuse light (Eq. 15). Sums stay in single
//! precision from level 0 down to 1×1 and each level is quantized once, unlike Appendix F,
//! which re-expands its own bytes at every level (and only works for square maps).
//!
//! Any size works. Each level halves (rounding down, never below 1) like OpenGL's mip sizes;
//! texel i of the next level covers texels 2i and 2i+1, and where the size is odd the last
//! texel also takes the odd one out (2i+2). Every level-0 texel is thus counted exactly once at
//! every level and footprints are 2 or 3 texels wide. Level 0 is computed in the same pass that
//! sums level 1, so the height field is read once.

use glam::Vec3;
use rayon::prelude::*;

use crate::encoding::{Encoding, Texel};
use crate::height::HeightField;
use crate::image::{Image, Rgba8Mips};
use crate::normalmap::{NormalMapError, NormalMapOptions, RowEvaluator, RowScratch, encode_unit, output_size};

/// What the RGB and A of levels below 0 hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum MipMode {
    /// RGB = normalized mean, A = its length (Kilgard §5.3): the paper's, and ours by default.
    #[default]
    LengthInAlpha,
    /// RGB = normalized mean, A = 255: what most tools do. Diffuse then stays too bright.
    Renormalize,
}

crate::named!(MipMode {
    LengthInAlpha => "length-in-alpha": "RGB = normalized mean of the covered normals, A = its length (Kilgard §5.3)",
    Renormalize => "renormalize": "RGB = normalized mean, A = 255: what most tools do (too bright at a distance)",
});

/// Level 0 and every smaller level down to 1×1 (a chain imported with a file's own levels may
/// stop earlier), 8 bits per channel unless `T` says 16.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MipChain<T = [u8; 4]> {
    /// Level 0 first.
    pub levels: Vec<Image<T>>,
    /// How the directions are stored.
    pub encoding: Encoding,
}

pub use crate::levels::{footprint, level_count, next_size};

/// One row of sums in structure-of-arrays form, so adding and encoding run as SIMD lanes.
#[derive(Default)]
pub(crate) struct RowSums {
    x: Vec<f32>,
    y: Vec<f32>,
    z: Vec<f32>,
}

impl RowSums {
    fn reset(&mut self, n: usize) {
        for v in [&mut self.x, &mut self.y, &mut self.z] {
            v.clear();
            v.resize(n, 0.0);
        }
    }
}

/// Adds a row of `n` vectors (SoA) into the next level's row of `next_size(n)`: columns 2i and
/// 2i+1 into texel i, the odd last column into the last texel.
fn add_pairs(src: [&[f32]; 3], dst: &mut RowSums) {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        #[target_feature(enable = "avx2")]
        unsafe fn avx2(src: [&[f32]; 3], dst: &mut RowSums) {
            add_pairs_generic(src, dst)
        }
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { avx2(src, dst) };
    }
    add_pairs_generic(src, dst)
}

#[inline(always)]
fn add_pairs_generic(src: [&[f32]; 3], dst: &mut RowSums) {
    let n = src[0].len();
    let m = next_size(n);
    for (s, d) in src.into_iter().zip([&mut dst.x, &mut dst.y, &mut dst.z]) {
        let d = &mut d[..m];
        if n == 1 {
            d[0] += s[0];
            continue;
        }
        for (o, pair) in d.iter_mut().zip(s.chunks_exact(2)) {
            *o += pair[0] + pair[1];
        }
        if n % 2 == 1 {
            d[m - 1] += s[n - 1];
        }
    }
}

/// Encodes a mean of unit vectors, given their sum and the reciprocal of their count: its
/// direction in RGB (straight up if it vanished, as Appendix F does) and its length in A.
#[inline(always)]
pub fn encode_mean<T: Texel>(sum: Vec3, inv_count: f32, mode: MipMode, enc: Encoding) -> T {
    let mean = sum * inv_count;
    let len = mean.length();
    let inv = if len > 0.0 { 1.0 / len } else { 0.0 };
    let z = if len > 0.0 { mean.z * inv } else { 1.0 };
    let a = match mode {
        MipMode::LengthInAlpha => len,
        MipMode::Renormalize => 1.0,
    };
    T::pack(mean.x * inv, mean.y * inv, z, a, enc)
}

/// The size of every level and, per level, the reciprocal of how many level-0 columns each
/// texel column covers and how many level-0 rows each texel row covers.
struct Shape {
    w: Vec<usize>,
    h: Vec<usize>,
    inv_cols: Vec<Vec<f32>>,
    rows: Vec<Vec<u32>>,
}

impl Shape {
    fn new(w0: usize, h0: usize) -> Self {
        let (mut w, mut h) = (vec![w0], vec![h0]);
        let (mut cols, mut rows) = (vec![vec![1u32; w0]], vec![vec![1u32; h0]]);
        let fold = |counts: &[u32]| -> Vec<u32> {
            (0..next_size(counts.len())).map(|i| footprint(i, counts.len()).map(|k| counts[k]).sum()).collect()
        };
        while *w.last().unwrap() > 1 || *h.last().unwrap() > 1 {
            cols.push(fold(cols.last().unwrap()));
            rows.push(fold(rows.last().unwrap()));
            w.push(next_size(*w.last().unwrap()));
            h.push(next_size(*h.last().unwrap()));
        }
        let inv_cols = cols.iter().map(|c| c.iter().map(|&n| 1.0 / n as f32).collect()).collect();
        Self { w, h, inv_cols, rows }
    }

    fn levels(&self) -> usize {
        self.w.len()
    }

    fn inv_count(&self, k: usize, i: usize, j: usize) -> f32 {
        self.inv_cols[k][i] * (1.0 / self.rows[k][j] as f32)
    }
}

/// Encodes one row of level-k sums into bytes.
fn encode_sums_row<T: Texel>(
    acc: &RowSums,
    shape: &Shape,
    k: usize,
    j: usize,
    mode: MipMode,
    enc: Encoding,
    out: &mut [T],
) {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        #[target_feature(enable = "avx2")]
        unsafe fn avx2<T: Texel>(
            acc: &RowSums,
            shape: &Shape,
            k: usize,
            j: usize,
            mode: MipMode,
            enc: Encoding,
            out: &mut [T],
        ) {
            encode_sums_row_generic(acc, shape, k, j, mode, enc, out)
        }
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { avx2(acc, shape, k, j, mode, enc, out) };
    }
    encode_sums_row_generic(acc, shape, k, j, mode, enc, out)
}

#[inline(always)]
fn encode_sums_row_generic<T: Texel>(
    acc: &RowSums,
    shape: &Shape,
    k: usize,
    j: usize,
    mode: MipMode,
    enc: Encoding,
    out: &mut [T],
) {
    let inv_row = 1.0 / shape.rows[k][j] as f32;
    let n = out.len();
    let (x, y, z, ic) = (&acc.x[..n], &acc.y[..n], &acc.z[..n], &shape.inv_cols[k][..n]);
    for i in 0..n {
        out[i] = encode_mean(Vec3::new(x[i], y[i], z[i]), ic[i] * inv_row, mode, enc);
    }
}

/// What an [`OutOfMemory`](crate::buffer::OutOfMemory) error calls level 0 and the others.
const LEVEL_NAMES: [&str; 2] = ["the mip chain's level 0", "a level of the mip chain"];

/// How many levels are computed while streaming through row bands: level `K` is the deepest
/// whose rows are bands, so every level above it is written in the same pass as level 0.
const STREAMED_LEVELS: usize = 5;

/// Per-thread state of the streaming pass: the derivative row and one row of sums per level.
#[derive(Default)]
struct BandScratch {
    row: RowScratch,
    acc: Vec<RowSums>,
}

/// One band: its slice of rows in each streamed level and the first row index of each slice.
struct Band<'a, T> {
    out: Vec<&'a mut [T]>,
    first: Vec<usize>,
}

struct Streamer<'a> {
    eval: RowEvaluator<'a>,
    shape: &'a Shape,
    mode: MipMode,
    enc: Encoding,
}

impl Streamer<'_> {
    /// Computes row `r` of level `k` and everything under it, then adds it into level k+1.
    fn process<T: Texel>(&self, band: &mut Band<T>, scratch: &mut BandScratch, k: usize, r: usize, top: &mut [Vec3]) {
        let (w, last) = (self.shape.w[k], band.out.len() - 1);
        let local = r - band.first[k];
        let out = &mut band.out[k][local * w..(local + 1) * w];
        if k == 0 {
            self.eval.process_row(r, &mut scratch.row, out);
            if last > 0 {
                let row = &scratch.row;
                add_pairs([&row.nx[..w], &row.ny[..w], &row.nz[..w]], &mut scratch.acc[1]);
            }
            return;
        }
        scratch.acc[k].reset(w);
        for child in footprint(r, self.shape.h[k - 1]) {
            self.process(band, scratch, k - 1, child, top);
        }
        let out = &mut band.out[k][local * w..(local + 1) * w];
        encode_sums_row(&scratch.acc[k], self.shape, k, r, self.mode, self.enc, out);
        if k < last {
            let (lo, hi) = scratch.acc.split_at_mut(k + 1);
            let a = &lo[k];
            add_pairs([&a.x[..w], &a.y[..w], &a.z[..w]], &mut hi[0]);
        } else {
            let a = &scratch.acc[k];
            for (i, t) in top.iter_mut().enumerate() {
                *t = Vec3::new(a.x[i], a.y[i], a.z[i]);
            }
        }
    }
}

impl<T: Texel> MipChain<T> {
    /// Builds level 0 from the height field and every level below it.
    ///
    /// Level 0 and the next few levels are made in one pass over row bands, one band per row
    /// of the deepest streamed level, in parallel; the remaining small levels are reduced from
    /// that level's sums.
    pub fn from_height(field: &HeightField, options: &NormalMapOptions, mode: MipMode) -> Result<Self, NormalMapError> {
        let (w0, h0) = output_size(field.width(), field.height(), options)?;
        let shape = Shape::new(w0, h0);
        let deepest = STREAMED_LEVELS.min(shape.levels() - 1);
        let mut bytes: Vec<Vec<T>> = (0..shape.levels())
            .map(|k| crate::buffer::try_zeroed::<T>(shape.w[k] * shape.h[k], LEVEL_NAMES[k.min(1)]))
            .collect::<Result<_, _>>()?;
        let streamer =
            Streamer { eval: RowEvaluator::new(field, *options)?, shape: &shape, mode, enc: options.encoding };

        // Split each streamed level into per-band row slices.
        let bands_n = shape.h[deepest];
        let mut bands: Vec<Band<T>> = (0..bands_n).map(|_| Band { out: Vec::new(), first: Vec::new() }).collect();
        for (k, level) in bytes.iter_mut().enumerate().take(deepest + 1) {
            let mut rest = level.as_mut_slice();
            for (j, band) in bands.iter_mut().enumerate() {
                let rows = rows_of_band(&shape, deepest, j, k);
                let (head, tail) = rest.split_at_mut(rows.len() * shape.w[k]);
                band.out.push(head);
                band.first.push(rows.start);
                rest = tail;
            }
        }
        let mut top = vec![Vec3::ZERO; shape.w[deepest] * bands_n];
        bands.into_par_iter().zip(top.par_chunks_mut(shape.w[deepest])).enumerate().for_each_init(
            || BandScratch { row: RowScratch::default(), acc: (0..=deepest).map(|_| RowSums::default()).collect() },
            |scratch, (j, (mut band, top))| streamer.process(&mut band, scratch, deepest, j, top),
        );

        // The small levels: reduce the deepest streamed level's sums, level by level.
        reduce_levels(&shape, deepest, top, &mut bytes, mode, options.encoding).map_err(NormalMapError::OutOfMemory)?;
        let levels = bytes
            .into_iter()
            .enumerate()
            .map(|(k, texels)| Image { width: shape.w[k], height: shape.h[k], texels })
            .collect();
        Ok(Self { levels, encoding: options.encoding })
    }

    /// A chain from level-0 unit normals given directly (an object-space normal map, say), with
    /// the same averaging and encoding as [`MipChain::from_height`]. Panics if
    /// `normals.len() != width·height` or a dimension is zero.
    pub fn from_normals(width: usize, height: usize, normals: &[Vec3], encoding: Encoding, mode: MipMode) -> Self {
        Self::try_from_normals(width, height, normals, encoding, mode).unwrap_or_else(|e| {
            std::alloc::handle_alloc_error(
                std::alloc::Layout::from_size_align(e.bytes as usize, 16).unwrap_or(std::alloc::Layout::new::<Vec3>()),
            )
        })
    }

    /// [`MipChain::from_normals`] whose buffers sized by the input are asked for fallibly: an
    /// [`OutOfMemory`](crate::buffer::OutOfMemory) naming the one that would not fit, rather
    /// than an abort.
    pub fn try_from_normals(
        width: usize,
        height: usize,
        normals: &[Vec3],
        encoding: Encoding,
        mode: MipMode,
    ) -> Result<Self, crate::buffer::OutOfMemory> {
        assert!(width > 0 && height > 0 && normals.len() == width * height, "{width}x{height} normals");
        let shape = Shape::new(width, height);
        let mut bytes: Vec<Vec<T>> = (0..shape.levels())
            .map(|k| crate::buffer::try_zeroed::<T>(shape.w[k] * shape.h[k], "a mip level"))
            .collect::<Result<_, _>>()?;
        for (texel, &n) in bytes[0].iter_mut().zip(normals) {
            *texel = encode_unit(n, encoding);
        }
        let mut sums = Vec::new();
        sums.try_reserve_exact(normals.len())
            .map_err(|_| crate::buffer::OutOfMemory::of::<Vec3>("the sums of level 0's normals", normals.len()))?;
        sums.extend_from_slice(normals);
        reduce_levels(&shape, 0, sums, &mut bytes, mode, encoding)?;
        let levels = bytes
            .into_iter()
            .enumerate()
            .map(|(k, texels)| Image { width: shape.w[k], height: shape.h[k], texels })
            .collect();
        Ok(Self { levels, encoding })
    }

    /// Number of levels: `1 + floor(log2(max(w, h)))`.
    pub fn len(&self) -> usize {
        self.levels.len()
    }

    /// Whether the chain has no level (never, for one this crate made).
    pub fn is_empty(&self) -> bool {
        self.levels.is_empty()
    }
}

impl MipChain {
    /// The levels as a texture (a copy): what a scene's material holds.
    pub fn to_mips(&self) -> Rgba8Mips {
        Rgba8Mips::from_levels(self.levels.clone())
    }

    /// The levels as a texture, moved rather than copied (the encoding is dropped).
    pub fn into_mips(self) -> Rgba8Mips {
        Rgba8Mips::from_levels(self.levels)
    }

    /// The chain as [`MipMode::Renormalize`] stores it: the same directions with A = 1 on every
    /// level (RGB already holds the normalized mean).
    pub fn with_opaque_alpha(&self) -> MipChain {
        let levels = self
            .levels
            .iter()
            .map(|l| Image {
                width: l.width,
                height: l.height,
                texels: l.texels.iter().map(|&[r, g, b, _]| [r, g, b, 255]).collect(),
            })
            .collect();
        MipChain { levels, encoding: self.encoding }
    }
}

/// Fills `bytes[k]` for every level below `from`, reducing `sums` (level `from`'s sums of unit
/// normals) one level at a time.
fn reduce_levels<T: Texel>(
    shape: &Shape,
    from: usize,
    sums: Vec<Vec3>,
    bytes: &mut [Vec<T>],
    mode: MipMode,
    enc: Encoding,
) -> Result<(), crate::buffer::OutOfMemory> {
    let (mut sums, mut w, mut h) = (sums, shape.w[from], shape.h[from]);
    for (k, level) in bytes.iter_mut().enumerate().skip(from + 1) {
        let (nw, nh) = (shape.w[k], shape.h[k]);
        let mut next = Vec::new();
        next.try_reserve_exact(nw * nh)
            .map_err(|_| crate::buffer::OutOfMemory::of::<Vec3>("a mip level's sums", nw * nh))?;
        next.resize(nw * nh, Vec3::ZERO);
        for j in 0..nh {
            for sy in footprint(j, h) {
                for i in 0..nw {
                    for sx in footprint(i, w) {
                        next[j * nw + i] += sums[sy * w + sx];
                    }
                }
            }
            for i in 0..nw {
                level[j * nw + i] = encode_mean(next[j * nw + i], shape.inv_count(k, i, j), mode, enc);
            }
        }
        (sums, w, h) = (next, nw, nh);
    }
    Ok(())
}

/// The rows of level `k` under row `j` of level `deepest` (footprints composed downward).
fn rows_of_band(shape: &Shape, deepest: usize, j: usize, k: usize) -> std::ops::Range<usize> {
    let mut rows = j..j + 1;
    for level in (k..deepest).rev() {
        let h = shape.h[level];
        rows = footprint(rows.start, h).start..footprint(rows.end - 1, h).end;
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::height::HeightPreset;
    use crate::kernel::Kernel;
    use crate::normalmap::normal_map_level0;

    fn chain(field: &HeightField, mode: MipMode) -> MipChain {
        MipChain::<[u8; 4]>::from_height(field, &NormalMapOptions::default(), mode).unwrap()
    }

    #[test]
    fn flat_field_is_up_with_full_length_at_every_level() {
        for (w, h) in [(16, 16), (13, 7), (1, 9), (5, 1)] {
            let c = chain(&HeightField::from_fn(w, h, |_, _| 0.5), MipMode::LengthInAlpha);
            assert_eq!(c.len(), 1 + (w.max(h) as f32).log2().floor() as usize, "{w}x{h}");
            for (k, level) in c.levels.iter().enumerate() {
                assert!(level.texels.iter().all(|&t| t == [128, 128, 255, 255]), "{w}x{h} level {k}");
            }
            assert_eq!((c.levels.last().unwrap().width, c.levels.last().unwrap().height), (1, 1));
        }
    }

    #[test]
    fn dimpled_field_dims_in_the_smaller_levels() {
        // Kilgard §2.4.2: averaging bumpy unit normals shortens them, so A < 1 in smaller levels
        // while a flat map keeps A = 1. The dimples are 32 texels across at 256², so by level 5
        // every texel averages whole dimples.
        let steep = NormalMapOptions { scale: 16.0, ..Default::default() };
        let dimples = HeightPreset::Dimples.render(256, 256);
        let c = MipChain::<[u8; 4]>::from_height(&dimples, &steep, MipMode::LengthInAlpha).unwrap();
        let mean_alpha = |k: usize| {
            let l = &c.levels[k];
            l.texels.iter().map(|t| t[3] as f32).sum::<f32>() / l.texels.len() as f32
        };
        assert_eq!(mean_alpha(0), 255.0);
        assert!(mean_alpha(5) < 235.0, "level 5 mean alpha {}", mean_alpha(5));
        assert!(mean_alpha(5) < mean_alpha(1), "dimming grows with the footprint");
        let renorm = MipChain::<[u8; 4]>::from_height(&dimples, &steep, MipMode::Renormalize).unwrap();
        assert!(renorm.levels[5].texels.iter().all(|t| t[3] == 255));
        assert_eq!(
            renorm.levels[5].texels.iter().map(|t| [t[0], t[1], t[2]]).collect::<Vec<_>>(),
            c.levels[5].texels.iter().map(|t| [t[0], t[1], t[2]]).collect::<Vec<_>>()
        );
    }

    #[test]
    fn every_level_is_the_mean_of_the_level0_normals_it_covers() {
        // Odd, non-square, non-power-of-two: 11×6 → 5×3 → 2×1 → 1×1. Compare with a brute-force
        // mean over the footprint composed level by level.
        let field = HeightPreset::Noise(3).render(11, 6);
        let opts = NormalMapOptions { kernel: Kernel::Sobel3, scale: 8.0, ..Default::default() };
        let c = MipChain::<[u8; 4]>::from_height(&field, &opts, MipMode::LengthInAlpha).unwrap();
        let sizes: Vec<_> = c.levels.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, vec![(11, 6), (5, 3), (2, 1), (1, 1)]);
        let eval = RowEvaluator::new(&field, opts).unwrap();
        let mut normals = vec![Vec3::ZERO; 66];
        let mut scratch = RowScratch::default();
        for y in 0..6 {
            eval.row(y, &mut scratch, |x, n| normals[y * 11 + x] = n);
        }
        // Level-0 columns and rows covered by each texel, composed through the levels.
        let mut cols: Vec<Vec<usize>> = (0..11).map(|i| vec![i]).collect();
        let mut rows: Vec<Vec<usize>> = (0..6).map(|i| vec![i]).collect();
        for level in &c.levels[1..] {
            let merge = |v: &Vec<Vec<usize>>| {
                (0..next_size(v.len())).map(|i| footprint(i, v.len()).flat_map(|k| v[k].clone()).collect()).collect()
            };
            cols = merge(&cols);
            rows = merge(&rows);
            for (j, rs) in rows.iter().enumerate() {
                for (i, cs) in cols.iter().enumerate() {
                    let mut mean = Vec3::ZERO;
                    for &y in rs {
                        for &x in cs {
                            mean += normals[y * 11 + x];
                        }
                    }
                    let want: [u8; 4] =
                        encode_mean(mean, 1.0 / (rs.len() * cs.len()) as f32, MipMode::LengthInAlpha, c.encoding);
                    // The brute-force sum adds in another order; f32 rounding may move a value
                    // across a byte boundary, never by more than one step.
                    let got = level.texel(i, j);
                    assert!(got.iter().zip(want).all(|(&g, w)| g.abs_diff(w) <= 1), "{got:?} vs {want:?}");
                }
            }
        }
        assert_eq!(c.levels[0], normal_map_level0(&field, &opts).unwrap());
    }

    #[test]
    fn sixteen_bit_chain_is_the_eight_bit_chain_with_more_bits() {
        // One code path makes both depths: every channel of every level of the 16-bit chain
        // rounds to the 8-bit chain's byte, within one step (the two round at different places).
        let field = HeightPreset::Bricks.render(37, 20);
        let opts = NormalMapOptions { scale: 6.0, ..Default::default() };
        let c8 = MipChain::<[u8; 4]>::from_height(&field, &opts, MipMode::LengthInAlpha).unwrap();
        let c16 = MipChain::<[u16; 4]>::from_height(&field, &opts, MipMode::LengthInAlpha).unwrap();
        assert_eq!(c8.len(), c16.len());
        let mut finer = 0;
        for (l8, l16) in c8.levels.iter().zip(&c16.levels) {
            assert_eq!((l8.width, l8.height), (l16.width, l16.height));
            for (a, b) in l8.texels.iter().zip(&l16.to_rgba8().texels) {
                assert!(a.iter().zip(b).all(|(x, y)| x.abs_diff(*y) <= 1), "{a:?} vs {b:?}");
            }
            finer += l16.texels.iter().filter(|t| t[0] % 257 != 0).count();
        }
        assert!(finer > 0, "16-bit texels hold values no byte can");
        assert!(c16.levels[0].texels.iter().all(|t| t[3] == u16::MAX));
    }
}
