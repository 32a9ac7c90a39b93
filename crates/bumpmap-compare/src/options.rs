//! What `compare` is asked to measure, and how it tells its progress.

use std::cell::Cell;

use bumpmap::{BackendChoice, HeightPreset, SceneKind};
use bumpmap_io::HeightSource;

/// What to measure. The defaults are `bumpmap compare`'s (a test holds the two together).
#[derive(Clone, Debug)]
pub struct CompareOptions {
    /// A built-in surface: the reference evaluates the exact surface.
    pub scene: SceneKind,
    /// The height field the bumps come from.
    pub height_field: HeightSource,
    /// Its scale: the height of a unit step, in texels (≥ 0).
    pub bump_scale: f32,
    /// The images' side in pixels.
    pub size: usize,
    /// The reference's samples per pixel; the convergence study uses 1, 4, 16, … up to it.
    pub spp: u32,
    /// What draws the techniques (the reference always runs on the CPU).
    pub backend: BackendChoice,
    /// The techniques to draw, by name (empty: every technique of the catalogue but the two
    /// references). A name the catalogue does not know is skipped, with its reason.
    pub techniques: Vec<String>,
    /// The studies made besides the table.
    pub studies: Vec<Study>,
}

impl Default for CompareOptions {
    fn default() -> Self {
        CompareOptions {
            scene: SceneKind::Torus,
            height_field: HeightSource::Preset { preset: HeightPreset::Bricks, size: HeightPreset::DEFAULT_SIZE },
            bump_scale: 4.0,
            size: 256,
            spp: 64,
            backend: BackendChoice::Cpu,
            techniques: Vec::new(),
            studies: Study::ALL.to_vec(),
        }
    }
}

impl CompareOptions {
    /// Whether `study` is asked for.
    pub fn runs(&self, study: Study) -> bool {
        self.studies.contains(&study)
    }
}

/// A study of the report, made on its own scene whatever the options' scene is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Study {
    /// A dimpled sphere at a distance: the length factor against renormalized mips (Kilgard
    /// §2.4.2).
    GolfBall,
    /// The golf ball's highlight at a distance by specular filter (Kilgard §2.5.3).
    Specular,
    /// Embossing head-on, at a distance and lit from behind (Kilgard §3.1).
    Emboss,
    /// Peercy's Figures 5–7 on his stretched patch.
    Peercy,
    /// Heights as geometry: every march against the displaced reference on a wall at 30°–85°.
    Parallax,
    /// Bumps that shadow each other against shadow rays; ambient occlusion and bent normals
    /// against occlusion rays.
    Shadows,
    /// Detail normals: every blend against added heights and draped detail.
    Detail,
}

impl Study {
    /// Every study, in the report's order.
    pub const ALL: [Study; 7] = [
        Study::GolfBall,
        Study::Specular,
        Study::Emboss,
        Study::Peercy,
        Study::Parallax,
        Study::Shadows,
        Study::Detail,
    ];

    /// Its name, as the command line and Python take it.
    pub const fn name(self) -> &'static str {
        match self {
            Study::GolfBall => "golf-ball",
            Study::Specular => "specular",
            Study::Emboss => "emboss",
            Study::Peercy => "peercy",
            Study::Parallax => "parallax",
            Study::Shadows => "shadows",
            Study::Detail => "detail",
        }
    }

    /// What it shows, in a line.
    pub const fn description(self) -> &'static str {
        match self {
            Study::GolfBall => {
                "a dimpled sphere at a distance: the length factor against renormalized mips (Kilgard §2.4.2)"
            }
            Study::Specular => "the golf ball's highlight at a distance by specular filter (Kilgard §2.5.3)",
            Study::Emboss => "embossing head-on, at a distance and lit from behind (Kilgard §3.1)",
            Study::Peercy => "Peercy's Figures 5–7 on his stretched patch",
            Study::Parallax => "heights as geometry: every march against the displaced reference on a wall at 30°–85°",
            Study::Shadows => {
                "bumps that shadow each other (horizon map, POM's march, Eq. 12) against shadow rays, lights 45°–80°; ambient occlusion and bent normals against 256 rays a texel"
            }
            Study::Detail => {
                "detail normals: every blend (RNM, partial derivatives, whiteout, UDN, linear, overlay) of noise over bricks and dimples against added heights and draped detail"
            }
        }
    }
}

impl bumpmap::Named for Study {
    const ALL: &'static [Self] = &Study::ALL;

    fn name(self) -> &'static str {
        Study::name(self)
    }

    fn description(self) -> &'static str {
        Study::description(self)
    }
}

/// Something `compare` tells as it goes besides its steps.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CompareNote {
    /// A technique that cannot draw the scene, and why (also kept in the results).
    Skipped {
        /// The technique's name as asked for.
        name: String,
        /// Why it was skipped.
        reason: String,
    },
    /// [`BackendChoice::Auto`] found no GPU and draws on the CPU.
    OnTheCpu {
        /// Why there is no GPU.
        reason: String,
    },
}

/// Told `compare`'s steps as they are taken; every method does nothing unless overridden, and
/// `()` is the observer that shows nothing.
pub trait Progress {
    /// The work has `steps` steps.
    fn start(&self, steps: u64) {
        let _ = steps;
    }
    /// What the next step does, in words.
    fn step(&self, what: &str) {
        let _ = what;
    }
    /// `done` steps of the total are done.
    fn advance(&self, done: u64) {
        let _ = done;
    }
    /// Something to tell besides the steps.
    fn note(&self, note: &CompareNote) {
        let _ = note;
    }
    /// Every step is done.
    fn finish(&self) {}
}

impl Progress for () {}

/// The steps counted for a [`Progress`].
pub(crate) struct Steps<'a> {
    progress: &'a dyn Progress,
    done: Cell<u64>,
}

impl<'a> Steps<'a> {
    pub(crate) fn new(progress: &'a dyn Progress, steps: u64) -> Self {
        progress.start(steps);
        Steps { progress, done: Cell::new(0) }
    }

    pub(crate) fn set_message(&self, what: impl AsRef<str>) {
        self.progress.step(what.as_ref());
    }

    pub(crate) fn inc(&self) {
        self.done.set(self.done.get() + 1);
        self.progress.advance(self.done.get());
    }

    pub(crate) fn finish(&self) {
        self.progress.finish();
    }
}
