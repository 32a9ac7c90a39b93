//! Hostile input, round two (issue #23): each class of fault found by probing the command line
//! as an adversarial user would, with the inputs made here (small files, not stored ones).

mod common;

use common::{bumpmap, limited, listing, scratch, stderr};

/// `ARGS… -o OUT` (`bench` writes no file) in a fresh folder: the exit status, and that
/// nothing was written.
fn status(name: &str, args: &[&str]) -> (Option<i32>, String) {
    let dir = scratch(name);
    let out = dir.join("out.png");
    let mut all: Vec<&str> = args.to_vec();
    if args[0] != "bench" {
        all.extend(["-o", out.to_str().unwrap()]);
    }
    let o = bumpmap(&all);
    let err = stderr(&o);
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert!(listing(&dir).is_empty(), "{args:?}: nothing may be written: {:?}", listing(&dir));
    (o.status.code(), err)
}

#[test]
fn a_value_out_of_range_exits_2_however_it_is_noticed() {
    // By the normal-map library, by the preset parser, by the renderer's framebuffer check, by
    // the command: one rule.
    for (i, (args, expect)) in [
        (&["normalmap", "bricks@64", "--scale", "1e30"][..], "scale must be a number in [-1e6, 1e6]"),
        (&["normalmap", "bricks@64", "--scale", "NaN"], "got NaN"),
        (&["normalmap", "bricks@64", "--scale", "inf"], "got inf"),
        (&["normalmap", "bricks@16385"], "size 16385 is outside 1..=16384"),
        (&["render", "--size", "16384"], "framebuffer 16384x16384 refused"),
        (&["render", "--size", "32", "--bump-scale", "1e30"], "--bump-scale"),
        (&["render", "--size", "32", "--scene", "blah"], "unknown scene 'blah'"),
        (&["render", "--size", "32", "--height-field", "bricks@16385"], "size 16385 is outside"),
        (&["render", "--size", "32", "--tessellation", "4096,64"], "'4096' is not a count in 1..=2048"),
        (&["compare", "--size", "16", "--techniques", "kilgard,kilgard"], "--techniques names kilgard twice"),
        (&["render", "--size", "16", "--specular", "1e40"], "'1e40' is beyond single precision"),
        (&["bench", "reference", "--size", "16384", "--runs", "1"], "framebuffer 16384x16384 refused"),
    ]
    .into_iter()
    .enumerate()
    {
        let (code, err) = status(&format!("exit_two_{i}"), args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains(expect), "{args:?}: message must say '{expect}': {err}");
    }
}

/// Every file under `dir`, recursively, as paths relative to it.
fn everything(dir: &std::path::Path) -> Vec<String> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        let name = p.strip_prefix(dir).unwrap().display().to_string();
        if p.is_dir() {
            out.extend(everything(&p).into_iter().map(|n| format!("{name}/{n}")));
            out.push(format!("{name}/"));
        } else {
            out.push(name);
        }
    }
    out
}

