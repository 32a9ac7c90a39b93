//! One height field into the maps a bump-mapped material is made of, each as `bumpmap
//! normalmap` writes it and the Python package returns it: the normal map (level 0 or its
//! chain, 8 or 16 bits a channel), the heights the parallax techniques read, the horizon map
//! (ambient occlusion and bent normals come from it), the roughness map and LEAN's moments.
//!
//! ```
//! use bumpmap::maps::{self, Chain, MapOptions};
//! use bumpmap::HeightPreset;
//!
//! let field = HeightPreset::Bricks.render(64, 64);
//! let options = MapOptions { bits: 16, ..MapOptions::default() };
//! let Chain::Rgba16(chain) = maps::normal_map(&options, true, &field).unwrap() else { panic!() };
//! assert_eq!(chain.levels.len(), 7); // 64² down to 1²
//! let heights = maps::height_mips(&options, &field).unwrap();
//! assert!(heights.clamped.is_none(), "the preset's heights are in [0, 1]");
//! ```
//!
//! [`write_chain`] writes a chain as `normalmap -o` does (PNG files, or one DDS or KTX2 file);
//! [`write_cube_map`] a normalization cube map as `cubemap -o` does.
//!
//! [`MapOutputs`] is the whole set `normalmap` writes from one field — the files planned and
//! checked against each other, the memory of every map together refused up front, glTF's ORM
//! packing, all files or none — and [`FolderBatch`] a folder of fields into normal maps.
//!
//! What this module does not do: read height fields (`bumpmap_io`), or print (what a caller may
//! want to say comes back as data: [`Clamped`], [`Written`], [`FolderBatch::skipped`]).

mod blend;
mod cube;
mod files;
mod folder;
mod outputs;

pub use blend::{BlendError, BlendOptions, Blended, MAX_REPEAT, blend_files, blend_maps, blended_chain};
pub use cube::write_cube_map;
pub use files::{SaveError, chain_layout, check_container, write_chain, write_chain_into};
pub use folder::{FolderBatch, FolderError};
pub use outputs::{MapOutputs, Output, OutputsError, Written, lean_files, write_heights, write_heights_into};

use bumpmap_math::buffer::OutOfMemory;
use bumpmap_math::normalmap::{NormalMapError, normal_map_level0_texels};
use bumpmap_math::{
    HeightField, HeightMips, HeightMipsError, HorizonError, HorizonMap, Image, LeanMips, MipChain, MipMode,
    NormalMapOptions, Texel, YConvention,
};

use crate::options::RoughnessLayout;

/// How the maps are made from heights: the normal map's options and what the other maps need.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapOptions {
    /// How heights become normals: the kernel, the scale, the wrap, the Y convention, the
    /// encoding. The scale is also the depth, in texels, the horizons and the occlusion are
    /// taken at. A negative scale turns the bumps inward: the normal map's slopes flip, and the
    /// heights, horizons, occlusion and bent normals are those of the heights turned upside
    /// down (`1 − h`), the surface the normal map shows.
    pub normals: NormalMapOptions,
    /// Bits a channel the normal map and the heights are stored in: 8 or 16.
    pub bits: u8,
    /// What the smaller levels of the normal map hold.
    pub mip_mode: MipMode,
    /// The surface's own perceptual roughness, in [0, 1], for the roughness map.
    pub roughness: f32,
    /// The roughness map's channels.
    pub roughness_layout: RoughnessLayout,
}

impl Default for MapOptions {
    /// Green up (as glTF and Blender read a map), 8 bits, the length in alpha, roughness 0.5 in
    /// gray: what `bumpmap normalmap` makes with no flags.
    fn default() -> Self {
        MapOptions {
            normals: NormalMapOptions { y_convention: YConvention::YUp, ..Default::default() },
            bits: 8,
            mip_mode: MipMode::LengthInAlpha,
            roughness: 0.5,
            roughness_layout: RoughnessLayout::Gray,
        }
    }
}

