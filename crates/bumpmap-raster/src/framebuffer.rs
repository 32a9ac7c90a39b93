//! The RGBA8 colour buffer and float depth buffer, stored as 64×64 tiles so each tile can be
//! rasterized by its own thread, and the per-fragment operations that touch them: the depth
//! test and GL 1.2 blending with 8-bit results.
//!
//! Row 0 is the top of the image. The blend arithmetic is float; its result is rounded to 8
//! bits when written, so every pass sees the framebuffer's quantization as the hardware did.

use glam::Vec4;

use crate::error::RasterError;
use crate::raster::DrawBuffers;

/// Tile edge length in pixels.
pub const TILE: usize = 64;

/// The largest framebuffer accepted, in pixels (8192² = 64 Mi pixels, 512 MiB of colour+depth).
pub const MAX_PIXELS: usize = 8192 * 8192;

/// One tile: up to TILE×TILE pixels, row-major within the tile.
#[derive(Clone, Debug)]
pub struct Tile {
    pub x0: usize,
    pub y0: usize,
    pub width: usize,
    pub height: usize,
    pub color: Vec<[u8; 4]>,
    pub depth: Vec<f32>,
}

/// A tiled RGBA8 + depth framebuffer.
#[derive(Clone, Debug)]
pub struct Framebuffer {
    pub width: usize,
    pub height: usize,
    pub tiles_x: usize,
    pub tiles: Vec<Tile>,
    /// Reused by [`crate::raster::draw`].
    pub(crate) draw_buffers: DrawBuffers,
}

impl Framebuffer {
    /// A cleared framebuffer (black, alpha 0, depth 1). Refuses empty or oversized ones.
    pub fn new(width: usize, height: usize) -> Result<Self, RasterError> {
        if width == 0 || height == 0 || width.saturating_mul(height) > MAX_PIXELS {
            return Err(RasterError::FramebufferSize { width, height, max_pixels: MAX_PIXELS });
        }
        let (tiles_x, tiles_y) = (width.div_ceil(TILE), height.div_ceil(TILE));
        let mut tiles = Vec::with_capacity(tiles_x * tiles_y);
        for ty in 0..tiles_y {
            for tx in 0..tiles_x {
                let (x0, y0) = (tx * TILE, ty * TILE);
                let (w, h) = (TILE.min(width - x0), TILE.min(height - y0));
                tiles.push(Tile {
                    x0,
                    y0,
                    width: w,
                    height: h,
                    color: vec![[0, 0, 0, 0]; w * h],
                    depth: vec![1.0; w * h],
                });
            }
        }
        Ok(Self { width, height, tiles_x, tiles, draw_buffers: DrawBuffers::default() })
    }

    /// `glClear` of colour and depth.
    pub fn clear(&mut self, color: [u8; 4], depth: f32) {
        use rayon::prelude::*;
        self.tiles.par_iter_mut().for_each(|t| {
            t.color.fill(color);
            t.depth.fill(depth);
        });
    }

    /// The colour buffer as row-major RGBA8, row 0 at the top.
    pub fn to_rgba8(&self) -> Vec<[u8; 4]> {
        let mut out = vec![[0u8; 4]; self.width * self.height];
        for t in &self.tiles {
            for y in 0..t.height {
                let dst = (t.y0 + y) * self.width + t.x0;
                out[dst..dst + t.width].copy_from_slice(&t.color[y * t.width..(y + 1) * t.width]);
            }
        }
        out
    }

    /// The depth buffer, row-major, row 0 at the top.
    pub fn depth(&self) -> Vec<f32> {
        let mut out = vec![1.0; self.width * self.height];
        for t in &self.tiles {
            for y in 0..t.height {
                let dst = (t.y0 + y) * self.width + t.x0;
                out[dst..dst + t.width].copy_from_slice(&t.depth[y * t.width..(y + 1) * t.width]);
            }
        }
        out
    }

