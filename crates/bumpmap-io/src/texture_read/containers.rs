//! DDS and KTX2 containers in: the header checked (one 2D face, a linear format, no
//! supercompression, each level's bytes present) before any level is decoded, then every level
//! decoded from its layout (RGBA8, BGRA8, RGBA16, R8/R16/R16G16 heights, BC5 and BC7 blocks).
//!
//! What this module does not do: read images (`texture_read.rs` hands those to `image_file`) or
//! interpret the texels (`bumpmap_math::imported`).

use std::path::Path;

use bumpmap_math::{Encoding, Rgba8Image, Rgba16Image};

use super::{StoredLevels, StoredTexture, bad};
use crate::error::IoError;
use crate::image_file::MAX_DIMENSION;
use crate::texture_file::TextureFormat;

pub(super) const KTX2_IDENTIFIER: [u8; 12] = [0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A];

/// How a container's texels are laid out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Layout {
    Rgba8,
    Bgra8,
    Rgba16,
    Bc5,
    Bc7,
    /// One 8-bit channel, read as (r, r, r, 255).
    R8,
    /// One 16-bit channel, read as (r, r, r, 65535).
    R16,
    /// Two 16-bit channels, read as (r, g, 0, 65535).
    Rg16,
}

impl Layout {
    /// The bytes of a `w`×`h` level, or `None` if that overflows.
    fn level_bytes(self, w: usize, h: usize) -> Option<usize> {
        match self {
            Layout::R8 => w.checked_mul(h),
            Layout::R16 => w.checked_mul(h)?.checked_mul(2),
            Layout::Rgba8 | Layout::Bgra8 | Layout::Rg16 => w.checked_mul(h)?.checked_mul(4),
            Layout::Rgba16 => w.checked_mul(h)?.checked_mul(8),
            Layout::Bc5 | Layout::Bc7 => w.div_ceil(4).checked_mul(h.div_ceil(4))?.checked_mul(16),
        }
    }

    fn format(self) -> TextureFormat {
        match self {
            Layout::Rgba8 | Layout::Bgra8 => TextureFormat::Rgba8,
            Layout::Rgba16 => TextureFormat::Rgba16,
            Layout::Bc5 => TextureFormat::Bc5,
            Layout::Bc7 => TextureFormat::Bc7,
            Layout::R8 => TextureFormat::R8,
            Layout::R16 => TextureFormat::R16,
            Layout::Rg16 => TextureFormat::Rg16,
        }
    }

    /// Whether levels decode to 16 bits a channel.
    fn sixteen(self) -> bool {
        matches!(self, Layout::Rgba16 | Layout::R16 | Layout::Rg16)
    }
}

/// The sizes of `levels` levels from `width`×`height`, checked against the limits.
fn level_sizes(path: &Path, width: u32, height: u32, levels: u32) -> Result<Vec<(usize, usize)>, IoError> {
    if width == 0 || height == 0 {
        return Err(IoError::Empty { path: path.to_path_buf(), width, height });
    }
    if width > MAX_DIMENSION || height > MAX_DIMENSION {
        return Err(IoError::TooLarge {
            path: path.to_path_buf(),
            width: width as u64,
            height: height as u64,
            max: MAX_DIMENSION,
        });
    }
    let most = bumpmap_math::levels::level_count(width as usize, height as usize) as u32;
    if levels > most {
        return Err(bad(
            path,
            format!("declares {levels} mip levels, but a {width}x{height} texture has at most {most}"),
        ));
    }
    let mut sizes = bumpmap_math::levels::chain_sizes(width as usize, height as usize);
    sizes.truncate(levels.max(1) as usize);
    Ok(sizes)
}

