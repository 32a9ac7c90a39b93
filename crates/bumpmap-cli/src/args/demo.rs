//! `bumpmap demo`'s options.

use std::path::PathBuf;

use clap::{Args, ValueEnum};

/// `bumpmap demo`.
#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Folder to write into (created if missing)
    #[arg(short, long, default_value = "out/demo")]
    pub output: PathBuf,
    /// Also render the figures on the GPU (wgpu); `auto` does when an adapter exists and says so
    /// when none does
    #[arg(long, value_enum, default_value = "auto")]
    pub gpu: DemoGpuArg,
}

/// Whether the demo draws on the GPU too.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum DemoGpuArg {
    /// GPU images when an adapter exists
    Auto,
    /// GPU images, and an error when no adapter exists
    Always,
    /// CPU images only
    Never,
}
