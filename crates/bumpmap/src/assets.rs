//! A user's own assets, ready for a [`SceneSpec`]: a normal map file brought into texture
//! space, and a mesh file with its glTF material (normal texture with its scale, base colour as
//! the decal) and tangents (the file's, or made here).
//!
//! What this module does not do: decide between an asset and an explicit option (the caller
//! does: an explicit height field or decal replaces the material's), or parse formats (that is
//! `bumpmap-io`; texel meaning is `bumpmap_math::imported`).

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use bumpmap_core::scene::AlphaMode;
use bumpmap_core::state::{MagFilter, MaterialSampler, MinFilter, WrapMode};
use bumpmap_core::{BumpSource, MeshPart, MeshParts, PartMaterial, SceneKind, SceneSpec};
use bumpmap_io::MeshOptions;
use bumpmap_math::imported::{ImportOptions, UNIT_TOLERANCE};
use bumpmap_math::mesh::Mesh;
use bumpmap_math::tangent::{TangentOptions, generate_tangents};
use bumpmap_math::{MipMode, Rgba8Image, Rgba8Mips, YConvention};

use crate::error::Error;

mod look;
mod normal_map;

pub use normal_map::{LoadedNormalMap, given_or_load_normal_map, green_way, load_normal_map, normal_map_from_texture};

/// The fraction of texels off unit length above which a normal map gets a
/// [`Warning::NotUnitLength`]: a baked map's empty background can be a few percent; a photograph
/// is most of it.
pub const OFF_UNIT_WARNING: f32 = 0.1;

/// Something an asset loaded with, that its user should hear about.
#[derive(Clone, Debug, PartialEq)]
pub enum Warning {
    /// Many texels of a normal map are not unit vectors: perhaps not a normal map at all.
    NotUnitLength {
        /// The file (or the glTF texture).
        path: PathBuf,
        /// The fraction of level 0's texels more than `UNIT_TOLERANCE` from unit length.
        fraction: f32,
    },
    /// A normal map whose alpha held something else than the normal's length (a height or a
    /// gloss packed there): it is drawn with the length instead.
    ForeignAlpha {
        /// The file (or the glTF texture).
        path: PathBuf,
    },
    /// A normal map whose own smaller levels were renormalized (alpha 1 everywhere though
    /// level 0's normals vary): the length factor and Toksvig's filter get nothing from them.
    RenormalizedMips {
        /// The file (or the glTF texture).
        path: PathBuf,
    },
    /// Something the mesh file asked for that is not drawn.
    Ignored {
        /// The file.
        path: PathBuf,
        /// What, in words.
        what: String,
    },
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::NotUnitLength { path, fraction } => write!(
                f,
                "{}: {:.0} % of its texels are not unit vectors (their length is off by more than {UNIT_TOLERANCE}): \
                 is it a normal map? It is drawn renormalized",
                path.display(),
                100.0 * fraction
            ),
            Warning::ForeignAlpha { path } => write!(
                f,
                "{}: its alpha is not the length of the normal (it is below 1 at level 0: a height or gloss packed there?); \
                 it is drawn with the length in alpha instead",
                path.display()
            ),
            Warning::RenormalizedMips { path } => write!(
                f,
                "{}: its own mip levels were renormalized (their alpha, the length of the averaged normal, is 1 \
                 everywhere though its normals vary): the length factor and Toksvig's specular filter have \
                 nothing to work with, so the bumps stay too bright and too shiny at a distance. \
                 Let bumpmap make the levels from level 0 instead: --rebuild-mips",
                path.display()
            ),
            Warning::Ignored { path, what } => write!(f, "{}: {what}", path.display()),
        }
    }
}

/// How [`load_mesh`] reads a mesh file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshLoad {
    /// How the file itself is read (which material textures among them).
    pub mesh: MeshOptions,
    /// Replaces the material's `normalTexture.scale`.
    pub normal_scale: Option<f32>,
    /// How the material's normal map gets its smaller levels.
    pub mip_mode: MipMode,
}

impl Default for MeshLoad {
    /// Both material textures read, the file's scale, the length in alpha.
    fn default() -> Self {
        Self {
            mesh: MeshOptions { read_normal_texture: true, read_base_color_texture: true, ..Default::default() },
            normal_scale: None,
            mip_mode: MipMode::LengthInAlpha,
        }
    }
}

