//! The WGSL every program starts with, generated from the Rust constants it must agree with, so
//! that no number crosses the Rust–WGSL boundary written twice:
//!
//! - the vertex stage: the vec4 locations that carry [`bumpmap_core::vertex::MAX_VARYINGS`]
//!   varyings, `vs_main`, and `vary`/`vary3` to read slot k;
//! - each varying slot of [`bumpmap_core::vertex::var`] as a constant (`VAR_L`, `VAR_H`, …);
//! - the lit program's switches: their override constants (named by
//!   `crate::lit::LitVariant::overrides`) and a constant per value (`SELF_SHADOW_RAMP`, …)
//!   whose number is the one [`crate::lit::LitVariant::of`] passes;
//! - the model's own numbers (`MIN_PERCEPTUAL_ROUGHNESS`).
//!
//! `lit.wgsl` and `shading.wgsl` use these names and declare no constant of their own (this
//! module's tests check both, and that the compiled program's constants equal Rust's).

use std::fmt::Write as _;

use bumpmap_core::vertex::{MAX_VARYINGS, var};

use crate::lit::{self, LitVariant, Override};

/// The lit program's fragment stage, after the prelude and the model.
pub(crate) const LIT_WGSL: &str = include_str!("lit.wgsl");
/// `bumpmap_core::shading::shade` in WGSL (with its `Terms` and `Fragment`); it reads the
/// prelude's switch constants ([`shading_wgsl`]).
pub(crate) const SHADING_WGSL: &str = include_str!("shading.wgsl");
/// `bumpmap_core::detail::detail_normal` in WGSL; it reads the prelude's `DETAIL_*` values.
pub(crate) const DETAIL_WGSL: &str = include_str!("detail.wgsl");
/// `bumpmap_core::parallax` in WGSL; it reads the prelude's switches and constants, and the
/// includer's height functions ([`parallax_wgsl`]).
pub(crate) const PARALLAX_WGSL: &str = include_str!("parallax.wgsl");

/// The override constant both kinds of fragment program discard below: a pass's alpha test
/// cutoff, or −1 (none). Declared by the vertex stage.
pub(crate) const ALPHA_CUTOFF: &str = "ALPHA_CUTOFF";

/// The varying slots by the names WGSL uses.
pub(crate) const SLOTS: [(&str, usize); 19] = [
    ("VAR_S", var::S),
    ("VAR_T", var::T),
    ("VAR_L", var::L),
    ("VAR_H", var::H),
    ("VAR_V", var::V),
    ("VAR_LIGHT_DISTANCE", var::LIGHT_DISTANCE),
    ("VAR_SPOT", var::SPOT),
    ("VAR_PROJ", var::PROJ),
    ("VAR_N", var::N),
    ("VAR_EMBOSS", var::EMBOSS),
    ("VAR_EMBOSS_UNFORCED", var::EMBOSS_UNFORCED),
    ("VAR_PARAM_FRAME", var::PARAM_FRAME),
    ("VAR_TEX_VIEW", var::TEX_VIEW),
    ("VAR_TEX_LIGHT", var::TEX_LIGHT),
    ("VAR_TANGENT_FROM_TEX", var::TANGENT_FROM_TEX),
    ("VAR_CURVATURE", var::CURVATURE),
    ("VAR_COLOR", var::COLOR),
    ("VAR_TANGENT", var::TANGENT),
    ("VAR_COUNT", var::COUNT),
];

/// The model's numbers `shading.wgsl` and `parallax.wgsl` read, by their Rust names (and
/// `F32_INFINITY`, `f32::MAX`, where Rust says infinity: WGSL has no literal for it).
pub(crate) const MODEL_CONSTANTS: [(&str, f32); 7] = [
    ("MIN_PERCEPTUAL_ROUGHNESS", bumpmap_core::shading::MIN_PERCEPTUAL_ROUGHNESS),
    ("SHADOW_BIAS", bumpmap_core::parallax::SHADOW_BIAS),
    ("SOFT_SHADOW_SHARPNESS", bumpmap_core::parallax::SOFT_SHADOW_SHARPNESS),
    ("EXACT_SHADOW_LIFT", bumpmap_core::parallax::EXACT_SHADOW_LIFT),
    ("MAX_ANISOTROPY", bumpmap_core::parallax::MAX_ANISOTROPY),
    ("HORIZON_EDGE", bumpmap_math::horizon::HORIZON_EDGE),
    ("F32_INFINITY", f32::MAX),
];

/// The marches' counts `parallax.wgsl` reads, by their Rust names.
pub(crate) const MODEL_COUNTS: [(&str, u32); 4] = [
    ("RELIEF_BISECTIONS", bumpmap_core::parallax::RELIEF_BISECTIONS),
    ("SAMPLES_PER_CELL", bumpmap_math::height_trace::SAMPLES_PER_CELL as u32),
    ("BISECTIONS", bumpmap_math::height_trace::BISECTIONS as u32),
    ("AZIMUTHS", bumpmap_math::horizon::AZIMUTHS as u32),
];

