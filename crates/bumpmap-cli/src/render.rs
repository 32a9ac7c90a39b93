//! `bumpmap render`: the options made into a scene and a technique of the catalogue
//! (`crate::setup`), drawn by the front door's renderer into a PNG (and, with `--passes`, one
//! PNG per pass).
//!
//! The library refuses what a technique cannot do with typed errors; this module is where they
//! get the names of the flags that caused them ([`core_err`], [`lib_err`]).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use bumpmap::bumpmap_core::Feature;
use bumpmap::options::SceneOptions;
use bumpmap::{BackendChoice, BumpSource, CoreError, Prepared, Renderer, Rgba8Image, Scene, Technique, TechniqueName};
use bumpmap_io::atomic::{FileSet, ensure_not_input};
use bumpmap_io::image_file::{PngLayout, save_png_into};

use crate::args::RenderArgs;
use crate::error::CliError;

/// A rendered frame and, when asked for, the framebuffer after each named pass.
pub struct Frame {
    /// The final image.
    pub image: Rgba8Image,
    /// `(pass name, image)` for Kilgard Figure 12.
    pub snapshots: Vec<(String, Rgba8Image)>,
}

/// What `render` draws, typed: the library's scene options, the frame's size, the backend, and
/// whether each pass is kept. The command line makes it from its flags, the Python package from
/// its keywords.
#[derive(Clone, Debug)]
pub struct Request {
    /// What is drawn and how.
    pub options: SceneOptions,
    /// The frame's width and height in pixels.
    pub size: (usize, usize),
    /// What draws it (the reference always draws on the CPU).
    pub backend: BackendChoice,
    /// Keep the framebuffer after each of kilgard's passes.
    pub passes: bool,
    /// Where the frame goes, for messages.
    pub output: PathBuf,
}

/// `render`'s square frame side when none is given.
pub const DEFAULT_SIZE: usize = 512;

impl Default for Request {
    /// What `bumpmap render` draws with no flags (a test holds the two together).
    fn default() -> Self {
        Request {
            options: SceneOptions::default(),
            size: (DEFAULT_SIZE, DEFAULT_SIZE),
            backend: BackendChoice::Cpu,
            passes: false,
            output: PathBuf::from("out/render.png"),
        }
    }
}

impl Request {
    /// The request `render`'s flags make.
    pub fn from_args(args: &RenderArgs) -> Result<Self, CliError> {
        let size = match (args.width, args.height) {
            (Some(w), Some(h)) => (w, h),
            _ => (args.size, args.size),
        };
        Ok(Request {
            options: crate::setup::scene_options(&args.setup)?,
            size,
            backend: args.setup.backend.backend,
            passes: args.passes,
            output: args.output.clone(),
        })
    }
}

/// Runs `bumpmap render`.
pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    let request = Request::from_args(args)?;
    let named = request.options.named_inputs();
    ensure_not_input(&args.output, &named.iter().map(PathBuf::as_path).collect::<Vec<_>>())?;
    let drawn = draw_request(&request, &crate::report::Progress::Bar, &crate::setup::Given::default())?;
    let inputs: Vec<&Path> = drawn.inputs.iter().map(PathBuf::as_path).collect();
    let written = write_frame(&drawn.frame, &args.output, &inputs)?;
    eprintln!(
        "wrote {} ({})",
        written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "),
        drawn.by
    );
    Ok(())
}

/// What `render`'s options drew, before anything is written.
pub struct Drawn {
    /// The image, and the passes when `--passes` asked for them.
    pub frame: Frame,
    /// How it was drawn, in words: the technique and the backend.
    pub by: String,
    /// Every file read: no output may replace one.
    pub inputs: Vec<PathBuf>,
}

/// What `args` describe, set up and prepared once: the frame's size, the scene with the
/// technique's maps made, and how its inputs were read. A frame that would not fit, `--passes`
/// without passes, a bad option or input: refused before any drawing.
pub struct PreparedArgs {
    /// `--width`×`--height`, or `--size` squared.
    pub size: (usize, usize),
    /// The scene with the technique's maps.
    pub prepared: Prepared,
    /// The setup it came from (its notes for stderr, the files it read).
    pub setup: crate::setup::Setup,
    /// What `--depth` did, for stderr.
    pub depth_notes: Vec<String>,
}

