//! What bumpmap's refusals and notes say to a person. The libraries refuse and note with typed
//! values (`bumpmap::frame::FrameError`, `bumpmap::options::SetupError`, `bumpmap::maps::MapError`,
//! `bumpmap_compare::CompareError`, …); this crate words each one once, naming the option that
//! caused it, for both skins: the command line shows the words as they are (`--bump-scale`),
//! the Python package turns each flag into its keyword ([`as_keywords`]: `bump_scale`) and picks
//! its exception class from the [`Error`] variant, as the command line picks its exit status
//! ([`Error::exit_code`]).
//!
//! - [`Error`]: every layer's errors as one type;
//! - [`frame`], [`setup`], [`maps`], [`compare`]: each library's errors and notes in words;
//! - [`report`]: warnings and notes said on stderr, or collected for a caller that says them its
//!   own way (Python's `warnings` and `logging`);
//! - [`as_keywords`]: a message in a keyword API's words.
//!
//! What this crate does not do: decide anything. Which values are in range, what a technique can
//! draw and which inputs are too big are the libraries' rules; this crate only says them.

#![warn(missing_docs)]

pub mod bake;
pub mod compare;
mod error;
pub mod frame;
mod keywords;
mod library;
pub mod maps;
pub mod report;
pub mod setup;

pub use error::Error;
pub use keywords::{as_keywords, keyword};
