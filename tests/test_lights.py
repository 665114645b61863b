"""Point and directional lights (issue 16): the Python classes and the glTF loader."""

from __future__ import annotations

import math

import numpy as np
import pytest

import vsgl
import gltf_fixtures as fx

# ------------------------------------------------------------------------------------------
# API and loader
# ------------------------------------------------------------------------------------------


def test_point_and_directional_light_classes():
    p = vsgl.PointLight(position=(1, 2, 3), intensity=5.0, color=(1, 0.5, 0.25))
    assert p.position == (1, 2, 3) and p.intensity == 5.0 and p.color == (1, 0.5, 0.25)
    d = vsgl.DirectionalLight(direction=(0, -2, 0), intensity=3.0)
    assert d.direction == (0, -1, 0), "the direction is normalised"
    assert d.intensity == 3.0 and d.color == (1, 1, 1)
    assert "PointLight(" in repr(p) and "DirectionalLight(" in repr(d)


@pytest.mark.parametrize(
    "make,name",
    [
        (lambda: vsgl.PointLight(position=(0, math.nan, 0), intensity=1.0), "position"),
        (lambda: vsgl.PointLight(position=(0, 0), intensity=1.0), "position"),
        (lambda: vsgl.PointLight(position=(0, 0, 0), intensity=0.0), "intensity"),
        (lambda: vsgl.PointLight(position=(0, 0, 0), intensity=math.inf), "intensity"),
        (lambda: vsgl.PointLight(position=(0, 0, 0), intensity=1.0, color=(1, -1, 1)), "color"),
        (lambda: vsgl.DirectionalLight(direction=(0, 0, 0), intensity=1.0), "direction"),
        (lambda: vsgl.DirectionalLight(direction=(0, math.inf, 0), intensity=1.0), "direction"),
        (lambda: vsgl.DirectionalLight(direction=(0, -1, 0), intensity=-2.0), "intensity"),
        (lambda: vsgl.DirectionalLight(direction=(0, -1, 0), intensity=1.0, color=(1, 1, math.nan)), "color"),
    ],
)
def test_bad_light_arguments_raise_argument_error_naming_them(make, name):
    with pytest.raises(vsgl.ArgumentError, match=f"^{name}:"):
        make()


def test_scene_takes_a_mix_of_light_types():
    scene = vsgl.scenes.cornell_box()
    spot = scene.lights[0]
    scene.add_light(vsgl.PointLight(position=(0, 1, 0), intensity=2.0))
    scene.add_light(vsgl.DirectionalLight(direction=(0, -1, 0), intensity=3.0))
    assert [type(light) for light in scene.lights] == [vsgl.SpotLight, vsgl.PointLight, vsgl.DirectionalLight]
    assert scene.stats["lights"] == 3
    assert scene.stats["lights_by_type"] == {"spot": 1, "point": 1, "directional": 1}
    scene.lights = [vsgl.DirectionalLight(direction=(1, -1, 0), intensity=1.0), spot]
    assert [type(light) for light in scene.lights] == [vsgl.DirectionalLight, vsgl.SpotLight]
    assert scene.stats["lights_by_type"] == {"spot": 1, "point": 0, "directional": 1}
    with pytest.raises(TypeError):
        scene.add_light("a lamp")


def test_loader_reads_point_and_directional_lights_with_gltf_conventions(tmp_path):
    scene = vsgl.Scene.load(fx.write_spot_light_camera(tmp_path))
    spot, point, sun = scene.lights
    assert isinstance(point, vsgl.PointLight) and point.position == (0, 0, 0) and point.intensity == 10.0
    # KHR_lights_punctual: the light travels along its node's −Z (here rotated to −Y); the
    # node's translation does not matter for a directional light.
    assert isinstance(sun, vsgl.DirectionalLight)
    np.testing.assert_allclose(sun.direction, (0, -1, 0), atol=1e-6)
    assert sun.intensity == 2.0 and sun.color == (0.5, 1.0, 1.0)
    assert any("range = 3 is ignored" in w for w in scene.warnings), scene.warnings
