// The single pass's fragment program: the texture lookups, per-fragment renormalization,
// attenuation and spotlight that make a Fragment, then shading.wgsl's shade(). Texture units:
// the normal map, the decal, the gloss map (white 1x1 textures where absent), the spotlight
// pattern and the normalization cube map.

struct Lit {
    ambient: vec4<f32>,
    diffuse: vec4<f32>,
    // xyz: k_specular · light colour.
    specular: vec4<f32>,
    // Polynomial: constant, linear, quadratic; exponential: density in x.
    attenuation: vec4<f32>,
    // x: cos(cutoff); y: exponent.
    spot: vec4<f32>,
    // xy: the texture-coordinate scale of a map made for the surface (NormalSpace::texcoord_scale;
    // 1, 1 for a map that repeats with the texture).
    normal_scale: vec4<f32>,
    // x: an offset map's range; yz: the derivatives' scale (NormalTexels::Derivatives).
    texels: vec4<f32>,
};

// The model's switches, one pipeline per combination (src/lit.rs, LitVariant).
// Self-shadow: 0 Eq. 12's ramp, 1 step, 2 off. Specular gate: 0 Kilgard, 1 Cg Tutorial, 2 off.
override SELF_SHADOW: u32 = 0u;
override SPECULAR_SHADOW: u32 = 0u;
// Renormalize L and H by the cube map (1) or by math (0).
override NORMALIZE_CUBE: u32 = 0u;
// H per fragment from L and V (1) or interpolated from the vertices (0).
override FRAGMENT_HALF_ANGLE: u32 = 0u;
// Gloss: 0 none, 1 the decal's alpha, 2 the gloss map's red.
override GLOSS: u32 = 0u;
// The normal map is in object space (1) or tangent space (0).
override OBJECT_SPACE: u32 = 0u;
// Attenuation: 0 none, 1 polynomial, 2 exp, 3 exp2.
override ATTENUATION: u32 = 0u;
// A spotlight (1), and a pattern projected by it (1).
override SPOTLIGHT: u32 = 0u;
override SPOT_PATTERN: u32 = 0u;
override SHININESS: f32 = 8.0;
// The normal map's texels: 0 unit normals, 1 an offset map, 2 height derivatives for a
// per-pixel Blinn (range and scale in u.texels).
override NORMAL_TEXELS: u32 = 0u;

@group(0) @binding(0) var<uniform> u: Lit;
@group(0) @binding(1) var normal_map: texture_2d<f32>;
@group(0) @binding(2) var decal_map: texture_2d<f32>;
@group(0) @binding(3) var gloss_map: texture_2d<f32>;
@group(0) @binding(4) var pattern_map: texture_2d<f32>;
@group(0) @binding(5) var cube_map: texture_cube<f32>;
@group(0) @binding(6) var material_sampler: sampler;
@group(0) @binding(7) var clamp_sampler: sampler;

const S: u32 = 0u;
const L: u32 = 2u;
const H: u32 = 5u;
const V: u32 = 8u;
const LIGHT_DISTANCE: u32 = 11u;
const SPOT: u32 = 12u;
const PROJ: u32 = 15u;
const N: u32 = 18u;
const PARAM_FRAME: u32 = 25u;

// normalize(v), or +Z where v has no direction.
fn normalize_or_z(v: vec3<f32>) -> vec3<f32> {
    let d = dot(v, v);
    if d > 0.0 && d < 3.0e38 {
        return v * inverseSqrt(d);
    }
    return vec3<f32>(0.0, 0.0, 1.0);
}

// Per-fragment renormalization: by math, or by the cube map expanded as 2c - 1.
fn unit(v: vec3<f32>) -> vec3<f32> {
    if NORMALIZE_CUBE == 1u {
        return textureSampleLevel(cube_map, clamp_sampler, v, 0.0).rgb * 2.0 - 1.0;
    }
    return normalize_or_z(v);
}

fn attenuation(d: f32) -> f32 {
    let a = u.attenuation;
    switch ATTENUATION {
        case 1u: {
            return clamp(1.0 / (a.x + a.y * d + a.z * d * d), 0.0, 1.0);
        }
        case 2u: {
            return exp(-a.x * d);
        }
        case 3u: {
            let x = a.x * d;
            return exp(-(x * x));
        }
        default: {
            return 1.0;
        }
    }
}

