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
//!
//! Clipping, setup, binning and the quad loop stay in this one file on purpose: they share the
//! private set-up types (`Setup`, `Plane`, `WindowVertex`) and are tuned together as one hot
//! path (BENCHMARKS.md). The batch of quads they fill and a shader shades is `raster/batch.rs`;
//! what happens after a batch is shaded — the alpha test, the late depth test, blending and the
//! writes — is `raster/write_back.rs`; the tests live in `raster/tests.rs`.

use glam::Vec4;
use rayon::prelude::*;

pub use bumpmap_core::state::{BlendFactor, DepthFunc, PassState};
pub use bumpmap_core::vertex::{MAX_VARYINGS, Vertex};

use crate::combiners::{LANES, Lanes};
use crate::framebuffer::{Framebuffer, TILE, Tile};
mod batch;

pub use batch::{FragmentBatch, FragmentShader};

/// Quads per shading batch.
pub const QUADS: usize = LANES / 4;

/// The state of one draw call: the pass's GL state and how many varyings to interpolate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawState {
    /// Depth, blend, colour mask, culling.
    pub pass: PassState,
    /// How many varyings (from slot 0) the shader reads; only these are interpolated.
    pub varyings: usize,
}

impl DrawState {
    /// Depth LESS with writes, no blending, back faces culled, every varying.
    #[cfg(test)]
    pub const OPAQUE: DrawState = DrawState { pass: PassState::OPAQUE, varyings: MAX_VARYINGS };

    /// `pass` interpolating `varyings` varyings.
    pub const fn new(pass: PassState, varyings: usize) -> Self {
        Self { pass, varyings }
    }
}

const SUBPIXEL_BITS: u32 = 8;
const SUBPIXEL: f32 = (1 << SUBPIXEL_BITS) as f32;
/// Guard band: x and y are clipped at ±GUARD·w, keeping fixed-point products within i64.
const GUARD: f32 = 8.0;

/// The clip volume as planes (p, d): a position is inside plane i when p·clip − d ≥ 0.
const CLIP_PLANES: [(Vec4, f32); 7] = [
    (Vec4::new(0.0, 0.0, 1.0, 1.0), 0.0),    // near: z + w ≥ 0
    (Vec4::new(0.0, 0.0, -1.0, 1.0), 0.0),   // far: w − z ≥ 0
    (Vec4::new(1.0, 0.0, 0.0, GUARD), 0.0),  // left guard band
    (Vec4::new(-1.0, 0.0, 0.0, GUARD), 0.0), // right
    (Vec4::new(0.0, 1.0, 0.0, GUARD), 0.0),  // bottom
    (Vec4::new(0.0, -1.0, 0.0, GUARD), 0.0), // top
    (Vec4::new(0.0, 0.0, 0.0, 1.0), 1e-7),   // w > 0, kept slightly positive
];
/// Outcode bit of a position that is not finite.
const NOT_FINITE: u8 = 1 << 7;

/// How far inside a plane of [`CLIP_PLANES`] a clip-space position is (negative: outside).
#[inline(always)]
fn inside((plane, d): (Vec4, f32), clip: Vec4) -> f32 {
    plane.dot(clip) - d
}

/// Which planes of [`CLIP_PLANES`] a clip-space position is outside of (bit i), or
/// [`NOT_FINITE`].
fn outcode(clip: Vec4) -> u8 {
    if !clip.is_finite() {
        return NOT_FINITE;
    }
    CLIP_PLANES.iter().enumerate().fold(0, |code, (i, &plane)| code | ((inside(plane, clip) < 0.0) as u8) << i)
}

/// A vertex in window coordinates. Computed by one function from the clip position alone, so
/// that a vertex shared by triangles, or drawn again in a later pass, lands on the same
/// fixed-point position with the same depth.
#[derive(Clone, Copy, Debug)]
struct WindowVertex {
    /// x and y in 1/256 pixels, y down.
    x: i64,
    y: i64,
    /// Window depth in [0, 1].
    z: f32,
    inv_w: f32,
}

