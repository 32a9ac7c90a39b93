//! The demo's "normal maps in" part: `inspect`'s verdicts on the demo's own normal maps, and
//! heights back from one of them beside the heights it was made from.

use bumpmap::Named;
use std::path::Path;

use bumpmap::heights::{HeightOptions, heights_from_inspection};
use bumpmap::inspect::{inspect_map, read_file, read_map};
use bumpmap_io::image_file::{PngLayout, save_png};
use bumpmap_math::NormalMapOptions;

use bumpmap_words::Error;

/// The round-trip figure (the README shows it).
pub const ROUND_TRIP_FIGURE: &str = "height_round_trip.png";

/// The verdicts file.
pub const INSPECT_TEXT: &str = "inspect.txt";

/// How much the difference panel magnifies |recovered − original|.
const ERROR_GAIN: f32 = 20.0;

/// Writes `inspect.txt` (the verdicts on `maps`, files in `out`) and the round-trip figure made
/// from `heights` and `normals` (files in `out`, the map made at the default scale): the
/// heights, the normal map, the heights `bumpmap height --scale 4` gets back (their mean moved
/// onto the original's), and their difference ×20, all on the original's 0..1 mapping. Returns
/// the index's lines.
pub fn write(out: &Path, maps: &[&str], heights: &str, normals: &str) -> Result<String, Error> {
    let mut text = String::new();
    for name in maps {
        let path = out.join(name);
        let map = read_map(&path).map_err(bumpmap_words::frame::lib_err)?;
        for line in inspect_map(name, &map).lines() {
            text += &line;
            text.push('\n');
        }
    }
    crate::write_text(&out.join(INSPECT_TEXT), &text)?;

    let field = bumpmap_io::load_height_field(&out.join(heights), bumpmap_io::Channel::Luminance)?;
    let map = read_file(&out.join(normals)).map_err(bumpmap_words::frame::lib_err)?;
    let report = inspect_map(normals, &map);
    let level0 = &map.levels[0];
    // The demo's maps are made at the default scale: given it, the heights come back in the
    // units they were made in, and both panels share the original's 0..1 mapping.
    let options = HeightOptions { scale: NormalMapOptions::default().scale, ..Default::default() };
    let back = heights_from_inspection(level0, &report.inspection, &options)
        .map_err(|e| Error::Render(format!("{normals}: {e}")))?;
    let original = field.to_f32();
    let (lo, hi) = original.iter().fold((f32::MAX, f32::MIN), |(l, h), &x| (l.min(x), h.max(x)));
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    let (mo, mb) = (mean(&original), mean(&back.texels));
    let span = (hi - lo).max(f32::EPSILON);
    let truth: Vec<f32> = original.iter().map(|x| (x - lo) / span).collect();
    let got: Vec<f32> = back.texels.iter().map(|x| (x - mb + mo - lo) / span).collect();
    let (w, h) = (back.width, back.height);
    let gray = |v: f32| {
        let b = (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        [b, b, b]
    };
    let mut rgb = Vec::with_capacity(4 * w * h * 3);
    for y in 0..h {
        for x in 0..w {
            rgb.extend(gray(truth[y * w + x]));
        }
        for x in 0..w {
            let n = level0.texel(x, y);
            rgb.extend([n.x, n.y, n.z].map(|c| ((c * 0.5 + 0.5).clamp(0.0, 1.0) * 255.0).round() as u8));
        }
        for x in 0..w {
            rgb.extend(gray(got[y * w + x]));
        }
        for x in 0..w {
            rgb.extend(gray(ERROR_GAIN * (got[y * w + x] - truth[y * w + x]).abs()));
        }
    }
    save_png(&out.join(ROUND_TRIP_FIGURE), 4 * w, h, PngLayout::Rgb8, &rgb)?;
    let rms = (truth.iter().zip(&got).map(|(a, b)| (a - b).powi(2)).sum::<f32>() / truth.len() as f32).sqrt();
    Ok(format!(
        "- `{INSPECT_TEXT}`: `bumpmap inspect` on the demo's normal maps\n\
- `{ROUND_TRIP_FIGURE}`: from left to right, `{heights}`, `{normals}` (8 bits), the heights `bumpmap height --scale 4` gets back from it (method {}, kernel {}, read as {}), and the difference ×{ERROR_GAIN} (RMS {:.2} % of the range)\n",
        back.method.boundary.name(),
        back.method.derivative.name(),
        back.y_convention.name(),
        rms * 100.0
    ))
}
