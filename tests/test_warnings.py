"""Black images say why: `frame.warnings` names the cause when a frame is
black because the scene has no light, the camera sees no geometry, or no light reaches anything
visible; an ordinary frame has none. The CLI prints them."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import vsgl


def test_an_ordinary_frame_has_no_warnings(renderer):
    f = renderer.render(vsgl.scenes.cornell_box(), method="vsgl", rsm_size=32, num_lights=16, aovs=["image"])
    assert f.warnings == []
    assert f.image.max() > 0


def test_a_scene_without_lights_says_so(renderer):
    scene = vsgl.scenes.cornell_box()
    scene.lights = []
    f = renderer.render(scene, aovs=["image"])
    assert not f.image.any()
    assert len(f.warnings) == 1 and f.warnings[0].startswith("the scene has no light")


def test_a_camera_facing_away_from_the_scene_says_so(renderer):
    scene = vsgl.scenes.cornell_box()
    cam = vsgl.Camera.look_at(eye=(0, 1, 10), target=(0, 1, 20))
    f = renderer.render(scene, cam, aovs=["image"])
    assert not f.image.any()
    assert any(w.startswith("the camera sees no geometry: all 3072 pixels are background") for w in f.warnings), f.warnings


@pytest.mark.parametrize("light", [
    # Behind the camera, pointing away from the box (nothing lies that way); and a cone too
    # narrow to hit anything (outer 1e-6°).
    dict(position=(0, 1, 6), direction=(0, 0, 1), intensity=5.0),
    dict(position=(0, 1.9, 0), direction=(0, -1, 0), intensity=5.0, inner_cone_deg=0.0, outer_cone_deg=1e-6),
])
def test_lights_that_reach_nothing_visible_say_so(renderer, light):
    scene = vsgl.scenes.cornell_box()
    scene.lights = [vsgl.SpotLight(**light)]
    f = renderer.render(scene, method="direct", aovs=["image"])
    if f.image.any():
        pytest.fail(f"the light reaches a visible pixel: max {f.image.max()}")
    assert any(w.startswith("the image is black: no light reaches any of the") for w in f.warnings), f.warnings


@pytest.mark.gpu
def test_the_cli_prints_the_warnings(tmp_path):
    # A built-in scene cannot be emptied from the shell; a glTF quad without lights can.
    import gltf_fixtures

    path = gltf_fixtures._quad(tmp_path)
    out = subprocess.run([sys.executable, "-m", "vsgl", "render", str(path), "--size", "32x24", "-o", str(tmp_path / "a.png")],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "warning   the scene has no light" in out.stdout, out.stdout
    # From the shell the way out is --light, and the hint's example must itself be accepted.
    hint = next(line for line in out.stdout.splitlines() if line.startswith("hint      "))
    example = hint.split('--light "', 1)[1].split('"', 1)[0]
    lit = subprocess.run([sys.executable, "-m", "vsgl", "render", str(path), "--size", "32x24", "-o", str(tmp_path / "b.png"), "--light", example],
                         capture_output=True, text=True)
    assert lit.returncode == 0 and "warning" not in lit.stdout, lit.stdout + lit.stderr  # lit, and not black
