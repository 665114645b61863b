"""glTF loading through the Python API: valid files, hostile files, the shared real scenes."""

from __future__ import annotations

import json

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


def _twin_frames(renderer, path_a, path_b, camera, aovs=("image", "albedo")):
    frames = []
    for path in (path_a, path_b):
        scene = vsgl.Scene.load(path)
        scene.add_light(vsgl.SpotLight(position=(0.5, 0.5, 3.0), direction=(0, 0, -1), intensity=20.0, outer_cone_deg=60, inner_cone_deg=50))
        frames.append(renderer.render(scene, camera=camera, method="direct", aovs=list(aovs)))
    return frames


def _rel_rms(a, b):
    a, b = np.asarray(a, np.float64), np.asarray(b, np.float64)
    return float(np.sqrt(np.mean((a - b) ** 2)) / max(np.sqrt(np.mean(b**2)), 1e-30))


def test_a_texture_transform_renders_as_its_baked_twin_and_is_visibly_not_ignored(tmp_path, renderer):
    """KHR_texture_transform on the base colour and emissive references renders as the same
    quad whose TEXCOORD_0 carries the transform, within 8-bit rounding; ignoring it (the
    untransformed quad) is far off."""
    paths = {}
    for kind in ("transformed", "baked", "ignored"):
        (tmp_path / kind).mkdir()
        paths[kind] = fx.write_texture_transform(tmp_path / kind, baked=kind == "baked", ignored=kind == "ignored")
    scene = vsgl.Scene.load(paths["transformed"])
    want = fx.texture_transform_matrix()
    got = scene.materials[0]["uv_transforms"]
    assert set(got) == {"base_color", "emissive"}
    np.testing.assert_allclose(got["base_color"], want, rtol=1e-6, atol=1e-7)
    camera = vsgl.Camera.look_at(eye=(0.5, 0.5, 1.6), target=(0.5, 0.5, 0.0))
    transformed, baked = _twin_frames(renderer, paths["transformed"], paths["baked"], camera)
    _, ignored = _twin_frames(renderer, paths["transformed"], paths["ignored"], camera)
    for aov in ("image", "albedo"):
        a, b, c = transformed.aov(aov), baked.aov(aov), ignored.aov(aov)
        assert np.abs(a - b).max() <= 2.0 / 255.0 * max(float(b.max()), 1e-30), aov
        assert _rel_rms(c, b) > 0.2, aov


def test_a_texture_transform_that_overflows_is_a_scene_error_naming_it(tmp_path):
    path = fx.write_texture_transform(tmp_path)
    root = json.loads(path.read_text())
    root["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"]["scale"] = [1e300, 1.0]
    path.write_text(json.dumps(root))
    with pytest.raises(vsgl.SceneError, match=r"materials\[0\]\.pbrMetallicRoughness\.baseColorTexture\.extensions\.KHR_texture_transform\.scale"):
        vsgl.Scene.load(path)


def test_a_texture_transforms_texcoord_override_is_honoured(tmp_path):
    """The extension's texCoord overrides the reference's: TEXCOORD_1 is not supported, so the
    texture is dropped with the usual warning."""
    path = fx.write_texture_transform(tmp_path)
    root = json.loads(path.read_text())
    root["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"]["texCoord"] = 1
    path.write_text(json.dumps(root))
    scene = vsgl.Scene.load(path)
    assert "base_color" not in scene.materials[0]["textures"]
    assert any("texCoord 1 is not supported" in w for w in scene.warnings)


def test_a_quantized_mesh_renders_as_its_float_twin(tmp_path, renderer):
    """KHR_mesh_quantization: SHORT positions dequantized by the node's scale and offset, BYTE
    normals and UNSIGNED_SHORT texture coordinates, all normalized, render as the FLOAT twin
    holding the same values, within 8-bit rounding of the image."""
    (tmp_path / "q").mkdir()
    (tmp_path / "f").mkdir()
    quantized, floats = fx.write_quantized(tmp_path / "q"), fx.write_quantized(tmp_path / "f", quantized=False)
    assert "KHR_mesh_quantization" in json.loads(quantized.read_text())["extensionsRequired"]
    lo_q, hi_q = vsgl.Scene.load(quantized).bounds
    lo_f, hi_f = vsgl.Scene.load(floats).bounds
    np.testing.assert_allclose(lo_q, lo_f, atol=1e-6)
    np.testing.assert_allclose(hi_q, hi_f, atol=1e-6)
    camera = vsgl.Camera.look_at(eye=(2.0, 0.8, 1.5), target=(0.4, 0.5, -0.4))
    a, b = _twin_frames(renderer, quantized, floats, camera, aovs=("image", "albedo", "normal"))
    for aov in ("image", "albedo", "normal"):
        assert np.abs(a.aov(aov) - b.aov(aov)).max() <= 2.0 / 255.0 * max(float(np.abs(b.aov(aov)).max()), 1e-30), aov
    assert float(b.aov("image").max()) > 0.0
