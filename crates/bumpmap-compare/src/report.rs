//! What `compare` writes besides images and plots: `results.json`, and `report.html`, which
//! links only files in its own folder so the folder can be copied and opened anywhere.

mod detail;
mod shadows;

use serde_json::{Value, json};

use super::{PEERCY, Results, default_techniques};

/// The numbers, machine-readable: `{"techniques": {NAME: {"rmse", "psnr", "bias", "flip_mean",
/// "ssim", "millis"}}, "skipped": {NAME: reason}, …}`.
pub fn json(r: &Results) -> String {
    let mut techniques = serde_json::Map::new();
    let mut skipped = serde_json::Map::new();
    for o in &r.outcomes {
        match &o.result {
            Ok(x) => {
                let s = &x.scores;
                let displaced = x.displaced.map(|d| {
                    json!({"rmse": d.rmse, "psnr": d.psnr, "bias": d.bias, "flip_mean": d.flip_mean, "ssim": d.ssim})
                });
                techniques.insert(
                    o.name.clone(),
                    json!({"rmse": s.rmse, "psnr": s.psnr, "bias": s.bias, "flip_mean": s.flip_mean,
                           "ssim": s.ssim, "millis": x.millis, "image": format!("{}.png", o.name),
                           "heat_map": format!("{}.flip.png", o.name), "against_displaced": displaced}),
                );
            }
            Err(reason) => {
                skipped.insert(o.name.clone(), Value::String(reason.clone()));
            }
        }
    }
    let mut value = json!({
        "scene": r.scene,
        "size": r.size,
        "spp": r.spp,
        "backend": r.backend,
        "reference": {"image": "reference.png", "millis": r.reference_millis},
        "reference_displaced": match &r.displaced {
            Ok((_, millis)) => json!({"image": "reference-displaced.png", "millis": millis}),
            Err(reason) => json!({"skipped": reason}),
        },
        "techniques": techniques,
        "skipped": skipped,
        "convergence": r.convergence.iter().map(|(k, e)| json!({"k": k, "rmse_to_4k": e})).collect::<Vec<_>>(),
        "total_millis": r.total_millis,
    });
    let studies = value.as_object_mut().expect("an object");
    if let Some([headlight, side]) = &r.golf_ball {
        studies.insert("golf_ball".into(), golf_json(headlight).into());
        studies.insert("golf_ball_side_light".into(), golf_json(side).into());
    }
    if let Some(specular) = &r.specular {
        studies.insert("specular_filtering".into(), specular_json(specular).into());
    }
    if let Some(e) = &r.emboss {
        studies.insert("emboss".into(), json!({
            "by_angle": e.by_angle.iter().map(|(a, er, eb, sr, sb, c)| json!({"degrees": a, "emboss_rmse": er,
                "emboss_bias": eb, "single_pass_rmse": sr, "single_pass_bias": sb, "emboss_contrast_ratio": c})).collect::<Vec<_>>(),
            "by_distance": e.by_distance.iter().map(|(d, em, sp)| json!({"distance": d,
                "emboss_contrast_ratio": em, "single_pass_contrast_ratio": sp})).collect::<Vec<_>>(),
            "facing_away": {"dark_fraction": e.facing_away.0, "forced_lit_fraction": e.facing_away.1,
                "unforced_lit_fraction": e.facing_away.2},
        }));
    }
    if let Some(peercy) = &r.peercy {
        studies.insert("peercy".into(), json!({
            "size": peercy.size,
            "shown_bump_scale": peercy.shown_scale,
            "images": peercy.images.iter().map(|(n, _, _)| format!("{n}.png")).collect::<Vec<_>>(),
            "by_bump_scale": peercy.rows.iter().map(|row| {
                let per = |values: &[f64; 3]| -> serde_json::Map<String, Value> {
                    PEERCY.iter().zip(values).map(|(n, v)| (n.to_string(), json!(v))).collect()
                };
                json!({"bump_scale": row.bump_scale, "rmse_same_slopes": per(&row.rmse_same_slopes),
                       "rmse_raw_heights": per(&row.rmse_raw_heights), "flip_from_dependent": per(&row.flip_from_dependent)})
            }).collect::<Vec<_>>(),
        }));
    }
    if let Some(p) = &r.parallax {
        studies.insert("parallax".into(), parallax_json(p));
    }
    if let Some(s) = &r.shadows {
        studies.insert("shadows".into(), shadows::json(s));
    }
    if let Some(d) = &r.detail {
        studies.insert("detail".into(), detail::json(d));
    }
    serde_json::to_string_pretty(&value).expect("a JSON value serializes") + "\n"
}

