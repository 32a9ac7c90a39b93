//! BC5 and BC7 normal maps read back by readers other than ours: the DDS container by
//! `ddsfile`, the KTX2 container by `ktx2`, the blocks by `image_dds`'s decoder (`bcdec_rs`,
//! not the ISPC encoder that wrote them). The decoded normals must stay within a stated angle of
//! the uncompressed map, on every level of the chain.

use std::path::PathBuf;

use bumpmap_io::texture_file::{TextureFormat, TextureLayout, write_dds, write_ktx2};
use bumpmap_math::{HeightPreset, MipChain, MipMode, NormalMapOptions, Rgba8Image, YConvention};

/// A file under the target folder (not the system's temporary one: a run leaves nothing in /tmp).
fn tmp(name: &str) -> PathBuf {
    std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("bc-{}-{name}", std::process::id()))
}

/// The unit normal a texel encodes; for BC5, Z rebuilt from X and Y as a shader does.
fn normal(t: [u8; 4], two_channel: bool) -> glam::Vec3 {
    let x = t[0] as f32 / 255.0 * 2.0 - 1.0;
    let y = t[1] as f32 / 255.0 * 2.0 - 1.0;
    let z = if two_channel { (1.0 - x * x - y * y).max(0.0).sqrt() } else { t[2] as f32 / 255.0 * 2.0 - 1.0 };
    glam::Vec3::new(x, y, z).normalize_or_zero()
}

/// Worst and mean angle in degrees between two levels' normals.
fn angles(want: &Rgba8Image, got: &[u8], two_channel: bool) -> (f32, f32) {
    let mut worst = 0.0f32;
    let mut sum = 0.0f64;
    for (w, g) in want.texels.iter().zip(got.chunks_exact(4)) {
        let a =
            normal(*w, false).dot(normal([g[0], g[1], g[2], g[3]], two_channel)).clamp(-1.0, 1.0).acos().to_degrees();
        worst = worst.max(a);
        sum += a as f64;
    }
    (worst, (sum / want.texels.len() as f64) as f32)
}

fn decode(format: image_dds::ImageFormat, w: usize, h: usize, data: &[u8]) -> Vec<u8> {
    let surface = image_dds::Surface {
        width: w as u32,
        height: h as u32,
        depth: 1,
        layers: 1,
        mipmaps: 1,
        image_format: format,
        data,
    };
    surface.decode_rgba8().unwrap().data
}

#[test]
fn bc5_and_bc7_decode_elsewhere_to_within_a_stated_angle_of_the_uncompressed_map() {
    let field = HeightPreset::Bricks.render(256, 256);
    let options = NormalMapOptions { y_convention: YConvention::YUp, ..Default::default() };
    let chain = MipChain::<[u8; 4]>::from_height(&field, &options, MipMode::LengthInAlpha).unwrap();
    let layout = TextureLayout { faces: vec![chain.levels.iter().map(Into::into).collect()] };
    // (format, DXGI, theirs, worst bound, mean bound). BC5 keeps 8 bits of X and Y in 3-bit
    // palettes of a 4×4 block; BC7's shared endpoints bend the steep mortar edges more. The
    // bounds are about 1.4× the worst level measured (README).
    let cases = [
        (TextureFormat::Bc5, ddsfile::DxgiFormat::BC5_UNorm, image_dds::ImageFormat::BC5RgUnorm, 12.0, 2.0),
        (TextureFormat::Bc7, ddsfile::DxgiFormat::BC7_UNorm, image_dds::ImageFormat::BC7RgbaUnorm, 36.0, 5.0),
    ];
    for (format, dxgi, theirs, worst_bound, mean_bound) in cases {
        let path = tmp(&format!("{format:?}.dds"));
        write_dds(&path, &layout, format).unwrap();
        let dds = ddsfile::Dds::read(std::fs::File::open(&path).unwrap()).expect("a DDS ddsfile reads");
        assert_eq!(dds.get_dxgi_format(), Some(dxgi));
        assert_eq!((dds.get_width(), dds.get_height()), (256, 256));
        assert_eq!(dds.get_num_mipmap_levels() as usize, chain.levels.len());
        let mut offset = 0;
        for (k, level) in chain.levels.iter().enumerate() {
            let blocks = level.width.div_ceil(4) * level.height.div_ceil(4);
            let bytes = &dds.data[offset..offset + 16 * blocks];
            offset += 16 * blocks;
            let (worst, mean) =
                angles(level, &decode(theirs, level.width, level.height, bytes), format == TextureFormat::Bc5);
            eprintln!("{format:?} level {k} ({}²): worst {worst:.2}°, mean {mean:.3}°", level.width);
            if k == 0 {
                assert!(mean > 0.0, "{format:?}: a lossless result would mean nothing was compressed");
            }
            assert!(worst < worst_bound && mean < mean_bound, "{format:?} level {k}: {worst}° worst, {mean}° mean");
        }
        assert_eq!(offset, dds.data.len(), "{format:?}: every level, nothing more");
        // The same blocks in KTX2, smallest level last in the index, read by `ktx2`.
        let path = tmp(&format!("{format:?}.ktx2"));
        write_ktx2(&path, &layout, format).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let reader = ktx2::Reader::new(&bytes[..]).expect("a KTX2 the ktx2 crate reads");
        let want =
            if format == TextureFormat::Bc5 { ktx2::Format::BC5_UNORM_BLOCK } else { ktx2::Format::BC7_UNORM_BLOCK };
        assert_eq!(reader.header().format, Some(want));
        let mut offset = 0;
        for (level, data) in chain.levels.iter().zip(reader.levels()) {
            let blocks = level.width.div_ceil(4) * level.height.div_ceil(4);
            assert_eq!(
                data.data,
                &dds.data[offset..offset + 16 * blocks],
                "{format:?}: KTX2 and DDS hold the same blocks"
            );
            offset += 16 * blocks;
        }
    }
}