/// Decodes one level's bytes (exactly its size) into texels.
fn decode_level(path: &Path, layout: Layout, (w, h): (usize, usize), data: &[u8]) -> Result<Level, IoError> {
    Ok(match layout {
        Layout::Rgba8 => {
            Level::Rgba8(Rgba8Image::new(w, h, data.chunks_exact(4).map(|p| [p[0], p[1], p[2], p[3]]).collect()))
        }
        Layout::Bgra8 => {
            Level::Rgba8(Rgba8Image::new(w, h, data.chunks_exact(4).map(|p| [p[2], p[1], p[0], p[3]]).collect()))
        }
        Layout::Rgba16 => {
            let c = |b: &[u8]| u16::from_le_bytes([b[0], b[1]]);
            Level::Rgba16(Rgba16Image::new(
                w,
                h,
                data.chunks_exact(8).map(|p| [c(&p[0..]), c(&p[2..]), c(&p[4..]), c(&p[6..])]).collect(),
            ))
        }
        Layout::R8 => Level::Rgba8(Rgba8Image::new(w, h, data.iter().map(|&r| [r, r, r, 255]).collect())),
        Layout::R16 => {
            let texels = data.chunks_exact(2).map(|p| {
                let r = u16::from_le_bytes([p[0], p[1]]);
                [r, r, r, 65535]
            });
            Level::Rgba16(Rgba16Image::new(w, h, texels.collect()))
        }
        Layout::Rg16 => {
            let c = |b: &[u8]| u16::from_le_bytes([b[0], b[1]]);
            Level::Rgba16(Rgba16Image::new(
                w,
                h,
                data.chunks_exact(4).map(|p| [c(&p[0..]), c(&p[2..]), 0, 65535]).collect(),
            ))
        }
        Layout::Bc5 | Layout::Bc7 => {
            let image_format = if layout == Layout::Bc5 {
                image_dds::ImageFormat::BC5RgUnorm
            } else {
                image_dds::ImageFormat::BC7RgbaUnorm
            };
            let surface = image_dds::Surface {
                width: w as u32,
                height: h as u32,
                depth: 1,
                layers: 1,
                mipmaps: 1,
                image_format,
                data,
            };
            let rgba =
                surface.decode_rgba8().map_err(|e| bad(path, format!("its {w}x{h} level does not decode: {e}")))?;
            let texels = rgba.data.chunks_exact(4).map(|p| {
                if layout == Layout::Bc7 {
                    return [p[0], p[1], p[2], p[3]];
                }
                // BC5 holds X and Y; Z from the unit length, as a shader rebuilds it.
                let (x, y) = (Encoding::Unorm.decode(p[0]), Encoding::Unorm.decode(p[1]));
                [p[0], p[1], Encoding::Unorm.encode((1.0 - x * x - y * y).max(0.0).sqrt()), 255]
            });
            Level::Rgba8(Rgba8Image::new(w, h, texels.collect()))
        }
    })
}

/// One decoded level.
enum Level {
    Rgba8(Rgba8Image),
    Rgba16(Rgba16Image),
}

/// Decodes every level of a container, `data(k)` giving level k's bytes (already checked to be
/// exactly its size).
fn decode_levels<'a>(
    path: &Path,
    layout: Layout,
    sizes: &[(usize, usize)],
    data: impl Fn(usize) -> &'a [u8],
) -> Result<StoredTexture, IoError> {
    // Every level's texels, asked for before the first is decoded (BC blocks decode to RGBA8).
    let texel_bytes = if layout.sixteen() { 8 } else { 4 };
    let needed: u64 = sizes.iter().map(|&(w, h)| w as u64 * h as u64 * texel_bytes).sum();
    bumpmap_math::buffer::ensure_available(needed, "decoding its levels")
        .map_err(|source| IoError::OutOfMemory { path: path.to_path_buf(), source })?;
    let mut eight = Vec::new();
    let mut sixteen = Vec::new();
    for (k, &size) in sizes.iter().enumerate() {
        match decode_level(path, layout, size, data(k))? {
            Level::Rgba8(l) => eight.push(l),
            Level::Rgba16(l) => sixteen.push(l),
        }
    }
    let levels = if layout.sixteen() { StoredLevels::Rgba16(sixteen) } else { StoredLevels::Rgba8(eight) };
    Ok(StoredTexture { levels, format: layout.format() })
}

fn refuse_srgb(path: &Path, name: impl std::fmt::Debug) -> IoError {
    bad(path, format!("{name:?} is an sRGB format: a normal map is linear data (store it as a UNORM format)"))
}

