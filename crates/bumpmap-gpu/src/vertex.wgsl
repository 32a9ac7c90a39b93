// The vertex stage's output as the GPU interpolates it: the clip position (depth remapped from
// GL's [-1, 1] to wgpu's [0, 1], so window depth is GL's (z/w + 1)/2) and the 28 varying slots
// of bumpmap_core::vertex::var, four to a location, interpolated perspective-correctly.

struct VertexIn {
    @location(0) clip: vec4<f32>,
    @location(1) v0: vec4<f32>,
    @location(2) v1: vec4<f32>,
    @location(3) v2: vec4<f32>,
    @location(4) v3: vec4<f32>,
    @location(5) v4: vec4<f32>,
    @location(6) v5: vec4<f32>,
    @location(7) v6: vec4<f32>,
};

struct Varyings {
    // @invariant: every pipeline computes the same depth for the same vertices, so depth
    // EQUAL holds across passes.
    @builtin(position) @invariant position: vec4<f32>,
    @location(0) v0: vec4<f32>,
    @location(1) v1: vec4<f32>,
    @location(2) v2: vec4<f32>,
    @location(3) v3: vec4<f32>,
    @location(4) v4: vec4<f32>,
    @location(5) v5: vec4<f32>,
    @location(6) v6: vec4<f32>,
};

@vertex
fn vs_main(v: VertexIn) -> Varyings {
    var o: Varyings;
    o.position = vec4<f32>(v.clip.x, v.clip.y, 0.5 * (v.clip.z + v.clip.w), v.clip.w);
    o.v0 = v.v0;
    o.v1 = v.v1;
    o.v2 = v.v2;
    o.v3 = v.v3;
    o.v4 = v.v4;
    o.v5 = v.v5;
    o.v6 = v.v6;
    return o;
}

// Varying slot k (bumpmap_core::vertex::var).
fn vary(f: Varyings, k: u32) -> f32 {
    let slots = array<vec4<f32>, 7>(f.v0, f.v1, f.v2, f.v3, f.v4, f.v5, f.v6);
    return slots[k / 4u][k % 4u];
}

// Slots k, k + 1, k + 2 as a vector.
fn vary3(f: Varyings, k: u32) -> vec3<f32> {
    return vec3<f32>(vary(f, k), vary(f, k + 1u), vary(f, k + 2u));
}
