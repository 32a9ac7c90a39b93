//! DDS and KTX2 containers: a whole mip chain, or a cube map, in one file an engine loads.
//!
//! These formats, all linear (never sRGB: normal maps and heights are data), rows in memory
//! order, row 0 first, exactly as `glTexImage2D` takes them:
//! - [`TextureFormat::Rgba8`]: uncompressed (`DXGI R8G8B8A8_UNORM` / `VK_FORMAT_R8G8B8A8_UNORM`);
//! - [`TextureFormat::Rgba16`]: uncompressed, 16 bits a channel (`R16G16B16A16_UNORM`, little
//!   endian), for bakers' 16-bit normal maps;
//! - [`TextureFormat::Bc5`]: red and green only, 8 bits per texel (`BC5_UNORM`), Z rebuilt in
//!   the shader as √(1 − x² − y²) — blue and alpha (the mip chain's length factor) are dropped;
//! - [`TextureFormat::Bc7`]: all four channels, 8 bits per texel (`BC7_UNORM`);
//! - [`TextureFormat::Rgba32Float`]: LEAN's moments (`R32G32B32A32_FLOAT`);
//! - [`TextureFormat::R8`], [`TextureFormat::R16`], [`TextureFormat::Rg16`]: heights and their
//!   min–max bounds (`R8_UNORM`, `R16_UNORM`, `R16G16_UNORM`).
//!
//! Every level is compressed on its own from the chain given (the chain's own mips, not the
//! encoder's), by Intel's ISPC texture compressor through `image_dds`; a 16-bit level is
//! rounded to 8 bits first, an 8-bit level stored as 16 bits is widened exactly (`v·257`).
//! DDS files of every format but RGBA8 carry the DX10 header extension; KTX2 files a basic data-format descriptor of the
//! format's colour model.

use std::io::Write;
use std::path::Path;

use crate::atomic::FileSet;
use crate::error::IoError;
use bumpmap_math::{Image, Rgba8Image, Rgba16Image};

/// What a texture file holds: `levels[face][level]`, one face for 2D, six (+X, −X, +Y, −Y, +Z,
/// −Z) for a cube map. Every face has the same number of levels and sizes.
pub struct TextureLayout<'a> {
    /// `faces[face][level]`.
    pub faces: Vec<Vec<Level<'a>>>,
}

/// One level's texels, at the depth they were made in.
#[derive(Clone, Copy, Debug)]
pub enum Level<'a> {
    /// 8 bits a channel.
    Rgba8(&'a Rgba8Image),
    /// 16 bits a channel.
    Rgba16(&'a Rgba16Image),
    /// 32-bit floats (LEAN's moments: slopes and their squares, not colours).
    Rgba32F(&'a Image<[f32; 4]>),
    /// One 8-bit channel (heights).
    Gray8(&'a Image<u8>),
    /// One 16-bit channel (heights).
    Gray16(&'a Image<u16>),
    /// Two 16-bit channels (heights' min–max bounds).
    Rg16(&'a Image<[u16; 2]>),
}

impl Level<'_> {
    /// Width and height in texels.
    pub fn size(self) -> (usize, usize) {
        match self {
            Level::Rgba8(l) => (l.width, l.height),
            Level::Rgba16(l) => (l.width, l.height),
            Level::Rgba32F(l) => (l.width, l.height),
            Level::Gray8(l) => (l.width, l.height),
            Level::Gray16(l) => (l.width, l.height),
            Level::Rg16(l) => (l.width, l.height),
        }
    }
}

impl<'a> From<&'a Rgba8Image> for Level<'a> {
    fn from(level: &'a Rgba8Image) -> Self {
        Level::Rgba8(level)
    }
}

impl<'a> From<&'a Rgba16Image> for Level<'a> {
    fn from(level: &'a Rgba16Image) -> Self {
        Level::Rgba16(level)
    }
}

/// How the texels are stored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TextureFormat {
    /// 8-bit RGBA, uncompressed.
    #[default]
    Rgba8,
    /// 16-bit RGBA, uncompressed.
    Rgba16,
    /// BC5 (two channels, red and green).
    Bc5,
    /// BC7 (four channels).
    Bc7,
    /// 32-bit float RGBA, uncompressed (for [`Level::Rgba32F`] only).
    Rgba32Float,
    /// One 8-bit channel (for [`Level::Gray8`]).
    R8,
    /// One 16-bit channel (for [`Level::Gray16`], or [`Level::Gray8`] widened).
    R16,
    /// Two 16-bit channels (for [`Level::Rg16`]).
    Rg16,
}

/// The formats a user picks for a normal map's file (the others hold the maps written beside
/// it); the name texconv uses (`BC5_UNORM`) is an alias.
impl bumpmap_math::Named for TextureFormat {
    const ALL: &'static [Self] = &[TextureFormat::Rgba8, TextureFormat::Rgba16, TextureFormat::Bc5, TextureFormat::Bc7];

    fn name(self) -> &'static str {
        match self {
            TextureFormat::Rgba8 => "rgba8",
            TextureFormat::Rgba16 => "rgba16",
            TextureFormat::Bc5 => "bc5",
            TextureFormat::Bc7 => "bc7",
            TextureFormat::Rgba32Float => "rgba32f",
            TextureFormat::R8 => "r8",
            TextureFormat::R16 => "r16",
            TextureFormat::Rg16 => "rg16",
        }
    }

    fn description(self) -> &'static str {
        match self {
            TextureFormat::Rgba8 => "Uncompressed 8-bit RGBA (16-bit with 16 bits a channel)",
            TextureFormat::Rgba16 => "Uncompressed 16-bit RGBA (the same as 16 bits a channel)",
            TextureFormat::Bc5 => "BC5: two channels (X, Y), 8 bits per texel",
            TextureFormat::Bc7 => "BC7: four channels, 8 bits per texel",
            TextureFormat::Rgba32Float => "Uncompressed 32-bit float RGBA",
            TextureFormat::R8 => "One 8-bit channel",
            TextureFormat::R16 => "One 16-bit channel",
            TextureFormat::Rg16 => "Two 16-bit channels",
        }
    }

    fn aliases(self) -> &'static [&'static str] {
        match self {
            TextureFormat::Rgba8 => &["r8g8b8a8_unorm"],
            TextureFormat::Rgba16 => &["r16g16b16a16_unorm"],
            TextureFormat::Bc5 => &["bc5_unorm"],
            TextureFormat::Bc7 => &["bc7_unorm"],
            _ => &[],
        }
    }
}

