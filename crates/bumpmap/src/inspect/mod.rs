//! What a normal map file is: its Y convention, whether it is a normal map at all, how it is
//! stored, how its mips were made, whether it tiles, what block compression cost it — in a
//! short verdict for a person ([`MapReport::lines`]) and a machine one ([`MapReport::to_json`]).
//!
//! The questions are answered by [`bumpmap_math::inspect`] on the decoded vectors; this module
//! reads the file, decodes its texels as the format says (unorm, float signed or not, BC5's
//! rebuilt Z), and words the answers.
//!
//! ```
//! use bumpmap::inspect::{StoredAs, inspect_levels};
//! use bumpmap::{HeightPreset, MipChain, MipMode, NormalMapOptions, YConvention};
//!
//! let heights = HeightPreset::Dimples.render(64, 64);
//! let options = NormalMapOptions { y_convention: YConvention::YUp, ..Default::default() };
//! let chain: MipChain = MipChain::from_height(&heights, &options, MipMode::LengthInAlpha).unwrap();
//! let report = inspect_levels("dimples", StoredAs::Unorm8, &chain.levels);
//! assert_eq!(report.inspection.convention.convention, Ok(YConvention::YUp));
//! assert!(report.findings().is_empty());
//! ```
//!
//! What this module does not do: change the file, or repair a map (`render --rebuild-mips`
//! makes its mips anew; `normalmap` makes a map from heights).

use bumpmap_math::Named;
use std::path::Path;

use bumpmap_math::Image;
use bumpmap_math::encoding::Texel;
use bumpmap_math::inspect::{Inspection, MapKind, MipFilter, inspect};
use bumpmap_math::integration::{Boundary, Derivative, Slopes, fit_derivative};
use bumpmap_math::normalmap::YConvention;

use crate::Error;

mod compression;
mod read;

pub use read::{DecodedMap, WORKING_BYTES_PER_TEXEL, maps_in_folder, read_bytes, read_file, read_map};

/// How a file stores its vectors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StoredAs {
    /// 8-bit unsigned-normalized channels (`2c/255 − 1`).
    Unorm8,
    /// 16-bit unsigned-normalized channels.
    Unorm16,
    /// BC5 blocks: X and Y, Z rebuilt.
    Bc5,
    /// BC7 blocks: RGBA.
    Bc7,
    /// Floating point, −1..1 as stored.
    FloatSigned,
    /// Floating point, 0..1 (`2v − 1`).
    FloatUnsigned,
}

impl StoredAs {
    /// In words, for the verdict.
    pub fn describe(self) -> &'static str {
        match self {
            StoredAs::Unorm8 => "8-bit unsigned",
            StoredAs::Unorm16 => "16-bit unsigned",
            StoredAs::Bc5 => "BC5 (X and Y only, Z rebuilt)",
            StoredAs::Bc7 => "BC7",
            StoredAs::FloatSigned => "floating point, signed (−1..1)",
            StoredAs::FloatUnsigned => "floating point, unsigned (0..1)",
        }
    }

    /// The name in JSON: `unorm8`, `unorm16`, `bc5`, `bc7`, `float-signed`, `float-unsigned`.
    pub fn name(self) -> &'static str {
        match self {
            StoredAs::Unorm8 => "unorm8",
            StoredAs::Unorm16 => "unorm16",
            StoredAs::Bc5 => "bc5",
            StoredAs::Bc7 => "bc7",
            StoredAs::FloatSigned => "float-signed",
            StoredAs::FloatUnsigned => "float-unsigned",
        }
    }
}

/// One file's verdict.
#[derive(Clone, Debug, PartialEq)]
pub struct MapReport {
    /// The file (or what the caller called the texels).
    pub source: String,
    /// How the texels were stored.
    pub stored: StoredAs,
    /// Every question's answer.
    pub inspection: Inspection,
    /// What block compression added, in degrees RMS, estimated where the map reads as a gradient.
    pub compression_degrees: Option<f32>,
    /// The difference the slopes fit best ([`DerivativeFit::best`](bumpmap_math::integration::DerivativeFit::best)), where the convention is
    /// decided: the kernel to give `height --kernel` and `normalmap --kernel` (slopes cannot
    /// tell a kernel from a smoother one of its family: the sharpest is named).
    pub made_with: Option<Derivative>,
}

