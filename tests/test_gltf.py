"""glTF loading through the Python API: valid files, hostile files, the shared real scenes."""

from __future__ import annotations

import numpy as np
import pytest

import gltf_fixtures as fx
import vsgl


@pytest.mark.parametrize("name", sorted(fx.VALID))
def test_valid_files_load(tmp_path, name):
    writer, triangles = fx.VALID[name]
    scene = vsgl.Scene.load(writer(tmp_path))
    assert scene.stats["triangles"] == triangles


@pytest.mark.parametrize("name", sorted(fx.HOSTILE))
def test_hostile_files_raise_scene_error_naming_the_element(tmp_path, name):
    writer, element = fx.HOSTILE[name]
    path = writer(tmp_path)
    with pytest.raises(vsgl.SceneError) as info:
        vsgl.Scene.load(path)
    message = str(info.value)
    assert path.name in message, f"the message names the file: {message}"
    assert element in message, f"the message names {element!r}: {message}"
    assert fx.HOSTILE_KEYWORDS[name].lower() in message.lower(), message


@pytest.mark.parametrize("name", sorted(fx.WARNING_CASES))
def test_unsupported_content_loads_with_a_warning(tmp_path, name):
    writer, warning = fx.WARNING_CASES[name]
    scene = vsgl.Scene.load(writer(tmp_path))
    assert any(warning in w for w in scene.warnings), scene.warnings


def test_missing_file_is_a_scene_error(tmp_path):
    with pytest.raises(vsgl.SceneError, match="nope.gltf"):
        vsgl.Scene.load(tmp_path / "nope.gltf")


def test_textured_normal_mapped_file_renders_with_texture_variant(tmp_path, renderer):
    scene = vsgl.Scene.load(fx.write_textured(tmp_path))
    assert {"textures", "normal_maps"} <= set(scene.stats["features"])
    scene.add_light(vsgl.SpotLight(position=(0, 0, 3), direction=(0, 0, -1), intensity=10.0, outer_cone_deg=60, inner_cone_deg=50))
    frame = renderer.render(scene, camera=vsgl.Camera.look_at(eye=(0, 0, 3), target=(0, 0, 0)))
    assert "material" in frame.passes and "material_texture_fetch" not in frame.skipped
    assert np.isfinite(frame.image).all()


def test_spot_light_and_camera_from_file(tmp_path):
    scene = vsgl.Scene.load(fx.write_spot_light_camera(tmp_path))
    assert len(scene.cameras) == 1
    assert [type(light) for light in scene.lights] == [vsgl.SpotLight, vsgl.PointLight, vsgl.DirectionalLight]


@pytest.mark.parametrize(
    "rel,triangles",
    [
        ("CornellBox/CornellBox.glb", 36),
        ("CornellBoxOriginal/CornellBoxOriginal.glb", 32),
        ("LightsSpot/LightsSpot.gltf", 2),
        ("BoomBox/BoomBox.gltf", 6036),
        ("FlightHelmet/FlightHelmet.gltf", 94722),
    ],
)
def test_shared_real_scenes_load_and_render(shared_scenes, renderer, rel, triangles):
    scene = vsgl.Scene.load(shared_scenes / rel)
    assert scene.stats["triangles"] == triangles
    if not scene.lights:
        (lo, hi) = scene.bounds
        c = [(a + b) / 2 for a, b in zip(lo, hi)]
        extent = max(b - a for a, b in zip(lo, hi))
        scene.add_light(vsgl.SpotLight(position=(c[0], c[1] + 2 * extent, c[2] + 2 * extent), direction=(0, -1, -1), intensity=20.0 * extent**2))
    frame = renderer.render(scene)
    assert np.isfinite(frame.image).all()
    assert frame.image.max() > 0.0
