//! The paper's combiner setups as data, written to be read next to Kilgard Appendices G and H.
//!
//! Each `Input::new(register, mapping, usage)` is one `glCombinerInputNV` call and each
//! `Outputs { … }` one `glCombinerOutputNV` call, in the appendices' order.

use glam::Vec4;

use crate::combiners::{
    Bias, CombinerSetup, ComponentUsage::*, FinalCombiner, FinalInput, GeneralStage, Input, InputMapping::*, Outputs,
    Portion, Register::*, Scale,
};

/// Pass 1, the decal: `rgb = texture0.rgb`, `alpha = texture0.alpha` (what `GL_REPLACE` gives).
pub fn decal() -> CombinerSetup {
    let pass_through = Portion::discarded(Rgb);
    let stage = GeneralStage { rgb: pass_through, alpha: Portion::discarded(Alpha) };
    let final_combiner = FinalCombiner {
        a: FinalInput::ZERO,
        b: FinalInput::ZERO,
        c: FinalInput::ZERO,
        d: FinalInput::reg(Texture0, Rgb),
        e: FinalInput::ZERO,
        f: FinalInput::ZERO,
        g: FinalInput::reg(Texture0, Alpha),
        color_sum_clamp: true,
    };
    CombinerSetup { stages: vec![stage], final_combiner, constant0: Vec4::ZERO, constant1: Vec4::ZERO }
}

/// Pass 1 for vertices with colours: the decal times the interpolated colour, RGB and alpha
/// (`texture0 · PRIMARY_COLOR`, what `GL_MODULATE` gives with a colour array; glTF's
/// `baseColorTexture · COLOR_0`), or the colour alone without a texture (`textured` false).
pub fn vertex_colored_decal(textured: bool) -> CombinerSetup {
    let texel = |usage| if textured { Input::new(Texture0, UnsignedIdentity, usage) } else { Input::one(usage) };
    let times_color = |usage| Portion {
        a: texel(usage),
        b: Input::new(PrimaryColor, UnsignedIdentity, usage),
        c: Input::zero(usage),
        d: Input::zero(usage),
        outputs: Outputs { ab: Some(Spare0), ..Outputs::DISCARD },
    };
    let mut setup = decal();
    setup.stages[0] = GeneralStage { rgb: times_color(Rgb), alpha: times_color(Alpha) };
    setup.final_combiner.d = FinalInput::reg(Spare0, Rgb);
    setup.final_combiner.g = FinalInput::reg(Spare0, Alpha);
    setup
}

/// A material's emission added after its lit passes (glTF `emissiveTexture`, the factor folded
/// into the texels): texture 0's RGB; alpha texture 1's (the decal's, for a blended material,
/// under `glBlendFunc(GL_SRC_ALPHA, GL_ONE)`) or 1.
pub fn emission(alpha_from_texture1: bool) -> CombinerSetup {
    let mut setup = decal();
    setup.final_combiner.g = if alpha_from_texture1 {
        FinalInput::reg(Texture1, Alpha)
    } else {
        FinalInput { mapping: UnsignedInvert, ..FinalInput::reg(Zero, Alpha) }
    };
    setup
}

/// `setup` (Appendix G's, [`ambient_and_diffuse`]) with the ambient term multiplied by
/// texture 2's RGB, an occlusion map: stage 1's free C·D makes `spare1 = I_ambient · occlusion`,
/// which the final combiner adds in place of the constant.
pub fn with_ambient_occlusion(mut setup: CombinerSetup) -> CombinerSetup {
    let rgb = &mut setup.stages[1].rgb;
    rgb.c = Input::new(ConstantColor0, UnsignedIdentity, Rgb);
    rgb.d = Input::new(Texture2, UnsignedIdentity, Rgb);
    rgb.outputs.cd = Some(Spare1);
    setup.final_combiner.d = FinalInput::reg(Spare1, Rgb);
    setup
}

/// The RGB portion both appendices open with: `spare0rgb = expand(texture0) · expand(texture1)`,
/// the normal map's N' dotted with the cube map's normalized L (Appendix G) or H (Appendix H).
fn normal_dot_cube() -> Portion {
    Portion {
        a: Input::new(Texture0, ExpandNormal, Rgb),
        b: Input::new(Texture1, ExpandNormal, Rgb),
        c: Input::zero(Rgb),
        d: Input::zero(Rgb),
        outputs: Outputs { ab: Some(Spare0), ab_dot: true, ..Outputs::DISCARD },
    }
}