impl TextureFormat {
    /// The name texconv uses.
    pub fn dxgi_name(self) -> &'static str {
        match self {
            TextureFormat::Rgba8 => "R8G8B8A8_UNORM",
            TextureFormat::Rgba16 => "R16G16B16A16_UNORM",
            TextureFormat::Bc5 => "BC5_UNORM",
            TextureFormat::Bc7 => "BC7_UNORM",
            TextureFormat::Rgba32Float => "R32G32B32A32_FLOAT",
            TextureFormat::R8 => "R8_UNORM",
            TextureFormat::R16 => "R16_UNORM",
            TextureFormat::Rg16 => "R16G16_UNORM",
        }
    }

    fn dxgi(self) -> u32 {
        match self {
            TextureFormat::Rgba8 => 28,
            TextureFormat::Rgba16 => 11,
            TextureFormat::Bc5 => 83,
            TextureFormat::Bc7 => 98,
            TextureFormat::Rgba32Float => 2,
            TextureFormat::R8 => 61,
            TextureFormat::R16 => 56,
            TextureFormat::Rg16 => 35,
        }
    }

    fn vk(self) -> u32 {
        match self {
            TextureFormat::Rgba8 => 37,
            TextureFormat::Rgba16 => 91,
            TextureFormat::Bc5 => 141,
            TextureFormat::Bc7 => 145,
            TextureFormat::Rgba32Float => 109,
            TextureFormat::R8 => 9,
            TextureFormat::R16 => 70,
            TextureFormat::Rg16 => 77,
        }
    }

    /// Whether texels are stored in 4×4 compressed blocks.
    pub fn is_compressed(self) -> bool {
        matches!(self, TextureFormat::Bc5 | TextureFormat::Bc7)
    }

    /// Bytes of one texel block (1×1 uncompressed, 4×4 for BC).
    fn block_bytes(self) -> usize {
        match self {
            TextureFormat::R8 => 1,
            TextureFormat::R16 => 2,
            TextureFormat::Rgba8 | TextureFormat::Rg16 => 4,
            TextureFormat::Rgba16 => 8,
            TextureFormat::Bc5 | TextureFormat::Bc7 | TextureFormat::Rgba32Float => 16,
        }
    }
}

/// Rows per band a level is compressed in, in parallel: a multiple of the 4-row block, so the
/// bands' blocks laid end to end are the level's.
#[cfg(not(target_arch = "wasm32"))]
const BAND_ROWS: usize = 64;

