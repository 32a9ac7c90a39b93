use super::*;
use crate::frame::FrameRequest;
use crate::options::SceneOption;

fn all() -> Vec<&'static Opt<FrameRequest>> {
    render().collect()
}

/// A default shown in `--help` reads back, through the option, as the typed options' default:
/// setting every shown default leaves the request as it was.
#[test]
fn shown_defaults_read_back_as_the_typed_defaults() {
    let mut request = FrameRequest::default();
    let mut shown = 0;
    for row in all() {
        if let Some(text) = row.default_text() {
            let value = row.parse_text(&text).unwrap_or_else(|e| panic!("--{} {text}: {e}", row.name));
            row.set(&mut request, value).expect("a default sets");
            shown += 1;
        }
    }
    assert!(shown >= 25, "most options show a default ({shown})");
    assert_eq!(format!("{request:?}"), format!("{:?}", FrameRequest::default()));
}

#[test]
fn names_are_unique_and_what_they_need_is_a_row() {
    let rows = all();
    let names: Vec<&str> = rows.iter().map(|r| r.name).collect();
    for (i, name) in names.iter().enumerate() {
        assert!(!names[..i].contains(name), "{name} twice");
        assert!(name.chars().all(|c| c.is_ascii_lowercase() || c == '-'), "{name}: lower case words joined by -");
    }
    for row in &rows {
        for other in row.requires.iter().chain(row.conflicts) {
            assert!(names.contains(other), "{} names {other}, which is no option", row.name);
        }
    }
}

/// Every option a setup message names (`SceneOption`) is a row, by the same name.
#[test]
fn every_option_a_message_names_is_a_row() {
    for option in SceneOption::ALL {
        let name = option.name().replace('_', "-");
        assert!(find(SCENE, &name).is_some(), "{option:?} is named {name}, which is no option of SCENE");
    }
}

#[test]
fn text_is_read_as_the_kind_and_checked() {
    let row = |n| find(SCENE, n).or_else(|| find(FRAME, n)).expect("a row");
    assert_eq!(row("eye").parse_text("0,-3,1.5"), Ok(Value::Numbers(vec![0.0, -3.0, 1.5])));
    assert!(row("eye").parse_text("0,nan,1").unwrap_err().contains("three finite numbers"));
    assert_eq!(
        row("depth").parse_text("0").unwrap_err(),
        "'0' is not a depth: give a positive number of the scene's units"
    );
    assert_eq!(row("layers").parse_text("999").unwrap_err(), "999 is not in 1..=256");
    assert_eq!(row("layers").parse_text("-1").unwrap_err(), "-1 is not in 1..=256");
    assert_eq!(row("size").parse_text("100000").unwrap_err(), "'100000' is not a size in 1..=16384 pixels");
    assert_eq!(row("tessellation").parse_text("4096,64").unwrap_err(), "'4096' is not a count in 1..=2048");
    assert!(row("specular").parse_text("1e40").unwrap_err().contains("beyond single precision"));
    assert!(row("scene").parse_text("teapot").unwrap_err().starts_with("unknown scene 'teapot'"));
    assert!(row("technique").parse_text("phong").unwrap_err().contains("possible values: kilgard, single-pass"));
    assert_eq!(row("y-convention").parse_text("y-down"), Ok(Value::Word("y-down".into())), "an alias");
}

