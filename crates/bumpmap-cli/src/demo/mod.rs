//! `bumpmap demo`: the paper's figures and the toolkit's outputs on built-in defaults, written
//! into one folder, with an index of what each file shows.

use std::path::Path;
use std::sync::Arc;

use bumpmap::frame::draw_passes;
use bumpmap::{BackendChoice, BumpSource, ParallaxOptions, ParallaxShadow, Renderer, TechniqueName, TechniqueOptions};
use bumpmap_core::BumpMap;
use bumpmap_core::scene::{Attenuation, SceneLight, Spot};
use bumpmap_core::scenes::{self, SceneKind, SceneParams};
use bumpmap_core::technique::{Gloss, KilgardOptions, SinglePassOptions, Technique};
use bumpmap_io::image_file::{PngLayout, save_png};
use bumpmap_math::lighting::Light;
use bumpmap_math::{
    Encoding, HeightField, HeightPreset, MipMode, NormalMapOptions, NormalizationCubeMap, Rgba8Image, Rgba8Mips,
};
use glam::Vec3;
use indicatif::{ProgressBar, ProgressStyle};

mod normal_maps_in;

use crate::args::{DemoArgs, DemoGpuArg};
use crate::error::CliError;
use crate::render::write_frame;
use bumpmap_words::frame::{core_err, lib_err};

/// One image of the demo: its file, what it shows, and the scene and technique that make it.
struct DemoRender {
    file: &'static str,
    what: &'static str,
    /// Also write the framebuffer after each pass (Kilgard Figure 12).
    passes: bool,
    make: fn() -> (SceneKind, SceneParams, Technique),
}

fn kilgard() -> Technique {
    Technique::Kilgard(KilgardOptions::default())
}

fn single(options: SinglePassOptions) -> Technique {
    Technique::SinglePass(options)
}

fn at(x: f32, y: f32, z: f32) -> SceneLight {
    SceneLight::white(Light::Positional(Vec3::new(x, y, z)))
}

fn coloured(light: SceneLight, r: f32, g: f32, b: f32) -> SceneLight {
    SceneLight { color: Vec3::new(r, g, b), ..light }
}

fn preset(p: HeightPreset) -> HeightField {
    p.render(256, 256)
}

