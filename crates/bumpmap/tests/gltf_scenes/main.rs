//! Real glTF scenes, one feature a test, on glTF files the tests write: each primitive with its
//! own material, double-sided materials, node hierarchies, `KHR_texture_transform`, primitives
//! without texture coordinates, and the files that must be refused. Every image test runs on
//! the CPU and, where an adapter exists (always under CI: lavapipe), on the GPU.

mod builder;
mod look;

use std::path::PathBuf;

use builder::{Gltf, color_png, normal_png, ramp_png};
use bumpmap::assets::{MeshAsset, MeshLoad, load_mesh};
use bumpmap::{BackendChoice, Light, Renderer, Rgba8Image, SceneLight, SceneSpec, TechniqueName, ViewerModel};
use bumpmap_testkit::{assert_has_content, assert_psnr, output_dir, psnr, write_png};
use glam::Vec3;

/// The CPU renderer, and the GPU's where an adapter exists (required under CI).
fn renderers() -> Vec<(&'static str, Renderer)> {
    let mut all = vec![("cpu", Renderer::new(BackendChoice::Cpu).expect("the CPU backend"))];
    match Renderer::new(BackendChoice::Gpu) {
        Ok(gpu) => all.push(("gpu", gpu)),
        Err(e) if std::env::var_os("CI").is_none() && std::env::var_os("BUMPMAP_REQUIRE_GPU").is_none() => {
            eprintln!("SKIPPED the GPU half: no adapter ({e}); install mesa-vulkan-drivers for lavapipe");
        }
        Err(e) => panic!("no GPU adapter under CI: {e}"),
    }
    all
}

fn write(name: &str, gltf: &Gltf) -> PathBuf {
    let dir = output_dir().join("gltf_scenes");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.gltf"));
    std::fs::write(&path, gltf.json()).unwrap();
    path
}

fn load(name: &str, gltf: &Gltf) -> MeshAsset {
    load_mesh(&write(name, gltf), &MeshLoad::default()).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The asset's scene seen from `eye` toward the origin, lit by a directional light from
/// `light`, with an infinite viewer (so a view and its mirror are lit alike).
fn spec(asset: &MeshAsset, eye: Vec3, light: Vec3) -> SceneSpec {
    let mut spec = asset.spec();
    spec.params.eye = Some(eye);
    spec.params.target = Some(Vec3::ZERO);
    spec.params.up = Some(Vec3::Y);
    spec.params.viewer = ViewerModel::Infinite;
    spec.params.lights = vec![SceneLight::white(Light::Directional(light))];
    // No highlight: a grazing light's diffuse shading shows the bumps best, and the
    // three-pass technique drops its specular pass.
    spec.params.specular = Vec3::ZERO;
    spec.params.diffuse = Vec3::splat(0.8);
    spec
}

fn draw(renderer: &mut Renderer, spec: &SceneSpec, technique: TechniqueName, (w, h): (usize, usize)) -> Rgba8Image {
    renderer.render(spec, technique, w, h).unwrap_or_else(|e| panic!("{technique:?}: {e}"))
}

/// Pixels brighter than the background, by any channel.
fn lit(image: &Rgba8Image) -> usize {
    image.texels.iter().filter(|t| t[..3].iter().any(|&c| c > 8)).count()
}

fn mean(image: &Rgba8Image) -> f64 {
    image.texels.iter().map(|t| t[..3].iter().map(|&c| c as f64).sum::<f64>()).sum::<f64>() / image.texels.len() as f64
}

fn mirrored(image: &Rgba8Image) -> Rgba8Image {
    let texels = (0..image.height)
        .flat_map(|y| (0..image.width).rev().map(move |x| (x, y)))
        .map(|(x, y)| image.texel(x, y))
        .collect();
    Rgba8Image::new(image.width, image.height, texels)
}

/// Saves an image for a person to look at (`target/test-output/gltf_scenes/`).
fn keep(name: &str, image: &Rgba8Image) {
    write_png(&output_dir().join("gltf_scenes").join(format!("{name}.png")), image);
}

const FRONT: [[f32; 3]; 4] = [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]];
const TOWARD_Z: [f32; 3] = [0.0, 0.0, 1.0];

