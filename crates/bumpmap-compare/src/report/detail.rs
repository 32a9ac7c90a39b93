//! The detail-normal study in `results.json` and `report.html`: the table, the plots and when
//! each blend is right, in the numbers measured.

use bumpmap::Named;
use bumpmap_math::detail::BlendMethod;
use serde_json::{Value, json};

use crate::detail::{BASE_SCALE, BASES, DETAIL_SCALE, DetailStudy, SIZE, STRENGTHS};

/// The study as JSON: every row.
pub fn json(d: &DetailStudy) -> Value {
    json!({
        "size": SIZE, "bits": 16, "base_scale": BASE_SCALE, "detail_scale": DETAIL_SCALE,
        "rows": d.rows.iter().map(|r| json!({
            "base": r.base, "detail": "noise", "strength": r.strength, "method": r.method.name(),
            "added_heights_mean_degrees": r.added.0, "added_heights_p95_degrees": r.added.1,
            "draped_detail_mean_degrees": r.draped.0, "draped_detail_p95_degrees": r.draped.1,
        })).collect::<Vec<_>>(),
    })
}

/// The study's section of the report.
pub fn section(d: &DetailStudy) -> String {
    let mut table = String::new();
    for base in BASES {
        for strength in STRENGTHS {
            for &m in BlendMethod::ALL {
                if let Some(r) = d.row(base, strength, m) {
                    table += &format!(
                        "<tr><td>{base} + noise</td><td>{strength}</td><td><b>{}</b></td><td>{:.3}°</td><td>{:.3}°</td><td>{:.3}°</td><td>{:.3}°</td></tr>\n",
                        super::escape(m.name()),
                        r.added.0,
                        r.added.1,
                        r.draped.0,
                        r.draped.1
                    );
                }
            }
        }
    }
    let at = |m: BlendMethod| d.row("bricks", 1.0, m);
    let mean = |m: BlendMethod, added: bool| at(m).map_or(f64::NAN, |r| if added { r.added.0 } else { r.draped.0 });
    let summary = format!(
        "On the bricks at strength 1: partial derivatives meet added heights within {pd:.3}° on average and RNM meets draped detail within {rnm:.3}° — \
         what is left is the 16-bit rounding of the two maps. Each is off the other composition by about as much as the two compositions differ \
         ({pd_draped:.3}° and {rnm_added:.3}°). Whiteout ({wo_added:.3}° and {wo_draped:.3}°) and UDN ({udn_added:.3}° and {udn_draped:.3}°) fall between the two, \
         closer to draped detail. Linear blending ({lin:.1}°) and overlay ({ov:.1}°) are off both by degrees: they flatten the base where the detail is flat. \
         Which composition is right is what the detail is: pores, scratches or grain cut into the base's own surface are heights that add — partial derivatives; \
         a pattern laid over the base's forms (a weave on a sculpted cloth, a label on a dented can) is draped — RNM. \
         The gap between them grows with the detail's strength and with the base's slopes.",
        pd = mean(BlendMethod::PartialDerivative, true),
        rnm = mean(BlendMethod::Rnm, false),
        pd_draped = mean(BlendMethod::PartialDerivative, false),
        rnm_added = mean(BlendMethod::Rnm, true),
        wo_added = mean(BlendMethod::Whiteout, true),
        wo_draped = mean(BlendMethod::Whiteout, false),
        udn_added = mean(BlendMethod::Udn, true),
        udn_draped = mean(BlendMethod::Udn, false),
        lin = mean(BlendMethod::Linear, true),
        ov = mean(BlendMethod::Overlay, true),
    );
    format!(
        r#"<h2>Detail normals: every blend against the exact compositions</h2>
<p>A noise detail (<code>normalmap --scale {detail}</code>) laid over bricks and over dimples (<code>--scale {base}</code>), {size}² texels each, both maps stored at 16 bits, by each blend of <code>bumpmap blend</code>, its slopes times the strength. Measured against two exact normals computed in float from the heights: <b>added heights</b>, the normal of the base's heights plus the detail's; and <b>draped detail</b>, the detail's normal turned by the rotation that takes the surface's normal to the base's. Mean and 95th percentile of the angle, every texel.</p>
<table><tr><th>maps</th><th>strength</th><th>method</th><th>added heights: mean</th><th>95th pct</th><th>draped detail: mean</th><th>95th pct</th></tr>
{table}</table>
<p><img src="detail_added.svg" alt="mean angle to added heights by strength, bricks"> <img src="detail_draped.svg" alt="mean angle to draped detail by strength, bricks"></p>
<p>{summary}</p>
"#,
        detail = DETAIL_SCALE,
        base = BASE_SCALE,
        size = SIZE,
    )
}
