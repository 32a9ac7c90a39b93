//! A [`Chain`] written as `bumpmap normalmap -o OUT` writes it, by `OUT`'s extension: PNG files
//! (level 0 at `OUT`, `OUT.mip1.png`, … beside it), or one DDS or KTX2 file holding every level
//! in a [`TextureFormat`]. The files are staged into a [`FileSet`], so a caller writes them all
//! or none, none replacing an input.
//!
//! What this module does not do: convert between depths (a 16-bit chain goes into 16-bit files,
//! BC5 and BC7 take 8-bit levels), or read the files back (`bumpmap_io::load_texture_chain`).

use std::path::{Path, PathBuf};

use bumpmap_io::IoError;
use bumpmap_io::atomic::FileSet;
use bumpmap_io::image_file::{PngLayout, level_path, save_png_into, save_png16_into};
use bumpmap_io::texture_file::{Level, TextureFormat, TextureLayout, write_dds_into, write_ktx2_into};

use super::Chain;

/// Why a chain could not be written.
#[derive(Debug, thiserror::Error)]
pub enum SaveError {
    /// Block-compressed texels asked of a PNG, which holds uncompressed texels only.
    #[error("{}: format {} needs a .dds or .ktx2 file (PNG holds uncompressed texels only)", bumpmap_io::error::shown(path), format.dxgi_name())]
    NeedsContainer {
        /// The PNG asked for.
        path: PathBuf,
        /// The compressed format.
        format: TextureFormat,
    },
    /// A file could not be written (or its extension names no format this writes).
    #[error(transparent)]
    Io(#[from] IoError),
}

/// Refuses, before any work, a `format` that `out`'s file cannot hold.
pub fn check_container(out: &Path, format: TextureFormat) -> Result<(), SaveError> {
    if format.is_compressed() && extension(out) == "png" {
        return Err(SaveError::NeedsContainer { path: out.to_path_buf(), format });
    }
    Ok(())
}

/// `chain`'s levels as one face of a DDS or KTX2 file's texture.
pub fn chain_layout(chain: &Chain) -> TextureLayout<'_> {
    TextureLayout {
        faces: vec![match chain {
            Chain::Rgba8(c) => c.levels.iter().map(Level::from).collect(),
            Chain::Rgba16(c) => c.levels.iter().map(Level::from).collect(),
        }],
    }
}

/// `out`'s extension in lower case ("" for none).
fn extension(out: &Path) -> String {
    out.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default()
}

/// Stages `chain`'s files for `out` into `set`, to be committed (or dropped) by the caller; DDS
/// and KTX2 texels in `format`.
pub fn write_chain_into(set: &mut FileSet, out: &Path, chain: &Chain, format: TextureFormat) -> Result<(), SaveError> {
    check_container(out, format)?;
    let layout = || chain_layout(chain);
    match extension(out).as_str() {
        "png" => match chain {
            Chain::Rgba8(c) => {
                for (k, level) in c.levels.iter().enumerate() {
                    save_png_into(
                        set,
                        &level_path(out, k),
                        level.width,
                        level.height,
                        PngLayout::Rgba8,
                        level.as_bytes(),
                    )?;
                }
            }
            Chain::Rgba16(c) => {
                for (k, level) in c.levels.iter().enumerate() {
                    save_png16_into(set, &level_path(out, k), level)?;
                }
            }
        },
        "dds" => write_dds_into(set, out, &layout(), format)?,
        "ktx2" => write_ktx2_into(set, out, &layout(), format)?,
        _ => return Err(IoError::UnsupportedOutput { path: out.to_path_buf(), expected: ".png, .dds or .ktx2" }.into()),
    }
    Ok(())
}

/// Writes `chain` for `out` ([`write_chain_into`]), all files or none, none of them replacing
/// one of `inputs`; returns the paths written.
///
/// ```
/// use bumpmap::maps::{self, MapOptions};
/// use bumpmap::HeightPreset;
/// use bumpmap::bumpmap_io::texture_file::TextureFormat;
///
/// let dir = std::env::temp_dir().join(format!("bumpmap-doc-{}", std::process::id()));
/// let chain = maps::normal_map(&MapOptions::default(), true, &HeightPreset::Bricks.render(32, 32)).unwrap();
/// let written = maps::write_chain(&dir.join("n.png"), &chain, TextureFormat::Rgba8, &[]).unwrap();
/// assert_eq!(written.len(), 6); // 32² down to 1²: n.png, n.mip1.png, …, n.mip5.png
/// assert!(maps::write_chain(&dir.join("n.png"), &chain, TextureFormat::Bc5, &[]).is_err());
/// std::fs::remove_dir_all(dir).unwrap();
/// ```
pub fn write_chain(
    out: &Path,
    chain: &Chain,
    format: TextureFormat,
    inputs: &[&Path],
) -> Result<Vec<PathBuf>, SaveError> {
    let mut set = FileSet::new(inputs);
    write_chain_into(&mut set, out, chain, format)?;
    Ok(set.commit()?)
}
