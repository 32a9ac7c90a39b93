use super::*;
use crate::{HeightField, HeightPreset, Kernel, MipChain, MipMode, NormalMapOptions, YConvention};

fn map(field: &HeightField, kernel: Kernel, scale: f32, y: YConvention) -> Vec<Image<Vec4>> {
    let options = NormalMapOptions { kernel, scale, y_convention: y, ..Default::default() };
    let chain: MipChain = MipChain::from_height(field, &options, MipMode::LengthInAlpha).unwrap();
    signed_levels(&chain.levels)
}

#[test]
fn the_curl_test_names_the_convention_a_map_was_made_with() {
    let field = HeightPreset::Dimples.render(96, 96);
    for kernel in Kernel::ALL {
        for y in [YConvention::YUp, YConvention::YDown] {
            let v = detect_convention(&map(&field, kernel, 4.0, y)[0]);
            assert_eq!(v.convention, Ok(y), "{kernel:?} {y:?}: {v:?}");
            assert!(v.confidence > 0.5, "{kernel:?} {y:?}: {v:?}");
        }
    }
}

#[test]
fn a_flat_map_and_a_one_direction_ramp_are_undecidable() {
    let flat = HeightField::from_fn(64, 64, |_, _| 0.5);
    let v = detect_convention(&map(&flat, Kernel::Sobel3, 4.0, YConvention::YUp)[0]);
    assert_eq!(v.convention, Err(Undecidable::Flat), "{v:?}");
    // Ridges along one direction (and f(u) + g(v)): both readings are gradients.
    let ridges = HeightField::from_fn(64, 64, |x, _| (x as f32 * 0.3).sin() * 0.5 + 0.5);
    let v = detect_convention(&map(&ridges, Kernel::Sobel3, 4.0, YConvention::YUp)[0]);
    assert_eq!(v.convention, Err(Undecidable::OneDirectional), "{v:?}");
    let sum = HeightField::from_fn(64, 64, |x, y| 0.25 * ((x as f32 * 0.3).sin() + (y as f32 * 0.2).cos()) + 0.5);
    let v = detect_convention(&map(&sum, Kernel::Central, 4.0, YConvention::YDown)[0]);
    assert_eq!(v.convention, Err(Undecidable::OneDirectional), "{v:?}");
}

#[test]
fn the_mip_filter_is_named() {
    let field = HeightPreset::Bricks.render(64, 64);
    let levels = map(&field, Kernel::Sobel3, 4.0, YConvention::YUp);
    let report = classify_mips(&levels).unwrap();
    assert_eq!(report.filter, MipFilter::LengthInAlpha, "{report:?}");
    // The same chain renormalized, alpha 1, as most tools write it.
    let renormalized: Vec<Image<Vec4>> = levels
        .iter()
        .map(|l| Image::new(l.width, l.height, l.texels.iter().map(|t| t.truncate().normalize().extend(1.0)).collect()))
        .collect();
    let report = classify_mips(&renormalized).unwrap();
    assert_eq!(report.filter, MipFilter::Renormalized, "{report:?}");
    let brighter = report.renormalized_brightening().unwrap();
    assert!(brighter > 1.05, "bricks' level 3 normals average shorter than 0.95: {report:?}");
    // Unnormalized box means.
    let boxed: Vec<Image<Vec4>> = levels
        .iter()
        .map(|l| Image::new(l.width, l.height, l.texels.iter().map(|t| (t.truncate() * t.w).extend(1.0)).collect()))
        .collect();
    assert_eq!(classify_mips(&boxed).unwrap().filter, MipFilter::Box);
    assert!(classify_mips(&levels[..1]).is_none());
}

#[test]
fn gray_and_colour_images_are_not_normal_maps() {
    let gray = Image::new(8, 8, (0..64).map(|i| Vec4::splat(i as f32 / 32.0 - 1.0)).collect());
    assert_eq!(TexelStats::of(&gray).kind(false), MapKind::Gray);
    let colours = Image::new(
        8,
        8,
        (0..64)
            .map(|i| {
                Vec4::new(
                    ((i * 37) % 11) as f32 / 5.5 - 1.0,
                    ((i * 13) % 7) as f32 / 3.5 - 1.0,
                    ((i * 5) % 9) as f32 / 4.5 - 1.0,
                    1.0,
                )
            })
            .collect(),
    );
    assert_eq!(TexelStats::of(&colours).kind(false), MapKind::NotUnitVectors);
    let field = HeightPreset::Pinwheel.render(32, 32);
    let normals = map(&field, Kernel::Forward, 4.0, YConvention::YUp);
    let stats = TexelStats::of(&normals[0]);
    assert_eq!(stats.kind(false), MapKind::NormalMap, "{stats:?}");
    assert!(stats.off_unit == 0.0 && stats.facing_away == 0.0, "{stats:?}");
}

