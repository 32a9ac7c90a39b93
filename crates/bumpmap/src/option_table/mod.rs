//! Every option of a command, declared once as data: its name, what kind of value it takes, its
//! default (read from the typed options' own `Default`), its help, its section of `--help`, the
//! options it needs or excludes, and the field of the typed options it sets. The command line
//! builds its arguments from these tables and the Python package its keywords, signatures and
//! docstrings, so adding an option is one [`Opt`] row beside the code that uses the field.
//!
//! ```
//! use bumpmap::frame::FrameRequest;
//! use bumpmap::option_table::{self, Value};
//!
//! let mut request = FrameRequest::default();
//! let row = option_table::find(option_table::SCENE, "spot-exponent").expect("render takes it");
//! assert_eq!(row.default_text().as_deref(), Some("2"), "the default is the typed options' own");
//! row.set(&mut request, row.parse_text("4")?)?;
//! assert_eq!(request.options.lights.spot_exponent, 4.0);
//! assert_eq!(row.requires, ["spot"]);
//! # Ok::<(), String>(())
//! ```
//!
//! A skin reads a value its own way into a [`Value`] of the row's [`Kind`] (the command line from
//! text with [`Opt::parse_text`], Python from its objects), then [`Opt::set`] checks it against
//! the row's range and sets the field; [`check_together`] refuses options given without the one
//! they need, or beside one they exclude.
//!
//! What this module does not do: check a value against the others or load a file (the typed
//! options' `set_up` does: a Rust user who sets the fields directly gets the same checks), or
//! word anything in a skin's terms (`--spot-exponent` is the command line's, `spot_exponent`
//! Python's; [`Opt::name`] is the one both are made from).

use std::fmt;
use std::path::PathBuf;

use bumpmap_core::scene::{Attenuation, SceneLight};

mod bake;
mod blend;
mod fields;
mod maps;
mod render;

pub use bake::BAKE;
pub use blend::BLEND;
pub use fields::{AutoWordField, Field, MaybeWordField, WordField};
pub use maps::{CHANNEL, FORMAT, HEIGHTS, MAPS, TANGENTS};
pub use render::{FRAME, SCENE, render};

/// What kind of value an option takes: how a skin reads it, and what `--help` shows.
#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    /// Given or not (`--silhouettes`; Python's `True`/`False`).
    Flag,
    /// A real number (single precision).
    Number,
    /// A whole number in `min..=max`.
    Whole {
        /// The least value taken.
        min: u64,
        /// The largest value taken.
        max: u64,
    },
    /// This many real numbers (`X,Y,Z` on the command line, a tuple in Python).
    Numbers(usize),
    /// A word of a closed set.
    Word(Vec<Choice>),
    /// Text the library reads itself (a scene's name, a preset or a file).
    Text,
    /// A file.
    Path,
    /// Lights, in the notation `[dir:]X,Y,Z[@R,G,B]`; the command line repeats the option.
    Lights,
    /// Attenuation with distance: `C,L,Q`, `exp:D` or `exp2:D`.
    Attenuation,
    /// Several words, comma-separated on the command line (a list in Python): of a closed set
    /// where it has one, else names the library checks itself.
    List(Option<Vec<Choice>>),
}

/// One word of a closed set, with its meaning.
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    /// The word.
    pub name: &'static str,
    /// Other words taken for it.
    pub aliases: &'static [&'static str],
    /// One line on what it does (and what it needs).
    pub help: String,
}

/// A value as a skin read it, before it is set into the typed options.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// [`Kind::Flag`].
    Flag(bool),
    /// [`Kind::Number`].
    Number(f32),
    /// [`Kind::Whole`].
    Whole(u64),
    /// [`Kind::Numbers`].
    Numbers(Vec<f32>),
    /// [`Kind::Word`]: the word as given (a name or an alias).
    Word(String),
    /// [`Kind::Text`].
    Text(String),
    /// [`Kind::Path`].
    Path(PathBuf),
    /// [`Kind::Lights`].
    Lights(Vec<SceneLight>),
    /// [`Kind::Attenuation`].
    Attenuation(Attenuation),
    /// [`Kind::List`].
    Words(Vec<String>),
}