/// Sets up and prepares what `request` describes, with the inputs `given` in memory in place of
/// their options' files.
pub fn prepare_request(request: &Request, given: &crate::setup::Given) -> Result<PreparedArgs, CliError> {
    let (width, height) = request.size;
    // Refuse an impossible framebuffer, and --passes without passes, before any work.
    Renderer::check_size(width, height).map_err(lib_err)?;
    let name = request.options.technique.technique;
    if request.passes && name != TechniqueName::Kilgard {
        return Err(CliError::Usage(format!(
            "--passes shows the three passes of --technique kilgard; {name} draws {}",
            if name.is_reference() { "no passes (it samples the exact surface)" } else { "one pass per light" }
        )));
    }
    let setup = crate::setup::set_up_options(&request.options, given)?;
    let bumps = bumps_name(&request.options);
    let prepared = Prepared::new(&setup.spec, name, &setup.options)
        .map_err(|e| too_big(prepare_err(e), &setup.spec, bumps.as_deref()))?;
    let depth_notes = depth_notes(&request.options, &setup.spec, &prepared);
    Ok(PreparedArgs { size: (width, height), prepared, setup, depth_notes })
}

/// The file or preset the bumps come from, as messages name it.
fn bumps_name(options: &SceneOptions) -> Option<String> {
    match &options.height_field {
        Some(source) => Some(source.to_string()),
        None => options.normal_map.as_ref().map(|p| p.display().to_string()),
    }
}

/// Draws what `request` describes: the scene set up, the technique prepared, the frame drawn on
/// its backend (the reference always on the CPU, its tiles' progress shown as `progress` says).
/// The notes the assets bring (what a glTF's material gave) go to stderr.
pub fn draw_request(
    request: &Request,
    progress: &crate::report::Progress,
    given: &crate::setup::Given,
) -> Result<Drawn, CliError> {
    let name = request.options.technique.technique;
    let PreparedArgs { size: (width, height), prepared, setup, depth_notes } = prepare_request(request, given)?;
    for note in setup.notes.iter().chain(&depth_notes) {
        crate::report::setup_line(note);
    }
    let bumps = bumps_name(&request.options);
    let too_big = |e| too_big(e, &setup.spec, bumps.as_deref());
    let mut renderer = if name.is_reference() {
        // The reference runs on the CPU whatever the backend; no device need open for it.
        let mut r = Renderer::new(BackendChoice::Cpu).map_err(lib_err)?;
        match progress {
            crate::report::Progress::Hidden => {}
            crate::report::Progress::Bar => r.set_reference_progress(Some(reference_bar())),
            crate::report::Progress::Report(f) => {
                let f = f.clone();
                r.set_reference_progress(Some(std::sync::Arc::new(move |done, total| f(done as u64, total as u64))));
            }
        }
        r
    } else {
        renderer(request.backend)?
    };
    let frame =
        draw(&mut renderer, &prepared.scene, &prepared.technique, width, height, request.passes).map_err(too_big)?;
    ensure_drawn(frame.image.texels.iter().all(|&[r, g, b, _]| r == 0 && g == 0 && b == 0), &request.output)?;
    let by = if name.is_reference() {
        format!("reference, {} samples per pixel", setup.options.reference.samples_per_pixel)
    } else {
        format!("{name}, {}", renderer.describe())
    };
    Ok(Drawn { frame, by, inputs: setup.inputs })
}

