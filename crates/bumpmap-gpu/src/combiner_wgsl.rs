//! A WGSL code generator for NV_register_combiners setups (SPECS.md §1): one [`CombinerSetup`]
//! becomes straight-line WGSL, specialised to that setup, that evaluates it exactly as the CPU
//! evaluator (`bumpmap_cpu::combiners::Combiners::run`) does; `tests/combiner_parity.rs` checks it
//! on random valid setups.
//!
//! [`combiners_wgsl`] returns a self-contained WGSL snippet that defines
//!
//! ```wgsl
//! struct Registers {
//!     tex0: vec4<f32>, tex1: vec4<f32>, tex2: vec4<f32>, tex3: vec4<f32>, // TEXTURE0..3_ARB
//!     primary: vec4<f32>,   // PRIMARY_COLOR_NV
//!     secondary: vec4<f32>, // SECONDARY_COLOR_NV
//! }
//! fn combiners(regs: Registers) -> vec4<f32>
//! ```
//!
//! plus, for [`Precision::Fixed9`], the helpers `nv_div255`, `nv_q9` and `nv_q9v`. `combiners`
//! returns the final combiner's fragment colour: `rgb = min(A·B + (1−A)·C + D, 1)`, `a = G`.
//!
//! The register set entering general combiner stage 0 is the one the CPU pipeline loads:
//! the six per-fragment registers above; ZERO = 0; CONSTANT_COLOR0_NV / 1_NV = the setup's
//! constants clamped to [0, 1] (as `Combiners::new` and `glCombinerParameterfvNV` do), baked in
//! as literals; FOG = (0, 0, 0, 1), fog disabled; SPARE0_NV = (0, 0, 0, texture0 alpha) — the
//! spec leaves its RGB undefined, a fresh `RegisterFile` holds 0 — and SPARE1_NV = 0 (undefined
//! in the spec, 0 in a fresh `RegisterFile`). Variables that read ZERO, the constants or FOG are
//! folded at generation time with the CPU's own arithmetic.
//!
//! Rounding points of `Precision::Fixed9`, as on the CPU: every *mapped* general-combiner
//! variable (A–D of both portions) and every *kept* stage output (after bias, scale and the
//! [−1, 1] clamp) is rounded to `round_half_away(clamp(x, −1, 1)·255)/255`. AB/CD products that
//! only feed the sum or mux are not rounded, and the final combiner computes in float.
//!
//! It does not: validate the setup (call [`CombinerSetup::validate`] first; an invalid setup
//! gives WGSL of unspecified meaning), emulate NV_register_combiners2's per-stage constants,
//! fog, the GeForce 256's wrong results above 2 with COLOR_SUM_CLAMP_NV off, disabled texture
//! units (the caller supplies all four registers), or the pipeline's carrying of SPARE0 RGB /
//! SPARE1 from one CPU batch to the next. NaN inputs are not matched (the CPU's clamps send a
//! NaN to the range's low end; WGSL's `max`/`clamp` on NaN are implementation-defined). It
//! cannot stop the driver from contracting `a·b + c` into an FMA or reassociating (WGSL has no
//! `precise`; naga emits no SPIR-V `NoContraction`): Float results agree to a few ulps, and in
//! Fixed9 a stage output whose exact value is a rounding tie — possible only for `(x − ½)·1` and
//! `x·½` outputs, as products of multiples of 1/255 are K/255² — may round the other way.
//! Only one setup per WGSL module (the names are fixed).

use std::fmt::Write as _;

use bumpmap_core::combiners as nv;
use nv::{
    Bias, CombinerSetup, ComponentUsage, FinalCombiner, FinalInput, FinalSource, Input, InputMapping, Outputs, Portion,
    Precision, Register, Scale,
};

/// The WGSL struct of per-fragment registers that `combiners()` takes.
pub const REGISTERS_WGSL: &str = "struct Registers {
    tex0: vec4<f32>,
    tex1: vec4<f32>,
    tex2: vec4<f32>,
    tex3: vec4<f32>,
    primary: vec4<f32>,
    secondary: vec4<f32>,
}
";

