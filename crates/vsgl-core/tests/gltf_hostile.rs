//! Integration tests of the glTF loader on hostile and malformed files: refused with an error
//! that names the element, never a panic, an out-of-folder read or unbounded work.

mod common;

use common::gltf_fixtures::*;
use common::tmpdir;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde_json::{json, Value};
use vsgl_core::scene::gltf::{load, load_with, LoadOptions, DEFAULT_MAX_TEXTURE_BYTES};
use vsgl_core::Error;

// ---------------------------------------------------------------------------------------------
// Hostile and malformed files
// ---------------------------------------------------------------------------------------------

#[test]
fn truncated_buffer_is_refused() {
    let dir = tmpdir("gltf", "truncated");
    let path = quad_with_node(&dir, json!({}));
    let data = std::fs::read(dir.join("quad.bin")).unwrap();
    std::fs::write(dir.join("quad.bin"), &data[..data.len() - 5]).unwrap();
    expect_scene_error(&path, &["buffers[0].uri", "truncated"]);
}

#[test]
fn accessor_out_of_view_bounds_is_refused() {
    let dir = tmpdir("gltf", "accessor_oob");
    let path = quad_with_node(&dir, json!({}));
    let mut r: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    r["accessors"][0]["count"] = json!(5); // the view holds 4 VEC3
    write_json(&path, &r);
    expect_scene_error(&path, &["accessors[0]", "out of bounds"]);
    // A count whose byte size overflows u64 arithmetic.
    r["accessors"][0]["count"] = json!(u64::MAX / 2);
    r["accessors"][0]["byteOffset"] = json!(u64::MAX - 3);
    write_json(&path, &r);
    expect_scene_error(&path, &["accessors[0]"]);
    // A view past the end of its buffer.
    r["accessors"][0]["count"] = json!(4);
    r["accessors"][0]["byteOffset"] = json!(0);
    r["bufferViews"][0]["byteOffset"] = json!(1000);
    write_json(&path, &r);
    expect_scene_error(&path, &["bufferViews[0]", "buffers[0]"]);
}

#[test]
fn index_out_of_range_is_refused() {
    let dir = tmpdir("gltf", "index_oob");
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let idx = bin.indices(&[0, 1, 2, 0, 2, 7]);
    std::fs::write(dir.join("i.bin"), &bin.data).unwrap();
    let r = root(
        &bin,
        json!({"uri": "i.bin", "byteLength": bin.data.len()}),
        json!({
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
            "nodes": [{"mesh": 0}],
        }),
    );
    let path = dir.join("i.gltf");
    write_json(&path, &r);
    expect_scene_error(
        &path,
        &["meshes[0].primitives[0]", "index 7", "out of range"],
    );
}

fn quad_with_buffer_uri(dir: &Path, uri: &str) -> PathBuf {
    let path = quad_with_node(dir, json!({}));
    let mut r: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    r["buffers"][0]["uri"] = json!(uri);
    write_json(&path, &r);
    path
}

#[test]
fn parent_directory_uri_is_refused() {
    let dir = tmpdir("gltf", "dotdot");
    let scene_dir = dir.join("scene");
    std::fs::create_dir_all(&scene_dir).unwrap();
    let path = quad_with_buffer_uri(&scene_dir, "../outside.bin");
    // The target exists, so only the folder rule can refuse it.
    std::fs::copy(scene_dir.join("quad.bin"), dir.join("outside.bin")).unwrap();
    expect_scene_error(&path, &["buffers[0].uri", "escapes the scene folder"]);
    let path = quad_with_buffer_uri(&scene_dir, "sub/../../outside.bin");
    expect_scene_error(&path, &["buffers[0].uri", "escapes"]);
    let path = quad_with_buffer_uri(&scene_dir, "%2e%2e/outside.bin");
    expect_scene_error(&path, &["buffers[0].uri", "escapes"]);
    let path = quad_with_buffer_uri(&scene_dir, "..\\outside.bin");
    expect_scene_error(&path, &["buffers[0].uri", "escapes"]);
    // ".." that stays inside the folder is fine.
    std::fs::create_dir_all(scene_dir.join("sub")).unwrap();
    let path = quad_with_buffer_uri(&scene_dir, "sub/../quad.bin");
    assert_eq!(load(&path).unwrap().stats().triangles, 2);
}

