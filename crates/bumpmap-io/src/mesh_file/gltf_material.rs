//! A glTF material as far as this crate reads it: which texture-coordinate set and
//! `KHR_texture_transform` the mesh is read with, the checks the specification asks of the
//! material's values, its textures decoded, and what it asks for that is not drawn, in words.
//!
//! What this module does not do: apply a material (the renderers do), or read the mesh.

use std::path::Path;

use bumpmap_math::mesh::AlphaMode;
use glam::Vec2;

use super::{MaterialTexture, MeshMaterial, MeshOptions, TextureSampler, TextureTransform, mesh_err};
use crate::error::IoError;

impl TextureTransform {
    /// `KHR_texture_transform`'s `uv' = T·R·S·uv`, with `R = [[cos r, sin r], [−sin r, cos r]]`
    /// (the extension's README, r in radians, counter-clockwise in the image as displayed).
    ///
    /// ```
    /// use bumpmap_io::mesh_file::TextureTransform;
    /// let quarter = TextureTransform { rotation: std::f32::consts::FRAC_PI_2, ..Default::default() };
    /// let uv = quarter.apply(glam::Vec2::new(1.0, 0.0));
    /// assert!((uv - glam::Vec2::new(0.0, -1.0)).length() < 1e-6);
    /// ```
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        let (sin, cos) = self.rotation.sin_cos();
        let s = uv * self.scale;
        Vec2::new(cos * s.x + sin * s.y, -sin * s.x + cos * s.y) + self.offset
    }

    /// Whether it changes nothing (the extension absent, or all defaults).
    pub fn is_identity(&self) -> bool {
        self.offset == Vec2::ZERO && self.rotation == 0.0 && self.scale == Vec2::ONE
    }

    /// Whether it turns or mirrors texture space (so tangents made for the untransformed
    /// coordinates no longer follow the texture's +s).
    pub fn turns_or_mirrors(&self) -> bool {
        self.rotation.rem_euclid(std::f32::consts::TAU) != 0.0 || self.scale.x < 0.0 || self.scale.y < 0.0
    }
}

/// How a texture reference reads the mesh: its `texCoord` and its `KHR_texture_transform`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct TextureRead {
    pub set: u32,
    pub transform: TextureTransform,
}

/// The `KHR_texture_transform` in a texture reference's `extensions` (a JSON object), checked.
fn transform_of(
    path: &Path,
    what: &str,
    value: Option<&gltf::json::Value>,
) -> Result<Option<TextureTransform>, IoError> {
    let Some(value) = value else { return Ok(None) };
    let bad = |reason: String| mesh_err(path, format!("{what}: KHR_texture_transform {reason}"));
    let numbers = |key: &str, n: usize, default: f32| -> Result<Vec<f32>, IoError> {
        match value.get(key) {
            None => Ok(vec![default; n]),
            Some(v) => {
                let list: Vec<f32> = match v {
                    gltf::json::Value::Array(items) => {
                        items.iter().filter_map(|x| x.as_f64()).map(|x| x as f32).collect()
                    }
                    other => other.as_f64().map(|x| vec![x as f32]).unwrap_or_default(),
                };
                if list.len() != n {
                    return Err(bad(format!("{key} is {v}; it must be {n} number(s)")));
                }
                if let Some(x) = list.iter().find(|x| !x.is_finite()) {
                    return Err(bad(format!("{key} holds {x}; it must be finite")));
                }
                Ok(list)
            }
        }
    };
    let offset = numbers("offset", 2, 0.0)?;
    let rotation = numbers("rotation", 1, 0.0)?;
    let scale = numbers("scale", 2, 1.0)?;
    let tex_coord = match value.get("texCoord") {
        None => None,
        Some(v) => Some(
            v.as_u64().filter(|&n| n < 16).ok_or_else(|| bad(format!("texCoord is {v}; it must be a set index")))?
                as u32,
        ),
    };
    Ok(Some(TextureTransform {
        offset: Vec2::new(offset[0], offset[1]),
        rotation: rotation[0],
        scale: Vec2::new(scale[0], scale[1]),
        tex_coord,
    }))
}