#[test]
fn a_signal_during_a_write_leaves_nothing_behind() {
    // A 4096² chain of PNGs into folders the set creates: level 0 alone takes a while to
    // encode, so the signal arrives while temporary files exist.
    for signal in ["INT", "TERM"] {
        let dir = scratch(&format!("signal_{signal}"));
        let out = dir.join("new/deeper/n.png");
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_bumpmap"))
            .args(["normalmap", "noise:5@4096", "--mips", "-o", out.to_str().unwrap()])
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let start = std::time::Instant::now();
        while !everything(&dir).iter().any(|n| n.ends_with(".tmp")) {
            assert!(start.elapsed().as_secs() < 60, "no temporary file appeared");
            if child.try_wait().unwrap().is_some() {
                panic!("the command finished before it could be interrupted");
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        let kill = std::process::Command::new("kill").args([&format!("-{signal}"), &child.id().to_string()]).status();
        assert!(kill.unwrap().success());
        let o = child.wait_with_output().unwrap();
        assert_eq!(o.status.code(), Some(130), "SIG{signal}: {}", stderr(&o));
        assert!(stderr(&o).contains("interrupted"), "{}", stderr(&o));
        assert!(everything(&dir).is_empty(), "SIG{signal}: left {:?}", everything(&dir));
    }
}

#[test]
fn a_normal_map_too_big_for_the_memory_is_an_error_with_its_size_and_writes_nothing() {
    // 8192² heights fit in 600 MiB (256 MiB of floats); the 16-bit chain and what making it
    // takes (18 bytes a texel, 1.1 GiB) do not: refused before any of it is made.
    let dir = scratch("out_of_memory");
    let out = dir.join("big.png");
    let o = limited(600, &["normalmap", "bricks@8192", "--bits", "16", "--mips", "-o", out.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("bricks@8192: not enough memory: making these maps needs 1.1 GiB"), "{err}");
    assert!(!err.contains("panicked") && !err.contains("memory allocation of"), "{err}");
    assert!(listing(&dir).is_empty(), "nothing may be written: {:?}", listing(&dir));
}

#[test]
fn a_render_too_big_for_the_memory_is_an_error_naming_the_sizes_and_writes_nothing() {
    // An 8192² field's normal map, its mips and the texture unit's copies pass 700 MiB;
    // whichever buffer fails first, the message names the scene's sizes, never an abort.
    let dir = scratch("render_out_of_memory");
    let out = dir.join("big.png");
    let o = limited(700, &["render", "--height-field", "bricks@8192", "--size", "64", "-o", out.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("this scene (bumps 8192x8192 from bricks@8192) is too big for the memory"), "{err}");
    assert!(err.contains("not enough memory:") && err.contains("MiB"), "{err}");
    assert!(!err.contains("panicked") && !err.contains("memory allocation of"), "{err}");
    assert!(listing(&dir).is_empty(), "nothing may be written: {:?}", listing(&dir));
}

#[test]
fn an_image_too_big_to_decode_in_the_memory_is_refused_from_its_header() {
    // A 100-byte PNG declaring a legal 16384² greyscale image: the decoder's 256 MiB buffer (not
    // asked for fallibly) and the copies made from it would not fit in 600 MiB.
    let dir = scratch("decode_out_of_memory");
    let input = dir.join("claims.png");
    std::fs::write(&input, common::png_header_only(16384, 16384)).unwrap();
    let o = limited(600, &["normalmap", input.to_str().unwrap(), "-o", dir.join("n.png").to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("claims.png: not enough memory: decoding it needs 1.5 GiB"), "{err}");
    assert!(!err.contains("panicked") && !err.contains("memory allocation of"), "{err}");
    assert_eq!(listing(&dir), ["claims.png"]);
}

#[test]
fn inputs_that_are_not_regular_files_or_are_huge_are_refused_without_reading_them() {
    let dir = scratch("not_regular");
    // A FIFO with no writer: opening it would block for ever.
    let fifo = dir.join("heights.png");
    assert!(std::process::Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let o = limited(4096, &["normalmap", fifo.to_str().unwrap(), "-o", dir.join("n.png").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("not a regular file"), "{}", stderr(&o));
    // A 3 GB normal map (sparse; PNG's signature, then nothing) for `tangents --normal-map`:
    // refused by its size, not read into memory (which a 1 GiB address space would not hold).
    let big = dir.join("big.png");
    {
        use std::io::Write;
        let mut f = std::fs::File::create(&big).unwrap();
        f.write_all(b"\x89PNG\r\n\x1a\n").unwrap();
        f.set_len(3 << 30).unwrap();
    }
    let obj = dir.join("t.obj");
    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n").unwrap();
    let glb = dir.join("t.glb");
    let args = ["tangents", obj.to_str().unwrap(), "--normal-map", big.to_str().unwrap(), "-o", glb.to_str().unwrap()];
    let o = limited(1024, &args);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("3221225472 bytes"), "{}", stderr(&o));
    assert!(!glb.exists());
    std::fs::remove_file(&big).unwrap();
}

#[test]
fn a_demo_that_fails_leaves_nothing_and_keeps_the_last_one() {
    // No adapter (a backend this platform has not) with --gpu always: the demo fails at its GPU
    // step, after dozens of files were written into its staging folder.
    let dir = scratch("demo_fails");
    let out = dir.join("new/demo");
    let demo = |out: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_bumpmap"))
            .args(["demo", "-o", out.to_str().unwrap(), "--gpu", "always"])
            .env("WGPU_BACKEND", "metal")
            .output()
            .unwrap()
    };
    let o = demo(&out);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(everything(&dir).is_empty(), "left {:?}", everything(&dir));
    // An earlier demo's folder stays as it was.
    let earlier = dir.join("demo");
    std::fs::create_dir_all(&earlier).unwrap();
    std::fs::write(earlier.join("README.md"), "# bumpmap demo\n\nthe last one").unwrap();
    let o = demo(&earlier);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("adapter"), "it failed at its GPU step: {}", stderr(&o));
    assert_eq!(everything(&dir), ["demo/README.md", "demo/"]);
    assert_eq!(std::fs::read_to_string(earlier.join("README.md")).unwrap(), "# bumpmap demo\n\nthe last one");
}

#[test]
fn the_demo_never_replaces_a_folder_of_the_users() {
    // The demo replaces its folder whole: a folder that is not an earlier demo's is refused
    // before any work, and left as it was.
    let dir = scratch("demo_users_folder");
    std::fs::write(dir.join("thesis.tex"), "months of work").unwrap();
    let o = bumpmap(&["demo", "-o", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("holds 1 file(s) or folder(s) and is not an earlier demo's folder"), "{}", stderr(&o));
    assert_eq!(everything(&dir), ["thesis.tex"]);
    // An empty folder of the user's counts too.
    std::fs::remove_file(dir.join("thesis.tex")).unwrap();
    std::fs::create_dir(dir.join("keep")).unwrap();
    let o = bumpmap(&["demo", "-o", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(everything(&dir), ["keep/"]);
    let beside = listing(dir.parent().unwrap());
    assert!(!beside.iter().any(|n| n.starts_with(".demo_users_folder.")), "no staging folder: {beside:?}");
}

#[test]
fn two_runs_writing_one_chain_at_once_leave_one_run_s_chain() {
    // Different scales, the same output: whichever lands last, the chain is all of one run.
    let dir = scratch("concurrent");
    let one = |scale: &str, out: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_bumpmap"))
            .args(["normalmap", "bricks@256", "--mips", "--scale", scale, "-o", out.to_str().unwrap()])
            .spawn()
            .unwrap()
    };
    let levels = |stem: &str| -> Vec<Vec<u8>> {
        (0..9)
            .map(|k| {
                let name = if k == 0 { format!("{stem}.png") } else { format!("{stem}.mip{k}.png") };
                std::fs::read(dir.join(name)).unwrap()
            })
            .collect()
    };
    assert!(one("2", &dir.join("a.png")).wait().unwrap().success());
    assert!(one("8", &dir.join("b.png")).wait().unwrap().success());
    let (a, b) = (levels("a"), levels("b"));
    for round in 0..6 {
        let mut first = one("2", &dir.join("n.png"));
        let mut second = one("8", &dir.join("n.png"));
        assert!(first.wait().unwrap().success() && second.wait().unwrap().success());
        let n = levels("n");
        assert!(n == a || n == b, "round {round}: the chain mixes both runs' levels");
    }
    assert!(!everything(&dir).iter().any(|n| n.ends_with(".tmp")));
}

#[test]
fn a_black_frame_is_an_error_not_a_picture() {
    // Looking away, a torus of one quad (every triangle degenerate), one too large to see, an
    // eye so far away the torus covers no pixel centre: each once gave a black PNG and exit 0.
    for (i, args) in [
        &["render", "--size", "32", "--target", "0,0,100"][..],
        &["render", "--size", "32", "--tessellation", "1,1"],
        &["render", "--size", "32", "--torus-radii", "1e30,1"],
        &["render", "--size", "32", "--eye", "1e30,0,0"],
        &["render", "--size", "32", "--technique", "reference", "--spp", "1", "--target", "0,0,100"],
    ]
    .into_iter()
    .enumerate()
    {
        let (code, err) = status(&format!("black_{i}"), args);
        assert_eq!(code, Some(1), "{args:?}: {err}");
        assert!(err.contains("out.png: not written: the image is black"), "{args:?}: {err}");
    }
    // The same scene in view is drawn.
    let dir = scratch("black_control");
    let out = dir.join("out.png");
    let o = bumpmap(&["render", "--size", "32", "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn an_output_reached_through_a_missing_folder_still_cannot_replace_the_input() {
    let dir = scratch("same_via_missing");
    let input = dir.join("h.png");
    common::write_gray_png(&input, 8, 8, |x, y| (x * 30 + y) as u8);
    let before = std::fs::read(&input).unwrap();
    let sneaky = dir.join("missing/../h.png");
    let o = bumpmap(&["normalmap", input.to_str().unwrap(), "-o", sneaky.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("input"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&input).unwrap(), before, "the input is untouched");
    assert_eq!(listing(&dir), ["h.png"], "no folder made for it either");
    // A folder run whose output folder is its input folder, reached the same way.
    let o = bumpmap(&["normalmap", dir.to_str().unwrap(), "-o", dir.join("zz/..").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("output folder is the input folder"), "{}", stderr(&o));
    assert_eq!(listing(&dir), ["h.png"]);
    // And a new folder reached through one yet to be made is written without leaving that one.
    let out = scratch("same_via_missing_out");
    let o = bumpmap(&["normalmap", dir.to_str().unwrap(), "-o", out.join("zz/../maps").to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(listing(&out), ["maps"]);
}

#[test]
fn a_folder_run_reads_tga_and_every_netpbm_extension() {
    // A TGA has no magic bytes (its extension names it); .pbm/.pam/.pnm were skipped by the walk.
    let dir = scratch("formats_in");
    let img = image::GrayImage::from_fn(8, 8, |x, y| image::Luma([(x * 25 + y * 3) as u8]));
    for name in ["a.tga", "b.pam", "c.pnm", "d.pgm"] {
        let format = image::ImageFormat::from_path(name).unwrap();
        img.save_with_format(dir.join(name), format).unwrap();
    }
    let out = scratch("formats_out");
    let o = bumpmap(&["normalmap", dir.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(listing(&out), ["a.png", "b.png", "c.png", "d.png"], "{}", stderr(&o));
}

#[test]
fn a_level_beside_a_small_map_that_is_huge_is_refused_from_its_header() {
    // A 64² heights file and normal map, each with a 16384² `NAME.mip1.png` beside it: the
    // level is checked against its place in the chain (32²) from its header, before anything
    // decodes it into the gigabytes it would take (the heights once aborted there).
    let dir = scratch("huge_sibling");
    let small = |name: &str, color: image::ColorType| {
        let bytes = vec![0u8; 64 * 64 * color.bytes_per_pixel() as usize];
        image::save_buffer(dir.join(name), &bytes, 64, 64, color).unwrap();
    };
    small("h.png", image::ColorType::L8);
    small("n.png", image::ColorType::Rgb8);
    // The heights' own normal map, without a sibling: the heights are checked against its size.
    small("m.png", image::ColorType::Rgb8);
    let huge = vec![0u8; 16384 * 16384];
    image::save_buffer(dir.join("h.mip1.png"), &huge, 16384, 16384, image::ColorType::L8).unwrap();
    std::fs::copy(dir.join("h.mip1.png"), dir.join("n.mip1.png")).unwrap();
    let at = |name: &str| dir.join(name).to_str().unwrap().to_string();
    for (args, file) in [
        (
            vec![
                "render",
                "--scene",
                "wall",
                "--technique",
                "pom",
                "--normal-map",
                &at("m.png"),
                "--height-map",
                &at("h.png"),
                "-o",
                &at("out.png"),
            ],
            "h.mip1.png",
        ),
        (vec!["inspect", &at("n.png")], "n.mip1.png"),
    ] {
        let o = limited(600, &args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains(&format!("{file}: is 16384x16384, but as level 1 of a 64x64 map it must be 32x32")),
            "{err}"
        );
    }
    assert!(!dir.join("out.png").exists());
}
