//! A material's look beyond its normal map and base colour: `alphaMode` MASK and BLEND,
//! `occlusionTexture`, emission and the roughness of `metallicRoughnessTexture`, each on a quad
//! the test writes, on both backends. The quads face the eye and the light head-on, without a
//! normal map, so each expected colour is a sum a person can do by hand.

use super::*;
use builder::columns_png;

const NEAR: [[f32; 3]; 4] = [[-1.0, -1.0, 0.5], [1.0, -1.0, 0.5], [1.0, 1.0, 0.5], [-1.0, 1.0, 0.5]];
const FAR: [[f32; 3]; 4] = [[-1.5, -1.5, 0.0], [1.5, -1.5, 0.0], [1.5, 1.5, 0.0], [-1.5, 1.5, 0.0]];
const SIZE: (usize, usize) = (96, 96);
const EYE: Vec3 = Vec3::new(0.0, 0.0, 4.0);

/// A red quad (material members `near`) in front of a green opaque one; the near quad's node
/// comes first when `near_first`, so only sorting draws it after the far one.
fn in_front_of_green(near: &str, near_first: bool) -> Gltf {
    let mut g = Gltf::default();
    let m_near = g.material(near);
    let m_far = g.material(r#""name":"green","pbrMetallicRoughness":{"baseColorFactor":[0,1,0,1]}"#);
    let a = g.quad(NEAR, TOWARD_Z, Some(m_near));
    let b = g.quad(FAR, TOWARD_Z, Some(m_far));
    let order = if near_first { [a, b] } else { [b, a] };
    for mesh in order {
        g.node(&format!(r#""mesh":{mesh}"#));
    }
    g
}

/// The scene lit head-on with ambient `ambient` and diffuse `diffuse`, no highlight.
fn head_on(asset: &MeshAsset, ambient: f32, diffuse: f32) -> SceneSpec {
    let mut spec = spec(asset, EYE, Vec3::Z);
    spec.params.ambient = Vec3::splat(ambient);
    spec.params.diffuse = Vec3::splat(diffuse);
    spec
}

/// The pixel `dx` pixels right of the image's centre row's middle.
fn at(image: &Rgba8Image, dx: i32) -> [u8; 4] {
    image.texel((image.width as i32 / 2 + dx) as usize, image.height / 2)
}

/// The largest difference of any channel of any pixel (the pictures here are flat colours,
/// which `assert_psnr` refuses as possibly black).
fn max_diff(a: &Rgba8Image, b: &Rgba8Image) -> u8 {
    a.texels.iter().zip(&b.texels).flat_map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c]))).max().unwrap_or(0)
}

fn close(what: &str, got: [u8; 4], want: [f32; 3], tolerance: f32) {
    let off = (0..3).map(|c| (got[c] as f32 - want[c]).abs()).fold(0.0, f32::max);
    assert!(off <= tolerance, "{what}: {got:?}, want {want:?} (± {tolerance})");
}

