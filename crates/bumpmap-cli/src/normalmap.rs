//! `bumpmap normalmap`: one height field, or a folder of them, into normal maps.

use std::path::{Path, PathBuf};

use bumpmap::maps::{self, Chain, MapOptions};
use bumpmap_io::atomic::{FileSet, ensure_not_input};
use bumpmap_io::height_file::HeightBits;
use bumpmap_io::texture_file::{Level, TextureFormat, TextureLayout, write_dds_into, write_ktx2_into};
use bumpmap_io::{Channel, HeightSource};
use bumpmap_math::{HeightField, MipChain, MipMode, NormalMapOptions};
use bumpmap_words::maps::{map_error, save_error, scale_err};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use crate::args::NormalmapArgs;
use crate::error::CliError;

mod extras;

pub(crate) use extras::height_levels;
use extras::lean_paths;

/// Image extensions a folder walk picks up.
const IMAGE_EXTENSIONS: [&str; 13] =
    ["png", "tga", "bmp", "jpg", "jpeg", "tif", "tiff", "pgm", "ppm", "pbm", "pam", "pnm", "exr"];

pub fn run(args: &NormalmapArgs) -> Result<(), CliError> {
    let options = args.maps.0.normals;
    let channel: Channel = args.channel.0;
    let input = Path::new(&args.input);
    if input.is_dir() {
        if args.roughness_out.is_some()
            || args.lean_out.is_some()
            || args.height_out.is_some()
            || args.horizon_out.is_some()
            || args.ao_out.is_some()
            || args.bent_normals_out.is_some()
        {
            return Err(CliError::Usage(
                "--roughness-out, --lean-out, --height-out, --horizon-out, --ao-out and --bent-normals-out write one map: give one height field, not a folder"
                    .into(),
            ));
        }
        return run_folder(input, args, &options, channel);
    }
    let source = HeightSource::parse(&args.input);
    let format = texel_format(args)?;
    let output = output_file(&args.output, &source, &args.input, format);
    maps::check_container(&output, format).map_err(save_error)?;
    let inputs: Vec<&Path> = source.path().into_iter().collect();
    let lean_out = args.lean_out.as_ref().map(|l| lean_paths(l)).transpose()?;
    for out in std::iter::once(&output).chain(&args.roughness_out).chain(lean_out.iter().flatten()) {
        ensure_not_input(out, &inputs)?;
    }
    if let Some(lean) = &lean_out {
        let others = [Some(level_path(&output, 0)), args.roughness_out.as_ref().map(|r| level_path(r, 0))];
        if let Some(clash) = lean.iter().find(|l| others.iter().flatten().any(|o| o == *l)) {
            return Err(CliError::Usage(format!("--lean-out: {} is another output's file", clash.display())));
        }
    }
    if let Some(rough) = &args.roughness_out
        && level_path(rough, 0) == level_path(&output, 0)
    {
        return Err(CliError::Usage(format!("--roughness-out {} is the normal map's own file", rough.display())));
    }
    let height_files = match &args.height_out {
        Some(h) => {
            let files = bumpmap_io::height_file::heights_files(h, 1)?;
            for f in &files {
                ensure_not_input(f, &inputs)?;
            }
            let others = [Some(level_path(&output, 0)), args.roughness_out.as_ref().map(|r| level_path(r, 0))];
            if let Some(clash) = files.iter().find(|f| others.iter().flatten().any(|o| o == *f)) {
                return Err(CliError::Usage(format!("--height-out: {} is another output's file", clash.display())));
            }
            files
        }
        None => Vec::new(),
    };
    if let Some(lean) = &lean_out
        && let Some(clash) = lean.iter().find(|l| height_files.contains(l))
    {
        return Err(CliError::Usage(format!("--lean-out: {} is --height-out's file", clash.display())));
    }
    let mut taken: Vec<(&str, PathBuf)> = std::iter::once(("-o", level_path(&output, 0)))
        .chain(args.roughness_out.iter().map(|r| ("--roughness-out", level_path(r, 0))))
        .chain(lean_out.iter().flatten().map(|l| ("--lean-out", l.clone())))
        .chain(height_files.iter().map(|h| ("--height-out", h.clone())))
        .collect();
    let horizon_outputs = [
        (
            "--horizon-out",
            args.horizon_out.as_ref().map(|h| bumpmap_io::horizon_file::horizon_files(h, 1)).transpose()?,
        ),
        (
            "--ao-out",
            args.ao_out.as_ref().map(|a| bumpmap_io::horizon_file::gray_file(a).map(|f| vec![f])).transpose()?,
        ),
        ("--bent-normals-out", args.bent_normals_out.as_ref().map(|b| vec![level_path(b, 0)])),
    ];
    for (flag, files) in &horizon_outputs {
        for file in files.iter().flatten() {
            ensure_not_input(file, &inputs)?;
            if let Some((other, _)) = taken.iter().find(|(_, t)| t == file) {
                return Err(CliError::Usage(format!("{flag}: {} is also {other}'s file", file.display())));
            }
            taken.push((flag, file.clone()));
        }
    }
    let field = source.load(channel)?;
    extras::ensure_room(args, field.width(), field.height())?;
    let asked = map_options(args);
    let err = |e| map_error(e, &args.input);
    let levels = make_chain(&field, &options, args.mips, args.maps.0.mip_mode, format, &args.input)?;
    let horizons = if args.horizon_out.is_some() || args.ao_out.is_some() || args.bent_normals_out.is_some() {
        Some(maps::horizon_map(&asked, &field).map_err(err)?)
    } else {
        None
    };
    let mut roughness = match &args.roughness_out {
        Some(_) => Some(maps::roughness_map(&asked, &field).map_err(err)?),
        None => None,
    };
    let lean = match &lean_out {
        Some(_) => Some(maps::lean_moments(&asked, &field, Some(&levels)).map_err(err)?),
        None => None,
    };
    let heights = match &args.height_out {
        Some(_) => Some(height_levels(&asked, &field, &args.input)?),
        None => None,
    };
    // glTF's ORM texture holds the occlusion in red: with --ao-out, the occlusion's own levels.
    if let (Some(chain), Some(map), true, Some(_)) = (
        &mut roughness,
        &horizons,
        args.maps.0.roughness_layout == bumpmap::options::RoughnessLayout::Gltf,
        &args.ao_out,
    ) {
        let ao = map.ambient_occlusion_levels(options.scale.abs()).map_err(CliError::OutOfMemory)?;
        for (level, occlusion) in chain.levels.iter_mut().zip(&ao) {
            for (texel, &v) in level.texels.iter_mut().zip(&occlusion.texels) {
                texel[0] = bumpmap_math::roughness::unorm8(v);
            }
        }
    }
    // The heights are not needed to write the chain: a 16384² field is 1 GiB of floats.
    drop(field);
    let mut set = FileSet::new(&inputs);
    maps::write_chain_into(&mut set, &output, &levels, format).map_err(save_error)?;
    if let (Some(out), Some(chain)) = (&args.roughness_out, roughness) {
        maps::write_chain_into(&mut set, out, &Chain::Rgba8(chain), TextureFormat::Rgba8).map_err(save_error)?;
    }
    if let (Some(paths), Some(planes)) = (&lean_out, &lean) {
        for (path, plane) in paths.iter().zip(planes) {
            let tex = TextureLayout { faces: vec![plane.iter().map(Level::Rgba32F).collect()] };
            match path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).as_deref() {
                Some("dds") => write_dds_into(&mut set, path, &tex, TextureFormat::Rgba32Float)?,
                _ => write_ktx2_into(&mut set, path, &tex, TextureFormat::Rgba32Float)?,
            }
        }
    }
    let bits = if args.maps.0.bits == 16 { HeightBits::Sixteen } else { HeightBits::Eight };
    if let (Some(path), Some(heights)) = (&args.height_out, &heights) {
        bumpmap_io::height_file::write_heights_into(&mut set, path, heights, bits)?;
    }
    if let Some(map) = &horizons {
        // Texels per unit of height: the normal map's own geometry.
        let depth = options.scale.abs();
        if let Some(path) = &args.horizon_out {
            let count = if args.mips { map.levels().len() } else { 1 };
            bumpmap_io::horizon_file::write_horizons_into(&mut set, path, map, count, bits)?;
        }
        if let Some(path) = &args.ao_out {
            let ao = map.ambient_occlusion(depth);
            bumpmap_io::horizon_file::write_gray_into(&mut set, path, (map.width(), map.height()), &ao, bits)?;
        }
        if let Some(path) = &args.bent_normals_out {
            let format = if args.maps.0.bits == 16 { TextureFormat::Rgba16 } else { TextureFormat::Rgba8 };
            maps::write_chain_into(&mut set, path, &maps::bent_normals(&asked, map), format).map_err(save_error)?;
        }
    }
    let written = set.commit()?;
    eprintln!("wrote {}", describe(&written));
    Ok(())
}

