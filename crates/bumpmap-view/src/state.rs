//! The viewer's model, with no window: what the user has chosen (technique, scene, the passes
//! and options toggled, bump scale, shininess, where the camera and light are), how each
//! [`Action`] changes it, and the [`Prepared`] scene it makes. The window (`window`)
//! and `--record` (`crate::record`) only draw what this holds, so every key can be tested here
//! without a display.
//!
//! A change that cannot be drawn (a technique that cannot draw the scene, a file that cannot be
//! read) is undone: the old scene stays and the reason becomes [`Viewer::message`].
//!
//! The viewer keeps the scene's [`SceneOptions`] (the flags made into options once) and changes
//! them where a key or a dropped file asks; `state/prepare.rs` makes the scene and technique a
//! set of [`Choices`] describes.

// Built without the window (the `window` feature off), only the recording uses
// the model, and what only the window reads goes unused.
#![cfg_attr(not(feature = "window"), allow(dead_code))]

use std::path::{Path, PathBuf};

use bumpmap::Named;
use bumpmap::bumpmap_core::detail::BlendMethod;
use bumpmap::bumpmap_core::parallax::{MAX_LAYERS, ParallaxMethod};
use bumpmap::motion::{LightOrbit, MAX_TILT, orbit_camera};
use bumpmap::options::{Given, SceneChoice, SceneOptions};
use bumpmap::{
    BumpSource, Camera, MipMode, Normalize, ParallaxShadow, Prepared, ReferenceOptions, SceneKind, SpecularFilter,
    Technique, TechniqueName,
};
use bumpmap_io::HeightSource;

use super::keys::Action;

use crate::setup::{Setup, set_up_options};
use bumpmap_words::Error;

mod choices;
mod prepare;

pub use choices::{Choices, Effect, Mips, View};
use prepare::{HeightsCache, prepare};

/// The samples per pixel the reference is drawn with, one step per frame while nothing moves:
/// a rough picture at once, then more, then `--spp`'s (64 by default) a few frames later.
pub const REFERENCE_STEPS: [usize; 3] = [1, 4, 16];

/// The turns per second of the light's orbit: once in 8 s, slow enough to follow a highlight.
pub const TURNS_PER_SECOND: f32 = 0.125;

/// The viewer's state and the scene it has prepared.
pub struct Viewer {
    /// The options the scene is set up from: the flags', then what keys and dropped files
    /// changed.
    options: SceneOptions,
    base: Setup,
    /// The scenes `o` cycles through.
    pub scenes: Vec<SceneKind>,
    /// What is chosen.
    pub choices: Choices,
    /// Where things are.
    pub view: View,
    prepared: Prepared,
    home: Camera,
    orbit: LightOrbit,
    /// Steps of [`REFERENCE_STEPS`] drawn since the last move.
    reference_step: usize,
    /// The last error or note, for the overlay.
    pub message: Option<String>,
    /// The heights as geometry made from the base's height field, kept while it is the same
    /// field: depth, layers and shadow keys prepare the scene again without remaking them.
    heights: HeightsCache,
}

/// The scenes a viewer offers: the four the issue names, and the one it started on when that
/// is another (the floor, the wall on the floor, a loaded mesh).
fn scenes_with(kind: &SceneKind) -> Vec<SceneKind> {
    let mut scenes = vec![SceneKind::Torus, SceneKind::Wall, SceneKind::Sphere, SceneKind::Patch];
    if !scenes.contains(kind) {
        scenes.push(kind.clone());
    }
    scenes
}

impl Viewer {
    /// The viewer on what `options` describe (files loaded, technique prepared).
    pub fn new(options: SceneOptions) -> Result<Self, Error> {
        let base = set_up_options(&options, &Given::default())?;
        for note in &base.notes {
            say!("{note}");
        }
        let name = options.technique.technique;
        let choices = Choices {
            technique: TechniqueName::ALL.iter().position(|&t| t == name).unwrap_or(0),
            scene: 0,
            decal: true,
            diffuse: true,
            specular: true,
            self_shadow: base.options.kilgard.self_shadow,
            mips: match base.spec.params.mip_mode {
                MipMode::LengthInAlpha => Mips::LengthFactor,
                MipMode::Renormalize => Mips::Renormalized,
            },
            cube: base.options.single_pass.normalize == Normalize::Cube,
            nearest: false,
            specular_filter: base.options.single_pass.specular_filter,
            bump_scale: options.bump_scale.unwrap_or(match base.spec.params.bumps {
                BumpSource::Heights(_) => base.spec.params.normal_map.scale,
                BumpSource::NormalMap(_) => 1.0,
            }),
            shininess: base.spec.params.shininess,
            depth: base.spec.params.depth,
            layers: base.options.parallax.layers,
            parallax_shadow: base.options.parallax.shadow,
            detail: base.options.single_pass.detail.as_ref().map(|d| d.method),
        };
        let scenes = scenes_with(&base.spec.kind);
        let choices = Choices { scene: scenes.iter().position(|k| *k == base.spec.kind).unwrap_or(0), ..choices };
        let mut heights = None;
        let prepared = prepare(&base, &scenes, &choices, &mut heights).map_err(bumpmap_words::frame::lib_err)?;
        let (home, orbit) = (prepared.scene.camera, LightOrbit::of(&prepared.scene));
        Ok(Self {
            options,
            base,
            scenes,
            choices,
            view: View::default(),
            prepared,
            home,
            orbit,
            reference_step: 0,
            message: None,
            heights,
        })
    }