/// Fixed9 helpers, free of float rounding that a driver could change: `nv_div255(k)` builds
/// the f32 nearest k/255 (k in 0..=255) from integers — k/255 is k's byte repeated in binary,
/// 0.kkkk…, never a tie — instead of `OpFDiv` (2.5 ulp allowed in Vulkan); `nv_q9` is the CPU's
/// `quantize` (round half away from zero), with no product feeding an add (no FMA contraction).
const FIXED9_WGSL: &str = "fn nv_div255(k: u32) -> f32 {
    let b = firstLeadingBit(k) + 1u; // bit length of k
    let p = k * 0x01010101u; // k/255 to 32 bits
    let m = (p >> b) + ((p >> (b - 1u)) & 1u); // 24-bit significand, rounded
    return select(bitcast<f32>(((b + 118u) << 23u) + m - 0x800000u), 0.0, k == 0u);
}
fn nv_q9(x: f32) -> f32 {
    let y = clamp(x, -1.0, 1.0) * 255.0;
    let a = abs(y);
    let t = floor(a);
    let k = u32(t) + select(0u, 1u, a >= t + 0.5);
    return select(1.0, -1.0, y < 0.0) * nv_div255(k);
}
fn nv_q9v(v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(nv_q9(v.x), nv_q9(v.y), nv_q9(v.z));
}
";

/// WGSL for `setup` under `precision`: the `Registers` struct, the Fixed9 helpers if needed, and
/// `fn combiners(regs: Registers) -> vec4<f32>`. `setup` must be valid (`setup.validate()`).
pub fn combiners_wgsl(setup: &CombinerSetup, precision: Precision) -> String {
    let clamp01 = |c: [f32; 4]| c.map(|x| x.clamp(0.0, 1.0));
    let (c0, c1) = (clamp01(setup.constant0.to_array()), clamp01(setup.constant1.to_array()));
    let g = Gen { fixed: precision == Precision::Fixed9, c0, c1 };
    let mut w = String::from(REGISTERS_WGSL);
    if g.fixed {
        w += FIXED9_WGSL;
    }
    w += "fn combiners(regs: Registers) -> vec4<f32> {\n";
    w += "    // Writable registers entering stage 0; ZERO, CONSTANT_COLOR0/1_NV and FOG are folded.\n";
    for r in ["tex0", "tex1", "tex2", "tex3", "primary", "secondary"] {
        let _ = writeln!(w, "    var {r} = regs.{r};");
    }
    w += "    var spare0 = vec4<f32>(0.0, 0.0, 0.0, regs.tex0.a); // SPARE0_NV alpha = texture 0 alpha\n";
    w += "    var spare1 = vec4<f32>(0.0);\n";
    for (s, stage) in setup.stages.iter().enumerate() {
        // Both portions read this stage's input register set: all reads first, then the writes.
        let rgb = g.portion(&mut w, &format!("s{s}_rgb"), &stage.rgb, true);
        let alpha = g.portion(&mut w, &format!("s{s}_a"), &stage.alpha, false);
        for (dst, v) in rgb {
            let _ = writeln!(w, "    {0} = vec4<f32>({v}, {0}.a);", name(dst));
        }
        for (dst, v) in alpha {
            let _ = writeln!(w, "    {}.a = {v};", name(dst));
        }
    }
    g.final_combiner(&mut w, &setup.final_combiner);
    w += "}\n";
    w
}

struct Gen {
    fixed: bool,
    c0: [f32; 4],
    c1: [f32; 4],
}

/// The WGSL variable of a writable register.
fn name(r: Register) -> &'static str {
    match r {
        Register::PrimaryColor => "primary",
        Register::SecondaryColor => "secondary",
        Register::Spare0 => "spare0",
        Register::Spare1 => "spare1",
        Register::Texture0 => "tex0",
        Register::Texture1 => "tex1",
        Register::Texture2 => "tex2",
        Register::Texture3 => "tex3",
        Register::Zero | Register::ConstantColor0 | Register::ConstantColor1 | Register::Fog => {
            unreachable!("read-only registers are folded")
        }
    }
}

/// Fixed9's rounding, as the evaluators do it.
fn quantize(x: f32) -> f32 {
    Precision::quantize_fixed9(x)
}

/// An exact f32 literal: decimal when the decimal is the value exactly, else its bits.
fn lit(v: f32) -> String {
    let s = format!("{v:?}");
    if s.parse::<f64>() == Ok(v as f64) { s } else { format!("bitcast<f32>({:#010x}u /* {s} */)", v.to_bits()) }
}

fn vec3_lit(v: [f32; 3]) -> String {
    if v[0] == v[1] && v[1] == v[2] {
        format!("vec3<f32>({})", lit(v[0]))
    } else {
        format!("vec3<f32>({}, {}, {})", lit(v[0]), lit(v[1]), lit(v[2]))
    }
}

