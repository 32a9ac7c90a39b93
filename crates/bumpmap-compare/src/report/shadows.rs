//! The shadow study in `results.json` and `report.html`: the table, the plots and what the
//! numbers say, in the numbers measured.

use serde_json::{Value, json};

use crate::shadows::{FIELDS, LIGHTS, OCCLUSION_RAYS, ShadowMethod, ShadowStudy};

/// The study as JSON: every row, and occlusion per field.
pub fn json(s: &ShadowStudy) -> Value {
    json!({
        "depth_texels": s.depth_texels,
        "view_degrees": 0.0,
        "rows": s.rows.iter().map(|row| json!({
            "field": row.field, "light_degrees": row.light, "method": row.method.name(),
            "agreement": row.agreement, "flip_mean": row.flip,
        })).collect::<Vec<_>>(),
        "occlusion": s.occlusion.iter().map(|o| json!({
            "field": o.field, "rays_per_texel": OCCLUSION_RAYS, "texels": o.texels,
            "ao_mean_abs_error": o.ao_error, "ao_mean": o.ao_mean, "bent_normal_mean_degrees": o.bent_degrees,
        })).collect::<Vec<_>>(),
    })
}

/// The study's section of the report.
pub fn section(s: &ShadowStudy) -> String {
    let mut table = String::new();
    for field in FIELDS {
        for light in LIGHTS {
            for m in ShadowMethod::ALL {
                if let Some(row) = s.row(field, light, m) {
                    table += &format!(
                        "<tr><td>{field}</td><td>{light}°</td><td><b>{}</b></td><td>{:.1} %</td><td>{:.4}</td></tr>\n",
                        super::escape(m.name()),
                        100.0 * row.agreement,
                        row.flip
                    );
                }
            }
        }
    }
    let occlusion: String = s
        .occlusion
        .iter()
        .map(|o| {
            format!(
                "<tr><td>{}</td><td>{:.4}</td><td>{:.3}</td><td>{:.2}°</td><td>{}</td></tr>\n",
                o.field, o.ao_error, o.ao_mean, o.bent_degrees, o.texels
            )
        })
        .collect();
    let agree = |m: ShadowMethod, light: f32| s.row("bricks", light, m).map_or(f64::NAN, |r| 100.0 * r.agreement);
    let flip = |m: ShadowMethod, light: f32| s.row("bricks", light, m).map_or(f64::NAN, |r| r.flip);
    let summary = format!(
        "On the bricks with the light 70° from the normal, Kilgard's Eq. 12 agrees with the shadow rays on {eq:.1} % of the pixels that face the light — exactly as often as no shadow at all ({none:.1} %): \
         the wall's base surface faces the light everywhere, so the term never darkens the mortar a brick hides. \
         The horizon map agrees on {hz:.1} % ({hz80:.1} % at 80°), with no march; POM's march toward the light on {pm:.1} %, and POM's hit shadowed by the horizon map on {ph:.1} %. \
         FLIP against the reference with shadow rays: {fnone:.3} without shadows, {fhz:.3} with the horizon map, {fpm:.3} for POM with its march.",
        eq = agree(ShadowMethod::Eq12, 70.0),
        none = agree(ShadowMethod::NoShadow, 70.0),
        hz = agree(ShadowMethod::Horizon, 70.0),
        hz80 = agree(ShadowMethod::Horizon, 80.0),
        pm = agree(ShadowMethod::PomMarch, 70.0),
        ph = agree(ShadowMethod::PomHorizon, 70.0),
        fnone = flip(ShadowMethod::NoShadow, 70.0),
        fhz = flip(ShadowMethod::Horizon, 70.0),
        fpm = flip(ShadowMethod::PomMarch, 70.0),
    );
    format!(
        r#"<h2>Bumps that shadow each other, and hold ambient light</h2>
<p>The wall seen head-on from 1.2 units, lit by a directional light 45°, 70° and 80° from the normal; the heights carve {depth:.1} texels deep. <b>Agrees</b>: over the pixels whose exact surface faces the light, the share where the method's shadow (lit above ½) matches a shadow ray cast from the displaced surface. <b>FLIP</b>: the technique's image against the displaced reference drawn with its shadow rays (Eq. 12 is the single pass's own term, so its image is the single pass's).</p>
<table><tr><th>field</th><th>light</th><th>method</th><th>agrees</th><th>FLIP</th></tr>
{table}</table>
<p><img src="shadows_bricks.svg" alt="shadow agreement by light angle, bricks"> <img src="shadows_dimples.svg" alt="shadow agreement by light angle, dimples"></p>
<p>{summary}</p>
<p>Ambient occlusion and bent normals from the same horizon map (8 directions), against {rays} occlusion rays a texel (stratified, cosine-weighted) traced to the displaced surface from every fourth texel's centre along each axis:</p>
<table><tr><th>field</th><th>AO mean |error|</th><th>rays' mean AO</th><th>bent normal, mean angle</th><th>texels</th></tr>
{occlusion}</table>
"#,
        depth = s.depth_texels,
        rays = OCCLUSION_RAYS,
    )
}
