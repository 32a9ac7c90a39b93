//! NV_register_combiners (v1.7), as the extension specification defines it (SPECS.md §1).
//!
//! The description, not the evaluator: a [`CombinerSetup`] is plain data, written the way
//! `glCombinerInputNV` / `glCombinerOutputNV` calls read, so Kilgard's Appendices G and H can
//! be checked line by line (`setups.rs`). [`CombinerSetup::validate`] checks it against every
//! INVALID_OPERATION / INVALID_VALUE rule of the spec. Each backend evaluates a valid setup its
//! own way (the CPU backend over structure-of-arrays lanes, the GPU backend as generated WGSL)
//! and is tested against the spec's tables. Not described: NV_register_combiners2's per-stage
//! constants.

use crate::lane_math::{clamp_lo, max_lo};
use glam::Vec4;

mod validate;
pub use validate::{CombinerError, MAX_GENERAL_COMBINERS, PortionName};

/// The combiner registers (SPECS.md §1 table), in a fixed order for indexing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Register {
    /// `GL_ZERO`: the constant 0 in every component; read-only.
    Zero,
    /// `GL_CONSTANT_COLOR0_NV`: [`CombinerSetup::constant0`]; read-only.
    ConstantColor0,
    /// `GL_CONSTANT_COLOR1_NV`: [`CombinerSetup::constant1`]; read-only.
    ConstantColor1,
    /// `GL_FOG`: RGB the fog colour, alpha the fog factor (alpha readable only by the final combiner).
    Fog,
    /// `GL_PRIMARY_COLOR_NV`: the interpolated primary colour.
    PrimaryColor,
    /// `GL_SECONDARY_COLOR_NV`: the interpolated secondary colour; its alpha is undefined.
    SecondaryColor,
    /// `GL_SPARE0_NV`: scratch; RGB starts undefined, alpha as texture 0's alpha (if unit 0 is enabled).
    Spare0,
    /// `GL_SPARE1_NV`: scratch, initially undefined.
    Spare1,
    /// `GL_TEXTURE0_ARB`: the filtered texel of texture unit 0.
    Texture0,
    /// `GL_TEXTURE1_ARB`: the filtered texel of texture unit 1.
    Texture1,
    /// `GL_TEXTURE2_ARB`: the filtered texel of texture unit 2.
    Texture2,
    /// `GL_TEXTURE3_ARB`: the filtered texel of texture unit 3.
    Texture3,
}

/// Number of registers (the length of [`Register`]'s order).
pub const REGISTERS: usize = 12;

impl Register {
    /// Every register, in the order of [`Register`] (its index order).
    pub const ALL: [Register; REGISTERS] = [
        Register::Zero,
        Register::ConstantColor0,
        Register::ConstantColor1,
        Register::Fog,
        Register::PrimaryColor,
        Register::SecondaryColor,
        Register::Spare0,
        Register::Spare1,
        Register::Texture0,
        Register::Texture1,
        Register::Texture2,
        Register::Texture3,
    ];

    /// Whether a general combiner may write it (ZERO, the constants and FOG are read-only).
    pub fn writable(self) -> bool {
        !matches!(self, Register::Zero | Register::ConstantColor0 | Register::ConstantColor1 | Register::Fog)
    }

    /// The register of texture unit `i` (0–3).
    pub fn texture(i: usize) -> Register {
        [Register::Texture0, Register::Texture1, Register::Texture2, Register::Texture3][i]
    }
}

/// The eight input mappings (spec table NV_register_combiners.4), applied per component.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum InputMapping {
    /// max(0, e)
    UnsignedIdentity,
    /// 1 − min(max(0, e), 1)
    UnsignedInvert,
    /// 2·max(0, e) − 1
    ExpandNormal,
    /// −2·max(0, e) + 1
    ExpandNegate,
    /// max(0, e) − ½
    HalfBiasNormal,
    /// −max(0, e) + ½
    HalfBiasNegate,
    /// e
    SignedIdentity,
    /// −e
    SignedNegate,
}

/// An input mapping written as `k·min(max(e, lo), hi) + b`: every row of the spec's table has
/// this form, so one branch-free expression evaluates any of them with the same result as
/// [`InputMapping::apply`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine {
    /// The factor.
    pub k: f32,
    /// The offset added after scaling.
    pub b: f32,
    /// The low end of the clamp (−∞ for the signed mappings).
    pub lo: f32,
    /// The high end of the clamp (+∞ for all but UNSIGNED_INVERT).
    pub hi: f32,
}

impl Affine {
    /// `k·clamp(e, lo, hi) + b`; a NaN input takes `lo`.
    #[inline(always)]
    pub fn apply(self, e: f32) -> f32 {
        self.k * clamp_lo(e, self.lo, self.hi) + self.b
    }
}

