//! OBJ files that `tobj` alone would read with parts silently missing: each must be refused
//! with the file, the line and what is wrong.

use std::path::Path;

use bumpmap_io::{MeshFormat, read_mesh};

fn refused(obj: &str, expect: &str) {
    let name = Path::new("models/bad.obj");
    let e = read_mesh(obj.as_bytes(), name, MeshFormat::Obj).unwrap_err().to_string();
    assert!(e.contains("models/bad.obj"), "the message names the file: {e}");
    assert!(e.contains(expect), "message must say '{expect}': {e}");
}

const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";

#[test]
fn faces_of_one_or_two_vertices_are_errors_naming_the_line() {
    refused(&format!("{QUAD}f 1/1 2/2 3/3\nf 1/1 2/2\n"), "line 10: a face needs at least 3 vertices, this one has 2");
    refused(&format!("{QUAD}f 4/4\n"), "line 9: a face needs at least 3 vertices, this one has 1");
}

#[test]
fn texture_coordinates_on_only_some_faces_are_an_error() {
    refused(
        &format!("{QUAD}f 1/1 2/2 3/3\nf 1 3 4\n"),
        "only some faces have texture coordinates (line 9 has, line 10 has not)",
    );
    refused(&format!("{QUAD}f 1/1 2/2 3/3\nf 1//1 3/3 4/4\n"), "only some faces");
}

#[test]
fn a_whole_obj_loads_and_its_material_library_is_not_opened() {
    // The mtllib points at a file that must not be read (it does not exist; tobj would try).
    let obj = format!("mtllib /etc/passwd\n{QUAD}usemtl x\nf 1/1 2/2 3/3 4/4\n");
    let m = read_mesh(obj.as_bytes(), Path::new("ok.obj"), MeshFormat::Obj).unwrap().mesh;
    assert_eq!(m.indices.len(), 2);
    assert_eq!(m.texcoords.len(), 4);
    // Faces without any texture coordinates are fine: the mesh has none.
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let m = read_mesh(obj.as_bytes(), Path::new("ok.obj"), MeshFormat::Obj).unwrap().mesh;
    assert!(m.texcoords.is_empty());
}
