//! The NV_register_combiners evaluator (SPECS.md §1) over fragment batches.
//!
//! [`Combiners::new`] validates a [`CombinerSetup`] (the description lives in
//! `bumpmap_core::combiners`); [`Combiners::run`] evaluates it over a batch of fragments in
//! structure-of-arrays lanes, one pass of each operation over all lanes, so the setup is
//! interpreted per batch and never per pixel. Precision is float by default or `Fixed9`, which
//! rounds like the 9-bit signed NV10 datapath. Not emulated: the GeForce 256's wrong results
//! above 2 with the colour-sum clamp off.

pub use bumpmap_core::combiners::*;
use bumpmap_core::lane_math::{clamp_lo, max_lo, min_hi};
use glam::Vec4;

/// Fragments evaluated together.
pub const LANES: usize = 128;
/// One value per lane.
pub type Lanes = [f32; LANES];

/// The per-batch register set: RGBA lanes for each register, and the combiners' temporaries
/// (kept here so a batch allocates and clears nothing).
pub struct RegisterFile {
    /// Every register's R, G, B and A lanes, indexed by `Register as usize`.
    pub regs: [[Lanes; 4]; REGISTERS],
    tmp: Temporaries,
}

struct Temporaries {
    /// AB, CD and sum outputs of the RGB and the alpha portion.
    rgb: [[Lanes; 4]; 3],
    alpha: [[Lanes; 4]; 3],
    /// Final combiner variables A–F and E·F.
    fin: [[Lanes; 3]; 7],
}

impl RegisterFile {
    /// A zeroed register file, boxed (it is large).
    pub fn new() -> Box<Self> {
        Box::new(Self {
            regs: [[[0.0; LANES]; 4]; REGISTERS],
            tmp: Temporaries {
                rgb: [[[0.0; LANES]; 4]; 3],
                alpha: [[[0.0; LANES]; 4]; 3],
                fin: [[[0.0; LANES]; 3]; 7],
            },
        })
    }

    /// Register `r`'s R, G, B and A lanes.
    pub fn reg_mut(&mut self, r: Register) -> &mut [Lanes; 4] {
        &mut self.regs[r as usize]
    }
}

/// A validated setup, ready to evaluate.
#[derive(Clone, Debug, PartialEq)]
pub struct Combiners {
    setup: CombinerSetup,
    precision: Precision,
    gray: GrayPlan,
}

/// Which RGB values are gray (R = G = B in every lane), found once per setup so that the
/// evaluation computes them on one channel and copies it. A dot product is gray, and so is an
/// alpha or blue read, ZERO, FOG and a constant with equal components; products, sums and the
/// mux of gray values are gray. The results are the same bits as per-channel evaluation.
#[derive(Clone, Debug, PartialEq, Default)]
struct GrayPlan {
    /// Per general stage: the RGB portion's AB, CD and sum.
    stages: Vec<[bool; 3]>,
    /// The final combiner's RGB (A·B + (1 − A)·C + D, from the inputs it reads).
    final_rgb: bool,
}

impl GrayPlan {
    fn new(setup: &CombinerSetup) -> Self {
        let gray_constant = |c: Vec4| c.x == c.y && c.y == c.z;
        let mut reg = [false; REGISTERS];
        reg[Register::Zero as usize] = true;
        reg[Register::Fog as usize] = true;
        reg[Register::ConstantColor0 as usize] = gray_constant(setup.constant0);
        reg[Register::ConstantColor1 as usize] = gray_constant(setup.constant1);
        let input = |reg: &[bool; REGISTERS], i: &Input| i.usage != ComponentUsage::Rgb || reg[i.register as usize];
        let mut stages = Vec::with_capacity(setup.stages.len());
        for stage in &setup.stages {
            let (p, o) = (&stage.rgb, &stage.rgb.outputs);
            let ab = o.ab_dot || (input(&reg, &p.a) && input(&reg, &p.b));
            let cd = o.cd_dot || (input(&reg, &p.c) && input(&reg, &p.d));
            let gray = [ab, cd, ab && cd];
            for (dst, g) in [o.ab, o.cd, o.sum].into_iter().zip(gray) {
                if let Some(r) = dst {
                    reg[r as usize] = g;
                }
            }
            stages.push(gray);
        }
        let f = &setup.final_combiner;
        let fin = |i: &FinalInput| match i.source {
            FinalSource::Register(r) => i.usage != ComponentUsage::Rgb || reg[r as usize],
            FinalSource::ETimesF => false,
            FinalSource::Spare0PlusSecondary => {
                reg[Register::Spare0 as usize] && reg[Register::SecondaryColor as usize]
            }
        };
        let ef = fin(&f.e) && fin(&f.f);
        let abcd = [&f.a, &f.b, &f.c, &f.d].map(|i| if i.source == FinalSource::ETimesF { ef } else { fin(i) });
        GrayPlan { stages, final_rgb: abcd.iter().all(|&g| g) }
    }
}

