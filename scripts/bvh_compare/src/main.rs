//! The rays of the bake benchmark (`scripts/bench_bake_blender.py`: a million-triangle wavy
//! sphere baked onto a 32×16 one at 2048², 4 samples a texel) cast through each BVH crate the
//! baker could use, built and timed side by side in one run, with the hits counted so a crate
//! that answers differently shows.
//!
//!     cargo run --release --manifest-path scripts/bvh_compare/Cargo.toml -- [SIZE] [SPP]
//!
//! The rays: for each sample of each texel, the point of the unit sphere at the texel's
//! (u, v) (longitude u, colatitude v, as the benchmark's OBJ files map it), from 0.1 outside the
//! sphere inward, as far as 0.1 inside: what `bumpmap bake --extrude 0.1 --max-distance 0.1`
//! casts from the low-poly sphere, whose averaged normals are the sphere's own to within its
//! facets (obvhs 0.3 built here on glam 0.33, which parry3d needs; the baker builds it on 0.30).
//! Each crate gives the nearest hit; the times are the build (from the triangle list)
//! and the rays (rayon over rows, as the baker goes).

use std::time::Instant;

use rayon::prelude::*;

type P = [f32; 3];

/// The benchmark's HIGH: a unit sphere of `nu`×`nv` quads, radius 1 + 0.02·sin 8θ·sin 6φ,
/// less the triangles the poles make degenerate.
fn sphere(nu: usize, nv: usize) -> (Vec<P>, Vec<[u32; 3]>) {
    let mut positions = Vec::new();
    for j in 0..=nv {
        for i in 0..=nu {
            let (theta, phi) =
                (i as f64 / nu as f64 * std::f64::consts::TAU, j as f64 / nv as f64 * std::f64::consts::PI);
            let r = 1.0 + 0.02 * (8.0 * theta).sin() * (6.0 * phi).sin();
            positions.push([
                (r * phi.sin() * theta.cos()) as f32,
                (r * phi.sin() * theta.sin()) as f32,
                (r * phi.cos()) as f32,
            ]);
        }
    }
    let at = |i: usize, j: usize| (j * (nu + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    let area = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|k| positions[k as usize]);
        let (e, f) = (sub(b, a), sub(c, a));
        let n = [e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]];
        (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt()
    };
    triangles.retain(|t| area(t) > 1e-12);
    (positions, triangles)
}

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The rays of row `y`: origin, unit direction.
fn row_rays(y: usize, size: usize, spp: usize) -> impl Iterator<Item = (P, P)> {
    let n = (spp as f64).sqrt().ceil() as usize;
    (0..size).flat_map(move |x| {
        (0..spp).map(move |k| {
            let (ox, oy) = (((k % n) as f64 + 0.5) / n as f64, ((k / n) as f64 + 0.5) / n as f64);
            let (u, v) = ((x as f64 + ox) / size as f64, (y as f64 + oy) / size as f64);
            let (theta, phi) = (u * std::f64::consts::TAU, v * std::f64::consts::PI);
            let d = [phi.sin() * theta.cos(), phi.sin() * theta.sin(), phi.cos()];
            let origin = d.map(|c| (1.1 * c) as f32);
            (origin, d.map(|c| -c as f32))
        })
    })
}

/// The nearest hit: its distance.
trait Caster: Sync {
    fn first_hit(&self, origin: P, direction: P, reach: f32) -> Option<f32>;
}

struct Obvhs3 {
    bvh: obvhs::cwbvh::CwBvh,
    triangles: Vec<obvhs::triangle::Triangle>,
}

impl Caster for Obvhs3 {
    fn first_hit(&self, origin: P, direction: P, reach: f32) -> Option<f32> {
        use obvhs::ray::{Ray, RayHit};
        let ray = Ray::new(glam::Vec3A::from(origin), glam::Vec3A::from(direction), 0.0, reach);
        let mut hit = RayHit::none();
        self.bvh.ray_traverse(ray, &mut hit, |ray, id| self.triangles[id].intersect(ray)).then_some(hit.t)
    }
}

