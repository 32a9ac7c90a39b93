//! glTF and GLB files made to break the loader: each must be refused with a message that names
//! the file and what is wrong — no panic, no huge allocation, no file read outside the glTF's
//! folder.

use std::path::{Path, PathBuf};

use bumpmap_io::load_mesh;

fn scratch(name: &str) -> PathBuf {
    // Under the target folder, not the system's temporary one: a run leaves nothing in /tmp.
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("hostile-gltf-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// One triangle: positions (36 bytes), texture coordinates (24), u16 indices (6, padded to 8).
fn triangle_bin() -> Vec<u8> {
    let mut b = Vec::new();
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for i in [0u16, 1, 2, 0] {
        b.extend_from_slice(&i.to_le_bytes());
    }
    b
}

/// The triangle's glTF JSON with `uri` as its buffer and the given index and texcoord
/// component types.
fn gltf_json(uri: &str, index_type: u32, uv_type: u32, uv_normalized: bool) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},
"buffers":[{{"uri":"{uri}","byteLength":68}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":24}},{{"buffer":0,"byteOffset":60,"byteLength":6}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":{uv_type},"normalized":{uv_normalized},"count":3,"type":"VEC2"}},
{{"bufferView":2,"componentType":{index_type},"count":3,"type":"SCALAR"}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":1}},"indices":2}}]}}]}}"#
    )
}

fn refused(path: &Path, expect: &str) -> String {
    let result = std::panic::catch_unwind(|| load_mesh(path));
    let result = result.unwrap_or_else(|_| panic!("{}: the loader panicked", path.display()));
    let e = result.err().unwrap_or_else(|| panic!("{}: must be refused", path.display())).to_string();
    assert!(e.contains(&path.display().to_string()), "the message names the file: {e}");
    assert!(e.contains(expect), "message must say '{expect}': {e}");
    e
}

#[test]
fn a_well_formed_triangle_loads_from_a_file_and_from_a_data_uri() {
    let dir = scratch("ok");
    std::fs::write(dir.join("t.bin"), triangle_bin()).unwrap();
    std::fs::write(dir.join("t.gltf"), gltf_json("t.bin", 5123, 5126, false)).unwrap();
    let m = load_mesh(&dir.join("t.gltf")).unwrap().mesh;
    assert_eq!((m.positions.len(), m.indices.len(), m.texcoords.len()), (3, 1, 3));
    // A percent-encoded name inside the folder is fine.
    std::fs::write(dir.join("a b.bin"), triangle_bin()).unwrap();
    std::fs::write(dir.join("s.gltf"), gltf_json("a%20b.bin", 5123, 5126, false)).unwrap();
    assert_eq!(load_mesh(&dir.join("s.gltf")).unwrap().mesh.positions.len(), 3);
    let data = format!("data:application/octet-stream;base64,{}", base64::encode(triangle_bin()));
    std::fs::write(dir.join("d.gltf"), gltf_json(&data, 5123, 5126, false)).unwrap();
    assert_eq!(load_mesh(&dir.join("d.gltf")).unwrap().mesh.positions.len(), 3);
    // A buffer file longer than byteLength: only byteLength bytes are read (and used).
    let mut long = triangle_bin();
    long.extend(vec![0xAB; 300_000]);
    std::fs::write(dir.join("long.bin"), long).unwrap();
    std::fs::write(dir.join("l.gltf"), gltf_json("long.bin", 5123, 5126, false)).unwrap();
    assert_eq!(load_mesh(&dir.join("l.gltf")).unwrap().mesh.indices, [[0, 1, 2]]);
}