const KHR: &str = "KHR_texture_transform";

/// The set and transform each texture of `material` reads, keyed by the texture's role.
pub(crate) struct MaterialReads {
    pub normal: Option<TextureRead>,
    pub base_color: Option<TextureRead>,
    /// The other textures of its look, by their names in the file: they are drawn as the base
    /// colour is.
    pub others: Vec<(&'static str, TextureRead)>,
}

/// The texture references' sets and transforms, with the transforms checked.
pub(crate) fn reads(path: &Path, doc: &gltf::Document, material: &gltf::Material) -> Result<MaterialReads, IoError> {
    let name = material_name(material);
    let json = material.index().and_then(|i| doc.as_json().materials.get(i));
    // The gltf crate keeps a normalTexture's and an occlusionTexture's extensions as JSON.
    let json_read = |role: &str, tex_coord: u32, transform: Option<&gltf::json::Value>| {
        let what = format!("material {name}'s {role}");
        let t = transform_of(path, &what, transform)?;
        Ok::<_, IoError>(read_of(tex_coord, t))
    };
    let normal = match (material.normal_texture(), json.and_then(|m| m.normal_texture.as_ref())) {
        (Some(n), Some(j)) => {
            Some(json_read("normalTexture", n.tex_coord(), j.extensions.as_ref().and_then(|e| e.others.get(KHR)))?)
        }
        _ => None,
    };
    let info_read = |role: &str, info: &gltf::texture::Info| {
        let what = format!("material {name}'s {role}");
        let t = info.texture_transform().map(|t| TextureTransform {
            offset: Vec2::from(t.offset()),
            rotation: t.rotation(),
            scale: Vec2::from(t.scale()),
            tex_coord: t.tex_coord(),
        });
        if let Some(t) = &t
            && !(t.offset.is_finite() && t.rotation.is_finite() && t.scale.is_finite())
        {
            return Err(mesh_err(path, format!("{what}: KHR_texture_transform {}: it must be finite", describe(t))));
        }
        Ok(read_of(info.tex_coord(), t))
    };
    let pbr = material.pbr_metallic_roughness();
    let base_color = pbr.base_color_texture().map(|i| info_read("baseColorTexture", &i)).transpose()?;
    let mut others = Vec::new();
    if let (Some(o), Some(j)) = (material.occlusion_texture(), json.and_then(|m| m.occlusion_texture.as_ref())) {
        others.push((
            "occlusionTexture",
            json_read("occlusionTexture", o.tex_coord(), j.extensions.as_ref().and_then(|e| e.others.get(KHR)))?,
        ));
    }
    if let Some(i) = material.emissive_texture() {
        others.push(("emissiveTexture", info_read("emissiveTexture", &i)?));
    }
    if let Some(i) = pbr.metallic_roughness_texture() {
        others.push(("metallicRoughnessTexture", info_read("metallicRoughnessTexture", &i)?));
    }
    Ok(MaterialReads { normal, base_color, others })
}

fn read_of(tex_coord: u32, transform: Option<TextureTransform>) -> TextureRead {
    let transform = transform.unwrap_or_default();
    TextureRead { set: transform.tex_coord.unwrap_or(tex_coord), transform }
}

/// The material's name for messages, after the word "material": `'name'`, its index, or
/// `(default)` for glTF's default material.
pub(crate) fn material_name(m: &gltf::Material) -> String {
    match (m.name(), m.index()) {
        (Some(n), _) => format!("'{n}'"),
        (None, Some(i)) => i.to_string(),
        (None, None) => "(default)".into(),
    }
}

/// Checks what the specification bounds to [0, 1] and is drawn (`alphaCutoff`, the occlusion's
/// `strength`, `emissiveFactor`, `roughnessFactor`) and returns what the material asks for that
/// is not drawn.
pub(crate) fn check(path: &Path, material: &gltf::Material) -> Result<Vec<&'static str>, IoError> {
    let pbr = material.pbr_metallic_roughness();
    let emissive = material.emissive_factor();
    let bounded = [
        ("alphaCutoff", material.alpha_cutoff()),
        ("occlusionTexture.strength", material.occlusion_texture().map(|o| o.strength())),
        ("emissiveFactor", emissive.into_iter().find(|c| !(0.0..=1.0).contains(c))),
        ("pbrMetallicRoughness.roughnessFactor", Some(pbr.roughness_factor())),
    ];
    for (what, value) in bounded {
        if let Some(v) = value
            && !(0.0..=1.0).contains(&v)
        {
            let name = material_name(material);
            let v = if what == "emissiveFactor" { format!("{emissive:?}") } else { v.to_string() };
            return Err(mesh_err(path, format!("material {name}'s {what} is {v}; glTF 2.0 wants it in [0, 1]")));
        }
    }
    let mut left_out = Vec::new();
    if pbr.metallic_roughness_texture().is_some() && pbr.metallic_factor() > 0.0 {
        left_out.push("metalness (metallicRoughnessTexture's blue: reflections of an environment)");
    }
    Ok(left_out)
}