fn obvhs3(positions: &[P], indices: &[[u32; 3]], params: obvhs::BvhBuildParams) -> Obvhs3 {
    use obvhs::triangle::Triangle;
    let v = |k: u32| glam::Vec3A::from(positions[k as usize]);
    let triangles: Vec<Triangle> = indices.iter().map(|t| Triangle { v0: v(t[0]), v1: v(t[1]), v2: v(t[2]) }).collect();
    let bvh = obvhs::cwbvh::builder::build_cwbvh_from_tris(&triangles, params, &mut Default::default());
    let triangles = bvh.primitive_indices.iter().map(|&p| triangles[p as usize]).collect();
    Obvhs3 { bvh, triangles }
}

struct Obvhs4 {
    bvh: obvhs4::cwbvh::CwBvh,
    triangles: Vec<obvhs4::triangle::Triangle>,
}

impl Caster for Obvhs4 {
    fn first_hit(&self, origin: P, direction: P, reach: f32) -> Option<f32> {
        use obvhs4::ray::{Ray, RayHit};
        let (o, d) = (glam34::Vec3A::from(origin), glam34::Vec3A::from(direction));
        let ray = Ray::new(o, d, 0.0, reach);
        let mut hit = RayHit::none();
        self.bvh.ray_traverse(ray, &mut hit, |ray, id| self.triangles[id].intersect(ray)).then_some(hit.t)
    }
}

fn obvhs4(positions: &[P], indices: &[[u32; 3]]) -> Obvhs4 {
    use obvhs4::triangle::Triangle;
    let v = |k: u32| glam34::Vec3A::from(positions[k as usize]);
    let triangles: Vec<Triangle> = indices.iter().map(|t| Triangle { v0: v(t[0]), v1: v(t[1]), v2: v(t[2]) }).collect();
    let params = obvhs4::BvhBuildParams::medium_build();
    let bvh = obvhs4::cwbvh::builder::build_cwbvh_from_tris(&triangles, params, &mut Default::default());
    let triangles = bvh.primitive_indices.iter().map(|&p| triangles[p as usize]).collect();
    Obvhs4 { bvh, triangles }
}

/// A triangle for the `bvh` crate, which keeps its node's index in it.
struct BvhTriangle {
    corners: [nalgebra::Point3<f32>; 3],
    node: usize,
}

impl bvh::aabb::Bounded<f32, 3> for BvhTriangle {
    fn aabb(&self) -> bvh::aabb::Aabb<f32, 3> {
        let [a, b, c] = self.corners;
        bvh::aabb::Aabb::with_bounds(a.inf(&b).inf(&c), a.sup(&b).sup(&c))
    }
}

impl bvh::bounding_hierarchy::BHShape<f32, 3> for BvhTriangle {
    fn set_bh_node_index(&mut self, index: usize) {
        self.node = index;
    }
    fn bh_node_index(&self) -> usize {
        self.node
    }
}

struct SvenstaroBvh {
    bvh: bvh::bvh::Bvh<f32, 3>,
    triangles: Vec<BvhTriangle>,
}

impl Caster for SvenstaroBvh {
    fn first_hit(&self, origin: P, direction: P, reach: f32) -> Option<f32> {
        let ray = bvh::ray::Ray::new(origin.into(), direction.into());
        let mut best = reach;
        let mut found = false;
        // Boxes nearest first: once a box starts beyond the best hit, none after it is nearer.
        for t in self.bvh.nearest_traverse_iterator(&ray, &self.triangles) {
            let aabb = bvh::aabb::Bounded::aabb(t);
            if ray.intersection_slice_for_aabb(&aabb).is_some_and(|(enter, _)| enter > best) {
                break;
            }
            // Both faces: the crate's own test skips triangles met from behind.
            let [a, b, c] = t.corners;
            for (b, c) in [(b, c), (c, b)] {
                let hit = ray.intersects_triangle(&a, &b, &c).distance;
                if hit >= 0.0 && hit < best {
                    best = hit;
                    found = true;
                }
            }
        }
        found.then_some(best)
    }
}

