//! Baking from files, as `bumpmap bake HIGH LOW -o OUT` does it: both meshes read (OBJ, glTF
//! or GLB, every node with its transform), LOW made ready as the renderer will draw it, the
//! bake (`bumpmap_bake`), and its maps written as one set of files — the tangent-space normal
//! map (8 or 16 bits, green up or down, with its mip chain where asked), and where asked the
//! object-space normals, HIGH's ambient occlusion, a mask of the texels whose rays met HIGH,
//! and LOW itself as a GLB with the tangents the map was baked for and the map as its
//! `normalTexture`.
//!
//! LOW is baked as drawn: its file's tangents where it has them (what a renderer reading the
//! file uses), else tangents made in [`BakeRequest::tangents`]' mode; either way the normals and
//! tangents as a glTF file stores them (unit length, tangents perpendicular to the normals), so
//! the GLB written beside the map decodes it exactly.
//!
//! What this module does not do: cast the rays (`bumpmap_bake`), or say anything (progress goes
//! to a function, notes come back as data).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use bumpmap_io::atomic::FileSet;
use bumpmap_io::height_file::HeightBits;
use bumpmap_io::image_file::{PngLayout, save_png_into};
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_io::{IoError, LoadedMesh};
use bumpmap_math::mesh::{Mesh, MeshError};
use bumpmap_math::normalmap::encode_unit;
use bumpmap_math::tangent::{TangentMode, TangentOptions, generate_tangents};
use bumpmap_math::{Encoding, MipChain, MipMode, Texel, YConvention};
use glam::Vec3;

pub use bumpmap_bake::{
    BakeError, BakeOptions, Baked, MAX_OCCLUSION_RAYS, MAX_SAMPLES, MAX_SIDE, RayMode, TangentDecode, bake,
    bake_with_cage, encode_in_frame,
};

use crate::maps::{Chain, SaveError};

/// Occlusion rays a sample casts for an occlusion map when the request names none.
pub const DEFAULT_OCCLUSION_RAYS: u32 = 64;

/// What a bake from files is asked for, besides its files.
#[derive(Clone, Debug, PartialEq)]
pub struct BakeRequest {
    /// The bake itself: size, samples, rays, distances, padding, decode.
    pub options: BakeOptions,
    /// How LOW's tangents are made when its file has none.
    pub tangents: TangentMode,
    /// Which way green points in the normal map's file.
    pub y_convention: YConvention,
    /// Bits a channel of the normal map: 8 or 16.
    pub bits: u8,
    /// Write the normal map's whole mip chain (the length of the averaged normal in alpha).
    pub mips: bool,
    /// A cage: LOW's mesh with its vertices moved (outward, usually), where the rays start.
    pub cage: Option<PathBuf>,
}

impl Default for BakeRequest {
    /// The bake's defaults; MikkTSpace tangents; green up (glTF, Blender); 8 bits; level 0.
    fn default() -> Self {
        BakeRequest {
            options: BakeOptions::default(),
            tangents: TangentMode::MikkTSpace,
            y_convention: YConvention::YUp,
            bits: 8,
            mips: false,
            cage: None,
        }
    }
}

/// Where a bake's maps go; all but the normal map optional.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BakeOutputs {
    /// The tangent-space normal map: PNG (`.mipN.png` beside it with mips), `.dds` or `.ktx2`.
    pub normal_map: PathBuf,
    /// The object-space normal map (8-bit RGB PNG, `(x, y, z)` range-compressed).
    pub object_space: Option<PathBuf>,
    /// The texels whose rays met HIGH (8-bit gray PNG: 255 hit, 0 missed or outside LOW's UVs).
    pub mask: Option<PathBuf>,
    /// HIGH's ambient occlusion (8-bit gray PNG, or 16-bit with 16 bits: 1 unoccluded), with
    /// the request's occlusion rays ([`DEFAULT_OCCLUSION_RAYS`] where it asks for none).
    pub occlusion: Option<PathBuf>,
    /// The displacement: the signed distance from LOW to HIGH along each texel's ray, outward
    /// positive, as a 16-bit gray image (PNG, DDS or KTX2) mapped from its range, which is
    /// written beside it as `STEM.range.json` (`{"min": …, "max": …}` in the meshes' units).
    pub displacement: Option<PathBuf>,
    /// LOW as baked for: a `.glb` or `.gltf` with its tangents and the map as its normalTexture.
    pub low: Option<PathBuf>,
}