/// A glTF material, ready to draw.
#[derive(Clone, Debug)]
pub struct MaterialAsset {
    /// How messages name it after the word "material": `'its name'`, else its index.
    pub name: String,
    /// `normalTexture` in texture space (glTF's green is up), scaled.
    pub normal_map: Option<LoadedNormalMap>,
    /// The scale its X and Y were multiplied by.
    pub normal_scale: f32,
    /// `baseColorTexture` times `baseColorFactor`'s RGB (or the factor alone, when it is not
    /// white), as the decal, with box-filtered mipmaps; sRGB-encoded as the texture is (the
    /// renderers, like the hardware they emulate, take the decal's bytes as they are). Its
    /// alpha is the texture's, times the factor's for a cut-out or blended material.
    pub decal: Option<Arc<Rgba8Mips>>,
    /// Where the decal came from, in words.
    pub decal_source: Option<String>,
    /// The texture-coordinate set the mesh was read with.
    pub tex_coord: u32,
    /// `doubleSided`: its parts' back faces are drawn, lit from their own side.
    pub double_sided: bool,
    /// The `KHR_texture_transform` applied to its parts' texture coordinates, if any.
    pub texture_transform: Option<bumpmap_io::TextureTransform>,
    /// Its textures' wrap modes, and filters where the file names them.
    pub sampler: MaterialSampler,
    /// `alphaMode` with its cutoff.
    pub alpha: AlphaMode,
    /// `occlusionTexture` with its strength folded in: what multiplies the ambient term.
    pub occlusion: Option<Arc<Rgba8Mips>>,
    /// `emissiveTexture · emissiveFactor`, added to the lit colour.
    pub emission: Option<Arc<Rgba8Mips>>,
    /// `metallicRoughnessTexture`'s roughness at the normal map's size, for the roughness-map
    /// filter.
    pub roughness_map: Option<Arc<Rgba8Mips>>,
}

/// One glTF primitive of one node, ready to draw.
#[derive(Clone, Debug)]
pub struct PartAsset {
    /// Its geometry with tangents; a double-sided material's back faces are copies of its
    /// triangles wound the other way, with the normal and the tangent frame reversed.
    pub mesh: Arc<Mesh>,
    /// An index into [`MeshAsset::materials`], or `None` for glTF's default material.
    pub material: Option<usize>,
    /// Whether it has the texture coordinates its material reads (without, it is drawn
    /// unbumped and untextured).
    pub textured: bool,
}

/// A mesh file, ready to draw.
#[derive(Clone, Debug)]
pub struct MeshAsset {
    /// The whole mesh, in the file's own units and axes, with tangents.
    pub mesh: Arc<Mesh>,
    /// Whether the tangents are the file's (glTF's TANGENT) or were made here.
    pub tangents_from_file: bool,
    /// Whether the normals are the file's or were made from the faces.
    pub normals_from_file: bool,
    /// The glTF materials the parts draw with.
    pub materials: Vec<MaterialAsset>,
    /// The glTF primitives, each with its own material; empty for a file without materials
    /// (an OBJ), which is drawn as one mesh with the scene's bumps.
    pub parts: Vec<PartAsset>,
    /// Every file read (the mesh, its buffers and images): no output may replace one.
    pub sources: Vec<PathBuf>,
    /// What the file asked for that is not drawn, and maps that look wrong.
    pub warnings: Vec<Warning>,
}

