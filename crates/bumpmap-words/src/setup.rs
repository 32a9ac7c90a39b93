//! What setting a scene up refused ([`SetupError`]) or noted ([`SetupNote`]), named by the
//! flags that caused it. Values out of range are usage errors (exit status 2).

use bumpmap::options::{SceneOption, SetupError, SetupNote};
use bumpmap::{Named, SpecularFilter};

use crate::Error;
use crate::library::lib_err;

/// The flag that sets `option`.
pub fn flag(option: SceneOption) -> String {
    format!("--{}", option.name().replace('_', "-"))
}

/// `--specular-filter`'s value for `filter`.
fn specular_filter_value(filter: SpecularFilter) -> String {
    filter.name().to_owned()
}

/// What the library refused, in the words of the command line.
pub fn setup_err(e: SetupError) -> Error {
    match e {
        SetupError::OutOfRange { option, expected, got } => {
            Error::Usage(format!("{} must be {expected}, got {got}", flag(option)))
        }
        SetupError::KilgardOnly { option, technique } => Error::Render(format!(
            "{} belongs to --technique kilgard's register combiners; --technique {technique} takes --shininess and computes in float",
            flag(option)
        )),
        SetupError::SpecularFilterNotDrawn { technique } => Error::Render(format!(
            "--specular-filter shapes the single pass's float specular; --technique {technique} does not draw with it (use --technique toksvig, or single-pass and its family)"
        )),
        SetupError::CubeNormalizes => Error::Usage(
            "--technique single-pass-cube normalizes by the cube map: drop --normalize math, or use --technique single-pass".into(),
        ),
        SetupError::RoughnessMapUnread { technique, specular_filter } => Error::Usage(format!(
            "--roughness-map is read by the roughness-map specular filter: add --technique roughness-map (or --specular-filter roughness-map), not --technique {technique}{}",
            match specular_filter {
                SpecularFilter::None => String::new(),
                f => format!(" with --specular-filter {}", specular_filter_value(f)),
            }
        )),
        SetupError::DetailNotDrawn { technique } => Error::Usage(format!(
            "--detail-map is laid over the normal map per pixel by single-pass and its variants, not by --technique {technique}{}: \
             add --technique single-pass (or pom, toksvig, …), or blend the detail into the normal map first \
             (`bumpmap blend BASE DETAIL -o OUT`, then --normal-map OUT), as a GeForce 256 title would have: \
             the paper's combiners have both texture units taken (the normal map, the normalization cube map)",
            if technique == bumpmap::options::TechniqueChoice::default().technique { " (the default)" } else { "" }
        )),
        SetupError::NoMinMax { path, minmax, technique } => Error::Path {
            path,
            reason: format!(
                "has no min–max levels beside it ({} not found), and --technique {technique} walks them: \
                 write the heights again with `bumpmap normalmap --mips --height-out H`, or use --technique pom",
                minmax.display()
            ),
        },
        e @ SetupError::LevelSize { .. } => Error::Render(format!("{e} (--roughness-map's levels)")),
        SetupError::Io(e) => Error::Io(e),
        SetupError::Library(e) => lib_err(e),
        e @ (SetupError::MeshValues { .. }
        | SetupError::NoExtent { .. }
        | SetupError::TooBig { .. }
        | SetupError::SizeMismatch { .. }) => Error::Render(e.to_string()),
    }
}

/// A setup note as a line for stderr, naming flags.
pub fn note_line(note: &SetupNote) -> String {
    match note {
        SetupNote::Warning(w) => format!("warning: {w}"),
        SetupNote::Replaces { path, option } => {
            format!("{}: {} replaces the material's {}", path.display(), flag(*option), SetupNote::replaced(*option))
        }
        SetupNote::NothingToScale { path } => format!(
            "{}: --bump-scale has nothing to scale: the material has no normalTexture (--height-field or --normal-map add bumps)",
            path.display()
        ),
        n @ SetupNote::OneRoughnessLevel { .. } => {
            format!("warning: {n}; `bumpmap normalmap --mips --roughness-out` writes every level")
        }
        n @ SetupNote::About { .. } => n.to_string(),
    }
}