/// Table NV_register_combiners.4 as a WGSL expression on `x` (a vec3 if `rgb`, else an f32).
fn map_expr(m: InputMapping, x: &str, rgb: bool) -> String {
    let (z, o) = if rgb { ("vec3<f32>(0.0)", "vec3<f32>(1.0)") } else { ("0.0", "1.0") };
    match m {
        InputMapping::UnsignedIdentity => format!("max({x}, {z})"),
        InputMapping::UnsignedInvert => format!("(1.0 - clamp({x}, {z}, {o}))"),
        InputMapping::ExpandNormal => format!("(2.0 * max({x}, {z}) - 1.0)"),
        InputMapping::ExpandNegate => format!("(1.0 - 2.0 * max({x}, {z}))"),
        InputMapping::HalfBiasNormal => format!("(max({x}, {z}) - 0.5)"),
        InputMapping::HalfBiasNegate => format!("(0.5 - max({x}, {z}))"),
        InputMapping::SignedIdentity => x.to_string(),
        InputMapping::SignedNegate => format!("(-{x})"),
    }
}

impl Gen {
    /// The value of a read-only register, or `None` for a writable one.
    fn constant(&self, r: Register) -> Option<[f32; 4]> {
        match r {
            Register::Zero => Some([0.0; 4]),
            Register::ConstantColor0 => Some(self.c0),
            Register::ConstantColor1 => Some(self.c1),
            Register::Fog => Some([0.0, 0.0, 0.0, 1.0]),
            _ => None,
        }
    }

    /// A register's components by usage: `(source expression, folded value if read-only)`, a
    /// vec3 (RGB usage, or alpha replicated) when `rgb`, else an f32 (alpha, or blue).
    fn read(&self, r: Register, usage: ComponentUsage, rgb: bool) -> (String, Option<[f32; 3]>) {
        let pick = |v: [f32; 4]| match usage {
            ComponentUsage::Rgb => [v[0], v[1], v[2]],
            ComponentUsage::Alpha => [v[3]; 3],
            ComponentUsage::Blue => [v[2]; 3],
        };
        if let Some(v) = self.constant(r) {
            return (String::new(), Some(pick(v)));
        }
        let n = name(r);
        let src = match (usage, rgb) {
            (ComponentUsage::Rgb, _) => format!("{n}.rgb"),
            (ComponentUsage::Alpha, true) => format!("vec3<f32>({n}.a)"),
            (ComponentUsage::Alpha, false) => format!("{n}.a"),
            (ComponentUsage::Blue, _) => format!("{n}.b"),
        };
        (src, None)
    }

    /// A general-combiner variable: register, component usage, input mapping, and in Fixed9
    /// the rounding of the mapped value.
    fn general_input(&self, i: &Input, rgb: bool) -> String {
        let q = |s: String| {
            if !self.fixed {
                s
            } else if rgb {
                format!("nv_q9v({s})")
            } else {
                format!("nv_q9({s})")
            }
        };
        match self.read(i.register, i.usage, rgb) {
            (_, Some(v)) => {
                let v = v.map(|e| i.mapping.apply(e)).map(|e| if self.fixed { quantize(e) } else { e });
                if rgb { vec3_lit(v) } else { lit(v[0]) }
            }
            (src, None) => q(map_expr(i.mapping, &src, rgb)),
        }
    }

