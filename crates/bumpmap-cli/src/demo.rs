//! `bumpmap demo`: the paper's figures and the toolkit's outputs on built-in defaults, written
//! into one folder, with an index of what each file shows.

use std::path::Path;

use bumpmap_io::image_file::{PngLayout, save_png};
use bumpmap_math::{Encoding, HeightPreset, MipMode, NormalMapOptions, NormalizationCubeMap};
use indicatif::{ProgressBar, ProgressStyle};

use crate::args::DemoArgs;
use crate::error::CliError;

/// Renders (name, description, `bumpmap render` arguments).
const RENDERS: &[(&str, &str, &[&str])] = &[
    (
        "fig11_torus.png",
        "Kilgard Figure 11: the bump-mapped brick torus, three passes on the emulated GeForce",
        &["--passes"],
    ),
    (
        "fig14_no_self_shadow.png",
        "Kilgard Figure 14, left: light from the far right, no self-shadowing term",
        &["--light", "6,0,0.5", "--no-self-shadow"],
    ),
    (
        "fig14_self_shadow.png",
        "Kilgard Figure 14, right: the same light with Eq. 12's self-shadowing",
        &["--light", "6,0,0.5"],
    ),
    (
        "fig8-4_wall_floor.png",
        "Cg Tutorial Figure 8-4: wall and floor lit consistently by one light",
        &["--scene", "wall-floor"],
    ),
    (
        "single_pass_torus.png",
        "The same torus in one float pass per light (Kilgard §6)",
        &["--technique", "single-pass"],
    ),
    (
        "single_pass_two_lights.png",
        "Two coloured lights, single pass",
        &["--technique", "single-pass", "--light", "4,-3,3@1,0.35,0.2", "--light", "-4,-3,3@0.2,0.45,1"],
    ),
    (
        "single_pass_gloss.png",
        "Gloss map: shiny bricks, dull mortar (Cg Tutorial §8.5.2)",
        &["--technique", "single-pass", "--gloss", "bricks", "--shininess", "40"],
    ),
    (
        "single_pass_spotlight.png",
        "A spotlight projecting a pinwheel pattern on the wall (Kilgard §5.6)",
        &[
            "--technique",
            "single-pass",
            "--scene",
            "wall",
            "--light",
            "0,0,4",
            "--spot",
            "0,0,-1",
            "--spot-cutoff",
            "30",
            "--spot-pattern",
            "pinwheel",
            "--specular",
            "0.3",
        ],
    ),
    (
        "single_pass_attenuation.png",
        "Attenuation 1/(0.2 + 0.5·d²) from a light just above the floor",
        &[
            "--technique",
            "single-pass",
            "--scene",
            "floor",
            "--attenuation",
            "0.2,0,0.5",
            "--light",
            "0,0.6,0",
            "--eye",
            "0,3,6",
        ],
    ),
    (
        "single_pass_object_space.png",
        "Object-space lighting with an object-space normal map baked for the torus (Peercy §2.1)",
        &["--technique", "single-pass", "--space", "object"],
    ),
    (
        "patch_pinwheel.png",
        "Peercy Figure 4's stretched bicubic patch with the pinwheel height field",
        &["--scene", "patch", "--height-field", "pinwheel"],
    ),
    (
        "sphere_dimples.png",
        "A golf ball: dimples on a sphere",
        &["--scene", "sphere", "--height-field", "dimples", "--bump-scale", "8"],
    ),
];

pub fn run(args: &DemoArgs) -> Result<(), CliError> {
    let out = &args.output;
    std::fs::create_dir_all(out).map_err(|e| CliError::Path { path: out.clone(), reason: e.to_string() })?;
    let presets = [
        ("bricks", HeightPreset::Bricks),
        ("pinwheel", HeightPreset::Pinwheel),
        ("dimples", HeightPreset::Dimples),
        ("noise", HeightPreset::Noise(1)),
    ];
    let bar = ProgressBar::new((presets.len() + 1 + RENDERS.len()) as u64)
        .with_style(ProgressStyle::with_template("{bar:40} {pos}/{len} {wide_msg}").expect("valid template"));
    let mut index = String::from("# bumpmap demo\n\n");
    for (name, preset) in presets {
        bar.set_message(format!("normal map: {name}"));
        let field = preset.render(256, 256);
        save_png(&out.join(format!("{name}_height.png")), 256, 256, PngLayout::Gray8, &field.to_u8())?;
        let chain = crate::normalmap::make(&field, &NormalMapOptions::default(), true, MipMode::LengthInAlpha, name)?;
        crate::normalmap::write(&out.join(format!("{name}_normal.png")), &chain)?;
        index += &format!(
            "- `{name}_height.png`, `{name}_normal.png` (+ `.mip1` … `.mip8`): the {name} preset and its normal map; alpha of the mips is the length of the averaged normal\n"
        );
        bar.inc(1);
    }
    bar.set_message("normalization cube map");
    crate::cubemap::write(&out.join("cubemap"), &NormalizationCubeMap::new(32, Encoding::Unorm))?;
    index += "- `cubemap/px.png` … `nz.png`: a 32² normalization cube map\n";
    bar.inc(1);
    for (file, what, extra) in RENDERS {
        bar.set_message(format!("render: {file}"));
        render(&out.join(file), extra)?;
        index += &format!("- `{file}`: {what}\n");
        bar.inc(1);
    }
    index += "- `fig11_torus.decal.png`, `.diffuse.png`, `.specular.png`: Kilgard Figure 12, the framebuffer after each pass\n";
    crate::normalmap::write_text(&out.join("README.md"), &index)?;
    bar.finish_and_clear();
    eprintln!("wrote the demo into {} (see its README.md)", out.display());
    Ok(())
}

/// Runs `bumpmap render ARGS -o path --size 512` in-process.
fn render(path: &Path, extra: &[&str]) -> Result<(), CliError> {
    use clap::Parser;
    let mut argv = vec!["bumpmap", "render", "--size", "512", "-o"];
    let p = path.to_string_lossy().into_owned();
    argv.push(&p);
    argv.extend_from_slice(extra);
    let cli = crate::args::Cli::try_parse_from(argv).map_err(|e| CliError::Render(e.to_string()))?;
    let crate::args::Command::Render(args) = cli.command else { unreachable!("parsed a render command") };
    let scene = crate::render::build_scene(&args)?;
    let mut fb = bumpmap_raster::Framebuffer::new(512, 512).map_err(|e| CliError::Render(e.to_string()))?;
    crate::render::render_to(&scene, &args, &mut fb, path)?;
    Ok(())
}
