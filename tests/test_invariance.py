"""End-to-end invariances that catch fixed world-space epsilons and f32 cancellation:
a scene far from the origin, and a scene scaled down with intensities scaled to match, must
render the same image (docs/frames.md, "Precision far from the origin")."""

from __future__ import annotations

import numpy as np
import pytest

import vsgl


def _relative_rms(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.sqrt(np.mean((a - b) ** 2)) / np.sqrt(np.mean(b**2)))


def _transformed(name: str, scale: float, offset: np.ndarray, intensity_scale: float):
    scene = vsgl.scenes.load(name)
    m = np.eye(4)
    m[:3, :3] *= scale
    m[:3, 3] = offset
    for node in scene.node_names:
        scene.set_transform(node, m)
    moved = []
    for light in scene.lights:
        moved.append(
            vsgl.SpotLight(
                position=tuple(scale * np.array(light.position) + offset),
                direction=light.direction,
                intensity=light.intensity * intensity_scale,
                color=light.color,
                inner_cone_deg=light.inner_cone_deg,
                outer_cone_deg=light.outer_cone_deg,
            )
        )
    scene.lights = moved
    cam = scene.cameras[0]
    eye = scale * np.array(cam.eye) + offset
    camera = vsgl.Camera.look_at(eye=tuple(eye), target=tuple(eye + np.array(cam.forward)), up=cam.up, fov_y_deg=cam.fov_y_deg)
    return scene, camera


@pytest.mark.parametrize("name", ["cornell_box", "glossy_cornell"])
def test_translation_by_1e4_m_gives_the_same_image(renderer, name):
    base, cam = _transformed(name, 1.0, np.zeros(3), 1.0)
    far, far_cam = _transformed(name, 1.0, np.array([1e4, -1e4, 1e4]), 1.0)
    a = renderer.render(base, camera=cam).image
    b = renderer.render(far, camera=far_cam).image
    assert _relative_rms(b, a) < 1e-3


@pytest.mark.parametrize("name", ["cornell_box", "caustics_ring"])
def test_scaling_by_1e_3_with_intensity_1e_6_gives_the_same_image(renderer, name):
    base, cam = _transformed(name, 1.0, np.zeros(3), 1.0)
    small, small_cam = _transformed(name, 1e-3, np.zeros(3), 1e-6)
    a = renderer.render(base, camera=cam).image
    b = renderer.render(small, camera=small_cam).image
    assert _relative_rms(b, a) < 1e-3


def test_lights_setter_replaces_lights():
    scene = vsgl.scenes.cornell_box()
    scene.lights = []
    assert scene.lights == [] or len(scene.lights) == 0
    scene.lights = [vsgl.SpotLight(position=(0, 1, 0), direction=(0, -1, 0), intensity=1.0)]
    assert len(scene.lights) == 1


def _orbit(scale: float, offset: np.ndarray, cam) -> list[dict]:
    """Three cameras moving around the first one, in the transformed scene's coordinates."""
    eye0 = np.array(cam.eye)
    frames = []
    for d in ([0.0, 0.0, 0.0], [0.3, 0.1, -0.2], [-0.4, -0.1, 0.3]):
        eye = scale * (eye0 + np.array(d)) + offset
        target = scale * (eye0 + np.array(cam.forward)) + offset
        frames.append({"camera": vsgl.Camera.look_at(eye=tuple(eye), target=tuple(target), up=cam.up, fov_y_deg=cam.fov_y_deg)})
    return frames


@pytest.mark.parametrize(
    ("name", "scale", "offset", "intensity_scale"),
    [("glossy_cornell", 1.0, [1e4, -1e4, 1e4], 1.0), ("cornell_box", 1e-3, [0.0, 0.0, 0.0], 1e-6)],
)
def test_invariance_holds_for_a_moving_camera_that_reuses_the_upload(renderer, name, scale, offset, intensity_scale):
    # The camera moves while the scene stays uploaded (positions relative to the scene's
    # anchor, the eye applied on the GPU): every frame must match the untransformed scene's.
    offset = np.array(offset)
    base, cam = _transformed(name, 1.0, np.zeros(3), 1.0)
    moved, _ = _transformed(name, scale, offset, intensity_scale)
    want = list(renderer.render_sequence(base, _orbit(1.0, np.zeros(3), cam), method="vsgl", aovs=["image"], interleave=4))
    got = list(renderer.render_sequence(moved, _orbit(scale, offset, cam), method="vsgl", aovs=["image"], interleave=4))
    assert [f.settings["scene_upload"] for f in got] == ["uploaded", "reused", "reused"]
    for i, (a, b) in enumerate(zip(want, got)):
        assert _relative_rms(b.image, a.image) < 1e-3, f"frame {i}"
    assert not np.array_equal(want[0].image, want[1].image), "the camera did not move"