/// Kilgard Appendix G (§5.4): ambient + diffuse with the self-shadowing term, Eq. 11 and 12.
/// Texture 0 is the normal map, texture 1 the normalization cube map indexed by L.
///
/// `ambient` is `I_ambient` (constant colour 0) and `diffuse` is `k_diffuse` (constant colour
/// 1); the appendix uses (0.1, 0.1, 0.1) and (0.9, 1.0, 1.0).
pub fn ambient_and_diffuse(ambient: Vec4, diffuse: Vec4) -> CombinerSetup {
    let stage0 = GeneralStage {
        // Argb = expand(texture0rgb) = N'; Brgb = expand(texture1rgb) = L; spare0rgb = A·B.
        rgb: normal_dot_cube(),
        // Aa = 1, Ba = expand(texture1b) = Lz, Ca = 1, Da = Lz; spare0a = 4·(Lz + Lz) = 8·Lz.
        alpha: Portion {
            a: Input::new(Zero, UnsignedInvert, Alpha),
            b: Input::new(Texture1, ExpandNormal, Blue),
            c: Input::new(Zero, UnsignedInvert, Alpha),
            d: Input::new(Texture1, ExpandNormal, Blue),
            outputs: Outputs { sum: Some(Spare0), scale: Scale::ByFour, ..Outputs::DISCARD },
        },
    };
    let stage1 = GeneralStage {
        // Argb = spare0rgb = L·N' clamped ≥ 0; Brgb = texture0 alpha = the mip length factor.
        rgb: Portion {
            a: Input::new(Spare0, UnsignedIdentity, Rgb),
            b: Input::new(Texture0, UnsignedIdentity, Alpha),
            c: Input::zero(Rgb),
            d: Input::zero(Rgb),
            outputs: Outputs { ab: Some(Spare0), ..Outputs::DISCARD },
        },
        alpha: Portion::discarded(Alpha),
    };
    // rgb = A·EF + D = s_self·k_diffuse·max(0, L·N')·|N'| + I_ambient; alpha = G = s_self.
    let final_combiner = FinalCombiner {
        a: FinalInput::reg(Spare0, Alpha),
        b: FinalInput::E_TIMES_F,
        c: FinalInput::ZERO,
        d: FinalInput::reg(ConstantColor0, Rgb),
        e: FinalInput::reg(ConstantColor1, Rgb),
        f: FinalInput::reg(Spare0, Rgb),
        g: FinalInput::reg(Spare0, Alpha),
        color_sum_clamp: true,
    };
    CombinerSetup { stages: vec![stage0, stage1], final_combiner, constant0: ambient, constant1: diffuse }
}

/// The same pass without the self-shadowing term (Figure 14, left): spare0 alpha = 1.
pub fn ambient_and_diffuse_unshadowed(ambient: Vec4, diffuse: Vec4) -> CombinerSetup {
    let mut setup = ambient_and_diffuse(ambient, diffuse);
    let alpha = &mut setup.stages[0].alpha;
    alpha.b = Input::one(Alpha);
    alpha.c = Input::zero(Alpha);
    alpha.outputs = Outputs { sum: Some(Spare0), ..Outputs::DISCARD };
    setup
}

/// Kilgard Appendix H (§5.5): the specular `max(0, H·N')^8` by squaring, zeroed by the mux where
/// the unperturbed `H·N = H_z` is negative. Texture 0 is the normal map, texture 1 the cube map
/// indexed by H.
pub fn specular() -> CombinerSetup {
    let stage0 = GeneralStage {
        // spare0rgb = expand(texture0rgb) · expand(texture1rgb) = N'·H.
        rgb: normal_dot_cube(),
        // spare0a = texture1b · 1 = unexpanded Hz (≥ ½ exactly when Hz ≥ 0).
        alpha: Portion {
            a: Input::new(Texture1, UnsignedIdentity, Blue),
            b: Input::new(Zero, UnsignedInvert, Alpha),
            c: Input::zero(Alpha),
            d: Input::zero(Alpha),
            outputs: Outputs { ab: Some(Spare0), ..Outputs::DISCARD },
        },
    };
    let stage1 = GeneralStage {
        // spare0rgb = (spare0a ≥ ½) ? spare0rgb² : 0 via the mux (A = B = 0, C = D = H·N').
        rgb: Portion {
            a: Input::zero(Rgb),
            b: Input::zero(Rgb),
            c: Input::new(Spare0, UnsignedIdentity, Rgb),
            d: Input::new(Spare0, SignedIdentity, Rgb),
            outputs: Outputs { sum: Some(Spare0), mux_sum: true, ..Outputs::DISCARD },
        },
        alpha: Portion::discarded(Alpha),
    };
    // rgb = A·B = (E·F)·(E·F) = (H·N')^8; alpha = 0.
    let final_combiner = FinalCombiner {
        a: FinalInput::E_TIMES_F,
        b: FinalInput::E_TIMES_F,
        c: FinalInput::ZERO,
        d: FinalInput::ZERO,
        e: FinalInput::reg(Spare0, Rgb),
        f: FinalInput::reg(Spare0, Rgb),
        g: FinalInput::reg(Zero, Alpha),
        color_sum_clamp: true,
    };
    CombinerSetup { stages: vec![stage0, stage1], final_combiner, constant0: Vec4::ZERO, constant1: Vec4::ZERO }
}

