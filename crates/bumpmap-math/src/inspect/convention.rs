//! DirectX or OpenGL? The curl test.
//!
//! A normal map made from heights holds a discrete gradient: `p = K_u ∗ h`, `q = K_v ∗ h` for
//! the kernel `K` that made it. Convolutions commute, so with the same kernel
//! `K_u ∗ q − K_v ∗ p = K_u ∗ K_v ∗ h − K_v ∗ K_u ∗ h = 0`: the map's curl, measured by its own
//! kernel, vanishes. Reading green the wrong way negates `q`, and the same measure gives
//! `−2·K_u ∗ K_v ∗ h`. So the reading whose curl energy is smaller is the map's convention, and the
//! ratio of the two energies says how sure that is. The kernel is not known: every kernel of
//! [`Kernel::ALL`] is tried and the one whose better reading is cleanest is used (a map made by
//! another tool's difference is measured by the nearest).
//!
//! Where `K_u ∗ K_v ∗ h` is itself near zero — a flat map, heights that vary along one
//! direction, or `h = f(u) + g(v)` — both readings are equally curl-free and there is nothing to
//! decide: the verdict is undecidable, never a guess.
//!
//! A map baked from a mesh is UV islands, whose seams (and the texels where a cage's rays met
//! another part) no height field has: a few stencils there can outweigh the rest. Where counting
//! every stencil leaves the map undecided, a second measure leaves the most abrupt
//! [`ABRUPT_LEFT_OUT`] of them out ([`ConventionVerdict::left_out`]).
//!
//! Reading X the wrong way also negates one slope: a map with red flipped reads as the other
//! convention. What this module does not do: read files or decide anything else about a map.
//!
//! ```
//! use bumpmap_math::inspect::{centre_crop, detect_convention};
//! use bumpmap_math::{HeightPreset, MipChain, MipMode, NormalMapOptions, YConvention};
//!
//! let field = HeightPreset::Dimples.render(64, 64);
//! let options = NormalMapOptions { y_convention: YConvention::YDown, ..Default::default() };
//! let chain: MipChain = MipChain::from_height(&field, &options, MipMode::LengthInAlpha).unwrap();
//! let verdict = detect_convention(&centre_crop(&chain.levels[0]));
//! assert_eq!(verdict.convention.ok(), Some(YConvention::YDown));
//! ```

use glam::Vec4;

use crate::encoding::Texel;
use crate::image::Image;
use crate::kernel::{Kernel, Tap};
use crate::normalmap::YConvention;

/// The largest crop measured, per side: the centre of a bigger map (the test is statistical;
/// 512² texels decide as well as 4096²).
pub const CROP: usize = 512;

/// The smallest `n_z` whose slopes are used: a texel steeper than 84° gives a slope that one
/// quantization step moves by a lot.
const MIN_NZ: f32 = 0.1;

/// The fewest texels (every tap of every kernel on a usable texel) the test decides on.
const MIN_TEXELS: usize = 64;

/// The largest ratio of the cleaner reading's curl energy to the other's that still decides.
/// On the test corpus (`crates/bumpmap/tests/inspect_corpus.rs`: 2800 maps, every preset and
/// kernel, scales 1–8, 8/16 bits, BC5, BC7, JPEG q75) the median ratio is 0.004 and the 99th
/// percentile 0.21; the few maps above 0.5 are JPEG's, which it leaves undecided.
pub const DECIDE_BELOW: f32 = 0.5;

/// The smallest variance of the slopes (per texel, both directions) of a map that is not flat: a
/// few 16-bit steps. Between it and 8-bit quantization's noise (about 1e-5) the ratio test
/// speaks: noise has as much curl either way.
pub const FLAT_BELOW: f32 = 1e-9;

/// Where neither reading is clearly cleaner: below this ratio of the other reading's curl
/// energy to the slopes' energy there is no mixed derivative to speak of, so the heights vary
/// along one direction (or as `f(u) + g(v)`); above it the slopes are not a gradient. (A smooth
/// map at high resolution has little mixed energy per texel too, but its cleaner reading still
/// stands out, so this only words the reason.)
pub const MIXED_BELOW: f32 = 2e-3;

/// The fraction of stencils, the most abrupt (largest `|K_u∗q| + |K_v∗p|`), left out of a second
/// measure where the first leaves the map undecided. A baked map's island seams and the texels
/// whose rays met another part are a few percent of its texels but most of its curl energy:
/// on a six-island cube baked with averaged rays the ratio falls from 0.96 to 0.16 with 5 % left
/// out. The first measure keeps every stencil because, on a map made from heights, the
/// largest mixed derivatives carry most of the signal.
pub const ABRUPT_LEFT_OUT: f32 = 0.05;

/// The mixed energy below which the two readings differ by round-off alone.
const MIXED_FLOOR: f32 = 1e-9;

