//! Triangle rasterization: clipping in homogeneous space, fixed-point setup with a top-left
//! fill rule, binning into the framebuffer's tiles, and 2×2 quads shaded in batches.
//!
//! What a GL 1.2 implementation guarantees and this one keeps: no gaps or double hits along
//! shared edges (integer edge functions on 1/256-pixel snapped vertices, top-left rule);
//! perspective-correct varyings; window depth interpolated linearly in screen space and
//! computed identically for identical vertices, so `DepthFunc::Equal` holds across passes;
//! near-plane (and far-plane) clipping; back-face culling. Pixel centres are at half-integers.
//! Quads include helper pixels outside the triangle so a shader can take derivatives (λ) once
//! per quad. Not done: line and point primitives, polygon offset, scissor, stencil.

use glam::Vec4;
use rayon::prelude::*;

use crate::combiners::{LANES, Lanes};
use crate::framebuffer::{Blend, DepthFunc, Framebuffer, TILE, Tile, to_byte};

/// Varyings per vertex (texture coordinates, light and half-angle vectors, …).
pub const MAX_VARYINGS: usize = 24;
/// Quads per shading batch.
pub const QUADS: usize = LANES / 4;

/// A vertex after the vertex stage: clip-space position and its varyings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex {
    pub clip: Vec4,
    pub varyings: [f32; MAX_VARYINGS],
}

/// Fixed-function state of one draw call.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawState {
    pub depth_func: DepthFunc,
    pub depth_write: bool,
    pub blend: Blend,
    /// `glColorMask(r, g, b, a)`.
    pub color_mask: [bool; 4],
    pub cull_back: bool,
    /// How many varyings (from slot 0) the shader reads; only these are interpolated.
    pub varyings: usize,
}