    /// Emits one portion's reads and arithmetic as `let`s named `{p}_…`; returns the kept
    /// outputs (destination register, finished value) for the caller to store after both
    /// portions have read the stage's inputs. A portion that writes nothing emits nothing.
    fn portion(&self, w: &mut String, p: &str, portion: &Portion, rgb: bool) -> Vec<(Register, String)> {
        let o: &Outputs = &portion.outputs;
        let need_sum = o.sum.is_some();
        let need = [o.ab.is_some() || need_sum, o.cd.is_some() || need_sum];
        if !need[0] && !need[1] {
            return Vec::new();
        }
        let _ = writeln!(w, "    // {p}: general combiner {} portion", if rgb { "RGB" } else { "alpha" });
        let pairs = [("ab", &portion.a, &portion.b, o.ab_dot), ("cd", &portion.c, &portion.d, o.cd_dot)];
        for (&(xy, x, y, dot), needed) in pairs.iter().zip(need) {
            if !needed {
                continue;
            }
            let (vx, vy) = (&xy[..1], &xy[1..]);
            let _ = writeln!(w, "    let {p}_{vx} = {};", self.general_input(x, rgb));
            let _ = writeln!(w, "    let {p}_{vy} = {};", self.general_input(y, rgb));
            let prod = if dot {
                // abDotProduct / cdDotProduct: 3-component dot in the CPU's order, replicated.
                let [x, y, z] = ["x", "y", "z"].map(|c| format!("{p}_{vx}.{c} * {p}_{vy}.{c}"));
                format!("vec3<f32>({x} + {y} + {z})")
            } else {
                format!("{p}_{vx} * {p}_{vy}")
            };
            let _ = writeln!(w, "    let {p}_{xy} = {prod};");
        }
        if need_sum {
            let sum = if o.mux_sum {
                // The mux reads SPARE0 alpha of this stage's inputs (Aug 2000 sense: < ½ → AB).
                format!("select({p}_cd, {p}_ab, spare0.a < 0.5)")
            } else {
                format!("{p}_ab + {p}_cd")
            };
            let _ = writeln!(w, "    let {p}_sum = {sum};");
        }
        // Bias before scale, then the [−1, 1] clamp (and the Fixed9 rounding).
        let bias = if o.bias == Bias::MinusOneHalf { " - 0.5" } else { "" };
        let scale = match o.scale {
            Scale::None => "",
            Scale::ByTwo => " * 2.0",
            Scale::ByFour => " * 4.0",
            Scale::ByOneHalf => " * 0.5",
        };
        let (lo, hi) = if rgb { ("vec3<f32>(-1.0)", "vec3<f32>(1.0)") } else { ("-1.0", "1.0") };
        let mut kept = Vec::new();
        for (dst, v) in [(o.ab, "ab"), (o.cd, "cd"), (o.sum, "sum")] {
            let Some(dst) = dst else { continue };
            let x = if bias.is_empty() { format!("{p}_{v}") } else { format!("({p}_{v}{bias})") };
            let c = format!("clamp({x}{scale}, {lo}, {hi})");
            let c = match (self.fixed, rgb) {
                (false, _) => c,
                (true, true) => format!("nv_q9v({c})"),
                (true, false) => format!("nv_q9({c})"),
            };
            let _ = writeln!(w, "    let {p}_{v}_out = {c};");
            kept.push((dst, format!("{p}_{v}_out")));
        }
        kept
    }

    /// A final-combiner variable A–F (vec3): `(expression, folded value if constant)`.
    fn final_input(&self, i: &FinalInput, clamp_sum: bool) -> (String, Option<[f32; 3]>) {
        let src = match i.source {
            FinalSource::Register(r) => match self.read(r, i.usage, true) {
                (_, Some(v)) => {
                    let v = v.map(|e| i.mapping.apply(e));
                    return (vec3_lit(v), Some(v));
                }
                (src, None) => src,
            },
            FinalSource::ETimesF => "fin_ef".to_string(),
            FinalSource::Spare0PlusSecondary => {
                let z = "vec3<f32>(0.0)";
                let s = format!("max(spare0.rgb, {z}) + max(secondary.rgb, {z})");
                if clamp_sum { format!("min({s}, vec3<f32>(1.0))") } else { format!("({s})") }
            }
        };
        (map_expr(i.mapping, &src, true), None)
    }

    /// The final combiner: E·F if A–D read it, then `min(A·B + (1−A)·C + D, 1)` with the
    /// terms that constant inputs make exact dropped (as the CPU does), and G.
    fn final_combiner(&self, w: &mut String, f: &FinalCombiner) {
        w.push_str("    // Final combiner\n");
        let cs = f.color_sum_clamp;
        if [&f.a, &f.b, &f.c, &f.d].iter().any(|i| i.source == FinalSource::ETimesF) {
            let _ = writeln!(w, "    let fin_e = {};", self.final_input(&f.e, cs).0);
            let _ = writeln!(w, "    let fin_f = {};", self.final_input(&f.f, cs).0);
            w.push_str("    let fin_ef = fin_e * fin_f; // E_TIMES_F_NV\n");
        }
        let uniform = |v: Option<[f32; 3]>| v.filter(|v| v[0] == v[1] && v[1] == v[2]).map(|v| v[0]);
        let [(a, ak), (b, _), (c, ck), (d, dk)] = [&f.a, &f.b, &f.c, &f.d].map(|i| self.final_input(i, cs));
        let (a_k, c_zero, d_zero) = (uniform(ak), uniform(ck) == Some(0.0), uniform(dk) == Some(0.0));
        // A = 0: A·B + 1·C exactly; A = 1: B + 0·C; C = 0 or D = 0: its term is +0 exactly.
        let (lerp, reads) = match (a_k, c_zero) {
            (Some(0.0), true) => (None, [false; 3]),
            (Some(0.0), false) => (Some("fin_c"), [false, false, true]),
            (Some(1.0), _) => (Some("fin_b"), [false, true, false]),
            (_, true) => (Some("fin_a * fin_b"), [true, true, false]),
            _ => (Some("fin_a * fin_b + (1.0 - fin_a) * fin_c"), [true; 3]),
        };
        for ((n, e), r) in
            [("a", &a), ("b", &b), ("c", &c), ("d", &d)].into_iter().zip([reads[0], reads[1], reads[2], !d_zero])
        {
            if r {
                let _ = writeln!(w, "    let fin_{n} = {e};");
            }
        }
        let rgb = match (lerp, d_zero) {
            (None, true) => "vec3<f32>(0.0)".to_string(),
            (None, false) => "fin_d".to_string(),
            (Some(l), true) => l.to_string(),
            (Some(l), false) => format!("{l} + fin_d"),
        };
        // G: alpha or blue of a register.
        let FinalSource::Register(r) = f.g.source else { unreachable!("validated: G reads a register") };
        let g = match self.read(r, f.g.usage, false) {
            (_, Some(v)) => lit(f.g.mapping.apply(v[0])),
            (src, None) => map_expr(f.g.mapping, &src, false),
        };
        let _ = writeln!(w, "    return vec4<f32>(min({rgb}, vec3<f32>(1.0)), {g});");
    }
}

