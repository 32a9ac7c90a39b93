//! Every kind of glTF the tool writes, checked by the Khronos glTF validator (npm
//! `gltf-validator`, installed by `.ci/run` into `scripts/gltf-validator/`): 0 errors each.
//! Covers both tangent modes on every test mesh (degenerate and zero-normal ones included), .gltf
//! and .glb, file names that need percent-encoding, an OBJ → glTF round trip, and the low-poly
//! mesh `bake --low-out` writes with its baked map.
//!
//! Without Node or the validator the test says so and passes — except under CI (`CI` set),
//! where that is a failure.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::*;

fn validator() -> Option<PathBuf> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/gltf-validator/validate.js");
    let module = script.with_file_name("node_modules/gltf-validator");
    let node = Command::new("node").arg("--version").output().is_ok_and(|o| o.status.success());
    if node && module.is_dir() {
        return Some(script);
    }
    let why = "the Khronos glTF validator needs Node and `npm ci` in scripts/gltf-validator";
    assert!(std::env::var_os("CI").is_none(), "{why}");
    eprintln!("skipped: {why}");
    None
}

/// Runs the validator on `files`; returns each file's (errors, messages).
fn validate(script: &Path, files: &[PathBuf]) -> Vec<(String, u64, Vec<String>)> {
    let o = Command::new("node").arg(script).args(files).output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.code().is_some_and(|c| c <= 1), "validator failed to run: {}", stderr(&o));
    text.lines()
        .map(|line| {
            let field = |name: &str| -> &str {
                let at = line.find(&format!("\"{name}\":")).unwrap() + name.len() + 3;
                &line[at..]
            };
            let errors: u64 = field("errors").split([',', '}']).next().unwrap().parse().unwrap();
            let file = field("file").split('"').nth(1).unwrap().to_string();
            (file, errors, vec![field("messages").to_string()])
        })
        .collect()
}

#[test]
fn every_gltf_the_tool_writes_passes_the_khronos_validator() {
    let Some(script) = validator() else { return };
    let dir = scratch("gltf_validator");
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../bumpmap-io/tests/data/mikktspace");
    let mut files = Vec::new();
    for name in ["cube", "doomcone", "doomcone_smooth", "rancid_geometry", "obliterated"] {
        for mode in ["ours", "mikktspace"] {
            for ext in ["gltf", "glb"] {
                let out = dir.join(format!("{name}_{mode}.{ext}"));
                let input = data.join(format!("{name}.obj"));
                let o = bumpmap(&["tangents", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--mode", mode]);
                assert!(o.status.success(), "{name} {mode}: {}", stderr(&o));
                files.push(out);
            }
        }
    }
    // Names a URI must escape.
    let cube = data.join("cube.obj");
    for name in ["a%20b.gltf", "my cube#1.gltf", "ünï cödé.gltf"] {
        let out = dir.join(name);
        let o = bumpmap(&["tangents", cube.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        files.push(out);
    }
    // A ready-to-view asset: the normal map packed as the material's normalTexture.
    let normal = dir.join("bricks_normal.png");
    let o = bumpmap(&["normalmap", "bricks@64", "-o", normal.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for ext in ["glb", "gltf"] {
        let out = dir.join(format!("packed.{ext}"));
        let o = bumpmap(&[
            "tangents",
            cube.to_str().unwrap(),
            "--normal-map",
            normal.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let (doc, _, images) = gltf::import(&out).unwrap();
        let material = doc.meshes().next().unwrap().primitives().next().unwrap().material();
        assert_eq!(material.normal_texture().map(|t| t.texture().source().index()), Some(0));
        assert_eq!((images[0].width, images[0].height), (64, 64), "the packed image is the normal map");
        files.push(out);
    }
    // LOW as a bake writes it (--low-out): its tangents and the baked map as its normalTexture.
    let (high, low) = (dir.join("bake_high.obj"), dir.join("bake_low.obj"));
    std::fs::write(&high, "v -1 -1 0.1\nv 1 -1 0.1\nv 1 1 0.2\nv -1 1 0.1\nf 1 2 3\nf 1 3 4\n").unwrap();
    std::fs::write(
        &low,
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
    )
    .unwrap();
    for ext in ["glb", "gltf"] {
        let out = dir.join(format!("baked_low.{ext}"));
        let map = dir.join(format!("baked_{ext}.png"));
        let o = bumpmap(&[
            "bake",
            high.to_str().unwrap(),
            low.to_str().unwrap(),
            "-o",
            map.to_str().unwrap(),
            "--size",
            "32",
            "--extrude",
            "0.5",
            "--low-out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        files.push(out);
    }
    let results = validate(&script, &files);
    assert_eq!(results.len(), files.len(), "one report per file");
    let bad: Vec<_> = results.iter().filter(|(_, errors, _)| *errors > 0).collect();
    assert!(bad.is_empty(), "files with validator errors: {bad:#?}");
}

#[test]
fn an_obj_quad_comes_out_of_gltf_the_right_way_up_with_gltf_handedness() {
    let dir = scratch("obj_round_trip");
    // A unit quad facing +z; OBJ's v = 0 at the bottom edge (y = 0), as Blender writes it.
    let obj =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";
    let input = dir.join("quad.obj");
    std::fs::write(&input, obj).unwrap();
    for (flag, top_v, w) in [("flip", 0.0, 1.0), ("keep", 1.0, -1.0)] {
        let out = dir.join(format!("quad_{flag}.glb"));
        let o = bumpmap(&["tangents", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--obj-v", flag]);
        assert!(o.status.success(), "{}", stderr(&o));
        let (doc, buffers, _) = gltf::import(&out).unwrap();
        let prim = doc.meshes().next().unwrap().primitives().next().unwrap();
        let reader = prim.reader(|b| Some(&buffers[b.index()]));
        let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        let uvs: Vec<[f32; 2]> = reader.read_tex_coords(0).unwrap().into_f32().collect();
        let tangents: Vec<[f32; 4]> = reader.read_tangents().unwrap().collect();
        for ((p, uv), t) in positions.iter().zip(&uvs).zip(&tangents) {
            // glTF's v = 0 is the image's top row: the quad's top edge (y = 1) with the OBJ
            // convention flipped; the bottom edge if the file's v is kept as it is.
            let want_v = if p[1] == 1.0 { top_v } else { 1.0 - top_v };
            assert_eq!(uv[1], want_v, "--obj-v {flag}: vertex {p:?} has v {}", uv[1]);
            assert_eq!(uv[0], p[0], "u runs along x");
            // T along +x; glTF's bitangent cross(N, T)·w = +y must point to the image's up.
            assert!((t[0] - 1.0).abs() < 1e-5, "tangent {t:?}");
            assert_eq!(t[3], w, "--obj-v {flag}: w");
        }
    }
}

#[test]
fn a_normal_map_that_is_not_a_png_is_refused_and_nothing_is_written() {
    let dir = scratch("normal_map_not_png");
    let cube = Path::new(env!("CARGO_MANIFEST_DIR")).join("../bumpmap-io/tests/data/mikktspace/cube.obj");
    let fake = dir.join("n.jpg");
    std::fs::write(&fake, [0xFF, 0xD8, 0xFF, 0xE0, 0, 16]).unwrap();
    let out = dir.join("o.glb");
    fails_cleanly(
        &dir,
        &["tangents", cube.to_str().unwrap(), "--normal-map", fake.to_str().unwrap(), "-o", out.to_str().unwrap()],
        &fake,
        "must be a PNG",
    );
}
