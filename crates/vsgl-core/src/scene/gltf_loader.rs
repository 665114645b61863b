//! glTF 2.0 loader (`.gltf` + `.bin`/data URIs, and `.glb`) for untrusted files.
//!
//! The `gltf` crate is used for its JSON data model only. Everything that touches bytes —
//! the GLB container, buffers, data URIs, image files, accessors — is done here so that every
//! size is checked against what is really on disk before anything is allocated, every file
//! name stays inside the scene's own folder, and no input can make the loader panic. The
//! crate's own validation is not used: it indexes arrays with unchecked input.
//!
//! Every failure is an [`Error::Scene`] naming the file and the glTF element
//! (`buffers[0].uri`, `accessors[5]`, `meshes[1].primitives[0]`, `nodes[4]`, ...).
//! Unsupported but harmless content (points/lines, point and directional lights,
//! orthographic cameras, extra UV sets, ...) is skipped with a note in [`Scene::warnings`].

use std::borrow::Cow;
use std::cell::Cell;
use std::collections::HashMap;
use std::io::{Cursor, Read};
use std::path::{Path, PathBuf};

use glam::{DMat4, DQuat, DVec3, Vec3};
use gltf::json;
use json::accessor::{ComponentType, GenericComponentType, IndexComponentType, Type as AccType};
use json::mesh::{Mode, Semantic};
use json::validation::Checked;

use crate::error::{Error, Result};
use crate::scene::{
    Camera, Material, Mesh, Node, Primitive, Scene, SpotLight, Texture, TextureUsage,
};

/// Largest accepted `.gltf`/`.glb` file.
const MAX_SCENE_FILE_BYTES: u64 = 2 << 30;
/// Largest accepted JSON document (`.gltf` file or GLB JSON chunk).
const MAX_JSON_BYTES: u64 = 256 << 20;
/// Largest accepted buffer `byteLength`.
const MAX_BUFFER_BYTES: u64 = 2 << 30;
/// Largest accepted encoded image (file, data URI or bufferView).
const MAX_IMAGE_FILE_BYTES: u64 = 256 << 20;
/// Largest accepted image side, checked from the header before decoding.
const MAX_IMAGE_SIDE: u32 = 16384;
/// Cap on all decoded RGBA8 texels of one scene.
const MAX_TEXTURE_BYTES: u64 = 4 << 30;
/// Cap on all vertex and index data produced for one scene (guards against one accessor
/// being referenced by thousands of meshes).
const MAX_GEOMETRY_BYTES: u64 = 4 << 30;
/// Cap on the sum of all buffers' byteLength (guards against many buffers naming one file).
const MAX_TOTAL_BUFFER_BYTES: u64 = 4 << 30;
/// Cap on the sum of all encoded image sizes read.
const MAX_TOTAL_IMAGE_FILE_BYTES: u64 = 4 << 30;
/// Cap on elements of accessors without a bufferView (zero-filled, not backed by the file).
const MAX_UNBACKED_ELEMENTS: u64 = 1 << 24;

/// Required extensions this loader honours (the others in `extensionsUsed` are optional by
/// definition and ignored).
const SUPPORTED_REQUIRED_EXTENSIONS: &[&str] = &[
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_specular",
    "KHR_mesh_quantization",
];

/// Loads a `.gltf` or `.glb` scene. Only nodes reachable from the default scene (or scene 0,
/// or every root node when the file has no scene) instance meshes, lights and cameras.
pub fn load(path: &Path) -> Result<Scene> {
    let meta = std::fs::metadata(path)
        .map_err(|e| Error::scene(path, "file", format!("cannot read the scene file: {e}")))?;
    if !meta.is_file() {
        return Err(Error::scene(path, "file", "not a regular file"));
    }
    if meta.len() > MAX_SCENE_FILE_BYTES {
        return Err(Error::scene(
            path,
            "file",
            format!(
                "file is {} bytes; at most {MAX_SCENE_FILE_BYTES} are accepted",
                meta.len()
            ),
        ));
    }
    let bytes = std::fs::read(path)
        .map_err(|e| Error::scene(path, "file", format!("cannot read the scene file: {e}")))?;

    let (json_bytes, bin) = if bytes.starts_with(b"glTF") {
        parse_glb(path, &bytes)?
    } else {
        (&bytes[..], None)
    };
    if json_bytes.len() as u64 > MAX_JSON_BYTES {
        return Err(Error::scene(
            path,
            "JSON",
            format!(
                "JSON is {} bytes; at most {MAX_JSON_BYTES} are accepted",
                json_bytes.len()
            ),
        ));
    }
    let json_bytes = json_bytes
        .strip_prefix(b"\xEF\xBB\xBF")
        .unwrap_or(json_bytes);
    let root: json::Root = json::deserialize::from_slice(json_bytes)
        .map_err(|e| Error::scene(path, "JSON", format!("invalid glTF JSON: {e}")))?;

    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let base = folder.canonicalize().map_err(|e| {
        Error::scene(
            path,
            "file",
            format!("cannot resolve the scene folder: {e}"),
        )
    })?;

    let mut ctx = Ctx {
        file: path,
        base,
        root,
        buffers: Vec::new(),
        views: Vec::new(),
        geometry_bytes: Cell::new(0),
        unbacked_elements: Cell::new(0),
        texture_bytes: Cell::new(0),
        image_file_bytes: Cell::new(0),
    };
    ctx.check_header()?;
    ctx.load_buffers(bin)?;
    ctx.check_views()?;

    let mut b = Builder {
        scene: Scene {
            source: path.display().to_string(),
            ..Default::default()
        },
        mesh_map: HashMap::new(),
        material_map: HashMap::new(),
        texture_map: HashMap::new(),
    };
    build_scene(&ctx, &mut b)?;
    Ok(b.scene)
}

// ------------------------------------------------------------------------------------------
// GLB container
// ------------------------------------------------------------------------------------------

fn le_u32(data: &[u8], offset: usize) -> Option<u32> {
    let end = offset.checked_add(4)?;
    let b: [u8; 4] = data.get(offset..end)?.try_into().ok()?;
    Some(u32::from_le_bytes(b))
}

const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// Splits a GLB file into its JSON chunk and optional BIN chunk, checking every length.
fn parse_glb<'b>(file: &Path, data: &'b [u8]) -> Result<(&'b [u8], Option<&'b [u8]>)> {
    let bad = |element: &str, msg: String| Error::scene(file, element, msg);
    let version = le_u32(data, 4).ok_or_else(|| {
        bad(
            "GLB header",
            "file is shorter than the 12-byte header".into(),
        )
    })?;
    let length = le_u32(data, 8).ok_or_else(|| {
        bad(
            "GLB header",
            "file is shorter than the 12-byte header".into(),
        )
    })?;
    if version != 2 {
        return Err(bad(
            "GLB header",
            format!("unsupported GLB version {version} (only 2)"),
        ));
    }
    let length = length as usize;
    if length < 12 || length > data.len() {
        return Err(bad(
            "GLB header",
            format!(
                "declared length {length} does not fit the file ({} bytes)",
                data.len()
            ),
        ));
    }
    let data = data.get(..length).unwrap_or(data);

    let mut pos = 12usize;
    let mut json: Option<&[u8]> = None;
    let mut bin: Option<&[u8]> = None;
    let mut index = 0usize;
    while pos < data.len() {
        let el = format!("GLB chunk {index}");
        let (Some(len), Some(ty)) = (le_u32(data, pos), le_u32(data, pos + 4)) else {
            return Err(bad(&el, "truncated chunk header".into()));
        };
        let start = pos + 8;
        let end = start
            .checked_add(len as usize)
            .filter(|&e| e <= data.len())
            .ok_or_else(|| {
                bad(
                    &el,
                    format!("chunk length {len} runs past the end of the file"),
                )
            })?;
        let body = data.get(start..end).unwrap_or_default();
        match (index, ty) {
            (0, CHUNK_JSON) => json = Some(body),
            (0, _) => return Err(bad(&el, "the first chunk must be the JSON chunk".into())),
            (_, CHUNK_JSON) => return Err(bad(&el, "more than one JSON chunk".into())),
            (_, CHUNK_BIN) if bin.is_none() => bin = Some(body),
            (_, CHUNK_BIN) => return Err(bad(&el, "more than one BIN chunk".into())),
            _ => {} // unknown chunk types are skipped (glTF 2.0 §4.4.3.1)
        }
        pos = end;
        index += 1;
    }
    let json = json.ok_or_else(|| bad("GLB chunk 0", "missing JSON chunk".into()))?;
    Ok((json, bin))
}

// ------------------------------------------------------------------------------------------
// URIs
// ------------------------------------------------------------------------------------------

