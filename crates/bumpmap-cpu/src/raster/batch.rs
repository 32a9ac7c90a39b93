//! A batch of 2×2 quads in structure-of-arrays lanes, as the rasterizer fills it and a
//! [`FragmentShader`] shades it: the live lanes listed once, and any per-lane values packed at
//! them (a gather where AVX2 is compiled in, a loop otherwise).
//!
//! What this module does not do: fill a batch (the quad loop in `raster.rs` does) or write its
//! colours back (`write_back.rs`).

use bumpmap_core::vertex::MAX_VARYINGS;

use super::QUADS;
use crate::combiners::{LANES, Lanes};
use crate::framebuffer::TILE;

/// Fragments of up to [`QUADS`] 2×2 quads in structure-of-arrays lanes: lane `4q + k` is pixel
/// k of quad q, k = 0 (x, y), 1 (x+1, y), 2 (x, y+1), 3 (x+1, y+1). Helper lanes (outside the
/// triangle) carry varyings for derivatives; the shader computes colours for the live lanes
/// only, listed in [`FragmentBatch::live`].
pub struct FragmentBatch {
    pub quads: usize,
    pub varyings: [Lanes; MAX_VARYINGS],
    pub depth: Lanes,
    /// Which pixels of each quad are covered by the triangle, inside the frame, and pass the
    /// depth test (bits 0–3 = k).
    pub(super) quad_live: [u8; QUADS],
    /// The live lanes in order, then slack so that 8 indices can always be read at once.
    live: [u8; LANES + 8],
    pub(super) live_count: usize,
    /// Tile-local index (`y · width + x`) of each quad's pixel 0.
    pub(super) corner: [u16; QUADS],
    /// Tile-local index of each live fragment's pixel, in the order of `live` (with its slack).
    pub(super) pixel: [u16; LANES + 8],
}

/// Four u16 as one integer (memory order), so that adding `x · 0x0001_0001_0001_0001` adds x
/// to each while no sum exceeds `u16::MAX`.
fn pack_u16x4(v: [u16; 4]) -> u64 {
    let b = v.map(u16::to_ne_bytes);
    u64::from_ne_bytes([b[0][0], b[0][1], b[1][0], b[1][1], b[2][0], b[2][1], b[3][0], b[3][1]])
}

/// The inverse of [`pack_u16x4`].
fn unpack_u16x4(v: u64) -> [u16; 4] {
    let b = v.to_ne_bytes();
    [[b[0], b[1]], [b[2], b[3]], [b[4], b[5]], [b[6], b[7]]].map(u16::from_ne_bytes)
}

// Tile-local pixel indices fit the batch's u16 fields.
const _: () = assert!(TILE * TILE <= 1 << 16);

/// For each 4-bit live mask, the pixels it holds in order (unused entries 0) and their count.
const MASK_LANES: [([u8; 4], usize); 16] = {
    let mut table = [([0u8; 4], 0usize); 16];
    let mut m = 0;
    while m < 16 {
        let mut n = 0;
        let mut k = 0;
        while k < 4 {
            if m & (1 << k) != 0 {
                table[m].0[n] = k as u8;
                n += 1;
            }
            k += 1;
        }
        table[m].1 = n;
        m += 1;
    }
    table
};

impl FragmentBatch {
    pub(super) fn new() -> Box<Self> {
        Box::new(Self {
            quads: 0,
            varyings: [[0.0; LANES]; MAX_VARYINGS],
            depth: [0.0; LANES],
            quad_live: [0; QUADS],
            live: [0; LANES + 8],
            live_count: 0,
            corner: [0; QUADS],
            pixel: [0; LANES + 8],
        })
    }

    /// Number of lanes in use (`4 · quads`), helpers included.
    pub fn lanes(&self) -> usize {
        4 * self.quads
    }

    /// The live lanes, in order: fragment j of the batch is lane `live()[j]`.
    pub fn live(&self) -> &[u8] {
        &self.live[..self.live_count]
    }

