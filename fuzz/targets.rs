//! The fuzz targets' bodies, in one place: the libFuzzer binaries in `fuzz_targets/` call them,
//! and `crates/bumpmap-cli/tests/fuzz_regressions.rs` replays every saved crash through them on
//! stable. Each must return (a value or an error, thrown away) and never panic.

// Each binary calls one of these.
#![allow(dead_code)]

use std::path::Path;

use bumpmap_io::{
    Channel, DecodeLimits, MeshFormat, StoredLevels, read_height_field, read_mesh, read_rgba8, read_texture,
};
use bumpmap_math::imported::{ImportOptions, import_normal_map};
use clap::Parser;

/// 1024² at most, so a declared size costs at most 1024² × 8 bytes (RGBA16) per image.
pub const IMAGE_LIMITS: DecodeLimits = DecodeLimits { max_dimension: 1024, max_alloc: 64 << 20 };

/// Image decoding as a height field (the first byte picks the channel; its bit 6 names the
/// file as a TGA) or, with the first byte's top bit set, as an RGBA8 texture (normal maps, decals, gloss maps).
pub fn image(data: &[u8]) {
    let Some((&pick, bytes)) = data.split_first() else { return };
    // A TGA has no magic bytes: only its name makes the reader try it.
    let name = Path::new(if pick & 0x40 != 0 { "fuzz.tga" } else { "fuzz.img" });
    let channel = [Channel::Luminance, Channel::Red, Channel::Green, Channel::Blue, Channel::Alpha][pick as usize % 5];
    if pick & 0x80 == 0 {
        let _ = read_height_field(bytes, name, channel, &IMAGE_LIMITS);
    } else {
        let _ = read_rgba8(bytes, name, &IMAGE_LIMITS);
    }
}

/// A normal map as `render --normal-map` reads it: a DDS, KTX2 or image file decoded with the
/// levels it carries (BC5 and BC7 blocks included), then brought into texture space; and as
/// `inspect` and `height` read it: every question asked, and its heights integrated.
pub fn texture(data: &[u8]) {
    use bumpmap::inspect::{DecodedMap, StoredAs, inspect_map};
    let Ok(texture) = read_texture(data, Path::new("fuzz.dds"), &IMAGE_LIMITS) else { return };
    let options = ImportOptions::default();
    let map = match &texture.levels {
        StoredLevels::Rgba8(levels) => {
            let _ = import_normal_map(levels, &options);
            DecodedMap::from_unorm(levels, StoredAs::Unorm8)
        }
        StoredLevels::Rgba16(levels) => {
            let _ = import_normal_map(levels, &options);
            DecodedMap::from_unorm(levels, StoredAs::Unorm16)
        }
    };
    let report = inspect_map("fuzz", &map);
    let _ = (report.lines(), report.to_json());
    if let Some(level0) = map.levels.first() {
        let _ = bumpmap::heights::heights_from_normals(level0, &Default::default());
    }
}

/// OBJ text to a mesh.
pub fn obj(data: &[u8]) {
    let _ = read_mesh(data, Path::new("fuzz.obj"), MeshFormat::Obj);
}

/// glTF JSON or GLB to a mesh, from memory: only data: URIs and the GLB chunk supply buffers
/// and the material's images; then made ready to draw as `render --scene mesh:` makes it
/// (tangents, the normal texture imported with its scale, the base colour tinted).
pub fn gltf(data: &[u8]) {
    let name = Path::new("fuzz.gltf");
    if let Ok(loaded) = read_mesh(data, name, MeshFormat::Gltf) {
        let _ = bumpmap::assets::mesh_asset(loaded, name, &bumpmap::assets::MeshLoad::default());
    }
}

/// The command line's parser and all its value parsers: words split on NUL, parsed, not run.
pub fn cli_args(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let words = std::iter::once("bumpmap").chain(text.split('\0'));
    if let Ok(cli) = bumpmap_cli::args::Cli::try_parse_from(words) {
        // The debug form walks every parsed value.
        let _ = format!("{cli:?}");
    }
}

/// A heights or horizon set as `render --height-map` / `--horizon-map` reads it: the file named
/// and the files found by name beside it. The first byte picks the container (its value mod 3:
/// PNG, KTX2, DDS) and the set (top bit: horizons); the rest is up to 8 files, each a 2-byte
/// little-endian length and its bytes: the named file, its sibling (`H.minmax` or `H.dirs4-7`),
/// then for PNG the `.mipK.png` levels of each in turn. Written into a folder of this process's
/// own, emptied first, and read back with every image bounded by [`IMAGE_LIMITS`].
pub fn height_sets(data: &[u8]) {
    use bumpmap_io::{height_file, horizon_file};
    let Some((&pick, mut rest)) = data.split_first() else { return };
    let ext = ["png", "ktx2", "dds"][pick as usize % 3];
    let horizons = pick & 0x80 != 0;
    let mut parts: Vec<&[u8]> = Vec::new();
    while parts.len() < 8 && rest.len() >= 2 {
        let n = (u16::from_le_bytes([rest[0], rest[1]]) as usize).min(rest.len() - 2);
        parts.push(&rest[2..2 + n]);
        rest = &rest[2 + n..];
    }
    let dir = std::env::temp_dir().join(format!("bumpmap-fuzz-sets-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    if std::fs::create_dir_all(&dir).is_err() {
        return;
    }
    let main = dir.join(format!("h.{ext}"));
    let sibling = if horizons { format!("h.dirs4-7.{ext}") } else { format!("h.minmax.{ext}") };
    let mut names = vec![main.clone(), dir.join(&sibling)];
    for k in 1..=3 {
        names.push(dir.join(format!("h.mip{k}.png")));
        names.push(dir.join(sibling.replace(".png", &format!(".mip{k}.png"))));
    }
    for (name, bytes) in names.iter().zip(&parts) {
        let _ = std::fs::write(name, bytes);
    }
    if horizons {
        let _ = horizon_file::files_read(&main);
        let _ = horizon_file::load_horizons_within(&main, Some(&IMAGE_LIMITS));
    } else {
        let _ = height_file::files_read(&main);
        let _ = height_file::load_heights_within(&main, Some(&IMAGE_LIMITS));
    }
    let _ = bumpmap_io::declared_size(&main);
    let _ = std::fs::remove_dir_all(&dir);
}