impl MeshAsset {
    /// The scene as the file describes it: each part with its material's normal map (none, no
    /// bumps: a material without a `normalTexture` is flat) and base colour. A file without a
    /// material keeps the default bumps (the paper's bricks) so that bump mapping shows.
    pub fn spec(&self) -> SceneSpec {
        let mut spec = SceneSpec::new(SceneKind::Mesh(self.mesh.clone()));
        if self.parts.is_empty() {
            return spec;
        }
        let flat = || BumpSource::flat_map(1, 1);
        let mut materials: Vec<PartMaterial> = self
            .materials
            .iter()
            .map(|m| PartMaterial {
                name: m.name.clone(),
                bumps: Some(m.normal_map.as_ref().map_or_else(flat, LoadedNormalMap::bumps)),
                decal: m.decal.clone(),
                sampler: m.sampler,
                alpha: m.alpha,
                occlusion: m.occlusion.clone(),
                emission: m.emission.clone(),
                roughness_map: m.roughness_map.clone(),
            })
            .collect();
        // glTF's default material, and each material without texture coordinates to read its
        // maps with: no bumps, and only maps of one texel (the base colour and emissive factors).
        let mut plain: Vec<Option<usize>> = vec![None; self.materials.len() + 1];
        let parts = self
            .parts
            .iter()
            .map(|part| {
                let material = match (part.material, part.textured) {
                    (Some(m), true) => m,
                    (m, _) => {
                        let slot = m.unwrap_or(self.materials.len());
                        *plain[slot].get_or_insert_with(|| {
                            let one_texel = |d: &Arc<Rgba8Mips>| d.levels()[0].width == 1 && d.levels()[0].height == 1;
                            let own = m.map(|m| &self.materials[m]);
                            let decal = own.and_then(|m| m.decal.clone()).filter(one_texel);
                            let name = own.map_or("(default)".into(), |m| m.name.clone());
                            materials.push(PartMaterial {
                                name,
                                bumps: Some(flat()),
                                decal,
                                sampler: Default::default(),
                                alpha: own.map_or(AlphaMode::Opaque, |m| m.alpha),
                                occlusion: None,
                                emission: own.and_then(|m| m.emission.clone()).filter(one_texel),
                                roughness_map: None,
                            });
                            materials.len() - 1
                        })
                    }
                };
                MeshPart { mesh: part.mesh.clone(), material }
            })
            .collect();
        // The scene's own bumps are the first normal map's (what a technique's requirements and
        // an explicit option's notes look at); its decal is none.
        spec.params.bumps =
            self.materials.iter().find_map(|m| m.normal_map.as_ref()).map_or_else(flat, LoadedNormalMap::bumps);
        spec.params.default_decal = false;
        spec.params.parts = Some(Arc::new(MeshParts { materials, parts }));
        spec
    }

    /// How many parts draw without bumps (no `normalTexture`, or no texture coordinates).
    pub fn unbumped_parts(&self) -> usize {
        self.parts
            .iter()
            .filter(|p| !p.textured || p.material.is_none_or(|m| self.materials[m].normal_map.is_none()))
            .count()
    }