    /// The pixel at (x, y), row 0 at the top.
    pub fn pixel(&self, x: usize, y: usize) -> [u8; 4] {
        let t = &self.tiles[(y / TILE) * self.tiles_x + x / TILE];
        t.color[(y - t.y0) * t.width + (x - t.x0)]
    }
}

/// Rounds a blended value to a framebuffer byte, clamping to [0, 1] first (NaN becomes 0).
#[inline(always)]
pub(crate) fn to_byte(v: f32) -> u8 {
    let v = crate::lane_math::clamp_lo(v, 0.0, 1.0) * 255.0 + 0.5;
    // SAFETY: v is finite and in [0.5, 255.5].
    unsafe { v.to_int_unchecked::<i32>() as u8 }
}

/// An RGBA8 value as four floats in [0, 255]: one conversion with SSE4.1, which texture
/// filtering shares.
#[inline(always)]
pub(crate) fn rgba8_bytes(p: [u8; 4]) -> Vec4 {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse4.1"))]
    // SAFETY: SSE4.1 is enabled at compile time (the cfg); the intrinsics only move registers.
    unsafe {
        use std::arch::x86_64::*;
        Vec4::from(_mm_cvtepi32_ps(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(i32::from_ne_bytes(p)))))
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse4.1")))]
    Vec4::from_array(p.map(|b| b as f32))
}

/// A stored pixel as four floats in [0, 1] (`byte / 255`, as the blend reads it).
#[inline(always)]
pub(crate) fn rgba8_to_vec4(p: [u8; 4]) -> Vec4 {
    rgba8_bytes(p) * (1.0 / 255.0)
}

/// [`to_byte`] of each channel, the four at once.
#[inline(always)]
pub(crate) fn vec4_to_rgba8(v: Vec4) -> [u8; 4] {
    // `Vec4::clamp` is max then min, so NaN becomes 0 as in `to_byte`.
    let v = v.clamp(Vec4::ZERO, Vec4::ONE) * 255.0 + 0.5;
    #[cfg(all(target_arch = "x86_64", target_feature = "sse4.1"))]
    // SAFETY: SSE4.1 is enabled at compile time (the cfg); v is in [0.5, 255.5], so truncation
    // and the saturating packs keep every value.
    unsafe {
        use std::arch::x86_64::*;
        let i = _mm_cvttps_epi32(v.into());
        let w = _mm_packus_epi32(i, i);
        (_mm_cvtsi128_si32(_mm_packus_epi16(w, w))).to_ne_bytes()
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse4.1")))]
    // SAFETY: v is finite and in [0.5, 255.5].
    v.to_array().map(|c| unsafe { c.to_int_unchecked::<i32>() as u8 })
}

/// `glDepthFunc` values used by the techniques.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthFunc {
    Always,
    Less,
    LEqual,
    Equal,
}

impl DepthFunc {
    #[inline(always)]
    pub fn passes(self, fragment: f32, stored: f32) -> bool {
        match self {
            DepthFunc::Always => true,
            DepthFunc::Less => fragment < stored,
            DepthFunc::LEqual => fragment <= stored,
            DepthFunc::Equal => fragment == stored,
        }
    }
}

/// GL 1.2 blend factors (the imaging subset's constant colour included).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlendFactor {
    Zero,
    One,
    SrcColor,
    DstColor,
    SrcAlpha,
    DstAlpha,
    OneMinusSrcAlpha,
    /// `GL_CONSTANT_COLOR` with the blend colour of [`Blend`].
    ConstantColor,
}

/// `glBlendFunc(src, dst)` and `glBlendColor`; `Blend::REPLACE` is blending disabled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blend {
    pub src: BlendFactor,
    pub dst: BlendFactor,
    pub color: [f32; 4],
}