fn parallax_json(p: &super::parallax::ParallaxStudy) -> Value {
    json!({
        "size": p.size,
        "spp": p.spp,
        "depth_texels": p.depth_texels,
        "light_degrees": super::parallax::LIGHT_DEGREES,
        "images": p.figure.iter().map(|(n, _, _)| format!("{n}.png")).collect::<Vec<_>>(),
        "rows": p.rows.iter().map(|row| json!({
            "field": row.field, "degrees": row.angle, "technique": row.technique.name(),
            "hit_error_mean": row.hit_mean, "hit_error_p95": row.hit_p95,
            "shadow_agreement": row.shadow_agreement, "flip_mean": row.flip, "rmse": row.rmse, "millis": row.millis,
            "flip_mean_hit_normal_map": row.flip_by_hit_normal.map(|f| f.0),
            "flip_mean_hit_normal_heights": row.flip_by_hit_normal.map(|f| f.1),
        })).collect::<Vec<_>>(),
    })
}

fn specular_json(rows: &[super::studies::SpecularRow]) -> Vec<Value> {
    rows.iter()
        .map(|row| {
            let mut filters = serde_json::Map::new();
            for (k, name) in super::studies::SPECULAR_FILTERS.iter().enumerate() {
                let (energy, width) = row.filters[k];
                filters.insert(
                    name.to_string(),
                    json!({"energy": energy, "width": width, "energy_error": row.energy_errors()[k]}),
                );
            }
            json!({
                "distance": row.distance,
                "reference": {"energy": row.reference.0, "width": row.reference.1},
                "filters": filters,
            })
        })
        .collect()
}

fn golf_json(rows: &[(f32, f64, f64, f64)]) -> Vec<Value> {
    rows.iter()
        .map(|(d, re, l, n)| json!({"distance": d, "reference": re, "length_factor": l, "renormalized": n}))
        .collect()
}

