//! The bake itself: options, what comes out, and the rays cast from every texel of LOW's UV
//! layout into HIGH (the crate's page says how a texel is baked).

use bumpmap_math::buffer::OutOfMemory;
use bumpmap_math::mesh::{Mesh, MeshError};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::encode::TangentDecode;
use crate::frame::{Frame, averaged_normals, cage_ray};
use crate::high::{BYTES_PER_TRIANGLE, HighPoly};
use crate::pad::pad;
use crate::texels::{Layout, sample_offset};

/// The most texels a side.
pub const MAX_SIDE: usize = 16384;

/// The most samples a texel.
pub const MAX_SAMPLES: u32 = 64;

/// The most occlusion rays a sample.
pub const MAX_OCCLUSION_RAYS: u32 = 4096;

/// Which way a texel's ray goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RayMode {
    /// Along LOW's averaged normal: the normals of every vertex at one position averaged, so
    /// the two sides of a hard edge cast the same rays and no gap or overlap opens there (a
    /// smooth cage, xNormal's and Marmoset's default).
    #[default]
    Averaged,
    /// Along LOW's own vertex normals, split at hard edges: a seam opens along every hard edge.
    Explicit,
}

bumpmap_math::named!(RayMode {
    Averaged => "averaged": "Along LOW's averaged normals: a smooth cage, no seam at hard edges (xNormal's and Marmoset's default)",
    Explicit => "explicit": "Along LOW's own normals, split at hard edges: each face projects straight, and a seam opens along each hard edge",
});

/// How a bake is made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BakeOptions {
    /// Texels across.
    pub width: usize,
    /// Texels down.
    pub height: usize,
    /// Samples a texel, stratified (1: the texel's centre).
    pub samples: u32,
    /// Which way the rays go.
    pub rays: RayMode,
    /// How far in front of LOW the rays start (the cage's distance); `None`: 5 % of LOW's
    /// bounding box diagonal.
    pub front: Option<f32>,
    /// How far behind LOW they still look; `None`: as far as [`Self::front`].
    pub back: Option<f32>,
    /// Texels filled beyond each UV island's edge.
    pub padding: u32,
    /// The decode the tangent-space normals are made for.
    pub decode: TangentDecode,
    /// Rays a sample casts for ambient occlusion (0: none is baked).
    pub occlusion_rays: u32,
    /// Bake HIGH's curvature too (it costs a pass over HIGH before the rays).
    pub curvature: bool,
}

impl Default for BakeOptions {
    /// 1024², 4 samples a texel, averaged rays, 5 % of the diagonal in front and behind,
    /// 16 texels of padding, MikkTSpace's decode.
    fn default() -> Self {
        BakeOptions {
            width: 1024,
            height: 1024,
            samples: 4,
            rays: RayMode::Averaged,
            front: None,
            back: None,
            padding: 16,
            decode: TangentDecode::MikkTSpace,
            occlusion_rays: 0,
            curvature: false,
        }
    }
}

/// Which of HIGH's triangles each of LOW's rays may meet, for a bake of parts paired by name
/// (an *exploded* bake without moving the parts apart): groups of HIGH's triangles, and each of
/// LOW's triangles' group.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Pairing {
    /// Each group's triangles of HIGH (indices into its triangles; none empty).
    pub high: Vec<Vec<u32>>,
    /// Each of LOW's triangles' group (an index into [`Pairing::high`]).
    pub low: Vec<u32>,
}

