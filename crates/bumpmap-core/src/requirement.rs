//! What a technique needs of a scene, in words: what the catalogue declares of each technique
//! and what a refusal ([`crate::CoreError::Needs`]) names.

use std::fmt;

/// What a technique needs of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Requirement {
    /// An analytic surface (every built-in scene): its map or its shading is made from the
    /// surface's exact ∂P/∂u and ∂P/∂v, which a loaded mesh does not have.
    BuiltInSurface,
    /// A height field: the technique differentiates heights itself, which a normal map given as
    /// it is does not carry.
    HeightField,
    /// One light: its passes have room for one.
    OneLight,
    /// Heights to take as geometry: a height field, or heights given beside a normal map.
    Heights,
}

impl Requirement {
    /// The requirement in a few words (its `Display` says why).
    pub fn brief(self) -> &'static str {
        match self {
            Requirement::BuiltInSurface => "a built-in surface",
            Requirement::HeightField => "a height field",
            Requirement::OneLight => "one light",
            Requirement::Heights => "heights",
        }
    }
}

impl fmt::Display for Requirement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Requirement::BuiltInSurface => write!(
                f,
                "a built-in surface ({}): it uses the surface's exact derivatives, which a mesh does not have",
                crate::spec::SceneKind::built_in_names()
            ),
            Requirement::HeightField => f.write_str(
                "a height field: it differentiates the heights itself, and a normal map given as it is has none",
            ),
            Requirement::OneLight => f.write_str("exactly one light"),
            Requirement::Heights => f.write_str(
                "heights to take as geometry: a height field, or heights given with the normal map (the heights file `bumpmap normalmap` writes)",
            ),
        }
    }
}