#[test]
fn a_map_made_with_wrapping_tiles_and_a_slope_does_not() {
    let field = HeightPreset::Bricks.render(64, 64);
    let seam = Seam::of(&map(&field, Kernel::Sobel3, 4.0, YConvention::YUp)[0]);
    assert!(seam.tiles(), "{seam:?}");
    // Smooth waves whose periods do not divide the size: each edge meets another phase.
    let waves = Image::new(
        64,
        64,
        (0..64 * 64)
            .map(|i| {
                let (x, y) = ((i % 64) as f32, (i / 64) as f32);
                let (p, q) = (0.8 * (0.37 * x + 0.1 * y).cos(), 0.6 * (0.29 * y).sin());
                Vec4::new(-p, -q, 1.0, 0.0).normalize().truncate().extend(1.0)
            })
            .collect(),
    );
    let seam = Seam::of(&waves);
    assert!(!seam.tiles(), "{seam:?}");
}

#[test]
fn two_channel_maps_are_found_and_their_z_rebuilt() {
    let mut level = Image::new(2, 1, vec![Vec4::new(0.6, 0.0, -1.0, 1.0), Vec4::new(0.0, -0.8, -1.0, 1.0)]);
    assert!(is_xy_only(&level));
    rebuild_z(&mut level);
    assert!((level.texels[0].z - 0.8).abs() < 1e-6 && (level.texels[1].z - 0.6).abs() < 1e-6);
    assert!(!is_xy_only(&level));
}

/// A normal map laid out as a bake lays one out: islands of different heights and kernels, each
/// turned by a quarter turn or not (the heights turned, then their normals made, as a baker
/// stores a turned island), on a flat background, each island's edge copied a few texels outward
/// (dilation padding) — so that neighbouring islands meet in seams where the normals jump.
fn atlas(y: YConvention, seed: u64) -> Image<Vec4> {
    use crate::hash::splitmix64;
    let n = 512;
    let mut state = seed;
    let mut next = |below: u64| {
        state = splitmix64(state);
        (state % below) as usize
    };
    let mut out = vec![Vec4::new(0.0, 0.0, 1.0, 1.0); n * n];
    let mut filled = vec![false; n * n];
    let presets = [HeightPreset::Bricks, HeightPreset::Dimples, HeightPreset::Pinwheel, HeightPreset::Noise(seed)];
    for (cell, (cx, cy)) in (0..4).flat_map(|j| (0..4).map(move |i| (i * 128, j * 128))).enumerate() {
        let (w, h) = (60 + next(60), 60 + next(60));
        let (x0, y0) = (cx + 2 + next((124 - w) as u64), cy + 2 + next((124 - h) as u64));
        let source = presets[cell % presets.len()].render(128, 128);
        let turns = next(4);
        let field = HeightField::from_fn(w, h, |x, y| match turns {
            0 => source.get(x, y),
            1 => source.get(y, 127 - x),
            2 => source.get(127 - x, 127 - y),
            _ => source.get(127 - y, x),
        });
        let kernel = Kernel::ALL[next(Kernel::ALL.len() as u64)];
        let scale = 2.0 + next(6) as f32;
        let options =
            NormalMapOptions { kernel, scale, y_convention: y, wrap: crate::Wrap::Clamp, ..Default::default() };
        let chain: MipChain = MipChain::from_height(&field, &options, MipMode::LengthInAlpha).unwrap();
        let island = &signed_levels(&chain.levels[..1])[0];
        for yy in 0..h {
            for xx in 0..w {
                out[(y0 + yy) * n + x0 + xx] = island.texel(xx, yy);
                filled[(y0 + yy) * n + x0 + xx] = true;
            }
        }
    }
    // Dilation: six passes, each background texel beside an island's copying it.
    for _ in 0..6 {
        let before = filled.clone();
        for i in 0..n * n {
            let (x, y) = (i % n, i / n);
            if before[i] {
                continue;
            }
            let beside = [
                (x > 0).then(|| i - 1),
                (x + 1 < n).then(|| i + 1),
                (y > 0).then(|| i - n),
                (y + 1 < n).then(|| i + n),
            ];
            if let Some(j) = beside.into_iter().flatten().find(|&j| before[j]) {
                out[i] = out[j];
                filled[i] = true;
            }
        }
    }
    Image::new(n, n, out)
}

#[test]
fn a_baked_layout_of_turned_padded_islands_is_decided() {
    for seed in 0..6 {
        for y in [YConvention::YUp, YConvention::YDown] {
            let v = detect_convention(&atlas(y, seed));
            assert_eq!(v.convention, Ok(y), "seed {seed} {y:?}: {v:?}");
        }
    }
}
