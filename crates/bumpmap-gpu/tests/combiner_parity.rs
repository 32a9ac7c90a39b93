//! The generated WGSL combiners (`combiner_wgsl`) against the CPU evaluator
//! (`bumpmap_cpu::combiners::Combiners::run`): random valid setups over nearly the whole state
//! space and the paper's setups, random register inputs, Float and Fixed9, on a compute shader.
//!
//! Tolerances and their reasons:
//! - Float: 1e-5 per component. Both sides compute in f32, but a GPU driver may contract
//!   `a·b + c` into an FMA and reassociate sums (WGSL has no `precise`); measured: at most a few
//!   ulps (5.4e-7) over 10⁷ values, scaled by at most ×4 per stage over two stages.
//! - Fixed9: 1e-5, except where a stage output is exactly a rounding tie of the 1/255 grid —
//!   possible only for `(x − ½)·1` and `x·½` outputs, as products of multiples of 1/255 are
//!   K/255² — and the driver's contraction rounds it the other way: at most 1 value in 10⁴, and
//!   only in such setups. Measured: 1.8e-6 of values. The paper's setups must meet 1e-5
//!   everywhere.

mod common;

use bumpmap_core::combiners::{
    Bias, CombinerSetup, ComponentUsage, FinalCombiner, FinalInput, FinalSource, GeneralStage, Input, InputMapping,
    Outputs, Portion, Precision, Register, Scale,
};
use bumpmap_core::{setups, technique::kilgard::decal_times_diffuse};
use bumpmap_cpu::{Combiners, LANES, RegisterFile};
use bumpmap_gpu::combiners_wgsl;
use glam::Vec4;

