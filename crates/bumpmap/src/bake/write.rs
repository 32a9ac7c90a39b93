//! A bake's files: the maps of [`BakeOutputs`] written as one set, all or none, and the forms
//! they take (the normal map's chain, the 16-bit images mapped from a range written beside
//! them).
//!
//! What this module does not do: read the meshes or bake (the module above).

use std::path::{Path, PathBuf};

use bumpmap_io::IoError;
use bumpmap_io::atomic::FileSet;
use bumpmap_io::gray_file::{GrayFormat, save_gray_into};
use bumpmap_io::height_file::HeightBits;
use bumpmap_io::image_file::{PngLayout, save_png_into};
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_math::normalmap::encode_unit;
use bumpmap_math::{Encoding, MipChain, MipMode, Texel, YConvention};
use glam::Vec3;

use super::{
    BakeCounts, BakeError, BakeFileError, BakeRequest, Baked, DEFAULT_OCCLUSION_RAYS, FromFiles, bake_from_files,
};
use crate::maps::Chain;

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
    /// positive, as a 16-bit gray image (PNG, DDS or KTX2) mapped from its range, or as the
    /// distances themselves in a 32-bit float OpenEXR file (`.exr`); the range is written
    /// beside it as `STEM.range.json` (`{"min": …, "max": …}` in the meshes' units).
    pub displacement: Option<PathBuf>,
    /// HIGH's mean curvature as a 16-bit gray image (PNG, DDS or KTX2; `.exr`: the values
    /// themselves, 32-bit float), mid-gray flat, lighter
    /// where convex and darker in creases, mapped from a range symmetric about 0 (the 99th
    /// percentile of the texels' |curvature|, beyond which it is clamped) written beside it as
    /// `STEM.range.json` (in 1 / the meshes' units).
    pub curvature: Option<PathBuf>,
    /// LOW as baked for: a `.glb` or `.gltf` with its tangents and the map as its normalTexture.
    pub low: Option<PathBuf>,
}

/// A map a bake writes besides the tangent-space normal map: `--maps`' names, each with the
/// file it goes to beside the normal map when no file is named for it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BakeMap {
    /// [`BakeOutputs::object_space`], `STEM_object.png`.
    ObjectSpace,
    /// [`BakeOutputs::occlusion`], `STEM_ao.png`.
    Occlusion,
    /// [`BakeOutputs::displacement`], `STEM_height.png`.
    Displacement,
    /// [`BakeOutputs::curvature`], `STEM_curvature.png`.
    Curvature,
    /// [`BakeOutputs::mask`], `STEM_mask.png`.
    Mask,
    /// [`BakeOutputs::low`], `STEM_low.glb`.
    Low,
}

impl BakeMap {
    /// Every map, in the order the help lists them.
    pub const ALL: [BakeMap; 6] = [
        BakeMap::ObjectSpace,
        BakeMap::Occlusion,
        BakeMap::Displacement,
        BakeMap::Curvature,
        BakeMap::Mask,
        BakeMap::Low,
    ];

    /// Its name, as `--maps` takes it.
    pub fn name(self) -> &'static str {
        match self {
            BakeMap::ObjectSpace => "object",
            BakeMap::Occlusion => "ao",
            BakeMap::Displacement => "height",
            BakeMap::Curvature => "curvature",
            BakeMap::Mask => "mask",
            BakeMap::Low => "low",
        }
    }

    /// The map `name` names, if any.
    pub fn parse(name: &str) -> Option<BakeMap> {
        BakeMap::ALL.into_iter().find(|m| m.name().eq_ignore_ascii_case(name.trim()))
    }

    /// The file it goes to beside `normal_map`: `STEM_NAME.png` (`STEM_low.glb` for LOW), in
    /// the normal map's folder.
    ///
    /// ```
    /// use bumpmap::bake::BakeMap;
    /// use std::path::Path;
    /// assert_eq!(BakeMap::Occlusion.file_beside(Path::new("out/n.ktx2")), Path::new("out/n_ao.png"));
    /// assert_eq!(BakeMap::Low.file_beside(Path::new("n.png")), Path::new("n_low.glb"));
    /// ```
    pub fn file_beside(self, normal_map: &Path) -> PathBuf {
        let stem = normal_map.file_stem().unwrap_or_default().to_string_lossy();
        let ext = if self == BakeMap::Low { "glb" } else { "png" };
        normal_map.with_file_name(format!("{stem}_{}.{ext}", self.name()))
    }

    /// The output in `outputs` this map fills.
    fn slot(self, outputs: &mut BakeOutputs) -> &mut Option<PathBuf> {
        match self {
            BakeMap::ObjectSpace => &mut outputs.object_space,
            BakeMap::Occlusion => &mut outputs.occlusion,
            BakeMap::Displacement => &mut outputs.displacement,
            BakeMap::Curvature => &mut outputs.curvature,
            BakeMap::Mask => &mut outputs.mask,
            BakeMap::Low => &mut outputs.low,
        }
    }
}

