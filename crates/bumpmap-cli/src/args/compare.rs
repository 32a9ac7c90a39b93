//! `bumpmap compare`'s options.

use std::path::PathBuf;

use bumpmap_compare::CompareOptions;
use bumpmap_compare::option_table::COMPARE;
use clap::Args;

use crate::args::table::{Table, rows};

rows!(
    /// What `compare` measures: the library's [`COMPARE`] table.
    Compare: CompareOptions = COMPARE
);

/// `bumpmap compare`.
#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap compare                                    # the torus, out/compare/report.html\n  \
bumpmap compare --scene patch --height-field pinwheel --spp 256\n  \
bumpmap compare --techniques kilgard,single-pass --backend gpu\n  \
bumpmap compare --techniques pom,height-exact --studies parallax\n\n\
Writes OUT/results.json (every score), OUT/report.html (images, FLIP heat maps, the table and \
plots; relative links only, so the folder can be copied), one PNG per technique and its \
FLIP heat map, and the plots as SVG. A technique that cannot render the scene is skipped, with \
its reason on stderr and in the report.\n\n\
Whatever the scene, the report also makes studies (--studies), each on its own scene: Kilgard \
§2.4.2's golf ball at a distance (the length factor against renormalized mips) and §2.5.3's \
highlight at a distance (by specular filter), §3.1's embossing (flat head-on, lost at a distance, \
lit where the light is behind), Peercy's Figures 5–7 on his stretched patch (per-pixel Blinn, the \
surface-dependent and the surface-independent map, at bump scales 1, 2 and 4), and heights as \
geometry (every parallax technique on a brick wall at 30° to 85°: hit error, shadows, FLIP and \
cost against the displaced reference).")]
pub struct CompareArgs {
    /// What is measured: the library's [`COMPARE`] table.
    #[command(flatten)]
    pub options: Table<Compare>,
    /// Output folder
    #[arg(short, long, default_value = "out/compare")]
    pub output: PathBuf,
}
