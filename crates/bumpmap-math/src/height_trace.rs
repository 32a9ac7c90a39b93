//! Rays against a height field taken as geometry: the surface `h = clamp(F(x, y), 0, 1)` over
//! the plane, F the C¹ interpolant of the heights (`crate::interpolant`), inside the slab
//! 0 ≤ h ≤ 1. A ray is given in texel space: x and y in texels (`x = s · width`), h in units
//! of the heights (1 the slab's top, where a rasterized polygon lies, 0 its floor).
//!
//! [`trace`] finds the first point where a ray meets the surface by walking the min–max levels
//! (`crate::height_mips`; Tevs, Ihrke & Seidel 2008): at level k it skips a node whole when
//! the ray stays above the node's highest point over the node, steps up a level after a skip
//! and down one otherwise; in a cell (level 0) it samples the surface along the ray at eight
//! points and refines the first crossing by bisection to a few ulps. The reference renderer's
//! flat objects and the `height-exact` technique call this one function, so they agree
//! wherever their rays do.
//!
//! What "exact" leaves out: two crossings within an eighth of a cell's span of the ray (a
//! sliver under 0.18 texel grazed tangentially) can be missed. What this module does not do:
//! curved surfaces (the reference micro-tessellates them), or rays that enter the slab from
//! below.

use glam::Vec3;

use crate::height_mips::MinMaxLevel;
use crate::interpolant::{HeightGrid, cell_texels, eval_cell_value};
use crate::kernel::Wrap;

/// Samples of the surface per cell crossing before refining the first one below the surface.
pub const SAMPLES_PER_CELL: usize = 8;
/// Bisection steps refining a crossing (an eighth of a cell to 2⁻²⁷ of a cell).
pub const BISECTIONS: usize = 24;

/// A ray in texel space: a point and a direction, `p(τ) = origin + τ · dir`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexelRay {
    /// Where it starts: x, y in texels, h in heights.
    pub origin: Vec3,
    /// Its direction in the same units (not normalized).
    pub dir: Vec3,
}

impl TexelRay {
    /// The point at `tau`.
    #[inline]
    pub fn at(&self, tau: f32) -> Vec3 {
        self.origin + tau * self.dir
    }

    /// Where the ray leaves the slab 0 ≤ h ≤ 1 (through the floor going down, the top going
    /// up); infinite for a level ray.
    pub fn slab_exit(&self) -> f32 {
        if self.dir.z < 0.0 {
            self.origin.z.max(0.0) / -self.dir.z
        } else if self.dir.z > 0.0 {
            (1.0 - self.origin.z).max(0.0) / self.dir.z
        } else {
            f32::INFINITY
        }
    }
}

/// The surface's height at texel point (x, y): the interpolant clamped to the slab.
#[inline]
pub fn surface_height(grid: &impl HeightGrid, x: f32, y: f32) -> f32 {
    crate::interpolant::sample_texels(grid, Wrap::Repeat, x, y).value.clamp(0.0, 1.0)
}

