//! `bumpmap compare`: every technique that can render a scene, measured against the reference,
//! with the studies the papers make in pictures made into numbers and plots.
//!
//! - this module: the technique catalogue, the renders and the studies, all files or none;
//! - [`metrics`]: RMSE, PSNR, bias, FLIP and SSIM against the reference;
//! - [`report`]: `results.json`, the plots (SVG) and `report.html`.
//!
//! What it does not do: decide what a technique is (the core's passes do) or draw (the
//! backends and the reference do).

mod metrics;
mod report;

use std::path::Path;
use std::time::Instant;

use bumpmap_core::scenes::{self, SceneKind, SceneParams};
use bumpmap_core::technique::{BackFacing, EmbossOptions, KilgardOptions, Normalize, SinglePassOptions, Technique};
use bumpmap_io::atomic::FileSet;
use bumpmap_io::image_file::{PngLayout, save_png_into};
use bumpmap_io::{Channel, HeightSource};
use bumpmap_math::{HeightField, MipMode, NormalMapOptions, Rgba8Image};
use bumpmap_reference::{LinearImage, ReferenceOptions};
use glam::Vec3;
use indicatif::{ProgressBar, ProgressStyle};

use crate::args::CompareArgs;
use crate::backend::Backend;
use crate::error::CliError;
use crate::render::{core_err, reference_err, rgb};

pub use metrics::Scores;

/// The techniques `compare` knows, in the report's order: name and what it is, in the papers'
/// words.
pub const TECHNIQUES: [(&str, &str); 12] = [
    (
        "kilgard",
        "Kilgard's three passes on the emulated GeForce 256: normalization cube map, register combiners, 8-bit framebuffer (§5)",
    ),
    ("single-pass", "one float pass per light with the same model, L and H normalized by math (§6)"),
    ("single-pass-cube", "the single pass with L and H normalized by the cube map, as the hardware did (§5.4)"),
    ("object-space", "the single pass with an object-space normal map made for the surface (Peercy §2.1, Kilgard §5)"),
    (
        "mip-renormalized",
        "the single pass with mips that renormalize the averaged normal, dropping its length (§2.4.2)",
    ),
    ("no-bump", "the single pass on a flat height field: the surface without bumps"),
    (
        "peercy-independent",
        "Peercy's surface-independent map (Eq. 8–11, Figure 7): tangent-space normals from the 7×7 derivative of a Gaussian, lit per pixel in the interpolated frame",
    ),
    (
        "peercy-dependent",
        "Peercy's surface-dependent map (Eq. 3–6, Figures 3 and 6): Blinn's normal per texel from the surface's exact ∂P/∂u, ∂P/∂v and the same 7×7 kernel, in object space",
    ),
    (
        "emboss",
        "embossing (Kilgard §3.1, Eq. 29–30): the height field fetched twice, shifted toward the light by a texel, subtracted, plus L_z; L_x, L_y forced to 0 where L_z ≤ 0; diffuse only",
    ),
    ("emboss-unforced", "embossing without forcing the shift to 0 where the light is behind the surface"),
    (
        "offset-map",
        "an offset map (Kilgard §2.2, Eq. 6–7): the slopes' offset D stored in RG, filtered, and N + D renormalized per pixel, lit by the single pass",
    ),
    (
        "peercy-blinn",
        "Peercy's Figure 2 hardware (Figure 5): the height derivatives from the same 7×7 kernel in a texture, Blinn's normal made per pixel from them and the interpolated ∂P/∂u, ∂P/∂v",
    ),
];

/// One technique's outcome.
pub struct Outcome {
    /// Its name.
    pub name: String,
    /// What it is.
    pub description: String,
    /// Its image, scores against the reference and FLIP heat map, or why it was skipped.
    pub result: Result<Rendered, String>,
}

