//! `blend`'s options ([`BLEND`]): which blend lays the detail over the base, how strong and how
//! often it repeats, which way each map's green points, and how the result is stored.

use super::maps::bits;
use super::{Access, Kind, Opt, Value};
use crate::maps::{BlendOptions, MAX_REPEAT};

/// The options of the command (no section of their own).
const COMMAND: &str = "";

type Row = Opt<BlendOptions>;

/// A strength: finite and not negative.
pub(super) fn strength(v: &Value) -> Result<(), String> {
    match v {
        Value::Number(x) if x.is_finite() && *x >= 0.0 => Ok(()),
        _ => Err(format!("'{v}' is not a strength (a number, 0 or more)")),
    }
}

/// How a detail normal map is laid over a base one.
pub static BLEND: &[Row] = &[
    Row::word("method", COMMAND, "How the detail is laid over the base", |o| &mut o.method),
    Row::new("detail-strength", COMMAND, "What the detail's slopes are multiplied by (0: no detail, 1: as it is, 2: twice as steep)", |o| &mut o.strength).check(strength),
    Row::new("detail-repeat", COMMAND, "How many times the detail repeats across the base, each way (sampled bilinearly, wrapping; the result has the base's size)", |o| &mut o.repeat).range(1, MAX_REPEAT as u64),
    Row::word("y-convention", COMMAND, "Which way green points in the base's file and the result's: opengl (alias y-up: glTF, Blender, Unity) or directx (alias y-down: Unreal)", |o| &mut o.y_convention),
    Row::maybe_word("detail-y-convention", COMMAND, "Which way green points in the detail's file, when not as in the base's: it is flipped to the base's, and said [default: the base's]", |o| &mut o.detail_y_convention),
    Row::with(
        "bits",
        COMMAND,
        "Bits per channel of the result, 8 or 16 (16-bit PNG, R16G16B16A16_UNORM in .dds and .ktx2) [default: the finer input's, and said when they differ]",
        Access::Custom {
            kind: || Kind::Whole { min: 8, max: 16 },
            get: |o| o.bits.map(|b| Value::Whole(b as u64)),
            set: |o, v| match v {
                Value::Whole(b @ (8 | 16)) => {
                    o.bits = Some(b as u8);
                    Ok(())
                }
                other => Err(format!("'{other}' is not 8 or 16")),
            },
        },
    )
    .check(bits),
    Row::new("mips", COMMAND, "Also write the mip chain, each level's alpha the length of the averaged normal", |o| &mut o.mips),
];
