// bumpmap_core::detail::detail_normal, a detail normal map laid over the base's filtered normal,
// as WGSL: tests/detail_parity.rs checks it against the Rust definition on random texels. The
// blends are bumpmap_math::detail's; the method is one of the prelude's DETAIL_* values.

// normalize(v), or `fallback` where v has no direction (glam's normalize_or).
fn detail_normalize_or(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let r = 1.0 / length(v);
    if r > 0.0 && r < 3.0e38 {
        return v * r;
    }
    return fallback;
}

fn detail_overlay(a: f32, b: f32) -> f32 {
    if a < 0.5 {
        return 2.0 * a * b;
    }
    return 1.0 - 2.0 * (1.0 - a) * (1.0 - b);
}

// `n2` laid over `n1` (both unit) by `method` (bumpmap_math::detail::blend).
fn detail_blend(n1: vec3<f32>, n2: vec3<f32>, method: u32) -> vec3<f32> {
    var b: vec3<f32>;
    switch method {
        case DETAIL_RNM: {
            let t = n1 + vec3<f32>(0.0, 0.0, 1.0);
            let u = n2 * vec3<f32>(-1.0, -1.0, 1.0);
            b = t * dot(t, u) / t.z - u;
        }
        case DETAIL_PARTIAL_DERIVATIVE: {
            b = vec3<f32>(n1.x * n2.z + n2.x * n1.z, n1.y * n2.z + n2.y * n1.z, n1.z * n2.z);
        }
        case DETAIL_WHITEOUT: {
            b = vec3<f32>(n1.xy + n2.xy, n1.z * n2.z);
        }
        case DETAIL_UDN: {
            b = vec3<f32>(n1.xy + n2.xy, n1.z);
        }
        case DETAIL_LINEAR: {
            b = n1 + n2;
        }
        case DETAIL_OVERLAY: {
            let a = n1 * 0.5 + 0.5;
            let c = n2 * 0.5 + 0.5;
            b = vec3<f32>(detail_overlay(a.x, c.x), detail_overlay(a.y, c.y), detail_overlay(a.z, c.z)) * 2.0 - 1.0;
        }
        default: {
            b = n1;
        }
    }
    return detail_normalize_or(b, n1);
}

// 1 / |N| - 1: a filtered normal's length as a slope variance (Toksvig).
fn detail_variance(a: f32) -> f32 {
    return 1.0 / clamp(a, 1.0e-4, 1.0) - 1.0;
}

// `detail` (RGB range-compressed, A its length) over `base` (the same) at `strength`.
fn detail_normal(base: vec4<f32>, detail: vec4<f32>, method: u32, strength: f32) -> vec4<f32> {
    if strength == 0.0 {
        return base;
    }
    let z = vec3<f32>(0.0, 0.0, 1.0);
    let n1 = detail_normalize_or(base.rgb * 2.0 - 1.0, z);
    let d = detail_normalize_or(detail.rgb * 2.0 - 1.0, z);
    let n2 = detail_normalize_or(vec3<f32>(d.xy * strength, d.z), z);
    let n = detail_blend(n1, n2, method) * 0.5 + 0.5;
    let a = 1.0 / (1.0 + detail_variance(base.a) + strength * strength * detail_variance(detail.a));
    return vec4<f32>(n, a);
}