/// One level's bytes in `format`.
fn encode_level(path: &Path, level: Level, format: TextureFormat) -> Result<Vec<u8>, IoError> {
    let narrowed;
    let le16 = |v: &[u16]| v.iter().flat_map(|c| c.to_le_bytes()).collect::<Vec<u8>>();
    let level = match (level, format) {
        (Level::Gray8(l), TextureFormat::R8) => return Ok(l.texels.clone()),
        (Level::Gray8(l), TextureFormat::R16) => {
            return Ok(l.texels.iter().flat_map(|&b| (b as u16 * 257).to_le_bytes()).collect());
        }
        (Level::Gray16(l), TextureFormat::R16) => return Ok(le16(&l.texels)),
        (Level::Rg16(l), TextureFormat::Rg16) => return Ok(le16(l.texels.as_flattened())),
        (Level::Gray8(_) | Level::Gray16(_) | Level::Rg16(_), _)
        | (_, TextureFormat::R8 | TextureFormat::R16 | TextureFormat::Rg16) => {
            return Err(IoError::Write {
                path: path.to_path_buf(),
                source: std::io::Error::other(format!(
                    "one- and two-channel levels are stored as R8_UNORM, R16_UNORM or R16G16_UNORM and only they are, not as {}",
                    format.dxgi_name()
                )),
            });
        }
        (Level::Rgba32F(l), TextureFormat::Rgba32Float) => {
            return Ok(l.texels.iter().flatten().flat_map(|v| v.to_le_bytes()).collect());
        }
        (Level::Rgba32F(_), _) | (_, TextureFormat::Rgba32Float) => {
            return Err(IoError::Write {
                path: path.to_path_buf(),
                source: std::io::Error::other(format!(
                    "float levels are stored as R32G32B32A32_FLOAT and only they are, not as {}",
                    format.dxgi_name()
                )),
            });
        }
        (Level::Rgba16(l), TextureFormat::Rgba16) => return Ok(l.to_le_bytes()),
        (Level::Rgba8(l), TextureFormat::Rgba16) => {
            return Ok(l.as_bytes().iter().flat_map(|&b| (b as u16 * 257).to_le_bytes()).collect());
        }
        (Level::Rgba8(l), _) => l,
        (Level::Rgba16(l), _) => {
            narrowed = l.to_rgba8();
            &narrowed
        }
    };
    let target = match format {
        TextureFormat::Rgba8 => return Ok(level.as_bytes().to_vec()),
        TextureFormat::Rgba16
        | TextureFormat::Rgba32Float
        | TextureFormat::R8
        | TextureFormat::R16
        | TextureFormat::Rg16 => unreachable!("handled above"),
        TextureFormat::Bc5 => image_dds::ImageFormat::BC5RgUnorm,
        TextureFormat::Bc7 => image_dds::ImageFormat::BC7RgbaUnorm,
    };
    // A level whose sides are not multiples of the 4×4 block gets its partial edge blocks filled
    // by repeating the last column and row (as texconv and NVTT do): the encoder would pad
    // them with zeros, a direction far from the texels beside it that pulls the block's
    // endpoints away from them.
    let padded;
    let level = if level.width % 4 != 0 || level.height % 4 != 0 {
        padded = clamp_to_blocks(level);
        &padded
    } else {
        level
    };
    encode_blocks(level, target, path)
}

/// `level` (whole 4×4 blocks) encoded as `target`, in bands of rows on every core.
#[cfg(not(target_arch = "wasm32"))]
fn encode_blocks(level: &Rgba8Image, target: image_dds::ImageFormat, path: &Path) -> Result<Vec<u8>, IoError> {
    use rayon::prelude::*;
    let row_bytes = 4 * level.width;
    let bands: Vec<Vec<u8>> = level
        .as_bytes()
        .par_chunks(BAND_ROWS * row_bytes)
        .map(|band| {
            let surface = image_dds::SurfaceRgba8 {
                width: level.width as u32,
                height: (band.len() / row_bytes) as u32,
                depth: 1,
                layers: 1,
                mipmaps: 1,
                data: band,
            };
            surface
                .encode(target, image_dds::Quality::Slow, image_dds::Mipmaps::FromSurface)
                .map(|s| s.data)
                .map_err(|e| IoError::Write { path: path.to_path_buf(), source: std::io::Error::other(e.to_string()) })
        })
        .collect::<Result<_, _>>()?;
    Ok(bands.concat())
}

