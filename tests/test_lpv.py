"""method="lpv": light propagation volumes (Kaplanyan & Dachsbacher 2010), held to the float64
NumPy implementation in lpv_model.py on a small grid, to the RSM's power, and to the every-texel
reference on the diffuse Cornell box."""

from __future__ import annotations

import numpy as np
import pytest

import vsgl
import lpv_model


def _frame(renderer, scene, **options):
    return renderer.render(scene, method="lpv", rsm_size=64, capture_rsm=True, capture_lpv=True, aovs=["indirect_diffuse"], **options)


def _grid(frame, cascade=0):
    g = frame.settings["lpv_cascade_grids"][cascade]
    return np.array(g["min"]), g["cell"]


def _relative_error(gpu, model):
    return np.abs(gpu.astype(np.float64) - model).max() / np.abs(model).max()


def _unambiguous(u):
    """Asserts that no texel's cell coordinates u lie within 1e-4 cells of a boundary (the
    model and the GPU may round such a texel into different cells). The Cornell boxes' walls
    and blocks lie on whole cells of an 8³ grid; the caustics ring's geometry does not."""
    assert np.abs(u - np.round(u)).min() > 1e-4


def test_injection_equals_the_numpy_model_and_carries_the_rsms_reflected_power(renderer):
    scene = vsgl.scenes.caustics_ring()
    frame = _frame(renderer, scene, lpv_grid=8, lpv_iterations=0)
    texels = lpv_model.rsm_texels(frame, scene.lights[0].position)
    grid_min, cell = _grid(frame)
    lit = texels["flux"].max(axis=-1) > 0
    _unambiguous((texels["p"][lit] + 0.5 * cell * texels["n"][lit] - grid_min) / cell)
    model = lpv_model.inject(texels, grid_min, cell, 8)
    injected = frame.lpv("injected")
    assert injected.shape == (1, 8, 8, 8, 3, 4)
    assert _relative_error(injected[0], model) < 1e-4
    # The DC term integrates the intensity over the sphere: ∫I dω = c₀·Y₀₀·4π is the flux.
    flux = injected[0, ..., 0].astype(np.float64).sum(axis=(0, 1, 2)) * lpv_model.Y00 * 4 * np.pi
    power = texels["flux"].sum(axis=0)
    assert np.all(np.abs(flux / power - 1) < 0.01), (flux, power)


def test_the_geometry_volume_equals_the_numpy_model(renderer):
    scene = vsgl.scenes.caustics_ring()
    frame = _frame(renderer, scene, lpv_grid=8, lpv_iterations=2)
    assert "lpv_geometry" in [p.split("[")[0] for p in frame.passes]
    texels = lpv_model.rsm_texels(frame, scene.lights[0].position)
    # Texels that see no surface have a zero normal.
    background = np.all(frame.rsm("normal").reshape(-1, 3) == 0, axis=-1)
    grid_min, cell = _grid(frame)
    _unambiguous((texels["p"][~background] - grid_min) / cell + 0.5)
    model = lpv_model.geometry(texels, lpv_model.texel_areas(texels, frame), grid_min, cell, 8, background)
    assert _relative_error(frame.lpv("geometry")[0], model) < 1e-4


@pytest.mark.parametrize("occlusion", [False, True])
def test_propagation_equals_the_numpy_model(renderer, occlusion):
    scene = vsgl.scenes.diffuse_cornell()
    frame = _frame(renderer, scene, lpv_grid=8, lpv_iterations=4, lpv_occlusion=occlusion)
    injected = frame.lpv("injected")[0].astype(np.float64)
    gv = frame.lpv("geometry")[0].astype(np.float64) if occlusion else None
    model = lpv_model.propagate(injected, gv, 4)
    assert _relative_error(frame.lpv("total")[0], model) < 1e-4
    if occlusion:
        # The geometry volume matters here: without it the sum differs.
        assert _relative_error(lpv_model.propagate(injected, None, 4), model) > 1e-3


def test_mean_indirect_light_on_the_diffuse_cornell_box_is_within_half_and_one_and_a_half_of_the_reference(make_renderer):
    r = make_renderer(64, 64)
    scene = vsgl.scenes.diffuse_cornell()
    ref = r.render(scene, method="reference", rsm_size=128, aovs=["indirect_diffuse"]).aov("indirect_diffuse").astype(np.float64)
    frame = r.render(scene, method="lpv", rsm_size=128, aovs=["indirect_diffuse", "indirect_specular"])
    lpv = frame.aov("indirect_diffuse").astype(np.float64)
    ratio = lpv.mean() / ref.mean()
    assert 0.5 <= ratio <= 1.5, ratio
    assert frame.settings["lpv_iterations"] == 32 == frame.settings["lpv_grid"]
    # Diffuse only, and the frame says why.
    assert np.all(frame.aov("indirect_specular") == 0)
    assert "indirect_specular" in frame.skipped


