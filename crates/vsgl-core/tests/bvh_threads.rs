//! The ray tracers' BVH is the same bytes whether one thread or many build it, on every
//! built-in scene and on the real scenes of `../shared/scenes` (skipped with a message where
//! that folder is absent): the parallel build's splice may not reorder a node or a triangle.

use std::path::Path;
use vsgl_core::scene::{builtin, gltf, Scene};
use vsgl_core::upload::bvh::{scene_triangles, Bvh};

fn assert_same_bytes(name: &str, scene: &Scene) {
    let triangles = scene_triangles(scene, scene.bounds().center());
    let one = Bvh::build_with(&triangles, usize::MAX);
    // Every subtree of 64 triangles or more split across threads, far below the default.
    let many = Bvh::build_with(&triangles, 64);
    assert!(one.nodes == many.nodes, "{name}: nodes differ");
    assert!(one.triangle_ids == many.triangle_ids, "{name}: triangles differ");
    assert_eq!(Bvh::build(&triangles).nodes, one.nodes, "{name}: the default build differs");
}

#[test]
fn builtin_scenes_build_the_same_bvh_on_any_thread_count() {
    for name in builtin::NAMES {
        assert_same_bytes(name, &builtin::by_name(name).expect("a built-in scene"));
    }
}

#[test]
fn real_scenes_build_the_same_bvh_on_any_thread_count() {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/scenes"));
    if !root.is_dir() {
        println!("skipping: ../shared/scenes not found at {}", root.display());
        return;
    }
    for file in ["FlightHelmet/FlightHelmet.gltf", "BoomBox/BoomBox.gltf", "CornellBoxOriginal/CornellBoxOriginal.glb"] {
        let path = root.join(file);
        if !path.is_file() {
            println!("skipping {file}: not found");
            continue;
        }
        let scene = gltf::load(&path).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_same_bytes(file, &scene);
    }
}
