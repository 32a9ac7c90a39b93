//! One height field into the normal map and every map asked for beside it, written as one set
//! of files, as `bumpmap normalmap` writes them: the files planned first (each output's files,
//! none of them another output's or an input), the memory they take together checked before any
//! map is made, then each map made and every file staged into one [`FileSet`], so all land or
//! none. glTF's ORM packing is done here too: with the ambient occlusion asked for and the
//! roughness in glTF's layout, the roughness map's red channel holds each level's occlusion.
//! The heights alone, as a set of files of their own, go through [`write_heights`].
//!
//! What this module does not do: read the heights (the caller does, so a preset or a file),
//! say anything (the heights' clamping comes back as data), or name the command line's flags
//! ([`Output`] is named by the skins).

use std::path::{Path, PathBuf};

use bumpmap_io::IoError;
use bumpmap_io::atomic::{FileSet, ensure_not_input};
use bumpmap_io::height_file::HeightBits;
use bumpmap_io::image_file::level_path;
use bumpmap_io::texture_file::{Level, TextureFormat, TextureLayout, write_dds_into, write_ktx2_into};
use bumpmap_math::HeightField;
use bumpmap_math::buffer::OutOfMemory;

use super::{Chain, Clamped, MapError, MapOptions, SaveError};
use crate::options::RoughnessLayout;

/// One of the files a [`MapOutputs`] writes, for messages (the skins name each by its flag or
/// keyword).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// The normal map itself.
    NormalMap,
    /// The roughness map.
    Roughness,
    /// LEAN's two moment files.
    Lean,
    /// The heights the parallax techniques read.
    Heights,
    /// The horizon map.
    Horizons,
    /// The ambient occlusion.
    AmbientOcclusion,
    /// The bent normals.
    BentNormals,
}

/// Where each map goes; every map but the normal map is optional.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MapOutputs {
    /// The normal map: PNG (`.mipN.png` beside it with its chain), `.dds` or `.ktx2`.
    pub normal_map: PathBuf,
    /// The roughness map's chain (RGBA8).
    pub roughness: Option<PathBuf>,
    /// LEAN's moments: this `.ktx2` or `.dds` and one with `.mxy-j` before the extension.
    pub lean: Option<PathBuf>,
    /// The heights and their min–max levels.
    pub heights: Option<PathBuf>,
    /// The horizon map.
    pub horizons: Option<PathBuf>,
    /// The ambient occlusion (a gray image).
    pub ambient_occlusion: Option<PathBuf>,
    /// The bent normals (level 0).
    pub bent_normals: Option<PathBuf>,
}

