//! The paper's own C code, transcribed with C's float/double rules, against the library.

use bumpmap_math::normalmap::normal_map_level0;
use bumpmap_math::{Encoding, HeightField, HeightPreset, Kernel, NormalMapOptions, NormalizationCubeMap, Wrap};

/// Kilgard Appendix E's `convertHeightFieldToNormalMap` for the wrapping case, with Eq. 25's
/// orientation (`nx = dcx`, `ny = dcy`) instead of the appendix's 90° rotation
/// (`nx = dcy`, `ny = −dcx`). Returns RGBA bytes.
fn appendix_e(pixels: &[u8], w: usize, h: usize, scale: f32) -> Vec<[u8; 4]> {
    let one_over_255: f32 = (1.0f64 / 255.0) as f32;
    let mut out = Vec::with_capacity(w * h);
    for i in 0..h {
        for j in 0..w {
            let c = pixels[i * w + j] as f32 * one_over_255;
            let cx = pixels[i * w + (j + 1) % w] as f32 * one_over_255;
            let cy = pixels[((i + 1) % h) * w + j] as f32 * one_over_255;
            let dcx = scale * (c - cx);
            let dcy = scale * (c - cy);
            let sqrlen = dcx * dcx + dcy * dcy + 1.0;
            let recip_len = (1.0f64 / (sqrlen as f64).sqrt()) as f32;
            let (nx, ny, nz) = (dcx * recip_len, dcy * recip_len, recip_len);
            out.push([(128.0 + 127.0 * nx) as u8, (128.0 + 127.0 * ny) as u8, (128.0 + 127.0 * nz) as u8, 255]);
        }
    }
    out
}

#[test]
fn level0_equals_appendix_e_to_the_byte() {
    for (w, h, scale) in [(64, 64, 4.0f32), (37, 20, 11.5), (128, 8, 1.0)] {
        let bytes = HeightPreset::Noise(17).render(w, h).to_u8();
        let field = HeightField::from_u8(w, h, &bytes).unwrap();
        let opts = NormalMapOptions {
            kernel: Kernel::Forward,
            scale,
            wrap: Wrap::Repeat,
            encoding: Encoding::Kilgard,
            ..Default::default()
        };
        let ours = normal_map_level0(&field, &opts).unwrap();
        let theirs = appendix_e(&bytes, w, h, scale);
        let differing = ours.texels.iter().zip(&theirs).filter(|(a, b)| a != b).count();
        assert_eq!(differing, 0, "{w}x{h} scale {scale}: {differing} texels differ from Appendix E");
        // A test that passes on a flat map proves nothing: the field must tilt normals.
        assert!(ours.texels.iter().any(|t| t[0] != 128 && t[1] != 128));
    }
}

#[test]
fn cube_map_32_equals_the_cg_toolkit_bytes() {
    let golden = include_bytes!("golden/cg_toolkit_normcm_32_rgb8.raw");
    let ours = NormalizationCubeMap::new(32, Encoding::Kilgard).to_bytes();
    assert_eq!(ours.len(), golden.len());
    let first = ours.iter().zip(golden).position(|(a, b)| a != b);
    assert_eq!(first, None, "first differing byte at {first:?}");
}
