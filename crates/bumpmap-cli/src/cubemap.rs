//! `bumpmap cubemap`: write a normalization cube map, or tabulate its accuracy.

use bumpmap_math::cubemap::worst_angular_error_degrees;
use bumpmap_math::{Encoding, NormalizationCubeMap};

use crate::args::CubemapArgs;
use crate::error::CliError;

pub fn run(args: &CubemapArgs) -> Result<(), CliError> {
    if args.accuracy {
        print!("{}", accuracy_table());
        return Ok(());
    }
    let out = args.output.as_ref().expect("clap requires --output without --accuracy");
    let map = NormalizationCubeMap::new(args.size as usize, args.encoding);
    write(out, &map)
}

/// Writes six PNG faces into a folder, or one DDS / KTX2 cube map.
pub fn write(out: &std::path::Path, map: &NormalizationCubeMap) -> Result<(), CliError> {
    Ok(bumpmap::maps::write_cube_map(out, map)?)
}

/// Markdown table of the worst angular error for face sizes 8–128 in both encodings.
pub fn accuracy_table() -> String {
    let mut s =
        String::from("| face size | unorm: worst error (°) | kilgard: worst error (°) |\n| --- | --- | --- |\n");
    for size in [8, 16, 32, 64, 128] {
        let e = |enc| worst_angular_error_degrees(&NormalizationCubeMap::new(size, enc));
        s += &format!("| {size} | {:.3} | {:.3} |\n", e(Encoding::Unorm), e(Encoding::Kilgard));
    }
    s
}