/// What `--depth` did, for stderr: clamped to what the surface allows, or a depth whose slopes
/// the normal map `spec` makes from heights (with `--bump-scale`) does not share.
pub fn depth_notes(options: &SceneOptions, spec: &bumpmap::SceneSpec, prepared: &Prepared) -> Vec<String> {
    let mut notes = Vec::new();
    let Some(asked) = options.heights.depth else { return notes };
    let Some(object) = prepared.scene.objects.iter().find(|o| o.material.heights.is_some()) else { return notes };
    let used = object.material.depth;
    if used < asked * (1.0 - 1e-6) {
        notes.push(format!(
            "note: --depth {asked} would carve past the surface's bounds; drawn at {used} (a quarter of a wall's or floor's shorter side, half a torus's tube radius or a sphere's radius, a quarter of the patch's narrower side)"
        ));
    }
    let size = object.material.heights.as_ref().map_or((1, 1), |h| (h.width(), h.height()));
    if let (Some(side), BumpSource::Heights(_)) = (object.texel_side(size), &spec.params.bumps) {
        let scale = spec.params.normal_map.scale;
        let texels = used / side;
        if (texels - scale).abs() > 0.01 * scale.abs().max(1e-6) {
            notes.push(format!(
                "note: --depth {used} is {texels:.3} texels of this surface's mean texel side ({side:.5}); the normal map keeps --bump-scale {scale}'s slopes: add --bump-scale {texels:.3} for the slopes of the geometry"
            ));
        }
    }
    notes
}

/// Refuses `output` for a frame that came out black (`black`: no pixel has any colour): nothing
/// in view was drawn or lit, and a black PNG with exit status 0 would pass for a result. Judged
/// from the image, so it holds for every backend and the reference alike; the causes are named,
/// since the image cannot tell them apart.
pub fn ensure_drawn(black: bool, output: &Path) -> Result<(), CliError> {
    if !black {
        return Ok(());
    }
    Err(CliError::Path {
        path: output.to_path_buf(),
        reason: "not written: the image is black (no pixel was drawn or lit). The object may be out of \
                 view (--eye, --target, --up, --fov), too small or too flat to cover a pixel (--tessellation, \
                 --torus-radii, the mesh), or facing away from the eye or the light (--light, --ambient)"
            .into(),
    })
}

/// An out-of-memory error with the sizes that caused it: the bump texture's (and `bumps`, the
/// file or preset it came from) and the tessellation's: what a user can make smaller.
pub(crate) fn too_big(e: CliError, spec: &bumpmap::SceneSpec, bumps: Option<&str>) -> CliError {
    let CliError::OutOfMemory(oom) = e else { return e };
    let (w, h) = spec.params.bumps.size();
    let from = bumps.map(|b| format!(" from {b}")).unwrap_or_default();
    let mesh = match spec.params.tessellation {
        Some((u, v)) => format!(", tessellation {u}x{v}"),
        None => String::new(),
    };
    let decal = match &spec.params.decal {
        Some(d) if !spec.params.default_decal => format!(", decal {}x{}", d.levels()[0].width, d.levels()[0].height),
        _ => String::new(),
    };
    CliError::Render(format!(
        "this scene (bumps {w}x{h}{from}{decal}{mesh}) is too big for the memory this process may use: {oom}. \
         The README's \"Memory\" section gives what the largest inputs need; a smaller --height-field, \
         --normal-map, --decal, --gloss or --tessellation needs less"
    ))
}

/// A progress bar on stderr for the reference's tiles.
fn reference_bar() -> bumpmap::renderer::Progress {
    let bar = indicatif::ProgressBar::new(0).with_style(
        indicatif::ProgressStyle::with_template("reference {bar:40} {pos}/{len} tiles {elapsed}")
            .expect("valid template"),
    );
    Arc::new(move |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
        if done == total {
            bar.finish_and_clear();
        }
    })
}

/// Opens the backend `arg` names; `auto` says on stderr why it fell back to the CPU.
pub fn renderer(arg: BackendChoice) -> Result<Renderer, CliError> {
    let renderer = Renderer::new(arg).map_err(lib_err)?;
    if let Some(why) = renderer.fallback_reason() {
        crate::report::note(format!("--backend auto: drawing on the CPU ({why})"));
    }
    Ok(renderer)
}

/// Draws `technique`'s passes of `scene`; with `snapshots`, also the framebuffer after each
/// named pass.
pub fn draw(
    renderer: &mut Renderer,
    scene: &Scene,
    technique: &Technique,
    width: usize,
    height: usize,
    snapshots: bool,
) -> Result<Frame, CliError> {
    let mut shots = Vec::new();
    let mut keep = |name: &str, image: &bumpmap::Rgba8Image| shots.push((name.to_string(), image.clone()));
    let on_pass: Option<bumpmap::renderer::OnPass> = if snapshots { Some(&mut keep) } else { None };
    let image = renderer.draw_scene(scene, technique, width, height, on_pass).map_err(lib_err)?;
    Ok(Frame { image, snapshots: shots })
}