impl WindowVertex {
    /// Precondition: `clip` is inside the clip volume (its [`outcode`] is 0).
    fn new(clip: Vec4, w: usize, h: usize) -> Self {
        let iw = 1.0 / clip.w;
        let (nx, ny, nz) = (clip.x * iw, clip.y * iw, clip.z * iw);
        WindowVertex {
            x: ((nx + 1.0) * 0.5 * w as f32 * SUBPIXEL).round() as i64,
            y: ((1.0 - ny) * 0.5 * h as f32 * SUBPIXEL).round() as i64,
            z: ((nz + 1.0) * 0.5).clamp(0.0, 1.0),
            inv_w: iw,
        }
    }
}

/// A quantity that varies linearly in window space, as `a + gx·(X − X₀) + gy·(Y − Y₀)` at the
/// pixel centre (X, Y), with (X₀, Y₀) the triangle's first vertex (in pixels).
#[derive(Clone, Copy, Debug)]
struct Plane {
    a: f32,
    gx: f32,
    gy: f32,
}

/// A triangle ready to rasterize.
struct Setup {
    x: [i64; 3],
    y: [i64; 3],
    bias: [i64; 3],
    /// Window depth and 1/w (for perspective correction) as planes.
    z: Plane,
    inv_w: Plane,
    /// Where this triangle's varying planes start in its chunk's `var_w`.
    var: usize,
    bbox: [usize; 4],
}

/// The triangles set up from one run of the index list, with the planes of their varyings
/// divided by w: `var_w[s.var + j]` is varying j's. Only the varyings the draw reads are kept,
/// so a frame's set-up data stays small.
#[derive(Default)]
struct SetupChunk {
    setups: Vec<Setup>,
    var_w: Vec<Plane>,
}

/// The rasterizer and the vectors a draw fills (window-space vertices, set-up chunks, tile
/// bins), kept between draws so that their memory is reused rather than allocated, faulted in
/// and freed again on every draw. It keeps the largest draw's vectors as long as it lives.
#[derive(Default)]
pub struct Rasterizer {
    window: Vec<(u8, WindowVertex)>,
    chunks: Vec<SetupChunk>,
    bins: Vec<Vec<[u32; 2]>>,
}

impl std::fmt::Debug for Rasterizer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Rasterizer")
    }
}

impl Setup {
    /// Edge function of the edge from vertex a to vertex b at fixed-point (px, py).
    #[inline(always)]
    fn edge(&self, a: usize, b: usize, px: i64, py: i64) -> i64 {
        (self.x[b] - self.x[a]) * (py - self.y[a]) - (self.y[b] - self.y[a]) * (px - self.x[a])
    }
}

/// Draws indexed triangles into `fb` with `state`, shading with `shader`, on a fresh
/// [`Rasterizer`]. Triangles whose indices are out of range or whose positions are not finite
/// are skipped.
#[cfg(test)]
pub fn draw<S: FragmentShader>(
    fb: &mut Framebuffer,
    vertices: &[Vertex],
    triangles: &[[u32; 3]],
    state: &DrawState,
    shader: &S,
) {
    Rasterizer::default().draw(fb, vertices, triangles, state, shader);
}

impl Rasterizer {
    /// Draws indexed triangles into `fb` with `state`, shading with `shader`, reusing this
    /// rasterizer's vectors. Triangles whose indices are out of range or whose positions are
    /// not finite are skipped.
    pub fn draw<S: FragmentShader>(
        &mut self,
        fb: &mut Framebuffer,
        vertices: &[Vertex],
        triangles: &[[u32; 3]],
        state: &DrawState,
        shader: &S,
    ) {
        draw_with(self, fb, vertices, triangles, state, shader);
    }
}