/// Reads the textures `options` asks for of `material`; `set` is the texture-coordinate set
/// the mesh was read with for it.
pub(crate) fn read(
    path: &Path,
    file: &mut crate::gltf_read::GltfFile,
    material: &gltf::Material,
    reads: &MaterialReads,
    set: u32,
    options: &MeshOptions,
    notes: &mut Vec<String>,
) -> Result<MeshMaterial, IoError> {
    let texture = |file: &mut crate::gltf_read::GltfFile, texture: gltf::Texture, what: &str, scale: f32| {
        let image = texture.source();
        let what = format!("{what} (image {})", image.index());
        // Errors name the glTF and the texture, then the image file's own error.
        let named = |e: IoError| match e {
            IoError::Mesh { .. } => e,
            other => mesh_err(path, format!("{what}: {other}")),
        };
        let (bytes, source) = file.image_bytes(path, &image, &what).map_err(named)?;
        let limits = crate::image_file::DecodeLimits::default();
        let decoded = crate::texture_read::read_texture(&bytes, &source, &limits).map_err(named)?;
        Ok::<_, IoError>(MaterialTexture { texture: decoded, scale, source, image: image.index() })
    };
    let normal = match material.normal_texture() {
        Some(n) if options.read_normal_texture => Some(texture(file, n.texture(), "normalTexture", n.scale())?),
        _ => None,
    };
    let pbr = material.pbr_metallic_roughness();
    let base_color = match pbr.base_color_texture() {
        Some(c) if options.read_base_color_texture => Some(texture(file, c.texture(), "baseColorTexture", 1.0)?),
        _ => None,
    };
    // Occlusion, emission and roughness are the material's whatever replaces its base colour
    // (`--decal` speaks of the base colour alone): a decal given draws with the file's glow.
    let occlusion = match material.occlusion_texture() {
        Some(o) => Some(texture(file, o.texture(), "occlusionTexture", o.strength())?),
        None => None,
    };
    let emissive = match material.emissive_texture() {
        Some(e) => Some(texture(file, e.texture(), "emissiveTexture", 1.0)?),
        None => None,
    };
    let metallic_roughness = match pbr.metallic_roughness_texture() {
        Some(t) => Some(texture(file, t.texture(), "metallicRoughnessTexture", 1.0)?),
        None => None,
    };
    let alpha_mode = match material.alpha_mode() {
        gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
        gltf::material::AlphaMode::Mask => AlphaMode::Mask { cutoff: material.alpha_cutoff().unwrap_or(0.5) },
        gltf::material::AlphaMode::Blend => AlphaMode::Blend,
    };
    let transform = |r: Option<TextureRead>| r.map(|r| r.transform).filter(|t| !t.is_identity());
    let sampler_of = |t: gltf::Texture| {
        let s = t.sampler();
        TextureSampler {
            wrap_s: s.wrap_s().as_gl_enum(),
            wrap_t: s.wrap_t().as_gl_enum(),
            mag_filter: s.mag_filter().map(|f| f.as_gl_enum()),
            min_filter: s.min_filter().map(|f| f.as_gl_enum()),
        }
    };
    let normal_sampler =
        material.normal_texture().filter(|_| options.read_normal_texture).map(|n| sampler_of(n.texture()));
    let color_sampler =
        pbr.base_color_texture().filter(|_| options.read_base_color_texture).map(|c| sampler_of(c.texture()));
    if let (Some(n), Some(c)) = (normal_sampler, color_sampler)
        && n != c
    {
        notes.push(format!(
            "material {}: the baseColorTexture's sampler differs from the normalTexture's; both are drawn with the normalTexture's",
            material_name(material)
        ));
    }
    Ok(MeshMaterial {
        name: material_name(material),
        normal,
        base_color,
        base_color_factor: pbr.base_color_factor(),
        tex_coord: set,
        double_sided: material.double_sided(),
        texture_transform: if options.read_normal_texture && reads.normal.is_some() {
            transform(reads.normal)
        } else {
            transform(reads.base_color)
        },
        sampler: normal_sampler.or(color_sampler).unwrap_or_default(),
        alpha_mode,
        occlusion,
        emissive,
        emissive_factor: material.emissive_factor(),
        metallic_roughness,
        roughness_factor: pbr.roughness_factor(),
    })
}

