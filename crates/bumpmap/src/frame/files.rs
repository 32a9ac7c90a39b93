//! A [`Frame`] written as `bumpmap render -o OUT` writes it: `OUT` and, for each pass image kept
//! (`--passes`), `OUT.NAME.png` beside it, RGB PNGs staged in one set so all land or none.
//!
//! What this module does not do: draw (see the parent module) or keep the colour buffer's alpha
//! (it holds s_self, not coverage).

use std::path::{Path, PathBuf};

use bumpmap_io::IoError;
use bumpmap_io::atomic::FileSet;
use bumpmap_io::image_file::{PngLayout, save_png_into};

use super::Frame;
use crate::Rgba8Image;

/// Writes `frame` to `out` with its pass images beside it, all or none, none of them replacing
/// one of `inputs`; returns the paths written.
pub fn write_frame(frame: &Frame, out: &Path, inputs: &[&Path]) -> Result<Vec<PathBuf>, IoError> {
    // The set makes a missing folder, and takes it away again if anything fails.
    let mut set = FileSet::new(inputs);
    for (name, image) in &frame.snapshots {
        let stem = out.file_stem().unwrap_or_default().to_string_lossy();
        let path = out.with_file_name(format!("{stem}.{name}.png"));
        save_png_into(&mut set, &path, image.width, image.height, PngLayout::Rgb8, &rgb(image))?;
    }
    save_png_into(&mut set, out, frame.image.width, frame.image.height, PngLayout::Rgb8, &rgb(&frame.image))?;
    set.commit()
}

/// An image's RGB bytes without alpha.
pub fn rgb(image: &Rgba8Image) -> Vec<u8> {
    image.texels.iter().flat_map(|&[r, g, b, _]| [r, g, b]).collect()
}