#[test]
fn buffers_outside_the_gltfs_folder_are_refused_without_reading_them() {
    let root = scratch("outside");
    let dir = root.join("model");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(root.join("secret.bin"), b"SECRET-BYTES-NOT-TO-ECHO-0123456789012345678901234567890123456789")
        .unwrap();
    for (name, uri) in [
        ("parent", "../secret.bin"),
        ("encoded", "..%2Fsecret.bin"),
        ("encoded_dots", "%2E%2E/secret.bin"),
        ("absolute", "/etc/passwd"),
        ("dev_zero", "/dev/zero"),
        ("backslash", "..\\\\secret.bin"),
    ] {
        let path = dir.join(format!("{name}.gltf"));
        std::fs::write(&path, gltf_json(uri, 5123, 5126, false)).unwrap();
        let e = refused(&path, "outside the glTF's folder");
        assert!(!e.contains("SECRET") && !e.contains("root:"), "no bytes of the file in the message: {e}");
    }
    // A URI with a scheme is no path at all.
    let path = dir.join("scheme.gltf");
    std::fs::write(&path, gltf_json("file:///etc/passwd", 5123, 5126, false)).unwrap();
    refused(&path, "has a scheme");
    // With outside paths allowed, `..` is followed — still to a regular file, at most
    // byteLength bytes; /dev/zero is still refused without being read.
    std::fs::write(root.join("t.bin"), triangle_bin()).unwrap();
    let path = dir.join("allowed.gltf");
    std::fs::write(&path, gltf_json("../t.bin", 5123, 5126, false)).unwrap();
    let allow = bumpmap_io::MeshOptions { allow_outside_paths: true, ..Default::default() };
    let loaded = bumpmap_io::load_mesh_with(&path, &allow).unwrap();
    assert_eq!(loaded.mesh.positions.len(), 3);
    assert!(loaded.sources.iter().any(|s| s.ends_with("t.bin")), "the buffer file is a protected input");
    let path = dir.join("zero_allowed.gltf");
    std::fs::write(&path, gltf_json("/dev/zero", 5123, 5126, false)).unwrap();
    let e = bumpmap_io::load_mesh_with(&path, &allow).unwrap_err().to_string();
    assert!(e.contains("not a regular file"), "{e}");
    // A link inside the folder that leads out is refused too.
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(root.join("secret.bin"), dir.join("link.bin")).unwrap();
        std::os::unix::fs::symlink("/dev/zero", dir.join("zero.bin")).unwrap();
        for link in ["link.bin", "zero.bin"] {
            let path = dir.join(format!("{link}.gltf"));
            std::fs::write(&path, gltf_json(link, 5123, 5126, false)).unwrap();
            refused(&path, "outside the glTF's folder");
        }
    }
    // Something that is not a regular file is not read.
    std::fs::create_dir_all(dir.join("folder.bin")).unwrap();
    let path = dir.join("folder.gltf");
    std::fs::write(&path, gltf_json("folder.bin", 5123, 5126, false)).unwrap();
    refused(&path, "not a regular file");
}

