//! A normalization cube map written as `bumpmap cubemap -o OUT` writes it: six RGB PNG faces
//! (`px.png` … `nz.png`) into the folder `OUT`, or one `.dds` or `.ktx2` cube texture.
//!
//! What this module does not do: make the map (`bumpmap_math::NormalizationCubeMap`).

use std::path::Path;

use bumpmap_io::IoError;
use bumpmap_io::atomic::FileSet;
use bumpmap_io::image_file::{PngLayout, save_png_into};
use bumpmap_io::texture_file::{TextureFormat, TextureLayout, write_dds, write_ktx2};
use bumpmap_math::{CubeFace, NormalizationCubeMap, Rgba8Image};

/// Writes `map` by `out`'s extension: one DDS or KTX2 cube map, or six PNG faces into the folder
/// `out` (made if missing; an existing file that is not a folder is refused).
pub fn write_cube_map(out: &Path, map: &NormalizationCubeMap) -> Result<(), IoError> {
    let ext = out.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    let n = map.size;
    match ext.as_deref() {
        Some("dds") | Some("ktx2") => {
            let rgba: Vec<Rgba8Image> = map
                .faces
                .iter()
                .map(|f| Rgba8Image::new(n, n, f.iter().map(|&[r, g, b]| [r, g, b, 255]).collect()))
                .collect();
            let layout = TextureLayout { faces: rgba.iter().map(|f| vec![f.into()]).collect() };
            if ext.as_deref() == Some("dds") {
                write_dds(out, &layout, TextureFormat::Rgba8)
            } else {
                write_ktx2(out, &layout, TextureFormat::Rgba8)
            }
        }
        Some(_) if !out.is_dir() => {
            Err(IoError::UnsupportedOutput { path: out.to_path_buf(), expected: "a folder, .dds or .ktx2" })
        }
        _ => {
            // The set makes the folder if it is missing (and removes it again on failure).
            let mut set = FileSet::new(&[]);
            for face in CubeFace::ALL {
                let path = out.join(format!("{}.png", face.stem()));
                save_png_into(&mut set, &path, n, n, PngLayout::Rgb8, map.faces[face as usize].as_flattened())?;
            }
            set.commit().map(|_| ())
        }
    }
}
