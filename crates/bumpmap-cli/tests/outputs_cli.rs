//! Output sets end to end: every file of a command checked against every input before any is
//! written, and written all or nothing; inputs never replaced; no empty folders left behind.

mod common;

use common::*;

#[test]
fn a_mip_level_output_that_is_an_input_is_refused_and_the_input_survives() {
    let dir = scratch("out_mip_input");
    let input = dir.join("out.mip1.png");
    write_gray_png(&input, 16, 16, |x, y| (x * 9 + y * 5) as u8);
    let before = std::fs::read(&input).unwrap();
    let out = dir.join("out.png");
    fails_cleanly(
        &dir,
        &["normalmap", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--mips"],
        &input,
        "overwrite the input",
    );
    assert_eq!(std::fs::read(&input).unwrap(), before, "the input is unchanged");
}

#[test]
fn a_pass_image_that_is_an_input_is_refused_before_anything_is_written() {
    let dir = scratch("out_pass_input");
    let input = dir.join("t.diffuse.png");
    write_gray_png(&input, 32, 32, |x, y| ((x ^ y) * 8) as u8);
    let before = std::fs::read(&input).unwrap();
    let out = dir.join("t.png");
    let args =
        ["render", "--passes", "--size", "32", "-o", out.to_str().unwrap(), "--height-field", input.to_str().unwrap()];
    fails_cleanly(&dir, &args, &input, "overwrite the input");
    assert_eq!(std::fs::read(&input).unwrap(), before);
    // The spotlight's pattern as the output, too.
    let pattern = dir.join("tex.png");
    write_gray_png(&pattern, 8, 8, |x, _| x as u8 * 30);
    let args = [
        "render",
        "--technique",
        "single-pass",
        "--size",
        "16",
        "--spot",
        "0,0,-1",
        "--spot-pattern",
        pattern.to_str().unwrap(),
        "-o",
        pattern.to_str().unwrap(),
    ];
    fails_cleanly(&dir, &args, &pattern, "overwrite the input");
}

#[test]
fn a_gltf_whose_buffer_is_the_outputs_bin_is_refused() {
    let dir = scratch("out_gltf_bin");
    let cube = concat!(env!("CARGO_MANIFEST_DIR"), "/../bumpmap-io/tests/data/mikktspace/cube.obj");
    let first = dir.join("in.gltf");
    let o = bumpmap(&["tangents", cube, "-o", first.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    // in.gltf's buffer is in.bin; writing out.gltf next to a copy whose buffer is out.bin
    // would replace the buffer being read.
    let json = std::fs::read_to_string(&first).unwrap().replace("\"in.bin\"", "\"out.bin\"");
    let input = dir.join("src.gltf");
    std::fs::write(&input, json).unwrap();
    std::fs::copy(dir.join("in.bin"), dir.join("out.bin")).unwrap();
    let bin_before = std::fs::read(dir.join("out.bin")).unwrap();
    let out = dir.join("out.gltf");
    fails_cleanly(
        &dir,
        &["tangents", input.to_str().unwrap(), "-o", out.to_str().unwrap()],
        &dir.join("out.bin"),
        "overwrite the input",
    );
    assert_eq!(std::fs::read(dir.join("out.bin")).unwrap(), bin_before, "the buffer being read is unchanged");
}

#[test]
fn folder_inputs_whose_outputs_collide_are_refused_up_front() {
    let root = scratch("out_collide");
    let input = root.join("in");
    std::fs::create_dir_all(&input).unwrap();
    write_gray_png(&input.join("a.png"), 8, 8, |x, _| x as u8 * 20);
    image::GrayImage::from_fn(8, 8, |x, y| image::Luma([(x + y) as u8 * 10])).save(input.join("a.tga")).unwrap();
    let out = root.join("out");
    let o = bumpmap(&["normalmap", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("a.png") && stderr(&o).contains("a.tga"), "names both inputs: {}", stderr(&o));
    assert!(!out.exists(), "nothing written, not even the folder");
    // With --mips, b.mip1.png's output would be a level of b.png's chain.
    std::fs::remove_file(input.join("a.tga")).unwrap();
    write_gray_png(&input.join("a.mip1.png"), 4, 4, |x, _| x as u8 * 50);
    let o = bumpmap(&["normalmap", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--mips"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("mip level"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn a_folder_of_only_bad_files_leaves_no_output_folder() {
    let root = scratch("out_all_bad");
    let input = root.join("in");
    std::fs::create_dir_all(&input).unwrap();
    std::fs::write(input.join("x.png"), b"not a png").unwrap();
    std::fs::write(input.join("y.png"), png_header_only(4, 4)).unwrap();
    let out = root.join("out");
    let o = bumpmap(&["normalmap", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("2 of 2 files failed"), "{}", stderr(&o));
    assert!(!out.exists(), "no empty output folder");
}

#[test]
fn a_render_whose_output_is_the_meshs_buffer_file_is_refused() {
    let dir = scratch("out_render_bin");
    let cube = concat!(env!("CARGO_MANIFEST_DIR"), "/../bumpmap-io/tests/data/mikktspace/cube.obj");
    let mesh = dir.join("m.gltf");
    let o = bumpmap(&["tangents", cube, "-o", mesh.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A buffer file named like the render's output.
    let json = std::fs::read_to_string(&mesh).unwrap().replace("\"m.bin\"", "\"frame.png\"");
    std::fs::write(&mesh, json).unwrap();
    std::fs::rename(dir.join("m.bin"), dir.join("frame.png")).unwrap();
    let before = std::fs::read(dir.join("frame.png")).unwrap();
    let scene = format!("mesh:{}", mesh.display());
    let out = dir.join("frame.png");
    let o = bumpmap(&["render", "--scene", &scene, "--size", "16", "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("overwrite the input"), "{}", stderr(&o));
    assert_eq!(std::fs::read(dir.join("frame.png")).unwrap(), before, "the buffer file is unchanged");
}

#[test]
fn missing_output_folders_are_made_by_every_command() {
    let dir = scratch("out_folders");
    let cube = concat!(env!("CARGO_MANIFEST_DIR"), "/../bumpmap-io/tests/data/mikktspace/cube.obj");
    let runs: [(&str, Vec<String>); 4] = [
        ("a/n.png", vec!["normalmap".into(), "bricks@16".into()]),
        ("b/r.png", vec!["render".into(), "--size".into(), "16".into()]),
        ("c/faces", vec!["cubemap".into(), "--size".into(), "2".into()]),
        ("d/t.gltf", vec!["tangents".into(), cube.into()]),
    ];
    for (out, args) in runs {
        let out = dir.join(out);
        let mut all: Vec<&str> = args.iter().map(String::as_str).collect();
        all.extend(["-o", out.to_str().unwrap()]);
        let o = bumpmap(&all);
        assert!(o.status.success(), "{all:?}: {}", stderr(&o));
        assert!(out.exists(), "{all:?} wrote {}", out.display());
    }
}

#[test]
fn normalmap_into_an_existing_folder_writes_the_inputs_name_there() {
    let dir = scratch("out_into_folder");
    let input = dir.join("rocks.png");
    write_gray_png(&input, 16, 16, |x, y| (x * 7 + y * 3) as u8);
    let folder = dir.join("maps");
    std::fs::create_dir_all(&folder).unwrap();
    let o = bumpmap(&["normalmap", input.to_str().unwrap(), "-o", folder.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(folder.join("rocks.png").exists());
    assert!(stderr(&o).contains("wrote"), "{}", stderr(&o));
    // A preset's file is named after the preset.
    let o = bumpmap(&["normalmap", "bricks@16", "-o", &format!("{}/", folder.display())]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(folder.join("bricks.png").exists());
}

#[test]
fn value_errors_on_the_command_line_exit_2_everywhere_and_an_empty_path_is_named() {
    let dir = scratch("out_exit_codes");
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    for args in [
        vec!["render", "--size", "0", "-o", out],
        vec!["cubemap", "--size", "0", "-o", out],
        vec!["render", "--width", "20000", "--height", "5", "-o", out],
        vec!["render", "--technique", "single-pass", "--spot-pattern", "pinwheel", "-o", out],
        vec!["render", "--spot-cutoff", "10", "-o", out],
        vec!["cubemap", "--accuracy", "--size", "3"],
        // Ranges checked after parsing are usage errors too.
        vec!["render", "--fov", "-5", "-o", out],
        vec!["render", "--technique", "single-pass", "--shininess", "-3", "-o", out],
        vec!["render", "--ambient", "-5", "-o", out],
        vec!["tangents", "no-such.obj", "--split-angle", "200", "-o", "t.glb"],
    ] {
        let o = bumpmap(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    }
    assert!(listing(&dir).is_empty(), "nothing written: {:?}", listing(&dir));
    let o = bumpmap(&["normalmap", "", "-o", out]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("(an empty path)"), "{}", stderr(&o));
}

#[test]
fn tangents_follow_a_buffer_outside_the_folder_only_when_allowed() {
    let dir = scratch("out_outside");
    let cube = concat!(env!("CARGO_MANIFEST_DIR"), "/../bumpmap-io/tests/data/mikktspace/cube.obj");
    let first = dir.join("c.gltf");
    assert!(bumpmap(&["tangents", cube, "-o", first.to_str().unwrap()]).status.success());
    let sub = dir.join("sub");
    std::fs::create_dir_all(&sub).unwrap();
    let json = std::fs::read_to_string(&first).unwrap().replace("\"c.bin\"", "\"../c.bin\"");
    let input = sub.join("up.gltf");
    std::fs::write(&input, json).unwrap();
    let out = dir.join("t.glb");
    let o = bumpmap(&["tangents", input.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("outside the glTF's folder"), "{}", stderr(&o));
    assert!(!out.exists());
    let o = bumpmap(&["tangents", input.to_str().unwrap(), "-o", out.to_str().unwrap(), "--allow-outside-paths"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.exists());
}
