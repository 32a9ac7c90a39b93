//! The front door's errors in words (`bumpmap::Error`, the core's, the reference's): the flag
//! the user typed that caused each. Every other module words its own library's errors through
//! these.

use bumpmap::CoreError;
use bumpmap::bumpmap_core::Feature;

use crate::Error;

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
        Feature::PerPixelDecode => "--decode mikktspace (this lights in the per-vertex tangent frame, as --decode per-vertex does)".into(),
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
        Feature::DetailMap => "--detail-map on this map".into(),
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
        CoreError::Unsupported { technique, feature: Feature::DetailMap } => Error::Render(format!(
            "--detail-map is laid over a tangent-space map of unit normals, and --technique {technique}'s map is made otherwise \
             (object space, offsets or derivatives): use --technique single-pass, or blend the detail in first with `bumpmap blend`"
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
