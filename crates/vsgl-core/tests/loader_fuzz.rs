//! Bounded, deterministic fuzzing of the glTF loader through its public entry point
//! (`scene::gltf::load_with`), for CI: a few thousand mutated files in well under two minutes.
//!
//! Seeds: the real scenes of `shared/scenes` (copied, with their buffers and images, into a
//! temporary folder; skipped with a message when the folder is absent) and two small synthetic
//! files that reach every part of the loader (a `.gltf` with data: URIs and an embedded PNG; a
//! `.glb` with a BIN chunk, an image in a bufferView, a hierarchy, a camera and a spot light;
//! the `.gltf` also has an animation, and every scene that loads is posed at a few times).
//! Mutations, from one seeded generator: bit flips and byte overwrites, truncation, JSON
//! numbers replaced by boundary values, JSON fields deleted, retyped, duplicated or pointed at
//! other indices, GLB header and chunk lengths corrupted, and bytes of a referenced `.bin`.
//!
//! Each case must end, within `CASE_LIMIT`, in `Ok` or a clean `Error::Scene`: a panic, any
//! other error kind or a case over the limit fails the test, which names the case (its
//! seed file, number and mutations) and keeps the offending input for replay. Mutations that
//! corrupt a `.bin` only flip, overwrite or truncate bytes.

use std::panic::{catch_unwind, AssertUnwindSafe};
mod common;

use common::{base64, glb, tmpdir};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use serde_json::{json, Value};
use vsgl_core::scene::gltf::{load_with, LoadOptions};
use vsgl_core::Error;

/// Mutated files per seed file; with the 7 seeds of today about 4200 cases (6 to 25 s in release on
/// two CPU cores).
const CASES_PER_SEED: usize = 600;
/// Wall-clock cap of the whole run: a slow machine or a debug build stops early (the cases
/// run are then a prefix of the same deterministic sequence) and says so.
const RUN_LIMIT: Duration = Duration::from_secs(90);
/// Longest a single load may take. The slowest unmutated seed (FlightHelmet: a 3 MB buffer
/// and 512² PNGs) loads in a few tens of milliseconds; a limit 100× above that catches loops
/// and quadratic blow-ups without failing on a busy machine.
const CASE_LIMIT: Duration = Duration::from_secs(5);
/// A small texture budget keeps each case cheap (big images are refused from their headers)
/// and exercises the budget check itself.
const TEXTURE_BUDGET: u64 = 4 << 20;

/// SplitMix64: small, seedable and good enough to pick mutations.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        if n == 0 { 0 } else { (self.next() % n as u64) as usize }
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Numbers at the edges of what the loader's checks compare against.
const BOUNDARY_NUMBERS: &[&str] = &[
    "0", "-1", "1", "2", "3", "4", "255", "256", "65535", "65536", "2147483647", "2147483648",
    "4294967295", "4294967296", "9007199254740993", "18446744073709551615", "1e308", "-1e308",
    "1e-320", "0.5", "-0.0", "16384", "16385", "5120", "5121", "5123", "5125", "5126",
];

/// A seed: the file to mutate, in a folder holding whatever it references.
struct Seed {
    name: String,
    folder: PathBuf,
    bytes: Vec<u8>,
    /// Buffer files next to it that a mutation may also corrupt.
    bins: Vec<PathBuf>,
}


