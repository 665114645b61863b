"""Editing a Scene while another thread renders it (issue 20, item 4): the render takes a
snapshot of the scene when it starts and lets go of the Python object, so the edits succeed at
once (no "Already borrowed"), the frame shows the state the render started with, and the next
render shows the edits."""

from __future__ import annotations

import threading
import time

import numpy as np

import vsgl


def test_edits_during_a_render_apply_and_the_render_sees_its_starting_state():
    r = vsgl.Renderer(16, 16)
    scene = vsgl.scenes.cornell_box()
    kw = dict(method="pathtrace", spp=2048, seed=3, aovs=["image"])
    before = r.render(scene, **kw).image.copy()

    out: dict = {}

    def render():
        try:
            out["frame"] = r.render(scene, **kw)
        except BaseException as e:  # noqa: BLE001 - reported below
            out["error"] = e

    t = threading.Thread(target=render)
    t.start()
    time.sleep(0.2)
    assert t.is_alive(), "the render finished before the edits: make it longer"
    edits = 0
    extra = vsgl.PointLight(position=(0.3, 1.5, 0.2), intensity=2.0)
    while t.is_alive() and edits < 200:
        scene.add_light(extra)
        scene.lights = scene.lights[:1]
        edits += 1
    scene.add_light(extra)
    t.join()
    assert "error" not in out, out.get("error")
    assert edits > 0
    np.testing.assert_array_equal(out["frame"].image, before)
    assert len(scene.lights) == 2
    after = r.render(scene, **kw).image
    assert after.sum() > before.sum(), "the added light does not show in the next render"
