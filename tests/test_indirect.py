"""Reflective shadow maps, the VPL baseline and the every-texel reference (issue: RSM/VPL)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import vsgl
from scene_builders import write_quad
from test_direct import ggx_over_rs
from camera_model import camera_rays


def cone_power(intensity: float, inner_deg: float, outer_deg: float) -> float:
    """Power of a glTF spot light: 2π I ∫ att(cosθ) dcosθ with the quadratic smooth falloff:
    ∫_{cos o}^{cos i} ((c − cos o)/(cos i − cos o))² dc = (cos i − cos o)/3, plus 1 − cos i."""
    ci, co = math.cos(math.radians(inner_deg)), math.cos(math.radians(outer_deg))
    return 2.0 * math.pi * intensity * ((1.0 - ci) + (ci - co) / 3.0)


@pytest.mark.parametrize("rsm_size", [128, 256])
def test_rsm_total_diffuse_flux_equals_light_power_times_rd(tmp_path, renderer, rsm_size):
    rd = 0.6
    scene = vsgl.Scene.load(write_quad(tmp_path, half_size=50.0, base_color=(rd, rd, rd)))
    intensity, inner, outer = 7.0, 25.0, 35.0
    scene.add_light(vsgl.SpotLight(position=(0, 2, 0), direction=(0, -1, 0), intensity=intensity, inner_cone_deg=inner, outer_cone_deg=outer))
    cam = vsgl.Camera.look_at(eye=(0, 3, 3), target=(0, 0, 0))
    frame = renderer.render(scene, camera=cam, method="vpl", num_lights=16, rsm_size=rsm_size, capture_rsm=True)
    total = frame.rsm("flux_diffuse").astype(np.float64).sum(axis=(0, 1))
    np.testing.assert_allclose(total, rd * cone_power(intensity, inner, outer), rtol=0.005)
    # Φ·R_s uses F0 = 0.04 for a dielectric.
    spec = frame.rsm("flux_specular").astype(np.float64).sum(axis=(0, 1))
    np.testing.assert_allclose(spec, 0.04 * cone_power(intensity, inner, outer), rtol=0.005)

def test_a_spot_rsm_fitted_to_a_small_scene_lands_its_texels_on_it_and_keeps_its_light(tmp_path, renderer):
    """rsm_fit="scene" (the default): a 35° spot 5 m above a 1 m square spends ~2% of a cone
    RSM's texels on it; fitted to the square's bounds it spends most of them there, and the
    flux they carry is the square's exact share of the light (within the cone's inner part,
    I·Ω·R_d with Ω the square's solid angle) far closer than the cone's coarse edge gives it."""
    rd, half, height, intensity = 0.5, 0.5, 5.0, 3.0
    scene = vsgl.Scene.load(write_quad(tmp_path, half_size=half, base_color=(rd, rd, rd)))
    scene.add_light(vsgl.SpotLight(position=(0, height, 0), direction=(0, -1, 0), intensity=intensity, inner_cone_deg=25.0, outer_cone_deg=35.0))
    cam = vsgl.Camera.look_at(eye=(0, 3, 3), target=(0, 0, 0))
    solid_angle = 4.0 * math.asin(half * half / (half * half + height * height))
    exact = intensity * solid_angle * rd
    lit, error = {}, {}
    for fit in ("cone", "scene"):
        frame = renderer.render(scene, camera=cam, method="vpl", num_lights=16, rsm_size=64, capture_rsm=True, rsm_fit=fit)
        flux = frame.rsm("flux_diffuse").astype(np.float64)
        lit[fit] = int((flux.sum(-1) > 0).sum())
        error[fit] = abs(flux.sum(axis=(0, 1))[0] - exact) / exact
    assert lit["cone"] < 0.03 * 64 * 64 and lit["scene"] > 0.9 * 64 * 64, lit
    # Texels on the square's edge count whole: ~1.6% of a 64² fit (measured 2.0%; 0.4% at 256²,
    # 0.03% at 1024²), against 19.5% of the cone's 10 × 10 texels.
    assert error["scene"] < 0.025 and error["scene"] < 0.25 * error["cone"], error



def test_reference_matches_a_numpy_sum_over_every_rsm_texel(renderer):
    """The reference at a few pixels, recomputed in float64 from the RSM the GPU used."""
    scene = vsgl.scenes.cornell_box()
    frame = renderer.render(scene, method="reference", rsm_size=32, capture_rsm=True)
    cam = scene.cameras[0]
    light = scene.lights[0]
    h, w = frame.height, frame.width
    rays = camera_rays(cam, w, h)
    depth = frame.aov("depth")[..., 0].astype(np.float64)
    fwd = np.array(cam.forward)
    pos = rays * (depth / (rays @ fwd))[..., None]  # relative to the camera
    normal = frame.aov("normal").astype(np.float64)
    albedo = frame.aov("albedo").astype(np.float64)
    vpl_pos = frame.rsm("position").reshape(-1, 3).astype(np.float64)
    # Background texels (no surface) have position 0 and no flux; keep them finite.
    to_light = -vpl_pos / np.maximum(np.linalg.norm(vpl_pos, axis=1, keepdims=True), 1e-30)
    vpl_pos = vpl_pos + (np.array(light.position) - np.array(cam.eye))
    vpl_n = frame.rsm("normal").reshape(-1, 3).astype(np.float64)
    vpl_rough = frame.rsm("roughness").reshape(-1).astype(np.float64)
    fd = frame.rsm("flux_diffuse").reshape(-1, 3).astype(np.float64)
    fs = frame.rsm("flux_specular").reshape(-1, 3).astype(np.float64)
    lit = fd.sum(axis=1) + fs.sum(axis=1) > 0
    gpu = frame.aov("indirect")
    checked = 0
    for py, px in [(h // 2, w // 2), (h // 3, w // 4), (2 * h // 3, 3 * w // 4), (h - 5, w // 2)]:
        if depth[py, px] <= 0:
            continue
        p, n, v = pos[py, px], normal[py, px], -rays[py, px]
        total = np.zeros(3)
        for i in np.nonzero(lit)[0]:
            d = vpl_pos[i] - p
            dist2 = d @ d
            wi = d / math.sqrt(dist2)
            cr, cv = n @ wi, -(vpl_n[i] @ wi)
            if cr <= 0 or cv <= 0:
                continue
            a_v = max(vpl_rough[i] ** 2, 1e-4)
            hv = to_light[i] - wi
            hv /= np.linalg.norm(hv)
            spec_v = ggx_over_rs(max(vpl_n[i] @ to_light[i], 1e-9), cv, vpl_n[i] @ hv, a_v) if vpl_n[i] @ to_light[i] > 0 else 0.0
            intensity = (fd[i] / math.pi + fs[i] * spec_v) * cv
            e = intensity * cr / dist2
            hr = wi + v
            hr /= np.linalg.norm(hr)
            # cornell_box: dielectric, roughness 1 → R_s = 0.04, α = 1.
            f = albedo[py, px] / math.pi + 0.04 * ggx_over_rs(cr, n @ v, n @ hr, 1.0)
            total += f * e
        np.testing.assert_allclose(gpu[py, px], total, rtol=2e-3, atol=1e-7)
        checked += 1
    assert checked >= 3


def test_aovs_add_up(renderer):
    frame = renderer.render(vsgl.scenes.glossy_cornell(), method="vpl", num_lights=64, rsm_size=64)
    np.testing.assert_allclose(frame.aov("indirect"), frame.aov("indirect_diffuse") + frame.aov("indirect_specular"), rtol=1e-6, atol=1e-7)
    np.testing.assert_allclose(frame.image, frame.aov("direct") + frame.aov("indirect"), rtol=1e-6, atol=1e-7)
    assert frame.aov("indirect_specular").max() > 0 and frame.aov("indirect_diffuse").max() > 0
    assert "pdf_mips" in frame.passes and frame.settings["num_lights"] == 64


def _rmse(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.sqrt(np.mean((a - b) ** 2)))


def test_vpl_estimator_is_unbiased_and_converges_at_inverse_sqrt_rate(renderer):
    scene = vsgl.scenes.cornell_box()
    reference = renderer.render(scene, method="reference", rsm_size=32).aov("indirect")
    renders = [
        renderer.render(scene, method="vpl", num_lights=32, rsm_size=32, sampling="random", seed=seed).aov("indirect")
        for seed in range(64)
    ]
    errors = {m: _rmse(np.mean(renders[:m], axis=0), reference) for m in (4, 16, 64)}
    # Unbiased: the error of the mean of M renders falls like 1/√M (factor 2 per 4× M); a bias
    # would make it level off. Allow the ratio to wander from 2 by the noise of the estimate.
    assert 1.5 < errors[4] / errors[16] < 3.0, errors
    assert 1.5 < errors[16] / errors[64] < 3.0, errors
    mean_all = np.mean(renders, axis=0)
    assert abs(mean_all.mean() - reference.mean()) < 0.01 * reference.mean()


@pytest.mark.parametrize("sampling", ["stratified", "random"])
def test_vpl_error_falls_as_n_grows(renderer, sampling):
    scene = vsgl.scenes.cornell_box()
    reference = renderer.render(scene, method="reference", rsm_size=64).aov("indirect")

    def error(n: int) -> float:
        return float(np.mean([
            _rmse(renderer.render(scene, method="vpl", num_lights=n, rsm_size=64, sampling=sampling, seed=s).aov("indirect"), reference)
            for s in range(4)
        ]))

    e16, e128, e1024 = error(16), error(128), error(1024)
    assert e16 > e128 > e1024, (e16, e128, e1024)


def test_seeds_differ_and_repeat(renderer):
    scene = vsgl.scenes.cornell_box()
    a = renderer.render(scene, method="vpl", num_lights=32, rsm_size=32, seed=1).image
    b = renderer.render(scene, method="vpl", num_lights=32, rsm_size=32, seed=1).image
    c = renderer.render(scene, method="vpl", num_lights=32, rsm_size=32, seed=2).image
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


def test_vpl_clamp_bounds_spikes_and_is_off_by_default(renderer):
    # On the diffuse box the VPL spikes come from the 1/d² singularity near walls and corners,
    # which is exactly what the clamp bounds (measured: peak 0.97 → 0.23 at vpl_clamp=0.05).
    scene = vsgl.scenes.cornell_box()
    free = renderer.render(scene, method="vpl", num_lights=64, rsm_size=64, seed=3)
    clamped = renderer.render(scene, method="vpl", num_lights=64, rsm_size=64, seed=3, vpl_clamp=0.05)
    assert free.settings["vpl_clamp"] == 0.0
    assert clamped.aov("indirect").max() < 0.5 * free.aov("indirect").max()
    # Clamping only removes energy (it is biased low), never adds it.
    assert clamped.aov("indirect").mean() <= free.aov("indirect").mean()
    assert np.isfinite(clamped.image).all()


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(method="vpl", rsm_size=100), "rsm_size"),
        (dict(method="vpl", rsm_size=16), "rsm_size"),
        (dict(method="vpl", num_lights=0), "num_lights"),
        (dict(method="vpl", sampling="sobol"), "sampling"),
        (dict(method="vpl", vpl_clamp=-1.0), "vpl_clamp"),
        (dict(method="vpl", visibility="shadow_maps"), "visibility"),
        (dict(method="vpl", seed=-1), "seed"),
    ],
)
def test_bad_indirect_settings_raise_value_error(renderer, kwargs, match):
    with pytest.raises(ValueError, match=match):
        renderer.render(vsgl.scenes.cornell_box(), **kwargs)


def test_rsm_is_only_kept_on_request(renderer):
    frame = renderer.render(vsgl.scenes.cornell_box(), method="vpl", num_lights=16, rsm_size=32)
    with pytest.raises(ValueError, match="capture_rsm"):
        frame.rsm("weight")


def test_long_light_lists_are_not_truncated(make_renderer):
    """lavapipe ends shader loops after 65536 iterations; the shading passes split long VPL and
    VSGL lists over dispatches, so 131072 lights and a 512² reference count every light."""
    r = make_renderer(8, 6)
    scene = vsgl.scenes.cornell_box()
    ref256 = r.render(scene, method="reference", rsm_size=256).aov("indirect").mean()
    ref512 = r.render(scene, method="reference", rsm_size=512).aov("indirect").mean()
    assert abs(ref512 / ref256 - 1) < 0.01
    vpl = r.render(scene, method="vpl", rsm_size=512, num_lights=131072).aov("indirect").mean()
    assert abs(vpl / ref512 - 1) < 0.01
    few = r.render(scene, method="vsgl", rsm_size=512, num_lights=16384, interleave=1).aov("indirect").mean()
    many = r.render(scene, method="vsgl", rsm_size=512, num_lights=131072, interleave=1).aov("indirect").mean()
    assert abs(many / few - 1) < 0.02