impl fmt::Display for Value {
    /// As the command line writes it: numbers joined by commas, a path as given.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Flag(b) => write!(f, "{b}"),
            Value::Number(v) => write!(f, "{v}"),
            Value::Whole(v) => write!(f, "{v}"),
            Value::Numbers(v) => {
                let parts: Vec<String> = v.iter().map(f32::to_string).collect();
                write!(f, "{}", parts.join(","))
            }
            Value::Word(w) | Value::Text(w) => write!(f, "{w}"),
            Value::Path(p) => write!(f, "{}", p.display()),
            Value::Lights(l) => write!(f, "{} lights", l.len()),
            Value::Attenuation(a) => write!(f, "{a:?}"),
            Value::Words(w) => write!(f, "{}", w.join(",")),
        }
    }
}

/// What a value must be beyond its kind: `Err` says why it is not, quoting the value.
pub type Check = fn(&Value) -> Result<(), String>;

/// How an option reaches its field.
pub enum Access<R> {
    /// The field itself: its kind, default and setting are the field type's ([`Field`]).
    Field(fn(&mut R) -> &mut dyn Field),
    /// A field holding a word of a closed set ([`crate::Named`]).
    Word(fn(&mut R) -> &mut dyn WordField),
    /// A field holding a word of a closed set or none, the library's choice.
    MaybeWord(fn(&mut R) -> &mut dyn MaybeWordField),
    /// A field holding a word of a closed set or none, which the option names `auto` (listed
    /// first, with this meaning).
    AutoWord(fn(&mut R) -> &mut dyn AutoWordField, &'static str),
    /// Anything else (a flag that sets another field's value, one value setting two fields).
    Custom {
        /// The value's kind.
        kind: fn() -> Kind,
        /// The value in `R` as the option gives it, `None` where it has none to show.
        get: fn(&R) -> Option<Value>,
        /// Sets the value into `R`.
        set: fn(&mut R, Value) -> Result<(), String>,
    },
}

/// One option of a command, setting a field of `R` (the command's typed options).
pub struct Opt<R> {
    /// The name: words joined by `-` (`spot-exponent`). The command line's flag is `--` and this,
    /// Python's keyword this with `_`.
    pub name: &'static str,
    /// The section of `--help` it is listed in.
    pub heading: &'static str,
    /// What it means, in the papers' terms, and what its default is where that depends.
    pub help: &'static str,
    /// The field it sets.
    pub access: Access<R>,
    /// Options it is given only with.
    pub requires: &'static [&'static str],
    /// Options it is never given with.
    pub conflicts: &'static [&'static str],
    /// The value's placeholder in `--help` (`None`: the name in capitals).
    pub value_name: Option<&'static str>,
    /// What the value must be beyond its kind, checked when it is set; the message quotes the
    /// value as the command line writes it.
    pub check: Option<Check>,
    /// The range of a whole number (`None`: the field type's).
    pub range: Option<(u64, u64)>,
}

impl<R> Opt<R> {
    /// An option that sets a field, with nothing it needs or excludes.
    pub const fn new(
        name: &'static str,
        heading: &'static str,
        help: &'static str,
        field: fn(&mut R) -> &mut dyn Field,
    ) -> Self {
        Self::with(name, heading, help, Access::Field(field))
    }

    /// An option that sets a word of a closed set.
    pub const fn word(
        name: &'static str,
        heading: &'static str,
        help: &'static str,
        field: fn(&mut R) -> &mut dyn WordField,
    ) -> Self {
        Self::with(name, heading, help, Access::Word(field))
    }

    /// An option that sets a word of a closed set where the library decides when none is given.
    pub const fn maybe_word(
        name: &'static str,
        heading: &'static str,
        help: &'static str,
        field: fn(&mut R) -> &mut dyn MaybeWordField,
    ) -> Self {
        Self::with(name, heading, help, Access::MaybeWord(field))
    }

