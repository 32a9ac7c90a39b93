// The single pass's fragment program: the texture lookups, per-fragment renormalization,
// attenuation and spotlight that make a Fragment, then shading.wgsl's shade(). Texture units: the normal map, the decal, the gloss map (white 1x1
// textures where absent), the spotlight pattern and the normalization cube map.

struct Lit {
    ambient: vec4<f32>,
    diffuse: vec4<f32>,
    // xyz: k_specular · light colour; w: shininess.
    specular: vec4<f32>,
    // x: self-shadow (0 Eq. 12's ramp, 1 step, 2 off); y: specular gate (0 Kilgard, 1 Cg
    // Tutorial, 2 off); z: normalize (0 math, 1 cube map); w: half-angle (0 vertex, 1 fragment).
    modes: vec4<u32>,
    // x: gloss (0 none, 1 decal alpha, 2 map); y: object space (1) or tangent space (0);
    // z: attenuation (0 none, 1 polynomial, 2 exp, 3 exp2); w: spotlight pattern (1) or none.
    modes2: vec4<u32>,
    // Polynomial: constant, linear, quadratic; exponential: density in x.
    attenuation: vec4<f32>,
    // x: spotlight (1) or none (0); y: cos(cutoff); z: exponent.
    spot: vec4<f32>,
    // xy: the object-space map's coordinate scale (1, 1 in tangent space).
    normal_scale: vec4<f32>,
};

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
    if u.modes.z == 1u {
        return textureSampleLevel(cube_map, clamp_sampler, v, 0.0).rgb * 2.0 - 1.0;
    }
    return normalize_or_z(v);
}

fn attenuation(d: f32) -> f32 {
    let a = u.attenuation;
    switch u.modes2.z {
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
    if u.spot.x == 0.0 {
        return 1.0;
    }
    let c = -dot(normalize_or_z(vary3(f, L)), normalize_or_z(vary3(f, SPOT)));
    var k = 0.0;
    if c >= u.spot.y {
        k = select(select(pow(c, u.spot.z), 0.0, c <= 0.0), 1.0, u.spot.z == 0.0);
    }
    if u.modes2.w == 1u {
        let p = vary3(f, PROJ);
        var pattern = 0.0;
        if p.z > 0.0 {
            pattern = textureSampleLevel(pattern_map, clamp_sampler, p.xy / p.z, 0.0).r;
        }
        k = k * pattern;
    }
    return k;
}

@fragment
fn fs_lit(f: Varyings) -> @location(0) vec4<f32> {
    let st = vec2<f32>(vary(f, S), vary(f, S + 1u));
    let normal = textureSample(normal_map, material_sampler, st * u.normal_scale.xy);
    let decal = textureSample(decal_map, material_sampler, st);
    let gloss_texel = textureSample(gloss_map, material_sampler, st);
    var gloss = 1.0;
    if u.modes2.x == 1u {
        gloss = decal.a;
    } else if u.modes2.x == 2u {
        gloss = gloss_texel.r;
    }
    let l = unit(vary3(f, L));
    var h_in = vary3(f, H);
    if u.modes.w == 1u {
        h_in = normalize_or_z(normalize_or_z(vary3(f, L)) + normalize_or_z(vary3(f, V)));
    }
    let h = unit(h_in);
    var l_n = l.z;
    var h_n = h.z;
    if u.modes2.y == 1u {
        let n = normalize_or_z(vary3(f, N));
        l_n = dot(l, n);
        h_n = dot(h, n);
    }
    let light = attenuation(vary(f, LIGHT_DISTANCE)) * spot_factor(f);
    let t = Terms(u.ambient.rgb, u.diffuse.rgb, u.specular.rgb, u.specular.w, u.modes.x, u.modes.y);
    let frag = Fragment(normal, decal.rgb, gloss, l, h, l_n, h_n, light);
    return vec4<f32>(shade(t, frag), 1.0);
}
