//! Closed sets by name: each enum whose values a user picks by word (a filter, a self-shadowing
//! factor, a Y convention, …) says here, once, the word for each value, its aliases and one line
//! on what it does. The command line's value parsers, the viewer and the Python package's
//! keywords and stubs read these, so no skin spells a value of its own.
//!
//! What this module does not do: parse anything but a whole word, or pick a default (each enum's
//! `Default` does).
//!
//! ```
//! use bumpmap_math::{Named, YConvention};
//! assert_eq!(YConvention::parse("directx"), Some(YConvention::YDown));
//! assert_eq!(YConvention::parse("y-up"), Some(YConvention::YUp), "an alias");
//! assert_eq!(YConvention::parse("DirectX"), None, "words are lower case");
//! assert_eq!(YConvention::names(), ["opengl", "directx"]);
//! ```

/// An enum whose values have names: what commands and keywords take.
pub trait Named: Copy + PartialEq + Send + Sync + 'static {
    /// Every value, in the order lists and `--help` show them.
    const ALL: &'static [Self];

    /// The word for this value (lower case, words joined by `-`).
    fn name(self) -> &'static str;

    /// One line on what this value does, for `--help` and docstrings.
    fn description(self) -> &'static str;

    /// One line for a list of choices (`--help`, docstrings): the description, and what this
    /// value needs where it has such a condition.
    fn help(self) -> String {
        self.description().to_string()
    }

    /// Other words accepted for this value.
    fn aliases(self) -> &'static [&'static str] {
        &[]
    }

    /// The value `word` names (its name or an alias), or `None`.
    fn parse(word: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|v| v.name() == word || v.aliases().contains(&word))
    }

    /// Every value's name, in [`Named::ALL`]'s order.
    fn names() -> Vec<&'static str> {
        Self::ALL.iter().map(|v| v.name()).collect()
    }
}

/// The word that leaves a choice to the tool, beside a set's own words: `None` where a value of
/// the set is optional and the tool decides when it is not given.
pub const AUTO: &str = "auto";

/// `word` as an optional value of `T`: `Some(None)` for [`AUTO`], `Some(Some(v))` for a word of
/// `T`, `None` for anything else.
///
/// ```
/// use bumpmap_math::named::parse_or_auto;
/// use bumpmap_math::YConvention;
/// assert_eq!(parse_or_auto::<YConvention>("auto"), Some(None));
/// assert_eq!(parse_or_auto::<YConvention>("directx"), Some(Some(YConvention::YDown)));
/// assert_eq!(parse_or_auto::<YConvention>("up"), None);
/// ```
pub fn parse_or_auto<T: Named>(word: &str) -> Option<Option<T>> {
    if word == AUTO { Some(None) } else { T::parse(word).map(Some) }
}

/// Implements [`Named`] for an enum from one table: `Type { Variant => "name" | "alias":
/// "description", … }`.
#[macro_export]
macro_rules! named {
    ($ty:ident { $($variant:ident => $name:literal $(| $alias:literal)* : $description:literal),+ $(,)? }) => {
        impl $crate::named::Named for $ty {
            const ALL: &'static [Self] = &[$($ty::$variant),+];

            fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name),+
                }
            }

            fn description(self) -> &'static str {
                match self {
                    $($ty::$variant => $description),+
                }
            }

            fn aliases(self) -> &'static [&'static str] {
                match self {
                    $($ty::$variant => &[$($alias),*]),+
                }
            }
        }
    };
}

#[cfg(test)]
mod tests {
    use super::Named;
    use crate::YConvention;

    /// Every word names one value: no name or alias is shared, and each parses back.
    #[test]
    fn words_are_unique_and_parse_back() {
        let mut words: Vec<&str> = Vec::new();
        for v in YConvention::ALL {
            assert_eq!(YConvention::parse(v.name()), Some(*v));
            words.push(v.name());
            words.extend(v.aliases());
        }
        let mut sorted = words.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), words.len());
    }
}