/// On the web the encoder (ISPC kernels) is not built: BC5 and BC7 are refused in words.
#[cfg(target_arch = "wasm32")]
fn encode_blocks(_: &Rgba8Image, target: image_dds::ImageFormat, path: &Path) -> Result<Vec<u8>, IoError> {
    let why = format!("{target:?} encoding is not built for WebAssembly: write rgba8 or rgba16, or encode natively");
    Err(IoError::Write { path: path.to_path_buf(), source: std::io::Error::other(why) })
}

/// `level` grown to whole 4×4 blocks, the new texels copies of the nearest edge texel.
fn clamp_to_blocks(level: &Rgba8Image) -> Rgba8Image {
    let (w, h) = (level.width.next_multiple_of(4), level.height.next_multiple_of(4));
    let texels = (0..h)
        .flat_map(|y| {
            let row = y.min(level.height - 1) * level.width;
            (0..w).map(move |x| level.texels[row + x.min(level.width - 1)])
        })
        .collect();
    Rgba8Image::new(w, h, texels)
}

/// Every level of every face in `format`, `[face][level]`, the levels in parallel: what the
/// writers store. `path` is the file errors name.
pub fn encode(path: &Path, tex: &TextureLayout, format: TextureFormat) -> Result<Vec<Vec<Vec<u8>>>, IoError> {
    use rayon::prelude::*;
    // A chain the readers take back: each level half the one before (rounded down, at least
    // 1), ending at 1×1 at the latest.
    let refuse = |reason: String| IoError::Write { path: path.to_path_buf(), source: std::io::Error::other(reason) };
    for face in &tex.faces {
        bumpmap_math::levels::check_chain(face.iter().map(|l| l.size())).map_err(|e| refuse(e.to_string()))?;
    }
    tex.faces.iter().map(|face| face.par_iter().map(|&l| encode_level(path, l, format)).collect()).collect()
}

/// Writes a DDS file: the legacy header (32-bit RGBA masks for [`TextureFormat::Rgba8`], the
/// DX10 extension for the others), mipmap count, cube-map caps.
pub fn write_dds(path: &Path, tex: &TextureLayout, format: TextureFormat) -> Result<(), IoError> {
    let mut set = FileSet::new(&[]);
    write_dds_into(&mut set, path, tex, format)?;
    set.commit().map(|_| ())
}

/// [`write_dds`] as one file of a [`FileSet`].
pub fn write_dds_into(
    set: &mut FileSet,
    path: &Path,
    tex: &TextureLayout,
    format: TextureFormat,
) -> Result<(), IoError> {
    let data = encode(path, tex, format)?;
    let (base_width, base_height) = tex.faces[0][0].size();
    let levels = tex.faces[0].len() as u32;
    let cube = tex.faces.len() == 6;
    const CAPS: u32 = 0x1;
    const HEIGHT: u32 = 0x2;
    const WIDTH: u32 = 0x4;
    const PITCH: u32 = 0x8;
    const PIXELFORMAT: u32 = 0x1000;
    const MIPMAPCOUNT: u32 = 0x20000;
    const LINEARSIZE: u32 = 0x80000;
    let compressed = format.is_compressed();
    let dx10 = format != TextureFormat::Rgba8;
    let mut flags = CAPS | HEIGHT | WIDTH | PIXELFORMAT | if compressed { LINEARSIZE } else { PITCH };
    let mut caps = 0x1000; // DDSCAPS_TEXTURE
    if levels > 1 {
        flags |= MIPMAPCOUNT;
        caps |= 0x8 | 0x40_0000; // COMPLEX | MIPMAP
    }
    let mut caps2 = 0;
    if cube {
        caps |= 0x8;
        caps2 = 0x200 | 0xFC00; // CUBEMAP and all six faces
    }
    let mut header = Vec::with_capacity(128);
    let mut put = |v: u32| header.extend_from_slice(&v.to_le_bytes());
    put(u32::from_le_bytes(*b"DDS "));
    let pitch = if compressed { data[0][0].len() } else { format.block_bytes() * base_width } as u32;
    for v in [124, flags, base_height as u32, base_width as u32, pitch, 0, levels] {
        put(v);
    }
    for _ in 0..11 {
        put(0);
    }
    if dx10 {
        // DDS_PIXELFORMAT: FOURCC "DX10"; the format is in the extension header.
        for v in [32, 0x4, u32::from_le_bytes(*b"DX10"), 0, 0, 0, 0, 0] {
            put(v);
        }
    } else {
        // DDS_PIXELFORMAT: RGB | ALPHAPIXELS, 32 bits, R in the lowest byte.
        for v in [32, 0x41, 0, 32, 0x0000_00ff, 0x0000_ff00, 0x00ff_0000, 0xff00_0000] {
            put(v);
        }
    }
    for v in [caps, caps2, 0, 0, 0] {
        put(v);
    }
    if dx10 {
        // DDS_HEADER_DXT10: format, TEXTURE2D, TEXTURECUBE if a cube, one array element.
        for v in [format.dxgi(), 3, if cube { 0x4 } else { 0 }, 1, 0] {
            put(v);
        }
    }
    set.write(path, |w| {
        w.write_all(&header)?;
        for face in &data {
            for level in face {
                w.write_all(level)?;
            }
        }
        Ok(())
    })
}