/// Whether `uri` starts with an RFC 3986 scheme (`http:`, `file:`, `data:`, `C:` ...).
fn uri_scheme(uri: &str) -> Option<&str> {
    let colon = uri.find(':')?;
    let scheme = uri.get(..colon)?;
    let mut chars = scheme.chars();
    let first = chars.next()?;
    if first.is_ascii_alphabetic() && chars.all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
    {
        Some(scheme)
    } else {
        None
    }
}

fn hex_value(c: u8) -> Option<u8> {
    match c {
        b'0'..=b'9' => Some(c - b'0'),
        b'a'..=b'f' => Some(c - b'a' + 10),
        b'A'..=b'F' => Some(c - b'A' + 10),
        _ => None,
    }
}

/// Decodes `%XX` escapes. `None` on a malformed escape.
fn percent_decode(s: &[u8]) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(s.len());
    let mut i = 0;
    while let Some(&c) = s.get(i) {
        if c == b'%' {
            let hi = hex_value(*s.get(i + 1)?)?;
            let lo = hex_value(*s.get(i + 2)?)?;
            out.push(hi << 4 | lo);
            i += 3;
        } else {
            out.push(c);
            i += 1;
        }
    }
    Some(out)
}

/// Standard (and URL-safe) base64 with optional padding; ASCII whitespace is skipped.
fn base64_decode(s: &[u8]) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(s.len() / 4 * 3 + 3);
    let mut acc: u32 = 0;
    let mut bits = 0u32;
    let mut padding = 0;
    for &c in s {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            b'=' => {
                padding += 1;
                continue;
            }
            b' ' | b'\t' | b'\r' | b'\n' => continue,
            _ => return None,
        };
        if padding > 0 {
            return None; // data after padding
        }
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    // 6 leftover bits means a lone sextet, which encodes no byte.
    if padding > 2 || bits >= 6 {
        return None;
    }
    Some(out)
}

// ------------------------------------------------------------------------------------------
// Loading context: the JSON plus checked binary data
// ------------------------------------------------------------------------------------------

/// A bufferView checked against its buffer.
#[derive(Clone, Copy)]
struct ViewInfo {
    buffer: usize,
    offset: usize,
    len: usize,
    stride: Option<usize>,
}

struct Ctx<'a> {
    file: &'a Path,
    /// Canonical folder of the scene file; every referenced file must lie under it.
    base: PathBuf,
    root: json::Root,
    buffers: Vec<Cow<'a, [u8]>>,
    views: Vec<ViewInfo>,
    geometry_bytes: Cell<u64>,
    unbacked_elements: Cell<u64>,
    texture_bytes: Cell<u64>,
    image_file_bytes: Cell<u64>,
}

/// How an accessor's components become output values.
trait Component: Copy + Default {
    fn decode(bytes: &[u8], ct: ComponentType, normalized: bool) -> Option<Self>;
}

fn read_le<const N: usize>(bytes: &[u8]) -> Option<[u8; N]> {
    bytes.get(..N)?.try_into().ok()
}

impl Component for f32 {
    fn decode(b: &[u8], ct: ComponentType, normalized: bool) -> Option<f32> {
        Some(match ct {
            ComponentType::F32 => f32::from_le_bytes(read_le(b)?),
            ComponentType::I8 => {
                let v = f32::from(i8::from_le_bytes(read_le(b)?));
                if normalized {
                    (v / 127.0).max(-1.0)
                } else {
                    v
                }
            }
            ComponentType::U8 => {
                let v = f32::from(u8::from_le_bytes(read_le(b)?));
                if normalized {
                    v / 255.0
                } else {
                    v
                }
            }
            ComponentType::I16 => {
                let v = f32::from(i16::from_le_bytes(read_le(b)?));
                if normalized {
                    (v / 32767.0).max(-1.0)
                } else {
                    v
                }
            }
            ComponentType::U16 => {
                let v = f32::from(u16::from_le_bytes(read_le(b)?));
                if normalized {
                    v / 65535.0
                } else {
                    v
                }
            }
            ComponentType::U32 => {
                let v = u32::from_le_bytes(read_le(b)?) as f64;
                (if normalized { v / u32::MAX as f64 } else { v }) as f32
            }
        })
    }
}

impl Component for u32 {
    fn decode(b: &[u8], ct: ComponentType, _normalized: bool) -> Option<u32> {
        match ct {
            ComponentType::U8 => Some(u32::from(u8::from_le_bytes(read_le(b)?))),
            ComponentType::U16 => Some(u32::from(u16::from_le_bytes(read_le(b)?))),
            ComponentType::U32 => Some(u32::from_le_bytes(read_le(b)?)),
            _ => None,
        }
    }
}

fn type_name(t: AccType) -> &'static str {
    match t {
        AccType::Scalar => "SCALAR",
        AccType::Vec2 => "VEC2",
        AccType::Vec3 => "VEC3",
        AccType::Vec4 => "VEC4",
        AccType::Mat2 => "MAT2",
        AccType::Mat3 => "MAT3",
        AccType::Mat4 => "MAT4",
    }
}

impl<'a> Ctx<'a> {
    fn err(&self, element: impl Into<String>, message: impl Into<String>) -> Error {
        Error::scene(self.file, element, message)
    }

    fn check_header(&self) -> Result<()> {
        let v = &self.root.asset.version;
        if !v.starts_with("2.") {
            return Err(self.err(
                "asset.version",
                format!("glTF version \"{v}\" is not supported (2.x only)"),
            ));
        }
        for (i, ext) in self.root.extensions_required.iter().enumerate() {
            if !SUPPORTED_REQUIRED_EXTENSIONS.contains(&ext.as_str()) {
                return Err(self.err(
                    format!("extensionsRequired[{i}]"),
                    format!("required extension {ext} is not supported"),
                ));
            }
        }
        Ok(())
    }

    /// Bytes named by a buffer or image URI: a `data:` URI or a file inside the scene folder.
    /// `exact` is a buffer's byteLength: the file must hold at least that many bytes, and
    /// only those are read. Without it the whole file is read, up to `cap` bytes.
    fn fetch_uri(&self, uri: &str, element: &str, exact: Option<u64>, cap: u64) -> Result<Vec<u8>> {
        if let Some(scheme) = uri_scheme(uri) {
            if scheme.eq_ignore_ascii_case("data") {
                return self.decode_data_uri(uri.get(5..).unwrap_or_default(), element, exact, cap);
            }
            return Err(self.err(
                element,
                format!(
                    "URI scheme \"{scheme}:\" is not allowed; only relative file names inside the \
                     scene folder and data: URIs are accepted"
                ),
            ));
        }
        let path = self.resolve_relative(uri, element)?;
        let meta = std::fs::metadata(&path)
            .map_err(|e| self.err(element, format!("cannot open \"{uri}\": {e}")))?;
        if !meta.is_file() {
            return Err(self.err(element, format!("\"{uri}\" is not a regular file")));
        }
        let want = match exact {
            Some(n) => {
                if meta.len() < n {
                    return Err(self.err(
                        element,
                        format!(
                            "file \"{uri}\" is truncated: it has {} bytes but byteLength is {n}",
                            meta.len()
                        ),
                    ));
                }
                n
            }
            None => {
                if meta.len() > cap {
                    return Err(self.err(
                        element,
                        format!(
                            "file \"{uri}\" is {} bytes; at most {cap} are accepted",
                            meta.len()
                        ),
                    ));
                }
                meta.len()
            }
        };
        let want_usize =
            usize::try_from(want).map_err(|_| self.err(element, "too large for this machine"))?;
        let file = std::fs::File::open(&path)
            .map_err(|e| self.err(element, format!("cannot open \"{uri}\": {e}")))?;
        let mut data = Vec::with_capacity(want_usize);
        file.take(want)
            .read_to_end(&mut data)
            .map_err(|e| self.err(element, format!("cannot read \"{uri}\": {e}")))?;
        if (data.len() as u64) < want {
            return Err(self.err(
                element,
                format!(
                    "file \"{uri}\" is truncated: read {} of {want} bytes",
                    data.len()
                ),
            ));
        }
        Ok(data)
    }

