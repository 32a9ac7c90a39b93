//! The paper's setups (`bumpmap_core::setups`, Kilgard Appendices G and H) evaluated on
//! known vectors: what each appendix computes, checked against its equations.

use crate::combiners::{Combiners, LANES, Precision, RegisterFile};
use bumpmap_core::combiners::{CombinerSetup, Register::*};
use bumpmap_core::setups::*;
use glam::Vec3;
use glam::Vec4;

/// Evaluates `setup` with range-compressed texels: N' and |N'| in texture 0, a vector in
/// texture 1 (as a cube map would return it, exactly).
fn eval(setup: CombinerSetup, n: Vec3, len: f32, v: Vec3) -> Vec4 {
    let comb = Combiners::new(setup, Precision::Float).unwrap();
    let mut regs = RegisterFile::new();
    comb.load_constants(&mut regs, 1);
    let pack = |x: Vec3| (x + Vec3::ONE) * 0.5;
    let (t0, t1) = (pack(n).extend(len), pack(v).extend(1.0));
    for c in 0..4 {
        regs.reg_mut(Texture0)[c][0] = t0[c];
        regs.reg_mut(Texture1)[c][0] = t1[c];
    }
    regs.reg_mut(Spare0)[3][0] = t0.w; // SPARE0 alpha starts as texture 0's alpha
    let mut out = [[0.0; LANES]; 4];
    comb.run(&mut regs, 1, &mut out);
    Vec4::new(out[0][0], out[1][0], out[2][0], out[3][0])
}

#[test]
fn appendix_g_evaluates_eq_11_and_12() {
    let (amb, kd) = (Vec4::new(0.1, 0.1, 0.1, 0.0), Vec4::new(0.9, 1.0, 1.0, 0.0));
    let n = Vec3::new(0.3, -0.2, 0.9).normalize();
    for l in [
        Vec3::new(0.5, 0.1, 0.8).normalize(),
        Vec3::new(0.7, 0.1, 0.07).normalize(),
        Vec3::new(0.1, 0.3, -0.5).normalize(),
    ] {
        let got = eval(ambient_and_diffuse(amb, kd), n, 0.8, l);
        let s_self = (8.0 * l.z).clamp(0.0, 1.0);
        let want = amb.truncate() + kd.truncate() * s_self * 0.8 * l.dot(n).max(0.0);
        assert!((got.truncate() - want.min(Vec3::ONE)).abs().max_element() < 1e-5, "L={l}: {got} vs {want}");
        assert!((got.w - s_self).abs() < 1e-6, "alpha holds s_self");
    }
    let unshadowed = eval(ambient_and_diffuse_unshadowed(amb, kd), n, 1.0, Vec3::new(0.7, 0.1, 0.05).normalize());
    assert_eq!(unshadowed.w, 1.0);
}

#[test]
fn appendix_h_evaluates_the_eighth_power_gated_by_hz() {
    let n = Vec3::new(0.1, 0.2, 0.97).normalize();
    let h = Vec3::new(0.2, 0.1, 0.95).normalize();
    let got = eval(specular(), n, 1.0, h);
    let want = h.dot(n).max(0.0).powi(8);
    assert!((got.x - want).abs() < 1e-5 && got.w == 0.0, "{got} vs {want}");
    // H below the surface (H_z < 0): the mux zeroes the term even though H·N' > 0.
    let below = Vec3::new(0.9, 0.0, -0.1).normalize();
    let tilted = Vec3::new(0.9, 0.0, 0.2).normalize();
    assert_eq!(eval(specular(), tilted, 1.0, below).x, 0.0);
    assert!(eval(specular(), tilted, 1.0, Vec3::new(0.9, 0.0, 0.1).normalize()).x > 0.3);
}

#[test]
fn specular_ramp_is_zero_below_three_quarters_and_one_at_one() {
    let up = Vec3::Z;
    assert!((eval(specular_ramp(), up, 1.0, up).x - 1.0).abs() < 1e-6);
    let h = Vec3::new(0.0, 0.8, 0.6); // H·N' = 0.6 < ¾
    assert_eq!(eval(specular_ramp(), up, 1.0, h).x, 0.0);
    let h = Vec3::new(0.0, 0.5, 0.866); // 4·(0.866 − 0.75) = 0.464, squared 0.215
    assert!((eval(specular_ramp(), up, 1.0, h).x - 0.2153).abs() < 2e-3);
}