const RENDERS: &[DemoRender] = &[
    DemoRender {
        file: "fig11_torus.png",
        what: "Kilgard Figure 11: the bump-mapped brick torus, three passes on the emulated GeForce",
        passes: true,
        make: || (SceneKind::Torus, SceneParams::default(), kilgard()),
    },
    DemoRender {
        file: "fig14_no_self_shadow.png",
        what: "Kilgard Figure 14, left: light from the far right, no self-shadowing term",
        passes: false,
        make: || {
            let params = SceneParams { lights: vec![at(6.0, 0.0, 0.5)], ..Default::default() };
            (SceneKind::Torus, params, Technique::Kilgard(KilgardOptions { self_shadow: false, ..Default::default() }))
        },
    },
    DemoRender {
        file: "fig14_self_shadow.png",
        what: "Kilgard Figure 14, right: the same light with Eq. 12's self-shadowing",
        passes: false,
        make: || (SceneKind::Torus, SceneParams { lights: vec![at(6.0, 0.0, 0.5)], ..Default::default() }, kilgard()),
    },
    DemoRender {
        file: "fig8-4_wall_floor.png",
        what: "Cg Tutorial Figure 8-4: wall and floor lit consistently by one light",
        passes: false,
        make: || (SceneKind::WallFloor, SceneParams::default(), kilgard()),
    },
    DemoRender {
        file: "single_pass_torus.png",
        what: "The same torus in one float pass per light (Kilgard §6)",
        passes: false,
        make: || (SceneKind::Torus, SceneParams::default(), single(SinglePassOptions::default())),
    },
    DemoRender {
        file: "single_pass_two_lights.png",
        what: "Two coloured lights, single pass",
        passes: false,
        make: || {
            let lights =
                vec![coloured(at(4.0, -3.0, 3.0), 1.0, 0.35, 0.2), coloured(at(-4.0, -3.0, 3.0), 0.2, 0.45, 1.0)];
            (SceneKind::Torus, SceneParams { lights, ..Default::default() }, single(SinglePassOptions::default()))
        },
    },
    DemoRender {
        file: "single_pass_gloss.png",
        what: "Gloss map: shiny bricks, dull mortar (Cg Tutorial §8.5.2)",
        passes: false,
        make: || {
            let gloss = Rgba8Image::from_gray(256, 256, &bumpmap_math::height::bricks_gloss(256, 256));
            let options = SinglePassOptions {
                gloss: Gloss::Map(Arc::new(Rgba8Mips::with_box_mipmaps(gloss))),
                ..Default::default()
            };
            (SceneKind::Torus, SceneParams { shininess: 40.0, ..Default::default() }, single(options))
        },
    },
    DemoRender {
        file: "single_pass_spotlight.png",
        what: "A spotlight projecting a pinwheel pattern on the wall (Kilgard §5.6)",
        passes: false,
        make: || {
            let field = preset(HeightPreset::Pinwheel);
            let pattern = Rgba8Mips::single(Rgba8Image::from_gray(field.width(), field.height(), &field.to_u8()));
            let spot =
                Spot { direction: Vec3::NEG_Z, cutoff_degrees: 30.0, exponent: 2.0, pattern: Some(Arc::new(pattern)) };
            let lights = vec![SceneLight { spot: Some(spot), ..at(0.0, 0.0, 4.0) }];
            let params = SceneParams { lights, specular: Vec3::splat(0.3), ..Default::default() };
            (SceneKind::Wall, params, single(SinglePassOptions::default()))
        },
    },
    DemoRender {
        file: "single_pass_attenuation.png",
        what: "Attenuation 1/(0.2 + 0.5·d²) from a light just above the floor",
        passes: false,
        make: || {
            let attenuation = Attenuation::Polynomial { constant: 0.2, linear: 0.0, quadratic: 0.5 };
            let lights = vec![SceneLight { attenuation, ..at(0.0, 0.6, 0.0) }];
            let params = SceneParams { lights, eye: Some(Vec3::new(0.0, 3.0, 6.0)), ..Default::default() };
            (SceneKind::Floor, params, single(SinglePassOptions::default()))
        },
    },
    DemoRender {
        file: "single_pass_object_space.png",
        what: "Object-space lighting with an object-space normal map baked for the torus (Peercy §2.1)",
        passes: false,
        make: || {
            (
                SceneKind::Torus,
                SceneParams { bump_map: BumpMap::ObjectSpace, ..Default::default() },
                single(SinglePassOptions::default()),
            )
        },
    },
    DemoRender {
        file: "patch_pinwheel.png",
        what: "Peercy Figure 4's stretched bicubic patch with the pinwheel height field",
        passes: false,
        make: || {
            let params = SceneParams {
                bumps: BumpSource::Heights(Arc::new(preset(HeightPreset::Pinwheel))),
                default_decal: false,
                ..Default::default()
            };
            (SceneKind::Patch, params, kilgard())
        },
    },
    DemoRender {
        file: "sphere_dimples.png",
        what: "A golf ball: dimples on a sphere",
        passes: false,
        make: || {
            let params = SceneParams {
                bumps: BumpSource::Heights(Arc::new(preset(HeightPreset::Dimples))),
                normal_map: NormalMapOptions { scale: 8.0, ..Default::default() },
                default_decal: false,
                ..Default::default()
            };
            (SceneKind::Sphere, params, kilgard())
        },
    },
    DemoRender {
        file: "parallax_normal_mapping.png",
        what: "Heights as geometry, 1 of 2: the brick wall at a grazing angle by normal mapping (single-pass): flat bricks painted with slopes",
        passes: false,
        make: || grazing_wall(TechniqueName::SinglePass),
    },
    DemoRender {
        file: "parallax_pom.png",
        what: "Heights as geometry, 2 of 2: the same wall by parallax occlusion mapping (pom) with hard shadows: the bricks hide the mortar behind them and shade the joints",
        passes: false,
        make: || grazing_wall(TechniqueName::Pom),
    },
    DemoRender {
        file: "shadows_normal_mapping.png",
        what: "Bumps that shadow each other, 1 of 2: the brick wall head-on, lit low from the side (70° from the normal), by the single pass: Eq. 12 lights every joint, since the wall itself faces the light",
        passes: false,
        make: || low_light_wall(TechniqueName::SinglePass),
    },
    DemoRender {
        file: "shadows_horizon.png",
        what: "Bumps that shadow each other, 2 of 2: the same by the horizon map (horizon, with --ambient-occlusion): each brick shadows the joint beside it, no march",
        passes: false,
        make: || low_light_wall(TechniqueName::Horizon),
    },
];

