//! Baking from files, as `bumpmap bake HIGH LOW -o OUT` does it: both meshes read (OBJ, glTF
//! or GLB, every node with its transform), LOW made ready as the renderer will draw it, the
//! bake (`bumpmap_bake`), and its maps written as one set of files — the tangent-space normal
//! map (8 or 16 bits, green up or down, with its mip chain where asked), and where asked the
//! object-space normals, HIGH's ambient occlusion and curvature, the displacement, a mask of
//! the texels whose rays met HIGH, and LOW itself as a GLB with the tangents the map was baked for and the map as its
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

use bumpmap_io::{IoError, LoadedMesh};
use bumpmap_math::YConvention;
use bumpmap_math::mesh::{Mesh, MeshError};
use bumpmap_math::tangent::{TangentMode, TangentOptions, generate_tangents};
use glam::Vec3;

pub use bumpmap_bake::{
    BakeError, BakeOptions, Baked, MAX_OCCLUSION_RAYS, MAX_SAMPLES, MAX_SIDE, Pairing, RayMode, TangentDecode, bake,
    bake_paired, bake_with_cage, encode_in_frame,
};

use crate::maps::SaveError;

mod write;

pub use write::{
    BakeMap, BakeOutputs, BakedFiles, bake_files, curvature_range, displacement_range, range_file, tangent_chain,
};

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
    /// Pair LOW's parts with HIGH's by name ([`part_key`]): each part's rays meet only its own.
    pub match_names: bool,
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
            match_names: false,
        }
    }
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
    /// Parts of LOW that no part of HIGH is named as, with `match_names`.
    #[error(
        "{}: its parts {} have no part of the same name in the high-poly mesh, whose parts are {} (names are compared without case and without a suffix _low, _high, _lo, _hi, _lp or _hp)",
        low.display(),
        quoted(unmatched),
        quoted(high_parts)
    )]
    Unmatched {
        /// LOW's file.
        low: PathBuf,
        /// Its parts without a match.
        unmatched: Vec<String>,
        /// HIGH's parts.
        high_parts: Vec<String>,
    },
    /// A mesh without named parts, with `match_names`.
    #[error("{}: pairing parts by name needs named parts (glTF nodes, OBJ objects or groups), and this mesh has none", path.display())]
    Unnamed {
        /// The mesh's file (or its stand-in).
        path: PathBuf,
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
    bake_from_meshes(high_mesh, (low_loaded, low), request, progress)
}