    fn decode_data_uri(
        &self,
        rest: &str,
        element: &str,
        exact: Option<u64>,
        cap: u64,
    ) -> Result<Vec<u8>> {
        let comma = rest
            .find(',')
            .ok_or_else(|| self.err(element, "malformed data: URI (no comma)"))?;
        let header = rest.get(..comma).unwrap_or_default();
        let payload = rest.get(comma + 1..).unwrap_or_default().as_bytes();
        let is_base64 = header.to_ascii_lowercase().ends_with(";base64");
        // Upper bound of the decoded size, to refuse an impossible byteLength before decoding.
        let bound = if is_base64 {
            payload.len() as u64 / 4 * 3 + 3
        } else {
            payload.len() as u64
        };
        if let Some(n) = exact {
            if n > bound {
                return Err(self.err(
                    element,
                    format!("data: URI is truncated: it holds at most {bound} bytes but byteLength is {n}"),
                ));
            }
        }
        let data = if is_base64 {
            base64_decode(payload)
                .ok_or_else(|| self.err(element, "malformed base64 in data: URI"))?
        } else {
            percent_decode(payload)
                .ok_or_else(|| self.err(element, "malformed percent-encoding in data: URI"))?
        };
        match exact {
            Some(n) if (data.len() as u64) < n => Err(self.err(
                element,
                format!(
                    "data: URI is truncated: it holds {} bytes but byteLength is {n}",
                    data.len()
                ),
            )),
            None if data.len() as u64 > cap => Err(self.err(
                element,
                format!(
                    "data: URI holds {} bytes; at most {cap} are accepted",
                    data.len()
                ),
            )),
            _ => Ok(data),
        }
    }

    /// Resolves a relative URI to a canonical path under the scene folder, or refuses it.
    fn resolve_relative(&self, uri: &str, element: &str) -> Result<PathBuf> {
        let decoded = percent_decode(uri.as_bytes()).ok_or_else(|| {
            self.err(
                element,
                format!("malformed percent-encoding in URI \"{uri}\""),
            )
        })?;
        let decoded = String::from_utf8(decoded)
            .map_err(|_| self.err(element, format!("URI \"{uri}\" is not UTF-8")))?;
        if decoded.is_empty() {
            return Err(self.err(element, "empty URI"));
        }
        if decoded.contains('\0') {
            return Err(self.err(element, "URI contains a NUL byte"));
        }
        if decoded.starts_with('/')
            || decoded.starts_with('\\')
            || Path::new(&decoded).is_absolute()
        {
            return Err(self.err(
                element,
                format!("absolute path \"{decoded}\" is not allowed; URIs must be relative to the scene folder"),
            ));
        }
        let mut rel = PathBuf::new();
        let mut depth = 0usize;
        for part in decoded.split(['/', '\\']) {
            match part {
                "" | "." => {}
                ".." => {
                    if depth == 0 {
                        return Err(self.err(
                            element,
                            format!("\"{decoded}\" escapes the scene folder with \"..\""),
                        ));
                    }
                    depth -= 1;
                    rel.pop();
                }
                p => {
                    depth += 1;
                    rel.push(p);
                }
            }
        }
        if depth == 0 {
            return Err(self.err(element, format!("\"{decoded}\" does not name a file")));
        }
        let full = self.base.join(&rel);
        let canonical = full
            .canonicalize()
            .map_err(|e| self.err(element, format!("cannot open \"{decoded}\": {e}")))?;
        if !canonical.starts_with(&self.base) {
            return Err(self.err(
                element,
                format!("\"{decoded}\" resolves outside the scene folder (symbolic link?)"),
            ));
        }
        Ok(canonical)
    }

