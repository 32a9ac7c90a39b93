// bumpmap_core::parallax (and the walk of bumpmap_math::height_trace it calls), as WGSL:
// tests/parallax_parity.rs checks every march, the shadows and fragment() against the Rust
// definitions on random rays. Texture space is (s, t, h), h = 1 on the polygon, 0 at the depth.
//
// The includer defines how heights are read: height_texel(x, y, level) and height_size(level)
// (level 0 the heights, each a texel of a level of the mip chain), minmax_texel(x, y, level),
// minmax_size(level) and minmax_levels() (the min-max levels, cells first), and the horizon
// map's: horizon_texel(x, y, level, half) (directions 0-3 for half 0, 4-7 for half 1) and
// horizon_size(level). The lit program
// reads textures; the parity test reads storage buffers.

struct TextureRay {
    st: vec2<f32>,
    // Texture coordinates per unit of height descended.
    step: vec2<f32>,
    // The base surface's fall below its tangent plane, heights per unit of s^2 and t^2.
    curvature: vec2<f32>,
};

fn ray_at(r: TextureRay, descent: f32) -> vec2<f32> {
    return r.st + descent * r.step;
}

fn ray_height(r: TextureRay, descent: f32) -> f32 {
    let o = descent * r.step;
    return 1.0 - descent + (r.curvature.x * o.x * o.x + r.curvature.y * o.y * o.y);
}

// bumpmap_math::height_mips::HeightLevel::bilinear: GL's LINEAR with REPEAT at one level.
struct Linear {
    i0: i32,
    i1: i32,
    a: f32,
};

fn linear_repeat(s: f32, n: u32) -> Linear {
    let u = (s - floor(s)) * f32(n) - 0.5;
    let f = floor(u);
    let i = i32(f);
    let last = i32(n) - 1;
    let i0 = select(min(i, last), last, i < 0);
    return Linear(i0, select(i0 + 1, 0, i0 + 1 == i32(n)), u - f);
}

fn height_bilinear(level: u32, st: vec2<f32>) -> f32 {
    let size = height_size(level);
    let x = linear_repeat(st.x, size.x);
    let y = linear_repeat(st.y, size.y);
    let ca = 1.0 - x.a;
    let cb = 1.0 - y.a;
    var v = height_texel(x.i0, y.i0, level) * (ca * cb);
    v = fma(height_texel(x.i1, y.i0, level), x.a * cb, v);
    v = fma(height_texel(x.i0, y.i1, level), ca * y.a, v);
    return fma(height_texel(x.i1, y.i1, level), x.a * y.a, v);
}

struct MarchHit {
    st: vec2<f32>,
    descent: f32,
    // False where the ray left the slab first (a silhouette).
    ok: bool,
};

fn offset_march(r: TextureRay, cos_view: f32, level: u32) -> MarchHit {
    let descent = (1.0 - height_bilinear(level, r.st)) * clamp(cos_view, 0.0, 1.0);
    return MarchHit(ray_at(r, descent), descent, true);
}

struct Layer {
    i: u32,
    // The ray over the heights one layer back, and the heights over the ray now.
    above: f32,
    below: f32,
    ok: bool,
};

fn first_layer_below(r: TextureRay, n: u32, level: u32) -> Layer {
    var prev_ray = 1.0;
    var prev_height = 1.0;
    for (var i = 0u; i <= 4u * n; i++) {
        let d = f32(i) / f32(n);
        let h_ray = ray_height(r, d);
        if i > 0u && h_ray > 1.0 {
            return Layer(0u, 0.0, 0.0, false);
        }
        let h = height_bilinear(level, ray_at(r, d));
        if h >= h_ray {
            return Layer(i, prev_ray - prev_height, h - h_ray, true);
        }
        prev_ray = h_ray;
        prev_height = h;
    }
    return Layer(0u, 0.0, 0.0, false);
}

fn steep_march(r: TextureRay, layers: u32, level: u32) -> MarchHit {
    let n = max(layers, 1u);
    let l = first_layer_below(r, n, level);
    let d = f32(l.i) / f32(n);
    return MarchHit(ray_at(r, d), d, l.ok);
}