/// [`lib_err`], but a scene whose maps will not fit is an [`CliError::OutOfMemory`] that
/// [`too_big`] can name the inputs of.
pub(crate) fn prepare_err(e: bumpmap::Error) -> CliError {
    match e {
        bumpmap::Error::OutOfMemory { source, .. } => CliError::OutOfMemory(source),
        other => lib_err(other),
    }
}

/// A front-door error in the words of the command line.
pub fn lib_err(e: bumpmap::Error) -> CliError {
    match e {
        bumpmap::Error::Core(e) | bumpmap::Error::Cpu(bumpmap_cpu::CpuError::Core(e)) => core_err(e),
        bumpmap::Error::Cpu(bumpmap_cpu::CpuError::OutOfMemory(e)) => CliError::OutOfMemory(e),
        bumpmap::Error::Io(e) => CliError::Io(e),
        bumpmap::Error::Gpu(bumpmap_gpu::GpuError::NoAdapter(reason)) => CliError::NoDevice(format!(
            "no GPU adapter found ({reason}): install a Vulkan driver (on Debian without a GPU, \
             `apt-get install mesa-vulkan-drivers libvulkan1` gives Mesa's lavapipe) or use --backend cpu"
        )),
        bumpmap::Error::Reference(e) => CliError::Render(reference_err(e)),
        // A size out of range is a value out of range, like any other.
        bumpmap::Error::Cpu(e @ bumpmap_cpu::CpuError::FramebufferSize { .. }) => {
            CliError::Usage(format!("{e} (--size, or --width and --height)"))
        }
        other => CliError::Render(other.to_string()),
    }
}

/// A library error in the words of the command line: what the user typed that caused it.
pub fn core_err(e: CoreError) -> CliError {
    let flag = |f: &Feature| {
        match f {
        Feature::Shininess(s) => format!("--shininess {s} (its combiners square three times: 8 only; --specular-mode ramp gives a tighter highlight)"),
        Feature::Gloss => "--gloss".into(),
        Feature::Attenuation => "--attenuation".into(),
        Feature::Spotlight => "--spot".into(),
        Feature::NormalizeByMath | Feature::FragmentHalfAngle | Feature::SelfShadowStep => {
            "--normalize, --half-angle or --self-shadow (it always normalizes by the cube map, with per-vertex H, the ramp or --no-self-shadow)".into()
        }
        Feature::ObjectSpace => "object-space lighting (its self-shadowing reads tangent-space L_z)".into(),
        Feature::SpecularColor => "--specular other than 0 or 1 (its specular is white)".into(),
        Feature::MultipleLights => "more than one --light".into(),
        Feature::BumpScale(s) => format!("--bump-scale {s} (its combiners scale by 1, 2 or 4)"),
        Feature::HeightMap => "a scene without its height field (--normal-map, or a glTF's own normal map)".into(),
        Feature::OffsetMap => "an offset map (its combiners cannot renormalize N + D per pixel)".into(),
        Feature::SurfaceMap => "a normal map made for one surface (its passes read every texture with the repeating coordinates)".into(),
        Feature::LeanFilter => "--specular-filter lean on this map".into(),
        Feature::RoughnessFilter => "--specular-filter roughness-map on this map".into(),
        Feature::Parallax => "heights as geometry on this map".into(),
        Feature::MaskWithDepth => "a glTF material with alphaMode MASK under --write-depth or --silhouettes".into(),
    }
    };
    match e {
        CoreError::Unsupported { feature: Feature::LeanFilter, .. } => CliError::Render(
            "--specular-filter lean or clean (or --technique lean or clean) reads the slopes of a tangent-space map of unit normals; \
             the object-space, offset-map and peercy-blinn techniques' maps have none: use --specular-filter toksvig"
                .into(),
        ),
        CoreError::Unsupported { feature: Feature::RoughnessFilter, .. } => CliError::Render(
            "--specular-filter roughness-map (or --technique roughness-map) reads the normal lengths a map of unit normals keeps in its mips' alpha; \
             the offset-map and peercy-blinn techniques' maps hold offsets or derivatives there: use --technique single-pass"
                .into(),
        ),
        e @ CoreError::RoughnessSize { .. } => CliError::Render(format!("--roughness-map: {e}")),
        CoreError::Unsupported { technique, feature: Feature::Parallax } => CliError::Render(format!(
            "--technique {technique} with heights as geometry reads a tangent-space map of unit normals at each hit; \
             the object-space, offset-map and peercy techniques' maps are made otherwise: use --technique pom (or another parallax technique) on its own"
        )),
        e @ CoreError::HeightsSize { .. } => CliError::Render(format!("--height-map: {e}")),
        CoreError::NoMinMax { technique } => CliError::Render(format!(
            "--technique {technique} walks the heights' min–max levels, and --height-map has none beside it \
             (H.minmax.png or H.minmax.ktx2 / .dds): write the heights again with `bumpmap normalmap --mips --height-out H`, or use --technique pom"
        )),
        CoreError::Unsupported { technique, feature } => CliError::Render(format!(
            "--technique {technique} cannot do {}: the paper's combiners have no room for it; use --technique single-pass",
            flag(&feature)
        )),
        CoreError::Needs { technique, requirement } => {
            CliError::Render(format!("--technique {technique} needs {requirement}"))
        }
        CoreError::GlossNeedsDecal => CliError::Render(
            "--gloss decal-alpha needs a decal (--decal FILE, or the bricks height field's own)".into(),
        ),
        // Too big for the machine is not a usage error: the same command fits elsewhere.
        CoreError::OutOfMemory(e)
        | CoreError::HeightField(bumpmap::bumpmap_math::normalmap::NormalMapError::OutOfMemory(e)) => {
            CliError::OutOfMemory(e)
        }
        // Values out of their range, however they are noticed, are usage errors.
        e @ (CoreError::OutOfRange { .. } | CoreError::EyeAtTarget { .. } | CoreError::HeightField(_)) => {
            CliError::Usage(e.to_string())
        }
        other => CliError::Render(other.to_string()),
    }
}

