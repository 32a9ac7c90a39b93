//! The libraries' errors, as `bumpmap_words` says them, as Python exceptions in Python's words
//! (each flag named as its keyword): `OSError` for files (`FileNotFoundError` for a missing
//! one), `MemoryError` for inputs that need more memory than the process may have (the message
//! says how much), `RuntimeError` for a missing device, `ValueError` for values and combinations
//! that cannot be drawn or made.

use bumpmap_io::IoError;
use bumpmap_words::Error;
use pyo3::exceptions::{
    PyFileNotFoundError, PyKeyboardInterrupt, PyMemoryError, PyOSError, PyRuntimeError, PyValueError,
};
use pyo3::prelude::*;

pyo3::create_exception!(
    bumpmap,
    BumpmapWarning,
    pyo3::exceptions::PyUserWarning,
    "What bumpmap warns about: an input used in a way the caller may not expect (heights clamped \
     to [0, 1], a roughness map of one level). A `warnings` filter on this category silences \
     them or makes them errors."
);

/// `e` as the exception `function` raises.
pub fn to_py(function: &str, e: Error) -> PyErr {
    let message = format!("{function}(): {}", bumpmap_words::as_keywords(&e.to_string()));
    if e.exit_code() == 2 {
        // A value out of range, however it was noticed (the command line's exit status 2).
        return PyValueError::new_err(message);
    }
    match &e {
        Error::Io(IoError::Read { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(message)
        }
        Error::OutOfMemory(_) | Error::Io(IoError::OutOfMemory { .. }) => PyMemoryError::new_err(message),
        Error::Io(_) | Error::Path { .. } => PyOSError::new_err(message),
        Error::NoDevice(_) => PyRuntimeError::new_err(message),
        Error::Interrupted => PyKeyboardInterrupt::new_err(message),
        _ => PyValueError::new_err(message),
    }
}
