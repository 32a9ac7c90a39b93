//! One plane of floats out: heights recovered from a normal map (`bumpmap height`), as a gray
//! PNG of 8 or 16 bits (values in [0, 1] mapped onto the full range, rounded) or a one-channel
//! 32-bit float OpenEXR (values as they are, channel `Y`, which the height readers take as
//! luminance).
//!
//! What this module does not do: rescale. A PNG stores [0, 1]; values outside are clamped.

use std::path::Path;

use crate::atomic::FileSet;
use crate::error::IoError;
use crate::image_file::{Png16, PngLayout, save_png_into, save_png16_samples_into};

/// How a plane is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GrayFormat {
    /// 8-bit gray PNG.
    Png8,
    /// 16-bit gray PNG.
    Png16,
    /// 32-bit float OpenEXR, one channel.
    Exr,
}

impl GrayFormat {
    /// The format `path`'s extension names (`.exr`: EXR; else PNG at `bits`, 8 or 16).
    pub fn for_path(path: &Path, bits: u8) -> Self {
        let exr = path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("exr"));
        match (exr, bits) {
            (true, _) => GrayFormat::Exr,
            (false, 8) => GrayFormat::Png8,
            _ => GrayFormat::Png16,
        }
    }
}

/// Stages `samples` (`width·height`, row 0 first) into `set` as `format` at `path`.
pub fn save_gray_into(
    set: &mut FileSet,
    path: &Path,
    width: usize,
    height: usize,
    samples: &[f32],
    format: GrayFormat,
) -> Result<(), IoError> {
    debug_assert_eq!(samples.len(), width * height);
    match format {
        GrayFormat::Png8 => {
            let bytes: Vec<u8> = samples.iter().map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8).collect();
            save_png_into(set, path, width, height, PngLayout::Gray8, &bytes)
        }
        GrayFormat::Png16 => {
            let values: Vec<u16> = samples.iter().map(|v| (v.clamp(0.0, 1.0) * 65535.0).round() as u16).collect();
            save_png16_samples_into(set, path, width, height, Png16::Gray, &values)
        }
        GrayFormat::Exr => {
            use exr::prelude::*;
            let channel = AnyChannel::new("Y", FlatSamples::F32(samples.to_vec()));
            let layer = Layer::new(
                (width, height),
                LayerAttributes::named("heights"),
                exr::prelude::Encoding::FAST_LOSSLESS,
                AnyChannels::sort(SmallVec::from_vec(vec![channel])),
            );
            let mut bytes = std::io::Cursor::new(Vec::new());
            exr::prelude::Image::from_layer(layer).write().to_buffered(&mut bytes).map_err(|e| IoError::Write {
                path: path.to_path_buf(),
                source: std::io::Error::other(e.to_string()),
            })?;
            let bytes = bytes.into_inner();
            set.write(path, |w| std::io::Write::write_all(w, &bytes))
        }
    }
}
