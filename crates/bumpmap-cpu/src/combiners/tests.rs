//! The register combiners against the specification's tables and error rules.

use super::*;
use ComponentUsage::{Alpha, Blue, Rgb};

/// Runs `setup` on one fragment whose registers hold `values` (others zero); returns RGBA.
fn run1(setup: CombinerSetup, values: &[(Register, Vec4)], precision: Precision) -> Vec4 {
    let comb = Combiners::new(setup, precision).expect("valid setup");
    let mut regs = RegisterFile::new();
    comb.load_constants(&mut regs, 1);
    for &(r, v) in values {
        for c in 0..4 {
            regs.reg_mut(r)[c][0] = v[c];
        }
    }
    let mut out = [[0.0; LANES]; 4];
    comb.run(&mut regs, 1, &mut out);
    Vec4::new(out[0][0], out[1][0], out[2][0], out[3][0])
}

/// A setup whose final combiner shows SPARE0's RGB (D) and alpha (G) unchanged.
fn show_spare0(stage: GeneralStage) -> CombinerSetup {
    let final_combiner = FinalCombiner {
        a: FinalInput::ZERO,
        b: FinalInput::ZERO,
        c: FinalInput::ZERO,
        d: FinalInput::reg(Register::Spare0, Rgb),
        e: FinalInput::ZERO,
        f: FinalInput::ZERO,
        g: FinalInput::reg(Register::Spare0, Alpha),
        color_sum_clamp: true,
    };
    CombinerSetup { stages: vec![stage], final_combiner, ..Default::default() }
}

/// A stage computing `mapping(primary)·1` into SPARE0; returns SPARE0's red after the stage.
fn mapped(mapping: InputMapping, e: f32) -> f32 {
    let mut stage = GeneralStage::default();
    stage.rgb.a = Input::new(Register::PrimaryColor, mapping, Rgb);
    stage.rgb.outputs = Outputs { sum: Some(Register::Spare0), ..Outputs::DISCARD };
    // The final combiner only shows values in [0, 1]; read the signed SPARE0 from the registers.
    let comb = Combiners::new(show_spare0(stage), Precision::Float).unwrap();
    let mut regs = RegisterFile::new();
    comb.load_constants(&mut regs, 1);
    regs.reg_mut(Register::PrimaryColor)[0][0] = e;
    let mut out = [[0.0; LANES]; 4];
    comb.run(&mut regs, 1, &mut out);
    regs.regs[Register::Spare0 as usize][0][0]
}

#[test]
fn every_input_mapping_follows_the_table() {
    use InputMapping::*;
    // (mapping, e, f(e)) straight from spec table NV_register_combiners.4.
    let cases = [
        (UnsignedIdentity, -0.5, 0.0),
        (UnsignedIdentity, 0.75, 0.75),
        (UnsignedInvert, 0.25, 0.75),
        (UnsignedInvert, -0.5, 1.0),
        (ExpandNormal, 0.75, 0.5),
        (ExpandNormal, -0.3, -1.0),
        (ExpandNegate, 0.75, -0.5),
        (ExpandNegate, -0.3, 1.0),
        (HalfBiasNormal, 0.75, 0.25),
        (HalfBiasNormal, -0.3, -0.5),
        (HalfBiasNegate, 0.75, -0.25),
        (HalfBiasNegate, -0.3, 0.5),
        (SignedIdentity, -0.3, -0.3),
        (SignedNegate, -0.3, 0.3),
    ];
    for (m, e, want) in cases {
        assert_eq!(m.apply(e), want, "{m:?}({e})");
        assert!((mapped(m, e) - want).abs() < 1e-6, "{m:?}({e}) through a stage: {}", mapped(m, e));
    }
}

