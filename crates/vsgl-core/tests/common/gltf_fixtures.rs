//! glTF fixtures the loader tests write into a temporary folder: a binary buffer with its views
//! and accessors, a unit quad, textured and hierarchy scenes, and the checks on what loads.

use std::path::{Path, PathBuf};

use glam::DVec3;
use serde_json::{json, Value};
use vsgl_core::scene::gltf::load;
use vsgl_core::scene::Scene;
use vsgl_core::Error;

use super::glb;

/// Accumulates one binary buffer plus its bufferViews and accessors.
#[derive(Default)]
pub struct Bin {
    pub data: Vec<u8>,
    pub views: Vec<Value>,
    pub accessors: Vec<Value>,
}

impl Bin {
    pub fn align(&mut self) {
        while !self.data.len().is_multiple_of(4) {
            self.data.push(0);
        }
    }
    pub fn view(&mut self, bytes: &[u8]) -> usize {
        self.align();
        let offset = self.data.len();
        self.data.extend_from_slice(bytes);
        self.views
            .push(json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()}));
        self.views.len() - 1
    }
    /// A float accessor of `ty` ("VEC3", "VEC2", ...) with its own bufferView.
    pub fn floats(&mut self, values: &[f32], ty: &str, ncomp: usize) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes);
        let mut acc = json!({
            "bufferView": view, "componentType": 5126, "count": values.len() / ncomp, "type": ty
        });
        if ty == "VEC3" {
            let mut min = [f32::INFINITY; 3];
            let mut max = [f32::NEG_INFINITY; 3];
            for c in values.chunks(3) {
                for k in 0..3 {
                    min[k] = min[k].min(c[k]);
                    max[k] = max[k].max(c[k]);
                }
            }
            if min.iter().chain(&max).all(|v| v.is_finite()) {
                acc["min"] = json!(min);
                acc["max"] = json!(max);
            }
        }
        self.accessors.push(acc);
        self.accessors.len() - 1
    }
    pub fn indices(&mut self, values: &[u32]) -> usize {
        let bytes: Vec<u8> = values
            .iter()
            .flat_map(|v| (*v as u16).to_le_bytes())
            .collect();
        let view = self.view(&bytes);
        self.accessors.push(json!({
            "bufferView": view, "componentType": 5123, "count": values.len(), "type": "SCALAR"
        }));
        self.accessors.len() - 1
    }
}

/// Unit quad in the z = 0 plane, counter-clockwise seen from +z.
pub const QUAD_POS: [f32; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
pub const QUAD_UV: [f32; 8] = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
pub const QUAD_IDX: [u32; 6] = [0, 1, 2, 0, 2, 3];

/// Root JSON with the buffer views/accessors of `bin`; `buffer` is buffers[0], `extra` is
/// merged in (meshes, nodes, scenes, ...).
pub fn root(bin: &Bin, buffer: Value, extra: Value) -> Value {
    let mut r = json!({
        "asset": {"version": "2.0"},
        "buffers": [buffer],
        "bufferViews": bin.views,
        "accessors": bin.accessors,
    });
    if let (Some(r), Value::Object(extra)) = (r.as_object_mut(), extra) {
        r.extend(extra);
    }
    r
}

pub fn write_json(path: &Path, v: &Value) {
    std::fs::write(path, serde_json::to_vec_pretty(v).unwrap()).unwrap();
}

/// A one-mesh, one-node quad scene (node 0 has `node` merged in), buffer in "quad.bin".
pub fn quad_with_node(dir: &Path, node: Value) -> PathBuf {
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let idx = bin.indices(&QUAD_IDX);
    std::fs::write(dir.join("quad.bin"), &bin.data).unwrap();
    let mut n = json!({"mesh": 0, "name": "quad"});
    if let (Some(n), Value::Object(extra)) = (n.as_object_mut(), node) {
        n.extend(extra);
    }
    let r = root(
        &bin,
        json!({"uri": "quad.bin", "byteLength": bin.data.len()}),
        json!({
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
            "nodes": [n],
            "scenes": [{"nodes": [0]}],
            "scene": 0,
        }),
    );
    let path = dir.join("quad.gltf");
    write_json(&path, &r);
    path
}



pub fn glb_value(json: &Value, bin: &[u8]) -> Vec<u8> {
    glb(&serde_json::to_vec(json).unwrap(), bin)
}

pub fn write_png(path: &Path, w: u32, h: u32, rgba: [u8; 4]) {
    image::RgbaImage::from_pixel(w, h, image::Rgba(rgba))
        .save(path)
        .unwrap();
}

/// Asserts that loading fails with `Error::Scene` whose element and message mention all
/// `needles` (case-insensitive).
pub fn expect_scene_error(path: &Path, needles: &[&str]) -> String {
    match load(path) {
        Ok(s) => panic!(
            "{}: expected an error, got a scene with {} triangles",
            path.display(),
            s.stats().triangles
        ),
        Err(e @ Error::Scene { .. }) => {
            let text = e.to_string();
            for n in needles {
                assert!(
                    text.to_lowercase().contains(&n.to_lowercase()),
                    "error {text:?} does not mention {n:?}"
                );
            }
            text
        }
        Err(e) => panic!("expected Error::Scene, got {e:?}"),
    }
}

pub fn close3(a: [f32; 3], b: [f32; 3]) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-5)
}

pub fn dclose(a: DVec3, b: DVec3) -> bool {
    (a - b).length() < 1e-9
}

pub fn world_points(scene: &Scene, node: usize) -> Vec<DVec3> {
    let w = scene.world_transform(node);
    let m = scene.nodes[node].mesh.unwrap();
    scene.meshes[m].primitives[0]
        .positions
        .iter()
        .map(|p| w.transform_point3(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)))
        .collect()
}


/// Quad with UVs and a material using three PNG textures; no NORMAL, no TANGENT.
pub fn textured_scene(dir: &Path, with_uvs: bool) -> PathBuf {
    write_png(&dir.join("base color.png"), 4, 2, [255, 0, 0, 255]);
    write_png(&dir.join("mr.png"), 2, 2, [0, 128, 255, 255]);
    std::fs::create_dir_all(dir.join("tex")).unwrap();
    write_png(&dir.join("tex/normal.png"), 2, 2, [128, 128, 255, 255]);
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let idx = bin.indices(&QUAD_IDX);
    let mut attributes = json!({"POSITION": pos});
    if with_uvs {
        attributes["TEXCOORD_0"] = json!(bin.floats(&QUAD_UV, "VEC2", 2));
    }
    std::fs::write(dir.join("tex.bin"), &bin.data).unwrap();
    let r = root(
        &bin,
        json!({"uri": "tex.bin", "byteLength": bin.data.len()}),
        json!({
            "images": [{"uri": "base%20color.png"}, {"uri": "mr.png"}, {"uri": "tex/normal.png"}],
            "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
            "materials": [{
                "name": "painted",
                "pbrMetallicRoughness": {
                    "baseColorFactor": [1.0, 0.5, 0.25, 1.0],
                    "baseColorTexture": {"index": 0},
                    "metallicFactor": 0.25,
                    "roughnessFactor": 0.75,
                    "metallicRoughnessTexture": {"index": 1}
                },
                "normalTexture": {"index": 2, "scale": 0.5}
            }],
            "meshes": [{"primitives": [{"attributes": attributes, "indices": idx, "material": 0}]}],
            "nodes": [{"mesh": 0}],
            "scenes": [{"nodes": [0]}],
        }),
    );
    let path = dir.join("tex.gltf");
    write_json(&path, &r);
    path
}

