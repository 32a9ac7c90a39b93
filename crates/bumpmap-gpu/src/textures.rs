//! Textures on the device: a scene's RGBA8 mip chains (every level uploaded, linear
//! `Rgba8Unorm`, never sRGB), normalization cube maps (Kilgard Appendix D) as cube textures,
//! white 1×1 stand-ins for absent units, LEAN moments as half floats, heights as geometry as
//! 32-bit floats, and GL sampler state as wgpu samplers.
//!
//! Uploads are cached by the scene's `Arc`s, so a texture crosses the bus once however many
//! passes and frames read it.

use std::sync::Arc;

use bumpmap_core::cache::ArcCache;
use bumpmap_core::state::{MagFilter, MinFilter, Sampler, WrapMode};
use bumpmap_math::{Encoding, HeightMips, HorizonMap, LeanMips, NormalizationCubeMap, Rgba8Image, Rgba8Mips};

use crate::context::Context;
use crate::error::GpuError;

/// The device's copies of textures and samplers.
#[derive(Default)]
pub struct Textures {
    mips: ArcCache<Rgba8Mips, wgpu::TextureView>,
    /// LEAN moments, keyed by the normal map they were made from.
    moments: ArcCache<Rgba8Mips, [wgpu::TextureView; 2]>,
    /// CLEAN moments, likewise.
    clean: ArcCache<Rgba8Mips, wgpu::TextureView>,
    /// Roughness maps made for the roughness-map filter (uploaded as any other chain).
    pub roughness: bumpmap_core::shading::RoughnessTextures,
    cubes: Vec<((usize, Encoding), wgpu::TextureView)>,
    samplers: Vec<(Sampler, wgpu::Sampler)>,
    white_2d: Option<wgpu::TextureView>,
    white_cube: Option<wgpu::TextureView>,
    /// Heights as geometry: (heights, bounds) by the scene's `Arc`.
    heights: Vec<(Arc<HeightMips>, [wgpu::TextureView; 2])>,
    no_heights: Option<[wgpu::TextureView; 2]>,
    /// Horizon maps: directions 0–3 and 4–7 by the heights' `Arc`.
    horizons: Vec<(Arc<HorizonMap>, [wgpu::TextureView; 2])>,
    no_horizons: Option<[wgpu::TextureView; 2]>,
}

/// A 2D texture of `format` with one mip level per `(width, height, bytes)` of `levels`, level
/// 0 first, each row `bytes_per_texel × width` bytes without padding.
fn levels_texture(
    ctx: &Context,
    label: &str,
    format: wgpu::TextureFormat,
    bytes_per_texel: u32,
    levels: &[(usize, usize, Vec<u8>)],
) -> wgpu::TextureView {
    let (w0, h0, _) = &levels[0];
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width: *w0 as u32, height: *h0 as u32, depth_or_array_layers: 1 },
        mip_level_count: levels.len() as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (k, (w, h, bytes)) in levels.iter().enumerate() {
        ctx.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: k as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytes,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(bytes_per_texel * *w as u32),
                rows_per_image: Some(*h as u32),
            },
            wgpu::Extent3d { width: *w as u32, height: *h as u32, depth_or_array_layers: 1 },
        );
    }
    texture.create_view(&wgpu::TextureViewDescriptor::default())
}

/// A float texture of `levels` (each `(width, height, texels as f32s, N a texel)`): `R32Float`
/// for one channel, `Rg32Float` for two, `Rgba32Float` for four; read with `textureLoad`, never
/// filtered.
fn float_texture<const N: usize>(ctx: &Context, label: &str, levels: &[(usize, usize, &[f32])]) -> wgpu::TextureView {
    const { assert!(N == 1 || N == 2 || N == 4, "heights are one channel, their bounds two, horizons four") };
    let format = match N {
        1 => wgpu::TextureFormat::R32Float,
        2 => wgpu::TextureFormat::Rg32Float,
        _ => wgpu::TextureFormat::Rgba32Float,
    };
    let bytes: Vec<_> =
        levels.iter().map(|&(w, h, texels)| (w, h, texels.iter().flat_map(|v| v.to_le_bytes()).collect())).collect();
    levels_texture(ctx, label, format, 4 * N as u32, &bytes)
}

fn texture(ctx: &Context, label: &str, width: usize, height: usize, layers: u32, levels: u32) -> wgpu::Texture {
    ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width: width as u32, height: height as u32, depth_or_array_layers: layers },
        mip_level_count: levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

