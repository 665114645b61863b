//! Integration tests of the glTF loader: fixtures are generated into a temp dir per test.

mod common;

use common::gltf_fixtures::*;
use common::{base64, tmpdir};
use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use serde_json::{json, Value};
use vsgl_core::scene::gltf::load;
use vsgl_core::scene::{Light, TextureUsage};

// ---------------------------------------------------------------------------------------------
// Valid files
// ---------------------------------------------------------------------------------------------

#[test]
fn external_bin_quad_with_generated_normals_and_transform() {
    let dir = tmpdir("gltf", "external_bin");
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let idx = bin.indices(&QUAD_IDX);
    // A file name with a space, referenced percent-encoded.
    std::fs::write(dir.join("my quad.bin"), &bin.data).unwrap();
    let r = root(
        &bin,
        json!({"uri": "my%20quad.bin", "byteLength": bin.data.len()}),
        json!({
            "meshes": [{"name": "quad", "primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
            "nodes": [{"mesh": 0, "name": "q", "translation": [5.0, 0.0, 0.0]}],
            "scenes": [{"nodes": [0]}],
        }),
    );
    let path = dir.join("quad.gltf");
    write_json(&path, &r);

    let scene = load(&path).unwrap();
    assert_eq!(scene.source, path.display().to_string());
    assert_eq!(scene.stats().triangles, 2);
    assert_eq!(scene.meshes.len(), 1);
    let prim = &scene.meshes[0].primitives[0];
    assert_eq!(prim.indices, QUAD_IDX.to_vec());
    assert_eq!(prim.positions.len(), 4);
    for (p, q) in prim.positions.iter().zip(QUAD_POS.chunks(3)) {
        assert!(close3(*p, [q[0], q[1], q[2]]));
    }
    // Counter-clockwise from +z: generated normals point to +z.
    assert_eq!(prim.normals.len(), 4);
    for n in &prim.normals {
        assert!(close3(*n, [0.0, 0.0, 1.0]), "normal {n:?}");
    }
    assert!(prim.uvs.is_empty() && prim.tangents.is_empty());
    // The default material was appended once.
    assert_eq!(scene.materials.len(), 1);
    assert_eq!(scene.materials[prim.material].name, "default");
    // Node transform.
    assert_eq!(scene.nodes.len(), 1);
    assert_eq!(scene.nodes[0].name, "q");
    let pts = world_points(&scene, 0);
    assert!(dclose(pts[0], DVec3::new(5.0, 0.0, 0.0)));
    assert!(dclose(pts[2], DVec3::new(6.0, 1.0, 0.0)));
    let b = scene.bounds();
    assert!(dclose(b.min, DVec3::new(5.0, 0.0, 0.0)) && dclose(b.max, DVec3::new(6.0, 1.0, 0.0)));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn clockwise_winding_flips_generated_normals() {
    let dir = tmpdir("gltf", "clockwise");
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let idx = bin.indices(&[0, 2, 1, 0, 3, 2]);
    std::fs::write(dir.join("q.bin"), &bin.data).unwrap();
    let r = root(
        &bin,
        json!({"uri": "q.bin", "byteLength": bin.data.len()}),
        json!({
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
            "nodes": [{"mesh": 0}],
        }),
    );
    let path = dir.join("q.gltf");
    write_json(&path, &r);
    let scene = load(&path).unwrap();
    for n in &scene.meshes[0].primitives[0].normals {
        assert!(close3(*n, [0.0, 0.0, -1.0]), "normal {n:?}");
    }
}

#[test]
fn glb_with_bin_chunk() {
    let dir = tmpdir("gltf", "glb");
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let idx = bin.indices(&QUAD_IDX);
    let r = root(
        &bin,
        json!({"byteLength": bin.data.len()}),
        json!({
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
            "nodes": [{"mesh": 0, "scale": [2.0, 2.0, 2.0]}],
            "scenes": [{"nodes": [0]}],
            "scene": 0,
        }),
    );
    let path = dir.join("quad.glb");
    std::fs::write(&path, glb_value(&r, &bin.data)).unwrap();
    let scene = load(&path).unwrap();
    assert_eq!(scene.stats().triangles, 2);
    let pts = world_points(&scene, 0);
    assert!(dclose(pts[2], DVec3::new(2.0, 2.0, 0.0)));
}

#[test]
fn data_uri_buffer() {
    let dir = tmpdir("gltf", "data_uri");
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let r = root(
        &bin,
        json!({
            "uri": format!("data:application/octet-stream;base64,{}", base64(&bin.data)),
            "byteLength": bin.data.len()
        }),
        // Non-indexed: 4 vertices are not a multiple of 3, but TRIANGLE_FAN (mode 6) gives 2.
        json!({
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "mode": 6}]}],
            "nodes": [{"mesh": 0}],
        }),
    );
    let path = dir.join("data.gltf");
    write_json(&path, &r);
    let scene = load(&path).unwrap();
    assert_eq!(scene.stats().triangles, 2);
    let prim = &scene.meshes[0].primitives[0];
    assert!(close3(prim.positions[2], [1.0, 1.0, 0.0]));
    for n in &prim.normals {
        assert!(
            close3(*n, [0.0, 0.0, 1.0]),
            "fan winding kept: normal {n:?}"
        );
    }
}