impl InputMapping {
    /// Every mapping, in the spec table's order.
    pub const ALL: [InputMapping; 8] = [
        InputMapping::UnsignedIdentity,
        InputMapping::UnsignedInvert,
        InputMapping::ExpandNormal,
        InputMapping::ExpandNegate,
        InputMapping::HalfBiasNormal,
        InputMapping::HalfBiasNegate,
        InputMapping::SignedIdentity,
        InputMapping::SignedNegate,
    ];

    /// This mapping as `k·clamp(e, lo, hi) + b`.
    pub fn affine(self) -> Affine {
        let (inf, ninf) = (f32::INFINITY, f32::NEG_INFINITY);
        let (k, b, lo, hi) = match self {
            InputMapping::UnsignedIdentity => (1.0, 0.0, 0.0, inf),
            InputMapping::UnsignedInvert => (-1.0, 1.0, 0.0, 1.0),
            InputMapping::ExpandNormal => (2.0, -1.0, 0.0, inf),
            InputMapping::ExpandNegate => (-2.0, 1.0, 0.0, inf),
            InputMapping::HalfBiasNormal => (1.0, -0.5, 0.0, inf),
            InputMapping::HalfBiasNegate => (-1.0, 0.5, 0.0, inf),
            InputMapping::SignedIdentity => (1.0, 0.0, ninf, inf),
            InputMapping::SignedNegate => (-1.0, 0.0, ninf, inf),
        };
        Affine { k, b, lo, hi }
    }

    #[inline(always)]
    /// f(e) of table NV_register_combiners.4 for one component; a NaN takes 0 wherever the mapping clamps.
    pub fn apply(self, e: f32) -> f32 {
        match self {
            InputMapping::UnsignedIdentity => max_lo(e, 0.0),
            InputMapping::UnsignedInvert => 1.0 - clamp_lo(e, 0.0, 1.0),
            InputMapping::ExpandNormal => 2.0 * max_lo(e, 0.0) - 1.0,
            InputMapping::ExpandNegate => -2.0 * max_lo(e, 0.0) + 1.0,
            InputMapping::HalfBiasNormal => max_lo(e, 0.0) - 0.5,
            InputMapping::HalfBiasNegate => -max_lo(e, 0.0) + 0.5,
            InputMapping::SignedIdentity => e,
            InputMapping::SignedNegate => -e,
        }
    }
}

/// Which components of a register a variable reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ComponentUsage {
    /// R, G, B (RGB portion and final combiner A–F only).
    Rgb,
    /// The alpha, replicated to RGB on the RGB portion.
    Alpha,
    /// The blue, as the alpha portion's value (alpha portion and final G only).
    Blue,
}

/// One variable's source: register, mapping and component usage (`glCombinerInputNV`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Input {
    /// The register read (`GL_ZERO`, `GL_SPARE0_NV`, `GL_TEXTURE0_ARB`, …).
    pub register: Register,
    /// The input mapping applied per component (e.g. `GL_EXPAND_NORMAL_NV`).
    pub mapping: InputMapping,
    /// `GL_RGB`, `GL_ALPHA` or `GL_BLUE`; which are legal depends on the portion.
    pub usage: ComponentUsage,
}

impl Input {
    /// An input as `glCombinerInputNV` takes it; legality is checked by [`CombinerSetup::validate`].
    pub const fn new(register: Register, mapping: InputMapping, usage: ComponentUsage) -> Self {
        Self { register, mapping, usage }
    }

    /// ZERO under UNSIGNED_INVERT: the constant 1.
    pub const fn one(usage: ComponentUsage) -> Self {
        Self::new(Register::Zero, InputMapping::UnsignedInvert, usage)
    }

    /// ZERO under UNSIGNED_IDENTITY: the constant 0.
    pub const fn zero(usage: ComponentUsage) -> Self {
        Self::new(Register::Zero, InputMapping::UnsignedIdentity, usage)
    }
}

/// `GL_SCALE_BY_*` of a portion's outputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scale {
    /// `GL_NONE`: factor 1.
    None,
    /// `GL_SCALE_BY_TWO_NV`: factor 2.
    ByTwo,
    /// `GL_SCALE_BY_FOUR_NV`: factor 4 (not allowed with `GL_BIAS_BY_NEGATIVE_ONE_HALF_NV`).
    ByFour,
    /// `GL_SCALE_BY_ONE_HALF_NV`: factor ½ (not allowed with `GL_BIAS_BY_NEGATIVE_ONE_HALF_NV`).
    ByOneHalf,
}

impl Scale {
    /// The output scale as a factor.
    pub fn factor(self) -> f32 {
        match self {
            Scale::None => 1.0,
            Scale::ByTwo => 2.0,
            Scale::ByFour => 4.0,
            Scale::ByOneHalf => 0.5,
        }
    }
}