/// A technique's image and scores.
pub struct Rendered {
    /// The image.
    pub image: Rgba8Image,
    /// Scores against the reference.
    pub scores: Scores,
    /// FLIP's error map, magma-coloured RGB8.
    pub heat: Vec<u8>,
    /// Wall-clock milliseconds of the render.
    pub millis: f64,
}

/// Every number `report` writes.
pub struct Results {
    /// The scene's name.
    pub scene: String,
    /// Image side in pixels.
    pub size: usize,
    /// The reference's samples per pixel.
    pub spp: usize,
    /// The backend the techniques were drawn with, in words.
    pub backend: String,
    /// The reference image.
    pub reference: LinearImage,
    /// The reference's milliseconds.
    pub reference_millis: f64,
    /// Each technique, in catalogue order (then unknown names).
    pub outcomes: Vec<Outcome>,
    /// `(K, RMSE between K and 4K samples per pixel)`.
    pub convergence: Vec<(usize, f64)>,
    /// The golf ball at a distance, lit from behind the eye: `(distance factor, reference,
    /// length factor, renormalized)` mean brightness over the ball.
    pub golf_ball: Vec<(f32, f64, f64, f64)>,
    /// The same with the sphere's own light, from the side.
    pub golf_ball_side: Vec<(f32, f64, f64, f64)>,
    /// Kilgard §3.1's embossing studies.
    pub emboss: EmbossStudy,
    /// Total milliseconds of the command.
    pub total_millis: f64,
}

/// Kilgard §3.1 measured, on the brick wall without specular (embossing is diffuse only), 96²,
/// directional lights.
pub struct EmbossStudy {
    /// `(angle of the light from the normal in degrees, emboss RMSE, emboss bias, single-pass
    /// RMSE, single-pass bias, emboss contrast / reference contrast)`; contrast is the standard
    /// deviation of the wall's brightness.
    pub by_angle: Vec<(f32, f64, f64, f64, f64, f64)>,
    /// `(distance factor, emboss contrast / reference contrast, single-pass contrast / reference
    /// contrast)` with the light at 45°: embossing's shift is one level-0 texel, so at small mip
    /// levels the two fetches agree and the bumps vanish.
    pub by_distance: Vec<(f32, f64, f64)>,
    /// The sphere lit from the side (half of it turned away from the light): the fraction of the
    /// image the reference leaves dark (ambient only), and the fraction of those pixels that
    /// emboss lights with the shift forced to 0 where `L_z ≤ 0`, and without.
    pub facing_away: (f64, f64, f64),
}

