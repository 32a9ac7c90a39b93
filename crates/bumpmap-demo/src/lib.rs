//! `bumpmap demo` as a library: the papers' figures and the toolkit's outputs on built-in
//! defaults, written into one folder with an index (`README.md`) of what each file shows — the
//! presets' heights and normal maps, `inspect`'s verdicts and heights back, a normalization cube
//! map, every figure's render on the CPU (and the GPU where an adapter exists), a
//! user's own assets read back, the orbiting light as an animated PNG, and `compare`'s report.
//!
//! ```no_run
//! use bumpmap_demo::{GpuImages, write};
//! let out = write(std::path::Path::new("out/demo"), GpuImages::Never, &()).unwrap();
//! assert!(out.join("README.md").exists());
//! ```
//!
//! The folder is written whole or not at all: staged beside the output and put in place once
//! everything is written. What this crate does not do: print (its steps go to a
//! [`Progress`], its notes through `bumpmap_words::report`), or parse a command line.

#![warn(missing_docs)]

use std::path::{Path, PathBuf};

use bumpmap::frame::{draw_passes, write_frame};
use bumpmap::{BackendChoice, Named, Renderer};
use bumpmap_core::scenes::{self, SceneKind};
use bumpmap_io::image_file::{PngLayout, save_png};
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_math::{Encoding, HeightPreset, MipMode, NormalMapOptions, NormalizationCubeMap};
use bumpmap_words::Error;
use bumpmap_words::frame::{core_err, lib_err};
use bumpmap_words::maps::{save_error, scale_err};
use glam::Vec3;

pub use bumpmap_compare::Progress;

mod bake;
mod blend;
mod figures;
mod normal_maps_in;

use figures::RENDERS;

/// Whether the demo draws its figures on the GPU too.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum GpuImages {
    /// GPU images when an adapter exists; a line in the index says why there are none otherwise.
    #[default]
    Auto,
    /// GPU images, and an error when no adapter exists.
    Always,
    /// CPU images only.
    Never,
}

impl Named for GpuImages {
    const ALL: &'static [Self] = &[Self::Auto, Self::Always, Self::Never];
    fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Always => "always",
            Self::Never => "never",
        }
    }
    fn description(self) -> &'static str {
        match self {
            Self::Auto => "GPU images when an adapter exists",
            Self::Always => "GPU images, and an error when no adapter exists",
            Self::Never => "CPU images only",
        }
    }
}

/// The figure of normal mapping beside POM at a grazing angle (the README shows it).
const PARALLAX_FIGURE: &str = "parallax_figure.png";
/// The figure of normal mapping beside the horizon map under a low light (the README shows it).
const SHADOWS_FIGURE: &str = "shadows_figure.png";

