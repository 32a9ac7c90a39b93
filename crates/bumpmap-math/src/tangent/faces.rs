//! Each triangle's frame for ours: its unit ∂P/∂s, handedness, whether it is usable, and its
//! corner angles. Computed eight triangles at a time in structure-of-arrays lanes, plain
//! arithmetic without branches that the compiler turns into vector instructions (no
//! intrinsics, so every target runs the same code and gets the same bits). It does not blend
//! or split at vertices: that is `ours` in `tangent.rs`.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::mesh::Mesh;

/// One triangle's contribution: unit tangent in the triangle, handedness, usable or not, and
/// (when usable) its corner angles, which weight its tangent at each vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Face {
    pub tangent: Vec3,
    pub w: f32,
    pub ok: bool,
    pub geometric: bool,
    pub angles: [f32; 3],
}

/// What the frames say about the triangles: degenerate in texture space, degenerate in space,
/// mirrored (no split vertices yet).
pub(super) fn count(faces: &[Face]) -> super::TangentReport {
    faces
        .par_iter()
        .fold(super::TangentReport::default, |mut r, f| {
            r.degenerate_uv += (!f.ok && f.geometric) as usize;
            r.degenerate_geometry += !f.geometric as usize;
            r.mirrored += (f.ok && f.w < 0.0) as usize;
            r
        })
        .reduce(super::TangentReport::default, |a, b| super::TangentReport {
            degenerate_uv: a.degenerate_uv + b.degenerate_uv,
            degenerate_geometry: a.degenerate_geometry + b.degenerate_geometry,
            mirrored: a.mirrored + b.mirrored,
            vertices_split: 0,
        })
}

/// Triangles per block.
const BLOCK: usize = 8;

/// The frame of every triangle of `mesh`, in order.
pub(super) fn face_frames(mesh: &Mesh) -> Vec<Face> {
    let blocks: Vec<[Face; BLOCK]> = mesh.indices.par_chunks(BLOCK).map(|tris| face_block(mesh, tris)).collect();
    let mut faces = blocks.into_flattened();
    faces.truncate(mesh.indices.len());
    faces
}

/// The frames of up to [`BLOCK`] triangles; lanes past the last triangle repeat it.
fn face_block(mesh: &Mesh, tris: &[[u32; 3]]) -> [Face; BLOCK] {
    // Corner c's coordinates, lane by lane.
    let mut p = [[[0.0f32; BLOCK]; 3]; 3];
    let mut t = [[[0.0f32; BLOCK]; 2]; 3];
    for l in 0..BLOCK {
        let tri = tris[l.min(tris.len() - 1)];
        for c in 0..3 {
            let (q, uv) = (mesh.positions[tri[c] as usize], mesh.texcoords[tri[c] as usize]);
            (p[c][0][l], p[c][1][l], p[c][2][l]) = (q.x, q.y, q.z);
            (t[c][0][l], t[c][1][l]) = (uv.x, uv.y);
        }
    }
    let mut out = [[0.0f32; BLOCK]; 7];
    let mut flags = [[false; BLOCK]; 2];
    for l in 0..BLOCK {
        let corner = |c: usize| (Vec3::new(p[c][0][l], p[c][1][l], p[c][2][l]), Vec2::new(t[c][0][l], t[c][1][l]));
        let f = frame([corner(0), corner(1), corner(2)]);
        [out[0][l], out[1][l], out[2][l], out[3][l]] = [f.tangent.x, f.tangent.y, f.tangent.z, f.w];
        [out[4][l], out[5][l], out[6][l]] = f.angles;
        [flags[0][l], flags[1][l]] = [f.ok, f.geometric];
    }
    std::array::from_fn(|l| Face {
        tangent: Vec3::new(out[0][l], out[1][l], out[2][l]),
        w: out[3][l],
        ok: flags[0][l],
        geometric: flags[1][l],
        angles: [out[4][l], out[5][l], out[6][l]],
    })
}