fn occlusion_layers(layers: u32, cos_view: f32) -> u32 {
    let most = f32(max(layers, 1u));
    let least = ceil(most / 4.0);
    return u32(max(floor(most + (least - most) * clamp(cos_view, 0.0, 1.0) + 0.5), 1.0));
}

fn occlusion_march(r: TextureRay, layers: u32, cos_view: f32, level: u32) -> MarchHit {
    let n = occlusion_layers(layers, cos_view);
    let l = first_layer_below(r, n, level);
    var at = 0.0;
    if l.i > 0u {
        let sum = l.above + l.below;
        var w = 1.0;
        if sum != 0.0 {
            w = l.above / sum;
        }
        at = (f32(l.i) - 1.0 + w) / f32(n);
    }
    return MarchHit(ray_at(r, at), at, l.ok);
}

fn relief_march(r: TextureRay, layers: u32, level: u32) -> MarchHit {
    let n = max(layers, 1u);
    let l = first_layer_below(r, n, level);
    if !l.ok {
        return MarchHit(r.st, 0.0, false);
    }
    if l.i == 0u {
        return MarchHit(r.st, 0.0, true);
    }
    var a = f32(l.i - 1u) / f32(n);
    var b = f32(l.i) / f32(n);
    for (var k = 0u; k < RELIEF_BISECTIONS; k++) {
        let mid = 0.5 * (a + b);
        if height_bilinear(level, ray_at(r, mid)) >= ray_height(r, mid) {
            b = mid;
        } else {
            a = mid;
        }
    }
    let d = 0.5 * (a + b);
    return MarchHit(ray_at(r, d), d, true);
}

// bumpmap_math::interpolant: Catmull-Rom weights and a cell's 4x4 texels (REPEAT).
fn catmull_rom(t: f32) -> vec4<f32> {
    let t2 = t * t;
    let t3 = t * t * t;
    return vec4<f32>(
        0.5 * (-t3 + 2.0 * t2 - t),
        0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
        0.5 * (-3.0 * t3 + 4.0 * t2 + t),
        0.5 * (t3 - t2),
    );
}

fn catmull_rom_derivative(t: f32) -> vec4<f32> {
    let t2 = t * t;
    return vec4<f32>(
        0.5 * (-3.0 * t2 + 4.0 * t - 1.0),
        0.5 * (9.0 * t2 - 10.0 * t),
        0.5 * (-9.0 * t2 + 8.0 * t + 1.0),
        0.5 * (3.0 * t2 - 2.0 * t),
    );
}

fn wrap_index(i: i32, n: u32) -> i32 {
    let m = i32(n);
    return ((i % m) + m) % m;
}

fn cell_texels(i: i32, j: i32) -> mat4x4<f32> {
    let size = height_size(0u);
    var p: mat4x4<f32>;
    for (var r = 0; r < 4; r++) {
        let row = wrap_index(j - 1 + r, size.y);
        p[r] = vec4<f32>(
            height_texel(wrap_index(i - 1, size.x), row, 0u),
            height_texel(wrap_index(i, size.x), row, 0u),
            height_texel(wrap_index(i + 1, size.x), row, 0u),
            height_texel(wrap_index(i + 2, size.x), row, 0u),
        );
    }
    return p;
}

fn eval_cell_value(p: mat4x4<f32>, fx: f32, fy: f32) -> f32 {
    let wx = catmull_rom(fx);
    let wy = catmull_rom(fy);
    var value = 0.0;
    for (var j = 0; j < 4; j++) {
        let r = wx.x * p[j].x + wx.y * p[j].y + wx.z * p[j].z + wx.w * p[j].w;
        value += wy[j] * r;
    }
    return value;
}

// bumpmap_math::interpolant::sample at texture coordinates st: (value, d/dx, d/dy per texel).
fn interpolant(st: vec2<f32>) -> vec3<f32> {
    let size = vec2<f32>(height_size(0u));
    let c = st * size - 0.5;
    let ij = floor(c);
    let p = cell_texels(i32(ij.x), i32(ij.y));
    let f = c - ij;
    let wx = catmull_rom(f.x);
    let dwx = catmull_rom_derivative(f.x);
    let wy = catmull_rom(f.y);
    let dwy = catmull_rom_derivative(f.y);
    var value = 0.0;
    var dx = 0.0;
    var dy = 0.0;
    for (var j = 0; j < 4; j++) {
        var r = 0.0;
        var rd = 0.0;
        for (var i = 0; i < 4; i++) {
            r += wx[i] * p[j][i];
            rd += dwx[i] * p[j][i];
        }
        value += wy[j] * r;
        dx += wy[j] * rd;
        dy += dwy[j] * r;
    }
    return vec3<f32>(value, dx, dy);
}