fn spot_factor(f: Varyings) -> f32 {
    if SPOTLIGHT == 0u {
        return 1.0;
    }
    let c = -dot(normalize_or_z(vary3(f, L)), normalize_or_z(vary3(f, SPOT)));
    var k = 0.0;
    if c >= u.spot.x {
        k = select(select(pow(c, u.spot.y), 0.0, c <= 0.0), 1.0, u.spot.y == 0.0);
    }
    if SPOT_PATTERN == 1u {
        let p = vary3(f, PROJ);
        var pattern = 0.0;
        if p.z > 0.0 {
            pattern = textureSampleLevel(pattern_map, clamp_sampler, p.xy / p.z, 0.0).r;
        }
        k = k * pattern;
    }
    return k;
}

// An offset-map texel (Kilgard Eq. 6-7) as a normal-map texel: N' = normalize((0, 0, 1) + D)
// with D = range (2 rg - 1), range-compressed, A = 1 (bumpmap_core::shading::offset_to_normal).
fn offset_to_normal(t: vec4<f32>, range: f32) -> vec4<f32> {
    let d = (t.xy * 2.0 - 1.0) * range;
    let inv = 1.0 / sqrt(d.x * d.x + d.y * d.y + 1.0);
    return vec4<f32>(d.x * inv * 0.5 + 0.5, d.y * inv * 0.5 + 0.5, inv * 0.5 + 0.5, 1.0);
}

// Peercy Figure 2 per pixel (bumpmap_core::shading::blinn_from_derivatives): Blinn's normal in
// the tangent frame from the texel's slopes and the interpolated (|Pu|, Pv.T, Pv.B).
fn blinn_from_derivatives(t: vec4<f32>, range: f32, scale: vec2<f32>, pf: vec3<f32>) -> vec4<f32> {
    let d = -scale * (t.xy * 2.0 - 1.0) * range;
    var sigma = 1.0;
    if pf.z < 0.0 {
        sigma = -1.0;
    }
    let n = normalize_or_z(vec3<f32>(sigma * (-d.x * pf.z), sigma * (d.x * pf.y - d.y * pf.x), abs(pf.x * pf.z)));
    return vec4<f32>(n * 0.5 + 0.5, 1.0);
}

@fragment
fn fs_lit(f: Varyings) -> @location(0) vec4<f32> {
    let st = vec2<f32>(vary(f, S), vary(f, S + 1u));
    var normal = textureSample(normal_map, material_sampler, st * u.normal_scale.xy);
    if NORMAL_TEXELS == 1u {
        normal = offset_to_normal(normal, u.texels.x);
    } else if NORMAL_TEXELS == 2u {
        normal = blinn_from_derivatives(normal, u.texels.x, u.texels.yz, vary3(f, PARAM_FRAME));
    }
    let decal = textureSample(decal_map, material_sampler, st);
    var gloss = 1.0;
    if GLOSS == 1u {
        gloss = decal.a;
    } else if GLOSS == 2u {
        gloss = textureSample(gloss_map, material_sampler, st).r;
    }
    let l = unit(vary3(f, L));
    var h_in = vary3(f, H);
    if FRAGMENT_HALF_ANGLE == 1u {
        h_in = normalize_or_z(normalize_or_z(vary3(f, L)) + normalize_or_z(vary3(f, V)));
    }
    let h = unit(h_in);
    var l_n = l.z;
    var h_n = h.z;
    if OBJECT_SPACE == 1u {
        let n = normalize_or_z(vary3(f, N));
        l_n = dot(l, n);
        h_n = dot(h, n);
    }
    let light = attenuation(vary(f, LIGHT_DISTANCE)) * spot_factor(f);
    let t = Terms(u.ambient.rgb, u.diffuse.rgb, u.specular.rgb, SHININESS, SELF_SHADOW, SPECULAR_SHADOW);
    let frag = Fragment(normal, decal.rgb, gloss, l, h, l_n, h_n, light);
    return vec4<f32>(shade(t, frag), 1.0);
}