#[cfg(unix)]
#[test]
fn symlink_out_of_the_folder_is_refused() {
    let dir = tmpdir("gltf", "symlink");
    let scene_dir = dir.join("scene");
    std::fs::create_dir_all(&scene_dir).unwrap();
    let path = quad_with_buffer_uri(&scene_dir, "link.bin");
    std::fs::rename(scene_dir.join("quad.bin"), dir.join("outside.bin")).unwrap();
    std::os::unix::fs::symlink(dir.join("outside.bin"), scene_dir.join("link.bin")).unwrap();
    expect_scene_error(&path, &["buffers[0].uri", "outside the scene folder"]);
}

#[test]
fn absolute_uri_is_refused() {
    let dir = tmpdir("gltf", "absolute");
    let path = quad_with_buffer_uri(&dir, "/etc/passwd");
    expect_scene_error(&path, &["buffers[0].uri", "absolute"]);
    let path = quad_with_buffer_uri(&dir, "%2Fetc%2Fpasswd");
    expect_scene_error(&path, &["buffers[0].uri", "absolute"]);
    let path = quad_with_buffer_uri(&dir, "file:///etc/passwd");
    expect_scene_error(&path, &["buffers[0].uri", "file:"]);
}

#[test]
fn http_uri_is_refused() {
    let dir = tmpdir("gltf", "http");
    let path = quad_with_buffer_uri(&dir, "http://example.com/quad.bin");
    expect_scene_error(&path, &["buffers[0].uri", "http:", "not allowed"]);
    let path = quad_with_buffer_uri(&dir, "HTTPS://example.com/quad.bin");
    expect_scene_error(&path, &["buffers[0].uri", "not allowed"]);
}

#[test]
fn missing_texture_image_is_refused() {
    let dir = tmpdir("gltf", "missing_texture");
    let path = textured_scene(&dir, true);
    std::fs::remove_file(dir.join("mr.png")).unwrap();
    expect_scene_error(&path, &["images[1]", "mr.png"]);
}

#[test]
fn oversized_image_is_refused_before_decoding() {
    let dir = tmpdir("gltf", "big_image");
    let path = textured_scene(&dir, true);
    // 16385 × 1 pixels: tiny on disk, one pixel over the side limit.
    image::GrayImage::new(16385, 1)
        .save(dir.join("mr.png"))
        .unwrap();
    expect_scene_error(&path, &["images[1]", "16384"]);
    // Not an image at all.
    std::fs::write(dir.join("mr.png"), b"this is not a PNG").unwrap();
    expect_scene_error(&path, &["images[1]"]);
}

#[test]
fn texture_budget_is_checked_from_the_header_and_counts_every_texture() {
    let dir = tmpdir("gltf", "texture_budget");
    let path = textured_scene(&dir, true);
    // mr.png as a 64×64 grey PNG: 16 KiB as RGBA8 plus 4 KiB of grey decoder output. The base
    // colour (4×2 RGBA8, 32 bytes) is decoded before it; the 2×2 normal map (16 bytes) after.
    image::GrayImage::new(64, 64).save(dir.join("mr.png")).unwrap();
    let peak = 32 + 64 * 64 * 4 + 64 * 64;
    let with = |max_texture_bytes| load_with(&path, &LoadOptions { max_texture_bytes });
    let scene = with(peak).unwrap();
    assert_eq!(scene.textures.len(), 3);
    let text = with(peak - 1).unwrap_err().to_string();
    for needle in ["tex.gltf", "images[1]", "\"mr.png\"", "64×64", &(peak - 1).to_string(), "max_texture_bytes="] {
        assert!(text.contains(needle), "{text:?} does not mention {needle:?}");
    }
    // An RGBA8 file needs no conversion buffer: its own size is enough.
    write_png(&dir.join("mr.png"), 64, 64, [1, 2, 3, 4]);
    assert!(with(32 + 64 * 64 * 4 + 16).is_ok());
    assert!(with(32 + 64 * 64 * 4 + 15).is_err(), "the normal map decoded after it counts too");
    assert!(matches!(with(0), Err(Error::InvalidArgument { .. })));
    assert_eq!(LoadOptions::default().max_texture_bytes, DEFAULT_MAX_TEXTURE_BYTES);
}

