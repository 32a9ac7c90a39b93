//! The techniques end to end: the three passes against a float evaluation of the same
//! equations, and small golden images.

use std::path::{Path, PathBuf};

use bumpmap_core::BumpMap;
use bumpmap_core::scenes::{self, SceneKind, SceneParams};
use bumpmap_core::technique::{KilgardOptions, Normalize, SinglePassOptions, Technique};
use bumpmap_cpu::{Framebuffer, render};

fn torus() -> bumpmap_core::Scene {
    scenes::build(&SceneKind::Torus, &SceneParams::default()).unwrap()
}

fn render_kilgard_with(size: usize, options: KilgardOptions) -> Vec<[u8; 4]> {
    let mut fb = Framebuffer::new(size, size).unwrap();
    render(&torus(), &Technique::Kilgard(options), &mut fb).unwrap();
    fb.to_rgba8()
}

fn render_kilgard(size: usize) -> Vec<[u8; 4]> {
    render_kilgard_with(size, KilgardOptions::default())
}

fn render_single(size: usize, normalize: Normalize) -> Vec<[u8; 4]> {
    let mut fb = Framebuffer::new(size, size).unwrap();
    let options = SinglePassOptions { normalize, ..Default::default() };
    render(&torus(), &Technique::SinglePass(options), &mut fb).unwrap();
    fb.to_rgba8()
}

/// Per-channel RGB differences of the pixels both images cover.
fn rgb_diffs(a: &[[u8; 4]], b: &[[u8; 4]]) -> Vec<u8> {
    a.iter()
        .zip(b)
        .filter(|(p, q)| p[..3] != [0, 0, 0] || q[..3] != [0, 0, 0])
        .flat_map(|(p, q)| (0..3).map(move |c| p[c].abs_diff(q[c])))
        .collect()
}

#[test]
fn three_passes_agree_with_a_float_evaluation_within_the_quantization_bound() {
    // With the paper's settings (cube-map normalization, shininess 8, Eq. 12's ramp, the same
    // 8-bit textures), the only differences are the 8-bit framebuffer between passes:
    // pass 1 rounds the decal D (½ LSB); pass 2 rounds C·D (½ LSB, plus C ≤ 1 times D's ½);
    // its alpha rounds s_self (½ LSB, times a specular ≤ 1 in pass 3); pass 3 rounds again
    // (½ LSB). The single pass rounds once (½ LSB). Total 2.5 LSB, so bytes differ by ≤ 2;
    // 3 allows for single-precision noise at a rounding boundary.
    let three = render_kilgard(192);
    let one = render_single(192, Normalize::Cube);
    let d = rgb_diffs(&three, &one);
    let lit = three.iter().filter(|p| p[0] > 40).count();
    assert!(lit > 5000, "the torus must be drawn and lit ({lit} pixels)");
    let max = *d.iter().max().unwrap();
    let mean = d.iter().map(|&x| x as f64).sum::<f64>() / d.len() as f64;
    println!("three passes vs one float pass (cube map): max {max}/255, mean {mean:.3}/255 over {} channels", d.len());
    assert!(max <= 3, "max difference {max}/255");
    assert!(mean < 1.0, "mean difference {mean}/255");
}

#[test]
fn math_normalization_differs_measurably_from_the_cube_map() {
    let cube = render_single(192, Normalize::Cube);
    let math = render_single(192, Normalize::Math);
    let d = rgb_diffs(&cube, &math);
    let max = *d.iter().max().unwrap();
    let mean = d.iter().map(|&x| x as f64).sum::<f64>() / d.len() as f64;
    println!("single pass, cube map vs normalize(): max {max}/255, mean {mean:.3}/255 over {} channels", d.len());
    // The 32² cube map is off by up to ~1.1° (README table); at a highlight's (H·N')^8 that
    // is a few per cent: visible in numbers, not to the eye.
    assert!(max > 0 && max < 40, "max {max}");
    assert!(mean < 2.0, "mean {mean}");
}

