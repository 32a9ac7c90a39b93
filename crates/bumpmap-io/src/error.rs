//! Errors at the file boundary. Every message names the file.

use std::path::{Path, PathBuf};

/// A path as messages show it; an empty one (`-o ""`) says so instead of showing nothing.
pub fn shown(path: &Path) -> String {
    if path.as_os_str().is_empty() { "(an empty path)".into() } else { path.display().to_string() }
}

#[derive(Debug, thiserror::Error)]
pub enum IoError {
    #[error("{}: cannot read: {source}", shown(path))]
    Read { path: PathBuf, source: std::io::Error },
    #[error("{}: not a readable image: {reason}", shown(path))]
    Decode { path: PathBuf, reason: String },
    #[error("{}: image is {width}x{height}; the limit is {max}x{max} texels", shown(path))]
    TooLarge { path: PathBuf, width: u64, height: u64, max: u32 },
    #[error("{}: image has no texels ({width}x{height})", shown(path))]
    Empty { path: PathBuf, width: u32, height: u32 },
    #[error("{}: image has no {channel} channel (it has {has})", shown(path))]
    NoSuchChannel { path: PathBuf, channel: &'static str, has: String },
    #[error("{}: cannot write: {source}", shown(path))]
    Write { path: PathBuf, source: std::io::Error },
    #[error("{}: output would overwrite the input file", shown(path))]
    SameAsInput { path: PathBuf },
    #[error("{}: unsupported output format (use {expected})", shown(path))]
    UnsupportedOutput { path: PathBuf, expected: &'static str },
    #[error("{}: {reason}", shown(path))]
    Mesh { path: PathBuf, reason: String },
}