#[test]
fn points_primitive_is_skipped_with_a_warning() {
    let dir = tmpdir("gltf", "points");
    let path = quad_with_node(&dir, json!({}));
    let mut r: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    r["meshes"][0]["primitives"][0]["mode"] = json!(0);
    write_json(&path, &r);
    let scene = load(&path).unwrap();
    assert_eq!(scene.stats().triangles, 0);
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("meshes[0].primitives[0]") && w.contains("POINTS")),
        "{:?}",
        scene.warnings
    );
    r["meshes"][0]["primitives"][0]["mode"] = json!(99);
    write_json(&path, &r);
    expect_scene_error(&path, &["meshes[0].primitives[0].mode"]);
}

#[test]
fn invalid_json_is_refused() {
    let dir = tmpdir("gltf", "invalid_json");
    let path = dir.join("bad.gltf");
    std::fs::write(&path, b"{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [").unwrap();
    expect_scene_error(&path, &["JSON"]);
    std::fs::write(&path, b"").unwrap();
    expect_scene_error(&path, &["JSON"]);
    std::fs::write(&path, b"{\"asset\": {\"version\": \"1.0\"}}").unwrap();
    expect_scene_error(&path, &["asset.version"]);
    std::fs::write(&path, b"{\"asset\": {\"version\": \"2.0\"}, \"extensionsRequired\": [\"KHR_draco_mesh_compression\"]}").unwrap();
    expect_scene_error(
        &path,
        &["extensionsRequired[0]", "KHR_draco_mesh_compression"],
    );
}

#[test]
fn node_cycle_is_refused() {
    let dir = tmpdir("gltf", "cycle");
    let path = quad_with_node(&dir, json!({}));
    let mut r: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    r["nodes"] = json!([{"children": [1]}, {"children": [2]}, {"children": [1], "mesh": 0}]);
    r["scenes"] = json!([{"nodes": [0]}]);
    write_json(&path, &r);
    expect_scene_error(&path, &["nodes[1]", "two parents"]);
    // A pure cycle: every node has exactly one parent.
    r["nodes"] = json!([{"children": [1]}, {"children": [2]}, {"children": [0], "mesh": 0}]);
    write_json(&path, &r);
    expect_scene_error(&path, &["nodes[", "cycle"]);
    r["nodes"] = json!([{"children": [0]}]);
    write_json(&path, &r);
    expect_scene_error(&path, &["nodes[0]", "cycle"]);
    r["nodes"] = json!([{"children": [7]}]);
    write_json(&path, &r);
    expect_scene_error(&path, &["nodes[0].children[0]"]);
}

#[test]
fn huge_byte_length_fails_fast() {
    let dir = tmpdir("gltf", "huge");
    let path = quad_with_node(&dir, json!({}));
    let mut r: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    r["buffers"][0]["byteLength"] = json!(1_000_000_000_000_000u64);
    write_json(&path, &r);
    let t = Instant::now();
    expect_scene_error(&path, &["buffers[0]", "byteLength"]);
    // Within the size cap but larger than the file: refused from the file size.
    r["buffers"][0]["byteLength"] = json!(1_000_000_000u64);
    write_json(&path, &r);
    expect_scene_error(&path, &["buffers[0].uri", "truncated"]);
    // Same for a data: URI and a GLB chunk.
    r["buffers"][0]["uri"] = json!("data:application/octet-stream;base64,AAAA");
    write_json(&path, &r);
    expect_scene_error(&path, &["buffers[0].uri", "truncated"]);
    assert!(t.elapsed().as_secs_f64() < 2.0, "took {:?}", t.elapsed());
}