fn write_level(ctx: &Context, texture: &wgpu::Texture, level: u32, layer: u32, image: &Rgba8Image) {
    ctx.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: level,
            origin: wgpu::Origin3d { x: 0, y: 0, z: layer },
            aspect: wgpu::TextureAspect::All,
        },
        image.as_bytes(),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * image.width as u32),
            rows_per_image: Some(image.height as u32),
        },
        wgpu::Extent3d { width: image.width as u32, height: image.height as u32, depth_or_array_layers: 1 },
    );
}

/// The moments of `normal_map`'s level 0, every level; refused when larger than the adapter
/// allows.
fn lean_mips(ctx: &Context, normal_map: &Rgba8Mips) -> Result<LeanMips, GpuError> {
    let max = ctx.max_texture_side();
    let (width, height) = (normal_map.width(), normal_map.height());
    if width > max as usize || height > max as usize {
        return Err(GpuError::TooLarge { what: "a texture", width, height, max });
    }
    Ok(LeanMips::from_normal_map(normal_map, Encoding::Unorm).map_err(bumpmap_core::CoreError::from)?)
}

/// A half-float texture of every level of `lean`, each texel's `N` channels `texel` (2 or 4:
/// `Rg16Float` or `Rgba16Float`).
fn half_texture<const N: usize>(
    ctx: &Context,
    label: &str,
    lean: &LeanMips,
    texel: impl Fn(&bumpmap_math::lean::LeanMoments) -> [f32; N],
) -> wgpu::TextureView {
    const { assert!(N == 2 || N == 4, "half-float moment textures hold 2 or 4 channels") };
    let format = if N == 2 { wgpu::TextureFormat::Rg16Float } else { wgpu::TextureFormat::Rgba16Float };
    let bytes: Vec<_> = lean
        .levels
        .iter()
        .map(|level| {
            let texels =
                level.texels.iter().flat_map(&texel).flat_map(|x| half::f16::from_f32(x).to_le_bytes()).collect();
            (level.width, level.height, texels)
        })
        .collect();
    levels_texture(ctx, label, format, 2 * N as u32, &bytes)
}

/// Uploads `mips`, every level; refused when larger than the adapter allows.
fn upload_mips(ctx: &Context, mips: &Arc<Rgba8Mips>) -> Result<wgpu::TextureView, GpuError> {
    let max = ctx.max_texture_side();
    if mips.width() > max as usize || mips.height() > max as usize {
        return Err(GpuError::TooLarge { what: "a texture", width: mips.width(), height: mips.height(), max });
    }
    let t = texture(ctx, "texture", mips.width(), mips.height(), 1, mips.levels().len() as u32);
    for (k, level) in mips.levels().iter().enumerate() {
        write_level(ctx, &t, k as u32, 0, level);
    }
    let view = t.create_view(&wgpu::TextureViewDescriptor::default());
    Ok(view)
}

impl Textures {
    /// The device's copy of `mips`, every level; refused when larger than the adapter allows.
    pub fn mips(&mut self, ctx: &Context, mips: &Arc<Rgba8Mips>) -> Result<wgpu::TextureView, GpuError> {
        self.mips.get_or_try_make(mips, |mips| upload_mips(ctx, mips))
    }

    /// Drops the uploads of maps nothing but this store holds any more.
    pub fn evict_unused(&mut self) {
        self.mips.evict_unused();
        self.moments.evict_unused();
        self.clean.evict_unused();
        self.roughness.evict_unused();
        self.heights.retain(|(h, _)| Arc::strong_count(h) > 1);
        self.horizons.retain(|(h, _)| Arc::strong_count(h) > 1);
    }

    /// The LEAN moments of `normal_map`'s level 0 (`bumpmap_math::lean`), every level, as two
    /// half-float textures the material sampler filters like the normal map: `Rgba16Float`
    /// (Bx, By, Mxx, Myy) and `Rg16Float` (Mxy, J). Half floats keep 11 bits: M − BBᵀ loses about
    /// 10⁻³·M to rounding, small beside the lobe's own 1/s for the exponents used here.
    pub fn moments(&mut self, ctx: &Context, normal_map: &Arc<Rgba8Mips>) -> Result<[wgpu::TextureView; 2], GpuError> {
        self.moments.get_or_try_make(normal_map, |normal_map| {
            let lean = lean_mips(ctx, normal_map)?;
            Ok([
                half_texture(ctx, "LEAN B, Mxx, Myy", &lean, |t| [t.b.x, t.b.y, t.m.x, t.m.z]),
                half_texture(ctx, "LEAN Mxy, J", &lean, |t| [t.m.y, t.j]),
            ])
        })
    }

