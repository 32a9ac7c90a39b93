//! A PNG's mip chain as `bumpmap normalmap --mips` writes it: level 0 and its `NAME.mipK.png`
//! siblings, read back as one texture. What it does not do: read levels from another folder,
//! or make missing levels.

use std::path::Path;

use super::{StoredLevels, StoredTexture, bad, load_texture};
use crate::error::IoError;

/// [`load_texture`] with a PNG's smaller levels: the `NAME.mip1.png`, `NAME.mip2.png`, … that
/// `bumpmap normalmap --mips` writes beside it, read from the same folder only
/// ([`crate::siblings::beside`]), each half the size of the one before and as many bits deep as
/// level 0, down to the first one missing. Another file is read as [`load_texture`] reads it:
/// a DDS or KTX2 carries its levels itself. What `write_texture` wrote, read back.
pub fn load_texture_chain(path: &Path) -> Result<StoredTexture, IoError> {
    let mut texture = load_texture(path)?;
    if !path.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) || texture.levels.len() != 1 {
        return Ok(texture);
    }
    let full = texture.levels.size();
    let mut size = full;
    for k in 1.. {
        if size == (1, 1) {
            break;
        }
        size = (bumpmap_math::levels::next_size(size.0), bumpmap_math::levels::next_size(size.1));
        let Some(file) = crate::siblings::png_level(path, k, full, size)? else {
            break;
        };
        let level = load_texture(&file)?.levels;
        let wrong = |reason: String| Err(bad(&file, reason));
        if level.size() != size {
            let (w, h) = level.size();
            return wrong(format!(
                "is {w}x{h}, but as level {k} of a {}x{} map it must be {}x{}",
                full.0, full.1, size.0, size.1
            ));
        }
        match (&mut texture.levels, level) {
            (StoredLevels::Rgba8(chain), StoredLevels::Rgba8(mut l)) => chain.append(&mut l),
            (StoredLevels::Rgba16(chain), StoredLevels::Rgba16(mut l)) => chain.append(&mut l),
            (StoredLevels::Rgba8(_), _) => {
                return wrong(format!("is 16 bits a channel, but level 0 ({}) is 8", path.display()));
            }
            (StoredLevels::Rgba16(_), _) => {
                return wrong(format!("is 8 bits a channel, but level 0 ({}) is 16", path.display()));
            }
        }
    }
    Ok(texture)
}