#[test]
fn mux_selects_ab_below_one_half_and_cd_from_one_half() {
    let mut stage = GeneralStage::default();
    stage.rgb.a = Input::one(Rgb); // AB = 1·0.25
    stage.rgb.b = Input::new(Register::ConstantColor0, InputMapping::UnsignedIdentity, Rgb);
    stage.rgb.c = Input::one(Rgb); // CD = 1·0.75
    stage.rgb.d = Input::new(Register::ConstantColor1, InputMapping::UnsignedIdentity, Rgb);
    stage.rgb.outputs = Outputs { sum: Some(Register::Spare0), mux_sum: true, ..Outputs::DISCARD };
    stage.alpha.outputs = Outputs::DISCARD;
    let mut setup = show_spare0(stage);
    setup.constant0 = Vec4::splat(0.25);
    setup.constant1 = Vec4::splat(0.75);
    for (spare0_alpha, want) in [(0.0, 0.25), (0.499, 0.25), (0.5, 0.75), (1.0, 0.75)] {
        let got = run1(setup.clone(), &[(Register::Spare0, Vec4::new(0.0, 0.0, 0.0, spare0_alpha))], Precision::Float);
        assert_eq!(got.x, want, "spare0.a = {spare0_alpha}");
    }
}

#[test]
fn bias_is_added_before_scaling_and_outputs_clamp() {
    let mut stage = GeneralStage::default();
    stage.rgb.a = Input::new(Register::PrimaryColor, InputMapping::SignedIdentity, Rgb);
    stage.rgb.outputs =
        Outputs { sum: Some(Register::Spare0), scale: Scale::ByTwo, bias: Bias::MinusOneHalf, ..Outputs::DISCARD };
    let setup = show_spare0(stage);
    // (0.9 − 0.5)·2 = 0.8; scale-then-bias would give 1.3 → 1.
    let got = run1(setup.clone(), &[(Register::PrimaryColor, Vec4::splat(0.9))], Precision::Float);
    assert!((got.x - 0.8).abs() < 1e-6, "{got}");
    // (0.1 − 0.5)·2 = −0.8, stored signed; the final combiner's D clamps it to 0.
    assert_eq!(run1(setup, &[(Register::PrimaryColor, Vec4::splat(0.1))], Precision::Float).x, 0.0);
    // Scale by four clamps to [−1, 1].
    let mut s4 = GeneralStage::default();
    s4.rgb.a = Input::new(Register::PrimaryColor, InputMapping::SignedIdentity, Rgb);
    s4.rgb.outputs = Outputs { sum: Some(Register::Spare0), scale: Scale::ByFour, ..Outputs::DISCARD };
    let comb = Combiners::new(show_spare0(s4), Precision::Float).unwrap();
    let mut regs = RegisterFile::new();
    comb.load_constants(&mut regs, 2);
    regs.reg_mut(Register::PrimaryColor)[0][..2].copy_from_slice(&[0.6, -0.6]);
    comb.run(&mut regs, 2, &mut [[0.0; LANES]; 4]);
    assert_eq!(&regs.regs[Register::Spare0 as usize][0][..2], &[1.0, -1.0]);
}

#[test]
fn final_combiner_is_lerp_plus_d_with_clamps() {
    let fc = FinalCombiner {
        a: FinalInput::reg(Register::ConstantColor0, Rgb),
        b: FinalInput::reg(Register::Texture0, Rgb),
        c: FinalInput::reg(Register::Texture1, Rgb),
        d: FinalInput::E_TIMES_F,
        e: FinalInput::reg(Register::PrimaryColor, Rgb),
        f: FinalInput { mapping: InputMapping::UnsignedInvert, ..FinalInput::reg(Register::PrimaryColor, Rgb) },
        g: FinalInput::reg(Register::Texture0, Blue),
        color_sum_clamp: true,
    };
    let mut stage = GeneralStage::default();
    stage.rgb.outputs = Outputs::DISCARD;
    stage.alpha.outputs = Outputs::DISCARD;
    let setup =
        CombinerSetup { stages: vec![stage], final_combiner: fc, constant0: Vec4::splat(0.25), constant1: Vec4::ZERO };
    let got = run1(
        setup.clone(),
        &[
            (Register::Texture0, Vec4::new(0.8, 0.4, 0.6, 0.1)),
            (Register::Texture1, Vec4::splat(0.2)),
            (Register::PrimaryColor, Vec4::splat(0.5)),
        ],
        Precision::Float,
    );
    // A·B + (1−A)·C + E·F = 0.25·0.8 + 0.75·0.2 + 0.5·0.5 = 0.6; G = texture0 blue = 0.6.
    assert!((got.x - 0.6).abs() < 1e-6 && (got.w - 0.6).abs() < 1e-6, "{got}");
    // The sum clamps at 1.
    let bright = run1(
        setup,
        &[(Register::Texture0, Vec4::ONE), (Register::Texture1, Vec4::ONE), (Register::PrimaryColor, Vec4::splat(0.5))],
        Precision::Float,
    );
    assert_eq!(bright.x, 1.0);
    // SPARE0 + SECONDARY clamps when COLOR_SUM_CLAMP is on (the default) and not when off:
    // A = 0.5, B = 0.7 + 0.6, C = D = 0.
    let mut sum = CombinerSetup::default();
    sum.stages[0].rgb.outputs = Outputs::DISCARD;
    sum.constant0 = Vec4::splat(0.5);
    sum.final_combiner.a = FinalInput::reg(Register::ConstantColor0, Rgb);
    sum.final_combiner.c = FinalInput::ZERO;
    let regs = [(Register::Spare0, Vec4::splat(0.7)), (Register::SecondaryColor, Vec4::splat(0.6))];
    assert!((run1(sum.clone(), &regs, Precision::Float).x - 0.5).abs() < 1e-6);
    sum.final_combiner.color_sum_clamp = false;
    assert!((run1(sum.clone(), &regs, Precision::Float).x - 0.65).abs() < 1e-6);
    // A may not read spare0 + secondary: an error, not a value.
    sum.final_combiner.a = FinalInput { source: FinalSource::Spare0PlusSecondary, ..FinalInput::ZERO };
    assert!(matches!(
        Combiners::new(sum, Precision::Float),
        Err(CombinerError::FinalSourceNotAllowed { var: 'A', .. })
    ));
}

