//! `bumpmap demo`'s options.

use std::path::PathBuf;

use bumpmap_demo::GpuImages;
use clap::Args;

use crate::args::choice;

/// `bumpmap demo`.
#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Folder to write into (created if missing)
    #[arg(short, long, default_value = "out/demo")]
    pub output: PathBuf,
    /// Also render the figures on the GPU (wgpu); `auto` does when an adapter exists and says so
    /// when none does
    #[arg(long, value_parser = choice::<GpuImages>(), default_value = "auto")]
    pub gpu: GpuImages,
}