// bumpmap_math::height_trace: the first crossing of the ray o + tau d (cell coordinates)
// below the cell's surface within [ta, tb], or -1.
fn cell_crossing(p: mat4x4<f32>, o: vec3<f32>, d: vec3<f32>, corner: vec2<f32>, ta: f32, tb: f32) -> f32 {
    if cell_below(p, o, d, corner, ta) {
        return ta;
    }
    let step = (tb - ta) / f32(SAMPLES_PER_CELL);
    var prev = ta;
    for (var i = 1u; i <= SAMPLES_PER_CELL; i++) {
        var t = ta + step * f32(i);
        if i == SAMPLES_PER_CELL {
            t = tb;
        }
        if cell_below(p, o, d, corner, t) {
            var a = prev;
            var b = t;
            for (var k = 0u; k < BISECTIONS; k++) {
                let mid = 0.5 * (a + b);
                if mid <= a || mid >= b {
                    break;
                }
                if cell_below(p, o, d, corner, mid) {
                    b = mid;
                } else {
                    a = mid;
                }
            }
            return b;
        }
        prev = t;
    }
    return -1.0;
}

fn cell_below(p: mat4x4<f32>, o: vec3<f32>, d: vec3<f32>, corner: vec2<f32>, tau: f32) -> bool {
    let q = o + tau * d;
    let f = clamp(q.xy - corner, vec2<f32>(0.0), vec2<f32>(1.0));
    return clamp(eval_cell_value(p, f.x, f.y), 0.0, 1.0) >= q.z;
}

fn slab_exit(origin: vec3<f32>, dir: vec3<f32>) -> f32 {
    if dir.z < 0.0 {
        return max(origin.z, 0.0) / -dir.z;
    }
    if dir.z > 0.0 {
        return max(1.0 - origin.z, 0.0) / dir.z;
    }
    return F32_INFINITY;
}

fn exit_along(o: f32, d: f32, lo: f32, hi: f32) -> f32 {
    if d > 0.0 {
        return (hi - o) / d;
    }
    if d < 0.0 {
        return (lo - o) / d;
    }
    return F32_INFINITY;
}

fn node_span(node: u32, nodes: u32, cells: u32, k: u32, base: f32) -> vec2<f32> {
    let start = f32(node << k);
    var stop = f32((node + 1u) << k);
    if node + 1u == nodes {
        stop = f32(cells);
    }
    return vec2<f32>(base + start, base + stop);
}