    fn load_buffers(&mut self, bin: Option<&'a [u8]>) -> Result<()> {
        let mut buffers = Vec::with_capacity(self.root.buffers.len());
        let mut total = 0u64;
        for (i, buffer) in self.root.buffers.iter().enumerate() {
            let el = format!("buffers[{i}]");
            let len = buffer.byte_length.0;
            if len > MAX_BUFFER_BYTES {
                return Err(self.err(
                    el,
                    format!("byteLength {len} exceeds the limit of {MAX_BUFFER_BYTES} bytes"),
                ));
            }
            total = total.saturating_add(len);
            if total > MAX_TOTAL_BUFFER_BYTES {
                return Err(self.err(
                    el,
                    format!("the buffers' byteLengths add up to more than {MAX_TOTAL_BUFFER_BYTES} bytes"),
                ));
            }
            let data: Cow<'a, [u8]> = match &buffer.uri {
                None => {
                    let chunk =
                        match (i, bin) {
                            (0, Some(chunk)) => chunk,
                            _ => return Err(self.err(
                                el,
                                "buffer has no uri (only the first buffer of a .glb may omit it, \
                                 and this file has no BIN chunk for it)",
                            )),
                        };
                    let n = usize::try_from(len).unwrap_or(usize::MAX);
                    let slice = chunk.get(..n).ok_or_else(|| {
                        self.err(
                            el.clone(),
                            format!(
                                "truncated: byteLength is {len} but the GLB BIN chunk has {} bytes",
                                chunk.len()
                            ),
                        )
                    })?;
                    Cow::Borrowed(slice)
                }
                Some(uri) => {
                    let el = format!("{el}.uri");
                    let mut data = self.fetch_uri(uri, &el, Some(len), MAX_BUFFER_BYTES)?;
                    data.truncate(usize::try_from(len).unwrap_or(usize::MAX));
                    Cow::Owned(data)
                }
            };
            buffers.push(data);
        }
        self.buffers = buffers;
        Ok(())
    }

    fn check_views(&mut self) -> Result<()> {
        let mut views = Vec::with_capacity(self.root.buffer_views.len());
        for (i, view) in self.root.buffer_views.iter().enumerate() {
            let el = format!("bufferViews[{i}]");
            let b = view.buffer.value();
            let buffer = self.buffers.get(b).ok_or_else(|| {
                self.err(
                    format!("{el}.buffer"),
                    format!("buffers[{b}] does not exist"),
                )
            })?;
            let offset = view.byte_offset.map_or(0, |o| o.0);
            let len = view.byte_length.0;
            let end = offset.checked_add(len).filter(|&e| e <= buffer.len() as u64).ok_or_else(|| {
                self.err(
                    el.clone(),
                    format!(
                        "byteOffset {offset} + byteLength {len} runs past the end of buffers[{b}] ({} bytes)",
                        buffer.len()
                    ),
                )
            })?;
            let stride = match view.byte_stride {
                Some(s) if !(4..=252).contains(&s.0) => {
                    return Err(self.err(
                        format!("{el}.byteStride"),
                        format!("byteStride {} is not in 4..=252", s.0),
                    ))
                }
                Some(s) => Some(s.0),
                None => None,
            };
            // end <= buffer.len(), so both fit in usize.
            views.push(ViewInfo {
                buffer: b,
                offset: offset as usize,
                len: (end - offset) as usize,
                stride,
            });
        }
        self.views = views;
        Ok(())
    }

    fn view_bytes(&self, v: ViewInfo) -> Option<&[u8]> {
        self.buffers
            .get(v.buffer)?
            .get(v.offset..v.offset.checked_add(v.len)?)
    }

    fn charge_geometry(&self, bytes: u64, element: &str) -> Result<()> {
        let total = self.geometry_bytes.get().saturating_add(bytes);
        if total > MAX_GEOMETRY_BYTES {
            return Err(self.err(
                element,
                format!("the scene's vertex and index data exceed the limit of {MAX_GEOMETRY_BYTES} bytes"),
            ));
        }
        self.geometry_bytes.set(total);
        Ok(())
    }

    /// Reads accessor `idx` as `count × multiplicity(ty)` values, with every bound checked.
    /// `used_as` names the referencing element (for messages).
    fn read_accessor<T: Component>(
        &self,
        idx: usize,
        ty: AccType,
        used_as: &str,
        allowed: &[ComponentType],
    ) -> Result<Vec<T>> {
        let acc = self
            .root
            .accessors
            .get(idx)
            .ok_or_else(|| self.err(used_as, format!("accessors[{idx}] does not exist")))?;
        let el = format!("accessors[{idx}]");
        match acc.type_ {
            Checked::Valid(t) if t == ty => {}
            Checked::Valid(t) => {
                return Err(self.err(
                    el,
                    format!(
                        "type is {} but {used_as} needs {}",
                        type_name(t),
                        type_name(ty)
                    ),
                ))
            }
            Checked::Invalid => return Err(self.err(el, "invalid accessor type")),
        }
        let ct = match acc.component_type {
            Checked::Valid(GenericComponentType(ct)) => ct,
            Checked::Invalid => return Err(self.err(el, "invalid componentType")),
        };
        if !allowed.contains(&ct) {
            return Err(self.err(
                el,
                format!("componentType {ct:?} is not allowed for {used_as}"),
            ));
        }
        let ncomp = ty.multiplicity();
        let csize = ct.size();
        let elem = ncomp * csize;
        let count = acc.count.0;
        let values = count
            .checked_mul(ncomp as u64)
            .ok_or_else(|| self.err(el.clone(), format!("count {count} is too large")))?;
        let out_bytes = values.saturating_mul(std::mem::size_of::<T>() as u64);

        let mut out: Vec<T> = match acc.buffer_view {
            Some(v) => {
                let vi = v.value();
                let view = *self.views.get(vi).ok_or_else(|| {
                    self.err(
                        format!("{el}.bufferView"),
                        format!("bufferViews[{vi}] does not exist"),
                    )
                })?;
                let stride = view.stride.unwrap_or(elem);
                if stride < elem {
                    return Err(self.err(
                        el,
                        format!("bufferViews[{vi}].byteStride {stride} is smaller than the element size {elem}"),
                    ));
                }
                let offset = acc.byte_offset.map_or(0, |o| o.0);
                let need = if count == 0 {
                    Some(offset)
                } else {
                    (count - 1)
                        .checked_mul(stride as u64)
                        .and_then(|x| x.checked_add(offset))
                        .and_then(|x| x.checked_add(elem as u64))
                };
                let need = need.filter(|&n| n <= view.len as u64).ok_or_else(|| {
                    self.err(
                        el.clone(),
                        format!(
                            "out of bounds: byteOffset {offset} + byteStride {stride} × (count {count} − 1) + \
                             element size {elem} exceeds bufferViews[{vi}].byteLength {}",
                            view.len
                        ),
                    )
                })?;
                // Every element now lies inside the view, so `values` is bounded by the file.
                self.charge_geometry(out_bytes, &el)?;
                let data = self
                    .view_bytes(view)
                    .and_then(|d| d.get(offset as usize..need as usize))
                    .ok_or_else(|| self.err(el.clone(), "bufferView out of range"))?;
                let mut out = Vec::with_capacity(values as usize);
                for i in 0..count as usize {
                    let start = i * stride;
                    for c in 0..ncomp {
                        let s = start + c * csize;
                        let v = data
                            .get(s..)
                            .and_then(|b| T::decode(b, ct, acc.normalized))
                            .ok_or_else(|| self.err(el.clone(), "cannot decode element"))?;
                        out.push(v);
                    }
                }
                out
            }
            None => {
                let total = self.unbacked_elements.get().saturating_add(count);
                if total > MAX_UNBACKED_ELEMENTS {
                    return Err(self.err(
                        el,
                        format!(
                            "count {count} without a bufferView exceeds the limit of {MAX_UNBACKED_ELEMENTS} \
                             zero-filled elements"
                        ),
                    ));
                }
                self.unbacked_elements.set(total);
                self.charge_geometry(out_bytes, &el)?;
                vec![T::default(); values as usize]
            }
        };

        if let Some(sparse) = &acc.sparse {
            self.apply_sparse(&mut out, sparse, idx, count, ncomp, ct, acc.normalized)?;
        }
        Ok(out)
    }

    #[allow(clippy::too_many_arguments)]
    fn apply_sparse<T: Component>(
        &self,
        out: &mut [T],
        sparse: &json::accessor::sparse::Sparse,
        idx: usize,
        count: u64,
        ncomp: usize,
        ct: ComponentType,
        normalized: bool,
    ) -> Result<()> {
        let el = format!("accessors[{idx}].sparse");
        let n = sparse.count.0;
        if n > count {
            return Err(self.err(
                el,
                format!("sparse count {n} exceeds the accessor count {count}"),
            ));
        }
        let ict = match sparse.indices.component_type {
            Checked::Valid(IndexComponentType(c)) => c,
            Checked::Invalid => {
                return Err(self.err(format!("{el}.indices"), "invalid componentType"))
            }
        };
        let region = |view: json::Index<json::buffer::View>,
                      offset: u64,
                      elem: usize,
                      what: &str|
         -> Result<&[u8]> {
            let vi = view.value();
            let v = *self.views.get(vi).ok_or_else(|| {
                self.err(
                    format!("{el}.{what}"),
                    format!("bufferViews[{vi}] does not exist"),
                )
            })?;
            let end = n
                .checked_mul(elem as u64)
                .and_then(|x| x.checked_add(offset))
                .filter(|&e| e <= v.len as u64)
                .ok_or_else(|| {
                    self.err(
                        format!("{el}.{what}"),
                        format!("out of bounds of bufferViews[{vi}]"),
                    )
                })?;
            self.view_bytes(v)
                .and_then(|d| d.get(offset as usize..end as usize))
                .ok_or_else(|| self.err(format!("{el}.{what}"), "out of bounds"))
        };
        let isize_ = ict.size();
        let elem = ncomp * ct.size();
        let indices = region(
            sparse.indices.buffer_view,
            sparse.indices.byte_offset.0,
            isize_,
            "indices",
        )?;
        let values = region(
            sparse.values.buffer_view,
            sparse.values.byte_offset.0,
            elem,
            "values",
        )?;
        for k in 0..n as usize {
            let target = indices
                .get(k * isize_..)
                .and_then(|b| u32::decode(b, ict, false))
                .ok_or_else(|| self.err(format!("{el}.indices"), "cannot decode index"))?;
            if u64::from(target) >= count {
                return Err(self.err(
                    format!("{el}.indices"),
                    format!("index {target} is out of range (count {count})"),
                ));
            }
            for c in 0..ncomp {
                let v = values
                    .get(k * elem + c * ct.size()..)
                    .and_then(|b| T::decode(b, ct, normalized))
                    .ok_or_else(|| self.err(format!("{el}.values"), "cannot decode value"))?;
                if let Some(slot) = out.get_mut(target as usize * ncomp + c) {
                    *slot = v;
                }
            }
        }
        Ok(())
    }

    /// Reads a float attribute and checks that every value is finite.
    fn read_floats(&self, idx: usize, ty: AccType, used_as: &str) -> Result<Vec<f32>> {
        use ComponentType::*;
        let v: Vec<f32> = self.read_accessor(idx, ty, used_as, &[F32, I8, U8, I16, U16])?;
        if let Some(pos) = v.iter().position(|x| !x.is_finite()) {
            return Err(self.err(
                format!("accessors[{idx}]"),
                format!(
                    "non-finite value in element {} (used as {used_as})",
                    pos / ty.multiplicity().max(1)
                ),
            ));
        }
        Ok(v)
    }

    /// Reads an image (file, data URI or bufferView), checks its size from the header and
    /// decodes it to RGBA8.
    fn decode_image(&self, i: usize) -> Result<(u32, u32, Vec<u8>)> {
        let el = format!("images[{i}]");
        let image = self
            .root
            .images
            .get(i)
            .ok_or_else(|| self.err(el.clone(), "image does not exist"))?;
        let bytes: Cow<[u8]> = match (&image.uri, image.buffer_view) {
            (Some(uri), _) => {
                let used = self.image_file_bytes.get();
                if used >= MAX_TOTAL_IMAGE_FILE_BYTES {
                    return Err(self.err(
                        el,
                        format!("the scene's image files exceed the limit of {MAX_TOTAL_IMAGE_FILE_BYTES} bytes"),
                    ));
                }
                let cap = MAX_IMAGE_FILE_BYTES.min(MAX_TOTAL_IMAGE_FILE_BYTES - used);
                let data = self.fetch_uri(uri, &format!("{el}.uri"), None, cap)?;
                self.image_file_bytes.set(used + data.len() as u64);
                Cow::Owned(data)
            }
            (None, Some(v)) => {
                let vi = v.value();
                let view = *self.views.get(vi).ok_or_else(|| {
                    self.err(
                        format!("{el}.bufferView"),
                        format!("bufferViews[{vi}] does not exist"),
                    )
                })?;
                if view.len as u64 > MAX_IMAGE_FILE_BYTES {
                    return Err(self.err(
                        el,
                        format!("image data is larger than {MAX_IMAGE_FILE_BYTES} bytes"),
                    ));
                }
                Cow::Borrowed(
                    self.view_bytes(view)
                        .ok_or_else(|| self.err(el.clone(), "bufferView out of range"))?,
                )
            }
            (None, None) => return Err(self.err(el, "image has neither uri nor bufferView")),
        };
        let reader = || -> Result<image::ImageReader<Cursor<&[u8]>>> {
            let r = image::ImageReader::new(Cursor::new(&bytes[..]))
                .with_guessed_format()
                .map_err(|e| self.err(el.clone(), format!("cannot read image: {e}")))?;
            match r.format() {
                Some(image::ImageFormat::Png | image::ImageFormat::Jpeg) => Ok(r),
                Some(f) => Err(self.err(
                    el.clone(),
                    format!("image format {f:?} is not supported (PNG and JPEG only)"),
                )),
                None => Err(self.err(el.clone(), "unrecognised image format (PNG and JPEG only)")),
            }
        };
        let (w, h) = reader()?
            .into_dimensions()
            .map_err(|e| self.err(el.clone(), format!("cannot read the image header: {e}")))?;
        if w == 0 || h == 0 || w > MAX_IMAGE_SIDE || h > MAX_IMAGE_SIDE {
            return Err(self.err(
                el,
                format!(
                    "image is {w}×{h} pixels; sides of 1 to {MAX_IMAGE_SIDE} pixels are accepted"
                ),
            ));
        }
        let texels = u64::from(w) * u64::from(h) * 4;
        let total = self.texture_bytes.get().saturating_add(texels);
        if total > MAX_TEXTURE_BYTES {
            return Err(self.err(
                el,
                format!("the scene's textures exceed the limit of {MAX_TEXTURE_BYTES} bytes"),
            ));
        }
        self.texture_bytes.set(total);
        let mut r = reader()?;
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(MAX_IMAGE_SIDE);
        limits.max_image_height = Some(MAX_IMAGE_SIDE);
        // Room for 16-bit RGBA plus decoder scratch.
        limits.max_alloc = Some(u64::from(w) * u64::from(h) * 8 + (64 << 20));
        r.limits(limits);
        let img = r
            .decode()
            .map_err(|e| self.err(el.clone(), format!("cannot decode image: {e}")))?;
        let rgba = img.to_rgba8();
        let (w, h) = rgba.dimensions();
        Ok((w, h, rgba.into_raw()))
    }
}

