//! `bumpmap render`: the flags made into the library's [`FrameRequest`], prepared and drawn by
//! `bumpmap::frame` on the renderer the backend names, written as a PNG (and, with `--passes`,
//! one PNG per pass).
//!
//! The library refuses what a technique cannot do with typed errors and says what it noted as
//! data; this module is where they get the names of the flags that caused them ([`frame_err`],
//! [`core_err`], [`lib_err`], [`frame_notes`]).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use bumpmap::bumpmap_core::Feature;
use bumpmap::bumpmap_math::buffer::OutOfMemory;
use bumpmap::frame::{DepthNote, FrameError, SceneSize};
use bumpmap::options::SceneOptions;
use bumpmap::{BackendChoice, CoreError, Renderer, Rgba8Image};
use bumpmap_io::atomic::{FileSet, ensure_not_input};
use bumpmap_io::image_file::{PngLayout, save_png_into};

use crate::args::RenderArgs;
use crate::error::CliError;

pub use bumpmap::frame::{DEFAULT_SIZE, Frame, FrameRequest, PreparedFrame};

/// The frame `render`'s flags ask for.
pub fn frame_request(args: &RenderArgs) -> Result<FrameRequest, CliError> {
    let size = match (args.width, args.height) {
        (Some(w), Some(h)) => (w, h),
        _ => (args.size, args.size),
    };
    Ok(FrameRequest {
        options: crate::setup::scene_options(&args.setup)?,
        size,
        backend: args.setup.backend.backend,
        passes: args.passes,
    })
}

/// Runs `bumpmap render`.
pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    let request = frame_request(args)?;
    let named = request.options.named_inputs();
    ensure_not_input(&args.output, &named.iter().map(PathBuf::as_path).collect::<Vec<_>>())?;
    let drawn = draw_request(&request, &args.output, &crate::report::Progress::Bar, &crate::setup::Given::default())?;
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

/// Sets up and prepares what `request` describes ([`bumpmap::frame::prepare_frame`]), with the
/// inputs `given` in memory in place of their options' files; what it refuses, in the flags'
/// words.
pub fn prepare_request(request: &FrameRequest, given: &crate::setup::Given) -> Result<PreparedFrame, CliError> {
    bumpmap::frame::prepare_frame(request, given).map_err(|e| frame_err(e, &request.options, None))
}

/// What setting `prepared` up noted and what its depth did, a line each as stderr shows them
/// (a warning's line starts `warning: `).
pub fn frame_notes(prepared: &PreparedFrame) -> Vec<String> {
    let setup = prepared.set_up.notes.iter().map(crate::setup::note_line);
    setup.chain(prepared.depth_notes.iter().map(depth_line)).collect()
}

/// The file or preset the bumps come from, as messages name it.
fn bumps_name(options: &SceneOptions) -> Option<String> {
    match &options.height_field {
        Some(source) => Some(source.to_string()),
        None => options.normal_map.as_ref().map(|p| p.display().to_string()),
    }
}

/// Draws what `request` describes: the scene set up, the technique prepared, the frame drawn on
/// its backend (the reference always on the CPU, its tiles' progress shown as `progress` says)
/// and refused if black, `output` named in that refusal. The notes the assets bring (what a
/// glTF's material gave) go to stderr.
pub fn draw_request(
    request: &FrameRequest,
    output: &Path,
    progress: &crate::report::Progress,
    given: &crate::setup::Given,
) -> Result<Drawn, CliError> {
    let name = request.options.technique.technique;
    let prepared = prepare_request(request, given)?;
    for note in frame_notes(&prepared) {
        crate::report::setup_line(&note);
    }
    let mut renderer = if name.is_reference() {
        // The reference runs on the CPU whatever the backend; no device need open for it.
        let mut r = Renderer::new(request.backend_for()).map_err(lib_err)?;
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
        renderer(request.backend_for())?
    };
    let frame = bumpmap::frame::draw_frame(&mut renderer, &prepared, request.passes)
        .map_err(|e| frame_err(e, &request.options, Some(output)))?;
    let by = if name.is_reference() {
        format!("reference, {} samples per pixel", prepared.set_up.options.reference.samples_per_pixel)
    } else {
        format!("{name}, {}", renderer.describe())
    };
    Ok(Drawn { frame, by, inputs: prepared.set_up.inputs })
}

/// A frame's refusal in the command line's words: the flags that caused it, the inputs that
/// made a scene too big, and `output` where a black image was not written.
pub fn frame_err(e: FrameError, options: &SceneOptions, output: Option<&Path>) -> CliError {
    match e {
        FrameError::Passes { technique } => CliError::Usage(format!(
            "--passes shows the three passes of --technique kilgard; {technique} draws {}",
            if technique.is_reference() { "no passes (it samples the exact surface)" } else { "one pass per light" }
        )),
        FrameError::SetUp(e) => crate::setup::setup_err(e),
        FrameError::TooBig { size, source } => too_big(source, size, bumps_name(options).as_deref()),
        FrameError::Black => not_drawn(output.unwrap_or(Path::new("the frame"))),
        FrameError::Library(e) => lib_err(e),
    }
}

/// A depth note as stderr shows it, naming the flags.
fn depth_line(note: &DepthNote) -> String {
    match *note {
        DepthNote::Clamped { asked, used } => format!(
            "note: --depth {asked} would carve past the surface's bounds; drawn at {used} (a quarter of a wall's or floor's shorter side, half a torus's tube radius or a sphere's radius, a quarter of the patch's narrower side)"
        ),
        DepthNote::Slopes { depth, texels, side, scale } => format!(
            "note: --depth {depth} is {texels:.3} texels of this surface's mean texel side ({side:.5}); the normal map keeps --bump-scale {scale}'s slopes: add --bump-scale {texels:.3} for the slopes of the geometry"
        ),
    }
}

/// Refuses `output` for a frame that came out black (`black`: no pixel has any colour): nothing
/// in view was drawn or lit, and a black PNG with exit status 0 would pass for a result. Judged
/// from the image, so it holds for every backend and the reference alike; the causes are named,
/// since the image cannot tell them apart.
pub fn ensure_drawn(black: bool, output: &Path) -> Result<(), CliError> {
    if black { Err(not_drawn(output)) } else { Ok(()) }
}

/// [`ensure_drawn`]'s refusal.
fn not_drawn(output: &Path) -> CliError {
    CliError::Path {
        path: output.to_path_buf(),
        reason: "not written: the image is black (no pixel was drawn or lit). The object may be out of \
                 view (--eye, --target, --up, --fov), too small or too flat to cover a pixel (--tessellation, \
                 --torus-radii, the mesh), or facing away from the eye or the light (--light, --ambient)"
            .into(),
    }
}

/// An out-of-memory error with the sizes that caused it: the bump texture's (and `bumps`, the
/// file or preset it came from) and the tessellation's: what a user can make smaller.
pub(crate) fn too_big(oom: OutOfMemory, size: SceneSize, bumps: Option<&str>) -> CliError {
    let (w, h) = size.bumps;
    let from = bumps.map(|b| format!(" from {b}")).unwrap_or_default();
    let mesh = match size.tessellation {
        Some((u, v)) => format!(", tessellation {u}x{v}"),
        None => String::new(),
    };
    let decal = match size.decal {
        Some((dw, dh)) => format!(", decal {dw}x{dh}"),
        None => String::new(),
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
