//! Every technique of the catalogue through `bumpmap render --technique NAME`, on the CPU and on
//! the GPU backend (lavapipe in CI): an image with content, unlike the surface without bumps, and
//! the two backends close. The images stay in `target/test-output/catalogue/` to be looked at.
//! A name that cannot draw the scene exits 1 and says why.

mod common;

use bumpmap_testkit::{assert_has_content, output_dir, psnr};
use common::*;

/// Every name, as `render --help` lists them.
fn names() -> Vec<String> {
    let help = String::from_utf8_lossy(&bumpmap(&["render", "--help"]).stdout).into_owned();
    let listed: Vec<String> = help
        .lines()
        .skip_while(|l| !l.contains("--technique <TECHNIQUE>"))
        .skip(1)
        .take_while(|l| !l.contains("[default: kilgard]"))
        .filter_map(|l| l.trim().strip_prefix("- ")?.split(':').next().map(str::to_string))
        .collect();
    assert!(listed.len() >= 13, "render --help lists the catalogue: {listed:?}");
    listed
}

#[test]
fn every_technique_renders_on_both_backends() {
    let dir = output_dir().join("catalogue");
    for backend in ["cpu", "gpu"] {
        std::fs::create_dir_all(dir.join(backend)).unwrap();
    }
    let mut gpu = true;
    let names = names();
    for name in &names {
        for backend in ["cpu", "gpu"] {
            if backend == "gpu" && !gpu {
                continue;
            }
            let out = dir.join(backend).join(format!("{name}.png"));
            let args = [
                "render",
                "--technique",
                name,
                "--backend",
                backend,
                "--size",
                "96",
                "--spp",
                "4",
                "-o",
                out.to_str().unwrap(),
            ];
            let o = bumpmap(&args);
            if backend == "gpu" && !gpu_ran(&o) {
                gpu = false;
                continue;
            }
            assert!(o.status.success(), "{name} on the {backend}: {}", stderr(&o));
            // The references say "reference, N samples per pixel": they draw on the CPU whatever the backend.
            assert!(
                stderr(&o).contains(&format!("({name}, {backend}")) || name.starts_with("reference"),
                "{}",
                stderr(&o)
            );
            assert_has_content(&format!("{name} ({backend})"), &read_png(&out));
        }
    }
    // Every technique with bumps looks different from the surface without them, and the two
    // backends agree: 45 dB, below the 48–52 dB measured at 96² (lavapipe), for the GPU's float
    // texture filtering and its rasterization rules at the silhouette against the emulated
    // GeForce's; the reference is drawn on the CPU for both.
    let flat = read_png(&dir.join("cpu/no-bump.png"));
    for name in names.iter().filter(|n| *n != "no-bump") {
        let cpu = read_png(&dir.join(format!("cpu/{name}.png")));
        let db = psnr(&flat, &cpu);
        assert!(db < 35.0, "{name} looks like the surface without bumps ({db:.1} dB)");
        if gpu {
            let on_gpu = read_png(&dir.join(format!("gpu/{name}.png")));
            let db = psnr(&cpu, &on_gpu);
            println!("{name}: CPU vs GPU {db:.1} dB");
            assert!(db >= 45.0, "{name}: the GPU's image is {db:.1} dB from the CPU's");
        }
    }
}

#[test]
fn a_technique_that_cannot_draw_the_scene_exits_1_and_says_why() {
    let dir = scratch("catalogue_refused");
    let out = dir.join("o.png");
    let cube = concat!("mesh:", env!("CARGO_MANIFEST_DIR"), "/../bumpmap-io/tests/data/mikktspace/cube.obj");
    let normal = dir.join("n.png");
    ok(&["normalmap", "bricks@32", "-o", normal.to_str().unwrap()]);
    let cases: [(&[&str], &str); 4] = [
        (&["--technique", "peercy-dependent", "--scene", cube], "needs a built-in surface"),
        (&["--technique", "reference", "--scene", cube], "needs a built-in surface"),
        (&["--technique", "emboss", "--normal-map", normal.to_str().unwrap()], "needs a height field"),
        (&["--technique", "offset-map", "--normal-map", normal.to_str().unwrap()], "needs a height field"),
    ];
    for (args, expect) in cases {
        let mut all = vec!["render", "--size", "32", "-o", out.to_str().unwrap()];
        all.extend_from_slice(args);
        let o = bumpmap(&all);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(expect) && err.contains(args[1]), "{args:?}: names the technique and why: {err}");
        assert!(!out.exists(), "{args:?}: nothing written");
    }
}