/// Why a map cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum MapError {
    /// Bits a channel other than 8 or 16.
    #[error("bits must be 8 or 16, got {0}")]
    Bits(u8),
    /// A roughness outside [0, 1].
    #[error("roughness must be in [0, 1], got {0}")]
    Roughness(f32),
    /// The normal map (a scale out of range, or its buffers).
    #[error(transparent)]
    NormalMap(#[from] NormalMapError),
    /// The heights' levels.
    #[error(transparent)]
    Heights(#[from] HeightMipsError),
    /// The horizon map.
    #[error(transparent)]
    Horizons(#[from] HorizonError),
    /// A buffer that would not fit.
    #[error(transparent)]
    OutOfMemory(#[from] OutOfMemory),
}

impl MapOptions {
    /// Refuses bits other than 8 or 16 and a roughness outside [0, 1]. (The scale is checked
    /// where the normals are made.)
    pub fn check(&self) -> Result<(), MapError> {
        if !matches!(self.bits, 8 | 16) {
            return Err(MapError::Bits(self.bits));
        }
        if !(0.0..=1.0).contains(&self.roughness) {
            return Err(MapError::Roughness(self.roughness));
        }
        Ok(())
    }
}

/// A chain of RGBA levels at the depth it is stored in.
#[derive(Clone, Debug)]
pub enum Chain {
    /// 8 bits a channel (what RGBA8, BC5 and BC7 files hold).
    Rgba8(MipChain),
    /// 16 bits a channel.
    Rgba16(MipChain<[u16; 4]>),
}

/// Bytes a texel of level 0 costs beyond the height field itself, as measured (peak resident
/// memory of `normalmap bricks@4096 --mips` with each output alone, less the run without it,
/// over 4096², rounded up): the normal map at 8 and 16 bits (its chain and what making it
/// takes), and each map written beside it. A horizon map is shared by the horizons, the
/// occlusion and the bent normals; the bent normals cost a little more on top.
pub(crate) mod per_texel {
    pub const NORMAL_MAP_8: u64 = 8;
    pub const NORMAL_MAP_16: u64 = 18;
    pub const LEAN: u64 = 74;
    pub const ROUGHNESS: u64 = 20;
    pub const HEIGHTS: u64 = 24;
    pub const HORIZONS: u64 = 44;
    pub const BENT_NORMALS: u64 = 10;
}

/// Refuses, before anything of it is made, a map of `field` costing `per` bytes a texel of
/// level 0 (its [`per_texel`] figure) when it will not fit in the memory the process may still
/// have; a negative scale's upside-down copy of the field counts too.
fn ensure_room(options: &MapOptions, field: &HeightField, per: u64, what: &'static str) -> Result<(), MapError> {
    let per = per + if options.normals.scale < 0.0 { 4 } else { 0 };
    let bytes = (field.width() as u64 * field.height() as u64).saturating_mul(per);
    Ok(bumpmap_math::buffer::ensure_available(bytes, what)?)
}

/// The normal map of `field` at the depth `format` stores (16 bits a channel for
/// [`TextureFormat::Rgba16`](bumpmap_io::texture_file::TextureFormat), else 8): level 0, or
/// every level down to 1×1 with `mips`, the smaller levels as `options.mip_mode` says.
pub fn normal_map_as(
    options: &MapOptions,
    mips: bool,
    format: bumpmap_io::texture_file::TextureFormat,
    field: &HeightField,
) -> Result<Chain, MapError> {
    let (normals, mode) = (&options.normals, options.mip_mode);
    Ok(if format == bumpmap_io::texture_file::TextureFormat::Rgba16 {
        Chain::Rgba16(normal_chain(field, normals, mips, mode)?)
    } else {
        Chain::Rgba8(normal_chain(field, normals, mips, mode)?)
    })
}

/// The normal map of `field`: level 0, or every level down to 1×1 with `mips`, at
/// `options.bits`.
pub fn normal_map(options: &MapOptions, mips: bool, field: &HeightField) -> Result<Chain, MapError> {
    use bumpmap_io::texture_file::TextureFormat;
    options.check()?;
    let per = if options.bits == 16 { per_texel::NORMAL_MAP_16 } else { per_texel::NORMAL_MAP_8 };
    ensure_room(options, field, per, "making the normal map")?;
    let format = if options.bits == 16 { TextureFormat::Rgba16 } else { TextureFormat::Rgba8 };
    normal_map_as(options, mips, format, field)
}

/// The normal map of `field` in texels `T`: level 0, or every level with `mips`, the smaller
/// levels as `mode` says.
pub fn normal_chain<T: Texel>(
    field: &HeightField,
    normals: &NormalMapOptions,
    mips: bool,
    mode: MipMode,
) -> Result<MipChain<T>, NormalMapError> {
    if mips {
        MipChain::from_height(field, normals, mode)
    } else {
        let level = normal_map_level0_texels(field, normals)?;
        Ok(MipChain { levels: vec![level], encoding: normals.encoding })
    }
}

/// Heights outside [0, 1], which the stored heights clamp: 1 is the surface, 0 the parallax
/// depth below it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clamped {
    /// The lowest height of the field.
    pub lowest: f32,
    /// The highest.
    pub highest: f32,
}

impl std::fmt::Display for Clamped {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "heights from {} to {} are clamped to [0, 1] (1 on the surface, 0 at the depth below it)",
            self.lowest, self.highest
        )
    }
}

/// The heights as the parallax techniques read them, and whether the field had to be clamped.
#[derive(Clone, Debug)]
pub struct StoredHeights {
    /// The levels and the min–max levels.
    pub mips: HeightMips,
    /// The field's range, where it leaves [0, 1].
    pub clamped: Option<Clamped>,
}