/// Compares with a golden PNG: at most 1/255 per channel and on at most 0.5 % of pixels (the
/// paths are deterministic; the slack covers libm differences in sin/cos between machines).
/// `BUMPMAP_BLESS=1` rewrites the golden file. On failure, writes the actual image and a
/// difference image next to the test binary's temporary folder and names them.
fn check_golden(name: &str, size: usize, rgba: &[[u8; 4]]) {
    let golden_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden").join(format!("{name}.png"));
    let rgb: Vec<u8> = rgba.iter().flat_map(|p| [p[0], p[1], p[2]]).collect();
    // A golden test on a black or flat image proves nothing.
    let mean = rgb.iter().map(|&v| v as f64).sum::<f64>() / rgb.len() as f64;
    let distinct = rgb.chunks(3).map(|c| (c[0], c[1], c[2])).collect::<std::collections::HashSet<_>>().len();
    assert!(mean > 10.0 && distinct > 100, "{name}: image looks empty (mean {mean}, {distinct} colours)");
    if std::env::var_os("BUMPMAP_BLESS").is_some() {
        image::RgbImage::from_raw(size as u32, size as u32, rgb).unwrap().save(&golden_path).unwrap();
        return;
    }
    let golden = image::open(&golden_path)
        .unwrap_or_else(|e| panic!("{}: {e} (run with BUMPMAP_BLESS=1 to create)", golden_path.display()))
        .to_rgb8();
    assert_eq!(golden.dimensions(), (size as u32, size as u32));
    let diff: Vec<u8> = golden.as_raw().iter().zip(&rgb).map(|(a, b)| a.abs_diff(*b)).collect();
    let max = *diff.iter().max().unwrap();
    let off = diff.chunks(3).filter(|c| c.iter().any(|&d| d > 0)).count();
    if max > 1 || off * 200 > size * size {
        let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
        let actual = dir.join(format!("{name}.actual.png"));
        let diff_path = dir.join(format!("{name}.diff.png"));
        image::RgbImage::from_raw(size as u32, size as u32, rgb).unwrap().save(&actual).unwrap();
        let amplified: Vec<u8> = diff.iter().map(|&d| d.saturating_mul(32)).collect();
        image::RgbImage::from_raw(size as u32, size as u32, amplified).unwrap().save(&diff_path).unwrap();
        panic!(
            "{name}: max difference {max}, {off} pixels differ; see {} and {}",
            actual.display(),
            diff_path.display()
        );
    }
}

#[test]
fn fixed9_combiners_stay_within_a_few_steps_of_float() {
    let float = render_kilgard(128);
    let options = KilgardOptions { precision: bumpmap_core::combiners::Precision::Fixed9, ..Default::default() };
    let d = rgb_diffs(&float, &render_kilgard_with(128, options));
    let max = *d.iter().max().unwrap();
    println!("fixed9 vs float combiners: max {max}/255");
    // Rounding each of ~8 combiner values to 1/255 moves a result by a few steps, and the
    // eighth power by squaring magnifies a step near 1 about eightfold.
    assert!(max > 0, "fixed9 must round somewhere");
    assert!(max <= 24, "max {max}");
}

fn render_scene(kind: SceneKind, params: SceneParams, options: SinglePassOptions, size: usize) -> Vec<[u8; 4]> {
    let scene = scenes::build(&kind, &params).unwrap();
    let mut fb = Framebuffer::new(size, size).unwrap();
    render(&scene, &Technique::SinglePass(options), &mut fb).unwrap();
    fb.to_rgba8()
}

#[test]
fn object_space_lighting_matches_tangent_space_on_the_torus() {
    // The same normals, expressed in object space through the torus's frames: only the object
    // map's resampling (nearest texels of level 0, new mips) differs.
    let tangent = render_scene(SceneKind::Torus, SceneParams::default(), SinglePassOptions::default(), 160);
    let object = render_scene(
        SceneKind::Torus,
        SceneParams { bump_map: BumpMap::ObjectSpace, ..Default::default() },
        SinglePassOptions::default(),
        160,
    );
    let d = rgb_diffs(&tangent, &object);
    let mean = d.iter().map(|&x| x as f64).sum::<f64>() / d.len() as f64;
    println!("object vs tangent space: mean {mean:.3}/255");
    assert!(mean < 3.0, "mean difference {mean}/255");
}