fn draw_with<S: FragmentShader>(
    buffers: &mut Rasterizer,
    fb: &mut Framebuffer,
    vertices: &[Vertex],
    triangles: &[[u32; 3]],
    state: &DrawState,
    shader: &S,
) {
    let (w, h) = (fb.width, fb.height);
    let varyings = state.varyings.min(MAX_VARYINGS);
    let Rasterizer { window, chunks, bins } = buffers;
    // Each vertex is transformed once, however many triangles share it.
    vertices
        .par_iter()
        .with_min_len(1024)
        .map(|v| {
            let code = outcode(v.clip);
            let at = if code == 0 {
                WindowVertex::new(v.clip, w, h)
            } else {
                WindowVertex { x: 0, y: 0, z: 0.0, inv_w: 0.0 }
            };
            (code, at)
        })
        .collect_into_vec(window);
    const CHUNK: usize = 512;
    chunks.resize_with(triangles.len().div_ceil(CHUNK), SetupChunk::default);
    chunks.par_iter_mut().zip(triangles.par_chunks(CHUNK)).for_each(|(out, tris)| {
        out.setups.clear();
        out.var_w.clear();
        for &[a, b, c] in tris {
            let get = |i: u32| Some((vertices.get(i as usize)?, window[i as usize]));
            let (Some(a), Some(b), Some(c)) = (get(a), get(b), get(c)) else { continue };
            let codes = [a.1.0, b.1.0, c.1.0];
            if codes == [0; 3] {
                setup([a.0, b.0, c.0], [a.1.1, b.1.1, c.1.1], (w, h), state.pass.cull_back, varyings, out);
            } else if codes.iter().all(|&c| c & NOT_FINITE == 0) && codes[0] & codes[1] & codes[2] == 0 {
                // Partly outside (not wholly outside one plane): clip.
                clip_and_setup([a.0, b.0, c.0], w, h, state.pass.cull_back, varyings, out);
            }
        }
    });

    // Bin each triangle into the tiles its bounding box touches, keeping submission order.
    let tiles_x = fb.tiles_x;
    bins.resize_with(fb.tiles.len(), Vec::new);
    bins.iter_mut().for_each(Vec::clear);
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

/// Clips a triangle that is partly outside the near, far or guard-band planes, then sets up
/// each triangle of the clipped polygon.
fn clip_and_setup(v: [&Vertex; 3], w: usize, h: usize, cull_back: bool, varyings: usize, out: &mut SetupChunk) {
    let mut poly: Vec<Vertex> = v.iter().map(|&&v| v).collect();
    for &plane in &CLIP_PLANES {
        let mut next = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            let (da, db) = (inside(plane, a.clip), inside(plane, b.clip));
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
    let window: Vec<WindowVertex> = poly.iter().map(|v| WindowVertex::new(v.clip, w, h)).collect();
    for i in 1..poly.len() - 1 {
        setup(
            [&poly[0], &poly[i], &poly[i + 1]],
            [window[0], window[i], window[i + 1]],
            (w, h),
            cull_back,
            varyings,
            out,
        );
    }
}

fn setup(
    v: [&Vertex; 3],
    at: [WindowVertex; 3],
    (w, h): (usize, usize),
    cull_back: bool,
    varyings: usize,
    out: &mut SetupChunk,
) {
    let (x, y) = (at.map(|a| a.x), at.map(|a| a.y));
    // Signed area in y-down window coordinates: negative = counter-clockwise as seen = front.
    let area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if area == 0 || (area > 0 && cull_back) {
        return;
    }
    let order = if area < 0 { [0, 2, 1] } else { [0, 1, 2] };
    let (x, y, at) = (order.map(|i| x[i]), order.map(|i| y[i]), order.map(|i| at[i]));
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
    // A quantity's plane from its values at the three vertices: barycentric i is edge
    // function i over the area, and edge i runs from vertex i+1 to vertex i+2, so its
    // per-pixel gradient is (−Δy, Δx)·256 / area of that edge (in f64, then rounded once).
    let scale = (1u64 << SUBPIXEL_BITS) as f64 / area as f64;
    let (ex, ey): ([f64; 3], [f64; 3]) = (
        std::array::from_fn(|i| -((y[(i + 2) % 3] - y[(i + 1) % 3]) as f64) * scale),
        std::array::from_fn(|i| (x[(i + 2) % 3] - x[(i + 1) % 3]) as f64 * scale),
    );
    let plane = |q: [f32; 3]| {
        let q = q.map(f64::from);
        Plane {
            a: q[0] as f32,
            gx: (q[0] * ex[0] + q[1] * ex[1] + q[2] * ex[2]) as f32,
            gy: (q[0] * ey[0] + q[1] * ey[1] + q[2] * ey[2]) as f32,
        }
    };
    let var = out.var_w.len();
    let (ordered, inv_w) = (order.map(|i| &v[i].varyings), at.map(|a| a.inv_w));
    out.var_w.extend((0..varyings).map(|j| plane([0, 1, 2].map(|k| ordered[k][j] * inv_w[k]))));
    out.setups.push(Setup { x, y, bias, z: plane(at.map(|a| a.z)), inv_w: plane(inv_w), var, bbox });
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
    // Elsewhere (the web's wasm32) the loads wait as they come.
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (buffer, tile, x0, x1, y0, y1);
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
/// it is shaded when full, at the end of the tile, or before a quad that covers a pixel whose
/// fragment is still waiting (so depth tests and blending see earlier triangles' results in
/// submission order).
fn raster_triangle<S: FragmentShader>(
    s: &Setup,
    var_w: &[Plane],
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
    // Each edge at the quad's four pixels relative to its pixel (0, 0), with the top-left bias
    // folded in for the coverage test, and the largest of the four.
    let off: [[i64; 4]; 3] =
        std::array::from_fn(|i| [0, step_x[i], step_y[i], step_x[i] + step_y[i]].map(|o| o + s.bias[i]));
    let max_off: [i64; 3] = std::array::from_fn(|i| *off[i].iter().max().expect("four pixels"));
    let (tx1, ty1) = (tile.x0 + tile.width, tile.y0 + tile.height);
    let (fx0, fy0) = (((x0 as i64) << SUBPIXEL_BITS) + half, ((y0 as i64) << SUBPIXEL_BITS) + half);
    let mut e_row = [s.edge(1, 2, fx0, fy0), s.edge(2, 0, fx0, fy0), s.edge(0, 1, fx0, fy0)];
    // The planes' offsets (X − X₀, Y − Y₀) at a quad's pixels. Steps of 2 keep them exact: they
    // are multiples of 1/256 well within f32's 24 bits for any frame this rasterizer accepts.
    let from_vertex = |fixed: i64, vertex: i64| (fixed - vertex) as f32 * (1.0 / SUBPIXEL);
    let (dx0, mut dy) =
        (from_vertex(fx0, s.x[0]), Vec4::splat(from_vertex(fy0, s.y[0])) + Vec4::new(0.0, 0.0, 1.0, 1.0));
    let quads_in_row = (x1 - x0).div_ceil(2) as i64;
    let mut var_row = [Vec4::ZERO; MAX_VARYINGS];
    for qy in (y0..y1).step_by(2) {
        // The quads of the row that every edge allows: quad n has a pixel on the inner side of
        // edge i when e_row + max_off + 2·step_x·n ≥ 0. The divisions are exact (integers).
        let (mut first, mut end) = (0i64, quads_in_row);
        for i in 0..3 {
            let (v, step) = (e_row[i] + max_off[i], 2 * step_x[i]);
            if v < 0 {
                if step > 0 {
                    first = first.max((-v as u64).div_ceil(step as u64) as i64);
                } else {
                    end = 0;
                }
            } else if step < 0 {
                end = end.min(v / -step + 1);
            }
        }
        let row_e = e_row;
        for i in 0..3 {
            e_row[i] += 2 * step_y[i];
        }
        let row_dy = dy;
        dy += Vec4::splat(2.0);
        if first >= end {
            continue;
        }
        // Pixels of the quad's second row fall outside the tile on its last odd row.
        let rows_in = if qy + 1 < ty1 { 0b1111u32 } else { 0b0011 };
        // The planes along this row: a + gy·(Y − Y₀), and gx for the steps along x.
        let row = |p: &Plane| Vec4::splat(p.gy).mul_add(row_dy, Vec4::splat(p.a));
        let (z_row, inv_w_row) = (row(&s.z), row(&s.inv_w));
        for (r, p) in var_row.iter_mut().zip(var_w) {
            *r = row(p);
        }
        let mut e: [i64; 3] = std::array::from_fn(|i| row_e[i] + 2 * step_x[i] * first);
        let mut dx = Vec4::splat(dx0 + 2.0 * first as f32) + Vec4::new(0.0, 1.0, 0.0, 1.0);
        for qx in (x0 + 2 * first as usize..x0 + 2 * end as usize).step_by(2) {
            // A pixel is covered when no edge function is negative there.
            let negative = negative_pixels(e, &off);
            let cols_in = if qx + 1 < tx1 { 0b1111u32 } else { 0b0101 };
            let covered = !(negative[0] | negative[1] | negative[2]) & rows_in & cols_in;
            let quad_dx = dx;
            for i in 0..3 {
                e[i] += 2 * step_x[i];
            }
            dx += Vec4::splat(2.0);
            if covered == 0 {
                continue;
            }
            let (lx, ly) = (qx - tile.x0, qy - tile.y0);
            if task.overlaps(lx, ly, covered) {
                flush(tile, state, shader, task);
            }
            let q = task.batch.quads;
            let batch = &mut task.batch;
            // Depth from its plane: every pass evaluates the same plane at the same pixels, so
            // depth EQUAL holds across passes.
            let z = Vec4::splat(s.z.gx).mul_add(quad_dx, z_row);
            batch.depth[4 * q..4 * q + 4].copy_from_slice(&z.to_array());
            // The stored depths of the quad's pixels, read without branches: a pixel outside
            // the tile (not covered) reads some in-range value that the mask then ignores.
            let idx = ly * tile.width + lx;
            let last = tile.depth.len() - 1;
            let stored = |k: usize| tile.depth[(idx + (k >> 1) * tile.width + (k & 1)).min(last)];
            let stored = Vec4::new(stored(0), stored(1), stored(2), stored(3));
            // A shader that writes its depth is tested after shading; before it, only LESS and
            // LEQUAL can drop what its depth (never nearer than the triangle's) would fail too.
            let passes =
                if shader.writes_depth() && !matches!(state.pass.depth_func, DepthFunc::Less | DepthFunc::LEqual) {
                    0b1111
                } else {
                    depth_test_quad(state.pass.depth_func, z, stored)
                };
            let live = covered & passes;
            if live == 0 {
                continue;
            }
            batch.quad_live[q] = live as u8;
            // Perspective-correct varyings for all four lanes at once (helpers too, for
            // derivatives): v = (v/w) / (1/w), both interpolated linearly in window space.
            let w = Vec4::ONE / Vec4::splat(s.inv_w.gx).mul_add(quad_dx, inv_w_row);
            for ((var, p), r) in batch.varyings.iter_mut().zip(var_w).zip(&var_row) {
                let v = Vec4::splat(p.gx).mul_add(quad_dx, *r) * w;
                var[4 * q..4 * q + 4].copy_from_slice(&v.to_array());
            }
            task.pending[ly] |= ((live & 0b11) as u64) << lx;
            if ly + 1 < TILE {
                task.pending[ly + 1] |= ((live >> 2) as u64) << lx;
            }
            batch.corner[q] = idx as u16;
            batch.quads += 1;
            if batch.quads == QUADS {
                flush(tile, state, shader, task);
            }
        }
    }
}

/// The depth test of a quad's four pixels as a bit mask (bit k = pixel k passes): the vector
/// form of `DepthFunc::passes` (tested equal).
#[inline(always)]
pub(crate) fn depth_test_quad(func: DepthFunc, z: Vec4, stored: Vec4) -> u32 {
    match func {
        DepthFunc::Always => 0b1111,
        DepthFunc::Less => z.cmplt(stored).bitmask(),
        DepthFunc::LEqual => z.cmple(stored).bitmask(),
        DepthFunc::Equal => z.cmpeq(stored).bitmask(),
    }
}

mod write_back;

#[cfg(test)]
use write_back::fast_blend;
use write_back::flush;

#[cfg(test)]
mod tests;