/// A reference error in the words of the command line.
pub fn reference_err(e: bumpmap_reference::ReferenceError) -> String {
    use bumpmap_reference::ReferenceError;
    match e {
        ReferenceError::NoSurface { .. } => format!(
            "--technique reference needs a built-in surface ({}), not a mesh",
            bumpmap::SceneKind::built_in_names()
        ),
        ReferenceError::NoHeights { .. } => {
            "--technique reference needs a height field (--height-field), not a normal map given as it is".into()
        }
        ReferenceError::SpotPattern { .. } => "--technique reference does not sample --spot-pattern".into(),
        ReferenceError::NoDisplacement { .. } => {
            "--technique reference-displaced needs heights: a height field (--height-field) or --height-map with a --normal-map".into()
        }
        other => other.to_string(),
    }
}

/// Writes `out` and, for each pass image of the frame, `OUT.NAME.png` beside it, all or none,
/// none of them replacing one of `inputs`; returns the paths written. The colour buffer's alpha
/// (s_self, not coverage) is left out.
pub fn write_frame(frame: &Frame, out: &Path, inputs: &[&Path]) -> Result<Vec<PathBuf>, CliError> {
    // The set makes a missing folder, and takes it away again if anything fails.
    let mut set = FileSet::new(inputs);
    for (name, image) in &frame.snapshots {
        let stem = out.file_stem().unwrap_or_default().to_string_lossy();
        let path = out.with_file_name(format!("{stem}.{name}.png"));
        save_png_into(&mut set, &path, image.width, image.height, PngLayout::Rgb8, &rgb(image))?;
    }
    save_png_into(&mut set, out, frame.image.width, frame.image.height, PngLayout::Rgb8, &rgb(&frame.image))?;
    Ok(set.commit()?)
}

/// An image's RGB bytes without alpha.
pub fn rgb(image: &Rgba8Image) -> Vec<u8> {
    image.texels.iter().flat_map(|&[r, g, b, _]| [r, g, b]).collect()
}
