//! A folder of height fields into a folder of normal maps, as `bumpmap normalmap IN_DIR -o
//! OUT_DIR` makes them: every image directly in the folder, one normal map each (`STEM.png`, or
//! `STEM.dds` for a compressed format), made in parallel, each written all files or none.
//!
//! Planned before any work ([`FolderBatch::plan`]): two inputs whose outputs would be the same
//! files (`a.png` and `a.jpg`; `a.png` and `a.mip1.png` with mips) are refused, as is an output
//! folder that is the input folder; a link leading out of the folder is skipped (the folder is
//! what the user pointed at), and said so in [`FolderBatch::skipped`].
//!
//! What this module does not do: say anything (each file's outcome goes to the caller's
//! function, from any thread), or stop at the first failure (the others are still made).

use std::collections::BTreeMap;
use std::path::{Component, Path, PathBuf};

use bumpmap_io::texture_file::TextureFormat;
use bumpmap_io::{Channel, IoError};
use rayon::prelude::*;

use super::{MapOptions, OutputsError};

/// Image extensions a folder walk picks up.
const IMAGE_EXTENSIONS: [&str; 13] =
    ["png", "tga", "bmp", "jpg", "jpeg", "tif", "tiff", "pgm", "ppm", "pbm", "pam", "pnm", "exr"];

/// Why a folder cannot be made into normal maps (nothing was read or written).
#[derive(Debug, thiserror::Error)]
pub enum FolderError {
    /// The output names a file, not a folder.
    #[error("a folder input needs a folder output")]
    OutputNotAFolder(PathBuf),
    /// The input folder could not be listed.
    #[error("{1}")]
    List(PathBuf, std::io::Error),
    /// No image in the folder.
    #[error("no image files in this folder")]
    Empty(PathBuf),
    /// Two inputs would write the same output.
    #[error("its output {stem}.png would also be the output of {}; rename one", other.display())]
    SameOutput {
        /// The input found second.
        file: PathBuf,
        /// The output's stem.
        stem: String,
        /// The input with that output already.
        other: PathBuf,
    },
    /// An input's output would be a mip level of another's chain.
    #[error("its output {stem}.png would be a mip level of {}'s chain; rename one", other.display())]
    MipOfAnother {
        /// The input.
        file: PathBuf,
        /// Its output's stem.
        stem: String,
        /// The input whose chain it would be part of.
        other: PathBuf,
    },
    /// The output folder is the input folder.
    #[error("output folder is the input folder; outputs would mix with inputs")]
    SameFolder(PathBuf),
}

impl FolderError {
    /// The file or folder at fault.
    pub fn path(&self) -> &Path {
        match self {
            Self::OutputNotAFolder(p) | Self::List(p, _) | Self::Empty(p) | Self::SameFolder(p) => p,
            Self::SameOutput { file, .. } | Self::MipOfAnother { file, .. } => file,
        }
    }
}

/// The height fields of a folder and the folder their normal maps go to.
#[derive(Debug)]
pub struct FolderBatch {
    /// Every image read, sorted.
    pub files: Vec<PathBuf>,
    /// Where the normal maps go (a `..` after a folder yet to be made resolved, so no empty
    /// folder is left behind).
    pub out_dir: PathBuf,
    /// The entries skipped, each with why (a link out of the folder, say).
    pub skipped: Vec<IoError>,
}

impl FolderBatch {
    /// Lists `input`'s images and checks them and `out_dir` before any work; `mips` says whether
    /// each output is a chain (whose `.mipN.png` files another input's output must not be).
    pub fn plan(input: &Path, out_dir: &Path, mips: bool) -> Result<FolderBatch, FolderError> {
        if out_dir.extension().is_some() && !out_dir.is_dir() {
            return Err(FolderError::OutputNotAFolder(out_dir.to_path_buf()));
        }
        let place = format!("the folder {}", input.display());
        let mut skipped = Vec::new();
        let mut files: Vec<PathBuf> = std::fs::read_dir(input)
            .map_err(|e| FolderError::List(input.to_path_buf(), e))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.extension()
                    .is_some_and(|e| IMAGE_EXTENSIONS.contains(&e.to_string_lossy().to_ascii_lowercase().as_str()))
                    && !p.is_dir()
            })
            .filter(|p| match bumpmap_io::siblings::in_folder(input, p, &place) {
                Ok(found) => found.is_some(),
                Err(e) => {
                    skipped.push(e);
                    false
                }
            })
            .collect();
        files.sort();
        if files.is_empty() {
            return Err(FolderError::Empty(input.to_path_buf()));
        }
        let stem = |p: &Path| p.file_stem().unwrap_or_default().to_string_lossy().into_owned();
        let mut by_stem: BTreeMap<String, &PathBuf> = BTreeMap::new();
        for file in &files {
            if let Some(other) = by_stem.insert(stem(file), file) {
                return Err(FolderError::SameOutput { file: file.clone(), stem: stem(file), other: other.clone() });
            }
        }
        if mips {
            for file in &files {
                let s = stem(file);
                let base = s.rsplit_once(".mip").filter(|(_, k)| k.parse::<u32>().is_ok_and(|k| k > 0)).map(|(b, _)| b);
                if let Some(other) = base.and_then(|b| by_stem.get(b)) {
                    return Err(FolderError::MipOfAnother { file: file.clone(), stem: s, other: (*other).clone() });
                }
            }
        }
        // The folder is made by the first set written into it (and removed with the last one
        // that fails or is interrupted, when nothing else landed there): see `FileSet`.
        // Compared with the input as it will resolve (`missing/../in` is the input folder once
        // `missing` is made).
        let resolved = bumpmap_io::atomic::resolved(out_dir);
        if resolved.is_some() && resolved == std::fs::canonicalize(input).ok() {
            return Err(FolderError::SameFolder(out_dir.to_path_buf()));
        }
        // A `..` after a folder yet to be made would make that folder and leave it empty: write
        // to the folder the path resolves to instead.
        let out_dir = match resolved {
            Some(r) if out_dir.components().any(|c| c == Component::ParentDir) => r,
            _ => out_dir.to_path_buf(),
        };
        Ok(FolderBatch { files, out_dir, skipped })
    }

    /// Makes and writes every file's normal map (the chain with `mips`, texels in `format`,
    /// heights read from `channel`), in parallel; `done` is told each file's outcome as it
    /// finishes. Returns how many failed.
    pub fn run(
        &self,
        options: &MapOptions,
        mips: bool,
        format: TextureFormat,
        channel: Channel,
        done: &(dyn Fn(&Path, Result<(), OutputsError>) + Sync),
    ) -> usize {
        // Compressed texels need a container: one .dds per input.
        let ext = if format.is_compressed() { "dds" } else { "png" };
        self.files
            .par_iter()
            .map(|file| {
                let out =
                    self.out_dir.join(format!("{}.{ext}", file.file_stem().unwrap_or_default().to_string_lossy()));
                let result = (|| -> Result<(), OutputsError> {
                    bumpmap_io::atomic::ensure_not_input(&out, &[file])?;
                    let field = bumpmap_io::load_height_field(file, channel)?;
                    let chain = super::normal_map_as(options, mips, format, &field)?;
                    super::write_chain(&out, &chain, format, &[file])?;
                    Ok(())
                })();
                let failed = result.is_err() as usize;
                done(file, result);
                failed
            })
            .sum()
    }
}