    /// An option that sets a word of a closed set or `auto` (none: the library decides, as
    /// `auto_help` says).
    pub const fn auto_word(
        name: &'static str,
        heading: &'static str,
        help: &'static str,
        auto_help: &'static str,
        field: fn(&mut R) -> &mut dyn AutoWordField,
    ) -> Self {
        Self::with(name, heading, help, Access::AutoWord(field, auto_help))
    }

    /// An option reaching its field(s) through `access`.
    pub const fn with(name: &'static str, heading: &'static str, help: &'static str, access: Access<R>) -> Self {
        Opt { name, heading, help, access, requires: &[], conflicts: &[], value_name: None, check: None, range: None }
    }

    /// The same, a whole number in `min..=max`.
    pub const fn range(mut self, min: u64, max: u64) -> Self {
        self.range = Some((min, max));
        self
    }

    /// The same, given only with `others`.
    pub const fn requires(mut self, others: &'static [&'static str]) -> Self {
        self.requires = others;
        self
    }

    /// The same, never given with `others`.
    pub const fn conflicts(mut self, others: &'static [&'static str]) -> Self {
        self.conflicts = others;
        self
    }

    /// The same, with `--help`'s placeholder `name`.
    pub const fn value_name(mut self, name: &'static str) -> Self {
        self.value_name = Some(name);
        self
    }

    /// The same, with a check of the value beyond its kind.
    pub const fn check(mut self, check: Check) -> Self {
        self.check = Some(check);
        self
    }

    /// The name as a Python keyword (`spot_exponent`).
    pub fn keyword(&self) -> String {
        self.name.replace('-', "_")
    }
}

impl<R: Default> Opt<R> {
    /// The kind of value it takes.
    pub fn kind(&self) -> Kind {
        let mut defaults = R::default();
        let kind = match &self.access {
            Access::Field(field) => field(&mut defaults).kind(),
            Access::Word(field) => field(&mut defaults).kind(),
            Access::MaybeWord(field) => field(&mut defaults).kind(),
            Access::AutoWord(field, auto_help) => match field(&mut defaults).kind() {
                Kind::Word(words) => {
                    let auto = Choice { name: bumpmap_math::named::AUTO, aliases: &[], help: auto_help.to_string() };
                    Kind::Word(std::iter::once(auto).chain(words).collect())
                }
                kind => kind,
            },
            Access::Custom { kind, .. } => kind(),
        };
        match (kind, self.range) {
            (Kind::Whole { .. }, Some((min, max))) => Kind::Whole { min, max },
            (kind, _) => kind,
        }
    }

    /// Its default as the command line writes it: the typed options' own default, `None` where
    /// the option has none to show (it is optional, or a flag).
    pub fn default_text(&self) -> Option<String> {
        let mut defaults = R::default();
        let value = match &self.access {
            Access::Field(field) => field(&mut defaults).get(),
            Access::Word(field) => field(&mut defaults).get(),
            Access::MaybeWord(field) => field(&mut defaults).get(),
            Access::AutoWord(field, _) => field(&mut defaults).get(),
            Access::Custom { get, .. } => get(&defaults),
        };
        value.filter(|v| !matches!(v, Value::Flag(_))).map(|v| v.to_string())
    }

    /// Checks `value` (its range, [`Opt::check`]) and sets it into `options`; the message says
    /// what is wrong with the value, without naming the option (the skin names it its way).
    pub fn set(&self, options: &mut R, value: Value) -> Result<(), String> {
        if let Some(check) = self.check {
            check(&value)?;
        }
        if let (Kind::Whole { min, max }, Value::Whole(v)) = (self.kind(), &value)
            && !(min..=max).contains(v)
        {
            return Err(format!("{v} is not in {min}..={max}"));
        }
        match &self.access {
            Access::Field(field) => field(options).set(value),
            Access::Word(field) => field(options).set(value),
            Access::MaybeWord(field) => field(options).set(value),
            Access::AutoWord(field, _) => field(options).set(value),
            Access::Custom { set, .. } => set(options, value),
        }
    }