/// vec4 locations carrying the varyings.
pub(crate) const LOCATIONS: usize = MAX_VARYINGS / 4;
// The vertex buffer holds the varyings whole vec4s at a time.
const _: () = assert!(MAX_VARYINGS.is_multiple_of(4));

/// The vertex stage: the clip position (depth remapped from GL's [−1, 1] to wgpu's [0, 1], so
/// window depth is GL's (z/w + 1)/2) and the varyings, four to a location, interpolated
/// perspective-correctly; `vary`/`vary3` read slot k.
pub(crate) fn vertex_stage() -> String {
    let mut s =
        String::from("// Generated from bumpmap_core::vertex (bumpmap-gpu src/prelude.rs): the vertex stage.\n");
    let locations =
        |first: usize| (0..LOCATIONS).map(move |i| format!("    @location({}) v{i}: vec4<f32>,\n", i + first));
    s += "struct VertexIn {\n    @location(0) clip: vec4<f32>,\n";
    s.extend(locations(1));
    s += "};\n\nstruct Varyings {\n";
    s += "    // @invariant: every pipeline computes the same depth for the same vertices, so depth\n";
    s += "    // EQUAL holds across passes.\n    @builtin(position) @invariant position: vec4<f32>,\n";
    s.extend(locations(0));
    s += "};\n\n@vertex\nfn vs_main(v: VertexIn) -> Varyings {\n    var o: Varyings;\n";
    s += "    o.position = vec4<f32>(v.clip.x, v.clip.y, 0.5 * (v.clip.z + v.clip.w), v.clip.w);\n";
    for i in 0..LOCATIONS {
        let _ = writeln!(s, "    o.v{i} = v.v{i};");
    }
    s += "    return o;\n}\n\n// Varying slot k (VAR_*).\nfn vary(f: Varyings, k: u32) -> f32 {\n";
    let fields: Vec<String> = (0..LOCATIONS).map(|i| format!("f.v{i}")).collect();
    let _ = writeln!(s, "    let slots = array<vec4<f32>, {LOCATIONS}>({});", fields.join(", "));
    s += "    return slots[k / 4u][k % 4u];\n}\n\n// Slots k, k + 1, k + 2 as a vector.\n";
    s += "fn vary3(f: Varyings, k: u32) -> vec3<f32> {\n    return vec3<f32>(vary(f, k), vary(f, k + 1u), vary(f, k + 2u));\n}\n";
    for (name, slot) in SLOTS {
        let _ = writeln!(s, "const {name}: u32 = {slot}u;");
    }
    let _ = writeln!(
        s,
        "// The pass's alpha test (glAlphaFunc(GL_GEQUAL, cutoff)), or -1: none.\noverride {}: f32 = -1.0;",
        ALPHA_CUTOFF
    );
    s
}

/// The lit program's switches: each override constant with its default (the default variant's
/// value), and each named value's constant.
pub(crate) fn switches() -> String {
    let mut s = String::from("// Generated from bumpmap-gpu src/lit.rs: the lit program's switches.\n");
    for (name, value) in LitVariant::default().overrides() {
        let _ = match value {
            Override::Flag(b) => writeln!(s, "override {name}: bool = {b};"),
            Override::Code(c) => writeln!(s, "override {name}: u32 = {c}u;"),
            Override::Float(x) => writeln!(s, "override {name}: f32 = {x:?};"),
        };
    }
    for (name, code) in lit::named_values() {
        let _ = writeln!(s, "const {name}: u32 = {code}u;");
    }
    for (name, value) in MODEL_CONSTANTS {
        let _ = writeln!(s, "const {name}: f32 = {value:?};");
    }
    for (name, value) in MODEL_COUNTS {
        let _ = writeln!(s, "const {name}: u32 = {value}u;");
    }
    s
}

/// `bumpmap_core::parallax`'s marches in WGSL with the constants they read; the includer
/// defines how heights are read (`parallax.wgsl`'s head says which functions).
pub fn parallax_wgsl() -> String {
    format!("{}\n{}", switches(), PARALLAX_WGSL)
}

/// `bumpmap_core::shading::shade` and `bumpmap_core::detail::detail_normal` in WGSL with the
/// constants they read: what the lit program includes, and what the tests run against the Rust
/// definitions.
pub fn shading_wgsl() -> String {
    format!("{}\n{}\n{}", switches(), SHADING_WGSL, DETAIL_WGSL)
}

/// `lit.wgsl`'s uniform block `Lit`, a `vec4<f32>` per member of [`lit::LitMember::ALL`] in
/// that order, with what each holds: the order [`lit::uniforms`] packs the bytes in.
pub(crate) fn lit_block() -> String {
    let mut s = String::from(
        "// Generated from bumpmap-gpu src/lit.rs (LitMember): the lit program's uniform block.\nstruct Lit {\n",
    );
    for m in lit::LitMember::ALL {
        let _ = writeln!(s, "    // {}\n    {}: vec4<f32>,", m.holds(), m.name());
    }
    s += "};\n";
    s
}

