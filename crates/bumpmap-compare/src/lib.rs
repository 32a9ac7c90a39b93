//! Every technique that can render a scene, measured against the reference, with the studies the
//! papers make in pictures made into numbers and plots: what `bumpmap compare` and the Python
//! package's `compare` write, as a library.
//!
//! ```no_run
//! use bumpmap_compare::{CompareOptions, Study};
//!
//! let mut options = CompareOptions::default();
//! options.size = 64;
//! options.studies = vec![Study::GolfBall];
//! let (results, _inputs) = bumpmap_compare::measure(&options, &())?;
//! for outcome in &results.outcomes {
//!     if let Ok(rendered) = &outcome.result {
//!         println!("{}: FLIP {:.3}", outcome.name, rendered.scores.flip_mean);
//!     }
//! }
//! bumpmap_compare::write("out/compare".as_ref(), &results, &[], &|| false)?;
//! # Ok::<(), bumpmap_compare::CompareError>(())
//! ```
//!
//! - this crate's root: the options, the technique catalogue and the renders, all files or none;
//! - [`option_table`]: `compare`'s options as data, which the command line and Python read;
//! - [`studies`]: the golf ball (Kilgard §2.4.2), embossing (§3.1) and Peercy's Figures 5–7;
//! - [`parallax`]: heights as geometry, every march against the displaced reference on a wall
//!   seen at grazing angles;
//! - [`shadows`]: bumps that shadow each other (horizon maps, marches, Eq. 12) against shadow
//!   rays, and ambient occlusion and bent normals against occlusion rays;
//! - [`detail`]: detail normals, every blend against added heights and draped detail;
//! - `metrics`: RMSE, PSNR, bias, FLIP and SSIM against the reference;
//! - `plots`: the report's plots (SVG);
//! - `report`: `results.json` and `report.html`;
//! - [`CompareError`]: what can go wrong, naming the value or the file; [`Progress`]: the steps
//!   as they are taken, and the techniques skipped.
//!
//! What it does not do: decide what a technique is (the core's passes do), draw (the backends
//! and the reference do), or name a command-line flag (the CLI words [`CompareError`]).

#![warn(missing_docs)]

pub mod detail;
mod error;
mod metrics;
pub mod option_table;
mod options;
pub mod parallax;
mod plots;
mod report;
pub mod shadows;
pub mod studies;

use std::path::{Path, PathBuf};
use std::time::Instant;

use std::sync::Arc;

use bumpmap::{BumpSource, Prepared, Renderer, SceneParams, SceneSpec, TechniqueName, TechniqueOptions};
use bumpmap_io::atomic::FileSet;
use bumpmap_io::image_file::{PngLayout, save_png_into};
use bumpmap_io::{Channel, HeightSource};
use bumpmap_math::{NormalMapOptions, Rgba8Image};
use bumpmap_reference::{LinearImage, ReferenceOptions};

pub use error::CompareError;
pub use metrics::Scores;
pub use options::{CompareNote, CompareOptions, Progress, Study};
pub use report::json;
pub use studies::{EmbossStudy, PEERCY, PeercyStudy};

/// The techniques `compare` draws by default: the catalogue's, in its order, but the two
/// references, which are what they are measured against.
pub fn default_techniques() -> Vec<TechniqueName> {
    TechniqueName::ALL
        .into_iter()
        .filter(|&t| !matches!(t, TechniqueName::Reference | TechniqueName::ReferenceDisplaced))
        .collect()
}

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
    /// Scores against the displaced reference (heights as geometry), where there is one.
    pub displaced: Option<Scores>,
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
    /// The displaced reference (the surface carved by the heights, `--depth` the bump scale's)
    /// and its milliseconds, or why there is none.
    pub displaced: Result<(LinearImage, f64), String>,
    /// Each technique, in catalogue order (then unknown names).
    pub outcomes: Vec<Outcome>,
    /// `(K, RMSE between K and 4K samples per pixel)`.
    pub convergence: Vec<(usize, f64)>,
    /// The golf ball at a distance (`--studies golf-ball`): lit from behind the eye, then by the
    /// sphere's own light from the side, each `(distance factor, reference, length factor,
    /// renormalized)` mean brightness over the ball.
    pub golf_ball: Option<[Vec<studies::GolfRow>; 2]>,
    /// The golf ball's highlight at a distance, by specular filter (Kilgard §2.5.3).
    pub specular: Option<Vec<studies::SpecularRow>>,
    /// Kilgard §3.1's embossing studies.
    pub emboss: Option<EmbossStudy>,
    /// Peercy's Figures 5–7 on his patch.
    pub peercy: Option<PeercyStudy>,
    /// Heights as geometry on the wall at grazing angles.
    pub parallax: Option<parallax::ParallaxStudy>,
    /// Bumps that shadow each other, ambient occlusion and bent normals.
    pub shadows: Option<shadows::ShadowStudy>,
    /// Detail normals: every blend against both exact compositions.
    pub detail: Option<detail::DetailStudy>,
    /// Total milliseconds of the command.
    pub total_millis: f64,
}