/// Runs `bumpmap compare`.
pub fn run(args: &CompareArgs) -> Result<(), CliError> {
    let start = Instant::now();
    let out = &args.output;
    if out.exists() && !out.is_dir() {
        return Err(CliError::Path {
            path: out.clone(),
            reason: "is a file; compare writes a folder of results".into(),
        });
    }
    let kind = SceneKind::parse(&args.scene).ok_or_else(|| {
        CliError::Usage(format!(
            "unknown scene '{}': compare takes a built-in surface (torus, wall, floor, wall-floor, patch, sphere), \
             because the reference evaluates the exact surface",
            args.scene
        ))
    })?;
    if !(args.bump_scale.is_finite() && args.bump_scale >= 0.0) {
        return Err(CliError::Usage(format!("--bump-scale must be a number ≥ 0, got {}", args.bump_scale)));
    }
    let source = HeightSource::parse(&args.height_field);
    let inputs: Vec<&Path> = source.path().into_iter().collect();
    let field = source.load(Channel::Luminance)?;
    let is_bricks = matches!(source, HeightSource::Preset { preset: bumpmap_math::HeightPreset::Bricks, .. });
    let base = SceneParams {
        height_field: field,
        normal_map: NormalMapOptions { scale: args.bump_scale, ..Default::default() },
        default_decal: is_bricks,
        ..Default::default()
    };
    let size = args.size;
    let spp = args.spp as usize;
    crate::backend::check_size(size, size)?;

    // Unknown names are reported, not fatal; the default is every technique.
    let wanted: Vec<String> = if args.techniques.is_empty() {
        TECHNIQUES.iter().map(|(n, _)| n.to_string()).collect()
    } else {
        args.techniques.iter().map(|t| t.trim().to_string()).filter(|t| !t.is_empty()).collect()
    };
    let mut backend = Backend::new(args.backend)?;
    let steps = (wanted.len() + 4) as u64;
    let bar = ProgressBar::new(steps)
        .with_style(ProgressStyle::with_template("{bar:40} {pos}/{len} {elapsed} {wide_msg}").expect("valid template"));

    bar.set_message(format!("reference, {spp} samples per pixel"));
    let scene = scenes::build(&kind, &base).map_err(core_err)?;
    let t = Instant::now();
    let reference = reference_image(&scene, size, spp)?;
    let reference_millis = t.elapsed().as_secs_f64() * 1e3;
    bar.inc(1);

    let ref_rgb = metrics::reference_rgb8(&reference);
    let mut outcomes = Vec::new();
    for name in &wanted {
        bar.set_message(name.clone());
        let description = TECHNIQUES.iter().find(|(n, _)| n == name).map_or("", |(_, d)| d).to_string();
        let result = render_technique(name, &kind, &base, &mut backend, size).map(|(image, millis)| {
            let (scores, heat) = metrics::score(&reference, &ref_rgb, &image);
            Rendered { image, scores, heat, millis }
        });
        if let Err(reason) = &result {
            bar.suspend(|| eprintln!("skipped {name}: {reason}"));
        }
        outcomes.push(Outcome { name: name.clone(), description, result });
        bar.inc(1);
    }

    bar.set_message("convergence of the reference");
    let convergence = convergence(&scene, size, spp, &reference)?;
    bar.inc(1);
    bar.set_message("golf ball at a distance (Kilgard §2.4.2)");
    let (golf_ball, golf_ball_side) = (golf_ball_study(&mut backend, true)?, golf_ball_study(&mut backend, false)?);
    bar.set_message("embossing (Kilgard §3.1)");
    let emboss = emboss_study(&mut backend)?;
    bar.inc(1);
    bar.finish_and_clear();

    let results = Results {
        scene: args.scene.clone(),
        size,
        spp,
        backend: backend.name(),
        reference,
        reference_millis,
        outcomes,
        convergence,
        golf_ball,
        golf_ball_side,
        emboss,
        total_millis: start.elapsed().as_secs_f64() * 1e3,
    };
    let written = write(out, &results, &inputs)?;
    let shown = results.outcomes.iter().filter(|o| o.result.is_ok()).count();
    eprintln!(
        "wrote {} files into {} ({shown} techniques against the reference; open {})",
        written.len(),
        out.display(),
        out.join("report.html").display()
    );
    Ok(())
}

/// The reference at `spp` samples per pixel, with the CLI's errors.
fn reference_image(scene: &bumpmap_core::Scene, size: usize, spp: usize) -> Result<LinearImage, CliError> {
    let options = ReferenceOptions { samples_per_pixel: spp, ..Default::default() };
    bumpmap_reference::render(scene, size, size, &options, &|_, _| {}).map_err(|e| CliError::Render(reference_err(e)))
}

