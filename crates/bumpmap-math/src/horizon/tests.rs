use super::*;
use crate::height::HeightField;

/// 32×8 heights: 0, with a wall of height 1 from column 10 on.
fn wall() -> HeightField {
    HeightField::from_fn(32, 8, |x, _| if x >= 10 { 1.0 } else { 0.0 })
}

#[test]
fn a_wall_rises_by_its_height_over_its_distance_on_either_side() {
    let map = HorizonMap::from_heights(&wall(), Wrap::Repeat).unwrap();
    let h = map.levels()[0].texels[2 * 32 + 5];
    // Toward +x the wall's first centre is 5 texels away (the midpoint before it, at 4½,
    // reads 8/16 of the wall: a lower rise).
    assert!((decode_rise(h[0]) - 1.0 / 5.0).abs() < 1e-5, "{}", decode_rise(h[0]));
    // Toward −x it wraps around: column 31 is 6 texels away.
    assert!((decode_rise(h[4]) - 1.0 / 6.0).abs() < 1e-5, "{}", decode_rise(h[4]));
    // Along the wall nothing rises.
    assert_eq!(h[2], 0.0);
    assert_eq!(h[6], 0.0);
    // On top of the wall nothing rises anywhere.
    assert_eq!(map.levels()[0].texels[2 * 32 + 20], [0.0; AZIMUTHS]);
    // Under clamp, −x sees no wall.
    let clamped = HorizonMap::from_heights(&wall(), Wrap::Clamp).unwrap();
    assert_eq!(clamped.levels()[0].texels[2 * 32 + 5][4], 0.0);
}

#[test]
fn a_light_above_the_horizon_is_seen_and_one_below_it_is_not() {
    let map = HorizonMap::from_heights(&wall(), Wrap::Repeat).unwrap();
    let h = map.levels()[0].texels[2 * 32 + 5];
    // The wall rises 0.2 heights per texel toward +x.
    assert_eq!(visibility(&h, Vec3::new(1.0, 0.0, 0.3)), 1.0);
    assert_eq!(visibility(&h, Vec3::new(1.0, 0.0, 0.12)), 0.0);
    assert!((visibility(&h, Vec3::new(1.0, 0.0, 0.2)) - 0.5).abs() < 1e-4, "the edge's middle");
    // Along the wall the light is seen down to the plane, and straight above always.
    assert_eq!(visibility(&h, Vec3::new(0.0, 1.0, 0.1)), 1.0);
    assert_eq!(visibility(&h, Vec3::Z), 1.0);
    // Below the plane it never is.
    assert_eq!(visibility(&h, Vec3::new(0.0, 1.0, -0.1)), 0.0);
}

#[test]
fn between_two_directions_the_horizon_is_interpolated_by_angle() {
    let mut h = [0.0; AZIMUTHS];
    h[1] = 0.4;
    h[2] = 0.8;
    let toward = |deg: f32| {
        let a = deg.to_radians();
        horizon_toward(&h, a.cos(), a.sin())
    };
    assert!((toward(45.0) - 0.4).abs() < 1e-6);
    assert!((toward(67.5) - 0.6).abs() < 1e-5);
    assert!((toward(90.0) - 0.8).abs() < 1e-5);
    assert!((toward(-10.0) - 0.0).abs() < 1e-6);
    assert!((toward(337.5 + 360.0) - 0.0).abs() < 1e-6);
}

#[test]
fn an_open_texel_is_unoccluded_and_its_bent_normal_is_the_base_normal() {
    let open = [0.0; AZIMUTHS];
    assert!((ambient_occlusion(&open, 4.0) - 1.0).abs() < 1e-6);
    assert!((bent_normal(&open, 4.0) - Vec3::Z).length() < 1e-6);
    // A horizon of 30° all round leaves cos² 30° = ¾ open.
    let rise = 30f32.to_radians().tan() / 4.0;
    let ring = [encode_rise(rise); AZIMUTHS];
    assert!((ambient_occlusion(&ring, 4.0) - 0.75).abs() < 1e-5);
    assert!((bent_normal(&ring, 4.0) - Vec3::Z).length() < 1e-5);
    // A wall on one side bends the normal away from it.
    let mut wall = [0.0; AZIMUTHS];
    wall[0] = encode_rise(1.0);
    let bent = bent_normal(&wall, 4.0);
    assert!(bent.x < -0.05 && bent.y.abs() < 1e-6 && (bent.length() - 1.0).abs() < 1e-6, "{bent}");
    assert!(ambient_occlusion(&wall, 4.0) < 1.0);
    // Deeper heights occlude more.
    assert!(ambient_occlusion(&ring, 8.0) < ambient_occlusion(&ring, 4.0));
}