    /// Lists the live lanes and their pixels from the quads' masks (before shading); `width`
    /// is the tile's.
    pub(super) fn list_live(&mut self, width: usize) {
        // For each mask, where its pixels lie relative to the quad's pixel 0.
        let step = [0, 1, width as u16, width as u16 + 1];
        let offsets: [u64; 16] = std::array::from_fn(|m| pack_u16x4(MASK_LANES[m].0.map(|k| step[k as usize])));
        let mut n = 0;
        for q in 0..self.quads {
            let mask = self.quad_live[q] as usize;
            let (lanes, count) = MASK_LANES[mask];
            // Four entries written, `count` kept: the slack after LANES absorbs the rest. The
            // additions are lane by lane within one integer (no lane can carry: lane indices
            // stay below 256, pixel indices below 2¹⁶).
            let lanes = u32::from_ne_bytes(lanes) + (4 * q as u32) * 0x0101_0101;
            self.live[n..n + 4].copy_from_slice(&lanes.to_ne_bytes());
            let pixels = offsets[mask] + self.corner[q] as u64 * 0x0001_0001_0001_0001;
            self.pixel[n..n + 4].copy_from_slice(&unpack_u16x4(pixels));
            n += count;
        }
        self.live_count = n;
    }

    /// `dst[j] = varyings[slot][live()[j]]`: one varying at the live lanes, packed. Entries
    /// from `live().len()` up to the next multiple of eight may be overwritten.
    #[inline]
    pub fn pack(&self, slot: usize, dst: &mut Lanes) {
        self.pack_lanes(&self.varyings[slot], dst);
    }

    /// `dst[j] = src[live()[j]]` for any per-lane values, as [`FragmentBatch::pack`].
    #[inline]
    pub fn pack_lanes(&self, src: &Lanes, dst: &mut Lanes) {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
        {
            use std::arch::x86_64::*;
            for j in (0..self.live_count).step_by(8) {
                // SAFETY: AVX2 is enabled at compile time (the cfg); `live` has 8 readable
                // bytes from j (its slack), every entry is a lane index < LANES, and j + 8 ≤
                // LANES because LANES is a multiple of 8.
                unsafe {
                    let idx = _mm256_cvtepu8_epi32(_mm_loadl_epi64(self.live.as_ptr().add(j).cast()));
                    let v = _mm256_i32gather_ps::<4>(src.as_ptr(), idx);
                    _mm256_storeu_ps(dst.as_mut_ptr().add(j), v);
                }
            }
        }
        #[cfg(not(all(target_arch = "x86_64", target_feature = "avx2")))]
        for (d, &lane) in dst.iter_mut().zip(self.live()) {
            *d = src[lane as usize];
        }
    }
}

/// Computes fragment colours for a batch. Implemented by the techniques' pixel stages.
pub trait FragmentShader: Sync {
    /// Per-thread working memory (register files, temporaries), made once per tile task.
    type Scratch: Send;
    fn scratch(&self) -> Self::Scratch;
    /// Writes the RGBA of live fragment j (lane `batch.live()[j]`) into `out[..][j]`.
    fn shade(&self, batch: &FragmentBatch, scratch: &mut Self::Scratch, out: &mut [Lanes; 4]);
    /// Whether [`FragmentShader::depth`] gives each fragment's depth (`gl_FragDepth`): the depth
    /// test then runs after shading, on that depth. Such a shader's depth is never nearer than
    /// the triangle's, so a fragment the triangle's depth already fails under LESS or LEQUAL is
    /// dropped before shading.
    fn writes_depth(&self) -> bool {
        false
    }
    /// After [`FragmentShader::shade`]: live fragment j's window depth, NaN for a fragment
    /// discarded; `None` when the shader does not write depth.
    fn depth<'a>(&self, _scratch: &'a Self::Scratch) -> Option<&'a Lanes> {
        None
    }
}