/// Renders technique `name` on the scene `base` describes; `Err` says why it was skipped.
fn render_technique(
    name: &str,
    kind: &SceneKind,
    base: &SceneParams,
    backend: &mut Backend,
    size: usize,
) -> Result<(Rgba8Image, f64), String> {
    let mut params = base.clone();
    let single = SinglePassOptions::default();
    let technique = match name {
        "kilgard" => Technique::Kilgard(KilgardOptions::default()),
        "single-pass" => Technique::SinglePass(single),
        "single-pass-cube" => Technique::SinglePass(SinglePassOptions { normalize: Normalize::Cube, ..single }),
        "object-space" => {
            params.object_space = true;
            Technique::SinglePass(single)
        }
        "mip-renormalized" => {
            params.mip_mode = MipMode::Renormalize;
            Technique::SinglePass(single)
        }
        "peercy-independent" => {
            params.normal_map.kernel = bumpmap_math::Kernel::Gaussian7;
            Technique::SinglePass(single)
        }
        "peercy-dependent" => {
            params.normal_map.kernel = bumpmap_math::Kernel::Gaussian7;
            params.object_space = true;
            params.object_map = bumpmap_core::scenes::ObjectMap::Blinn;
            Technique::SinglePass(single)
        }
        "peercy-blinn" => {
            params.normal_map.kernel = bumpmap_math::Kernel::Gaussian7;
            params.per_pixel_blinn = true;
            Technique::SinglePass(single)
        }
        "offset-map" => {
            params.offset_map = true;
            Technique::SinglePass(single)
        }
        "emboss" => Technique::Emboss(EmbossOptions::default()),
        "emboss-unforced" => {
            Technique::Emboss(EmbossOptions { back_facing: BackFacing::Unforced, ..Default::default() })
        }
        "no-bump" => {
            let f = &base.height_field;
            params.height_field = HeightField::from_fn(f.width(), f.height(), |_, _| 0.5);
            Technique::SinglePass(single)
        }
        other => {
            let known: Vec<&str> = TECHNIQUES.iter().map(|(n, _)| *n).collect();
            return Err(format!("unknown technique '{other}' (known: {})", known.join(", ")));
        }
    };
    let scene = scenes::build(kind, &params).map_err(|e| e.to_string())?;
    let t = Instant::now();
    let frame = backend.render(&scene, &technique, size, size, false).map_err(|e| e.to_string())?;
    Ok((frame.image, t.elapsed().as_secs_f64() * 1e3))
}

/// RMSE between the reference at K and at 4K samples per pixel, for K = 1, 4, 16, … while
/// 4K ≤ `spp` (the reference at `spp` itself is reused).
fn convergence(
    scene: &bumpmap_core::Scene,
    size: usize,
    spp: usize,
    full: &LinearImage,
) -> Result<Vec<(usize, f64)>, CliError> {
    let mut ks = vec![1];
    while ks.last().expect("non-empty") * 4 <= spp {
        ks.push(ks.last().expect("non-empty") * 4);
    }
    let images: Vec<LinearImage> = ks
        .iter()
        .map(|&k| if k == spp { Ok(full.clone()) } else { reference_image(scene, size, k) })
        .collect::<Result<_, _>>()?;
    Ok(ks
        .windows(2)
        .zip(images.windows(2))
        .map(|(k, im)| (k[0], metrics::pixel_errors(&im[1].pixels, &im[0].pixels).0))
        .collect())
}

