//! `--mode mikktspace` against the reference MikkTSpace C implementation on bevy_mikktspace's
//! test meshes (CC0, degenerate geometry included).
//!
//! `tests/data/mikktspace/NAME.tan` holds the reference's output: one `[f32; 4]` tangent per
//! triangle corner, face-major, made by running the C `genTangSpaceDefault` (through the
//! `../shared/peers/mikktspace_bench.c` driver) on the triangle soup that
//! [`write_soup_for_reference`] writes from our loader's mesh.

use std::path::{Path, PathBuf};

use bumpmap_io::{MeshOptions, ObjTexcoords, load_mesh_with};
use bumpmap_math::mesh::Mesh;
use bumpmap_math::tangent::{mikktspace_corner_tangents, mikktspace_in_pieces};

const MESHES: [&str; 5] = ["cube", "doomcone", "doomcone_smooth", "rancid_geometry", "obliterated"];

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mikktspace").join(name)
}

/// The mesh with its OBJ texture coordinates as written (v up): the reference data were made
/// from those.
fn raw(name: &str) -> Mesh {
    let options = MeshOptions { obj_texcoords: ObjTexcoords::Keep, ..Default::default() };
    load_mesh_with(&data(&format!("{name}.obj")), &options).unwrap().mesh
}

fn reference(name: &str) -> Vec<[f32; 4]> {
    let bytes = std::fs::read(data(&format!("{name}.tan"))).unwrap();
    bytes
        .chunks_exact(16)
        .map(|c| std::array::from_fn(|i| f32::from_le_bytes(c[4 * i..4 * i + 4].try_into().unwrap())))
        .collect()
}

#[test]
fn mikktspace_mode_equals_the_reference_c_code() {
    for name in MESHES {
        let mesh = raw(name);
        let ours = mikktspace_corner_tangents(&mesh).unwrap();
        let want = reference(name);
        assert_eq!(ours.len(), want.len(), "{name}: corner count");
        let mut worst = 0.0f32;
        for (i, (a, b)) in ours.iter().zip(&want).enumerate() {
            assert_eq!(a.w, b[3], "{name} corner {i}: handedness");
            let d = (a.truncate() - glam::Vec3::new(b[0], b[1], b[2])).abs().max_element();
            worst = worst.max(d);
        }
        // bevy_mikktspace reproduces the C code's arithmetic; 1e-5 allows for a differently
        // ordered float sum, far below anything visible (1e-5 rad ≈ 0.0006°).
        assert!(worst <= 1e-5, "{name}: worst component difference {worst}");
    }
}

#[test]
fn mikktspace_in_parallel_pieces_equals_the_whole_mesh_bit_for_bit() {
    // The large-mesh path splits faces into pieces with a one-ring halo; on the broken test
    // meshes (degenerate, duplicated, seamed geometry) it must change nothing at all.
    for name in MESHES {
        let mesh = raw(name);
        let whole = mikktspace_in_pieces(&mesh, 1).unwrap();
        for pieces in [2, 3, 7] {
            let split = mikktspace_in_pieces(&mesh, pieces).unwrap();
            let differing = whole
                .iter()
                .zip(&split)
                .filter(|(a, b)| a.to_array().map(f32::to_bits) != b.to_array().map(f32::to_bits))
                .count();
            assert_eq!(differing, 0, "{name} in {pieces} pieces: {differing} corners differ");
        }
    }
}

#[test]
fn split_vertices_carry_each_corners_tangent_and_nothing_else_changes() {
    use bumpmap_math::tangent::{TangentMode, TangentOptions, generate_tangents};
    let options = TangentOptions { mode: TangentMode::MikkTSpace, ..Default::default() };
    let mut split_somewhere = false;
    for name in MESHES {
        let mesh = raw(name);
        let corners = mikktspace_corner_tangents(&mesh).unwrap();
        let (out, report) = generate_tangents(&mesh, &options).unwrap();
        assert_eq!(out.vertex_count(), mesh.vertex_count() + report.vertices_split, "{name}");
        // One new vertex per vertex and tangent that differs from its first corner's.
        let mut distinct = std::collections::HashSet::new();
        let mut first = vec![None; mesh.vertex_count()];
        for (c, &t) in corners.iter().enumerate() {
            let v = mesh.indices[c / 3][c % 3] as usize;
            let bits = t.to_array().map(f32::to_bits);
            match first[v] {
                None => first[v] = Some(t),
                Some(f) if f != t => {
                    distinct.insert((v, bits));
                }
                Some(_) => {}
            }
        }
        assert_eq!(report.vertices_split, distinct.len(), "{name}");
        split_somewhere |= report.vertices_split > 0;
        for (c, &t) in corners.iter().enumerate() {
            let (old, new) = (mesh.indices[c / 3][c % 3] as usize, out.indices[c / 3][c % 3] as usize);
            let bits = |v: glam::Vec4| v.to_array().map(f32::to_bits);
            assert_eq!(bits(out.tangents[new]), bits(t), "{name} corner {c}");
            assert_eq!(out.positions[new], mesh.positions[old], "{name} corner {c}");
            assert_eq!(out.texcoords[new], mesh.texcoords[old], "{name} corner {c}");
            assert!(new == old || new >= mesh.vertex_count(), "{name} corner {c}: moved to another old vertex");
        }
    }
    assert!(split_somewhere, "no test mesh split a vertex: the check above saw nothing");
}

/// Writes each test mesh as the triangle soup the C driver reads (`int32 nverts, int32 ntris,
/// float pos[3n], nrm[3n], uv[2n], uint32 idx[3t]`), one vertex per corner. Run with
/// `--ignored` to regenerate the reference: `BUMPMAP_SOUP_DIR=/tmp/mk cargo test -p bumpmap-io
/// --test mikktspace_reference -- --ignored`, then the driver on each `.mesh`.
#[test]
#[ignore]
fn write_soup_for_reference() {
    let dir = PathBuf::from(std::env::var("BUMPMAP_SOUP_DIR").unwrap_or("/tmp".into()));
    for name in MESHES {
        let mesh = raw(name);
        let corners: Vec<usize> = mesh.indices.iter().flatten().map(|&i| i as usize).collect();
        let mut out = Vec::new();
        out.extend((corners.len() as i32).to_le_bytes());
        out.extend((mesh.indices.len() as i32).to_le_bytes());
        for &c in &corners {
            out.extend(mesh.positions[c].to_array().iter().flat_map(|v| v.to_le_bytes()));
        }
        for &c in &corners {
            out.extend(mesh.normals[c].to_array().iter().flat_map(|v| v.to_le_bytes()));
        }
        for &c in &corners {
            out.extend(mesh.texcoords[c].to_array().iter().flat_map(|v| v.to_le_bytes()));
        }
        for i in 0..corners.len() as u32 {
            out.extend(i.to_le_bytes());
        }
        std::fs::write(dir.join(format!("{name}.mesh")), out).unwrap();
    }
}
