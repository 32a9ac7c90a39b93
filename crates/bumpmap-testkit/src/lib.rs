//! What every backend's image tests share: a metric (PSNR over RGB), a check against a
//! threshold that writes the actual image and a difference image when it fails, and a guard
//! against tests that pass on a black or flat picture.
//!
//! Not a perceptual metric: PSNR is what the parity tests state their thresholds in. Files go
//! to `target/test-output/` (or `$BUMPMAP_TEST_OUTPUT`), never next to the sources.

#![warn(missing_docs)]

use std::path::{Path, PathBuf};

use bumpmap_math::Rgba8Image;

/// Where failing tests write their images.
pub fn output_dir() -> PathBuf {
    let dir = std::env::var_os("BUMPMAP_TEST_OUTPUT")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/test-output"));
    std::fs::create_dir_all(&dir).expect("test output folder");
    dir
}

/// Mean squared error and peak signal-to-noise ratio (dB, peak 255) of the RGB channels.
/// Identical images give `f64::INFINITY`. Panics when the sizes differ.
pub fn psnr(a: &Rgba8Image, b: &Rgba8Image) -> f64 {
    assert_eq!((a.width, a.height), (b.width, b.height), "images of different sizes");
    let mut sum = 0.0f64;
    for (p, q) in a.texels.iter().zip(&b.texels) {
        for c in 0..3 {
            let d = p[c] as f64 - q[c] as f64;
            sum += d * d;
        }
    }
    let mse = sum / (a.texels.len() * 3) as f64;
    if mse == 0.0 { f64::INFINITY } else { 10.0 * (255.0f64 * 255.0 / mse).log10() }
}

/// The largest per-channel RGB difference.
pub fn max_difference(a: &Rgba8Image, b: &Rgba8Image) -> u8 {
    a.texels.iter().zip(&b.texels).flat_map(|(p, q)| (0..3).map(move |c| p[c].abs_diff(q[c]))).max().unwrap_or(0)
}

/// Panics unless `image` has content: some pixels brighter than black and more than a few
/// distinct colours. A parity test between two black images would prove nothing.
pub fn assert_has_content(name: &str, image: &Rgba8Image) {
    let lit = image.texels.iter().filter(|p| p[0].max(p[1]).max(p[2]) > 24).count();
    let distinct = image.texels.iter().map(|p| [p[0], p[1], p[2]]).collect::<std::collections::HashSet<_>>().len();
    assert!(
        lit * 20 > image.texels.len() && distinct > 50,
        "{name}: the image is black or flat ({lit} lit pixels, {distinct} colours)"
    );
}

/// Writes `image`'s RGB as a PNG.
pub fn write_png(path: &Path, image: &Rgba8Image) {
    let rgb: Vec<u8> = image.texels.iter().flat_map(|p| [p[0], p[1], p[2]]).collect();
    image::save_buffer(path, &rgb, image.width as u32, image.height as u32, image::ColorType::Rgb8).expect("write PNG");
}

/// The per-channel absolute difference, scaled ×8 so one step shows, as an image.
pub fn difference_image(a: &Rgba8Image, b: &Rgba8Image) -> Rgba8Image {
    let texels = a
        .texels
        .iter()
        .zip(&b.texels)
        .map(|(p, q)| {
            let d = |c: usize| (p[c].abs_diff(q[c]) as u32 * 8).min(255) as u8;
            [d(0), d(1), d(2), 255]
        })
        .collect();
    Rgba8Image::new(a.width, a.height, texels)
}

/// Checks `actual` against `expected` at `min_psnr` dB (`reason` says why that threshold).
/// Both must have content. On failure writes `NAME.expected.png`, `NAME.actual.png` and
/// `NAME.diff.png` into [`output_dir`] and names them in the panic message. Returns the PSNR.
pub fn assert_psnr(name: &str, expected: &Rgba8Image, actual: &Rgba8Image, min_psnr: f64, reason: &str) -> f64 {
    assert_has_content(&format!("{name} (expected)"), expected);
    assert_has_content(&format!("{name} (actual)"), actual);
    let db = psnr(expected, actual);
    let max = max_difference(expected, actual);
    println!("{name}: PSNR {db:.2} dB, max difference {max}/255 (threshold {min_psnr} dB: {reason})");
    if db < min_psnr {
        let dir = output_dir();
        let paths = ["expected", "actual", "diff"].map(|k| dir.join(format!("{name}.{k}.png")));
        write_png(&paths[0], expected);
        write_png(&paths[1], actual);
        write_png(&paths[2], &difference_image(expected, actual));
        panic!(
            "{name}: PSNR {db:.2} dB < {min_psnr} dB ({reason}); see {}, {} and {}",
            paths[0].display(),
            paths[1].display(),
            paths[2].display()
        );
    }
    db
}

/// Reads a PNG as RGBA8 (RGB gets alpha 255).
pub fn read_png(path: &Path) -> Rgba8Image {
    let img = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())).to_rgba8();
    let (w, h) = img.dimensions();
    Rgba8Image::new(w as usize, h as usize, img.pixels().map(|p| p.0).collect())
}

/// An example's image held against its screenshot (`screenshot`, a PNG in the repository) at
/// `min_psnr` dB, `reason` saying why that threshold, as the wgpu examples are tested: alpha is
/// left out. `BUMPMAP_BLESS=1` (re)writes the screenshot from `actual` instead; a failure
/// writes the expected, actual and difference images ([`assert_psnr`]). Returns the PSNR.
pub fn assert_screenshot(name: &str, screenshot: &Path, actual: &Rgba8Image, min_psnr: f64, reason: &str) -> f64 {
    if std::env::var_os("BUMPMAP_BLESS").is_some() {
        write_png(screenshot, actual);
        println!("{name}: wrote the screenshot {}", screenshot.display());
    }
    let expected = read_png(screenshot);
    assert_psnr(name, &expected, actual, min_psnr, reason)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn psnr_of_one_step_everywhere_is_48_db() {
        let a = Rgba8Image::new(4, 4, vec![[100, 100, 100, 255]; 16]);
        let b = Rgba8Image::new(4, 4, vec![[101, 101, 101, 255]; 16]);
        assert!((psnr(&a, &b) - 48.13).abs() < 0.01, "{}", psnr(&a, &b));
        assert_eq!(psnr(&a, &a), f64::INFINITY);
        assert_eq!(max_difference(&a, &b), 1);
    }

    #[test]
    #[should_panic(expected = "black or flat")]
    fn a_black_image_has_no_content() {
        assert_has_content("black", &Rgba8Image::new(8, 8, vec![[0, 0, 0, 255]; 64]));
    }
}
