"""Editing a Scene while another thread renders it: the render takes a
snapshot of the scene when it starts and lets go of the Python object, so the edits succeed at
once (no "Already borrowed"), the frame shows the state the render started with, and the next
render shows the edits."""

from __future__ import annotations

import threading

import numpy as np

import vsgl


def test_edits_during_a_render_apply_and_the_render_sees_its_starting_state():
    r = vsgl.Renderer(16, 16)
    scene = vsgl.scenes.cornell_box()
    # Camera paths: bit-deterministic, so "the starting state" is compared exactly.
    kw = dict(method="pathtrace", strategy="camera", spp=4096, seed=3, aovs=["image"])
    before = r.render(scene, **kw).image.copy()

    # The render's progress callback (between its GPU batches) says it is in flight and waits
    # until the edits are done, so the edits happen during the render on any machine.
    in_flight, edited = threading.Event(), threading.Event()

    def progress(done, total, unit):
        in_flight.set()
        edited.wait(30)

    out: dict = {}

    def render():
        try:
            out["frame"] = r.render(scene, progress=progress, **kw)
        except BaseException as e:  # noqa: BLE001 - reported below
            out["error"] = e

    t = threading.Thread(target=render)
    t.start()
    assert in_flight.wait(30), "the render reported no progress"
    extra = vsgl.PointLight(position=(0.3, 1.5, 0.2), intensity=2.0)
    for _ in range(50):
        scene.add_light(extra)
        scene.lights = scene.lights[:1]
    scene.add_light(extra)
    assert t.is_alive()
    edited.set()
    t.join()
    assert "error" not in out, out.get("error")
    np.testing.assert_array_equal(out["frame"].image, before)
    assert len(scene.lights) == 2
    after = r.render(scene, **{**kw, "spp": 64}).image
    assert after.sum() > r.render(vsgl.scenes.cornell_box(), **{**kw, "spp": 64}).image.sum(), "the added light does not show in the next render"
