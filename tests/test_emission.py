"""Emissive materials: glTF emissiveFactor × KHR_materials_emissive_strength ×
emissiveTexture is the emitted radiance L_e, and every method shows it where the camera sees the
surface: in `image` and `direct`, never in `indirect`. Emissive surfaces also light other
surfaces: as area lights in the path tracer, as clusters of lights elsewhere
(tests/test_emitters.py; docs/scenes.md, "Emission")."""

from __future__ import annotations

import numpy as np
import pytest

import gltf_fixtures as fx
import vsgl
from vsgl.stability import small_settings

def settings(method: str) -> dict:
    # Small settings for whichever options the method takes (lavapipe runs the shaders on the CPU).
    return small_settings(method, shadow_size=64, num_lights=16, rsm_size=32, spp=2, lpv_grid=8)


@pytest.fixture(scope="module")
def emissive_quad(tmp_path_factory) -> vsgl.Scene:
    return vsgl.Scene.load(fx.write_emissive_glb(tmp_path_factory.mktemp("emissive")))


# Straight at the unit quad's centre from 2 units away: it covers the middle of the frame.
QUAD_CAMERA = dict(eye=(0.5, 0.5, 2.0), target=(0.5, 0.5, 0.0), fov_y_deg=45.0)


@pytest.mark.parametrize("method", vsgl.METHODS)
def test_an_emissive_texture_with_strength_shows_in_every_method_without_lights(make_renderer, emissive_quad, method):
    r = make_renderer(32, 32)
    f = r.render(emissive_quad, vsgl.Camera.look_at(**QUAD_CAMERA), method=method, **settings(method))
    expected = np.array(fx.emissive_radiance(), dtype=np.float32)
    inner = f.image[12:20, 12:20].reshape(-1, 3)
    np.testing.assert_allclose(inner, np.broadcast_to(expected, inner.shape), rtol=0.01)
    # What reaches the camera without a bounce: direct holds it, image = direct + indirect.
    np.testing.assert_array_equal(f.aov("direct"), f.image)
    if "indirect" in f.aovs:
        assert not f.aov("indirect").any(), "emission leaked into the indirect AOV"
    # Background pixels stay black: emission is where the quad is, nowhere else.
    assert not f.image[0, 0].any() and not f.image[-1, -1].any()
    assert "emission" not in f.skipped
    # No punctual light, and every method lights with emitters, but the quad has nothing in
    # front of it to light: the warning says so.
    assert vsgl.method_info(method)["emitters"] in ("area", "clusters")
    assert len(f.warnings) == 1 and "nothing lies in front of its emissive surfaces" in f.warnings[0], f.warnings


def test_emission_is_reported_in_the_scene_stats(emissive_quad):
    stats = emissive_quad.stats
    assert "emissive" in stats["features"] and "textures" in stats["features"]
    assert 'as area lights in method="pathtrace", as clusters of lights (option emitter_lights)' in stats["emission"]
    assert emissive_quad.warnings == []


def test_scenes_without_emission_leave_it_out_and_a_channel_of_zeros_changes_nothing(make_renderer):
    r = make_renderer(32, 32)
    scene = vsgl.scenes.cornell_box()
    auto = r.render(scene, method="vsgl", **settings("vsgl"))
    assert "emissive" in auto.skipped["emission"]
    # plan="full" writes the emission channel (zeros here) and adds it: bit-identical.
    full = r.render(scene, method="vsgl", plan="full", **settings("vsgl"))
    assert "emission" not in full.skipped
    np.testing.assert_array_equal(full.image, auto.image)
    np.testing.assert_array_equal(full.aov("direct"), auto.aov("direct"))