/// Why a set of maps was not written (nothing was).
#[derive(Debug, thiserror::Error)]
pub enum OutputsError {
    /// Two outputs would write the same file: `output`'s `path` is also `other`'s.
    #[error("{path}: a file of two outputs ({output:?} and {other:?})")]
    Clash {
        /// The output found second.
        output: Output,
        /// The output that has the file already.
        other: Output,
        /// The file.
        path: PathBuf,
    },
    /// LEAN's moments asked of a file that holds no floats.
    #[error("{path}: the moments are floats, which .ktx2 or .dds hold (not .{extension})")]
    LeanNeedsFloats {
        /// The file asked for.
        path: PathBuf,
        /// Its extension.
        extension: String,
    },
    /// The maps together need more memory than the process may use.
    #[error("{source} from its {width}x{height} heights")]
    TooBig {
        /// The heights' width.
        width: usize,
        /// The heights' height.
        height: usize,
        /// What was asked for.
        source: OutOfMemory,
    },
    /// A map could not be made.
    #[error(transparent)]
    Map(#[from] MapError),
    /// A chain could not be written.
    #[error(transparent)]
    Save(#[from] SaveError),
    /// A file could not be written, or would replace an input.
    #[error(transparent)]
    Io(#[from] IoError),
}

/// The files each output takes, planned before any work.
struct Planned {
    lean: Option<[PathBuf; 2]>,
}

/// What [`MapOutputs::write`] did: the files written, and the heights' range where it left
/// [0, 1] (they were clamped for the heights' file).
#[derive(Debug)]
pub struct Written {
    /// Every file, in the order written.
    pub files: Vec<PathBuf>,
    /// The heights' range, where the heights' file clamped it.
    pub clamped: Option<Clamped>,
}

/// LEAN's two files for `out`: `out` itself and `out`'s stem with `.mxy-j` before the
/// extension. Only `.ktx2` and `.dds` hold floats.
pub fn lean_files(out: &Path) -> Result<[PathBuf; 2], OutputsError> {
    let ext = out.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    if ext != "ktx2" && ext != "dds" {
        return Err(OutputsError::LeanNeedsFloats { path: out.to_path_buf(), extension: ext });
    }
    let stem = out.file_stem().unwrap_or_default().to_string_lossy();
    let ext = out.extension().unwrap_or_default().to_string_lossy();
    Ok([out.to_path_buf(), out.with_file_name(format!("{stem}.mxy-j.{ext}"))])
}

/// Writes `field`'s heights as the parallax techniques read them ([`super::height_mips`]: every
/// level rounded to `options.bits`, and the min–max levels), as `normalmap --height-out OUT`
/// writes them: by `out`'s extension (`.png` with `.mipK.png` and `.minmax.png` files beside it,
/// or one `.ktx2` / `.dds` and its `.minmax` twin), all files or none, none replacing one of
/// `inputs`. The files are checked before any work.
///
/// ```
/// use bumpmap::maps::{self, MapOptions};
/// use bumpmap::HeightPreset;
///
/// let dir = std::env::temp_dir().join(format!("bumpmap-doc-heights-{}", std::process::id()));
/// let field = HeightPreset::Bricks.render(16, 16);
/// let written = maps::write_heights(&dir.join("h.ktx2"), &MapOptions::default(), &field, &[]).unwrap();
/// assert_eq!(written.files, [dir.join("h.ktx2"), dir.join("h.minmax.ktx2")]);
/// assert!(written.clamped.is_none()); // the preset's heights lie in [0, 1]
/// assert!(maps::write_heights(&dir.join("h.jpg"), &MapOptions::default(), &field, &[]).is_err());
/// std::fs::remove_dir_all(dir).unwrap();
/// ```
pub fn write_heights(
    out: &Path,
    options: &MapOptions,
    field: &HeightField,
    inputs: &[&Path],
) -> Result<Written, OutputsError> {
    for file in bumpmap_io::height_file::heights_files(out, 1)? {
        ensure_not_input(&file, inputs)?;
    }
    let mut set = FileSet::new(inputs);
    let clamped = write_heights_into(&mut set, out, options, field)?;
    Ok(Written { files: set.commit()?, clamped })
}

/// [`write_heights`] staged into `set` (which a caller commits, or drops to write nothing);
/// returns the heights' range where it leaves [0, 1]. `out`'s extension is checked before any
/// work.
pub fn write_heights_into(
    set: &mut FileSet,
    out: &Path,
    options: &MapOptions,
    field: &HeightField,
) -> Result<Option<Clamped>, OutputsError> {
    bumpmap_io::height_file::heights_files(out, 1)?;
    let stored = super::height_mips(options, field)?;
    let bits = HeightBits::of(options.bits);
    bumpmap_io::height_file::write_heights_into(set, out, &stored.mips, bits)?;
    Ok(stored.clamped)
}

impl MapOutputs {
    /// Whether any map besides the normal map is asked for.
    pub fn any_beside(&self) -> bool {
        self.roughness.is_some()
            || self.lean.is_some()
            || self.heights.is_some()
            || self.horizons.is_some()
            || self.ambient_occlusion.is_some()
            || self.bent_normals.is_some()
    }

    /// Whether the horizon map is made (the horizons, the occlusion or the bent normals).
    pub fn makes_horizon_map(&self) -> bool {
        self.horizons.is_some() || self.ambient_occlusion.is_some() || self.bent_normals.is_some()
    }

    /// Refuses, before any work, outputs that would write the same file or replace one of
    /// `inputs` ([`Self::write`] checks again).
    pub fn check(&self, inputs: &[&Path]) -> Result<(), OutputsError> {
        self.plan(inputs).map(|_| ())
    }

    /// [`Self::check`], and the files of the outputs with more than one.
    fn plan(&self, inputs: &[&Path]) -> Result<Planned, OutputsError> {
        let clash = |output, other, path: &Path| OutputsError::Clash { output, other, path: path.to_path_buf() };
        let lean = self.lean.as_deref().map(lean_files).transpose()?;
        let normal0 = level_path(&self.normal_map, 0);
        let roughness0 = self.roughness.as_ref().map(|r| level_path(r, 0));
        for out in std::iter::once(&self.normal_map).chain(&self.roughness).chain(lean.iter().flatten()) {
            ensure_not_input(out, inputs)?;
        }
        // What the normal map and the roughness map write first.
        let firsts = [Some((Output::NormalMap, &normal0)), roughness0.as_ref().map(|r| (Output::Roughness, r))];
        let first_of = |path: &PathBuf| firsts.iter().flatten().find(|(_, p)| *p == path).map(|(o, _)| *o);
        if let Some(lean) = &lean
            && let Some((other, path)) = lean.iter().find_map(|l| first_of(l).map(|o| (o, l)))
        {
            return Err(clash(Output::Lean, other, path));
        }
        if let Some(r) = &roughness0
            && *r == normal0
        {
            return Err(clash(Output::Roughness, Output::NormalMap, r));
        }
        let heights = match &self.heights {
            Some(h) => {
                let files = bumpmap_io::height_file::heights_files(h, 1)?;
                for f in &files {
                    ensure_not_input(f, inputs)?;
                }
                if let Some((other, path)) = files.iter().find_map(|f| first_of(f).map(|o| (o, f))) {
                    return Err(clash(Output::Heights, other, path));
                }
                files
            }
            None => Vec::new(),
        };
        if let Some(lean) = &lean
            && let Some(path) = lean.iter().find(|l| heights.contains(l))
        {
            return Err(clash(Output::Lean, Output::Heights, path));
        }
        let mut taken: Vec<(Output, PathBuf)> = std::iter::once((Output::NormalMap, normal0.clone()))
            .chain(roughness0.iter().map(|r| (Output::Roughness, r.clone())))
            .chain(lean.iter().flatten().map(|l| (Output::Lean, l.clone())))
            .chain(heights.iter().map(|h| (Output::Heights, h.clone())))
            .collect();
        let beside_horizons = [
            (
                Output::Horizons,
                self.horizons.as_ref().map(|h| bumpmap_io::horizon_file::horizon_files(h, 1)).transpose()?,
            ),
            (
                Output::AmbientOcclusion,
                self.ambient_occlusion
                    .as_ref()
                    .map(|a| bumpmap_io::horizon_file::gray_file(a).map(|f| vec![f]))
                    .transpose()?,
            ),
            (Output::BentNormals, self.bent_normals.as_ref().map(|b| vec![level_path(b, 0)])),
        ];
        for (output, files) in beside_horizons {
            for file in files.into_iter().flatten() {
                ensure_not_input(&file, inputs)?;
                if let Some((other, _)) = taken.iter().find(|(_, t)| *t == file) {
                    return Err(clash(output, *other, &file));
                }
                taken.push((output, file));
            }
        }
        Ok(Planned { lean })
    }

    /// Refuses, before any of it is made, what these outputs ask of a `width`×`height` height
    /// field at `bits` a channel when it will not fit in the memory the process may still have
    /// (the field itself is loaded). Every buffer is also asked for fallibly where the library
    /// can; this check is what keeps the rest (the moments as written, the encoders' copies)
    /// from aborting.
    pub fn ensure_room(&self, bits: u8, width: usize, height: usize) -> Result<(), OutputsError> {
        use super::per_texel::*;
        let mut per = if bits == 16 { NORMAL_MAP_16 } else { NORMAL_MAP_8 };
        if self.lean.is_some() {
            per += LEAN + if bits == 16 { NORMAL_MAP_8 } else { 0 };
        }
        if self.roughness.is_some() {
            per += ROUGHNESS;
        }
        if self.heights.is_some() {
            per += HEIGHTS;
        }
        if self.makes_horizon_map() {
            per += HORIZONS;
        }
        if self.bent_normals.is_some() {
            per += BENT_NORMALS;
        }
        let bytes = (width as u64 * height as u64).saturating_mul(per);
        bumpmap_math::buffer::ensure_available(bytes, "making these maps").map_err(|source| OutputsError::TooBig {
            width,
            height,
            source,
        })
    }

    /// Checks the outputs against each other and `inputs` ([`Self::check`]) and the memory they
    /// need ([`Self::ensure_room`]), then makes every map of `field` asked for (the normal map's
    /// chain with `mips`, at `format`'s depth) and writes them all or none, the normal map's DDS
    /// or KTX2 texels in `format`; the horizon map's file holds every level with `mips`. The
    /// horizon map, the long part where one is made ([`Self::makes_horizon_map`]), tells
    /// `progress(rows done, rows)` ([`super::horizon_map`]).
    pub fn write(
        &self,
        field: HeightField,
        options: &MapOptions,
        mips: bool,
        format: TextureFormat,
        inputs: &[&Path],
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Written, OutputsError> {
        let planned = self.plan(inputs)?;
        self.ensure_room(options.bits, field.width(), field.height())?;
        let chain = super::normal_map_as(options, mips, format, &field)?;
        let horizons =
            if self.makes_horizon_map() { Some(super::horizon_map(options, &field, progress)?) } else { None };
        let mut roughness = if self.roughness.is_some() { Some(super::roughness_map(options, &field)?) } else { None };
        let lean = match &planned.lean {
            Some(_) => Some(super::lean_moments(options, &field, Some(&chain))?),
            None => None,
        };
        let heights = match &self.heights {
            Some(_) => Some(super::height_mips(options, &field)?),
            None => None,
        };
        // glTF's ORM texture holds the occlusion in red: with the occlusion asked for, the
        // occlusion's own levels.
        if let (Some(chain), Some(map), RoughnessLayout::Gltf, Some(_)) =
            (&mut roughness, &horizons, options.roughness_layout, &self.ambient_occlusion)
        {
            let ao = map.ambient_occlusion_levels(options.normals.scale.abs()).map_err(MapError::OutOfMemory)?;
            for (level, occlusion) in chain.levels.iter_mut().zip(&ao) {
                for (texel, &v) in level.texels.iter_mut().zip(&occlusion.texels) {
                    texel[0] = bumpmap_math::roughness::unorm8(v);
                }
            }
        }
        // The heights are not needed to write the maps: a 16384² field is 1 GiB of floats.
        drop(field);
        let mut set = FileSet::new(inputs);
        super::write_chain_into(&mut set, &self.normal_map, &chain, format)?;
        if let (Some(out), Some(chain)) = (&self.roughness, roughness) {
            super::write_chain_into(&mut set, out, &Chain::Rgba8(chain), TextureFormat::Rgba8)?;
        }
        if let (Some(paths), Some(planes)) = (&planned.lean, &lean) {
            for (path, plane) in paths.iter().zip(planes) {
                let tex = TextureLayout { faces: vec![plane.iter().map(Level::Rgba32F).collect()] };
                match path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).as_deref() {
                    Some("dds") => write_dds_into(&mut set, path, &tex, TextureFormat::Rgba32Float)?,
                    _ => write_ktx2_into(&mut set, path, &tex, TextureFormat::Rgba32Float)?,
                }
            }
        }
        let bits = HeightBits::of(options.bits);
        if let (Some(path), Some(heights)) = (&self.heights, &heights) {
            bumpmap_io::height_file::write_heights_into(&mut set, path, &heights.mips, bits)?;
        }
        if let Some(map) = &horizons {
            // Texels per unit of height: the normal map's own geometry.
            let depth = options.normals.scale.abs();
            if let Some(path) = &self.horizons {
                let count = if mips { map.levels().len() } else { 1 };
                bumpmap_io::horizon_file::write_horizons_into(&mut set, path, map, count, bits)?;
            }
            if let Some(path) = &self.ambient_occlusion {
                let ao = map.ambient_occlusion(depth);
                bumpmap_io::horizon_file::write_gray_into(&mut set, path, (map.width(), map.height()), &ao, bits)?;
            }
            if let Some(path) = &self.bent_normals {
                let format = if options.bits == 16 { TextureFormat::Rgba16 } else { TextureFormat::Rgba8 };
                super::write_chain_into(&mut set, path, &super::bent_normals(options, map), format)?;
            }
        }
        let clamped = heights.and_then(|h| h.clamped);
        Ok(Written { files: set.commit()?, clamped })
    }
}
