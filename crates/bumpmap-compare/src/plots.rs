//! The report's plots as SVG (`plotters`): the reference's convergence, the golf ball at a
//! distance, its highlight's energy and width by specular filter, embossing by light angle and
//! Peercy's figures by bump scale.
//!
//! What this module does not do: measure anything (the studies do) or write files.

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;

use super::Results;

/// `(file name, SVG)` of each plot.
pub fn plots(r: &Results) -> Vec<(&'static str, String)> {
    let mut plots = vec![("convergence.svg", convergence_plot(r))];
    if let Some([golf, _]) = &r.golf_ball {
        plots.push(("golf_ball.svg", golf_ball_plot(golf)));
    }
    if let Some(specular) = &r.specular {
        plots.push(("specular_energy.svg", specular_plot(specular, 0)));
        plots.push(("specular_width.svg", specular_plot(specular, 1)));
    }
    if let Some(emboss) = &r.emboss {
        plots.push(("emboss_angle.svg", emboss_plot(emboss)));
    }
    if let Some(peercy) = &r.peercy {
        plots.push(("peercy.svg", peercy_plot(peercy)));
    }
    if let Some(p) = &r.parallax {
        plots.push(("parallax_hits_bricks.svg", parallax_plot(p, "bricks", true)));
        plots.push(("parallax_hits_dimples.svg", parallax_plot(p, "dimples", true)));
        plots.push(("parallax_flip_bricks.svg", parallax_plot(p, "bricks", false)));
        plots.push(("parallax_flip_dimples.svg", parallax_plot(p, "dimples", false)));
    }
    if let Some(s) = &r.shadows {
        plots.push(("shadows_bricks.svg", shadow_plot(s, "bricks")));
        plots.push(("shadows_dimples.svg", shadow_plot(s, "dimples")));
    }
    if let Some(d) = &r.detail {
        plots.push(("detail_added.svg", detail_plot(d, true)));
        plots.push(("detail_draped.svg", detail_plot(d, false)));
    }
    plots
}

/// Detail normals on the bricks: each blend's mean angle to added heights (`added`) or to
/// draped detail by the detail's strength, log scale.
fn detail_plot(d: &super::detail::DetailStudy, added: bool) -> String {
    use bumpmap::Named;
    use bumpmap_math::detail::BlendMethod;
    let caption = if added { "bricks + noise: against added heights" } else { "bricks + noise: against draped detail" };
    let labels = Labels {
        caption,
        x: "detail strength",
        y: "mean angle (degrees)",
        legend: Some(SeriesLabelPosition::UpperLeft),
    };
    let lines: Vec<(&str, Vec<(f64, f64)>)> = BlendMethod::ALL
        .iter()
        .map(|m| {
            let points = d
                .rows
                .iter()
                .filter(|r| r.base == "bricks" && r.method == *m)
                .map(|r| (r.strength as f64, if added { r.added.0 } else { r.draped.0 }.max(1e-4)))
                .collect();
            (m.name(), points)
        })
        .collect();
    // From the 16-bit rounding's thousandths of a degree to linear blending's tens, and room
    // above for the legend.
    svg_plot(labels, 0.4f64..2.1, (1e-3f64..1e4).log_scale(), |chart| {
        let colors = [BLACK, RED, BLUE, GREEN, MAGENTA, RGBColor(230, 140, 0)];
        for ((name, points), color) in lines.iter().zip(colors) {
            labelled_line(chart, name, color, points.clone());
        }
    })
}