/// The first `τ` in `[0, min(tau_max, the slab exit)]` where `ray` meets the surface of
/// `grid` (at or below it), walking `minmax` (its levels, cells first). A ray going down always
/// meets it by the floor (the surface is never below 0); one going up may leave through the top
/// unblocked (`None`). A ray that starts inside the surface meets it at 0.
pub fn trace(grid: &impl HeightGrid, minmax: &[MinMaxLevel], ray: &TexelRay, tau_max: f32) -> Option<f32> {
    let (w, h) = (grid.width(), grid.height());
    let end = ray.slab_exit().min(tau_max);
    if !end.is_finite() || end < 0.0 || !ray.origin.is_finite() || !ray.dir.is_finite() {
        return None;
    }
    if ray.dir.z > 0.0 && ray.origin.z >= 1.0 {
        // Leaving through the top where it starts: a surface at the top only touches it.
        return None;
    }
    let top = minmax.len() - 1;
    // Cell coordinates: cell i spans texel coordinates [i + ½, i + 1½).
    let o = ray.origin - Vec3::new(0.5, 0.5, 0.0);
    let d = ray.dir;
    // A step past a node's far edge, so the next lookup lands in the next node.
    let speed = d.x.abs().max(d.y.abs());
    let nudge = if speed > 0.0 { 1e-4 / speed } else { 0.0 };
    // A budget of steps: a few per level for every cell the ray crosses, the crossing capped at
    // four tiles' worth (only a ray within a hair of level crosses more; past the budget it is
    // stopped where a ray going down must stop, the floor).
    let crossed = (speed * end + 2.0).min(4.0 * (w + h) as f32 + 4096.0);
    let max_steps = (64.0 + 4.0 * (top as f32 + 1.0) * crossed) as usize;
    let height = |tau: f32| o.z + tau * d.z;
    let (mut k, mut tau) = (top, 0.0f32);
    for _ in 0..max_steps {
        if tau > end {
            break;
        }
        let ahead = o + (tau + nudge).min(end) * d;
        let (ux, uy) = (ahead.x.floor(), ahead.y.floor());
        let (cx, cy) = ((ux as i64).rem_euclid(w as i64) as usize, (uy as i64).rem_euclid(h as i64) as usize);
        let level = &minmax[k];
        let (nx, ny) =
            (MinMaxLevel::node_of(cx, k as u32, level.width), MinMaxLevel::node_of(cy, k as u32, level.height));
        // The node's extent in unwrapped cell coordinates.
        let span = |node: usize, nodes: usize, cells: usize, base: f32| {
            let start = (node << k) as f32;
            let stop = if node + 1 == nodes { cells as f32 } else { ((node + 1) << k) as f32 };
            (base + start, base + stop)
        };
        let (x0, x1) = span(nx, level.width, w, ux - cx as f32);
        let (y0, y1) = span(ny, level.height, h, uy - cy as f32);
        let exit_along = |o: f32, d: f32, lo: f32, hi: f32| {
            if d > 0.0 {
                (hi - o) / d
            } else if d < 0.0 {
                (lo - o) / d
            } else {
                f32::INFINITY
            }
        };
        let exit = exit_along(o.x, d.x, x0, x1).min(exit_along(o.y, d.y, y0, y1)).min(end).max(tau);
        let [lo, hi] = level.at(nx, ny);
        let (ha, hb) = (height(tau), height(exit));
        if ha.min(hb) > hi {
            // Above everything this node holds: past it, and look wider.
            tau = exit + nudge;
            k = (k + 1).min(top);
            continue;
        }
        if ha.max(hb) < lo {
            // Below everything it holds over the whole span: inside from the start.
            return Some(tau);
        }
        if k > 0 {
            k -= 1;
            continue;
        }
        let p = cell_texels(grid, Wrap::Repeat, cx as i64, cy as i64);
        if let Some(hit) = cell_crossing(&p, o, d, (ux, uy), tau, exit) {
            return Some(hit);
        }
        tau = exit + nudge;
        k = (k + 1).min(top);
    }
    // Past the slab (or, for a degenerate ray, past the step budget): a ray going down is
    // stopped by the floor.
    (d.z < 0.0 && end == ray.slab_exit()).then_some(end)
}

