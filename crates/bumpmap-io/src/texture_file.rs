//! DDS and KTX2 containers: a whole mip chain, or a cube map, in one file an engine loads.
//!
//! Both hold uncompressed 8-bit RGBA (`DXGI R8G8B8A8_UNORM` / `VK_FORMAT_R8G8B8A8_UNORM`),
//! linear (never sRGB: normal maps are data). Rows are written in memory order, row 0 first,
//! exactly as `glTexImage2D` takes them. Block compression is left to dedicated tools.

use std::io::Write;
use std::path::Path;

use crate::atomic::FileSet;
use crate::error::IoError;
use bumpmap_math::Rgba8Image;

/// What a texture file holds: `levels[face][level]`, one face for 2D, six (+X, −X, +Y, −Y, +Z,
/// −Z) for a cube map. Every face has the same number of levels and sizes.
pub struct TextureLayout<'a> {
    pub faces: Vec<Vec<&'a Rgba8Image>>,
}

/// Writes a DDS file (legacy header, 32-bit RGBA masks, mipmap count, cube-map caps).
pub fn write_dds(path: &Path, tex: &TextureLayout) -> Result<(), IoError> {
    let mut set = FileSet::new(&[]);
    write_dds_into(&mut set, path, tex)?;
    set.commit().map(|_| ())
}

/// [`write_dds`] as one file of a [`FileSet`].
pub fn write_dds_into(set: &mut FileSet, path: &Path, tex: &TextureLayout) -> Result<(), IoError> {
    let base = tex.faces[0][0];
    let levels = tex.faces[0].len() as u32;
    let cube = tex.faces.len() == 6;
    const CAPS: u32 = 0x1;
    const HEIGHT: u32 = 0x2;
    const WIDTH: u32 = 0x4;
    const PITCH: u32 = 0x8;
    const PIXELFORMAT: u32 = 0x1000;
    const MIPMAPCOUNT: u32 = 0x20000;
    let mut flags = CAPS | HEIGHT | WIDTH | PITCH | PIXELFORMAT;
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
    for v in [124, flags, base.height as u32, base.width as u32, 4 * base.width as u32, 0, levels] {
        put(v);
    }
    for _ in 0..11 {
        put(0);
    }
    // DDS_PIXELFORMAT: RGB | ALPHAPIXELS, 32 bits, R in the lowest byte.
    for v in [32, 0x41, 0, 32, 0x0000_00ff, 0x0000_ff00, 0x00ff_0000, 0xff00_0000] {
        put(v);
    }
    for v in [caps, caps2, 0, 0, 0] {
        put(v);
    }
    set.write(path, |w| {
        w.write_all(&header)?;
        for face in &tex.faces {
            for level in face {
                w.write_all(level.as_bytes())?;
            }
        }
        Ok(())
    })
}

/// Writes a KTX 2.0 file: `VK_FORMAT_R8G8B8A8_UNORM`, a basic data-format descriptor with
/// linear transfer, levels stored smallest first as the specification requires.
pub fn write_ktx2(path: &Path, tex: &TextureLayout) -> Result<(), IoError> {
    let mut set = FileSet::new(&[]);
    write_ktx2_into(&mut set, path, tex)?;
    set.commit().map(|_| ())
}

