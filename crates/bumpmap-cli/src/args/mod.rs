//! Command-line arguments, a module per command; the value parsers and enums more than one
//! command reads live here. The help texts are the user manual: they say what each option
//! means in the papers' terms and what the default is.

mod bake;
mod bench;
mod blend;
mod compare;
mod cubemap;
mod demo;
mod inspect;
mod normalmap;
mod render;
pub mod table;
mod tangents;
mod view;

pub use bake::*;
pub use bench::*;
pub use blend::*;
pub use compare::*;
pub use cubemap::*;
pub use demo::*;
pub use inspect::*;
pub use normalmap::*;
pub use render::*;
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
    /// High-poly mesh → normal map over a low-poly mesh's UV layout, synced to its tangent frame
    Bake(Box<BakeArgs>),
    /// Lay a detail normal map over a base one (reoriented, partial derivatives, whiteout, …)
    Blend(BlendArgs),
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

/// One number as typed (the library's reading: text beyond single precision is refused with the
/// text, `NaN` and `inf` typed as such pass, for the option's own range check to name).
pub use bumpmap::option_table::parse_number as parse_f32;

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

/// The value parser of a closed set the library names ([`Named`]): its names, aliases and
/// descriptions are what `--help` lists and what the option takes.
pub fn choice<T: Named>() -> impl TypedValueParser<Value = T> {
    let values =
        T::ALL.iter().map(|v| PossibleValue::new(v.name()).help(v.help()).aliases(v.aliases().iter().copied()));
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