// bumpmap_math::height_trace::trace: the first tau in [0, min(tau_max, the slab's exit)] where
// the ray meets the surface, or -1.
fn trace_heights(origin: vec3<f32>, dir: vec3<f32>, tau_max: f32) -> f32 {
    let size = height_size(0u);
    let exit_slab = slab_exit(origin, dir);
    let end = min(exit_slab, tau_max);
    if end >= F32_INFINITY || end < 0.0 {
        return -1.0;
    }
    if dir.z > 0.0 && origin.z >= 1.0 {
        return -1.0;
    }
    let top = minmax_levels() - 1u;
    let o = origin - vec3<f32>(0.5, 0.5, 0.0);
    let d = dir;
    let speed = max(abs(d.x), abs(d.y));
    var nudge = 0.0;
    if speed > 0.0 {
        nudge = 1e-4 / speed;
    }
    let crossed = min(speed * end + 2.0, 4.0 * f32(size.x + size.y) + 4096.0);
    let max_steps = u32(64.0 + 4.0 * (f32(top) + 1.0) * crossed);
    var k = top;
    var tau = 0.0;
    for (var step = 0u; step < max_steps; step++) {
        if tau > end {
            break;
        }
        let ahead = o + min(tau + nudge, end) * d;
        let u = floor(ahead.xy);
        let cx = u32(wrap_index(i32(u.x), size.x));
        let cy = u32(wrap_index(i32(u.y), size.y));
        let nodes = minmax_size(k);
        let nx = min(cx >> k, nodes.x - 1u);
        let ny = min(cy >> k, nodes.y - 1u);
        let xs = node_span(nx, nodes.x, size.x, k, u.x - f32(cx));
        let ys = node_span(ny, nodes.y, size.y, k, u.y - f32(cy));
        let exit = max(min(min(exit_along(o.x, d.x, xs.x, xs.y), exit_along(o.y, d.y, ys.x, ys.y)), end), tau);
        let bounds = minmax_texel(i32(nx), i32(ny), k);
        let ha = o.z + tau * d.z;
        let hb = o.z + exit * d.z;
        if min(ha, hb) > bounds.y {
            tau = exit + nudge;
            k = min(k + 1u, top);
            continue;
        }
        if max(ha, hb) < bounds.x {
            return tau;
        }
        if k > 0u {
            k -= 1u;
            continue;
        }
        let p = cell_texels(i32(cx), i32(cy));
        let hit = cell_crossing(p, o, d, u, tau, exit);
        if hit >= 0.0 {
            return hit;
        }
        tau = exit + nudge;
        k = min(k + 1u, top);
    }
    if d.z < 0.0 && end == exit_slab {
        return end;
    }
    return -1.0;
}

fn exact_march(r: TextureRay) -> MarchHit {
    let size = vec2<f32>(height_size(0u));
    let origin = vec3<f32>(r.st * size, 1.0);
    let dir = vec3<f32>(r.step * size, -1.0);
    var descent = trace_heights(origin, dir, F32_INFINITY);
    if descent < 0.0 {
        descent = 1.0;
    }
    return MarchHit(ray_at(r, descent), descent, ray_height(r, descent) <= 1.0 || descent == 0.0);
}

// bumpmap_core::parallax::shadow: the light reaching a hit through a march.
fn shadow_march(st: vec2<f32>, height: f32, to_light: vec3<f32>, layers: u32, mode: u32, level: u32) -> f32 {
    if mode == PARALLAX_SHADOW_OFF || to_light.z <= 0.0 || height >= 1.0 {
        return 1.0;
    }
    let rise = 1.0 - height;
    let step = to_light.xy / to_light.z;
    let n = max(u32(ceil(f32(max(layers, 1u)) * rise)), 1u);
    var worst = 0.0;
    for (var i = 1u; i <= n; i++) {
        let r = rise * f32(i) / f32(n);
        let above = height_bilinear(level, st + r * step) - (height + r);
        if mode == PARALLAX_SHADOW_HARD && above > SHADOW_BIAS {
            return 0.0;
        }
        if mode == PARALLAX_SHADOW_SOFT {
            worst = max(worst, (above - SHADOW_BIAS) * (1.0 - f32(i) / f32(n)));
        }
    }
    return 1.0 - clamp(worst * SOFT_SHADOW_SHARPNESS, 0.0, 1.0);
}

fn exact_shadow(st: vec2<f32>, height: f32, to_light: vec3<f32>) -> f32 {
    if to_light.z <= 0.0 {
        return 1.0;
    }
    let size = vec2<f32>(height_size(0u));
    let step = to_light.xy / to_light.z;
    let origin = vec3<f32>(st * size, min(height + EXACT_SHADOW_LIFT, 1.0));
    let dir = vec3<f32>(step * size, 1.0);
    return select(1.0, 0.0, trace_heights(origin, dir, F32_INFINITY) >= 0.0);
}

// bumpmap_core::parallax::TextureFrame.
// bumpmap_math::horizon::HorizonLevel::bilinear, four directions at a time.
fn horizon_bilinear(level: u32, st: vec2<f32>, half: u32) -> vec4<f32> {
    let size = horizon_size(level);
    let x = linear_repeat(st.x, size.x);
    let y = linear_repeat(st.y, size.y);
    let ca = 1.0 - x.a;
    let cb = 1.0 - y.a;
    var v = horizon_texel(x.i0, y.i0, level, half) * (ca * cb);
    v = fma(horizon_texel(x.i1, y.i0, level, half), vec4<f32>(x.a * cb), v);
    v = fma(horizon_texel(x.i0, y.i1, level, half), vec4<f32>(ca * y.a), v);
    return fma(horizon_texel(x.i1, y.i1, level, half), vec4<f32>(x.a * y.a), v);
}