/// The set and transform the mesh is read with for `reads`: the normal texture's when it is
/// read, else the base colour's when that is read, else the first other texture's, else set 0
/// untransformed; and a note naming every texture that would have read the mesh otherwise.
pub(crate) fn mesh_read(reads: &MaterialReads, options: &MeshOptions, name: &str) -> (TextureRead, Option<String>) {
    let normal = reads.normal.filter(|_| options.read_normal_texture);
    let color = reads.base_color.filter(|_| options.read_base_color_texture);
    let others: &[(&'static str, TextureRead)] = &reads.others;
    let (chosen_role, chosen) = match (normal, color, others.first()) {
        (Some(n), _, _) => ("normalTexture", n),
        (None, Some(c), _) => ("baseColorTexture", c),
        (None, None, Some(&(role, r))) => (role, r),
        (None, None, None) => ("", TextureRead::default()),
    };
    // Every other texture read is drawn as the chosen one: say which read otherwise.
    let mut differing: Vec<(&str, TextureRead)> = Vec::new();
    if let (Some(_), Some(c)) = (normal, color) {
        differing.push(("baseColorTexture", c));
    }
    differing.extend(others.iter().copied());
    differing.retain(|(_, r)| *r != chosen);
    let note = (!differing.is_empty()).then(|| {
        let each: Vec<String> = differing
            .iter()
            .map(|(role, r)| format!("the {role} reads TEXCOORD_{} {}", r.set, describe(&r.transform)))
            .collect();
        format!(
            "material {name}: {}, the {chosen_role} TEXCOORD_{} {}; all are drawn as the {chosen_role} reads",
            each.join(", "),
            chosen.set,
            describe(&chosen.transform)
        )
    });
    (chosen, note)
}

/// A transform in words, for notes.
pub(crate) fn describe(t: &TextureTransform) -> String {
    if t.is_identity() {
        "untransformed".into()
    } else {
        format!(
            "through KHR_texture_transform (offset {:?}, rotation {} rad, scale {:?})",
            t.offset.to_array(),
            t.rotation,
            t.scale.to_array()
        )
    }
}
