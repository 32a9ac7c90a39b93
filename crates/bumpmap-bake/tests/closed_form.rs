//! The bake against a closed form: HIGH is a plane subdivided to four vertices a texel and
//! displaced along its normal by a height field, LOW the plane itself; the bake must be
//! `normalmap`'s normal map of the same heights at the matching scale (depth × texels per unit).

use bumpmap_bake::{BakeError, BakeOptions, RayMode, bake};
use bumpmap_math::mesh::Mesh;
use bumpmap_math::normalmap::normal_map_level0_texels;
use bumpmap_math::{Encoding, HeightField, Kernel, NormalMapOptions, Wrap, YConvention};
use glam::{Vec2, Vec3, Vec4};

/// Texels a side.
const N: usize = 64;
/// How far the heights displace HIGH, in the plane's units (the plane is 1 across).
const DEPTH: f32 = 0.05;

/// Heights in [0, 1] over the unit square, periodic across it (so `normalmap --wrap repeat`
/// reads them as the plane has them).
fn heights(x: f32, y: f32) -> f32 {
    use std::f32::consts::TAU;
    0.5 + 0.25 * (TAU * 2.0 * x).sin() * (TAU * 3.0 * y).cos() + 0.1 * (TAU * (x + y)).sin()
}

/// The unit square in z = 0, texture coordinates (x, y): t grows with y, so B = N × T = +y.
fn low() -> Mesh {
    let corners = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(1.0, 1.0), Vec2::new(0.0, 1.0)];
    Mesh {
        positions: corners.iter().map(|c| c.extend(0.0)).collect(),
        normals: vec![Vec3::Z; 4],
        texcoords: corners.to_vec(),
        tangents: vec![Vec4::new(1.0, 0.0, 0.0, 1.0); 4],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Default::default()
    }
}