// The horizons at st, every direction.
fn horizons_at(st: vec2<f32>, level: u32) -> array<f32, AZIMUTHS> {
    var h = array<f32, AZIMUTHS>();
    let a = horizon_bilinear(level, st, 0u);
    let b = horizon_bilinear(level, st, 1u);
    for (var k = 0u; k < 4u; k++) {
        h[k] = a[k];
        h[k + 4u] = b[k];
    }
    return h;
}

// bumpmap_core::parallax::horizon_occlusion with bumpmap_math::horizon::ambient_occlusion: the
// mean of cos^2 of the horizons' elevations at the frame's depth in texels.
fn horizon_occlusion(h: array<f32, AZIMUTHS>, j: vec4<f32>, depth_st: f32) -> f32 {
    let size = vec2<f32>(height_size(0u));
    let texel_side = sqrt(abs(j.x * j.w - j.y * j.z) / (size.x * size.y));
    var depth = 0.0;
    if texel_side > 0.0 {
        depth = depth_st / texel_side;
    }
    var sum = 0.0;
    for (var k = 0u; k < AZIMUTHS; k++) {
        let e = atan(depth * tan(clamp(h[k], 0.0, 1.0) * 1.5707964));
        sum += cos(e) * cos(e);
    }
    return sum / f32(AZIMUTHS);
}

// bumpmap_core::parallax::horizon_shadow with bumpmap_math::horizon::{horizon_toward,
// visibility}: the light let through by horizons h.
fn horizon_shadow(h_in: array<f32, AZIMUTHS>, to_light_st: vec3<f32>) -> f32 {
    var h = h_in;
    let size = vec2<f32>(height_size(0u));
    let to_light = vec3<f32>(to_light_st.xy * size, to_light_st.z);
    // atan2(y, x) in turns of the directions, wrapped into [0, AZIMUTHS).
    let n = f32(AZIMUTHS);
    let turns = atan2(to_light.y, to_light.x) * (n / 6.2831855);
    let f = turns - n * floor(turns / n);
    let k = min(u32(floor(f)), AZIMUTHS - 1u);
    let horizon = h[k] + (f - f32(k)) * (h[(k + 1u) % AZIMUTHS] - h[k]);
    // Elevations as stored: atan(rise) / 90 degrees.
    let light = atan2(to_light.z, length(to_light.xy)) * 0.63661975;
    return smoothstep(horizon - HORIZON_EDGE, horizon + HORIZON_EDGE, light);
}

fn frame_to_tangent(j: vec4<f32>, depth: f32, v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(j.x * v.x + j.y * v.y, j.z * v.x + j.w * v.y, v.z * depth);
}

fn frame_normal(j: vec4<f32>, depth: f32, g: vec2<f32>) -> vec3<f32> {
    let det = j.x * j.w - j.y * j.z;
    var inv = 0.0;
    if det != 0.0 && abs(det) < F32_INFINITY {
        inv = 1.0 / det;
    }
    let n = vec3<f32>(-(j.w * g.x - j.z * g.y) * inv * depth, -(j.x * g.y - j.y * g.x) * inv * depth, 1.0);
    return normalize(n);
}

// What a parallax fragment brings to the lighting model (bumpmap_core::parallax::ParallaxFragment).
struct ParallaxFragment {
    st: vec2<f32>,
    l: vec3<f32>,
    v: vec3<f32>,
    light: f32,
    kappa: f32,
    // The exact walk's normal (tangent frame), (0, 0, 1) for the others.
    normal: vec3<f32>,
    // What multiplies the ambient term (the horizon map's ambient occlusion, or 1).
    occlusion: f32,
    // False: discarded (a silhouette).
    ok: bool,
};

