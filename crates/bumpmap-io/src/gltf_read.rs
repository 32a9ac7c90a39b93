//! Reading a glTF or GLB file without trusting it: the GLB header and chunk lengths checked
//! before anything is allocated, buffers read only from `data:` URIs, the GLB's own chunk, or
//! regular files inside the glTF's own folder — at most `byteLength` bytes each — and every
//! accessor the mesh loader reads checked for its component type, shape and byte range, so the
//! `gltf` crate's reader never indexes out of bounds.
//!
//! Images (a material's textures) are read on request ([`GltfFile::image_bytes`]) under the
//! same rules: a `data:` URI, a buffer view, or a regular file inside the glTF's folder.
//!
//! Not read: sparse accessors (refused), files outside the glTF's folder (refused; a URI with
//! `..`, an absolute path, a scheme such as `file://`, or a link that leads out).

use std::io::Read as _;
use std::path::{Component, Path, PathBuf};

use gltf::accessor::{DataType, Dimensions};

use crate::error::IoError;

/// The largest glTF, GLB or buffer file read, in bytes.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

fn err(path: &Path, reason: impl std::fmt::Display) -> IoError {
    IoError::Mesh { path: path.to_path_buf(), reason: reason.to_string() }
}

/// A parsed document and its buffers' bytes (each exactly its `byteLength`).
pub(crate) struct GltfFile<'a> {
    pub document: gltf::Document,
    pub buffers: Vec<Vec<u8>>,
    /// The buffer (and image) files read besides the glTF itself.
    pub files: Vec<PathBuf>,
    /// Where its files may come from.
    files_from: BufferFiles<'a>,
}

/// Where a glTF's buffer and image files may come from.
#[derive(Clone, Copy, Debug)]
pub(crate) enum BufferFiles<'a> {
    /// Nowhere: the glTF was read from memory; only `data:` URIs and the GLB chunk.
    None,
    /// Files inside `dir` (the glTF's folder), or anywhere if `allow_outside`.
    Folder { dir: &'a Path, allow_outside: bool },
}

impl GltfFile<'_> {
    /// The bytes of `image` (`what` names it in messages, e.g. `normalTexture (image 0)`), and
    /// a name for the file they came from: the image's own file, or the glTF with the image's
    /// index for a buffer view or a `data:` URI.
    pub fn image_bytes(&mut self, path: &Path, image: &gltf::Image, what: &str) -> Result<(Vec<u8>, PathBuf), IoError> {
        let embedded = PathBuf::from(format!("{} ({what})", path.display()));
        // The JSON, not `Image::source`: that unwraps a mimeType the gltf crate's validation
        // does not insist on (a buffer-view image without one made it panic).
        let json = &self.document.as_json().images[image.index()];
        match (json.buffer_view, json.uri.as_deref()) {
            (Some(index), _) => {
                let view = self.document.views().nth(index.value()).ok_or_else(|| {
                    err(path, format!("{what} names bufferView {}, which the file does not have", index.value()))
                })?;
                let buffer = self.buffers.get(view.buffer().index()).map_or(&[][..], Vec::as_slice);
                let bytes = view
                    .offset()
                    .checked_add(view.length())
                    .and_then(|end| buffer.get(view.offset()..end))
                    .ok_or_else(|| {
                        err(
                            path,
                            format!(
                                "{what}: bufferView {} runs past its buffer of {} bytes",
                                view.index(),
                                buffer.len()
                            ),
                        )
                    })?;
                Ok((bytes.to_vec(), embedded))
            }
            (None, Some(uri)) => {
                let uri = uri.to_string();
                let before = self.files.len();
                let bytes = read_uri(path, self.files_from, what, &uri, MAX_FILE_BYTES as usize, &mut self.files)?;
                let name = if self.files.len() > before { self.files[before].clone() } else { embedded };
                Ok((bytes, name))
            }
            (None, None) => Err(err(path, format!("{what} has neither a uri nor a bufferView"))),
        }
    }
}

