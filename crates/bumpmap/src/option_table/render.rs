//! `render`'s options: what is drawn and how ([`SCENE`]: the scene, camera, lights, material,
//! technique, heights and backend, which `bench render` and `view` take too) and the frame's
//! size ([`FRAME`]); [`render`] is both, in `--help`'s order.

use bumpmap_core::detail::MAX_DETAIL_REPEAT;
use bumpmap_core::parallax::MAX_LAYERS;
use bumpmap_core::technique::SelfShadow;

use super::{Access, Kind, Opt, Value};
use crate::frame::{FrameRequest, MAX_SIDE};
use crate::options::{MAX_CUBE_SIZE, MAX_SAMPLES_PER_PIXEL, MAX_TESSELLATION};

/// A row of `render`'s table.
type Row = Opt<FrameRequest>;

const SCENE_: &str = "Scene";
const CAMERA: &str = "Camera";
const LIGHTS: &str = "Lights";
const MATERIAL: &str = "Material";
const TECHNIQUE: &str = "Technique";
const HEIGHTS: &str = "Heights as geometry (parallax, steep-parallax, pom, relief, height-exact, reference-displaced)";
const DETAIL: &str = "Detail normal map (single-pass and its variants, the specular filters, heights as geometry)";
const BACKEND: &str = "Backend";
/// The frame's options are listed with the command's own (no section of their own).
const COMMAND: &str = "";

/// A positive, finite depth.
fn depth(v: &Value) -> Result<(), String> {
    match v {
        Value::Number(d) if d.is_finite() && *d > 0.0 => Ok(()),
        _ => Err(format!("'{v}' is not a depth: give a positive number of the scene's units")),
    }
}

/// Two counts of quads, each in 1..=[`MAX_TESSELLATION`].
fn tessellation(v: &Value) -> Result<(), String> {
    let Value::Numbers(counts) = v else { return Ok(()) };
    for c in counts {
        if !(c.fract() == 0.0 && *c >= 1.0 && *c <= MAX_TESSELLATION as f32) {
            return Err(format!("'{c}' is not a count in 1..={MAX_TESSELLATION}"));
        }
    }
    Ok(())
}

/// Two repeats, neither 0 (a map made for the surface is addressed with 1/repeat) and neither
/// beyond ±1024 (texture coordinates stay well inside single precision's whole numbers).
fn repeat(v: &Value) -> Result<(), String> {
    let Value::Numbers(r) = v else { return Ok(()) };
    if r.iter().all(|&x| x != 0.0 && x.abs() <= 1024.0) {
        Ok(())
    } else {
        Err(format!("repeats must be non-zero and within ±1024, got '{v}'"))
    }
}

/// A detail's repeat: positive, at most [`MAX_DETAIL_REPEAT`].
fn detail_repeat(v: &Value) -> Result<(), String> {
    match v {
        Value::Number(r) if *r > 0.0 && *r <= MAX_DETAIL_REPEAT => Ok(()),
        _ => Err(format!("'{v}' is not a repeat: give a number in (0, {MAX_DETAIL_REPEAT}]")),
    }
}

/// An image side in 1..=[`MAX_SIDE`] pixels.
fn side(v: &Value) -> Result<(), String> {
    match v {
        Value::Whole(n) if (1..=MAX_SIDE as u64).contains(n) => Ok(()),
        _ => Err(format!("'{v}' is not a size in 1..={MAX_SIDE} pixels")),
    }
}

fn side_kind() -> Kind {
    Kind::Whole { min: 1, max: MAX_SIDE as u64 }
}

fn whole(v: Value) -> Result<usize, String> {
    match v {
        Value::Whole(n) => Ok(n as usize),
        other => Err(format!("{other} is not a size")),
    }
}

