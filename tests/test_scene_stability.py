"""The scene-level stability suite (`python -m vsgl stability --scenes`):
every method on three built-ins, the generated corpus scenes (helmet_shell, furnished_room, atrium)
and a room read from a glTF file (also written with a 1e5 m offset in its nodes) moved 1e5 m, scaled 1e-3, 0.37 and 1e3 (intensities × scale²), with
intensities × 1e-8 and at 1e30 cd, a light grazing a wall, every material at roughness 1e-4 and
the camera inside geometry renders no NaN/Inf, and is invariant within 1e-3 (relative RMSE)
where the scene is representable."""

from __future__ import annotations

import pytest

import vsgl
from vsgl import stability


@pytest.mark.gpu
@pytest.mark.slow
def test_every_method_on_every_case_passes():
    rows = stability.scene_suite()
    print("\n" + stability.format_scene_table(rows))
    # Seven scenes (the generated corpus scenes and the file scene among them) × every method × 10
    # cases, and the file scene's own case per method: the offset written into the file.
    assert len(rows) == 7 * len(vsgl.METHODS) * 10 + len(vsgl.METHODS)
    assert {r["scene"] for r in rows} == {"cornell_box", "glossy_cornell", "caustics_ring", *vsgl.scenes.GENERATED_CORPUS, stability.FILE_SCENE}
    # Every method met the near-mirror materials.
    stiff = [r for r in rows if r["case"] == "roughness 1e-4"]
    assert len(stiff) == 7 * len(vsgl.METHODS) and {r["method"] for r in stiff} == set(vsgl.METHODS)
    assert not [r for r in rows if r["nonfinite"]], "frames with NaN/Inf"
    failed = [r for r in rows if not r["passed"]]
    assert not failed, failed
    # The invariance rows were compared, not skipped.
    moved = [r for r in rows if r["case"] == "moved 1e5 m"]
    assert moved and all(r["rel_rmse"] is not None for r in moved)
    # A file whose nodes (geometry, light, camera) stand 1e5 m out renders as the same file at
    # the origin in every method (the loader reads node transforms in f64).
    in_file = [r for r in rows if r["case"] == "moved 1e5 m in the file"]
    assert {r["method"] for r in in_file} == set(vsgl.METHODS) and all(r["rel_rmse"] is not None and r["passed"] for r in in_file)
    # Scaled by 0.37, pixels on the Cornell box's ceiling/left-wall edge see the wall instead of
    # the ceiling (f32 rounding of the vertices, in every method alike); they are set apart by
    # the G-buffer and the rest is invariant. An H200 does this at 1e-3 and 1e3 as well.
    edge = [r for r in rows if r["scene"] == "cornell_box" and r["case"].startswith("scaled 0.37")]
    assert edge and all(r["surface"] > 0 for r in edge), edge


@pytest.mark.gpu
def test_the_suite_can_fail(monkeypatch):
    # An intensity doubled but divided by 1: the invariance row must fail.
    real = stability._scene_cases

    def wrong(name):
        for case, scene, camera, divide, geometry_scale in real(name):
            if case == "base":
                yield case, scene, camera, divide, geometry_scale
        yield "intensity x 2 divided by 1", *stability.transformed_scene(name, intensity_scale=2.0), 1.0, 1.0

    monkeypatch.setattr(stability, "_scene_cases", wrong)
    rows = stability.scene_suite(scenes=("cornell_box",), methods=("direct", "vsgl"))
    assert [r["passed"] for r in rows if r["case"] != "base"] == [False, False]
    assert all(r["rel_rmse"] > 0.5 for r in rows if r["case"] != "base")


@pytest.mark.gpu
def test_pixels_that_change_surface_are_counted_apart_and_bounded(monkeypatch):
    """The G-buffer decides which pixels changed surface: a camera turned by 3° changes most of
    them, which must fail as "surface" (not pass because they were set apart)."""
    import numpy as np

    real = stability._scene_cases

    def turned(name):
        for case, scene, camera, divide, geometry_scale in real(name):
            if case == "base":
                yield case, scene, camera, divide, geometry_scale
                eye, fwd = np.array(camera.eye), np.array(camera.forward)
                c, s = np.cos(np.radians(3.0)), np.sin(np.radians(3.0))
                fwd = np.array([c * fwd[0] + s * fwd[2], fwd[1], -s * fwd[0] + c * fwd[2]])
                cam = vsgl.Camera.look_at(eye=tuple(eye), target=tuple(eye + fwd), up=camera.up, fov_y_deg=camera.fov_y_deg)
                yield "camera turned 3°", scene, cam, 1.0, 1.0

    monkeypatch.setattr(stability, "_scene_cases", turned)
    rows = stability.scene_suite(scenes=("cornell_box",), methods=("direct", "vsgl"))
    moved = [r for r in rows if r["case"] != "base"]
    assert [r["passed"] for r in moved] == [False, False]
    assert all(r["surface"] > stability.SURFACE_FRACTION * 32 * 24 for r in moved), moved