/// Writes a KTX 2.0 file: the format's `VK_FORMAT`, a basic data-format descriptor with
/// linear transfer, levels stored smallest first as the specification requires.
pub fn write_ktx2(path: &Path, tex: &TextureLayout, format: TextureFormat) -> Result<(), IoError> {
    let mut set = FileSet::new(&[]);
    write_ktx2_into(&mut set, path, tex, format)?;
    set.commit().map(|_| ())
}

/// [`write_ktx2`] as one file of a [`FileSet`].
pub fn write_ktx2_into(
    set: &mut FileSet,
    path: &Path,
    tex: &TextureLayout,
    format: TextureFormat,
) -> Result<(), IoError> {
    let file = Ktx2::new(path, tex, format)?;
    set.write(path, |w| file.write(w))
}

/// The KTX2 file [`write_ktx2_into`] writes, as bytes in memory (what a web page offers to
/// save); `name` is the file messages name.
pub fn ktx2_bytes(name: &Path, tex: &TextureLayout, format: TextureFormat) -> Result<Vec<u8>, IoError> {
    let mut out = Vec::new();
    Ktx2::new(name, tex, format)?
        .write(&mut out)
        .map_err(|e| IoError::Texture { path: name.to_path_buf(), reason: e.to_string() })?;
    Ok(out)
}

/// A KTX2 file ready to write: its header, level index and data-format descriptor, and each
/// face's levels encoded.
struct Ktx2 {
    head: Vec<u8>,
    data: Vec<Vec<Vec<u8>>>,
    levels: usize,
    align: usize,
}

impl Ktx2 {
    fn new(path: &Path, tex: &TextureLayout, format: TextureFormat) -> Result<Self, IoError> {
        let data = encode(path, tex, format)?;
        let (base_width, base_height) = tex.faces[0][0].size();
        let levels = tex.faces[0].len();
        let faces = tex.faces.len();
        const IDENTIFIER: [u8; 12] = [0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A];
        let dfd = linear_dfd(format);
        let dfd_offset = 12 + 9 * 4 + 4 * 4 + 2 * 8 + 24 * levels;
        let mut offset = dfd_offset + dfd.len();
        // Level data, smallest level first; each level starts at a multiple of lcm(block size, 4)
        // (block sizes are powers of two).
        let align = format.block_bytes().max(4);
        let mut index = vec![(0u64, 0u64); levels];
        for level in (0..levels).rev() {
            offset = offset.next_multiple_of(align);
            let len: usize = data.iter().map(|f| f[level].len()).sum();
            index[level] = (offset as u64, len as u64);
            offset += len;
        }
        let mut head = Vec::with_capacity(dfd_offset + dfd.len());
        head.extend_from_slice(&IDENTIFIER);
        let type_size = match format {
            TextureFormat::Rgba16 | TextureFormat::R16 | TextureFormat::Rg16 => 2,
            TextureFormat::Rgba32Float => 4,
            _ => 1,
        };
        for v in [format.vk(), type_size, base_width as u32, base_height as u32, 0, 0, faces as u32, levels as u32, 0] {
            head.extend_from_slice(&v.to_le_bytes());
        }
        for v in [dfd_offset as u32, dfd.len() as u32, 0, 0] {
            head.extend_from_slice(&v.to_le_bytes());
        }
        head.extend_from_slice(&[0u8; 16]); // no supercompression global data
        for &(off, len) in &index {
            for v in [off, len, len] {
                head.extend_from_slice(&v.to_le_bytes());
            }
        }
        head.extend_from_slice(&dfd);
        Ok(Self { head, data, levels, align })
    }