#[test]
fn non_finite_positions_are_refused() {
    let dir = tmpdir("gltf", "nan");
    let mut bin = Bin::default();
    let mut p = QUAD_POS;
    p[4] = f32::NAN;
    let pos = bin.floats(&p, "VEC3", 3);
    let idx = bin.indices(&QUAD_IDX);
    std::fs::write(dir.join("n.bin"), &bin.data).unwrap();
    let r = root(
        &bin,
        json!({"uri": "n.bin", "byteLength": bin.data.len()}),
        json!({
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
            "nodes": [{"mesh": 0}],
        }),
    );
    let path = dir.join("n.gltf");
    write_json(&path, &r);
    expect_scene_error(&path, &["accessors[0]", "non-finite"]);
}

#[test]
fn malformed_glb_containers_are_refused() {
    let dir = tmpdir("gltf", "bad_glb");
    let path = dir.join("x.glb");
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let r = root(
        &bin,
        json!({"byteLength": bin.data.len()}),
        json!({"meshes": [{"primitives": [{"attributes": {"POSITION": pos}}]}], "nodes": [{"mesh": 0}]}),
    );
    let good = glb_value(&r, &bin.data);
    // Truncated file: the header's length no longer fits.
    std::fs::write(&path, &good[..good.len() - 8]).unwrap();
    expect_scene_error(&path, &["GLB header"]);
    // JSON chunk length past the end.
    let mut bad = good.clone();
    bad[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
    std::fs::write(&path, &bad).unwrap();
    expect_scene_error(&path, &["GLB chunk 0"]);
    // byteLength larger than the BIN chunk.
    let mut r2 = r.clone();
    r2["buffers"][0]["byteLength"] = json!(4096);
    std::fs::write(&path, glb_value(&r2, &bin.data)).unwrap();
    expect_scene_error(&path, &["buffers[0]", "BIN chunk"]);
    // Tiny header lengths must not underflow.
    std::fs::write(&path, b"glTF\x02\0\0\0\x04\0\0\0").unwrap();
    expect_scene_error(&path, &["GLB header"]);
    std::fs::write(&path, &good).unwrap();
    assert_eq!(
        load(&path).unwrap().meshes[0].primitives[0].indices.len(),
        3
    );
}

#[test]
fn dangling_indices_are_refused() {
    let dir = tmpdir("gltf", "dangling");
    let path = quad_with_node(&dir, json!({}));
    let orig: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    let cases: &[(&str, Value, &str)] = &[
        (
            "/meshes/0/primitives/0/attributes/POSITION",
            json!(42),
            "accessors[42]",
        ),
        ("/meshes/0/primitives/0/indices", json!(42), "accessors[42]"),
        ("/meshes/0/primitives/0/material", json!(3), "materials[3]"),
        ("/accessors/0/bufferView", json!(9), "bufferViews[9]"),
        ("/bufferViews/0/buffer", json!(5), "buffers[5]"),
        ("/nodes/0/mesh", json!(8), "meshes[8]"),
        ("/nodes/0/camera", json!(1), "cameras[1]"),
        ("/scenes/0/nodes/0", json!(6), "scenes[0].nodes[0]"),
        ("/scene", json!(4), "scenes[4]"),
        ("/accessors/0/type", json!("MAT4"), "accessors[0]"),
        ("/accessors/0/componentType", json!(5130), "accessors[0]"),
        (
            "/bufferViews/0/byteStride",
            json!(2),
            "bufferViews[0].byteStride",
        ),
    ];
    for (ptr, value, needle) in cases {
        let mut r = orig.clone();
        set_pointer(&mut r, ptr, value.clone());
        write_json(&path, &r);
        expect_scene_error(&path, &[needle]);
    }
}

/// Sets the JSON value at `ptr`, creating the last object key when absent.
fn set_pointer(r: &mut Value, ptr: &str, value: Value) {
    let (parent, key) = ptr.rsplit_once('/').unwrap();
    let parent = r.pointer_mut(parent).unwrap();
    match parent {
        Value::Array(a) => a[key.parse::<usize>().unwrap()] = value,
        Value::Object(o) => {
            o.insert(key.to_string(), value);
        }
        _ => panic!("{ptr}: parent is not a container"),
    }
}

#[test]
fn sparse_accessor_substitutes_values() {
    let dir = tmpdir("gltf", "sparse");
    let mut bin = Bin::default();
    let idx = bin.indices(&QUAD_IDX);
    // Sparse POSITION without a bufferView: zeros, then vertices 1..3 substituted.
    let sparse_idx = bin.view(&[1u8, 0, 2, 0, 3, 0]);
    let vals: Vec<u8> = QUAD_POS[3..].iter().flat_map(|v| v.to_le_bytes()).collect();
    let sparse_vals = bin.view(&vals);
    bin.accessors.push(json!({
        "componentType": 5126, "count": 4, "type": "VEC3",
        "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0],
        "sparse": {"count": 3,
                   "indices": {"bufferView": sparse_idx, "componentType": 5123},
                   "values": {"bufferView": sparse_vals}}
    }));
    std::fs::write(dir.join("s.bin"), &bin.data).unwrap();
    let r = root(
        &bin,
        json!({"uri": "s.bin", "byteLength": bin.data.len()}),
        json!({
            "meshes": [{"primitives": [{"attributes": {"POSITION": 1}, "indices": idx}]}],
            "nodes": [{"mesh": 0}],
        }),
    );
    let path = dir.join("s.gltf");
    write_json(&path, &r);
    let scene = load(&path).unwrap();
    let prim = &scene.meshes[0].primitives[0];
    for (p, q) in prim.positions.iter().zip(QUAD_POS.chunks(3)) {
        assert!(close3(*p, [q[0], q[1], q[2]]), "{:?}", prim.positions);
    }
    // A sparse index past the accessor's count.
    let mut r2 = r.clone();
    r2["accessors"][1]["count"] = json!(3);
    write_json(&path, &r2);
    expect_scene_error(&path, &["accessors[1].sparse.indices", "out of range"]);
    // More sparse values than the view holds.
    let mut r3 = r.clone();
    r3["accessors"][1]["sparse"]["values"]["byteOffset"] = json!(8);
    write_json(&path, &r3);
    expect_scene_error(&path, &["accessors[1].sparse.values"]);
}

/// Deterministic xorshift, for the mutation test below.
fn xorshift(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

#[test]
fn mutated_files_never_panic() {
    let dir = tmpdir("gltf", "mutations");
    // A textured GLB-free scene (JSON text) and a GLB, both valid before mutation.
    let gltf_path = textured_scene(&dir, true);
    let gltf_bytes = std::fs::read(&gltf_path).unwrap();
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let uv = bin.floats(&QUAD_UV, "VEC2", 2);
    let idx = bin.indices(&QUAD_IDX);
    let r = root(
        &bin,
        json!({"byteLength": bin.data.len()}),
        json!({
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx}]}],
            "nodes": [{"mesh": 0, "children": [1]}, {"camera": 0}],
            "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        }),
    );
    let glb_bytes = glb_value(&r, &bin.data);
    let glb_path = dir.join("m.glb");
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut outcomes = [0usize; 2];
    for round in 0..1500 {
        let (path, orig) = if round % 2 == 0 {
            (&gltf_path, &gltf_bytes)
        } else {
            (&glb_path, &glb_bytes)
        };
        let mut data = orig.clone();
        let edits = 1 + xorshift(&mut state) % 4;
        for _ in 0..edits {
            let at = (xorshift(&mut state) % data.len() as u64) as usize;
            match xorshift(&mut state) % 4 {
                // Digits keep JSON valid more often, reaching the deeper checks.
                0 => data[at] = b"0123456789"[(xorshift(&mut state) % 10) as usize],
                1 => data[at] = xorshift(&mut state) as u8,
                2 => data[at] ^= 1 << (xorshift(&mut state) % 8),
                _ => data.truncate(at.max(1)),
            }
        }
        std::fs::write(path, &data).unwrap();
        // Any outcome but a panic is acceptable; errors must be Error::Scene.
        match load(path) {
            Ok(_) => outcomes[0] += 1,
            Err(Error::Scene { .. }) => outcomes[1] += 1,
            Err(e) => panic!("unexpected error kind {e:?}"),
        }
    }
    println!("mutations: {} loaded, {} refused", outcomes[0], outcomes[1]);
    assert!(outcomes[1] > 0);
}

