//! `bake`'s options ([`BAKE`]): the bake's size and samples, where its rays start and how far
//! they look, its padding, the decode its tangent-space normals are made for, and how its
//! normal map is stored.

use bumpmap_bake::{MAX_OCCLUSION_RAYS, MAX_SAMPLES, MAX_SIDE};

use super::maps::bits;
use super::{Access, Kind, Opt, Value};
use crate::bake::BakeRequest;

/// The options of the command (no section of their own).
const COMMAND: &str = "";

type Row = Opt<BakeRequest>;

/// A distance: finite and not negative.
fn distance(v: &Value) -> Result<(), String> {
    match v {
        Value::Number(x) if x.is_finite() && *x >= 0.0 => Ok(()),
        _ => Err(format!("'{v}' is not a distance (a number, 0 or more)")),
    }
}

/// How a high-poly mesh is baked onto a low-poly one's UV layout.
pub static BAKE: &[Row] = &[
    Row::with(
        "size",
        COMMAND,
        "The normal map's side in texels (a square map)",
        Access::Custom {
            kind: || Kind::Whole { min: 1, max: MAX_SIDE as u64 },
            get: |r| Some(Value::Whole(r.options.width as u64)),
            set: |r, v| match v {
                Value::Whole(n) => {
                    (r.options.width, r.options.height) = (n as usize, n as usize);
                    Ok(())
                }
                other => Err(format!("{other} is not a size")),
            },
        },
    ),
    Row::new("spp", COMMAND, "Rays a texel, at stratified points of it (1: the texel's centre); their normals are averaged", |r| &mut r.options.samples).range(1, MAX_SAMPLES as u64),
    Row::word("ray", COMMAND, "Which way each texel's ray goes", |r| &mut r.options.rays),
    Row::new("extrude", COMMAND, "How far in front of LOW the rays start, in the meshes' units: the cage's distance; the first hit from there inward wins [default: 5% of LOW's bounding box diagonal]", |r| &mut r.options.front).check(distance),
    Row::new("max-distance", COMMAND, "How far behind LOW the rays still look, in the meshes' units [default: --extrude's distance]", |r| &mut r.options.back).check(distance),
    Row::new("cage", COMMAND, "A cage: LOW's mesh file with its vertices moved (outward, usually), the same vertices and triangles. Each ray starts on it and goes through LOW as far as --max-distance beyond (--extrude is not used)", |r| &mut r.cage).value_name("FILE"),
    Row::new("match-names", COMMAND, "Pair LOW's parts with HIGH's by name (glTF node names, OBJ objects or groups; without case or a suffix _low, _high, _lo, _hi, _lp, _hp): each part's rays meet only its own, an exploded bake with the parts left in place. A LOW part without a match is an error", |r| &mut r.match_names),
    Row::new("padding", COMMAND, "Texels filled beyond each UV island's edge from the island's own, so filtering and mips do not read the background", |r| &mut r.options.padding).range(0, 4096),
    Row::new("ao-rays", COMMAND, "Rays each sample casts for HIGH's ambient occlusion, cosine-weighted over the hemisphere around HIGH's normal at the hit (0: no occlusion; --ao-out bakes it with 64 when this is 0)", |r| &mut r.options.occlusion_rays).range(0, MAX_OCCLUSION_RAYS as u64),
    Row::word("decode", COMMAND, "The tangent-space decode the map is made for, inverted exactly (interpolated, unnormalized T and N)", |r| &mut r.options.decode),
    Row::word("tangents", COMMAND, "How LOW's tangents are made when its file has none (a glTF's own TANGENT is used as it is)", |r| &mut r.tangents),
    Row::word("y-convention", COMMAND, "Which way green points in the normal map's file: opengl (alias y-up: glTF, Blender, Unity) or directx (alias y-down: Unreal)", |r| &mut r.y_convention),
    Row::new("bits", COMMAND, "Bits per channel of the normal map: 8, or 16 (16-bit PNG, R16G16B16A16_UNORM in .dds and .ktx2)", |r| &mut r.bits).check(bits),
    Row::new("mips", COMMAND, "Also write the normal map's mip chain, each level's alpha the length of the averaged normal", |r| &mut r.mips),
];