/// The heights-as-geometry study: how it was measured, the figure, the table, the plots and
/// where each family of march breaks down, in the measured numbers.
fn parallax_section(p: &super::parallax::ParallaxStudy) -> String {
    use super::parallax::{ANGLES, FIELDS, LIGHT_DEGREES, TECHNIQUES};
    use bumpmap::TechniqueName as T;
    let mut table = String::new();
    for field in FIELDS {
        for angle in ANGLES {
            for t in TECHNIQUES {
                if let Some(row) = p.row(field, angle, t) {
                    let by_normal =
                        row.flip_by_hit_normal.map_or("—".to_string(), |(m, h)| format!("{m:.4} / {h:.4}"));
                    table += &format!(
                        "<tr><td>{field}</td><td>{angle}°</td><td><b>{}</b></td><td>{:.3}</td><td>{:.3}</td><td>{:.1} %</td><td>{:.4}</td><td>{by_normal}</td><td>{:.4}</td><td>{:.1}</td></tr>\n",
                        t.name(),
                        row.hit_mean,
                        row.hit_p95,
                        100.0 * row.shadow_agreement,
                        row.flip,
                        row.rmse,
                        row.millis
                    );
                }
            }
        }
    }
    let figure: String = p
        .figure
        .iter()
        .map(|(n, caption, _)| {
            format!(
                "<figure><img src=\"{n}.png\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n",
                escape(caption),
                escape(caption)
            )
        })
        .collect();
    let hit = |t: T, angle: f32| p.row("bricks", angle, t).map_or(f64::NAN, |r| r.hit_mean);
    let p95 = |t: T, angle: f32| p.row("bricks", angle, t).map_or(f64::NAN, |r| r.hit_p95);
    let flip = |t: T, angle: f32| p.row("bricks", angle, t).map_or(f64::NAN, |r| r.flip);
    let shadow = |t: T, angle: f32| p.row("bricks", angle, t).map_or(f64::NAN, |r| 100.0 * r.shadow_agreement);
    let by_normal =
        |t: T, angle: f32| p.row("bricks", angle, t).and_then(|r| r.flip_by_hit_normal).unwrap_or((f64::NAN, f64::NAN));
    let ms = |t: T| {
        let rows: Vec<f64> = p.rows.iter().filter(|r| r.technique == t).map(|r| r.millis).collect();
        rows.iter().sum::<f64>() / rows.len().max(1) as f64
    };
    let breakdown = format!(
        "On the bricks: normal mapping reads every map where the ray enters the polygon, {sp30:.2} texels from the exact hit at 30° and {sp85:.1} at 85°, \
         and no brick ever hides its mortar. Parallax mapping's single offset follows the height at the entry point, not along the ray: \
         it moves the maps the right way on gentle slopes ({pa30:.2} texels at 30°) but swims at brick edges, where the entry point's height says nothing of what the ray meets ({pa70:.2} at 70°, {pa85:.1} at 85°, \
         and its shadows agree with the shadow rays on only {pas70:.1} % of the lit pixels at 70°, because the shadow starts from the wrong place). \
         Steep parallax stops at the first layer below the heights, so its error is up to a layer's span of the ray, which grows as the view grazes: {st30:.3} texels at 30°, {st85:.2} at 85° (95th percentile {st85p:.2}). \
         Parallax occlusion mapping interpolates between the last two layers and stays within a tenth of a texel up to 75° ({po70:.3} at 70°, {po75:.3} at 75°); \
         at 85° a layer's span is longer than a brick's bevel, so the linear search steps over thin ridges and the interpolation then lands on the wrong side of them ({po85:.3}, 95th percentile {po85p:.2}). \
         Relief mapping's binary search refines the same layer and fails where POM's linear search does ({re85:.3} at 85°). \
         The exact walk meets the interpolant within rounding everywhere ({ex85:.1e} texels at 85°) at {ex_ms:.0} ms a frame against POM's {po_ms:.0} ms. \
         The marches' hard shadows agree with the shadow rays on {pos70:.1} % (POM) of the pixels that face the light at 70°. \
         FLIP against the displaced reference ({pof70:.3} for POM at 70°, {exf70:.3} for the exact walk) is the hit's error and the normal's together; each march is drawn twice to tell them apart (the table's second FLIP column, <code>--hit-normal</code>). \
         Shaded with the normal map at the hit (8 bits, filtered between texels and levels), POM reads {pom_m:.3} at 70°, relief {re_m:.3}, the exact walk {ex_m:.3}: nearly alike, however exact the hit. \
         Shaded with the heights' own normal (their interpolant's at level 0, which the reference draws: the exact walk's default, <code>--hit-normal heights</code> for the marches), POM reads {pom_h:.3}, relief {re_h:.3}, the exact walk {ex_h:.3}: the normal map was most of the error. \
         What is left is the hits themselves and the reference's antialiasing ({spp} samples a pixel where every technique takes one).",
        sp30 = hit(T::SinglePass, 30.0),
        sp85 = hit(T::SinglePass, 85.0),
        pa30 = hit(T::Parallax, 30.0),
        pa70 = hit(T::Parallax, 70.0),
        pa85 = hit(T::Parallax, 85.0),
        pas70 = shadow(T::Parallax, 70.0),
        st30 = hit(T::SteepParallax, 30.0),
        st85 = hit(T::SteepParallax, 85.0),
        st85p = p95(T::SteepParallax, 85.0),
        po70 = hit(T::Pom, 70.0),
        po75 = hit(T::Pom, 75.0),
        po85 = hit(T::Pom, 85.0),
        po85p = p95(T::Pom, 85.0),
        re85 = hit(T::Relief, 85.0),
        ex85 = hit(T::HeightExact, 85.0),
        ex_ms = ms(T::HeightExact),
        po_ms = ms(T::Pom),
        pos70 = shadow(T::Pom, 70.0),
        pof70 = flip(T::Pom, 70.0),
        exf70 = flip(T::HeightExact, 70.0),
        pom_m = by_normal(T::Pom, 70.0).0,
        pom_h = by_normal(T::Pom, 70.0).1,
        re_m = by_normal(T::Relief, 70.0).0,
        re_h = by_normal(T::Relief, 70.0).1,
        ex_m = by_normal(T::HeightExact, 70.0).0,
        ex_h = by_normal(T::HeightExact, 70.0).1,
        spp = p.spp,
    );
    format!(
        r#"<h2>Heights as geometry: the wall at grazing angles</h2>
<p>The brick wall (and the dimples) seen from 1.2 units at 30°, 60°, 70°, 75° and 85° from its normal, {size}×{size} pixels (about a third of a texel across a pixel at the centre), lit by a directional light {light}° from the normal. The heights carve {depth} texels deep, what the bump scale stands for; the normal maps are made with central differences, whose slope at each texel centre is the interpolant's. Each technique runs with its defaults (32 layers) against the displaced reference ({spp} samples per pixel). <b>Hit error</b>: for every pixel whose ray enters the wall, the distance in texels between where the technique reads its maps and where the pixel-centre ray meets the interpolant (the march as both backends run it, per pixel; normal mapping "hits" where the ray enters the polygon). <b>Shadow</b>: each march's hard shadow at its own hit against a shadow ray from the exact hit, over the pixels whose exact surface faces the light. <b>FLIP</b> and <b>RMSE</b>: the technique's image against the reference's.</p>
<div class="grid">
{figure}</div>
<table><tr><th>field</th><th>view</th><th>technique</th><th>hit error, mean</th><th>hit error, 95 %</th><th>shadow agrees</th><th>FLIP</th><th>FLIP, hit normal map / heights</th><th>RMSE</th><th>ms</th></tr>
{table}</table>
<p><img src="parallax_hits_bricks.svg" alt="hit error by angle, bricks"> <img src="parallax_flip_bricks.svg" alt="FLIP by angle, bricks"></p>
<p><img src="parallax_hits_dimples.svg" alt="hit error by angle, dimples"> <img src="parallax_flip_dimples.svg" alt="FLIP by angle, dimples"></p>
<p>{breakdown}</p>
"#,
        size = p.size,
        spp = p.spp,
        light = LIGHT_DEGREES,
        depth = p.depth_texels,
    )
}

