//! What a key does in the viewer: one closed set of actions, each with the key that triggers
//! it, its name for `--keys` and its line in the help overlay. The window, `--keys` and the
//! overlay all read this table; nothing else names a key.

/// Something the user can ask of the viewer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Action {
    /// Pause or resume the light's orbit.
    Pause,
    /// The next technique of the catalogue.
    NextTechnique,
    /// The previous technique.
    PreviousTechnique,
    /// The next scene (torus, wall, sphere, patch, the loaded mesh).
    NextScene,
    /// The decal (Kilgard Figure 12's first pass) on or off.
    Decal,
    /// The diffuse pass on or off.
    Diffuse,
    /// The specular pass on or off.
    Specular,
    /// Self-shadowing (Kilgard Eq. 11/12) on or off.
    SelfShadow,
    /// The mip mode: the length factor, renormalized, none (level 0 only).
    MipMode,
    /// Per-fragment normalization by the cube map or by math.
    Normalize,
    /// The textures' filter: trilinear or nearest.
    Filter,
    /// The specular filter: none, Toksvig's, the roughness map's, LEAN, CLEAN (single-pass
    /// techniques).
    SpecularFilter,
    /// A larger bump scale, the normal map rebuilt.
    BumpsUp,
    /// A smaller bump scale.
    BumpsDown,
    /// A larger specular exponent.
    ShininessUp,
    /// A smaller specular exponent.
    ShininessDown,
    /// Heights as geometry carved deeper.
    DepthUp,
    /// Carved less deep.
    DepthDown,
    /// More layers for the marches.
    LayersUp,
    /// Fewer layers.
    LayersDown,
    /// The marches' self-shadowing: off, hard, soft.
    ParallaxShadow,
    /// The detail map's blend, each in turn, then none (with `--detail-map`).
    Detail,
    /// The other backend (CPU or GPU).
    Backend,
    /// The triangles' edges drawn over the image.
    Wireframe,
    /// The frame rate shown in the corner.
    FrameRate,
    /// The help overlay listing every key.
    Help,
    /// Write the window's picture as a PNG.
    Screenshot,
    /// The camera and light back where they started.
    ResetView,
    /// Close the viewer.
    Quit,
}

impl Action {
    /// Every action, in the order the help overlay lists them.
    pub const ALL: [Action; 29] = [
        Action::Pause,
        Action::NextTechnique,
        Action::PreviousTechnique,
        Action::NextScene,
        Action::Decal,
        Action::Diffuse,
        Action::Specular,
        Action::SelfShadow,
        Action::MipMode,
        Action::Normalize,
        Action::Filter,
        Action::SpecularFilter,
        Action::BumpsUp,
        Action::BumpsDown,
        Action::ShininessUp,
        Action::ShininessDown,
        Action::DepthUp,
        Action::DepthDown,
        Action::LayersUp,
        Action::LayersDown,
        Action::ParallaxShadow,
        Action::Detail,
        Action::Backend,
        Action::Wireframe,
        Action::FrameRate,
        Action::Help,
        Action::Screenshot,
        Action::ResetView,
        Action::Quit,
    ];

    /// The character typed for it (`' '` for space), as the window receives it.
    pub fn key(self) -> char {
        match self {
            Action::Pause => ' ',
            Action::NextTechnique => 't',
            Action::PreviousTechnique => 'T',
            Action::NextScene => 'o',
            Action::Decal => '1',
            Action::Diffuse => '2',
            Action::Specular => '3',
            Action::SelfShadow => 'x',
            Action::MipMode => 'm',
            Action::Normalize => 'n',
            Action::Filter => 'l',
            Action::SpecularFilter => 'g',
            Action::BumpsUp => '+',
            Action::BumpsDown => '-',
            Action::ShininessUp => ']',
            Action::ShininessDown => '[',
            Action::DepthUp => 'D',
            Action::DepthDown => 'd',
            Action::LayersUp => 'K',
            Action::LayersDown => 'k',
            Action::ParallaxShadow => 'p',
            Action::Detail => 'e',
            Action::Backend => 'b',
            Action::Wireframe => 'w',
            Action::FrameRate => 'f',
            Action::Help => 'h',
            Action::Screenshot => 's',
            Action::ResetView => 'r',
            Action::Quit => 'q',
        }
    }