/// Heights as geometry on `field`: each technique's mean hit error (`hits`, texels, log scale)
/// or FLIP against the displaced reference by view angle.
fn parallax_plot(p: &super::parallax::ParallaxStudy, field: &str, hits: bool) -> String {
    let rows: Vec<_> = p.rows.iter().filter(|row| row.field == field).collect();
    let value = |row: &super::parallax::ParallaxRow| if hits { row.hit_mean.max(1e-6) } else { row.flip };
    let hi = rows.iter().map(|row| value(row)).fold(1e-3, f64::max);
    let caption = if hits {
        format!("{field}: mean distance of the hit from the exact one")
    } else {
        format!("{field}: FLIP against the displaced reference")
    };
    let labels = Labels {
        caption: &caption,
        x: "view angle from the normal (degrees)",
        y: if hits { "hit error (texels)" } else { "FLIP mean" },
        legend: Some(SeriesLabelPosition::UpperLeft),
    };
    let lines: Vec<(&str, Vec<(f64, f64)>)> = super::parallax::TECHNIQUES
        .iter()
        .map(|t| {
            let points =
                rows.iter().filter(|row| row.technique == *t).map(|row| (row.angle as f64, value(row))).collect();
            (t.name(), points)
        })
        .collect();
    fn draw_lines<DB: DrawingBackend, CT: CoordTranslate<From = (f64, f64)>>(
        chart: &mut ChartContext<'_, DB, CT>,
        lines: &[(&str, Vec<(f64, f64)>)],
    ) {
        let colors = [BLACK, RED, MAGENTA, BLUE, GREEN, RGBColor(230, 140, 0)];
        for ((name, points), color) in lines.iter().zip(colors) {
            labelled_line(chart, name, color, points.clone());
        }
    }
    if hits {
        // The exact walk's errors are rounding's, down to a millionth of a texel; room above the
        // lines for the legend.
        svg_plot(labels, 25f64..90.0, (1e-6f64..hi * 1e4).log_scale(), |c| draw_lines(c, &lines))
    } else {
        svg_plot(labels, 25f64..90.0, 0f64..hi * 1.6, |c| draw_lines(c, &lines))
    }
}

/// Bumps that shadow each other on `field`: each method's mask agreement with the shadow rays
/// (percent of the pixels facing the light) by the light's angle.
fn shadow_plot(s: &super::shadows::ShadowStudy, field: &str) -> String {
    use super::shadows::ShadowMethod;
    let caption = format!("{field}: shadow mask against shadow rays");
    let labels = Labels {
        caption: &caption,
        x: "light angle from the normal (degrees)",
        y: "pixels facing the light that agree (%)",
        legend: Some(SeriesLabelPosition::LowerLeft),
    };
    let lines: Vec<(&str, Vec<(f64, f64)>)> = ShadowMethod::ALL
        .iter()
        .map(|m| {
            let points = s
                .rows
                .iter()
                .filter(|row| row.field == field && row.method == *m)
                .map(|row| (row.light as f64, 100.0 * row.agreement))
                .collect();
            (m.name(), points)
        })
        .collect();
    let lo = s.rows.iter().filter(|r| r.field == field).map(|r| 100.0 * r.agreement).fold(100.0, f64::min);
    svg_plot(labels, 40f64..85.0, (lo - 0.6 * (100.0 - lo)).max(0.0)..100.5, |chart| {
        let colors = [BLACK, RGBColor(150, 150, 150), RED, BLUE, GREEN, RGBColor(230, 140, 0)];
        for ((name, points), color) in lines.iter().zip(colors) {
            labelled_line(chart, name, color, points.clone());
        }
    })
}

/// The captions of one plot, and where its legend goes (none without a position).
struct Labels<'a> {
    caption: &'a str,
    x: &'a str,
    y: &'a str,
    legend: Option<SeriesLabelPosition>,
}

/// A 560×360 SVG plot on white with its caption, axes over `x` and `y` and their descriptions;
/// `draw` adds the series, then the legend of those [`labelled_line`] drew is placed.
fn svg_plot<X, Y>(
    labels: Labels<'_>,
    x: X,
    y: Y,
    draw: impl FnOnce(&mut ChartContext<'_, SVGBackend<'_>, Cartesian2d<X::CoordDescType, Y::CoordDescType>>),
) -> String
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (560, 360)).into_drawing_area();
        root.fill(&WHITE).expect("drawing into a string");
        let mut chart = ChartBuilder::on(&root)
            .caption(labels.caption, ("sans-serif", 16))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(56)
            .build_cartesian_2d(x, y)
            .expect("valid ranges");
        chart.configure_mesh().light_line_style(TRANSPARENT).x_desc(labels.x).y_desc(labels.y).draw().expect("mesh");
        draw(&mut chart);
        if let Some(position) = labels.legend {
            legend(&mut chart, position);
        }
        root.present().expect("drawing into a string");
    }
    svg
}