// ------------------------------------------------------------------------------------------
// Scene building
// ------------------------------------------------------------------------------------------

struct Builder {
    scene: Scene,
    /// glTF mesh → Scene mesh.
    mesh_map: HashMap<usize, usize>,
    /// (glTF material or default, keep normal map) → Scene material.
    material_map: HashMap<(Option<usize>, bool), usize>,
    /// (glTF image, is colour) → Scene texture.
    texture_map: HashMap<(usize, bool), usize>,
}

impl Builder {
    fn warn(&mut self, msg: String) {
        log::warn!("{}: {msg}", self.scene.source);
        self.scene.warnings.push(msg);
    }
}

fn finite_all(v: &[f32]) -> bool {
    v.iter().all(|x| x.is_finite())
}

fn node_local(ctx: &Ctx, i: usize, node: &json::Node) -> Result<DMat4> {
    if let Some(m) = node.matrix {
        if !finite_all(&m) {
            return Err(ctx.err(format!("nodes[{i}].matrix"), "non-finite matrix element"));
        }
        return Ok(DMat4::from_cols_array(&m.map(f64::from)));
    }
    let t = node.translation.unwrap_or([0.0; 3]);
    let s = node.scale.unwrap_or([1.0; 3]);
    let r = node.rotation.map_or([0.0, 0.0, 0.0, 1.0], |q| q.0);
    if !finite_all(&t) {
        return Err(ctx.err(format!("nodes[{i}].translation"), "non-finite translation"));
    }
    if !finite_all(&s) {
        return Err(ctx.err(format!("nodes[{i}].scale"), "non-finite scale"));
    }
    let q = DQuat::from_xyzw(
        f64::from(r[0]),
        f64::from(r[1]),
        f64::from(r[2]),
        f64::from(r[3]),
    );
    let len = q.length();
    if !(len.is_finite() && len > 1e-12) {
        return Err(ctx.err(
            format!("nodes[{i}].rotation"),
            "rotation is not a unit quaternion",
        ));
    }
    let q = q / len;
    Ok(DMat4::from_scale_rotation_translation(
        DVec3::new(f64::from(s[0]), f64::from(s[1]), f64::from(s[2])),
        q,
        DVec3::new(f64::from(t[0]), f64::from(t[1]), f64::from(t[2])),
    ))
}

fn build_scene(ctx: &Ctx, b: &mut Builder) -> Result<()> {
    let nodes = &ctx.root.nodes;
    let nn = nodes.len();

    // Parents from children lists: every node has at most one parent.
    let mut parent: Vec<Option<usize>> = vec![None; nn];
    for (i, node) in nodes.iter().enumerate() {
        for (k, c) in node.children.iter().flatten().enumerate() {
            let c = c.value();
            if c >= nn {
                return Err(ctx.err(
                    format!("nodes[{i}].children[{k}]"),
                    format!("nodes[{c}] does not exist"),
                ));
            }
            if c == i {
                return Err(ctx.err(
                    format!("nodes[{i}]"),
                    "node is its own child (cycle in the node hierarchy)",
                ));
            }
            if let Some(slot) = parent.get_mut(c) {
                if let Some(p) = *slot {
                    return Err(ctx.err(
                        format!("nodes[{c}]"),
                        format!("node has two parents (nodes[{p}] and nodes[{i}])"),
                    ));
                }
                *slot = Some(i);
            }
        }
    }
    // Cycles: follow parent links, colouring nodes (1 = on the current path, 2 = done).
    let mut state = vec![0u8; nn];
    for start in 0..nn {
        let mut path = Vec::new();
        let mut cur = Some(start);
        while let Some(c) = cur {
            match state.get(c).copied() {
                Some(0) => {
                    if let Some(s) = state.get_mut(c) {
                        *s = 1;
                    }
                    path.push(c);
                    cur = parent.get(c).copied().flatten();
                }
                Some(1) => {
                    return Err(ctx.err(format!("nodes[{c}]"), "cycle in the node hierarchy"));
                }
                _ => break,
            }
        }
        for c in path {
            if let Some(s) = state.get_mut(c) {
                *s = 2;
            }
        }
    }

    // Roots of the displayed scene.
    let roots: Vec<usize> = {
        let scene_index = match ctx.root.scene {
            Some(s) => Some((s.value(), "scene")),
            None if !ctx.root.scenes.is_empty() => Some((0, "scenes[0]")),
            None => None,
        };
        match scene_index {
            Some((s, el)) => {
                let scene = ctx
                    .root
                    .scenes
                    .get(s)
                    .ok_or_else(|| ctx.err(el, format!("scenes[{s}] does not exist")))?;
                let mut roots = Vec::with_capacity(scene.nodes.len());
                for (k, n) in scene.nodes.iter().enumerate() {
                    let n = n.value();
                    if n >= nn {
                        return Err(ctx.err(
                            format!("scenes[{s}].nodes[{k}]"),
                            format!("nodes[{n}] does not exist"),
                        ));
                    }
                    roots.push(n);
                }
                roots
            }
            None => (0..nn)
                .filter(|&i| parent.get(i).copied().flatten().is_none())
                .collect(),
        }
    };
    let mut reachable = vec![false; nn];
    let mut stack = roots;
    while let Some(i) = stack.pop() {
        match reachable.get_mut(i) {
            Some(r) if !*r => *r = true,
            _ => continue,
        }
        if let Some(node) = nodes.get(i) {
            stack.extend(node.children.iter().flatten().map(|c| c.value()));
        }
    }
    if nn == 0 && !ctx.root.meshes.is_empty() {
        b.warn("the file has meshes but no nodes; nothing is instanced".into());
    }

    // Nodes (all of them, so indices match the file); meshes only on reachable ones.
    for (i, node) in nodes.iter().enumerate() {
        let local = node_local(ctx, i, node)?;
        let is_reachable = reachable.get(i).copied().unwrap_or(false);
        let mesh = match (node.mesh, is_reachable) {
            (Some(m), true) => Some(load_mesh(ctx, b, m.value(), i)?),
            _ => None,
        };
        if is_reachable && node.skin.is_some() {
            b.warn(format!(
                "nodes[{i}]: skinning is not supported; the mesh is shown unskinned"
            ));
        }
        b.scene.nodes.push(Node {
            name: node.name.clone().unwrap_or_else(|| format!("nodes[{i}]")),
            local,
            parent: parent.get(i).copied().flatten(),
            mesh,
        });
    }

    // Lights and cameras of reachable nodes, in node order.
    let lights: &[json::extensions::scene::khr_lights_punctual::Light] = ctx
        .root
        .extensions
        .as_ref()
        .and_then(|e| e.khr_lights_punctual.as_ref())
        .map_or(&[], |l| &l.lights[..]);
    let mut world_memo: Vec<Option<DMat4>> = vec![None; nn];
    for (i, node) in nodes.iter().enumerate() {
        if !reachable.get(i).copied().unwrap_or(false) {
            continue;
        }
        let has_light = node
            .extensions
            .as_ref()
            .is_some_and(|e| e.khr_lights_punctual.is_some());
        if !has_light && node.camera.is_none() {
            continue;
        }
        let world = world_transform(&b.scene.nodes, &mut world_memo, i);
        if let Some(ext) = node
            .extensions
            .as_ref()
            .and_then(|e| e.khr_lights_punctual.as_ref())
        {
            let li = ext.light.value();
            let light = lights.get(li).ok_or_else(|| {
                ctx.err(
                    format!("nodes[{i}].extensions.KHR_lights_punctual.light"),
                    format!("KHR_lights_punctual.lights[{li}] does not exist"),
                )
            })?;
            add_light(ctx, b, i, li, light, world)?;
        }
        if let Some(c) = node.camera {
            let ci = c.value();
            let camera = ctx.root.cameras.get(ci).ok_or_else(|| {
                ctx.err(
                    format!("nodes[{i}].camera"),
                    format!("cameras[{ci}] does not exist"),
                )
            })?;
            add_camera(ctx, b, i, ci, camera, world)?;
        }
    }
    Ok(())
}

