//! Blinn's perturbed normal (Kilgard Eq. 5, Peercy Eq. 1–2) and the displacement a normal
//! map's bump scale stands for.
//!
//! Displacing the surface along its unit normal by `d(u, v)`, `P' = P + d·n̂`, and dropping the
//! terms in `d` itself (Blinn's approximation, the one every technique here makes), the normal
//! becomes `N' = N + d_u (n̂ × P_v) − d_v (n̂ × P_u)` with `N = P_u × P_v`. The reference renderer
//! evaluates it per sample; Peercy's surface-dependent map (`peercy-dependent`) per texel. What
//! this module does not do: the surface-independent approximation (that is `normalmap`).

use crate::surface::{Surface, SurfacePoint};
use glam::{Vec2, Vec3};

/// The unit perturbed normal for displacement derivatives `d_u = ∂d/∂u`, `d_v = ∂d/∂v`, oriented
/// like `p.normal` whichever way the parameterization turns.
pub fn perturbed_normal(p: &SurfacePoint, d_u: f32, d_v: f32) -> Vec3 {
    let n = p.normal;
    let cross = p.dp_du.cross(p.dp_dv);
    // P_u × P_v points along n̂ for a right-handed parameterization and against it otherwise;
    // the perturbation turns with it.
    let sigma = if cross.dot(n) >= 0.0 { 1.0 } else { -1.0 };
    let base = n * cross.length();
    let d = d_u * n.cross(p.dp_dv) - d_v * n.cross(p.dp_du);
    (base + sigma * d).normalize_or(n)
}

/// Object-space displacement per unit of height for a normal map of `size` texels with bump
/// `scale`, repeated `repeat` times over `surface`.
///
/// The map's slope is `scale · ∂F/∂x` with x in texels, which is exact where texels are squares of
/// one side. On a surface of area A covered by `|repeat.x|·width × |repeat.y|·height` texels the
/// mean texel side is `ℓ = √(A / texels)`, and a displacement `scale · ℓ · F` has the map's slope
/// wherever texels have that side. Where the surface stretches its texels (the torus's inside,
/// Peercy's patch) the true slope differs from the map's: that is the surface-independent
/// approximation the techniques make and the reference does not.
pub fn displacement_per_unit_height(surface: &Surface, repeat: Vec2, size: (usize, usize), scale: f32) -> f32 {
    const N: usize = 64;
    let mut area = 0.0f64;
    for j in 0..N {
        for i in 0..N {
            let p = surface.eval((i as f32 + 0.5) / N as f32, (j as f32 + 0.5) / N as f32);
            area += p.dp_du.cross(p.dp_dv).length() as f64;
        }
    }
    area /= (N * N) as f64;
    let texels = (repeat.x.abs() as f64 * size.0 as f64) * (repeat.y.abs() as f64 * size.1 as f64);
    scale * (area / texels).sqrt() as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn on_a_square_wall_the_perturbed_normal_is_the_normal_maps() {
        // Wall 4×4, repeat 2, 256² texels: texel side 1/128, so ℓ = 1/128.
        let wall = Surface::Wall { width: 4.0, height: 4.0 };
        let k = displacement_per_unit_height(&wall, Vec2::splat(2.0), (256, 256), 4.0);
        assert!((k - 4.0 / 128.0).abs() < 1e-6, "{k}");
        // Heights rising 0.01 per texel along x and 0.02 along y: the map says
        // n ∝ (−4·0.01, −4·0.02, 1) in (T, B, N).
        let p = wall.eval(0.3, 0.6);
        let (fx, fy) = (0.01, 0.02);
        // d = k·F, F(s) with s = 2u and x = 256 s: ∂d/∂u = k · 2 · 256 · fx.
        let n = perturbed_normal(&p, k * 512.0 * fx, k * 512.0 * fy);
        let want = Vec3::new(-4.0 * fx, -4.0 * fy, 1.0).normalize();
        let (t, b, nn) = p.frame();
        let got = Vec3::new(n.dot(t), n.dot(b), n.dot(nn));
        assert!((got - want).length() < 1e-5, "{got} vs {want}");
    }

    #[test]
    fn a_flat_height_leaves_every_surface_normal_alone() {
        for surface in [
            Surface::Floor { width: 3.0, depth: 2.0 },
            Surface::default_torus(),
            Surface::Sphere { radius: 1.5 },
            Surface::Patch(crate::surface::BicubicPatch::stretched()),
        ] {
            for (u, v) in [(0.1, 0.2), (0.5, 0.5), (0.9, 0.7)] {
                let p = surface.eval(u, v);
                assert!((perturbed_normal(&p, 0.0, 0.0) - p.normal).length() < 1e-5, "{surface:?}");
            }
        }
    }

    #[test]
    fn a_slope_tilts_the_normal_downhill_on_every_surface() {
        // Height rising along +u: the normal leans toward −∂P/∂u, whichever way the surface's
        // parameterization turns.
        for surface in
            [Surface::Floor { width: 3.0, depth: 2.0 }, Surface::default_torus(), Surface::Sphere { radius: 1.5 }]
        {
            let p = surface.eval(0.3, 0.4);
            let n = perturbed_normal(&p, 0.5, 0.0);
            assert!(n.dot(p.dp_du) < 0.0, "{surface:?}: {n}");
            let n = perturbed_normal(&p, 0.0, 0.5);
            assert!(n.dot(p.dp_dv) < 0.0, "{surface:?}: {n}");
        }
    }
}
