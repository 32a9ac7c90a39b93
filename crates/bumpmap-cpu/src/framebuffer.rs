//! The RGBA8 colour buffer and float depth buffer, stored as 64×64 tiles so each tile can be
//! rasterized by its own thread. Storage only: the depth test and blending are the
//! rasterizer's (`raster`), the conversions between bytes and floats `pixel`'s.
//!
//! Row 0 is the top of the image.

use crate::error::CpuError;

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
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Tiles along a row.
    pub tiles_x: usize,
    /// The tiles, row by row of tiles.
    pub tiles: Vec<Tile>,
}

impl Framebuffer {
    /// A cleared framebuffer (black, alpha 0, depth 1). Refuses empty or oversized ones.
    pub fn new(width: usize, height: usize) -> Result<Self, CpuError> {
        if width == 0 || height == 0 || width.saturating_mul(height) > MAX_PIXELS {
            return Err(CpuError::FramebufferSize { width, height, max_pixels: MAX_PIXELS });
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
        Ok(Self { width, height, tiles_x, tiles })
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_cover_the_frame_exactly() {
        let fb = Framebuffer::new(130, 70).unwrap();
        assert_eq!(fb.tiles.len(), 3 * 2);
        let area: usize = fb.tiles.iter().map(|t| t.width * t.height).sum();
        assert_eq!(area, 130 * 70);
        assert!(Framebuffer::new(0, 10).is_err());
        assert!(Framebuffer::new(100_000, 100_000).is_err());
    }
}