/// Why the test cannot say which way green points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Undecidable {
    /// The map has (almost) no slopes.
    Flat,
    /// Its heights vary along one direction only (or separately along each): both readings
    /// are gradients.
    OneDirectional,
    /// Both readings have about as much curl: not the gradient of heights (painted, noisy, or
    /// compressed past recognition).
    NotAGradient,
    /// Too few texels lean less than 84° from the surface normal to measure.
    TooSteep,
    /// The map is too small to hold the test's stencils (it needs 14×14 texels).
    TooSmall,
}

impl Undecidable {
    /// Why, in words.
    pub fn reason(self) -> &'static str {
        match self {
            Undecidable::Flat => "the map is flat",
            Undecidable::OneDirectional => "its bumps vary along one direction only, which reads the same either way",
            Undecidable::NotAGradient => {
                "neither reading is the gradient of a height field (a painted or heavily compressed map?)"
            }
            Undecidable::TooSteep => "too few of its texels are shallow enough to measure",
            Undecidable::TooSmall => "the map is too small to measure (the test needs 14x14 texels)",
        }
    }
}

/// What the curl test found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConventionVerdict {
    /// The map's convention, or why there is none.
    pub convention: Result<YConvention, Undecidable>,
    /// `1 −` [`ConventionVerdict::curl_ratio`] where decided, 0 where not.
    pub confidence: f32,
    /// The cleaner reading's curl energy over the other's (0: a perfect gradient, 1: no
    /// preference).
    pub curl_ratio: f32,
    /// The kernel whose curl measure separated the readings best.
    pub kernel: Kernel,
    /// The other reading's curl energy over the slopes' energy: how much the map has to decide on.
    pub mixed_energy: f32,
    /// Texels measured.
    pub texels: usize,
    /// The fraction of the most abrupt stencils left out ([`ABRUPT_LEFT_OUT`]; 0: none), where
    /// counting them all left the map undecided: the seams of a baked map's UV islands.
    pub left_out: f32,
}

/// The centre [`CROP`]² of unorm texels (8 or 16 bits) as signed vectors, the rest of the
/// level left undecoded: all of a map [`detect_convention`] reads, at a few megabytes whatever
/// the map's size.
pub fn centre_crop<T: Texel>(level: &Image<T>) -> Image<Vec4> {
    let (cw, ch) = (level.width.min(CROP), level.height.min(CROP));
    let (x0, y0) = ((level.width - cw) / 2, (level.height - ch) / 2);
    let texels = (0..cw * ch)
        .map(|i| Vec4::from(level.texel(x0 + i % cw, y0 + i / cw).unpack(crate::Encoding::Unorm)))
        .collect();
    Image::new(cw, ch, texels)
}

/// The curl test on `normals` (signed xyz; w not read).
pub fn detect_convention(normals: &Image<Vec4>) -> ConventionVerdict {
    let (cw, ch) = (normals.width.min(CROP), normals.height.min(CROP));
    let (x0, y0) = ((normals.width - cw) / 2, (normals.height - ch) / 2);
    // Slopes of the stored reading (green along +t, Y down), NaN where unusable.
    let mut p = vec![f32::NAN; cw * ch];
    let mut q = vec![f32::NAN; cw * ch];
    for y in 0..ch {
        for x in 0..cw {
            let n = normals.texel(x0 + x, y0 + y);
            if n.is_finite() && n.z >= MIN_NZ {
                p[y * cw + x] = -n.x / n.z;
                q[y * cw + x] = -n.y / n.z;
            }
        }
    }
    let r = Kernel::ALL.iter().map(|k| k.radius()).max().unwrap_or(1) as usize;
    let (mut slope_energy, mut sum_p, mut sum_q) = (0.0f64, 0.0f64, 0.0f64);
    let mut counted = 0usize;
    for y in r..ch.saturating_sub(r) {
        for i in y * cw + r..y * cw + cw.saturating_sub(r) {
            if p[i].is_finite() {
                slope_energy += (p[i] * p[i] + q[i] * q[i]) as f64;
                (sum_p, sum_q) = (sum_p + p[i] as f64, sum_q + q[i] as f64);
                counted += 1;
            }
        }
    }
    let slopes = Slopes { p: &p, q: &q, width: cw, height: ch, margin: r };
    let mut best = slopes.cleanest(None);
    let mut left_out = 0.0;
    // A map baked from a mesh is UV islands: at their seams, and where a cage's rays met other
    // parts, the slopes jump in ways no height field has, and those few stencils outweigh the
    // rest. Where every stencil counted leaves the map undecided, the most abrupt ones are left
    // out and the rest decide. (Only where the map has mixed derivatives to speak of: heights
    // along one direction have none, and quantization's noise would decide instead.)
    let mixed_of = |c: &Curl| if slope_energy > 0.0 { c.down.max(c.up) / slope_energy } else { 0.0 };
    if best.is_some_and(|b| b.ratio() >= DECIDE_BELOW as f64 && mixed_of(&b) >= MIXED_BELOW as f64) {
        let trimmed = slopes.cleanest(Some(ABRUPT_LEFT_OUT));
        if trimmed.is_some_and(|t| t.ratio() < DECIDE_BELOW as f64) {
            (best, left_out) = (trimmed, ABRUPT_LEFT_OUT);
        }
    }
    let best = best.map(|b| (b.down, b.up, b.kernel, b.stencils));
    let (down, up, kernel, n) = best.unwrap_or((0.0, 0.0, Kernel::Forward, 0));
    let ratio = if down.max(up) > 0.0 { (down.min(up) / down.max(up)) as f32 } else { 1.0 };
    let mixed = if slope_energy > 0.0 { (down.max(up) / slope_energy) as f32 } else { 0.0 };
    // The slopes' variance: a plane (a constant slope, or 8-bit's "flat" that decodes to
    // 0.004) is as flat as level ground for the curl.
    let slope_variance = if counted > 0 {
        let n = counted as f64;
        (slope_energy / n - (sum_p / n).powi(2) - (sum_q / n).powi(2)) as f32
    } else {
        0.0
    };
    let interior_texels = cw.saturating_sub(2 * r) * ch.saturating_sub(2 * r);
    let convention = if interior_texels < MIN_TEXELS {
        Err(Undecidable::TooSmall)
    } else if counted > 0 && slope_variance < FLAT_BELOW {
        Err(Undecidable::Flat)
    } else if n < MIN_TEXELS {
        Err(Undecidable::TooSteep)
    } else if ratio >= DECIDE_BELOW || mixed < MIXED_FLOOR {
        Err(if mixed < MIXED_BELOW { Undecidable::OneDirectional } else { Undecidable::NotAGradient })
    } else if down < up {
        Ok(YConvention::YDown)
    } else {
        Ok(YConvention::YUp)
    };
    let confidence = if convention.is_ok() { 1.0 - ratio } else { 0.0 };
    ConventionVerdict { convention, confidence, curl_ratio: ratio, kernel, mixed_energy: mixed, texels: n, left_out }
}