impl DrawState {
    /// Depth LESS with writes, no blending, back faces culled: an ordinary first pass.
    pub const OPAQUE: DrawState = DrawState {
        depth_func: DepthFunc::Less,
        depth_write: true,
        blend: Blend::REPLACE,
        color_mask: [true; 4],
        cull_back: true,
        varyings: MAX_VARYINGS,
    };
}

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
    quad_live: [u8; QUADS],
    /// The live lanes in order, then slack so that 8 indices can always be read at once.
    live: [u8; LANES + 8],
    live_count: usize,
    origin: [(u16, u16); QUADS],
}

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
    fn new() -> Box<Self> {
        Box::new(Self {
            quads: 0,
            varyings: [[0.0; LANES]; MAX_VARYINGS],
            depth: [0.0; LANES],
            quad_live: [0; QUADS],
            live: [0; LANES + 8],
            live_count: 0,
            origin: [(0, 0); QUADS],
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

    /// Lists the live lanes from the quads' masks (before shading).
    fn list_live(&mut self) {
        let mut n = 0;
        for q in 0..self.quads {
            let (pixels, count) = MASK_LANES[self.quad_live[q] as usize];
            let base = 4 * q as u8;
            // Four bytes written, `count` kept: the slack after LANES absorbs the rest.
            self.live[n..n + 4].copy_from_slice(&pixels.map(|k| base + k));
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
}

const SUBPIXEL_BITS: u32 = 8;
const SUBPIXEL: f32 = (1 << SUBPIXEL_BITS) as f32;
/// Guard band: x and y are clipped at ±GUARD·w, keeping fixed-point products within i64.
const GUARD: f32 = 8.0;

/// A triangle ready to rasterize.
struct Setup {
    x: [i64; 3],
    y: [i64; 3],
    bias: [i64; 3],
    inv_area: f32,
    z: [f32; 3],
    inv_w: [f32; 3],
    /// Where this triangle's varyings start in its chunk's `var_w`.
    var: usize,
    bbox: [usize; 4],
}

/// The triangles set up from one run of the index list, with their varyings divided by w:
/// `var_w[s.var + j]` holds varying j at the three vertices. Only the varyings the draw reads
/// are kept, so a frame's set-up data stays small.
#[derive(Default)]
struct SetupChunk {
    setups: Vec<Setup>,
    var_w: Vec<[f32; 3]>,
}

impl Setup {
    /// Edge function of the edge from vertex a to vertex b at fixed-point (px, py).
    #[inline(always)]
    fn edge(&self, a: usize, b: usize, px: i64, py: i64) -> i64 {
        (self.x[b] - self.x[a]) * (py - self.y[a]) - (self.y[b] - self.y[a]) * (px - self.x[a])
    }
}

/// Draws indexed triangles with `state`, shading with `shader`. Triangles whose indices are out
/// of range or whose positions are not finite are skipped.
pub fn draw<S: FragmentShader>(
    fb: &mut Framebuffer,
    vertices: &[Vertex],
    triangles: &[[u32; 3]],
    state: &DrawState,
    shader: &S,
) {
    let (w, h) = (fb.width, fb.height);
    let varyings = state.varyings.min(MAX_VARYINGS);
    let chunks: Vec<SetupChunk> = triangles
        .par_chunks(512)
        .map(|tris| {
            let mut out = SetupChunk::default();
            for &[a, b, c] in tris {
                let vertex = |i: u32| vertices.get(i as usize);
                let (Some(a), Some(b), Some(c)) = (vertex(a), vertex(b), vertex(c)) else { continue };
                clip_and_setup([a, b, c], w, h, state.cull_back, varyings, &mut out);
            }
            out
        })
        .collect();

    // Bin each triangle into the tiles its bounding box touches, keeping submission order.
    let tiles_x = fb.tiles_x;
    let mut bins: Vec<Vec<[u32; 2]>> = vec![Vec::new(); fb.tiles.len()];
    for (c, chunk) in chunks.iter().enumerate() {
        for (i, s) in chunk.setups.iter().enumerate() {
            let [x0, y0, x1, y1] = s.bbox;
            for ty in y0 / TILE..y1.div_ceil(TILE) {
                for tx in x0 / TILE..x1.div_ceil(TILE) {
                    bins[ty * tiles_x + tx].push([c as u32, i as u32]);
                }
            }
        }
    }
    fb.tiles.par_iter_mut().zip(bins.par_iter()).filter(|(_, bin)| !bin.is_empty()).for_each_init(
        || TileTask {
            batch: FragmentBatch::new(),
            scratch: shader.scratch(),
            colors: Box::new([[0.0f32; LANES]; 4]),
            pending: [0; TILE],
        },
        |task, (tile, bin)| {
            for &[c, i] in bin {
                let chunk = &chunks[c as usize];
                let s = &chunk.setups[i as usize];
                raster_triangle(s, &chunk.var_w[s.var..s.var + varyings], tile, state, shader, task);
            }
            flush(tile, state, shader, task);
        },
    );
}

/// Clips against the near, far and guard-band planes, then sets up each resulting triangle.
fn clip_and_setup(v: [&Vertex; 3], w: usize, h: usize, cull_back: bool, varyings: usize, out: &mut SetupChunk) {
    if v.iter().any(|v| !v.clip.is_finite()) {
        return;
    }
    // Each plane as (p, d): a vertex is inside when p·clip − d ≥ 0.
    let planes = [
        (Vec4::new(0.0, 0.0, 1.0, 1.0), 0.0),    // near: z + w ≥ 0
        (Vec4::new(0.0, 0.0, -1.0, 1.0), 0.0),   // far: w − z ≥ 0
        (Vec4::new(1.0, 0.0, 0.0, GUARD), 0.0),  // left guard band
        (Vec4::new(-1.0, 0.0, 0.0, GUARD), 0.0), // right
        (Vec4::new(0.0, 1.0, 0.0, GUARD), 0.0),  // bottom
        (Vec4::new(0.0, -1.0, 0.0, GUARD), 0.0), // top
        (Vec4::new(0.0, 0.0, 0.0, 1.0), 1e-7),   // w > 0, kept slightly positive
    ];
    let inside = |p: Vec4, (plane, d): (Vec4, f32)| plane.dot(p) - d;
    if v.iter().all(|v| planes.iter().all(|&pl| inside(v.clip, pl) >= 0.0)) {
        setup(v, w, h, cull_back, varyings, out);
        return;
    }
    let mut poly: Vec<Vertex> = v.iter().map(|&&v| v).collect();
    for &plane in &planes {
        let mut next = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (da, db) = (inside(a.clip, plane), inside(b.clip, plane));
            if da >= 0.0 {
                next.push(a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                let t = da / (da - db);
                let mut m = a;
                m.clip = a.clip + (b.clip - a.clip) * t;
                for k in 0..MAX_VARYINGS {
                    m.varyings[k] = a.varyings[k] + (b.varyings[k] - a.varyings[k]) * t;
                }
                next.push(m);
            }
        }
        poly = next;
        if poly.len() < 3 {
            return;
        }
    }
    for i in 1..poly.len() - 1 {
        setup([&poly[0], &poly[i], &poly[i + 1]], w, h, cull_back, varyings, out);
    }
}

fn setup(v: [&Vertex; 3], w: usize, h: usize, cull_back: bool, varyings: usize, out: &mut SetupChunk) {
    let mut x = [0i64; 3];
    let mut y = [0i64; 3];
    let mut z = [0f32; 3];
    let mut inv_w = [0f32; 3];
    for i in 0..3 {
        let c = v[i].clip;
        let iw = 1.0 / c.w;
        let (nx, ny, nz) = (c.x * iw, c.y * iw, c.z * iw);
        x[i] = ((nx + 1.0) * 0.5 * w as f32 * SUBPIXEL).round() as i64;
        y[i] = ((1.0 - ny) * 0.5 * h as f32 * SUBPIXEL).round() as i64;
        z[i] = ((nz + 1.0) * 0.5).clamp(0.0, 1.0);
        inv_w[i] = iw;
    }
    // Signed area in y-down window coordinates: negative = counter-clockwise as seen = front.
    let area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if area == 0 || (area > 0 && cull_back) {
        return;
    }
    let mut order = [0usize, 1, 2];
    if area < 0 {
        order = [0, 2, 1];
    }
    let pick = |a: [i64; 3]| order.map(|i| a[i]);
    let (x, y) = (pick(x), pick(y));
    let pickf = |a: [f32; 3]| order.map(|i| a[i]);
    let (z, inv_w) = (pickf(z), pickf(inv_w));
    let area = area.abs();
    // Top-left rule: an edge (a → b) owns the pixels on it if it is a top edge (horizontal,
    // going right) or a left edge (going up in y-down coordinates).
    let owns = |a: usize, b: usize| {
        let (dx, dy) = (x[b] - x[a], y[b] - y[a]);
        (dy == 0 && dx > 0) || dy < 0
    };
    let bias = [if owns(1, 2) { 0 } else { -1 }, if owns(2, 0) { 0 } else { -1 }, if owns(0, 1) { 0 } else { -1 }];
    let to_px = |v: i64, max: usize| ((v >> SUBPIXEL_BITS).clamp(0, max as i64)) as usize;
    let bbox = [
        to_px(*x.iter().min().unwrap(), w),
        to_px(*y.iter().min().unwrap(), h),
        to_px(*x.iter().max().unwrap() + (1 << SUBPIXEL_BITS), w),
        to_px(*y.iter().max().unwrap() + (1 << SUBPIXEL_BITS), h),
    ];
    if bbox[0] >= bbox[2] || bbox[1] >= bbox[3] {
        return;
    }
    let var = out.var_w.len();
    let ordered = order.map(|i| &v[i].varyings);
    out.var_w.extend((0..varyings).map(|j| [0, 1, 2].map(|k| ordered[k][j] * inv_w[k])));
    out.setups.push(Setup { x, y, bias, inv_area: (1.0 / area as f64) as f32, z, inv_w, var, bbox });
}

/// Per-thread state of a tile task: the batch being filled, the shader's scratch, the output
/// colours and which pixels of the tile have a fragment waiting in the batch.
struct TileTask<S> {
    batch: Box<FragmentBatch>,
    scratch: S,
    colors: Box<[Lanes; 4]>,
    /// One bit per pixel of the tile, row by row: set while a live lane for it is batched.
    pending: [u64; TILE],
}

impl<S> TileTask<S> {
    /// Whether any of the pixels `mask` picks from the quad at (lx, ly) (tile-local; bits 0–3 as
    /// in [`FragmentBatch`]) has a fragment waiting.
    #[inline(always)]
    fn overlaps(&self, lx: usize, ly: usize, mask: u32) -> bool {
        let top = ((mask & 0b11) as u64) << lx;
        let bottom = ((mask >> 2) as u64) << lx;
        (self.pending[ly] & top) | (self.pending[(ly + 1).min(TILE - 1)] & bottom) != 0
    }
}

/// Asks for the cache lines of `buffer` (one value per tile pixel) under the pixel rectangle
/// [x0, x1) × [y0, y1) ahead of the depth tests and blending: shading evicts the tile from L1, and
/// the loads would otherwise wait one by one.
#[inline(always)]
fn prefetch_rows<T>(buffer: &[T], tile: &Tile, x0: usize, x1: usize, y0: usize, y1: usize) {
    #[cfg(target_arch = "x86_64")]
    for y in y0..y1 {
        let row = (y - tile.y0) * tile.width;
        for x in [x0, x1 - 1] {
            // SAFETY: prefetching has no architectural effect; the pointer stays inside `buffer`.
            unsafe {
                use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
                _mm_prefetch::<_MM_HINT_T0>(buffer.as_ptr().add(row + x - tile.x0).cast());
            }
        }
    }
}

/// For each edge, the quad's pixels (bits 0–3) where its function `e + off` is negative.
#[inline(always)]
fn negative_pixels(e: [i64; 3], off: &[[i64; 4]; 3]) -> [u32; 3] {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
    {
        use std::arch::x86_64::*;
        // SAFETY: AVX2 is enabled at compile time (the cfg); the loads read [i64; 4] arrays.
        unsafe {
            std::array::from_fn(|i| {
                let v = _mm256_add_epi64(_mm256_set1_epi64x(e[i]), _mm256_loadu_si256(off[i].as_ptr().cast()));
                _mm256_movemask_pd(_mm256_castsi256_pd(v)) as u32
            })
        }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "avx2")))]
    {
        std::array::from_fn(|i| (0..4).fold(0, |m, k| m | (((e[i] + off[i][k]) < 0) as u32) << k))
    }
}

/// Rasterizes one triangle into a tile's batch. Quads from consecutive triangles share a batch;
/// it is shaded when full, at the end of the tile, or before a quad that touches a pixel whose
/// fragment is still waiting (so depth tests and blending see earlier triangles' results in
/// submission order).
fn raster_triangle<S: FragmentShader>(
    s: &Setup,
    var_w: &[[f32; 3]],
    tile: &mut Tile,
    state: &DrawState,
    shader: &S,
    task: &mut TileTask<S::Scratch>,
) {
    let x0 = s.bbox[0].max(tile.x0) & !1;
    let y0 = s.bbox[1].max(tile.y0) & !1;
    let x1 = s.bbox[2].min(tile.x0 + tile.width);
    let y1 = s.bbox[3].min(tile.y0 + tile.height);
    if x0 >= x1 || y0 >= y1 {
        return;
    }
    prefetch_rows(&tile.depth, tile, x0, x1, y0, y1);
    prefetch_rows(&tile.color, tile, x0, x1, y0, y1);
    let half = 1i64 << (SUBPIXEL_BITS - 1);
    let one = 1i64 << SUBPIXEL_BITS;
    // Edge steps per pixel in x and y, for edges (1→2), (2→0), (0→1).
    let step_x = [-(s.y[2] - s.y[1]) * one, -(s.y[0] - s.y[2]) * one, -(s.y[1] - s.y[0]) * one];
    let step_y = [(s.x[2] - s.x[1]) * one, (s.x[0] - s.x[2]) * one, (s.x[1] - s.x[0]) * one];
    // Each edge at the quad's four pixels relative to its pixel (0, 0), and the same with the
    // top-left bias folded in for the coverage test.
    let off: [[i64; 4]; 3] = std::array::from_fn(|i| [0, step_x[i], step_y[i], step_x[i] + step_y[i]]);
    let off_biased: [[i64; 4]; 3] = std::array::from_fn(|i| off[i].map(|o| o + s.bias[i]));
    let off_f: [Vec4; 3] = std::array::from_fn(|i| Vec4::from_array(off[i].map(|o| o as f32)));
    let (tx1, ty1) = (tile.x0 + tile.width, tile.y0 + tile.height);
    let fx0 = ((x0 as i64) << SUBPIXEL_BITS) + half;
    let mut e_row = {
        let fy = ((y0 as i64) << SUBPIXEL_BITS) + half;
        [s.edge(1, 2, fx0, fy), s.edge(2, 0, fx0, fy), s.edge(0, 1, fx0, fy)]
    };
    // The largest value of each edge function over a quad's pixels, relative to pixel 0.
    let max_off: [i64; 3] = std::array::from_fn(|i| *off_biased[i].iter().max().expect("four pixels"));
    for qy in (y0..y1).step_by(2) {
        // Pixels of the quad's second row fall outside the tile on its last odd row.
        let rows_in = if qy + 1 < ty1 { 0b1111u32 } else { 0b0011 };
        // Quads left of the triangle are skipped: an edge that grows to the right and is
        // negative at every pixel needs at least ⌈−v / 2·step⌉ quads to turn. The quotient is
        // taken in f64 and floored, which never exceeds that (|v| < 2⁵³).
        let mut skip = 0i64;
        for i in 0..3 {
            let v = e_row[i] + max_off[i];
            if step_x[i] > 0 && v < 0 {
                skip = skip.max(((-v) as f64 / (2 * step_x[i]) as f64).floor() as i64);
            }
        }
        let mut e: [i64; 3] = std::array::from_fn(|i| e_row[i] + 2 * step_x[i] * skip);
        let start = x0.saturating_add(2 * skip.min((x1 - x0) as i64) as usize);
        for qx in (start..x1).step_by(2) {
            // A pixel is covered when no edge function is negative there.
            let negative = negative_pixels(e, &off_biased);
            let cols_in = if qx + 1 < tx1 { 0b1111u32 } else { 0b0101 };
            let covered = !(negative[0] | negative[1] | negative[2]) & rows_in & cols_in;
            let e_quad = e;
            for i in 0..3 {
                e[i] += 2 * step_x[i];
            }
            if covered == 0 {
                // Past the triangle: an edge that does not grow to the right is negative at all
                // four pixels, so it is at every quad further along the row.
                if (0..3).any(|i| step_x[i] <= 0 && negative[i] == 0b1111) {
                    break;
                }
                continue;
            }
            let (lx, ly) = (qx - tile.x0, qy - tile.y0);
            if task.overlaps(lx, ly, covered) {
                flush(tile, state, shader, task);
            }
            let q = task.batch.quads;
            let batch = &mut task.batch;
            // Barycentrics of the quad's four pixels as lanes of one vector each: the edge
            // function at pixel 0 plus the per-pixel steps, in float. Every pass computes them
            // the same way, so depth EQUAL still holds across passes.
            let lanes = |i: usize| (Vec4::splat(e_quad[i] as f32) + off_f[i]) * s.inv_area;
            let (b0, b1, b2) = (lanes(0), lanes(1), lanes(2));
            let z = b0 * s.z[0] + b1 * s.z[1] + b2 * s.z[2];
            batch.depth[4 * q..4 * q + 4].copy_from_slice(&z.to_array());
            // The stored depths of the quad's pixels, read without branches: a pixel outside
            // the tile (not covered) reads some in-range value that the mask then ignores.
            let idx = ly * tile.width + lx;
            let last = tile.depth.len() - 1;
            let stored = |k: usize| tile.depth[(idx + (k >> 1) * tile.width + (k & 1)).min(last)];
            let stored = Vec4::new(stored(0), stored(1), stored(2), stored(3));
            let passes = match state.depth_func {
                DepthFunc::Always => 0b1111,
                DepthFunc::Less => z.cmplt(stored).bitmask(),
                DepthFunc::LEqual => z.cmple(stored).bitmask(),
                DepthFunc::Equal => z.cmpeq(stored).bitmask(),
            };
            let live = covered & passes;
            if live == 0 {
                continue;
            }
            batch.quad_live[q] = live as u8;
            // Perspective-correct varyings for all four lanes at once (helpers too, for
            // derivatives): v = Σ bᵢ·(v/w)ᵢ / Σ bᵢ·(1/w)ᵢ.
            let wc = Vec4::ONE / (b0 * s.inv_w[0] + b1 * s.inv_w[1] + b2 * s.inv_w[2]);
            let (w0, w1, w2) = (b0 * wc, b1 * wc, b2 * wc);
            for (var, vw) in batch.varyings.iter_mut().zip(var_w) {
                let v = w0 * vw[0] + w1 * vw[1] + w2 * vw[2];
                var[4 * q..4 * q + 4].copy_from_slice(&v.to_array());
            }
            task.pending[ly] |= ((live & 0b11) as u64) << lx;
            if ly + 1 < TILE {
                task.pending[ly + 1] |= ((live >> 2) as u64) << lx;
            }
            batch.origin[q] = (qx as u16, qy as u16);
            batch.quads += 1;
            if batch.quads == QUADS {
                flush(tile, state, shader, task);
            }
        }
        for i in 0..3 {
            e_row[i] += 2 * step_y[i];
        }
    }
}

/// Shades the batch and writes its live fragments: depth (if enabled) and blended colour.
fn flush<S: FragmentShader>(tile: &mut Tile, state: &DrawState, shader: &S, task: &mut TileTask<S::Scratch>) {
    let TileTask { batch, scratch, colors, pending } = task;
    if batch.quads == 0 {
        return;
    }
    batch.list_live();
    shader.shade(batch, scratch, colors);
    // The blend equation is chosen once per batch; the common ones get their own loop.
    use crate::framebuffer::BlendFactor as F;
    let all = state.color_mask == [true; 4];
    match (state.blend.src, state.blend.dst) {
        (F::One, F::Zero) if all => write_lanes(tile, state, batch, colors, |s, _| s),
        (F::DstColor, F::Zero) if all => write_lanes(tile, state, batch, colors, |s, d| s.map2(d, |a, b| a * b)),
        (F::DstAlpha, F::One) if all => write_lanes(tile, state, batch, colors, |s, d| s.map2(d, |a, b| a * d[3] + b)),
        (F::One, F::One) if all => write_lanes(tile, state, batch, colors, |s, d| s.map2(d, |a, b| a + b)),
        _ => {
            let (blend, mask) = (state.blend, state.color_mask);
            write_lanes_bytes(tile, state, batch, colors, |s, stored| blend.apply(s, stored, mask))
        }
    }
    batch.quads = 0;
    *pending = [0; TILE];
}

/// Pairs of RGBA values combined channel by channel.
trait Map2 {
    fn map2(self, other: Self, f: impl Fn(f32, f32) -> f32) -> Self;
}

impl Map2 for [f32; 4] {
    #[inline(always)]
    fn map2(self, other: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        [f(self[0], other[0]), f(self[1], other[1]), f(self[2], other[2]), f(self[3], other[3])]
    }
}

/// Writes every live lane: depth if enabled, colour = `f(src clamped to [0,1], dst)` rounded.
#[inline(always)]
fn write_lanes(
    tile: &mut Tile,
    state: &DrawState,
    batch: &FragmentBatch,
    colors: &[Lanes; 4],
    f: impl Fn([f32; 4], [f32; 4]) -> [f32; 4],
) {
    write_lanes_bytes(tile, state, batch, colors, |src, stored| {
        let src = src.map(|v| crate::lane_math::clamp_lo(v, 0.0, 1.0));
        let dst = stored.map(|b| b as f32 * (1.0 / 255.0));
        f(src, dst).map(to_byte)
    })
}

#[inline(always)]
fn write_lanes_bytes(
    tile: &mut Tile,
    state: &DrawState,
    batch: &FragmentBatch,
    colors: &[Lanes; 4],
    f: impl Fn([f32; 4], [u8; 4]) -> [u8; 4],
) {
    for (j, &lane) in batch.live().iter().enumerate() {
        let lane = lane as usize;
        let (qx, qy) = batch.origin[lane / 4];
        let k = lane % 4;
        let (px, py) = (qx as usize + (k & 1), qy as usize + (k >> 1));
        let idx = (py - tile.y0) * tile.width + (px - tile.x0);
        if state.depth_write {
            tile.depth[idx] = batch.depth[lane];
        }
        let src = [colors[0][j], colors[1][j], colors[2][j], colors[3][j]];
        tile.color[idx] = f(src, tile.color[idx]);
    }
}

#[cfg(test)]
mod tests;
