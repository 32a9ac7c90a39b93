//! The option groups `render`, `bench render` and `view` share, turned into the library's
//! [`SceneOptions`] and set up there; what the library refuses or notes, put in the command
//! line's words by `bumpmap_words::setup` (the flag that caused it). Values out of range are
//! usage errors (status 2).
//!
//! What this module does not do: read the flags (the library's option table, through
//! `crate::args`), check a value, load a file or build a scene (all
//! `bumpmap::options`'s), or draw (`bumpmap::Renderer`).

use bumpmap::options::SceneOptions;

use crate::args::SceneSetup;
use crate::error::CliError;

pub use bumpmap::options::Given;
pub use bumpmap_view::{Setup, set_up_options};

/// Reads the options: checks their ranges, loads the files they name and builds the scene
/// description, the technique and its options.
pub fn setup(s: &SceneSetup) -> Result<Setup, CliError> {
    set_up_options(&s.0.options, &Given::default())
}

/// The library's options as the flags give them (the table read them: `crate::args::SceneSetup`).
pub fn scene_options(s: &SceneSetup) -> SceneOptions {
    s.0.options.clone()
}

#[cfg(test)]
mod tests {
    use clap::{CommandFactory, Parser};

    use bumpmap::SelfShadow;
    use bumpmap::options::{DecalChoice, GlossChoice, SceneChoice, SceneOption};
    use bumpmap_words::setup::flag;

    use super::*;
    use crate::args::{Cli, Command};

    fn render_setup(words: &[&str]) -> SceneSetup {
        let argv = ["bumpmap", "render"].iter().chain(words);
        match Cli::try_parse_from(argv).expect("parses").command {
            Command::Render(a) => a.setup,
            _ => unreachable!("render parses as render"),
        }
    }

    #[test]
    fn the_flags_defaults_are_the_librarys() {
        // Debug text compares every field, floats included, without the options needing
        // PartialEq (a light's spotlight pattern is an image).
        let from_flags = scene_options(&render_setup(&[]));
        assert_eq!(format!("{from_flags:?}"), format!("{:?}", SceneOptions::default()));
    }

    #[test]
    fn renders_defaults_are_the_requests() {
        let args = match Cli::try_parse_from(["bumpmap", "render"]).expect("parses").command {
            Command::Render(a) => a,
            _ => unreachable!("render parses as render"),
        };
        let from_flags = crate::render::frame_request(&args).expect("the defaults set up");
        assert_eq!(format!("{from_flags:?}"), format!("{:?}", bumpmap::frame::FrameRequest::default()));
    }

    #[test]
    fn every_option_a_message_names_is_a_flag_of_render() {
        let command = Cli::command();
        let render = command.find_subcommand("render").expect("render exists");
        for option in SceneOption::ALL {
            let flag = flag(option);
            assert!(
                render.get_arguments().any(|a| a.get_long() == flag.strip_prefix("--")),
                "{option:?} is named {flag}, which render does not take"
            );
        }
    }

    #[test]
    fn flags_reach_the_library_as_typed_values() {
        let o = scene_options(&render_setup(&[
            "--scene",
            "mesh:m.obj",
            "--decal",
            "none",
            "--gloss",
            "bricks",
            "--no-self-shadow",
            "--technique",
            "single-pass",
            "--filter",
            "nearest",
        ]));
        assert_eq!(o.scene, SceneChoice::Mesh(std::path::PathBuf::from("m.obj")));
        assert_eq!(o.decal, Some(DecalChoice::None));
        assert_eq!(o.material.gloss, GlossChoice::Bricks);
        assert_eq!(o.technique.self_shadow, SelfShadow::Off);
        assert_eq!(o.technique.filter, Some(bumpmap::options::Filter::Nearest));
        assert_eq!(o.technique.technique, bumpmap::TechniqueName::SinglePass);
    }
}
