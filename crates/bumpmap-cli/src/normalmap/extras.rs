//! The maps `normalmap` writes beside the normal map, each from the same height field: the
//! heights as geometry (`--height-out`), the horizon map that ambient occlusion and bent
//! normals come from, the roughness map and LEAN's moments. What this module does not do: write
//! files (the command stages them all in one set).

use std::path::{Path, PathBuf};

use bumpmap_math::normalmap::NormalMapError;
use bumpmap_math::{HeightField, MipChain, MipMode, NormalMapOptions};

use super::{Chain, make_texels, scale_err};
use crate::error::CliError;

/// Bytes a texel of level 0 costs beyond the height field itself, as measured (peak resident
/// memory of `normalmap bricks@4096 --mips` with each output alone, less the run without it,
/// over 4096², rounded up): the normal map at 8 and 16 bits (its chain and what making it
/// takes), and each map written beside it. A horizon map is shared by `--horizon-out`,
/// `--ao-out` and `--bent-normals-out`; the bent normals cost a little more on top.
mod per_texel {
    pub const NORMAL_MAP_8: u64 = 8;
    pub const NORMAL_MAP_16: u64 = 18;
    pub const LEAN: u64 = 74;
    pub const ROUGHNESS: u64 = 20;
    pub const HEIGHTS: u64 = 24;
    pub const HORIZONS: u64 = 44;
    pub const BENT_NORMALS: u64 = 10;
}

/// Refuses, before any of it is made, what `args` ask of a `width`×`height` height field when
/// it will not fit in the memory the process may still have (the field itself is loaded).
/// Every buffer is also asked for fallibly where the library can; this check is what keeps the
/// rest (the moments as written, the encoders' copies) from aborting.
pub(super) fn ensure_room(args: &crate::args::NormalmapArgs, width: usize, height: usize) -> Result<(), CliError> {
    use per_texel::*;
    let mut per = if args.bits == 16 { NORMAL_MAP_16 } else { NORMAL_MAP_8 };
    if args.lean_out.is_some() {
        per += LEAN + if args.bits == 16 { NORMAL_MAP_8 } else { 0 };
    }
    if args.roughness_out.is_some() {
        per += ROUGHNESS;
    }
    if args.height_out.is_some() {
        per += HEIGHTS;
    }
    if args.horizon_out.is_some() || args.ao_out.is_some() || args.bent_normals_out.is_some() {
        per += HORIZONS;
    }
    if args.bent_normals_out.is_some() {
        per += BENT_NORMALS;
    }
    let bytes = (width as u64 * height as u64).saturating_mul(per);
    bumpmap_math::buffer::ensure_available(bytes, "making these maps").map_err(|e| {
        CliError::Render(format!(
            "{}: {e} from its {width}x{height} heights, more than this process may use. Fewer outputs at \
             once (--lean-out, --roughness-out, --height-out, --horizon-out, --ao-out, --bent-normals-out) \
             or a smaller field need less",
            args.input
        ))
    })
}

/// `--height-out`'s heights: the field rounded to `bits` first, so the levels and the min–max
/// bounds are those of the heights stored; a warning where the field leaves [0, 1].
pub(crate) fn height_levels(field: &HeightField, bits: u8, name: &str) -> Result<bumpmap_math::HeightMips, CliError> {
    let mut row = Vec::new();
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for y in 0..field.height() {
        for &v in field.row(y, &mut row) {
            (lo, hi) = (lo.min(v), hi.max(v));
        }
    }
    if lo < 0.0 || hi > 1.0 {
        crate::report::warn(format!(
            "{name}: heights from {lo} to {hi} are clamped to [0, 1] for --height-out (1 on the surface, 0 at --depth below it)"
        ));
    }
    let steps = if bits == 16 { 65535 } else { 255 };
    bumpmap_math::HeightMips::from_field_rounded(field, steps).map_err(|e| match e {
        bumpmap_math::HeightMipsError::OutOfMemory(e) => CliError::OutOfMemory(e),
        other => CliError::Path { path: name.into(), reason: other.to_string() },
    })
}

/// The horizon map of `field` (`--horizon-out`, and what `--ao-out` and `--bent-normals-out`
/// are made from), read beyond the edges as `wrap` says.
pub(crate) fn horizon_map(
    field: &HeightField,
    wrap: bumpmap_math::Wrap,
    name: &str,
) -> Result<bumpmap_math::HorizonMap, CliError> {
    bumpmap_math::HorizonMap::from_heights(field, wrap).map_err(|e| match e {
        bumpmap_math::HorizonError::OutOfMemory(e) => CliError::OutOfMemory(e),
        other => CliError::Path { path: name.into(), reason: other.to_string() },
    })
}

/// `--roughness-out`'s levels ([`bumpmap::options::roughness_map`]), named `name` in errors.
pub(crate) fn roughness_chain(
    field: &HeightField,
    options: &NormalMapOptions,
    perceptual: f32,
    layout: bumpmap::options::RoughnessLayout,
    name: &str,
) -> Result<MipChain, CliError> {
    bumpmap::options::roughness_map(field, options, perceptual, layout).map_err(|e| scale_err(e, name))
}

/// `--lean-out`'s two files: `L` itself and `L`'s stem with `.mxy-j` before the extension.
/// Only .ktx2 and .dds hold floats.
pub(super) fn lean_paths(out: &Path) -> Result<[PathBuf; 2], CliError> {
    let ext = out.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    if ext != "ktx2" && ext != "dds" {
        return Err(CliError::Usage(format!(
            "--lean-out {}: the moments are floats, which .ktx2 or .dds hold (not .{ext})",
            out.display()
        )));
    }
    let stem = out.file_stem().unwrap_or_default().to_string_lossy();
    let ext = out.extension().unwrap_or_default().to_string_lossy();
    Ok([out.to_path_buf(), out.with_file_name(format!("{stem}.mxy-j.{ext}"))])
}

/// `--lean-out`'s levels, two planes: (Bx, By, Mxx, Myy) and (Mxy, J, 0, 0), from the 8-bit
/// normal map's level 0 (the chain `render` draws from, whatever `--bits` the normal map is
/// written at), by [`LeanMips`](bumpmap_math::LeanMips): the written chain's own level 0 when
/// it is 8-bit (its mip mode changes no level-0 texel), else one made at 8 bits.
pub(crate) fn lean_levels(
    field: &HeightField,
    options: &NormalMapOptions,
    written: &Chain,
    name: &str,
) -> Result<[Vec<bumpmap_math::Image<[f32; 4]>>; 2], CliError> {
    let made;
    let chain: &MipChain = match written {
        Chain::Rgba8(chain) => chain,
        Chain::Rgba16(_) => {
            made = make_texels(field, options, true, MipMode::LengthInAlpha, name)?;
            &made
        }
    };
    let lean = bumpmap_math::LeanMips::from_level0(&chain.levels[0], chain.levels.len(), chain.encoding)
        .map_err(|e| CliError::NormalMap { path: name.to_string(), source: NormalMapError::OutOfMemory(e) })?;
    let plane = |texel: fn(&bumpmap_math::LeanMoments) -> [f32; 4]| {
        lean.levels
            .iter()
            .map(|l| bumpmap_math::Image::new(l.width, l.height, l.texels.iter().map(texel).collect()))
            .collect()
    };
    Ok([plane(|t| [t.b.x, t.b.y, t.m.x, t.m.z]), plane(|t| [t.m.y, t.j, 0.0, 0.0])])
}