/// [`bake_from_files`] from meshes already read (or made: their normals are computed where
/// they have none, as a file's are), `low` with the name its errors give it; the request's
/// cage is still a file.
pub fn bake_from_meshes(
    high: LoadedMesh,
    (low, low_name): (LoadedMesh, &Path),
    request: &BakeRequest,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<FromFiles, BakeFileError> {
    let (mut high_mesh, mut low_loaded) = (high, low);
    for (mesh, which) in [(&mut high_mesh.mesh, "high-poly"), (&mut low_loaded.mesh, "low-poly")] {
        mesh.validate().map_err(|source| BakeError::Mesh { which, source })?;
        if mesh.normals.len() != mesh.positions.len() {
            mesh.compute_normals();
        }
    }
    let cage_loaded = request.cage.as_deref().map(bumpmap_io::load_mesh).transpose()?;
    let mut sources: Vec<PathBuf> = high_mesh.sources.clone();
    sources.extend(low_loaded.sources.iter().cloned());
    sources.extend(cage_loaded.iter().flat_map(|c| c.sources.iter().cloned()));
    let cage_of_low = match (&cage_loaded, &request.cage) {
        (Some(cage), Some(path)) => Some(cage_positions(&low_loaded.mesh, &cage.mesh, path)?),
        _ => None,
    };
    let pairing = match request.match_names {
        true => Some(pair_by_name(&high_mesh, &low_loaded, low_name)?),
        false => None,
    };
    let low_mesh = low_as_drawn(low_loaded, low_name, request.tangents)?;
    let options = &request.options;
    let cage = cage_of_low.as_ref().map(|c| c.points_for(&low_mesh));
    let baked = match (&pairing, &cage) {
        (Some(pairing), cage) => bake_paired(&high_mesh.mesh, &low_mesh, cage.as_deref(), pairing, options, progress)?,
        (None, Some(cage)) => bake_with_cage(&high_mesh.mesh, &low_mesh, cage, options, progress)?,
        (None, None) => bake(&high_mesh.mesh, &low_mesh, options, progress)?,
    };
    let counts = BakeCounts {
        covered: baked.covered.iter().filter(|c| **c).count(),
        hit: baked.hit.iter().filter(|h| **h).count(),
        high_triangles: high_mesh.mesh.triangle_count(),
        low_triangles: low_mesh.triangle_count(),
    };
    Ok(FromFiles { baked, low: low_mesh, counts, sources })
}

/// A part's name as pairing compares it: lower case, without a last suffix `_low`, `_high`,
/// `_lo`, `_hi`, `_lp` or `_hp` (`.` or `-` before it as well as `_`), as Substance's and
/// Marmoset's bakers pair `Bolt_low` with `bolt_high`.
///
/// ```
/// use bumpmap::bake::part_key;
/// assert_eq!(part_key("Bolt_low"), part_key("bolt_HIGH"));
/// assert_eq!(part_key("wheel.hp"), "wheel");
/// assert_ne!(part_key("Bolt_low"), part_key("Nut_high"));
/// ```
pub fn part_key(name: &str) -> String {
    let lower = name.trim().to_lowercase();
    for suffix in ["low", "high", "lo", "hi", "lp", "hp"] {
        if let Some(stem) = lower.strip_suffix(suffix)
            && let Some(stem) = stem.strip_suffix(['_', '.', '-'])
            && !stem.is_empty()
        {
            return stem.to_string();
        }
    }
    lower
}

/// HIGH's parts grouped by [`part_key`], and each of LOW's triangles' group; every LOW part
/// must have one.
fn pair_by_name(high: &LoadedMesh, low: &LoadedMesh, low_name: &Path) -> Result<Pairing, BakeFileError> {
    for (mesh, path) in [(high, high.sources.first().map(PathBuf::as_path)), (low, Some(low_name))] {
        if mesh.objects.is_empty() {
            return Err(BakeFileError::Unnamed { path: path.unwrap_or(Path::new("<high Mesh>")).to_path_buf() });
        }
    }
    let mut keys: Vec<String> = Vec::new();
    let mut pairing = Pairing { high: Vec::new(), low: vec![0; low.mesh.indices.len()] };
    for (name, triangles) in &high.objects {
        let key = part_key(name);
        let group = keys.iter().position(|k| *k == key).unwrap_or_else(|| {
            keys.push(key);
            pairing.high.push(Vec::new());
            keys.len() - 1
        });
        pairing.high[group].extend(triangles.clone().map(|t| t as u32));
    }
    let mut unmatched = Vec::new();
    for (name, triangles) in &low.objects {
        match keys.iter().position(|k| *k == part_key(name)) {
            Some(group) if !pairing.high[group].is_empty() => {
                pairing.low[triangles.clone()].fill(group as u32);
            }
            _ if triangles.is_empty() => {}
            _ => unmatched.push(name.clone()),
        }
    }
    if !unmatched.is_empty() {
        let high_parts = high.objects.iter().map(|(n, _)| n.clone()).collect();
        return Err(BakeFileError::Unmatched { low: low_name.to_path_buf(), unmatched, high_parts });
    }
    Ok(pairing)
}

/// Names in quotes, joined by commas.
fn quoted(names: &[String]) -> String {
    names.iter().map(|n| format!("'{n}'")).collect::<Vec<_>>().join(", ")
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