/// One triangle's frame from its corners' positions and texture coordinates, every quantity
/// computed and the results selected (no early return), so that lanes vectorize.
#[inline(always)]
fn frame(corners: [(Vec3, Vec2); 3]) -> Face {
    let [(p0, t0), (p1, t1), (p2, t2)] = corners;
    let (e1, e2) = (p1 - p0, p2 - p0);
    let (d1, d2) = (t1 - t0, t2 - t0);
    let area = e1.cross(e2);
    let det = d1.x * d2.y - d2.x * d1.y;
    // Zero area in texture space, relative to the UV edge lengths (scale-free).
    let uv_scale = d1.length_squared().max(d2.length_squared());
    // Zero area in space, relative to the edge lengths: a sliver whose sine of angle is below
    // 1e-6 (such as a pole's fan triangle, two of whose vertices coincide up to rounding).
    let geometric = (area.length_squared() > 1e-12 * e1.length_squared() * e2.length_squared()) & area.is_finite();
    let usable = (det.abs() > 1e-7 * uv_scale) & (uv_scale > 0.0) & geometric;
    // ∂P/∂s = (e1·Δt2 − e2·Δt1) / det; ∂P/∂t = (e2·Δs1 − e1·Δs2) / det. Only ∂P/∂s's
    // direction and the sign of (area × ∂P/∂s)·∂P/∂t are used, so the division is by the sign
    // of det alone (the product's sign needs neither: det² > 0).
    let along_s = e1 * d2.y - e2 * d1.y;
    let dp_ds = along_s * det.signum();
    let dp_dt = e2 * d1.x - e1 * d2.x;
    let w = if area.cross(along_s).dot(dp_dt) >= 0.0 { 1.0 } else { -1.0 };
    // `Vec3::try_normalize`, unrolled.
    let rcp = dp_ds.length_recip();
    let ok = usable & rcp.is_finite() & (rcp > 0.0);
    let angles = corner_angles([p0, p1, p2]);
    Face {
        tangent: if ok { dp_ds * rcp } else { Vec3::ZERO },
        w: if usable { w } else { 1.0 },
        ok,
        geometric,
        angles: if ok { angles } else { [0.0; 3] },
    }
}

/// The angles of a triangle at its corners 0, 1, 2 (0 at a corner with an edge of zero length).
#[inline(always)]
pub(super) fn corner_angles(p: [Vec3; 3]) -> [f32; 3] {
    // Edge k runs from corner k to corner k + 1; the angle at corner k lies between edge k
    // and edge k − 1 reversed: cos = −(e_k · e_{k−1}) / (|e_k| |e_{k−1}|).
    let e = [p[1] - p[0], p[2] - p[1], p[0] - p[2]];
    let len2 = e.map(Vec3::length_squared);
    std::array::from_fn(|k| {
        let before = (k + 2) % 3;
        let lengths = (len2[k] * len2[before]).sqrt();
        let cos = -e[k].dot(e[before]) / lengths;
        // A zero-length edge (or one too long to square) leaves no angle.
        if (lengths > 0.0) & lengths.is_finite() { acos(cos) } else { 0.0 }
    })
}