/// The brick wall head-on, lit from the side 70° from its normal, by `name` (ambient occlusion
/// from the horizon map for the techniques that read it).
fn low_light_wall(name: TechniqueName) -> (SceneKind, SceneParams, Technique) {
    let l = 70f32.to_radians();
    let base = SceneParams {
        eye: Some(Vec3::new(0.0, 0.0, 1.8)),
        target: Some(Vec3::ZERO),
        lights: vec![SceneLight::white(Light::Directional(Vec3::new(l.sin() * 0.8, -l.sin() * 0.6, l.cos())))],
        ..Default::default()
    };
    let options = TechniqueOptions {
        parallax: ParallaxOptions { ambient_occlusion: true, ..Default::default() },
        ..Default::default()
    };
    (SceneKind::Wall, name.scene_params(&base), name.technique(&options))
}

/// The brick wall seen 65° off its normal, lit from the side, by `name` (hard shadows from the
/// heights for the techniques that take them as geometry).
fn grazing_wall(name: TechniqueName) -> (SceneKind, SceneParams, Technique) {
    let base = SceneParams {
        eye: Some(Vec3::new(0.0, -1.25, 0.55)),
        target: Some(Vec3::new(0.0, 0.1, 0.0)),
        lights: vec![SceneLight::white(Light::Directional(Vec3::new(1.0, -0.2, 0.45).normalize()))],
        ..Default::default()
    };
    let options = TechniqueOptions {
        parallax: ParallaxOptions { shadow: ParallaxShadow::Hard, ..Default::default() },
        ..Default::default()
    };
    (SceneKind::Wall, name.scene_params(&base), name.technique(&options))
}

/// The figure of normal mapping beside POM at a grazing angle (the README shows it).
const PARALLAX_FIGURE: &str = "parallax_figure.png";
/// The figure of normal mapping beside the horizon map under a low light (the README shows it).
const SHADOWS_FIGURE: &str = "shadows_figure.png";

/// Writes `left` and `right` (two images of the demo in `out`, the same height) side by side,
/// RGB, as `file`.
fn side_by_side(out: &Path, left: &str, right: &str, file: &str) -> Result<(), CliError> {
    let (a, b) = (bumpmap_io::load_rgba8(&out.join(left))?, bumpmap_io::load_rgba8(&out.join(right))?);
    let (width, height) = (a.width + b.width, a.height.min(b.height));
    let mut rgb = Vec::with_capacity(width * height * 3);
    for y in 0..height {
        for image in [&a, &b] {
            rgb.extend(image.texels[y * image.width..(y + 1) * image.width].iter().flat_map(|t| [t[0], t[1], t[2]]));
        }
    }
    save_png(&out.join(file), width, height, PngLayout::Rgb8, &rgb)?;
    Ok(())
}

/// The demo's image size.
const SIZE: usize = 512;

