//! The library's option tables (`bumpmap::option_table`) as clap's arguments: [`Table`] is a
//! table flattened into a command ([`augment`] makes each row an argument: its long name, help,
//! section, its kind's parser, the typed options' default, what it needs or excludes) and read
//! back into the typed options ([`read`]). The Python package makes its keywords, signatures,
//! docstrings and stubs from the same tables, so no option is declared twice; a test
//! (`tests/python_options.rs`) holds each command's `--help` to its table.
//!
//! What this module does not do: declare an option (the library's tables do), or check a value
//! (each row does, through the library).

use bumpmap::option_table::{Kind, Opt, Value as OptValue};
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::parser::ValueSource;
use clap::{Arg, ArgAction, ArgMatches, Command};
use clap::{Args, FromArgMatches};

/// A library option table ([`Rows::rows`]) as a group of clap arguments, flattened into a
/// command; [`Table::0`] is the typed options they set, the library's defaults elsewhere.
pub struct Table<T: Rows>(pub T::Target);

/// Which table a [`Table`] reads, and the typed options it sets.
pub trait Rows: 'static {
    /// The typed options.
    type Target: Default + Clone + std::fmt::Debug + Send + Sync + 'static;
    /// The rows, in `--help`'s order.
    fn rows() -> &'static [Opt<Self::Target>];
}

impl<T: Rows> Clone for Table<T> {
    fn clone(&self) -> Self {
        Table(self.0.clone())
    }
}

impl<T: Rows> std::fmt::Debug for Table<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl<T: Rows> Default for Table<T> {
    fn default() -> Self {
        Table(T::Target::default())
    }
}

impl<T: Rows> FromArgMatches for Table<T> {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut table = Table::default();
        table.update_from_arg_matches(m)?;
        Ok(table)
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        read(T::rows(), m, &mut self.0)
    }
}

impl<T: Rows> Args for Table<T> {
    fn augment_args(cmd: Command) -> Command {
        augment(cmd, T::rows())
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        augment(cmd, T::rows())
    }
}

/// Declares a [`Rows`] marker for a library table.
macro_rules! rows {
    ($(#[$doc:meta])* $name:ident: $target:ty = $rows:expr) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy)]
        pub struct $name;

        impl $crate::args::table::Rows for $name {
            type Target = $target;
            fn rows() -> &'static [bumpmap::option_table::Opt<$target>] {
                $rows
            }
        }
    };
}
pub(crate) use rows;

/// `cmd` with an argument for each row of `rows`, in order: its long name, help and section,
/// its kind's parser (a closed set's words with their meanings), the typed options' default,
/// and the options it needs or excludes.
pub fn augment<R: Default + 'static>(mut cmd: Command, rows: &'static [Opt<R>]) -> Command {
    for row in rows {
        cmd = cmd.arg(argument(row));
    }
    cmd
}

fn argument<R: Default + 'static>(row: &'static Opt<R>) -> Arg {
    let value_name = row.value_name.map_or_else(|| row.name.to_uppercase().replace('-', "_"), str::to_string);
    let mut arg = Arg::new(row.name).long(row.name).help(row.help).value_name(value_name);
    if !row.heading.is_empty() {
        arg = arg.help_heading(row.heading);
    }
    arg = match row.kind() {
        Kind::Flag => arg.action(ArgAction::SetTrue),
        Kind::Word(choices) => {
            let values =
                choices.into_iter().map(|c| PossibleValue::new(c.name).help(c.help).aliases(c.aliases.iter().copied()));
            arg.value_parser(PossibleValuesParser::new(values).map(OptValue::Word))
        }
        Kind::Lights => {
            arg.action(ArgAction::Append).allow_hyphen_values(true).value_parser(move |text: &str| row.parse_text(text))
        }
        Kind::Numbers(_) | Kind::Attenuation => {
            arg.allow_hyphen_values(true).value_parser(move |text: &str| row.parse_text(text))
        }
        Kind::Number | Kind::Whole { .. } => {
            arg.allow_negative_numbers(true).value_parser(move |text: &str| row.parse_text(text))
        }
        Kind::Text | Kind::Path => arg.value_parser(move |text: &str| row.parse_text(text)),
        Kind::List(words) => {
            let arg = arg.action(ArgAction::Append).value_delimiter(',');
            match words {
                Some(words) => {
                    let values = words.into_iter().map(|c| PossibleValue::new(c.name).help(c.help));
                    arg.value_parser(PossibleValuesParser::new(values).map(|w| OptValue::Words(vec![w])))
                }
                None => arg.value_parser(move |text: &str| row.parse_text(text)),
            }
        }
    };
    if let Some(default) = row.default_text().filter(|_| row.kind() != Kind::Flag) {
        arg = match row.kind() {
            Kind::List(_) => arg.default_values(default.split(',').map(str::to_string).collect::<Vec<_>>()),
            _ => arg.default_value(default),
        };
    }
    for other in row.requires {
        arg = arg.requires(*other);
    }
    for other in row.conflicts {
        arg = arg.conflicts_with(*other);
    }
    arg
}

/// Sets into `options` each value of `rows` given on the command line, and each default a
/// command set differently from the library's (`view`'s backend), in the table's order.
pub fn read<R: Default + 'static>(rows: &'static [Opt<R>], m: &ArgMatches, options: &mut R) -> Result<(), clap::Error> {
    for row in rows {
        let value = match m.value_source(row.name) {
            Some(ValueSource::CommandLine) => given(row, m),
            Some(ValueSource::DefaultValue) => {
                given(row, m).filter(|v| Some(v.to_string()) != row.default_text() && !matches!(v, OptValue::Flag(_)))
            }
            _ => None,
        };
        if let Some(value) = value {
            row.set(options, value).map_err(|e| {
                clap::Error::raw(clap::error::ErrorKind::ValueValidation, format!("--{}: {e}\n", row.name))
            })?;
        }
    }
    Ok(())
}

/// The value of `row` in `m` (every `--light` as one list).
fn given<R: Default>(row: &Opt<R>, m: &ArgMatches) -> Option<OptValue> {
    match row.kind() {
        Kind::Flag => Some(OptValue::Flag(m.get_flag(row.name))),
        Kind::Lights => {
            let lights = m
                .get_many::<OptValue>(row.name)?
                .flat_map(|v| match v {
                    OptValue::Lights(l) => l.clone(),
                    _ => Vec::new(),
                })
                .collect();
            Some(OptValue::Lights(lights))
        }
        Kind::List(_) => {
            let words = m
                .get_many::<OptValue>(row.name)?
                .flat_map(|v| match v {
                    OptValue::Words(w) => w.clone(),
                    _ => Vec::new(),
                })
                .collect();
            Some(OptValue::Words(words))
        }
        _ => m.get_one::<OptValue>(row.name).cloned(),
    }
}
