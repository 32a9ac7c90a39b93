//! `bumpmap normalmap`: one height field, or a folder of them, into normal maps. The planning,
//! making and writing are the library's (`bumpmap::maps`: `MapOutputs`, `FolderBatch`); this
//! module makes the flags into them and says what was written.

use std::path::{Path, PathBuf};

use bumpmap::maps::{self, FolderBatch, MapOutputs};
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_io::{Channel, HeightSource};
use bumpmap_words::maps::{outputs_error, save_error};
use indicatif::{ProgressBar, ProgressStyle};

use crate::args::NormalmapArgs;
use crate::error::CliError;

pub fn run(args: &NormalmapArgs) -> Result<(), CliError> {
    let channel: Channel = args.channel.0;
    let input = Path::new(&args.input);
    let source = HeightSource::parse(&args.input);
    let format = texel_format(args)?;
    let outputs = MapOutputs {
        normal_map: output_file(&args.output, &source, &args.input, format),
        roughness: args.roughness_out.clone(),
        lean: args.lean_out.clone(),
        heights: args.height_out.clone(),
        horizons: args.horizon_out.clone(),
        ambient_occlusion: args.ao_out.clone(),
        bent_normals: args.bent_normals_out.clone(),
    };
    if input.is_dir() {
        if outputs.any_beside() {
            return Err(CliError::Usage(
                "--roughness-out, --lean-out, --height-out, --horizon-out, --ao-out and --bent-normals-out write one map: give one height field, not a folder"
                    .into(),
            ));
        }
        return run_folder(input, args, channel);
    }
    maps::check_container(&outputs.normal_map, format).map_err(save_error)?;
    let inputs: Vec<&Path> = source.path().into_iter().collect();
    let err = |e| outputs_error(e, &args.input);
    outputs.check(&inputs).map_err(err)?;
    let field = source.load(channel)?;
    // The horizon map is the long part (minutes for 8192²): its rows on a bar.
    let bar = if outputs.makes_horizon_map() { ProgressBar::new(field.height() as u64) } else { ProgressBar::hidden() };
    let bar = bar.with_style(
        ProgressStyle::with_template("horizon map {bar:40} {pos}/{len} rows {elapsed}").expect("a valid template"),
    );
    let written =
        outputs.write(field, &args.maps.0, args.mips, format, &inputs, &|rows, _| bar.set_position(rows as u64));
    bar.finish_and_clear();
    let written = written.map_err(err)?;
    if let Some(clamped) = written.clamped {
        crate::report::warn(format!("{}: {clamped} for --height-out", args.input));
    }
    eprintln!("wrote {}", describe(&written.files));
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

/// `a.png` for one file, `a.png, a.mip1.png, … (9 files)` for a chain.
fn describe(written: &[PathBuf]) -> String {
    match written {
        [one] => one.display().to_string(),
        [first, .., last] => format!("{}, …, {} ({} files)", first.display(), last.display(), written.len()),
        [] => "nothing".into(),
    }
}

fn run_folder(input: &Path, args: &NormalmapArgs, channel: Channel) -> Result<(), CliError> {
    let format = texel_format(args)?;
    let batch = FolderBatch::plan(input, &args.output, args.mips)
        .map_err(|e| CliError::Path { path: e.path().to_path_buf(), reason: e.to_string() })?;
    for skipped in &batch.skipped {
        crate::report::warn(format!("skipped {skipped}"));
    }
    let bar = ProgressBar::new(batch.files.len() as u64)
        .with_style(ProgressStyle::with_template("{bar:40} {pos}/{len} {wide_msg}").expect("valid template"));
    let failed = batch.run(&args.maps.0, args.mips, format, channel, &|file, result| {
        bar.inc(1);
        bar.set_message(file.file_name().unwrap_or_default().to_string_lossy().into_owned());
        if let Err(e) = result {
            let e = outputs_error(e, &file.display().to_string());
            bar.suspend(|| eprintln!("error: {e}"));
        }
    });
    bar.finish_and_clear();
    let total = batch.files.len();
    if failed > 0 {
        return Err(CliError::Batch { failed, total });
    }
    let plural = if total == 1 { "normal map" } else { "normal maps" };
    eprintln!("wrote {total} {plural} into {}", batch.out_dir.display());
    Ok(())
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
        assert_eq!(args.maps.0, MapOptions::default());
    }
}
