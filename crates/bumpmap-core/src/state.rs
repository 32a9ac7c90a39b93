//! GL state as data: what a pass sets with `glDepthFunc`, `glDepthMask`, `glBlendFunc`,
//! `glBlendColor`, `glColorMask`, `glCullFace`, and each texture unit's filter and wrap modes.
//!
//! These are the definitions; a backend maps them onto its own machinery (the CPU pipeline's
//! vector loops, wgpu's pipeline state) and is tested against the functions here. Only the
//! state the techniques use is described: no stencil, no logic ops, no border colour (CLAMP
//! without _TO_EDGE), no LOD bias, no anisotropy; the alpha test only as `GL_GEQUAL` (a glTF
//! `alphaMode` MASK's cut).

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
    /// `glEnable(GL_ALPHA_TEST)` with `glAlphaFunc(GL_GEQUAL, cutoff)`: a fragment whose alpha
    /// (clamped to [0, 1]) is below the cutoff is discarded, its depth not written; `None`:
    /// disabled.
    pub alpha_test: Option<f32>,
}

impl PassState {
    /// Depth LESS with writes, no blending, back faces culled: an ordinary first pass.
    pub const OPAQUE: PassState = PassState {
        depth_func: DepthFunc::Less,
        depth_write: true,
        blend: Blend::REPLACE,
        color_mask: [true; 4],
        cull_back: true,
        alpha_test: None,
    };

    /// Depth EQUAL without writes, blended by `blend`: a later pass over the same surfaces.
    pub const fn equal(blend: Blend) -> PassState {
        PassState {
            depth_func: DepthFunc::Equal,
            depth_write: false,
            blend,
            color_mask: [true; 4],
            cull_back: true,
            alpha_test: None,
        }
    }

    /// Whether a fragment of alpha `a` passes this pass's alpha test (always, where disabled).
    #[inline(always)]
    pub fn alpha_passes(&self, a: f32) -> bool {
        self.alpha_test.is_none_or(|cutoff| a.clamp(0.0, 1.0) >= cutoff)
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
    /// `GL_MIRRORED_REPEAT` (GL 1.4): every other repeat mirrored. The same lookups as
    /// CLAMP_TO_EDGE at the coordinate folded into [0, 1] ([`WrapMode::mirror`]), filters and
    /// levels included (GL 4.6 §8.14.2's integer form gives the same texels and weights).
    MirroredRepeat,
}

impl WrapMode {
    /// The mode a GL enum names (`GL_REPEAT` 10497, `GL_CLAMP_TO_EDGE` 33071,
    /// `GL_MIRRORED_REPEAT` 33648: the numbers glTF's samplers store), if it is one.
    pub fn from_gl(code: u32) -> Option<Self> {
        match code {
            10497 => Some(WrapMode::Repeat),
            33071 => Some(WrapMode::ClampToEdge),
            33648 => Some(WrapMode::MirroredRepeat),
            _ => None,
        }
    }

    /// MIRRORED_REPEAT's fold of a texture coordinate into [0, 1]: `s` on even repeats,
    /// `1 − frac(s)` on odd ones (a NaN stays NaN, for the lookup's own handling).
    ///
    /// ```
    /// use bumpmap_core::state::WrapMode;
    /// assert_eq!([0.25, 1.25, 2.25, -0.25].map(WrapMode::mirror), [0.25, 0.75, 0.25, 0.25]);
    /// ```
    #[inline(always)]
    pub fn mirror(s: f32) -> f32 {
        let t = s - 2.0 * (0.5 * s).floor();
        1.0 - (t - 1.0).abs()
    }
}

/// A material's own sampler state, a glTF sampler's: wrap modes, and filters where the file
/// names them (else the technique's own).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MaterialSampler {
    /// `wrapS`.
    pub wrap_s: WrapMode,
    /// `wrapT`.
    pub wrap_t: WrapMode,
    /// `minFilter`, if named.
    pub min: Option<MinFilter>,
    /// `magFilter`, if named.
    pub mag: Option<MagFilter>,
}

impl Default for MaterialSampler {
    /// Repeating, the technique's filters: what a glTF texture without a sampler gets.
    fn default() -> Self {
        Self { wrap_s: WrapMode::Repeat, wrap_t: WrapMode::Repeat, min: None, mag: None }
    }
}

impl MinFilter {
    /// The filter a GL enum names (`GL_NEAREST` 9728 … `GL_LINEAR_MIPMAP_LINEAR` 9987), if any.
    pub fn from_gl(code: u32) -> Option<Self> {
        Some(match code {
            9728 => MinFilter::Nearest,
            9729 => MinFilter::Linear,
            9984 => MinFilter::NearestMipmapNearest,
            9985 => MinFilter::LinearMipmapNearest,
            9986 => MinFilter::NearestMipmapLinear,
            9987 => MinFilter::LinearMipmapLinear,
            _ => return None,
        })
    }
}

impl MagFilter {
    /// The filter a GL enum names (`GL_NEAREST` 9728, `GL_LINEAR` 9729), if any.
    pub fn from_gl(code: u32) -> Option<Self> {
        match code {
            9728 => Some(MagFilter::Nearest),
            9729 => Some(MagFilter::Linear),
            _ => None,
        }
    }
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

    /// This state with a material's own: its wrap modes, and its filters where it names them.
    pub fn for_material(self, m: &MaterialSampler) -> Sampler {
        Sampler { min: m.min.unwrap_or(self.min), mag: m.mag.unwrap_or(self.mag), wrap_s: m.wrap_s, wrap_t: m.wrap_t }
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