/// Something a user must act on (`inspect --strict` exits 1 on any).
#[derive(Clone, Debug, PartialEq)]
pub enum Finding {
    /// The texels are not a tangent-space normal map.
    NotANormalMap(MapKind),
    /// Texels whose vectors point into the surface (the fraction).
    FacingAway(f32),
    /// Texels whose length is far from 1 (the fraction).
    NotUnitLength(f32),
    /// Smaller levels renormalized: distant diffuse light this many times too bright.
    RenormalizedMips(f32),
}

impl std::fmt::Display for Finding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Finding::NotANormalMap(kind) => write!(f, "{}", kind.describe()),
            Finding::FacingAway(p) => write!(f, "{:.2}% of texels point into the surface (z ≤ 0)", p * 100.0),
            Finding::NotUnitLength(p) => write!(f, "{:.1}% of texels are not of unit length", p * 100.0),
            Finding::RenormalizedMips(b) => write!(
                f,
                "the mips were renormalized: distant diffuse light is up to {:.0}% too bright (make them anew: render --rebuild-mips)",
                (b - 1.0) * 100.0
            ),
        }
    }
}

/// The fraction of texels facing away above which a map needs fixing.
const FACING_AWAY_FINDING: f32 = 0.001;
/// The fraction of texels off unit length above which a map needs fixing.
const OFF_UNIT_FINDING: f32 = 0.01;
/// The brightening by renormalized mips above which they need fixing.
const BRIGHTENING_FINDING: f32 = 1.02;

impl MapReport {
    /// What a user must act on; empty for a clean map.
    pub fn findings(&self) -> Vec<Finding> {
        let i = &self.inspection;
        if !i.kind.is_normal_map() {
            return vec![Finding::NotANormalMap(i.kind)];
        }
        let mut out = Vec::new();
        if i.texels.facing_away > FACING_AWAY_FINDING {
            out.push(Finding::FacingAway(i.texels.facing_away));
        }
        if !i.two_channel && i.texels.off_unit > OFF_UNIT_FINDING {
            out.push(Finding::NotUnitLength(i.texels.off_unit));
        }
        if let Some(m) = &i.mips
            && m.filter == MipFilter::Renormalized
            && let Some(b) = m.renormalized_brightening()
            && b > BRIGHTENING_FINDING
        {
            out.push(Finding::RenormalizedMips(b));
        }
        out
    }