/// World transform of node `i`, memoised so that a deep hierarchy costs O(nodes) in all
/// (the hierarchy is known to be acyclic here).
fn world_transform(nodes: &[Node], memo: &mut [Option<DMat4>], i: usize) -> DMat4 {
    let mut chain = Vec::new();
    let mut cur = Some(i);
    let mut m = DMat4::IDENTITY;
    while let Some(c) = cur {
        if let Some(w) = memo.get(c).copied().flatten() {
            m = w;
            break;
        }
        chain.push(c);
        cur = nodes.get(c).and_then(|n| n.parent);
    }
    for &c in chain.iter().rev() {
        m *= nodes.get(c).map_or(DMat4::IDENTITY, |n| n.local);
        if let Some(slot) = memo.get_mut(c) {
            *slot = Some(m);
        }
    }
    m
}

fn add_light(
    ctx: &Ctx,
    b: &mut Builder,
    node: usize,
    li: usize,
    light: &json::extensions::scene::khr_lights_punctual::Light,
    world: DMat4,
) -> Result<()> {
    use json::extensions::scene::khr_lights_punctual::Type;
    let el = format!("extensions.KHR_lights_punctual.lights[{li}]");
    let kind = match light.type_ {
        Checked::Valid(t) => t,
        Checked::Invalid => return Err(ctx.err(format!("{el}.type"), "invalid light type")),
    };
    let (inner, outer) = match kind {
        Type::Spot => light
            .spot
            .as_ref()
            .map_or((0.0, std::f32::consts::FRAC_PI_4), |s| {
                (s.inner_cone_angle, s.outer_cone_angle)
            }),
        Type::Point | Type::Directional => {
            let what = if kind == Type::Point {
                "point"
            } else {
                "directional"
            };
            b.warn(format!(
                "nodes[{node}]: {what} light {el} is not supported (spot lights only); skipped"
            ));
            return Ok(());
        }
    };
    if !(light.intensity.is_finite() && light.intensity >= 0.0) {
        return Err(ctx.err(
            format!("{el}.intensity"),
            format!("intensity {} is not a finite value ≥ 0", light.intensity),
        ));
    }
    if !finite_all(&light.color) || light.color.iter().any(|&c| c < 0.0) {
        return Err(ctx.err(
            format!("{el}.color"),
            "color must be finite and non-negative",
        ));
    }
    if !(inner.is_finite() && outer.is_finite()) {
        return Err(ctx.err(format!("{el}.spot"), "non-finite cone angle"));
    }
    let half_pi = std::f32::consts::FRAC_PI_2;
    let outer_c = outer.clamp(1e-4, half_pi);
    let inner_c = inner.clamp(0.0, outer_c * 0.999);
    if outer_c != outer || inner_c != inner {
        b.warn(format!(
            "{el}: cone angles inner {inner}, outer {outer} are outside 0 ≤ inner < outer ≤ π/2; \
             clamped to {inner_c}, {outer_c}"
        ));
    }
    let position = world.transform_point3(DVec3::ZERO);
    let direction = world.transform_vector3(DVec3::NEG_Z);
    let len = direction.length();
    if !(len.is_finite() && len > 1e-12 && position.is_finite()) {
        b.warn(format!(
            "nodes[{node}]: light {el} has a degenerate transform; skipped"
        ));
        return Ok(());
    }
    b.scene.add_light(SpotLight {
        position,
        direction: direction / len,
        intensity: light.intensity,
        color: Vec3::from_array(light.color),
        inner_cone: inner_c,
        outer_cone: outer_c,
    });
    Ok(())
}

fn add_camera(
    ctx: &Ctx,
    b: &mut Builder,
    node: usize,
    ci: usize,
    camera: &json::Camera,
    world: DMat4,
) -> Result<()> {
    use json::camera::Type;
    let el = format!("cameras[{ci}]");
    match camera.type_ {
        Checked::Valid(Type::Perspective) => {}
        Checked::Valid(Type::Orthographic) => {
            b.warn(format!(
                "nodes[{node}]: orthographic camera {el} is not supported; skipped"
            ));
            return Ok(());
        }
        Checked::Invalid => return Err(ctx.err(format!("{el}.type"), "invalid camera type")),
    }
    let p = camera.perspective.as_ref().ok_or_else(|| {
        ctx.err(
            format!("{el}.perspective"),
            "perspective camera without perspective properties",
        )
    })?;
    if !(p.yfov.is_finite() && p.yfov > 0.0 && p.yfov < std::f32::consts::PI) {
        return Err(ctx.err(
            format!("{el}.perspective.yfov"),
            format!("yfov {} is not in (0, π)", p.yfov),
        ));
    }
    let eye = world.transform_point3(DVec3::ZERO);
    let forward = world.transform_vector3(DVec3::NEG_Z);
    let up = world.transform_vector3(DVec3::Y);
    let ok = eye.is_finite() && forward.length() > 1e-12 && forward.is_finite() && up.is_finite();
    let forward = forward.normalize_or_zero();
    let up = (up - forward * up.dot(forward)).normalize_or_zero();
    if !ok || up == DVec3::ZERO || forward == DVec3::ZERO {
        b.warn(format!(
            "nodes[{node}]: camera {el} has a degenerate transform; skipped"
        ));
        return Ok(());
    }
    b.scene.cameras.push(Camera {
        eye,
        forward,
        up,
        fov_y: p.yfov,
    });
    Ok(())
}

fn load_mesh(ctx: &Ctx, b: &mut Builder, m: usize, node: usize) -> Result<usize> {
    if let Some(&s) = b.mesh_map.get(&m) {
        return Ok(s);
    }
    let mesh = ctx.root.meshes.get(m).ok_or_else(|| {
        ctx.err(
            format!("nodes[{node}].mesh"),
            format!("meshes[{m}] does not exist"),
        )
    })?;
    let mut primitives = Vec::with_capacity(mesh.primitives.len());
    for (p, prim) in mesh.primitives.iter().enumerate() {
        if let Some(prim) = load_primitive(ctx, b, m, p, prim)? {
            primitives.push(prim);
        }
    }
    b.scene.meshes.push(Mesh {
        name: mesh.name.clone().unwrap_or_else(|| format!("meshes[{m}]")),
        primitives,
    });
    let s = b.scene.meshes.len() - 1;
    b.mesh_map.insert(m, s);
    Ok(s)
}

fn to_vec3s(v: &[f32]) -> Vec<[f32; 3]> {
    v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
}