    /// Its name in `--keys`: the character, or for the ones a list or a shell would mangle, a
    /// word (`space`, `plus`, `minus`, `bracketleft`, `bracketright`, xdotool's names).
    pub fn name(self) -> String {
        match self.key() {
            ' ' => "space".into(),
            '+' => "plus".into(),
            '-' => "minus".into(),
            '[' => "bracketleft".into(),
            ']' => "bracketright".into(),
            c => c.to_string(),
        }
    }

    /// What it does, for the help overlay and `--help`.
    pub fn description(self) -> &'static str {
        match self {
            Action::Pause => "pause / resume the light's orbit",
            Action::NextTechnique => "next technique",
            Action::PreviousTechnique => "previous technique",
            Action::NextScene => "next scene (torus/wall/sphere/patch/mesh)",
            Action::Decal => "decal pass on / off",
            Action::Diffuse => "diffuse pass on / off",
            Action::Specular => "specular pass on / off",
            Action::SelfShadow => "self-shadowing on / off",
            Action::MipMode => "mips: length factor, renormalized, none",
            Action::Normalize => "normalize by cube map / math",
            Action::Filter => "texture filter: trilinear / nearest",
            Action::SpecularFilter => "spec. filter: off/Toksvig/rough/LEAN/CLEAN",
            Action::BumpsUp => "bumps higher (normal map rebuilt)",
            Action::BumpsDown => "bumps lower",
            Action::ShininessUp => "shininess up",
            Action::ShininessDown => "shininess down",
            Action::DepthUp => "heights as geometry: deeper",
            Action::DepthDown => "heights as geometry: shallower",
            Action::LayersUp => "more layers (parallax marches)",
            Action::LayersDown => "fewer layers",
            Action::ParallaxShadow => "parallax shadows: off/hard/soft/horizon",
            Action::Detail => "detail map: next blend, then off",
            Action::Backend => "switch backend (cpu / gpu)",
            Action::Wireframe => "wireframe on / off",
            Action::FrameRate => "frame rate on / off",
            Action::Help => "this help (also F1)",
            Action::Screenshot => "screenshot PNG",
            Action::ResetView => "reset camera and light",
            Action::Quit => "quit (also Esc)",
        }
    }

    /// The action for a typed character (`=` counts as `+`, the same key unshifted).
    pub fn for_key(c: char) -> Option<Action> {
        let c = if c == '=' { '+' } else { c };
        Action::ALL.into_iter().find(|a| a.key() == c)
    }

    /// The action `--keys` names, by [`Action::name`] or by its character.
    pub fn parse(name: &str) -> Result<Action, String> {
        let mut chars = name.chars();
        if let (Some(c), None) = (chars.next(), chars.next())
            && let Some(a) = Action::for_key(c)
        {
            return Ok(a);
        }
        Action::ALL.into_iter().find(|a| a.name() == name).ok_or_else(|| {
            format!(
                "'{name}' is not a viewer key; the keys are {}",
                Action::ALL.iter().map(|a| a.name()).collect::<Vec<_>>().join(", ")
            )
        })
    }
}

/// A comma-separated list of keys for `--keys` (`space,t,t,s`).
pub fn parse_keys(list: &str) -> Result<Vec<Action>, String> {
    list.split(',').map(str::trim).filter(|k| !k.is_empty()).map(Action::parse).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_action_has_its_own_key_and_name_and_parses_back() {
        for (i, a) in Action::ALL.iter().enumerate() {
            for b in &Action::ALL[i + 1..] {
                assert_ne!(a.key(), b.key(), "{a:?} and {b:?} share a key");
            }
            assert_eq!(Action::parse(&a.name()), Ok(*a));
            assert_eq!(Action::for_key(a.key()), Some(*a));
            // The help overlay's glyphs are drawn twice their size in the default 800-pixel
            // window only while every line (a 7-column key, then this) fits 49 columns.
            assert!(a.description().chars().count() + 7 <= 49, "{a:?}: its help line is too long for 2x glyphs");
        }
    }

    #[test]
    fn key_lists_parse_and_unknown_keys_are_named() {
        assert_eq!(
            parse_keys("space, t,T,plus,=,bracketleft"),
            Ok(vec![
                Action::Pause,
                Action::NextTechnique,
                Action::PreviousTechnique,
                Action::BumpsUp,
                Action::BumpsUp,
                Action::ShininessDown
            ])
        );
        let err = parse_keys("t,zz").unwrap_err();
        assert!(err.contains("'zz'") && err.contains("space"), "{err}");
    }
}