/// Why nothing was baked.
#[derive(Debug, thiserror::Error)]
pub enum BakeError {
    /// LOW has no texture coordinates to bake into.
    #[error("the low-poly mesh has no texture coordinates: there is no layout to bake into")]
    NoTexcoords,
    /// LOW has no tangents (make them in the mode the renderer will use first).
    #[error("the low-poly mesh has no tangents")]
    NoTangents,
    /// A mesh that cannot be used.
    #[error("the {which} mesh: {source}")]
    Mesh {
        /// `high-poly` or `low-poly`.
        which: &'static str,
        /// Why.
        source: MeshError,
    },
    /// A size out of range.
    #[error("a bake of {width}x{height} texels: each side must be 1 to {MAX_SIDE}")]
    Size {
        /// Asked width.
        width: usize,
        /// Asked height.
        height: usize,
    },
    /// Samples out of range.
    #[error("{0} samples a texel: 1 to {MAX_SAMPLES}")]
    Samples(u32),
    /// A cage with another number of points than LOW has vertices.
    #[error("the cage has {cage} points for the low-poly mesh's {low} vertices: a cage is LOW with its vertices moved")]
    CageSize {
        /// The cage's points.
        cage: usize,
        /// LOW's vertices.
        low: usize,
    },
    /// A cage point that is NaN or infinite.
    #[error("the cage's point {0} is not finite")]
    CageNotFinite(usize),
    /// Occlusion rays out of range.
    #[error("{0} occlusion rays a sample: 0 to {MAX_OCCLUSION_RAYS}")]
    OcclusionRays(u32),
    /// A ray distance that is negative or not finite.
    #[error("ray distances must be finite and not negative, got {front} in front and {back} behind")]
    Distance {
        /// In front.
        front: f32,
        /// Behind.
        back: f32,
    },
    /// No texel of the layout lies in a triangle (UVs all outside [0, 1], or degenerate).
    #[error("no texel of the {width}x{height} bake lies inside the low-poly mesh's UV layout")]
    NothingCovered {
        /// The bake's width.
        width: usize,
        /// The bake's height.
        height: usize,
    },
    /// Most rays met nothing: the meshes do not overlap, or the distances are too short.
    #[error(
        "{missed} of {covered} texels' rays met the high-poly mesh nowhere within {front} in front and {back} behind: the meshes do not overlap there, or the distances are too short"
    )]
    MostMissed {
        /// Texels whose rays all missed.
        missed: usize,
        /// Texels of the layout.
        covered: usize,
        /// The distance in front used.
        front: f32,
        /// The distance behind used.
        back: f32,
    },
    /// A pairing that does not fit the meshes.
    #[error("a pairing of parts: {0}")]
    Pairing(String),
    /// The bake would not fit in memory.
    #[error(transparent)]
    OutOfMemory(#[from] OutOfMemory),
}

/// What a bake gives, texel by texel (row-major, row 0 at `t = 0`).
#[derive(Clone, Debug)]
pub struct Baked {
    /// Texels across.
    pub width: usize,
    /// Texels down.
    pub height: usize,
    /// Unit normals in LOW's tangent frame, `y` along B (the renderer's texture space: toward
    /// increasing `t`); `(0, 0, 1)` where nothing was hit and nothing padded.
    pub tangent: Vec<Vec3>,
    /// Unit normals in LOW's object space (`(0, 0, 0)` where nothing was hit or padded).
    pub object: Vec<Vec3>,
    /// Signed distance from LOW to HIGH along the ray, outward positive.
    pub displacement: Vec<f32>,
    /// HIGH's mean curvature at the hit, in 1 / the meshes' units: positive where it is convex,
    /// negative in creases, 0 where flat (and where nothing was hit or padded); empty unless
    /// asked for.
    pub curvature: Vec<f32>,
    /// HIGH's ambient occlusion at the hit: the cosine-weighted share of the hemisphere around
    /// HIGH's normal there that HIGH leaves open, 1 unoccluded (empty unless asked for). Around
    /// HIGH's own normal, so a convex HIGH reads 1 everywhere whichever way the rays came.
    pub occlusion: Vec<f32>,
    /// Texels of LOW's layout whose rays met HIGH.
    pub hit: Vec<bool>,
    /// Texels of LOW's layout (some sample inside a triangle).
    pub covered: Vec<bool>,
    /// Texels that hold a value: hit, or padded from their neighbours.
    pub filled: Vec<bool>,
    /// The ray distances used, in front and behind.
    pub distances: (f32, f32),
}

