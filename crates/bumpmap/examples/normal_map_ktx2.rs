//! A height field becomes a normal map with its mip chain (the length of the averaged normal in
//! alpha, Kilgard §5.3), written as one KTX2 file for an engine, and read back as a renderer
//! reads a user's map; level 0 read back is held against its screenshot
//! (`examples/screenshots/normal_map_ktx2.png`) exactly: integer arithmetic from a preset,
//! the same bytes on every machine.
//!
//! `cargo run --release -p bumpmap --example normal_map_ktx2 [OUT.ktx2]`

use std::path::PathBuf;

use bumpmap::assets::load_normal_map;
use bumpmap::bumpmap_io::texture_file::{Level, TextureFormat, TextureLayout, write_ktx2};
use bumpmap::{HeightPreset, ImportOptions, MipChain, MipMode, NormalMapOptions, YConvention};

fn main() -> Result<(), bumpmap::Error> {
    let out = std::env::args().nth(1).map_or_else(|| PathBuf::from("out/examples/bricks.ktx2"), PathBuf::from);
    let heights = HeightPreset::Bricks.render(256, 256);
    // Green up, as glTF, Blender and Unity read normal maps.
    let options = NormalMapOptions { scale: 4.0, y_convention: YConvention::YUp, ..Default::default() };
    let chain = MipChain::<[u8; 4]>::from_height(&heights, &options, MipMode::LengthInAlpha)
        .map_err(|e| bumpmap::Error::Core(e.into()))?;
    let layout = TextureLayout { faces: vec![chain.levels.iter().map(Level::from).collect()] };
    write_ktx2(&out, &layout, TextureFormat::Rgba8)?;

    // Read back with every level the file carries, green turned to point along +t.
    let map = load_normal_map(&out, &ImportOptions::default())?;
    assert_eq!(map.stored_levels, chain.len(), "every level travels in the file");
    let screenshot = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/screenshots/normal_map_ktx2.png");
    let level0 = &map.chain.levels[0];
    let db = bumpmap_testkit::assert_screenshot("normal_map_ktx2", screenshot.as_ref(), level0, f64::INFINITY, "exact");
    assert!(db.is_infinite());
    let far = map.chain.levels.last().expect("a chain");
    println!(
        "wrote {} ({}); its 1x1 level keeps a length of {:.2} in alpha: the bricks dim at a distance",
        out.display(),
        map.describe(),
        far.texels[0][3] as f32 / 255.0
    );
    Ok(())
}
