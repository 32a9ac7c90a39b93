//! How far an image is from the reference: RMSE, PSNR and bias over linear RGB in [0, 1], FLIP
//! (NVIDIA's perceptual difference, through `nv-flip`) and SSIM on luminance (`image-compare`).
//!
//! The reference is float; a technique's image is what its 8-bit framebuffer holds. FLIP and
//! SSIM see both as 8-bit images, the reference rounded, as a viewer would display them.

use bumpmap_math::Rgba8Image;
use bumpmap_reference::LinearImage;
use glam::Vec3;

/// FLIP's viewing condition: a 0.7 m distance to a 0.7 m wide 4K monitor (FLIP's default, about
/// 67 pixels per degree).
const PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

/// The numbers of one technique's image against the reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scores {
    /// Root-mean-square error over every channel of every pixel.
    pub rmse: f64,
    /// `20·log10(1 / rmse)` in dB (infinite for identical images).
    pub psnr: f64,
    /// Mean of (image − reference) over every channel: positive is too bright.
    pub bias: f64,
    /// Mean FLIP error in [0, 1].
    pub flip_mean: f64,
    /// Mean SSIM of the luminance in [−1, 1] (1 for identical images).
    pub ssim: f64,
}

/// The image's colours in [0, 1].
pub fn linear(image: &Rgba8Image) -> Vec<Vec3> {
    image.texels.iter().map(|t| Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32) / 255.0).collect()
}

/// RMSE, PSNR and bias of `test` against `reference`, both linear RGB of the same length.
pub fn pixel_errors(reference: &[Vec3], test: &[Vec3]) -> (f64, f64, f64) {
    assert_eq!(reference.len(), test.len(), "images of one size");
    let (mut sq, mut signed) = (0.0f64, 0.0f64);
    for (r, t) in reference.iter().zip(test) {
        let d = *t - *r;
        sq += d.length_squared() as f64;
        signed += (d.x + d.y + d.z) as f64;
    }
    let n = 3.0 * reference.len() as f64;
    let rmse = (sq / n).sqrt();
    (rmse, 20.0 * (1.0 / rmse).log10(), signed / n)
}

/// The reference as the 8-bit RGB that FLIP and SSIM compare against, made once per run.
pub fn reference_rgb8(reference: &LinearImage) -> Vec<u8> {
    rgb8(&reference.to_rgba8())
}

fn rgb8(img: &Rgba8Image) -> Vec<u8> {
    img.texels.iter().flat_map(|t| [t[0], t[1], t[2]]).collect()
}

/// Every score of `test` against `reference` (`ref_rgb` its [`reference_rgb8`]), and FLIP's
/// error map coloured with magma (the heat map the report shows), RGB8.
pub fn score(reference: &LinearImage, ref_rgb: &[u8], test: &Rgba8Image) -> (Scores, Vec<u8>) {
    let (w, h) = (reference.width as u32, reference.height as u32);
    let (rmse, psnr, bias) = pixel_errors(&reference.pixels, &linear(test));
    let test_rgb = rgb8(test);
    let error = flip_error(w, h, ref_rgb, &test_rgb);
    let flip_mean = nv_flip::FlipPool::from_image(&error).mean() as f64;
    let heat = error.apply_color_lut(&nv_flip::magma_lut()).to_vec();
    let gray = |rgb: &[u8]| {
        let luma =
            rgb.chunks(3).map(|c| (0.2126 * c[0] as f32 + 0.7152 * c[1] as f32 + 0.0722 * c[2] as f32).round() as u8);
        image::GrayImage::from_raw(w, h, luma.collect()).expect("w·h values")
    };
    let ssim = image_compare::gray_similarity_structure(
        &image_compare::Algorithm::MSSIMSimple,
        &gray(ref_rgb),
        &gray(&test_rgb),
    )
    .map(|s| s.score)
    .unwrap_or(f64::NAN);
    (Scores { rmse, psnr, bias, flip_mean, ssim }, heat)
}

/// FLIP's per-pixel error of `test` against `reference`, both `w`×`h` RGB8.
fn flip_error(w: u32, h: u32, reference: &[u8], test: &[u8]) -> nv_flip::FlipImageFloat {
    nv_flip::flip(
        nv_flip::FlipImageRgb8::with_data(w, h, reference),
        nv_flip::FlipImageRgb8::with_data(w, h, test),
        PIXELS_PER_DEGREE,
    )
}

/// Mean FLIP of `test` against `reference`, two 8-bit images of one size: how visible their
/// difference is.
pub fn flip_mean(reference: &Rgba8Image, test: &Rgba8Image) -> f64 {
    assert_eq!((reference.width, reference.height), (test.width, test.height), "images of one size");
    let error = flip_error(reference.width as u32, reference.height as u32, &rgb8(reference), &rgb8(test));
    nv_flip::FlipPool::from_image(&error).mean() as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reference(c: f32) -> LinearImage {
        LinearImage { width: 16, height: 16, pixels: vec![Vec3::splat(c); 256] }
    }

    #[test]
    fn identical_images_score_perfectly_and_a_brighter_one_has_positive_bias() {
        let r = reference(0.4);
        let same = r.to_rgba8();
        let ref_rgb = reference_rgb8(&r);
        let (s, _) = score(&r, &ref_rgb, &same);
        assert!(s.rmse < 0.002 && s.flip_mean < 1e-3 && (s.ssim - 1.0).abs() < 1e-6, "{s:?}");
        let brighter = Rgba8Image::new(16, 16, vec![[153, 153, 153, 255]; 256]); // 0.6
        let (s, heat) = score(&r, &ref_rgb, &brighter);
        assert!((s.bias - 0.2).abs() < 0.003 && (s.rmse - 0.2).abs() < 0.003, "{s:?}");
        assert!((s.psnr - 20.0 * 5f64.log10()).abs() < 0.2 && s.flip_mean > 0.05, "{s:?}");
        assert_eq!(heat.len(), 16 * 16 * 3);
        // The same FLIP between two 8-bit images.
        assert!(flip_mean(&same, &same) < 1e-3);
        assert!((flip_mean(&same, &brighter) - s.flip_mean).abs() < 1e-3, "{}", flip_mean(&same, &brighter));
    }
}
