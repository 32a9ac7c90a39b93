//! `bumpmap::maps`' sets of outputs and folder batches, as the library promises them (the
//! command line's own tests check its words and exit statuses).

use std::path::{Path, PathBuf};

use bumpmap::HeightPreset;
use bumpmap::maps::{FolderBatch, FolderError, MapOptions, MapOutputs, Output, OutputsError};
use bumpmap::options::RoughnessLayout;
use bumpmap_io::texture_file::TextureFormat;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpmap-map-outputs-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

#[test]
fn outputs_on_one_file_are_refused_before_anything_is_written() {
    let dir = scratch("clash");
    let n = dir.join("n.png");
    let cases = [
        (MapOutputs { roughness: Some(n.clone()), ..Default::default() }, Output::Roughness, Output::NormalMap),
        (
            MapOutputs { heights: Some(dir.join("h.png")), horizons: Some(dir.join("h.png")), ..Default::default() },
            Output::Horizons,
            Output::Heights,
        ),
        (
            MapOutputs {
                roughness: Some(dir.join("r.png")),
                ambient_occlusion: Some(dir.join("r.png")),
                ..Default::default()
            },
            Output::AmbientOcclusion,
            Output::Roughness,
        ),
    ];
    for (outputs, output, other) in cases {
        let outputs = MapOutputs { normal_map: n.clone(), ..outputs };
        let field = HeightPreset::Bricks.render(16, 16);
        match outputs.write(field, &MapOptions::default(), true, TextureFormat::Rgba8, &[], &|_, _| {}) {
            Err(OutputsError::Clash { output: o, other: t, .. }) => assert_eq!((o, t), (output, other)),
            other => panic!("{outputs:?}: {other:?}"),
        }
    }
    let lean = MapOutputs { normal_map: n, lean: Some(dir.join("m.png")), ..Default::default() };
    assert!(matches!(lean.check(&[]), Err(OutputsError::LeanNeedsFloats { .. })), "LEAN's moments are floats");
    assert!(files_in(&dir).is_empty(), "nothing written: {:?}", files_in(&dir));
}

#[test]
fn gltfs_orm_texture_holds_the_occlusion_in_red() {
    let dir = scratch("orm");
    let outputs = MapOutputs {
        normal_map: dir.join("n.png"),
        roughness: Some(dir.join("orm.png")),
        ambient_occlusion: Some(dir.join("ao.png")),
        ..Default::default()
    };
    let options = MapOptions { roughness_layout: RoughnessLayout::Gltf, ..Default::default() };
    let field = HeightPreset::Bricks.render(32, 32);
    let written = outputs.write(field, &options, true, TextureFormat::Rgba8, &[], &|_, _| {}).unwrap();
    assert!(written.files.contains(&dir.join("orm.mip1.png")), "{:?}", written.files);
    let orm = bumpmap_io::load_rgba8(&dir.join("orm.png")).unwrap();
    let ao = bumpmap_io::load_rgba8(&dir.join("ao.png")).unwrap();
    let red: Vec<u8> = orm.texels.iter().map(|t| t[0]).collect();
    let gray: Vec<u8> = ao.texels.iter().map(|t| t[0]).collect();
    // The same occlusion in both files, each rounded to 8 bits once.
    assert!(red.iter().zip(&gray).all(|(r, g)| r.abs_diff(*g) <= 1), "red is the occlusion");
    assert!(red.iter().any(|&r| r < 200), "the mortar is occluded: not a constant 1");
    // Without the occlusion, red is glTF's 1.
    let plain =
        MapOutputs { normal_map: dir.join("p.png"), roughness: Some(dir.join("p_orm.png")), ..Default::default() };
    plain.write(HeightPreset::Bricks.render(32, 32), &options, false, TextureFormat::Rgba8, &[], &|_, _| {}).unwrap();
    let orm = bumpmap_io::load_rgba8(&dir.join("p_orm.png")).unwrap();
    assert!(orm.texels.iter().all(|t| t[0] == 255));
}

