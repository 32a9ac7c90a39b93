//! `bumpmap tangents` end to end: glTF out with TANGENT, and bad meshes failing cleanly.

mod common;

use common::*;

const CUBE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../bumpmap-io/tests/data/mikktspace/cube.obj");

#[test]
fn tangents_writes_gltf_with_a_tangent_attribute() {
    let dir = scratch("tangents_gltf");
    for (mode, ext) in [("ours", "glb"), ("mikktspace", "gltf")] {
        let out = dir.join(format!("cube_{mode}.{ext}"));
        let o = bumpmap(&["tangents", CUBE, "-o", out.to_str().unwrap(), "--mode", mode]);
        assert!(o.status.success(), "{}", stderr(&o));
        let report = String::from_utf8_lossy(&o.stdout);
        assert!(report.contains("mirrored") && report.contains("vertices split"), "{report}");
        let (doc, buffers, _) = gltf::import(&out).unwrap();
        let prim = doc.meshes().next().unwrap().primitives().next().unwrap();
        let reader = prim.reader(|b| Some(&buffers[b.index()].0[..]));
        let tangents: Vec<[f32; 4]> = reader.read_tangents().expect("TANGENT attribute").collect();
        let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
        assert!(!tangents.is_empty());
        for (t, n) in tangents.iter().zip(&normals) {
            assert!(t[3] == 1.0 || t[3] == -1.0, "w = ±1, got {}", t[3]);
            let len = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
            assert!((len - 1.0).abs() < 1e-4, "{mode}: unit tangent, got |T| = {len}");
            // Ours is always ⟂ N; MikkTSpace, like its C original, leaves its default (1, 0, 0)
            // on corners of faces with no texture-space area and no usable neighbour.
            if mode == "ours" {
                let dot = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
                assert!(dot.abs() < 1e-4, "tangent ⟂ normal ({dot})");
            }
        }
    }
    assert_eq!(listing(&dir), ["cube_mikktspace.bin", "cube_mikktspace.gltf", "cube_ours.glb"]);
}

/// `tangents IN -o out.glb` must fail cleanly, naming IN.
fn fails(dir: &std::path::Path, input: &std::path::Path, expect: &str) {
    let out = dir.join("out.glb");
    fails_cleanly(dir, &["tangents", input.to_str().unwrap(), "-o", out.to_str().unwrap()], input, expect);
}

#[test]
fn bad_meshes_fail_with_a_clear_message_and_no_output() {
    let dir = scratch("bad_meshes");
    let write = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let cube = std::fs::read_to_string(CUBE).unwrap();
    fails(&dir, &write("truncated.obj", &cube[..cube.len() / 2].replace("\nf ", "\nf 1/")), "");
    fails(&dir, &write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 99/3\n"), "");
    fails(&dir, &write("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n"), "");
    fails(&dir, &write("inf.obj", "v 1e39 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n"), "");
    fails(&dir, &write("nouv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "texture coordinates");
    // A glTF whose accessor claims three billion vertices over a 36-byte buffer.
    let huge = r#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
        "bufferViews":[{"buffer":0,"byteLength":36}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3000000000,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]}"#;
    fails(&dir, &write("huge.gltf", huge), "");
    fails(&dir, &write("truncated.gltf", &huge[..80]), "not a readable glTF");
    fails(&dir, &dir.join("missing.obj"), "cannot read");
}

#[test]
fn output_must_not_replace_the_input() {
    let dir = scratch("tangents_same");
    let input = dir.join("m.glb");
    let o = bumpmap(&["tangents", CUBE, "-o", input.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let before = std::fs::read(&input).unwrap();
    let o = bumpmap(&["tangents", input.to_str().unwrap(), "-o", input.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("overwrite the input"));
    assert_eq!(std::fs::read(&input).unwrap(), before);
}

#[test]
fn a_gltf_pointing_outside_its_folder_is_refused_end_to_end() {
    let root = scratch("tangents_outside");
    let dir = root.join("model");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(root.join("secret.bin"), vec![7u8; 64]).unwrap();
    let json = r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"../secret.bin","byteLength":64}],
"bufferViews":[{"buffer":0,"byteLength":36}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]}"#;
    let input = dir.join("evil.gltf");
    std::fs::write(&input, json).unwrap();
    let out = dir.join("out.glb");
    let (input_s, out_s, scene) =
        (input.display().to_string(), out.display().to_string(), format!("mesh:{}", input.display()));
    let tangents = ["tangents", input_s.as_str(), "-o", out_s.as_str()];
    let render = ["render", "--size", "16", "-o", out_s.as_str(), "--scene", scene.as_str()];
    for command in [&tangents[..], &render[..]] {
        fails_cleanly(&dir, command, &input, "outside the glTF's folder");
    }
}