    /// The value `text` stands for, as the command line gives it, checked as [`Opt::set`]
    /// would check it (the field's own reading included, on a default `R`).
    pub fn parse_text(&self, text: &str) -> Result<Value, String> {
        let value = parse_text(&self.kind(), text)?;
        self.set(&mut R::default(), value.clone())?;
        Ok(value)
    }
}

/// The row named `name` (as the command line spells it, or as a Python keyword).
pub fn find<'a, R>(table: &'a [Opt<R>], name: &str) -> Option<&'a Opt<R>> {
    let name = name.replace('_', "-");
    table.iter().find(|o| o.name == name)
}

/// What [`check_together`] refuses.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Together {
    /// `option` is given only with `needs`.
    Needs {
        /// The option given.
        option: &'static str,
        /// The option it needs.
        needs: &'static str,
    },
    /// `option` and `other` cannot both be given.
    Excludes {
        /// The option given.
        option: &'static str,
        /// The other option given, which it excludes.
        other: &'static str,
    },
}

/// Refuses an option of `given` (names as [`Opt::name`] spells them) that needs one not given,
/// or excludes one that is.
pub fn check_together<R>(table: &[Opt<R>], given: &[&str]) -> Result<(), Together> {
    let has = |n: &str| given.contains(&n);
    for row in table.iter().filter(|r| has(r.name)) {
        if let Some(needs) = row.requires.iter().find(|n| !has(n)) {
            return Err(Together::Needs { option: row.name, needs });
        }
        if let Some(other) = row.conflicts.iter().find(|n| has(n)) {
            return Err(Together::Excludes { option: row.name, other });
        }
    }
    Ok(())
}

/// A number as typed: text that overflows single precision (`1e40`) is refused with the text,
/// rather than becoming `inf`; `NaN` and `inf` typed as such pass, for the option's own check.
pub fn parse_number(text: &str) -> Result<f32, String> {
    let v = text.trim().parse::<f32>().map_err(|_| format!("'{text}' is not a number"))?;
    if v.is_infinite() && !text.to_ascii_lowercase().contains("inf") {
        return Err(format!("'{text}' is beyond single precision (about ±3.4e38)"));
    }
    Ok(v)
}

/// A value of `kind` from the command line's text.
fn parse_text(kind: &Kind, text: &str) -> Result<Value, String> {
    Ok(match kind {
        Kind::Flag => Value::Flag(text.parse().map_err(|_| format!("'{text}' is not true or false"))?),
        Kind::Number => Value::Number(parse_number(text)?),
        Kind::Whole { min, max } => {
            let v: i128 = text.trim().parse().map_err(|_| format!("'{text}' is not a whole number"))?;
            let v = u64::try_from(v).map_err(|_| format!("{v} is not in {min}..={max}"))?;
            Value::Whole(v)
        }
        Kind::Numbers(n) => {
            let v: Vec<f32> = text
                .split(',')
                .map(|p| p.trim().parse::<f32>().map_err(|_| format!("'{p}' is not a number")))
                .collect::<Result<_, _>>()?;
            if v.len() != *n || !v.iter().all(|c| c.is_finite()) {
                let (names, count) = match n {
                    2 => ("A,B", "two"),
                    3 => ("X,Y,Z", "three"),
                    _ => ("numbers", "that many"),
                };
                return Err(format!("expected {names} ({count} finite numbers), got '{text}'"));
            }
            Value::Numbers(v)
        }
        Kind::Word(_) => Value::Word(text.to_string()),
        Kind::Text => Value::Text(text.to_string()),
        Kind::Path => Value::Path(PathBuf::from(text)),
        Kind::Lights => Value::Lights(vec![SceneLight::parse(text)?]),
        Kind::Attenuation => Value::Attenuation(Attenuation::parse(text)?),
        Kind::List(_) => Value::Words(text.split(',').map(|w| w.trim().to_string()).collect()),
    })
}

/// The choices of a closed set `T`, each with its help ([`crate::Named::help`]).
pub fn choices<T: crate::Named>() -> Vec<Choice> {
    T::ALL.iter().map(|v| Choice { name: v.name(), aliases: v.aliases(), help: v.help() }).collect()
}

#[cfg(test)]
mod tests;