#[inline(always)]
fn quantize(x: f32) -> f32 {
    Precision::quantize_fixed9(x)
}

impl Combiners {
    /// Validates `setup`; constants are clamped to [0, 1] as `glCombinerParameterfvNV` does.
    pub fn new(mut setup: CombinerSetup, precision: Precision) -> Result<Self, CombinerError> {
        setup.validate()?;
        setup.constant0 = setup.constant0.clamp(Vec4::ZERO, Vec4::ONE);
        setup.constant1 = setup.constant1.clamp(Vec4::ZERO, Vec4::ONE);
        let gray = GrayPlan::new(&setup);
        Ok(Self { setup, precision, gray })
    }

    /// The setup being evaluated.
    pub fn setup(&self) -> &CombinerSetup {
        &self.setup
    }

    /// Fills the registers the pipeline does not supply per fragment: ZERO, the constants, and
    /// FOG (colour 0, factor 1: fog disabled).
    pub fn load_constants(&self, regs: &mut RegisterFile, n: usize) {
        for (r, v) in [
            (Register::Zero, Vec4::ZERO),
            (Register::ConstantColor0, self.setup.constant0),
            (Register::ConstantColor1, self.setup.constant1),
            (Register::Fog, Vec4::new(0.0, 0.0, 0.0, 1.0)),
        ] {
            let reg = regs.reg_mut(r);
            for c in 0..4 {
                reg[c][..n].fill(v[c]);
            }
        }
    }

    /// Evaluates lanes `0..n`: the general stages in order, then the final combiner, writing
    /// RGBA into `out`. The caller has loaded the texture registers, PRIMARY and SECONDARY,
    /// SPARE0's alpha (texture 0's alpha) and the constants ([`Combiners::load_constants`]).
    /// Lanes from `n` up to the next multiple of eight are evaluated too, on whatever the
    /// registers hold there, so that every loop runs over whole vectors.
    pub fn run(&self, file: &mut RegisterFile, n: usize, out: &mut [Lanes; 4]) {
        debug_assert!(n <= LANES);
        let n = n.next_multiple_of(8);
        let fixed = self.precision == Precision::Fixed9;
        let RegisterFile { regs, tmp } = file;
        for (stage, &gray) in self.setup.stages.iter().zip(&self.gray.stages) {
            // Both portions read this stage's inputs; their writes form the next stage's set.
            // A portion that discards all three outputs changes nothing and is skipped.
            let writes = |p: &Portion| p.outputs.ab.is_some() || p.outputs.cd.is_some() || p.outputs.sum.is_some();
            // The alpha portion runs last and can store straight into its registers; the RGB
            // portion too, unless the alpha portion reads the blue of a register it writes.
            let rgb_outputs = [stage.rgb.outputs.ab, stage.rgb.outputs.cd, stage.rgb.outputs.sum];
            let alpha_reads_written_blue = [stage.alpha.a, stage.alpha.b, stage.alpha.c, stage.alpha.d]
                .iter()
                .any(|i| i.usage == ComponentUsage::Blue && rgb_outputs.contains(&Some(i.register)));
            let rgb_direct = !(writes(&stage.alpha) && alpha_reads_written_blue);
            if writes(&stage.rgb) {
                eval_portion(regs, &stage.rgb, Some(gray), n, fixed, &mut tmp.rgb, rgb_direct);
            }
            if writes(&stage.alpha) {
                eval_portion(regs, &stage.alpha, None, n, fixed, &mut tmp.alpha, true);
            }
            if !rgb_direct {
                let o = &stage.rgb.outputs;
                for (dst, v) in [(o.ab, &tmp.rgb[0]), (o.cd, &tmp.rgb[1]), (o.sum, &tmp.rgb[2])] {
                    if let Some(dst) = dst {
                        for c in 0..3 {
                            regs[dst as usize][c][..n].copy_from_slice(&v[c][..n]);
                        }
                    }
                }
            }
        }
        self.final_combiner(regs, &mut tmp.fin, n, out);
    }