fn copy_folder(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_folder(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

fn shared_scene_seeds(work: &Path) -> Vec<Seed> {
    let shared = std::env::var_os("VSGL_SHARED_SCENES")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes"));
    let Ok(folders) = std::fs::read_dir(&shared) else {
        println!(
            "skipping the real scenes: {} not found (set VSGL_SHARED_SCENES to the shared scene folder); \
             fuzzing the synthetic seeds only",
            shared.display()
        );
        return Vec::new();
    };
    let mut folders: Vec<PathBuf> = folders.flatten().map(|e| e.path()).filter(|p| p.is_dir()).collect();
    folders.sort();
    let mut seeds = Vec::new();
    for folder in folders {
        let copy = work.join(folder.file_name().unwrap());
        copy_folder(&folder, &copy);
        let mut files: Vec<PathBuf> = std::fs::read_dir(&copy).unwrap().flatten().map(|e| e.path()).collect();
        files.sort();
        let bins: Vec<PathBuf> = files.iter().filter(|p| p.extension().is_some_and(|e| e == "bin")).cloned().collect();
        for f in files.iter().filter(|p| p.extension().is_some_and(|e| e == "gltf" || e == "glb")) {
            seeds.push(Seed {
                name: f.file_name().unwrap().to_string_lossy().into_owned(),
                folder: copy.clone(),
                bytes: std::fs::read(f).unwrap(),
                bins: bins.clone(),
            });
        }
    }
    seeds
}

fn png(w: u32, h: u32) -> Vec<u8> {
    let img = image::RgbaImage::from_fn(w, h, |x, y| image::Rgba([x as u8 * 40, y as u8 * 40, 128, 255]));
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}


/// Binary data of a textured quad (positions, normals, UVs, u16 indices) and its JSON parts.
fn quad_binary(image: Option<&[u8]>) -> (Vec<u8>, Value, Value) {
    let f32s = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let parts: Vec<Vec<u8>> = vec![
        f32s(&[0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.]),
        f32s(&[0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0., 1.]),
        f32s(&[0., 0., 1., 0., 1., 1., 0., 1.]),
        [0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()).collect(),
    ];
    let mut data = Vec::new();
    let mut views = Vec::new();
    for p in parts.iter().map(Vec::as_slice).chain(image) {
        while data.len() % 4 != 0 {
            data.push(0);
        }
        views.push(json!({"buffer": 0, "byteOffset": data.len(), "byteLength": p.len()}));
        data.extend_from_slice(p);
    }
    let accessors = json!([
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}
    ]);
    (data, Value::Array(views), accessors)
}

fn synthetic_seeds(work: &Path) -> Vec<Seed> {
    let dir = work.join("synthetic");
    std::fs::create_dir_all(&dir).unwrap();
    let mut seeds = Vec::new();

    // .gltf: buffer and image as data: URIs, a material using the texture, a child node, and
    // an animation (LINEAR translation, STEP rotation) in a second buffer, so mutations reach
    // the animation loader too.
    let (data, mut views, mut accessors) = quad_binary(None);
    let f32s = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let anim: Vec<u8> = [f32s(&[0.0, 1.0]), f32s(&[0., 0., 0., 1., 2., 3.]), f32s(&[0., 0., 0., 1., 0., 0.7071068, 0., 0.7071068])].concat();
    let first_view = views.as_array().map_or(0, Vec::len);
    for (offset, len) in [(0, 8), (8, 24), (32, 32)] {
        views.as_array_mut().unwrap().push(json!({"buffer": 1, "byteOffset": offset, "byteLength": len}));
    }
    let first_accessor = accessors.as_array().map_or(0, Vec::len);
    for (k, (count, ty)) in [(2, "SCALAR"), (2, "VEC3"), (2, "VEC4")].into_iter().enumerate() {
        accessors.as_array_mut().unwrap().push(json!({"bufferView": first_view + k, "componentType": 5126, "count": count, "type": ty}));
    }
    let gltf = json!({
        "asset": {"version": "2.0"},
        "buffers": [
            {"uri": format!("data:application/octet-stream;base64,{}", base64(&data)), "byteLength": data.len()},
            {"uri": format!("data:application/octet-stream;base64,{}", base64(&anim)), "byteLength": anim.len()}
        ],
        "bufferViews": views, "accessors": accessors,
        "animations": [{"name": "move", "samplers": [
            {"input": first_accessor, "output": first_accessor + 1},
            {"input": first_accessor, "output": first_accessor + 2, "interpolation": "STEP"}
        ], "channels": [
            {"sampler": 0, "target": {"node": 1, "path": "translation"}},
            {"sampler": 1, "target": {"node": 0, "path": "rotation"}}
        ]}],
        "images": [{"uri": format!("data:image/png;base64,{}", base64(&png(4, 4)))}],
        "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
        "nodes": [{"children": [1], "translation": [1, 2, 3]}, {"mesh": 0, "scale": [2, 2, 2]}],
        "scenes": [{"nodes": [0]}], "scene": 0
    });
    seeds.push(Seed { name: "synthetic.gltf".into(), folder: dir.clone(), bytes: serde_json::to_vec_pretty(&gltf).unwrap(), bins: vec![] });

    // .glb: BIN chunk with the image in a bufferView, a camera and a KHR_lights_punctual spot.
    let image = png(8, 8);
    let (data, views, accessors) = quad_binary(Some(&image));
    let glb_json = json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "spot", "intensity": 20.0, "color": [1, 1, 1], "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}}
        ]}},
        "buffers": [{"byteLength": data.len()}],
        "bufferViews": views, "accessors": accessors,
        "images": [{"bufferView": 4, "mimeType": "image/png"}],
        "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 0}}, "normalTexture": {"index": 0}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "nodes": [
            {"mesh": 0, "children": [1, 2]},
            {"camera": 0, "translation": [0, 0, 3]},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "rotation": [0.7071068, 0, 0, 0.7071068]}
        ],
        "scenes": [{"nodes": [0]}]
    });
    seeds.push(Seed { name: "synthetic.glb".into(), folder: dir, bytes: glb(&serde_json::to_vec(&glb_json).unwrap(), &data), bins: vec![] });
    seeds
}