#[test]
fn initial_state_is_the_gl_color_sum() {
    // Stage 0 initial: spare0 = primary·1; final: fog.a·(spare0+secondary) + (1−fog.a)·fog.rgb with
    // fog disabled (factor 1) = primary + secondary; G = spare0.a = primary.a.
    let got = run1(
        CombinerSetup::default(),
        &[(Register::PrimaryColor, Vec4::new(0.2, 0.3, 0.4, 0.5)), (Register::SecondaryColor, Vec4::splat(0.1))],
        Precision::Float,
    );
    assert!((got - Vec4::new(0.3, 0.4, 0.5, 0.5)).abs().max_element() < 1e-6, "{got}");
}

#[test]
fn fixed9_rounds_to_255ths() {
    let mut stage = GeneralStage::default();
    stage.rgb.a = Input::new(Register::PrimaryColor, InputMapping::SignedIdentity, Rgb);
    let setup = show_spare0(stage);
    let f = run1(setup.clone(), &[(Register::PrimaryColor, Vec4::splat(0.3001))], Precision::Fixed9);
    assert_eq!(f.x, (0.3001f32 * 255.0).round() / 255.0);
    assert_eq!(run1(setup, &[(Register::PrimaryColor, Vec4::splat(0.3001))], Precision::Float).x, 0.3001);
}

