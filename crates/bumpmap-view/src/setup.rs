//! A scene set up from its options for drawing, with what the assets noted in words: what the
//! viewer keeps (and `bumpmap render`'s and `bench render`'s setup too).

use std::path::PathBuf;

use bumpmap::options::{Given, SceneOptions};
use bumpmap::{SceneSpec, TechniqueOptions};
use bumpmap_words::Error;
use bumpmap_words::setup::{note_line, setup_err};

/// What the options describe.
pub struct Setup {
    /// The scene, with the user's assets in it.
    pub spec: SceneSpec,
    /// The options of `--technique`'s family (and every other family's, at the values the
    /// options give).
    pub options: TechniqueOptions,
    /// Every file read: no output may replace one.
    pub inputs: Vec<PathBuf>,
    /// What the assets brought and what they left out, a line each for stderr (a warning's
    /// line starts `warning: `).
    pub notes: Vec<String>,
}

/// Sets `options` up, with the inputs `given` in memory in place of their files; what the
/// library refuses, in the flags' words.
pub fn set_up_options(options: &SceneOptions, given: &Given) -> Result<Setup, Error> {
    let set_up = options.set_up_given(given).map_err(setup_err)?;
    Ok(Setup {
        spec: set_up.spec,
        options: set_up.options,
        inputs: set_up.inputs,
        notes: set_up.notes.iter().map(note_line).collect(),
    })
}
