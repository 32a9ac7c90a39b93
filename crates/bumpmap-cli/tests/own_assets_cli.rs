//! A user's own assets through `bumpmap render`: a normal map file (PNG at 8 and 16 bits, KTX2
//! with its mips, BC5 in DDS; either green convention), a glTF with its own material, and meshes
//! drawn in their own units and axes. Bad assets fail with a message that names them, and
//! nothing is written.

mod common;

use std::path::{Path, PathBuf};

use bumpmap_testkit::{assert_has_content, psnr};
use common::*;

/// `render ARGS… --size 160 -o DIR/NAME.png` (single pass, CPU); returns the image and stderr.
fn render(dir: &Path, name: &str, args: &[&str]) -> (bumpmap_math::Rgba8Image, String) {
    let out = dir.join(format!("{name}.png"));
    let mut all = vec!["render", "--size", "160", "-o", out.to_str().unwrap()];
    all.extend_from_slice(args);
    let err = ok(&all);
    (read_png(&out), err)
}

#[test]
fn a_normal_map_file_renders_as_the_height_field_it_was_made_from() {
    let dir = scratch("own_normal_map");
    let path = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let heights = dir.join("heights.png");
    write_gray_png(&heights, 96, 96, |x, y| {
        let (dx, dy) = (x as f32 - 40.0, y as f32 - 52.0);
        // A bump and a checker of steps: slopes of every direction and flat runs (Y = 0).
        (200.0 * (-(dx * dx + dy * dy) / 300.0).exp()) as u8 + ((x / 8 + y / 8) % 2) as u8 * 30
    });
    let h = heights.to_str().unwrap();
    for technique in ["single-pass", "kilgard"] {
        let t = ["--technique", technique];
        let (from_heights, _) =
            render(&dir, &format!("{technique}_heights"), &[&["--height-field", h], &t[..]].concat());
        assert_has_content(technique, &from_heights);

        // What `normalmap` writes (green up) reads back with the default convention. Not byte for
        // byte: the symmetric unorm encoding rounds a tie (127.5·y whole, y = 0 among them) up
        // both ways, so a mirrored green is one step off there, and the smaller levels are made
        // from level 0's bytes rather than from the float normals. 50 dB is under a fifth of a
        // step on average.
        ok(&["normalmap", h, "-o", &path("up.png")]);
        let (up, err) =
            render(&dir, &format!("{technique}_up"), &[&["--normal-map", &path("up.png")], &t[..]].concat());
        assert!(err.contains("green up"), "{err}");
        let db = psnr(&from_heights, &up);
        println!("{technique}: opengl PNG {db:.1} dB from the height field's render");
        assert!(db >= 50.0, "{technique}: opengl PNG {db:.1} dB from the height field's render");

        // Green down, read as green down: level 0 is the very bytes; read as green up (the wrong
        // convention), the slopes along t point the other way.
        ok(&["normalmap", h, "-o", &path("down.png"), "--y-convention", "directx"]);
        let down_args = ["--normal-map", &path("down.png"), "--y-convention", "directx"];
        let (down, _) = render(&dir, &format!("{technique}_down"), &[&down_args[..], &t[..]].concat());
        let db = psnr(&from_heights, &down);
        println!("{technique}: directx PNG {db:.1} dB");
        assert!(db >= 50.0, "{technique}: directx PNG {db:.1} dB");
        let (wrong, _) =
            render(&dir, &format!("{technique}_wrong"), &[&["--normal-map", &path("down.png")], &t[..]].concat());
        let db = psnr(&from_heights, &wrong);
        println!("{technique}: read with the wrong convention {db:.1} dB");
        assert!(db < 30.0, "{technique}: the wrong convention must show ({db:.1} dB)");

        // A KTX2 with the chain the heights make, green down: byte for byte the same image.
        ok(&["normalmap", h, "-o", &path("down.ktx2"), "--mips", "--y-convention", "directx"]);
        let ktx_args = ["--normal-map", &path("down.ktx2"), "--y-convention", "directx"];
        let (ktx, err) = render(&dir, &format!("{technique}_ktx2"), &[&ktx_args[..], &t[..]].concat());
        assert!(err.contains("its own 7 levels"), "{err}");
        assert_eq!(ktx, from_heights, "{technique}: KTX2 with its own mips");

        // 16 bits a channel, rounded to the renderers' 8.
        ok(&["normalmap", h, "-o", &path("up16.png"), "--bits", "16"]);
        let (wide, err) =
            render(&dir, &format!("{technique}_16"), &[&["--normal-map", &path("up16.png")], &t[..]].concat());
        assert!(err.contains("R16G16B16A16_UNORM"), "{err}");
        let db = psnr(&from_heights, &wide);
        println!("{technique}: 16-bit PNG {db:.1} dB");
        assert!(db >= 50.0, "{technique}: 16-bit PNG {db:.1} dB");

        // BC5 in DDS: X and Y in 4×4 blocks, Z rebuilt, and no length in alpha (so mips are
        // renormalized); 38 dB against the PNG's render (measured 47.5 dB, single pass).
        ok(&["normalmap", h, "-o", &path("bc5.dds"), "--mips", "--format", "bc5"]);
        let (bc5, err) =
            render(&dir, &format!("{technique}_bc5"), &[&["--normal-map", &path("bc5.dds")], &t[..]].concat());
        assert!(err.contains("BC5_UNORM"), "{err}");
        let db = psnr(&up, &bc5);
        println!("{technique}: BC5 DDS {db:.1} dB from the PNG's render");
        assert!(db >= 38.0, "{technique}: BC5 DDS {db:.1} dB from the PNG's render");
    }
}