impl Blend {
    pub const REPLACE: Blend = Blend::new(BlendFactor::One, BlendFactor::Zero);
    /// Pass 2 of the paper: `glBlendFunc(GL_DST_COLOR, GL_ZERO)`.
    pub const MODULATE: Blend = Blend::new(BlendFactor::DstColor, BlendFactor::Zero);
    /// Pass 3 of the paper: `glBlendFunc(GL_DST_ALPHA, GL_ONE)`.
    pub const ADD_BY_DST_ALPHA: Blend = Blend::new(BlendFactor::DstAlpha, BlendFactor::One);
    pub const ADD: Blend = Blend::new(BlendFactor::One, BlendFactor::One);

    pub const fn new(src: BlendFactor, dst: BlendFactor) -> Self {
        Self { src, dst, color: [0.0; 4] }
    }

    #[inline(always)]
    fn factor(&self, f: BlendFactor, src: [f32; 4], dst: [f32; 4], c: usize) -> f32 {
        match f {
            BlendFactor::Zero => 0.0,
            BlendFactor::One => 1.0,
            BlendFactor::SrcColor => src[c],
            BlendFactor::DstColor => dst[c],
            BlendFactor::SrcAlpha => src[3],
            BlendFactor::DstAlpha => dst[3],
            BlendFactor::OneMinusSrcAlpha => 1.0 - src[3],
            BlendFactor::ConstantColor => self.color[c],
        }
    }

    /// Blends a fragment colour (clamped to [0, 1] first, as the GL does) over a stored pixel
    /// and rounds the result to 8 bits; channels not in `mask` keep the stored value.
    #[inline(always)]
    pub fn apply(&self, src: [f32; 4], stored: [u8; 4], mask: [bool; 4]) -> [u8; 4] {
        let src = src.map(|v| crate::lane_math::clamp_lo(v, 0.0, 1.0));
        let dst = rgba8_to_vec4(stored).to_array();
        let mut out = stored;
        for c in 0..4 {
            if mask[c] {
                let v = src[c] * self.factor(self.src, src, dst, c) + dst[c] * self.factor(self.dst, src, dst, c);
                out[c] = to_byte(v);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blend_modes_follow_the_gl_equations() {
        let dst = [200, 100, 50, 128];
        // DST_COLOR, ZERO: src·dst.
        assert_eq!(Blend::MODULATE.apply([0.5, 0.5, 1.0, 1.0], dst, [true; 4]), [100, 50, 50, 128]);
        // DST_ALPHA, ONE: src·dst.a + dst.
        assert_eq!(Blend::ADD_BY_DST_ALPHA.apply([0.4, 0.0, 1.0, 0.0], dst, [true; 4]), [251, 100, 178, 128]);
        // ONE, ZERO replaces; values outside [0, 1] clamp first.
        assert_eq!(Blend::REPLACE.apply([1.5, -0.2, 0.5, 1.0], dst, [true; 4]), [255, 0, 128, 255]);
        // The colour mask keeps channels.
        assert_eq!(Blend::REPLACE.apply([0.0; 4], dst, [false, false, false, true]), [200, 100, 50, 0]);
        assert!(Framebuffer::new(0, 10).is_err());
        assert!(Framebuffer::new(100_000, 100_000).is_err());
    }

    #[test]
    fn pixel_conversions_match_the_scalar_rounding() {
        for b in 0..=255u8 {
            let p = [b, 255 - b, b / 2, 7];
            assert_eq!(rgba8_to_vec4(p).to_array(), p.map(|b| b as f32 * (1.0 / 255.0)));
        }
        for i in -300..=1300 {
            let v = i as f32 / 1000.0;
            let w = Vec4::new(v, 1.0 - v, v * 0.5, f32::NAN);
            assert_eq!(vec4_to_rgba8(w), w.to_array().map(to_byte), "{w}");
        }
    }

    #[test]
    fn tiles_cover_the_frame_exactly() {
        let fb = Framebuffer::new(130, 70).unwrap();
        assert_eq!(fb.tiles.len(), 3 * 2);
        let area: usize = fb.tiles.iter().map(|t| t.width * t.height).sum();
        assert_eq!(area, 130 * 70);
    }
}