#[test]
fn a_folder_whose_inputs_share_an_output_is_refused() {
    let dir = scratch("folder");
    let input = dir.join("in");
    std::fs::create_dir_all(&input).unwrap();
    let field = HeightPreset::Bricks.render(8, 8);
    for name in ["a.png", "b.png"] {
        bumpmap_io::image_file::save_png(
            &input.join(name),
            8,
            8,
            bumpmap_io::image_file::PngLayout::Gray8,
            &field.to_u8(),
        )
        .unwrap();
    }
    let batch = FolderBatch::plan(&input, &dir.join("out"), true).unwrap();
    assert_eq!(batch.files.len(), 2);
    let failed =
        batch.run(&MapOptions::default(), true, TextureFormat::Rgba8, bumpmap_io::Channel::Luminance, &|_, r| {
            r.unwrap()
        });
    assert_eq!(failed, 0);
    assert!(files_in(&dir.join("out")).contains(&"a.mip3.png".to_string()));

    // a.mip1.png's output would be a level of a.png's chain; a.jpg's would be a.png's output.
    std::fs::copy(input.join("a.png"), input.join("a.mip1.png")).unwrap();
    assert!(matches!(FolderBatch::plan(&input, &dir.join("out"), true), Err(FolderError::MipOfAnother { .. })));
    assert!(FolderBatch::plan(&input, &dir.join("out"), false).is_ok(), "without mips, no chain to clash with");
    std::fs::copy(input.join("a.png"), input.join("b.tga")).unwrap();
    assert!(matches!(FolderBatch::plan(&input, &dir.join("out"), false), Err(FolderError::SameOutput { .. })));
    assert!(matches!(
        FolderBatch::plan(&input, &input, false),
        Err(FolderError::SameOutput { .. } | FolderError::SameFolder(_))
    ));
}

#[test]
fn a_negative_scale_makes_every_map_of_the_heights_turned_upside_down() {
    // `--scale -4` flips the normal map's slopes: the heights, horizons and occlusion written
    // beside it are those of 1 − h at scale 4, the surface the normal map shows (they were the
    // heights as given, the same as for +4's bumps).
    let field = HeightPreset::Bricks.render(64, 64);
    let flipped = bumpmap::HeightField::new(64, 64, field.to_f32().into_iter().map(|h| 1.0 - h).collect()).unwrap();
    let with = |scale: f32| {
        let mut o = MapOptions::default();
        o.normals.scale = scale;
        o
    };
    let (down, up) = (with(-4.0), with(4.0));
    let ao = |options: &MapOptions, f: &bumpmap::HeightField| {
        bumpmap::maps::horizon_map(options, f, &|_, _| {}).unwrap().ambient_occlusion(options.normals.scale.abs())
    };
    assert_eq!(ao(&down, &field), ao(&up, &flipped));
    assert_ne!(ao(&down, &field), ao(&up, &field), "bumps and dents are not occluded alike");
    let heights = |options: &MapOptions, f: &bumpmap::HeightField| {
        bumpmap::maps::height_mips(options, f).unwrap().mips.levels()[0].texels.clone()
    };
    assert_eq!(heights(&down, &field), heights(&up, &flipped));
    // The normal map itself: the same as 1 − h's at +4.
    let normals =
        |options: &MapOptions, f: &bumpmap::HeightField| match bumpmap::maps::normal_map(options, false, f).unwrap() {
            bumpmap::maps::Chain::Rgba8(c) => c.levels[0].texels.clone(),
            bumpmap::maps::Chain::Rgba16(_) => unreachable!("8 bits"),
        };
    assert_eq!(normals(&down, &field), normals(&up, &flipped));
}

#[test]
fn the_horizon_map_tells_its_rows_and_nothing_else_does() {
    use std::sync::Mutex;
    let dir = std::env::temp_dir().join(format!("bumpmap-outputs-told-{}", std::process::id()));
    let told = Mutex::new(Vec::new());
    let tell = |done: usize, total: usize| told.lock().unwrap().push((done, total));
    let field = || HeightPreset::Bricks.render(32, 24);
    let plain = MapOutputs { normal_map: dir.join("n.png"), ..Default::default() };
    plain.write(field(), &MapOptions::default(), false, TextureFormat::Rgba8, &[], &tell).unwrap();
    assert!(told.lock().unwrap().is_empty(), "no horizon map, nothing told");
    let with_ao = MapOutputs { normal_map: dir.join("n.png"), ambient_occlusion: Some(dir.join("ao.png")), ..plain };
    with_ao.write(field(), &MapOptions::default(), false, TextureFormat::Rgba8, &[], &tell).unwrap();
    let mut seen = told.into_inner().unwrap();
    // One call a row, from any thread, each with the rows in all.
    assert_eq!(seen.len(), 24);
    assert!(seen.iter().all(|&(_, total)| total == 24));
    seen.sort();
    assert_eq!(seen.iter().map(|&(done, _)| done).collect::<Vec<_>>(), (1..=24).collect::<Vec<_>>());
    std::fs::remove_dir_all(dir).unwrap();
}
