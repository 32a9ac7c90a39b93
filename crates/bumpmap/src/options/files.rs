//! The files the options name beyond the scene's own assets, read into what the scene holds: a
//! decal or gloss image with its mipmaps, a roughness map with its levels, and the files found
//! by name beside those given. What this module does not do: decide which option needs which
//! file (`build` and `technique` do).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use bumpmap_io::HeightSource;
use bumpmap_math::{Rgba8Image, Rgba8Mips};

use super::{DecalChoice, GlossChoice, RoughnessLayout, SceneChoice, SceneOptions, SetupError, SetupNote};

/// The files `o` names, before anything is read.
pub(super) fn named_inputs(o: &SceneOptions) -> Vec<PathBuf> {
    let mut files = Vec::new();
    if let SceneChoice::Mesh(p) = &o.scene {
        files.push(p.clone());
    }
    if let Some(HeightSource::File(p)) = &o.height_field {
        files.push(p.clone());
    }
    files.extend(o.normal_map.clone());
    if let Some(DecalChoice::File(p)) = &o.decal {
        files.push(p.clone());
    }
    files.extend(o.material.roughness_map.clone());
    files.extend(o.detail.map.clone());
    if let Some(h) = &o.heights.height_map {
        files.push(h.clone());
        files.push(bumpmap_io::height_file::minmax_path(h));
    }
    if let Some(HeightSource::File(p)) = &o.lights.spot_pattern {
        files.push(p.clone());
    }
    if let GlossChoice::File(p) = &o.material.gloss {
        files.push(p.clone());
    }
    files
}

/// The files read beside those the options name (found by name: a roughness map's or a height
/// map's `.mipK.png` levels, the heights' min–max, a horizon map's second half).
pub(super) fn files_beside(o: &SceneOptions) -> Result<Vec<PathBuf>, SetupError> {
    let mut files = Vec::new();
    if let Some(path) = &o.material.roughness_map
        && !is_container(path)
    {
        files.extend(bumpmap_io::siblings::png_levels(path)?);
    }
    if let Some(path) = &o.heights.height_map {
        files.extend(bumpmap_io::height_file::files_read(path)?);
    }
    if let Some(path) = &o.heights.horizon_map {
        files.extend(bumpmap_io::horizon_file::files_read(path)?);
    }
    Ok(files)
}

/// Whether `path` names a file that carries its own levels (.dds, .ktx2).
fn is_container(path: &Path) -> bool {
    let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    matches!(ext.as_deref(), Some("dds" | "ktx2"))
}

/// An RGBA8 image file with box-filtered mipmaps (a decal, a gloss map).
pub(super) fn texture_file(path: &Path) -> Result<Arc<Rgba8Mips>, SetupError> {
    decal_mips(bumpmap_io::load_rgba8(path)?, path)
}

/// `image` with its box mipmaps, as a decal; refused, naming `path`, when its levels and a
/// texture unit's copy of them will not fit beside what is loaded.
pub(super) fn decal_mips(image: Rgba8Image, path: &Path) -> Result<Arc<Rgba8Mips>, SetupError> {
    let texels = (image.width as u64 * image.height as u64) * 4 / 3;
    bumpmap_math::buffer::ensure_available(
        texels * 4 + bumpmap_cpu::texture_unit_bytes(texels),
        "its mipmaps and a texture unit's copy",
    )
    .map_err(|source| SetupError::TooBig { path: path.to_path_buf(), source })?;
    Ok(Arc::new(Rgba8Mips::with_box_mipmaps(image)))
}

/// A roughness map: a DDS or KTX2 file's own levels, or a PNG (or other image) with
/// `NAME.mip1.png`, `NAME.mip2.png`, … beside it as `normalmap --roughness-out` writes them;
/// each texel's roughness read by `layout` into the gray form the renderers sample. A lone
/// image gets box-filtered levels, and a note saying they keep no spread.
pub(super) fn load_roughness_map(
    path: &Path,
    layout: RoughnessLayout,
    notes: &mut Vec<SetupNote>,
) -> Result<Rgba8Mips, SetupError> {
    let to_rgba8 = |stored: bumpmap_io::StoredTexture| -> Vec<Rgba8Image> {
        match stored.levels {
            bumpmap_io::StoredLevels::Rgba8(levels) => levels,
            bumpmap_io::StoredLevels::Rgba16(levels) => levels
                .into_iter()
                .map(|l| {
                    use bumpmap_math::Texel as _;
                    Rgba8Image::new(l.width, l.height, l.texels.into_iter().map(|t| t.to_rgba8()).collect())
                })
                .collect(),
        }
    };
    let mut levels = to_rgba8(bumpmap_io::load_texture(path)?);
    if levels.len() == 1 && !is_container(path) {
        for (k, mip) in (1..).zip(bumpmap_io::siblings::png_levels(path)?) {
            let base = (levels[k - 1].width, levels[k - 1].height);
            let next = to_rgba8(bumpmap_io::load_texture(&mip)?).swap_remove(0);
            let want = (bumpmap_math::mip::next_size(base.0), bumpmap_math::mip::next_size(base.1));
            if (next.width, next.height) != want {
                return Err(SetupError::LevelSize { path: mip, level: k, size: (next.width, next.height), base, want });
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
                let r = bumpmap_math::roughness::unorm8(layout.read(t));
                [r, r, r, 255]
            })
            .collect();
        Rgba8Image::new(level.width, level.height, texels)
    };
    if levels.len() == 1 {
        notes.push(SetupNote::OneRoughnessLevel { path: path.to_path_buf() });
        return Ok(Rgba8Mips::with_box_mipmaps(gray(levels.swap_remove(0))));
    }
    Ok(Rgba8Mips::from_levels(levels.into_iter().map(gray).collect()))
}