/// The whole fragment shader of a combiner pass: each texture unit samples its texture (2D at
/// varyings (s, t) with implicit derivatives, or the cube map at varyings (r, r+1, r+2), level
/// 0) into `TEXTURE<i>`, PRIMARY_COLOR is the interpolated vertex colour where the program asks
/// for it and white otherwise, SECONDARY_COLOR black, SPARE0's alpha starts as texture 0's alpha (0 without units), then
/// [`combiners_wgsl`]'s function. Binding 3i is unit i's 2D texture, 3i + 1 its cube texture,
/// 3i + 2 its sampler. Precondition: at most four units and a setup that validates.
pub fn fragment_shader(p: &bumpmap_core::technique::CombinerProgram) -> String {
    use bumpmap_core::technique::Binding;
    let mut s = String::new();
    for i in 0..4 {
        let _ = writeln!(
            s,
            "@group(0) @binding({}) var unit{i}_2d: texture_2d<f32>;\n@group(0) @binding({}) var unit{i}_cube: texture_cube<f32>;\n@group(0) @binding({}) var unit{i}_sampler: sampler;",
            3 * i,
            3 * i + 1,
            3 * i + 2
        );
    }
    s += &combiners_wgsl(&p.setup, p.precision);
    s += "\n@fragment\nfn fs_combiners(f: Varyings) -> @location(0) vec4<f32> {\n    var regs: Registers;\n";
    let primary = if p.vertex_color {
        let k = bumpmap_core::vertex::var::COLOR;
        format!("vec4<f32>({}, {}, {}, {})", slot(k), slot(k + 1), slot(k + 2), slot(k + 3))
    } else {
        "vec4<f32>(1.0)".to_string()
    };
    let _ = writeln!(s, "    regs.primary = {primary};\n    regs.secondary = vec4<f32>(0.0);");
    for (i, unit) in p.units.iter().enumerate().take(4) {
        let _ = match unit.binding {
            Binding::TwoD { s: ks, t: kt, .. } => writeln!(
                s,
                "    regs.tex{i} = textureSample(unit{i}_2d, unit{i}_sampler, vec2<f32>({}, {}));",
                slot(ks),
                slot(kt)
            ),
            Binding::NormalizationCube { r, .. } => {
                writeln!(
                    s,
                    "    regs.tex{i} = textureSampleLevel(unit{i}_cube, unit{i}_sampler, vec3<f32>({}, {}, {}), 0.0);",
                    slot(r),
                    slot(r + 1),
                    slot(r + 2)
                )
            }
        };
    }
    s +=
        "    let color = combiners(regs);\n    if clamp(color.a, 0.0, 1.0) < ALPHA_CUTOFF {\n        discard;\n    }\n";
    s += "    return color;\n}\n";
    s
}

/// Varying slot `k` (`bumpmap_core::vertex::var`) as a field of the prelude's `Varyings`,
/// e.g. `f.v1.z`: a static access, where `vary(f, k)` builds an array and indexes it.
fn slot(k: usize) -> String {
    format!("f.v{}.{}", k / 4, ['x', 'y', 'z', 'w'][k % 4])
}