    /// Whether a general stage writes register `r` (then the caller must reload it per batch).
    pub fn writes(&self, r: Register) -> bool {
        self.setup
            .stages
            .iter()
            .flat_map(|s| [&s.rgb.outputs, &s.alpha.outputs])
            .any(|o| [o.ab, o.cd, o.sum].contains(&Some(r)))
    }

    fn final_combiner(
        &self,
        regs: &[[Lanes; 4]; REGISTERS],
        fin: &mut [[Lanes; 3]; 7],
        n: usize,
        out: &mut [Lanes; 4],
    ) {
        // n is a whole number of 8-lane vectors within the batch (`run`); saying so lets every
        // loop below compile to full vectors without bounds checks.
        let n = (n & !7).min(LANES);
        let f = &self.setup.final_combiner;
        let clamp_sum = f.color_sum_clamp;
        // A gray result is computed on channel 0 and copied ([`GrayPlan`]).
        let channels = if self.gray.final_rgb { 1 } else { 3 };
        let fetch = |input: &FinalInput, ef: Option<&[Lanes; 3]>, dst: &mut [Lanes; 3]| {
            for c in 0..channels {
                let d = &mut dst[c][..n];
                match input.source {
                    FinalSource::Register(r) => {
                        let ch = if input.usage == ComponentUsage::Rgb { c } else { 3 };
                        map_into(input.mapping, &regs[r as usize][ch][..n], d);
                    }
                    FinalSource::ETimesF => map_into(input.mapping, &ef.expect("E·F computed first")[c][..n], d),
                    FinalSource::Spare0PlusSecondary => {
                        let (s, t) = (&regs[Register::Spare0 as usize][c], &regs[Register::SecondaryColor as usize][c]);
                        for i in 0..n {
                            let v = max_lo(s[i], 0.0) + max_lo(t[i], 0.0);
                            d[i] = if clamp_sum { min_hi(v, 1.0) } else { v };
                        }
                        map_lanes(input.mapping, d);
                    }
                }
            }
        };
        let [a, b, cc, d, e, fv, ef] = fin;
        // E·F only when A–D read it; ZERO inputs are constants (0 or, inverted, 1).
        let abcd = [&f.a, &f.b, &f.c, &f.d];
        if abcd.iter().any(|i| i.source == FinalSource::ETimesF) {
            fetch(&f.e, None, e);
            fetch(&f.f, None, fv);
            for c in 0..channels {
                for i in 0..n {
                    ef[c][i] = e[c][i] * fv[c][i];
                }
            }
        }
        let constant =
            |i: &FinalInput| (i.source == FinalSource::Register(Register::Zero)).then(|| i.mapping.apply(0.0));
        // With A = 0, B is not read; with A = 1, C is not; a C or D that is the constant 0
        // drops out of the sum (its term is +0 exactly, as 1 − A ≥ 0).
        let a_const = constant(&f.a);
        let (c_zero, d_zero) = (constant(&f.c) == Some(0.0), constant(&f.d) == Some(0.0));
        let read = [true, a_const != Some(0.0), a_const != Some(1.0) && !c_zero, !d_zero];
        for ((input, dst), read) in abcd.into_iter().zip([&mut *a, &mut *b, &mut *cc, &mut *d]).zip(read) {
            if !read {
                continue;
            }
            match constant(input) {
                Some(k) => dst[..channels].iter_mut().for_each(|ch| ch[..n].fill(k)),
                None => fetch(input, Some(ef), dst),
            }
        }
        // A·B + (1 − A)·C + D, clamped to 1: one branch-free loop per case.
        for c in 0..channels {
            let (a, b, cc, d, out) = (&a[c], &b[c], &cc[c], &d[c], &mut out[c][..n]);
            macro_rules! each {
                (|$i:ident| $lerp:expr) => {
                    if d_zero {
                        for $i in 0..n {
                            out[$i] = min_hi($lerp, 1.0);
                        }
                    } else {
                        for $i in 0..n {
                            out[$i] = min_hi($lerp + d[$i], 1.0);
                        }
                    }
                };
            }
            match (a_const, c_zero) {
                (Some(0.0), true) => each!(|i| 0.0f32),
                (Some(0.0), false) => each!(|i| cc[i]),
                (Some(1.0), _) => each!(|i| b[i]),
                (_, true) => each!(|i| a[i] * b[i]),
                _ => each!(|i| a[i] * b[i] + (1.0 - a[i]) * cc[i]),
            }
        }
        if channels == 1 {
            copy_red_to_green_blue(out, n);
        }
        // G reads alpha or blue; pseudo-registers are not allowed for G.
        let FinalSource::Register(r) = f.g.source else { unreachable!("validated") };
        let ch = if f.g.usage == ComponentUsage::Blue { 2 } else { 3 };
        out[3][..n].copy_from_slice(&regs[r as usize][ch][..n]);
        map_lanes(f.g.mapping, &mut out[3][..n]);
    }
}