#[test]
fn invalid_setups_are_the_specs_errors() {
    let base = GeneralStage::default();
    let check = |stage: GeneralStage, want: fn(&CombinerError) -> bool| {
        let err =
            Combiners::new(CombinerSetup { stages: vec![stage], ..Default::default() }, Precision::Float).unwrap_err();
        assert!(want(&err), "got {err}");
    };
    // Two outputs of one portion to the same register.
    let mut s = base;
    s.rgb.outputs = Outputs { ab: Some(Register::Spare1), sum: Some(Register::Spare1), ..Outputs::DISCARD };
    check(s, |e| matches!(e, CombinerError::DuplicateOutput { register: Register::Spare1, .. }));
    // A dot product on the alpha portion.
    let mut s = base;
    s.alpha.outputs.ab_dot = true;
    check(s, |e| matches!(e, CombinerError::DotOnAlpha { .. }));
    // Scale by 4 (or ½) with bias −½.
    for scale in [Scale::ByFour, Scale::ByOneHalf] {
        let mut s = base;
        s.rgb.outputs.scale = scale;
        s.rgb.outputs.bias = Bias::MinusOneHalf;
        check(s, |e| matches!(e, CombinerError::ScaleWithBias { .. }));
    }
    // Scale by 2 with bias −½ is legal.
    let mut s = base;
    s.rgb.outputs.scale = Scale::ByTwo;
    s.rgb.outputs.bias = Bias::MinusOneHalf;
    assert!(Combiners::new(CombinerSetup { stages: vec![s], ..Default::default() }, Precision::Float).is_ok());
    // Component usages.
    let mut s = base;
    s.rgb.b.usage = Blue;
    check(s, |e| matches!(e, CombinerError::BlueOnRgb { var: 'B', .. }));
    let mut s = base;
    s.alpha.c.usage = Rgb;
    check(s, |e| matches!(e, CombinerError::RgbOnAlpha { var: 'C', .. }));
    let mut s = base;
    s.alpha.a = Input::new(Register::Fog, InputMapping::UnsignedIdentity, Alpha);
    check(s, |e| matches!(e, CombinerError::FogAlphaInGeneral { .. }));
    // Writing a read-only register.
    let mut s = base;
    s.rgb.outputs.sum = Some(Register::ConstantColor0);
    check(s, |e| matches!(e, CombinerError::NotWritable { .. }));
    // Stage count.
    let three = CombinerSetup { stages: vec![base; 3], ..Default::default() };
    assert_eq!(Combiners::new(three, Precision::Float).unwrap_err(), CombinerError::StageCount(3));
    // Final combiner: signed mappings, E·F in E, alpha of a pseudo-register, blue in A.
    let mut fc = CombinerSetup::default();
    fc.final_combiner.d.mapping = InputMapping::ExpandNormal;
    assert!(matches!(fc.validate(), Err(CombinerError::FinalMapping { var: 'D', .. })));
    let mut fc = CombinerSetup::default();
    fc.final_combiner.e = FinalInput::E_TIMES_F;
    assert!(matches!(fc.validate(), Err(CombinerError::FinalSourceNotAllowed { var: 'E', .. })));
    let mut fc = CombinerSetup::default();
    fc.final_combiner.b.usage = Alpha;
    assert!(matches!(fc.validate(), Err(CombinerError::FinalUsage { var: 'B', .. })));
    let mut fc = CombinerSetup::default();
    fc.final_combiner.a.usage = Blue;
    assert!(matches!(fc.validate(), Err(CombinerError::FinalUsage { var: 'A', .. })));
}

#[test]
fn both_portions_read_the_stage_inputs_before_either_writes() {
    // RGB writes SPARE0 = 1·(0.2, 0.4, 0.6); alpha reads SPARE0's blue, which must still be the
    // value entering the stage (0.9), not the RGB portion's 0.6.
    let mut stage = GeneralStage::default();
    stage.rgb.a = Input::new(Register::ConstantColor0, InputMapping::UnsignedIdentity, Rgb);
    stage.rgb.b = Input::one(Rgb);
    stage.rgb.c = Input::zero(Rgb);
    stage.rgb.d = Input::zero(Rgb);
    stage.rgb.outputs = Outputs { ab: Some(Register::Spare0), ..Outputs::DISCARD };
    stage.alpha.a = Input::new(Register::Spare0, InputMapping::UnsignedIdentity, Blue);
    stage.alpha.b = Input::one(Alpha);
    stage.alpha.c = Input::zero(Alpha);
    stage.alpha.d = Input::zero(Alpha);
    stage.alpha.outputs = Outputs { ab: Some(Register::Spare0), ..Outputs::DISCARD };
    let mut setup = show_spare0(stage);
    setup.constant0 = Vec4::new(0.2, 0.4, 0.6, 1.0);
    let out = run1(setup, &[(Register::Spare0, Vec4::new(0.0, 0.0, 0.9, 0.3))], Precision::Float);
    assert!((out - Vec4::new(0.2, 0.4, 0.6, 0.9)).abs().max_element() < 1e-6, "{out}");
}

#[test]
fn affine_form_of_each_mapping_equals_the_table() {
    for m in InputMapping::ALL {
        for i in -300..=300 {
            let e = i as f32 / 97.0;
            // Same operations on the same values: equal exactly (±0 compare equal).
            assert_eq!(m.affine().apply(e), m.apply(e), "{m:?}({e})");
        }
    }
}