/// Refuses an output that is a file: compare writes a folder.
pub fn check_output(out: &Path) -> Result<(), CompareError> {
    if out.exists() && !out.is_dir() {
        return Err(CompareError::OutputIsAFile(out.to_path_buf()));
    }
    Ok(())
}

/// Everything `compare` measures, before anything is written, and the files it read; its steps
/// told to `progress` as they are taken. Techniques that cannot draw the scene are skipped,
/// with their reason told to `progress` and kept in the results.
pub fn measure(args: &CompareOptions, progress: &dyn Progress) -> Result<(Results, Vec<PathBuf>), CompareError> {
    let start = Instant::now();
    let kind = args.scene.clone();
    if !kind.is_surface() {
        return Err(CompareError::NotASurface(kind));
    }
    if !(args.bump_scale.is_finite() && args.bump_scale >= 0.0) {
        return Err(CompareError::BumpScale(args.bump_scale));
    }
    if !(1..=bumpmap::options::MAX_SAMPLES_PER_PIXEL).contains(&args.spp) {
        return Err(CompareError::Spp(args.spp));
    }
    let source = &args.height_field;
    let inputs: Vec<PathBuf> = source.path().into_iter().map(Path::to_path_buf).collect();
    let field = source.load(Channel::Luminance)?;
    let is_bricks = matches!(source, HeightSource::Preset { preset: bumpmap_math::HeightPreset::Bricks, .. });
    let base = SceneParams {
        bumps: BumpSource::Heights(Arc::new(field)),
        normal_map: NormalMapOptions { scale: args.bump_scale, ..Default::default() },
        default_decal: is_bricks,
        ..Default::default()
    };
    let spec = SceneSpec { kind, params: base };
    let size = args.size;
    let spp = args.spp as usize;
    Renderer::check_size(size, size)?;

    // Unknown names are reported, not fatal; the default is every technique but the reference.
    let wanted: Vec<String> = if args.techniques.is_empty() {
        default_techniques().iter().map(|n| n.name().to_string()).collect()
    } else {
        args.techniques.iter().map(|t| t.trim().to_string()).filter(|t| !t.is_empty()).collect()
    };
    // A name twice would draw twice and then collide on its own PNG: refused before any work.
    for (i, name) in wanted.iter().enumerate() {
        let key = TechniqueName::parse(name).map(|t| t.name().to_string()).unwrap_or_else(|_| name.clone());
        if wanted[..i]
            .iter()
            .any(|w| TechniqueName::parse(w).map(|t| t.name().to_string()).unwrap_or_else(|_| w.clone()) == key)
        {
            return Err(CompareError::Twice(name.clone()));
        }
    }
    // The scene the references read and one technique's maps are alive at once: refused up
    // front when they will not fit, rather than aborting in the middle of the work.
    let largest = wanted
        .iter()
        .filter_map(|n| TechniqueName::parse(n).ok())
        .chain([TechniqueName::ReferenceDisplaced])
        .map(|t| Prepared::bytes_needed(&spec, t))
        .max()
        .unwrap_or(0);
    let bytes = Prepared::bytes_needed(&spec, TechniqueName::Reference) + largest;
    bumpmap::bumpmap_math::buffer::ensure_available(bytes, "measuring it")
        .map_err(|source| CompareError::TooBig { source, bumps: spec.params.bumps.size() })?;
    let mut backend = Renderer::new(args.backend)?;
    if let Some(reason) = backend.fallback_reason() {
        progress.note(&CompareNote::OnTheCpu { reason: reason.to_string() });
    }
    // The two references, each technique, convergence and the studies.
    let steps = (wanted.len() + 10) as u64;
    let bar = options::Steps::new(progress, steps);

    bar.set_message(format!("reference, {spp} samples per pixel"));
    let scene = spec.build()?;
    let t = Instant::now();
    let reference = reference_image(&scene, size, spp)?;
    if reference.pixels.iter().all(|p| *p == glam::Vec3::ZERO) {
        return Err(CompareError::BlackReference);
    }
    let reference_millis = t.elapsed().as_secs_f64() * 1e3;
    bar.inc();

    bar.set_message(format!("displaced reference, {spp} samples per pixel"));
    let t = Instant::now();
    let displaced = Prepared::new(&spec, TechniqueName::ReferenceDisplaced, &TechniqueOptions::default())
        .map_err(|e| e.to_string())
        .and_then(|p| parallax::displaced_reference(&p.scene, size, spp))
        .map(|image| (image, t.elapsed().as_secs_f64() * 1e3));
    let displaced_rgb = displaced.as_ref().ok().map(|(image, _)| metrics::reference_rgb8(image));
    bar.inc();

    let ref_rgb = metrics::reference_rgb8(&reference);
    let mut outcomes = Vec::new();
    for name in &wanted {
        bar.set_message(name.clone());
        let technique = TechniqueName::parse(name).map_err(|e| e.to_string()).and_then(|t| match t {
            TechniqueName::Reference | TechniqueName::ReferenceDisplaced => {
                Err("the references are what the techniques are measured against".to_string())
            }
            t => Ok(t),
        });
        let description = technique.as_ref().map_or("", |t| t.description()).to_string();
        let result = technique.and_then(|t| render_technique(t, &spec, &mut backend, size)).map(|(image, millis)| {
            let (scores, heat) = metrics::score(&reference, &ref_rgb, &image);
            let displaced = match (&displaced, &displaced_rgb) {
                (Ok((d, _)), Some(rgb)) => Some(metrics::score(d, rgb, &image).0),
                _ => None,
            };
            Rendered { image, scores, displaced, heat, millis }
        });
        if let Err(reason) = &result {
            progress.note(&CompareNote::Skipped { name: name.clone(), reason: reason.clone() });
        }
        outcomes.push(Outcome { name: name.clone(), description, result });
        bar.inc();
    }

    bar.set_message("convergence of the reference");
    let convergence = convergence(&scene, size, spp, &reference)?;
    bar.inc();
    let study = |which: Study, what: &str, bar: &options::Steps| {
        let runs = args.runs(which);
        if runs {
            bar.set_message(what);
        }
        bar.inc();
        runs
    };
    let golf_ball = if study(Study::GolfBall, "golf ball at a distance (Kilgard §2.4.2)", &bar) {
        Some([studies::golf_ball_study(&mut backend, true)?, studies::golf_ball_study(&mut backend, false)?])
    } else {
        None
    };
    let specular = study(Study::Specular, "specular filtering at a distance (Kilgard §2.5.3)", &bar)
        .then(|| studies::specular_study(&mut backend))
        .transpose()?;
    let emboss = study(Study::Emboss, "embossing (Kilgard §3.1)", &bar)
        .then(|| studies::emboss_study(&mut backend))
        .transpose()?;
    let peercy = study(Study::Peercy, "Peercy's Figures 5–7 on the stretched patch", &bar)
        .then(|| studies::peercy_study(&mut backend))
        .transpose()?;
    let parallax = study(Study::Parallax, "heights as geometry: the wall at grazing angles", &bar)
        .then(|| parallax::parallax_study(&mut backend))
        .transpose()?;
    let shadows = study(Study::Shadows, "bumps that shadow each other: horizon maps, marches, Eq. 12", &bar)
        .then(|| shadows::shadow_study(&mut backend))
        .transpose()?;
    let detail = study(Study::Detail, "detail normals: every blend against both exact compositions", &bar)
        .then(detail::detail_study);
    bar.finish();

    let results = Results {
        scene: args.scene.name().to_string(),
        size,
        spp,
        backend: backend.describe(),
        reference,
        reference_millis,
        displaced,
        outcomes,
        convergence,
        golf_ball,
        specular,
        emboss,
        peercy,
        parallax,
        shadows,
        detail,
        total_millis: start.elapsed().as_secs_f64() * 1e3,
    };
    Ok((results, inputs))
}

