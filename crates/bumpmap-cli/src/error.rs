//! The CLI's error type: the one `bumpmap_words` words every layer's errors in, each message
//! naming the file or value at fault, with the exit status it gives
//! ([`CliError::exit_code`]).

pub use bumpmap_words::Error as CliError;
