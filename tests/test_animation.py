"""Node animation (glTF ``animations``): sampling against TRS computed by hand at
keys and between them, STEP, CUBICSPLINE, clamping to [0, duration], lights that follow their
node, the geometry version (a moved mesh is uploaded again, a moved light is not), bad samplers
(in test_gltf.py through ``gltf_fixtures.HOSTILE``), and the animated built-ins."""

from __future__ import annotations

import math

import numpy as np
import pytest

import gltf_fixtures as fx
import vsgl


def trs(t=(0.0, 0.0, 0.0), yaw_deg=0.0, s=1.0, pitch_deg=0.0) -> np.ndarray:
    """T · R_y(yaw) · R_x(pitch) · S as a 4×4 matrix (column vectors, p' = M @ p)."""
    c, n = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))
    ry = np.array([[c, 0, n], [0, 1, 0], [-n, 0, c]])
    c, n = math.cos(math.radians(pitch_deg)), math.sin(math.radians(pitch_deg))
    rx = np.array([[1, 0, 0], [0, c, -n], [0, n, c]])
    m = np.eye(4)
    m[:3, :3] = ry @ rx * s
    m[:3, 3] = t
    return m


@pytest.fixture()
def animated(tmp_path) -> vsgl.Scene:
    return vsgl.Scene.load(fx.write_animated(tmp_path))


def test_the_animations_are_listed(animated):
    move, wiggle = animated.animations
    assert move == {"name": "move", "duration": 3.0, "channels": 3, "nodes": ["mover"],
                    "interpolations": ["LINEAR", "STEP"]}
    assert wiggle["duration"] == 2.0 and wiggle["interpolations"] == ["CUBICSPLINE"]
    assert vsgl.scenes.cornell_box().animations == []


# "move": translation (0,0,0) → (2,0,0) → (2,4,0), yaw 0° → 90° → 180° (LINEAR: slerp),
# scale 1 → 3 → 1 (STEP) at t = 0, 1, 3. Rest pose (translation (5,0,0), scale 2) is replaced
# wherever a channel drives a property.
@pytest.mark.parametrize("t, expected", [
    (0.0, trs()),
    (0.25, trs((0.5, 0, 0), 22.5, 1.0)),    # a quarter: slerp (a normalised lerp gives 21.6°)
    (0.5, trs((1, 0, 0), 45.0, 1.0)),       # half way: lerp, slerp to 45°, STEP holds key 0
    (1.0, trs((2, 0, 0), 90.0, 3.0)),       # on a key
    (2.0, trs((2, 2, 0), 135.0, 3.0)),
    (2.999, trs((2, 4 * 1.999 / 2, 0), 90.0 + 90.0 * 1.999 / 2, 3.0)),  # STEP jumps only at the key
    (3.0, trs((2, 4, 0), 180.0, 1.0)),
    (10.0, trs((2, 4, 0), 180.0, 1.0)),     # clamped to the duration
    (-1.0, trs()),                          # clamped to 0
])
def test_sampling_matches_hand_computed_trs(animated, t, expected):
    animated.set_time(t)
    np.testing.assert_allclose(np.array(animated.transform("mover")), expected, atol=1e-6)


