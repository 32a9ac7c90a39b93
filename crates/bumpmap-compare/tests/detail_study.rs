//! The detail-normal study's claims: partial derivatives are exact for heights that add and RNM
//! for a detail draped over the base, to the 16-bit rounding of the inputs (≤ 0.1° mean); the
//! other blends are not, and linear blending is off by degrees. The table is printed.

use bumpmap::Named;
use bumpmap_compare::detail::{BASES, STRENGTHS, detail_study, exact_normals, mean_p95};
use bumpmap_math::detail::{BlendMethod, added};
use bumpmap_math::{HeightField, HeightPreset};

#[test]
fn partial_derivatives_are_added_heights_and_rnm_is_draped_detail() {
    let study = detail_study();
    assert_eq!(study.rows.len(), BASES.len() * STRENGTHS.len() * BlendMethod::ALL.len());
    eprintln!("| maps | strength | method | added heights: mean | p95 | draped detail: mean | p95 |");
    eprintln!("| --- | --- | --- | --- | --- | --- | --- |");
    for r in &study.rows {
        eprintln!(
            "| {} + noise | {} | {} | {:.3}° | {:.3}° | {:.3}° | {:.3}° |",
            r.base,
            r.strength,
            r.method.name(),
            r.added.0,
            r.added.1,
            r.draped.0,
            r.draped.1
        );
    }
    for base in BASES {
        for strength in STRENGTHS {
            let row = |m| study.row(base, strength, m).expect("a row");
            let pd = row(BlendMethod::PartialDerivative);
            let rnm = row(BlendMethod::Rnm);
            assert!(pd.added.0 <= 0.1, "{base} {strength}: partial derivatives {}°", pd.added.0);
            assert!(rnm.draped.0 <= 0.1, "{base} {strength}: RNM {}°", rnm.draped.0);
            // Each exact for its own composition only: the two differ by more than rounding.
            assert!(pd.draped.0 > 10.0 * pd.added.0 && rnm.added.0 > 10.0 * rnm.draped.0);
            assert!(row(BlendMethod::Linear).added.0 > 1.0, "linear flattens");
        }
    }
}

#[test]
fn the_exact_normals_are_the_heights_and_slopes_add() {
    // The float normals the study compares with are what normalmap rounds, and the normal of
    // summed heights is the slopes summed.
    let n = 64;
    let (a, b) = (HeightPreset::Bricks.render(n, n), HeightPreset::Noise(3).render(n, n));
    let sum: Vec<f32> = a.to_f32().iter().zip(b.to_f32()).map(|(x, y)| x + 0.5 * y).collect();
    let summed = exact_normals(&HeightField::new(n, n, sum).unwrap(), 6.0);
    let (na, nb) = (exact_normals(&a, 6.0), exact_normals(&b, 3.0));
    let from_slopes: Vec<_> = na.iter().zip(&nb).map(|(x, y)| added(*x, *y)).collect();
    // Mean, not worst: an f32 dot product a rounding error from 1 reads as a few hundredths of a degree.
    assert!(mean_p95(&summed, &from_slopes).0 < 0.01);
}
