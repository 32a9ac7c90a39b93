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

#[test]
fn indices_that_name_no_element_are_errors_checked_in_64_bits() {
    let n = "vn 0 0 1\n";
    // tobj wrapped this one around to an index in range: vertex 0 got a normal not in the file.
    refused(
        &format!("{QUAD}{n}f 1/1/-6148914691236517207 2/2/1 3/3/1\n"),
        "line 10: normal index -6148914691236517207 names none",
    );
    refused(&format!("{QUAD}f 1/1 2/2 5/3\n"), "line 9: position index 5 names none of the file's 4 vs (1..=4");
    refused(&format!("{QUAD}f 1/1 2/0 3/3\n"), "texture coordinate index 0 names none");
    refused(&format!("{QUAD}f -5/1 2/2 3/3\n"), "position index -5 names none");
    refused(
        &format!("{QUAD}f 1/1 2/2 99999999999999999999/3\n"),
        "position index '99999999999999999999' is beyond any count of the file's vs",
    );
    refused(&format!("{QUAD}f 1/1 2/2 3x/3\n"), "position index '3x' is not a whole number");
    // Counting back reaches only what was defined before the face; forward indices, any of the file's.
    refused(&format!("v 0 0 0\nf -1 -2 -3\n{QUAD}"), "position index -2 names none");
    let obj = format!("{QUAD}f -4/-4 -3/-3 -2/-2\nv 5 5 5\nf 1/1 2/2 5/3\n");
    let m = read_mesh(obj.as_bytes(), Path::new("ok.obj"), MeshFormat::Obj).unwrap().mesh;
    assert_eq!(m.indices.len(), 2);
}
