//! Normal maps made elsewhere (a file's levels, a glTF material's texture) brought into this
//! crate's texture space: green turned to point along +t, glTF's normal scale applied, unit
//! length checked, and — when the map brings no smaller levels of its own — a mip chain with
//! the length of the averaged normal in alpha, as [`MipChain::from_height`] makes for heights.
//!
//! What this module does not do: read files (that is `bumpmap-io`, which also rebuilds BC5's Z
//! before the levels get here), or repair a map whose smaller levels another tool renormalized
//! (their A = 1 is kept; it is what the file says).

use glam::Vec3;
use rayon::prelude::*;

use crate::encoding::{Encoding, Texel};
use crate::image::Image;
use crate::levels::next_size;
use crate::mip::{MipChain, MipMode};
use crate::normalmap::{YConvention, encode_unit};

/// How far a stored vector's length may be from 1 before it counts as not a unit vector: well
/// above 8-bit quantization (|n| is within 0.007 of 1 for any unorm-encoded unit vector) and
/// BC5's, well below what a colour photograph's texels are.
pub const UNIT_TOLERANCE: f32 = 0.1;

/// The largest |scale| an imported map takes (glTF's `normalTexture.scale`).
pub const MAX_SCALE: f32 = 1000.0;

/// How a normal map made elsewhere is read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImportOptions {
    /// Which way the map's green points as the image is displayed.
    pub y_convention: YConvention,
    /// glTF's `normalTexture.scale`: X and Y are multiplied by it before renormalizing
    /// (`normalize((2c − 1) ⊙ (scale, scale, 1))`); 1 keeps the map as stored.
    pub scale: f32,
    /// What the smaller levels store when the map has none of its own.
    pub mip_mode: MipMode,
    /// Make the smaller levels from level 0 (with [`ImportOptions::mip_mode`]) even when the
    /// map has its own: what to do with levels another tool renormalized.
    pub rebuild_mips: bool,
}

impl Default for ImportOptions {
    /// Green up (glTF, Blender, and what `bumpmap normalmap` writes), scale 1, the length in
    /// alpha.
    fn default() -> Self {
        Self { y_convention: YConvention::YUp, scale: 1.0, mip_mode: MipMode::LengthInAlpha, rebuild_mips: false }
    }
}

/// A normal map in texture space, 8 bits a channel, unorm.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportedNormalMap {
    /// Level 0 and its smaller levels (the map's own, or made here down to 1×1).
    pub chain: MipChain,
    /// The fraction of level 0's texels whose stored vector is more than
    /// [`UNIT_TOLERANCE`] from unit length: near 0 for a normal map, large for a photograph.
    pub off_unit: f32,
    /// Whether the levels below 0 are the map's own (`false`: made here, or there are none).
    pub stored_mips: bool,
    /// Whether the map's alpha held something other than the normal's length (level 0's was not
    /// 1 everywhere: a height or a gloss packed there): it was replaced by the length.
    pub foreign_alpha: bool,
    /// Whether the map's own level 1 says every averaged normal has length 1 where averaging
    /// level 0 gives shorter ones: the levels were renormalized (as most tools write them), and
    /// the length factor (Kilgard §5.3) and Toksvig's filter, which read that length, have
    /// nothing to work with. Kept as stored; [`ImportOptions::rebuild_mips`] makes them anew.
    pub renormalized_mips: bool,
}

/// The longest the mean of a 2×2 block of level 0 may be, somewhere, for a map's own level 1
/// with alpha 1 everywhere to count as renormalized: a map whose neighbouring normals barely
/// differ loses nothing by renormalizing.
pub const RENORMALIZED_BELOW: f32 = 0.97;

/// The lowest level-0 alpha (of 1) still read as "the normal's length is 1": a map whose level
/// 0 has a lower alpha anywhere packs something else there.
pub const OPAQUE_ALPHA: f32 = 0.98;

