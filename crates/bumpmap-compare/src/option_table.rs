//! `compare`'s options as the library's option table (`bumpmap::option_table`): the command
//! line's `compare` and Python's `compare` are made from [`COMPARE`].

use bumpmap::frame::MAX_SIDE;
use bumpmap::option_table::{Access, Choice, Kind, Opt, Value};
use bumpmap::{Named, SceneKind};
use bumpmap_io::HeightSource;

use crate::{CompareOptions, Study};

/// `compare`'s options are listed with the command's own.
const COMMAND: &str = "";

type Row = Opt<CompareOptions>;

/// An image side in 1..=[`MAX_SIDE`] pixels.
fn side(v: &Value) -> Result<(), String> {
    match v {
        Value::Whole(n) if (1..=MAX_SIDE as u64).contains(n) => Ok(()),
        _ => Err(format!("'{v}' is not a size in 1..={MAX_SIDE} pixels")),
    }
}

/// The studies' words: all, none, then each study.
fn study_words() -> Vec<Choice> {
    let all = Choice { name: "all", aliases: &[], help: "every study".into() };
    let none = Choice { name: "none", aliases: &[], help: "none: the table alone".into() };
    [all, none]
        .into_iter()
        .chain(Study::ALL.iter().map(|s| Choice { name: s.name(), aliases: &[], help: s.help() }))
        .collect()
}

/// Names the catalogue knows (a technique that cannot draw the scene is still skipped, with its
/// reason, when the work runs; a name that is none is refused before it).
fn technique_names(v: &Value) -> Result<(), String> {
    let Value::Words(names) = v else { return Err(format!("{v} is not a list of techniques")) };
    match names.iter().find(|n| bumpmap::TechniqueName::parse(n).is_err()) {
        Some(unknown) => {
            Err(format!("'{unknown}' is not a technique (`bumpmap render --help` lists them under --technique)"))
        }
        None => Ok(()),
    }
}

fn text(v: Value) -> Result<String, String> {
    match v {
        Value::Text(t) => Ok(t),
        other => Err(format!("{other} is not a name")),
    }
}

/// What `compare` measures.
pub static COMPARE: &[Opt<CompareOptions>] = &[
    Row::with(
        "scene",
        COMMAND,
        "Built-in scene: torus, wall, floor, wall-floor, patch, sphere (the reference needs an exact surface)",
        Access::Custom {
            kind: || Kind::Text,
            get: |o| Some(Value::Text(o.scene.name().to_string())),
            set: |o, v| {
                let name = text(v)?;
                o.scene = SceneKind::parse(&name).ok_or_else(|| {
                format!(
                    "unknown scene '{name}': compare takes a built-in surface ({}), because the reference evaluates the exact surface",
                    SceneKind::built_in_names()
                )
            })?;
                Ok(())
            },
        },
    ),
    Row::with(
        "height-field",
        COMMAND,
        "Height field: image file or preset (bricks, pinwheel, dimples, noise:SEED[@SIZE])",
        Access::Custom {
            kind: || Kind::Text,
            // A preset at its default size shows as its name alone, as it is typed.
            get: |o| {
                Some(Value::Text(match &o.height_field {
                    HeightSource::Preset { preset, size } if *size == bumpmap::HeightPreset::DEFAULT_SIZE => {
                        preset.to_string()
                    }
                    other => other.to_string(),
                }))
            },
            set: |o, v| {
                o.height_field = HeightSource::parse(&text(v)?);
                Ok(())
            },
        },
    ),
    Row::new("bump-scale", COMMAND, "Bump scale: the height of a unit step, in texels", |o| &mut o.bump_scale),
    Row::new("size", COMMAND, "Square image size in pixels", |o| &mut o.size).check(side).range(1, MAX_SIDE as u64),
    Row::new(
        "spp",
        COMMAND,
        "The reference's samples per pixel (stratified); the convergence plot uses 1, 4, 16, … up to it",
        |o| &mut o.spp,
    )
    .range(1, bumpmap::options::MAX_SAMPLES_PER_PIXEL as u64),
    Row::word("backend", COMMAND, "What draws the techniques (the reference always runs on the CPU)", |o| {
        &mut o.backend
    }),
    Row::new(
        "techniques",
        COMMAND,
        "Comma-separated techniques to run (default: every technique of the catalogue, `bumpmap render --help` lists them, but the two references they are measured against)",
        |o| &mut o.techniques,
    )
    .check(technique_names),
    Row::with(
        "studies",
        COMMAND,
        "The studies the report makes besides the table, comma-separated: golf-ball (Kilgard §2.4.2), specular (§2.5.3's highlight at a distance), emboss (§3.1), peercy (Figures 5–7), parallax (heights as geometry on the wall at grazing angles), shadows (bumps that shadow each other, ambient occlusion and bent normals, against rays), detail (detail normals: every blend against added heights and draped detail); all, or none for the table alone",
        Access::Custom {
            kind: || Kind::List(Some(study_words())),
            get: |o| {
                let words = if o.studies == Study::ALL {
                    vec!["all".to_string()]
                } else {
                    o.studies.iter().map(|s| s.name().to_string()).collect()
                };
                Some(Value::Words(words))
            },
            set: |o, v| {
                let Value::Words(words) = v else { return Err(format!("{v} is not a list of studies")) };
                if let Some(w) =
                    words.iter().find(|w| !(*w == "all" || *w == "none" || <Study as Named>::parse(w).is_some()))
                {
                    let names: Vec<&str> = study_words().iter().map(|c| c.name).collect();
                    return Err(format!("invalid value '{w}'; possible values: {}", names.join(", ")));
                }
                o.studies = Study::ALL
                    .into_iter()
                    .filter(|s| words.iter().any(|w| w == "all" || w == s.name()))
                    .filter(|_| !words.iter().any(|w| w == "none"))
                    .collect();
                Ok(())
            },
        },
    ),
];