/// Runs `bumpmap demo`: every file is written into a staging folder beside the output, which
/// replaces the output folder whole once everything is written; a demo that fails (no GPU with
/// `--gpu always`, a failed step, Ctrl-C) leaves nothing behind and an earlier demo as it was.
///
/// Since the folder is replaced whole, it must be new, empty or an earlier demo holding nothing
/// the demo does not write: any other folder is refused (before any work when it is not a
/// demo's, after it when an earlier demo's holds files of the user's), and left as it was.
pub fn run(args: &DemoArgs) -> Result<(), CliError> {
    let refuse = |reason: String| CliError::Path { path: args.output.clone(), reason };
    let existing = files_under(&args.output);
    let is_demo = std::fs::read_to_string(args.output.join("README.md")).is_ok_and(|r| r.starts_with(DEMO_TITLE));
    if !existing.is_empty() && !is_demo {
        return Err(refuse(format!(
            "holds {} file(s) or folder(s) and is not an earlier demo's folder; the demo replaces its folder whole, so give a new or empty one",
            existing.len()
        )));
    }
    let staged = bumpmap_io::atomic::StagedFolder::new(&args.output)?;
    write_demo(staged.path(), args)?;
    let written = files_under(staged.path());
    // The GPU images (`gpu/`) are the demo's whether or not this run drew them.
    let foreign: Vec<String> = existing
        .difference(&written)
        .filter(|p| !p.starts_with(GPU_FOLDER))
        .map(|p| format!("'{}'", p.display()))
        .collect();
    if !foreign.is_empty() {
        return Err(refuse(format!(
            "holds files or folders the demo does not write ({}{}); move them away or give another folder",
            foreign[..foreign.len().min(3)].join(", "),
            if foreign.len() > 3 { ", …" } else { "" }
        )));
    }
    let out = staged.commit()?;
    eprintln!("wrote the demo into {} (see its README.md)", out.display());
    Ok(())
}

/// The subfolder of the GPU backend's images, written when an adapter draws them.
const GPU_FOLDER: &str = "gpu";

/// The first line of the demo's README: what marks a folder as an earlier demo's.
const DEMO_TITLE: &str = "# bumpmap demo\n";

/// Every entry under `dir` (none when it does not exist), relative to it: files, links (not
/// followed) and folders, empty ones included.
fn files_under(dir: &Path) -> std::collections::BTreeSet<std::path::PathBuf> {
    let mut out = std::collections::BTreeSet::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else { continue };
        for e in entries.flatten() {
            let p = e.path();
            if let Ok(rel) = p.strip_prefix(dir) {
                out.insert(rel.to_path_buf());
            }
            if e.file_type().is_ok_and(|t| t.is_dir()) {
                stack.push(p);
            }
        }
    }
    out
}

/// Everything the demo writes, into `out`.
fn write_demo(out: &Path, args: &DemoArgs) -> Result<(), CliError> {
    let presets = [
        ("bricks", HeightPreset::Bricks),
        ("pinwheel", HeightPreset::Pinwheel),
        ("dimples", HeightPreset::Dimples),
        ("noise", HeightPreset::Noise(1)),
    ];
    let bar = ProgressBar::new((presets.len() + 1 + RENDERS.len()) as u64)
        .with_style(ProgressStyle::with_template("{bar:40} {pos}/{len} {wide_msg}").expect("valid template"));
    let mut index = format!("{DEMO_TITLE}\n");
    for (name, preset) in presets {
        bar.set_message(format!("normal map: {name}"));
        let field = preset.render(256, 256);
        save_png(&out.join(format!("{name}_height.png")), 256, 256, PngLayout::Gray8, &field.to_u8())?;
        // A file for other tools: green up, as glTF and Blender read it.
        let options = NormalMapOptions { y_convention: bumpmap_math::YConvention::YUp, ..Default::default() };
        let chain = crate::normalmap::make(&field, &options, true, MipMode::LengthInAlpha, name)?;
        crate::normalmap::write(&out.join(format!("{name}_normal.png")), chain)?;
        index += &format!(
            "- `{name}_height.png`, `{name}_normal.png` (+ `.mip1` … `.mip8`): the {name} preset and its normal map (green up, as glTF and Blender read it); alpha of the mips is the length of the averaged normal\n"
        );
        bar.inc(1);
    }
    bar.set_message("normal maps in: inspect, and heights back");
    let maps: Vec<String> = presets.iter().map(|(name, _)| format!("{name}_normal.png")).collect();
    let maps: Vec<&str> = maps.iter().map(String::as_str).collect();
    index += &normal_maps_in::write(out, &maps, "bricks_height.png", "bricks_normal.png")?;
    bar.set_message("normalization cube map");
    crate::cubemap::write(&out.join("cubemap"), &NormalizationCubeMap::new(32, Encoding::Unorm))?;
    index += "- `cubemap/px.png` … `nz.png`: a 32² normalization cube map\n";
    bar.inc(1);
    let mut cpu = Renderer::new(BackendChoice::Cpu).map_err(lib_err)?;
    render_all(&mut cpu, out, &bar, "render")?;
    for r in RENDERS {
        index += &format!("- `{}`: {}\n", r.file, r.what);
    }
    side_by_side(out, "parallax_normal_mapping.png", "parallax_pom.png", PARALLAX_FIGURE)?;
    index += &format!(
        "- `{PARALLAX_FIGURE}`: the two side by side, normal mapping on the left, parallax occlusion mapping on the right\n"
    );
    side_by_side(out, "shadows_normal_mapping.png", "shadows_horizon.png", SHADOWS_FIGURE)?;
    index += &format!(
        "- `{SHADOWS_FIGURE}`: the two side by side, normal mapping on the left, the horizon map's shadows and ambient occlusion on the right\n"
    );
    index += "- `fig11_torus.decal.png`, `.diffuse.png`, `.specular.png`: Kilgard Figure 12, the framebuffer after each pass\n";
    bar.set_message("your own assets: a normal map file, a glTF with its material");
    index += &own_assets(&mut cpu, out)?;
    bar.set_message("the light orbiting the torus (an animated PNG)");
    index += &orbit(&mut cpu, out)?;
    bar.finish_and_clear();
    index += &gpu_renders(out, args.gpu)?;
    // compare's defaults: the torus, bricks, 256², 64 samples, on the CPU, every study.
    let compare = crate::args::CompareArgs { options: Default::default(), output: out.join("compare") };
    let (results, _) = crate::compare::measure(&compare, &crate::report::Progress::Bar)?;
    crate::compare::write(&compare.output, &results, &[], &|| false)?;
    index += "\n`compare/report.html`: every technique on the torus measured against the reference renderer \
(RMSE, PSNR, bias, FLIP, SSIM), with FLIP heat maps and the reference's convergence, and the studies: \
the golf ball at a distance (Kilgard §2.4.2), the highlight at a distance by specular filter (§2.5.3), \
embossing (§3.1), Peercy's Figures 5–7, and heights as geometry (every parallax technique on a brick \
wall from 30° to 85° against the displaced reference); the numbers are in `compare/results.json`.\n";
    crate::normalmap::write_text(&out.join("README.md"), &index)?;
    Ok(())
}

