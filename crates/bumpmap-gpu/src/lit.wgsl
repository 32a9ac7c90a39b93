// The single pass's fragment program: heights as geometry (parallax.wgsl) where asked, the
// texture lookups, per-fragment renormalization, attenuation and spotlight that make a
// Fragment, then shading.wgsl's shade(). Texture units: the normal map, the decal, the gloss
// map (white 1x1 textures where absent), the spotlight pattern, the normalization cube map,
// LEAN's two moment textures, the roughness map, the heights and their min-max bounds, the
// horizon map, the occlusion map, the detail normal map (detail.wgsl blends it).

// The uniform block `Lit` (the material's numbers, `u` below) is generated from Rust with the
// prelude (src/prelude.rs lit_block, from src/lit.rs LitMember), in the order Rust packs it.

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
// Heights as geometry: the heights (R32Float, every level) and their min-max bounds (Rg32Float,
// every level), read texel by texel by parallax.wgsl (1x1 stand-ins where unused).
@group(0) @binding(11) var heights: texture_2d<f32>;
@group(0) @binding(12) var height_bounds: texture_2d<f32>;

// The horizon map (bumpmap_math::horizon): directions 0-3 and 4-7 (Rgba32Float, every level),
// read texel by texel (1x1 stand-ins where unused).
@group(0) @binding(13) var horizons_0123: texture_2d<f32>;
@group(0) @binding(14) var horizons_4567: texture_2d<f32>;

// The material's occlusion map: what multiplies the ambient term, in red (white where unused).
@group(0) @binding(15) var occlusion_map: texture_2d<f32>;

// The detail normal map (bumpmap_core::detail), read at u.detail.x times the normal map's
// coordinates with its own mips (white where unused).
@group(0) @binding(16) var detail_map: texture_2d<f32>;

fn horizon_texel(x: i32, y: i32, level: u32, half: u32) -> vec4<f32> {
    if half == 0u {
        return textureLoad(horizons_0123, vec2<i32>(x, y), i32(level));
    }
    return textureLoad(horizons_4567, vec2<i32>(x, y), i32(level));
}

fn horizon_size(level: u32) -> vec2<u32> {
    return level_size(textureDimensions(horizons_0123, 0u), level);
}

fn height_texel(x: i32, y: i32, level: u32) -> f32 {
    return textureLoad(heights, vec2<i32>(x, y), i32(level)).r;
}

// A level's size from level 0's: floor(n / 2^k), at least 1, as the chains are made (not
// textureDimensions(t, k), which lavapipe, Mesa 25.0, answered with wrong sizes for k > 0 here).
fn level_size(size: vec2<u32>, level: u32) -> vec2<u32> {
    return max(size >> vec2<u32>(level), vec2<u32>(1u));
}

fn height_size(level: u32) -> vec2<u32> {
    return level_size(textureDimensions(heights, 0u), level);
}

fn minmax_texel(x: i32, y: i32, level: u32) -> vec2<f32> {
    return textureLoad(height_bounds, vec2<i32>(x, y), i32(level)).rg;
}

fn minmax_size(level: u32) -> vec2<u32> {
    return level_size(textureDimensions(height_bounds, 0u), level);
}

fn minmax_levels() -> u32 {
    return textureNumLevels(height_bounds);
}

// A map at uv: with heights as geometry at the hit, with the entry point's derivatives (as
// textureGrad reads it after a march); else as the hardware's implicit derivatives say.
fn sample_map(map: texture_2d<f32>, uv: vec2<f32>, dx: vec2<f32>, dy: vec2<f32>) -> vec4<f32> {
    if PARALLAX == PARALLAX_NONE {
        return textureSample(map, material_sampler, uv);
    }
    return textureSampleGrad(map, material_sampler, uv, dx, dy);
}

// normalize(v), or +Z where v has no direction.
fn normalize_or_z(v: vec3<f32>) -> vec3<f32> {
    let d = dot(v, v);
    if d > 0.0 && d < 3.0e38 {
        return v * inverseSqrt(d);
    }
    return vec3<f32>(0.0, 0.0, 1.0);
}