fn dv(p: [f32; 3]) -> DVec3 {
    DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

fn load_primitive(
    ctx: &Ctx,
    b: &mut Builder,
    m: usize,
    p: usize,
    prim: &json::mesh::Primitive,
) -> Result<Option<Primitive>> {
    let el = format!("meshes[{m}].primitives[{p}]");
    let mode = match prim.mode {
        Checked::Valid(mode) => mode,
        Checked::Invalid => return Err(ctx.err(format!("{el}.mode"), "invalid primitive mode")),
    };
    let mode_name = match mode {
        Mode::Points => Some("POINTS"),
        Mode::Lines => Some("LINES"),
        Mode::LineLoop => Some("LINE_LOOP"),
        Mode::LineStrip => Some("LINE_STRIP"),
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan => None,
    };
    if let Some(name) = mode_name {
        b.warn(format!(
            "{el}: mode {name} is not supported (triangles only); primitive skipped"
        ));
        return Ok(None);
    }
    if prim.targets.as_ref().is_some_and(|t| !t.is_empty()) {
        b.warn(format!(
            "{el}: morph targets are not supported; base shape used"
        ));
    }
    let attr = |s: Semantic| prim.attributes.get(&Checked::Valid(s)).map(|i| i.value());

    let pos_idx = attr(Semantic::Positions)
        .ok_or_else(|| ctx.err(el.clone(), "primitive has no POSITION attribute"))?;
    let positions =
        to_vec3s(&ctx.read_floats(pos_idx, AccType::Vec3, &format!("{el}.attributes.POSITION"))?);
    let n = positions.len();
    if n > u32::MAX as usize {
        return Err(ctx.err(el, format!("{n} vertices exceed the u32 index range")));
    }
    let same_count = |len: usize, name: &str, idx: usize| -> Result<()> {
        if len != n {
            return Err(ctx.err(
                format!("accessors[{idx}]"),
                format!("{name} of {el} has {len} elements but POSITION has {n}"),
            ));
        }
        Ok(())
    };

    let file_normals = match attr(Semantic::Normals) {
        Some(i) => {
            let v =
                to_vec3s(&ctx.read_floats(i, AccType::Vec3, &format!("{el}.attributes.NORMAL"))?);
            same_count(v.len(), "NORMAL", i)?;
            Some(v)
        }
        None => None,
    };
    let uvs: Vec<[f32; 2]> = match attr(Semantic::TexCoords(0)) {
        Some(i) => {
            use ComponentType::*;
            let v: Vec<f32> = ctx.read_accessor(
                i,
                AccType::Vec2,
                &format!("{el}.attributes.TEXCOORD_0"),
                &[F32, U8, U16, I8, I16],
            )?;
            if !finite_all(&v) {
                return Err(ctx.err(
                    format!("accessors[{i}]"),
                    format!("non-finite TEXCOORD_0 value in {el}"),
                ));
            }
            let v: Vec<[f32; 2]> = v.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
            same_count(v.len(), "TEXCOORD_0", i)?;
            v
        }
        None => Vec::new(),
    };

    // Indices, all checked against the vertex count.
    let raw_indices: Vec<u32> = match prim.indices {
        Some(ii) => {
            let ii = ii.value();
            use ComponentType::*;
            let idx: Vec<u32> = ctx.read_accessor(
                ii,
                AccType::Scalar,
                &format!("{el}.indices"),
                &[U8, U16, U32],
            )?;
            if let Some((k, &v)) = idx.iter().enumerate().find(|(_, &v)| v as usize >= n) {
                return Err(ctx.err(
                    el,
                    format!("index {v} (element {k} of accessors[{ii}]) is out of range: the vertex count is {n}"),
                ));
            }
            idx
        }
        None => {
            ctx.charge_geometry(n as u64 * 4, &el)?;
            (0..n as u32).collect()
        }
    };
    let mut indices: Vec<u32> = match mode {
        Mode::TriangleStrip => {
            let mut out = Vec::with_capacity(raw_indices.len().saturating_sub(2) * 3);
            for (i, w) in raw_indices.windows(3).enumerate() {
                let (a, b1, c) = (w[0], w[1], w[2]);
                if a == b1 || b1 == c || a == c {
                    continue;
                }
                if i % 2 == 0 {
                    out.extend([a, b1, c]);
                } else {
                    out.extend([a, c, b1]);
                }
            }
            out
        }
        Mode::TriangleFan => {
            let mut out = Vec::with_capacity(raw_indices.len().saturating_sub(2) * 3);
            if let Some((&first, rest)) = raw_indices.split_first() {
                for w in rest.windows(2) {
                    out.extend([w[0], w[1], first]);
                }
            }
            out
        }
        _ => raw_indices,
    };
    if !indices.len().is_multiple_of(3) {
        b.warn(format!(
            "{el}: {} indices are not a multiple of 3; the last partial triangle is dropped",
            indices.len()
        ));
        indices.truncate(indices.len() / 3 * 3);
    }
    if indices.is_empty() {
        b.warn(format!("{el}: no triangles; primitive skipped"));
        return Ok(None);
    }

    let normals = match file_normals {
        Some(v) => v
            .into_iter()
            .map(|nrm| {
                let d = dv(nrm);
                let l = d.length();
                if l > 1e-20 {
                    (d / l).as_vec3().to_array()
                } else {
                    [0.0, 1.0, 0.0]
                }
            })
            .collect(),
        None => generate_normals(&positions, &indices),
    };

    // Material, and whether its normal map can be used.
    let gm = prim.material.map(|i| i.value());
    let gltf_material = match gm {
        Some(g) => Some(ctx.root.materials.get(g).ok_or_else(|| {
            ctx.err(
                format!("{el}.material"),
                format!("materials[{g}] does not exist"),
            )
        })?),
        None => None,
    };
    let wants_normal_map = gltf_material
        .and_then(|mat| mat.normal_texture.as_ref())
        .is_some_and(|nt| nt.tex_coord == 0);
    let mut keep_normal_map = wants_normal_map;
    let mut tangents = Vec::new();
    if wants_normal_map {
        let file_tangents = match (attr(Semantic::Tangents), attr(Semantic::Normals)) {
            // Tangents are only meaningful with the file's own normals (glTF 2.0 §3.7.2.1).
            (Some(ti), Some(_)) => {
                let v = ctx.read_floats(ti, AccType::Vec4, &format!("{el}.attributes.TANGENT"))?;
                let v: Vec<[f32; 4]> = v
                    .chunks_exact(4)
                    .map(|c| [c[0], c[1], c[2], if c[3] < 0.0 { -1.0 } else { 1.0 }])
                    .collect();
                same_count(v.len(), "TANGENT", ti)?;
                Some(v)
            }
            _ => None,
        };
        if let Some(t) = file_tangents {
            tangents = t;
        } else if !uvs.is_empty() {
            tangents = generate_tangents(&positions, &normals, &uvs, &indices);
        } else {
            keep_normal_map = false;
            b.warn(format!(
                "{el}: materials[{}] has a normal map but the primitive has neither TANGENT nor TEXCOORD_0; \
                 normal map dropped",
                gm.unwrap_or_default()
            ));
        }
    }
    let material = material_index(ctx, b, gm, keep_normal_map)?;
    let vertex_bytes = (n as u64) * (12 + 12 + 8 + 16) + indices.len() as u64 * 4;
    ctx.charge_geometry(vertex_bytes, &el)?;
    Ok(Some(Primitive {
        positions,
        normals,
        uvs,
        tangents,
        indices,
        material,
    }))
}

/// Area-weighted vertex normals (the cross product's length is twice the triangle area).
fn generate_normals(positions: &[[f32; 3]], indices: &[u32]) -> Vec<[f32; 3]> {
    let mut acc = vec![DVec3::ZERO; positions.len()];
    for t in indices.chunks_exact(3) {
        let (i0, i1, i2) = (t[0] as usize, t[1] as usize, t[2] as usize);
        let (Some(&p0), Some(&p1), Some(&p2)) =
            (positions.get(i0), positions.get(i1), positions.get(i2))
        else {
            continue;
        };
        let n = (dv(p1) - dv(p0)).cross(dv(p2) - dv(p0));
        for i in [i0, i1, i2] {
            if let Some(a) = acc.get_mut(i) {
                *a += n;
            }
        }
    }
    acc.into_iter()
        .map(|n| {
            let l = n.length();
            if l > 0.0 && l.is_finite() {
                (n / l).as_vec3().to_array()
            } else {
                [0.0, 1.0, 0.0]
            }
        })
        .collect()
}

/// Any unit vector orthogonal to the unit vector `n`.
fn orthogonal(n: DVec3) -> DVec3 {
    let a = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    (a - n * n.dot(a)).normalize_or(DVec3::X)
}

/// Per-vertex tangents from per-triangle UV gradients, accumulated, then Gram–Schmidt
/// orthogonalised against the normal; w is the bitangent sign.
fn generate_tangents(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    uvs: &[[f32; 2]],
    indices: &[u32],
) -> Vec<[f32; 4]> {
    let n = positions.len();
    let mut tan = vec![DVec3::ZERO; n];
    let mut bit = vec![DVec3::ZERO; n];
    for t in indices.chunks_exact(3) {
        let ids = [t[0] as usize, t[1] as usize, t[2] as usize];
        let (Some(&p0), Some(&p1), Some(&p2)) = (
            positions.get(ids[0]),
            positions.get(ids[1]),
            positions.get(ids[2]),
        ) else {
            continue;
        };
        let (Some(&u0), Some(&u1), Some(&u2)) = (uvs.get(ids[0]), uvs.get(ids[1]), uvs.get(ids[2]))
        else {
            continue;
        };
        let e1 = dv(p1) - dv(p0);
        let e2 = dv(p2) - dv(p0);
        let (du1, dv1) = (f64::from(u1[0] - u0[0]), f64::from(u1[1] - u0[1]));
        let (du2, dv2) = (f64::from(u2[0] - u0[0]), f64::from(u2[1] - u0[1]));
        let det = du1 * dv2 - du2 * dv1;
        if det.is_nan() || det.abs() <= 1e-20 {
            continue;
        }
        let r = 1.0 / det;
        let sdir = (e1 * dv2 - e2 * dv1) * r;
        let tdir = (e2 * du1 - e1 * du2) * r;
        if !(sdir.is_finite() && tdir.is_finite()) {
            continue;
        }
        for i in ids {
            if let (Some(a), Some(b)) = (tan.get_mut(i), bit.get_mut(i)) {
                *a += sdir;
                *b += tdir;
            }
        }
    }
    (0..n)
        .map(|i| {
            let nrm = normals.get(i).map_or(DVec3::Y, |&v| dv(v));
            let t = tan.get(i).copied().unwrap_or_default();
            let b = bit.get(i).copied().unwrap_or_default();
            let t_orth = t - nrm * nrm.dot(t);
            let l = t_orth.length();
            let t_unit = if l > 1e-12 * (1.0 + t.length()) && l.is_finite() {
                t_orth / l
            } else {
                orthogonal(nrm)
            };
            let w = if nrm.cross(t_unit).dot(b) < 0.0 {
                -1.0
            } else {
                1.0
            };
            let t32 = t_unit.as_vec3();
            [t32.x, t32.y, t32.z, w]
        })
        .collect()
}

fn unit_factor(ctx: &Ctx, v: f32, element: String) -> Result<f32> {
    if !v.is_finite() {
        return Err(ctx.err(element, "non-finite value"));
    }
    Ok(v.clamp(0.0, 1.0))
}

fn material_index(
    ctx: &Ctx,
    b: &mut Builder,
    gm: Option<usize>,
    keep_normal_map: bool,
) -> Result<usize> {
    let key = (gm, keep_normal_map && gm.is_some());
    if let Some(&s) = b.material_map.get(&key) {
        return Ok(s);
    }
    let material = match gm {
        None => Material::default(),
        Some(g) => {
            let el = format!("materials[{g}]");
            let m = ctx
                .root
                .materials
                .get(g)
                .ok_or_else(|| ctx.err(el.clone(), "material does not exist"))?;
            let pbr = &m.pbr_metallic_roughness;
            let bcf = pbr.base_color_factor.0;
            if !finite_all(&bcf) {
                return Err(ctx.err(
                    format!("{el}.pbrMetallicRoughness.baseColorFactor"),
                    "non-finite value",
                ));
            }
            let metallic = unit_factor(
                ctx,
                pbr.metallic_factor.0,
                format!("{el}.pbrMetallicRoughness.metallicFactor"),
            )?;
            let roughness = unit_factor(
                ctx,
                pbr.roughness_factor.0,
                format!("{el}.pbrMetallicRoughness.roughnessFactor"),
            )?;
            let base_color_texture = match &pbr.base_color_texture {
                Some(info) => texture_index(
                    ctx,
                    b,
                    info.index.value(),
                    info.tex_coord,
                    TextureUsage::Color,
                    format!("{el}.pbrMetallicRoughness.baseColorTexture"),
                )?,
                None => None,
            };
            let metallic_roughness_texture = match &pbr.metallic_roughness_texture {
                Some(info) => texture_index(
                    ctx,
                    b,
                    info.index.value(),
                    info.tex_coord,
                    TextureUsage::Data,
                    format!("{el}.pbrMetallicRoughness.metallicRoughnessTexture"),
                )?,
                None => None,
            };
            let mut normal_scale = 1.0;
            let normal_texture = match (&m.normal_texture, keep_normal_map) {
                (Some(nt), true) => {
                    if !nt.scale.is_finite() {
                        return Err(
                            ctx.err(format!("{el}.normalTexture.scale"), "non-finite value")
                        );
                    }
                    normal_scale = nt.scale;
                    texture_index(
                        ctx,
                        b,
                        nt.index.value(),
                        nt.tex_coord,
                        TextureUsage::Data,
                        format!("{el}.normalTexture"),
                    )?
                }
                (Some(nt), false) if nt.tex_coord != 0 => {
                    b.warn(format!(
                        "{el}.normalTexture: texCoord {} is not supported (TEXCOORD_0 only); texture ignored",
                        nt.tex_coord
                    ));
                    None
                }
                _ => None,
            };
            // KHR_materials_specular: the scalar factor scales the dielectric F0 (0.04); the
            // coloured factor and the textures are not supported.
            let mut specular_factor = 1.0;
            if let Some(spec) = m.extensions.as_ref().and_then(|e| e.specular.as_ref()) {
                let sel = format!("{el}.extensions.KHR_materials_specular");
                specular_factor = unit_factor(ctx, spec.specular_factor.0, format!("{sel}.specularFactor"))?;
                if spec.specular_texture.is_some() || spec.specular_color_texture.is_some() {
                    b.warn(format!("{sel}: specular textures are not supported; the factor alone is used"));
                }
                if spec.specular_color_factor.0 != [1.0; 3] {
                    b.warn(format!("{sel}.specularColorFactor: coloured specular is not supported; treated as white"));
                }
            }
            let emissive = m.emissive_factor.0;
            if m.emissive_texture.is_some() || emissive.iter().any(|&e| e != 0.0) {
                b.warn(format!("{el}: emission is not supported; ignored"));
            }
            if !matches!(
                m.alpha_mode,
                Checked::Valid(json::material::AlphaMode::Opaque)
            ) {
                b.warn(format!(
                    "{el}: alphaMode other than OPAQUE is not supported; rendered opaque"
                ));
            }
            Material {
                name: m.name.clone().unwrap_or_else(|| el.clone()),
                base_color_factor: bcf.map(|c| c.clamp(0.0, 1.0)),
                metallic_factor: metallic,
                roughness_factor: roughness,
                base_color_texture,
                metallic_roughness_texture,
                normal_texture,
                normal_scale,
                specular_factor,
            }
        }
    };
    b.scene.materials.push(material);
    let s = b.scene.materials.len() - 1;
    b.material_map.insert(key, s);
    Ok(s)
}

fn texture_index(
    ctx: &Ctx,
    b: &mut Builder,
    ti: usize,
    tex_coord: u32,
    usage: TextureUsage,
    element: String,
) -> Result<Option<usize>> {
    if tex_coord != 0 {
        b.warn(format!(
            "{element}: texCoord {tex_coord} is not supported (TEXCOORD_0 only); texture ignored"
        ));
        return Ok(None);
    }
    let texture = ctx.root.textures.get(ti).ok_or_else(|| {
        ctx.err(
            format!("{element}.index"),
            format!("textures[{ti}] does not exist"),
        )
    })?;
    let ii = texture.source.value();
    let image = ctx.root.images.get(ii).ok_or_else(|| {
        ctx.err(
            format!("textures[{ti}].source"),
            format!("images[{ii}] does not exist"),
        )
    })?;
    let key = (ii, usage == TextureUsage::Color);
    if let Some(&s) = b.texture_map.get(&key) {
        return Ok(Some(s));
    }
    let (width, height, rgba8) = ctx.decode_image(ii)?;
    let name = image
        .name
        .clone()
        .or_else(|| image.uri.clone().filter(|u| uri_scheme(u).is_none()))
        .unwrap_or_else(|| format!("images[{ii}]"));
    b.scene.textures.push(Texture {
        name,
        width,
        height,
        rgba8,
        usage,
    });
    let s = b.scene.textures.len() - 1;
    b.texture_map.insert(key, s);
    Ok(Some(s))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trips() {
        assert_eq!(base64_decode(b"").as_deref(), Some(&b""[..]));
        assert_eq!(base64_decode(b"TQ==").as_deref(), Some(&b"M"[..]));
        assert_eq!(base64_decode(b"TWE=").as_deref(), Some(&b"Ma"[..]));
        assert_eq!(base64_decode(b"TWFu").as_deref(), Some(&b"Man"[..]));
        assert_eq!(base64_decode(b"TWFuTWE").as_deref(), Some(&b"ManMa"[..]));
        assert_eq!(base64_decode(b"TWFu!"), None);
        assert_eq!(base64_decode(b"TQ==TQ=="), None);
        assert_eq!(base64_decode(b"TWFuT"), None);
    }

    #[test]
    fn percent_and_scheme() {
        assert_eq!(percent_decode(b"a%20b").as_deref(), Some(&b"a b"[..]));
        assert_eq!(percent_decode(b"a%2"), None);
        assert_eq!(percent_decode(b"a%zz"), None);
        assert_eq!(uri_scheme("http://x"), Some("http"));
        assert_eq!(
            uri_scheme("data:application/octet-stream;base64,AA=="),
            Some("data")
        );
        assert_eq!(uri_scheme("file.bin"), None);
        assert_eq!(uri_scheme("./a:b.bin"), None);
    }

    #[test]
    fn glb_lengths_never_panic() {
        let f = Path::new("x.glb");
        for data in [
            &b"glTF"[..],
            b"glTF\x02\0\0\0\x00\0\0\0",
            b"glTF\x02\0\0\0\x0c\0\0\0",
            b"glTF\x02\0\0\0\x14\0\0\0\xff\xff\xff\xffJSON",
            b"glTF\x01\0\0\0\x0c\0\0\0",
        ] {
            assert!(parse_glb(f, data).is_err());
        }
    }
}
