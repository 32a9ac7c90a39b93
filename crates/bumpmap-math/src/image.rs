//! The project's image type, and a mip chain of them.
//!
//! A normal-map level, a decal, a gloss map, a spotlight pattern, a cube-map face and a file's
//! pixels are all [`Rgba8Image`]s; a 16-bit normal map written for a file is an
//! [`Rgba16Image`], the same [`Image`] with wider texels; textures with their smaller levels are [`Rgba8Mips`]. Row 0
//! is texture coordinate t = 0, as `glTexImage2D` takes it. These types hold data only: how a
//! texture is sampled belongs to the backends, and what the bytes mean (a normal's encoding,
//! sRGB or linear) to whoever made them.

use glam::Vec3;

use crate::Encoding;
use crate::levels::{footprint, next_size};

/// `width`×`height` texels of type `T`, row-major, row 0 (t = 0) first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image<T> {
    /// Width in texels.
    pub width: usize,
    /// Height in texels.
    pub height: usize,
    /// `width·height` texels, row 0 first.
    pub texels: Vec<T>,
}

/// 8-bit RGBA: what every renderer samples.
pub type Rgba8Image = Image<[u8; 4]>;

/// 16-bit RGBA: normal maps for files only (`bumpmap normalmap --bits 16`).
pub type Rgba16Image = Image<[u16; 4]>;

impl<T: Copy> Image<T> {
    /// An image from its texels. Panics unless `texels.len() == width · height`.
    pub fn new(width: usize, height: usize, texels: Vec<T>) -> Self {
        assert_eq!(texels.len(), width * height, "texel count of a {width}x{height} image");
        Self { width, height, texels }
    }

    /// The texel at (x, y). Panics when out of range.
    #[inline]
    pub fn texel(&self, x: usize, y: usize) -> T {
        self.texels[y * self.width + x]
    }
}

impl Rgba16Image {
    /// The texels as little-endian bytes (R, G, B, A, two bytes each): the layout of DDS's
    /// `R16G16B16A16_UNORM` and KTX2's `VK_FORMAT_R16G16B16A16_UNORM`.
    pub fn to_le_bytes(&self) -> Vec<u8> {
        self.texels.iter().flat_map(|t| t.iter().flat_map(|c| c.to_le_bytes())).collect()
    }

    /// Decodes a normal-map texel into its unit direction and the length stored in alpha.
    pub fn decode(&self, x: usize, y: usize, encoding: Encoding) -> (Vec3, f32) {
        let [r, g, b, a] = self.texel(x, y);
        let d = Vec3::new(encoding.decode16(r), encoding.decode16(g), encoding.decode16(b));
        (d, a as f32 / 65535.0)
    }

    /// The image at 8 bits, each channel rounded to the nearest byte (`(v + 128) / 257`).
    pub fn to_rgba8(&self) -> Rgba8Image {
        let texels = self.texels.iter().map(|&t| crate::Texel::to_rgba8(t)).collect();
        Image { width: self.width, height: self.height, texels }
    }
}

impl Rgba8Image {
    /// Lays `overlay` (straight alpha, the same size) over this image: each colour becomes
    /// `mix(colour, overlay, alpha)`, rounded; this image's alpha is kept. What a viewer's text
    /// and wireframe do to a frame; `bumpmap_gpu`'s window surface does the same in WGSL.
    ///
    /// ```
    /// use bumpmap_math::Rgba8Image;
    ///
    /// let mut frame = Rgba8Image::new(2, 1, vec![[100, 100, 100, 7]; 2]);
    /// let overlay = Rgba8Image::new(2, 1, vec![[0, 0, 0, 0], [255, 0, 0, 255]]);
    /// frame.overlay(&overlay);
    /// assert_eq!(frame.texels, [[100, 100, 100, 7], [255, 0, 0, 7]]);
    /// ```
    pub fn overlay(&mut self, overlay: &Rgba8Image) {
        assert_eq!((self.width, self.height), (overlay.width, overlay.height), "an overlay of the image's size");
        for (c, o) in self.texels.iter_mut().zip(&overlay.texels) {
            let a = o[3] as u32;
            for k in 0..3 {
                c[k] = ((c[k] as u32 * (255 - a) + o[k] as u32 * a + 127) / 255) as u8;
            }
        }
    }