/// The output file for one input: `-o` itself, or, when `-o` is a folder (an existing one, or
/// a path ending in `/`), `FOLDER/STEM.png` (`.dds` for a compressed format) with the input's
/// file stem or the preset's name.
fn output_file(output: &Path, source: &HeightSource, spec: &str, format: TextureFormat) -> PathBuf {
    let as_folder = output.is_dir() || output.as_os_str().to_string_lossy().ends_with(std::path::MAIN_SEPARATOR);
    if !as_folder {
        return output.to_path_buf();
    }
    let stem = match source.path() {
        Some(p) => p.file_stem().unwrap_or_default().to_string_lossy().into_owned(),
        None => spec.split(['@', ':']).next().unwrap_or("normal").to_string(),
    };
    output.join(format!("{stem}.{}", if format.is_compressed() { "dds" } else { "png" }))
}

/// The maps' options `normalmap`'s flags ask for.
pub fn map_options(args: &NormalmapArgs) -> MapOptions {
    args.maps.0
}

/// The texel format `--format` and `--bits` ask for together.
pub fn texel_format(args: &NormalmapArgs) -> Result<TextureFormat, CliError> {
    let format: TextureFormat = args.format.0;
    match (format, args.maps.0.bits) {
        (TextureFormat::Rgba8, 16) => Ok(TextureFormat::Rgba16),
        (TextureFormat::Rgba16, _) => Ok(TextureFormat::Rgba16),
        (f, 16) => Err(CliError::Usage(format!(
            "--bits 16 cannot be stored as --format {}: BC5 and BC7 hold 8 bits a channel (use rgba8 with --bits 16)",
            f.dxgi_name()
        ))),
        (f, _) => Ok(f),
    }
}