/// What is drawn and how: the options `render`, `bench render` and `view` share.
pub static SCENE: &[Opt<FrameRequest>] = &[
    Row::new("scene", SCENE_, "torus, wall, floor, wall-floor, patch, sphere, or mesh:FILE (.obj, .gltf, .glb: drawn in its own units and axes, with a glTF's own normal map and base colour unless the options below replace them)", |r| &mut r.options.scene),
    Row::new("height-field", SCENE_, "Height field the normal map is made from: image file or preset (bricks, pinwheel, dimples, noise:SEED[@SIZE]) [default: bricks, or a glTF material's normal map]", |r| &mut r.options.height_field).conflicts(&["normal-map"]),
    Row::new("normal-map", SCENE_, "A normal map to draw as it is (PNG at 8 or 16 bits, other images, DDS or KTX2 with the mip levels it carries, BC5/BC7 included); without stored mips the chain is made with the length in alpha", |r| &mut r.options.normal_map),
    Row::new("rebuild-mips", SCENE_, "Make --normal-map's smaller levels from its level 0, with the length in alpha, instead of using the file's own (for levels another tool renormalized, which the length factor and --specular-filter toksvig get nothing from)", |r| &mut r.options.rebuild_mips).requires(&["normal-map"]),
    Row::word("y-convention", SCENE_, "Which way --normal-map's green points as the image is displayed: opengl (alias y-up: glTF, Blender, Unity, and what `bumpmap normalmap` writes) or directx (alias y-down: Unreal, 3ds Max)", |r| &mut r.options.y_convention).requires(&["normal-map"]),
    Row::new("bump-scale", SCENE_, "Bump strength: a height field's scale (the height of a unit step, in texels) [default: 4]; for a normal map (--normal-map or a glTF's) it multiplies the slopes as glTF's normalTexture.scale does [default: 1, or the material's]", |r| &mut r.options.bump_scale),
    Row::new("decal", SCENE_, "Decal image, or \"none\" [default: a glTF material's base colour; the brick decal for the bricks preset; none otherwise]", |r| &mut r.options.decal),
    Row::new("torus-radii", SCENE_, "Torus radii R,r (hole centre to tube centre, tube)", |r| &mut r.options.torus_radii),
    Row::new("tessellation", SCENE_, "Quads along u and v, each at most 2048 (default: the scene's; torus 128,64)", |r| &mut r.options.tessellation).check(tessellation),
    Row::new("repeat", SCENE_, "Texture repeats along s and t (default: the scene's; torus 6,2); negative mirrors; each non-zero, within ±1024", |r| &mut r.options.repeat).check(repeat),
    Row::new("allow-outside-paths", SCENE_, "mesh: glTF only: let buffer and image URIs lead outside the glTF's folder (absolute paths, ..); off by default, so a downloaded glTF cannot make bumpmap read other files", |r| &mut r.options.allow_outside_paths),
    Row::word("obj-v", SCENE_, "OBJ only: flip (v = 0 at the image's bottom, the OBJ convention) or keep the file's v", |r| &mut r.options.obj_texcoords),
    Row::new("eye", CAMERA, "Eye position [default: the scene's; for a mesh, in front of its bounds (glTF's +Z) and above, far enough to see all of it]", |r| &mut r.options.camera.eye),
    Row::new("target", CAMERA, "Point looked at [default: the scene's; for a mesh, the centre of its bounds]", |r| &mut r.options.camera.target),
    Row::new("up", CAMERA, "The world's up direction [default: +Z for torus, patch and sphere; +Y for wall, floor and meshes, as glTF and OBJ have it]; looking straight along it takes another up rather than drawing nothing", |r| &mut r.options.camera.up),
    Row::new("fov", CAMERA, "Vertical field of view in degrees", |r| &mut r.options.camera.fov_y_degrees),
    Row::word("viewer", CAMERA, "Local or infinite viewer for the half-angle vector", |r| &mut r.options.camera.viewer),
    Row::new("light", LIGHTS, "A light, repeatable: [dir:]X,Y,Z[@R,G,B] (default: the scene's)", |r| &mut r.options.lights.lights).value_name("LIGHTS"),
    Row::new("attenuation", LIGHTS, "single-pass: attenuation with distance: C,L,Q (1/(C + L·d + Q·d²)), exp:D or exp2:D", |r| &mut r.options.lights.attenuation),
    Row::new("spot", LIGHTS, "single-pass: make every positional light a spotlight aimed along DX,DY,DZ", |r| &mut r.options.lights.spot),
    Row::new("spot-cutoff", LIGHTS, "Spotlight cone half-angle in degrees, in (0, 90)", |r| &mut r.options.lights.spot_cutoff_degrees).requires(&["spot"]),
    Row::new("spot-exponent", LIGHTS, "Spotlight fall-off exponent (cos^E), ≥ 0", |r| &mut r.options.lights.spot_exponent).requires(&["spot"]),
    Row::new("spot-pattern", LIGHTS, "Pattern projected by the spotlight: an image or a height-field preset (e.g. pinwheel); sampled at up to 2048 a side (a larger one is box-halved)", |r| &mut r.options.lights.spot_pattern).requires(&["spot"]),
    Row::new("ambient", MATERIAL, "Ambient intensity I_ambient", |r| &mut r.options.material.ambient),
    Row::new("diffuse", MATERIAL, "Diffuse coefficient k_diffuse", |r| &mut r.options.material.diffuse),
    Row::new("specular", MATERIAL, "Specular coefficient (0 drops the specular pass)", |r| &mut r.options.material.specular),
    Row::new("shininess", MATERIAL, "Specular exponent (kilgard's combiners are fixed at 8)", |r| &mut r.options.material.shininess),
    Row::new("gloss", MATERIAL, "single-pass: gloss map scaling the specular: decal-alpha, bricks (shiny bricks, dull mortar) or an image (red channel, same size as the decal)", |r| &mut r.options.material.gloss),
    Row::new("roughness-map", MATERIAL, "With --technique roughness-map (or --specular-filter roughness-map): read this roughness map instead of making one from the normal map's mips — `normalmap --mips --roughness-out`'s file (.ktx2 or .dds with every level, or R.png with R.mip1.png … beside it), at the normal map's size. Its roughness sets the exponent; --shininess stays the brightness of a texel of that roughness", |r| &mut r.options.material.roughness_map).value_name("FILE"),
    Row::word("roughness-layout", MATERIAL, "Channels --roughness-map holds its roughness in, as `normalmap --roughness-layout` writes them", |r| &mut r.options.material.roughness_layout).requires(&["roughness-map"]),
    Row::word("technique", TECHNIQUE, "Any technique of the catalogue (below); one that cannot draw the scene says why", |r| &mut r.options.technique.technique),
    Row::new("spp", TECHNIQUE, "reference: samples per pixel (stratified); the image converges as it grows", |r| &mut r.options.technique.samples_per_pixel).range(1, MAX_SAMPLES_PER_PIXEL as u64),
    Row::new("seed", TECHNIQUE, "reference: which sample pattern (each pixel's rotation of the stratified sequence; 0 is the usual one): another seed gives an independent image of the same scene, and two seeds' difference shows the noise left", |r| &mut r.options.technique.seed),
    Row::maybe_word("filter", TECHNIQUE, "Texture filtering of the normal map, decal and every other map; given, it replaces a glTF material's sampler's filters (its wrap modes stay) [default: the material's filters where its sampler names them, else trilinear]", |r| &mut r.options.technique.filter),
    Row::with("no-self-shadow", TECHNIQUE, "Leave out Eq. 12's self-shadowing term (Figure 14, left)", Access::Custom {
        kind: || Kind::Flag,
        get: |_| None,
        set: |r, v| {
            if v == Value::Flag(true) {
                r.options.technique.self_shadow = SelfShadow::Off;
            }
            Ok(())
        },
    }).conflicts(&["self-shadow"]),
    Row::word("precision", TECHNIQUE, "kilgard: register-combiner arithmetic", |r| &mut r.options.technique.precision),
    Row::word("specular-mode", TECHNIQUE, "kilgard: specular form of the third pass", |r| &mut r.options.technique.specular_mode),
    Row::new("cube-size", TECHNIQUE, "Face size of the normalization cube map", |r| &mut r.options.technique.cube_size).range(1, MAX_CUBE_SIZE as u64),
    Row::maybe_word("normalize", TECHNIQUE, "single-pass and its variants: how L and H are renormalized per fragment [default: math; the cube map for single-pass-cube and kilgard]", |r| &mut r.options.technique.normalize),
    Row::word("self-shadow", TECHNIQUE, "single-pass: the self-shadowing factor (kilgard: see --no-self-shadow)", |r| &mut r.options.technique.self_shadow),
    Row::maybe_word("decode", TECHNIQUE, "How a tangent-space normal map becomes the shading normal: mikktspace decodes per pixel in the interpolated frame as MikkTSpace's header says (what Blender, Substance, glTF viewers and `bumpmap bake` make maps for); per-vertex lights in each vertex's frame, as the papers do. kilgard, emboss, heights as geometry, lean, clean, detail maps and Peercy's surface maps light in the per-vertex frame [default: mikktspace on meshes where the technique can, per-vertex on the built-in surfaces and elsewhere]", |r| &mut r.options.technique.decode),
    Row::word("half-angle", TECHNIQUE, "single-pass: per-vertex or per-fragment half-angle vector", |r| &mut r.options.technique.half_angle),
    Row::word("specular-shadow", TECHNIQUE, "single-pass: geometric self-shadowing of the specular term", |r| &mut r.options.technique.specular_shadow),
    Row::word("specular-filter", TECHNIQUE, "single-pass: how the specular lobe answers the bumps a pixel averages (toksvig: the exponent from the mip chain's |N|; roughness-map: from a roughness map made of it, or --roughness-map FILE; lean and clean: the slopes' moments; a distant bumpy surface's highlight widens and dims; `--technique toksvig` or `lean` sets it)", |r| &mut r.options.technique.specular_filter),
    Row::new("depth", HEIGHTS, "How deep the heights carve below the surface, in the scene's units per unit of height (heights are 1 on the surface, 0 at this depth) [default: what --bump-scale stands for: that many texels of the surface's mean texel side, so the normal map's slopes are the geometry's]. Clamped to a quarter of a wall's or floor's shorter side, half a torus's tube radius or a sphere's radius, a quarter of the patch's narrower side", |r| &mut r.options.heights.depth).check(depth),
    Row::new("height-map", HEIGHTS, "The heights as a file, the normal map's size: what `normalmap --height-out` writes (H.png with H.mip1.png … and H.minmax.png …, or H.ktx2 / H.dds with H.minmax.ktx2 / .dds beside it); what a --normal-map needs for these techniques. height-exact needs the min–max files", |r| &mut r.options.heights.height_map).value_name("FILE"),
    Row::new("horizon-map", HEIGHTS, "The heights' horizon map as a file, the normal map's size: what `normalmap --horizon-out` writes (H.png and H.dirs4-7.png with their .mipK.png levels, or H.ktx2 / H.dds and H.dirs4-7 beside it), read by --parallax-shadow horizon, --technique horizon and --ambient-occlusion instead of the one made from the heights", |r| &mut r.options.heights.horizon_map).value_name("FILE"),
    Row::new("layers", HEIGHTS, "Layers of a march: steep-parallax and relief step through this many, pom through a quarter of it looking straight on up to all of it at grazing angles; a shadow march steps this many over the depth", |r| &mut r.options.heights.layers).range(1, MAX_LAYERS as u64),
    Row::word("parallax-shadow", HEIGHTS, "Self-shadowing by the heights (soft is Tatarchuk's engine-style penumbra). height-exact and reference-displaced cast exact shadow rays for hard and soft alike", |r| &mut r.options.heights.parallax_shadow),
    Row::new("silhouettes", HEIGHTS, "On curved surfaces, drop pixels whose ray leaves the surface without meeting the heights, so bumps cut the silhouette (the surface's curvature bends the ray, Oliveira & Policarpo 2005)", |r| &mut r.options.heights.silhouettes),
    Row::new("write-depth", HEIGHTS, "Write the depth where the ray met the heights instead of the polygon's, so two bumpy surfaces intersect where their bumps do", |r| &mut r.options.heights.write_depth),
    Row::maybe_word("hit-normal", HEIGHTS, "The normal the marches' hit is shaded with: the normal map's there, or the heights' own (their C1 interpolant at level 0, the surface the reference draws); compare's parallax study measures both: up close the heights' brings every march much nearer the displaced reference, for about a quarter more time a frame on the CPU, but unfiltered it sparkles where the heights are minified [default: heights for height-exact, map for the others]", |r| &mut r.options.heights.hit_normal),
    Row::new("ambient-occlusion", HEIGHTS, "Multiply the ambient term by the ambient occlusion of the heights' horizon map (Sloan & Cohen 2000): the share of the sky each point sees past the bumps around it, at the depth drawn", |r| &mut r.options.heights.ambient_occlusion),
    Row::new("detail-map", DETAIL, "A second normal map laid over the normal map per pixel, tiling (a fabric weave, pores, scratches): read as --normal-map reads files, with its own mip levels, at 8 bits a channel as every texture is. kilgard, emboss and the reference refuse it: blend it into the normal map first with `bumpmap blend`", |r| &mut r.options.detail.map).value_name("FILE"),
    Row::new("detail-repeat", DETAIL, "How many times the detail repeats over one repeat of the normal map, each way", |r| &mut r.options.detail.repeat).check(detail_repeat).requires(&["detail-map"]),
    Row::word("detail-method", DETAIL, "How the detail is laid over the normal map (rnm is exact for a detail draped over the bumps, partial-derivative for heights that add; compare's detail study measures every method)", |r| &mut r.options.detail.method).requires(&["detail-map"]),
    Row::new("detail-strength", DETAIL, "What the detail's slopes are multiplied by (0: no detail, 1: as stored)", |r| &mut r.options.detail.strength).check(super::blend::strength).requires(&["detail-map"]),
    Row::maybe_word("detail-y-convention", DETAIL, "Which way --detail-map's green points, when not as --y-convention says: it is flipped to the renderer's (opengl) and said [default: --y-convention's]", |r| &mut r.options.detail.y_convention).requires(&["detail-map"]),
    Row::word("backend", BACKEND, "cpu: the emulated GeForce on all cores; gpu: wgpu (Vulkan, Metal, DX12 or GL; on a machine without a GPU, Mesa's lavapipe: Debian's mesa-vulkan-drivers); auto: the GPU when an adapter exists, else the CPU (and says why). The reference always runs on the CPU", |r| &mut r.backend),
];

