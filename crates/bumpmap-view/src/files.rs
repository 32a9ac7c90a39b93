//! What a file given to the viewer (on the command line or dropped on the window) is taken
//! for: a mesh by its extension; an image by what its texels hold, since a normal map and a
//! height field are both images.
//!
//! What this module does not do: read the file for drawing (`crate::setup` does, as `render`
//! would with `--scene mesh:`, `--height-field` or `--normal-map`).

use std::path::Path;

use bumpmap_io::mesh_file::MeshFormat;

/// What a file holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// OBJ, glTF or GLB.
    Mesh,
    /// Heights: a gray image, or a float one (EXR, TIFF).
    HeightField,
    /// A tangent-space normal map: DDS or KTX2, or an image whose texels are mostly blue with
    /// red and green about the middle, as every tangent-space map is.
    NormalMap,
}

/// Decides what `path` holds, reading it only when it is an 8- or 16-bit image.
pub fn classify(path: &Path) -> Result<Kind, String> {
    if MeshFormat::from_path(path).is_some() {
        return Ok(Kind::Mesh);
    }
    let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    match ext.as_str() {
        "dds" | "ktx2" => return Ok(Kind::NormalMap),
        "exr" | "tif" | "tiff" => return Ok(Kind::HeightField),
        _ => {}
    }
    let image = bumpmap_io::image_file::load_rgba8(path).map_err(|e| e.to_string())?;
    Ok(judge(&image.texels))
}

/// A normal map when the texels are not gray and, on average, blue is high (the normal points
/// out of the surface) and red and green sit near the middle (slopes either way cancel).
fn judge(texels: &[[u8; 4]]) -> Kind {
    if texels.is_empty() || texels.iter().all(|&[r, g, b, _]| r == g && g == b) {
        return Kind::HeightField;
    }
    let n = texels.len() as f64;
    let mean = |c: usize| texels.iter().map(|t| t[c] as f64).sum::<f64>() / n / 255.0;
    let (r, g, b) = (mean(0), mean(1), mean(2));
    let centred = |m: f64| (0.35..=0.65).contains(&m);
    if b > 0.65 && centred(r) && centred(g) { Kind::NormalMap } else { Kind::HeightField }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gray_and_colour_images_are_heights_and_blue_ones_normal_maps() {
        assert_eq!(judge(&[[10, 10, 10, 255], [200, 200, 200, 255]]), Kind::HeightField);
        assert_eq!(judge(&[[200, 40, 40, 255], [180, 30, 60, 255]]), Kind::HeightField);
        assert_eq!(judge(&[[128, 128, 255, 255], [150, 110, 240, 255]]), Kind::NormalMap);
        assert_eq!(judge(&[]), Kind::HeightField);
        assert_eq!(classify(Path::new("a/b.GLB")), Ok(Kind::Mesh));
        assert_eq!(classify(Path::new("n.ktx2")), Ok(Kind::NormalMap));
        assert!(classify(Path::new("/nonexistent/x.png")).unwrap_err().contains("x.png"));
    }
}