    /// The file: the header, then the levels smallest first, each at its alignment.
    fn write(&self, w: &mut impl Write) -> std::io::Result<()> {
        w.write_all(&self.head)?;
        let mut written = self.head.len();
        for level in (0..self.levels).rev() {
            let pad = written.next_multiple_of(self.align) - written;
            w.write_all(&[0u8; 16][..pad])?;
            written += pad;
            for face in &self.data {
                w.write_all(&face[level])?;
                written += face[level].len();
            }
        }
        Ok(())
    }
}

/// The Khronos basic data-format descriptor of `format`, linear: RGBA8 as four 8-bit samples
/// (RGBSDA model), RGBA16 as four 16-bit ones; BC5 as two 64-bit samples, red and green (model BC5); BC7 as one 128-bit
/// sample (model BC7), with 4×4 texel blocks.
fn linear_dfd(format: TextureFormat) -> Vec<u8> {
    /// A sample: bit offset, bit length − 1, channel id with its qualifiers, lower and upper
    /// values.
    type Sample = (u16, u8, u8, u32, u32);
    // Float samples: channel id | KHR_DF_SAMPLE_DATATYPE_FLOAT | _SIGNED; lower −1.0, upper 1.0
    // as IEEE bits (the Data Format specification's convention for float formats).
    const F: u8 = 0x80 | 0x40;
    let (lo, hi) = ((-1.0f32).to_bits(), 1.0f32.to_bits());
    // Model, texel block dimensions − 1, bytes per block, samples.
    let (model, dims, bytes, samples): (u8, [u8; 4], u8, &[Sample]) = match format {
        TextureFormat::Rgba8 => {
            (1, [0, 0, 0, 0], 4, &[(0, 7, 0, 0, 255), (8, 7, 1, 0, 255), (16, 7, 2, 0, 255), (24, 7, 15, 0, 255)])
        }
        TextureFormat::Rgba16 => (
            1,
            [0, 0, 0, 0],
            8,
            &[(0, 15, 0, 0, 65535), (16, 15, 1, 0, 65535), (32, 15, 2, 0, 65535), (48, 15, 15, 0, 65535)],
        ),
        TextureFormat::R8 => (1, [0, 0, 0, 0], 1, &[(0, 7, 0, 0, 255)]),
        TextureFormat::R16 => (1, [0, 0, 0, 0], 2, &[(0, 15, 0, 0, 65535)]),
        TextureFormat::Rg16 => (1, [0, 0, 0, 0], 4, &[(0, 15, 0, 0, 65535), (16, 15, 1, 0, 65535)]),
        TextureFormat::Bc5 => (132, [3, 3, 0, 0], 16, &[(0, 63, 0, 0, u32::MAX), (64, 63, 1, 0, u32::MAX)]),
        TextureFormat::Bc7 => (134, [3, 3, 0, 0], 16, &[(0, 127, 0, 0, u32::MAX)]),
        TextureFormat::Rgba32Float => (
            1,
            [0, 0, 0, 0],
            16,
            &[(0, 31, F, lo, hi), (32, 31, 1 | F, lo, hi), (64, 31, 2 | F, lo, hi), (96, 31, 15 | F, lo, hi)],
        ),
    };
    let block = 24 + 16 * samples.len();
    let mut d = Vec::with_capacity(4 + block);
    d.extend_from_slice(&(4 + block as u32).to_le_bytes()); // dfdTotalSize
    d.extend_from_slice(&0u32.to_le_bytes()); // vendor 0 (Khronos), descriptor type 0 (basic)
    d.extend_from_slice(&2u16.to_le_bytes()); // version 1.3
    d.extend_from_slice(&(block as u16).to_le_bytes()); // descriptor block size
    d.extend_from_slice(&[model, 1, 1, 0]); // model, BT.709 primaries, linear, straight alpha
    d.extend_from_slice(&dims); // texel block dimensions, each minus one
    d.extend_from_slice(&[bytes, 0, 0, 0, 0, 0, 0, 0]); // bytes in plane 0
    for &(offset, length, channel, lower, upper) in samples {
        d.extend_from_slice(&offset.to_le_bytes());
        d.extend_from_slice(&[length, channel, 0, 0, 0, 0]); // bit length − 1, channel id, position 0
        d.extend_from_slice(&lower.to_le_bytes());
        d.extend_from_slice(&upper.to_le_bytes());
    }
    d
}

#[cfg(test)]
mod tests;
