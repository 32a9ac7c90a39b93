//! `bumpmap bake HIGH LOW -o OUT`: the library's bake from files (`bumpmap::bake`), its rows on
//! a bar, its refusals in the command line's words (`bumpmap_words::bake`).

use bumpmap::bake::{BakeOutputs, bake_files};
use indicatif::{ProgressBar, ProgressStyle};

use crate::args::BakeArgs;
use crate::error::CliError;

/// Runs `bumpmap bake`.
pub fn run(args: &BakeArgs) -> Result<(), CliError> {
    let request = &args.bake.0;
    let outputs = BakeOutputs {
        normal_map: args.output.clone(),
        object_space: args.object_out.clone(),
        mask: args.mask_out.clone(),
        occlusion: args.ao_out.clone(),
        displacement: args.height_out.clone(),
        curvature: args.curvature_out.clone(),
        low: args.low_out.clone(),
    }
    .with_maps_beside(&args.maps);
    let bar = ProgressBar::new(request.options.height as u64)
        .with_style(ProgressStyle::with_template("{bar:40} {pos}/{len} rows {elapsed}").expect("a valid template"));
    let done = bake_files(&args.high, &args.low, request, &outputs, &|rows, _| bar.set_position(rows as u64));
    bar.finish_and_clear();
    let done = done.map_err(|e| bumpmap_words::bake::bake_error(e, &args.high, &args.low))?;
    let c = done.counts;
    let (front, back) = done.baked.distances;
    eprintln!(
        "baked {} ({} triangles) onto {} ({} triangles): {} of {} texels of its UV layout hit, rays from {front} in front to {back} behind",
        args.high.display(),
        c.high_triangles,
        args.low.display(),
        c.low_triangles,
        c.hit,
        c.covered
    );
    if c.hit < c.covered {
        bumpmap_words::report::warn(format!(
            "{} texels' rays met nothing (see --mask-out; a longer --extrude or --max-distance reaches further)",
            c.covered - c.hit
        ));
    }
    let files = &done.files;
    eprintln!("wrote {}", files.iter().map(|f| f.display().to_string()).collect::<Vec<_>>().join(", "));
    Ok(())
}
