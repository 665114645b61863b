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
//!
//! Layout: this module holds the entry point [`load`], the limits, the loading context
//! (`Ctx`: the JSON plus checked binary data) and the scene `Builder`. The work is done in
//! `container` (GLB chunks), `uri` (data: URIs and files inside the scene folder), `buffer`
//! (buffers and bufferViews), `accessor`, `image` (images and textures), `mesh` (primitives,
//! generated normals and tangents), `material`, `nodes` (hierarchy, transforms, cameras),
//! `lights` (KHR_lights_punctual), `animation` (node animations) and `raw` (f64 node
//! transforms and KHR_texture_transform, which the crate's model rounds or lacks).

mod accessor;
mod animation;
mod buffer;
mod container;
mod image;
mod lights;
mod material;
mod mesh;
mod nodes;
mod raw;
mod uri;

use std::borrow::Cow;
use std::cell::Cell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use gltf::json;

use crate::error::{Error, Result};
use crate::scene::Scene;

use buffer::ViewInfo;
pub(crate) use mesh::generate_tangents;
use container::parse_glb;
use nodes::build_scene;

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
/// Default of [`LoadOptions::max_texture_bytes`]: 512 MiB holds 32 textures of 2048² RGBA8
/// (BoomBox, the scene of `shared/scenes` with the largest textures, keeps three of them,
/// 48 MiB), while a 16384² image (1 GiB as RGBA8, from a PNG of a few hundred kilobytes) is
/// refused.
pub const DEFAULT_MAX_TEXTURE_BYTES: u64 = 512 << 20;
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
    "KHR_texture_transform",
];

/// Limits of one load that a caller may change (the others are constants of this module).
#[derive(Clone, Debug)]
pub struct LoadOptions {
    /// Budget for decoded texture memory, in bytes: the RGBA8 texels of every texture kept
    /// so far plus, while an image is decoded, its decoder output in the file's own pixel
    /// format (the budget is checked from the image header, before anything is decoded). An
    /// image that does not fit is refused with an [`Error::Scene`]; it is not downscaled,
    /// because the JPEG decoder cannot decode at reduced size, so a downscale would first
    /// allocate the full image (docs/security.md).
    pub max_texture_bytes: u64,
}

impl Default for LoadOptions {
    fn default() -> Self {
        Self { max_texture_bytes: DEFAULT_MAX_TEXTURE_BYTES }
    }
}

/// Loads a `.gltf` or `.glb` scene with the default [`LoadOptions`].
pub fn load(path: &Path) -> Result<Scene> {
    load_with(path, &LoadOptions::default())
}

/// Loads a `.gltf` or `.glb` scene. Only nodes reachable from the default scene (or scene 0,
/// or every root node when the file has no scene) instance meshes, lights and cameras.
pub fn load_with(path: &Path, options: &LoadOptions) -> Result<Scene> {
    if options.max_texture_bytes == 0 {
        return Err(Error::invalid("max_texture_bytes", "must be a positive number of bytes, got 0"));
    }
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
    let raw = raw::parse(json_bytes)
        .map_err(|e| Error::scene(path, "JSON", format!("invalid glTF JSON (node transforms or texture transforms): {e}")))?;

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
        raw,
        buffers: Vec::new(),
        views: Vec::new(),
        geometry_bytes: Cell::new(0),
        unbacked_elements: Cell::new(0),
        texture_bytes: Cell::new(0),
        max_texture_bytes: options.max_texture_bytes,
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
    ctx.warn_extensions(&mut b);
    build_scene(&ctx, &mut b)?;
    Ok(b.scene)
}

/// Loading context: the JSON plus checked binary data.
struct Ctx<'a> {
    file: &'a Path,
    /// Canonical folder of the scene file; every referenced file must lie under it.
    base: PathBuf,
    root: json::Root,
    /// What `root` reads too coarsely or not at all: f64 node transforms, texture transforms.
    raw: raw::RawRoot,
    buffers: Vec<Cow<'a, [u8]>>,
    views: Vec<ViewInfo>,
    geometry_bytes: Cell<u64>,
    unbacked_elements: Cell<u64>,
    /// Decoded RGBA8 bytes of the textures kept so far.
    texture_bytes: Cell<u64>,
    max_texture_bytes: u64,
    image_file_bytes: Cell<u64>,
}

impl Ctx<'_> {
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

    /// glTF 2.0: every entry of `extensionsRequired` must also be in `extensionsUsed`.
    /// The loader does not need the second list, so a file that breaks the rule loads, but
    /// says so: other tools may refuse it.
    fn warn_extensions(&self, b: &mut Builder) {
        for (i, ext) in self.root.extensions_required.iter().enumerate() {
            if !self.root.extensions_used.contains(ext) {
                b.warn(format!(
                    "extensionsRequired[{i}]: {ext} is not listed in extensionsUsed \
                     (glTF 2.0 requires every required extension to be listed as used)"
                ));
            }
        }
    }
}

/// The scene being built, with the maps that share meshes, materials and textures.
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