/// Why a map cannot be imported.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ImportError {
    /// No level at all, or an empty one.
    #[error("the map has no texels")]
    Empty,
    /// A smaller level whose size is not half the one before it.
    #[error(
        "mip level {level} is {got_width}x{got_height}, but a {width}x{height} level 0 makes it {want_width}x{want_height}"
    )]
    LevelSize {
        /// The level's index.
        level: usize,
        /// Level 0's width.
        width: usize,
        /// Level 0's height.
        height: usize,
        /// Its width.
        got_width: usize,
        /// Its height.
        got_height: usize,
        /// The width it must have.
        want_width: usize,
        /// The height it must have.
        want_height: usize,
    },
    /// A scale that is not finite or beyond [`MAX_SCALE`].
    #[error("the normal scale must be a number in [-{MAX_SCALE}, {MAX_SCALE}], got {0}")]
    BadScale(f32),
    /// The texture-space chain (and, when the levels are made here, the normals they average)
    /// would not fit in the memory the process may still have.
    #[error(transparent)]
    OutOfMemory(#[from] crate::buffer::OutOfMemory),
}

/// The bytes [`import_normal_map`] works in for a `width`×`height` level 0, besides the levels
/// given: the RGBA8 chain it returns (4/3 of level 0), and when it makes the smaller levels
/// itself, level 0's unit normals twice (the vectors and the sums the first level averages,
/// 12 bytes a texel each), the next level's sums and level 0 encoded once more.
pub fn import_bytes(width: usize, height: usize, makes_levels: bool) -> u64 {
    let texels = width as u64 * height as u64;
    let chain = texels * 4 * 4 / 3;
    if makes_levels { chain + texels * (12 + 12 + 3 + 4) } else { chain }
}

