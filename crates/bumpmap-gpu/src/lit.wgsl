// The single pass's fragment program: the texture lookups, per-fragment renormalization,
// attenuation and spotlight that make a Fragment, then shading.wgsl's shade(). Texture units:
// the normal map, the decal, the gloss map (white 1x1 textures where absent), the spotlight
// pattern, the normalization cube map, LEAN's two moment textures and the roughness map.

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

// The model's switches are override constants, one pipeline per combination, declared with
// their named values by the generated prelude (src/prelude.rs, from src/lit.rs), as are the
// varying slots (VAR_*): nothing here restates a number Rust decides.

@group(0) @binding(0) var<uniform> u: Lit;
@group(0) @binding(1) var normal_map: texture_2d<f32>;
@group(0) @binding(2) var decal_map: texture_2d<f32>;
@group(0) @binding(3) var gloss_map: texture_2d<f32>;
@group(0) @binding(4) var pattern_map: texture_2d<f32>;
@group(0) @binding(5) var cube_map: texture_cube<f32>;
@group(0) @binding(6) var material_sampler: sampler;
@group(0) @binding(7) var clamp_sampler: sampler;
// LEAN's moments (Bx, By, Mxx, Myy) and (Mxy, J), at the normal map's size (white where unused);
// for CLEAN, (Bx, By, Mxx + Myy, J) in the first and nothing in the second.
@group(0) @binding(8) var lean_b_m: texture_2d<f32>;
@group(0) @binding(9) var lean_m_xy: texture_2d<f32>;
// The roughness map (perceptual roughness in red), at the normal map's size (white where unused).
@group(0) @binding(10) var roughness_map: texture_2d<f32>;

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
    if NORMALIZE_CUBE {
        return textureSampleLevel(cube_map, clamp_sampler, v, 0.0).rgb * 2.0 - 1.0;
    }
    return normalize_or_z(v);
}

fn attenuation(d: f32) -> f32 {
    let a = u.attenuation;
    switch ATTENUATION {
        case ATTENUATION_POLYNOMIAL: {
            return clamp(1.0 / (a.x + a.y * d + a.z * d * d), 0.0, 1.0);
        }
        case ATTENUATION_EXP: {
            return exp(-a.x * d);
        }
        case ATTENUATION_EXP2: {
            let x = a.x * d;
            return exp(-(x * x));
        }
        default: {
            return 1.0;
        }
    }
}

fn spot_factor(f: Varyings) -> f32 {
    if !SPOTLIGHT {
        return 1.0;
    }
    let c = -dot(normalize_or_z(vary3(f, VAR_L)), normalize_or_z(vary3(f, VAR_SPOT)));
    var k = 0.0;
    if c >= u.spot.x {
        k = select(select(pow(c, u.spot.y), 0.0, c <= 0.0), 1.0, u.spot.y == 0.0);
    }
    if SPOT_PATTERN {
        let p = vary3(f, VAR_PROJ);
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
    let st = vec2<f32>(vary(f, VAR_S), vary(f, VAR_T));
    var normal = textureSample(normal_map, material_sampler, st * u.normal_scale.xy);
    if NORMAL_TEXELS == NORMAL_TEXELS_OFFSET {
        normal = offset_to_normal(normal, u.texels.x);
    } else if NORMAL_TEXELS == NORMAL_TEXELS_DERIVATIVES {
        normal = blinn_from_derivatives(normal, u.texels.x, u.texels.yz, vary3(f, VAR_PARAM_FRAME));
    }
    let decal = textureSample(decal_map, material_sampler, st);
    var gloss = 1.0;
    if GLOSS == GLOSS_DECAL_ALPHA {
        gloss = decal.a;
    } else if GLOSS == GLOSS_MAP {
        gloss = textureSample(gloss_map, material_sampler, st).r;
    }
    let l = unit(vary3(f, VAR_L));
    var h_in = vary3(f, VAR_H);
    if FRAGMENT_HALF_ANGLE {
        h_in = normalize_or_z(normalize_or_z(vary3(f, VAR_L)) + normalize_or_z(vary3(f, VAR_V)));
    }
    let h = unit(h_in);
    var l_n = l.z;
    var h_n = h.z;
    if OBJECT_SPACE {
        let n = normalize_or_z(vary3(f, VAR_N));
        l_n = dot(l, n);
        h_n = dot(h, n);
    }
    let light = attenuation(vary(f, VAR_LIGHT_DISTANCE)) * spot_factor(f);
    let t = Terms(u.ambient.rgb, u.diffuse.rgb, u.specular.rgb, SHININESS, SELF_SHADOW, SPECULAR_SHADOW, SPECULAR_FILTER);
    var lean_b = vec2<f32>(0.0);
    var lean_m = vec3<f32>(0.0);
    var lean_j = 1.0;
    if SPECULAR_FILTER == SPECULAR_FILTER_LEAN {
        let bm = textureSample(lean_b_m, material_sampler, st * u.normal_scale.xy);
        let xy_j = textureSample(lean_m_xy, material_sampler, st * u.normal_scale.xy);
        lean_b = bm.xy;
        lean_m = vec3<f32>(bm.z, xy_j.r, bm.w);
        lean_j = xy_j.g;
    } else if SPECULAR_FILTER == SPECULAR_FILTER_CLEAN {
        // shade() reads only Mxx + Myy for CLEAN: the sum goes where Mxx would.
        let c = textureSample(lean_b_m, material_sampler, st * u.normal_scale.xy);
        lean_b = c.xy;
        lean_m = vec3<f32>(c.z, 0.0, 0.0);
        lean_j = c.w;
    }
    var roughness = 1.0;
    if SPECULAR_FILTER == SPECULAR_FILTER_ROUGHNESS_MAP {
        roughness = textureSample(roughness_map, material_sampler, st * u.normal_scale.xy).r;
    }
    let frag = Fragment(normal, decal.rgb, gloss, l, h, l_n, h_n, light, lean_b, lean_m, lean_j, roughness);
    return vec4<f32>(shade(t, frag), 1.0);
}