#[test]
fn textured_normal_mapped_material_generates_tangents() {
    let dir = tmpdir("gltf", "textured");
    let path = textured_scene(&dir, true);
    let scene = load(&path).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let prim = &scene.meshes[0].primitives[0];
    let mat = &scene.materials[prim.material];
    assert_eq!(mat.name, "painted");
    assert_eq!(mat.base_color_factor, [1.0, 0.5, 0.25, 1.0]);
    assert_eq!(
        (mat.metallic_factor, mat.roughness_factor, mat.normal_scale),
        (0.25, 0.75, 0.5)
    );

    assert_eq!(scene.textures.len(), 3);
    let base = &scene.textures[mat.base_color_texture.unwrap()];
    assert_eq!(
        (base.width, base.height, base.usage),
        (4, 2, TextureUsage::Color)
    );
    assert_eq!(base.rgba8.len(), 4 * 2 * 4);
    assert_eq!(&base.rgba8[..4], &[255, 0, 0, 255]);
    let mr = &scene.textures[mat.metallic_roughness_texture.unwrap()];
    assert_eq!(
        (mr.usage, &mr.rgba8[..4]),
        (TextureUsage::Data, &[0u8, 128, 255, 255][..])
    );
    let nt = &scene.textures[mat.normal_texture.unwrap()];
    assert_eq!((nt.width, nt.usage), (2, TextureUsage::Data));
    let stats = scene.stats();
    assert!(stats.has_textures && stats.has_normal_maps);

    assert_eq!(prim.uvs.len(), 4);
    assert_eq!(prim.tangents.len(), 4);
    for (t, n) in prim.tangents.iter().zip(&prim.normals) {
        let tv = Vec3::new(t[0], t[1], t[2]);
        let nv = Vec3::from_array(*n);
        assert!((tv.length() - 1.0).abs() < 1e-5, "tangent {t:?} not unit");
        assert!(
            tv.dot(nv).abs() < 1e-5,
            "tangent {t:?} not orthogonal to {n:?}"
        );
        assert!(t[3] == 1.0 || t[3] == -1.0);
        // u grows along +x, v along +y, normal +z: T = +x, B = N × T = +y → w = +1.
        assert!(
            close3([t[0], t[1], t[2]], [1.0, 0.0, 0.0]) && t[3] == 1.0,
            "tangent {t:?}"
        );
    }
}

/// A quad with UVs whose one material has `material` (JSON) and may name texture 0, an sRGB
/// PNG of one colour.
fn emissive_quad(dir: &Path, material: Value) -> PathBuf {
    write_png(&dir.join("glow.png"), 2, 2, [255, 128, 0, 255]);
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let uv = bin.floats(&QUAD_UV, "VEC2", 2);
    let idx = bin.indices(&QUAD_IDX);
    std::fs::write(dir.join("glow.bin"), &bin.data).unwrap();
    let r = root(
        &bin,
        json!({"uri": "glow.bin", "byteLength": bin.data.len()}),
        json!({
            "extensionsUsed": ["KHR_materials_emissive_strength"],
            "images": [{"uri": "glow.png"}],
            "textures": [{"source": 0}],
            "materials": [material],
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx, "material": 0}]}],
            "nodes": [{"mesh": 0}],
            "scenes": [{"nodes": [0]}],
        }),
    );
    let path = dir.join("glow.gltf");
    write_json(&path, &r);
    path
}