#[test]
fn accessors_the_loader_cannot_read_are_refused_not_panicked_on() {
    let dir = scratch("accessors");
    std::fs::write(dir.join("t.bin"), triangle_bin()).unwrap();
    let cases = [
        ("float_indices", gltf_json("t.bin", 5126, 5126, false), "indices accessor 2"),
        ("short_uv", gltf_json("t.bin", 5123, 5122, false), "TEXCOORD_0 accessor 1"),
        ("uint_uv", gltf_json("t.bin", 5123, 5125, false), "TEXCOORD_0 accessor 1"),
        ("unnormalized_byte_uv", gltf_json("t.bin", 5123, 5121, false), "TEXCOORD_0 accessor 1"),
    ];
    for (name, json, expect) in cases {
        let path = dir.join(format!("{name}.gltf"));
        std::fs::write(&path, json).unwrap();
        refused(&path, expect);
    }
    // COLOR_0 of a shape or component type glTF does not allow (the gltf crate's reader would
    // reach `unreachable!`): accessor 3 over the texture coordinates' bytes.
    let with_color = |component: u32, normalized: bool, shape: &str| {
        gltf_json("t.bin", 5123, 5126, false)
            .replace(
                r#"{"bufferView":2,"componentType":5123,"count":3,"type":"SCALAR"}]"#,
                &format!(
                    r#"{{"bufferView":2,"componentType":5123,"count":3,"type":"SCALAR"}},{{"bufferView":1,"componentType":{component},"normalized":{normalized},"count":1,"type":"{shape}"}}]"#
                ),
            )
            .replace(r#""TEXCOORD_0":1}"#, r#""TEXCOORD_0":1,"COLOR_0":3}"#)
    };
    for (name, component, normalized, shape) in [
        ("color_vec2", 5126, false, "VEC2"),
        ("color_scalar", 5126, false, "SCALAR"),
        ("color_mat4", 5126, false, "MAT4"),
        ("color_uint", 5125, false, "VEC4"),
        ("color_byte", 5120, true, "VEC4"),
        ("color_unnormalized", 5121, false, "VEC3"),
    ] {
        let path = dir.join(format!("{name}.gltf"));
        let json = with_color(component, normalized, shape);
        assert!(json.contains("\"COLOR_0\":3"), "{json}");
        std::fs::write(&path, json).unwrap();
        refused(&path, "COLOR_0 accessor 3");
    }
    // An allowed one loads (one entry for three vertices is refused as such, not panicked on).
    let path = dir.join("color_ok.gltf");
    std::fs::write(&path, with_color(5126, false, "VEC4")).unwrap();
    refused(&path, "COLOR_0 has 1 entries for 3 vertices");
    // Too many elements for the view, and a view past its buffer.
    let json = gltf_json("t.bin", 5123, 5126, false);
    let path = dir.join("count.gltf");
    std::fs::write(&path, json.replacen(r#""count":3,"type":"VEC3""#, r#""count":300,"type":"VEC3""#, 1)).unwrap();
    refused(&path, "runs past bufferView 0");
    let path = dir.join("view.gltf");
    std::fs::write(&path, json.replace(r#""byteOffset":60,"byteLength":6"#, r#""byteOffset":60,"byteLength":600"#))
        .unwrap();
    refused(&path, "runs past its buffer");
    // A buffer shorter than it says.
    let path = dir.join("short.gltf");
    std::fs::write(dir.join("short.bin"), &triangle_bin()[..20]).unwrap();
    std::fs::write(&path, gltf_json("short.bin", 5123, 5126, false)).unwrap();
    refused(&path, "declares 68 bytes but has 20");
    // No accessors at all, and an empty object.
    let path = dir.join("no_accessors.gltf");
    let stripped = json.replace(&json[json.find("\"accessors\"").unwrap()..json.find("\"meshes\"").unwrap()], "");
    std::fs::write(&path, stripped).unwrap();
    refused(&path, "no_accessors.gltf");
    let path = dir.join("empty.gltf");
    std::fs::write(&path, "{}").unwrap();
    refused(&path, "empty.gltf");
}

#[test]
fn glb_headers_that_lie_about_their_length_are_refused_before_any_allocation() {
    let dir = scratch("glb");
    let json = br#"{"asset":{"version":"2.0"}}  "#;
    let glb = |length: u32, chunk: u32| {
        let mut b = b"glTF".to_vec();
        b.extend_from_slice(&2u32.to_le_bytes());
        b.extend_from_slice(&length.to_le_bytes());
        b.extend_from_slice(&chunk.to_le_bytes());
        b.extend_from_slice(b"JSON");
        b.extend_from_slice(json);
        b
    };
    let real = 12 + 8 + json.len() as u32;
    for (name, bytes, expect) in [
        ("zero", glb(0, json.len() as u32), "GLB header says 0 bytes"),
        ("one", glb(1, json.len() as u32), "GLB header says 1 bytes"),
        ("huge", glb(u32::MAX, json.len() as u32), "GLB header says"),
        ("chunk", glb(real, u32::MAX - 4), "past the end of the file"),
        ("cut", b"glTF\x02\x00".to_vec(), "cut short"),
    ] {
        let path = dir.join(format!("{name}.glb"));
        std::fs::write(&path, bytes).unwrap();
        refused(&path, expect);
    }
}

#[test]
fn node_transforms_place_each_instance_and_mirrors_keep_the_winding() {
    let dir = scratch("nodes");
    std::fs::write(dir.join("t.bin"), triangle_bin()).unwrap();
    let base = gltf_json("t.bin", 5123, 5126, false);
    // Two instances of the triangle: one moved along x, one mirrored in x (scale -1).
    let json = base.replacen(
        r#""meshes""#,
        r#""scene":0,"scenes":[{"nodes":[0,1]}],"nodes":[{"mesh":0,"translation":[10,0,0]},{"mesh":0,"scale":[-1,1,1],"children":[2]},{"mesh":0,"translation":[0,0,5]}],"meshes""#,
        1,
    );
    let path = dir.join("two.gltf");
    std::fs::write(&path, json).unwrap();
    let m = load_mesh(&path).unwrap().mesh;
    assert_eq!(m.positions.len(), 9, "three instances, three copies");
    assert_eq!(m.positions[1], glam::Vec3::new(11.0, 0.0, 0.0));
    assert_eq!(m.positions[4], glam::Vec3::new(-1.0, 0.0, 0.0));
    // The child inherits the mirror: (1, 0, 0) + (0, 0, 5) seen through scale (-1, 1, 1).
    assert_eq!(m.positions[7], glam::Vec3::new(-1.0, 0.0, 5.0));
    // Every copy still faces +z: the mirrored ones' winding was turned around.
    for t in &m.indices {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        assert!((b - a).cross(c - a).z > 0.0, "triangle {t:?} faces away");
    }
    // A cycle in the hierarchy is an error, not a hang.
    let cyclic = base.replacen(
        r#""meshes""#,
        r#""nodes":[{"mesh":0,"children":[1]},{"children":[0]}],"scenes":[{"nodes":[0]}],"meshes""#,
        1,
    );
    let path = dir.join("cycle.gltf");
    std::fs::write(&path, cyclic).unwrap();
    let result = std::panic::catch_unwind(|| load_mesh(&path)).expect("no panic");
    assert!(result.is_err(), "a node that is its own ancestor is refused");
}

#[test]
fn a_gltf_in_memory_reads_no_files() {
    let dir = scratch("memory");
    std::fs::write(dir.join("t.bin"), triangle_bin()).unwrap();
    let json = gltf_json("t.bin", 5123, 5126, false);
    let name = dir.join("t.gltf");
    let e = bumpmap_io::read_mesh(json.as_bytes(), &name, bumpmap_io::MeshFormat::Gltf).unwrap_err().to_string();
    assert!(e.contains("has no folder"), "{e}");
}

#[test]
fn a_byte_stride_shorter_than_its_element_is_refused() {
    // Positions (12-byte VEC3) read through a view whose byteStride is 4: the gltf crate's
    // reader panicked on it; the accessor checks refuse it first.
    let dir = scratch("stride");
    std::fs::write(dir.join("t.bin"), triangle_bin()).unwrap();
    for (view, accessor) in [(0, 0), (1, 1)] {
        let json = gltf_json("t.bin", 5123, 5126, false).replacen(
            &format!(r#"{{"buffer":0,"byteOffset":{},"byteLength""#, [0, 36][view]),
            &format!(r#"{{"buffer":0,"byteStride":4,"byteOffset":{},"byteLength""#, [0, 36][view]),
            1,
        );
        let path = dir.join(format!("stride{view}.gltf"));
        std::fs::write(&path, json).unwrap();
        refused(&path, &format!("accessor {accessor} reads"));
    }
}

#[test]
fn a_node_graph_that_is_not_a_tree_is_refused_at_once() {
    // 40 nodes, each listing the next one twice: 2⁴⁰ paths, a 2 KB file that took 5 GiB.
    let dir = scratch("dag");
    std::fs::write(dir.join("t.bin"), triangle_bin()).unwrap();
    let nodes: Vec<String> = (0..40)
        .map(|i| if i == 39 { r#"{"mesh":0}"#.to_string() } else { format!(r#"{{"children":[{0},{0}]}}"#, i + 1) })
        .collect();
    let json = gltf_json("t.bin", 5123, 5126, false).replacen(
        r#""meshes""#,
        &format!(r#""scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{}],"meshes""#, nodes.join(",")),
        1,
    );
    let path = dir.join("dag.gltf");
    std::fs::write(&path, json).unwrap();
    refused(&path, "is reached twice");
}