/// [`write_ktx2`] as one file of a [`FileSet`].
pub fn write_ktx2_into(set: &mut FileSet, path: &Path, tex: &TextureLayout) -> Result<(), IoError> {
    let base = tex.faces[0][0];
    let levels = tex.faces[0].len();
    let faces = tex.faces.len();
    const IDENTIFIER: [u8; 12] = [0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A];
    let dfd = rgba8_linear_dfd();
    let dfd_offset = 12 + 9 * 4 + 4 * 4 + 2 * 8 + 24 * levels;
    let mut offset = dfd_offset + dfd.len();
    // Level data, smallest level first; each level starts 4-byte aligned.
    let mut index = vec![(0u64, 0u64); levels];
    for level in (0..levels).rev() {
        offset = offset.next_multiple_of(4);
        let len: usize = tex.faces.iter().map(|f| f[level].as_bytes().len()).sum();
        index[level] = (offset as u64, len as u64);
        offset += len;
    }
    let mut head = Vec::with_capacity(dfd_offset + dfd.len());
    head.extend_from_slice(&IDENTIFIER);
    for v in [37u32, 1, base.width as u32, base.height as u32, 0, 0, faces as u32, levels as u32, 0] {
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
    set.write(path, |w| {
        w.write_all(&head)?;
        let mut written = head.len();
        for level in (0..levels).rev() {
            let pad = written.next_multiple_of(4) - written;
            w.write_all(&[0u8; 4][..pad])?;
            written += pad;
            for face in &tex.faces {
                w.write_all(face[level].as_bytes())?;
                written += face[level].as_bytes().len();
            }
        }
        Ok(())
    })
}

/// The Khronos basic data-format descriptor of 8-bit linear RGBA, four samples.
fn rgba8_linear_dfd() -> Vec<u8> {
    let mut d = Vec::with_capacity(92);
    d.extend_from_slice(&92u32.to_le_bytes()); // dfdTotalSize
    d.extend_from_slice(&0u32.to_le_bytes()); // vendor 0 (Khronos), descriptor type 0 (basic)
    d.extend_from_slice(&2u16.to_le_bytes()); // version 1.3
    d.extend_from_slice(&88u16.to_le_bytes()); // block size: 24 + 4 samples × 16
    d.extend_from_slice(&[1, 1, 1, 0]); // RGBSDA model, BT.709 primaries, linear, straight alpha
    d.extend_from_slice(&[0, 0, 0, 0]); // 1×1×1×1 texel block
    d.extend_from_slice(&[4, 0, 0, 0, 0, 0, 0, 0]); // 4 bytes in plane 0
    for (i, channel) in [0u8, 1, 2, 15].into_iter().enumerate() {
        d.extend_from_slice(&(8 * i as u16).to_le_bytes());
        d.extend_from_slice(&[7, channel, 0, 0, 0, 0]); // 8 bits, channel id, position 0
        d.extend_from_slice(&0u32.to_le_bytes());
        d.extend_from_slice(&255u32.to_le_bytes());
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chain() -> Vec<Rgba8Image> {
        // 4×2 → 2×1 → 1×1 with distinct bytes per level.
        vec![
            Rgba8Image::new(4, 2, vec![[10; 4]; 8]),
            Rgba8Image::new(2, 1, vec![[20; 4]; 2]),
            Rgba8Image::new(1, 1, vec![[30; 4]]),
        ]
    }

    fn layout(data: &[Rgba8Image], faces: usize) -> TextureLayout<'_> {
        TextureLayout { faces: vec![data.iter().collect(); faces] }
    }

    fn tmp(name: &str) -> std::path::PathBuf {
        std::env::temp_dir().join(format!("bumpmap-{}-{name}", std::process::id()))
    }

    #[test]
    fn ktx2_parses_with_an_independent_reader() {
        let data = chain();
        for faces in [1, 6] {
            let path = tmp(&format!("t{faces}.ktx2"));
            write_ktx2(&path, &layout(&data, faces)).unwrap();
            let bytes = std::fs::read(&path).unwrap();
            let reader = ktx2::Reader::new(&bytes[..]).expect("valid KTX2");
            let h = reader.header();
            assert_eq!((h.pixel_width, h.pixel_height, h.face_count, h.level_count), (4, 2, faces as u32, 3));
            assert_eq!(h.format, Some(ktx2::Format::R8G8B8A8_UNORM));
            for (k, level) in reader.levels().enumerate() {
                assert_eq!(level.data, data[k].as_bytes().repeat(faces).as_slice(), "level {k}");
            }
            std::fs::remove_file(path).unwrap();
        }
    }

    #[test]
    fn dds_parses_with_an_independent_reader() {
        let data = chain();
        let path = tmp("t.dds");
        write_dds(&path, &layout(&data, 1)).unwrap();
        let dds = ddsfile::Dds::read(&mut std::fs::File::open(&path).unwrap()).expect("valid DDS");
        assert_eq!((dds.get_width(), dds.get_height(), dds.get_num_mipmap_levels()), (4, 2, 3));
        assert_eq!(dds.data, data.iter().flat_map(|l| l.as_bytes().to_vec()).collect::<Vec<u8>>());
        std::fs::remove_file(path).unwrap();
    }
}