#[test]
fn emission_is_factor_times_strength_with_an_srgb_texture() {
    let dir = tmpdir("gltf", "emissive");
    let path = emissive_quad(&dir, json!({
        "emissiveFactor": [1.0, 0.5, 0.25],
        "emissiveTexture": {"index": 0},
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 40.0}},
    }));
    let scene = load(&path).unwrap();
    assert!(scene.warnings.is_empty(), "emission loads without warnings: {:?}", scene.warnings);
    let mat = &scene.materials[scene.meshes[0].primitives[0].material];
    assert_eq!(mat.emissive, [40.0, 20.0, 10.0]);
    let tex = &scene.textures[mat.emissive_texture.expect("emissive texture kept")];
    assert_eq!((tex.usage, &tex.rgba8[..4]), (TextureUsage::Color, &[255u8, 128, 0, 255][..]));
    let stats = scene.stats();
    assert!(stats.has_emission && stats.has_textures);

    // Without the extension the strength is 1; a zero factor emits nothing, so its texture is
    // not even decoded.
    let plain = load(&emissive_quad(&tmpdir("gltf", "emissive_plain"), json!({"emissiveFactor": [0.25, 0.5, 1.0]}))).unwrap();
    assert_eq!(plain.materials[0].emissive, [0.25, 0.5, 1.0]);
    let dark = load(&emissive_quad(&tmpdir("gltf", "emissive_dark"), json!({"emissiveTexture": {"index": 0}}))).unwrap();
    assert!(dark.materials[0].emissive_texture.is_none() && dark.textures.is_empty() && !dark.stats().has_emission);

    for (what, strength) in [("negative", json!(-1.0)), ("too_large", json!(1e33))] {
        let path = emissive_quad(&tmpdir("gltf", &format!("emissive_{what}")), json!({
            "emissiveFactor": [1.0, 1.0, 1.0],
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": strength}},
        }));
        expect_scene_error(&path, &["materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength"]);
    }
}

#[test]
fn normal_map_without_uvs_is_dropped_with_a_warning() {
    let dir = tmpdir("gltf", "no_uvs");
    let path = textured_scene(&dir, false);
    let scene = load(&path).unwrap();
    let prim = &scene.meshes[0].primitives[0];
    assert!(prim.tangents.is_empty());
    assert_eq!(scene.materials[prim.material].normal_texture, None);
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("meshes[0].primitives[0]") && w.contains("normal map")),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn node_hierarchy_composes_parent_transforms() {
    let dir = tmpdir("gltf", "hierarchy");
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let idx = bin.indices(&QUAD_IDX);
    std::fs::write(dir.join("h.bin"), &bin.data).unwrap();
    let r = root(
        &bin,
        json!({"uri": "h.bin", "byteLength": bin.data.len()}),
        json!({
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
            "nodes": [
                {"name": "parent", "translation": [1.0, 2.0, 3.0], "scale": [2.0, 2.0, 2.0], "children": [1]},
                {"name": "child", "translation": [1.0, 0.0, 0.0], "mesh": 0},
                // Not in the scene: its mesh must not be instanced.
                {"name": "orphan", "mesh": 0},
                // A 90° rotation about +z given as a matrix (column-major).
                {"name": "rotated", "matrix": [0,1,0,0, -1,0,0,0, 0,0,1,0, 0,0,0,1], "mesh": 0}
            ],
            "scenes": [{"nodes": [0, 3]}],
            "scene": 0,
        }),
    );
    let path = dir.join("h.gltf");
    write_json(&path, &r);
    let scene = load(&path).unwrap();
    assert_eq!(scene.nodes.len(), 4);
    assert_eq!(scene.nodes[1].parent, Some(0));
    assert_eq!(scene.nodes[0].parent, None);
    assert_eq!(scene.nodes[2].mesh, None, "unreachable node keeps no mesh");
    assert_eq!(scene.stats().triangles, 4);
    assert_eq!(scene.meshes.len(), 1, "one mesh shared by two nodes");
    let child = world_points(&scene, 1);
    // parent(T(1,2,3)·S(2)) · child(T(1,0,0)) · p
    assert!(dclose(child[0], DVec3::new(3.0, 2.0, 3.0)));
    assert!(dclose(child[2], DVec3::new(5.0, 4.0, 3.0)));
    let rotated = world_points(&scene, 3);
    assert!(dclose(rotated[1], DVec3::new(0.0, 1.0, 0.0)));
}

