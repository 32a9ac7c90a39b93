//! A frame's refusals and notes ([`bumpmap::frame`], the renderer, the core's and the
//! reference's errors), named by the flags that caused them.

use std::path::Path;

use bumpmap::bumpmap_core::Feature;
use bumpmap::bumpmap_math::buffer::OutOfMemory;
use bumpmap::frame::{DepthNote, FrameError, PreparedFrame, SceneSize};
use bumpmap::options::SceneOptions;
use bumpmap::{CoreError, Renderer};

use crate::Error;

/// The note for a renderer that `--backend auto` opened on the CPU, `why` being the renderer's
/// [`fallback_reason`](bumpmap::Renderer::fallback_reason).
pub fn on_the_cpu(why: &str) -> String {
    format!("--backend auto: drawing on the CPU ({why})")
}

/// Says why `renderer` draws on the CPU when `--backend auto` opened it there, as a note
/// ([`crate::report::note`]); nothing otherwise.
pub fn note_fallback(renderer: &Renderer) {
    if let Some(why) = renderer.fallback_reason() {
        crate::report::note(on_the_cpu(why));
    }
}

/// What setting `prepared` up noted and what its depth did, a line each as stderr shows them
/// (a warning's line starts `warning: `).
pub fn frame_notes(prepared: &PreparedFrame) -> Vec<String> {
    let setup = prepared.set_up.notes.iter().map(crate::setup::note_line);
    setup.chain(prepared.depth_notes.iter().map(depth_line)).collect()
}

/// Says [`frame_notes`] (each warning as a warning, the rest as notes: [`crate::report`]) and
/// returns them.
pub fn say_frame_notes(prepared: &PreparedFrame) -> Vec<String> {
    let notes = frame_notes(prepared);
    for note in &notes {
        crate::report::setup_line(note);
    }
    notes
}

/// The file or preset the bumps come from, as messages name it.
fn bumps_name(options: &SceneOptions) -> Option<String> {
    match &options.height_field {
        Some(source) => Some(source.to_string()),
        None => options.normal_map.as_ref().map(|p| p.display().to_string()),
    }
}

/// A frame's refusal in the command line's words: the flags that caused it, the inputs that
/// made a scene too big, and `output` where a black image was not written.
pub fn frame_err(e: FrameError, options: &SceneOptions, output: Option<&Path>) -> Error {
    match e {
        FrameError::Passes { technique } => Error::Usage(format!(
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
pub fn ensure_drawn(black: bool, output: &Path) -> Result<(), Error> {
    if black { Err(not_drawn(output)) } else { Ok(()) }
}

/// [`ensure_drawn`]'s refusal.
fn not_drawn(output: &Path) -> Error {
    Error::Path {
        path: output.to_path_buf(),
        reason: "not written: the image is black (no pixel was drawn or lit). The object may be out of \
                 view (--eye, --target, --up, --fov), too small or too flat to cover a pixel (--tessellation, \
                 --torus-radii, the mesh), or facing away from the eye or the light (--light, --ambient)"
            .into(),
    }
}

/// An out-of-memory error with the sizes that caused it: the bump texture's (and `bumps`, the
/// file or preset it came from) and the tessellation's: what a user can make smaller.
pub fn too_big(oom: OutOfMemory, size: SceneSize, bumps: Option<&str>) -> Error {
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
    Error::Render(format!(
        "this scene (bumps {w}x{h}{from}{decal}{mesh}) is too big for the memory this process may use: {oom}. \
         The README's \"Memory\" section gives what the largest inputs need; a smaller --height-field, \
         --normal-map, --decal, --gloss or --tessellation needs less"
    ))
}

/// A front-door error in the words of the command line.
pub fn lib_err(e: bumpmap::Error) -> Error {
    match e {
        bumpmap::Error::Core(e) | bumpmap::Error::Cpu(bumpmap_cpu::CpuError::Core(e)) => core_err(e),
        bumpmap::Error::Cpu(bumpmap_cpu::CpuError::OutOfMemory(e)) => Error::OutOfMemory(e),
        bumpmap::Error::Io(e) => Error::Io(e),
        bumpmap::Error::Gpu(bumpmap_gpu::GpuError::NoAdapter(reason)) => Error::NoDevice(format!(
            "no GPU adapter found ({reason}): install a Vulkan driver (on Debian without a GPU, \
             `apt-get install mesa-vulkan-drivers libvulkan1` gives Mesa's lavapipe) or use --backend cpu"
        )),
        bumpmap::Error::Reference(e) => Error::Render(reference_err(e)),
        // A size out of range is a value out of range, like any other.
        bumpmap::Error::Cpu(e @ bumpmap_cpu::CpuError::FramebufferSize { .. }) => {
            Error::Usage(format!("{e} (--size, or --width and --height)"))
        }
        other => Error::Render(other.to_string()),
    }
}

/// A library error in the words of the command line: what the user typed that caused it.
pub fn core_err(e: CoreError) -> Error {
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
        CoreError::Unsupported { feature: Feature::LeanFilter, .. } => Error::Render(
            "--specular-filter lean or clean (or --technique lean or clean) reads the slopes of a tangent-space map of unit normals; \
             the object-space, offset-map and peercy-blinn techniques' maps have none: use --specular-filter toksvig"
                .into(),
        ),
        CoreError::Unsupported { feature: Feature::RoughnessFilter, .. } => Error::Render(
            "--specular-filter roughness-map (or --technique roughness-map) reads the normal lengths a map of unit normals keeps in its mips' alpha; \
             the offset-map and peercy-blinn techniques' maps hold offsets or derivatives there: use --technique single-pass"
                .into(),
        ),
        e @ CoreError::RoughnessSize { .. } => Error::Render(format!("--roughness-map: {e}")),
        CoreError::Unsupported { technique, feature: Feature::Parallax } => Error::Render(format!(
            "--technique {technique} with heights as geometry reads a tangent-space map of unit normals at each hit; \
             the object-space, offset-map and peercy techniques' maps are made otherwise: use --technique pom (or another parallax technique) on its own"
        )),
        e @ CoreError::HeightsSize { .. } => Error::Render(format!("--height-map: {e}")),
        CoreError::NoMinMax { technique } => Error::Render(format!(
            "--technique {technique} walks the heights' min–max levels, and --height-map has none beside it \
             (H.minmax.png or H.minmax.ktx2 / .dds): write the heights again with `bumpmap normalmap --mips --height-out H`, or use --technique pom"
        )),
        CoreError::Unsupported { technique, feature } => Error::Render(format!(
            "--technique {technique} cannot do {}: the paper's combiners have no room for it; use --technique single-pass",
            flag(&feature)
        )),
        CoreError::Needs { technique, requirement } => {
            Error::Render(format!("--technique {technique} needs {requirement}"))
        }
        CoreError::GlossNeedsDecal => Error::Render(
            "--gloss decal-alpha needs a decal (--decal FILE, or the bricks height field's own)".into(),
        ),
        // Too big for the machine is not a usage error: the same command fits elsewhere.
        CoreError::OutOfMemory(e)
        | CoreError::HeightField(bumpmap::bumpmap_math::normalmap::NormalMapError::OutOfMemory(e)) => {
            Error::OutOfMemory(e)
        }
        // Values out of their range, however they are noticed, are usage errors.
        e @ (CoreError::OutOfRange { .. } | CoreError::EyeAtTarget { .. } | CoreError::HeightField(_)) => {
            Error::Usage(e.to_string())
        }
        other => Error::Render(other.to_string()),
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