/// Reads and checks `path` (see the module docs); `allow_outside` lets buffer URIs lead out
/// of its folder (absolute paths, `..`).
pub(crate) fn read(path: &Path, allow_outside: bool) -> Result<GltfFile<'_>, IoError> {
    let bytes = read_file(path, path, MAX_FILE_BYTES)?;
    let dir = path.parent().unwrap_or(Path::new(""));
    parse(path, &bytes, BufferFiles::Folder { dir, allow_outside })
}

/// Checks and parses a glTF or GLB file's `bytes`; `name` is the file errors name.
pub(crate) fn parse<'a>(name: &Path, bytes: &[u8], files_from: BufferFiles<'a>) -> Result<GltfFile<'a>, IoError> {
    let path = name;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(err(path, format!("{} bytes; the limit is {MAX_FILE_BYTES}", bytes.len())));
    }
    if bytes.starts_with(b"glTF") {
        check_glb(path, bytes)?;
    }
    let unread = |e: gltf::Error| err(path, format!("not a readable glTF file: {e}"));
    let gltf = gltf::Gltf::from_slice_without_validation(bytes).map_err(unread)?;
    // The gltf crate's own validation indexes the accessors a primitive names without a bounds
    // check: check those indices first, then let it validate the rest.
    let json = gltf.document.as_json();
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let named = prim.attributes.values().chain(prim.indices.as_ref());
            if let Some(bad) = named.map(|i| i.value()).find(|&i| i >= json.accessors.len()) {
                return Err(err(
                    path,
                    format!("mesh {m} primitive {p} names accessor {bad}, but the file has {}", json.accessors.len()),
                ));
            }
        }
    }
    let gltf =
        gltf::Gltf { document: gltf::Document::from_json(gltf.document.into_json()).map_err(unread)?, blob: gltf.blob };
    let mut buffers = Vec::new();
    let mut files = Vec::new();
    for buffer in gltf.document.buffers() {
        let length = buffer.length();
        if length as u64 > MAX_FILE_BYTES {
            return Err(err(
                path,
                format!("buffer {} declares {length} bytes; the limit is {MAX_FILE_BYTES}", buffer.index()),
            ));
        }
        let mut data = match buffer.source() {
            gltf::buffer::Source::Bin => gltf.blob.clone().ok_or_else(|| {
                err(path, format!("buffer {} refers to a GLB chunk the file does not have", buffer.index()))
            })?,
            gltf::buffer::Source::Uri(uri) => {
                read_uri(path, files_from, &format!("buffer {}", buffer.index()), uri, length, &mut files)?
            }
        };
        if data.len() < length {
            return Err(err(path, format!("buffer {} declares {length} bytes but has {}", buffer.index(), data.len())));
        }
        data.truncate(length);
        buffers.push(data);
    }
    check_accessors(path, &gltf.document, &buffers)?;
    Ok(GltfFile { document: gltf.document, buffers, files, files_from })
}

/// Reads at most `max` bytes of a regular file.
pub(crate) fn read_file(named: &Path, file: &Path, max: u64) -> Result<Vec<u8>, IoError> {
    let meta = std::fs::metadata(file).map_err(|source| IoError::Read { path: file.to_path_buf(), source })?;
    if !meta.is_file() {
        return Err(err(named, format!("{} is not a regular file", file.display())));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(err(named, format!("{} is {} bytes; the limit is {MAX_FILE_BYTES}", file.display(), meta.len())));
    }
    let mut data = Vec::new();
    std::fs::File::open(file)
        .and_then(|f| f.take(max).read_to_end(&mut data))
        .map_err(|source| IoError::Read { path: file.to_path_buf(), source })?;
    Ok(data)
}