#[test]
fn the_rise_round_trips_through_its_encoding() {
    for rise in [0.0, 0.01, 0.3, 1.0, 7.5] {
        assert!((decode_rise(encode_rise(rise)) - rise).abs() < 1e-4 * (1.0 + rise), "{rise}");
    }
    assert_eq!(encode_rise(-1.0), 0.0);
}

#[test]
fn every_level_is_the_mean_of_the_one_above_down_to_one_texel() {
    let field = HeightField::from_fn(13, 6, |x, y| ((x * 7 + y * 3) % 5) as f32 / 4.0);
    let map = HorizonMap::from_heights(&field, Wrap::Repeat).unwrap();
    let sizes: Vec<_> = map.levels().iter().map(|l| (l.width, l.height)).collect();
    assert_eq!(sizes, vec![(13, 6), (6, 3), (3, 1), (1, 1)]);
    let l0 = &map.levels()[0];
    let l1 = &map.levels()[1];
    // Texel (5, 2) of level 1 covers columns 10..13 (the odd column folds into the last) and
    // rows 4..6 of level 0.
    for k in 0..AZIMUTHS {
        let mean =
            (10..13).flat_map(|x| (4..6).map(move |y| (x, y))).map(|(x, y)| l0.texels[y * 13 + x][k]).sum::<f32>()
                / 6.0;
        assert!((l1.texels[2 * 6 + 5][k] - mean).abs() < 1e-6);
    }
}

#[test]
fn levels_of_the_wrong_size_or_out_of_range_are_refused() {
    let level = |w, h, v| HorizonLevel { width: w, height: h, texels: vec![[v; AZIMUTHS]; w * h] };
    let err = HorizonMap::from_levels(vec![level(8, 8, 0.1), level(3, 4, 0.1)]).unwrap_err();
    assert!(matches!(err, HorizonError::LevelSize { level: 1, want_w: 4, want_h: 4, .. }), "{err}");
    let err = HorizonMap::from_levels(vec![level(4, 4, f32::NAN)]).unwrap_err();
    assert!(matches!(err, HorizonError::NotAHorizon { level: 0, .. }), "{err}");
    assert_eq!(HorizonMap::from_levels(vec![]).unwrap_err(), HorizonError::Empty);
    assert_eq!(HorizonMap::from_levels(vec![level(4, 4, 0.5)]).unwrap().levels().len(), 3);
}

#[test]
fn the_max_pyramid_skips_only_what_changes_nothing() {
    use crate::height::HeightPreset;
    // Fields of every kind the search meets, sizes not powers of two among them: plateaus
    // (bricks), smooth bumps (dimples), noise, and a few spikes on flat ground far apart, where
    // whole blocks lie below the start (a falling bound) and single ones above it.
    let spikes = HeightField::from_fn(300, 70, |x, y| if (x * 7 + y * 13) % 97 == 0 { 0.9 } else { 0.2 });
    let fields = [
        HeightPreset::Bricks.render(96, 64),
        HeightPreset::Dimples.render(67, 45),
        HeightPreset::Noise(3).render(128, 128),
        spikes,
    ];
    for field in &fields {
        let (w, h) = (field.width(), field.height());
        let range = (0..w * h).fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), i| {
            (lo.min(field.get(i % w, i / w)), hi.max(field.get(i % w, i / w)))
        });
        let map = HorizonMap::from_heights(field, Wrap::Repeat).unwrap();
        let maxima = MaxPyramid::new(field).unwrap();
        for y in 0..h {
            for x in 0..w {
                let every_step = horizons_at(field, Wrap::Repeat, range, x, y);
                assert_eq!(map.levels()[0].texels[y * w + x], every_step, "{w}x{h} at ({x}, {y})");
                // Bit for bit, as the map itself is made.
                let bounded = search(field, Wrap::Repeat, range, Some(&maxima), x, y);
                assert_eq!(bounded.map(f32::to_bits), every_step.map(f32::to_bits));
            }
        }
    }
    // And it does skip: on level ground, from step 40 toward +x, the 16-texel block there (one
    // of level 4) holds nothing above the start, so all its steps from here go at once.
    let flat = HeightField::from_fn(256, 256, |_, _| 0.5);
    let maxima = MaxPyramid::new(&flat).unwrap();
    assert_eq!(maxima.skip((40, 7), (1, 0), 40, 200, 0.5, 1.0, 0.0), Ok(8));
    // A block with a height above the start that could rise above the horizon is stepped.
    assert!(maxima.skip((40, 7), (1, 0), 40, 200, 0.4, 1.0, 0.0).is_err());
}