/// The square subdivided `per_texel` times a texel side and displaced by DEPTH × heights, its
/// normals from its faces (as a sculpt exported without normals has them).
fn high(per_texel: usize) -> Mesh {
    let n = N * per_texel;
    let mut mesh = Mesh::default();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f32 / n as f32, j as f32 / n as f32);
            mesh.positions.push(Vec3::new(x, y, DEPTH * heights(x, y)));
        }
    }
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    for j in 0..n {
        for i in 0..n {
            mesh.indices.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            mesh.indices.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    mesh.compute_normals();
    mesh
}

/// `normalmap` of the heights at texel centres, central differences, at DEPTH × N texels per
/// unit of height, in texture space (y toward increasing t), decoded from 16 bits.
fn normal_map() -> Vec<Vec3> {
    let texels: Vec<f32> =
        (0..N * N).map(|k| heights(((k % N) as f32 + 0.5) / N as f32, ((k / N) as f32 + 0.5) / N as f32)).collect();
    let field = HeightField::new(N, N, texels).unwrap();
    let options = NormalMapOptions {
        kernel: Kernel::Central,
        wrap: Wrap::Repeat,
        scale: DEPTH * N as f32,
        y_convention: YConvention::TEXTURE_SPACE,
        ..Default::default()
    };
    let map = normal_map_level0_texels::<[u16; 4]>(&field, &options).unwrap();
    let d = |v: u16| Encoding::Unorm.decode16(v);
    map.texels.iter().map(|t| Vec3::new(d(t[0]), d(t[1]), d(t[2])).normalize()).collect()
}

/// Mean and 99th percentile of the angles between two sets of unit vectors, in degrees.
fn angles(a: &[Vec3], b: &[Vec3]) -> (f32, f32) {
    let mut degrees: Vec<f32> = a.iter().zip(b).map(|(p, q)| p.dot(*q).clamp(-1.0, 1.0).acos().to_degrees()).collect();
    degrees.sort_by(f32::total_cmp);
    (degrees.iter().sum::<f32>() / degrees.len() as f32, degrees[degrees.len() * 99 / 100])
}

#[test]
fn a_displaced_plane_bakes_to_the_normal_map_of_its_heights() {
    let options = BakeOptions {
        width: N,
        height: N,
        samples: 1,
        front: Some(2.0 * DEPTH),
        back: Some(2.0 * DEPTH),
        ..Default::default()
    };
    let baked = bake(&high(2), &low(), &options, &|_, _| {}).unwrap();
    assert!(baked.hit.iter().all(|h| *h), "every texel of the plane meets the displaced plane");
    let (mean, p99) = angles(&baked.tangent, &normal_map());
    eprintln!("plane, 4 vertices a texel: mean {mean:.3}°, 99th percentile {p99:.3}°");
    assert!(mean <= 0.5 && p99 <= 2.0, "mean {mean}°, 99th percentile {p99}°");
    // Not flat: the heights tilt the normals by several degrees.
    let tilt = baked.tangent.iter().map(|n| n.z.acos().to_degrees()).fold(0.0, f32::max);
    assert!(tilt > 5.0, "{tilt}°");
    // The displacement is the heights' own, DEPTH × F, at each texel centre.
    let worst = (0..N * N)
        .map(|k| {
            let f = heights(((k % N) as f32 + 0.5) / N as f32, ((k / N) as f32 + 0.5) / N as f32);
            (baked.displacement[k] - DEPTH * f).abs()
        })
        .fold(0.0, f32::max);
    assert!(worst < 0.02 * DEPTH, "{worst}");
}

#[test]
fn rays_that_meet_nothing_are_an_error_not_a_flat_map() {
    let mut far = high(1);
    far.positions.iter_mut().for_each(|p| p.z += 1.0);
    let options = BakeOptions { width: 16, height: 16, front: Some(0.1), back: Some(0.1), ..Default::default() };
    match bake(&far, &low(), &options, &|_, _| {}) {
        Err(BakeError::MostMissed { missed, covered, .. }) => assert_eq!((missed, covered), (256, 256)),
        other => panic!("{other:?}"),
    }
    let mut no_uvs = low();
    no_uvs.texcoords.clear();
    assert!(matches!(bake(&high(1), &no_uvs, &options, &|_, _| {}), Err(BakeError::NoTexcoords)));
    let mut nan = high(1);
    nan.positions[5].x = f32::NAN;
    assert!(matches!(bake(&nan, &low(), &options, &|_, _| {}), Err(BakeError::Mesh { which: "high-poly", .. })));
    let empty = Mesh::default();
    assert!(matches!(bake(&empty, &low(), &options, &|_, _| {}), Err(BakeError::Mesh { which: "high-poly", .. })));
    let wide = BakeOptions { width: 0, ..options };
    assert!(matches!(bake(&high(1), &low(), &wide, &|_, _| {}), Err(BakeError::Size { .. })));
}

#[test]
fn explicit_rays_follow_the_split_normals_and_averaged_rays_do_not() {
    // A hard edge: two faces of a roof meeting at 90°, each with its own normals.
    let roof = {
        let p =
            [Vec3::new(-1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 1.0, 1.0), Vec3::new(-1.0, 1.0, 0.0)];
        let q =
            [Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 1.0)];
        let (nl, nr) = (Vec3::new(-1.0, 0.0, 1.0).normalize(), Vec3::new(1.0, 0.0, 1.0).normalize());
        let uv = |k: f32| [Vec2::new(k, 0.0), Vec2::new(k + 0.5, 0.0), Vec2::new(k + 0.5, 1.0), Vec2::new(k, 1.0)];
        Mesh {
            positions: p.iter().chain(&q).copied().collect(),
            normals: [nl; 4].into_iter().chain([nr; 4]).collect(),
            texcoords: uv(0.0).into_iter().chain(uv(0.5)).collect(),
            tangents: [nr.cross(Vec3::Y).extend(1.0); 4]
                .into_iter()
                .chain([Vec3::Y.cross(nl).extend(-1.0); 4])
                .collect(),
            indices: vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]],
            ..Default::default()
        }
    };
    let bake_with = |rays| {
        let options = BakeOptions {
            width: 32,
            height: 8,
            samples: 1,
            rays,
            front: Some(0.3),
            back: Some(0.3),
            padding: 0,
            ..Default::default()
        };
        bake(&roof, &roof, &options, &|_, _| {}).unwrap()
    };
    let (averaged, explicit) = (bake_with(RayMode::Averaged), bake_with(RayMode::Explicit));
    // Baked onto itself, each face's normal is flat in its own frame either way.
    for baked in [&averaged, &explicit] {
        let flat = baked.tangent.iter().zip(&baked.hit).filter(|(_, h)| **h).all(|(n, _)| n.z > 0.999);
        assert!(flat, "{:?}", baked.tangent.iter().map(|n| n.z).fold(1.0, f32::min));
    }
    // Averaged rays leave the ridge at an angle: they reach HIGH at other distances than the
    // explicit ones, which go straight down each face.
    let spread = |b: &bumpmap_bake::Baked| b.displacement.iter().map(|d| d.abs()).fold(0.0, f32::max);
    assert!(spread(&explicit) < 1e-4, "{}", spread(&explicit));
}

