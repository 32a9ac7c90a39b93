//! What `normalmap` needs around the maps it writes beside the normal map (`bumpmap::maps`
//! makes them): the memory they take together, checked before any is made; the heights'
//! warning; LEAN's file names. What this module does not do: make a map, or write files (the
//! command stages them all in one set).

use std::path::{Path, PathBuf};

use bumpmap::maps::{self, MapOptions};
use bumpmap_math::{HeightField, HeightMips};

use crate::error::CliError;
use bumpmap_words::maps::map_error;

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
    let mut per = if args.maps.0.bits == 16 { NORMAL_MAP_16 } else { NORMAL_MAP_8 };
    if args.lean_out.is_some() {
        per += LEAN + if args.maps.0.bits == 16 { NORMAL_MAP_8 } else { 0 };
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

/// `--height-out`'s heights ([`maps::height_mips`]), with a warning where the field leaves
/// [0, 1]; `name` names the field.
pub(crate) fn height_levels(map: &MapOptions, field: &HeightField, name: &str) -> Result<HeightMips, CliError> {
    let stored = maps::height_mips(map, field).map_err(|e| map_error(e, name))?;
    if let Some(clamped) = stored.clamped {
        crate::report::warn(format!("{name}: {clamped} for --height-out"));
    }
    Ok(stored.mips)
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