/// [`maps::normal_chain`] at the depth `format` stores, `name` naming the field in errors.
pub fn make_chain(
    field: &HeightField,
    options: &NormalMapOptions,
    mips: bool,
    mode: MipMode,
    format: TextureFormat,
    name: &str,
) -> Result<Chain, CliError> {
    let err = |source| scale_err(source, name);
    Ok(if format == TextureFormat::Rgba16 {
        Chain::Rgba16(maps::normal_chain(field, options, mips, mode).map_err(err)?)
    } else {
        Chain::Rgba8(maps::normal_chain(field, options, mips, mode).map_err(err)?)
    })
}

/// `a.png` for one file, `a.png, a.mip1.png, … (9 files)` for a chain.
fn describe(written: &[PathBuf]) -> String {
    match written {
        [one] => one.display().to_string(),
        [first, .., last] => format!("{}, …, {} ({} files)", first.display(), last.display(), written.len()),
        [] => "nothing".into(),
    }
}

/// Level 0, or the whole chain, 8 bits a channel.
pub fn make(
    field: &HeightField,
    options: &NormalMapOptions,
    mips: bool,
    mode: MipMode,
    name: &str,
) -> Result<MipChain, CliError> {
    maps::normal_chain(field, options, mips, mode).map_err(|source| scale_err(source, name))
}

pub use bumpmap_io::image_file::level_path;

/// Writes a chain by the output's extension: PNG files, or one DDS / KTX2 file.
pub fn write(out: &Path, chain: MipChain) -> Result<(), CliError> {
    write_set(out, &Chain::Rgba8(chain), &[], TextureFormat::Rgba8).map(|_| ())
}

/// [`write`], all files or none, none of them replacing one of `inputs`, texels of DDS and
/// KTX2 files in `format`; returns the paths.
pub fn write_set(out: &Path, chain: &Chain, inputs: &[&Path], format: TextureFormat) -> Result<Vec<PathBuf>, CliError> {
    maps::write_chain(out, chain, format, inputs).map_err(save_error)
}