def test_cubic_spline_and_lights_follow_their_node(animated):
    rest_light = animated.lights[0]
    assert rest_light.position == pytest.approx((5.0, 2.0, 0.0))  # rest: lamp 1 m above, ×2
    animated.set_time(1.0)
    # "wiggle" at t = 1 of [0, 2]: Hermite with s = 1/2, Δt = 2, v0 = 0, out-tangent 1,
    # v1 = 1, in-tangent 0: 0.5·0 + 2·0.125·1 + 0.5·1 − 2·0.125·0 = 0.75 along x.
    lamp = np.array(animated.transform("lamp"))
    np.testing.assert_allclose(lamp[:3, 3], [0.75, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(lamp, trs((0.75, 0, 0), 0.0, 1.0, -90.0), atol=1e-6)
    # The light on the lamp: mover at t = 1 is T(2,0,0)·R_y(90°)·S(3), so the lamp's origin is
    # (2,0,0) + R_y(90°)(2.25,0,0) = (2, 0, −2.25); it still points down.
    light = animated.lights[0]
    assert light.position == pytest.approx((2.0, 0.0, -2.25), abs=1e-6)
    assert light.direction == pytest.approx((0.0, -1.0, 0.0), abs=1e-6)
    world = np.array(animated.transform("lamp", world=True))
    np.testing.assert_allclose(world[:3, 3], light.position, atol=1e-9)
    # Replacing the lights detaches them: the next pose leaves the new ones where they are.
    animated.lights = [rest_light]
    animated.set_time(2.0)
    assert animated.lights[0].position == pytest.approx((5.0, 2.0, 0.0))


def test_set_transform_moves_an_attached_light(tmp_path):
    scene = vsgl.Scene.load(fx.write_spot_light_camera(tmp_path))
    up = np.eye(4)
    up[1, 3] = 7.0
    scene.set_transform("spot", (up @ np.array(scene.transform("spot"))).tolist())
    assert scene.lights[0].position == pytest.approx((0.0, 12.0, 0.0))


def test_bad_times_are_refused(animated):
    with pytest.raises(vsgl.ArgumentError, match="t: time must be a finite"):
        animated.set_time(float("nan"))
    with pytest.raises(vsgl.ArgumentError, match="t: time must be a finite"):
        animated.set_time(float("inf"))


def test_a_moved_mesh_is_uploaded_again_a_moved_light_is_not(renderer, animated):
    cam = vsgl.Camera.look_at(eye=(0, 3, 12), target=(2, 1, 0), fov_y_deg=60)
    renderer.render(animated, camera=cam, method="direct", aovs=[])
    animated.set_time(0.5)
    assert renderer.render(animated, camera=cam, method="direct", aovs=[]).settings["scene_upload"] == "uploaded"
    cave = vsgl.scenes.cave_flashlight()
    renderer.render(cave, method="direct", aovs=[])
    cave.set_time(1.0)
    assert renderer.render(cave, method="direct", aovs=[]).settings["scene_upload"] == "reused"


def test_the_cave_flashlight_sweeps(renderer):
    cave = vsgl.scenes.cave_flashlight()
    (sweep,) = cave.animations
    assert sweep["name"] == "flashlight_sweep" and sweep["duration"] == 4.0
    rest = np.array(cave.lights[0].direction)
    images = []
    for t in (0.0, 1.0, 3.0):
        cave.set_time(t)
        images.append(renderer.render(cave, method="direct", aovs=["image"]).image)
    # The beam turns by 35° either way (horizontally), so the lit spot moves across the image:
    # the brightest column shifts one way at t = 1 and the other way at t = 3.
    cave.set_time(0.0)
    assert np.allclose(cave.lights[0].direction, rest, atol=1e-12)
    column = [int(np.argmax(im.sum(axis=(0, 2)))) for im in images]
    assert column[1] != column[0] and column[2] != column[0]
    assert (column[1] - column[0]) * (column[2] - column[0]) < 0, column


def test_a_sequence_plays_time(renderer):
    cave = vsgl.scenes.cave_flashlight()
    frames = [f.image for f in renderer.render_sequence(cave, [{"time": 0.0}, {"time": 1.0}], method="direct", aovs=["image"])]
    cave.set_time(1.0)
    one = renderer.render(cave, method="direct", aovs=["image"]).image
    np.testing.assert_array_equal(frames[1], one)
    assert not np.array_equal(frames[0], frames[1])
    with pytest.raises(vsgl.ArgumentError, match=r'frames\[0\]\["time"\]'):
        list(renderer.render_sequence(cave, [{"time": float("nan")}], method="direct"))