    /// Which of the file's parts are drawn, a line each, for the user.
    pub fn describe(&self) -> Vec<String> {
        let mut lines = vec![format!(
            "{} triangles; tangents: {}; normals: {}",
            self.mesh.triangle_count(),
            if self.tangents_from_file { "the file's TANGENT attribute" } else { "generated (the file has none)" },
            if self.normals_from_file { "the file's" } else { "computed from the faces (the file has none)" }
        )];
        if self.parts.len() > 1 || self.materials.len() > 1 {
            lines.push(format!(
                "{} primitive(s) drawn with {} material(s); {} of them unbumped (no normalTexture or no texture coordinates)",
                self.parts.len(),
                self.materials.len(),
                self.unbumped_parts()
            ));
        }
        // Every material of a small file; of a large one the first few and a count.
        const LISTED: usize = 4;
        let listed = if self.materials.len() > LISTED + 1 { LISTED } else { self.materials.len() };
        for m in &self.materials[..listed] {
            lines.push(match &m.normal_map {
                Some(map) => format!(
                    "material {}: normalTexture {} (scale {}, TEXCOORD_{}) as the normal map",
                    m.name,
                    map.describe(),
                    m.normal_scale,
                    m.tex_coord
                ),
                None => format!(
                    "material {}: its normalTexture is not used (it has none, or an option replaced it)",
                    m.name
                ),
            });
            lines.push(match &m.decal_source {
                Some(d) => format!("material {}: {d} as the decal", m.name),
                None => format!(
                    "material {}: its baseColorTexture is not used (it has none, or an option replaced it)",
                    m.name
                ),
            });
            if m.double_sided {
                lines.push(format!("material {}: double-sided, back faces lit from their own side", m.name));
            }
            if m.sampler != MaterialSampler::default() {
                let s = &m.sampler;
                lines.push(format!(
                    "material {}: its sampler wraps {:?} × {:?}, filters {} / {}",
                    m.name,
                    s.wrap_s,
                    s.wrap_t,
                    s.min.map_or("the technique's".to_string(), |f| format!("{f:?}")),
                    s.mag.map_or("the technique's".to_string(), |f| format!("{f:?}"))
                ));
            }
            match m.alpha {
                AlphaMode::Opaque => {}
                AlphaMode::Mask { cutoff } => {
                    lines.push(format!("material {}: alphaMode MASK, cut out where alpha < {cutoff}", m.name))
                }
                AlphaMode::Blend => lines.push(format!(
                    "material {}: alphaMode BLEND, blended over what is behind (by single-pass techniques; \
                     the multipass ones draw it opaque)",
                    m.name
                )),
            }
            for (map, what) in [
                (&m.occlusion, "occlusionTexture on the ambient term"),
                (&m.emission, "emission added"),
                (&m.roughness_map, "metallicRoughnessTexture's roughness for the roughness-map filter"),
            ] {
                if map.is_some() {
                    lines.push(format!("material {}: {what}", m.name));
                }
            }
            if let Some(t) = &m.texture_transform {
                lines.push(format!(
                    "material {}: KHR_texture_transform applied (offset {:?}, rotation {} rad, scale {:?})",
                    m.name,
                    t.offset.to_array(),
                    t.rotation,
                    t.scale.to_array()
                ));
            }
        }
        if listed < self.materials.len() {
            let rest = &self.materials[listed..];
            lines.push(format!(
                "and {} more materials: {} with a normalTexture, {} with a base colour, {} double-sided, {} with a KHR_texture_transform, \
                 {} cut out or blended, {} emissive, {} with occlusion",
                rest.len(),
                rest.iter().filter(|m| m.normal_map.is_some()).count(),
                rest.iter().filter(|m| m.decal.is_some()).count(),
                rest.iter().filter(|m| m.double_sided).count(),
                rest.iter().filter(|m| m.texture_transform.is_some()).count(),
                rest.iter().filter(|m| m.alpha != AlphaMode::Opaque).count(),
                rest.iter().filter(|m| m.emission.is_some()).count(),
                rest.iter().filter(|m| m.occlusion.is_some()).count()
            ));
        }
        lines
    }
}