/// Kilgard §2.4.2: a dimpled sphere (a golf ball) moving away. Averaging the dimples' normals
/// shortens them; mips that keep the length in alpha dim the ball as the reference does, mips
/// that renormalize stay too bright. The brightness of the whole frame divided by the number of
/// pixels the reference's ball touches: a sum, so the reference's antialiased edge pixels and
/// a rasterizer's all-or-nothing ones count the same area.
///
/// `headlight` puts a directional light behind the eye, where Kilgard's argument holds (few of a
/// footprint's normals face away from the light); otherwise the sphere's own light, from the
/// side, where clamping N·L at 0 makes the length factor a lower bound (the mean of clamped
/// dot products is at least the clamped dot product of the mean) and it comes out too dark.
fn golf_ball_study(backend: &mut Backend, headlight: bool) -> Result<Vec<(f32, f64, f64, f64)>, CliError> {
    const SIZE: usize = 96;
    let near = Vec3::new(0.0, -5.0, 1.5);
    let lights = if headlight {
        vec![bumpmap_core::scene::SceneLight::white(bumpmap_math::lighting::Light::Directional(near.normalize()))]
    } else {
        Vec::new()
    };
    let base = SceneParams {
        lights,
        height_field: bumpmap_math::HeightPreset::Dimples.render(256, 256),
        normal_map: NormalMapOptions { scale: 12.0, ..Default::default() },
        default_decal: false,
        specular: Vec3::ZERO,
        ..Default::default()
    };
    let mut rows = Vec::new();
    for factor in [1.0f32, 2.0, 4.0, 8.0] {
        let params = SceneParams { eye: Some(near * factor), ..base.clone() };
        let scene = scenes::build(&SceneKind::Sphere, &params).map_err(core_err)?;
        let reference = reference_image(&scene, SIZE, 64)?;
        let covered: Vec<bool> = reference.pixels.iter().map(|c| c.max_element() > 0.0).collect();
        let n = covered.iter().filter(|&&c| c).count().max(1) as f64;
        let mean = |pixels: &[Vec3]| pixels.iter().map(|p| (p.x + p.y + p.z) as f64 / 3.0).sum::<f64>() / n;
        let mut technique_mean = |mode| -> Result<f64, CliError> {
            let scene = scenes::build(&SceneKind::Sphere, &SceneParams { mip_mode: mode, ..params.clone() })
                .map_err(core_err)?;
            let frame =
                backend.render(&scene, &Technique::SinglePass(SinglePassOptions::default()), SIZE, SIZE, false)?;
            Ok(mean(&metrics::linear(&frame.image)))
        };
        let length = technique_mean(MipMode::LengthInAlpha)?;
        let renormalized = technique_mean(MipMode::Renormalize)?;
        rows.push((factor, mean(&reference.pixels), length, renormalized));
    }
    Ok(rows)
}

/// The pixels the reference covers whose eight neighbours it covers too: the surface without
/// its antialiased edge.
fn interior(reference: &LinearImage) -> Vec<bool> {
    let (w, h) = (reference.width, reference.height);
    let covered = |x: usize, y: usize| reference.pixels[y * w + x].max_element() > 0.0;
    (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            x > 0 && y > 0 && x + 1 < w && y + 1 < h && (0..9).all(|k| covered(x + k % 3 - 1, y + k / 3 - 1))
        })
        .collect()
}

