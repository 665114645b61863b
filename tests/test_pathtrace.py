"""`method="pathtrace"`: one-bounce ground truth by ray tracing (issue: RSM/VPL/references).

The path tracer must converge to what the every-texel VPL `reference` computes wherever nothing
occludes the bounce, report an honest standard error, and trace the same direct light as the
shadow-mapped direct pass away from shadow edges.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import vsgl
from scene_builders import write_quads
from camera_model import camera_rays

W, H = 64, 48


def _world_positions(frame: vsgl.Frame, cam: vsgl.Camera) -> np.ndarray:
    rays = camera_rays(cam, frame.width, frame.height)
    depth = frame.aov("depth")[..., 0].astype(np.float64)
    return np.array(cam.eye) + rays * (depth / (rays @ np.array(cam.forward)))[..., None]


def _corner_scene(tmp_path, wall_metallic: float):
    """A floor and a perpendicular wall meeting along z = −2, y = 0: a concave corner, so no
    segment between two surface points is occluded and the reference's missing visibility
    between virtual lights and pixels costs nothing. The spot light lights both."""
    floor = dict(name="floor", corners=[(-2, 0, 1), (2, 0, 1), (2, 0, -2), (-2, 0, -2)], base_color=(0.8, 0.8, 0.8), roughness=0.5)
    wall = dict(name="wall", corners=[(-2, 0, -2), (2, 0, -2), (2, 2.5, -2), (-2, 2.5, -2)], base_color=(0.9, 0.6, 0.3),
                metallic=wall_metallic, roughness=0.6)
    scene = vsgl.Scene.load(write_quads(tmp_path, [floor, wall]))
    scene.add_light(vsgl.SpotLight(position=(0.3, 1.8, 0.3), direction=(-0.2, -1, -0.8), intensity=10.0, inner_cone_deg=30, outer_cone_deg=45))
    cam = vsgl.Camera.look_at(eye=(0, 1.0, 1.6), target=(0, 0.6, -2), fov_y_deg=60)
    return scene, cam


@pytest.mark.parametrize("wall_metallic", [0.0, 1.0], ids=["dielectric_wall", "metal_wall"])
def test_pathtrace_agrees_with_reference_where_nothing_is_occluded(tmp_path, make_renderer, wall_metallic):
    scene, cam = _corner_scene(tmp_path, wall_metallic)
    r = make_renderer(W, H)
    pt = r.render(scene, camera=cam, method="pathtrace", spp=256, seed=1)
    ref = r.render(scene, camera=cam, method="reference", rsm_size=128)
    a = pt.aov("indirect").astype(np.float64)
    b = ref.aov("indirect").astype(np.float64)
    err = pt.aov("stderr").astype(np.float64)
    surface = pt.aov("depth")[..., 0] > 0
    # Near the floor–wall edge the reference's VPL spacing (one RSM texel, ~3 cm here) is
    # comparable to the distance to the bounce surface, where its 1/d² kernel makes the
    # discretization error unbounded; leave a 10 cm band out (2% of the pixels).
    pos = _world_positions(pt, cam)
    away_from_edge = np.hypot(pos[..., 1], pos[..., 2] + 2.0) > 0.1
    mask = surface & away_from_edge
    assert mask.mean() > 0.7
    # Per-pixel z test: |pt − ref| ≤ 3σ, plus a small floor for the reference's own
    # discretization (2% of the value and 1% of the mean). Measured: 0.9% (dielectric) and
    # 2.7% (metal wall, heavier tails) of the pixels fail; Gaussian errors would give 0.3%.
    floor = 0.02 * b + 0.01 * b[mask].mean()
    outliers = (np.abs(a - b) > 3.0 * err + floor)[mask].mean()
    assert outliers < 0.05, f"{outliers:.1%} of pixels beyond 3 standard errors"
    # Image means: the pixel errors are independent, so the mean's standard error is
    # √Σσ² / n; allow 4 of them plus 0.5% for the reference's discretization.
    n = mask.sum()
    for c in range(3):
        se = math.sqrt((err[..., c][mask] ** 2).sum()) / n
        mean_pt, mean_ref = a[..., c][mask].mean(), b[..., c][mask].mean()
        assert abs(mean_pt - mean_ref) <= 4.0 * se + 0.005 * mean_ref, (c, mean_pt, mean_ref, se)
    # The diffuse and specular parts converge separately too.
    for part in ["indirect_diffuse", "indirect_specular"]:
        mp, mr = pt.aov(part)[mask].mean(), ref.aov(part)[mask].mean()
        assert mp == pytest.approx(mr, rel=0.05), part
    assert np.allclose(pt.aov("image"), pt.aov("direct") + pt.aov("indirect"), rtol=1e-6, atol=1e-7)


def _dilate(m: np.ndarray, r: int) -> np.ndarray:
    out = m.copy()
    padded = np.pad(m, r)
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            out |= padded[r + dy:r + dy + m.shape[0], r + dx:r + dx + m.shape[1]]
    return out


def test_pathtrace_direct_equals_the_direct_pass_away_from_shadow_edges(tmp_path, renderer):
    """A floor under a spot light with a floating square occluder: the traced shadow rays and
    the shadow map must agree on the lit part (1%) and on the umbra (both dark)."""
    floor = dict(name="floor", corners=[(-3, 0, 3), (3, 0, 3), (3, 0, -3), (-3, 0, -3)], base_color=(0.7, 0.7, 0.7), roughness=0.4)
    occluder = dict(name="occluder", corners=[(0.0, 0.6, 0.4), (0.6, 0.6, 0.4), (0.6, 0.6, -0.2), (0.0, 0.6, -0.2)], base_color=(0.5, 0.5, 0.5))
    scene = vsgl.Scene.load(write_quads(tmp_path, [floor, occluder]))
    scene.add_light(vsgl.SpotLight(position=(0, 2, 0), direction=(0, -1, 0), intensity=20.0, inner_cone_deg=30, outer_cone_deg=40))
    cam = vsgl.Camera.look_at(eye=(0, 2.5, 3), target=(0, 0, 0))
    pt = renderer.render(scene, camera=cam, method="pathtrace", spp=1)
    dp = renderer.render(scene, camera=cam, method="direct")
    x = pt.aov("direct").astype(np.float64)[..., 1]
    y = dp.aov("direct").astype(np.float64)[..., 1]
    peak = y.max()
    assert peak > 0
    # Pixels inside the cone whose shadow ray is blocked: the umbra as the ray tracer sees it.
    pos = _world_positions(pt, cam)
    to_point = pos - np.array([0.0, 2.0, 0.0])
    cos_axis = -to_point[..., 1] / np.linalg.norm(to_point, axis=-1)
    on_floor = (np.abs(pos[..., 1]) < 1e-3) & (pt.aov("depth")[..., 0] > 0)
    in_cone = on_floor & (cos_axis > math.cos(math.radians(38)))
    umbra = in_cone & (x == 0.0)
    assert umbra.sum() >= 10, "the occluder must cast a shadow on the floor"
    # Shadow edges (the shadow map's PCF and normal offset), the cone's fading rim and the
    # occluder's own silhouette are left out: 2 pixels around every place the two disagree on
    # being dark.
    dark = (x == 0.0) | (y < 1e-3 * peak)
    edge = _dilate(dark, 2) & ~_erode(dark, 2)
    lit = (y > 1e-2 * peak) & ~edge
    assert lit.sum() > 200
    rel = np.abs(x - y)[lit] / y[lit]
    assert rel.max() < 0.01, f"max relative difference {rel.max():.3%}"
    core = _erode(umbra, 2)
    assert core.sum() > 0
    assert y[core].max() <= 1e-3 * peak, "the shadow map must agree on the umbra"


def _erode(m: np.ndarray, r: int) -> np.ndarray:
    return ~_dilate(~m, r)


def test_stderr_falls_as_one_over_sqrt_spp_and_is_deterministic(renderer):
    """Camera paths (strategy="camera") are bit-deterministic for a seed."""
    scene = vsgl.scenes.cornell_box()
    f16 = renderer.render(scene, method="pathtrace", strategy="camera", spp=16, seed=3)
    f64 = renderer.render(scene, method="pathtrace", strategy="camera", spp=64, seed=3)
    e16, e64 = f16.aov("stderr"), f64.aov("stderr")
    for e in (e16, e64):
        assert e.shape == (renderer.height, renderer.width, 3)
        assert np.isfinite(e).all() and (e >= 0).all()
    # Background pixels have no error; all others see some indirect light in the box.
    background = f64.aov("depth")[..., 0] == 0
    assert (e64[background] == 0).all()
    both = (e16 > 0) & (e64 > 0)
    assert both.mean() > 0.5
    # σ/√N: the median ratio over pixels (robust to the noisy per-pixel estimates) is 2.
    ratio = np.median(e16[both] / e64[both])
    assert ratio == pytest.approx(2.0, rel=0.15)
    # The mean of σ̂² is unbiased, so its ratio is 4 up to the spread of heavy tails.
    assert (e16[both].astype(np.float64) ** 2).mean() / (e64[both].astype(np.float64) ** 2).mean() == pytest.approx(4.0, rel=0.3)
    again = renderer.render(scene, method="pathtrace", strategy="camera", spp=16, seed=3)
    for name in ["image", "indirect", "indirect_diffuse", "indirect_specular", "stderr", "direct"]:
        np.testing.assert_array_equal(again.aov(name), f16.aov(name), err_msg=name)
    other = renderer.render(scene, method="pathtrace", strategy="camera", spp=16, seed=4)
    assert not np.array_equal(other.aov("indirect"), f16.aov("indirect"))
    np.testing.assert_array_equal(other.aov("direct"), f16.aov("direct"))
    assert f16.settings["spp"] == 16 and f16.settings["seed"] == 3


def test_stderr_matches_the_spread_of_independent_renders(renderer):
    """The reported error is honest: over independent seeds, the variance of a pixel's
    estimate matches the mean of its reported σ̂² (pooled over pixels)."""
    scene = vsgl.scenes.cornell_box()
    frames = [renderer.render(scene, method="pathtrace", spp=16, seed=100 + s) for s in range(8)]
    est = np.stack([f.aov("indirect").astype(np.float64) for f in frames])
    reported = np.stack([f.aov("stderr").astype(np.float64) ** 2 for f in frames]).mean(axis=0)
    observed = est.var(axis=0, ddof=1)
    lit = reported > 0
    ratio = observed[lit].sum() / reported[lit].sum()
    assert ratio == pytest.approx(1.0, rel=0.25)


@pytest.mark.parametrize("spp", [0, -1, 65537])
def test_bad_spp_raises_value_error_naming_it(renderer, spp):
    with pytest.raises(ValueError, match="spp"):
        renderer.render(vsgl.scenes.cornell_box(), method="pathtrace", spp=spp)


def test_the_default_strategy_is_bidirectional_and_repeats_within_float_rounding(renderer):
    """The default converges on caustics (bidirectional); its light splats are float atomics
    added in a varying order, so a seed repeats within a few f32 roundings of the sum, not bit
    for bit, while another seed is a different estimate."""
    scene = vsgl.scenes.mirror_panel()
    a = renderer.render(scene, method="pathtrace", spp=16, seed=3, aovs=["indirect"])
    assert a.settings["strategy"] == "bidirectional"
    b = renderer.render(scene, method="pathtrace", spp=16, seed=3, aovs=["indirect"])
    c = renderer.render(scene, method="pathtrace", spp=16, seed=4, aovs=["indirect"])
    ia, ib, ic = (f.aov("indirect").astype(np.float64) for f in (a, b, c))
    scale = float(ia.max())
    assert scale > 0.0
    assert np.abs(ia - ib).max() <= 1e-5 * scale
    assert np.abs(ia - ic).max() > 1e-2 * scale


def test_pathtrace_frame_reports_what_ran(renderer):
    f = renderer.render(vsgl.scenes.cornell_box(), method="pathtrace", strategy="camera", spp=2)
    assert "stderr" in f.aovs
    assert "pathtrace_direct" in f.passes and "bvh_build" in f.passes
    assert "shadow_map" in f.skipped and "direct" not in f.passes
    assert np.isfinite(f.aov("image")).all()
    # Leaving out the texture fetches (no textured material) changes nothing.
    full = renderer.render(vsgl.scenes.cornell_box(), method="pathtrace", strategy="camera", spp=2, plan="full")
    assert "pathtrace" in full.passes and "pathtrace[untextured]" in f.passes
    np.testing.assert_array_equal(full.aov("image"), f.aov("image"))


def test_the_frame_that_builds_the_bvh_says_its_time_and_size(renderer):
    scene = vsgl.scenes.glossy_cornell()
    built = renderer.render(scene, method="pathtrace", strategy="camera", spp=1, aovs=[])
    assert "bvh_build" in built.passes
    assert built.settings["bvh_build_ms"] > 0
    # 4 bytes a leaf-ordered triangle id (the corners are the upload's raster vertices) and 32 a
    # node: at most 64 bytes a triangle in all (the scale issue's bound; 78 with a copy of the
    # corners in leaf order).
    assert 4 < built.settings["bvh_bytes_per_triangle"] <= 64
    reused = renderer.render(scene, method="pathtrace", strategy="camera", spp=1, aovs=[])
    assert "bvh_build" in reused.skipped
    assert "bvh_build_ms" not in reused.settings and "bvh_bytes_per_triangle" not in reused.settings


# ------------------------------------------------------------------------------------------
# strategy="bidirectional": light tracing + camera paths by MIS
# ------------------------------------------------------------------------------------------


def _caustic_scene(tmp_path):
    """A glossy metal wall (roughness 0.3) lit by a narrow spot throws a caustic onto a diffuse
    floor: spot → glossy → diffuse → eye, the paths camera paths find only by chance. The camera
    sees only floor; nothing occludes any floor–wall segment, so the unshadowed every-texel
    `reference` is valid there."""
    floor = dict(corners=[(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="floor")
    wall = dict(corners=[(0.9, 0.0, -0.5), (0.9, 0.0, 0.5), (0.9, 0.8, 0.5), (0.9, 0.8, -0.5)], base_color=(0.9, 0.9, 0.9),
                metallic=1.0, roughness=0.3, name="glossy_wall")
    scene = vsgl.Scene.load(write_quads(tmp_path, [floor, wall], name="caustic.gltf"))
    d = np.array([0.9, -0.8, 0.0]) / np.hypot(0.9, 0.8)
    scene.lights = [vsgl.SpotLight(position=(0.0, 1.2, 0.0), direction=tuple(d), intensity=10.0, inner_cone_deg=15, outer_cone_deg=20)]
    cam = vsgl.Camera.look_at(eye=(-0.2, 2.4, 1.2), target=(0.3, 0.0, 0.0), fov_y_deg=30)
    return scene, cam


def _lum(x: np.ndarray) -> np.ndarray:
    return x.astype(np.float64).sum(axis=-1)


def test_bidirectional_pathtrace_converges_on_a_caustic_to_the_every_texel_reference(tmp_path, make_renderer):
    scene, cam = _caustic_scene(tmp_path)
    r = make_renderer(24, 24)
    ref = _lum(r.render(scene, camera=cam, method="reference", rsm_size=512).aov("indirect"))
    # The reference's own error, conservatively: its difference from one with half the RSM side.
    ref_err = np.abs(ref - _lum(r.render(scene, camera=cam, method="reference", rsm_size=256).aov("indirect")))
    lit = ref > 0.01 * ref.max()
    assert lit.mean() > 0.5, "the caustic should cover most of the view"
    bd = r.render(scene, camera=cam, method="pathtrace", spp=256, strategy="bidirectional", seed=5)
    got, sigma = _lum(bd.aov("indirect")), _lum(bd.aov("stderr"))
    z = (got - ref) / np.sqrt(sigma**2 + ref_err**2 + 1e-30)
    assert (np.abs(z[lit]) <= 3).mean() >= 0.95, f"only {(np.abs(z[lit]) <= 3).mean():.3f} of lit pixels within 3σ"
    assert got.mean() == pytest.approx(ref.mean(), rel=0.03)
    # Light tracing is what converges here: camera paths alone at the same spp are far noisier.
    cam_only = r.render(scene, camera=cam, method="pathtrace", spp=64, strategy="camera", seed=5)
    bd64 = r.render(scene, camera=cam, method="pathtrace", spp=64, strategy="bidirectional", seed=5)
    rel = lambda f: np.median(_lum(f.aov("stderr"))[lit] / np.maximum(_lum(f.aov("indirect"))[lit], 1e-30))
    assert rel(bd64) < 0.3 * rel(cam_only), (rel(bd64), rel(cam_only))
    # Its stderr halves from 4× the samples (64 → 256).
    assert rel(bd) / rel(bd64) == pytest.approx(0.5, abs=0.1)


def test_light_tracing_alone_and_bidirectional_estimate_the_same_image(tmp_path, make_renderer):
    """`strategy="light"` (photons only) and the MIS combination share no camera samples: the
    same pixel averages from independent estimates, within their errors."""
    scene, cam = _caustic_scene(tmp_path)
    r = make_renderer(24, 24)
    a = r.render(scene, camera=cam, method="pathtrace", spp=256, strategy="light", seed=1)
    b = r.render(scene, camera=cam, method="pathtrace", spp=256, strategy="bidirectional", seed=2)
    ga, gb, sa, sb = _lum(a.aov("indirect")), _lum(b.aov("indirect")), _lum(a.aov("stderr")), _lum(b.aov("stderr"))
    z = (ga - gb) / np.sqrt(sa**2 + sb**2 + 1e-30)
    lit = gb > 0.01 * gb.max()
    assert (np.abs(z[lit]) <= 3).mean() >= 0.95
    assert abs(ga.mean() - gb.mean()) < 3 * math.sqrt((sa**2).sum() + (sb**2).sum()) / ga.size
    assert a.settings["strategy"] == "light" and b.settings["strategy"] == "bidirectional"
    for f in (a, b):
        for name in f.aovs:
            assert np.isfinite(f.aov(name)).all()


@pytest.mark.parametrize("light", ["point", "directional"])
def test_bidirectional_pathtrace_handles_point_and_directional_lights(tmp_path, make_renderer, light):
    scene, cam = _caustic_scene(tmp_path)
    scene.lights = [vsgl.PointLight(position=(0.0, 1.2, 0.0), intensity=3.0) if light == "point" else vsgl.DirectionalLight(direction=(0.6, -1, 0.2), intensity=2.0)]
    r = make_renderer(24, 24)
    a = r.render(scene, camera=cam, method="pathtrace", spp=128, strategy="camera", seed=1)
    b = r.render(scene, camera=cam, method="pathtrace", spp=128, strategy="bidirectional", seed=2)
    ga, gb, sa, sb = _lum(a.aov("indirect")), _lum(b.aov("indirect")), _lum(a.aov("stderr")), _lum(b.aov("stderr"))
    # The camera's pixel-centre values and the bidirectional pixel averages agree in the mean
    # (the floor is flat and the indirect light smooth at this pixel size).
    assert gb.mean() > 0
    assert abs(ga.mean() - gb.mean()) < 4 * math.sqrt((sa**2).sum() + (sb**2).sum()) / ga.size + 0.01 * gb.mean()


def test_many_samples_per_call_lose_no_light_on_a_cpu_adapter():
    """lavapipe ends the loops of a shader invocation past 65535 loop iterations in all, and the
    path tracer's camera pass loops over a dispatch's samples, each looping over BVH nodes: with
    1024 samples per dispatch, glossy_cornell's image mean came out 0.73× that of 64 spp (blocks
    behind the sphere, whose rays pass its 4096 triangles, 0.27×). Where the adapter caps loops a
    dispatch now takes 16 samples (crates/vsgl-core/src/passes/pathtrace.rs). On a GPU the two
    agree anyway."""
    r = vsgl.Renderer(32, 32)
    scene = vsgl.scenes.glossy_cornell()

    def indirect(spp, seed):
        f = r.render(scene, method="pathtrace", strategy="camera", spp=spp, seed=seed, aovs=["indirect"])
        return f.aov("indirect").astype(np.float64).sum(axis=-1).reshape(4, 8, 4, 8).mean(axis=(1, 3))

    # 1024 samples in one call against 16 calls of 64 (each within the cap on any adapter); the
    # median over those calls, as camera paths on this scene throw fireflies (one call of the 16
    # had 8× the others' mean).
    few, many = np.median([indirect(64, seed) for seed in range(16)], axis=0), indirect(1024, 99)
    ratio = many / np.maximum(few, 1e-12)
    print(f"1024 spp in one call over 16 calls of 64: image mean {many.mean() / few.mean():.3f}, lowest 8x8 block {ratio.min():.3f}")
    assert many.mean() / few.mean() > 0.9
    assert ratio.min() > 0.6


def test_bidirectional_silhouette_pixels_whose_centre_misses_keep_their_area_light(renderer):
    """The bidirectional default estimates each pixel's area average, so a silhouette pixel whose
    centre sees the background but whose area covers part of a surface gets that part's light
    (jittered camera rays and light splats), while camera paths, which start at the centre's
    surface, leave it at 0. Leaving those pixels out lost 0.34–0.42% of the Cornell boxes'
    indirect light at 48² against Mitsuba 3 (experiments/pathtracer_vs_mitsuba.md). helmet_shell: an object against
    the background whose lit parts reach its outline (the boxes' outlines are unlit outer walls)."""
    scene = vsgl.scenes.helmet_shell()
    bd = renderer.render(scene, method="pathtrace", spp=64, seed=2, aovs=["indirect", "depth"])
    cam = renderer.render(scene, method="pathtrace", strategy="camera", spp=16, seed=2, aovs=["indirect"])
    missed = bd.aov("depth")[..., 0] == 0
    # Centre-missed pixels next to a hit pixel: the silhouette.
    hit = ~missed
    near = np.zeros_like(missed)
    near[1:, :] |= hit[:-1, :]
    near[:-1, :] |= hit[1:, :]
    near[:, 1:] |= hit[:, :-1]
    near[:, :-1] |= hit[:, 1:]
    silhouette = missed & near
    far = missed & ~near
    assert silhouette.sum() >= 4, "the view has no silhouette to test"
    lit = bd.aov("indirect").sum(axis=-1)
    assert (lit[silhouette] > 0).sum() >= 3, lit[silhouette]
    assert (cam.aov("indirect")[missed] == 0).all()
    # Pixels a whole pixel away from any surface get nothing either way.
    if far.any():
        assert (lit[far] == 0).all()
