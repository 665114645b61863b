"""Direct lighting against closed forms, determinism, and NaN/Inf safety."""

from __future__ import annotations

import math

import numpy as np
import pytest

import vsgl
from scene_builders import write_quad

SIZE = 33  # odd, so the centre pixel's ray is exactly the optical axis


def ggx_over_rs(n_dot_l: float, n_dot_v: float, n_dot_h: float, alpha: float) -> float:
    """D·G2/(4 n·l n·v) for GGX with height-correlated Smith (Walter 2007; Heitz 2014)."""
    a2 = alpha * alpha
    d = a2 / (math.pi * (n_dot_h * n_dot_h * (a2 - 1.0) + 1.0) ** 2)

    def lam(c: float) -> float:
        t2 = (1.0 - c * c) / (c * c)
        return (-1.0 + math.sqrt(1.0 + a2 * t2)) / 2.0

    g2 = 1.0 / (1.0 + lam(n_dot_l) + lam(n_dot_v))
    return d * g2 / (4.0 * n_dot_l * n_dot_v)


def centre(frame: vsgl.Frame, aov: str = "direct") -> np.ndarray:
    return frame.aov(aov)[SIZE // 2, SIZE // 2]


@pytest.mark.parametrize("rho,intensity,d", [(0.8, 20.0, 2.0), (0.5, 3.0, 0.7), (0.3, 1e4, 50.0)])
def test_diffuse_plane_under_spot_light_matches_closed_form(tmp_path, make_renderer, rho, intensity, d):
    scene = vsgl.Scene.load(write_quad(tmp_path, half_size=2.0 * d, base_color=(rho, rho, rho), roughness=1.0))
    scene.add_light(vsgl.SpotLight(position=(0, d, 0), direction=(0, -1, 0), intensity=intensity, inner_cone_deg=30, outer_cone_deg=40))
    cam = vsgl.Camera.look_at(eye=(0, 1.5 * d, 0), target=(0, 0, 0), up=(0, 0, -1), fov_y_deg=30)
    frame = make_renderer(SIZE, SIZE).render(scene, camera=cam)
    # L = (ρ/π + Rs·f_ggx) · I/d² · cosθ with l = v = n; Rs = 0.04 for a glTF dielectric
    # (docs/scenes.md, "Materials"), roughness 1 → α = 1.
    expected = (rho / math.pi + 0.04 * ggx_over_rs(1.0, 1.0, 1.0, 1.0)) * intensity / d**2
    got = centre(frame)
    np.testing.assert_allclose(got, expected, rtol=0.01)


@pytest.mark.parametrize("roughness", [0.2, 0.5])
def test_ggx_plane_in_mirror_direction_matches_closed_form(tmp_path, make_renderer, roughness):
    scene = vsgl.Scene.load(write_quad(tmp_path, half_size=6.0, base_color=(1, 1, 1), metallic=1.0, roughness=roughness))
    light_pos = np.array([-1.5, 2.0, 0.0])
    scene.add_light(vsgl.SpotLight(position=tuple(light_pos), direction=tuple(-light_pos), intensity=10.0, inner_cone_deg=20, outer_cone_deg=30))
    cam = vsgl.Camera.look_at(eye=(1.5, 2.0, 0.0), target=(0, 0, 0), fov_y_deg=20)
    frame = make_renderer(SIZE, SIZE).render(scene, camera=cam)
    dist2 = float(light_pos @ light_pos)
    cos = 2.0 / math.sqrt(dist2)
    alpha = roughness**2
    # Metal with base colour 1: Rs = 1, Rd = 0; mirror configuration: h = n.
    expected = ggx_over_rs(cos, cos, 1.0, alpha) * 10.0 / dist2 * cos
    np.testing.assert_allclose(centre(frame), expected, rtol=0.02)


def test_same_render_twice_gives_identical_pixels(renderer):
    scene = vsgl.scenes.glossy_cornell()
    a = renderer.render(scene).image
    b = renderer.render(scene).image
    assert np.array_equal(a, b)


def _assert_finite(frame: vsgl.Frame) -> None:
    for name in frame.aovs:
        arr = frame.aov(name)
        assert np.isfinite(arr).all(), f"AOV {name} has NaN/Inf"


def test_camera_inside_geometry_is_finite(renderer):
    scene = vsgl.scenes.cornell_box()
    # Inside the tall block (x ∈ [−0.65, −0.05], y ∈ [0, 1.2], z ∈ [−0.6, 0]).
    cam = vsgl.Camera.look_at(eye=(-0.35, 0.6, -0.3), target=(0.5, 0.6, -0.3), fov_y_deg=90)
    frame = renderer.render(scene, camera=cam)
    _assert_finite(frame)


def test_light_pointing_away_is_finite_and_dark(tmp_path, renderer):
    scene = vsgl.Scene.load(write_quad(tmp_path))
    # The only light points straight up, away from the plane below it.
    scene.add_light(vsgl.SpotLight(position=(0, 1, 0), direction=(0, 1, 0), intensity=5.0))
    cam = vsgl.Camera.look_at(eye=(0, 3, 3), target=(0, 0, 0), fov_y_deg=60)
    frame = renderer.render(scene, camera=cam)
    _assert_finite(frame)
    assert frame.image.max() == 0.0
    assert frame.aov("depth").max() > 0.0, "the plane is visible"


@pytest.mark.parametrize("name", vsgl.scenes.names())
def test_builtin_scenes_render_finite_and_lit(renderer, name):
    frame = renderer.render(vsgl.scenes.load(name))
    _assert_finite(frame)
    img = frame.image
    assert img.shape == (48, 64, 3) and img.dtype == np.float32
    assert img.max() > 0.0, "the default spot light lights something"
    # Variants carry their leave-outs in brackets, e.g. "direct[diffuse_only]".
    assert frame.passes[0] == "visibility" and "direct" in [p.split("[")[0] for p in frame.passes]
    assert frame.timings_ms["total"] > 0.0
    assert frame.timings_clock in ("gpu-timestamp", "cpu-wall")


def test_moving_a_node_changes_the_image(renderer):
    scene = vsgl.scenes.cornell_box()
    before = renderer.render(scene).image
    m = np.eye(4)
    m[0, 3] = 0.3  # translate the short block along +x
    scene.set_transform("short_block", m)
    after = renderer.render(scene).image
    assert np.abs(after - before).max() > 1e-3
    with pytest.raises(ValueError, match="no node named"):
        scene.set_transform("nope", m)