/// Mean and standard deviation of the brightness of `pixels` where `mask` is set.
fn brightness_stats(pixels: &[Vec3], mask: &[bool]) -> (f64, f64) {
    let values: Vec<f64> =
        pixels.iter().zip(mask).filter(|(_, m)| **m).map(|(p, _)| (p.x + p.y + p.z) as f64 / 3.0).collect();
    let n = values.len().max(1) as f64;
    let mean = values.iter().sum::<f64>() / n;
    (mean, (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt())
}

/// [`EmbossStudy`]: the wall at six light angles and four distances, the sphere lit from the side.
fn emboss_study(backend: &mut Backend) -> Result<EmbossStudy, CliError> {
    use bumpmap_core::scene::SceneLight;
    use bumpmap_math::lighting::Light;
    const SIZE: usize = 96;
    let directional = |degrees: f32| {
        let a = degrees.to_radians();
        vec![SceneLight::white(Light::Directional(Vec3::new(a.sin(), 0.0, a.cos())))]
    };
    // No decal, so brightness varies with the bumps alone.
    let base = SceneParams { specular: Vec3::ZERO, default_decal: false, ..Default::default() };
    let forced = Technique::Emboss(EmbossOptions::default());
    let single = Technique::SinglePass(SinglePassOptions::default());
    // Renders the reference and the techniques of `params` on `kind`: the reference, then each.
    let mut run = |kind: &SceneKind, params: &SceneParams, techniques: &[&Technique]| {
        let scene = scenes::build(kind, params).map_err(core_err)?;
        let reference = reference_image(&scene, SIZE, 16)?;
        let mut images = Vec::new();
        for t in techniques {
            images.push(metrics::linear(&backend.render(&scene, t, SIZE, SIZE, false)?.image));
        }
        Ok::<_, CliError>((reference, images))
    };
    let mut by_angle = Vec::new();
    for degrees in [0.0f32, 15.0, 30.0, 45.0, 60.0, 75.0] {
        let params = SceneParams { lights: directional(degrees), ..base.clone() };
        let (reference, images) = run(&SceneKind::Wall, &params, &[&forced, &single])?;
        let mask = interior(&reference);
        let (emboss_rmse, _, emboss_bias) = metrics::pixel_errors(&reference.pixels, &images[0]);
        let (single_rmse, _, single_bias) = metrics::pixel_errors(&reference.pixels, &images[1]);
        let contrast = brightness_stats(&images[0], &mask).1 / brightness_stats(&reference.pixels, &mask).1.max(1e-9);
        by_angle.push((degrees, emboss_rmse, emboss_bias, single_rmse, single_bias, contrast));
    }
    let mut by_distance = Vec::new();
    for factor in [1.0f32, 2.0, 4.0, 8.0] {
        let params =
            SceneParams { lights: directional(45.0), eye: Some(Vec3::new(0.0, 0.0, 6.0 * factor)), ..base.clone() };
        let (reference, images) = run(&SceneKind::Wall, &params, &[&forced, &single])?;
        let mask = interior(&reference);
        let reference_contrast = brightness_stats(&reference.pixels, &mask).1.max(1e-9);
        by_distance.push((
            factor,
            brightness_stats(&images[0], &mask).1 / reference_contrast,
            brightness_stats(&images[1], &mask).1 / reference_contrast,
        ));
    }
    let unforced = Technique::Emboss(EmbossOptions { back_facing: BackFacing::Unforced, ..Default::default() });
    let params = SceneParams { lights: directional(90.0), default_decal: false, ..base.clone() };
    let (reference, images) = run(&SceneKind::Sphere, &params, &[&forced, &unforced])?;
    // The dark side: pixels the reference leaves at the ambient term (0.2, white surface). A
    // pixel there is wrongly lit when it is more than 5 steps of 8 bits brighter.
    let dark: Vec<bool> =
        reference.pixels.iter().map(|c| c.max_element() > 0.0 && c.max_element() < 0.2 + 1.5 / 255.0).collect();
    let lit = |image: &[Vec3]| {
        let n = dark.iter().filter(|&&d| d).count().max(1) as f64;
        image.iter().zip(&dark).filter(|(c, d)| **d && c.max_element() > 0.2 + 5.0 / 255.0).count() as f64 / n
    };
    let facing_away =
        (dark.iter().filter(|&&d| d).count() as f64 / (SIZE * SIZE) as f64, lit(&images[0]), lit(&images[1]));
    Ok(EmbossStudy { by_angle, by_distance, facing_away })
}

/// Writes every image, heat map, plot, `results.json` and `report.html` into `out`, all or none.
fn write(out: &Path, results: &Results, inputs: &[&Path]) -> Result<Vec<std::path::PathBuf>, CliError> {
    let mut set = FileSet::new(inputs);
    let size = results.size;
    let png = |set: &mut FileSet, name: &str, rgb: &[u8]| {
        save_png_into(set, &out.join(name), size, size, PngLayout::Rgb8, rgb)
    };
    png(&mut set, "reference.png", &rgb(&results.reference.to_rgba8()))?;
    for o in &results.outcomes {
        if let Ok(r) = &o.result {
            png(&mut set, &format!("{}.png", o.name), &rgb(&r.image))?;
            png(&mut set, &format!("{}.flip.png", o.name), &r.heat)?;
        }
    }
    for (name, svg) in report::plots(results) {
        set.write(&out.join(name), |w| std::io::Write::write_all(w, svg.as_bytes()))?;
    }
    let json = report::json(results);
    set.write(&out.join("results.json"), |w| std::io::Write::write_all(w, json.as_bytes()))?;
    let html = report::html(results);
    set.write(&out.join("report.html"), |w| std::io::Write::write_all(w, html.as_bytes()))?;
    Ok(set.commit()?)
}
