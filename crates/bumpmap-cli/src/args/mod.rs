//! Command-line arguments, a module per command; the value parsers and enums more than one
//! command reads live here. The help texts are the user manual: they say what each option
//! means in the papers' terms and what the default is.

mod bench;
mod compare;
mod cubemap;
mod demo;
mod inspect;
mod normalmap;
mod render;
mod table;
mod tangents;
mod view;

pub use bench::*;
pub use compare::*;
pub use cubemap::*;
pub use demo::*;
pub use inspect::*;
pub use normalmap::*;
pub use render::*;
pub use table::{options_table, options_table_text};
pub use tangents::*;
pub use view::*;

use bumpmap::Named;
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Parser, Subcommand};

/// `bumpmap` and its subcommand.
#[derive(Parser, Debug)]
#[command(
    name = "bumpmap",
    version,
    about = "Bump mapping toolkit and renderer after Kilgard (2000), the Cg Tutorial ch. 8 and Peercy et al. (1997)",
    long_about = "Bump mapping toolkit and renderer.\n\n\
Makes tangent-space normal maps from height fields, with mip chains that keep the length of the \
averaged normal in alpha so bumpy surfaces dim correctly at a distance (Kilgard 2000, §2.4.2); \
builds normalization cube maps and tangent frames; and renders bump-mapped objects with every \
technique the papers compare (`bumpmap render --help` lists them), on an emulated GeForce 256 or \
the GPU, from built-in surfaces or your own meshes, normal maps and glTF materials, measured \
against a ground-truth reference by `bumpmap compare`.\n\n\
Start with `bumpmap demo`, which writes example outputs into ./out/demo.\n\n\
Texture convention: the first row of an image file is texture coordinate t = 0 (OpenGL's \
glTexImage2D order), so the normal map's +Y (green) points toward the next row."
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Height field → normal map (and its mip chain)
    Normalmap(NormalmapArgs),
    /// Write a normalization cube map, or measure the accuracy of its lookup
    Cubemap(CubemapArgs),
    /// Measure speed (median of several runs); --json prints one machine-readable line
    Bench(BenchArgs),
    /// Render a bump-mapped scene
    Render(Box<RenderArgs>),
    /// Generate tangent frames for a mesh and write glTF with a TANGENT attribute
    Tangents(TangentsArgs),
    /// Run everything on built-in defaults and write the results into a folder
    Demo(DemoArgs),
    /// Render every technique on one scene, measure each against the reference, write a report
    Compare(CompareArgs),
    /// A window on a scene with the light moving: keys switch techniques, passes and options
    View(Box<ViewArgs>),
    /// What a normal map made elsewhere is: DirectX or OpenGL, a normal map at all, its mips, its seam
    Inspect(InspectArgs),
    /// Normal map → heights: integrate its slopes back into a height field
    Height(HeightArgs),
}

/// One number as typed: text that overflows single precision (`1e40`) is refused with the
/// text, rather than becoming `inf` and reported as that; `NaN` and `inf` typed as such pass,
/// for the option's own range check to name.
pub fn parse_f32(s: &str) -> Result<f32, String> {
    let v = s.trim().parse::<f32>().map_err(|_| format!("'{s}' is not a number"))?;
    if v.is_infinite() && !s.to_ascii_lowercase().contains("inf") {
        return Err(format!("'{s}' is beyond single precision (about ±3.4e38)"));
    }
    Ok(v)
}

/// Three numbers, `X,Y,Z`.
pub fn parse_vec3(s: &str) -> Result<glam::Vec3, String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|p| p.trim().parse::<f32>().map_err(|_| format!("'{p}' is not a number")))
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(glam::Vec3::new(*x, *y, *z)),
        _ => Err(format!("expected X,Y,Z (three finite numbers), got '{s}'")),
    }
}

/// Two numbers, `A,B`.
pub fn parse_pair(s: &str) -> Result<(f32, f32), String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|p| p.trim().parse::<f32>().map_err(|_| format!("'{p}' is not a number")))
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [a, b] if a.is_finite() && b.is_finite() => Ok((*a, *b)),
        _ => Err(format!("expected A,B (two finite numbers), got '{s}'")),
    }
}

/// Texture repeats `S,T`: two finite numbers, neither 0 (a map made for the surface is addressed
/// with 1/repeat) and neither beyond ±1024 (texture coordinates stay well inside single
/// precision's whole numbers).
pub fn parse_repeat(s: &str) -> Result<(f32, f32), String> {
    let (a, b) = parse_pair(s)?;
    let ok = |v: f32| v != 0.0 && v.abs() <= 1024.0;
    if ok(a) && ok(b) { Ok((a, b)) } else { Err(format!("repeats must be non-zero and within ±1024, got '{s}'")) }
}

/// The largest image side `render` and `bench render` take: the library's.
pub use bumpmap::frame::MAX_SIDE;

/// An image side in pixels, 1..=[`MAX_SIDE`].
pub fn parse_side(s: &str) -> Result<usize, String> {
    s.trim()
        .parse::<usize>()
        .ok()
        .filter(|n| (1..=MAX_SIDE).contains(n))
        .ok_or_else(|| format!("'{s}' is not a size in 1..={MAX_SIDE} pixels"))
}

/// The most quads along u or v (the library's bound).
pub use bumpmap::options::MAX_TESSELLATION;

/// Two positive integers, `U,V`.
pub fn parse_counts(s: &str) -> Result<(usize, usize), String> {
    let (a, b) = s.split_once(',').ok_or_else(|| format!("expected U,V, got '{s}'"))?;
    let p = |x: &str| {
        x.trim()
            .parse::<usize>()
            .ok()
            .filter(|&n| (1..=MAX_TESSELLATION).contains(&n))
            .ok_or_else(|| format!("'{x}' is not a count in 1..={MAX_TESSELLATION}"))
    };
    Ok((p(a)?, p(b)?))
}

/// A value of `T`, or `None` where the option says `auto`. (An alias, so that clap's derive takes
/// the whole `Option` as the option's value rather than make the option optional.)
pub type OrAuto<T> = Option<T>;

/// [`choice`] with `auto` (`None`: the tool decides, as `auto_help` says) listed first.
pub fn choice_or_auto<T: Named>(auto_help: &'static str) -> impl TypedValueParser<Value = OrAuto<T>> {
    let auto = PossibleValue::new(bumpmap_math::named::AUTO).help(auto_help);
    let values = std::iter::once(auto).chain(
        T::ALL.iter().map(|v| PossibleValue::new(v.name()).help(v.description()).aliases(v.aliases().iter().copied())),
    );
    PossibleValuesParser::new(values)
        .map(|word| bumpmap_math::named::parse_or_auto::<T>(&word).expect("clap accepts only auto and the set's names"))
}

/// The value parser of a closed set the library names ([`Named`]): its names, aliases and
/// descriptions are what `--help` lists and what the option takes.
pub fn choice<T: Named>() -> impl TypedValueParser<Value = T> {
    let values =
        T::ALL.iter().map(|v| PossibleValue::new(v.name()).help(v.description()).aliases(v.aliases().iter().copied()));
    // An option with `ignore_case` hands over the word as typed: it is matched the same way.
    PossibleValuesParser::new(values).map(|word| {
        T::parse(&word)
            .or_else(|| {
                T::ALL.iter().copied().find(|v| {
                    v.name().eq_ignore_ascii_case(&word) || v.aliases().iter().any(|a| a.eq_ignore_ascii_case(&word))
                })
            })
            .expect("clap accepts only the set's names")
    })
}