#[test]
fn bad_normal_maps_fail_cleanly_and_a_photo_gets_a_warning() {
    let dir = scratch("own_normal_map_bad");
    let out = dir.join("o.png");
    let o = out.to_str().unwrap();
    let map = dir.join("m.dds");
    ok(&["normalmap", "bricks@64", "-o", map.to_str().unwrap(), "--mips"]);
    let bytes = std::fs::read(&map).unwrap();
    // Level data cut short of what the header declares.
    let short = dir.join("short.dds");
    std::fs::write(&short, &bytes[..bytes.len() - 100]).unwrap();
    fails_cleanly(
        &dir,
        &["render", "--normal-map", short.to_str().unwrap(), "-o", o],
        &short,
        "its header declares 7 level(s)",
    );
    // A normal map that is no image at all, and one that does not exist.
    let junk = dir.join("junk.png");
    std::fs::write(&junk, b"not an image at all").unwrap();
    fails_cleanly(&dir, &["render", "--normal-map", junk.to_str().unwrap(), "-o", o], &junk, "not a readable image");
    let missing = dir.join("missing.png");
    fails_cleanly(&dir, &["render", "--normal-map", missing.to_str().unwrap(), "-o", o], &missing, "cannot read");
    // Heights and a normal map at once: a usage error.
    let both = bumpmap(&["render", "--normal-map", map.to_str().unwrap(), "--height-field", "bricks", "-o", o]);
    assert_eq!(both.status.code(), Some(2), "{}", stderr(&both));
    assert!(stderr(&both).contains("--height-field") && stderr(&both).contains("--normal-map"), "{}", stderr(&both));
    assert!(!out.exists());
    // A colour photograph passed by mistake is drawn, with a warning that names the fraction.
    let photo = dir.join("photo.png");
    image::RgbImage::from_fn(64, 64, |x, y| image::Rgb([(x * 4) as u8, (y * 4) as u8, 90])).save(&photo).unwrap();
    let err = ok(&["render", "--normal-map", photo.to_str().unwrap(), "--size", "32", "-o", o]);
    assert!(err.contains("warning") && err.contains("% of its texels are not unit vectors"), "{err}");
}

/// A glTF 2.0 file with one mesh (a data: URI buffer): `positions` with `normals` and `uvs`,
/// `indices`; `node` is the scene's one node (JSON, `"mesh":0` added), `extra` more top-level
/// members (materials, textures, images) and `material` the primitive's.
fn gltf(
    path: &Path,
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    uvs: &[[f32; 2]],
    indices: &[u32],
    node: &str,
    extra: &str,
    material: Option<usize>,
) {
    let mut bin = Vec::new();
    let floats = |v: &[f32], bin: &mut Vec<u8>| bin.extend(v.iter().flat_map(|x| x.to_le_bytes()));
    floats(positions.as_flattened(), &mut bin);
    floats(normals.as_flattened(), &mut bin);
    floats(uvs.as_flattened(), &mut bin);
    bin.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    let n = positions.len();
    let (lo, hi) = positions.iter().fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
        (std::array::from_fn(|i| lo[i].min(p[i])), std::array::from_fn(|i| hi[i].max(p[i])))
    });
    let material = material.map_or(String::new(), |m| format!(r#","material":{m}"#));
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0{node}}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}},"indices":3{material}}}]}}],
"buffers":[{{"byteLength":{len},"uri":"data:application/octet-stream;base64,{data}"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{p}}},{{"buffer":0,"byteOffset":{p},"byteLength":{p}}},{{"buffer":0,"byteOffset":{p2},"byteLength":{t}}},{{"buffer":0,"byteOffset":{i0},"byteLength":{il}}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":{n},"type":"VEC3","min":{lo:?},"max":{hi:?}}},{{"bufferView":1,"componentType":5126,"count":{n},"type":"VEC3"}},{{"bufferView":2,"componentType":5126,"count":{n},"type":"VEC2"}},{{"bufferView":3,"componentType":5125,"count":{ni},"type":"SCALAR"}}]{extra}}}"#,
        len = bin.len(),
        data = base64::encode(&bin),
        p = 12 * n,
        p2 = 24 * n,
        t = 8 * n,
        i0 = 32 * n,
        il = 4 * indices.len(),
        ni = indices.len(),
    );
    std::fs::write(path, json).unwrap();
}

