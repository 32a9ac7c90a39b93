//! `bumpmap compare`'s options.

use std::path::PathBuf;

use bumpmap_compare::Study;
use clap::Args;

use crate::args::{parse_f32, parse_side};

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
    /// Built-in scene: torus, wall, floor, wall-floor, patch, sphere (the reference needs an exact surface)
    #[arg(long, default_value = "torus")]
    pub scene: String,
    /// Height field: image file or preset (bricks, pinwheel, dimples, noise:SEED[@SIZE])
    #[arg(long = "height-field", default_value = "bricks")]
    pub height_field: String,
    /// Bump scale: the height of a unit step, in texels
    #[arg(value_parser = parse_f32, long = "bump-scale", default_value_t = 4.0)]
    pub bump_scale: f32,
    /// Square image size in pixels
    #[arg(long, default_value_t = 256, value_parser = parse_side)]
    pub size: usize,
    /// The reference's samples per pixel (stratified); the convergence plot uses 1, 4, 16, … up to it
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub spp: u32,
    /// What draws the techniques (the reference always runs on the CPU)
    #[arg(long, value_parser = crate::args::choice::<bumpmap::BackendChoice>(), default_value = "cpu")]
    pub backend: bumpmap::BackendChoice,
    /// Comma-separated techniques to run (default: every technique of the catalogue, `bumpmap render --help` lists them, but the two references they are measured against)
    #[arg(long, value_delimiter = ',')]
    pub techniques: Vec<String>,
    /// The studies the report makes besides the table, comma-separated: golf-ball (Kilgard §2.4.2), specular (§2.5.3's highlight at a distance), emboss (§3.1), peercy (Figures 5–7), parallax (heights as geometry on the wall at grazing angles), shadows (bumps that shadow each other, ambient occlusion and bent normals, against rays); all, or none for the table alone
    #[arg(long, value_enum, value_delimiter = ',', default_value = "all")]
    pub studies: Vec<StudyArg>,
    /// Output folder
    #[arg(short, long, default_value = "out/compare")]
    pub output: PathBuf,
}

/// A study of `compare`'s report (`bumpmap_compare::Study`), or all or none of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StudyArg {
    /// every study
    All,
    /// none: the table alone
    None,
    /// one study
    One(Study),
}

impl clap::ValueEnum for StudyArg {
    fn value_variants<'a>() -> &'a [Self] {
        const ALL: [StudyArg; Study::ALL.len() + 2] = {
            let mut all = [StudyArg::All; Study::ALL.len() + 2];
            all[1] = StudyArg::None;
            let mut i = 0;
            while i < Study::ALL.len() {
                all[i + 2] = StudyArg::One(Study::ALL[i]);
                i += 1;
            }
            all
        };
        &ALL
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        use clap::builder::PossibleValue;
        Some(match self {
            StudyArg::All => PossibleValue::new("all").help("every study"),
            StudyArg::None => PossibleValue::new("none").help("none: the table alone"),
            StudyArg::One(s) => PossibleValue::new(s.name()).help(s.description()),
        })
    }
}

impl CompareArgs {
    /// The studies asked for, in the report's order.
    pub fn studies(&self) -> Vec<Study> {
        if self.studies.contains(&StudyArg::None) {
            return Vec::new();
        }
        let all = self.studies.contains(&StudyArg::All);
        Study::ALL.into_iter().filter(|s| all || self.studies.contains(&StudyArg::One(*s))).collect()
    }
}
