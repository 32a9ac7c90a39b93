//! `bumpmap inspect` and `bumpmap height`: normal maps made elsewhere, read.

use std::path::PathBuf;

use clap::Args;

use bumpmap::heights::{HeightChoiceError, HeightChoices, HeightOptions};
use bumpmap::option_table::HEIGHTS;

use super::normalmap::parse_bits;
use crate::args::table::{Table, rows};

rows!(
    /// How a normal map's slopes become heights: the library's [`HEIGHTS`] table.
    Heights: HeightChoices = HEIGHTS
);

/// `bumpmap inspect`.
#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap inspect rock_normal.png\n  \
bumpmap inspect textures/ --json > report.json\n  \
bumpmap inspect n.ktx2 --strict && echo clean\n\n\
For each file: whether it is a normal map at all (unit-length vectors leaning out of the surface, \
not a gray height or roughness map or a colour image); which way its green points, by the curl \
test (a normal map made from heights is a gradient field, whose curl vanishes only when green is \
read the way it was written; a map whose bumps vary along one direction cannot tell, and says \
\"undecidable\" rather than guess); how its mips were made (box-filtered, length in alpha, \
renormalized — and what renormalizing costs at a distance); whether it tiles (its seam against its \
own worst neighbouring texels); which finite-difference kernel its slopes fit (what to give \
`height --kernel`); and for BC5 and BC7 an estimate of the angle the compression added.\n\n\
Reads PNG (8/16-bit; its NAME.mip1.png, ... beside it as its mips), TGA, TIFF, JPEG, OpenEXR, \
DDS and KTX2 (with their mips, BC5 and BC7 included), or every such file directly inside a \
folder. Exit status: 0, or 1 when a file cannot \
be read or, with --strict, when a map needs fixing (not a normal map, texels facing into the \
surface or far from unit length, renormalized mips); 2 for a malformed command line.")]
pub struct InspectArgs {
    /// Normal map files, or folders of them
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Print one JSON array (an object per file) instead of the verdicts in words
    #[arg(long)]
    pub json: bool,
    /// Exit 1 when any map needs fixing (the lines marked FIX)
    #[arg(long)]
    pub strict: bool,
}

/// `bumpmap height`.
#[derive(Args, Debug)]
#[command(after_help = "Examples:\n  \
bumpmap height rock_normal.png -o rock_height.png              # 16-bit, 0..1, range printed\n  \
bumpmap height n.png -o h.exr --raw --scale 4                   # heights in texels, float\n  \
bumpmap height n.png -o h.png --method kernel --kernel sobel3 --scale 4   # undo normalmap exactly\n\n\
Integrates the slopes a normal map holds (p = −nx/nz, q = −ny/nz, green read as --y-convention \
says) back into heights: the least-squares surface whose slopes they are under the difference \
that made them (--kernel), solved with FFTs. The heights come back with mean zero in texels \
divided by --scale (the --scale `bumpmap normalmap` made the map with: the height of a unit \
step in texels), then mapped onto 0..1 for the file unless --raw. Which method, kernel and \
convention were used, and why, is printed.\n\n\
A kernel that smooths (sobel5, gaussian7) loses detail no integration brings back; --kernel \
auto then finds the sharpest kernel that explains the map (slopes cannot tell sobel5 from \
sobel3 applied to smoother heights), whose heights give the same map back.")]
pub struct HeightArgs {
    /// The normal map: PNG (8/16-bit), TGA, TIFF, JPEG, OpenEXR, DDS or KTX2 (level 0 is used)
    pub input: PathBuf,
    /// Output: .png (16-bit gray, or --bits 8) or .exr (32-bit float)
    #[arg(short, long)]
    pub output: PathBuf,
    /// How the slopes are integrated: the library's [`HEIGHTS`] table.
    #[command(flatten)]
    pub choices: Table<Heights>,
    /// Bits per channel of a PNG output: 8 or 16
    #[arg(long, default_value_t = 16, value_parser = parse_bits)]
    pub bits: u8,
    /// Refuse (exit 1) a file inspect says is not a normal map, rather than warn and integrate it
    #[arg(long)]
    pub strict: bool,
}

impl HeightArgs {
    /// The library's options from `--method`, `--kernel`, `--y-convention` and `--scale`.
    pub fn options(&self) -> Result<HeightOptions, crate::error::CliError> {
        use crate::error::CliError;
        self.choices.0.options().map_err(|e| match e {
            HeightChoiceError::Scale(e) => CliError::Usage(format!("--scale: {e}")),
            HeightChoiceError::KernelUnnamed => CliError::Usage(
                "--method kernel undoes a named kernel: add --kernel NAME (normalmap's --kernel); --method fft fits one itself"
                    .into(),
            ),
            HeightChoiceError::KernelSpectral => CliError::Usage(
                "--method kernel undoes a finite-difference kernel, and --kernel spectral is none: use --method fft for the spectral derivative"
                    .into(),
            ),
        })
    }
}