fn svenstaro(positions: &[P], indices: &[[u32; 3]]) -> SvenstaroBvh {
    let mut triangles: Vec<BvhTriangle> =
        indices.iter().map(|t| BvhTriangle { corners: t.map(|k| positions[k as usize].into()), node: 0 }).collect();
    let bvh = bvh::bvh::Bvh::build_with_executor(&mut triangles, bvh::bvh::rayon_executor);
    SvenstaroBvh { bvh, triangles }
}

struct Parry {
    mesh: parry3d::shape::TriMesh,
}

impl Caster for Parry {
    fn first_hit(&self, origin: P, direction: P, reach: f32) -> Option<f32> {
        use parry3d::math::Vector;
        use parry3d::query::{Ray, RayCast};
        let ray = Ray::new(Vector::from_array(origin), Vector::from_array(direction));
        self.mesh.cast_local_ray(&ray, reach, false)
    }
}

fn parry(positions: &[P], indices: &[[u32; 3]]) -> Parry {
    use parry3d::math::Vector;
    let vertices = positions.iter().map(|p| Vector::from_array(*p)).collect();
    Parry { mesh: parry3d::shape::TriMesh::new(vertices, indices.to_vec()).expect("a valid mesh") }
}

fn main() {
    let args: Vec<usize> =
        std::env::args().skip(1).map(|a| a.parse().expect("SIZE and SPP are whole numbers")).collect();
    let (size, spp) = (args.first().copied().unwrap_or(2048), args.get(1).copied().unwrap_or(4));
    let start = Instant::now();
    let (positions, indices) = sphere(1000, 500);
    println!(
        "HIGH: {} triangles (made in {:.2} s); {} rays ({size}², {spp} a texel); {} threads",
        indices.len(),
        start.elapsed().as_secs_f64(),
        size * size * spp,
        rayon::current_num_threads()
    );
    println!("| crate | BVH | build | rays | rays/s | hits | mean distance |");
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    type Build<'a> = Box<dyn Fn() -> Box<dyn Caster> + 'a>;
    let (p, i) = (&positions, &indices);
    let builds: Vec<(&str, &str, Build)> = vec![
        (
            "obvhs 0.3.3",
            "CWBVH, PLOC, medium_build (the baker's)",
            Box::new(|| Box::new(obvhs3(p, i, obvhs::BvhBuildParams::medium_build()))),
        ),
        (
            "obvhs 0.3.3",
            "CWBVH, PLOC, fast_build",
            Box::new(|| Box::new(obvhs3(p, i, obvhs::BvhBuildParams::fast_build()))),
        ),
        (
            "obvhs 0.3.3",
            "CWBVH, PLOC, very_fast_build",
            Box::new(|| Box::new(obvhs3(p, i, obvhs::BvhBuildParams::very_fast_build()))),
        ),
        (
            "obvhs 0.3.3",
            "CWBVH, PLOC, slow_build (pre-split)",
            Box::new(|| Box::new(obvhs3(p, i, obvhs::BvhBuildParams::slow_build()))),
        ),
        ("obvhs 0.4.0", "CWBVH, PLOC, medium_build", Box::new(|| Box::new(obvhs4(p, i)))),
        ("parry3d 0.31.1", "TriMesh's own (binary, SAH)", Box::new(|| Box::new(parry(p, i)))),
        ("bvh 0.12.0", "binary, SAH, nearest-first iterator", Box::new(|| Box::new(svenstaro(p, i)))),
    ];
    for (name, kind, build) in builds {
        let start = Instant::now();
        let caster = build();
        let built = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let (hits, sum) = (0..size)
            .into_par_iter()
            .map(|y| {
                row_rays(y, size, spp).fold((0u64, 0.0f64), |(n, s), (o, d)| match caster.first_hit(o, d, 0.2) {
                    Some(t) => (n + 1, s + t as f64),
                    None => (n, s),
                })
            })
            .reduce(|| (0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1));
        let cast = start.elapsed().as_secs_f64();
        let rays = (size * size * spp) as f64;
        println!(
            "| {name} | {kind} | {built:.2} s | {cast:.2} s | {:.1} M | {hits} | {:.6} |",
            rays / cast / 1e6,
            sum / hits.max(1) as f64
        );
    }
}
