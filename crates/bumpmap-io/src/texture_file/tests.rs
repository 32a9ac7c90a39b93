//! The containers read back by independent readers (`ktx2`, `ddsfile`).

use super::*;

fn chain() -> Vec<Rgba8Image> {
    // 4×2 → 2×1 → 1×1 with distinct bytes per level.
    vec![
        Rgba8Image::new(4, 2, vec![[10; 4]; 8]),
        Rgba8Image::new(2, 1, vec![[20; 4]; 2]),
        Rgba8Image::new(1, 1, vec![[30; 4]]),
    ]
}

fn layout(data: &[Rgba8Image], faces: usize) -> TextureLayout<'_> {
    TextureLayout { faces: vec![data.iter().map(Level::from).collect(); faces] }
}

fn tmp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("bumpmap-{}-{name}", std::process::id()))
}

#[test]
fn ktx2_parses_with_an_independent_reader() {
    let data = chain();
    for faces in [1, 6] {
        let path = tmp(&format!("t{faces}.ktx2"));
        write_ktx2(&path, &layout(&data, faces), TextureFormat::Rgba8).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let reader = ktx2::Reader::new(&bytes[..]).expect("valid KTX2");
        let h = reader.header();
        assert_eq!((h.pixel_width, h.pixel_height, h.face_count, h.level_count), (4, 2, faces as u32, 3));
        assert_eq!(h.format, Some(ktx2::Format::R8G8B8A8_UNORM));
        for (k, level) in reader.levels().enumerate() {
            assert_eq!(level.data, data[k].as_bytes().repeat(faces).as_slice(), "level {k}");
        }
        std::fs::remove_file(path).unwrap();
    }
}

#[test]
fn float_levels_parse_with_independent_readers_and_refuse_other_formats() {
    let data: Vec<Image<[f32; 4]>> = vec![
        Image::new(2, 2, vec![[-1.5, 0.25, 2.25, 1e-3], [0.0, -0.0, 7.0, 1.0], [3.5, 1.0, 0.5, 2.0], [1.0; 4]]),
        Image::new(1, 1, vec![[0.5, -0.5, 1.25, 9.0]]),
    ];
    let tex = TextureLayout { faces: vec![data.iter().map(Level::Rgba32F).collect()] };
    let floats = |l: &Image<[f32; 4]>| l.texels.iter().flatten().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>();
    let path = tmp("tf.ktx2");
    write_ktx2(&path, &tex, TextureFormat::Rgba32Float).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let reader = ktx2::Reader::new(&bytes[..]).expect("valid KTX2");
    assert_eq!(reader.header().format, Some(ktx2::Format::R32G32B32A32_SFLOAT));
    assert_eq!(reader.header().type_size, 4);
    for (k, level) in reader.levels().enumerate() {
        assert_eq!(level.data, floats(&data[k]).as_slice(), "level {k}");
    }
    std::fs::remove_file(path).unwrap();
    let path = tmp("tf.dds");
    write_dds(&path, &tex, TextureFormat::Rgba32Float).unwrap();
    let dds = ddsfile::Dds::read(std::fs::File::open(&path).unwrap()).expect("valid DDS");
    assert_eq!(dds.get_dxgi_format(), Some(ddsfile::DxgiFormat::R32G32B32A32_Float));
    assert_eq!(dds.get_num_mipmap_levels(), 2);
    assert_eq!(dds.data, [floats(&data[0]), floats(&data[1])].concat());
    std::fs::remove_file(path).unwrap();
    // Floats are not squeezed into bytes, nor bytes passed off as floats.
    assert!(write_dds(&tmp("tf8.dds"), &tex, TextureFormat::Rgba8).is_err());
    let eight = chain();
    assert!(write_ktx2(&tmp("t8f.ktx2"), &layout(&eight, 1), TextureFormat::Rgba32Float).is_err());
}

#[test]
fn sixteen_bit_levels_parse_with_independent_readers() {
    let data: Vec<Rgba16Image> = vec![
        Rgba16Image::new(4, 2, (0..8).map(|i| [i * 1000, 65535 - i, 257, 65535]).collect()),
        Rgba16Image::new(2, 1, vec![[1, 2, 3, 4]; 2]),
        Rgba16Image::new(1, 1, vec![[40000; 4]]),
    ];
    let tex = TextureLayout { faces: vec![data.iter().map(Level::from).collect()] };
    let path = tmp("t16.ktx2");
    write_ktx2(&path, &tex, TextureFormat::Rgba16).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let reader = ktx2::Reader::new(&bytes[..]).expect("valid KTX2");
    assert_eq!(reader.header().format, Some(ktx2::Format::R16G16B16A16_UNORM));
    assert_eq!(reader.header().type_size, 2);
    for (k, level) in reader.levels().enumerate() {
        assert_eq!(level.data, data[k].to_le_bytes().as_slice(), "level {k}");
    }
    std::fs::remove_file(&path).unwrap();

    let path = tmp("t16.dds");
    write_dds(&path, &tex, TextureFormat::Rgba16).unwrap();
    let dds = ddsfile::Dds::read(&mut std::fs::File::open(&path).unwrap()).expect("valid DDS");
    assert_eq!(dds.get_dxgi_format(), Some(ddsfile::DxgiFormat::R16G16B16A16_UNorm));
    assert_eq!((dds.get_width(), dds.get_height(), dds.get_num_mipmap_levels()), (4, 2, 3));
    assert_eq!(dds.data, data.iter().flat_map(|l| l.to_le_bytes()).collect::<Vec<u8>>());
    std::fs::remove_file(path).unwrap();
}