/// A triangle standing on the x axis with its apex up (+Y), facing +Z (glTF's front).
fn triangle(path: &Path, node: &str) {
    gltf(
        path,
        &[[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.0]],
        &[[0.0, 0.0, 1.0]; 3],
        &[[0.0, 1.0], [1.0, 1.0], [0.5, 0.0]],
        &[0, 1, 2],
        node,
        "",
        None,
    );
}

/// A 2×2 square lying in the x–z plane, facing up (+Y).
fn floor(path: &Path, extra: &str, material: Option<usize>) {
    let p = [[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 0.0, -1.0], [-1.0, 0.0, -1.0]];
    let uv = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    gltf(path, &p, &[[0.0, 1.0, 0.0]; 4], &uv, &[0, 1, 2, 0, 2, 3], "", extra, material);
}

/// Lit pixels (any channel above 24): how many, their centroid, and the widths of the top and
/// bottom lit rows.
fn coverage(image: &bumpmap_math::Rgba8Image) -> (usize, (f64, f64), (usize, usize)) {
    let lit = |x: usize, y: usize| image.texel(x, y)[..3].iter().any(|&c| c > 24);
    let mut count = 0;
    let (mut sx, mut sy) = (0.0, 0.0);
    let mut rows = Vec::new();
    for y in 0..image.height {
        let n = (0..image.width).filter(|&x| lit(x, y)).count();
        for x in (0..image.width).filter(|&x| lit(x, y)) {
            sx += x as f64;
            sy += y as f64;
        }
        count += n;
        if n > 0 {
            rows.push(n);
        }
    }
    let c = count.max(1) as f64;
    (count, (sx / c, sy / c), (*rows.first().unwrap_or(&0), *rows.last().unwrap_or(&0)))
}