/// GLB: magic, version 2, a total length equal to the file's, and chunks inside it.
fn check_glb(path: &Path, bytes: &[u8]) -> Result<(), IoError> {
    let word = |at: usize| bytes.get(at..at + 4).map(|b| u32::from_le_bytes(b.try_into().expect("4 bytes")) as usize);
    let (Some(version), Some(length)) = (word(4), word(8)) else {
        return Err(err(path, "GLB header is cut short (12 bytes expected)"));
    };
    if version != 2 {
        return Err(err(path, format!("GLB version {version}; only version 2 is read")));
    }
    if length != bytes.len() {
        return Err(err(path, format!("GLB header says {length} bytes but the file has {}", bytes.len())));
    }
    let mut at = 12;
    while at < bytes.len() {
        let Some(chunk) = word(at) else {
            return Err(err(path, format!("GLB chunk header at byte {at} is cut short")));
        };
        if word(at + 4).is_none() || at + 8 + chunk > bytes.len() {
            return Err(err(path, format!("GLB chunk at byte {at} claims {chunk} bytes, past the end of the file")));
        }
        at += 8 + chunk;
    }
    if word(12).is_none() {
        return Err(err(path, "GLB has no JSON chunk"));
    }
    Ok(())
}

/// `%XX` escapes decoded (a URI's path, RFC 3986); a malformed escape is an error.
fn percent_decode(uri: &str) -> Option<String> {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = std::str::from_utf8(b.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// A buffer's or image's bytes (`what` names it) from its URI: a base64 `data:` URI, or a file
/// `files_from` allows; at most `length` bytes.
fn read_uri(
    path: &Path,
    files_from: BufferFiles,
    what: &str,
    uri: &str,
    length: usize,
    files: &mut Vec<PathBuf>,
) -> Result<Vec<u8>, IoError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, encoded) =
            rest.split_once(";base64,").ok_or_else(|| err(path, format!("{what}: only base64 data: URIs are read")))?;
        if encoded.len() / 4 * 3 > length + 3 {
            return Err(err(path, format!("{what}: its data: URI holds more than its {length} bytes")));
        }
        return base64::decode(encoded).map_err(|e| err(path, format!("{what}: bad base64 in its data: URI: {e}")));
    }
    let BufferFiles::Folder { dir, allow_outside } = files_from else {
        return Err(err(path, format!("{what} is the file '{uri}', but a glTF read from memory has no folder")));
    };
    let outside = || {
        err(
            path,
            format!(
                "{what}'s uri '{uri}' points outside the glTF's folder; only files beside it or below it are read (unless outside paths are allowed)"
            ),
        )
    };
    let has_scheme = uri.split_once(':').is_some_and(|(scheme, _)| !scheme.is_empty() && !scheme.contains('/'));
    let decoded =
        percent_decode(uri).ok_or_else(|| err(path, format!("{what}'s uri '{uri}' has a malformed %-escape")))?;
    if has_scheme {
        return Err(err(path, format!("{what}'s uri '{uri}' has a scheme; only data: URIs and paths are read")));
    }
    if allow_outside {
        let file = dir.join(Path::new(&decoded));
        let real_file = std::fs::canonicalize(&file).map_err(|source| IoError::Read { path: file.clone(), source })?;
        let data = read_file(path, &real_file, length as u64)?;
        files.push(real_file);
        return Ok(data);
    }
    if decoded.starts_with(['/', '\\']) || decoded.contains('\\') {
        return Err(outside());
    }
    let relative = Path::new(&decoded);
    if !relative.components().all(|c| matches!(c, Component::Normal(_) | Component::CurDir)) {
        return Err(outside());
    }
    let file: PathBuf = dir.join(relative);
    // A link may still lead out: compare where both really are.
    let real_dir = std::fs::canonicalize(if dir.as_os_str().is_empty() { Path::new(".") } else { dir })
        .map_err(|source| IoError::Read { path: dir.to_path_buf(), source })?;
    let real_file = std::fs::canonicalize(&file).map_err(|source| IoError::Read { path: file.clone(), source })?;
    if !real_file.starts_with(&real_dir) {
        return Err(outside());
    }
    let data = read_file(path, &real_file, length as u64)?;
    files.push(real_file);
    Ok(data)
}