/// Brings `levels` (level 0 first; one level for a file without mips) into texture space.
///
/// Level 0's texels are kept as stored where nothing changes them (8 bits, Y already along +t,
/// scale 1), but for A, which is the length of a unit normal there: 1. A file's smaller levels
/// keep their alpha (the length of the averaged normal, as this crate's files store it) unless
/// level 0's alpha shows the map packs something else there; then every level's A is the
/// length of its stored vector. A mirrored green is `max − g`, the opposite direction in the symmetric unorm
/// encoding — within one step of what a map written the other way holds, as the writer rounded
/// a tie (127.5·y a whole number, y = 0 among them) up both ways. The smaller levels are the map's own, treated the same way, or made
/// from level 0's renormalized vectors as [`MipChain::from_normals`] makes them.
pub fn import_normal_map<T: Texel>(
    levels: &[Image<T>],
    options: &ImportOptions,
) -> Result<ImportedNormalMap, ImportError> {
    let Some(level0) = levels.first().filter(|l| l.width > 0 && l.height > 0 && l.texels.len() == l.width * l.height)
    else {
        return Err(ImportError::Empty);
    };
    let (width, height) = (level0.width, level0.height);
    let (mut w, mut h) = (width, height);
    for (k, level) in levels.iter().enumerate().skip(1) {
        (w, h) = (next_size(w), next_size(h));
        if (level.width, level.height) != (w, h) || level.texels.len() != w * h {
            return Err(ImportError::LevelSize {
                level: k,
                width,
                height,
                got_width: level.width,
                got_height: level.height,
                want_width: w,
                want_height: h,
            });
        }
    }
    let scale = options.scale;
    if !(scale.is_finite() && scale.abs() <= MAX_SCALE) {
        return Err(ImportError::BadScale(scale));
    }
    let stored_mips = levels.len() > 1 && !options.rebuild_mips;
    crate::buffer::ensure_available(import_bytes(width, height, !stored_mips), "the normal map in texture space")?;
    let mirror = options.y_convention != YConvention::TEXTURE_SPACE;
    let to_texture_space = |t: T| if mirror { t.mirror_green() } else { t };
    let enc = Encoding::Unorm;
    let rescaled = scale != 1.0;
    // A stored texel as a direction in texture space, scaled as glTF says.
    let direction = |t: T| {
        let [x, y, z, _] = to_texture_space(t).unpack(enc);
        Vec3::new(x * scale, y * scale, z)
    };
    // Level 0's bytes, and its unit vectors for the smaller levels.
    let off = level0
        .texels
        .par_iter()
        .filter(|&&t| {
            let [x, y, z, _] = t.unpack(enc);
            (Vec3::new(x, y, z).length() - 1.0).abs() > UNIT_TOLERANCE
        })
        .count();
    // Asked for fallibly as well as estimated above: the estimate probes the address space
    // once, and what the allocator then hands out can still fall short by a little.
    const WHAT: &str = "the normal map in texture space";
    let convert = |level: &Image<T>| -> Result<Image<[u8; 4]>, ImportError> {
        let mut texels = Vec::new();
        texels
            .try_reserve_exact(level.texels.len())
            .map_err(|_| crate::buffer::OutOfMemory::of::<[u8; 4]>(WHAT, level.texels.len()))?;
        texels.par_extend(level.texels.par_iter().map(|&t| {
            if rescaled {
                let a = t.to_rgba8()[3];
                let [r, g, b, _] = encode_unit::<[u8; 4]>(direction(t).normalize_or(Vec3::Z), enc);
                [r, g, b, a]
            } else {
                to_texture_space(t).to_rgba8()
            }
        }));
        Ok(Image { width: level.width, height: level.height, texels })
    };
    let foreign_alpha = level0.texels.iter().any(|t| t.unpack(enc)[3] < OPAQUE_ALPHA);
    let renormalized_mips = levels.len() > 1 && !foreign_alpha && renormalized(levels, &direction);
    let chain = if stored_mips {
        let mut chain = MipChain { levels: levels.iter().map(convert).collect::<Result<_, _>>()?, encoding: enc };
        if foreign_alpha {
            for level in &mut chain.levels[1..] {
                for t in &mut level.texels {
                    let [x, y, z, _] = t.unpack(enc);
                    t[3] = enc.encode_unsigned(Vec3::new(x, y, z).length());
                }
            }
        }
        chain.levels[0].texels.iter_mut().for_each(|t| t[3] = 255);
        chain
    } else {
        let mut normals: Vec<Vec3> = Vec::new();
        normals
            .try_reserve_exact(level0.texels.len())
            .map_err(|_| crate::buffer::OutOfMemory::of::<Vec3>(WHAT, level0.texels.len()))?;
        normals.par_extend(level0.texels.par_iter().map(|&t| direction(t).normalize_or(Vec3::Z)));
        let mut chain = MipChain::<[u8; 4]>::try_from_normals(width, height, &normals, enc, options.mip_mode)?;
        chain.levels[0] = convert(level0)?;
        chain.levels[0].texels.iter_mut().for_each(|t| t[3] = 255);
        chain
    };
    Ok(ImportedNormalMap {
        chain,
        off_unit: off as f32 / (width * height) as f32,
        stored_mips,
        foreign_alpha,
        renormalized_mips,
    })
}