    /// CLEAN's moments of `normal_map` (`bumpmap_math::lean::LeanMoments::isotropic`), every
    /// level, as one `Rgba16Float` texture: (Bx, By, Mxx + Myy, J), where LEAN needs two.
    pub fn clean_moments(&mut self, ctx: &Context, normal_map: &Arc<Rgba8Mips>) -> Result<wgpu::TextureView, GpuError> {
        self.clean.get_or_try_make(normal_map, |normal_map| {
            let lean = lean_mips(ctx, normal_map)?;
            Ok(half_texture(ctx, "CLEAN B, Mxx + Myy, J", &lean, |t| [t.b.x, t.b.y, t.m.x + t.m.z, t.j]))
        })
    }

    /// The normalization cube map of face size `size` (faces +X, −X, +Y, −Y, +Z, −Z: wgpu's
    /// layer order and face selection are GL's, Kilgard Table 1).
    pub fn cube(&mut self, ctx: &Context, size: usize, encoding: Encoding) -> wgpu::TextureView {
        if let Some((_, v)) = self.cubes.iter().find(|(k, _)| *k == (size, encoding)) {
            return v.clone();
        }
        let map = NormalizationCubeMap::new(size, encoding);
        let t = texture(ctx, "normalization cube map", size, size, 6, 1);
        for (layer, face) in map.faces.iter().enumerate() {
            let image = Rgba8Image::new(size, size, face.iter().map(|&[r, g, b]| [r, g, b, 255]).collect());
            write_level(ctx, &t, 0, layer as u32, &image);
        }
        let view = t.create_view(&wgpu::TextureViewDescriptor {
            label: Some("normalization cube map"),
            dimension: Some(wgpu::TextureViewDimension::Cube),
            array_layer_count: Some(6),
            ..Default::default()
        });
        self.cubes.push(((size, encoding), view.clone()));
        view
    }

    /// Heights as geometry on the device: the heights (`R32Float`) and their min–max bounds
    /// (`Rg32Float`), every level, read with `textureLoad` as `parallax.wgsl` walks them
    /// (heights without bounds get a 1×1 stand-in, which only the exact walk would read, and the
    /// core refuses it there); refused when larger than the adapter allows.
    pub fn heights(&mut self, ctx: &Context, heights: &Arc<HeightMips>) -> Result<[wgpu::TextureView; 2], GpuError> {
        if let Some((_, v)) = self.heights.iter().find(|(h, _)| Arc::ptr_eq(h, heights)) {
            return Ok(v.clone());
        }
        let max = ctx.max_texture_side() as usize;
        let (width, height) = (heights.width(), heights.height());
        if width > max || height > max {
            return Err(GpuError::TooLarge { what: "the heights", width, height, max: max as u32 });
        }
        let levels: Vec<(usize, usize, &[f32])> =
            heights.levels().iter().map(|l| (l.width, l.height, l.texels.as_slice())).collect();
        let bounds = match heights.minmax() {
            Some(m) => {
                let levels: Vec<(usize, usize, &[f32])> =
                    m.iter().map(|l| (l.width, l.height, l.texels.as_flattened())).collect();
                float_texture::<2>(ctx, "height bounds", &levels)
            }
            None => self.no_heights(ctx)[1].clone(),
        };
        let views = [float_texture::<1>(ctx, "heights", &levels), bounds];
        self.heights.push((heights.clone(), views.clone()));
        Ok(views)
    }

    /// The horizon map on the device: directions 0–3 and 4–7 as two `Rgba32Float` textures,
    /// every level, read with `textureLoad` as `parallax.wgsl` filters them; refused when larger
    /// than the adapter allows.
    pub fn horizons(&mut self, ctx: &Context, horizons: &Arc<HorizonMap>) -> Result<[wgpu::TextureView; 2], GpuError> {
        // parallax.wgsl reads the directions as two vec4s.
        const { assert!(bumpmap_math::horizon::AZIMUTHS == 8) };
        if let Some((_, v)) = self.horizons.iter().find(|(h, _)| Arc::ptr_eq(h, horizons)) {
            return Ok(v.clone());
        }
        let max = ctx.max_texture_side() as usize;
        let (width, height) = (horizons.width(), horizons.height());
        if width > max || height > max {
            return Err(GpuError::TooLarge { what: "the horizon map", width, height, max: max as u32 });
        }
        let half = |k: usize| -> Vec<(usize, usize, Vec<f32>)> {
            horizons
                .levels()
                .iter()
                .map(|l| (l.width, l.height, l.texels.iter().flat_map(|t| t[4 * k..4 * k + 4].to_vec()).collect()))
                .collect()
        };
        let texture = |k: usize, label: &str| {
            let levels = half(k);
            let refs: Vec<(usize, usize, &[f32])> = levels.iter().map(|(w, h, v)| (*w, *h, v.as_slice())).collect();
            float_texture::<4>(ctx, label, &refs)
        };
        let views = [texture(0, "horizons 0-3"), texture(1, "horizons 4-7")];
        self.horizons.push((horizons.clone(), views.clone()));
        Ok(views)
    }