    /// The verdict for a person: a heading line, then one indented line per question.
    pub fn lines(&self) -> Vec<String> {
        let i = &self.inspection;
        let (w, h) = i.size;
        let plural = if i.levels == 1 { "" } else { "s" };
        let mut out = vec![format!("{}: {w}x{h}, {}, {} level{plural}", self.source, self.stored.describe(), i.levels)];
        let t = &i.texels;
        out.push(if !i.kind.is_normal_map() {
            format!("  {} (mean |n| {:.3}, {:.0}% gray texels)", i.kind.describe(), t.mean_length, t.gray * 100.0)
        } else if i.two_channel {
            format!(
                "  a normal map (two channels: lengths are 1 by construction); {:.2}% facing away",
                t.facing_away * 100.0
            )
        } else {
            format!(
                "  a normal map: {:.1}% of texels unit length (mean |n| {:.3}), {:.2}% facing away",
                (1.0 - t.off_unit) * 100.0,
                t.mean_length,
                t.facing_away * 100.0
            )
        });
        let c = &i.convention;
        out.push(match c.convention {
            Ok(y) => format!(
                "  convention: {} (green {}), confidence {:.2} (curl test{}){}",
                y.name(),
                if y == YConvention::YUp { "up" } else { "down" },
                c.confidence,
                if c.left_out > 0.0 {
                    format!(
                        ", its {:.0}% most abrupt stencils left out: seams of UV islands, as a baked map has",
                        c.left_out * 100.0
                    )
                } else {
                    String::new()
                },
                match self.made_with {
                    Some(Derivative::Kernel(k)) => format!("; its slopes fit the {} kernel best", k.name()),
                    Some(Derivative::Spectral) => "; no kernel fits its slopes better than the exact derivative".into(),
                    None => String::new(),
                }
            ),
            Err(why) => format!("  convention: undecidable: {}", why.reason()),
        });
        out.push(match &i.mips {
            None => "  mips: none stored".to_string(),
            Some(m) => {
                let cost = match (m.filter, m.quoted()) {
                    (MipFilter::Renormalized, Some(q)) => format!(
                        ": at level {} a box filter keeps a mean length of {:.2}, so renormalized they light the distant surface up to {:.0}% brighter than its bumps average up close (Kilgard §2.4.2)",
                        q.level,
                        q.box_length,
                        (1.0 / q.box_length.max(1e-3) - 1.0) * 100.0
                    ),
                    (MipFilter::LengthInAlpha, _) => {
                        ": the averaged normal's length is in alpha, for the length factor and Toksvig's filter (Kilgard §5.3)".into()
                    }
                    (MipFilter::Box, _) => ": unnormalized means, the shortening kept in RGB".into(),
                    (MipFilter::Smooth, _) => ": the normals barely differ, so nothing is lost by any filter".into(),
                    (MipFilter::Other, Some(q)) => format!(
                        ": not a box filter of the level above (mean error {:.3} at level {})",
                        q.errors.iter().cloned().fold(f32::MAX, f32::min),
                        q.level
                    ),
                    (MipFilter::Other | MipFilter::Renormalized, None) => String::new(),
                };
                format!("  mips: {} levels below 0, {}{cost}", i.levels - 1, m.filter.name())
            }
        });
        let s = &i.seam;
        out.push(format!(
            "  tiling: {} (seam {:.1}°, worst interior neighbours {:.1}°){}",
            if s.tiles() { "tiles" } else { "does not tile" },
            s.seam_degrees(),
            s.interior_degrees(),
            if s.tiles() && !s.heights_tile() {
                format!(
                    ", but the heights it holds climb {:.3}, {:.3} per texel and do not",
                    s.mean_slope[0], s.mean_slope[1]
                )
            } else {
                String::new()
            }
        ));
        match self.stored {
            StoredAs::Bc5 | StoredAs::Bc7 => {
                let name = if self.stored == StoredAs::Bc5 { "BC5" } else { "BC7" };
                out.push(match self.compression_degrees {
                    Some(d) => format!(
                        "  compression: {name} added about {d:.1}° RMS (estimated from the slopes no height field explains)"
                    ),
                    None => format!(
                        "  compression: {name}; its error cannot be estimated here (it is read from the slopes no height field explains, which needs a decided convention and few texels steeper than 60°)"
                    ),
                })
            }
            _ => {}
        }
        for f in self.findings() {
            out.push(format!("  FIX: {f}"));
        }
        out
    }