/// Kilgard §3.1: embossing's and the single pass's RMSE by light angle.
fn emboss_plot(emboss: &super::studies::EmbossStudy) -> String {
    let emax = emboss.by_angle.iter().map(|row| row.1.max(row.3)).fold(0.01, f64::max) * 1.2;
    let labels = Labels {
        caption: "Embossing against the reference by light angle (Kilgard §3.1)",
        x: "light angle from the normal (degrees)",
        y: "RMSE",
        legend: Some(SeriesLabelPosition::UpperRight),
    };
    let by_angle = &emboss.by_angle;
    svg_plot(labels, -5f64..80.0, 0f64..emax, |chart| {
        for (label, emboss, color) in [("emboss", true, RED), ("single-pass", false, BLUE)] {
            let points = by_angle.iter().map(|row| (row.0 as f64, if emboss { row.1 } else { row.3 })).collect();
            labelled_line(chart, label, color, points);
        }
    })
}

/// Peercy Figures 5–7: each implementation's RMSE against the same-slopes reference by bump scale.
fn peercy_plot(peercy: &super::studies::PeercyStudy) -> String {
    let rows = &peercy.rows;
    let values = rows.iter().flat_map(|row| row.rmse_same_slopes);
    let (lo, hi) = values.fold((f64::MAX, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let (lo, hi) = (lo.min(hi) * 0.85, hi.max(1e-3) * 1.2);
    let smax = rows.last().map_or(4.0, |row| row.bump_scale as f64) * 1.15;
    let labels = Labels {
        caption: "Peercy Figures 5–7: error by bump scale (same f_u, f_v)",
        x: "bump scale (height of a unit step in texels)",
        y: "RMSE against the reference",
        legend: Some(SeriesLabelPosition::UpperLeft),
    };
    svg_plot(labels, 0.5f64..smax, lo..hi, |chart| {
        let names = ["independent (Fig. 7)", "dependent (Fig. 6)", "per-pixel Blinn (Fig. 5)"];
        for (i, (label, color)) in names.into_iter().zip([RED, BLUE, BLACK]).enumerate() {
            let points = rows.iter().map(|row| (row.bump_scale as f64, row.rmse_same_slopes[i])).collect();
            labelled_line(chart, label, color, points);
        }
    })
}

/// A line through `points` with a dot at each, named `label` in the legend.
fn labelled_line<DB: DrawingBackend, CT: CoordTranslate<From = (f64, f64)>>(
    chart: &mut ChartContext<'_, DB, CT>,
    label: &str,
    color: RGBColor,
    points: Vec<(f64, f64)>,
) {
    chart.draw_series(points.iter().map(|p| Circle::new(*p, 3, color.filled()))).expect("drawing into a string");
    chart
        .draw_series(LineSeries::new(points, color.stroke_width(2)))
        .expect("drawing into a string")
        .label(label)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
}

/// The legend of the lines [`labelled_line`] drew, at `position`.
fn legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
) {
    chart
        .configure_series_labels()
        .position(position)
        .border_style(BLACK)
        .background_style(WHITE)
        .draw()
        .expect("drawing into a string");
}

/// The reference's RMSE between K and 4K samples per pixel, log–log.
fn convergence_plot(r: &Results) -> String {
    let kmax = r.convergence.last().map_or(4.0, |(k, _)| *k as f64 * 2.0);
    let emax = r.convergence.iter().map(|(_, e)| *e).fold(1e-4, f64::max) * 2.0;
    let emin = r.convergence.iter().map(|(_, e)| *e).fold(emax, f64::min).max(1e-6) / 2.0;
    let labels = Labels {
        caption: "Reference: RMSE between K and 4K samples per pixel",
        x: "K (samples per pixel)",
        y: "RMSE",
        legend: None,
    };
    svg_plot(labels, (0.5f64..kmax).log_scale(), (emin..emax).log_scale(), |chart| {
        let points: Vec<(f64, f64)> = r.convergence.iter().map(|(k, e)| (*k as f64, *e)).collect();
        chart.draw_series(LineSeries::new(points.clone(), BLUE.stroke_width(2))).expect("series");
        chart.draw_series(points.iter().map(|p| Circle::new(*p, 4, BLUE.filled()))).expect("points");
    })
}

/// Kilgard §2.5.3: the golf ball's specular energy (`which` 0) or highlight width (1) by
/// distance, the reference and each filter.
fn specular_plot(specular: &[super::studies::SpecularRow], which: usize) -> String {
    let pick = |v: (f64, f64)| if which == 0 { v.0 } else { v.1 };
    let values = specular.iter().flat_map(|row| std::iter::once(pick(row.reference)).chain(row.filters.map(pick)));
    // The energies start at 0: room above them for the legend, which would cross the lines
    // in the lower left. The widths leave the lower left free.
    let hi = values.fold(0.0f64, f64::max) * if which == 0 { 1.7 } else { 1.15 } + 1e-3;
    let dmax = specular.last().map_or(16.0, |row| row.distance as f64 * 1.3);
    let distances: Vec<f64> = specular.iter().map(|row| row.distance as f64).collect();
    let labels = Labels {
        caption: if which == 0 {
            "Golf ball's highlight by distance: specular energy"
        } else {
            "Golf ball's highlight by distance: width (× ball radius)"
        },
        x: "distance (× nearest)",
        y: if which == 0 { "specular energy" } else { "highlight width" },
        legend: Some(if which == 0 { SeriesLabelPosition::UpperRight } else { SeriesLabelPosition::LowerLeft }),
    };
    svg_plot(labels, (0.8f64..dmax).log_scale().with_key_points(distances), 0.0..hi, |chart| {
        let line = |row: &super::studies::SpecularRow, k: Option<usize>| {
            (row.distance as f64, pick(k.map_or(row.reference, |k| row.filters[k])))
        };
        let reference = specular.iter().map(|row| line(row, None)).collect();
        labelled_line(chart, "reference", BLACK, reference);
        let colors = [RED, BLUE, GREEN, MAGENTA, CYAN, RGBColor(230, 140, 0)];
        for (k, name) in super::studies::SPECULAR_FILTERS.iter().enumerate() {
            labelled_line(chart, name, colors[k], specular.iter().map(|row| line(row, Some(k))).collect());
        }
    })
}

/// Kilgard §2.4.2: the golf ball's mean brightness by distance.
fn golf_ball_plot(golf: &[(f32, f64, f64, f64)]) -> String {
    let values = golf.iter().flat_map(|(_, a, b, c)| [*a, *b, *c]);
    let (lo, hi) = values.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let pad = ((hi - lo) * 0.15).max(0.01);
    let dmax = golf.last().map_or(8.0, |row| row.0 as f64 * 1.3);
    let labels = Labels {
        caption: "Golf ball at a distance: mean brightness (Kilgard §2.4.2)",
        x: "distance (× nearest)",
        y: "mean brightness",
        legend: Some(SeriesLabelPosition::UpperRight),
    };
    let distances: Vec<f64> = golf.iter().map(|row| row.0 as f64).collect();
    svg_plot(labels, (0.8f64..dmax).log_scale().with_key_points(distances), (lo - pad)..(hi + pad), |chart| {
        let series = [("reference", 1usize, BLACK), ("length factor in alpha", 2, BLUE), ("renormalized mips", 3, RED)];
        for (label, column, color) in series {
            let points = golf.iter().map(|row| (row.0 as f64, [row.1, row.2, row.3][column - 1])).collect();
            labelled_line(chart, label, color, points);
        }
    })
}