// ---------------------------------------------------------------------------------------------
// Random numbers (xorshift64*; no external crate).

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
    fn chance(&mut self, p: f32) -> bool {
        self.unit() < p
    }
    fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[self.below(xs.len())]
    }
    /// A register or constant component: texel-like k/255, uniform, or a special value.
    fn component(&mut self, lo: f32, hi: f32) -> f32 {
        match self.below(10) {
            0..=3 => self.below(256) as f32 / 255.0,
            4..=8 => lo + (hi - lo) * self.unit(),
            _ => self.pick(&[0.0, 0.5, 1.0, 127.0 / 255.0, 128.0 / 255.0, lo, hi]),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Random setups: drawn over (nearly) the whole state space, kept only if `validate()` accepts.

use Register::*;
const REGS: [Register; 12] = Register::ALL;
const WRITABLE: [Register; 8] = [PrimaryColor, SecondaryColor, Spare0, Spare1, Texture0, Texture1, Texture2, Texture3];

fn random_input(rng: &mut Rng, rgb: bool) -> Input {
    use ComponentUsage::*;
    let usage = if rng.chance(0.03) {
        rng.pick(&[Rgb, Alpha, Blue]) // sometimes illegal: validate() filters
    } else if rgb {
        rng.pick(&[Rgb, Rgb, Alpha])
    } else {
        rng.pick(&[Alpha, Blue])
    };
    Input::new(rng.pick(&REGS), rng.pick(&InputMapping::ALL), usage)
}

fn random_outputs(rng: &mut Rng, rgb: bool) -> Outputs {
    let mut dst = || if rng.chance(0.4) { None } else { Some(rng.pick(&WRITABLE)) };
    let (ab, cd, sum) = (dst(), dst(), dst());
    Outputs {
        ab,
        cd,
        sum,
        scale: rng.pick(&[Scale::None, Scale::None, Scale::ByTwo, Scale::ByFour, Scale::ByOneHalf]),
        bias: if rng.chance(0.35) { Bias::MinusOneHalf } else { Bias::None },
        ab_dot: rng.chance(if rgb { 0.3 } else { 0.02 }),
        cd_dot: rng.chance(if rgb { 0.3 } else { 0.02 }),
        mux_sum: rng.chance(0.3),
    }
}

fn random_portion(rng: &mut Rng, rgb: bool) -> Portion {
    Portion {
        a: random_input(rng, rgb),
        b: random_input(rng, rgb),
        c: random_input(rng, rgb),
        d: random_input(rng, rgb),
        outputs: random_outputs(rng, rgb),
    }
}

fn random_final_input(rng: &mut Rng, var: char) -> FinalInput {
    use ComponentUsage::*;
    let source = match rng.below(20) {
        0..=2 if var <= 'D' => FinalSource::ETimesF,
        3..=5 if ('B'..='D').contains(&var) => FinalSource::Spare0PlusSecondary,
        6..=9 => FinalSource::Register(rng.pick(&[Spare0, Spare1])), // what stages usually write
        _ => FinalSource::Register(rng.pick(&REGS)),
    };
    let mapping = if rng.chance(0.03) {
        rng.pick(&InputMapping::ALL)
    } else {
        rng.pick(&[InputMapping::UnsignedIdentity, InputMapping::UnsignedInvert])
    };
    let usage = match (var, source) {
        ('G', _) => rng.pick(&[Alpha, Alpha, Blue]),
        (_, FinalSource::Register(_)) => rng.pick(&[Rgb, Rgb, Alpha]),
        _ => Rgb,
    };
    FinalInput { source, mapping, usage }
}

fn random_constant(rng: &mut Rng) -> Vec4 {
    if rng.chance(0.2) {
        Vec4::splat(rng.component(-0.2, 1.2))
    } else {
        Vec4::from_array(std::array::from_fn(|_| rng.component(-0.2, 1.2)))
    }
}

fn random_setup(rng: &mut Rng) -> (CombinerSetup, usize) {
    for tries in 1.. {
        let stages = (0..1 + rng.below(2))
            .map(|_| GeneralStage { rgb: random_portion(rng, true), alpha: random_portion(rng, false) })
            .collect();
        let mut v = |c| random_final_input(rng, c);
        let final_combiner = FinalCombiner {
            a: v('A'),
            b: v('B'),
            c: v('C'),
            d: v('D'),
            e: v('E'),
            f: v('F'),
            g: v('G'),
            color_sum_clamp: rng.chance(0.7),
        };
        let setup =
            CombinerSetup { stages, final_combiner, constant0: random_constant(rng), constant1: random_constant(rng) };
        if setup.validate().is_ok() {
            return (setup, tries);
        }
    }
    unreachable!()
}

/// The paper's setups, the three-pass technique's extra-light setups, and the GL initial state.
fn paper_setups() -> Vec<(String, CombinerSetup)> {
    let (amb, kd) = (Vec4::new(0.1, 0.1, 0.1, 0.0), Vec4::new(0.9, 1.0, 1.0, 0.0));
    let mut v = vec![
        ("decal".into(), setups::decal()),
        ("ambient_and_diffuse (App. G)".into(), setups::ambient_and_diffuse(amb, kd)),
        ("ambient_and_diffuse_unshadowed".into(), setups::ambient_and_diffuse_unshadowed(amb, kd)),
        ("specular (App. H)".into(), setups::specular()),
        ("specular_ramp".into(), setups::specular_ramp()),
        ("GL initial state".into(), CombinerSetup::default()),
    ];
    for shadow in [false, true] {
        for decal in [false, true] {
            for color in [false, true] {
                let name = format!("decal_times_diffuse(shadow={shadow}, decal={decal}, vertex colour={color})");
                v.push((name, decal_times_diffuse(shadow, decal, color)));
            }
        }
    }
    for textured in [false, true] {
        v.push((format!("vertex_colored_decal(textured={textured})"), setups::vertex_colored_decal(textured)));
    }
    v
}

/// Registers TEXTURE0..3, PRIMARY_COLOR, SECONDARY_COLOR of one fragment (the WGSL struct).
#[derive(Clone, Copy)]
struct Regs([[f32; 4]; 6]);

const REG_ORDER: [Register; 6] = [Texture0, Texture1, Texture2, Texture3, PrimaryColor, SecondaryColor];

fn random_inputs(rng: &mut Rng, n: usize) -> Vec<Regs> {
    (0..n).map(|_| Regs(std::array::from_fn(|_| std::array::from_fn(|_| rng.component(0.0, 1.0))))).collect()
}

fn cpu(setup: &CombinerSetup, precision: Precision, inputs: &[Regs]) -> Vec<[f32; 4]> {
    let comb = Combiners::new(setup.clone(), precision).expect("valid");
    let mut out = Vec::with_capacity(inputs.len());
    for chunk in inputs.chunks(LANES) {
        let mut file = RegisterFile::new(); // fresh: SPARE0 rgb = SPARE1 = 0
        comb.load_constants(&mut file, LANES);
        for (i, regs) in chunk.iter().enumerate() {
            for (r, v) in REG_ORDER.iter().zip(&regs.0) {
                for c in 0..4 {
                    file.reg_mut(*r)[c][i] = v[c];
                }
            }
            file.reg_mut(Spare0)[3][i] = regs.0[0][3]; // SPARE0 alpha = texture 0 alpha
        }
        let mut o = [[0.0; LANES]; 4];
        comb.run(&mut file, chunk.len(), &mut o);
        out.extend((0..chunk.len()).map(|i| [o[0][i], o[1][i], o[2][i], o[3][i]]));
    }
    out
}

const ENTRY: &str = "
@group(0) @binding(0) var<storage, read> inputs: array<Registers>;
@group(0) @binding(1) var<storage, read_write> outputs: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&outputs) {
        outputs[id.x] = combiners(inputs[id.x]);
    }
}
";