    /// The verdict as JSON (what `inspect --json` prints and Python's `inspect()` returns).
    pub fn to_json(&self) -> serde_json::Value {
        use serde_json::json;
        let i = &self.inspection;
        let t = &i.texels;
        let c = &i.convention;
        let mips = i.mips.as_ref().map(|m| {
            json!({
                "filter": m.filter.name(),
                "renormalized_brightening": if m.filter == MipFilter::Renormalized { m.renormalized_brightening().map(f64::from) } else { None },
                "levels": m.levels.iter().map(|l| json!({
                    "level": l.level,
                    "size": [l.size.0, l.size.1],
                    "box_length": l.box_length,
                    "error_box": l.errors[0],
                    "error_length_in_alpha": l.errors[1],
                    "error_renormalized": l.errors[2],
                    "alpha_error": l.alpha_error,
                })).collect::<Vec<_>>(),
            })
        });
        json!({
            "file": self.source,
            "size": [i.size.0, i.size.1],
            "stored": self.stored.name(),
            "levels": i.levels,
            "two_channel": i.two_channel,
            "normal_map": i.kind.is_normal_map(),
            "kind": kind_name(i.kind),
            "texels": {
                "mean_length": t.mean_length,
                "length_rms_error": t.length_rms_error,
                "off_unit": t.off_unit,
                "facing_away": t.facing_away,
                "gray": t.gray,
            },
            "convention": {
                "verdict": match c.convention { Ok(y) => y.name(), Err(_) => "undecidable" },
                "reason": c.convention.err().map(|u| u.reason()),
                "confidence": c.confidence,
                "curl_ratio": c.curl_ratio,
                "curl_kernel": c.kernel.name(),
                "made_with": self.made_with.map(|d| d.name()),
                "mixed_energy": c.mixed_energy,
                "left_out": c.left_out,
            },
            "mips": mips,
            "seam": {
                "tiles": i.seam.tiles(),
                "heights_tile": i.seam.heights_tile(),
                "mean_slope": i.seam.mean_slope,
                "seam_degrees": i.seam.seam_degrees(),
                "interior_degrees": i.seam.interior_degrees(),
            },
            "compression_degrees": self.compression_degrees,
            "findings": self.findings().iter().map(|f| f.to_string()).collect::<Vec<_>>(),
        })
    }
}

fn kind_name(kind: MapKind) -> &'static str {
    match kind {
        MapKind::NormalMap => "normal-map",
        MapKind::Gray => "gray",
        MapKind::NotUnitVectors => "not-unit-vectors",
        MapKind::FacingAway => "facing-away",
    }
}

/// The Y convention the texels of a texture's level 0 show by the curl test, `None` where it
/// cannot decide; only the centre the test reads is decoded
/// ([`bumpmap_math::inspect::centre_crop`]), so a map of any size costs a few megabytes.
pub fn stored_convention(levels: &bumpmap_io::StoredLevels) -> Option<YConvention> {
    use bumpmap_math::inspect::{centre_crop, detect_convention};
    let crop = match levels {
        bumpmap_io::StoredLevels::Rgba8(l) => centre_crop(l.first()?),
        bumpmap_io::StoredLevels::Rgba16(l) => centre_crop(l.first()?),
    };
    detect_convention(&crop).convention.ok()
}

/// Inspects a file ([`read_map`] reads it).
pub fn inspect_file(path: &Path) -> Result<MapReport, Error> {
    Ok(inspect_map(&path.display().to_string(), &read_map(path)?))
}

/// Inspects unorm texels already in memory (level 0 first), named `source` in the verdict.
pub fn inspect_levels<T: Texel>(source: &str, stored: StoredAs, levels: &[Image<T>]) -> MapReport {
    inspect_map(source, &DecodedMap::from_unorm(levels, stored))
}

/// Inspects a decoded map, named `source` in the verdict.
pub fn inspect_map(source: &str, map: &DecodedMap) -> MapReport {
    let empty = [Image::new(0, 0, Vec::new())];
    let levels = if map.levels.is_empty() { &empty[..] } else { &map.levels[..] };
    let inspection = inspect(levels, map.two_channel).expect("at least one level");
    let compressed = matches!(map.stored, StoredAs::Bc5 | StoredAs::Bc7);
    // Level 0's slopes as the decided convention reads them; none where it is undecided.
    let slopes = inspection.convention.convention.ok().and_then(|y| Slopes::from_normals(&levels[0], y, 1.0).ok());
    let boundary = boundary_of(&inspection);
    let (compression_degrees, fit) = match &slopes {
        Some(slopes) if compressed => compression::estimate(&levels[0], slopes, boundary),
        Some(slopes) => (None, fit_derivative(slopes, boundary).ok()),
        None => (None, None),
    };
    let made_with = fit.map(|fit| fit.best());
    MapReport { source: source.to_string(), stored: map.stored, inspection, compression_degrees, made_with }
}

/// Periodic where the heights tile, else free.
fn boundary_of(inspection: &Inspection) -> Boundary {
    if inspection.seam.heights_tile() { Boundary::Periodic } else { Boundary::Free }
}
