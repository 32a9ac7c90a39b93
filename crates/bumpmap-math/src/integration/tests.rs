use super::*;

fn rms(a: &[f32], b: &[f32]) -> f32 {
    let ma = a.iter().sum::<f32>() / a.len() as f32;
    let mb = b.iter().sum::<f32>() / b.len() as f32;
    (a.iter().zip(b).map(|(x, y)| ((x - ma) - (y - mb)).powi(2)).sum::<f32>() / a.len() as f32).sqrt()
}

fn bumps(w: usize, h: usize) -> Vec<f32> {
    (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as f32 / w as f32, (i / w) as f32 / h as f32);
            let t = std::f32::consts::TAU;
            3.0 * (t * x).sin() * (2.0 * t * y).cos() + 1.5 * (t * (3.0 * x + y)).cos() + (t * 5.0 * y).sin()
        })
        .collect()
}

#[test]
fn the_kernel_method_inverts_the_forward_difference_exactly() {
    // Periodic, non-square, with a component at every frequency (the forward difference
    // sees them all): exact up to f32 round-off through two transforms.
    let (w, h) = (40, 24);
    let heights: Vec<f32> = (0..w * h).map(|i| ((i * 7919 + 13) % 101) as f32 / 10.0).collect();
    let kernel = Kernel::Forward;
    let got = integrate(&Slopes::of_heights(w, h, &heights, kernel), IntegrationMethod::kernel(kernel)).unwrap();
    let e = rms(&heights, &got);
    assert!(e < 2e-3, "rms {e} of heights spanning 10");
}

#[test]
fn smoothing_kernels_are_inverted_away_from_the_frequencies_they_cannot_see() {
    // Smooth heights (no content at Nyquist): every kernel's inverse gives them back.
    let (w, h) = (48, 32);
    let heights = bumps(w, h);
    for kernel in Kernel::ALL {
        let got = integrate(&Slopes::of_heights(w, h, &heights, kernel), IntegrationMethod::kernel(kernel)).unwrap();
        let e = rms(&heights, &got);
        assert!(e < 1e-3, "{kernel:?}: rms {e} of heights spanning about 11");
    }
}

#[test]
fn frankot_chellappa_recovers_band_limited_heights_from_their_exact_slopes() {
    let (w, h) = (64, 48);
    let t = std::f32::consts::TAU;
    let heights = bumps(w, h);
    // The analytic slopes of `bumps`, per texel.
    let (mut du, mut dv) = (Vec::new(), Vec::new());
    for i in 0..w * h {
        let (x, y) = ((i % w) as f32 / w as f32, (i / w) as f32 / h as f32);
        let (sx, sy) = (t / w as f32, t / h as f32);
        du.push(sx * (3.0 * (t * x).cos() * (2.0 * t * y).cos() - 4.5 * (t * (3.0 * x + y)).sin()));
        dv.push(
            sy * (-6.0 * (t * x).sin() * (2.0 * t * y).sin() - 1.5 * (t * (3.0 * x + y)).sin()
                + 5.0 * (t * 5.0 * y).cos()),
        );
    }
    let got = integrate(&Slopes { width: w, height: h, du, dv }, IntegrationMethod::FRANKOT_CHELLAPPA).unwrap();
    assert!(rms(&heights, &got) < 1e-3, "rms {}", rms(&heights, &got));
}

#[test]
fn the_dct_method_recovers_a_surface_that_does_not_tile() {
    // A tilted paraboloid: not periodic, so fft smears its edges; dct does not.
    let (w, h) = (48, 40);
    let f = |x: f32, y: f32| 0.02 * (x - 10.0).powi(2) + 0.3 * y - 0.01 * x * y;
    let heights: Vec<f32> = (0..w * h).map(|i| f((i % w) as f32, (i / w) as f32)).collect();
    let du: Vec<f32> = (0..w * h).map(|i| 0.04 * ((i % w) as f32 - 10.0) - 0.01 * (i / w) as f32).collect();
    let dv: Vec<f32> = (0..w * h).map(|i| 0.3 - 0.01 * (i % w) as f32).collect();
    let s = Slopes { width: w, height: h, du, dv };
    let range = heights.iter().cloned().fold(f32::MIN, f32::max) - heights.iter().cloned().fold(f32::MAX, f32::min);
    let dct = rms(
        &heights,
        &integrate(&s, IntegrationMethod { boundary: Boundary::Free, derivative: Derivative::Spectral }).unwrap(),
    ) / range;
    let fft = rms(&heights, &integrate(&s, IntegrationMethod::FRANKOT_CHELLAPPA).unwrap()) / range;
    assert!(dct < 0.01, "dct: rms {dct} of the range");
    assert!(fft > 5.0 * dct, "fft ({fft}) should be far worse than dct ({dct}) on a surface that does not tile");
}

#[test]
fn slopes_follow_the_y_convention_and_the_scale() {
    let n = Vec4::new(-0.2, 0.1, 0.9, 1.0);
    let img = Image::new(2, 2, vec![n; 4]);
    let down = Slopes::from_normals(&img, YConvention::YDown, 2.0).unwrap();
    let up = Slopes::from_normals(&img, YConvention::YUp, 2.0).unwrap();
    assert!((down.du[0] - 0.2 / 1.8).abs() < 1e-6 && (down.dv[0] + 0.1 / 1.8).abs() < 1e-6);
    assert_eq!(up.dv[0], -down.dv[0]);
    assert!(matches!(Slopes::from_normals(&img, YConvention::YUp, 0.0), Err(IntegrationError::BadScale(_))));
    let one = Image::new(1, 3, vec![n; 3]);
    assert!(matches!(Slopes::from_normals(&one, YConvention::YUp, 1.0), Err(IntegrationError::TooSmall { .. })));
    let nan = Image::new(2, 2, vec![n, n, Vec4::new(f32::NAN, 0.0, 1.0, 1.0), n]);
    assert_eq!(
        Slopes::from_normals(&nan, YConvention::YUp, 1.0).unwrap_err(),
        IntegrationError::NotANumber { x: 0, y: 1 }
    );
}
