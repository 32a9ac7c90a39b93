//! GL state as data: what a pass sets with `glDepthFunc`, `glDepthMask`, `glBlendFunc`,
//! `glBlendColor`, `glColorMask`, `glCullFace`, and each texture unit's filter and wrap modes.
//!
//! These are the definitions; a backend maps them onto its own machinery (the CPU pipeline's
//! vector loops, wgpu's pipeline state) and is tested against the functions here. Only the
//! state the techniques use is described: no stencil, no alpha test, no logic ops, no border
//! colour (CLAMP without _TO_EDGE), no LOD bias, no anisotropy.

use crate::lane_math::clamp_lo;

/// `glDepthFunc` values used by the techniques.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthFunc {
    /// `GL_ALWAYS`.
    Always,
    /// `GL_LESS`, the default.
    Less,
    /// `GL_LEQUAL`.
    LEqual,
    /// `GL_EQUAL`: the later passes of a multipass technique.
    Equal,
}

impl DepthFunc {
    /// Whether a fragment at depth `fragment` passes against the `stored` depth.
    #[inline(always)]
    pub fn passes(self, fragment: f32, stored: f32) -> bool {
        match self {
            DepthFunc::Always => true,
            DepthFunc::Less => fragment < stored,
            DepthFunc::LEqual => fragment <= stored,
            DepthFunc::Equal => fragment == stored,
        }
    }
}

/// GL 1.2 blend factors (the imaging subset's constant colour included).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlendFactor {
    /// `GL_ZERO`.
    Zero,
    /// `GL_ONE`.
    One,
    /// `GL_SRC_COLOR`.
    SrcColor,
    /// `GL_DST_COLOR`.
    DstColor,
    /// `GL_SRC_ALPHA`.
    SrcAlpha,
    /// `GL_DST_ALPHA`.
    DstAlpha,
    /// `GL_ONE_MINUS_SRC_ALPHA`.
    OneMinusSrcAlpha,
    /// `GL_CONSTANT_COLOR` with the blend colour of [`Blend`].
    ConstantColor,
}

/// `glBlendFunc(src, dst)` and `glBlendColor`; [`Blend::REPLACE`] is blending disabled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blend {
    /// The source factor.
    pub src: BlendFactor,
    /// The destination factor.
    pub dst: BlendFactor,
    /// `glBlendColor`, read by [`BlendFactor::ConstantColor`].
    pub color: [f32; 4],
}

impl Blend {
    /// Blending disabled: the fragment replaces the pixel.
    pub const REPLACE: Blend = Blend::new(BlendFactor::One, BlendFactor::Zero);
    /// Pass 2 of the paper: `glBlendFunc(GL_DST_COLOR, GL_ZERO)`.
    pub const MODULATE: Blend = Blend::new(BlendFactor::DstColor, BlendFactor::Zero);
    /// Pass 3 of the paper: `glBlendFunc(GL_DST_ALPHA, GL_ONE)`.
    pub const ADD_BY_DST_ALPHA: Blend = Blend::new(BlendFactor::DstAlpha, BlendFactor::One);
    /// `glBlendFunc(GL_ONE, GL_ONE)`: each further light of the single pass.
    pub const ADD: Blend = Blend::new(BlendFactor::One, BlendFactor::One);

    /// `glBlendFunc(src, dst)` with a zero blend colour.
    pub const fn new(src: BlendFactor, dst: BlendFactor) -> Self {
        Self { src, dst, color: [0.0; 4] }
    }

    /// The value of factor `f` for channel `c` (0–3), given the clamped source colour and the
    /// stored destination colour, both in [0, 1].
    #[inline(always)]
    pub fn factor(&self, f: BlendFactor, src: [f32; 4], dst: [f32; 4], c: usize) -> f32 {
        match f {
            BlendFactor::Zero => 0.0,
            BlendFactor::One => 1.0,
            BlendFactor::SrcColor => src[c],
            BlendFactor::DstColor => dst[c],
            BlendFactor::SrcAlpha => src[3],
            BlendFactor::DstAlpha => dst[3],
            BlendFactor::OneMinusSrcAlpha => 1.0 - src[3],
            BlendFactor::ConstantColor => self.color[c],
        }
    }

    /// The blend equation `src·S + dst·D` per channel, before the framebuffer rounds it. The
    /// fragment colour is clamped to [0, 1] first, as the GL does for a fixed-point buffer.
    #[inline(always)]
    pub fn equation(&self, src: [f32; 4], dst: [f32; 4]) -> [f32; 4] {
        let src = src.map(|v| clamp_lo(v, 0.0, 1.0));
        std::array::from_fn(|c| {
            src[c] * self.factor(self.src, src, dst, c) + dst[c] * self.factor(self.dst, src, dst, c)
        })
    }
}

/// The fixed-function state of one pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PassState {
    /// `glDepthFunc`.
    pub depth_func: DepthFunc,
    /// `glDepthMask`.
    pub depth_write: bool,
    /// `glBlendFunc` and `glBlendColor`.
    pub blend: Blend,
    /// `glColorMask(r, g, b, a)`.
    pub color_mask: [bool; 4],
    /// `glEnable(GL_CULL_FACE)` with `glCullFace(GL_BACK)`, counter-clockwise front faces.
    pub cull_back: bool,
}