/// The JSON text of a file (the whole `.gltf`, or a GLB's first chunk when it is readable)
/// and a function putting edited JSON back with consistent GLB lengths.
fn split_json(bytes: &[u8]) -> Option<(Vec<u8>, Option<Vec<u8>>)> {
    if !bytes.starts_with(b"glTF") {
        return Some((bytes.to_vec(), None));
    }
    let le = |o: usize| bytes.get(o..o + 4).map(|b| u32::from_le_bytes(b.try_into().unwrap()) as usize);
    let jlen = le(12)?;
    let json = bytes.get(20..20 + jlen)?.to_vec();
    let rest = 20 + jlen;
    let bin = match (le(rest), bytes.get(rest + 4..rest + 8)) {
        (Some(blen), Some(b"BIN\0")) => bytes.get(rest + 8..rest + 8 + blen).map(<[u8]>::to_vec),
        _ => None,
    };
    Some((json, Some(bin.unwrap_or_default())))
}

fn join_json(json: &[u8], bin: &Option<Vec<u8>>) -> Vec<u8> {
    match bin {
        None => json.to_vec(),
        Some(b) => glb(json, b),
    }
}

/// Every value of a JSON tree by pointer ("/meshes/0/primitives/0/indices"), objects and
/// arrays included.
fn pointers(v: &Value, at: String, out: &mut Vec<String>) {
    match v {
        Value::Object(m) => {
            for (k, c) in m {
                pointers(c, format!("{at}/{}", k.replace('~', "~0").replace('/', "~1")), out);
            }
        }
        Value::Array(a) => {
            for (i, c) in a.iter().enumerate() {
                pointers(c, format!("{at}/{i}"), out);
            }
        }
        _ => {}
    }
    out.push(at);
}

/// One structural JSON edit; returns what it did.
fn mutate_json_tree(rng: &mut Rng, root: &mut Value) -> String {
    let mut all = Vec::new();
    pointers(root, String::new(), &mut all);
    let at = rng.pick(&all).clone();
    let (parent_at, key) = match at.rfind('/') {
        Some(i) => (at[..i].to_string(), at[i + 1..].to_string()),
        None => (String::new(), String::new()),
    };
    let replacement = match rng.below(8) {
        0 => Value::Null,
        1 => json!("x"),
        2 => json!([]),
        3 => json!({}),
        4 => json!(-1),
        5 => json!(rng.below(8)),
        6 => json!(u64::MAX),
        _ => json!(1e300),
    };
    match rng.below(4) {
        // Delete a field or array element.
        0 => {
            match root.pointer_mut(&parent_at) {
                Some(Value::Object(m)) => {
                    m.remove(&key.replace("~1", "/").replace("~0", "~"));
                }
                Some(Value::Array(a)) => {
                    if let Ok(i) = key.parse::<usize>() {
                        if i < a.len() {
                            a.remove(i);
                        }
                    }
                }
                _ => {}
            }
            format!("delete {at}")
        }
        // Duplicate an array element (many references to one thing, repeated roots, ...).
        1 => {
            let copies = 1 + rng.below(3);
            if let Some(Value::Array(a)) = root.pointer_mut(&parent_at) {
                if let Ok(i) = key.parse::<usize>() {
                    if let Some(v) = a.get(i).cloned() {
                        for _ in 0..copies {
                            a.push(v.clone());
                        }
                    }
                }
            }
            format!("duplicate {at} ×{copies}")
        }
        // Retype or replace a value.
        _ => {
            let text = replacement.to_string();
            if let Some(v) = root.pointer_mut(&at) {
                *v = replacement;
            }
            format!("set {at} = {text}")
        }
    }
}

/// One mutation of a scene file's bytes; returns what it did.
fn mutate(rng: &mut Rng, bytes: &mut Vec<u8>) -> String {
    mutate_as(rng.below(7), rng, bytes)
}