fn run_folder(
    input: &Path,
    args: &NormalmapArgs,
    options: &NormalMapOptions,
    channel: Channel,
) -> Result<(), CliError> {
    let out_dir = &args.output;
    if out_dir.extension().is_some() && !out_dir.is_dir() {
        return Err(CliError::Path { path: out_dir.clone(), reason: "a folder input needs a folder output".into() });
    }
    // Compressed texels need a container: one .dds per input.
    let format = texel_format(args)?;
    let ext = if format.is_compressed() { "dds" } else { "png" };
    let read_err = |e: std::io::Error| CliError::Path { path: input.to_path_buf(), reason: e.to_string() };
    // Every image directly in the folder; a link leading out of it (or to what is not a file)
    // is skipped with a warning: the folder is what the user pointed at.
    let place = format!("the folder {}", input.display());
    let mut files: Vec<PathBuf> = std::fs::read_dir(input)
        .map_err(read_err)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension().is_some_and(|e| IMAGE_EXTENSIONS.contains(&e.to_string_lossy().to_ascii_lowercase().as_str()))
                && !p.is_dir()
        })
        .filter(|p| match bumpmap_io::siblings::in_folder(input, p, &place) {
            Ok(found) => found.is_some(),
            Err(e) => {
                crate::report::warn(format!("skipped {e}"));
                false
            }
        })
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(CliError::Path { path: input.to_path_buf(), reason: "no image files in this folder".into() });
    }
    // Two inputs whose outputs would be the same files (a.png and a.jpg; a.png and a.mip1.png
    // with --mips) are refused before anything is read or written: one would be lost.
    let stem = |p: &Path| p.file_stem().unwrap_or_default().to_string_lossy().into_owned();
    let mut by_stem: std::collections::BTreeMap<String, &PathBuf> = std::collections::BTreeMap::new();
    for file in &files {
        if let Some(other) = by_stem.insert(stem(file), file) {
            return Err(CliError::Path {
                path: file.clone(),
                reason: format!(
                    "its output {}.png would also be the output of {}; rename one",
                    stem(file),
                    other.display()
                ),
            });
        }
    }
    if args.mips {
        for file in &files {
            let s = stem(file);
            let base = s.rsplit_once(".mip").filter(|(_, k)| k.parse::<u32>().is_ok_and(|k| k > 0)).map(|(b, _)| b);
            if let Some(other) = base.and_then(|b| by_stem.get(b)) {
                return Err(CliError::Path {
                    path: file.clone(),
                    reason: format!(
                        "its output {s}.png would be a mip level of {}'s chain; rename one",
                        other.display()
                    ),
                });
            }
        }
    }
    // The folder is made by the first set written into it (and removed with the last one that
    // fails or is interrupted, when nothing else landed there): see `FileSet`. Compared with the
    // input as it will resolve (`missing/../in` is the input folder once `missing` is made).
    let resolved = bumpmap_io::atomic::resolved(out_dir);
    if resolved.is_some() && resolved == std::fs::canonicalize(input).ok() {
        return Err(CliError::Path {
            path: out_dir.clone(),
            reason: "output folder is the input folder; outputs would mix with inputs".into(),
        });
    }
    // A `..` after a folder yet to be made would make that folder and leave it empty: write to
    // the folder the path resolves to instead.
    let out_dir = &match resolved {
        Some(r) if out_dir.components().any(|c| c == std::path::Component::ParentDir) => r,
        _ => out_dir.clone(),
    };
    let bar = ProgressBar::new(files.len() as u64)
        .with_style(ProgressStyle::with_template("{bar:40} {pos}/{len} {wide_msg}").expect("valid template"));
    let failed: usize = files
        .par_iter()
        .map(|file| {
            let out = out_dir.join(format!("{}.{ext}", file.file_stem().unwrap_or_default().to_string_lossy()));
            let result = ensure_not_input(&out, &[file])
                .map_err(CliError::from)
                .and_then(|_| Ok(bumpmap_io::load_height_field(file, channel)?))
                .and_then(|field| {
                    make_chain(&field, options, args.mips, args.maps.0.mip_mode, format, &file.display().to_string())
                })
                .and_then(|chain| write_set(&out, &chain, &[file], format).map(|_| ()));
            bar.inc(1);
            bar.set_message(file.file_name().unwrap_or_default().to_string_lossy().into_owned());
            result.map_err(|e| bar.suspend(|| eprintln!("error: {e}"))).is_err() as usize
        })
        .sum();
    bar.finish_and_clear();
    if failed > 0 {
        return Err(CliError::Batch { failed, total: files.len() });
    }
    let plural = if files.len() == 1 { "normal map" } else { "normal maps" };
    eprintln!("wrote {} {plural} into {}", files.len(), out_dir.display());
    Ok(())
}

/// Writes a small text file atomically.
pub fn write_text(path: &Path, text: &str) -> Result<(), CliError> {
    use std::io::Write;
    Ok(bumpmap_io::atomic::write_atomic(path, |w| w.write_all(text.as_bytes()))?)
}

#[cfg(test)]
mod tests {
    use bumpmap::maps::MapOptions;
    use clap::Parser;

    use crate::args::{Cli, Command};

    #[test]
    fn normalmaps_defaults_are_the_librarys() {
        let Command::Normalmap(args) =
            Cli::try_parse_from(["bumpmap", "normalmap", "bricks", "-o", "n.png"]).expect("parses").command
        else {
            unreachable!("normalmap parses as normalmap")
        };
        assert_eq!(super::map_options(&args), MapOptions::default());
    }
}