    /// An image whose every texel is `(v, v, v, 255)` for the gray values `values`.
    pub fn from_gray(width: usize, height: usize, values: &[u8]) -> Self {
        Self::new(width, height, values.iter().map(|&v| [v, v, v, 255]).collect())
    }

    /// The texels as one flat byte slice (R, G, B, A, R, …).
    pub fn as_bytes(&self) -> &[u8] {
        self.texels.as_flattened()
    }

    /// Decodes a normal-map texel into its unit direction (`encoding`'s inverse) and the
    /// length stored in alpha.
    pub fn decode(&self, x: usize, y: usize, encoding: Encoding) -> (Vec3, f32) {
        let [r, g, b, a] = self.texel(x, y);
        let d = Vec3::new(encoding.decode(r), encoding.decode(g), encoding.decode(b));
        (d, a as f32 / 255.0)
    }

    /// The next smaller level by a box filter (`gluBuild2DMipmaps`-style): each texel the
    /// rounded mean of its 2×2 footprint, odd sizes folding their last texel into the last
    /// footprint. For colour images; normal maps average their unit normals instead (`mip`).
    pub fn box_halved(&self) -> Self {
        let (w, h) = (next_size(self.width), next_size(self.height));
        let mut texels = Vec::with_capacity(w * h);
        for j in 0..h {
            for i in 0..w {
                let (mut sum, mut n) = ([0u32; 4], 0);
                for y in footprint(j, self.height) {
                    for x in footprint(i, self.width) {
                        let t = self.texel(x, y);
                        for c in 0..4 {
                            sum[c] += t[c] as u32;
                        }
                        n += 1;
                    }
                }
                texels.push(sum.map(|s| ((s + n / 2) / n) as u8));
            }
        }
        Self { width: w, height: h, texels }
    }
}

/// A texture's levels: level 0 first, each level after it the next smaller size, possibly
/// down to 1×1. Never empty.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgba8Mips {
    levels: Vec<Rgba8Image>,
}

impl Rgba8Mips {
    /// A texture of level 0 alone.
    pub fn single(level0: Rgba8Image) -> Self {
        Self { levels: vec![level0] }
    }

    /// A texture from its levels. Panics when `levels` is empty or a level is not the
    /// [`next_size`] of the one before it.
    pub fn from_levels(levels: Vec<Rgba8Image>) -> Self {
        assert!(!levels.is_empty(), "a texture has at least level 0");
        for pair in levels.windows(2) {
            assert_eq!(
                (pair[1].width, pair[1].height),
                (next_size(pair[0].width), next_size(pair[0].height)),
                "mip level sizes halve"
            );
        }
        Self { levels }
    }

    /// Level 0 with a box-filtered chain down to 1×1 ([`Rgba8Image::box_halved`]).
    pub fn with_box_mipmaps(level0: Rgba8Image) -> Self {
        let mut levels = vec![level0];
        loop {
            let last = levels.last().expect("level 0");
            if last.width == 1 && last.height == 1 {
                return Self { levels };
            }
            let next = last.box_halved();
            levels.push(next);
        }
    }

    /// The levels, level 0 first.
    pub fn levels(&self) -> &[Rgba8Image] {
        &self.levels
    }

    /// Level 0's width.
    pub fn width(&self) -> usize {
        self.levels[0].width
    }

    /// Level 0's height.
    pub fn height(&self) -> usize {
        self.levels[0].height
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_chain_reaches_one_texel_and_keeps_a_constant() {
        let img = Rgba8Image::new(5, 3, vec![[10, 20, 30, 40]; 15]);
        let mips = Rgba8Mips::with_box_mipmaps(img);
        let sizes: Vec<_> = mips.levels().iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(5, 3), (2, 1), (1, 1)]);
        assert!(mips.levels().iter().all(|l| l.texels.iter().all(|&t| t == [10, 20, 30, 40])));
    }

    #[test]
    fn box_filter_rounds_the_mean() {
        // 0 and 255 average to 127.5, rounded to 128; the odd third column folds into the mean.
        let img = Rgba8Image::new(3, 2, vec![[0; 4], [255; 4], [255; 4], [0; 4], [255; 4], [255; 4]]);
        assert_eq!(img.box_halved().texels, vec![[170; 4]]);
    }
}