/// The component types (and whether normalized) an accessor may have.
type Accepted = &'static [(DataType, bool)];

/// Every accessor a primitive gives the mesh loader: the component type and shape it reads,
/// no sparse storage, and its bytes inside its buffer view and the view inside its buffer.
fn check_accessors(path: &Path, doc: &gltf::Document, buffers: &[Vec<u8>]) -> Result<(), IoError> {
    use gltf::Semantic;
    for mesh in doc.meshes() {
        for prim in mesh.primitives() {
            let mut wanted: Vec<(String, gltf::Accessor, Accepted, Dimensions)> = Vec::new();
            const FLOAT: &[(DataType, bool)] = &[(DataType::F32, false)];
            const UV: &[(DataType, bool)] = &[(DataType::F32, false), (DataType::U8, true), (DataType::U16, true)];
            const INDEX: &[(DataType, bool)] = &[(DataType::U8, false), (DataType::U16, false), (DataType::U32, false)];
            for (semantic, accessor) in prim.attributes() {
                match semantic {
                    Semantic::Positions => wanted.push(("POSITION".into(), accessor, FLOAT, Dimensions::Vec3)),
                    Semantic::Normals => wanted.push(("NORMAL".into(), accessor, FLOAT, Dimensions::Vec3)),
                    Semantic::Tangents => wanted.push(("TANGENT".into(), accessor, FLOAT, Dimensions::Vec4)),
                    Semantic::TexCoords(n) => wanted.push((format!("TEXCOORD_{n}"), accessor, UV, Dimensions::Vec2)),
                    // The same component types as texture coordinates, RGB or RGBA (glTF 2.0
                    // §3.7.2.1); the only colour set the loader reads.
                    Semantic::Colors(0) => {
                        let rgb = accessor.dimensions() == Dimensions::Vec3;
                        wanted.push((
                            "COLOR_0".into(),
                            accessor,
                            UV,
                            if rgb { Dimensions::Vec3 } else { Dimensions::Vec4 },
                        ))
                    }
                    _ => {}
                }
            }
            if let Some(indices) = prim.indices() {
                wanted.push(("indices".into(), indices, INDEX, Dimensions::Scalar));
            }
            for (what, a, types, dims) in wanted {
                let named = format!("{what} accessor {}", a.index());
                let normalized = a.normalized();
                if !types.contains(&(a.data_type(), normalized)) || a.dimensions() != dims {
                    return Err(err(
                        path,
                        format!(
                            "{named} is {:?} {:?}{}; expected {dims:?} of {types:?} (type, normalized)",
                            a.dimensions(),
                            a.data_type(),
                            if normalized { " normalized" } else { "" }
                        ),
                    ));
                }
                if a.sparse().is_some() {
                    return Err(err(path, format!("{named} is sparse, which is not read")));
                }
                let view = a.view().ok_or_else(|| err(path, format!("{named} has no bufferView")))?;
                let buffer_len = buffers.get(view.buffer().index()).map_or(0, Vec::len);
                if view.offset().checked_add(view.length()).is_none_or(|end| end > buffer_len) {
                    return Err(err(
                        path,
                        format!(
                            "bufferView {} (bytes {}..+{}) runs past its buffer of {buffer_len} bytes",
                            view.index(),
                            view.offset(),
                            view.length()
                        ),
                    ));
                }
                let element = a.size();
                let stride = view.stride().unwrap_or(element);
                let end = a.count().checked_sub(1).map_or(Some(0), |last| {
                    last.checked_mul(stride)
                        .and_then(|x| x.checked_add(a.offset()))
                        .and_then(|x| x.checked_add(element))
                });
                if end.is_none_or(|end| end > view.length()) {
                    return Err(err(
                        path,
                        format!(
                            "{named} ({} elements of {element} bytes from byte {}) runs past bufferView {} of {} bytes",
                            a.count(),
                            a.offset(),
                            view.index(),
                            view.length()
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}
