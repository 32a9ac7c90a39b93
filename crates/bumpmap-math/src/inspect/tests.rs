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