/// arccos x for x in [−1, 1] (clamped), within 2·10⁻⁸ of the exact value before f32 rounding:
/// Abramowitz & Stegun 4.4.46, √(1 − |x|) times a degree-7 polynomial (by Estrin's scheme, so
/// its products overlap), reflected for x < 0. Several times faster here than the C library's
/// `acosf`, which took a third of the time of making tangents, and it vectorizes. Multiplies
/// and adds, not `mul_add`: the same bits on every target, and no software fma.
#[inline(always)]
pub(super) fn acos(x: f32) -> f32 {
    // a₀ is the table's 1.5707963050, one f32 below π/2, not π/2 itself.
    #[allow(clippy::approx_constant)]
    const A: [f32; 8] = [
        1.570_796_3,
        -0.214_598_8,
        0.088_978_99,
        -0.050_174_303,
        0.030_891_88,
        -0.017_088_126,
        0.006_670_09,
        -0.001_262_491_1,
    ];
    let a = x.abs().min(1.0);
    let pair = |k: usize| A[k] + A[k + 1] * a;
    let a2 = a * a;
    let poly = (pair(0) + pair(2) * a2) + (pair(4) + pair(6) * a2) * (a2 * a2);
    let r = (1.0 - a).sqrt() * poly;
    if x < 0.0 { std::f32::consts::PI - r } else { r }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The frame with early returns and `try_normalize`, as written before the lanes: the
    /// definition the branch-free lanes must reproduce bit for bit.
    fn reference(p: [Vec3; 3], t: [Vec2; 3]) -> Face {
        let [(p0, t0), (p1, t1), (p2, t2)] = [(p[0], t[0]), (p[1], t[1]), (p[2], t[2])];
        let (e1, e2) = (p1 - p0, p2 - p0);
        let (d1, d2) = (t1 - t0, t2 - t0);
        let area = e1.cross(e2);
        let det = d1.x * d2.y - d2.x * d1.y;
        let uv_scale = d1.length_squared().max(d2.length_squared());
        let geometric = area.length_squared() > 1e-12 * e1.length_squared() * e2.length_squared() && area.is_finite();
        if !(det.abs() > 1e-7 * uv_scale && uv_scale > 0.0 && geometric) {
            return Face { tangent: Vec3::ZERO, w: 1.0, ok: false, geometric, angles: [0.0; 3] };
        }
        let dp_ds = (e1 * d2.y - e2 * d1.y) * det.signum();
        let dp_dt = e2 * d1.x - e1 * d2.x;
        let w = if area.cross(e1 * d2.y - e2 * d1.y).dot(dp_dt) >= 0.0 { 1.0 } else { -1.0 };
        match dp_ds.try_normalize() {
            Some(t) => Face { tangent: t, w, ok: true, geometric, angles: corner_angles([p0, p1, p2]) },
            None => Face { tangent: Vec3::ZERO, w, ok: false, geometric, angles: [0.0; 3] },
        }
    }

    fn bits(f: &Face) -> ([u32; 3], u32, bool, bool, [u32; 3]) {
        (f.tangent.to_array().map(f32::to_bits), f.w.to_bits(), f.ok, f.geometric, f.angles.map(f32::to_bits))
    }

    /// Random triangles, with repeated corners, slivers, mirrored and collapsed texture
    /// coordinates and huge coordinates among them, in blocks with a partial last one.
    #[test]
    fn blocked_frames_are_the_reference_bit_for_bit() {
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
        };
        let mut mesh = Mesh::default();
        for i in 0..3000 {
            let scale = [1.0, 1e-4, 1e19][i % 3];
            for _ in 0..3 {
                mesh.positions.push(Vec3::new(next(), next(), next()) * scale);
                mesh.texcoords.push(Vec2::new(next(), next()));
            }
            let v = 3 * i as u32;
            mesh.indices.push(match i % 5 {
                0 => [v, v, v + 2],
                _ => [v, v + 1, v + 2],
            });
            if i % 7 == 0 {
                let last = mesh.texcoords.len() - 1;
                mesh.texcoords[last] = mesh.texcoords[last - 1];
            }
        }
        mesh.indices.pop();
        let faces = face_frames(&mesh);
        assert_eq!(faces.len(), mesh.indices.len());
        let mut usable = 0;
        for (tri, face) in mesh.indices.iter().zip(&faces) {
            let r = reference(tri.map(|v| mesh.positions[v as usize]), tri.map(|v| mesh.texcoords[v as usize]));
            assert_eq!(bits(face), bits(&r), "triangle {tri:?}");
            usable += face.ok as usize;
        }
        assert!(usable > 1000 && usable < mesh.indices.len(), "{usable} usable: every branch taken");
    }
}