def test_the_cornell_box_ceiling_light_shows_its_emitted_radiance(shared_scenes, make_renderer):
    """The shared CornellBox (millimetres, no punctual lights): its ceiling quad has
    emissiveFactor 1 and emissiveStrength 100, so it must show radiance 100 in every channel."""
    scene = vsgl.Scene.load(shared_scenes / "CornellBox" / "CornellBox.glb")
    assert "emissive" in scene.stats["features"]
    assert not any("emission" in w for w in scene.warnings), scene.warnings
    # From the box's centre straight up at the quad (x in [-343, -213], z in [-332, -227] at
    # y = 547.9): it covers about the middle half of a 45° view.
    cam = vsgl.Camera.look_at(eye=(-278.0, 274.0, -279.5), target=(-278.0, 547.9, -279.5), up=(0, 0, -1), fov_y_deg=45.0)
    r = make_renderer(32, 32)
    for method in ("direct", "vsgl", "pathtrace"):
        # 8 paths a pixel, not 2: at 2 a ceiling corner's bounce is zero for 1 seed in 12 (each
        # emitter sample draws six more numbers since BSDF-sampled emitter hits, seed 0 is one).
        f = r.render(scene, cam, method=method, **dict(settings(method), **({"spp": 8} if method == "pathtrace" else {})))
        # What the quad sends without a bounce (where emitters light the scene, the quad also
        # reflects their light off the floor: image = direct + that).
        inner = f.aov("direct")[13:19, 13:19].reshape(-1, 3)
        np.testing.assert_allclose(inner, 100.0, rtol=0.01, err_msg=method)
        # Three image corners see the ceiling around the quad (the fourth a wall the quad lights):
        # it gets no direct light from the quad (they are coplanar), only its bounce off the
        # walls where the method makes one: lit, and far dimmer than the quad.
        ceiling = ((0, 0), (-1, 0), (-1, -1))
        corners = [f.image[y, x] for y, x in ceiling]
        assert all(not f.aov("direct")[y, x].any() for y, x in ceiling), method
        if "indirect" in f.aovs:
            assert all(0 < c.min() and c.max() < 1.0 for c in corners), (method, corners)
        else:
            assert all(not c.any() for c in corners), (method, corners)


def test_loaded_materials_show_their_emission(emissive_quad):
    (glow,) = emissive_quad.materials
    assert glow["name"] == "glow"
    assert glow["emissive"] == pytest.approx([f * fx.EMISSIVE_STRENGTH for f in fx.EMISSIVE_FACTOR])
    assert glow["textures"] == ["emissive"]


def test_a_material_made_emissive_from_python_shows_in_the_image(make_renderer):
    r = make_renderer(32, 32)
    scene = vsgl.scenes.cornell_box()
    scene.lights = []
    assert all(m["emissive"] == [0.0, 0.0, 0.0] for m in scene.materials)
    # Rendered once before the edit: the edit must re-upload the materials, not reuse the cache.
    assert not r.render(scene, method="vsgl", **settings("vsgl")).image.any()
    scene.set_material("red", emissive=(2.0, 0.5, 0.0))
    assert "emissive" in scene.stats["features"]
    f = r.render(scene, method="vsgl", **settings("vsgl"))
    direct = f.aov("direct").reshape(-1, 3)
    # Only the red wall emits: its pixels' direct light is exactly its radiance (it cannot light
    # itself), and it lights the rest of the box, directly and by a bounce.
    wall = np.all(direct == np.float32([2.0, 0.5, 0.0]), axis=1)
    assert wall.any() and not wall.all()
    assert (direct[~wall].sum(axis=1) > 0).mean() > 0.25  # measured 0.44 (one emitter light, its shadows)
    assert f.warnings == []
    assert f.aov("indirect").any()


@pytest.mark.parametrize("kw, message", [
    (dict(emissive=(-1.0, 0.0, 0.0)), r"emissive: must be finite, >= 0 and at most 1e32"),
    (dict(emissive=(1e33, 0.0, 0.0)), r"emissive: must be finite, >= 0 and at most 1e32"),
    (dict(roughness=1.5), r"roughness: must be in \[0, 1\], got 1.5"),
    (dict(base_color=(1.0, 2.0, 0.0)), r"base_color: must be in \[0, 1\], got 2"),
    (dict(metallic=10**400), r"metallic: must be in \[0, 1\], got inf"),
])
def test_bad_material_values_are_refused_by_name_and_change_nothing(kw, message):
    scene = vsgl.scenes.cornell_box()
    before = scene.materials
    with pytest.raises(vsgl.ArgumentError, match=message):
        scene.set_material("red", **kw)
    assert scene.materials == before
    with pytest.raises(vsgl.ArgumentError, match=r'name: no material named "no such"'):
        scene.set_material("no such", roughness=0.5)
