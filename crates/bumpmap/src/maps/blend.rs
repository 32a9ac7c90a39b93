//! Detail normals, as `bumpmap blend BASE DETAIL -o OUT` makes them: a detail normal map laid
//! over a base one by one of `bumpmap_math::detail`'s blends, the detail tiled `repeat` times
//! across the base (sampled bilinearly, wrapping), its slopes scaled by `strength`; the result
//! at the base's size, as a chain of 8 or 16 bits.
//!
//! Mixed inputs are never mixed silently: a detail whose green points the other way is flipped
//! to the base's convention, and the result's bits are the finer input's unless asked; each of
//! these is said in [`Blended::notes`].
//!
//! What this module does not do: read or write files itself (`bumpmap_io` and
//! [`crate::maps::write_chain_into`] do), or blend at render time.

use std::path::{Path, PathBuf};

use bumpmap_io::atomic::FileSet;
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_math::detail::{BlendMethod, blend, with_strength};
use bumpmap_math::normalmap::encode_unit;
use bumpmap_math::{Encoding, Image, MipChain, MipMode, Named, Texel, YConvention};
use glam::{Vec3, Vec4};

use crate::inspect::{DecodedMap, StoredAs};
use crate::maps::{Chain, SaveError};

/// The most times a detail may repeat across the base.
pub const MAX_REPEAT: u32 = 4096;

/// How a detail map is laid over a base map.
#[derive(Clone, Debug, PartialEq)]
pub struct BlendOptions {
    /// The blend.
    pub method: BlendMethod,
    /// What the detail's slopes are multiplied by (0: no detail; 1: as it is).
    pub strength: f32,
    /// How many times the detail repeats across the base, in each direction.
    pub repeat: u32,
    /// Which way green points in the base's file, and in the result's.
    pub y_convention: YConvention,
    /// Which way green points in the detail's file (`None`: as in the base's).
    pub detail_y_convention: Option<YConvention>,
    /// Bits a channel of the result, 8 or 16 (`None`: the finer input's).
    pub bits: Option<u8>,
    /// Write the whole mip chain (the length of the averaged normal in alpha).
    pub mips: bool,
}

impl Default for BlendOptions {
    /// Reoriented normal mapping, full strength, the detail once across, green up, the finer
    /// input's bits, level 0 only.
    fn default() -> Self {
        BlendOptions {
            method: BlendMethod::Rnm,
            strength: 1.0,
            repeat: 1,
            y_convention: YConvention::YUp,
            detail_y_convention: None,
            bits: None,
            mips: false,
        }
    }
}

