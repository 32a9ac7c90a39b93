//! `bumpmap blend BASE DETAIL -o OUT`: the library's blend from files (`bumpmap::maps`), its
//! notes and refusals in the command line's words.

use crate::args::BlendArgs;
use crate::error::CliError;

/// Runs `bumpmap blend`.
pub fn run(args: &BlendArgs) -> Result<(), CliError> {
    let options = &args.blend.0;
    let (blended, files) = bumpmap::maps::blend_files(&args.base, &args.detail, &args.output, options)
        .map_err(bumpmap_words::maps::blend_error)?;
    for note in &blended.notes {
        bumpmap_words::report::note(note.clone());
    }
    let n = &blended.normals;
    eprintln!(
        "blended {} over {} ({}x{}, {}-bit, {}): wrote {}",
        args.detail.display(),
        args.base.display(),
        n.width,
        n.height,
        blended.bits,
        bumpmap::Named::name(options.method),
        files.iter().map(|f| f.display().to_string()).collect::<Vec<_>>().join(", ")
    );
    Ok(())
}