/// §5.5's steeper alternative to the eighth power: `max(0, 4·(max(0, H·N') − ¾))²`.
///
/// The mux can only choose between two products, and the ramp is a sum, so the H_z test becomes
/// a steep gate instead: stage 1's alpha computes `clamp(4·(H_z' − ½))` from the unexpanded
/// `H_z'` (0 for H_z ≤ 0, 1 from H_z ≥ ½), and the final combiner multiplies by it. Constant 0
/// holds the offsets (¾ in RGB, ½ in alpha).
pub fn specular_ramp() -> CombinerSetup {
    let mut setup = specular();
    setup.constant0 = Vec4::new(0.75, 0.75, 0.75, 0.5);
    // Stage 1 RGB: spare0rgb = 4·(max(0, H·N')·1 + (−¾)·1).
    setup.stages[1].rgb = Portion {
        a: Input::new(Spare0, UnsignedIdentity, Rgb),
        b: Input::one(Rgb),
        c: Input::new(ConstantColor0, SignedNegate, Rgb),
        d: Input::one(Rgb),
        outputs: Outputs { sum: Some(Spare0), scale: Scale::ByFour, ..Outputs::DISCARD },
    };
    // Stage 1 alpha: spare0a = 4·(H_z'·1 + (−½)·1), the gate.
    setup.stages[1].alpha = Portion {
        a: Input::new(Spare0, UnsignedIdentity, Alpha),
        b: Input::one(Alpha),
        c: Input::new(ConstantColor0, SignedNegate, Alpha),
        d: Input::one(Alpha),
        outputs: Outputs { sum: Some(Spare0), scale: Scale::ByFour, bias: Bias::None, ..Outputs::DISCARD },
    };
    // rgb = (E·F)·gate with E = F = max(0, ramp).
    setup.final_combiner.a = FinalInput::E_TIMES_F;
    setup.final_combiner.b = FinalInput::reg(Spare0, Alpha);
    setup
}

/// Embossing (Kilgard §3.1, Eq. 29–30) in two general combiners: texture 0 is the height map
/// at (s, t), texture 1 the same map at (s, t) shifted toward the light by (L_x, L_y) texels,
/// texture 2 the cube map indexed by L. `scale` is the bump scale (1, 2 or 4: the combiners'
/// output scales).
///
/// `diffuse ≈ L_z − scale·(∂F/∂x·L_x + ∂F/∂y·L_y) ≈ L_z + scale·(F(s, t) − F(shifted))`, then
/// `rgb = I_ambient + k_diffuse · max(0, diffuse)`, alpha 0. Every intermediate clamps to
/// [−1, 1] and the sum to [0, 1], as the hardware did.
pub fn emboss(scale: Scale, ambient: Vec4, diffuse: Vec4) -> CombinerSetup {
    let stage0 = GeneralStage {
        // spare0rgb = scale·(texture0 − texture1): F(s, t) − F(s + L_x, t + L_y).
        rgb: Portion {
            a: Input::new(Texture0, UnsignedIdentity, Rgb),
            b: Input::one(Rgb),
            c: Input::new(Texture1, SignedNegate, Rgb),
            d: Input::one(Rgb),
            outputs: Outputs { sum: Some(Spare0), scale, ..Outputs::DISCARD },
        },
        // spare0a = expand(texture2b) = L_z (BLUE may be read by the alpha portion only).
        alpha: Portion {
            a: Input::new(Texture2, ExpandNormal, Blue),
            b: Input::one(Alpha),
            c: Input::zero(Alpha),
            d: Input::zero(Alpha),
            outputs: Outputs { ab: Some(Spare0), ..Outputs::DISCARD },
        },
    };
    let stage1 = GeneralStage {
        // spare0rgb = spare0rgb + spare0a = the difference + L_z.
        rgb: Portion {
            a: Input::new(Spare0, SignedIdentity, Rgb),
            b: Input::one(Rgb),
            c: Input::new(Spare0, SignedIdentity, Alpha),
            d: Input::one(Rgb),
            outputs: Outputs { sum: Some(Spare0), ..Outputs::DISCARD },
        },
        alpha: Portion::discarded(Alpha),
    };
    // rgb = A·B + D = k_diffuse · max(0, spare0) + I_ambient (A's unsigned mapping clamps at 0).
    let final_combiner = FinalCombiner {
        a: FinalInput::reg(Spare0, Rgb),
        b: FinalInput::reg(ConstantColor1, Rgb),
        c: FinalInput::ZERO,
        d: FinalInput::reg(ConstantColor0, Rgb),
        e: FinalInput::ZERO,
        f: FinalInput::ZERO,
        g: FinalInput::reg(Zero, Alpha),
        color_sum_clamp: true,
    };
    CombinerSetup { stages: vec![stage0, stage1], final_combiner, constant0: ambient, constant1: diffuse }
}