/// `orbit.png`: the paper's torus by its three passes with the light carried once round it, as
/// an animated PNG (what `bumpmap view --record` writes). Returns the index's line.
fn orbit(renderer: &mut Renderer, out: &Path) -> Result<String, CliError> {
    use bumpmap::{Prepared, SceneSpec, TechniqueName, TechniqueOptions};
    const SIDE: usize = 200;
    const FRAMES: usize = 30;
    let spec = SceneSpec::new(SceneKind::Torus);
    let mut prepared = Prepared::new(&spec, TechniqueName::Kilgard, &TechniqueOptions::default()).map_err(lib_err)?;
    let frames = bumpmap_view::record::orbit(renderer, &mut prepared, SIDE, SIDE, FRAMES, || {})?;
    let mut set = bumpmap_io::atomic::FileSet::new(&[]);
    bumpmap_io::image_file::save_apng_into(&mut set, &out.join("orbit.png"), SIDE, SIDE, &frames, 100)?;
    set.commit()?;
    Ok(format!(
        "- `orbit.png`: an animated PNG, the light carried once round the torus ({FRAMES} frames, `kilgard`): `bumpmap view` shows it live, `bumpmap view --record` writes it\n"
    ))
}

/// What a user brings: the dimples normal map the demo wrote (a PNG, green up) drawn on the
/// sphere as `render --normal-map` reads it, and a GLB made here — a tessellated sphere with
/// tangents and that map packed as its material's `normalTexture` — drawn as `render --scene
/// mesh:` reads it, with its own material. Returns the index's lines.
fn own_assets(renderer: &mut Renderer, out: &Path) -> Result<String, CliError> {
    use bumpmap::assets::{MeshLoad, load_mesh, load_normal_map};
    use bumpmap::{ImportOptions, Prepared, SceneSpec, TechniqueName, TechniqueOptions};
    let normal_png = out.join("dimples_normal.png");
    let map = load_normal_map(&normal_png, &ImportOptions::default()).map_err(lib_err)?;
    let mut spec = SceneSpec::new(SceneKind::Sphere);
    spec.params.bumps = map.bumps();
    spec.params.default_decal = false;
    let draw_to = |renderer: &mut Renderer, spec: &SceneSpec, file: &str| -> Result<(), CliError> {
        let prepared = Prepared::new(spec, TechniqueName::Kilgard, &TechniqueOptions::default()).map_err(lib_err)?;
        let frame = draw_passes(renderer, &prepared.scene, &prepared.technique, SIZE, SIZE, false).map_err(lib_err)?;
        write_frame(&frame, &out.join(file), &[])?;
        Ok(())
    };
    draw_to(renderer, &spec, "own_normal_map.png")?;

    // The sphere's poles turned from ±Z to ±Y, up as glTF has it: (x, y, z) → (x, z, −y).
    let mut sphere =
        bumpmap_math::surface::Surface::Sphere { radius: 1.0 }.tessellate(64, 32, glam::Vec2::new(4.0, 2.0));
    let turn = |v: Vec3| Vec3::new(v.x, v.z, -v.y);
    sphere.positions.iter_mut().chain(&mut sphere.normals).for_each(|v| *v = turn(*v));
    sphere.tangents.iter_mut().for_each(|t| *t = turn(t.truncate()).extend(t.w));
    let png =
        std::fs::read(&normal_png).map_err(|source| bumpmap_io::IoError::Read { path: normal_png.clone(), source })?;
    let glb = out.join("dimpled_sphere.glb");
    let mut set = bumpmap_io::atomic::FileSet::new(&[&normal_png]);
    bumpmap_io::mesh_file::save_gltf_into(&mut set, &glb, &sphere, Some(&png))?;
    set.commit()?;
    let asset = load_mesh(&glb, &MeshLoad::default()).map_err(lib_err)?;
    draw_to(renderer, &asset.spec(), "own_gltf.png")?;
    Ok(format!(
        "- `own_normal_map.png`: `dimples_normal.png` read back as `render --normal-map` reads a user's map ({}), on the sphere\n\
         - `dimpled_sphere.glb`, `own_gltf.png`: a sphere with tangents and that map packed as its material's normalTexture, drawn with its own material as `render --scene mesh:dimpled_sphere.glb` does ({})\n",
        map.describe(),
        asset.describe().join("; ")
    ))
}