/// `GL_BIAS_BY_NEGATIVE_ONE_HALF_NV` or none.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Bias {
    /// `GL_NONE`: no bias.
    None,
    /// `GL_BIAS_BY_NEGATIVE_ONE_HALF_NV`: −½, added before the scale.
    MinusOneHalf,
}

/// One portion's outputs (`glCombinerOutputNV`). `None` as a destination is `GL_DISCARD_NV`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Outputs {
    /// abOutput: the register A·B (or the dot product A•B) is written to.
    pub ab: Option<Register>,
    /// cdOutput: the register C·D (or the dot product C•D) is written to.
    pub cd: Option<Register>,
    /// sumOutput: the register AB + CD (or the mux) is written to.
    pub sum: Option<Register>,
    /// The scale of all three outputs: `out = clamp((x + bias)·scale, −1, 1)`.
    pub scale: Scale,
    /// The bias of all three outputs, added before the scale.
    pub bias: Bias,
    /// abDotProduct: AB is the three-component dot product A•B, replicated to RGB (RGB portion only).
    pub ab_dot: bool,
    /// cdDotProduct: CD is the three-component dot product C•D, replicated to RGB (RGB portion only).
    pub cd_dot: bool,
    /// The mux: `spare0.alpha < ½ ? AB : CD` instead of AB + CD.
    pub mux_sum: bool,
}

impl Outputs {
    /// All three discarded, no scale, bias, dot products or mux.
    pub const DISCARD: Outputs = Outputs {
        ab: None,
        cd: None,
        sum: None,
        scale: Scale::None,
        bias: Bias::None,
        ab_dot: false,
        cd_dot: false,
        mux_sum: false,
    };
}

/// The RGB or alpha half of a general combiner stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Portion {
    /// Variable A, multiplied by B into AB.
    pub a: Input,
    /// Variable B, multiplied by A into AB.
    pub b: Input,
    /// Variable C, multiplied by D into CD.
    pub c: Input,
    /// Variable D, multiplied by C into CD.
    pub d: Input,
    /// Where AB, CD and their sum go, with the scale and bias (`glCombinerOutputNV`).
    pub outputs: Outputs,
}

impl Portion {
    /// All four variables 0 and all three outputs discarded: a portion that does nothing.
    pub const fn discarded(usage: ComponentUsage) -> Self {
        Portion {
            a: Input::zero(usage),
            b: Input::zero(usage),
            c: Input::zero(usage),
            d: Input::zero(usage),
            outputs: Outputs::DISCARD,
        }
    }

    /// The spec's initial state: A = PRIMARY_COLOR, B = ZERO inverted (1), C = D = 0, sum → SPARE0.
    pub const fn initial(usage: ComponentUsage) -> Self {
        Portion {
            a: Input::new(Register::PrimaryColor, InputMapping::UnsignedIdentity, usage),
            b: Input::one(usage),
            c: Input::zero(usage),
            d: Input::zero(usage),
            outputs: Outputs { sum: Some(Register::Spare0), ..Outputs::DISCARD },
        }
    }
}

/// A general combiner stage: its RGB and alpha portions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct GeneralStage {
    /// The RGB portion (`GL_RGB`): RGB or ALPHA usage, dot products allowed.
    pub rgb: Portion,
    /// The alpha portion (`GL_ALPHA`): ALPHA or BLUE usage, no dot products.
    pub alpha: Portion,
}

impl Default for GeneralStage {
    fn default() -> Self {
        Self { rgb: Portion::initial(ComponentUsage::Rgb), alpha: Portion::initial(ComponentUsage::Alpha) }
    }
}

/// A final-combiner variable's source: a register or one of the two pseudo-registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FinalSource {
    /// A register as the last general stage left it.
    Register(Register),
    /// `GL_E_TIMES_F_NV`: E·F after their mappings (A–D only).
    ETimesF,
    /// `GL_SPARE0_PLUS_SECONDARY_COLOR_NV` (B–D only).
    Spare0PlusSecondary,
}

/// One final-combiner variable (`glFinalCombinerInputNV`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FinalInput {
    /// The register or pseudo-register read.
    pub source: FinalSource,
    /// Only `UnsignedIdentity` and `UnsignedInvert` are legal here.
    pub mapping: InputMapping,
    /// RGB or ALPHA for A–F (RGB only for a pseudo-register); ALPHA or BLUE for G.
    pub usage: ComponentUsage,
}

impl FinalInput {
    /// `register` under `GL_UNSIGNED_IDENTITY_NV` with the given component usage.
    pub const fn reg(register: Register, usage: ComponentUsage) -> Self {
        Self { source: FinalSource::Register(register), mapping: InputMapping::UnsignedIdentity, usage }
    }