/// Mutation `kind` (0, 1: bit flips or byte overwrites, 2: truncation, 3: a JSON number,
/// 4, 5: JSON structure, 6: GLB lengths).
fn mutate_as(kind: usize, rng: &mut Rng, bytes: &mut Vec<u8>) -> String {
    match kind {
        0 | 1 => {
            let mut what = Vec::new();
            for _ in 0..1 + rng.below(4) {
                if bytes.is_empty() {
                    break;
                }
                let at = rng.below(bytes.len());
                if kind == 0 {
                    let bit = rng.below(8);
                    bytes[at] ^= 1 << bit;
                    what.push(format!("flip bit {bit} of byte {at}"));
                } else {
                    let b = rng.next() as u8;
                    bytes[at] = b;
                    what.push(format!("byte {at} = {b}"));
                }
            }
            what.join(", ")
        }
        2 => {
            let at = rng.below(bytes.len());
            bytes.truncate(at);
            format!("truncate to {at} bytes")
        }
        3 => {
            // Replace a JSON number (found in the text) with a boundary value.
            let Some((json, bin)) = split_json(bytes) else { return "no JSON found".into() };
            let spans: Vec<(usize, usize)> = number_spans(&json);
            if spans.is_empty() {
                return "no number".into();
            }
            let (s, e) = *rng.pick(&spans);
            let new = *rng.pick(BOUNDARY_NUMBERS);
            let mut edited = json[..s].to_vec();
            edited.extend_from_slice(new.as_bytes());
            edited.extend_from_slice(&json[e..]);
            *bytes = join_json(&edited, &bin);
            format!("number at {s} = {new}")
        }
        4 | 5 => {
            let Some((json, bin)) = split_json(bytes) else { return "no JSON found".into() };
            let Ok(mut root) = serde_json::from_slice::<Value>(&json) else { return "JSON unreadable".into() };
            let mut what = Vec::new();
            for _ in 0..1 + rng.below(3) {
                what.push(mutate_json_tree(rng, &mut root));
            }
            *bytes = join_json(&serde_json::to_vec(&root).unwrap(), &bin);
            what.join(", ")
        }
        _ => {
            // GLB header or chunk lengths (a .gltf gets a bit flip instead).
            if !bytes.starts_with(b"glTF") || bytes.len() < 20 {
                let at = rng.below(bytes.len().max(1));
                if let Some(b) = bytes.get_mut(at) {
                    *b ^= 1;
                }
                return format!("flip bit 0 of byte {at}");
            }
            let jlen = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
            let fields = [8usize, 12, 20 + jlen];
            let at = *rng.pick(&fields);
            if at + 4 > bytes.len() {
                return "chunk beyond the end".into();
            }
            let old = u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
            let new = match rng.below(6) {
                0 => 0,
                1 => u32::MAX,
                2 => old.wrapping_add(1 + rng.below(8) as u32),
                3 => old.wrapping_sub(1 + rng.below(8) as u32),
                4 => rng.next() as u32,
                _ => old.wrapping_mul(2),
            };
            bytes[at..at + 4].copy_from_slice(&new.to_le_bytes());
            format!("length field at {at}: {old} -> {new}")
        }
    }
}

/// Byte ranges of JSON numbers outside strings.
fn number_spans(json: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let (mut i, mut in_string) = (0, false);
    while i < json.len() {
        let c = json[i];
        if in_string {
            if c == b'\\' {
                i += 1;
            } else if c == b'"' {
                in_string = false;
            }
            i += 1;
        } else if c == b'"' {
            in_string = true;
            i += 1;
        } else if c == b'-' || c.is_ascii_digit() {
            let s = i;
            while i < json.len() && (json[i].is_ascii_digit() || b"+-.eE".contains(&json[i])) {
                i += 1;
            }
            spans.push((s, i));
        } else {
            i += 1;
        }
    }
    spans
}

enum Outcome {
    Loaded,
    Refused,
    WrongError(String),
    Panicked(String),
}

/// Loads `path` on its own thread so that a hang is reported instead of stalling the test.
fn load_bounded(path: &Path) -> Option<(Outcome, Duration)> {
    let (tx, rx) = mpsc::channel();
    let p = path.to_path_buf();
    std::thread::spawn(move || {
        let t = Instant::now();
        let result = catch_unwind(AssertUnwindSafe(|| {
            let mut scene = load_with(&p, &LoadOptions { max_texture_bytes: TEXTURE_BUDGET })?;
            // Play what loaded: sampling must not panic on any keyframes the loader accepted.
            // A pose beyond the coordinate bound is refused by set_time, not by the loader.
            for t in [0.0, 0.37, 1.0, 1e30] {
                let _ = scene.set_time(t);
            }
            Ok(scene)
        }));
        let outcome = match result {
            Ok(Ok(_)) => Outcome::Loaded,
            Ok(Err(Error::Scene { .. })) => Outcome::Refused,
            Ok(Err(e)) => Outcome::WrongError(format!("{e:?}")),
            Err(payload) => Outcome::Panicked(
                payload
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default(),
            ),
        };
        let _ = tx.send((outcome, t.elapsed()));
    });
    rx.recv_timeout(CASE_LIMIT).ok()
}