#[test]
fn partial_edge_blocks_are_filled_from_the_edge_not_with_zeros() {
    // A smooth 130² map: the last two columns and rows sit in blocks half outside the level.
    // Filled with zeros, those blocks' endpoints were pulled toward (0, 0, 0): here the BC5
    // edge came back 3.7° off against 0.03° inside (on issue #23's steeper ramp, 26° for BC5
    // and 59° for BC7); filled by repeating the edge, they are as good as the inside.
    let field = bumpmap_math::HeightField::from_fn(130, 130, |x, y| {
        0.5 + 0.25 * (x as f32 / 17.0).sin() * (y as f32 / 23.0).cos()
    });
    let options = NormalMapOptions { scale: 8.0, wrap: bumpmap_math::Wrap::Clamp, ..Default::default() };
    let level = bumpmap_math::normalmap::normal_map_level0_texels::<[u8; 4]>(&field, &options).unwrap();
    let layout = TextureLayout { faces: vec![vec![(&level).into()]] };
    for (format, theirs) in [
        (TextureFormat::Bc5, image_dds::ImageFormat::BC5RgUnorm),
        (TextureFormat::Bc7, image_dds::ImageFormat::BC7RgbaUnorm),
    ] {
        let path = tmp(&format!("edge-{format:?}.dds"));
        write_dds(&path, &layout, format).unwrap();
        let dds = ddsfile::Dds::read(std::fs::File::open(&path).unwrap()).unwrap();
        assert_eq!((dds.get_width(), dds.get_height()), (130, 130));
        let got = decode(theirs, 130, 130, &dds.data);
        let two = format == TextureFormat::Bc5;
        let angle = |x: usize, y: usize| {
            let i = y * 130 + x;
            let g = &got[4 * i..4 * i + 4];
            normal(level.texels[i], false)
                .dot(normal([g[0], g[1], g[2], g[3]], two))
                .clamp(-1.0, 1.0)
                .acos()
                .to_degrees()
        };
        let (mut inside, mut edge) = (0.0f32, 0.0f32);
        for y in 0..130 {
            for x in 0..130 {
                if x >= 128 || y >= 128 { edge = edge.max(angle(x, y)) } else { inside = inside.max(angle(x, y)) }
            }
        }
        eprintln!("{format:?} 130²: worst inside {inside:.2}°, worst in the partial edge blocks {edge:.2}°");
        // The edge blocks hold fewer distinct normals than a whole block: no worse than inside,
        // with half a degree for the block's own quantization.
        assert!(edge <= inside + 0.5, "{format:?}: edge {edge}° against {inside}° inside");
        std::fs::remove_file(&path).ok();
    }
}
