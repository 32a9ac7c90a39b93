//! Errors at the file boundary. Every message names the file.

use std::path::{Path, PathBuf};

/// A path as messages show it; an empty one (`-o ""`) says so instead of showing nothing.
pub fn shown(path: &Path) -> String {
    if path.as_os_str().is_empty() { "(an empty path)".into() } else { path.display().to_string() }
}

/// What went wrong with a file, naming it.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    /// The file could not be opened or read.
    #[error("{}: cannot read: {source}", shown(path))]
    Read {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The file is not an image the decoder reads.
    #[error("{}: not a readable image: {reason}", shown(path))]
    Decode {
        /// The file.
        path: PathBuf,
        /// What the decoder said.
        reason: String,
    },
    /// An image larger than the limit, found from its header.
    #[error("{}: image is {width}x{height}; the limit is {max}x{max} texels", shown(path))]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The width its header declares.
        width: u64,
        /// The height its header declares.
        height: u64,
        /// The largest side accepted.
        max: u32,
    },
    /// An input whose decoded texels (with the copies made while converting them) are more
    /// than the machine gives, found from its header before decoding.
    #[error("{}: {source}", shown(path))]
    OutOfMemory {
        /// The file.
        path: PathBuf,
        /// What was needed.
        source: bumpmap_math::buffer::OutOfMemory,
    },
    /// An image of no texels.
    #[error("{}: image has no texels ({width}x{height})", shown(path))]
    Empty {
        /// The file.
        path: PathBuf,
        /// Its width.
        width: u32,
        /// Its height.
        height: u32,
    },
    /// A height-field channel the image does not have.
    #[error("{}: image has no {channel} channel (it has {has})", shown(path))]
    NoSuchChannel {
        /// The file.
        path: PathBuf,
        /// The channel asked for.
        channel: &'static str,
        /// The channels it has, in words.
        has: String,
    },
    /// The file could not be written (or renamed into place).
    #[error("{}: cannot write: {source}", shown(path))]
    Write {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// An output that is one of the command's inputs.
    #[error("{}: output would overwrite the input file", shown(path))]
    SameAsInput {
        /// The output.
        path: PathBuf,
    },
    /// Two outputs of one command that name the same file (a level of one output and another
    /// output, say): a usage error, found before anything is written.
    #[error("{}: cannot write: two outputs of one command would be the same file", shown(path))]
    SameOutput {
        /// The file named twice.
        path: PathBuf,
    },
    /// An output whose extension names no format this crate writes there.
    #[error("{}: unsupported output format (use {expected})", shown(path))]
    UnsupportedOutput {
        /// The output.
        path: PathBuf,
        /// The extensions accepted, in words.
        expected: &'static str,
    },
    /// A mesh file that cannot be used.
    #[error("{}: {reason}", shown(path))]
    Mesh {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// Neither a file nor a preset: no file has this name, and as a preset it has a value out
    /// of range (`bricks@16385`, `noise:x`) or a name that is none (`teapot`: perhaps a missing
    /// file).
    #[error("{}: cannot read: no such file, and not a preset: {hint}", shown(path))]
    NotAPreset {
        /// What was given.
        path: PathBuf,
        /// Why it is not a preset: the value out of range, or the names there are.
        hint: String,
        /// A preset's name with a size or seed out of range: a malformed argument.
        out_of_range: bool,
    },
    /// A texture file that cannot be used.
    #[error("{}: {reason}", shown(path))]
    Texture {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
}