#[test]
fn a_mesh_is_drawn_in_its_own_units_and_axes() {
    let dir = scratch("mesh_frame");
    let file = |name: &str| dir.join(name);
    let scene = |p: &PathBuf| format!("mesh:{}", p.display());
    // A Y-up glTF seen from the front by the default camera is upright: apex at the top.
    triangle(&file("tri.gltf"), "");
    let (image, err) = render(&dir, "upright", &["--scene", &scene(&file("tri.gltf")), "--technique", "single-pass"]);
    assert!(err.contains("tangents: generated"), "{err}");
    let (count, _, (top, bottom)) = coverage(&image);
    assert!(count > 2000, "the default camera frames the mesh ({count} lit pixels)");
    assert!(top * 4 < bottom, "apex up: the top lit row ({top} px) is much narrower than the bottom ({bottom} px)");

    // The same triangle in millimetres: the default camera, light and clip planes follow its
    // bounds, so it draws as in metres.
    triangle(&file("mm.gltf"), r#","scale":[1000,1000,1000]"#);
    let (mm, _) = render(&dir, "mm", &["--scene", &scene(&file("mm.gltf")), "--technique", "single-pass"]);
    let db = psnr(&image, &mm);
    assert!(db > 40.0, "in millimetres the image is {db:.1} dB from the one in metres");

    // Moved by +3 in x, or scaled by 2, from the same eye: elsewhere, or larger.
    triangle(&file("moved.gltf"), r#","translation":[3,0,0]"#);
    triangle(&file("scaled.gltf"), r#","scale":[2,2,2]"#);
    let eye = ["--eye", "1.5,1,14", "--target", "1.5,1,0", "--technique", "single-pass"];
    let at =
        |name: &str| render(&dir, name, &[&["--scene", &scene(&file(&format!("{name}.gltf")))], &eye[..]].concat()).0;
    let (base, moved, scaled) = (coverage(&at("tri")), coverage(&at("moved")), coverage(&at("scaled")));
    let shift = moved.1.0 - base.1.0;
    assert!(shift > 20.0, "+3 in x moves the image right: centroid {:.1} → {:.1}", base.1.0, moved.1.0);
    let grown = scaled.0 as f64 / base.0 as f64;
    assert!((3.0..5.0).contains(&grown), "scaled by 2, four times the area: {} → {} pixels", base.0, scaled.0);

    // Straight above a +Y-up floor (the view along up): another up is taken and the floor drawn.
    floor(&file("floor.gltf"), "", None);
    let (above, _) =
        render(&dir, "above", &["--scene", &scene(&file("floor.gltf")), "--eye", "0,6,0", "--target", "0,0,0"]);
    assert_has_content("a floor seen from straight above", &above);
    let (torus, _) = render(&dir, "torus_above", &["--eye", "0,0,10", "--target", "0,0,0"]);
    assert_has_content("the torus seen along its up axis", &torus);
}

#[test]
fn a_glb_renders_with_its_own_material() {
    let dir = scratch("own_material");
    let path = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let obj =
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";
    std::fs::write(dir.join("quad.obj"), obj).unwrap();
    ok(&["normalmap", "dimples@64", "-o", &path("n.png")]);
    ok(&["tangents", &path("quad.obj"), "--normal-map", &path("n.png"), "-o", &path("m.glb")]);
    let scene = format!("mesh:{}", path("m.glb"));
    let (own, err) = render(&dir, "own", &["--scene", &scene, "--technique", "single-pass"]);
    assert!(err.contains("normalTexture") && err.contains("tangents: the file's TANGENT"), "says what it used: {err}");
    let (explicit, err) =
        render(&dir, "explicit", &["--scene", &scene, "--technique", "single-pass", "--normal-map", &path("n.png")]);
    assert!(err.contains("--normal-map replaces"), "{err}");
    assert_has_content("the GLB's own normal map", &own);
    assert_eq!(own, explicit, "the material's normal map is the same map as given explicitly");
    let (flat, _) = render(&dir, "flat", &["--scene", &scene, "--technique", "no-bump"]);
    assert!(psnr(&own, &flat) < 35.0, "the material's bumps show");

    // A base colour texture becomes the decal.
    let mut png = Vec::new();
    image::RgbImage::from_pixel(4, 4, image::Rgb([250, 40, 30]))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let red = format!(
        r#","materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}],"textures":[{{"source":0}}],"images":[{{"uri":"data:image/png;base64,{}"}}]"#,
        base64::encode(&png)
    );
    floor(&dir.join("red.gltf"), &red, Some(0));
    let (image, err) =
        render(&dir, "red", &["--scene", &format!("mesh:{}", path("red.gltf")), "--technique", "single-pass"]);
    assert!(err.contains("baseColorTexture 4x4") && err.contains("as the decal"), "{err}");
    let (r, g) = image.texels.iter().fold((0u64, 0u64), |(r, g), t| (r + t[0] as u64, g + t[1] as u64));
    assert!(r > 3 * g, "the floor takes the texture's red (R {r}, G {g})");
}

#[test]
fn bad_material_textures_fail_cleanly() {
    let dir = scratch("own_material_bad");
    std::fs::create_dir_all(dir.join("asset")).unwrap();
    std::fs::write(dir.join("outside.png"), b"\x89PNG").unwrap();
    std::fs::write(dir.join("asset/junk.png"), b"\x89PNG\r\n\x1a\n not really").unwrap();
    let out = dir.join("o.png");
    for (name, uri, expect) in [
        ("missing", "missing.png", "cannot read"),
        ("outside", "../outside.png", "outside the glTF's folder"),
        ("junk", "junk.png", "not a readable image"),
    ] {
        let extra = format!(
            r#","materials":[{{"normalTexture":{{"index":0}}}}],"textures":[{{"source":0}}],"images":[{{"uri":"{uri}"}}]"#
        );
        let file = dir.join(format!("asset/{name}.gltf"));
        floor(&file, &extra, Some(0));
        let scene = format!("mesh:{}", file.display());
        let err = stderr(&bumpmap(&["render", "--scene", &scene, "-o", out.to_str().unwrap()]));
        fails_cleanly(&dir, &["render", "--scene", &scene, "-o", out.to_str().unwrap()], &file, expect);
        assert!(err.contains("normalTexture (image 0)") || err.contains(uri), "names the texture: {err}");
    }
}

#[test]
fn renormalized_stored_mips_get_a_warning_naming_the_fix_and_rebuild_mips_applies_it() {
    let dir = scratch("own_renormalized_mips");
    let (renormalized, own) = (dir.join("renormalized.ktx2"), dir.join("own.ktx2"));
    for (path, mode) in [(&renormalized, "renormalize"), (&own, "length-in-alpha")] {
        let o = bumpmap(&["normalmap", "dimples", "-o", path.to_str().unwrap(), "--mips", "--mip-mode", mode]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    // Far enough that the smaller levels are what is seen.
    let far = ["--technique", "toksvig", "--eye", "0,-24,10"];
    let (with_renormalized, err) =
        render(&dir, "a", &[&["--normal-map", renormalized.to_str().unwrap()], &far[..]].concat());
    assert!(
        err.contains("renormalized.ktx2: its own mip levels were renormalized") && err.contains("--rebuild-mips"),
        "{err}"
    );
    let (with_own, err) = render(&dir, "b", &[&["--normal-map", own.to_str().unwrap()], &far[..]].concat());
    assert!(!err.contains("renormalized ("), "a map with the length in alpha gets no warning: {err}");
    let rebuilt_args = [&["--normal-map", renormalized.to_str().unwrap(), "--rebuild-mips"], &far[..]].concat();
    let (rebuilt, err) = render(&dir, "c", &rebuilt_args);
    assert!(err.contains("its own 9 levels set aside") && !err.contains("warning"), "{err}");
    // Rebuilt from level 0, the levels are the length-in-alpha ones again (within the steps
    // level 0's quantization makes), and far from the renormalized ones.
    let (near_own, far_own) = (psnr(&rebuilt, &with_own), psnr(&with_renormalized, &with_own));
    assert!(near_own > far_own + 3.0, "rebuilt {near_own:.1} dB from the own levels, renormalized {far_own:.1} dB");
}

#[test]
fn a_gltf_scene_that_cannot_be_drawn_as_written_fails_cleanly() {
    let dir = scratch("own_scene_bad");
    let out = dir.join("o.png");
    let o = out.to_str().unwrap();
    for (name, material, node, expect) in [
        ("cutoff", r#","materials":[{"alphaMode":"MASK","alphaCutoff":2}]"#, "", "alphaCutoff is 2"),
        ("node", "", r#","translation":[1e39,0,0]"#, "not finite"),
        (
            "transform",
            r#","materials":[{"normalTexture":{"index":0,"extensions":{"KHR_texture_transform":{"rotation":1e39}}}}],"textures":[{"source":0}],"images":[{"uri":"n.png"}]"#,
            "",
            "KHR_texture_transform",
        ),
    ] {
        let file = dir.join(format!("{name}.gltf"));
        let material_index = (!material.is_empty()).then_some(0);
        gltf(
            &file,
            &[[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.0]],
            &[[0.0, 0.0, 1.0]; 3],
            &[[0.0, 1.0], [1.0, 1.0], [0.5, 0.0]],
            &[0, 1, 2],
            node,
            material,
            material_index,
        );
        let scene = format!("mesh:{}", file.display());
        fails_cleanly(&dir, &["render", "--scene", &scene, "-o", o], &file, expect);
    }
}

#[test]
fn a_gltf_without_texture_coordinates_is_drawn_unbumped_with_a_note() {
    // No primitive has TEXCOORD_0: it was refused ("the mesh has no texture coordinates"),
    // though one such primitive among others is drawn unbumped; three.js draws it too.
    let dir = scratch("gltf_no_texcoords");
    let positions: [f32; 12] = [-1.0, -1.0, 0.0, 1.0, -1.0, 0.0, 1.0, 1.0, 0.0, -1.0, 1.0, 0.0];
    let mut bin: Vec<u8> = positions.iter().flat_map(|v| v.to_le_bytes()).collect();
    bin.extend([0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()));
    std::fs::write(dir.join("q.bin"), &bin).unwrap();
    std::fs::write(
        dir.join("q.gltf"),
        r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"q.bin","byteLength":60}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],
"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}],
"materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.8,0.3,0.2,1]}}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0}"#,
    )
    .unwrap();
    let out = dir.join("out.png");
    let scene = format!("mesh:{}", dir.join("q.gltf").display());
    let o = bumpmap(&["render", "--scene", &scene, "--size", "64", "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("no primitive has texture coordinates: every one is drawn unbumped"), "{}", stderr(&o));
    // Lit in its base colour: red over green.
    let image = image::open(&out).unwrap().to_rgb8();
    let centre = image.get_pixel(32, 32);
    assert!(centre[0] > 60 && centre[0] > centre[1] + 30, "{centre:?}");
}
