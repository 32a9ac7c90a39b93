//! A Rust user's scene from `bumpmap::options` is the command line's: the same options set up
//! by the library and by `bumpmap render` draw the same bytes, and what the library refuses the
//! command line refuses with the flag named.

mod common;

use bumpmap::options::{GlossChoice, SceneChoice, SceneOptions};
use bumpmap::{BackendChoice, Prepared, Renderer, SceneKind, TechniqueName};
use common::*;

fn library_render(options: &SceneOptions, size: usize) -> Vec<u8> {
    let set_up = options.set_up().expect("the options set up");
    let prepared =
        Prepared::new(&set_up.spec, options.technique.technique, &set_up.options).expect("the technique prepares");
    let image = Renderer::new(BackendChoice::Cpu).unwrap().draw(&prepared, size, size).unwrap();
    image.texels.iter().flat_map(|t| [t[0], t[1], t[2]]).collect()
}

fn cli_render(words: &[&str], size: usize, out: &std::path::Path) -> Vec<u8> {
    let size = size.to_string();
    let mut args = vec!["render", "--size", &size, "-o", out.to_str().unwrap()];
    args.extend(words);
    let o = bumpmap(&args);
    assert!(o.status.success(), "{words:?}: {}", stderr(&o));
    image::open(out).unwrap().to_rgb8().into_raw()
}

#[test]
fn options_set_up_by_the_library_draw_what_the_command_line_draws() {
    let dir = scratch("library_options");
    let mut pom = SceneOptions { scene: SceneChoice::BuiltIn(SceneKind::Wall), ..Default::default() };
    pom.technique.technique = TechniqueName::Pom;
    pom.camera.eye = Some(glam::Vec3::new(0.0, -3.0, 1.2));
    pom.heights.layers = 24;
    let mut glossy = SceneOptions::default();
    glossy.technique.technique = TechniqueName::SinglePass;
    glossy.material.gloss = GlossChoice::Bricks;
    glossy.material.shininess = 24.0;
    let cases: [(&str, SceneOptions, &[&str]); 3] = [
        ("defaults", SceneOptions::default(), &[]),
        ("pom", pom, &["--scene", "wall", "--technique", "pom", "--eye", "0,-3,1.2", "--layers", "24"]),
        ("gloss", glossy, &["--technique", "single-pass", "--gloss", "bricks", "--shininess", "24"]),
    ];
    for (name, options, words) in cases {
        let ours = library_render(&options, 64);
        let theirs = cli_render(words, 64, &dir.join(format!("{name}.png")));
        // Exact: one CPU pipeline, the same scene and options, PNG is lossless (the file holds RGB).
        assert_eq!(ours, theirs, "{name}: the library's set-up draws other bytes than `bumpmap render {words:?}`");
        assert!(ours.chunks(3).any(|t| t[0] > 40), "{name}: the frame is lit");
    }
}

#[test]
fn what_the_library_refuses_the_command_line_names_by_flag() {
    let mut o = SceneOptions::default();
    o.material.ambient = 1.5;
    let e = o.set_up().err().expect("ambient 1.5 is refused");
    assert_eq!(e.to_string(), "ambient must be in [0, 1], got 1.5");
    let out = bumpmap(&["render", "--ambient", "1.5", "-o", "/nonexistent/never.png"]);
    assert_eq!(out.status.code(), Some(2), "a value out of range is a usage error");
    assert!(stderr(&out).contains("--ambient must be in [0, 1], got 1.5"), "{}", stderr(&out));

    let mut o = SceneOptions::default();
    o.technique.technique = TechniqueName::SinglePass;
    o.technique.specular_mode = bumpmap::SpecularMode::Ramp;
    let e = o.set_up().err().expect("kilgard's specular form is refused for the single pass");
    assert!(matches!(e, bumpmap::options::SetupError::KilgardOnly { .. }), "{e:?}");
}
