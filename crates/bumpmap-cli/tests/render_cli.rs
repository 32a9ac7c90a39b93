//! `bumpmap render` end to end: images that are not empty, and bad options failing cleanly.

mod common;

use common::*;

fn mean_and_colours(path: &std::path::Path) -> (f64, usize) {
    let img = image::open(path).unwrap().to_rgb8();
    let mean = img.as_raw().iter().map(|&v| v as f64).sum::<f64>() / img.as_raw().len() as f64;
    let colours = img.pixels().map(|p| p.0).collect::<std::collections::HashSet<_>>().len();
    (mean, colours)
}

#[test]
fn renders_every_scene_with_both_techniques() {
    let dir = scratch("render_scenes");
    let cube = concat!(env!("CARGO_MANIFEST_DIR"), "/../bumpmap-io/tests/data/mikktspace/doomcone_smooth.obj");
    let mesh = format!("mesh:{cube}");
    for scene in ["torus", "wall", "floor", "wall-floor", "patch", "sphere", mesh.as_str()] {
        for technique in ["kilgard", "single-pass"] {
            let out = dir.join(format!("{}_{technique}.png", scene.len()));
            let o = bumpmap(&[
                "render",
                "--scene",
                scene,
                "--technique",
                technique,
                "--size",
                "96",
                "-o",
                out.to_str().unwrap(),
            ]);
            assert!(o.status.success(), "{scene} {technique}: {}", stderr(&o));
            let (mean, colours) = mean_and_colours(&out);
            assert!(
                mean > 5.0 && colours > 50,
                "{scene} {technique}: image looks empty (mean {mean}, {colours} colours)"
            );
        }
    }
}