#[test]
fn a_displaced_planes_occlusion_is_its_horizon_maps() {
    // Deeper waves than the normals' test, so the valleys are occluded by a few per cent.
    let deep = |x: f32, y: f32| 4.0 * DEPTH * heights(x, y);
    let mut high = high(2);
    for p in &mut high.positions {
        p.z = deep(p.x, p.y);
    }
    high.compute_normals();
    let options = BakeOptions {
        width: N,
        height: N,
        samples: 1,
        front: Some(1.0),
        back: Some(1.0),
        occlusion_rays: 256,
        ..Default::default()
    };
    let baked = bake(&high, &low(), &options, &|_, _| {}).unwrap();
    let texels: Vec<f32> =
        (0..N * N).map(|k| heights(((k % N) as f32 + 0.5) / N as f32, ((k / N) as f32 + 0.5) / N as f32)).collect();
    let field = HeightField::new(N, N, texels).unwrap();
    let horizons = bumpmap_math::HorizonMap::from_heights(&field, Wrap::Repeat).unwrap();
    let ao = horizons.ambient_occlusion(4.0 * DEPTH * N as f32);
    // Away from the plane's edges, where HIGH ends and its rays see past it (the map tiles).
    let inner: Vec<usize> =
        (0..N * N).filter(|k| (8..N - 8).contains(&(k % N)) && (8..N - 8).contains(&(k / N))).collect();
    let mean_diff = inner.iter().map(|&k| (baked.occlusion[k] - ao[k]).abs()).sum::<f32>() / inner.len() as f32;
    let darkest = inner.iter().map(|&k| ao[k]).fold(1.0, f32::min);
    eprintln!("plane's occlusion against the horizon map's: mean |difference| {mean_diff:.4}, darkest {darkest:.3}");
    assert!(darkest < 0.97, "the valleys are occluded: {darkest}");
    // The horizon map's hemisphere is the plane's, the bake's HIGH's own normal's: they part
    // where the waves tilt (0.025 measured; 0.008 when the bake too took the plane's).
    assert!(mean_diff <= 0.03, "{mean_diff}");
}

#[test]
fn a_convex_high_poly_occludes_nothing() {
    // The rounded cube onto the hard-edged cube: averaged rays arrive tilted near the edges,
    // and a hemisphere around them would dip into HIGH's own face; around HIGH's normal it
    // does not.
    let low = bumpmap_math::tangent::generate_tangents(&bumpmap_math::mesh::rounded_cube(1, 0.0), &Default::default())
        .unwrap()
        .0;
    let high = bumpmap_math::mesh::rounded_cube(24, 0.2);
    let options = BakeOptions {
        width: 48,
        height: 48,
        samples: 1,
        front: Some(0.3),
        back: Some(0.3),
        occlusion_rays: 64,
        ..Default::default()
    };
    let baked = bake(&high, &low, &options, &|_, _| {}).unwrap();
    let open: Vec<f32> = baked.occlusion.iter().zip(&baked.hit).filter(|(_, h)| **h).map(|(o, _)| *o).collect();
    let darkest = open.iter().copied().fold(1.0, f32::min);
    let mean = open.iter().sum::<f32>() / open.len() as f32;
    // Not exactly 1: the bevels are facets, and a ray leaving a facet near its plane, around
    // the interpolated normal, can meet the next (2 rays of 64 at worst). Around the rays'
    // directions the faces read 0.93 on average and 0.75 at worst.
    assert!(darkest > 0.95 && mean > 0.995, "darkest {darkest}, mean {mean}");
}

#[test]
fn a_cage_is_where_the_rays_start() {
    use bumpmap_bake::bake_with_cage;
    let options =
        BakeOptions { width: 32, height: 32, samples: 1, front: Some(0.1), back: Some(0.1), ..Default::default() };
    let high = high(2);
    let plain = bake(&high, &low(), &options, &|_, _| {}).unwrap();
    // LOW pushed 0.1 out: the same rays as --extrude 0.1.
    let cage: Vec<Vec3> = low().positions.iter().map(|p| *p + Vec3::Z * 0.1).collect();
    let caged = bake_with_cage(&high, &low(), &cage, &options, &|_, _| {}).unwrap();
    let (mean, worst) = angles(&plain.tangent, &caged.tangent);
    assert!(mean < 1e-3 && worst < 0.05, "{mean}° {worst}° (float rounding of two ways to one ray)");
    // A cage too close in front misses the waves' crests: rays start below them.
    let low_cage: Vec<Vec3> = low().positions.iter().map(|p| *p + Vec3::Z * 0.01).collect();
    let short = bake_with_cage(&high, &low(), &low_cage, &BakeOptions { back: Some(0.0), ..options }, &|_, _| {});
    assert!(matches!(short, Err(BakeError::MostMissed { .. })) || short.unwrap().hit.iter().any(|h| !h));
    // A cage of another topology, or with NaN, is refused.
    assert!(matches!(
        bake_with_cage(&high, &low(), &cage[..3], &options, &|_, _| {}),
        Err(BakeError::CageSize { cage: 3, low: 4 })
    ));
    let mut nan = cage.clone();
    nan[2].y = f32::NAN;
    assert!(matches!(bake_with_cage(&high, &low(), &nan, &options, &|_, _| {}), Err(BakeError::CageNotFinite(2))));
}