/// Bakes `high` onto `low`'s UV layout (`low` carrying the normals and tangents the renderer
/// will draw it with), telling `progress(rows done, rows)` as rows finish (from any thread).
pub fn bake(
    high: &Mesh,
    low: &Mesh,
    options: &BakeOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Baked, BakeError> {
    bake_from(high, low, None, None, options, progress)
}

/// [`bake`] (or [`bake_with_cage`], with `cage`) where each of LOW's triangles' rays meet only
/// the triangles of HIGH that `pairing` gives it; the occlusion, too, sees only those.
pub fn bake_paired(
    high: &Mesh,
    low: &Mesh,
    cage: Option<&[Vec3]>,
    pairing: &Pairing,
    options: &BakeOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Baked, BakeError> {
    if let Some(cage) = cage {
        check_cage(cage, low)?;
    }
    let refuse = |why: String| Err(BakeError::Pairing(why));
    if pairing.low.len() != low.indices.len() {
        return refuse(format!("{} groups for the low-poly mesh's {} triangles", pairing.low.len(), low.indices.len()));
    }
    if let Some(g) = pairing.low.iter().find(|&&g| g as usize >= pairing.high.len()) {
        return refuse(format!("group {g} of {}", pairing.high.len()));
    }
    if let Some(g) = pairing.high.iter().position(Vec::is_empty) {
        return refuse(format!("group {g} has no triangle of the high-poly mesh"));
    }
    if let Some(t) = pairing.high.iter().flatten().find(|&&t| t as usize >= high.indices.len()) {
        return refuse(format!("triangle {t} of the high-poly mesh's {}", high.indices.len()));
    }
    bake_from(high, low, cage, Some(pairing), options, progress)
}

/// [`bake`] with each ray starting on a cage: `cage` holds, for each of LOW's vertices, where
/// the cage has it (LOW's own point pushed outward, usually; where the two are one point the ray
/// starts on LOW along the averaged or explicit direction). A ray goes from the cage's point
/// through LOW's, as far as [`BakeOptions::back`] beyond it; [`BakeOptions::front`] is not used.
pub fn bake_with_cage(
    high: &Mesh,
    low: &Mesh,
    cage: &[Vec3],
    options: &BakeOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Baked, BakeError> {
    check_cage(cage, low)?;
    bake_from(high, low, Some(cage), None, options, progress)
}

/// A cage of LOW's vertices, all finite.
fn check_cage(cage: &[Vec3], low: &Mesh) -> Result<(), BakeError> {
    if cage.len() != low.positions.len() {
        return Err(BakeError::CageSize { cage: cage.len(), low: low.positions.len() });
    }
    if let Some(i) = cage.iter().position(|p| !p.is_finite()) {
        return Err(BakeError::CageNotFinite(i));
    }
    Ok(())
}

fn bake_from(
    high: &Mesh,
    low: &Mesh,
    cage: Option<&[Vec3]>,
    pairing: Option<&Pairing>,
    options: &BakeOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Baked, BakeError> {
    let (width, height) = (options.width, options.height);
    if !(1..=MAX_SIDE).contains(&width) || !(1..=MAX_SIDE).contains(&height) {
        return Err(BakeError::Size { width, height });
    }
    if !(1..=MAX_SAMPLES).contains(&options.samples) {
        return Err(BakeError::Samples(options.samples));
    }
    if options.occlusion_rays > MAX_OCCLUSION_RAYS {
        return Err(BakeError::OcclusionRays(options.occlusion_rays));
    }
    low.validate().map_err(|source| BakeError::Mesh { which: "low-poly", source })?;
    high.validate().map_err(|source| BakeError::Mesh { which: "high-poly", source })?;
    if low.texcoords.len() != low.positions.len() {
        return Err(BakeError::NoTexcoords);
    }
    if low.tangents.len() != low.positions.len() {
        return Err(BakeError::NoTangents);
    }
    let (front, back) = distances(low, options)?;
    // Texel outputs (normals twice, the distance, the curvature, three flags), LOW's layout
    // and HIGH's BVH, before any of it.
    let texels = (width * height) as u64;
    let occlusion_bytes = if options.occlusion_rays > 0 { 4 } else { 0 };
    let curvature_bytes = if options.curvature { 4 } else { 0 };
    let bytes = texels * (31 + occlusion_bytes + curvature_bytes)
        + Layout::max_bytes(width, height)
        + high.indices.len() as u64 * BYTES_PER_TRIANGLE;
    bumpmap_math::buffer::ensure_available(bytes, "the bake")?;

    let high_normals;
    let high = if high.normals.len() == high.positions.len() {
        high
    } else {
        let mut with = high.clone();
        with.compute_normals();
        high_normals = with;
        &high_normals
    };
    let rays = match options.rays {
        RayMode::Averaged => averaged_normals(low),
        RayMode::Explicit => low.normals.clone(),
    };
    let layout = Layout::new(low, width, height);
    let curvature = if options.curvature { high.mean_curvature() } else { Vec::new() };
    // One BVH over HIGH, or one a group of a pairing.
    let targets: Vec<HighPoly> = match pairing {
        None => vec![HighPoly::new(high, &curvature, None)],
        Some(p) => p.high.iter().map(|only| HighPoly::new(high, &curvature, Some(only))).collect(),
    };
    let target_of = |triangle: u32| &targets[pairing.map_or(0, |p| p.low[triangle as usize] as usize)];

    let mut baked = Baked {
        width,
        height,
        tangent: vec![Vec3::Z; width * height],
        object: vec![Vec3::ZERO; width * height],
        displacement: vec![0.0; width * height],
        curvature: if options.curvature { vec![0.0; width * height] } else { Vec::new() },
        occlusion: if options.occlusion_rays > 0 { vec![1.0; width * height] } else { Vec::new() },
        hit: vec![false; width * height],
        covered: vec![false; width * height],
        filled: Vec::new(),
        distances: (front, back),
    };
    let told = bumpmap_math::progress::Told::new(progress, height);
    let samples = options.samples as usize;
    let reach_out = 2.0 * (front + back) + bounds_diagonal(high);
    // Without occlusion or curvature each row gets an empty slice of it.
    let (mut occlusion_rows, mut curvature_rows) =
        (rows_of(&mut baked.occlusion, width, height), rows_of(&mut baked.curvature, width, height));
    baked
        .tangent
        .par_chunks_mut(width)
        .zip(baked.object.par_chunks_mut(width))
        .zip(baked.displacement.par_chunks_mut(width))
        .zip(curvature_rows.par_iter_mut())
        .zip(baked.hit.par_chunks_mut(width))
        .zip(baked.covered.par_chunks_mut(width))
        .zip(occlusion_rows.par_iter_mut())
        .enumerate()
        .for_each(|(y, ((((((tangent, object), displacement), curvature), hit), covered), occlusion))| {
            if told.stopped() {
                return;
            }
            for x in 0..width {
                let (mut sum_t, mut sum_o, mut sum_d, mut hits, mut inside) = (Vec3::ZERO, Vec3::ZERO, 0.0, 0, false);
                let mut sum_k = 0.0;
                let mut open = 0.0;
                for k in 0..samples {
                    let p = Vec2::new(x as f32, y as f32) + sample_offset(k, samples);
                    let Some(at) = layout.at(x, y, p) else { continue };
                    inside = true;
                    let target = target_of(at.triangle);
                    let mut frame = Frame::at(low, &rays, at, options.decode);
                    // From the cage's point where there is one, else `front` along the frame's.
                    let front = match cage.and_then(|cage| cage_ray(cage, low, at, frame.p)) {
                        Some((out, distance)) => {
                            frame.d = out;
                            distance
                        }
                        None => front,
                    };
                    let Some(found) = target.first_hit(frame.p + frame.d * front, -frame.d, front + back) else {
                        continue;
                    };
                    let encoded = frame.encode(found.normal);
                    if options.occlusion_rays > 0 {
                        let at = frame.p + frame.d * (front - found.t);
                        let seed = [x as u32, y as u32, k as u32];
                        open += open_share(target, at, found.normal, options.occlusion_rays, reach_out, seed);
                    }
                    sum_t += encoded;
                    sum_o += found.normal;
                    sum_d += front - found.t;
                    sum_k += found.curvature;
                    hits += 1;
                }
                covered[x] = inside;
                if hits > 0 {
                    tangent[x] = sum_t.normalize_or(Vec3::Z);
                    object[x] = sum_o.normalize_or(Vec3::Z);
                    displacement[x] = sum_d / hits as f32;
                    if let Some(k) = curvature.get_mut(x) {
                        *k = sum_k / hits as f32;
                    }
                    if let Some(o) = occlusion.get_mut(x) {
                        *o = open / hits as f32;
                    }
                    hit[x] = true;
                }
            }
            told.step();
        });
    told.finish();

    let covered = baked.covered.iter().filter(|c| **c).count();
    if covered == 0 {
        return Err(BakeError::NothingCovered { width, height });
    }
    let missed = baked.covered.iter().zip(&baked.hit).filter(|(c, h)| **c && !**h).count();
    if missed * 2 > covered {
        return Err(BakeError::MostMissed { missed, covered, front, back });
    }
    let unit_mean = |v: &[Vec3]| v.iter().sum::<Vec3>().normalize_or(Vec3::Z);
    let rings = options.padding;
    pad(&mut baked.tangent, &baked.hit, width, height, rings, unit_mean);
    pad(&mut baked.object, &baked.hit, width, height, rings, unit_mean);
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    baked.filled = pad(&mut baked.displacement, &baked.hit, width, height, rings, mean);
    if !baked.curvature.is_empty() {
        pad(&mut baked.curvature, &baked.hit, width, height, rings, mean);
    }
    if !baked.occlusion.is_empty() {
        pad(&mut baked.occlusion, &baked.hit, width, height, rings, mean);
    }
    Ok(baked)
}

/// `plane`'s rows of `width`, or `height` empty rows where it is empty (a map not asked for).
fn rows_of(plane: &mut [f32], width: usize, height: usize) -> Vec<&mut [f32]> {
    if plane.is_empty() {
        (0..height).map(|_| <&mut [f32]>::default()).collect()
    } else {
        plane.chunks_mut(width).collect()
    }
}

/// The diagonal of `mesh`'s bounding box.
fn bounds_diagonal(mesh: &Mesh) -> f32 {
    let (lo, hi) = mesh.positions.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(l, h), p| (l.min(*p), h.max(*p)));
    (hi - lo).length()
}

/// The cosine-weighted share of the hemisphere around `up` that HIGH leaves open from `at`:
/// `rays` directions of a stratified sequence (Roberts' R2, rotated per texel and sample by a
/// hash of `seed`) mapped onto the hemisphere by Malley's method, each tested out to `reach`.
fn open_share(high: &HighPoly, at: Vec3, up: Vec3, rays: u32, reach: f32, seed: [u32; 3]) -> f32 {
    use bumpmap_math::hash::{hash32, unit};
    const A1: f32 = 0.754_877_7;
    const A2: f32 = 0.569_840_3;
    let (r1, r2) = (unit(hash32(&[seed[0], seed[1], seed[2], 1])), unit(hash32(&[seed[0], seed[1], seed[2], 2])));
    let (tx, ty) = up.any_orthonormal_pair();
    // Off the surface by a hair of the reach, so a ray does not meet the triangle it leaves.
    let near = reach * 1e-5;
    let open = (0..rays)
        .filter(|&k| {
            let (u, v) = ((0.5 + A1 * k as f32 + r1).fract(), (0.5 + A2 * k as f32 + r2).fract());
            let (r, phi) = (u.sqrt(), std::f32::consts::TAU * v);
            let dir = tx * (r * phi.cos()) + ty * (r * phi.sin()) + up * (1.0 - u).max(0.0).sqrt();
            !high.blocked(at, dir, near, reach)
        })
        .count();
    open as f32 / rays as f32
}

/// The ray distances in front and behind: as given, or 5 % of LOW's bounding box diagonal.
fn distances(low: &Mesh, options: &BakeOptions) -> Result<(f32, f32), BakeError> {
    let auto = 0.05 * bounds_diagonal(low);
    let front = options.front.unwrap_or(auto);
    let back = options.back.unwrap_or(front);
    if !(front.is_finite() && back.is_finite() && front >= 0.0 && back >= 0.0) || front + back == 0.0 {
        return Err(BakeError::Distance { front, back });
    }
    Ok((front, back))
}
