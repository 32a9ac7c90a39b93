//! The write-back after a batch is shaded: the alpha test, the late depth test of a shader that
//! writes its own depth, the blend equation (the common ones with vector loops of their own) and
//! the writes to the tile's colour and depth.

use glam::Vec4;

use super::{BlendFactor, DrawState, FragmentBatch, FragmentShader, TileTask};
use crate::combiners::Lanes;
use crate::framebuffer::{TILE, Tile};
use crate::pixel::{blend_pixel, rgba8_to_vec4, vec4_to_rgba8};

/// Shades the batch and writes its live fragments: depth (if enabled) and blended colour.
pub(super) fn flush<S: FragmentShader>(
    tile: &mut Tile,
    state: &DrawState,
    shader: &S,
    task: &mut TileTask<S::Scratch>,
) {
    let TileTask { batch, scratch, colors, pending } = task;
    if batch.quads == 0 {
        return;
    }
    batch.list_live(tile.width);
    shader.shade(batch, scratch, colors);
    if state.pass.alpha_test.is_some() {
        // The alpha test: a fragment that fails it is discarded as a NaN depth is.
        let mut depth = [0.0; crate::combiners::LANES];
        let shader_depth = shader.depth(scratch);
        let live = batch.live();
        for (j, z) in depth[..live.len()].iter_mut().enumerate() {
            let own = shader_depth.map_or(batch.depth[live[j] as usize], |d| d[j]);
            *z = if state.pass.alpha_passes(colors[3][j]) { own } else { f32::NAN };
        }
        write_tested(tile, state, batch, colors, &depth);
        batch.quads = 0;
        *pending = [0; TILE];
        return;
    }
    if let Some(depth) = shader.depth(scratch) {
        // The late depth test on the shader's depth; discarded fragments (NaN) fail it.
        write_tested(tile, state, batch, colors, depth);
        batch.quads = 0;
        *pending = [0; TILE];
        return;
    }
    // The blend equation is chosen once per batch; the common ones get their own loop.
    use BlendFactor as F;
    let all = state.pass.color_mask == [true; 4];
    match (state.pass.blend.src, state.pass.blend.dst) {
        (F::One, F::Zero) if all => write_lanes(tile, state, batch, colors, fast_blend::replace),
        (F::DstColor, F::Zero) if all => write_lanes(tile, state, batch, colors, fast_blend::modulate),
        (F::DstAlpha, F::One) if all => write_lanes(tile, state, batch, colors, fast_blend::add_by_dst_alpha),
        (F::One, F::One) if all => write_lanes(tile, state, batch, colors, fast_blend::add),
        _ => {
            let (blend, mask) = (state.pass.blend, state.pass.color_mask);
            write_lanes_bytes(tile, state, batch, colors, |s, stored| blend_pixel(&blend, s, stored, mask))
        }
    }
    batch.quads = 0;
    *pending = [0; TILE];
}

/// The blend equations with a vector loop of their own, `f(src clamped to [0, 1], dst)` in
/// floats: each equals [`blend_pixel`] with its factor pair (tested).
pub(super) mod fast_blend {
    use glam::Vec4;

    /// `ONE, ZERO`.
    #[inline(always)]
    pub fn replace(s: Vec4, _: Vec4) -> Vec4 {
        s
    }
    /// `DST_COLOR, ZERO`.
    #[inline(always)]
    pub fn modulate(s: Vec4, d: Vec4) -> Vec4 {
        s * d
    }
    /// `DST_ALPHA, ONE`.
    #[inline(always)]
    pub fn add_by_dst_alpha(s: Vec4, d: Vec4) -> Vec4 {
        s * d.w + d
    }
    /// `ONE, ONE`.
    #[inline(always)]
    pub fn add(s: Vec4, d: Vec4) -> Vec4 {
        s + d
    }
}

/// Writes the live fragments whose shader depth passes the depth test (and is a number): depth
/// if enabled, colour blended as the pass says.
fn write_tested(tile: &mut Tile, state: &DrawState, batch: &FragmentBatch, colors: &[Lanes; 4], depth: &Lanes) {
    let (blend, mask) = (state.pass.blend, state.pass.color_mask);
    for (j, &idx) in batch.pixel[..batch.live_count].iter().enumerate() {
        let (idx, z) = (idx as usize, depth[j]);
        if z.is_nan() || !state.pass.depth_func.passes(z, tile.depth[idx]) {
            continue;
        }
        if state.pass.depth_write {
            tile.depth[idx] = z;
        }
        let src = [colors[0][j], colors[1][j], colors[2][j], colors[3][j]];
        tile.color[idx] = blend_pixel(&blend, src, tile.color[idx], mask);
    }
}

/// Writes every live lane: depth if enabled, colour = `f(src clamped to [0,1], dst)` rounded.
#[inline(always)]
fn write_lanes(
    tile: &mut Tile,
    state: &DrawState,
    batch: &FragmentBatch,
    colors: &[Lanes; 4],
    f: impl Fn(Vec4, Vec4) -> Vec4,
) {
    write_lanes_bytes(tile, state, batch, colors, |src, stored| {
        let src = Vec4::from_array(src).clamp(Vec4::ZERO, Vec4::ONE);
        vec4_to_rgba8(f(src, rgba8_to_vec4(stored)))
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
    let pixels = &batch.pixel[..batch.live_count];
    if state.pass.depth_write {
        for (&lane, &idx) in batch.live().iter().zip(pixels) {
            tile.depth[idx as usize] = batch.depth[lane as usize];
        }
    }
    for (j, &idx) in pixels.iter().enumerate() {
        let src = [colors[0][j], colors[1][j], colors[2][j], colors[3][j]];
        let idx = idx as usize;
        tile.color[idx] = f(src, tile.color[idx]);
    }
}
