//! Conversions between framebuffer bytes and floats, and GL 1.2 blending with 8-bit results.
//!
//! The blend arithmetic is float (`bumpmap_core::state::Blend::equation`); its result is
//! rounded to 8 bits when written, so every pass sees the framebuffer's quantization as the
//! hardware did. [`blend_pixel`] is the general blend; the rasterizer's fast paths for the
//! common factor pairs are tested equal to it.

use glam::Vec4;

use bumpmap_core::lane_math::clamp_lo;
use bumpmap_core::state::Blend;

/// Rounds a blended value to a framebuffer byte, clamping to [0, 1] first (NaN becomes 0).
#[inline(always)]
pub(crate) fn to_byte(v: f32) -> u8 {
    let v = clamp_lo(v, 0.0, 1.0) * 255.0 + 0.5;
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

/// Blends a fragment colour (clamped to [0, 1] first, as the GL does) over a stored pixel
/// and rounds the result to 8 bits; channels not in `mask` keep the stored value.
#[inline(always)]
pub fn blend_pixel(blend: &Blend, src: [f32; 4], stored: [u8; 4], mask: [bool; 4]) -> [u8; 4] {
    let blended = blend.equation(src, rgba8_to_vec4(stored).to_array());
    std::array::from_fn(|c| if mask[c] { to_byte(blended[c]) } else { stored[c] })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blend_modes_follow_the_gl_equations() {
        let dst = [200, 100, 50, 128];
        // DST_COLOR, ZERO: src·dst.
        assert_eq!(blend_pixel(&Blend::MODULATE, [0.5, 0.5, 1.0, 1.0], dst, [true; 4]), [100, 50, 50, 128]);
        // DST_ALPHA, ONE: src·dst.a + dst.
        assert_eq!(blend_pixel(&Blend::ADD_BY_DST_ALPHA, [0.4, 0.0, 1.0, 0.0], dst, [true; 4]), [251, 100, 178, 128]);
        // ONE, ZERO replaces; values outside [0, 1] clamp first.
        assert_eq!(blend_pixel(&Blend::REPLACE, [1.5, -0.2, 0.5, 1.0], dst, [true; 4]), [255, 0, 128, 255]);
        // The colour mask keeps channels.
        assert_eq!(blend_pixel(&Blend::REPLACE, [0.0; 4], dst, [false, false, false, true]), [200, 100, 50, 0]);
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
}