/// The Python fixture generator (used by the Python tests) must produce what its tables
/// promise with this loader. Skipped when no `python3` is on PATH.
#[test]
fn python_fixtures_match_the_loader() {
    let script = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/gltf_fixtures.py"
    ));
    let dir = tmpdir("gltf", "python_fixtures");
    let status = std::process::Command::new("python3")
        .arg(script)
        .arg("--write")
        .arg(&dir)
        .output();
    let out = match status {
        Ok(out) => out,
        Err(e) => {
            println!("skipping: python3 not available ({e})");
            return;
        }
    };
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let manifest: Value =
        serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).unwrap()).unwrap();
    let manifest = manifest.as_object().unwrap();
    assert!(manifest.len() >= 20);
    for (name, entry) in manifest {
        let path = PathBuf::from(entry["path"].as_str().unwrap());
        let expect = entry["expect"].clone();
        match entry["kind"].as_str().unwrap() {
            "valid" => {
                let scene = load(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
                assert_eq!(
                    scene.stats().triangles as u64,
                    expect.as_u64().unwrap(),
                    "{name}"
                );
            }
            "warning" => {
                let scene = load(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
                let needle = expect.as_str().unwrap();
                assert!(
                    scene.warnings.iter().any(|w| w.contains(needle)),
                    "{name}: {:?}",
                    scene.warnings
                );
            }
            _ => {
                let keyword = entry["keyword"].as_str().unwrap();
                let text = expect_scene_error(&path, &[expect.as_str().unwrap(), keyword]);
                println!("{name}: {text}");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Real scenes
// ---------------------------------------------------------------------------------------------

#[test]
fn real_scenes_load_with_documented_triangle_counts() {
    let root = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/scenes"
    ));
    if !root.is_dir() {
        println!("skipping: ../shared/scenes not found at {}", root.display());
        return;
    }
    let cases = [
        ("CornellBox/CornellBox.glb", 36usize, false),
        ("CornellBoxOriginal/CornellBoxOriginal.glb", 32, false),
        ("FlightHelmet/FlightHelmet.gltf", 94_722, true),
        ("BoomBox/BoomBox.gltf", 6_036, true),
        ("LightsSpot/LightsSpot.gltf", 2, false),
    ];
    for (file, triangles, textured) in cases {
        let t = Instant::now();
        let scene = load(&root.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        let stats = scene.stats();
        println!(
            "{file}: {} triangles, {} meshes, {} materials, {} textures, {} lights, {} cameras, {:.2}s, warnings {:?}",
            stats.triangles,
            stats.meshes,
            stats.materials,
            stats.textures,
            stats.lights,
            scene.cameras.len(),
            t.elapsed().as_secs_f64(),
            scene.warnings
        );
        assert_eq!(stats.triangles, triangles, "{file}");
        assert_eq!(stats.has_textures, textured, "{file}");
        assert_eq!(stats.has_normal_maps, textured, "{file}");
        assert!(!scene.bounds().is_empty(), "{file}");
        for m in &scene.meshes {
            for p in &m.primitives {
                assert_eq!(p.normals.len(), p.positions.len(), "{file}");
                if scene.materials[p.material].normal_texture.is_some() {
                    assert_eq!(p.tangents.len(), p.positions.len(), "{file}");
                }
            }
        }
        for tex in &scene.textures {
            assert_eq!(
                tex.rgba8.len(),
                (tex.width * tex.height * 4) as usize,
                "{file}"
            );
        }
        if file.starts_with("LightsSpot") {
            assert_eq!(scene.lights.len(), 3);
            for l in &scene.lights {
                let l = l.as_spot().expect("a spot light");
                assert_eq!(l.intensity, 450.0);
                assert!((l.position.y - 5.0).abs() < 1e-3, "{l:?}");
                assert!(
                    l.direction.y < -0.5,
                    "spot lights point down at the plane: {l:?}"
                );
                assert!(
                    (l.inner_cone - 0.314).abs() < 1e-3 && (l.outer_cone - 0.524).abs() < 1e-3,
                    "{l:?}"
                );
            }
        }
        if file.starts_with("CornellBoxOriginal") {
            let b = scene.bounds();
            assert!(
                b.min.y > -0.01 && (b.max.y - 1.99).abs() < 0.02,
                "Z-up root matrix applied: {b:?}"
            );
        }
    }
}
