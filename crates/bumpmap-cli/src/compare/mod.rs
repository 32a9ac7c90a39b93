//! `bumpmap compare`: every technique that can render a scene, measured against the reference,
//! with the studies the papers make in pictures made into numbers and plots.
//!
//! - this module: the technique catalogue and the renders, all files or none;
//! - [`studies`]: the golf ball (Kilgard §2.4.2), embossing (§3.1) and Peercy's Figures 5–7;
//! - [`metrics`]: RMSE, PSNR, bias, FLIP and SSIM against the reference;
//! - [`plots`]: the report's plots (SVG);
//! - [`report`]: `results.json` and `report.html`.
//!
//! What it does not do: decide what a technique is (the core's passes do) or draw (the
//! backends and the reference do).

mod metrics;
mod plots;
mod report;
mod studies;

use std::path::Path;
use std::time::Instant;

use bumpmap_core::BumpMap;
use bumpmap_core::scenes::{self, SceneKind, SceneParams};
use bumpmap_core::technique::{BackFacing, EmbossOptions, KilgardOptions, Normalize, SinglePassOptions, Technique};
use bumpmap_io::atomic::FileSet;
use bumpmap_io::image_file::{PngLayout, save_png_into};
use bumpmap_io::{Channel, HeightSource};
use bumpmap_math::{HeightField, MipMode, NormalMapOptions, Rgba8Image};
use bumpmap_reference::{LinearImage, ReferenceOptions};
use indicatif::{ProgressBar, ProgressStyle};

use crate::args::CompareArgs;
use crate::backend::Backend;
use crate::error::CliError;
use crate::render::{core_err, reference_err, rgb};

pub use metrics::Scores;
pub use studies::{EmbossStudy, PEERCY, PeercyStudy};

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
        "Peercy's surface-dependent map (Eq. 3–6, Figures 3 and 6): Blinn's normal per texel from the surface's exact ∂P/∂u, ∂P/∂v and the same 7×7 kernel, in each texel's tangent frame, lit exactly as peercy-independent",
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
    /// Peercy's Figures 5–7 on his patch.
    pub peercy: PeercyStudy,
    /// Total milliseconds of the command.
    pub total_millis: f64,
}

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
    // The reference, each technique, convergence and the three studies.
    let steps = (wanted.len() + 5) as u64;
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
    let golf_ball = studies::golf_ball_study(&mut backend, true)?;
    let golf_ball_side = studies::golf_ball_study(&mut backend, false)?;
    bar.inc(1);
    bar.set_message("embossing (Kilgard §3.1)");
    let emboss = studies::emboss_study(&mut backend)?;
    bar.inc(1);
    bar.set_message("Peercy's Figures 5–7 on the stretched patch");
    let peercy = studies::peercy_study(&mut backend)?;
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
        peercy,
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
            params.bump_map = BumpMap::ObjectSpace;
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
            params.bump_map = BumpMap::SurfaceDependent;
            Technique::SinglePass(single)
        }
        "peercy-blinn" => {
            params.normal_map.kernel = bumpmap_math::Kernel::Gaussian7;
            params.bump_map = BumpMap::Derivatives;
            Technique::SinglePass(single)
        }
        "offset-map" => {
            params.bump_map = BumpMap::Offset;
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
    let study_size = results.peercy.size;
    for (name, _, image) in &results.peercy.images {
        save_png_into(
            &mut set,
            &out.join(format!("{name}.png")),
            study_size,
            study_size,
            PngLayout::Rgb8,
            &rgb(image),
        )?;
    }
    for (name, svg) in plots::plots(results) {
        set.write(&out.join(name), |w| std::io::Write::write_all(w, svg.as_bytes()))?;
    }
    let json = report::json(results);
    set.write(&out.join("results.json"), |w| std::io::Write::write_all(w, json.as_bytes()))?;
    let html = report::html(results);
    set.write(&out.join("report.html"), |w| std::io::Write::write_all(w, html.as_bytes()))?;
    Ok(set.commit()?)
}