/// An sRGB-encoded byte as linear light in [0, 1].
fn srgb_decode(b: u8) -> f32 {
    let c = b as f32 / 255.0;
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// Linear light as an sRGB-encoded byte (clamped to [0, 1]).
fn srgb_encode(l: f32) -> u8 {
    (srgb_encode_unit(l) * 255.0).round() as u8
}

/// Linear light (clamped to [0, 1]) sRGB-encoded, in [0, 1].
fn srgb_encode_unit(l: f32) -> f32 {
    let l = l.clamp(0.0, 1.0);
    if l <= 0.0031308 { l * 12.92 } else { 1.055 * l.powf(1.0 / 2.4) - 0.055 }
}

/// Loads a mesh file (OBJ, glTF, GLB) with tangents, and a glTF's material as `options` ask.
pub fn load_mesh(path: &Path, options: &MeshLoad) -> Result<MeshAsset, Error> {
    mesh_asset(bumpmap_io::load_mesh_with(path, &options.mesh)?, path, options)
}

/// A mesh already read (`path` names it in messages) made ready to draw as [`load_mesh`] makes
/// it: tangents where it has none, its material's normal map in texture space and its base
/// colour as the decal.
pub fn mesh_asset(mut loaded: bumpmap_io::LoadedMesh, path: &Path, options: &MeshLoad) -> Result<MeshAsset, Error> {
    // A glTF none of whose primitives has texture coordinates is drawn as one with some draws
    // the primitives without: unbumped and untextured (as three.js does), not refused.
    let no_texcoords = loaded.mesh.texcoords.is_empty() && !loaded.parts.is_empty();
    if no_texcoords {
        loaded.mesh.texcoords = vec![glam::Vec2::ZERO; loaded.mesh.positions.len()];
        loaded.notes.push("no primitive has texture coordinates: every one is drawn unbumped and untextured".into());
    }
    let mesh = if loaded.had_tangents {
        loaded.mesh
    } else {
        generate_tangents(&loaded.mesh, &TangentOptions::default())
            .map_err(|e| bumpmap_io::IoError::Mesh { path: path.to_path_buf(), reason: e.to_string() })?
            .0
    };
    // COLOR_0 is linear light; it multiplies the decal, whose texels (like the framebuffer) are
    // sRGB-encoded, so it is encoded the same way (as the base colour factor is).
    let mut mesh = mesh;
    for c in &mut mesh.colors {
        *c = glam::Vec4::new(srgb_encode_unit(c.x), srgb_encode_unit(c.y), srgb_encode_unit(c.z), c.w.clamp(0.0, 1.0));
    }
    let mut warnings: Vec<Warning> =
        loaded.notes.iter().map(|what| Warning::Ignored { path: path.to_path_buf(), what: what.clone() }).collect();
    let mut materials = Vec::with_capacity(loaded.materials.len());
    // Maps shared by several materials are imported once.
    let mut imported: Vec<(usize, f32, LoadedNormalMap)> = Vec::new();
    for m in &loaded.materials {
        materials.push(material_asset(m, path, options, &mut imported, &mut warnings)?);
    }
    let mesh = Arc::new(mesh);
    let parts = split_parts(&mesh, &loaded.parts, &materials);
    if parts.is_empty() {
        materials.clear();
    }
    Ok(MeshAsset {
        mesh,
        tangents_from_file: loaded.had_tangents,
        normals_from_file: loaded.had_normals,
        materials,
        parts,
        sources: loaded.sources,
        warnings,
    })
}

/// A glTF sampler's GL enums as sampler state (the glTF reader has refused any value glTF does
/// not allow, so the defaults below are never reached from a file).
fn material_sampler(s: &bumpmap_io::TextureSampler) -> MaterialSampler {
    MaterialSampler {
        wrap_s: WrapMode::from_gl(s.wrap_s).unwrap_or(WrapMode::Repeat),
        wrap_t: WrapMode::from_gl(s.wrap_t).unwrap_or(WrapMode::Repeat),
        min: s.min_filter.and_then(MinFilter::from_gl),
        mag: s.mag_filter.and_then(MagFilter::from_gl),
    }
}

/// The parts' own meshes cut from `mesh` (the whole mesh, shared, where one part is all of it
/// and single-sided), with a double-sided material's back faces added; none without materials.
fn split_parts(mesh: &Arc<Mesh>, parts: &[bumpmap_io::MeshPart], materials: &[MaterialAsset]) -> Vec<PartAsset> {
    if materials.is_empty() {
        return Vec::new();
    }
    let double_sided = |p: &bumpmap_io::MeshPart| p.material.is_some_and(|m| materials[m].double_sided);
    if let [only] = parts
        && only.triangles == (0..mesh.indices.len())
        && !double_sided(only)
    {
        return vec![PartAsset { mesh: mesh.clone(), material: only.material, textured: only.textured }];
    }
    parts
        .iter()
        .map(|p| {
            let triangles = &mesh.indices[p.triangles.clone()];
            let mut part = mesh.submesh(triangles);
            if double_sided(p) {
                part.add_back_faces();
            }
            PartAsset { mesh: Arc::new(part), material: p.material, textured: p.textured }
        })
        .collect()
}

/// A glTF material made ready to draw: its normal texture imported (once per image and scale,
/// `imported` remembers), its base colour tinted by the factor as the decal.
fn material_asset(
    m: &bumpmap_io::MeshMaterial,
    path: &Path,
    options: &MeshLoad,
    imported: &mut Vec<(usize, f32, LoadedNormalMap)>,
    warnings: &mut Vec<Warning>,
) -> Result<MaterialAsset, Error> {
    let normal_scale = options.normal_scale.unwrap_or_else(|| m.normal.as_ref().map_or(1.0, |n| n.scale));
    // The file's own scale out of range is the glTF's fault, not the image's.
    if options.normal_scale.is_none()
        && !(normal_scale.is_finite() && normal_scale.abs() <= bumpmap_math::imported::MAX_SCALE)
    {
        return Err(Error::Io(bumpmap_io::IoError::Mesh {
            path: path.to_path_buf(),
            reason: format!(
                "material {}'s normalTexture.scale is {normal_scale}; it must be a number in [-{1}, {1}]",
                m.name,
                bumpmap_math::imported::MAX_SCALE
            ),
        }));
    }
    let normal_map = match &m.normal {
        Some(t) => match imported.iter().find(|(image, scale, _)| *image == t.image && *scale == normal_scale) {
            Some((_, _, map)) => Some(map.clone()),
            None => {
                // glTF's normal textures are green up ("+Y is up").
                let import_options = ImportOptions {
                    y_convention: YConvention::YUp,
                    scale: normal_scale,
                    mip_mode: options.mip_mode,
                    rebuild_mips: false,
                };
                let map = normal_map_from_texture(&t.texture, &t.source, &import_options)?;
                warnings.extend(map.warnings());
                imported.push((t.image, normal_scale, map.clone()));
                Some(map)
            }
        },
        None => None,
    };
    // glTF: the texture is sRGB-encoded and the factor linear; their product is stored
    // sRGB-encoded again, so the decal's bytes look as the file's viewer shows them.
    let factor = m.base_color_factor;
    if factor[..3].iter().any(|c| !(0.0..=1.0).contains(c)) {
        warnings.push(Warning::Ignored {
            path: path.to_path_buf(),
            what: format!(
                "material {}'s baseColorFactor {:?} is outside [0, 1] (glTF 2.0 bounds each component): drawn clamped",
                m.name,
                &factor[..3]
            ),
        });
    }
    let alpha = m.alpha_mode;
    // Alpha is linear; an opaque material's is left as the texture has it (a gloss, say).
    let alpha_factor = if alpha == AlphaMode::Opaque { 1.0 } else { factor[3].clamp(0.0, 1.0) };
    let tint = |t: [u8; 4]| {
        let c = |i: usize| srgb_encode(srgb_decode(t[i]) * factor[i]);
        [c(0), c(1), c(2), (t[3] as f32 * alpha_factor).round() as u8]
    };
    let (decal, decal_source) = match &m.base_color {
        Some(t) => {
            let levels: Vec<Rgba8Image> = (&t.texture.levels).into();
            let level0 = &levels[0];
            // The tinted copy and its mipmaps, before either is made.
            let texels = level0.width as u64 * level0.height as u64;
            bumpmap_math::buffer::ensure_available(texels * 4 + texels * 4 * 4 / 3, "the decal and its mipmaps")
                .map_err(|source| Error::OutOfMemory { what: t.source.display().to_string(), source })?;
            let image = Rgba8Image::new(level0.width, level0.height, level0.texels.iter().map(|&t| tint(t)).collect());
            let what = format!("baseColorTexture {}x{} from {}", image.width, image.height, t.source.display());
            (Some(Arc::new(Rgba8Mips::with_box_mipmaps(image))), Some(what))
        }
        None if factor[..3] != [1.0; 3] || alpha_factor != 1.0 => {
            let image = Rgba8Image::new(1, 1, vec![tint([255; 4])]);
            (Some(Arc::new(Rgba8Mips::single(image))), Some(format!("baseColorFactor {factor:?}")))
        }
        None => (None, None),
    };
    // The roughness the roughness-map filter reads with the normal map's coordinates and levels.
    let roughness_map = match &m.metallic_roughness {
        Some(t) => {
            let size = normal_map.as_ref().map_or((1, 1), |n| (n.chain.levels[0].width, n.chain.levels[0].height));
            Some(look::roughness_map(t, m.roughness_factor, size)?)
        }
        None => None,
    };
    Ok(MaterialAsset {
        name: m.name.clone(),
        normal_map,
        normal_scale,
        decal,
        decal_source,
        tex_coord: m.tex_coord,
        double_sided: m.double_sided,
        texture_transform: m.texture_transform,
        sampler: material_sampler(&m.sampler),
        alpha,
        occlusion: m.occlusion.as_ref().map(look::occlusion_map).transpose()?,
        emission: look::emission_map(m.emissive.as_ref(), m.emissive_factor)?,
        roughness_map,
    })
}