fn dimples(s: f32, t: f32) -> f32 {
    let tau = std::f32::consts::TAU;
    0.5 + 0.25 * (2.0 * tau * s).sin() * (2.0 * tau * t).sin() + 0.15 * (tau * s).cos()
}

fn bumped_quad(double_sided: bool) -> Gltf {
    let mut g = Gltf::default();
    let normal = g.texture(&normal_png(64, dimples));
    let m = g.material(&format!(r#""normalTexture":{{"index":{normal}}},"doubleSided":{double_sided}"#));
    let mesh = g.quad(FRONT, TOWARD_Z, Some(m));
    g.node(&format!(r#""mesh":{mesh}"#));
    g
}

#[test]
fn a_double_sided_quad_seen_from_behind_is_its_front_mirrored_and_a_single_sided_one_is_culled() {
    let (single, double) = (load("single_sided", &bumped_quad(false)), load("double_sided", &bumped_quad(true)));
    assert!(double.describe().iter().any(|l| l.contains("double-sided")), "{:?}", double.describe());
    let light = Vec3::new(-1.0, 0.6, 0.5);
    let (front_eye, back_eye) = (Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.0, 0.0, -4.0));
    for (backend, mut r) in renderers() {
        let size = (96, 96);
        let culled = draw(&mut r, &spec(&single, back_eye, -light), TechniqueName::SinglePass, size);
        assert_eq!(lit(&culled), 0, "{backend}: a single-sided quad seen from behind draws nothing");
        let front = draw(&mut r, &spec(&double, front_eye, light), TechniqueName::SinglePass, size);
        let back = draw(&mut r, &spec(&double, back_eye, -light), TechniqueName::SinglePass, size);
        let back_unlit = draw(&mut r, &spec(&double, back_eye, light), TechniqueName::SinglePass, size);
        keep(&format!("double_sided_front_{backend}"), &front);
        keep(&format!("double_sided_back_{backend}"), &back);
        assert_has_content(&format!("{backend}: the back of a double-sided quad"), &back);
        // The back's whole frame is reversed (N, T and B): its perturbed normal is the front's
        // negated, so seen from the mirror eye with the mirror light it is the front's image,
        // mirrored left to right. Only the normal flipped would light the bumps from the other side.
        assert_psnr(
            &format!("double_sided_{backend}"),
            &mirrored(&front),
            &back,
            40.0,
            "the same texels and the same lighting; only the triangles' rasterization order differs",
        );
        assert!(
            mean(&back) > 2.0 * mean(&back_unlit),
            "{backend}: lit from its own side the back is bright ({:.1}), lit from the front's only ambient ({:.1})",
            mean(&back),
            mean(&back_unlit)
        );
    }
}

/// Two quads side by side, the left with normal map `left`, the right with `right`, as two
/// primitives of one mesh (each its own material).
fn two_quads(left: &[u8], right: &[u8]) -> Gltf {
    let mut g = Gltf::default();
    let (tl, tr) = (g.texture(left), g.texture(right));
    let ml = g.material(&format!(r#""name":"left","normalTexture":{{"index":{tl}}}"#));
    let mr = g.material(&format!(r#""name":"right","normalTexture":{{"index":{tr}}}"#));
    let shift = |dx: f32| FRONT.map(|p| [p[0] + dx, p[1], p[2]]);
    let a = g.quad_primitive(shift(-1.1), TOWARD_Z, Some(ml), true);
    let b = g.quad_primitive(shift(1.1), TOWARD_Z, Some(mr), true);
    g.meshes.push(format!("{{\"primitives\":[{a},{b}]}}"));
    g.node(r#""mesh":0"#);
    g
}

#[test]
fn two_primitives_each_draw_with_their_own_normal_map() {
    let tau = std::f32::consts::TAU;
    let across = normal_png(64, |s, t| 0.5 + 0.3 * (2.0 * tau * s).sin() + 0.1 * (tau * t).cos());
    let along = normal_png(64, |s, t| 0.5 + 0.3 * (2.0 * tau * t).sin() + 0.1 * (tau * s).cos());
    let both = load("two_materials", &two_quads(&across, &along));
    let swapped = load("two_materials_swapped", &two_quads(&along, &across));
    assert_eq!((both.parts.len(), both.materials.len()), (2, 2));
    let same = load("two_materials_same", &two_quads(&across, &across));
    let (eye, light) = (Vec3::new(0.0, 0.0, 3.2), Vec3::new(-1.0, 0.6, 0.5));
    let (w, h) = (128, 64);
    let half = |image: &Rgba8Image, right: bool| {
        let texels = (0..h)
            .flat_map(|y| (0..w / 2).map(move |x| (x, y)))
            .map(|(x, y)| image.texel(if right { x + w / 2 } else { x }, y))
            .collect();
        Rgba8Image::new(w / 2, h, texels)
    };
    for (backend, mut r) in renderers() {
        for technique in [TechniqueName::SinglePass, TechniqueName::Kilgard] {
            let name = format!("{backend}_{technique:?}");
            let image = draw(&mut r, &spec(&both, eye, light), technique, (w, h));
            keep(&format!("two_materials_{name}"), &image);
            let other = draw(&mut r, &spec(&swapped, eye, light), technique, (w, h));
            let uniform = draw(&mut r, &spec(&same, eye, light), technique, (w, h));
            // The left halves share a map (the same pixels); the right halves do not.
            assert_psnr(
                &format!("two_materials_left_{name}"),
                &half(&uniform, false),
                &half(&image, false),
                50.0,
                "the same map on the same quad",
            );
            let right = psnr(&half(&uniform, true), &half(&image, true));
            assert!(right < 25.0, "{name}: the right quad draws its own map, not the left's ({right:.1} dB apart)");
            let swapped_left = psnr(&half(&other, false), &half(&image, false));
            assert!(swapped_left < 25.0, "{name}: swapping the materials changes the left quad ({swapped_left:.1} dB)");
            assert_psnr(
                &format!("two_materials_swap_{name}"),
                &half(&other, true),
                &half(&uniform, true),
                50.0,
                "the right quad with the left's map, either way",
            );
        }
    }
}

#[test]
fn a_node_hierarchy_places_the_mesh_as_its_composed_transform_does() {
    let quad = |g: &mut Gltf| {
        let normal = g.texture(&normal_png(32, dimples));
        let m = g.material(&format!(r#""normalTexture":{{"index":{normal}}}"#));
        g.quad(FRONT, TOWARD_Z, Some(m))
    };
    // A parent turned 90° about +Z over a child moved +0.8 in x and halved: the quad ends at
    // +0.8 in y, turned, half its size.
    let mut nested = Gltf::default();
    let mesh = quad(&mut nested);
    let q = std::f32::consts::FRAC_1_SQRT_2;
    nested.node(&format!(r#""rotation":[0,0,{q},{q}],"children":[1]"#));
    nested.node(&format!(r#""mesh":{mesh},"translation":[0.8,0,0],"scale":[0.5,0.5,0.5]"#));
    nested.roots = vec![0];
    let mut flat = Gltf::default();
    let mesh = quad(&mut flat);
    flat.node(&format!(r#""mesh":{mesh},"translation":[0,0.8,0],"rotation":[0,0,{q},{q}],"scale":[0.5,0.5,0.5]"#));
    let mut still = Gltf::default();
    let mesh = quad(&mut still);
    still.node(&format!(r#""mesh":{mesh}"#));
    let (nested, flat, still) = (load("nested", &nested), load("nested_flat", &flat), load("unmoved", &still));
    let (eye, light) = (Vec3::new(0.0, 0.0, 4.0), Vec3::new(-1.0, 0.6, 0.5));
    for (backend, mut r) in renderers() {
        let image = draw(&mut r, &spec(&nested, eye, light), TechniqueName::SinglePass, (64, 64));
        let direct = draw(&mut r, &spec(&flat, eye, light), TechniqueName::SinglePass, (64, 64));
        let unmoved = draw(&mut r, &spec(&still, eye, light), TechniqueName::SinglePass, (64, 64));
        keep(&format!("nested_{backend}"), &image);
        assert_psnr(&format!("nested_{backend}"), &direct, &image, 45.0, "one transform, composed two ways in f32");
        let centroid = |image: &Rgba8Image| {
            let (mut n, mut sy) = (0.0f64, 0.0f64);
            for y in 0..image.height {
                for x in 0..image.width {
                    if image.texel(x, y)[..3].iter().any(|&c| c > 8) {
                        n += 1.0;
                        sy += y as f64;
                    }
                }
            }
            (n, sy / n.max(1.0))
        };
        let ((n, y), (n0, y0)) = (centroid(&image), centroid(&unmoved));
        assert!(y < y0 - 10.0, "{backend}: moved up the image, rows {y0:.1} → {y:.1}");
        assert!((n / n0 - 0.25).abs() < 0.05, "{backend}: half the size, a quarter of the pixels ({n0} → {n})");
    }
}

/// A quad whose normal texture reads its coordinates through `transform` (a
/// `KHR_texture_transform` object, or none).
fn transformed_quad(png: &[u8], transform: Option<&str>) -> Gltf {
    let mut g = Gltf::default();
    let normal = g.texture(png);
    let extension = transform.map_or(String::new(), |t| format!(r#","extensions":{{"KHR_texture_transform":{t}}}"#));
    let m = g.material(&format!(r#""normalTexture":{{"index":{normal}{extension}}}"#));
    let mesh = g.quad(FRONT, TOWARD_Z, Some(m));
    g.node(&format!(r#""mesh":{mesh}"#));
    if transform.is_some() {
        g.extensions_used.push("KHR_texture_transform");
    }
    g
}

#[test]
fn a_texture_transform_turns_the_bumps_and_their_tangent_frame_with_them() {
    let tau = std::f32::consts::TAU;
    let h = |s: f32, t: f32| 0.5 + 0.3 * (2.0 * tau * s).sin() + 0.15 * (tau * t).cos();
    // uv' = R(90°)·uv = (v, −u): the quad shows h(v, −u), which is the map of h2(s, t) = h(t, −s).
    let h2 = |s: f32, t: f32| h(t, -s);
    let turned = load("transform_90", &transformed_quad(&normal_png(64, h), Some(r#"{"rotation":1.5707963}"#)));
    let made_turned = load("transform_made_turned", &transformed_quad(&normal_png(64, h2), None));
    let unturned = load("transform_none", &transformed_quad(&normal_png(64, h), None));
    assert!(turned.describe().iter().any(|l| l.contains("KHR_texture_transform applied")), "{:?}", turned.describe());
    let (eye, light) = (Vec3::new(0.0, -1.0, 4.0), Vec3::new(-1.0, 0.6, 0.5));
    for (backend, mut r) in renderers() {
        let image = draw(&mut r, &spec(&turned, eye, light), TechniqueName::SinglePass, (96, 96));
        let expected = draw(&mut r, &spec(&made_turned, eye, light), TechniqueName::SinglePass, (96, 96));
        let plain = draw(&mut r, &spec(&unturned, eye, light), TechniqueName::SinglePass, (96, 96));
        keep(&format!("transform_90_{backend}"), &image);
        keep(&format!("transform_none_{backend}"), &plain);
        // The turned texels are the texels of the turned heights' map, each vector turned with
        // the frame: lit alike where the tangents follow the transformed coordinates.
        assert_psnr(
            &format!("transform_90_{backend}"),
            &expected,
            &image,
            35.0,
            "a quarter turn maps texel centres onto texel centres; the kernel's differences along s and t swap",
        );
        let apart = psnr(&plain, &image);
        assert!(apart < 25.0, "{backend}: the transform changes the picture ({apart:.1} dB from the untransformed)");
    }
}

#[test]
fn a_primitive_without_texture_coordinates_is_drawn_unbumped_beside_a_bumped_one() {
    let mut g = Gltf::default();
    let normal = g.texture(&normal_png(32, dimples));
    let color = g.texture(&color_png([230, 60, 40]));
    let m = g.material(&format!(
        r#""normalTexture":{{"index":{normal}}},"pbrMetallicRoughness":{{"baseColorTexture":{{"index":{color}}}}}"#
    ));
    let shift = |dx: f32| FRONT.map(|p| [p[0] + dx, p[1], p[2]]);
    let a = g.quad_primitive(shift(-1.1), TOWARD_Z, Some(m), true);
    let b = g.quad_primitive(shift(1.1), TOWARD_Z, Some(m), false);
    g.meshes.push(format!("{{\"primitives\":[{a},{b}]}}"));
    g.node(r#""mesh":0"#);
    let asset = load("untextured_part", &g);
    assert_eq!(asset.unbumped_parts(), 1);
    let said = asset.warnings.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n");
    assert!(said.contains("1 of 2 primitive(s) lack the texture coordinates"), "{said}");
    let mut r = Renderer::new(BackendChoice::Cpu).unwrap();
    let image = draw(
        &mut r,
        &spec(&asset, Vec3::new(0.0, 0.0, 6.0), Vec3::new(-1.0, 0.6, 0.5)),
        TechniqueName::SinglePass,
        (128, 64),
    );
    keep("untextured_part", &image);
    // The right quad: one flat colour (unbumped, untextured: white lit evenly); the left: red, bumped.
    let colours = |x0: usize| {
        (8..56).flat_map(|y| (x0..x0 + 48).map(move |x| (x, y))).map(|(x, y)| image.texel(x, y)).collect::<Vec<_>>()
    };
    let (left, right) = (colours(8), colours(72));
    let distinct = |c: &[[u8; 4]]| c.iter().map(|t| [t[0], t[1], t[2]]).collect::<std::collections::HashSet<_>>().len();
    assert!(distinct(&left) > 30, "the left quad shows its bumps ({} colours)", distinct(&left));
    assert!(distinct(&right) <= 4, "the right quad is flat ({} colours)", distinct(&right));
    let r0 = right[right.len() / 2];
    assert!(r0[0] > 40 && r0[0].abs_diff(r0[1]) < 4, "and untextured: grey-white, not the red texture ({r0:?})");
}

#[test]
fn each_wrap_mode_of_a_sampler_repeats_mirrors_or_clamps_the_texture() {
    // A base colour ramp (red left to right) read three times across the quad
    // (KHR_texture_transform scale 3), through a sampler of each wrap mode.
    let quad = |wrap: u32| {
        let mut g = Gltf::default();
        let t = g.texture_sampled(
            &ramp_png(16),
            &format!(r#""wrapS":{wrap},"wrapT":33071,"magFilter":9729,"minFilter":9729"#),
        );
        let m = g.material(&format!(
            r#""pbrMetallicRoughness":{{"baseColorTexture":{{"index":{t},"extensions":{{"KHR_texture_transform":{{"scale":[3,1]}}}}}}}}"#
        ));
        let mesh = g.quad(FRONT, TOWARD_Z, Some(m));
        g.node(&format!(r#""mesh":{mesh}"#));
        g.extensions_used.push("KHR_texture_transform");
        g
    };
    let modes = [("repeat", 10497u32), ("mirrored", 33648), ("clamp", 33071)];
    let assets: Vec<MeshAsset> = modes.iter().map(|(name, wrap)| load(&format!("wrap_{name}"), &quad(*wrap))).collect();
    let (eye, light) = (Vec3::new(0.0, 0.0, 1.5), Vec3::new(0.0, 0.0, 1.0));
    let mut images: Vec<Vec<Rgba8Image>> = Vec::new();
    for (backend, mut r) in renderers() {
        let mut row = Vec::new();
        for ((name, _), asset) in modes.iter().zip(&assets) {
            let image = draw(&mut r, &spec(asset, eye, light), TechniqueName::SinglePass, (120, 60));
            keep(&format!("wrap_{name}_{backend}"), &image);
            // The red across the middle row, where the quad covers it: 3 ramps up (repeat),
            // up-down-up (mirrored), one ramp then the last texel (clamp).
            let reds: Vec<i32> =
                (0..120).map(|x| image.texel(x, 30)).filter(|t| t[1] > 8).map(|t| t[0] as i32).collect();
            assert!(reds.len() > 80, "{backend} {name}: the quad covers the row ({} pixels)", reds.len());
            // Runs of falling red: (length in pixels, total fall).
            let mut runs: Vec<(usize, i32)> = Vec::new();
            let mut run = (0, 0);
            for d in reds.windows(2).map(|w| w[1] - w[0]) {
                if d < 0 {
                    run = (run.0 + 1, run.1 - d);
                } else if run.0 > 0 {
                    runs.push(std::mem::take(&mut run));
                }
            }
            if run.0 > 0 {
                runs.push(run);
            }
            let falls: Vec<&(usize, i32)> = runs.iter().filter(|r| r.1 > 150).collect();
            let n = reds.len();
            match *name {
                "repeat" => assert!(
                    falls.len() == 2 && falls.iter().all(|r| r.0 <= 4),
                    "{backend}: two sudden falls back to dark red: {runs:?} in {reds:?}"
                ),
                "mirrored" => assert!(
                    falls.len() == 1 && falls[0].0 > n / 5,
                    "{backend}: one slow fall, the middle ramp mirrored: {runs:?} in {reds:?}"
                ),
                _ => assert!(
                    falls.is_empty() && reds[n / 2..n - 2].iter().all(|&r| r >= 250),
                    "{backend}: one ramp, then its last texel: {reds:?}"
                ),
            }
            row.push(image);
        }
        images.push(row);
    }
    if let [cpu, gpu] = &images[..] {
        for (k, (name, _)) in modes.iter().enumerate() {
            // Not assert_psnr: the clamped image is mostly one colour, which its content guard
            // refuses; the rows above already showed each image's ramps.
            let db = psnr(&cpu[k], &gpu[k]);
            assert!(
                db > 35.0,
                "{name}: CPU and GPU {db:.1} dB apart (the same lookups; lavapipe filters in its own fixed point)"
            );
        }
    }
}

/// The message `load_mesh` refuses `json` with (the builder's file with `edit` applied).
fn refusal(name: &str, g: &Gltf, edit: impl Fn(String) -> String) -> String {
    let path = write(name, g);
    std::fs::write(&path, edit(g.json())).unwrap();
    match load_mesh(&path, &MeshLoad::default()) {
        Ok(_) => panic!("{name}: loaded, but should have been refused"),
        Err(e) => {
            let message = e.to_string();
            assert!(message.contains(&format!("{name}.gltf")), "{name}: names the file: {message}");
            message
        }
    }
}

#[test]
fn scenes_that_cannot_be_drawn_as_written_are_refused_naming_the_element() {
    let g = bumped_quad(false);
    let cycle = refusal("cycle", &g, |j| {
        j.replace(r#""nodes":[{"mesh":0}]"#, r#""nodes":[{"mesh":0,"children":[1]},{"children":[0]}]"#)
    });
    assert!(cycle.contains("node 0 is reached twice"), "{cycle}");
    let scene = refusal("scene_index", &g, |j| j.replace(r#""scene":0"#, r#""scene":4"#));
    assert!(scene.contains("scene"), "{scene}");
    let cutoff = refusal("alpha_cutoff", &g, |j| {
        j.replace(r#""doubleSided":false"#, r#""doubleSided":false,"alphaMode":"MASK","alphaCutoff":2"#)
    });
    assert!(cutoff.contains("alphaCutoff is 2"), "{cutoff}");
    let wrap = refusal("sampler_wrap", &g, |j| {
        j.replace(
            r#""textures":[{"source":0}]"#,
            r#""textures":[{"source":0,"sampler":0}],"samplers":[{"wrapS":12345}]"#,
        )
    });
    assert!(wrap.contains("samplers[0].wrapS"), "{wrap}");
    let material = refusal("material_index", &g, |j| j.replace(r#""material":0"#, r#""material":7"#));
    assert!(material.contains("material"), "{material}");
    let huge = refusal(
        "transform_not_finite",
        &transformed_quad(&color_png([128, 128, 255]), Some(r#"{"scale":[1e39,1]}"#)),
        |j| j,
    );
    assert!(huge.contains("KHR_texture_transform") && huge.contains("finite"), "{huge}");
    let node = refusal("node_not_finite", &g, |j| j.replace(r#"{"mesh":0}"#, r#"{"mesh":0,"translation":[1e39,0,0]}"#));
    assert!(node.contains("node 0") && node.contains("not finite"), "{node}");
    let points = refusal("only_points", &g, |j| {
        j.replace(r#""indices":3,"material":0"#, r#""indices":3,"material":0,"mode":0"#)
    });
    assert!(points.contains("no triangles") && points.contains("Points"), "{points}");
}

#[test]
fn what_cannot_be_drawn_is_said_once_and_lines_are_left_out() {
    let mut g = Gltf::default();
    let normal = g.texture(&normal_png(16, dimples));
    for name in ["steel", "chrome"] {
        // metallicFactor defaults to 1: the blue channel is metalness, which is not drawn.
        g.material(&format!(
            r#""name":"{name}","normalTexture":{{"index":{normal}}},"pbrMetallicRoughness":{{"metallicRoughnessTexture":{{"index":{normal}}}}}"#
        ));
    }
    let a = g.quad_primitive(FRONT, TOWARD_Z, Some(0), true);
    // Vertex colours on the first: its normals' accessor (three floats) serves as COLOR_0.
    let normals = a.split(r#""NORMAL":"#).nth(1).and_then(|r| r.split(|c: char| !c.is_ascii_digit()).next()).unwrap();
    let a = a.replacen(r#""NORMAL":"#, &format!(r#""COLOR_0":{normals},"NORMAL":"#), 1);
    let b = g.quad_primitive(FRONT.map(|p| [p[0] + 2.5, p[1], p[2]]), TOWARD_Z, Some(1), true);
    let lines = g.quad_primitive(FRONT, TOWARD_Z, Some(1), true).replace(r#""material":1"#, r#""material":1,"mode":1"#);
    g.meshes.push(format!("{{\"primitives\":[{a},{b},{lines}]}}"));
    g.node(r#""mesh":0"#);
    let asset = load("left_out", &g);
    assert_eq!(asset.parts.len(), 2, "the line primitive is left out");
    let said: Vec<String> = asset.warnings.iter().map(ToString::to_string).collect();
    let count = |what: &str| said.iter().filter(|l| l.contains(what)).count();
    assert_eq!(count("metalness"), 1, "{said:?}");
    assert!(
        said.iter().any(|l| l.contains("metalness") && l.contains("'steel'") && l.contains("'chrome'")),
        "{said:?}"
    );
    assert_eq!(count("1 Lines primitive(s) left out"), 1, "{said:?}");
    assert!(
        asset.describe().iter().any(|l| l.contains("'steel'") && l.contains("roughness")),
        "{:?}",
        asset.describe()
    );
}
