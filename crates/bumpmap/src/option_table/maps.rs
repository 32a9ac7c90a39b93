//! The options of the commands that make maps: how heights become normals and what else is
//! made ([`MAPS`], `normalmap`'s and Python's map functions'), which channel holds the heights
//! ([`CHANNEL`]), a texture file's texel format ([`FORMAT`]), tangent frames ([`TANGENTS`]), and
//! heights integrated back from a normal map ([`HEIGHTS`]).

use bumpmap_io::Channel;
use bumpmap_io::texture_file::TextureFormat;
use bumpmap_math::tangent::TangentOptions;

use super::{Opt, Value};
use crate::heights::HeightChoices;
use crate::maps::MapOptions;

/// The options of a command, listed with its own (no section of their own).
const COMMAND: &str = "";

/// 8 or 16 bits a channel.
pub(super) fn bits(v: &Value) -> Result<(), String> {
    match v {
        Value::Whole(8 | 16) => Ok(()),
        _ => Err(format!("'{v}' is not 8 or 16")),
    }
}

/// A number in [0, 1].
fn unit(v: &Value) -> Result<(), String> {
    match v {
        Value::Number(x) if (0.0..=1.0).contains(x) => Ok(()),
        _ => Err(format!("'{v}' is not in [0, 1]")),
    }
}

type MapRow = Opt<MapOptions>;

/// How heights become normals, and the chain, roughness and bits of what is made.
pub static MAPS: &[Opt<MapOptions>] = &[
    MapRow::word("mip-mode", COMMAND, "What the smaller levels store", |m| &mut m.mip_mode),
    MapRow::new("bits", COMMAND, "Bits per channel of uncompressed outputs: 8, or 16 (16-bit PNG, R16G16B16A16_UNORM in .dds and .ktx2)", |m| &mut m.bits).check(bits),
    MapRow::word("kernel", COMMAND, "Finite-difference kernel for ∂F/∂u and ∂F/∂v", |m| &mut m.normals.kernel),
    MapRow::new("scale", COMMAND, "Bump height: heights are in [0,1], derivatives per texel, n ∝ (−scale·∂F/∂u, −scale·∂F/∂v, 1)", |m| &mut m.normals.scale),
    MapRow::word("wrap", COMMAND, "What the kernel reads beyond the edges", |m| &mut m.normals.wrap),
    MapRow::word("encoding", COMMAND, "Byte encoding of the normal's components", |m| &mut m.normals.encoding),
    MapRow::word("y-convention", COMMAND, "Which way green points in the file, as the image is displayed: opengl (alias y-up: glTF, Blender, Unity) or directx (alias y-down: Unreal)", |m| &mut m.normals.y_convention),
    MapRow::new("roughness", COMMAND, "The surface's own perceptual roughness (glTF's roughnessFactor), in [0, 1]: level 0's value wherever its normal is one", |m| &mut m.roughness).check(unit),
    MapRow::word("roughness-layout", COMMAND, "Channels of --roughness-out: gray (roughness in RGB), gloss (1 − roughness in RGB), gltf (glTF's metallicRoughness and Unreal's ORM: G roughness, B metallic 0, R 1, or with --ao-out the occlusion, every level its mean), unity (Unity's metallic-smoothness: R metallic 0, A smoothness)", |m| &mut m.roughness_layout),
];

/// Which channel of a colour image holds the heights.
pub static CHANNEL: &[Opt<Channel>] = &[Opt::word(
    "channel",
    COMMAND,
    "Which channel of a colour image holds the heights (greyscale images: their grey value)",
    |c| c,
)];

/// A texture file's texel format.
pub static FORMAT: &[Opt<TextureFormat>] = &[Opt::word(
    "format",
    COMMAND,
    "Texel format of .dds and .ktx2 outputs: rgba8 (uncompressed), bc5 (red and green, Z rebuilt in the shader; drops the length factor in alpha), bc7 (all four channels). texconv's names work too (BC5_UNORM, …); a folder run with bc5/bc7 writes .dds files",
    |f| f,
)];

type TangentRow = Opt<TangentOptions>;

/// How tangent frames are made.
pub static TANGENTS: &[Opt<TangentOptions>] = &[
    TangentRow::word("mode", COMMAND, "Which algorithm makes the tangents", |t| &mut t.mode),
    TangentRow::new(
        "split-angle",
        COMMAND,
        "Ours: tangents further apart than this many degrees split a vertex",
        |t| &mut t.split_angle_degrees,
    ),
];

type HeightRow = Opt<HeightChoices>;

/// How a normal map's slopes are integrated back into heights.
pub static HEIGHTS: &[Opt<HeightChoices>] = &[
    HeightRow::word("method", COMMAND, "How the slopes are integrated", |h| &mut h.method),
    HeightRow::auto_word(
        "kernel",
        COMMAND,
        "The difference the map was made with (normalmap's --kernel)",
        "Fit every kernel and the spectral derivative iω to the slopes and take the one that explains them best",
        |h| &mut h.kernel,
    ),
    HeightRow::new(
        "scale",
        COMMAND,
        "The scale the map was made with (normalmap's --scale): heights come back divided by it",
        |h| &mut h.scale,
    ),
    HeightRow::auto_word(
        "y-convention",
        COMMAND,
        "Which way the map's green points",
        "The curl test's verdict (opengl where it cannot decide), said on stderr",
        |h| &mut h.y_convention,
    ),
    HeightRow::new(
        "raw",
        COMMAND,
        "Write the heights as they are (texels divided by --scale, mean zero) instead of mapped onto 0..1; needs an .exr output",
        |h| &mut h.raw,
    ),
];