#[test]
fn a_mask_cuts_out_where_the_decal_alpha_is_below_the_cutoff_and_shows_what_is_behind() {
    // Alpha 0 in the left half of the texture, 255 in the right; red everywhere.
    let red = columns_png(|x| [255, 0, 0, if x < 8 { 0 } else { 255 }]);
    let material = |mode: &str, g: &mut Gltf| {
        let t = g.texture(&red);
        format!(r#""name":"leaf","pbrMetallicRoughness":{{"baseColorTexture":{{"index":{t}}}}}{mode}"#)
    };
    let build = |mode: &str| {
        let mut g = Gltf::default();
        let members = material(mode, &mut g);
        // The texture is image 0; the materials are made after it.
        let m_near = g.material(&members);
        let m_far = g.material(r#""name":"green","pbrMetallicRoughness":{"baseColorFactor":[0,1,0,1]}"#);
        let a = g.quad(NEAR, TOWARD_Z, Some(m_near));
        let b = g.quad(FAR, TOWARD_Z, Some(m_far));
        g.node(&format!(r#""mesh":{a}"#));
        g.node(&format!(r#""mesh":{b}"#));
        g
    };
    let masked = load("mask", &build(r#","alphaMode":"MASK","alphaCutoff":0.5"#));
    let opaque = load("mask_opaque", &build(""));
    assert!(masked.describe().iter().any(|l| l.contains("MASK")), "{:?}", masked.describe());
    for (backend, mut r) in renderers() {
        for technique in [TechniqueName::SinglePass, TechniqueName::Kilgard] {
            let name = format!("{backend}_{technique:?}");
            let cut = draw(&mut r, &head_on(&masked, 0.1, 0.8), technique, SIZE);
            let whole = draw(&mut r, &head_on(&opaque, 0.1, 0.8), technique, SIZE);
            keep(&format!("mask_{name}"), &cut);
            // Lit head-on: ambient + diffuse = 0.9 of the base colour.
            let lit = 0.9 * 255.0;
            close(&format!("{name}: the cut-out half shows the green quad"), at(&cut, -16), [0.0, lit, 0.0], 2.0);
            close(&format!("{name}: the kept half is the red quad"), at(&cut, 16), [lit, 0.0, 0.0], 2.0);
            close(&format!("{name}: opaque, both halves are red"), at(&whole, -16), [lit, 0.0, 0.0], 2.0);
            // Only the cut half changed.
            let right = |image: &Rgba8Image| {
                let texels = (0..SIZE.1)
                    .flat_map(|y| (SIZE.0 / 2 + 4..SIZE.0).map(move |x| (x, y)))
                    .map(|(x, y)| image.texel(x, y))
                    .collect();
                Rgba8Image::new(SIZE.0 / 2 - 4, SIZE.1, texels)
            };
            assert_eq!(max_diff(&right(&whole), &right(&cut)), 0, "{name}: the uncut half alike");
        }
    }
}

#[test]
fn a_blended_material_shows_what_is_behind_it_drawn_after_the_opaque_ones() {
    let glass = r#""name":"glass","pbrMetallicRoughness":{"baseColorFactor":[1,0,0,0.5]},"alphaMode":"BLEND""#;
    let solid = r#""name":"glass","pbrMetallicRoughness":{"baseColorFactor":[1,0,0,1]}"#;
    // The glass comes first in the file: drawn in file order it would hide the green quad.
    let blended = load("blend", &in_front_of_green(glass, true));
    let opaque = load("blend_opaque", &in_front_of_green(solid, true));
    let behind = load("blend_behind", &in_front_of_green(&format!("{glass},\"doubleSided\":false"), false));
    assert!(blended.describe().iter().any(|l| l.contains("BLEND")), "{:?}", blended.describe());
    for (backend, mut r) in renderers() {
        let spec = |a| head_on(a, 0.1, 0.8);
        let image = draw(&mut r, &spec(&blended), TechniqueName::SinglePass, SIZE);
        let later = draw(&mut r, &spec(&behind), TechniqueName::SinglePass, SIZE);
        keep(&format!("blend_{backend}"), &image);
        let lit = 0.9 * 255.0;
        // Half the red surface over the green one behind it, whichever the file lists first.
        close(&format!("{backend}: blended"), at(&image, 0), [0.5 * lit, 0.5 * lit, 0.0], 2.0);
        close(&format!("{backend}: blended, listed last"), at(&later, 0), [0.5 * lit, 0.5 * lit, 0.0], 2.0);
        // The paper's multipass builds the colour in the framebuffer: it draws the glass opaque.
        let kilgard = draw(&mut r, &spec(&blended), TechniqueName::Kilgard, SIZE);
        let kilgard_opaque = draw(&mut r, &spec(&opaque), TechniqueName::Kilgard, SIZE);
        assert_eq!(max_diff(&kilgard_opaque, &kilgard), 0, "{backend}: kilgard draws the glass opaque");
    }
}

/// A white quad whose occlusion texture is 0 in its left half and 255 in its right, at
/// `strength`; none where `strength` is `None`.
fn occluded(strength: Option<f32>) -> Gltf {
    let mut g = Gltf::default();
    let member = match strength {
        Some(s) => {
            let t = g.texture(&columns_png(|x| if x < 8 { [0, 0, 0, 255] } else { [255, 255, 255, 255] }));
            format!(r#""occlusionTexture":{{"index":{t},"strength":{s}}}"#)
        }
        None => r#""name":"plain""#.into(),
    };
    let m = g.material(&member);
    let mesh = g.quad(FRONT, TOWARD_Z, Some(m));
    g.node(&format!(r#""mesh":{mesh}"#));
    g
}

#[test]
fn an_occlusion_texture_darkens_the_ambient_term_only() {
    let (full, half, plain) = (
        load("occlusion", &occluded(Some(1.0))),
        load("occlusion_half", &occluded(Some(0.5))),
        load("occlusion_none", &occluded(None)),
    );
    assert!(full.describe().iter().any(|l| l.contains("occlusionTexture")), "{:?}", full.describe());
    for (backend, mut r) in renderers() {
        for technique in [TechniqueName::SinglePass, TechniqueName::Kilgard] {
            let name = format!("{backend}_{technique:?}");
            // Ambient 0.3, diffuse 0.5 (lit head-on).
            let spec = |a| head_on(a, 0.3, 0.5);
            let (f, h, p) = (
                draw(&mut r, &spec(&full), technique, SIZE),
                draw(&mut r, &spec(&half), technique, SIZE),
                draw(&mut r, &spec(&plain), technique, SIZE),
            );
            keep(&format!("occlusion_{name}"), &f);
            close(&format!("{name}: unoccluded"), at(&p, -16), [0.8 * 255.0; 3], 2.0);
            close(&format!("{name}: occluded, the diffuse term alone"), at(&f, -16), [0.5 * 255.0; 3], 2.0);
            close(&format!("{name}: half strength, half the ambient"), at(&h, -16), [0.65 * 255.0; 3], 2.0);
            close(&format!("{name}: where the occlusion is 1, nothing changes"), at(&f, 16), [0.8 * 255.0; 3], 2.0);
            // Lit from behind, only the ambient term is left: the occluded half goes black.
            let mut dark = spec(&full);
            dark.params.lights = vec![SceneLight::white(Light::Directional(-Vec3::Z))];
            let unlit = draw(&mut r, &dark, technique, SIZE);
            close(&format!("{name}: unlit and occluded"), at(&unlit, -16), [0.0; 3], 1.0);
            close(&format!("{name}: unlit, ambient alone"), at(&unlit, 16), [0.3 * 255.0; 3], 2.0);
        }
    }
}

#[test]
fn emission_is_added_to_the_lit_colour() {
    let build = |emissive: &str| {
        let mut g = Gltf::default();
        let m = g.material(&format!(r#""name":"lamp"{emissive}"#));
        let mesh = g.quad(FRONT, TOWARD_Z, Some(m));
        g.node(&format!(r#""mesh":{mesh}"#));
        g
    };
    let glowing = load("emission", &build(r#","emissiveFactor":[0.2,0.4,0]"#));
    let plain = load("emission_none", &build(""));
    // The factor is linear light; the framebuffer holds sRGB-encoded bytes, as the decal does.
    let encode = |l: f32| 255.0 * (1.055 * l.powf(1.0 / 2.4) - 0.055);
    for (backend, mut r) in renderers() {
        for technique in [TechniqueName::SinglePass, TechniqueName::Kilgard] {
            let name = format!("{backend}_{technique:?}");
            let spec = |a| head_on(a, 0.1, 0.2);
            let (g, p) = (draw(&mut r, &spec(&glowing), technique, SIZE), draw(&mut r, &spec(&plain), technique, SIZE));
            keep(&format!("emission_{name}"), &g);
            let base = 0.3 * 255.0;
            close(&format!("{name}: plain"), at(&p, 0), [base; 3], 2.0);
            close(&format!("{name}: glowing"), at(&g, 0), [base + encode(0.2), base + encode(0.4), base], 2.0);
        }
    }
}

#[test]
fn the_roughness_of_a_metallic_roughness_texture_reaches_the_roughness_map_technique() {
    let build = |roughness: u8| {
        let mut g = Gltf::default();
        let normal = g.texture(&normal_png(64, dimples));
        let mr = g.texture(&columns_png(|_| [255, roughness, 0, 255]));
        let m = g.material(&format!(
            r#""name":"metal","normalTexture":{{"index":{normal}}},"pbrMetallicRoughness":{{"metallicFactor":0,"metallicRoughnessTexture":{{"index":{mr}}}}}"#
        ));
        let mesh = g.quad(FRONT, TOWARD_Z, Some(m));
        g.node(&format!(r#""mesh":{mesh}"#));
        g
    };
    let (smooth, rough) = (load("roughness_smooth", &build(40)), load("roughness_rough", &build(230)));
    assert!(smooth.warnings.iter().all(|w| !w.to_string().contains("metalness")), "metallicFactor 0: nothing left out");
    for (backend, mut r) in renderers() {
        let spec = |a| {
            let mut s = spec(a, EYE, Vec3::new(0.3, 0.2, 1.0));
            // Kept below saturation, so the peaks compare.
            s.params.specular = Vec3::splat(0.4);
            s.params.diffuse = Vec3::splat(0.3);
            s.params.shininess = 30.0;
            s
        };
        let (s, ro) = (
            draw(&mut r, &spec(&smooth), TechniqueName::RoughnessMap, SIZE),
            draw(&mut r, &spec(&rough), TechniqueName::RoughnessMap, SIZE),
        );
        keep(&format!("roughness_smooth_{backend}"), &s);
        keep(&format!("roughness_rough_{backend}"), &ro);
        let peak = |image: &Rgba8Image| {
            image.texels.iter().map(|t| t[0] as u32 + t[1] as u32 + t[2] as u32).max().unwrap_or(0)
        };
        assert!(
            peak(&s) > peak(&ro) + 60,
            "{backend}: a smooth surface's highlight is sharper ({} vs {})",
            peak(&s),
            peak(&ro)
        );
        let apart = psnr(&s, &ro);
        assert!(apart < 30.0, "{backend}: the two roughnesses draw differently ({apart:.1} dB)");
    }
}

#[test]
fn vertex_colours_multiply_the_base_colour_on_every_pass_that_draws_it() {
    // sRGB-encoded like the decal's texels: COLOR_0 is linear light.
    let encode = |l: f32| 255.0 * (1.055 * l.powf(1.0 / 2.4) - 0.055);
    let tint = [0.2f32, 0.6, 1.0];
    let build = |colors: [[f32; 4]; 4], members: &str, base: Option<&[u8]>| {
        let mut g = in_front_of_green(r#""name":"unused""#, true);
        // The near quad again, now coloured, with a material of its own; the first is dropped.
        let t = base.map(|png| g.texture(png));
        let texture =
            t.map_or(String::new(), |t| format!(r#","pbrMetallicRoughness":{{"baseColorTexture":{{"index":{t}}}}}"#));
        let m = g.material(&format!(r#""name":"painted"{texture}{members}"#));
        let mesh = g.quad_colored(NEAR, TOWARD_Z, Some(m), colors);
        g.nodes[0] = format!(r#"{{"mesh":{mesh}}}"#);
        g
    };
    let uniform = load("colors", &build([[tint[0], tint[1], tint[2], 1.0]; 4], "", None));
    // Left corners red, right corners blue, over a decal whose red channel is 128.
    let (red, blue) = ([1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]);
    let decal = columns_png(|_| [128, 255, 255, 255]);
    let ramp = load("colors_ramp", &build([red, blue, blue, red], "", Some(&decal)));
    // Alpha 0 at the left corners, 1 at the right: the left half is cut out.
    let (clear, solid) = ([1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 1.0]);
    let cut = r#","alphaMode":"MASK","alphaCutoff":0.5"#;
    let masked = load("colors_mask", &build([clear, solid, solid, clear], cut, None));
    for (backend, mut r) in renderers() {
        for technique in [TechniqueName::SinglePass, TechniqueName::Kilgard] {
            let name = format!("{backend}_{technique:?}");
            let image = draw(&mut r, &head_on(&uniform, 0.1, 0.8), technique, SIZE);
            keep(&format!("colors_{name}"), &image);
            let want = tint.map(|c| 0.9 * encode(c));
            close(&format!("{name}: the vertex colour"), at(&image, 0), want, 2.0);
            // Two lights (kilgard's second adds decal · diffuse in a pass of its own).
            let mut two = head_on(&uniform, 0.1, 0.4);
            two.params.lights.push(two.params.lights[0].clone());
            let image = draw(&mut r, &two, technique, SIZE);
            close(&format!("{name}: two lights"), at(&image, 0), want, 3.0);

            let image = draw(&mut r, &head_on(&ramp, 0.1, 0.8), technique, SIZE);
            keep(&format!("colors_ramp_{name}"), &image);
            // The vertex colour's red and blue at a pixel, the decal's 128 in red undone.
            let weights = |p: [u8; 4]| (p[0] as f32 / 128.0, p[2] as f32 / 255.0);
            let ((lr, lb), (rr, rb)) = (weights(at(&image, -20)), weights(at(&image, 20)));
            assert!(lr > 2.0 * lb && rb > 2.0 * rr, "{name}: red to blue, ({lr}, {lb}) to ({rr}, {rb})");
            // Interpolated between the corners (in their encoded values, as GL interpolates a
            // colour array), times the decal's 128 in red.
            let mid = at(&image, 0);
            close(&format!("{name}: the ramp's middle"), mid, [0.9 * 0.5 * 128.0, 0.0, 0.9 * 0.5 * 255.0], 4.0);

            let image = draw(&mut r, &head_on(&masked, 0.1, 0.8), technique, SIZE);
            keep(&format!("colors_mask_{name}"), &image);
            close(&format!("{name}: cut where COLOR_0's alpha < 0.5"), at(&image, -16), [0.0, 0.9 * 255.0, 0.0], 2.0);
            close(&format!("{name}: kept where it is above"), at(&image, 16), [0.9 * 255.0, 0.0, 0.0], 2.0);
        }
    }
}

#[test]
fn a_look_the_specification_bounds_otherwise_is_refused_naming_the_material_and_the_value() {
    let g = occluded(Some(1.0));
    let strength = refusal("occlusion_strength", &g, |j| j.replace(r#""strength":1"#, r#""strength":2"#));
    assert!(strength.contains("occlusionTexture.strength is 2"), "{strength}");
    let member =
        |extra: &'static str| move |j: String| j.replace(r#""strength":1}"#, &format!(r#""strength":1}}{extra}"#));
    let emissive = refusal("emissive_factor", &g, member(r#","emissiveFactor":[2,0,0]"#));
    assert!(emissive.contains("emissiveFactor is [2.0, 0.0, 0.0]"), "{emissive}");
    let roughness = refusal("roughness_factor", &g, member(r#","pbrMetallicRoughness":{"roughnessFactor":-1}"#));
    assert!(roughness.contains("roughnessFactor is -1"), "{roughness}");
    let transform = refusal("occlusion_transform", &g, |j| {
        j.replace(r#""strength":1}"#, r#""strength":1,"extensions":{"KHR_texture_transform":{"scale":[1e39,1]}}}"#)
    });
    assert!(transform.contains("occlusionTexture") && transform.contains("finite"), "{transform}");
    let emissive_transform = refusal(
        "emissive_transform",
        &g,
        member(r#","emissiveTexture":{"index":0,"extensions":{"KHR_texture_transform":{"rotation":1e39}}}"#),
    );
    assert!(
        emissive_transform.contains("emissiveTexture") && emissive_transform.contains("finite"),
        "{emissive_transform}"
    );
    let missing = refusal("occlusion_missing", &g, |j| {
        let start = j.find(r#""images":[{"uri":""#).expect("an image") + r#""images":[{"uri":""#.len();
        let end = start + j[start..].find('"').expect("the URI ends");
        format!("{}missing.png{}", &j[..start], &j[end..])
    });
    assert!(missing.contains("occlusionTexture") && missing.contains("missing.png"), "{missing}");
    let mut coloured = Gltf::default();
    let mesh = coloured.quad_colored(FRONT, TOWARD_Z, None, [[1.0, f32::NAN, 0.0, 1.0]; 4]);
    coloured.node(&format!(r#""mesh":{mesh}"#));
    let nan = refusal("colour_not_finite", &coloured, |j| j);
    assert!(nan.contains("colour of vertex 0 is not finite"), "{nan}");
}