/// Why nothing was blended.
#[derive(Debug, thiserror::Error)]
pub enum BlendError {
    /// A strength that is negative or not finite.
    #[error("a detail strength must be finite and not negative, got {0}")]
    Strength(f32),
    /// A repeat out of range.
    #[error("a detail repeat must be 1 to {MAX_REPEAT}, got {0}")]
    Repeat(u32),
    /// Bits other than 8 or 16.
    #[error("bits must be 8 or 16, got {0}")]
    Bits(u8),
    /// A map without texels.
    #[error("the {0} map has no texels")]
    Empty(&'static str),
    /// The chain could not be made (its memory).
    #[error(transparent)]
    OutOfMemory(#[from] bumpmap_math::buffer::OutOfMemory),
    /// An input could not be read.
    #[error(transparent)]
    Read(#[from] crate::Error),
    /// The output could not be written (or would replace an input).
    #[error(transparent)]
    Save(#[from] SaveError),
}

/// A blend's result at level 0.
#[derive(Clone, Debug)]
pub struct Blended {
    /// The blended unit normals, in the base's Y convention, row 0 first.
    pub normals: Image<Vec3>,
    /// The bits the result is stored at.
    pub bits: u8,
    /// What was converted or chosen for mixed inputs, in words.
    pub notes: Vec<String>,
}

/// The bits a map was stored at, as the result would keep them: 16 for 16-bit and float maps.
fn bits_of(stored: StoredAs) -> u8 {
    match stored {
        StoredAs::Unorm16 | StoredAs::FloatSigned | StoredAs::FloatUnsigned => 16,
        StoredAs::Unorm8 | StoredAs::Bc5 | StoredAs::Bc7 => 8,
    }
}

/// `detail` laid over `base` (both level 0 of decoded maps) as `options` say.
pub fn blend_maps(base: &DecodedMap, detail: &DecodedMap, options: &BlendOptions) -> Result<Blended, BlendError> {
    if !(options.strength.is_finite() && options.strength >= 0.0) {
        return Err(BlendError::Strength(options.strength));
    }
    if !(1..=MAX_REPEAT).contains(&options.repeat) {
        return Err(BlendError::Repeat(options.repeat));
    }
    if let Some(bits) = options.bits.filter(|b| !matches!(b, 8 | 16)) {
        return Err(BlendError::Bits(bits));
    }
    let b = base.levels.first().filter(|l| !l.texels.is_empty()).ok_or(BlendError::Empty("base"))?;
    let d = detail.levels.first().filter(|l| !l.texels.is_empty()).ok_or(BlendError::Empty("detail"))?;
    let mut notes = Vec::new();
    let detail_y = options.detail_y_convention.unwrap_or(options.y_convention);
    let flip = if detail_y != options.y_convention {
        notes.push(format!(
            "the detail's green points {} ({}): flipped to the base's {}",
            if detail_y == YConvention::YUp { "up" } else { "down" },
            detail_y.name(),
            options.y_convention.name()
        ));
        -1.0
    } else {
        1.0
    };
    let (base_bits, detail_bits) = (bits_of(base.stored), bits_of(detail.stored));
    let bits = options.bits.unwrap_or(base_bits.max(detail_bits));
    if base_bits != detail_bits && options.bits.is_none() {
        notes.push(format!("the base is {base_bits}-bit and the detail {detail_bits}-bit: the result is {bits}-bit"));
    }
    let unit = |t: Vec4| t.truncate().normalize_or(Vec3::Z);
    // The detail at a base texel's centre: tiled `repeat` times, bilinear, wrapping.
    let (dw, dh) = (d.width as f32, d.height as f32);
    let sample = |x: usize, y: usize| -> Vec3 {
        let u = (x as f32 + 0.5) / b.width as f32 * options.repeat as f32 * dw - 0.5;
        let v = (y as f32 + 0.5) / b.height as f32 * options.repeat as f32 * dh - 0.5;
        let (x0, y0) = (u.floor(), v.floor());
        let (fx, fy) = (u - x0, v - y0);
        let at = |i: f32, j: f32| {
            let (i, j) = (i.rem_euclid(dw) as usize, j.rem_euclid(dh) as usize);
            unit(d.texels[j * d.width + i])
        };
        let mixed = at(x0, y0) * (1.0 - fx) * (1.0 - fy)
            + at(x0 + 1.0, y0) * fx * (1.0 - fy)
            + at(x0, y0 + 1.0) * (1.0 - fx) * fy
            + at(x0 + 1.0, y0 + 1.0) * fx * fy;
        let n = mixed.normalize_or(Vec3::Z);
        with_strength(Vec3::new(n.x, flip * n.y, n.z), options.strength)
    };
    let texels: Vec<Vec3> = (0..b.width * b.height)
        .map(|k| blend(unit(b.texels[k]), sample(k % b.width, k / b.width), options.method))
        .collect();
    Ok(Blended { normals: Image::new(b.width, b.height, texels), bits, notes })
}

/// The blend as a chain at its bits: level 0, or every level with `mips`.
pub fn blended_chain(blended: &Blended, mips: bool) -> Result<Chain, BlendError> {
    fn chain<T: Texel>(n: &Image<Vec3>, mips: bool) -> Result<MipChain<T>, BlendError> {
        Ok(if mips {
            MipChain::try_from_normals(n.width, n.height, &n.texels, Encoding::Unorm, MipMode::LengthInAlpha)?
        } else {
            let texels = n.texels.iter().map(|&v| encode_unit::<T>(v, Encoding::Unorm)).collect();
            MipChain { levels: vec![Image::new(n.width, n.height, texels)], encoding: Encoding::Unorm }
        })
    }
    Ok(match blended.bits {
        16 => Chain::Rgba16(chain(&blended.normals, mips)?),
        _ => Chain::Rgba8(chain(&blended.normals, mips)?),
    })
}

/// Reads `base` and `detail` (any normal map `inspect` reads), blends, and writes `out` (PNG
/// with `.mipN.png` beside it, DDS or KTX2; uncompressed), all its files or none.
pub fn blend_files(
    base: &Path,
    detail: &Path,
    out: &Path,
    options: &BlendOptions,
) -> Result<(Blended, Vec<PathBuf>), BlendError> {
    let format = |bits: u8| if bits == 16 { TextureFormat::Rgba16 } else { TextureFormat::Rgba8 };
    let (base_map, detail_map) = (crate::inspect::read_map(base)?, crate::inspect::read_map(detail)?);
    let blended = blend_maps(&base_map, &detail_map, options)?;
    let chain = blended_chain(&blended, options.mips)?;
    let mut set = FileSet::new(&[base, detail]);
    crate::maps::write_chain_into(&mut set, out, &chain, format(blended.bits))?;
    let files = set.commit().map_err(|e| BlendError::Save(SaveError::Io(e)))?;
    Ok((blended, files))
}
