//! A normal map file brought into texture space: its levels read as the file stores them, the Y
//! convention applied, the chain kept or rebuilt, and what looks wrong with it said as
//! [`Warning`]s. What this module does not do: decide what the texels mean
//! (`bumpmap_math::imported`) or parse the file (`bumpmap-io`).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use bumpmap_core::BumpSource;
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_io::{StoredLevels, StoredTexture};
use bumpmap_math::imported::{ImportOptions, import_normal_map};
use bumpmap_math::{MipChain, MipMode};

use super::{OFF_UNIT_WARNING, Warning};
use crate::error::Error;

/// A normal map read from a file, in texture space with its mip chain.
#[derive(Clone, Debug)]
pub struct LoadedNormalMap {
    /// Level 0 and the smaller levels (the file's own, or made with the chosen mip mode).
    pub chain: Arc<MipChain>,
    /// How the file stored its texels.
    pub format: TextureFormat,
    /// How many levels the file carried (1: the smaller ones were made here).
    pub stored_levels: usize,
    /// The fraction of level 0's texels off unit length.
    pub off_unit: f32,
    /// Whether the file's alpha held something else than the normal's length.
    pub foreign_alpha: bool,
    /// Whether the file's own smaller levels were renormalized (see
    /// [`bumpmap_math::imported::ImportedNormalMap::renormalized_mips`]).
    pub renormalized_mips: bool,
    /// Whether the smaller levels drawn are the file's own (false: made here from level 0).
    pub own_mips: bool,
    /// How the smaller levels were made when the file had none.
    pub mip_mode: MipMode,
    /// Where it came from.
    pub source: PathBuf,
}

impl LoadedNormalMap {
    /// What the map is, in words: size, format, and where its mips came from.
    pub fn describe(&self) -> String {
        let level = &self.chain.levels[0];
        let made = match self.mip_mode {
            MipMode::LengthInAlpha => "mips made with the length in alpha",
            MipMode::Renormalize => "mips made renormalized",
        };
        let mips = match self.stored_levels {
            1 => made.to_string(),
            n if self.own_mips => format!("its own {n} levels"),
            n => format!("{made} (its own {n} levels set aside)"),
        };
        format!("{}x{} {}, {mips}", level.width, level.height, self.format.dxgi_name())
    }

    /// Warnings when the map looks like no normal map, or packs something else in alpha.
    pub fn warnings(&self) -> Vec<Warning> {
        let mut w = Vec::new();
        if self.off_unit > OFF_UNIT_WARNING {
            w.push(Warning::NotUnitLength { path: self.source.clone(), fraction: self.off_unit });
        }
        if self.foreign_alpha {
            w.push(Warning::ForeignAlpha { path: self.source.clone() });
        }
        if self.renormalized_mips && self.own_mips {
            w.push(Warning::RenormalizedMips { path: self.source.clone() });
        }
        w
    }

    /// The map as a scene's bumps.
    pub fn bumps(&self) -> BumpSource {
        BumpSource::NormalMap(self.chain.clone())
    }
}

/// A normal map already read ([`bumpmap_io::load_texture`]'s, or levels made in memory) made
/// ready to draw as [`load_normal_map`] makes a file's; `source` names it in messages.
pub fn normal_map_from_texture(
    texture: &StoredTexture,
    source: &Path,
    options: &ImportOptions,
) -> Result<LoadedNormalMap, Error> {
    let imported = match &texture.levels {
        StoredLevels::Rgba8(levels) => import_normal_map(levels, options),
        StoredLevels::Rgba16(levels) => import_normal_map(levels, options),
    }
    .map_err(|source_err| Error::NormalMap { path: source.to_path_buf(), source: source_err })?;
    Ok(LoadedNormalMap {
        chain: Arc::new(imported.chain),
        format: texture.format,
        stored_levels: texture.levels.len(),
        off_unit: imported.off_unit,
        foreign_alpha: imported.foreign_alpha,
        renormalized_mips: imported.renormalized_mips,
        own_mips: imported.stored_mips,
        mip_mode: options.mip_mode,
        source: source.to_path_buf(),
    })
}

/// [`normal_map_from_texture`] of `given` where the caller holds the texture in memory, else
/// [`load_normal_map`] of `path`.
pub fn given_or_load_normal_map(
    path: &Path,
    given: Option<&StoredTexture>,
    options: &ImportOptions,
) -> Result<LoadedNormalMap, Error> {
    match given {
        Some(texture) => normal_map_from_texture(texture, path, options),
        None => load_normal_map(path, options),
    }
}

/// Which way green points, as the notes say it (`up: opengl`, `down: directx`).
pub fn green_way(y: bumpmap_math::YConvention) -> &'static str {
    match y {
        bumpmap_math::YConvention::YUp => "up: opengl",
        bumpmap_math::YConvention::YDown => "down: directx",
    }
}

/// Reads a normal map: a PNG (8 or 16 bits) or another image, or a DDS or KTX2 file with the
/// levels it carries (RGBA8, BGRA8, RGBA16, BC5 with Z rebuilt, BC7). `options` say which way
/// its green points, how to scale its slopes, and how to make its smaller levels when it has
/// none.
pub fn load_normal_map(path: &Path, options: &ImportOptions) -> Result<LoadedNormalMap, Error> {
    normal_map_from_texture(&bumpmap_io::load_texture(path)?, path, options)
}