/// Escapes text for HTML.
pub(super) fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// The page: the reference and every technique with its heat map, the table sorted by RMSE,
/// the skipped techniques with their reasons, and the plots.
pub fn html(r: &Results) -> String {
    let mut rows: Vec<_> = r.outcomes.iter().filter_map(|o| o.result.as_ref().ok().map(|x| (o, x))).collect();
    rows.sort_by(|a, b| a.1.scores.rmse.total_cmp(&b.1.scores.rmse));
    let mut table = String::new();
    for (o, x) in &rows {
        let s = &x.scores;
        let displaced = x.displaced.map_or("<td>–</td><td>–</td>".to_string(), |d| {
            format!("<td>{:.4}</td><td>{:.4}</td>", d.rmse, d.flip_mean)
        });
        table += &format!(
            "<tr><td><b>{}</b></td><td>{:.4}</td><td>{:.2}</td><td>{:+.4}</td><td>{:.4}</td><td>{:.4}</td>{displaced}<td>{:.0}</td><td>{}</td></tr>\n",
            escape(&o.name),
            s.rmse,
            s.psnr,
            s.bias,
            s.flip_mean,
            s.ssim,
            x.millis,
            escape(&o.description)
        );
    }
    let mut grid = format!(
        "<figure><img src=\"reference.png\" alt=\"reference\"><figcaption>reference ({} samples per pixel, {:.0} ms)</figcaption></figure>\n",
        r.spp, r.reference_millis
    );
    let displaced_note = match &r.displaced {
        Ok((_, millis)) => {
            grid += &format!(
                "<figure><img src=\"reference-displaced.png\" alt=\"displaced reference\"><figcaption>displaced reference: the surface carved by the heights ({} samples per pixel, {millis:.0} ms)</figcaption></figure>\n",
                r.spp
            );
            "The last two number columns measure each image against the displaced reference instead: the same heights taken as geometry, carved below the surface by the depth the bump scale stands for, rays traced to it. Normal mapping's error there includes every bump it draws flat.".to_string()
        }
        Err(why) => format!("No displaced reference: {}.", escape(why)),
    };
    for (o, _) in &rows {
        let n = escape(&o.name);
        grid += &format!(
            "<figure><img src=\"{n}.png\" alt=\"{n}\"><img src=\"{n}.flip.png\" alt=\"{n} FLIP error\"><figcaption>{n}: image and FLIP error</figcaption></figure>\n"
        );
    }
    let skipped: String = r
        .outcomes
        .iter()
        .filter_map(|o| {
            o.result.as_ref().err().map(|why| format!("<li><b>{}</b>: {}</li>\n", escape(&o.name), escape(why)))
        })
        .collect();
    let skipped = if skipped.is_empty() { "<p>None.</p>".to_string() } else { format!("<ul>{skipped}</ul>") };
    let known: String =
        default_techniques().iter().map(|t| format!("<li><b>{t}</b>: {}</li>", escape(t.description()))).collect();
    let mut page = format!(
        r#"<!DOCTYPE html>
<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>bumpmap compare: {scene}</title>
<style>
body {{ font-family: sans-serif; margin: 2em; max-width: 1200px; }}
table {{ border-collapse: collapse; margin: 1em 0; }} td, th {{ border: 1px solid #ccc; padding: 4px 8px; text-align: right; }}
td:first-child, td:last-child {{ text-align: left; }}
.grid {{ display: flex; flex-wrap: wrap; gap: 12px; }} figure {{ margin: 0; }} figure img {{ display: block; image-rendering: pixelated; }}
figcaption {{ font-size: 0.85em; max-width: {size}px; }}
</style></head><body>
<h1>bumpmap compare: {scene}, {size}×{size}</h1>
<p>Every technique against the reference (Blinn's perturbed normal on the exact surface from a C¹ interpolant of the height field, {spp} samples per pixel, in float). Backend: {backend}. Total time {total:.1} s.</p>
<h2>Errors against the reference</h2>
<table><tr><th>technique</th><th>RMSE</th><th>PSNR (dB)</th><th>bias</th><th>FLIP mean</th><th>SSIM</th><th>RMSE, displaced</th><th>FLIP, displaced</th><th>ms</th><th>what it is</th></tr>
{table}</table>
<p>RMSE, PSNR and bias over linear RGB in [0, 1] (bias: mean of image − reference, positive is too bright); FLIP (NVIDIA) and SSIM of the luminance on the 8-bit images. The heat maps are FLIP's per-pixel error, black none, yellow most. {displaced_note}</p>
<h2>Skipped</h2>
{skipped}
<h2>Images</h2>
<div class="grid">
{grid}</div>
<h2>The reference converges</h2>
<p><img src="convergence.svg" alt="convergence plot"></p>
"#,
        scene = escape(&r.scene),
        size = r.size,
        spp = r.spp,
        backend = escape(&r.backend),
        total = r.total_millis / 1e3,
    );
    if let Some([headlight, side]) = &r.golf_ball {
        page += &golf_section(headlight, side);
    }
    if let Some(specular) = &r.specular {
        page += &specular_section(specular);
    }
    if let Some(emboss) = &r.emboss {
        page += &emboss_section(emboss);
    }
    if let Some(peercy) = &r.peercy {
        page += &peercy_section(peercy);
    }
    if let Some(p) = &r.parallax {
        page += &parallax_section(p);
    }
    if let Some(s) = &r.shadows {
        page += &shadows::section(s);
    }
    if let Some(d) = &r.detail {
        page += &detail::section(d);
    }
    page += &format!(
        r#"<h2>Techniques</h2>
<ul>{known}</ul>
<pre id="loaded"></pre>
<script>
// Records whether each image loaded (its natural width), for a headless browser to read.
window.addEventListener('load', () => {{
  document.getElementById('loaded').textContent =
    Array.from(document.images).map(i => i.getAttribute('src') + ' ' + i.naturalWidth).join('\n');
}});
</script>
</body></html>
"#
    );
    page
}

/// Kilgard §2.4.2's golf ball: the mean brightness by distance, lit from behind the eye and from
/// the side.
fn golf_section(headlight: &[(f32, f64, f64, f64)], side: &[(f32, f64, f64, f64)]) -> String {
    let golf_rows = |rows: &[(f32, f64, f64, f64)]| -> String {
        rows.iter()
            .map(|(d, re, l, n)| format!("<tr><td>{d}×</td><td>{re:.4}</td><td>{l:.4}</td><td>{n:.4}</td></tr>"))
            .collect()
    };
    let (golf, golf_side) = (golf_rows(headlight), golf_rows(side));
    format!(
        r#"<h2>A golf ball at a distance (Kilgard §2.4.2)</h2>
<p>A dimpled sphere (no specular) moving away, 96×96 pixels, lit from behind the eye: the mean brightness over the ball (the frame's sum over the pixels the reference's ball touches). Averaged bumpy normals are shorter than 1, so a bumpy ball far away is dimmer than a smooth one (the reference). Mips that renormalize the average forget that and stay too bright; mips that keep its length in alpha (Kilgard §5.3) dim the ball, and the table says by how much compared with the reference — the ball's limb, lit at grazing angles, pushes them a little too dark (the next paragraph says why).</p>
<table><tr><th>distance</th><th>reference</th><th>length factor</th><th>renormalized</th></tr>{golf}</table>
<p><img src="golf_ball.svg" alt="golf ball plot"></p>
<p>The same ball with the sphere scene's own light, from the side. Here much of each footprint faces away from the light, N·L is clamped at 0, and the length factor becomes a lower bound (the mean of clamped dot products is at least the clamped dot product of the mean normal): it is too dark.</p>
<table><tr><th>distance</th><th>reference</th><th>length factor</th><th>renormalized</th></tr>{golf_side}</table>
"#
    )
}

/// Kilgard §2.5.3's highlight at a distance, by specular filter.
fn specular_section(specular: &[super::studies::SpecularRow]) -> String {
    let specular_rows: String = specular
        .iter()
        .map(|row| {
            let errors = row.energy_errors();
            let cells: String = (0..super::studies::SPECULAR_FILTERS.len())
                .map(|k| {
                    let (e, w) = row.filters[k];
                    format!("<td>{e:.4} ({:+.1} %)</td><td>{w:.3}</td>", 100.0 * errors[k])
                })
                .collect();
            format!(
                "<tr><td>{}×</td><td>{:.4}</td><td>{:.3}</td>{cells}</tr>",
                row.distance, row.reference.0, row.reference.1
            )
        })
        .collect();
    let specular_summary = specular
        .iter()
        .map(|row| {
            let [renormalized, _, toksvig, roughness, lean, clean] = row.energy_errors();
            let ratio = |e: f64| e.abs() / renormalized.abs().max(1e-9);
            let (t, r, l, c) = (ratio(toksvig), ratio(roughness), ratio(lean), ratio(clean));
            format!("{}×: {t:.2}, {r:.2}, {l:.2} and {c:.2}", row.distance)
        })
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        r#"<h2>The golf ball's highlight at a distance: specular filtering (Kilgard §2.5.3)</h2>
<p>The same ball, 160×160 pixels, specular alone (ambient and diffuse 0, k_s 1, shininess 32), a directional light behind the eye, at five distances over a 16× range; every variant is the single pass. Specular energy is the frame's summed brightness over the pixels the reference's ball touches; width is the brightness-weighted RMS distance from the highlight's centre, as a fraction of the ball's radius. The mips average the dimples' normals into one, so the single pass keeps a highlight as tight as a smooth ball's while the reference's spreads and dims. The length in alpha does not reach the specular term (it is the same as renormalized mips here); Toksvig's filter widens the lobe by it, s′ = s·|N|/(|N| + s(1 − |N|)), with the energy factor (1 + s′)/(1 + s).</p>
<table><tr><th rowspan="2">distance</th><th colspan="2">reference</th><th colspan="2">renormalized mips</th><th colspan="2">length factor</th><th colspan="2">Toksvig</th><th colspan="2">roughness map</th><th colspan="2">LEAN</th><th colspan="2">CLEAN</th></tr>
<tr><th>energy</th><th>width</th><th>energy (error)</th><th>width</th><th>energy (error)</th><th>width</th><th>energy (error)</th><th>width</th><th>energy (error)</th><th>width</th><th>energy (error)</th><th>width</th><th>energy (error)</th><th>width</th></tr>
{specular_rows}</table>
<p>The roughness map is the file <code>bumpmap normalmap --mips --roughness-out</code> writes for this ball (Filament's prefilter of each level's mean normal length, 8 bits, every level, at shininess 32's roughness (2/34)<sup>¼</sup>), sampled by its own texture unit and read as an engine's Blinn–Phong shader reads roughness: GGX α² = roughness⁴, exponent s′ = 2/α² − 2, with the normalized lobes' ratio (s′ + 2)/(s + 2). LEAN mapping (Olano &amp; Baker 2010) filters the slopes' first and second moments, made from the normal map's level 0, and draws the highlight as a Gaussian of their covariance plus 1/s, scaled to Blinn–Phong's peak for a flat texel; CLEAN (their §5) shares the slopes' spread out equally in x and y, from one texture of (Bx, By, Mxx + Myy, J). Toksvig's, the roughness map's, LEAN's and CLEAN's energy error as a fraction of renormalized mips', by distance: {specular_summary}.</p>
<p><img src="specular_energy.svg" alt="specular energy by distance"> <img src="specular_width.svg" alt="highlight width by distance"></p>
"#
    )
}

/// Kilgard §3.1's embossing studies.
fn emboss_section(emboss: &super::studies::EmbossStudy) -> String {
    let emboss_angles: String = emboss
        .by_angle
        .iter()
        .map(|(a, er, eb, sr, sb, c)| {
            format!("<tr><td>{a}°</td><td>{er:.4}</td><td>{eb:+.4}</td><td>{c:.3}</td><td>{sr:.4}</td><td>{sb:+.4}</td></tr>")
        })
        .collect();
    let emboss_distances: String = emboss
        .by_distance
        .iter()
        .map(|(d, e, s)| format!("<tr><td>{d}×</td><td>{e:.3}</td><td>{s:.3}</td></tr>"))
        .collect();
    let (away_dark, away_forced, away_unforced) =
        (100.0 * emboss.facing_away.0, 100.0 * emboss.facing_away.1, 100.0 * emboss.facing_away.2);
    format!(
        r#"<h2>Embossing (Kilgard §3.1)</h2>
<p>The brick wall without specular (embossing is diffuse only), 96×96 pixels, a directional light at each angle from the wall's normal. Contrast is the standard deviation of the wall's brightness, as a fraction of the reference's. With the light along the normal the shift is zero, the two fetches agree, and embossing is flat (contrast near 0) and too bright (positive bias): it shows L_z = 1 where the bumps should turn the normal away from the light.</p>
<table><tr><th>light</th><th>emboss RMSE</th><th>emboss bias</th><th>emboss contrast</th><th>single-pass RMSE</th><th>single-pass bias</th></tr>{emboss_angles}</table>
<p><img src="emboss_angle.svg" alt="emboss error by light angle"></p>
<p>At a distance (light at 45°): embossing's shift is one texel of level 0, so at the small mip levels a distant wall samples, both fetches land on nearly the same filtered height and the bumps vanish; the single pass keeps them.</p>
<table><tr><th>distance</th><th>emboss contrast</th><th>single-pass contrast</th></tr>{emboss_distances}</table>
<p>Faces turned away: a sphere lit from the side, half of it away from the light; the reference leaves {away_dark:.1} % of the image at the ambient term. Of those pixels, embossing lights (more than 5 steps above ambient) {away_forced:.1} % with L_x, L_y forced to 0 where L_z ≤ 0, and {away_unforced:.1} % without forcing: the unforced shift keeps lighting bumps on the dark side.</p>
"#
    )
}

/// Peercy's Figures 5–7 on his patch.
fn peercy_section(peercy: &super::studies::PeercyStudy) -> String {
    let peercy_rows: String = peercy
        .rows
        .iter()
        .map(|row| {
            let cells = |v: &[f64; 3]| v.iter().map(|x| format!("<td>{x:.4}</td>")).collect::<String>();
            format!(
                "<tr><td>{}</td>{}{}<td>{:.4}</td><td>{:.4}</td></tr>",
                row.bump_scale,
                cells(&row.rmse_same_slopes),
                cells(&row.rmse_raw_heights),
                row.flip_from_dependent[2],
                row.flip_from_dependent[0]
            )
        })
        .collect();
    let peercy_summary = peercy
        .rows
        .iter()
        .map(|row| {
            let [ind, dep, blinn] = row.rmse_same_slopes;
            let percent = |x: f64| 100.0 * (x - dep) / dep;
            format!("at {}, Figure 5 {:+.1} % and Figure 7 {:+.1} %", row.bump_scale, percent(blinn), percent(ind))
        })
        .collect::<Vec<_>>()
        .join("; ");
    let peercy_images: String = peercy
        .images
        .iter()
        .map(|(n, caption, _)| {
            format!("<figure><img src=\"{n}.png\" alt=\"{caption}\"><figcaption>{caption}</figcaption></figure>\n")
        })
        .collect();
    format!(
        r#"<h2>Peercy's Figures 5–7 on his patch</h2>
<p>Peercy's scene: the highly stretched, sheared bicubic patch in 8×8×2 triangles with the pinwheel over it once, {peercy_size}×{peercy_size} pixels, every map made with the paper's 7×7 derivative of a Gaussian and filtered trilinearly. Figure 7 (<b>peercy-independent</b>) lights the surface-independent map of Eq. 8–11, which assumes square texels; Figure 6 (<b>peercy-dependent</b>) lights, in the same way, the map of Eq. 3–6 made per texel from the patch's exact ∂P/∂u, ∂P/∂v; Figure 5 (<b>peercy-blinn</b>) reads f_u, f_v from a texture and makes Blinn's normal per pixel from the interpolated surface derivatives. The paper compares the three with the same f_u, f_v, so the first error columns use a reference made from the heights as that kernel sees them (smoothed by the same Gaussian): what is left is how each implementation applies the slopes. The next columns use the raw heights, adding the kernel's own smoothing (a blade edge one texel wide spread over seven) to all three alike. The last columns are FLIP between Figure 6 and Figures 5 and 7: how visible the difference is.</p>
<table><tr><th rowspan="2">bump scale</th><th colspan="3">RMSE, same f_u, f_v</th><th colspan="3">RMSE, raw heights</th><th colspan="2">FLIP from Fig. 6</th></tr>
<tr><th>Fig. 7 indep.</th><th>Fig. 6 dep.</th><th>Fig. 5 Blinn</th><th>Fig. 7 indep.</th><th>Fig. 6 dep.</th><th>Fig. 5 Blinn</th><th>Fig. 5</th><th>Fig. 7</th></tr>
{peercy_rows}</table>
<p>RMSE against the same-slopes reference, relative to Figure 6's, by bump scale: {peercy_summary}. The paper finds Figures 5 and 6 almost indistinguishable and Figure 7 a little off. Where Figure 5 falls behind Figure 6 as the slopes steepen, the cause is filtering (the README gives the control experiment): it averages the slopes and makes the normal from the average, while the normal maps average the normals themselves, and the normal of an average slope is steeper than the average of the normals.</p>
<div class="grid">
{peercy_images}</div>
<p>The images: bump scale {peercy_shown}, the reference with the kernel's heights first.</p>
<p><img src="peercy.svg" alt="Peercy error by bump scale"></p>
"#,
        peercy_size = peercy.size,
        peercy_shown = peercy.shown_scale,
    )
}
