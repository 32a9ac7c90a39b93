//! The files the options name beyond the scene's own assets, read into what the scene holds:
//! a decal or gloss image with its mipmaps, a roughness map with its levels, and the files found
//! by name beside those given. What this module does not do: decide which option needs which
//! file (`setup` does).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use bumpmap::Rgba8Image;
use bumpmap::bumpmap_math::Rgba8Mips;

use crate::args::{RoughnessLayoutArg, SceneSetup};
use crate::error::CliError;

/// The files read beside those the options name (found by name: a roughness map's or a height
/// map's `.mipK.png` levels, the heights' min–max, a horizon map's second half): no output may
/// replace one either.
pub(super) fn files_beside(s: &SceneSetup) -> Result<Vec<PathBuf>, CliError> {
    let mut files = Vec::new();
    if let Some(path) = &s.material.roughness_map {
        let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
        if !matches!(ext.as_deref(), Some("dds" | "ktx2")) {
            files.extend(bumpmap_io::siblings::png_levels(path)?);
        }
    }
    if let Some(path) = &s.heights.height_map {
        files.extend(bumpmap_io::height_file::files_read(path)?);
    }
    if let Some(path) = &s.heights.horizon_map {
        files.extend(bumpmap_io::horizon_file::files_read(path)?);
    }
    Ok(files)
}

/// An RGBA8 image file with box-filtered mipmaps (`--decal`, `--gloss`): refused, naming the
/// file, when its levels and a texture unit's copy of them will not fit beside what is loaded.
pub(super) fn texture_file(path: &Path) -> Result<Arc<Rgba8Mips>, CliError> {
    decal_mips(bumpmap_io::load_rgba8(path)?, path)
}

/// `image` with its box mipmaps, as a decal; refused, naming `path`, where they would not fit.
pub(super) fn decal_mips(image: Rgba8Image, path: &Path) -> Result<Arc<Rgba8Mips>, CliError> {
    let texels = (image.width as u64 * image.height as u64) * 4 / 3;
    bumpmap::bumpmap_math::buffer::ensure_available(
        texels * 4 + bumpmap_cpu::texture_unit_bytes(texels),
        "its mipmaps and a texture unit's copy",
    )
    .map_err(|e| CliError::Render(format!("{}: {e}; a smaller image needs less", path.display())))?;
    Ok(Arc::new(Rgba8Mips::with_box_mipmaps(image)))
}

/// A roughness map for `--roughness-map`: a DDS or KTX2 file's own levels, or a PNG (or other
/// image) with `NAME.mip1.png`, `NAME.mip2.png`, … beside it as `normalmap --roughness-out`
/// writes them; each texel's roughness read by `layout` into the gray form the renderers
/// sample. A lone image gets box-filtered levels, with a warning: they keep no spread.
pub(super) fn load_roughness_map(path: &Path, layout: RoughnessLayoutArg) -> Result<Rgba8Mips, CliError> {
    let to_rgba8 = |stored: bumpmap_io::StoredTexture| -> Vec<Rgba8Image> {
        match stored.levels {
            bumpmap_io::StoredLevels::Rgba8(levels) => levels,
            bumpmap_io::StoredLevels::Rgba16(levels) => levels
                .into_iter()
                .map(|l| {
                    use bumpmap::bumpmap_math::Texel as _;
                    Rgba8Image::new(l.width, l.height, l.texels.into_iter().map(|t| t.to_rgba8()).collect())
                })
                .collect(),
        }
    };
    let mut levels = to_rgba8(bumpmap_io::load_texture(path)?);
    let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    let container = matches!(ext.as_deref(), Some("dds" | "ktx2"));
    if levels.len() == 1 && !container {
        for (k, mip) in (1..).zip(bumpmap_io::siblings::png_levels(path)?) {
            let (w, h) = (levels[k - 1].width, levels[k - 1].height);
            let next = to_rgba8(bumpmap_io::load_texture(&mip)?).swap_remove(0);
            let want = (bumpmap::bumpmap_math::mip::next_size(w), bumpmap::bumpmap_math::mip::next_size(h));
            if (next.width, next.height) != want {
                return Err(CliError::Path {
                    path: mip,
                    reason: format!(
                        "is {}x{}, but level {k} of a {w}x{h} level 0 is {}x{} (--roughness-map's levels)",
                        next.width, next.height, want.0, want.1
                    ),
                });
            }
            levels.push(next);
            if want == (1, 1) {
                break;
            }
        }
    }
    let gray = |level: Rgba8Image| {
        let texels = level
            .texels
            .iter()
            .map(|&t| {
                let r = bumpmap::bumpmap_math::roughness::unorm8(layout.read(t));
                [r, r, r, 255]
            })
            .collect();
        Rgba8Image::new(level.width, level.height, texels)
    };
    if levels.len() == 1 {
        crate::report::warn(format!(
            "{}: one level, so its smaller levels are box-filtered and hold no spread of the normals; \
             `bumpmap normalmap --mips --roughness-out` writes every level",
            bumpmap_io::error::shown(path)
        ));
        return Ok(Rgba8Mips::with_box_mipmaps(gray(levels.swap_remove(0))));
    }
    Ok(Rgba8Mips::from_levels(levels.into_iter().map(gray).collect()))
}