#[test]
fn values_reach_their_fields() {
    let mut r = FrameRequest::default();
    let set = |r: &mut FrameRequest, name: &str, text: &str| {
        let row = find(SCENE, name).or_else(|| find(FRAME, name)).expect("a row");
        row.set(r, row.parse_text(text).expect("parses")).expect("sets");
    };
    set(&mut r, "scene", "mesh:m.obj");
    set(&mut r, "decal", "none");
    set(&mut r, "gloss", "bricks");
    set(&mut r, "no-self-shadow", "true");
    set(&mut r, "technique", "single-pass");
    set(&mut r, "width", "40");
    set(&mut r, "height", "30");
    set(&mut r, "light", "dir:1,0,1@0.5,0.5,0.5");
    use crate::options::{DecalChoice, GlossChoice, SceneChoice};
    assert_eq!(r.options.scene, SceneChoice::Mesh("m.obj".into()));
    assert_eq!(r.options.decal, Some(DecalChoice::None));
    assert_eq!(r.options.material.gloss, GlossChoice::Bricks);
    assert_eq!(r.options.technique.self_shadow, crate::SelfShadow::Off);
    assert_eq!(r.options.technique.technique, crate::TechniqueName::SinglePass);
    assert_eq!(r.size, (40, 30));
    assert_eq!(r.options.lights.lights.len(), 1);
}

#[test]
fn options_given_together_are_checked() {
    let rows: Vec<Opt<FrameRequest>> = Vec::new();
    assert_eq!(check_together(&rows, &["spot-cutoff"]), Ok(()), "an empty table checks nothing");
    assert_eq!(check_together(SCENE, &["spot-cutoff"]), Err(Together::Needs { option: "spot-cutoff", needs: "spot" }));
    assert_eq!(check_together(SCENE, &["spot-cutoff", "spot"]), Ok(()));
    assert_eq!(
        check_together(SCENE, &["normal-map", "height-field"]),
        Err(Together::Excludes { option: "height-field", other: "normal-map" })
    );
    assert_eq!(
        check_together(FRAME, &["size", "width", "height"]),
        Err(Together::Excludes { option: "size", other: "width" })
    );
}

#[test]
fn bakes_defaults_read_back_and_its_values_reach_their_fields() {
    use crate::bake::{BakeRequest, RayMode};
    let mut request = BakeRequest::default();
    for row in BAKE {
        if let Some(text) = row.default_text() {
            let value = row.parse_text(&text).unwrap_or_else(|e| panic!("--{} {text}: {e}", row.name));
            row.set(&mut request, value).expect("a default sets");
        }
    }
    assert_eq!(request, BakeRequest::default());
    let set = |request: &mut BakeRequest, name: &str, text: &str| {
        let row = find(BAKE, name).expect("a row");
        let value = row.parse_text(text)?;
        row.set(request, value)
    };
    set(&mut request, "size", "256").unwrap();
    set(&mut request, "ray", "explicit").unwrap();
    set(&mut request, "extrude", "0.25").unwrap();
    assert_eq!((request.options.width, request.options.height), (256, 256));
    assert_eq!(request.options.rays, RayMode::Explicit);
    assert_eq!(request.options.front, Some(0.25));
    assert!(set(&mut request, "bits", "12").is_err());
    assert!(set(&mut request, "extrude", "-1").is_err());
    assert!(set(&mut request, "size", "0").is_err());
}

#[test]
fn blends_defaults_read_back_and_its_values_reach_their_fields() {
    use crate::maps::BlendOptions;
    use bumpmap_math::YConvention;
    use bumpmap_math::detail::BlendMethod;
    let mut options = BlendOptions::default();
    for row in BLEND {
        if let Some(text) = row.default_text() {
            let value = row.parse_text(&text).unwrap_or_else(|e| panic!("--{} {text}: {e}", row.name));
            row.set(&mut options, value).expect("a default sets");
        }
    }
    assert_eq!(options, BlendOptions::default());
    for (name, text) in [("method", "pd"), ("detail-y-convention", "directx"), ("bits", "16"), ("detail-repeat", "8")] {
        let row = find(BLEND, name).expect("a row");
        row.set(&mut options, row.parse_text(text).unwrap()).unwrap();
    }
    assert_eq!(options.method, BlendMethod::PartialDerivative);
    assert_eq!(options.detail_y_convention, Some(YConvention::YDown));
    assert_eq!((options.bits, options.repeat), (Some(16), 8));
    let bits = find(BLEND, "bits").unwrap();
    assert!(bits.parse_text("12").and_then(|v| bits.set(&mut options, v)).is_err());
}