    /// Every file the scene shown was read from (a glTF's buffers and images, levels found
    /// beside a file): no recording or screenshot may replace one.
    pub fn inputs(&self) -> &[PathBuf] {
        &self.base.inputs
    }

    /// The technique chosen.
    pub fn technique(&self) -> TechniqueName {
        TechniqueName::ALL[self.choices.technique]
    }

    /// The scene as it is to be drawn now: the light and camera where the view has them, the
    /// reference at its next number of samples.
    pub fn frame(&mut self) -> &Prepared {
        self.orbit.place(&mut self.prepared.scene, self.view.turns, self.view.light_tilt);
        self.prepared.scene.camera = orbit_camera(&self.home, self.view.yaw, self.view.pitch, self.view.zoom);
        if let Technique::Reference(options) = &mut self.prepared.technique {
            let full = self.base.options.reference.samples_per_pixel;
            let spp = REFERENCE_STEPS.get(self.reference_step).map_or(full, |&s| s.min(full));
            *options = ReferenceOptions { samples_per_pixel: spp, ..*options };
            self.reference_step = (self.reference_step + 1).min(REFERENCE_STEPS.len() + 1);
        }
        &self.prepared
    }

    /// Whether another frame would differ from the last: the light orbiting, or the reference
    /// still refining.
    pub fn animating(&self) -> bool {
        !self.view.paused || (self.technique().is_reference() && self.reference_step <= REFERENCE_STEPS.len())
    }

    /// The next frame as if nothing had moved for a while: the reference at its full samples.
    pub fn settle(&mut self) {
        self.reference_step = REFERENCE_STEPS.len();
    }

    /// Advances the light's orbit by `seconds` (nothing while paused).
    pub fn advance(&mut self, seconds: f32) {
        if !self.view.paused && seconds > 0.0 {
            self.view.turns = (self.view.turns + seconds * TURNS_PER_SECOND).fract();
            self.moved();
        }
    }

    /// The scene moved: the reference starts refining again.
    pub fn moved(&mut self) {
        self.reference_step = 0;
    }

    /// Turns the camera (left-drag) by `dx`, `dy` radians.
    pub fn orbit_camera(&mut self, dx: f32, dy: f32) {
        self.view.yaw -= dx;
        self.view.pitch = (self.view.pitch + dy).clamp(-MAX_TILT, MAX_TILT);
        self.moved();
    }

    /// Moves the light (right-drag) by `dx` of a turn round and `dy` radians up.
    pub fn move_light(&mut self, dx: f32, dy: f32) {
        self.view.turns = (self.view.turns + dx).rem_euclid(1.0);
        self.view.light_tilt = (self.view.light_tilt + dy).clamp(-MAX_TILT, MAX_TILT);
        self.moved();
    }

    /// Zooms by `steps` wheel notches (positive: closer).
    pub fn zoom(&mut self, steps: f32) {
        self.view.zoom = (self.view.zoom * 0.9f32.powf(steps)).clamp(0.1, 20.0);
        self.moved();
    }

