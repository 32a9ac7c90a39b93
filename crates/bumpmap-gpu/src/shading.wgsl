// bumpmap_core::shading, the lighting model, as WGSL: tests/lit_parity.rs checks shade()
// against the Rust definition on random fragments. Kilgard Eq. 11 (diffuse with Eq. 12's
// self-shadowing and the mip chain's length factor) and Eq. 16 (specular, gated).

struct Terms {
    ambient: vec3<f32>,
    diffuse: vec3<f32>,
    specular: vec3<f32>,
    shininess: f32,
    // SELF_SHADOW_RAMP (Eq. 12), SELF_SHADOW_STEP or SELF_SHADOW_OFF.
    self_shadow: u32,
    // SPECULAR_SHADOW_KILGARD (s_self, H_z >= 0), SPECULAR_SHADOW_CG_TUTORIAL (N'.L > 0 and
    // L_z > 0) or SPECULAR_SHADOW_OFF.
    specular_shadow: u32,
    // SPECULAR_FILTER_NONE, _TOKSVIG or _ROUGHNESS_MAP (the exponent from |N'|, SPECS.md 9), or
    // _LEAN or _CLEAN (the lobe from the moments).
    specular_filter: u32,
};

struct Fragment {
    // The filtered normal-map texel: RGB range-compressed N', A = |N'|.
    normal: vec4<f32>,
    decal: vec3<f32>,
    gloss: f32,
    l: vec3<f32>,
    h: vec3<f32>,
    // L.N and H.N with the unperturbed normal.
    l_n: f32,
    h_n: f32,
    // Attenuation x spotlight.
    light: f32,
    // The filtered LEAN moments: the mean slope B and (Mxx, Mxy, Myy).
    lean_b: vec2<f32>,
    lean_m: vec3<f32>,
    // And the mean slope-to-direction Jacobian J = 1/Nz^3.
    lean_j: f32,
    // The filtered roughness map's perceptual roughness.
    roughness: f32,
    // Ambient occlusion, multiplying the ambient term.
    occlusion: f32,
};

// x^k for a whole k by binary powering (the order of f32::powi).
fn powi(x0: f32, k: u32) -> f32 {
    var x = x0;
    var acc = 1.0;
    var e = k;
    loop {
        if (e & 1u) == 1u {
            acc = acc * x;
        }
        e = e >> 1u;
        if e == 0u {
            break;
        }
        x = x * x;
    }
    return acc;
}

fn specular_power(x: f32, s: f32) -> f32 {
    if s == trunc(s) && s <= 64.0 {
        return powi(x, u32(s));
    }
    return select(pow(x, s), 0.0, x <= 0.0);
}

// bumpmap_core::shading::toksvig: the filtered exponent and its energy factor.
fn toksvig(length: f32, s: f32) -> vec2<f32> {
    let len = clamp(length, 0.0, 1.0);
    let f = len / (len + s * (1.0 - len));
    let e = f * s;
    return vec2<f32>(e, (1.0 + e) / (1.0 + s));
}

// bumpmap_core::shading::roughness_exponent: a roughness texel as GGX alpha^2 = r^4 and the
// Blinn-Phong exponent and energy of that alpha.
fn roughness_exponent(roughness: f32, s: f32) -> vec2<f32> {
    let r = clamp(roughness, MIN_PERCEPTUAL_ROUGHNESS, 1.0);
    let alpha2 = (r * r) * (r * r);
    let e = max(2.0 / alpha2 - 2.0, 0.0);
    return vec2<f32>(e, (e + 2.0) / (s + 2.0));
}

// bumpmap_math::lean::LeanMoments::specular: the Gaussian of the slopes' covariance plus J/(s+1) at
// H's slope, widened by the mean Jacobian J, over Hz^3 (slopes to directions at H).
// bumpmap_math::lean::LeanMoments::isotropic (CLEAN): the second moments with the spread
// shared out, half of Mxx + Myy - |B|^2 along each axis.
fn clean_moments(b: vec2<f32>, m: vec3<f32>) -> vec3<f32> {
    let bx2 = b.x * b.x;
    let by2 = b.y * b.y;
    let half = 0.5 * ((m.x + m.z) - (bx2 + by2));
    return vec3<f32>(bx2 + half, b.x * b.y, by2 + half);
}

fn lean_specular(b: vec2<f32>, m: vec3<f32>, j: f32, h: vec3<f32>, s: f32) -> f32 {
    if h.z <= 1e-4 {
        return 0.0;
    }
    let inv_s = j / (s + 1.0);
    let sxx = m.x - b.x * b.x + inv_s;
    let sxy = m.y - b.x * b.y;
    let syy = m.z - b.y * b.y + inv_s;
    let det = max(sxx * syy - sxy * sxy, 1e-6 / ((s + 1.0) * (s + 1.0)));
    let hx = h.x / h.z - b.x;
    let hy = h.y / h.z - b.y;
    let e = (hx * hx * syy - 2.0 * hx * hy * sxy + hy * hy * sxx) / det;
    return exp(-0.5 * e) / ((s + 1.0) * sqrt(det)) / (h.z * h.z * h.z);
}

fn filtered_specular(h_dot_n: f32, s: f32, lobe_filter: u32, length: f32, roughness: f32) -> f32 {
    if lobe_filter == SPECULAR_FILTER_TOKSVIG {
        let k = toksvig(length, s);
        return specular_power(h_dot_n, k.x) * k.y;
    }
    if lobe_filter == SPECULAR_FILTER_ROUGHNESS_MAP {
        let k = roughness_exponent(roughness, s);
        return specular_power(h_dot_n, k.x) * k.y;
    }
    return specular_power(h_dot_n, s);
}

fn shade(t: Terms, f: Fragment) -> vec3<f32> {
    let nv = f.normal.rgb * 2.0 - 1.0;
    let n_dot_l = clamp(dot(f.l, nv), -1.0, 1.0);
    let h_dot_n = clamp(dot(f.h, nv), 0.0, 1.0);
    var s_self = 1.0;
    if t.self_shadow == SELF_SHADOW_RAMP {
        s_self = clamp(8.0 * f.l_n, 0.0, 1.0);
    } else if t.self_shadow == SELF_SHADOW_STEP {
        s_self = select(0.0, 1.0, f.l_n > 0.0);
    }
    var gate = 1.0;
    if t.specular_shadow == SPECULAR_SHADOW_KILGARD {
        gate = s_self * select(0.0, 1.0, f.h_n >= 0.0);
    } else if t.specular_shadow == SPECULAR_SHADOW_CG_TUTORIAL {
        gate = select(0.0, 1.0, n_dot_l > 0.0 && f.l_n > 0.0);
    }
    var power = 0.0;
    if t.specular_filter == SPECULAR_FILTER_LEAN {
        power = lean_specular(f.lean_b, f.lean_m, f.lean_j, f.h, t.shininess);
    } else if t.specular_filter == SPECULAR_FILTER_CLEAN {
        power = lean_specular(f.lean_b, clean_moments(f.lean_b, f.lean_m), f.lean_j, f.h, t.shininess);
    } else {
        power = filtered_specular(h_dot_n, t.shininess, t.specular_filter, f.normal.a, f.roughness);
    }
    let diffuse = min(t.ambient * f.occlusion + t.diffuse * (f.light * s_self * max(n_dot_l, 0.0) * f.normal.a), vec3<f32>(1.0));
    let specular = t.specular * (f.light * gate * f.gloss * power);
    return f.decal * diffuse + specular;
}