    /// `GL_ZERO`, RGB, unsigned identity: the constant 0.
    pub const ZERO: FinalInput = FinalInput::reg(Register::Zero, ComponentUsage::Rgb);
    /// `GL_E_TIMES_F_NV`, RGB, unsigned identity; legal for variables A–D only.
    pub const E_TIMES_F: FinalInput = FinalInput {
        source: FinalSource::ETimesF,
        mapping: InputMapping::UnsignedIdentity,
        usage: ComponentUsage::Rgb,
    };
}

/// The final combiner: `rgb = min(A·B + (1−A)·C + D, 1)`, `alpha = G`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FinalCombiner {
    /// Variable A: the blend factor between B and C.
    pub a: FinalInput,
    /// Variable B, weighted by A.
    pub b: FinalInput,
    /// Variable C, weighted by 1 − A.
    pub c: FinalInput,
    /// Variable D, added after the blend.
    pub d: FinalInput,
    /// Variable E, the first factor of `GL_E_TIMES_F_NV`.
    pub e: FinalInput,
    /// Variable F, the second factor of `GL_E_TIMES_F_NV`.
    pub f: FinalInput,
    /// Variable G: the fragment's alpha (ALPHA or BLUE usage).
    pub g: FinalInput,
    /// `GL_COLOR_SUM_CLAMP_NV` (default true): clamp spare0 + secondary to [0, 1].
    pub color_sum_clamp: bool,
}

impl Default for FinalCombiner {
    /// The spec's initial state: the GL 1.2 colour sum and fog.
    fn default() -> Self {
        FinalCombiner {
            a: FinalInput::reg(Register::Fog, ComponentUsage::Alpha),
            b: FinalInput { source: FinalSource::Spare0PlusSecondary, ..FinalInput::ZERO },
            c: FinalInput::reg(Register::Fog, ComponentUsage::Rgb),
            d: FinalInput::ZERO,
            e: FinalInput::ZERO,
            f: FinalInput::ZERO,
            g: FinalInput::reg(Register::Spare0, ComponentUsage::Alpha),
            color_sum_clamp: true,
        }
    }
}

/// The whole register-combiner state of one pass.
#[derive(Clone, Debug, PartialEq)]
pub struct CombinerSetup {
    /// The enabled general stages; `len()` is `GL_NUM_GENERAL_COMBINERS_NV`.
    pub stages: Vec<GeneralStage>,
    /// The final combiner, which turns the last stage's registers into the fragment colour.
    pub final_combiner: FinalCombiner,
    /// `GL_CONSTANT_COLOR0_NV` / `1_NV`, clamped to [0, 1] when set (as the GL does).
    pub constant0: Vec4,
    /// `GL_CONSTANT_COLOR1_NV`, likewise.
    pub constant1: Vec4,
}

impl CombinerSetup {
    /// Whether any variable of a general stage or of the final combiner reads `register`
    /// (`GL_SPARE0_PLUS_SECONDARY_COLOR_NV` reads SPARE0 and SECONDARY_COLOR).
    pub fn reads(&self, register: Register) -> bool {
        let stages = self.stages.iter().flat_map(|s| [s.rgb, s.alpha]).flat_map(|p| [p.a, p.b, p.c, p.d]);
        let f = &self.final_combiner;
        stages.clone().any(|i| i.register == register)
            || [f.a, f.b, f.c, f.d, f.e, f.f, f.g].iter().any(|i| match i.source {
                FinalSource::Register(r) => r == register,
                FinalSource::ETimesF => false,
                FinalSource::Spare0PlusSecondary => matches!(register, Register::Spare0 | Register::SecondaryColor),
            })
    }
}

impl Default for CombinerSetup {
    fn default() -> Self {
        Self {
            stages: vec![GeneralStage::default()],
            final_combiner: FinalCombiner::default(),
            constant0: Vec4::ZERO,
            constant1: Vec4::ZERO,
        }
    }
}

/// Arithmetic precision of the emulated datapath.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Precision {
    /// Single-precision floats in [−1, 1] (the spec is written as if this).
    #[default]
    Float,
    /// NV10's 9-bit signed fixed point: every mapped input and every stage output is rounded to
    /// a multiple of 1/255 in [−1, 1] (8 bits of magnitude plus a sign, so 8-bit texels and 1
    /// stay exact).
    Fixed9,
}

bumpmap_math::named!(Precision {
    Float => "float": "Single-precision combiners",
    Fixed9 => "fixed9": "The GeForce 256's 9-bit signed fixed point",
});

impl Precision {
    /// [`Precision::Fixed9`]'s rounding: `x` clamped to [−1, 1] and rounded (half away from
    /// zero) to a multiple of 1/255.
    #[inline(always)]
    pub fn quantize_fixed9(x: f32) -> f32 {
        (x.clamp(-1.0, 1.0) * 255.0).round() / 255.0
    }
}