    /// Does what `action` asks; a change that cannot be drawn is undone and named in
    /// [`Viewer::message`].
    pub fn apply(&mut self, action: Action) -> Effect {
        let mut c = self.choices.clone();
        let v = &mut self.view;
        match action {
            Action::Pause => v.paused = !v.paused,
            Action::Wireframe => v.wireframe = !v.wireframe,
            Action::FrameRate => v.frame_rate = !v.frame_rate,
            Action::Help => v.help = !v.help,
            Action::ResetView => {
                // Where they started; what is shown and whether the orbit runs stay.
                let keep = View {
                    paused: v.paused,
                    wireframe: v.wireframe,
                    frame_rate: v.frame_rate,
                    help: v.help,
                    ..View::default()
                };
                *v = keep;
            }
            Action::Screenshot => return Effect::Screenshot,
            Action::Backend => return Effect::SwitchBackend,
            Action::Quit => return Effect::Quit,
            Action::NextTechnique => return self.step_technique(1),
            Action::PreviousTechnique => return self.step_technique(TechniqueName::ALL.len() - 1),
            Action::NextScene => c.scene = (c.scene + 1) % self.scenes.len(),
            Action::Decal => c.decal = !c.decal,
            Action::Diffuse => c.diffuse = !c.diffuse,
            Action::Specular => c.specular = !c.specular,
            Action::SelfShadow => c.self_shadow = !c.self_shadow,
            Action::MipMode => c.mips = c.mips.next(),
            Action::Normalize => c.cube = !c.cube,
            Action::Filter => c.nearest = !c.nearest,
            Action::SpecularFilter => {
                c.specular_filter = match c.specular_filter {
                    SpecularFilter::None => SpecularFilter::Toksvig,
                    SpecularFilter::Toksvig => SpecularFilter::RoughnessMap,
                    SpecularFilter::RoughnessMap => SpecularFilter::Lean,
                    SpecularFilter::Lean => SpecularFilter::Clean,
                    SpecularFilter::Clean => SpecularFilter::None,
                }
            }
            Action::BumpsUp => c.bump_scale *= 1.25,
            Action::BumpsDown => c.bump_scale /= 1.25,
            Action::ShininessUp => c.shininess = (c.shininess * 1.5).min(1e4),
            Action::ShininessDown => c.shininess = (c.shininess / 1.5).max(0.5),
            Action::DepthUp | Action::DepthDown => match self.depth() {
                Some(d) => c.depth = Some(if action == Action::DepthUp { d * 1.25 } else { d / 1.25 }),
                None => self.message = Some(format!("{} takes no heights as geometry", self.technique().name())),
            },
            Action::LayersUp => c.layers = (c.layers * 2).min(MAX_LAYERS),
            Action::LayersDown => c.layers = (c.layers / 2).max(1),
            Action::ParallaxShadow if self.technique() == TechniqueName::Horizon => {
                self.message =
                    Some("horizon always shadows by the horizon map: the shadow key cycles the marches' shadows".into())
            }
            Action::ParallaxShadow => c.parallax_shadow = c.parallax_shadow.next(),
            Action::Detail if self.base.options.single_pass.detail.is_none() => {
                self.message = Some("no detail map to blend: start the viewer with --detail-map FILE".into())
            }
            Action::Detail => {
                let all = BlendMethod::ALL;
                c.detail = match c.detail {
                    None => Some(all[0]),
                    Some(m) => all.iter().position(|&x| x == m).and_then(|i| all.get(i + 1)).copied(),
                }
            }
        }
        self.moved();
        if c != self.choices {
            self.choose(c);
        }
        Effect::Redraw
    }

    /// The next technique `step` places on (modulo the catalogue) that can draw the scene;
    /// those skipped are named.
    fn step_technique(&mut self, step: usize) -> Effect {
        let n = TechniqueName::ALL.len();
        let mut skipped = Vec::new();
        let mut c = self.choices.clone();
        for _ in 1..n {
            c.technique = (c.technique + step) % n;
            let name = TechniqueName::ALL[c.technique];
            if self.choose(c.clone()) {
                if !skipped.is_empty() {
                    self.message = Some(format!("skipped {} (they cannot draw this scene)", skipped.join(", ")));
                }
                return Effect::Redraw;
            }
            skipped.push(name.name());
        }
        self.message = Some("no other technique can draw this scene".into());
        Effect::Redraw
    }

    /// Prepares the scene for `choices`; keeps them when that works, else keeps the old ones
    /// and says why. Whether it worked.
    fn choose(&mut self, choices: Choices) -> bool {
        if choices.bump_scale != self.choices.bump_scale
            && matches!(self.base.spec.params.bumps, BumpSource::NormalMap(_))
        {
            // A normal map's scale is applied as it is read (glTF's normalTexture.scale).
            let options = SceneOptions { bump_scale: Some(choices.bump_scale), ..self.options.clone() };
            match set_up_options(&options, &Given::default()) {
                Ok(base) => {
                    self.options = options;
                    self.base = base;
                }
                Err(e) => {
                    self.message = Some(e.to_string());
                    return false;
                }
            }
        }
        match prepare(&self.base, &self.scenes, &choices, &mut self.heights) {
            Ok(prepared) => {
                self.message = None;
                self.set_prepared(prepared);
                self.choices = choices;
                self.moved();
                true
            }
            Err(e) => {
                self.message = Some(format!("{}: {e}", TechniqueName::ALL[choices.technique].name()));
                false
            }
        }
    }

    /// Takes a newly prepared scene: the camera and the light's orbit start from its own.
    fn set_prepared(&mut self, prepared: Prepared) {
        self.home = prepared.scene.camera;
        self.orbit = LightOrbit::of(&prepared.scene);
        self.prepared = prepared;
    }