#[test]
fn mutated_scenes_load_or_fail_cleanly_in_bounded_time() {
    let work = tmpdir("fuzz", "loader");
    let mut seeds = shared_scene_seeds(&work);
    seeds.extend(synthetic_seeds(&work));
    let start = Instant::now();
    let mut rng = Rng(0x5EED_0F_F022);
    let (mut loaded, mut refused, mut slowest) = (0usize, 0usize, (Duration::ZERO, String::new()));
    let mut failures = Vec::new();
    for seed in &seeds {
        // Unmutated, every seed loads: otherwise the mutations below would only test one error.
        let clean = seed.folder.join(&seed.name);
        std::fs::write(&clean, &seed.bytes).unwrap();
        match load_bounded(&clean) {
            Some((Outcome::Loaded | Outcome::Refused, _)) => {}
            _ => panic!("{}: the unmutated seed does not load cleanly", seed.name),
        }
        let ext = Path::new(&seed.name).extension().unwrap().to_string_lossy().into_owned();
        let path = seed.folder.join(format!("fuzz-case.{ext}"));
        for case in 0..CASES_PER_SEED {
            if start.elapsed() > RUN_LIMIT {
                println!("stopping at {} case {case}: the run reached its {RUN_LIMIT:?} limit", seed.name);
                break;
            }
            let mut bytes = seed.bytes.clone();
            let mut what = Vec::new();
            for _ in 0..1 + rng.below(2) {
                what.push(mutate(&mut rng, &mut bytes));
            }
            // Now and then corrupt a buffer file the scene reads, restored after the case.
            let bin = (!seed.bins.is_empty() && rng.below(10) == 0).then(|| {
                let b = rng.pick(&seed.bins).clone();
                let original = std::fs::read(&b).unwrap();
                let mut data = original.clone();
                // Only byte-level mutations: a buffer has no JSON or chunks.
                let kind = rng.below(3);
                what.push(format!("{}: {}", b.file_name().unwrap().to_string_lossy(), mutate_as(kind, &mut rng, &mut data)));
                std::fs::write(&b, &data).unwrap();
                (b, original)
            });
            std::fs::write(&path, &bytes).unwrap();
            let label = format!("{} case {case}: {}", seed.name, what.join("; "));
            match load_bounded(&path) {
                None => {
                    let keep = work.join(format!("hang-{case}.{ext}"));
                    let _ = std::fs::copy(&path, &keep);
                    panic!("{label}: no result within {CASE_LIMIT:?} (input kept as {})", keep.display());
                }
                Some((outcome, took)) => {
                    if took > slowest.0 {
                        slowest = (took, label.clone());
                    }
                    match outcome {
                        Outcome::Loaded => loaded += 1,
                        Outcome::Refused => refused += 1,
                        Outcome::WrongError(e) => failures.push(format!("{label}: not a SceneError: {e}")),
                        Outcome::Panicked(m) => {
                            let keep = work.join(format!("panic-{}-{case}.{ext}", seed.name));
                            let _ = std::fs::copy(&path, &keep);
                            failures.push(format!("{label}: panicked: {m} (input kept as {})", keep.display()));
                        }
                    }
                }
            }
            if let Some((b, original)) = bin {
                std::fs::write(b, original).unwrap();
            }
        }
    }
    let total = loaded + refused + failures.len();
    println!(
        "{total} mutated files from {} seeds in {:.1} s: {loaded} loaded, {refused} refused, {} failed; \
         slowest case {:.1} ms ({})",
        seeds.len(),
        start.elapsed().as_secs_f64(),
        failures.len(),
        slowest.0.as_secs_f64() * 1e3,
        slowest.1
    );
    assert!(failures.is_empty(), "{} of {total} cases failed:\n{}", failures.len(), failures.join("\n"));
    assert!(refused > total / 10 && loaded > 0, "the mutations should both pass and fail the checks");
    let _ = std::fs::remove_dir_all(&work);
}