impl PassState {
    /// Depth LESS with writes, no blending, back faces culled: an ordinary first pass.
    pub const OPAQUE: PassState = PassState {
        depth_func: DepthFunc::Less,
        depth_write: true,
        blend: Blend::REPLACE,
        color_mask: [true; 4],
        cull_back: true,
    };

    /// Depth EQUAL without writes, blended by `blend`: a later pass over the same surfaces.
    pub const fn equal(blend: Blend) -> PassState {
        PassState { depth_func: DepthFunc::Equal, depth_write: false, blend, color_mask: [true; 4], cull_back: true }
    }
}

/// `GL_TEXTURE_MIN_FILTER` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MinFilter {
    /// `GL_NEAREST`: level 0, nearest texel.
    Nearest,
    /// `GL_LINEAR`: level 0, bilinear.
    Linear,
    /// `GL_NEAREST_MIPMAP_NEAREST`.
    NearestMipmapNearest,
    /// `GL_LINEAR_MIPMAP_NEAREST`.
    LinearMipmapNearest,
    /// `GL_NEAREST_MIPMAP_LINEAR`.
    NearestMipmapLinear,
    /// `GL_LINEAR_MIPMAP_LINEAR`: trilinear, the paper's choice.
    LinearMipmapLinear,
}

impl MinFilter {
    /// Whether the filter reads levels other than 0.
    pub fn uses_mipmaps(self) -> bool {
        !matches!(self, MinFilter::Nearest | MinFilter::Linear)
    }
}

/// `GL_TEXTURE_MAG_FILTER` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MagFilter {
    /// `GL_NEAREST`.
    Nearest,
    /// `GL_LINEAR`.
    Linear,
}

/// `GL_TEXTURE_WRAP_S/T` values emulated here.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WrapMode {
    /// `GL_REPEAT`.
    Repeat,
    /// `GL_CLAMP_TO_EDGE`.
    ClampToEdge,
}

/// Filter and wrap state of a texture unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sampler {
    /// `GL_TEXTURE_MIN_FILTER`.
    pub min: MinFilter,
    /// `GL_TEXTURE_MAG_FILTER`.
    pub mag: MagFilter,
    /// `GL_TEXTURE_WRAP_S`.
    pub wrap_s: WrapMode,
    /// `GL_TEXTURE_WRAP_T`.
    pub wrap_t: WrapMode,
}

impl Sampler {
    /// `GL_LINEAR_MIPMAP_LINEAR` / `GL_LINEAR`, repeating: the paper's normal-map and decal state.
    pub const TRILINEAR_REPEAT: Sampler = Sampler {
        min: MinFilter::LinearMipmapLinear,
        mag: MagFilter::Linear,
        wrap_s: WrapMode::Repeat,
        wrap_t: WrapMode::Repeat,
    };
    /// `GL_LINEAR` both ways, repeating, no mipmaps.
    pub const LINEAR_REPEAT: Sampler =
        Sampler { min: MinFilter::Linear, mag: MagFilter::Linear, wrap_s: WrapMode::Repeat, wrap_t: WrapMode::Repeat };
    /// `GL_NEAREST` both ways, repeating.
    pub const NEAREST_REPEAT: Sampler = Sampler {
        min: MinFilter::Nearest,
        mag: MagFilter::Nearest,
        wrap_s: WrapMode::Repeat,
        wrap_t: WrapMode::Repeat,
    };
    /// `GL_LINEAR`, `GL_CLAMP_TO_EDGE`: the normalization cube map's state (Appendix D).
    pub const LINEAR_CLAMP: Sampler = Sampler {
        min: MinFilter::Linear,
        mag: MagFilter::Linear,
        wrap_s: WrapMode::ClampToEdge,
        wrap_t: WrapMode::ClampToEdge,
    };

    /// The level `*_MIPMAP_NEAREST` reads at λ (GL 1.2 §3.8.9): 0 for λ ≤ ½, else ⌈λ + ½⌉ − 1,
    /// at most `last` (and `last` for a NaN λ).
    ///
    /// ```
    /// use bumpmap_core::state::Sampler;
    /// assert_eq!([0.3, 0.51, 1.49, 1.51, 9.0].map(|l| Sampler::nearest_level(l, 4)), [0, 1, 1, 2, 4]);
    /// ```
    #[inline(always)]
    pub fn nearest_level(lambda: f32, last: usize) -> usize {
        if lambda <= 0.5 { 0 } else { ((lambda + 0.5).ceil() - 1.0).min(last as f32) as usize }
    }

    /// Whether the minification filter reads mip levels.
    pub fn has_mipmaps(&self) -> bool {
        !matches!(self.min, MinFilter::Nearest | MinFilter::Linear)
    }

    /// The magnification/minification switch-over point c (GL 1.2 §3.8.8): λ ≤ c magnifies.
    pub fn switch_over(&self) -> f32 {
        let nearest_mip = matches!(self.min, MinFilter::NearestMipmapNearest | MinFilter::NearestMipmapLinear);
        if self.mag == MagFilter::Linear && nearest_mip { 0.5 } else { 0.0 }
    }
}