#[test]
fn dds_parses_with_an_independent_reader() {
    let data = chain();
    let path = tmp("t.dds");
    write_dds(&path, &layout(&data, 1), TextureFormat::Rgba8).unwrap();
    let dds = ddsfile::Dds::read(&mut std::fs::File::open(&path).unwrap()).expect("valid DDS");
    assert_eq!((dds.get_width(), dds.get_height(), dds.get_num_mipmap_levels()), (4, 2, 3));
    assert_eq!(dds.data, data.iter().flat_map(|l| l.as_bytes().to_vec()).collect::<Vec<u8>>());
    std::fs::remove_file(path).unwrap();
}

#[test]
fn one_and_two_channel_levels_parse_with_independent_readers() {
    let gray: Vec<Image<u16>> = vec![Image::new(3, 2, vec![0, 1, 65535, 300, 40000, 7]), Image::new(1, 1, vec![99])];
    let pairs: Vec<Image<[u16; 2]>> = vec![
        Image::new(3, 2, vec![[0, 65535], [5, 6], [7, 8], [9, 10], [11, 12], [13, 14]]),
        Image::new(1, 1, vec![[1, 2]]),
    ];
    let bytes8: Vec<Image<u8>> = vec![Image::new(3, 2, vec![0, 1, 2, 253, 254, 255]), Image::new(1, 1, vec![128])];
    let le = |v: &[u16]| v.iter().flat_map(|c| c.to_le_bytes()).collect::<Vec<u8>>();
    // (levels, format, what the KTX2 and DDS readers should call it, each level's bytes)
    type Case<'a> = (TextureLayout<'a>, TextureFormat, ktx2::Format, ddsfile::DxgiFormat, Vec<Vec<u8>>);
    let cases: Vec<Case> = vec![
        (
            TextureLayout { faces: vec![bytes8.iter().map(Level::Gray8).collect()] },
            TextureFormat::R8,
            ktx2::Format::R8_UNORM,
            ddsfile::DxgiFormat::R8_UNorm,
            bytes8.iter().map(|l| l.texels.clone()).collect(),
        ),
        (
            TextureLayout { faces: vec![gray.iter().map(Level::Gray16).collect()] },
            TextureFormat::R16,
            ktx2::Format::R16_UNORM,
            ddsfile::DxgiFormat::R16_UNorm,
            gray.iter().map(|l| le(&l.texels)).collect(),
        ),
        (
            TextureLayout { faces: vec![pairs.iter().map(Level::Rg16).collect()] },
            TextureFormat::Rg16,
            ktx2::Format::R16G16_UNORM,
            ddsfile::DxgiFormat::R16G16_UNorm,
            pairs.iter().map(|l| le(l.texels.as_flattened())).collect(),
        ),
    ];
    for (tex, format, vk, dxgi, want) in cases {
        let path = tmp(&format!("{}.ktx2", format.dxgi_name()));
        write_ktx2(&path, &tex, format).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let reader = ktx2::Reader::new(&bytes[..]).expect("valid KTX2");
        assert_eq!(reader.header().format, Some(vk));
        for (k, level) in reader.levels().enumerate() {
            assert_eq!(level.data, want[k].as_slice(), "{} level {k}", format.dxgi_name());
        }
        std::fs::remove_file(&path).unwrap();
        let path = tmp(&format!("{}.dds", format.dxgi_name()));
        write_dds(&path, &tex, format).unwrap();
        let dds = ddsfile::Dds::read(std::fs::File::open(&path).unwrap()).expect("valid DDS");
        assert_eq!(dds.get_dxgi_format(), Some(dxgi));
        assert_eq!(dds.get_num_mipmap_levels(), 2);
        assert_eq!(dds.data, want.concat());
        std::fs::remove_file(path).unwrap();
    }
    // Heights are not squeezed into colour formats, nor colours into height formats.
    let tex = TextureLayout { faces: vec![gray.iter().map(Level::Gray16).collect()] };
    assert!(write_ktx2(&tmp("g.ktx2"), &tex, TextureFormat::Rgba8).is_err());
    assert!(write_ktx2(&tmp("c.ktx2"), &layout(&chain(), 1), TextureFormat::R16).is_err());
}