/// Whether a setup can hit an exact Fixed9 rounding tie in a stage output (see the module
/// docs): a kept output with `(x − ½)·1` or `x·½`.
fn tie_capable(s: &CombinerSetup) -> bool {
    s.stages.iter().flat_map(|st| [&st.rgb.outputs, &st.alpha.outputs]).any(|o| {
        let kept = o.ab.is_some() || o.cd.is_some() || o.sum.is_some();
        kept && matches!((o.bias, o.scale), (Bias::MinusOneHalf, Scale::None) | (Bias::None, Scale::ByOneHalf))
    })
}

#[test]
fn generated_wgsl_evaluates_setups_as_the_cpu_evaluator_does() {
    let Some(ctx) = common::context() else { return };
    let (n_setups, n_inputs) = (300, 128);
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut cases = paper_setups();
    let papers = cases.len();
    for i in 0..n_setups {
        cases.push((format!("random #{i}"), random_setup(&mut rng).0));
    }
    // Coverage of what makes the generator hard: dot products, muxes, E·F, spare0+secondary.
    let portions = || cases.iter().flat_map(|(_, s)| s.stages.iter().flat_map(|st| [&st.rgb, &st.alpha]));
    assert!(portions().filter(|p| p.outputs.ab_dot).count() > 50, "dot products covered");
    assert!(portions().filter(|p| p.outputs.sum.is_some() && p.outputs.mux_sum).count() > 50, "muxes covered");
    let reads = |f: &FinalCombiner, src| [f.a, f.b, f.c, f.d].iter().any(|i| i.source == src);
    assert!(cases.iter().filter(|(_, s)| reads(&s.final_combiner, FinalSource::ETimesF)).count() > 30);
    assert!(cases.iter().filter(|(_, s)| reads(&s.final_combiner, FinalSource::Spare0PlusSecondary)).count() > 30);
    for precision in [Precision::Float, Precision::Fixed9] {
        let (mut values, mut over, mut over_other, mut max_paper, mut max_float) = (0usize, 0usize, 0usize, 0f32, 0f32);
        for (case, (label, setup)) in cases.iter().enumerate() {
            let mut irng = Rng(0x5851_f42d_4c95_7f2d ^ case as u64);
            let inputs = random_inputs(&mut irng, n_inputs);
            let flat: Vec<f32> = inputs.iter().flat_map(|r| r.0.iter().flatten().copied()).collect();
            let wgsl = format!("{}{ENTRY}", combiners_wgsl(setup, precision));
            let want = cpu(setup, precision, &inputs);
            let got = common::run_compute(&ctx, &wgsl, common::bytes(&flat), inputs.len())
                .unwrap_or_else(|e| panic!("{label} {precision:?}: the generated WGSL is refused: {e}"));
            for (i, (c, g)) in want.iter().zip(&got).enumerate() {
                for k in 0..4 {
                    let d = (c[k] - g[k]).abs();
                    let d = if d.is_nan() { f32::INFINITY } else { d };
                    values += 1;
                    if case < papers {
                        max_paper = max_paper.max(d);
                    }
                    match precision {
                        Precision::Float => {
                            max_float = max_float.max(d);
                            assert!(
                                d <= 1e-5,
                                "{label} Float, fragment {i} component {k}: cpu {c:?} gpu {g:?}\n{setup:#?}"
                            );
                        }
                        Precision::Fixed9 if d > 1e-5 => {
                            over += 1;
                            if !tie_capable(setup) {
                                over_other += 1;
                                eprintln!("{label} Fixed9, fragment {i} component {k}: cpu {c:?} gpu {g:?}");
                            }
                        }
                        Precision::Fixed9 => {}
                    }
                }
            }
        }
        println!(
            "{precision:?}: {} setups x {n_inputs} inputs, {values} values; paper setups max |diff| {max_paper:e}; \
             float max {max_float:e}; fixed9 values over 1e-5: {over} ({over_other} outside tie-capable setups)",
            cases.len()
        );
        assert!(max_paper <= 1e-5, "{precision:?}: the paper's setups differ by {max_paper}");
        assert_eq!(over_other, 0, "{precision:?}: differences outside the rounding-tie case");
        assert!((over as f64) <= 1e-4 * values as f64, "{precision:?}: {over} of {values} values over 1e-5");
    }
}