#[test]
fn the_per_pixel_decode_matches_the_per_vertex_frame_wherever_the_frames_agree() {
    // On the wall the frame is the same at every vertex, so MikkTSpace's per-pixel decode and
    // the per-vertex frame are one map read in one frame (the same bytes here); mirroring the
    // texture flips B in both. On the torus the frames turn between vertices and the two part a
    // little (0.04/255 on average), never by a wrong sign, which a mirrored map shows to be
    // much more.
    use bumpmap_math::tangent::TangentDecode;
    for (kind, repeat, most) in [
        (SceneKind::Wall, Some(glam::Vec2::new(2.0, 2.0)), 0.5),
        (SceneKind::Wall, Some(glam::Vec2::new(-2.0, 2.0)), 0.5),
        (SceneKind::Wall, Some(glam::Vec2::new(2.0, -2.0)), 0.5),
        (SceneKind::Torus, Some(glam::Vec2::new(6.0, 2.0)), 0.5),
    ] {
        let params = |decode| SceneParams { decode: Some(decode), repeat, shininess: 20.0, ..Default::default() };
        let per_vertex =
            render_scene(kind.clone(), params(TangentDecode::PerVertex), SinglePassOptions::default(), 128);
        let per_pixel =
            render_scene(kind.clone(), params(TangentDecode::MikkTSpace), SinglePassOptions::default(), 128);
        let d = rgb_diffs(&per_vertex, &per_pixel);
        let mean = d.iter().map(|&x| x as f64).sum::<f64>() / d.len() as f64;
        println!("{kind:?} {repeat:?}: per-pixel vs per-vertex decode, mean {mean:.3}/255");
        assert!(mean < most, "{kind:?} {repeat:?}: mean difference {mean}/255");
        let flipped = render_scene(
            kind.clone(),
            SceneParams { repeat: repeat.map(|r| r * glam::Vec2::new(1.0, -1.0)), ..params(TangentDecode::MikkTSpace) },
            SinglePassOptions::default(),
            128,
        );
        let d = rgb_diffs(&per_pixel, &flipped);
        let mean = d.iter().map(|&x| x as f64).sum::<f64>() / d.len() as f64;
        assert!(mean > 2.0 * most, "{kind:?}: the test sees a mirrored map ({mean}/255)");
    }
}

#[test]
fn the_per_pixel_decode_is_refused_in_words_where_the_light_is_in_the_per_vertex_frame() {
    use bumpmap_core::CoreError;
    use bumpmap_core::error::Feature;
    use bumpmap_math::tangent::TangentDecode;
    let params = SceneParams { decode: Some(TangentDecode::MikkTSpace), ..Default::default() };
    let scene = scenes::build(&SceneKind::Torus, &params).unwrap();
    let mut fb = Framebuffer::new(32, 32).unwrap();
    let lean = Technique::SinglePass(SinglePassOptions {
        specular_filter: bumpmap_core::technique::SpecularFilter::Lean,
        ..Default::default()
    });
    for technique in [Technique::Kilgard(Default::default()), lean] {
        let e = render(&scene, &technique, &mut fb).unwrap_err();
        let said = e.to_string();
        assert!(
            matches!(e, bumpmap_cpu::CpuError::Core(CoreError::Unsupported { feature: Feature::PerPixelDecode, .. })),
            "{said}"
        );
        assert!(said.contains("per-pixel decode"), "{said}");
    }
}

#[test]
fn maps_made_for_the_wall_match_its_tangent_space_map_however_the_texture_is_mirrored() {
    // The wall's texels are squares of the mean side, so the object-space map and Peercy's
    // surface-dependent map hold the tangent-space map's normals in other frames; a negative
    // repeat mirrors the texture, and every map must turn with it as the vertex stage's frame does.
    for (rs, rt) in [(2.0, 2.0), (-2.0, 2.0), (2.0, -2.0), (-2.0, -2.0)] {
        let params = |bump_map| SceneParams { bump_map, repeat: Some(glam::Vec2::new(rs, rt)), ..Default::default() };
        let tangent = render_scene(SceneKind::Wall, params(BumpMap::Tangent), SinglePassOptions::default(), 96);
        // The bricks show: not a flat image that any map would match.
        let grey: Vec<f64> = tangent.iter().map(|p| p[1] as f64).collect();
        let mean = grey.iter().sum::<f64>() / grey.len() as f64;
        let spread = (grey.iter().map(|g| (g - mean).powi(2)).sum::<f64>() / grey.len() as f64).sqrt();
        assert!(spread > 20.0, "repeat ({rs}, {rt}): the wall is nearly flat (σ {spread})");
        for map in [BumpMap::ObjectSpace, BumpMap::SurfaceDependent] {
            let other = render_scene(SceneKind::Wall, params(map), SinglePassOptions::default(), 96);
            let d = rgb_diffs(&tangent, &other);
            let mean = d.iter().map(|&x| x as f64).sum::<f64>() / d.len() as f64;
            // Only resampling differs (nearest level-0 texels, new mips): under a step on average.
            assert!(mean < 1.0, "repeat ({rs}, {rt}), {map:?}: mean difference {mean}/255");
        }
    }
}