pub(super) fn read_dds(bytes: &[u8], path: &Path) -> Result<StoredTexture, IoError> {
    use ddsfile::{Caps2, DxgiFormat as F, FourCC};
    // The reader keeps its own copy of the levels' bytes.
    bumpmap_math::buffer::ensure_available(bytes.len() as u64, "reading it")
        .map_err(|source| IoError::OutOfMemory { path: path.to_path_buf(), source })?;
    let dds = ddsfile::Dds::read(bytes).map_err(|e| bad(path, format!("not a readable DDS file: {e}")))?;
    let h = &dds.header;
    if h.caps2.contains(Caps2::CUBEMAP) {
        return Err(bad(path, "is a cube map; a normal map is one 2D texture"));
    }
    if h.depth.is_some_and(|d| d > 1) || h.caps2.contains(Caps2::VOLUME) {
        return Err(bad(path, "is a volume texture; a normal map is one 2D texture"));
    }
    // DX10's own word for the kind of texture, whatever the legacy header's flags say.
    if let Some(h10) = &dds.header10
        && h10.resource_dimension != ddsfile::D3D10ResourceDimension::Texture2D
    {
        return Err(bad(
            path,
            format!(
                "is declared a {:?} resource (DX10 header); a normal map is one 2D texture",
                h10.resource_dimension
            ),
        ));
    }
    if let Some(h10) = &dds.header10
        && h10.array_size > 1
    {
        return Err(bad(path, format!("is an array of {} textures; a normal map is one", h10.array_size)));
    }
    if let Some(h10) = &dds.header10
        && h10.misc_flag.contains(ddsfile::MiscFlag::TEXTURECUBE)
    {
        return Err(bad(path, "is a cube map; a normal map is one 2D texture"));
    }
    // A legacy header's RGB masks without ALPHA_PIXELS (X8R8G8B8, X8B8G8R8): the fourth byte is
    // padding, not alpha.
    let padded = dds.header10.is_none()
        && h.spf.fourcc.is_none()
        && !h.spf.flags.contains(ddsfile::PixelFormatFlags::ALPHA_PIXELS);
    let layout = match dds.get_dxgi_format() {
        Some(F::R8G8B8A8_UNorm) => Layout::Rgba8,
        Some(F::B8G8R8A8_UNorm) => Layout::Bgra8,
        Some(F::R16G16B16A16_UNorm) => Layout::Rgba16,
        Some(F::BC5_UNorm) => Layout::Bc5,
        Some(F::BC7_UNorm) => Layout::Bc7,
        Some(F::R8_UNorm) => Layout::R8,
        Some(F::R16_UNorm) => Layout::R16,
        Some(F::R16G16_UNorm) => Layout::Rg16,
        Some(f @ (F::R8G8B8A8_UNorm_sRGB | F::B8G8R8A8_UNorm_sRGB | F::BC7_UNorm_sRGB)) if dds.header10.is_some() => {
            return Err(refuse_srgb(path, f));
        }
        _ if h.spf.fourcc == Some(FourCC(u32::from_le_bytes(*b"BC5U"))) => Layout::Bc5,
        _ if h.spf.fourcc.as_ref().is_some_and(|f| f.0 == FourCC::DXT5) => {
            return Err(bad(
                path,
                "is DXT5/BC3, whose normal maps swizzle X and Y into alpha and green in ways tools disagree on: convert it to BC5, BC7 or RGBA8",
            ));
        }
        _ => match (h.spf.rgb_bit_count, h.spf.r_bit_mask, h.spf.g_bit_mask, h.spf.b_bit_mask) {
            (Some(32), Some(0xff), Some(0xff00), Some(0xff_0000)) => Layout::Rgba8,
            (Some(32), Some(0xff_0000), Some(0xff00), Some(0xff)) => Layout::Bgra8,
            _ => {
                let named = dds
                    .header10
                    .as_ref()
                    .map(|h10| format!("{:?}", h10.dxgi_format))
                    .or_else(|| {
                        h.spf.fourcc.as_ref().map(|f| format!("FourCC {:?}", f.0.to_le_bytes().map(char::from)))
                    })
                    .unwrap_or_else(|| format!("{:?}-bit masks", h.spf.rgb_bit_count));
                return Err(bad(
                    path,
                    format!(
                        "stores {named}; normal maps are read as R8G8B8A8, B8G8R8A8, R16G16B16A16, BC5 or BC7, heights as R8, R16 or R16G16 (UNORM)"
                    ),
                ));
            }
        },
    };
    let sizes = level_sizes(path, h.width, h.height, dds.get_num_mipmap_levels())?;
    let mut offsets = Vec::with_capacity(sizes.len() + 1);
    let mut total = 0usize;
    for &(w, hh) in &sizes {
        offsets.push(total);
        total = layout.level_bytes(w, hh).and_then(|n| total.checked_add(n)).ok_or_else(|| {
            bad(path, format!("{} levels from {}x{} overflow the addressable size", sizes.len(), h.width, h.height))
        })?;
    }
    offsets.push(total);
    if dds.data.len() < total {
        return Err(bad(
            path,
            format!(
                "holds {} bytes of texels, but its header declares {} level(s) from {}x{} in {}, which take {total}",
                dds.data.len(),
                sizes.len(),
                h.width,
                h.height,
                layout.format().dxgi_name()
            ),
        ));
    }
    let mut texture = decode_levels(path, layout, &sizes, |k| &dds.data[offsets[k]..offsets[k + 1]])?;
    if padded && let StoredLevels::Rgba8(levels) = &mut texture.levels {
        levels.iter_mut().flat_map(|l| l.texels.iter_mut()).for_each(|t| t[3] = 255);
    }
    Ok(texture)
}