// MikkTSpace's per-pixel decode of the tangent-space normal v (bumpmap_math::tangent::
// decode_per_pixel): the direction of v.x·T + v.y·w·(N × T) + v.z·N in the interpolated,
// unnormalized frame, at v's length; N's direction (or +Z) where the sum has none.
fn decode_per_pixel(v: vec3<f32>, t: vec3<f32>, w: f32, n: vec3<f32>) -> vec3<f32> {
    let b = select(-1.0, 1.0, w >= 0.0) * cross(n, t);
    let sum = v.x * t + v.y * b + v.z * n;
    let d = dot(sum, sum);
    if d > 0.0 && d < 3.0e38 {
        return sum * inverseSqrt(d) * length(v);
    }
    return normalize_or_z(n) * length(v);
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

struct LitOut {
    color: vec4<f32>,
    depth: f32,
};

fn lit(f: Varyings) -> LitOut {
    let entry = vec2<f32>(vary(f, VAR_S), vary(f, VAR_T));
    // Heights as geometry: where the view ray meets them, and L and V there.
    var st = entry;
    var dx = vec2<f32>(0.0);
    var dy = vec2<f32>(0.0);
    var par = ParallaxFragment(entry, vec3<f32>(0.0), vec3<f32>(0.0), 1.0, 0.0, vec3<f32>(0.0, 0.0, 1.0), 1.0, true);
    if PARALLAX != PARALLAX_NONE {
        dx = dpdxCoarse(entry);
        dy = dpdyCoarse(entry);
        // The footprint at the entry point in texels of the heights (GL 1.2 Eq. 3.14's terms),
        // and the level of its shorter side (bumpmap_core::parallax::height_lambda).
        let size = vec2<f32>(height_size(0u));
        var level = 0u;
        if HEIGHT_MIPMAPS {
            let lambda = height_lambda(dot(dx * size, dx * size), dot(dy * size, dy * size));
            level = nearest_level(lambda, textureNumLevels(heights) - 1u);
        }
        let jacobian = vec4<f32>(
            vary(f, VAR_TANGENT_FROM_TEX),
            vary(f, VAR_TANGENT_FROM_TEX + 1u),
            vary(f, VAR_TANGENT_FROM_TEX + 2u),
            vary(f, VAR_TANGENT_FROM_TEX + 3u),
        );
        let curvature = vec2<f32>(vary(f, VAR_CURVATURE), vary(f, VAR_CURVATURE + 1u));
        par = parallax_fragment(
            entry,
            vary3(f, VAR_TEX_VIEW),
            vary3(f, VAR_TEX_LIGHT),
            jacobian,
            curvature,
            u.parallax.y,
            u32(u.parallax.x),
            POSITIONAL_LIGHT,
            level,
        );
        if !par.ok {
            discard;
        }
        st = par.st;
    }
    let scale = u.normal_scale.xy;
    var normal: vec4<f32>;
    if PARALLAX != PARALLAX_NONE && HIT_NORMAL_HEIGHTS {
        // The heights' own normal at the hit, from their interpolant.
        normal = vec4<f32>(par.normal * 0.5 + 0.5, 1.0);
    } else {
        normal = sample_map(normal_map, st * scale, dx * scale, dy * scale);
        if NORMAL_TEXELS == NORMAL_TEXELS_OFFSET {
            normal = offset_to_normal(normal, u.texels.x);
        } else if NORMAL_TEXELS == NORMAL_TEXELS_DERIVATIVES {
            normal = blinn_from_derivatives(normal, u.texels.x, u.texels.yz, vary3(f, VAR_PARAM_FRAME));
        }
    }
    if DETAIL != DETAIL_NONE {
        let k = scale * u.detail.x;
        let d = sample_map(detail_map, st * k, dx * k, dy * k);
        normal = detail_normal(normal, d, DETAIL, u.detail.y);
    }
    var decal = sample_map(decal_map, st, dx, dy);
    var gloss = 1.0;
    if GLOSS == GLOSS_DECAL_ALPHA {
        gloss = decal.a;
    } else if GLOSS == GLOSS_MAP {
        gloss = sample_map(gloss_map, st, dx, dy).r;
    }
    // The base colour, alpha too, times the interpolated vertex colour (glTF COLOR_0).
    if VERTEX_COLOR {
        decal = decal * vec4<f32>(vary3(f, VAR_COLOR), vary(f, VAR_COLOR + 3u));
    }
    var l: vec3<f32>;
    var h: vec3<f32>;
    if PARALLAX != PARALLAX_NONE {
        // L and V where the ray met the heights; H from them per fragment.
        l = normalize_or_z(par.l);
        h = normalize_or_z(l + normalize_or_z(par.v));
    } else {
        l = unit(vary3(f, VAR_L));
        var h_in = vary3(f, VAR_H);
        if FRAGMENT_HALF_ANGLE {
            h_in = normalize_or_z(normalize_or_z(vary3(f, VAR_L)) + normalize_or_z(vary3(f, VAR_V)));
        }
        h = unit(h_in);
    }
    var l_n = l.z;
    var h_n = h.z;
    if OBJECT_SPACE {
        let n = normalize_or_z(vary3(f, VAR_N));
        l_n = dot(l, n);
        h_n = dot(h, n);
    }
    if PER_PIXEL_DECODE {
        normal = vec4<f32>(decode_per_pixel(normal.xyz * 2.0 - 1.0, vary3(f, VAR_TANGENT), vary(f, VAR_TANGENT + 3u), vary3(f, VAR_N)) * 0.5 + 0.5, normal.w);
    }
    let light = attenuation(vary(f, VAR_LIGHT_DISTANCE)) * spot_factor(f) * par.light;
    let t = Terms(u.ambient.rgb, u.diffuse.rgb, u.specular.rgb, SHININESS, SELF_SHADOW, SPECULAR_SHADOW, SPECULAR_FILTER);
    var lean_b = vec2<f32>(0.0);
    var lean_m = vec3<f32>(0.0);
    var lean_j = 1.0;
    if SPECULAR_FILTER == SPECULAR_FILTER_LEAN {
        let bm = sample_map(lean_b_m, st * scale, dx * scale, dy * scale);
        let xy_j = sample_map(lean_m_xy, st * scale, dx * scale, dy * scale);
        lean_b = bm.xy;
        lean_m = vec3<f32>(bm.z, xy_j.r, bm.w);
        lean_j = xy_j.g;
    } else if SPECULAR_FILTER == SPECULAR_FILTER_CLEAN {
        // shade() reads only Mxx + Myy for CLEAN: the sum goes where Mxx would.
        let c = sample_map(lean_b_m, st * scale, dx * scale, dy * scale);
        lean_b = c.xy;
        lean_m = vec3<f32>(c.z, 0.0, 0.0);
        lean_j = c.w;
    }
    var roughness = 1.0;
    if SPECULAR_FILTER == SPECULAR_FILTER_ROUGHNESS_MAP {
        roughness = sample_map(roughness_map, st * scale, dx * scale, dy * scale).r;
    }
    var occlusion = par.occlusion;
    if OCCLUSION_MAP {
        occlusion = occlusion * sample_map(occlusion_map, st, dx, dy).r;
    }
    let frag = Fragment(normal, decal.rgb, gloss, l, h, l_n, h_n, light, lean_b, lean_m, lean_j, roughness, occlusion);
    var depth = f.position.z;
    if WRITE_DEPTH {
        depth = displaced_depth(f.position.z, par.kappa, u.parallax.z);
    }
    // A blended material's pass: the decal's alpha weighs it against what is behind.
    var alpha = 1.0;
    if DECAL_ALPHA {
        alpha = decal.a;
    }
    return LitOut(vec4<f32>(shade(t, frag), alpha), depth);
}

// The pass's alpha test (ALPHA_CUTOFF < 0: none).
fn alpha_tested(c: vec4<f32>) -> vec4<f32> {
    if clamp(c.a, 0.0, 1.0) < ALPHA_CUTOFF {
        discard;
    }
    return c;
}

@fragment
fn fs_lit(f: Varyings) -> @location(0) vec4<f32> {
    return alpha_tested(lit(f).color);
}

struct LitDepthOut {
    @location(0) color: vec4<f32>,
    @builtin(frag_depth) depth: f32,
};

// The same program writing the depth where the view ray met the heights (WRITE_DEPTH).
@fragment
fn fs_lit_depth(f: Varyings) -> LitDepthOut {
    let o = lit(f);
    return LitDepthOut(alpha_tested(o.color), o.depth);
}