/// Lanes `0..n` of channel 0 (red) into channels 1 and 2: a gray value computed once.
fn copy_red_to_green_blue(v: &mut [Lanes; 4], n: usize) {
    let (red, rest) = v.split_at_mut(1);
    rest[0][..n].copy_from_slice(&red[0][..n]);
    rest[1][..n].copy_from_slice(&red[0][..n]);
}

/// `dst[i] = mapping(src[i])`, one loop per mapping.
#[inline(always)]
fn map_into(mapping: InputMapping, src: &[f32], dst: &mut [f32]) {
    macro_rules! each {
        ($m:expr) => {
            for (d, &s) in dst.iter_mut().zip(src) {
                *d = $m.apply(s);
            }
        };
    }
    match mapping {
        InputMapping::UnsignedIdentity => each!(InputMapping::UnsignedIdentity),
        InputMapping::UnsignedInvert => each!(InputMapping::UnsignedInvert),
        InputMapping::ExpandNormal => each!(InputMapping::ExpandNormal),
        InputMapping::ExpandNegate => each!(InputMapping::ExpandNegate),
        InputMapping::HalfBiasNormal => each!(InputMapping::HalfBiasNormal),
        InputMapping::HalfBiasNegate => each!(InputMapping::HalfBiasNegate),
        InputMapping::SignedIdentity => dst.copy_from_slice(src),
        InputMapping::SignedNegate => each!(InputMapping::SignedNegate),
    }
}

#[inline(always)]
fn map_lanes(mapping: InputMapping, v: &mut [f32]) {
    // One loop per mapping: the match is per batch, the loop body is branch-free.
    match mapping {
        InputMapping::UnsignedIdentity => v.iter_mut().for_each(|x| *x = InputMapping::UnsignedIdentity.apply(*x)),
        InputMapping::UnsignedInvert => v.iter_mut().for_each(|x| *x = InputMapping::UnsignedInvert.apply(*x)),
        InputMapping::ExpandNormal => v.iter_mut().for_each(|x| *x = InputMapping::ExpandNormal.apply(*x)),
        InputMapping::ExpandNegate => v.iter_mut().for_each(|x| *x = InputMapping::ExpandNegate.apply(*x)),
        InputMapping::HalfBiasNormal => v.iter_mut().for_each(|x| *x = InputMapping::HalfBiasNormal.apply(*x)),
        InputMapping::HalfBiasNegate => v.iter_mut().for_each(|x| *x = InputMapping::HalfBiasNegate.apply(*x)),
        InputMapping::SignedIdentity => {}
        InputMapping::SignedNegate => v.iter_mut().for_each(|x| *x = -*x),
    }
}