def test_a_second_light_adds_its_light_and_not_its_occluders_again(renderer):
    # Two identical point lights in one place light the box twice as brightly as one. Each
    # light's RSM sees the same occluders, and the geometry volume keeps per cell the light whose
    # view saw most surface (lpv_geometry_merge): summed per light, the occluders blocked twice
    # and two lights gave 0.709 of twice one (emissive lamps, split into several emitter lights,
    # lost more with each: 0.99 → 0.54 of the reference from 1 to 4 on CornellBox.glb).
    scene = vsgl.scenes.diffuse_cornell()
    spot = scene.lights[0]
    point = vsgl.PointLight(position=spot.position, intensity=spot.intensity)
    frames = {}
    for n in (1, 2):
        scene.lights = [point] * n
        frames[n] = renderer.render(scene, method="lpv", rsm_size=32, lpv_grid=16, capture_lpv=True, aovs=["indirect_diffuse"])
    one, two = (frames[n].aov("indirect_diffuse").astype(np.float64).mean() for n in (1, 2))
    assert two / (2 * one) == pytest.approx(1.0, abs=1e-3), (one, two)
    assert "lpv_geometry_merge" in [p.split("[")[0] for p in frames[2].passes]
    assert "lpv_geometry_merge" not in [p.split("[")[0] for p in frames[1].passes]
    np.testing.assert_allclose(frames[2].lpv("geometry"), frames[1].lpv("geometry"), rtol=1e-5, atol=1e-7)


def test_a_moved_block_changes_the_next_frame(renderer):
    scene = vsgl.scenes.cornell_box()
    before = renderer.render(scene, method="lpv", rsm_size=64, aovs=["indirect_diffuse"]).aov("indirect_diffuse")
    m = np.eye(4)
    m[0, 3] = 0.3
    scene.set_transform("short_block", m)
    after = renderer.render(scene, method="lpv", rsm_size=64, aovs=["indirect_diffuse"]).aov("indirect_diffuse")
    assert np.abs(after - before).max() > 1e-3 * np.abs(before).max()


def test_cascades_nest_inside_the_first_and_the_volumes_are_counted(renderer):
    scene = vsgl.scenes.cornell_box()
    frame = renderer.render(scene, method="lpv", rsm_size=64, lpv_grid=16, lpv_cascades=3)
    grids = frame.settings["lpv_cascade_grids"]
    assert [g["cell"] / grids[0]["cell"] for g in grids] == pytest.approx([1, 0.5, 0.25])
    outer = np.array(grids[0]["min"]), np.array(grids[0]["min"]) + 16 * grids[0]["cell"]
    for g in grids[1:]:
        lo, hi = np.array(g["min"]), np.array(g["min"]) + 16 * g["cell"]
        assert np.all(lo >= outer[0] - 1e-6) and np.all(hi <= outer[1] + 1e-6)
    light_bytes = 3 * 16**3 * 48
    assert frame.memory_bytes["lpv_light_volume_a_buffer"] == light_bytes
    assert frame.memory_bytes["lpv_light_volume_total_buffer"] == light_bytes
    assert frame.memory_bytes["lpv_geometry_volume_buffer"] == 3 * 17**3 * 16


@pytest.mark.parametrize(
    "options, named",
    [({"lpv_grid": 2}, "lpv_grid"), ({"lpv_cascades": 5}, "lpv_cascades"), ({"lpv_iterations": -1}, "lpv_iterations"), ({"lpv_occlusion": "yes"}, "lpv_occlusion"), ({"num_lights": 64}, "num_lights")],
)
def test_bad_options_name_themselves(renderer, options, named):
    with pytest.raises((vsgl.ArgumentError, TypeError), match=named):
        renderer.render(vsgl.scenes.cornell_box(), method="lpv", **options)


def test_asking_for_the_volumes_of_another_method_says_how_to_get_them(renderer):
    frame = renderer.render(vsgl.scenes.cornell_box(), method="vpl")
    with pytest.raises(vsgl.ArgumentError, match="capture_lpv"):
        frame.lpv("total")


def test_one_iteration_leaves_the_geometry_volume_out_and_plan_full_builds_it_to_the_same_image(renderer):
    # Occlusion applies from the second propagation step on, so with one step the volume is
    # never read: left out, and plan="full" (nothing left out) gives the same light.
    scene = vsgl.scenes.cornell_box()
    auto = renderer.render(scene, method="lpv", rsm_size=64, lpv_iterations=1, aovs=["indirect_diffuse"])
    full = renderer.render(scene, method="lpv", rsm_size=64, lpv_iterations=1, plan="full", aovs=["indirect_diffuse"])
    assert "lpv_geometry" in auto.skipped and "lpv_geometry" not in [p.split("[")[0] for p in auto.passes]
    assert "lpv_geometry" in [p.split("[")[0] for p in full.passes]
    assert auto.memory_bytes["lpv_geometry_volume_buffer"] == 16
    # Injection adds floats in no fixed order: equal to rounding.
    np.testing.assert_allclose(full.aov("indirect_diffuse"), auto.aov("indirect_diffuse"), rtol=1e-5, atol=1e-7 * float(auto.aov("indirect_diffuse").max()))
    two = renderer.render(scene, method="lpv", rsm_size=64, lpv_iterations=2)
    assert "lpv_geometry" in [p.split("[")[0] for p in two.passes]