/// The whole lit program: the vertex stage, the switches, the model, the marches, the uniform
/// block and `lit.wgsl`.
pub(crate) fn lit_program() -> String {
    format!("{}\n{}\n{}\n{}\n{}", vertex_stage(), shading_wgsl(), PARALLAX_WGSL, lit_block(), LIT_WGSL)
}

#[cfg(test)]
mod tests {
    use wgpu::naga;

    use super::*;

    /// The value of the `u32` constant `name` in `module`.
    fn constant(module: &naga::Module, name: &str) -> u32 {
        let (_, c) = module
            .constants
            .iter()
            .find(|(_, c)| c.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("the lit program declares no constant {name}"));
        match module.global_expressions[c.init] {
            naga::Expression::Literal(naga::Literal::U32(v)) => v,
            ref other => panic!("{name} is {other:?}"),
        }
    }

    #[test]
    fn the_compiled_program_holds_the_rust_constants() {
        let module = naga::front::wgsl::parse_str(&lit_program()).expect("the lit program parses");
        for (name, slot) in SLOTS {
            assert_eq!(constant(&module, name) as usize, slot, "{name}");
        }
        for (name, code) in lit::named_values() {
            assert_eq!(constant(&module, name), code, "{name}");
        }
        for (name, value) in MODEL_CONSTANTS {
            let (_, c) = module.constants.iter().find(|(_, c)| c.name.as_deref() == Some(name)).expect(name);
            match module.global_expressions[c.init] {
                naga::Expression::Literal(naga::Literal::F32(v)) => assert_eq!(v, value, "{name}"),
                ref other => panic!("{name} is {other:?}"),
            }
        }
        for (name, value) in MODEL_COUNTS {
            assert_eq!(constant(&module, name), value, "{name}");
        }
        let overrides: Vec<&str> = module.overrides.iter().filter_map(|(_, o)| o.name.as_deref()).collect();
        for (name, _) in LitVariant::default().constants() {
            assert!(overrides.contains(&name), "the pipeline sets {name}, which the program does not declare");
        }
        assert!(overrides.contains(&ALPHA_CUTOFF));
        assert_eq!(overrides.len(), LitVariant::default().constants().len() + 1, "{overrides:?}");
    }

    /// The uniform block the compiled program reads is `LitMember::ALL` in order, a vec4 of
    /// 16 bytes each, as `uniforms` packs it: no member moved, missing or extra.
    #[test]
    fn the_uniform_block_is_what_rust_packs() {
        let module = naga::front::wgsl::parse_str(&lit_program()).expect("the lit program parses");
        let lit = module.types.iter().find(|(_, t)| t.name.as_deref() == Some("Lit")).expect("a struct Lit");
        let naga::TypeInner::Struct { members, span } = &lit.1.inner else { panic!("Lit is a struct") };
        let names: Vec<&str> = members.iter().filter_map(|m| m.name.as_deref()).collect();
        let expected: Vec<&str> = lit::LitMember::ALL.iter().map(|m| m.name()).collect();
        assert_eq!(names, expected);
        for (k, m) in members.iter().enumerate() {
            assert_eq!(m.offset as usize, 16 * k, "{:?}", m.name);
        }
        // `uniforms` packs one [f32; 4] a member.
        assert_eq!(*span as usize, 16 * lit::LitMember::ALL.len());
        assert!(!LIT_WGSL.contains("struct Lit {"), "lit.wgsl declares no block of its own");
    }

    #[test]
    fn the_wgsl_files_restate_no_rust_number() {
        // A slot or a switch value written as a number here would not follow a change in Rust:
        // slots are read by their VAR_* names, switches compared with their values' names.
        let switches: Vec<&str> = LitVariant::default().constants().iter().map(|(n, _)| *n).collect();
        for (file, source) in [
            ("lit.wgsl", LIT_WGSL),
            ("shading.wgsl", SHADING_WGSL),
            ("parallax.wgsl", PARALLAX_WGSL),
            ("detail.wgsl", DETAIL_WGSL),
        ] {
            for (i, line) in source.lines().enumerate() {
                let code = line.split("//").next().unwrap_or_default().trim();
                let at = format!("{file}:{}: {code}", i + 1);
                assert!(!code.starts_with("const ") && !code.starts_with("override "), "declared by the prelude: {at}");
                for call in ["vary(f, ", "vary3(f, "] {
                    for (k, _) in code.match_indices(call) {
                        assert!(code[k + call.len()..].starts_with("VAR_"), "a slot by number: {at}");
                    }
                }
                let digit_after = |k: usize| code[k..].trim_start().starts_with(|c: char| c.is_ascii_digit());
                for name in &switches {
                    for (k, _) in code.match_indices(&format!("{name} ==")) {
                        assert!(!digit_after(k + name.len() + 3), "a switch value by number: {at}");
                    }
                }
                for field in ["self_shadow ==", "specular_shadow =="] {
                    for (k, _) in code.match_indices(field) {
                        assert!(!digit_after(k + field.len()), "a switch value by number: {at}");
                    }
                }
                if let Some(k) = code.find("case ") {
                    assert!(!digit_after(k + 5), "a switch value by number: {at}");
                }
            }
        }
    }
}