#[test]
fn final_combiner_with_constant_inputs_equals_the_full_sum() {
    // A ∈ {ZERO, ZERO inverted, a register}, C and D ∈ {ZERO, a register}: every folded case
    // against A·B + (1 − A)·C + D with the values written out.
    let (a_val, b_val, c_val, d_val) = (0.3, 0.7, 0.4, 0.2);
    let regs = [
        (Register::Texture0, Vec4::splat(a_val)),
        (Register::Texture1, Vec4::splat(b_val)),
        (Register::Texture2, Vec4::splat(c_val)),
        (Register::Texture3, Vec4::splat(d_val)),
    ];
    let one = FinalInput { mapping: InputMapping::UnsignedInvert, ..FinalInput::ZERO };
    for (a, av) in [(FinalInput::ZERO, 0.0), (one, 1.0), (FinalInput::reg(Register::Texture0, Rgb), a_val)] {
        for (c, cv) in [(FinalInput::ZERO, 0.0), (FinalInput::reg(Register::Texture2, Rgb), c_val)] {
            for (d, dv) in [(FinalInput::ZERO, 0.0), (FinalInput::reg(Register::Texture3, Rgb), d_val)] {
                let mut setup = CombinerSetup::default();
                setup.stages[0].rgb.outputs = Outputs::DISCARD;
                setup.final_combiner.a = a;
                setup.final_combiner.b = FinalInput::reg(Register::Texture1, Rgb);
                setup.final_combiner.c = c;
                setup.final_combiner.d = d;
                let got = run1(setup, &regs, Precision::Float).x;
                let want = av * b_val + (1.0 - av) * cv + dv;
                // Float products of values in [0, 1]: a few ulp.
                assert!((got - want).abs() < 1e-6, "A {av}, C {cv}, D {dv}: {got} vs {want}");
            }
        }
    }
}

#[test]
fn gray_values_computed_once_equal_per_channel_evaluation() {
    // Setups where the plan finds gray values (dot products, alpha reads, gray constants) and
    // where it must not (coloured constants, a gray AB summed with a coloured CD, an alpha
    // portion reading a blue the RGB portion writes), run on pseudo-random texture lanes with
    // and without the plan: the same bits.
    let (gray, colour) = (Vec4::splat(0.4), Vec4::new(0.9, 1.0, 0.8, 1.0));
    let mut mixed = bumpmap_core::setups::specular();
    mixed.stages[0].rgb.c = Input::new(Register::Texture0, InputMapping::UnsignedIdentity, Rgb);
    mixed.stages[0].rgb.d = Input::new(Register::Texture1, InputMapping::UnsignedIdentity, Rgb);
    mixed.stages[0].rgb.outputs.sum = Some(Register::Spare1);
    mixed.stages[0].alpha.a = Input::new(Register::Spare0, InputMapping::UnsignedIdentity, Blue);
    mixed.final_combiner.d = FinalInput::reg(Register::Spare1, Rgb);
    let setups = [
        bumpmap_core::setups::ambient_and_diffuse(gray, gray),
        bumpmap_core::setups::ambient_and_diffuse(gray, colour),
        bumpmap_core::setups::specular(),
        bumpmap_core::setups::specular_ramp(),
        bumpmap_core::setups::decal(),
        mixed,
    ];
    let n = 24;
    let mut seed = 12345u32;
    let mut random = || {
        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (seed >> 8) as f32 / (1 << 24) as f32
    };
    for (k, setup) in setups.into_iter().enumerate() {
        let planned = Combiners::new(setup, Precision::Float).unwrap();
        let per_channel = Combiners {
            gray: GrayPlan { stages: vec![[false; 3]; planned.setup.stages.len()], final_rgb: false },
            ..planned.clone()
        };
        assert!(planned.gray.stages.iter().flatten().any(|&g| g), "setup {k}: nothing gray");
        let mut regs = RegisterFile::new();
        planned.load_constants(&mut regs, LANES);
        for r in [Register::Texture0, Register::Texture1, Register::Texture2, Register::Spare0] {
            for c in 0..4 {
                regs.reg_mut(r)[c][..n].iter_mut().for_each(|v| *v = random());
            }
        }
        let mut results = [[[0.0; LANES]; 4]; 2];
        for (comb, out) in [&planned, &per_channel].into_iter().zip(&mut results) {
            let mut file = RegisterFile::new();
            file.regs = regs.regs;
            comb.run(&mut file, n, out);
        }
        for c in 0..4 {
            assert_eq!(results[0][c][..n], results[1][c][..n], "setup {k}, channel {c}");
        }
    }
}