/// The slopes of the stored reading (NaN where unusable), and the margin each side that every
/// kernel's stencil fits inside.
struct Slopes<'a> {
    p: &'a [f32],
    q: &'a [f32],
    width: usize,
    height: usize,
    margin: usize,
}

/// One kernel's curl energies of the two readings over the stencils counted.
#[derive(Clone, Copy)]
struct Curl {
    down: f64,
    up: f64,
    kernel: Kernel,
    stencils: usize,
}

impl Curl {
    /// The cleaner reading's energy over the other's.
    fn ratio(&self) -> f64 {
        self.down.min(self.up) / self.down.max(self.up).max(f64::MIN_POSITIVE)
    }
}

impl Slopes<'_> {
    /// The kernel whose two readings differ most, and their energies, with the `left_out`
    /// fraction of most abrupt stencils not counted.
    fn cleanest(&self, left_out: Option<f32>) -> Option<Curl> {
        let mut best: Option<Curl> = None;
        for kernel in Kernel::ALL {
            let curl = self.curl(kernel, left_out);
            if best.is_none_or(|b| curl.ratio() < b.ratio()) {
                best = Some(curl);
            }
        }
        best
    }

    /// `kernel`'s measure of the curl of both readings.
    fn curl(&self, kernel: Kernel, left_out: Option<f32>) -> Curl {
        let (cw, r) = (self.width, self.margin);
        let (du, dv) = (offsets(&kernel.taps_du(), cw), offsets(&kernel.taps_dv(), cw));
        // K_u∗q and K_v∗p at each stencil whose taps are all usable.
        let mut terms = Vec::new();
        for y in r..self.height.saturating_sub(r) {
            for i in y * cw + r..y * cw + cw.saturating_sub(r) {
                let kq: f32 = du.iter().map(|&(o, w)| w * self.q[(i as isize + o) as usize]).sum();
                let kp: f32 = dv.iter().map(|&(o, w)| w * self.p[(i as isize + o) as usize]).sum();
                if kq.is_finite() && kp.is_finite() {
                    terms.push((kq, kp));
                }
            }
        }
        if let Some(fraction) = left_out {
            let kept = terms.len() - (terms.len() as f32 * fraction) as usize;
            if kept < terms.len() {
                let abrupt = |&(kq, kp): &(f32, f32)| kq.abs() + kp.abs();
                terms.select_nth_unstable_by(kept, |a, b| abrupt(a).total_cmp(&abrupt(b)));
                terms.truncate(kept);
            }
        }
        // Stored green is +t (Y down): curl K_u∗q − K_v∗p. Y up: q negated.
        let down = terms.iter().map(|&(kq, kp)| ((kq - kp) as f64).powi(2)).sum();
        let up = terms.iter().map(|&(kq, kp)| ((kq + kp) as f64).powi(2)).sum();
        Curl { down, up, kernel, stencils: terms.len() }
    }
}

/// A kernel's taps as offsets into a row-major buffer `width` wide.
fn offsets(taps: &[Tap], width: usize) -> Vec<(isize, f32)> {
    taps.iter().map(|t| (t.dy as isize * width as isize + t.dx as isize, t.weight)).collect()
}