    /// Loads `path` in place: a mesh (OBJ, glTF, GLB) replaces the surface, a height field or
    /// normal map goes onto it. A file that cannot be read leaves everything as it was, with
    /// the reason in [`Viewer::message`]; the message on success says what it was taken for.
    pub fn load(&mut self, path: &Path) -> Result<String, String> {
        let mut options = self.options.clone();
        let what = super::files::classify(path)?;
        let shown = path.display();
        let note = match what {
            super::files::Kind::Mesh => {
                options.scene = SceneChoice::Mesh(path.to_path_buf());
                format!("{shown}: a mesh, replacing the surface")
            }
            super::files::Kind::HeightField => {
                // The file itself, even where its name reads as a preset's ("bricks").
                options.height_field = Some(HeightSource::File(path.to_path_buf()));
                options.normal_map = None;
                options.bump_scale = None;
                format!("{shown}: a height field")
            }
            super::files::Kind::NormalMap => {
                options.normal_map = Some(path.to_path_buf());
                options.height_field = None;
                options.bump_scale = None;
                format!("{shown}: a normal map")
            }
        };
        let base = set_up_options(&options, &Given::default()).map_err(|e| e.to_string())?;
        let scenes = scenes_with(&base.spec.kind);
        let mut choices = self.choices.clone();
        if let super::files::Kind::Mesh = what {
            choices.scene = scenes.iter().position(|k| *k == base.spec.kind).unwrap_or(0);
        } else {
            choices.scene = choices.scene.min(scenes.len() - 1);
        }
        choices.bump_scale = match base.spec.params.bumps {
            BumpSource::Heights(_) => base.spec.params.normal_map.scale,
            BumpSource::NormalMap(_) => 1.0,
        };
        // Try the chosen technique first, then any that can draw what was loaded.
        let n = TechniqueName::ALL.len();
        let found = (0..n).map(|k| (choices.technique + k) % n).find_map(|t| {
            let c = Choices { technique: t, ..choices.clone() };
            prepare(&base, &scenes, &c, &mut self.heights).ok().map(|p| (c, p))
        });
        let Some((choices, prepared)) = found else {
            return Err(format!("{shown}: no technique can draw it"));
        };
        self.options = options;
        self.base = base;
        self.scenes = scenes;
        self.choices = choices;
        self.set_prepared(prepared);
        self.moved();
        self.message = Some(note.clone());
        Ok(note)
    }

    /// The depth of the heights as geometry drawn now, where the technique takes them.
    pub fn depth(&self) -> Option<f32> {
        self.prepared.scene.objects.iter().find(|o| o.material.heights.is_some()).map(|o| o.material.depth)
    }

    /// One line saying what is drawn and with which options, for the overlay.
    pub fn status(&self) -> String {
        let c = &self.choices;
        let mut off: Vec<&str> = Vec::new();
        for (on, name) in [(c.decal, "decal"), (c.diffuse, "diffuse"), (c.specular, "specular")] {
            if !on {
                off.push(name);
            }
        }
        if !c.self_shadow {
            off.push("self-shadow");
        }
        let heights = match self.depth() {
            Some(d) => {
                let shadow = match c.parallax_shadow {
                    _ if self.technique() == TechniqueName::Horizon => " | horizon shadows".to_string(),
                    ParallaxShadow::Off => String::new(),
                    s => format!(" | {} shadows", s.name()),
                };
                let marches = self.technique().parallax_method().is_some_and(|m| m != ParallaxMethod::Flat);
                let layers = if marches { format!(" | layers {}", c.layers) } else { String::new() };
                format!(" | depth {d:.4}{layers}{shadow}")
            }
            None => String::new(),
        };
        // The filter the technique drawn applies (kilgard and emboss apply none, whatever `g`
        // chose; toksvig and lean apply their own), and the detail it lays over the normal map.
        let (filter, detail) = match &self.prepared.technique {
            Technique::SinglePass(o) => (o.specular_filter, o.detail.as_ref()),
            _ => (SpecularFilter::None, None),
        };
        let detail = detail.map(|d| format!(" | detail {} x{}", d.method.name(), d.repeat)).unwrap_or_default();
        format!(
            "{}{heights} | {} | bumps {:.2} | shininess {:.1} | mips {} | {}{}{}{detail}{}",
            self.technique().name(),
            self.scenes[c.scene].name(),
            c.bump_scale,
            c.shininess,
            c.mips.name(),
            if c.nearest { "nearest" } else { "trilinear" },
            if c.cube { " | cube map" } else { "" },
            match filter {
                SpecularFilter::None => "",
                SpecularFilter::Toksvig => " | toksvig",
                SpecularFilter::RoughnessMap => " | roughness map",
                SpecularFilter::Lean => " | LEAN",
                SpecularFilter::Clean => " | CLEAN",
            },
            if off.is_empty() { String::new() } else { format!(" | off: {}", off.join(", ")) },
        )
    }
}

#[cfg(test)]
mod tests;