/// Whether `levels[1]` stores length 1 everywhere (alpha ≥ [`OPAQUE_ALPHA`]) though the mean of
/// some 2×2 block of level 0's unit normals is shorter than [`RENORMALIZED_BELOW`].
fn renormalized<T: Texel>(levels: &[Image<T>], direction: &(impl Fn(T) -> Vec3 + Sync)) -> bool {
    let (level0, level1) = (&levels[0], &levels[1]);
    if level1.texels.iter().any(|&t| t.unpack(Encoding::Unorm)[3] < OPAQUE_ALPHA) {
        return false;
    }
    let w = level0.width;
    (0..level0.height / 2).into_par_iter().any(|y| {
        (0..w / 2).any(|x| {
            let at =
                |dx: usize, dy: usize| direction(level0.texels[(2 * y + dy) * w + 2 * x + dx]).normalize_or(Vec3::Z);
            ((at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1)) * 0.25).length() < RENORMALIZED_BELOW
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{HeightField, HeightPreset, NormalMapOptions};

    fn chain_of(convention: YConvention) -> MipChain {
        let field = HeightPreset::Bricks.render(32, 32);
        MipChain::<[u8; 4]>::from_height(
            &field,
            &NormalMapOptions { y_convention: convention, ..Default::default() },
            MipMode::LengthInAlpha,
        )
        .unwrap()
    }

    #[test]
    fn a_y_down_map_keeps_its_level_0_bytes_and_its_chain_within_a_step() {
        let made = chain_of(YConvention::YDown);
        let options = ImportOptions { y_convention: YConvention::YDown, ..Default::default() };
        let got = import_normal_map(&made.levels[..1], &options).unwrap();
        assert_eq!(got.chain.levels[0], made.levels[0], "level 0 as stored");
        assert!(!got.stored_mips && got.off_unit == 0.0);
        assert_eq!(got.chain.levels.len(), made.levels.len());
        // The smaller levels average the stored (quantized) normals rather than the float ones:
        // within one step of the chain made from the heights.
        for (k, (a, b)) in got.chain.levels.iter().zip(&made.levels).enumerate() {
            for (p, q) in a.texels.iter().zip(&b.texels) {
                assert!(p.iter().zip(q).all(|(x, y)| x.abs_diff(*y) <= 1), "level {k}: {p:?} vs {q:?}");
            }
        }
    }

    #[test]
    fn a_y_up_map_reads_back_as_the_y_down_one_but_at_ties() {
        let (up, down) = (chain_of(YConvention::YUp), chain_of(YConvention::YDown));
        let got = import_normal_map(&up.levels[..1], &ImportOptions::default()).unwrap();
        for (p, q) in got.chain.levels[0].texels.iter().zip(&down.levels[0].texels) {
            assert_eq!([p[0], p[2], p[3]], [q[0], q[2], q[3]]);
            // Where 127.5·y is whole (y = 0 among them) the writer rounded up both ways.
            assert!(p[1] == q[1] || p[1] + 1 == q[1], "{p:?} vs {q:?}");
        }
        // Read with the wrong convention, the slopes along t point the other way.
        let wrong = import_normal_map(
            &up.levels[..1],
            &ImportOptions { y_convention: YConvention::YDown, ..Default::default() },
        )
        .unwrap();
        assert_eq!(wrong.chain.levels[0], up.levels[0]);
        assert_ne!(wrong.chain.levels[0], got.chain.levels[0]);
    }

    #[test]
    fn stored_mips_are_kept_and_checked() {
        let made = chain_of(YConvention::YDown);
        let options = ImportOptions { y_convention: YConvention::YDown, ..Default::default() };
        let got = import_normal_map(&made.levels, &options).unwrap();
        assert!(got.stored_mips);
        assert_eq!(got.chain.levels, made.levels);
        let mut wrong = made.levels.clone();
        wrong[2] = Image::new(3, 3, vec![[128, 128, 255, 255]; 9]);
        let err = import_normal_map(&wrong, &options).unwrap_err();
        assert!(matches!(err, ImportError::LevelSize { level: 2, want_width: 8, want_height: 8, .. }), "{err}");
        assert_eq!(err.to_string(), "mip level 2 is 3x3, but a 32x32 level 0 makes it 8x8");
    }

    #[test]
    fn sixteen_bits_round_to_the_eight_bit_map() {
        let field = HeightPreset::Dimples.render(16, 16);
        let o = NormalMapOptions { y_convention: YConvention::YUp, ..Default::default() };
        let wide = MipChain::<[u16; 4]>::from_height(&field, &o, MipMode::LengthInAlpha).unwrap();
        let narrow = MipChain::<[u8; 4]>::from_height(&field, &o, MipMode::LengthInAlpha).unwrap();
        let a = import_normal_map(&wide.levels[..1], &ImportOptions::default()).unwrap();
        let b = import_normal_map(&narrow.levels[..1], &ImportOptions::default()).unwrap();
        for (p, q) in a.chain.levels[0].texels.iter().zip(&b.chain.levels[0].texels) {
            assert!(p.iter().zip(q).all(|(x, y)| x.abs_diff(*y) <= 1), "{p:?} vs {q:?}");
        }
    }

    #[test]
    fn scale_steepens_the_slopes_and_a_photo_is_off_unit() {
        // Gentle slopes, which doubling the scale nearly doubles.
        let field = HeightPreset::Dimples.render(32, 32);
        let gentle = NormalMapOptions { scale: 0.5, ..Default::default() };
        let made = MipChain::<[u8; 4]>::from_height(&field, &gentle, MipMode::LengthInAlpha).unwrap();
        let down = |scale| ImportOptions { y_convention: YConvention::YDown, scale, ..Default::default() };
        let base = import_normal_map(&made.levels[..1], &down(1.0)).unwrap();
        let steep = import_normal_map(&made.levels[..1], &down(2.0)).unwrap();
        let flat = import_normal_map(&made.levels[..1], &down(0.0)).unwrap();
        let slope = |m: &ImportedNormalMap| -> f32 {
            m.chain.levels[0].texels.iter().map(|t| (t[0] as f32 - 128.0).abs() + (t[1] as f32 - 128.0).abs()).sum()
        };
        assert!(slope(&steep) > 1.5 * slope(&base), "{} vs {}", slope(&steep), slope(&base));
        assert!(flat.chain.levels[0].texels.iter().all(|t| t[..3] == [128, 128, 255]));
        assert!(import_normal_map(&made.levels[..1], &down(f32::NAN)).is_err());

        // A height packed into alpha is not the normal's length: level 0 reads A = 1.
        let mut packed = made.levels[0].clone();
        packed.texels.iter_mut().enumerate().for_each(|(i, t)| t[3] = (i % 200) as u8);
        let got = import_normal_map(&[packed], &down(1.0)).unwrap();
        assert!(got.foreign_alpha && got.chain.levels[0].texels.iter().all(|t| t[3] == 255));
        assert!(!base.foreign_alpha);

        // Pixels of a colour photograph are mostly not unit vectors.
        let photo =
            Image::new(8, 8, (0..64u32).map(|i| [(i * 37 % 256) as u8, (i * 91 % 256) as u8, 40, 255]).collect());
        let got = import_normal_map::<[u8; 4]>(&[photo], &ImportOptions::default()).unwrap();
        assert!(got.off_unit > 0.5, "{}", got.off_unit);
        assert!(matches!(import_normal_map::<[u8; 4]>(&[], &ImportOptions::default()), Err(ImportError::Empty)));
    }

    #[test]
    fn renormalized_levels_are_told_from_the_length_in_alpha_and_rebuilt_on_request() {
        let field = HeightPreset::Dimples.render(64, 64);
        let chain = |mode| MipChain::<[u8; 4]>::from_height(&field, &NormalMapOptions::default(), mode).unwrap();
        let (own, renormalized) = (chain(MipMode::LengthInAlpha), chain(MipMode::Renormalize));
        let yup = ImportOptions { y_convention: YConvention::TEXTURE_SPACE, ..Default::default() };
        assert!(!import_normal_map(&own.levels, &yup).unwrap().renormalized_mips);
        let got = import_normal_map(&renormalized.levels, &yup).unwrap();
        assert!(got.renormalized_mips && got.stored_mips);
        assert!(got.chain.levels[1].texels.iter().all(|t| t[3] == 255), "kept as stored");
        // A flat map loses nothing by renormalizing: no warning.
        let flat = HeightField::from_fn(64, 64, |_, _| 0.5);
        let flat = MipChain::<[u8; 4]>::from_height(&flat, &NormalMapOptions::default(), MipMode::Renormalize).unwrap();
        assert!(!import_normal_map(&flat.levels, &yup).unwrap().renormalized_mips);
        // Rebuilt: the levels made from level 0, with the length in alpha.
        let rebuilt = import_normal_map(&renormalized.levels, &ImportOptions { rebuild_mips: true, ..yup }).unwrap();
        assert!(!rebuilt.stored_mips);
        assert!(rebuilt.chain.levels[1].texels.iter().any(|t| t[3] < 240), "lengths below 1 are back");
        assert_eq!(rebuilt.chain.levels.len(), renormalized.levels.len());
    }
}
