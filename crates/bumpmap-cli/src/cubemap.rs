//! `bumpmap cubemap`: write a normalization cube map, or tabulate its accuracy.

use bumpmap_io::atomic::FileSet;
use bumpmap_io::image_file::{PngLayout, save_png_into};
use bumpmap_io::texture_file::{TextureFormat, TextureLayout, write_dds, write_ktx2};
use bumpmap_math::Rgba8Image;
use bumpmap_math::cubemap::worst_angular_error_degrees;
use bumpmap_math::{CubeFace, Encoding, NormalizationCubeMap};

use crate::args::CubemapArgs;
use crate::error::CliError;

pub fn run(args: &CubemapArgs) -> Result<(), CliError> {
    if args.accuracy {
        print!("{}", accuracy_table());
        return Ok(());
    }
    let out = args.output.as_ref().expect("clap requires --output without --accuracy");
    let map = NormalizationCubeMap::new(args.size as usize, args.encoding);
    write(out, &map)
}

/// Writes six PNG faces into a folder, or one DDS / KTX2 cube map.
pub fn write(out: &std::path::Path, map: &NormalizationCubeMap) -> Result<(), CliError> {
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
            let format = TextureFormat::Rgba8;
            if ext.as_deref() == Some("dds") {
                write_dds(out, &layout, format)?
            } else {
                write_ktx2(out, &layout, format)?
            }
        }
        Some(_) if !out.is_dir() => {
            return Err(bumpmap_io::IoError::UnsupportedOutput {
                path: out.to_path_buf(),
                expected: "a folder, .dds or .ktx2",
            }
            .into());
        }
        _ => {
            // The set makes the folder if it is missing (and removes it again on failure).
            let mut set = FileSet::new(&[]);
            for face in CubeFace::ALL {
                let path = out.join(format!("{}.png", face.stem()));
                save_png_into(&mut set, &path, n, n, PngLayout::Rgb8, map.faces[face as usize].as_flattened())?;
            }
            set.commit()?;
        }
    }
    Ok(())
}

/// Markdown table of the worst angular error for face sizes 8–128 in both encodings.
pub fn accuracy_table() -> String {
    let mut s =
        String::from("| face size | unorm: worst error (°) | kilgard: worst error (°) |\n| --- | --- | --- |\n");
    for size in [8, 16, 32, 64, 128] {
        let e = |enc| worst_angular_error_degrees(&NormalizationCubeMap::new(size, enc));
        s += &format!("| {size} | {:.3} | {:.3} |\n", e(Encoding::Unorm), e(Encoding::Kilgard));
    }
    s
}
