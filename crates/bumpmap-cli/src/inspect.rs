//! `bumpmap inspect` and `bumpmap height`: the library's verdicts printed, and heights written.
//! Everything they decide is `bumpmap::inspect` and `bumpmap::heights`; this module only walks
//! the inputs, prints, and names flags in errors.

use bumpmap::Named;
use std::path::{Path, PathBuf};

use bumpmap::heights::{Chosen, heights_from_inspection};
use bumpmap::inspect::{MapReport, inspect_map, maps_in_folder, read_file, read_map};
use bumpmap_io::atomic::FileSet;
use bumpmap_io::gray_file::{GrayFormat, save_gray_into};
use bumpmap_math::integration::{Boundary, IntegrationError};

use crate::args::{HeightArgs, InspectArgs};
use crate::error::CliError;

/// `bumpmap inspect`.
pub fn run_inspect(args: &InspectArgs) -> Result<(), CliError> {
    let mut files: Vec<PathBuf> = Vec::new();
    for input in &args.inputs {
        if input.is_dir() {
            let found = maps_in_folder(input).map_err(bumpmap_words::frame::lib_err)?;
            if found.is_empty() {
                return Err(CliError::Path {
                    path: input.clone(),
                    reason: "holds no PNG, TGA, TIFF, JPEG, EXR, DDS or KTX2 file".into(),
                });
            }
            files.extend(found);
        } else {
            files.push(input.clone());
        }
    }
    let (mut failed, mut to_fix) = (0usize, 0usize);
    let mut json = Vec::new();
    for file in &files {
        match read_map(file).map(|m| inspect_map(&file.display().to_string(), &m)) {
            Ok(report) => {
                to_fix += usize::from(!report.findings().is_empty());
                if args.json {
                    json.push(report.to_json());
                } else {
                    print_report(&report);
                }
            }
            Err(e) if files.len() == 1 && !args.json => return Err(bumpmap_words::frame::lib_err(e)),
            Err(e) => {
                failed += 1;
                eprintln!("error: {e}");
                if args.json {
                    json.push(serde_json::json!({ "file": file.display().to_string(), "error": e.to_string() }));
                }
            }
        }
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&serde_json::Value::Array(json)).expect("JSON values print"));
    }
    if failed > 0 {
        return Err(CliError::Batch { failed, total: files.len() });
    }
    if args.strict && to_fix > 0 {
        return Err(CliError::Render(format!(
            "--strict: {to_fix} of {} map{} need{} fixing (the FIX lines)",
            files.len(),
            if files.len() == 1 { "" } else { "s" },
            if to_fix == 1 { "s" } else { "" }
        )));
    }
    Ok(())
}

fn print_report(report: &MapReport) {
    for line in report.lines() {
        println!("{line}");
    }
}

/// `bumpmap height`.
pub fn run_height(args: &HeightArgs) -> Result<(), CliError> {
    let options = args.options()?;
    let ext = args.output.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    if !matches!(ext.as_deref(), Some("png") | Some("exr")) {
        return Err(
            bumpmap_io::IoError::UnsupportedOutput { path: args.output.clone(), expected: ".png or .exr" }.into()
        );
    }
    let format = GrayFormat::for_path(&args.output, args.bits);
    if args.choices.0.raw && format != GrayFormat::Exr {
        return Err(CliError::Usage(format!(
            "--raw writes heights outside 0..1, which a PNG cannot hold: name an .exr output, not {}",
            args.output.display()
        )));
    }
    bumpmap_io::atomic::ensure_not_input(&args.output, &[&args.input])?;
    let map = read_file(&args.input).map_err(bumpmap_words::frame::lib_err)?;
    // Level 0's questions only: what height needs (the kind, the curl and seam tests).
    let inspection = bumpmap_math::inspect::inspect(&map.levels[..map.levels.len().min(1)], map.two_channel)
        .ok_or_else(|| CliError::Render(format!("{}: no texels", args.input.display())))?;
    if !inspection.kind.is_normal_map() {
        let what = inspection.kind.describe();
        if args.strict {
            return Err(CliError::Render(format!("{}: {what} (--strict refuses it)", args.input.display())));
        }
        crate::report::warn(format!("{}: {what}; integrating it anyway (--strict refuses it)", args.input.display()));
    }
    let level0 = map.levels.first().ok_or_else(|| CliError::Render(format!("{}: no texels", args.input.display())))?;
    let heights = heights_from_inspection(level0, &inspection, &options).map_err(|e| integration(&args.input, e))?;
    let (lo, hi) = heights.range();
    let seam = inspection.seam;
    let why_method = match (heights.boundary_chosen, heights.method.boundary) {
        (Chosen::Given, _) => "as given".to_string(),
        (_, Boundary::Free) if seam.tiles() => format!(
            "the map tiles but its heights climb: mean slope {:.3}, {:.3} per texel",
            seam.mean_slope[0], seam.mean_slope[1]
        ),
        (_, boundary) => format!(
            "the map {}: seam {:.1}° against {:.1}° inside",
            if boundary == Boundary::Periodic { "tiles" } else { "does not tile" },
            seam.seam_degrees(),
            seam.interior_degrees()
        ),
    };
    let why_kernel = match (heights.derivative_chosen, &heights.fit) {
        (Chosen::Given, _) | (_, None) => "as given".to_string(),
        (_, Some(fit)) => {
            let next = fit.residuals.iter().find(|r| r.0 != heights.method.derivative);
            match next {
                Some(next) => format!("fits the slopes best; next {}", next.0.name()),
                None => "fits the slopes best".to_string(),
            }
        }
    };
    let why_convention = match heights.convention_chosen {
        Chosen::Given => "as given".to_string(),
        Chosen::Detected(c) => format!("by the curl test, confidence {c:.2}"),
        Chosen::Default => format!(
            "the curl test could not decide ({}), so the glTF default; pass --y-convention if it is wrong",
            inspection.convention.convention.err().map_or("", |u| u.reason())
        ),
    };
    let flat = hi - lo <= f32::EPSILON * lo.abs().max(1.0);
    let samples = if args.choices.0.raw { heights.texels.clone() } else { heights.normalized() };
    let mut set = FileSet::new(&[&args.input]);
    save_gray_into(&mut set, &args.output, heights.width, heights.height, &samples, format)?;
    set.commit()?;
    eprintln!(
        "{}: method {} ({why_method}); kernel {} ({why_kernel}); read as {} ({why_convention})",
        args.input.display(),
        heights.method.boundary.name(),
        heights.method.derivative.name(),
        heights.y_convention.name(),
    );
    if flat {
        crate::report::warn(format!(
            "{}: the map is flat: every height is the same (written as 0)",
            args.input.display()
        ));
    }
    println!(
        "{}: {}x{} heights spanning {:.4} texels at --scale {} ({lo:.4} to {hi:.4}), written {}",
        args.output.display(),
        heights.width,
        heights.height,
        hi - lo,
        args.choices.0.scale,
        if args.choices.0.raw { "as they are (--raw)".to_string() } else { "mapped onto 0..1".to_string() }
    );
    Ok(())
}

fn integration(input: &Path, e: IntegrationError) -> CliError {
    match e {
        IntegrationError::OutOfMemory(m) => CliError::Render(format!("{}: {m}", input.display())),
        other => CliError::Render(format!("{}: {other}", input.display())),
    }
}