/// The frame's size: a square's side, or a width and a height.
pub static FRAME: &[Opt<FrameRequest>] = &[
    Row::with(
        "size",
        COMMAND,
        "Square image size (pixels)",
        Access::Custom {
            kind: side_kind,
            get: |r| Some(Value::Whole(r.size.0 as u64)),
            set: |r, v| {
                let n = whole(v)?;
                r.size = (n, n);
                Ok(())
            },
        },
    )
    .check(side)
    .conflicts(&["width", "height"]),
    Row::with(
        "width",
        COMMAND,
        "Image width in pixels (with --height, instead of --size)",
        Access::Custom {
            kind: side_kind,
            get: |_| None,
            set: |r, v| {
                r.size.0 = whole(v)?;
                Ok(())
            },
        },
    )
    .check(side)
    .requires(&["height"]),
    Row::with(
        "height",
        COMMAND,
        "Image height in pixels (with --width)",
        Access::Custom {
            kind: side_kind,
            get: |_| None,
            set: |r, v| {
                r.size.1 = whole(v)?;
                Ok(())
            },
        },
    )
    .check(side)
    .requires(&["width"]),
];

/// Every option of `render` the library reads: [`SCENE`], then [`FRAME`], in `--help`'s order.
pub fn render() -> impl Iterator<Item = &'static Opt<FrameRequest>> {
    SCENE.iter().chain(FRAME)
}
