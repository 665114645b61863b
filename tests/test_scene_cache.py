"""The renderer keeps the last scene it uploaded and reuses it while nothing the upload read has
changed (the scene instance, its geometry and the camera position): frames from the cache must
equal frames from a fresh upload, and every change that the upload reads must re-upload."""

from __future__ import annotations

import numpy as np

import vsgl


def _fresh_image(scene: vsgl.Scene, **kw) -> np.ndarray:
    # A new renderer has no cache: its frame is the fresh-upload truth.
    return vsgl.Renderer(width=64, height=48).render(scene, **kw).image


def test_an_unchanged_scene_is_uploaded_once_and_renders_the_same(renderer):
    scene = vsgl.scenes.cornell_box()
    first = renderer.render(scene, method="vsgl", num_lights=16, rsm_size=32)
    second = renderer.render(scene, method="vsgl", num_lights=16, rsm_size=32)
    assert first.settings["scene_upload"] == "uploaded"
    assert second.settings["scene_upload"] == "reused"
    np.testing.assert_array_equal(second.image, first.image)
    assert second.aov("indirect_diffuse").max() > 0.0
    # The uploading frame says what the upload cost: its time, and its geometry per triangle
    # (3 raster vertices of 16 bytes, 4 bytes of material, 12 of indices, and shading vertices
    # of 64 bytes, at most 3 a triangle).
    assert first.settings["scene_upload_ms"] > 0
    assert 3 * 16 + 4 + 12 < first.settings["scene_bytes_per_triangle"] <= 3 * 16 + 4 + 12 + 3 * 64
    assert "scene_upload_ms" not in second.settings and "scene_bytes_per_triangle" not in second.settings


def test_moving_a_node_re_uploads_and_matches_a_fresh_upload(renderer):
    scene = vsgl.scenes.cornell_box()
    before = renderer.render(scene).image
    m = np.eye(4)
    m[0, 3] = 0.3
    scene.set_transform("short_block", m)
    after = renderer.render(scene)
    assert after.settings["scene_upload"] == "uploaded"
    assert np.abs(after.image - before).max() > 1e-3, "the cached (stale) geometry was rendered"
    np.testing.assert_array_equal(after.image, _fresh_image(scene))


def test_changing_lights_reuses_the_upload_and_matches_a_fresh_upload(renderer):
    scene = vsgl.scenes.cornell_box()
    renderer.render(scene, method="vpl", num_lights=32, rsm_size=32)
    light = scene.lights[0]
    scene.lights = [
        vsgl.SpotLight(
            position=light.position,
            direction=light.direction,
            intensity=light.intensity * 3.0,
            color=(1.0, 0.5, 0.25),
            inner_cone_deg=light.inner_cone_deg,
            outer_cone_deg=light.outer_cone_deg,
        )
    ]
    frame = renderer.render(scene, method="vpl", num_lights=32, rsm_size=32)
    # Lights are read every frame, so they need no new upload of the geometry.
    assert frame.settings["scene_upload"] == "reused"
    np.testing.assert_array_equal(frame.image, _fresh_image(scene, method="vpl", num_lights=32, rsm_size=32))


def test_a_moved_camera_reuses_the_upload_and_another_scene_instance_re_uploads(renderer):
    scene = vsgl.scenes.cornell_box()
    renderer.render(scene)
    cam = scene.cameras[0]
    eye = np.array(cam.eye) + np.array([0.05, 0.0, 0.0])
    moved = vsgl.Camera.look_at(eye=tuple(eye), target=tuple(eye + np.array(cam.forward)), up=cam.up, fov_y_deg=cam.fov_y_deg)
    frame = renderer.render(scene, moved)
    # Positions are uploaded relative to the scene's anchor; the eye is applied on the GPU.
    assert frame.settings["scene_upload"] == "reused", "a moved camera must not re-upload the scene"
    np.testing.assert_array_equal(frame.image, _fresh_image(scene, camera=moved))
    # Another instance with the same geometry version (0) seen from the same eye: only the
    # scene id tells them apart (diffuse_cornell differs from cornell_box in its materials).
    other = vsgl.scenes.load("diffuse_cornell")
    frame = renderer.render(other, moved)
    assert frame.settings["scene_upload"] == "uploaded"
    np.testing.assert_array_equal(frame.image, _fresh_image(other, camera=moved))


def test_clearing_the_cache_re_uploads(renderer):
    scene = vsgl.scenes.cornell_box()
    first = renderer.render(scene)
    renderer.clear_scene_cache()
    again = renderer.render(scene)
    assert again.settings["scene_upload"] == "uploaded"
    np.testing.assert_array_equal(again.image, first.image)
