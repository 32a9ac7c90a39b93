//! glTF files the scene tests write: quads with their own materials in a node hierarchy, every
//! buffer and image a `data:` URI, so each test's file is one JSON document.

use bumpmap::bumpmap_math::{HeightField, MipChain, MipMode, NormalMapOptions};

/// A glTF document under construction.
#[derive(Default)]
pub struct Gltf {
    bin: Vec<u8>,
    views: Vec<String>,
    accessors: Vec<String>,
    pub meshes: Vec<String>,
    pub nodes: Vec<String>,
    pub materials: Vec<String>,
    images: Vec<String>,
    /// Each texture's sampler, if any; and the samplers.
    texture_samplers: Vec<Option<usize>>,
    samplers: Vec<String>,
    /// The root nodes of the scene; every node when empty.
    pub roots: Vec<usize>,
    pub extensions_used: Vec<&'static str>,
}

impl Gltf {
    fn accessor(&mut self, data: &[u8], component: u32, count: usize, kind: &str, min_max: &str) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        self.views.push(format!(r#"{{"buffer":0,"byteOffset":{},"byteLength":{}}}"#, self.bin.len(), data.len()));
        self.bin.extend_from_slice(data);
        self.accessors.push(format!(
            r#"{{"bufferView":{},"componentType":{component},"count":{count},"type":"{kind}"{min_max}}}"#,
            self.views.len() - 1
        ));
        self.accessors.len() - 1
    }

    /// A mesh of one primitive: the quad of `corners` (counter-clockwise seen from its front)
    /// with texture coordinates (0,0) (1,0) (1,1) (0,1) at them (glTF: v down the image), its
    /// normal `normal`, with `material`. Returns the mesh index.
    pub fn quad(&mut self, corners: [[f32; 3]; 4], normal: [f32; 3], material: Option<usize>) -> usize {
        let primitive = self.quad_primitive(corners, normal, material, true);
        self.meshes.push(format!(r#"{{"primitives":[{primitive}]}}"#));
        self.meshes.len() - 1
    }

    /// [`Gltf::quad`] with `COLOR_0` (float RGBA, linear) at its corners.
    pub fn quad_colored(
        &mut self,
        corners: [[f32; 3]; 4],
        normal: [f32; 3],
        material: Option<usize>,
        colors: [[f32; 4]; 4],
    ) -> usize {
        let bytes: Vec<u8> = colors.as_flattened().iter().flat_map(|x| x.to_le_bytes()).collect();
        let c = self.accessor(&bytes, 5126, 4, "VEC4", "");
        let primitive = self.quad_primitive(corners, normal, material, true);
        let primitive = primitive.replacen(r#""NORMAL":"#, &format!(r#""COLOR_0":{c},"NORMAL":"#), 1);
        self.meshes.push(format!(r#"{{"primitives":[{primitive}]}}"#));
        self.meshes.len() - 1
    }

    /// The quad's primitive JSON (see [`Gltf::quad`]), with or without TEXCOORD_0.
    pub fn quad_primitive(
        &mut self,
        corners: [[f32; 3]; 4],
        normal: [f32; 3],
        material: Option<usize>,
        texcoords: bool,
    ) -> String {
        let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
        let (lo, hi) = corners.iter().fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
            (std::array::from_fn(|i| lo[i].min(p[i])), std::array::from_fn(|i| hi[i].max(p[i])))
        });
        let p =
            self.accessor(&floats(corners.as_flattened()), 5126, 4, "VEC3", &format!(r#","min":{lo:?},"max":{hi:?}"#));
        let n = self.accessor(&floats(&[normal; 4].concat()), 5126, 4, "VEC3", "");
        let uv = [0.0f32, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
        let t = self.accessor(&floats(&uv), 5126, 4, "VEC2", "");
        let indices: Vec<u8> = [0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()).collect();
        let i = self.accessor(&indices, 5123, 6, "SCALAR", "");
        let texcoord = if texcoords { format!(r#","TEXCOORD_0":{t}"#) } else { String::new() };
        let material = material.map_or(String::new(), |m| format!(r#","material":{m}"#));
        format!(r#"{{"attributes":{{"POSITION":{p},"NORMAL":{n}{texcoord}}},"indices":{i}{material}}}"#)
    }

    /// A node (JSON members after `"mesh"` or alone); returns its index.
    pub fn node(&mut self, members: &str) -> usize {
        self.nodes.push(format!("{{{members}}}"));
        self.nodes.len() - 1
    }

    /// A PNG image and a texture of it; returns the texture index.
    pub fn texture(&mut self, png: &[u8]) -> usize {
        self.images.push(format!(r#"{{"uri":"data:image/png;base64,{}"}}"#, base64_encode(png)));
        self.texture_samplers.push(None);
        self.images.len() - 1
    }

    /// A PNG image and a texture of it with a sampler of its own (its JSON members); returns
    /// the texture index.
    pub fn texture_sampled(&mut self, png: &[u8], sampler: &str) -> usize {
        let t = self.texture(png);
        self.samplers.push(format!("{{{sampler}}}"));
        self.texture_samplers[t] = Some(self.samplers.len() - 1);
        t
    }

    /// A material (its JSON members); returns its index.
    pub fn material(&mut self, members: &str) -> usize {
        self.materials.push(format!("{{{members}}}"));
        self.materials.len() - 1
    }

    /// The document.
    pub fn json(&self) -> String {
        let roots: Vec<usize> =
            if self.roots.is_empty() { (0..self.nodes.len()).collect() } else { self.roots.clone() };
        let list = |v: &[String]| v.join(",");
        let textures: Vec<String> = (0..self.images.len())
            .map(|i| match self.texture_samplers[i] {
                Some(s) => format!(r#"{{"source":{i},"sampler":{s}}}"#),
                None => format!(r#"{{"source":{i}}}"#),
            })
            .collect();
        // glTF wants no empty arrays (the validator's EMPTY_ENTITY): samplers, textures and images
        // only when some.
        let samplers =
            if self.samplers.is_empty() { String::new() } else { format!(r#","samplers":[{}]"#, list(&self.samplers)) };
        let images = if self.images.is_empty() {
            String::new()
        } else {
            format!(r#","textures":[{}],"images":[{}]"#, list(&textures), list(&self.images))
        };
        let used = if self.extensions_used.is_empty() {
            String::new()
        } else {
            format!(r#","extensionsUsed":{:?}"#, self.extensions_used)
        };
        format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":{roots:?}}}],"nodes":[{}],"meshes":[{}],"materials":[{}]{images}{samplers},"buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}],"bufferViews":[{}],"accessors":[{}]{used}}}"#,
            list(&self.nodes),
            list(&self.meshes),
            list(&self.materials),
            self.bin.len(),
            base64_encode(&self.bin),
            list(&self.views),
            list(&self.accessors),
        )
    }
}

/// A glTF normal texture (green up, as glTF 2.0 wants it) of the heights `h(s, t)` over a
/// `size`² texture (s right, t down the image), as PNG bytes.
pub fn normal_png(size: usize, h: impl Fn(f32, f32) -> f32) -> Vec<u8> {
    let field =
        HeightField::from_fn(size, size, |x, y| h((x as f32 + 0.5) / size as f32, (y as f32 + 0.5) / size as f32));
    let options = NormalMapOptions { scale: 6.0, ..Default::default() };
    let chain = MipChain::<[u8; 4]>::from_height(&field, &options, MipMode::LengthInAlpha).expect("normal map");
    let level = &chain.levels[0];
    // Made with green along +t (down the image); glTF's green points up.
    let rgb: Vec<u8> = level.texels.iter().flat_map(|t| [t[0], 255 - t[1], t[2]]).collect();
    let mut png = Vec::new();
    image::RgbImage::from_raw(size as u32, size as u32, rgb)
        .expect("size")
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .expect("PNG");
    png
}

/// A PNG whose red grows with the column (0 to 255 over `width` columns), green 60, blue 30.
pub fn ramp_png(width: usize) -> Vec<u8> {
    let mut png = Vec::new();
    image::RgbImage::from_fn(width as u32, 4, |x, _| image::Rgb([(x as usize * 255 / (width - 1)) as u8, 60, 30]))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .expect("PNG");
    png
}

/// A one-colour PNG.
pub fn color_png(rgb: [u8; 3]) -> Vec<u8> {
    let mut png = Vec::new();
    image::RgbImage::from_pixel(4, 4, image::Rgb(rgb))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .expect("PNG");
    png
}

fn base64_encode(bytes: &[u8]) -> String {
    base64::encode(bytes)
}

/// A 16×4 RGBA PNG whose texel in column `x` is `f(x)`.
pub fn columns_png(f: impl Fn(usize) -> [u8; 4]) -> Vec<u8> {
    let mut png = Vec::new();
    image::RgbaImage::from_fn(16, 4, |x, _| image::Rgba(f(x as usize)))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .expect("PNG");
    png
}