/// Why a bake from files made nothing (nothing was written).
#[derive(Debug, thiserror::Error)]
pub enum BakeFileError {
    /// A mesh file could not be read, or an output written.
    #[error(transparent)]
    Io(#[from] IoError),
    /// LOW's tangents could not be made.
    #[error("{}: its tangents: {source}", path.display())]
    Tangents {
        /// LOW's file.
        path: PathBuf,
        /// Why.
        source: MeshError,
    },
    /// The bake refused.
    #[error(transparent)]
    Bake(#[from] BakeError),
    /// The normal map could not be written.
    #[error(transparent)]
    Save(#[from] SaveError),
    /// Bits other than 8 or 16.
    #[error("bits must be 8 or 16, got {0}")]
    Bits(u8),
    /// The GLB's normalTexture must be a PNG, green up as glTF has it.
    #[error("{}: LOW's glTF carries its normal map as a green-up PNG: write the map as .png with y-convention opengl", path.display())]
    LowNeedsPng {
        /// The GLB asked for.
        path: PathBuf,
    },
    /// A cage that is not LOW with its vertices moved.
    #[error("{}: {reason}", path.display())]
    Cage {
        /// The cage's file.
        path: PathBuf,
        /// How it differs from LOW.
        reason: String,
    },
    /// An output that is also an input or another output.
    #[error("{}: {what}", path.display())]
    Clash {
        /// The file.
        path: PathBuf,
        /// Which files it would be.
        what: &'static str,
    },
}

/// LOW as the renderer will draw it from `loaded` (read from `path`): normals computed where the
/// file has none, the file's tangents or ones made in `mode`, both as glTF stores them.
pub fn low_as_drawn(loaded: LoadedMesh, path: &Path, mode: TangentMode) -> Result<Mesh, BakeFileError> {
    let mut mesh = loaded.mesh;
    if mesh.texcoords.len() != mesh.positions.len() {
        return Err(BakeError::NoTexcoords.into());
    }
    if !loaded.had_tangents {
        let options = TangentOptions { mode, ..Default::default() };
        mesh = generate_tangents(&mesh, &options)
            .map_err(|source| BakeFileError::Tangents { path: path.to_path_buf(), source })?
            .0;
    }
    let (normals, tangents, _) = bumpmap_io::mesh_file::gltf_normals_and_tangents(&mesh);
    mesh.normals = normals;
    mesh.tangents = tangents;
    Ok(mesh)
}

/// A cage's point for each of LOW's positions (LOW as its file has it, before tangents split
/// any vertex).
struct CagePoints(HashMap<[u32; 3], Vec3>);

impl CagePoints {
    /// The cage's point of each vertex of `drawn` (LOW with its vertices split, each a copy of
    /// one of the file's).
    fn points_for(&self, drawn: &Mesh) -> Vec<Vec3> {
        drawn.positions.iter().map(|p| self.0.get(&key(*p)).copied().unwrap_or(*p)).collect()
    }
}

fn key(p: Vec3) -> [u32; 3] {
    p.to_array().map(f32::to_bits)
}

/// Checks that `cage` (read from `path`) is `low` with its vertices moved — as many, the same
/// triangles — and pairs each of LOW's positions with the cage's.
fn cage_positions(low: &Mesh, cage: &Mesh, path: &Path) -> Result<CagePoints, BakeFileError> {
    let refuse = |reason: String| BakeFileError::Cage { path: path.to_path_buf(), reason };
    if cage.positions.len() != low.positions.len() || cage.indices.len() != low.indices.len() {
        return Err(refuse(format!(
            "{} vertices and {} triangles, where the low-poly mesh has {} and {}: a cage is the low-poly mesh with its vertices moved",
            cage.positions.len(),
            cage.indices.len(),
            low.positions.len(),
            low.indices.len()
        )));
    }
    if let Some(t) = cage.indices.iter().zip(&low.indices).position(|(a, b)| a != b) {
        return Err(refuse(format!("its triangle {t} joins other vertices than the low-poly mesh's")));
    }
    Ok(CagePoints(low.positions.iter().zip(&cage.positions).map(|(p, c)| (key(*p), *c)).collect()))
}

/// A bake from files, before anything is written.
#[derive(Debug)]
pub struct FromFiles {
    /// The bake, texel by texel.
    pub baked: Baked,
    /// LOW as drawn: the normals and tangents the map was made for.
    pub low: Mesh,
    /// How much the bake covered.
    pub counts: BakeCounts,
    /// Every file read (the meshes and their buffers).
    pub sources: Vec<PathBuf>,
}

/// Reads `high`, `low` and the request's cage and bakes as `request` says (its occlusion rays
/// as given: 0, none), telling `progress(rows done, rows)`; writes nothing.
pub fn bake_from_files(
    high: &Path,
    low: &Path,
    request: &BakeRequest,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<FromFiles, BakeFileError> {
    let high_mesh = bumpmap_io::load_mesh(high)?;
    let low_loaded = bumpmap_io::load_mesh(low)?;
    let cage_loaded = request.cage.as_deref().map(bumpmap_io::load_mesh).transpose()?;
    let mut sources: Vec<PathBuf> = high_mesh.sources.clone();
    sources.extend(low_loaded.sources.iter().cloned());
    sources.extend(cage_loaded.iter().flat_map(|c| c.sources.iter().cloned()));
    let cage_of_low = match (&cage_loaded, &request.cage) {
        (Some(cage), Some(path)) => Some(cage_positions(&low_loaded.mesh, &cage.mesh, path)?),
        _ => None,
    };
    let low_mesh = low_as_drawn(low_loaded, low, request.tangents)?;
    let options = &request.options;
    let baked = match &cage_of_low {
        Some(cage) => bake_with_cage(&high_mesh.mesh, &low_mesh, &cage.points_for(&low_mesh), options, progress)?,
        None => bake(&high_mesh.mesh, &low_mesh, options, progress)?,
    };
    let counts = BakeCounts {
        covered: baked.covered.iter().filter(|c| **c).count(),
        hit: baked.hit.iter().filter(|h| **h).count(),
        high_triangles: high_mesh.mesh.triangle_count(),
        low_triangles: low_mesh.triangle_count(),
    };
    Ok(FromFiles { baked, low: low_mesh, counts, sources })
}

/// What [`bake_files`] did.
#[derive(Debug)]
pub struct BakedFiles {
    /// Every file written.
    pub files: Vec<PathBuf>,
    /// The bake, texel by texel.
    pub baked: Baked,
    /// LOW's texels covered and hit, and LOW's triangles and HIGH's, for a summary.
    pub counts: BakeCounts,
}

/// How much a bake covered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BakeCounts {
    /// Texels of LOW's UV layout.
    pub covered: usize,
    /// Of those, the texels whose rays met HIGH.
    pub hit: usize,
    /// HIGH's triangles.
    pub high_triangles: usize,
    /// LOW's triangles.
    pub low_triangles: usize,
}

/// Reads `high` and `low`, bakes as `request` says, and writes `outputs` all or none, telling
/// `progress(rows done, rows)`.
pub fn bake_files(
    high: &Path,
    low: &Path,
    request: &BakeRequest,
    outputs: &BakeOutputs,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<BakedFiles, BakeFileError> {
    if !matches!(request.bits, 8 | 16) {
        return Err(BakeFileError::Bits(request.bits));
    }
    let format = if request.bits == 16 { TextureFormat::Rgba16 } else { TextureFormat::Rgba8 };
    crate::maps::check_container(&outputs.normal_map, format)?;
    let png = outputs.normal_map.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if let Some(glb) = &outputs.low
        && (!png || request.y_convention != YConvention::YUp)
    {
        return Err(BakeFileError::LowNeedsPng { path: glb.clone() });
    }
    let range = outputs.displacement.as_deref().map(range_file);
    let named: Vec<(&Path, &'static str)> = std::iter::once((outputs.normal_map.as_path(), "the normal map"))
        .chain(range.as_deref().map(|p| (p, "the displacement's range")))
        .chain(outputs.object_space.as_deref().map(|p| (p, "the object-space map")))
        .chain(outputs.mask.as_deref().map(|p| (p, "the mask")))
        .chain(outputs.occlusion.as_deref().map(|p| (p, "the occlusion")))
        .chain(outputs.displacement.as_deref().map(|p| (p, "the displacement")))
        .chain(outputs.low.as_deref().map(|p| (p, "LOW's glTF")))
        .collect();
    for (k, (path, _)) in named.iter().enumerate() {
        if named[..k].iter().any(|(other, _)| other == path) {
            return Err(BakeFileError::Clash { path: path.to_path_buf(), what: "two outputs of the bake" });
        }
    }
    let mut request = request.clone();
    request.options.occlusion_rays = match (&outputs.occlusion, request.options.occlusion_rays) {
        (None, _) => 0,
        (Some(_), 0) => DEFAULT_OCCLUSION_RAYS,
        (Some(_), n) => n,
    };
    let request = &request;
    let FromFiles { baked, low: low_mesh, counts, sources: inputs } = bake_from_files(high, low, request, progress)?;
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    let mut set = FileSet::new(&inputs);
    let chain = tangent_chain(&baked, request)?;
    crate::maps::write_chain_into(&mut set, &outputs.normal_map, &chain, format)?;
    let (w, h) = (baked.width, baked.height);
    if let Some(path) = &outputs.object_space {
        let rgb: Vec<u8> =
            baked.object.iter().flat_map(|n| [n.x, n.y, n.z].map(|c| Encoding::Unorm.encode(c))).collect();
        save_png_into(&mut set, path, w, h, PngLayout::Rgb8, &rgb)?;
    }
    if let Some(path) = &outputs.mask {
        let gray: Vec<u8> = baked.hit.iter().map(|&h| if h { 255 } else { 0 }).collect();
        save_png_into(&mut set, path, w, h, PngLayout::Gray8, &gray)?;
    }
    if let Some(path) = &outputs.occlusion {
        let bits = if request.bits == 16 { HeightBits::Sixteen } else { HeightBits::Eight };
        bumpmap_io::horizon_file::write_gray_into(&mut set, path, (w, h), &baked.occlusion, bits)?;
    }
    if let Some(path) = &outputs.displacement {
        let (lo, hi) = displacement_range(&baked);
        let span = (hi - lo).max(f32::MIN_POSITIVE);
        let unit: Vec<f32> = baked.displacement.iter().map(|d| (d - lo) / span).collect();
        bumpmap_io::horizon_file::write_gray_into(&mut set, path, (w, h), &unit, HeightBits::Sixteen)?;
        let json = format!(
            "{{\"min\": {lo}, \"max\": {hi}, \"meaning\": \"signed distance from the low-poly surface to the high-poly one along each texel's ray, outward positive, in the meshes' units: 0 in the image is min, 65535 is max\"}}\n"
        );
        set.write(&range_file(path), |w| {
            use std::io::Write;
            w.write_all(json.as_bytes())
        })?;
    }
    if let Some(path) = &outputs.low {
        // The map's level 0 as the PNG the GLB carries: 8 bits, green up as glTF has it.
        let texels: Vec<[u8; 4]> =
            baked.tangent.iter().map(|n| encode_unit(Vec3::new(n.x, -n.y, n.z), Encoding::Unorm)).collect();
        let png = bumpmap_io::image_file::png_bytes(w, h, PngLayout::Rgba8, texels.as_flattened())?;
        bumpmap_io::mesh_file::save_gltf_into(&mut set, path, &low_mesh, Some(&png))?;
    }
    let files = set.commit()?;
    Ok(BakedFiles { files, baked, counts })
}

/// Where the displacement's range goes beside `displacement`: `STEM.range.json`.
pub fn range_file(displacement: &Path) -> PathBuf {
    let stem = displacement.file_stem().unwrap_or_default().to_string_lossy();
    displacement.with_file_name(format!("{stem}.range.json"))
}

/// The lowest and highest displacement of the texels a ray hit (0 and 0 where none did).
pub fn displacement_range(baked: &Baked) -> (f32, f32) {
    let hit = baked.displacement.iter().zip(&baked.hit).filter(|(_, h)| **h).map(|(d, _)| *d);
    let (lo, hi) = hit.fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), d| (l.min(d), h.max(d)));
    if lo <= hi { (lo, hi) } else { (0.0, 0.0) }
}

/// The tangent-space normals as the normal map's chain: level 0, or every level, at the bits
/// and Y convention asked for.
pub fn tangent_chain(baked: &Baked, request: &BakeRequest) -> Result<Chain, BakeFileError> {
    let flip = if request.y_convention == YConvention::TEXTURE_SPACE { 1.0 } else { -1.0 };
    let normals: Vec<Vec3> = baked.tangent.iter().map(|n| Vec3::new(n.x, flip * n.y, n.z)).collect();
    fn chain<T: Texel>(normals: &[Vec3], w: usize, h: usize, mips: bool) -> Result<MipChain<T>, BakeError> {
        Ok(if mips {
            MipChain::try_from_normals(w, h, normals, Encoding::Unorm, MipMode::LengthInAlpha)?
        } else {
            let texels = normals.iter().map(|&n| encode_unit::<T>(n, Encoding::Unorm)).collect();
            MipChain { levels: vec![bumpmap_math::Image::new(w, h, texels)], encoding: Encoding::Unorm }
        })
    }
    let (w, h) = (baked.width, baked.height);
    Ok(match request.bits {
        16 => Chain::Rgba16(chain(&normals, w, h, request.mips)?),
        8 => Chain::Rgba8(chain(&normals, w, h, request.mips)?),
        other => return Err(BakeFileError::Bits(other)),
    })
}
