//! Errors at the file boundary. Every message names the file.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum IoError {
    #[error("{}: cannot read: {source}", path.display())]
    Read { path: PathBuf, source: std::io::Error },
    #[error("{}: not a readable image: {reason}", path.display())]
    Decode { path: PathBuf, reason: String },
    #[error("{}: image is {width}x{height}; the limit is {max}x{max} texels", path.display())]
    TooLarge { path: PathBuf, width: u64, height: u64, max: u32 },
    #[error("{}: image has no texels ({width}x{height})", path.display())]
    Empty { path: PathBuf, width: u32, height: u32 },
    #[error("{}: image has no {channel} channel (it has {has})", path.display())]
    NoSuchChannel { path: PathBuf, channel: &'static str, has: String },
    #[error("{}: cannot write: {source}", path.display())]
    Write { path: PathBuf, source: std::io::Error },
    #[error("{}: output would overwrite the input file", path.display())]
    SameAsInput { path: PathBuf },
    #[error("{}: unsupported output format (use {expected})", path.display())]
    UnsupportedOutput { path: PathBuf, expected: &'static str },
    #[error("{}: {reason}", path.display())]
    Mesh { path: PathBuf, reason: String },
}