/// The first crossing of the ray `o + τd` (cell coordinates) below the cell's surface (texels
/// `p`, the cell's corner at `corner`) within `[ta, tb]`.
fn cell_crossing(p: &[[f32; 4]; 4], o: Vec3, d: Vec3, corner: (f32, f32), ta: f32, tb: f32) -> Option<f32> {
    let below = |tau: f32| {
        let q = o + tau * d;
        let (fx, fy) = ((q.x - corner.0).clamp(0.0, 1.0), (q.y - corner.1).clamp(0.0, 1.0));
        eval_cell_value(p, fx, fy).clamp(0.0, 1.0) >= q.z
    };
    if below(ta) {
        return Some(ta);
    }
    let step = (tb - ta) / SAMPLES_PER_CELL as f32;
    let mut prev = ta;
    for i in 1..=SAMPLES_PER_CELL {
        let t = if i == SAMPLES_PER_CELL { tb } else { ta + step * i as f32 };
        if below(t) {
            // Refine: `prev` above, `t` at or below.
            let (mut a, mut b) = (prev, t);
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (a + b);
                if mid <= a || mid >= b {
                    break;
                }
                if below(mid) { b = mid } else { a = mid }
            }
            return Some(b);
        }
        prev = t;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::height_mips::{HeightLevel, HeightMips};

    fn mips(field: &crate::HeightField) -> HeightMips {
        HeightMips::from_field(field).unwrap()
    }

    /// The first crossing found by marching in steps of 1/64 texel and bisecting: slow, simple.
    fn brute_force(level: &HeightLevel, ray: &TexelRay) -> f32 {
        let end = ray.slab_exit();
        let step = 1.0 / 64.0 / ray.dir.truncate().length().max(1e-3);
        let below = |t: f32| {
            let p = ray.at(t);
            surface_height(level, p.x, p.y) >= p.z
        };
        let mut t = 0.0;
        if below(0.0) {
            return 0.0;
        }
        loop {
            let next = (t + step).min(end);
            if below(next) {
                let (mut a, mut b) = (t, next);
                for _ in 0..40 {
                    let m = 0.5 * (a + b);
                    if below(m) { b = m } else { a = m }
                }
                return b;
            }
            if next >= end {
                return end;
            }
            t = next;
        }
    }

    #[test]
    fn a_flat_field_is_met_at_its_height() {
        let field = crate::HeightField::from_fn(8, 8, |_, _| 0.25);
        let m = mips(&field);
        let ray = TexelRay { origin: Vec3::new(3.0, 2.0, 1.0), dir: Vec3::new(2.0, 1.0, -0.5) };
        let tau = trace(&m.levels()[0], m.minmax().unwrap(), &ray, f32::INFINITY).unwrap();
        assert!((ray.at(tau).z - 0.25).abs() < 1e-4, "{}", ray.at(tau));
        // Straight down, anywhere.
        let ray = TexelRay { origin: Vec3::new(7.9, 0.1, 1.0), dir: Vec3::new(0.0, 0.0, -1.0) };
        let tau = trace(&m.levels()[0], m.minmax().unwrap(), &ray, f32::INFINITY).unwrap();
        assert!((tau - 0.75).abs() < 1e-4, "{tau}");
    }

    #[test]
    fn the_walk_finds_the_brute_force_crossing_on_bricks_at_grazing_angles() {
        let field = crate::HeightPreset::Bricks.render(64, 64);
        let m = mips(&field);
        let level = &m.levels()[0];
        let mut worst = 0f32;
        for i in 0..300 {
            let a = i as f32 * 0.618;
            // From 30° to 88° off the normal, every azimuth, starting anywhere on the tile.
            let theta = (30.0 + (i % 59) as f32).to_radians();
            let dir = Vec3::new(a.cos() * theta.sin(), a.sin() * theta.sin(), -theta.cos()) * 8.0;
            let ray = TexelRay { origin: Vec3::new((i * 37 % 64) as f32 + 0.3, (i * 11 % 64) as f32 + 0.7, 1.0), dir };
            let got = trace(level, m.minmax().unwrap(), &ray, f32::INFINITY).unwrap();
            let want = brute_force(level, &ray);
            let miss = (ray.at(got).truncate() - ray.at(want).truncate()).length();
            worst = worst.max(miss);
            assert!(
                miss < 1e-3,
                "ray {i} at {:.0}°: walk {} vs brute force {}",
                theta.to_degrees(),
                ray.at(got),
                ray.at(want)
            );
        }
        println!("worst distance between the walk's and the brute force's hits: {worst} texel");
    }

    #[test]
    fn a_ray_going_up_is_blocked_by_a_wall_and_not_by_open_sky() {
        // A ridge of height 1 along x = 8..10 over a floor at 0.
        let field = crate::HeightField::from_fn(16, 4, |x, _| if (8..10).contains(&x) { 1.0 } else { 0.0 });
        let m = mips(&field);
        let (level, minmax) = (&m.levels()[0], m.minmax().unwrap());
        let toward = TexelRay { origin: Vec3::new(4.0, 2.0, 0.01), dir: Vec3::new(1.0, 0.0, 0.05) };
        assert!(trace(level, minmax, &toward, f32::INFINITY).is_some(), "the ridge is in the way");
        let steep = TexelRay { origin: Vec3::new(4.0, 2.0, 0.01), dir: Vec3::new(1.0, 0.0, 1.0) };
        assert_eq!(trace(level, minmax, &steep, f32::INFINITY), None, "over the ridge: it leaves through the top");
        let away = TexelRay { origin: Vec3::new(4.0, 2.0, 0.01), dir: Vec3::new(-1.0, 0.0, 0.05) };
        // Away from the ridge the ray wraps round the tile to the ridge's other side (REPEAT)…
        assert!(trace(level, minmax, &away, f32::INFINITY).is_some());
        // …unless it stops first.
        assert_eq!(trace(level, minmax, &away, 2.0), None);
        // From the ridge's top, going up: leaving, not blocked by the top it starts on.
        let from_top = TexelRay { origin: Vec3::new(9.0, 2.0, 1.0), dir: Vec3::new(1.0, 0.0, 0.05) };
        assert_eq!(trace(level, minmax, &from_top, f32::INFINITY), None);
    }

    #[test]
    fn hostile_rays_end() {
        let field = crate::HeightPreset::Noise(2).render(16, 16);
        let m = mips(&field);
        let (level, minmax) = (&m.levels()[0], m.minmax().unwrap());
        for ray in [
            TexelRay { origin: Vec3::new(1.0, 1.0, 1.0), dir: Vec3::new(1e9, -1e9, -1e-9) },
            TexelRay { origin: Vec3::new(f32::NAN, 1.0, 1.0), dir: Vec3::new(1.0, 0.0, -1.0) },
            TexelRay { origin: Vec3::new(1.0, 1.0, 1.0), dir: Vec3::new(0.0, 0.0, 0.0) },
            TexelRay { origin: Vec3::new(1e30, -1e30, 0.5), dir: Vec3::new(1.0, 1.0, -1.0) },
            TexelRay { origin: Vec3::new(1.0, 1.0, 0.5), dir: Vec3::new(1.0, 0.0, 0.0) },
        ] {
            let _ = trace(level, minmax, &ray, f32::INFINITY);
        }
    }
}