/// The reference at `spp` samples per pixel.
fn reference_image(scene: &bumpmap_core::Scene, size: usize, spp: usize) -> Result<LinearImage, CompareError> {
    let options = ReferenceOptions { samples_per_pixel: spp, ..Default::default() };
    Ok(bumpmap_reference::render(scene, size, size, &options, &|_, _| {})?)
}

/// Renders technique `name` on the scene `spec` describes, with its default options; `Err`
/// says why it was skipped.
fn render_technique(
    name: TechniqueName,
    spec: &SceneSpec,
    renderer: &mut Renderer,
    size: usize,
) -> Result<(Rgba8Image, f64), String> {
    let prepared = Prepared::new(spec, name, &TechniqueOptions::default()).map_err(|e| e.to_string())?;
    let t = Instant::now();
    let image = renderer.draw(&prepared, size, size).map_err(|e| e.to_string())?;
    Ok((image, t.elapsed().as_secs_f64() * 1e3))
}

/// RMSE between the reference at K and at 4K samples per pixel, for K = 1, 4, 16, … while
/// 4K ≤ `spp` (the reference at `spp` itself is reused).
fn convergence(
    scene: &bumpmap_core::Scene,
    size: usize,
    spp: usize,
    full: &LinearImage,
) -> Result<Vec<(usize, f64)>, CompareError> {
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

/// The image's RGB bytes: the colour buffer's alpha (s_self, not coverage) left out.
fn rgb(image: &Rgba8Image) -> Vec<u8> {
    image.texels.iter().flat_map(|&[r, g, b, _]| [r, g, b]).collect()
}

/// Writes every image, heat map, plot, `results.json` and `report.html` into `out`, all or none;
/// none when `cancelled`, asked once the files are staged, says the caller gave up.
pub fn write(
    out: &Path,
    results: &Results,
    inputs: &[&Path],
    cancelled: &dyn Fn() -> bool,
) -> Result<Vec<std::path::PathBuf>, CompareError> {
    let mut set = FileSet::new(inputs);
    let size = results.size;
    let png = |set: &mut FileSet, name: &str, rgb: &[u8]| {
        save_png_into(set, &out.join(name), size, size, PngLayout::Rgb8, rgb)
    };
    png(&mut set, "reference.png", &rgb(&results.reference.to_rgba8()))?;
    if let Ok((image, _)) = &results.displaced {
        png(&mut set, "reference-displaced.png", &rgb(&image.to_rgba8()))?;
    }
    if let Some(p) = &results.parallax {
        for (name, _, image) in &p.figure {
            save_png_into(&mut set, &out.join(format!("{name}.png")), p.size, p.size, PngLayout::Rgb8, &rgb(image))?;
        }
    }
    for o in &results.outcomes {
        if let Ok(r) = &o.result {
            png(&mut set, &format!("{}.png", o.name), &rgb(&r.image))?;
            png(&mut set, &format!("{}.flip.png", o.name), &r.heat)?;
        }
    }
    if let Some(peercy) = &results.peercy {
        for (name, _, image) in &peercy.images {
            let file = out.join(format!("{name}.png"));
            save_png_into(&mut set, &file, peercy.size, peercy.size, PngLayout::Rgb8, &rgb(image))?;
        }
    }
    for (name, svg) in plots::plots(results) {
        set.write(&out.join(name), |w| std::io::Write::write_all(w, svg.as_bytes()))?;
    }
    let json = report::json(results);
    set.write(&out.join("results.json"), |w| std::io::Write::write_all(w, json.as_bytes()))?;
    let html = report::html(results);
    set.write(&out.join("report.html"), |w| std::io::Write::write_all(w, html.as_bytes()))?;
    if cancelled() {
        return Err(CompareError::Interrupted);
    }
    Ok(set.commit()?)
}