/// Every render of [`RENDERS`] by `backend` into `dir`, one step of `bar` each.
fn render_all(renderer: &mut Renderer, dir: &Path, bar: &ProgressBar, label: &str) -> Result<(), CliError> {
    for r in RENDERS {
        bar.set_message(format!("{label}: {}", r.file));
        let (kind, params, technique) = (r.make)();
        let scene = scenes::build(&kind, &params).map_err(core_err)?;
        let frame = draw_passes(renderer, &scene, &technique, SIZE, SIZE, r.passes).map_err(lib_err)?;
        write_frame(&frame, &dir.join(r.file), &[])?;
        bar.inc(1);
    }
    Ok(())
}

/// The same figures on the GPU into `out/gpu/`, when an adapter exists (or `always`): returns
/// the index's lines, which say which adapter drew them or why there are none.
fn gpu_renders(out: &Path, mode: DemoGpuArg) -> Result<String, CliError> {
    if mode == DemoGpuArg::Never {
        return Ok(String::new());
    }
    let mut gpu = match Renderer::new(BackendChoice::Gpu).map_err(lib_err) {
        Ok(g) => g,
        Err(e) if mode == DemoGpuArg::Auto => {
            eprintln!("no GPU images: {e}");
            return Ok(format!("\nNo GPU images: {e}\n"));
        }
        Err(e) => return Err(e),
    };
    let dir = out.join(GPU_FOLDER);
    std::fs::create_dir_all(&dir).map_err(|e| CliError::Path { path: dir.clone(), reason: e.to_string() })?;
    let bar = ProgressBar::new(RENDERS.len() as u64)
        .with_style(ProgressStyle::with_template("{bar:40} {pos}/{len} {wide_msg}").expect("valid template"));
    render_all(&mut gpu, &dir, &bar, "gpu")?;
    bar.finish_and_clear();
    eprintln!("GPU images drawn by {}", gpu.describe());
    Ok(format!("\n`gpu/`: the same renders by the wgpu backend on {}.\n", gpu.describe()))
}