#[test]
fn spot_light_and_perspective_camera() {
    let dir = tmpdir("gltf", "light_camera");
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let mut bin = Bin::default();
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    std::fs::write(dir.join("l.bin"), &bin.data).unwrap();
    let r = root(
        &bin,
        json!({"uri": "l.bin", "byteLength": bin.data.len()}),
        json!({
            "extensionsUsed": ["KHR_lights_punctual"],
            "extensionsRequired": ["KHR_lights_punctual"],
            "extensions": {"KHR_lights_punctual": {"lights": [
                {"type": "spot", "color": [1.0, 0.5, 0.0], "intensity": 450.0,
                 "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}},
                {"type": "point", "intensity": 10.0, "range": 3.0},
                {"type": "spot"},
                {"type": "directional", "intensity": 2.5, "color": [0.5, 1.0, 1.0]}
            ]}},
            "cameras": [
                {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}},
                {"type": "orthographic", "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 10.0}}
            ],
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "mode": 4}]}],
            "nodes": [
                // Rotated −90° about x: local −z becomes world −y.
                {"name": "spot", "translation": [0.0, 5.0, 0.0], "rotation": [-s, 0.0, 0.0, s],
                 "extensions": {"KHR_lights_punctual": {"light": 0}}},
                {"name": "bulb", "extensions": {"KHR_lights_punctual": {"light": 1}}},
                {"name": "rig", "translation": [0.0, 0.0, 1.0], "children": [3, 4, 5]},
                {"name": "cam", "translation": [0.0, 1.0, 9.0], "camera": 0},
                {"name": "ortho", "camera": 1},
                {"name": "default spot", "extensions": {"KHR_lights_punctual": {"light": 2}}},
                // Rotated −90° about x like the spot: light travels along world −y.
                {"name": "sun", "translation": [7.0, 8.0, 9.0], "rotation": [-s, 0.0, 0.0, s],
                 "extensions": {"KHR_lights_punctual": {"light": 3}}}
            ],
            "scenes": [{"nodes": [0, 1, 2, 6]}],
        }),
    );
    let path = dir.join("l.gltf");
    write_json(&path, &r);
    let scene = load(&path).unwrap();

    assert_eq!(scene.stats().triangles, 0, "the mesh is on no node");

    assert_eq!(scene.lights.len(), 4, "spot, point, default spot, directional");
    let l = *scene.lights[0].as_spot().expect("a spot light");
    assert!(dclose(l.position, DVec3::new(0.0, 5.0, 0.0)));
    assert!(
        (l.direction - DVec3::new(0.0, -1.0, 0.0)).length() < 1e-6,
        "{:?}",
        l.direction
    );
    assert_eq!(l.intensity, 450.0);
    assert_eq!(l.color, Vec3::new(1.0, 0.5, 0.0));
    assert_eq!((l.inner_cone, l.outer_cone), (0.3, 0.5));
    // KHR_lights_punctual: a point light at its node's origin, intensity in candela.
    match scene.lights[1] {
        Light::Point(p) => {
            assert!(dclose(p.position, DVec3::ZERO), "{p:?}");
            assert_eq!((p.intensity, p.color), (10.0, Vec3::ONE));
        }
        other => panic!("lights[1] should be the point light, got {other:?}"),
    }
    // A directional light points along its node's −Z; its translation is irrelevant.
    match scene.lights[3] {
        Light::Directional(d) => {
            assert!((d.direction - DVec3::new(0.0, -1.0, 0.0)).length() < 1e-6, "{d:?}");
            assert_eq!((d.intensity, d.color), (2.5, Vec3::new(0.5, 1.0, 1.0)));
        }
        other => panic!("lights[3] should be the directional light, got {other:?}"),
    }
    let d = *scene.lights[2].as_spot().expect("a spot light");
    assert!(
        dclose(d.position, DVec3::new(0.0, 0.0, 1.0)),
        "under the rig node: {d:?}"
    );
    assert!(dclose(d.direction, DVec3::new(0.0, 0.0, -1.0)));
    assert_eq!(
        (d.inner_cone, d.outer_cone, d.intensity),
        (0.0, std::f32::consts::FRAC_PI_4, 1.0)
    );
    assert_eq!(d.color, Vec3::ONE);

    assert_eq!(scene.cameras.len(), 1);
    let c = scene.cameras[0];
    assert!(dclose(c.eye, DVec3::new(0.0, 1.0, 10.0)));
    assert!(dclose(c.forward, DVec3::new(0.0, 0.0, -1.0)));
    assert!(dclose(c.up, DVec3::Y));
    assert_eq!(c.fov_y, 0.8);

    let warned = |what: &str| scene.warnings.iter().any(|w| w.contains(what));
    assert!(
        warned("nodes[1]") && warned("lights[1].range = 3 is ignored"),
        "{:?}",
        scene.warnings
    );
    assert!(!warned("spot lights only"), "every punctual light type loads: {:?}", scene.warnings);
    assert!(
        warned("nodes[4]") && warned("orthographic"),
        "{:?}",
        scene.warnings
    );
}

#[test]
fn triangle_strip_is_triangulated() {
    let dir = tmpdir("gltf", "strip");
    let mut bin = Bin::default();
    // Strip order 0,1,3,2 over the quad corners.
    let pos = bin.floats(&QUAD_POS, "VEC3", 3);
    let idx = bin.indices(&[0, 1, 3, 2]);
    std::fs::write(dir.join("s.bin"), &bin.data).unwrap();
    let r = root(
        &bin,
        json!({"uri": "s.bin", "byteLength": bin.data.len()}),
        json!({
            "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx, "mode": 5}]}],
            "nodes": [{"mesh": 0}],
        }),
    );
    let path = dir.join("s.gltf");
    write_json(&path, &r);
    let scene = load(&path).unwrap();
    let prim = &scene.meshes[0].primitives[0];
    assert_eq!(prim.indices, vec![0, 1, 3, 1, 2, 3]);
    for n in &prim.normals {
        assert!(close3(*n, [0.0, 0.0, 1.0]), "strip winding: normal {n:?}");
    }
}