#[test]
fn passes_writes_one_image_per_pass() {
    let dir = scratch("render_passes");
    let out = dir.join("t.png");
    let o = bumpmap(&["render", "--passes", "--size", "64", "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(listing(&dir), ["t.decal.png", "t.diffuse.png", "t.png", "t.specular.png"]);
    let (decal, _) = mean_and_colours(&dir.join("t.decal.png"));
    let (diffuse, _) = mean_and_colours(&dir.join("t.diffuse.png"));
    let (full, _) = mean_and_colours(&out);
    assert!(diffuse < decal, "pass 2 modulates the decal by light ≤ 1");
    assert!(full > diffuse, "pass 3 adds the specular");
}

/// `render ARGS… -o out.png` must exit 1 with `expect` in the message, no panic, no file.
fn refused(args: &[&str], expect: &str) {
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = scratch(&format!("render_refused_{n}"));
    let out = dir.join("out.png");
    let mut all = vec!["render", "-o", out.to_str().unwrap()];
    if !args.contains(&"--size") {
        all.extend(["--size", "32"]);
    }
    all.extend_from_slice(args);
    let o = bumpmap(&all);
    let err = stderr(&o);
    assert_ne!(o.status.code(), Some(0), "{args:?} must fail");
    assert!(err.contains(expect), "{args:?}: message must say '{expect}': {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(listing(&dir).is_empty(), "{args:?}: no output file");
}

#[test]
fn bad_options_are_refused_with_clear_messages() {
    refused(&["--size", "100000"], "'100000' is not a size in 1..=16384 pixels");
    refused(&["--size", "16384"], "framebuffer 16384x16384 refused");
    refused(&["--technique", "single-pass", "--shininess", "0"], "shininess");
    refused(&["--technique", "single-pass", "--shininess", "NaN"], "shininess");
    refused(&["--shininess", "16"], "kilgard cannot do --shininess");
    refused(&["--light", "dir:0,0,0"], "non-zero direction");
    refused(&["--light", "1,2"], "X,Y,Z");
    refused(&["--technique", "single-pass", "--spot", "0,0,-1", "--spot-cutoff", "95"], "cutoff");
    refused(
        &[
            "--technique",
            "single-pass",
            "--gloss",
            concat!(env!("CARGO_MANIFEST_DIR"), "/../bumpmap-math/tests/golden/none.png"),
        ],
        "cannot read",
    );
    refused(&["--scene", "teapot"], "unknown scene");
    // Two options the library's table declares contradictory.
    refused(&["--no-self-shadow", "--self-shadow", "step"], "cannot be used with");
    refused(&["--scene", "mesh:/no/such/file.obj"], "cannot read");
    refused(&["--eye", "1,1,1", "--target", "1,1,1"], "is at the point looked at");
    refused(&["--scene", "wall", "--eye", "0,0,0"], "is at the point looked at");
    // The reference needs an exact surface and samples no projected pattern; embossing's
    // combiners scale by 1, 2 or 4 and take one light.
    let cube = concat!("mesh:", env!("CARGO_MANIFEST_DIR"), "/../bumpmap-io/tests/data/mikktspace/cube.obj");
    refused(&["--technique", "reference", "--scene", cube], "needs a built-in surface");
    refused(&["--technique", "object-space", "--scene", cube], "--technique object-space needs a built-in surface");
    refused(
        &["--technique", "peercy-dependent", "--scene", cube],
        "--technique peercy-dependent needs a built-in surface",
    );
    refused(&["--technique", "object-space", "--repeat", "0,1"], "non-zero");
    refused(&["--technique", "phong"], "possible values: kilgard, single-pass");
    refused(&["--technique", "reference", "--spot", "0,0,-1", "--spot-pattern", "bricks"], "--spot-pattern");
    refused(&["--technique", "reference", "--spp", "0"], "0 is not in 1..=4096");
    refused(&["--technique", "reference", "--passes"], "--passes");
    refused(&["--technique", "emboss", "--bump-scale", "3"], "--bump-scale 3");
    // LEAN's and CLEAN's moments are tangent-space slopes: object-space and offset maps have none.
    for technique in ["object-space", "offset-map", "peercy-blinn"] {
        for filter in ["lean", "clean"] {
            refused(
                &["--technique", technique, "--specular-filter", filter],
                "--specular-filter lean or clean (or --technique lean or clean) reads the slopes of a tangent-space map",
            );
        }
    }
    refused(
        &["--technique", "emboss", "--light", "1,1,1", "--light", "-1,1,1"],
        "--technique emboss needs exactly one light",
    );
}

#[test]
fn gloss_map_of_another_size_than_the_decal_is_an_error() {
    let dir = scratch("render_gloss_size");
    let gloss = dir.join("gloss.png");
    write_gray_png(&gloss, 100, 50, |x, _| x as u8);
    let out = dir.join("out.png");
    let o = bumpmap(&[
        "render",
        "--technique",
        "single-pass",
        "--gloss",
        gloss.to_str().unwrap(),
        "--size",
        "32",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("gloss map is 100x50 but the decal is 256x256"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn no_gpu_adapter_is_a_clear_error_that_says_how_to_get_one() {
    // WGPU_BACKEND names a backend this machine does not have (DX12 exists on Windows only).
    let dir = scratch("render_no_adapter");
    let out = dir.join("out.png");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_bumpmap"))
        .args(["render", "--backend", "gpu", "--size", "32", "-o", out.to_str().unwrap()])
        .env("WGPU_BACKEND", "dx12")
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("no GPU adapter") && err.contains("mesa-vulkan-drivers") && err.contains("--backend cpu"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    assert!(listing(&dir).is_empty(), "no output file");
}

#[test]
fn the_gpu_backend_renders_and_writes_its_passes() {
    // Needs an adapter: lavapipe in CI (where a missing one fails), skipped elsewhere.
    let dir = scratch("render_gpu");
    let out = dir.join("g.png");
    let o = bumpmap(&["render", "--backend", "gpu", "--passes", "--size", "64", "-o", out.to_str().unwrap()]);
    if !o.status.success() && stderr(&o).contains("no GPU adapter") && std::env::var_os("CI").is_none() {
        eprintln!("SKIPPED: {}", stderr(&o));
        return;
    }
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(listing(&dir), ["g.decal.png", "g.diffuse.png", "g.png", "g.specular.png"]);
    let (mean, colours) = mean_and_colours(&out);
    assert!(mean > 5.0 && colours > 50, "the GPU image looks empty (mean {mean}, {colours} colours)");
    assert!(stderr(&o).contains("gpu:"), "names the adapter: {}", stderr(&o));
}

#[test]
fn options_that_do_not_apply_are_refused() {
    refused(&["--technique", "single-pass", "--passes"], "--passes");
    refused(&["--specular", "0.5"], "kilgard cannot do --specular");
    refused(&["--technique", "single-pass", "--precision", "fixed9"], "--precision belongs to --technique kilgard");
    refused(&["--normalize", "math"], "kilgard cannot do --normalize");
    refused(&["--technique", "single-pass-cube", "--normalize", "math"], "single-pass-cube normalizes by the cube map");
}

#[test]
fn negative_numbers_get_a_range_error_not_an_unknown_argument() {
    refused(&["--fov", "-5"], "--fov must be in [1, 170]");
    refused(&["--technique", "single-pass", "--shininess", "-3"], "--shininess must be a positive number, got -3");
    refused(&["--ambient", "-5"], "--ambient must be in [0, 1], got -5");
    refused(&["--technique", "single-pass", "--spot", "0,0,-1", "--spot-cutoff", "-4"], "cutoff");
    refused(&["--torus-radii", "-1,0.5"], "--torus-radii must be positive");
}

#[test]
fn thread_counts_are_bounded() {
    for bad in ["0", "2000"] {
        let o = bumpmap(&["bench", "render", "--threads", bad, "--size", "16", "--frames", "1", "--runs", "1"]);
        assert_eq!(o.status.code(), Some(2), "--threads {bad}: {}", stderr(&o));
        assert!(stderr(&o).contains("1..=256"), "--threads {bad} names the range: {}", stderr(&o));
    }
}

#[test]
fn the_specular_filters_leave_near_detail_alone() {
    // Up close the wall's normal map is magnified: level 0, every length 1, and Toksvig's
    // exponent is the unfiltered one, byte for byte (the roughness map's within a step; LEAN's
    // within a stated bound). Farther away, where the smaller levels are read, the filter acts.
    let dir = scratch("render_toksvig_near");
    let draw = |technique: &str, eye: &str| {
        let out = dir.join(format!("{technique}-{eye}.png"));
        let o = bumpmap(&[
            "render",
            "--scene",
            "wall",
            "--technique",
            technique,
            "--eye",
            eye,
            "--shininess",
            "32",
            "--size",
            "128",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        image::open(&out).unwrap().to_rgb8()
    };
    let near = draw("single-pass", "0,0,1.2");
    assert_eq!(near, draw("toksvig", "0,0,1.2"), "magnified: the same bytes");
    // The roughness map holds shininess 32's roughness, 0.4925, as the byte 126 (0.4941):
    // exponent 31.55 and energy (31.55 + 2)/34 = 0.987, so the specular is up to 1.3 % (3.4
    // steps of a full highlight) dimmer: within 4 steps (measured: 2).
    let rough = draw("roughness-map", "0,0,1.2");
    let most = near.as_raw().iter().zip(rough.as_raw()).map(|(a, b)| a.abs_diff(*b)).max();
    assert!(most <= Some(4), "magnified, the roughness map: {most:?}");
    // LEAN's lobe is a Gaussian over slopes ((H·N)^s to first order), and magnified its filter
    // still blends the moments of neighbouring texels, which is spread where their slopes
    // differ (the bricks' bevels): the same picture, most channels within a few steps.
    // Measured: mean 2.9 steps, 93 % within 8. CLEAN, the same spread made round, likewise.
    for technique in ["lean", "clean"] {
        let filtered = draw(technique, "0,0,1.2");
        let diffs: Vec<u8> = near.as_raw().iter().zip(filtered.as_raw()).map(|(a, b)| a.abs_diff(*b)).collect();
        let mean = diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64;
        let within = diffs.iter().filter(|&&d| d <= 8).count() as f64 / diffs.len() as f64;
        eprintln!("magnified, {technique}: mean {mean:.2} steps, {within:.3} within 8");
        assert!(mean < 4.0 && within > 0.9, "magnified, {technique}: mean {mean:.2} steps, {within:.3} within 8");
    }
    let (plain, filtered) = (draw("single-pass", "0,0,4"), draw("toksvig", "0,0,4"));
    let differing = plain.pixels().zip(filtered.pixels()).filter(|(a, b)| a != b).count();
    assert!(differing > 500, "minified, the filter acts: {differing} pixels differ");
}

#[test]
fn an_exported_roughness_map_is_read_as_the_one_made_from_the_normal_map() {
    // `normalmap --roughness-out` writes the dimples' roughness in three layouts; `render
    // --roughness-map` reads each back into the same texture, and that texture draws nearly
    // the picture of the one the renderer makes from the normal map's own (8-bit) lengths.
    // Shininess 30 is roughness 0.5 exactly: (2/32)^¼.
    let dir = scratch("render_roughness_file");
    let path = |name: &str| dir.join(name).to_str().unwrap().to_owned();
    for (k, (out, layout)) in [("r.png", "gray"), ("orm.ktx2", "gltf"), ("s.dds", "unity")].into_iter().enumerate() {
        let normal = path(&format!("n{k}.png"));
        let roughness = path(out);
        ok(&[
            "normalmap",
            "dimples@256",
            "-o",
            &normal,
            "--mips",
            "--roughness-out",
            &roughness,
            "--roughness",
            "0.5",
            "--roughness-layout",
            layout,
        ]);
    }
    let normal = path("n0.png");
    // The dimpled sphere far enough away to read the small levels, specular alone.
    let run = |backend: &str, extra: &[&str]| {
        let out = dir.join(format!("{backend}{}.png", extra.join("_").replace(['/', '.'], "")));
        let mut args = vec!["render", "--backend", backend, "--normal-map", &normal, "--scene", "sphere"];
        args.extend(["--eye", "0,-9,2.5", "--shininess", "30", "--ambient", "0", "--diffuse", "0", "--size", "128"]);
        args.extend_from_slice(extra);
        args.extend(["-o", out.to_str().unwrap()]);
        (bumpmap(&args), out)
    };
    let draw = |backend: &str, extra: &[&str]| {
        let (o, out) = run(backend, extra);
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
        read_png(&out)
    };
    let (gray, gltf, unity) = (path("r.png"), path("orm.ktx2"), path("s.dds"));
    // (mean, largest) channel difference.
    let diff = |a: &bumpmap_math::Rgba8Image, b: &bumpmap_math::Rgba8Image| {
        let d: Vec<u8> =
            a.texels.iter().zip(&b.texels).flat_map(|(x, y)| (0..3).map(move |c| x[c].abs_diff(y[c]))).collect();
        (d.iter().map(|&v| v as f64).sum::<f64>() / d.len() as f64, d.iter().copied().max().unwrap_or(0))
    };
    let file = draw("cpu", &["--technique", "roughness-map", "--roughness-map", &gray]);
    let orm = draw("cpu", &["--technique", "roughness-map", "--roughness-map", &gltf, "--roughness-layout", "gltf"]);
    assert_eq!(diff(&file, &orm), (0.0, 0), "the gray PNG set and the glTF KTX2");
    let smoothness = ["--specular-filter", "roughness-map", "--roughness-map", &unity, "--roughness-layout", "unity"];
    let unity_frame = draw("cpu", &[&["--technique", "single-pass"][..], &smoothness[..]].concat());
    // Unity's smoothness is 1 − roughness rounded on its own: a texel can come back a byte off.
    let (mean, most) = diff(&file, &unity_frame);
    assert!(mean < 0.01 && most <= 1, "the gray PNG set and Unity's smoothness in DDS: {mean}, {most}");
    let made = draw("cpu", &["--technique", "roughness-map"]);
    let plain = draw("cpu", &["--technique", "single-pass"]);
    let lit = file.texels.iter().filter(|t| t[0] > 0).count();
    assert!(lit > 500, "the highlight is drawn: {lit} pixels");
    let (file_vs_made, file_vs_plain) = (diff(&file, &made), diff(&file, &plain));
    eprintln!("file vs made: {file_vs_made:?}; file vs unfiltered: {file_vs_plain:?}");
    // The file's lengths come from a 16-bit chain, the made one's from the 8-bit normal map.
    assert!(file_vs_made.0 < 0.5 && file_vs_made.1 <= 8, "file vs made: {file_vs_made:?}");
    assert!(file_vs_plain.0 > 4.0 * file_vs_made.0, "the filter acts: {file_vs_plain:?} vs {file_vs_made:?}");

    // The GPU backend samples the same file through its own texture unit.
    let (o, gpu_out) = run("gpu", &["--technique", "roughness-map", "--roughness-map", &gray]);
    if gpu_ran(&o) {
        let gpu = diff(&file, &read_png(&gpu_out));
        eprintln!("gpu vs cpu: {gpu:?}");
        // Lavapipe picks the level per pixel, the CPU per quad: at the dimples' edges a few
        // pixels differ by tens of steps, as much for the unfiltered single pass (measured here:
        // mean 0.084, max 34; roughness map 0.063, 20). A texture unit left white (roughness 1)
        // would move the mean by far more.
        assert!(gpu.0 < 0.1 && gpu.1 <= 40, "GPU vs CPU: {gpu:?}");
    }

    // A lone image (no .mipK files beside it): its levels box-filtered, with a warning; the
    // gloss layout read as 1 − roughness. Level 0 agrees, so the picture changes only where the
    // small levels are read.
    let lone = path("lone.png");
    ok(&[
        "normalmap",
        "dimples@256",
        "-o",
        &path("l.png"),
        "--mips",
        "--roughness-out",
        &path("g.png"),
        "--roughness",
        "0.5",
        "--roughness-layout",
        "gloss",
    ]);
    std::fs::copy(dir.join("g.png"), &lone).unwrap();
    let (o, out) =
        run("cpu", &["--technique", "roughness-map", "--roughness-map", &lone, "--roughness-layout", "gloss"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("lone.png: one level") && stderr(&o).contains("--roughness-out"), "{}", stderr(&o));
    let boxed = diff(&file, &read_png(&out));
    eprintln!("file vs its level 0 box-filtered: {boxed:?}");
    assert!(boxed.0 > file_vs_made.0, "box-filtered levels lose the spread: {boxed:?}");
    let gloss = draw(
        "cpu",
        &["--technique", "roughness-map", "--roughness-map", &path("g.png"), "--roughness-layout", "gloss"],
    );
    let (mean, most) = diff(&file, &gloss);
    assert!(mean < 0.01 && most <= 1, "the gray PNG set and the gloss PNG set: {mean}, {most}");

    // Refusals: without the filter that reads it; another size than the normal map's; a mip
    // file of the wrong size; a layout without a map.
    let o = bumpmap(&["render", "--technique", "single-pass", "--roughness-map", &gray, "-o", &path("x.png")]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--technique roughness-map"), "{}", stderr(&o));
    let small = path("small.png");
    ok(&["normalmap", "bricks@64", "-o", &path("b.png"), "--mips", "--roughness-out", &small]);
    let (o, out) = run("cpu", &["--technique", "roughness-map", "--roughness-map", &small]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("the roughness map is 64x64 but the normal map is 256x256"), "{}", stderr(&o));
    assert!(!out.exists());
    std::fs::copy(dir.join("small.mip2.png"), dir.join("r.mip1.png")).unwrap();
    let (o, _) = run("cpu", &["--technique", "roughness-map", "--roughness-map", &gray]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("r.mip1.png") && stderr(&o).contains("is 16x16, but level 1"), "{}", stderr(&o));
    // A file that is not there, and one that is not an image.
    std::fs::write(dir.join("junk.png"), b"not a PNG at all").unwrap();
    for (name, expect) in [("missing.png", "missing.png"), ("junk.png", "junk.png")] {
        let (o, out) = run("cpu", &["--technique", "roughness-map", "--roughness-map", &path(name)]);
        assert_eq!(o.status.code(), Some(1), "{name}: {}", stderr(&o));
        assert!(stderr(&o).contains(expect) && !stderr(&o).contains("panicked"), "{name}: {}", stderr(&o));
        assert!(!out.exists());
    }
    let o = bumpmap(&["render", "--roughness-layout", "gltf", "-o", &path("x.png")]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!dir.join("x.png").exists());
}