#[test]
fn attenuation_darkens_with_distance() {
    use bumpmap_core::scene::{Attenuation, SceneLight};
    use bumpmap_math::lighting::Light;
    let light = |attenuation| SceneLight {
        attenuation,
        ..SceneLight::white(Light::Positional(glam::Vec3::new(0.0, 0.6, 1.5)))
    };
    let params = |attenuation| SceneParams {
        lights: vec![light(attenuation)],
        eye: Some(glam::Vec3::new(0.0, 3.0, 6.0)),
        ..Default::default()
    };
    let plain = render_scene(SceneKind::Floor, params(Attenuation::None), SinglePassOptions::default(), 96);
    let faded = render_scene(
        SceneKind::Floor,
        params(Attenuation::Polynomial { constant: 0.2, linear: 0.0, quadratic: 0.5 }),
        SinglePassOptions::default(),
        96,
    );
    let brightness = |img: &[[u8; 4]], rows: std::ops::Range<usize>| {
        let px: Vec<u32> = rows.flat_map(|y| (20..76).map(move |x| y * 96 + x)).map(|i| img[i][0] as u32).collect();
        px.iter().sum::<u32>() as f64 / px.len() as f64
    };
    // Near rows (bottom of the image, under the light) against far rows (the floor's far edge).
    let (near, far) = (brightness(&faded, 60..70), brightness(&faded, 32..38));
    let (near0, far0) = (brightness(&plain, 60..70), brightness(&plain, 32..38));
    assert!(near > 0.0 && far0 > 0.0, "both images are lit");
    assert!(far / far0 < near / near0, "farther from the light dims more: {far}/{far0} vs {near}/{near0}");
}

#[test]
fn golden_single_pass_features() {
    use bumpmap_core::scene::{SceneLight, Spot};
    use bumpmap_core::technique::Gloss;
    use bumpmap_math::lighting::Light;
    use std::sync::Arc;
    let coloured = |p: glam::Vec3, c: glam::Vec3| SceneLight { color: c, ..SceneLight::white(Light::Positional(p)) };
    let two = SceneParams {
        lights: vec![
            coloured(glam::Vec3::new(4.0, -3.0, 3.0), glam::Vec3::new(1.0, 0.35, 0.2)),
            coloured(glam::Vec3::new(-4.0, -3.0, 3.0), glam::Vec3::new(0.2, 0.45, 1.0)),
        ],
        ..Default::default()
    };
    check_golden(
        "single_pass_two_lights_64",
        64,
        &render_scene(SceneKind::Torus, two, SinglePassOptions::default(), 64),
    );
    let pattern = bumpmap_math::HeightPreset::Pinwheel.render(64, 64).to_u8();
    let pattern = bumpmap_math::Rgba8Mips::single(bumpmap_math::Rgba8Image::from_gray(64, 64, &pattern));
    let spot =
        Spot { direction: glam::Vec3::NEG_Z, cutoff_degrees: 30.0, exponent: 2.0, pattern: Some(Arc::new(pattern)) };
    let spot = SceneParams {
        lights: vec![SceneLight {
            spot: Some(spot),
            ..SceneLight::white(Light::Positional(glam::Vec3::new(0.0, 0.0, 4.0)))
        }],
        default_decal: false,
        specular: glam::Vec3::splat(0.3),
        ..Default::default()
    };
    check_golden(
        "single_pass_spotlight_64",
        64,
        &render_scene(SceneKind::Wall, spot, SinglePassOptions::default(), 64),
    );
    let gloss = bumpmap_math::Rgba8Image::from_gray(256, 256, &bumpmap_math::height::bricks_gloss(256, 256));
    let gloss = Gloss::Map(Arc::new(bumpmap_math::Rgba8Mips::with_box_mipmaps(gloss)));
    let options = SinglePassOptions { gloss, ..Default::default() };
    check_golden(
        "single_pass_gloss_64",
        64,
        &render_scene(SceneKind::Torus, SceneParams { shininess: 40.0, ..Default::default() }, options, 64),
    );
}

#[test]
fn golden_kilgard_torus() {
    check_golden("kilgard_torus_96", 96, &render_kilgard(96));
}

#[test]
fn golden_single_pass_torus() {
    check_golden("single_pass_torus_96", 96, &render_single(96, Normalize::Math));
}