/// Writes `left` and `right` (two images of the demo in `out`, the same height) side by side,
/// RGB, as `file`.
fn side_by_side(out: &Path, left: &str, right: &str, file: &str) -> Result<(), Error> {
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

/// Writes the demo into `output` and returns the folder written: every file is written into a
/// staging folder beside the output, which replaces the output folder whole once everything is
/// written; a demo that fails (no GPU with [`GpuImages::Always`], a failed step, Ctrl-C) leaves
/// nothing behind and an earlier demo as it was. Its steps are told to `progress`.
///
/// Since the folder is replaced whole, it must be new, empty or an earlier demo holding nothing
/// the demo does not write: any other folder is refused (before any work when it is not a
/// demo's, after it when an earlier demo's holds files of the user's), and left as it was.
pub fn write(output: &Path, gpu: GpuImages, progress: &dyn Progress) -> Result<PathBuf, Error> {
    let refuse = |reason: String| Error::Path { path: output.to_path_buf(), reason };
    let existing = files_under(output);
    let is_demo = std::fs::read_to_string(output.join("README.md")).is_ok_and(|r| r.starts_with(DEMO_TITLE));
    if !existing.is_empty() && !is_demo {
        return Err(refuse(format!(
            "holds {} file(s) or folder(s) and is not an earlier demo's folder; the demo replaces its folder whole, so give a new or empty one",
            existing.len()
        )));
    }
    let staged = bumpmap_io::atomic::StagedFolder::new(output)?;
    write_demo(staged.path(), gpu, progress)?;
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
    Ok(staged.commit()?)
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
fn write_demo(out: &Path, gpu: GpuImages, progress: &dyn Progress) -> Result<(), Error> {
    let presets = [
        ("bricks", HeightPreset::Bricks),
        ("pinwheel", HeightPreset::Pinwheel),
        ("dimples", HeightPreset::Dimples),
        ("noise", HeightPreset::Noise(1)),
    ];
    progress.start((presets.len() + 1 + RENDERS.len()) as u64);
    let mut done = 0;
    let mut advance = || {
        done += 1;
        progress.advance(done);
    };
    let mut index = format!("{DEMO_TITLE}\n");
    for (name, preset) in presets {
        progress.step(&format!("normal map: {name}"));
        let field = preset.render(256, 256);
        save_png(&out.join(format!("{name}_height.png")), 256, 256, PngLayout::Gray8, &field.to_u8())?;
        // A file for other tools: green up, as glTF and Blender read it.
        let options = NormalMapOptions { y_convention: bumpmap_math::YConvention::YUp, ..Default::default() };
        let chain = bumpmap::maps::normal_chain(&field, &options, true, MipMode::LengthInAlpha)
            .map_err(|source| scale_err(source, name))?;
        let chain = bumpmap::maps::Chain::Rgba8(chain);
        bumpmap::maps::write_chain(&out.join(format!("{name}_normal.png")), &chain, TextureFormat::Rgba8, &[])
            .map_err(save_error)?;
        index += &format!(
            "- `{name}_height.png`, `{name}_normal.png` (+ `.mip1` … `.mip8`): the {name} preset and its normal map (green up, as glTF and Blender read it); alpha of the mips is the length of the averaged normal\n"
        );
        advance();
    }
    progress.step("normal maps in: inspect, and heights back");
    let maps: Vec<String> = presets.iter().map(|(name, _)| format!("{name}_normal.png")).collect();
    let maps: Vec<&str> = maps.iter().map(String::as_str).collect();
    index += &normal_maps_in::write(out, &maps, "bricks_height.png", "bricks_normal.png")?;
    progress.step("normalization cube map");
    bumpmap::maps::write_cube_map(&out.join("cubemap"), &NormalizationCubeMap::new(32, Encoding::Unorm))?;
    index += "- `cubemap/px.png` … `nz.png`: a 32² normalization cube map\n";
    advance();
    let mut cpu = Renderer::new(BackendChoice::Cpu).map_err(lib_err)?;
    render_all(&mut cpu, out, &mut |file| {
        progress.step(&format!("render: {file}"));
        advance();
    })?;
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
    progress.step("your own assets: a normal map file, a glTF with its material");
    index += &own_assets(&mut cpu, out)?;
    progress.step("a bake: a rounded cube onto a plain one");
    index += &bake::write(out, &mut cpu)?;
    progress.step("detail normals: noise over the bricks by each blend");
    index += &blend::write(out, &out.join("bricks_normal.png"), &mut cpu)?;
    progress.step("the light orbiting the torus (an animated PNG)");
    index += &orbit(&mut cpu, out)?;
    progress.finish();
    index += &gpu_renders(out, gpu, progress)?;
    // compare's defaults: the torus, bricks, 256², 64 samples, on the CPU, every study.
    let options = bumpmap_compare::CompareOptions::default();
    let compare = out.join("compare");
    let bumps = options.height_field.to_string();
    let err = |e| bumpmap_words::compare::compare_err(e, Some(&bumps), Some(&compare));
    let (results, _) = bumpmap_compare::measure(&options, progress).map_err(err)?;
    bumpmap_compare::write(&compare, &results, &[], &|| false).map_err(err)?;
    index += "\n`compare/report.html`: every technique on the torus measured against the reference renderer \
(RMSE, PSNR, bias, FLIP, SSIM), with FLIP heat maps and the reference's convergence, and the studies: \
the golf ball at a distance (Kilgard §2.4.2), the highlight at a distance by specular filter (§2.5.3), \
embossing (§3.1), Peercy's Figures 5–7, and heights as geometry (every parallax technique on a brick \
wall from 30° to 85° against the displaced reference); the numbers are in `compare/results.json`.\n";
    write_text(&out.join("README.md"), &index)
}

/// Writes a small text file atomically.
fn write_text(path: &Path, text: &str) -> Result<(), Error> {
    use std::io::Write;
    Ok(bumpmap_io::atomic::write_atomic(path, |w| w.write_all(text.as_bytes()))?)
}

/// `orbit.png`: the paper's torus by its three passes with the light carried once round it, as
/// an animated PNG (what `bumpmap view --record` writes). Returns the index's line.
fn orbit(renderer: &mut Renderer, out: &Path) -> Result<String, Error> {
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
fn own_assets(renderer: &mut Renderer, out: &Path) -> Result<String, Error> {
    use bumpmap::assets::{MeshLoad, load_mesh, load_normal_map};
    use bumpmap::{ImportOptions, Prepared, SceneSpec, TechniqueName, TechniqueOptions};
    let normal_png = out.join("dimples_normal.png");
    let map = load_normal_map(&normal_png, &ImportOptions::default()).map_err(lib_err)?;
    let mut spec = SceneSpec::new(SceneKind::Sphere);
    spec.params.bumps = map.bumps();
    spec.params.default_decal = false;
    let draw_to = |renderer: &mut Renderer, spec: &SceneSpec, file: &str| -> Result<(), Error> {
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

/// Every render of [`RENDERS`] by `renderer` into `dir`, `drawing` told each file first.
fn render_all(renderer: &mut Renderer, dir: &Path, drawing: &mut dyn FnMut(&str)) -> Result<(), Error> {
    for r in RENDERS {
        drawing(r.file);
        let (kind, params, technique) = (r.make)();
        let scene = scenes::build(&kind, &params).map_err(core_err)?;
        let frame = draw_passes(renderer, &scene, &technique, SIZE, SIZE, r.passes).map_err(lib_err)?;
        write_frame(&frame, &dir.join(r.file), &[])?;
    }
    Ok(())
}

/// The same figures on the GPU into `out/gpu/`, when an adapter exists (or `always`): returns
/// the index's lines, which say which adapter drew them or why there are none.
fn gpu_renders(out: &Path, mode: GpuImages, progress: &dyn Progress) -> Result<String, Error> {
    if mode == GpuImages::Never {
        return Ok(String::new());
    }
    let mut gpu = match Renderer::new(BackendChoice::Gpu).map_err(lib_err) {
        Ok(g) => g,
        Err(e) if mode == GpuImages::Auto => {
            bumpmap_words::report::note(format!("no GPU images: {e}"));
            return Ok(format!("\nNo GPU images: {e}\n"));
        }
        Err(e) => return Err(e),
    };
    let dir = out.join(GPU_FOLDER);
    std::fs::create_dir_all(&dir).map_err(|e| Error::Path { path: dir.clone(), reason: e.to_string() })?;
    progress.start(RENDERS.len() as u64);
    let mut done = 0;
    render_all(&mut gpu, &dir, &mut |file| {
        progress.step(&format!("gpu: {file}"));
        done += 1;
        progress.advance(done);
    })?;
    progress.finish();
    bumpmap_words::report::note(format!("GPU images drawn by {}", gpu.describe()));
    Ok(format!("\n`gpu/`: the same renders by the wgpu backend on {}.\n", gpu.describe()))
}