/// Evaluates one portion into `out`: its AB, CD and sum outputs (RGBA lanes; only RGB or only A
/// meaningful), after bias, scale and clamp. `gray` is `Some` for the RGB portion, saying which
/// of AB, CD and sum are gray ([`GrayPlan`]): those are computed on channel 0 and copied.
fn eval_portion(
    regs: &mut [[Lanes; 4]; REGISTERS],
    p: &Portion,
    gray: Option<[bool; 3]>,
    n: usize,
    fixed: bool,
    out: &mut [[Lanes; 4]; 3],
    direct: bool,
) {
    // n is a whole number of 8-lane vectors within the batch (`run`); saying so lets every
    // loop below compile to full vectors without bounds checks.
    let n = (n & !7).min(LANES);
    let rgb = gray.is_some();
    // The channels each output is computed on.
    let channels: [&[usize]; 3] = match gray {
        Some(gray) => gray.map(|g| -> &[usize] {
            if g { &[0] } else { &[0, 1, 2] }
        }),
        None => [&[3]; 3],
    };
    let o = &p.outputs;
    // AB and CD are needed when kept or when the sum (or mux) is.
    let need_sum = o.sum.is_some();
    let need = [o.ab.is_some() || need_sum, o.cd.is_some() || need_sum];
    // A variable's values for channel c: its register's c, alpha or blue.
    let source = |input: &Input, c: usize| -> &Lanes {
        let ch = match input.usage {
            ComponentUsage::Rgb => c,
            ComponentUsage::Alpha => 3,
            ComponentUsage::Blue => 2,
        };
        &regs[input.register as usize][ch]
    };
    // Each product maps its two variables on the fly (and quantizes them in fixed9); `var`
    // is chosen once so that the lane loops are branch-free.
    fn product(
        x: [&Lanes; 3],
        y: [&Lanes; 3],
        (mx, my): (Affine, Affine),
        dot: bool,
        channels: &[usize],
        n: usize,
        var: impl Fn(Affine, f32) -> f32 + Copy,
        dst: &mut [Lanes; 4],
    ) {
        let n = (n & !7).min(LANES);
        if dot {
            // Into channel 0, then copied to the other channels asked for (none when gray).
            for i in 0..n {
                dst[0][i] = var(mx, x[0][i]) * var(my, y[0][i])
                    + var(mx, x[1][i]) * var(my, y[1][i])
                    + var(mx, x[2][i]) * var(my, y[2][i]);
            }
            if channels.len() == 3 {
                copy_red_to_green_blue(dst, n);
            }
        } else {
            for &c in channels {
                let (xs, ys) = (x[c.min(2)], y[c.min(2)]);
                for i in 0..n {
                    dst[c][i] = var(mx, xs[i]) * var(my, ys[i]);
                }
            }
        }
    }
    let product_of = |x: &Input, y: &Input, dot: bool, channels: &[usize], dst: &mut [Lanes; 4]| {
        // Sources per channel; the alpha portion's one channel travels in slot 2.
        let sources = |v: &Input| -> [&Lanes; 3] {
            if rgb { [source(v, 0), source(v, 1), source(v, 2)] } else { [source(v, 3); 3] }
        };
        let maps = (x.mapping.affine(), y.mapping.affine());
        let (xs, ys) = (sources(x), sources(y));
        if fixed {
            product(xs, ys, maps, dot, channels, n, |m, e| quantize(m.apply(e)), dst);
        } else {
            product(xs, ys, maps, dot, channels, n, |m, e| m.apply(e), dst);
        }
    };
    let [ab, cd, sum] = out;
    if need[0] {
        product_of(&p.a, &p.b, o.ab_dot, channels[0], ab);
    }
    if need[1] {
        product_of(&p.c, &p.d, o.cd_dot, channels[1], cd);
    }
    if need_sum {
        // A sum that is not gray reads all three channels of AB and CD.
        if channels[2].len() == 3 {
            for (v, ch) in [(&mut *ab, channels[0]), (&mut *cd, channels[1])] {
                if ch.len() == 1 && rgb {
                    copy_red_to_green_blue(v, n);
                }
            }
        }
        let spare0_alpha = &regs[Register::Spare0 as usize][3];
        for &c in channels[2] {
            if o.mux_sum {
                // Spec (Aug 2000 sense): spare0 alpha < ½ selects AB, otherwise CD.
                for i in 0..n {
                    sum[c][i] = if spare0_alpha[i] < 0.5 { ab[c][i] } else { cd[c][i] };
                }
            } else {
                for i in 0..n {
                    sum[c][i] = ab[c][i] + cd[c][i];
                }
            }
        }
    }
    // Bias before scale, then clamp to [−1, 1]; only for the outputs that are kept, into
    // their registers (`direct`) or left in `out` for the caller to store.
    let (bias, scale) = (if o.bias == Bias::MinusOneHalf { -0.5 } else { 0.0 }, o.scale.factor());
    let finish = |x: f32| {
        let y = clamp_lo((x + bias) * scale, -1.0, 1.0);
        if fixed { quantize(y) } else { y }
    };
    for ((v, kept), ch) in [(ab, o.ab), (cd, o.cd), (sum, o.sum)].into_iter().zip(channels) {
        let Some(r) = kept else { continue };
        for &c in ch {
            if direct {
                for (d, &x) in regs[r as usize][c][..n].iter_mut().zip(&v[c][..n]) {
                    *d = finish(x);
                }
            } else {
                v[c][..n].iter_mut().for_each(|x| *x = finish(*x));
            }
        }
        if rgb && ch.len() == 1 {
            copy_red_to_green_blue(if direct { &mut regs[r as usize] } else { v }, n);
        }
    }
}

#[cfg(test)]
mod setup_tests;
#[cfg(test)]
mod tests;