    /// 1×1 open horizons for programs without the horizon map's shadows.
    pub fn no_horizons(&mut self, ctx: &Context) -> [wgpu::TextureView; 2] {
        self.no_horizons
            .get_or_insert_with(|| {
                let open = [(1, 1, &[0.0f32; 4][..])];
                [float_texture::<4>(ctx, "no horizons", &open), float_texture::<4>(ctx, "no horizons", &open)]
            })
            .clone()
    }

    /// 1×1 heights and bounds for programs without heights as geometry.
    pub fn no_heights(&mut self, ctx: &Context) -> [wgpu::TextureView; 2] {
        self.no_heights
            .get_or_insert_with(|| {
                [
                    float_texture::<1>(ctx, "no heights", &[(1, 1, &[1.0])]),
                    float_texture::<2>(ctx, "no height bounds", &[(1, 1, &[0.0, 1.0])]),
                ]
            })
            .clone()
    }

    /// A white 1×1 texture: an absent decal or gloss map reads 1.
    pub fn white_2d(&mut self, ctx: &Context) -> wgpu::TextureView {
        self.white_2d
            .get_or_insert_with(|| {
                let t = texture(ctx, "white", 1, 1, 1, 1);
                write_level(ctx, &t, 0, 0, &Rgba8Image::new(1, 1, vec![[255; 4]]));
                t.create_view(&wgpu::TextureViewDescriptor::default())
            })
            .clone()
    }

    /// A white 1×1 cube texture for units that bind none.
    pub fn white_cube(&mut self, ctx: &Context) -> wgpu::TextureView {
        self.white_cube
            .get_or_insert_with(|| {
                let t = texture(ctx, "white cube", 1, 1, 6, 1);
                for layer in 0..6 {
                    write_level(ctx, &t, 0, layer, &Rgba8Image::new(1, 1, vec![[255; 4]]));
                }
                t.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::Cube),
                    array_layer_count: Some(6),
                    ..Default::default()
                })
            })
            .clone()
    }

    /// The wgpu sampler for GL sampler state. GL 1.2's switch-over point c = 0.5 (for a
    /// LINEAR magnification with a NEAREST_MIPMAP minification) has no wgpu equivalent: there
    /// the GPU switches at λ = 0.
    pub fn sampler(&mut self, ctx: &Context, s: Sampler) -> wgpu::Sampler {
        if let Some((_, v)) = self.samplers.iter().find(|(k, _)| *k == s) {
            return v.clone();
        }
        let address = |w| match w {
            WrapMode::Repeat => wgpu::AddressMode::Repeat,
            WrapMode::ClampToEdge => wgpu::AddressMode::ClampToEdge,
            WrapMode::MirroredRepeat => wgpu::AddressMode::MirrorRepeat,
        };
        let filter = |linear| if linear { wgpu::FilterMode::Linear } else { wgpu::FilterMode::Nearest };
        let (min, mip) = match s.min {
            MinFilter::Nearest => (false, None),
            MinFilter::Linear => (true, None),
            MinFilter::NearestMipmapNearest => (false, Some(false)),
            MinFilter::LinearMipmapNearest => (true, Some(false)),
            MinFilter::NearestMipmapLinear => (false, Some(true)),
            MinFilter::LinearMipmapLinear => (true, Some(true)),
        };
        let sampler = ctx.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("sampler"),
            address_mode_u: address(s.wrap_s),
            address_mode_v: address(s.wrap_t),
            address_mode_w: wgpu::AddressMode::ClampToEdge,
            mag_filter: filter(s.mag == MagFilter::Linear),
            min_filter: filter(min),
            mipmap_filter: if mip == Some(true) {
                wgpu::MipmapFilterMode::Linear
            } else {
                wgpu::MipmapFilterMode::Nearest
            },
            // Without a mipmap filter only level 0 is read, as GL's NEAREST and LINEAR do.
            lod_max_clamp: if mip.is_some() { 32.0 } else { 0.0 },
            ..Default::default()
        });
        self.samplers.push((s, sampler.clone()));
        sampler
    }
}