/// The heights as a height map stores them: level 0 rounded to `options.bits` first, so that
/// the mean levels and the min–max bounds are those of the heights stored.
pub fn height_mips(options: &MapOptions, field: &HeightField) -> Result<StoredHeights, MapError> {
    options.check()?;
    ensure_room(options, field, per_texel::HEIGHTS, "making the heights' levels and bounds")?;
    let field = &*as_bumped(options, field);
    let mut row = Vec::new();
    let (mut lowest, mut highest) = (f32::INFINITY, f32::NEG_INFINITY);
    for y in 0..field.height() {
        for &v in field.row(y, &mut row) {
            (lowest, highest) = (lowest.min(v), highest.max(v));
        }
    }
    let clamped = (lowest < 0.0 || highest > 1.0).then_some(Clamped { lowest, highest });
    let steps = if options.bits == 16 { 65535 } else { 255 };
    Ok(StoredHeights { mips: HeightMips::from_field_rounded(field, steps)?, clamped })
}

/// The horizon map of `field`, read beyond its edges as the normal map's wrap says (ambient
/// occlusion and bent normals are made from it, at the depth `options.normals.scale`), telling
/// `progress(rows done, rows)` as level 0's rows finish: the long part (minutes for 8192²).
pub fn horizon_map(
    options: &MapOptions,
    field: &HeightField,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<HorizonMap, MapError> {
    options.check()?;
    ensure_room(options, field, per_texel::HORIZONS, "making the horizon map")?;
    Ok(HorizonMap::from_heights_told(&*as_bumped(options, field), options.normals.wrap, progress)?)
}

/// The heights of the surface the normal map shows: `field` itself, or turned upside down
/// (`1 − h`) where a negative scale turns the bumps inward.
fn as_bumped<'a>(options: &MapOptions, field: &'a HeightField) -> std::borrow::Cow<'a, HeightField> {
    if options.normals.scale >= 0.0 {
        return std::borrow::Cow::Borrowed(field);
    }
    let flipped = field.to_f32().into_iter().map(|h| 1.0 - h).collect();
    std::borrow::Cow::Owned(HeightField::new(field.width(), field.height(), flipped).expect("the same size"))
}

/// The bent normals of `horizons` (level 0), encoded as the normal map is and at its bits.
pub fn bent_normals(options: &MapOptions, horizons: &HorizonMap) -> Chain {
    let (depth, y, encoding) = (options.normals.scale.abs(), options.normals.y_convention, options.normals.encoding);
    match options.bits {
        16 => Chain::Rgba16(MipChain { levels: vec![horizons.bent_normal_map(depth, y, encoding)], encoding }),
        _ => Chain::Rgba8(MipChain { levels: vec![horizons.bent_normal_map(depth, y, encoding)], encoding }),
    }
}

/// The roughness map's levels (RGBA8, every level down to 1×1): the surface's roughness made
/// rougher where the normals a texel averages spread
/// ([`roughness_map`](crate::options::roughness_map)), in the channels the layout names.
pub fn roughness_map(options: &MapOptions, field: &HeightField) -> Result<MipChain, MapError> {
    options.check()?;
    ensure_room(options, field, per_texel::ROUGHNESS, "making the roughness map")?;
    Ok(crate::options::roughness_map(field, &options.normals, options.roughness, options.roughness_layout)?)
}

/// LEAN mapping's moments, every level, as two planes: (Bx, By, Mxx, Myy) and (Mxy, J, 0, 0).
/// They come from the 8-bit normal map's level 0 (what the renderer draws from, whatever bits
/// the map is stored at): `made`'s, as many levels as it has, when it is an 8-bit chain (its
/// mip mode changes no texel of level 0, and LEAN makes its own levels); else level 0 made
/// here, with every level down to 1×1.
pub fn lean_moments(
    options: &MapOptions,
    field: &HeightField,
    made: Option<&Chain>,
) -> Result<[Vec<Image<[f32; 4]>>; 2], MapError> {
    options.check()?;
    let per = per_texel::LEAN + if matches!(made, Some(Chain::Rgba8(_))) { 0 } else { per_texel::NORMAL_MAP_8 };
    ensure_room(options, field, per, "making LEAN's moments")?;
    let own;
    let (level0, count) = match made {
        Some(Chain::Rgba8(chain)) => (&chain.levels[0], chain.levels.len()),
        _ => {
            own = normal_map_level0_texels(field, &options.normals)?;
            (&own, bumpmap_math::mip::level_count(own.width, own.height))
        }
    };
    let lean = LeanMips::from_level0(level0, count, options.normals.encoding)?;
    let plane = |texel: fn(&bumpmap_math::LeanMoments) -> [f32; 4]| {
        lean.levels.iter().map(|l| Image::new(l.width, l.height, l.texels.iter().map(texel).collect())).collect()
    };
    Ok([plane(|t| [t.b.x, t.b.y, t.m.x, t.m.z]), plane(|t| [t.m.y, t.j, 0.0, 0.0])])
}