impl BakeOutputs {
    /// The outputs with each of `maps` that has no file yet written beside the normal map
    /// ([`BakeMap::file_beside`]); a file already named for a map is kept.
    ///
    /// ```
    /// use bumpmap::bake::{BakeMap, BakeOutputs};
    /// use std::path::PathBuf;
    /// let outputs = BakeOutputs { normal_map: "n.png".into(), mask: Some("missed.png".into()), ..Default::default() }
    ///     .with_maps_beside(&[BakeMap::Occlusion, BakeMap::Mask]);
    /// assert_eq!(outputs.occlusion, Some(PathBuf::from("n_ao.png")));
    /// assert_eq!(outputs.mask, Some(PathBuf::from("missed.png")));
    /// assert_eq!(outputs.curvature, None);
    /// ```
    pub fn with_maps_beside(mut self, maps: &[BakeMap]) -> BakeOutputs {
        let normal_map = self.normal_map.clone();
        for &map in maps {
            map.slot(&mut self).get_or_insert_with(|| map.file_beside(&normal_map));
        }
        self
    }
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
    let curvature_file = outputs.curvature.as_deref().map(range_file);
    let named: Vec<(&Path, &'static str)> = std::iter::once((outputs.normal_map.as_path(), "the normal map"))
        .chain(range.as_deref().map(|p| (p, "the displacement's range")))
        .chain(curvature_file.as_deref().map(|p| (p, "the curvature's range")))
        .chain(outputs.curvature.as_deref().map(|p| (p, "the curvature")))
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
    request.options.curvature = outputs.curvature.is_some();
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
        let bits = HeightBits::of(request.bits);
        bumpmap_io::horizon_file::write_gray_into(&mut set, path, (w, h), &baked.occlusion, bits)?;
    }
    if let Some(path) = &outputs.displacement {
        let meaning = "signed distance from the low-poly surface to the high-poly one along each texel's ray, outward positive, in the meshes' units";
        write_ranged(&mut set, path, (w, h), &baked.displacement, displacement_range(&baked), meaning)?;
    }
    if let Some(path) = &outputs.curvature {
        let meaning = "the high-poly mesh's mean curvature at each texel's hit, in 1 / the meshes' units, positive where convex, 0 flat";
        write_ranged(&mut set, path, (w, h), &baked.curvature, curvature_range(&baked), meaning)?;
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

/// `values` in `path` — as they are in an OpenEXR file (`.exr`, 32-bit float), else mapped from
/// `(lo, hi)` to 16-bit gray — with the range and its `meaning` beside it in
/// `STEM.range.json`.
fn write_ranged(
    set: &mut FileSet,
    path: &Path,
    size: (usize, usize),
    values: &[f32],
    (lo, hi): (f32, f32),
    meaning: &str,
) -> Result<(), IoError> {
    let exr = GrayFormat::for_path(path, 16) == GrayFormat::Exr;
    let meaning = if exr {
        format!("{meaning}; the OpenEXR file holds the values themselves, unclamped")
    } else {
        format!("{meaning}: 0 in the image is min, 65535 is max, beyond the range clamped")
    };
    if exr {
        save_gray_into(set, path, size.0, size.1, values, GrayFormat::Exr)?;
    } else {
        let span = (hi - lo).max(f32::MIN_POSITIVE);
        let unit: Vec<f32> = values.iter().map(|d| ((d - lo) / span).clamp(0.0, 1.0)).collect();
        bumpmap_io::horizon_file::write_gray_into(set, path, size, &unit, HeightBits::Sixteen)?;
    }
    let json = format!("{{\"min\": {lo}, \"max\": {hi}, \"meaning\": \"{meaning}\"}}\n");
    set.write(&range_file(path), |w| {
        use std::io::Write;
        w.write_all(json.as_bytes())
    })
}

/// Where a 16-bit image's range goes beside it (the displacement's, the curvature's):
/// `STEM.range.json`.
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

/// The curvature's range: symmetric about 0 (flat mid-gray), out to the 99th percentile of the
/// hit texels' |curvature| (a sharp edge's spike does not wash the rest out); `(-1, 1)` where
/// nothing bends.
pub fn curvature_range(baked: &Baked) -> (f32, f32) {
    let mut bends: Vec<f32> =
        baked.curvature.iter().zip(&baked.hit).filter(|(_, h)| **h).map(|(k, _)| k.abs()).collect();
    // The 99th percentile by selection, not a sort of every texel.
    let at = bends.len() * 99 / 100;
    let r = if at < bends.len() { *bends.select_nth_unstable_by(at, f32::total_cmp).1 } else { 0.0 };
    if r > 0.0 { (-r, r) } else { (-1.0, 1.0) }
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
