//! What `bumpmap_compare` refused ([`CompareError`]), named by the flags that caused it, and
//! what it noted ([`CompareNote`]).

use std::path::Path;

use bumpmap::SceneKind;
use bumpmap_compare::{CompareError, CompareNote};

use crate::Error;

/// What `bumpmap_compare` refused, in the words of the command line; `args`, where given, names
/// the height field and the output.
pub fn compare_err(e: CompareError, bumps: Option<&str>, output: Option<&Path>) -> Error {
    match e {
        CompareError::NotASurface(kind) => Error::Usage(format!(
            "--scene {}: compare takes a built-in surface ({}), because the reference evaluates the exact surface",
            kind.name(),
            SceneKind::built_in_names()
        )),
        CompareError::BumpScale(b) => Error::Usage(format!("--bump-scale must be a number ≥ 0, got {b}")),
        CompareError::Spp(spp) => {
            Error::Usage(format!("--spp must be in 1..={}, got {spp}", bumpmap::options::MAX_SAMPLES_PER_PIXEL))
        }
        CompareError::Twice(name) => Error::Usage(format!("--techniques names {name} twice")),
        CompareError::TooBig { source, bumps: (w, h) } => Error::Render(format!(
            "this scene (bumps {w}x{h}{}) is too big for the memory this process may use: {source}. \
             The README's \"Memory\" section gives what the largest inputs need; a smaller --height-field needs less",
            bumps.map(|b| format!(" from {b}")).unwrap_or_default()
        )),
        CompareError::BlackReference => Error::Path {
            path: output.map(Path::to_path_buf).unwrap_or_default(),
            reason:
                "not written: the reference is black (nothing in view is lit); try another --scene or --height-field"
                    .into(),
        },
        CompareError::OutputIsAFile(path) => {
            Error::Path { path, reason: "is a file; compare writes a folder of results".into() }
        }
        CompareError::Interrupted => Error::Interrupted,
        CompareError::Reference(e) => Error::Render(crate::frame::reference_err(e)),
        CompareError::Io(e) => Error::Io(e),
        CompareError::Library(e) => crate::library::lib_err(e),
        e @ (CompareError::Study { .. } | CompareError::NormalMap { .. }) => Error::Render(e.to_string()),
    }
}

/// A note `compare` makes as it goes, as a line.
pub fn note_line(note: &CompareNote) -> String {
    match note {
        CompareNote::Skipped { name, reason } => format!("skipped {name}: {reason}"),
        CompareNote::OnTheCpu { reason } => crate::frame::on_the_cpu(reason),
    }
}