pub(super) fn read_ktx2(bytes: &[u8], path: &Path) -> Result<StoredTexture, IoError> {
    use ktx2::Format as F;
    let reader = ktx2::Reader::new(bytes).map_err(|e| bad(path, format!("not a readable KTX2 file: {e:?}")))?;
    let h = reader.header();
    if let Some(scheme) = h.supercompression_scheme {
        return Err(bad(path, format!("is supercompressed ({scheme:?}), which is not read")));
    }
    if h.face_count != 1 {
        return Err(bad(path, format!("has {} faces; a normal map is one 2D texture", h.face_count)));
    }
    if h.layer_count > 1 || h.pixel_depth > 1 {
        return Err(bad(path, "is an array or volume texture; a normal map is one 2D texture"));
    }
    let layout = match h.format {
        Some(F::R8G8B8A8_UNORM) => Layout::Rgba8,
        Some(F::B8G8R8A8_UNORM) => Layout::Bgra8,
        Some(F::R16G16B16A16_UNORM) => Layout::Rgba16,
        Some(F::BC5_UNORM_BLOCK) => Layout::Bc5,
        Some(F::BC7_UNORM_BLOCK) => Layout::Bc7,
        Some(F::R8_UNORM) => Layout::R8,
        Some(F::R16_UNORM) => Layout::R16,
        Some(F::R16G16_UNORM) => Layout::Rg16,
        Some(f @ (F::R8G8B8A8_SRGB | F::B8G8R8A8_SRGB | F::BC7_SRGB_BLOCK)) => return Err(refuse_srgb(path, f)),
        other => {
            return Err(bad(
                path,
                format!(
                    "stores {other:?}; normal maps are read as R8G8B8A8, B8G8R8A8, R16G16B16A16, BC5 or BC7, heights as R8, R16 or R16G16 (UNORM)"
                ),
            ));
        }
    };
    let sizes = level_sizes(path, h.pixel_width, h.pixel_height, h.level_count.max(1))?;
    // The reader indexes `level_count.max(1)` levels: as many as `sizes` holds.
    let levels: Vec<&[u8]> = reader.levels().map(|l| l.data).collect();
    for (k, (&(w, hh), data)) in sizes.iter().zip(&levels).enumerate() {
        let want = layout
            .level_bytes(w, hh)
            .ok_or_else(|| bad(path, format!("level {k}, {w}x{hh}, overflows the addressable size")))?;
        if data.len() != want {
            return Err(bad(
                path,
                format!(
                    "level {k} holds {} bytes, but a {w}x{hh} level of {:?} takes {want}",
                    data.len(),
                    layout.format()
                ),
            ));
        }
    }
    decode_levels(path, layout, &sizes, |k| levels[k])
}