// bumpmap_core::parallax::fragment for PARALLAX's march, its options and the heights' `level`.
fn parallax_fragment(
    st: vec2<f32>,
    to_eye: vec3<f32>,
    to_light_in: vec3<f32>,
    jacobian: vec4<f32>,
    curvature_in: vec2<f32>,
    depth: f32,
    layers: u32,
    positional: bool,
    level: u32,
) -> ParallaxFragment {
    var curvature = vec2<f32>(0.0);
    if SILHOUETTES {
        curvature = curvature_in;
    }
    let eye_tangent = frame_to_tangent(jacobian, depth, to_eye);
    let cos_view = eye_tangent.z / length(eye_tangent);
    var hit = MarchHit(st, 0.0, true);
    if to_eye.z > 0.0 {
        let r = TextureRay(st, vec2<f32>(-to_eye.x, -to_eye.y) / to_eye.z, curvature);
        if PARALLAX == PARALLAX_OFFSET {
            hit = offset_march(r, cos_view, level);
        } else if PARALLAX == PARALLAX_STEEP {
            hit = steep_march(r, layers, level);
        } else if PARALLAX == PARALLAX_OCCLUSION {
            hit = occlusion_march(r, layers, cos_view, level);
        } else if PARALLAX == PARALLAX_RELIEF {
            hit = relief_march(r, layers, level);
        } else if PARALLAX == PARALLAX_EXACT {
            hit = exact_march(r);
        }
    }
    let moved = vec3<f32>(hit.st - st, -hit.descent);
    var to_light = to_light_in;
    if positional {
        to_light = to_light_in - moved;
    }
    let to_eye_hit = to_eye - moved;
    var light = 1.0;
    var occlusion = 1.0;
    if PARALLAX_SHADOW == PARALLAX_SHADOW_HORIZON || AMBIENT_OCCLUSION {
        let h = horizons_at(hit.st, level);
        if AMBIENT_OCCLUSION {
            occlusion = horizon_occlusion(h, jacobian, depth);
        }
        if PARALLAX_SHADOW == PARALLAX_SHADOW_HORIZON {
            light = horizon_shadow(h, to_light);
        }
    }
    if PARALLAX_SHADOW != PARALLAX_SHADOW_OFF && PARALLAX_SHADOW != PARALLAX_SHADOW_HORIZON {
        if PARALLAX == PARALLAX_EXACT {
            light = exact_shadow(hit.st, 1.0 - hit.descent, to_light);
        } else {
            // From the heights where the march ended.
            light = shadow_march(hit.st, height_bilinear(level, hit.st), to_light, layers, PARALLAX_SHADOW, level);
        }
    }
    var normal = vec3<f32>(0.0, 0.0, 1.0);
    if HIT_NORMAL_HEIGHTS {
        let size = vec2<f32>(height_size(0u));
        let g = interpolant(hit.st);
        var gradient = vec2<f32>(0.0);
        if g.x >= 0.0 && g.x <= 1.0 {
            gradient = vec2<f32>(g.y * size.x, g.z * size.y);
        }
        normal = frame_normal(jacobian, depth, gradient);
    }
    var kappa = 0.0;
    if to_eye.z > 0.0 {
        kappa = hit.descent / to_eye.z;
    }
    return ParallaxFragment(
        hit.st,
        frame_to_tangent(jacobian, depth, to_light),
        frame_to_tangent(jacobian, depth, to_eye_hit),
        light,
        kappa,
        normal,
        occlusion,
        hit.ok,
    );
}

// bumpmap_core::parallax::displaced_depth.
fn displaced_depth(z: f32, kappa: f32, a: f32) -> f32 {
    return a + (z - a) / (1.0 + kappa);
}

// bumpmap_core::parallax::height_lambda: the level of detail of the footprint's shorter side,
// at most MAX_ANISOTROPY times shorter than its longer one.
fn height_lambda(rho2_x: f32, rho2_y: f32) -> f32 {
    let long = max(rho2_x, rho2_y);
    let short = min(rho2_x, rho2_y);
    return 0.5 * log2(max(short, long / (MAX_ANISOTROPY * MAX_ANISOTROPY)));
}

// bumpmap_core::state::Sampler::nearest_level: the level *_MIPMAP_NEAREST reads at lambda.
fn nearest_level(lambda: f32, last: u32) -> u32 {
    if lambda <= 0.5 {
        return 0u;
    }
    return u32(min(ceil(lambda + 0.5) - 1.0, f32(last)));
}
