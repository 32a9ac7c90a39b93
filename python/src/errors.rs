//! The command line's errors as Python exceptions, in Python's words: `OSError` for files
//! (`FileNotFoundError` for a missing one), `RuntimeError` for a missing device, `ValueError`
//! for values and combinations that cannot be drawn or made.

use bumpmap_cli::error::CliError;
use bumpmap_io::IoError;
use pyo3::exceptions::{PyFileNotFoundError, PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use crate::options::python_words;

pyo3::create_exception!(
    bumpmap,
    BumpmapWarning,
    pyo3::exceptions::PyUserWarning,
    "What bumpmap warns about: an input used in a way the caller may not expect (heights clamped \
     to [0, 1], a roughness map of one level). A `warnings` filter on this category silences \
     them or makes them errors."
);

/// `e` as the exception `function` raises.
pub fn to_py(function: &str, e: CliError) -> PyErr {
    let message = format!("{function}(): {}", python_words(&e.to_string()));
    if e.exit_code() == 2 {
        // A value out of range, however it was noticed (the command line's exit status 2).
        return PyValueError::new_err(message);
    }
    match &e {
        CliError::Io(IoError::Read { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(message)
        }
        CliError::Io(_) | CliError::Path { .. } => PyOSError::new_err(message),
        CliError::NoDevice(_) => PyRuntimeError::new_err(message),
        CliError::Interrupted => PyKeyboardInterrupt::new_err(message),
        _ => PyValueError::new_err(message),
    }
}
