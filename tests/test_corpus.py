"""The real-scene corpus (vsgl.scenes.corpus): its committed light specs, loading and lighting
the shared glTF files by them, and the accuracy figures the docs report on it
(docs/scenes.md, "The real-scene corpus"). Tests that need the files skip with a message when
the shared scene folder is absent; the spec tests always run."""

from __future__ import annotations

import numpy as np
import pytest

import vsgl
import vsgl.metrics
from vsgl import bench

# The three lights of the real-scene accuracy measurements, exactly (the corpus must keep them:
# every figure in the docs' tables was taken under them).
MEASURED_LIGHTS = {
    "flight_helmet": dict(position=(0.5, 0.9, 0.6), direction=(-0.6, -0.4, -0.6), intensity=3.0, inner=30.0, outer=40.0),
    "cornell_box_original": dict(position=(0.0, 1.9, 0.0), direction=(0.2, -1.0, 0.1), intensity=4.0, inner=40.0, outer=60.0),
    "boom_box": dict(position=(0.02, 0.03, 0.03), direction=(-0.5, -0.6, -0.8), intensity=0.002, inner=30.0, outer=45.0),
}


def _needs_files(name: str) -> None:
    if not vsgl.scenes.corpus_available(name):
        pytest.skip(f"skipping: corpus scene {name!r} needs {vsgl.scenes.shared_scenes_dir()} (the shared scene folder is absent)")


def test_corpus_names_cover_every_shared_scene():
    names = vsgl.scenes.corpus_names()
    assert set(MEASURED_LIGHTS) <= set(names)
    assert set(vsgl.scenes.GENERATED_CORPUS) <= set(names) and set(vsgl.scenes.GENERATED_CORPUS) <= set(vsgl.scenes.names())
    files = {vsgl.scenes._corpus_spec(n)["file"].split("/")[0] for n in names if n not in vsgl.scenes.GENERATED_CORPUS}
    assert files == {"BoomBox", "CornellBox", "CornellBoxOriginal", "FlightHelmet", "LightsSpot"}


@pytest.mark.parametrize("name", sorted(MEASURED_LIGHTS))
def test_corpus_spec_keeps_the_measured_light(name):
    spec = vsgl.scenes._corpus_spec(name)
    assert spec["scene_lights"] is False
    (light,) = [vsgl.scenes._spec_light(name, s) for s in spec["lights"]]
    want = MEASURED_LIGHTS[name]
    assert isinstance(light, vsgl.SpotLight)
    for key in ("position", "direction"):
        assert np.allclose(spec["lights"][0][key], want[key], rtol=0, atol=0), key
    assert spec["lights"][0]["intensity"] == want["intensity"]
    assert (spec["lights"][0]["inner_cone_deg"], spec["lights"][0]["outer_cone_deg"]) == (want["inner"], want["outer"])


def test_every_spec_light_is_valid():
    for name in vsgl.scenes.corpus_names():
        if name in vsgl.scenes.GENERATED_CORPUS:
            continue
        for s in vsgl.scenes._corpus_spec(name)["lights"]:
            vsgl.scenes._spec_light(name, s)


def test_a_bad_spec_light_names_the_scene_and_the_field():
    with pytest.raises(ValueError, match=r"corpus scene 'x'.*unknown \['cone'\]"):
        vsgl.scenes._spec_light("x", {"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "intensity": 1, "cone": 3})
    with pytest.raises(ValueError, match=r"corpus scene 'x'.*missing \['intensity'\]"):
        vsgl.scenes._spec_light("x", {"type": "point", "position": [0, 1, 0]})
    with pytest.raises(ValueError, match="type must be one of spot, point, directional"):
        vsgl.scenes._spec_light("x", {"type": "area"})


def test_unknown_corpus_scene_names_the_choices():
    with pytest.raises(ValueError, match="boom_box"):
        vsgl.scenes.corpus_scene("no_such_scene")


def test_missing_shared_folder_names_the_file_and_the_variable(monkeypatch, tmp_path):
    monkeypatch.setenv(vsgl.scenes.SHARED_SCENES_ENV, str(tmp_path))
    assert not vsgl.scenes.corpus_available()
    # The generated scenes need no files.
    assert [c.name for c in vsgl.scenes.corpus()] == list(vsgl.scenes.GENERATED_CORPUS)
    with pytest.raises(FileNotFoundError, match=r"VSGL_SCENES"):
        vsgl.scenes.corpus_scene("boom_box")


@pytest.mark.parametrize("name", vsgl.scenes.corpus_names())
def test_corpus_scene_loads_lit_and_renders(name, make_renderer):
    _needs_files(name)
    c = vsgl.scenes.corpus_scene(name)
    spec = {"scene_lights": True} if name in vsgl.scenes.GENERATED_CORPUS else vsgl.scenes._corpus_spec(name)
    if spec["scene_lights"]:
        assert len(c.scene.lights) >= 1
    else:
        assert len(c.scene.lights) == len(spec["lights"])
    f = make_renderer(32, 32).render(c.scene, method="vsgl", rsm_size=32, num_lights=64, aovs=["image", "indirect"])
    assert np.isfinite(f.image).all() and f.image.max() > 0


def test_a_bench_without_scenes_runs_two_corpus_scenes_where_their_files_are(monkeypatch, tmp_path, capsys):
    if vsgl.scenes.corpus_available("cornell_box_original") and vsgl.scenes.corpus_available("cornell_box_mm"):
        assert bench.default_scenes() == ["cornell_box", "cornell_box_original", "cornell_box_mm"]
    monkeypatch.setenv(vsgl.scenes.SHARED_SCENES_ENV, str(tmp_path))
    assert bench.default_scenes() == ["cornell_box"]
    assert "cornell_box_original, cornell_box_mm left out" in capsys.readouterr().err


def test_bench_and_cli_take_corpus_names():
    from vsgl.__main__ import _load_scene

    _needs_files("cornell_box_original")
    for scene in (bench._scene("cornell_box_original"), _load_scene("cornell_box_original")):
        assert scene.source.endswith("CornellBoxOriginal.glb")
        assert len(scene.lights) == 1 and isinstance(scene.lights[0], vsgl.SpotLight)
    with pytest.raises(ValueError, match="nor a corpus scene .*boom_box"):
        _load_scene("no_such_scene")


# --- Accuracy on the corpus: the setting of experiments/corpus_bias_vs_reference.md's corpus table ------------------
# 128², RSM 128², N = 1024, unshadowed, interleave 1, no denoiser, against the every-texel
# reference of the same RSM.

def _ratios(renderer, scene, method, **kw):
    aovs = ["indirect_diffuse", "indirect_specular"]
    ref = renderer.render(scene, method="reference", rsm_size=128, aovs=aovs)
    kw = {"num_lights": 1024, **kw}
    f = renderer.render(scene, method=method, rsm_size=128, aovs=aovs, **kw)
    return tuple(float(f.aov(a).mean() / ref.aov(a).mean()) for a in aovs)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(MEASURED_LIGHTS))
def test_vpls_are_near_the_reference_on_the_measured_scenes(name, make_renderer):
    # The corpus and its reference are consistent: VPLs, which estimate the reference without
    # bias, land near it (measured 0.90-1.00 diffuse, 0.98-1.03 specular; the 15% is the Monte
    # Carlo noise of 1024 VPLs on BoomBox, whose few lit concave texels carry its indirect light).
    # At N = 16384: since the spot RSMs are fitted to the scene BoomBox's RSM holds six times
    # more lit texels, and at N = 1024 its VPL means spread from 0.57 to 2.16 over 16 seeds
    # (their mean 0.97 ± 0.11 diffuse, 0.93 ± 0.08 specular; 0.97 / 1.02 at N = 16384).
    _needs_files(name)
    d, s = _ratios(make_renderer(128, 128), vsgl.scenes.corpus_scene(name).scene, "vpl", num_lights=16384)
    assert abs(d - 1) < 0.15 and abs(s - 1) < 0.15, (d, s)


# The acceptance bound, per corpus scene: default vsgl at N = 1024 within ±10% of the same-RSM
# reference in diffuse and in specular. Where it does not hold yet the test is a strict xfail
# naming what was measured (docs/scenes.md, "The real-scene corpus"), so a fix shows as an
# unexpected pass. lights_spot has no indirect light (its own test below).
_WITHIN_10_OPEN = {
    "boom_box": "1.49 / 1.87 against a reference that has 0.58 / 0.39 of the path tracer's light (vsgl 0.89 / 0.70 of it)",
    "helmet_shell": "1.01 / 1.59 against a reference that misses glossy-to-glossy light (0.82 / 0.46 of the path tracer's; vsgl 0.83 / 0.50)",
}


def _corpus_bound_params(still_open: dict[str, str]) -> list:
    """Every corpus scene with indirect light, a strict xfail naming its ratios where the bound
    is still open (so a fix shows as an unexpected pass)."""
    return [
        pytest.param(n, marks=pytest.mark.xfail(strict=True, reason=f"open: {still_open[n]}")) if n in still_open else n
        for n in vsgl.scenes.corpus_names() if n != "lights_spot"
    ]


@pytest.mark.slow
@pytest.mark.parametrize("name", _corpus_bound_params(_WITHIN_10_OPEN))
def test_default_vsgl_within_10_percent_on_the_corpus(name, make_renderer):
    _needs_files(name)
    d, s = _ratios(make_renderer(128, 128), vsgl.scenes.corpus_scene(name).scene, "vsgl", interleave=1, denoise=False)
    assert abs(d - 1) <= 0.10 and abs(s - 1) <= 0.10, (d, s)


# The acceptance's second bound: at N = the lit texels of the RSM, where each VSGL can be one
# texel, default vsgl within ±5% of the same-RSM reference in diffuse and in specular (VPLs are
# within 2% there). Measured (experiments/lavapipe/corpus/kernel_filter_lit_texels.txt):
# cornell_box_original 0.998 / 1.043, cornell_box_mm 0.997 / 0.960, furnished_room 1.019 / 1.015
# (1.056 while a kernel read at its nodes still drew its near-field texels from its parent
# node), atrium 0.983 / 1.010.
_WITHIN_5_AT_LIT_TEXELS_OPEN = {
    "flight_helmet": "1.018 / 1.105: specular over a reference of point texels (0.73 of the path tracer's specular at RSM 256²)",
    "boom_box": "1.58 / 1.92 against a reference that has 0.58 / 0.39 of the path tracer's light",
    "helmet_shell": "1.10 / 1.79 against a reference that misses glossy-to-glossy light",
}


@pytest.mark.slow
@pytest.mark.parametrize("name", _corpus_bound_params(_WITHIN_5_AT_LIT_TEXELS_OPEN))
def test_default_vsgl_within_5_percent_at_one_texel_per_vsgl(name, make_renderer):
    _needs_files(name)
    r = make_renderer(128, 128)
    scene = vsgl.scenes.corpus_scene(name).scene
    lit = int((r.render(scene, method="reference", rsm_size=128, capture_rsm=True, aovs=[]).rsm("weight")[..., 0] > 0).sum())
    d, s = _ratios(r, scene, "vsgl", num_lights=lit, interleave=1, denoise=False)
    assert abs(d - 1) <= 0.05 and abs(s - 1) <= 0.05, (lit, d, s)


# The acceptance's out-of-the-box bound: vsgl with all its own defaults (N = 1024, RSM 256²,
# interleave 8, the denoiser) at 256², mean indirect within ±15% of the 256² reference on the
# three shared scenes lit as committed. One frame's mean is one draw of a heavy-tailed estimate
# (FlightHelmet's spreads 0.65-1.19 over seeds: each pixel sees 16 VSGLs and a few texels carry
# the light), so the bound is on the mean over seeds 0-31, what the estimator delivers. Measured
# (experiments/lavapipe/corpus/out_of_the_box_32_seeds.txt): FlightHelmet 0.874 ± 0.025
# (standard error over the seeds), CornellBoxOriginal 1.020 ± 0.001; what FlightHelmet misses
# is the kernels' blur of its near-field light at RSM 256² (0.98 at RSM 128²).
_OUT_OF_THE_BOX_SEEDS = 32


# BoomBox is left out: its 32 frames take minutes on lavapipe, and its ratio (1.85 ± 0.14, the
# specular 2.98 over a reference that has 0.39 of the path tracer's) is the strict xfails' above.
@pytest.mark.slow
@pytest.mark.parametrize("name", ["flight_helmet", "cornell_box_original"])
def test_default_vsgl_out_of_the_box_within_15_percent(name, make_renderer):
    _needs_files(name)
    r = make_renderer(256, 256)
    scene = vsgl.scenes.corpus_scene(name).scene
    truth = float(r.render(scene, method="reference", rsm_size=256, aovs=["indirect"]).aov("indirect").astype(np.float64).mean())
    ratios = [float(r.render(scene, method="vsgl", seed=s, aovs=["indirect"]).aov("indirect").astype(np.float64).mean()) / truth
              for s in range(_OUT_OF_THE_BOX_SEEDS)]
    mean = float(np.mean(ratios))
    assert abs(mean - 1) <= 0.15, (mean, min(ratios), max(ratios))


def test_vsgls_default_budget_is_the_papers_and_vpls_is_unchanged(renderer):
    # Chosen on the corpus out of the box (experiments/vsgl_defaults_on_the_corpus.md,
    # experiments/lavapipe/corpus/default_num_lights.txt): 1024 VSGLs, the papers' own setting
    # with 8x8 interleaving (16 per pixel), had a lower block error than 256 on 7 of 9 scenes;
    # vpl keeps the 256 it was measured with everywhere. A default render builds that many.
    assert vsgl.method_options("vsgl")["num_lights"] == 1024
    assert vsgl.method_options("vpl")["num_lights"] == 256
    f = renderer.render(vsgl.scenes.cornell_box(), method="vsgl", rsm_size=64, aovs=[])
    assert len(f.vsgls()["diffuse_power"]) == 1024


@pytest.mark.parametrize("form", [{}, dict(lighting="asg"), dict(lighting="asg", plane_fade=False)])
def test_lone_plane_gets_no_indirect_light(form, make_renderer):
    # LightsSpot is one plane under three spots: every texel is coplanar with every receiver,
    # so the reference has no indirect light, and neither may VSGLs: each incoming-radiance SG
    # of a coplanar cluster points below the receiver's horizon (the papers' horizon clamp, which
    # lighting="asg" with plane_fade=False leaves alone to stop it), and the default's
    # clamped-cosine diffuse fades below each cluster's tangent plane.
    _needs_files("lights_spot")
    r = make_renderer(64, 64)
    scene = vsgl.scenes.corpus_scene("lights_spot").scene
    direct = r.render(scene, method="direct", aovs=["direct"]).aov("direct").mean()
    ref = r.render(scene, method="reference", rsm_size=64, aovs=["indirect"]).aov("indirect").mean()
    f = r.render(scene, method="vsgl", rsm_size=64, num_lights=256, interleave=1, denoise=False, aovs=["indirect"], **form)
    assert direct > 0
    assert ref <= 1e-6 * direct
    assert f.aov("indirect").mean() <= 1e-3 * direct


# --- Against the independent truth (the bidirectional path tracer, shadowed like it) ----------

def _over_path_tracer(renderer, scene, runs, spp=256):
    aovs = ["indirect_diffuse", "indirect_specular"]
    pt = renderer.render(scene, method="pathtrace", strategy="bidirectional", spp=spp, aovs=aovs)
    truth = [float(pt.aov(a).astype(np.float64).mean()) for a in aovs]
    out = {}
    for label, method, kw in runs:
        f = renderer.render(scene, method=method, rsm_size=128, visibility="raytrace", aovs=aovs, **kw)
        out[label] = [float(f.aov(a).astype(np.float64).mean()) / t for a, t in zip(aovs, truth)]
    return out


@pytest.mark.slow
def test_the_default_lighting_is_nearer_the_path_tracer_than_the_papers(make_renderer):
    # CornellBoxOriginal (roughness 1: rough lobes, where the papers' SG-ASG product loses half
    # of the light) against the path tracer (its own error 0.07% of the mean at 256 spp):
    # measured asg 0.854 / 0.388, blend 0.892 / 0.907 (experiments/real_scene_truth.py).
    _needs_files("cornell_box_original")
    vs = dict(num_lights=1024, interleave=1, denoise=False)
    got = _over_path_tracer(make_renderer(128, 128), vsgl.scenes.corpus_scene("cornell_box_original").scene,
                            [("default", "vsgl", vs), ("asg", "vsgl", dict(vs, lighting="asg"))])
    print(got)
    for k in range(2):
        assert abs(got["default"][k] - 1) < abs(got["asg"][k] - 1), (k, got)
    assert abs(got["default"][1] - 1) < 0.15, got


@pytest.mark.slow
def test_the_every_texel_reference_misses_most_of_boomboxs_specular(make_renderer):
    # What the docs explain BoomBox's "vsgl specular 9x the reference" by: against the path
    # tracer (1.4% own error) the every-texel reference of a 128² RSM over the spot's whole cone
    # has 0.07 of the specular light (point VPLs on a 0.6 mm grid under metal lobes narrower
    # than its angular spacing) and vsgl 0.53: the reference is the one that is off. Fitted to
    # the scene (rsm_fit="scene", the default), the same 128² RSM puts 6x more texels on the
    # box and its reference has 0.39 of the specular (measured; vsgl 0.67).
    # The spot's light alone: BoomBox's emissive texture lights the scene too since emitters
    # are lights (docs/scenes.md, "Emission in the corpus"), and this question is the spot's.
    _needs_files("boom_box")
    vs = dict(num_lights=1024, interleave=1, denoise=False)
    cone = dict(rsm_fit="cone")
    scene = vsgl.scenes.corpus_scene("boom_box").scene
    for m in scene.materials:
        if any(m["emissive"]):
            scene.set_material(m["name"], emissive=(0.0, 0.0, 0.0))
    got = _over_path_tracer(make_renderer(128, 128), scene,
                            [("reference_cone", "reference", cone), ("vsgl_cone", "vsgl", dict(vs, **cone)),
                             ("reference", "reference", {})])
    print(got)
    assert got["reference_cone"][1] < 0.2, got
    assert 0.4 < got["vsgl_cone"][1] < 1.2, got
    assert got["reference"][1] > 0.3 and got["reference"][1] > 4 * got["reference_cone"][1], got


@pytest.mark.slow
def test_helmet_shell_carries_what_the_boxes_lack(make_renderer):
    # The generated helmet-like scene (no files needed): its many small touching parts give
    # vsgl a block error several times vpl's, as on the real helmet (measured at 128², RSM 128²
    # over the spot's cone, N = 1024: vpl 0.162, vsgl 0.796; FlightHelmet 0.101 and 0.719), where
    # the boxes give 1-3x. A scene too easy to show that fails here. With the RSM fitted to the
    # scene (the default) both helmets get several times more texels and the gap narrows alike
    # (helmet_shell 0.196 and 0.325, FlightHelmet 0.303 and 0.390): the cone keeps the test's
    # question apart from the fit.
    r = make_renderer(128, 128)
    scene = vsgl.scenes.corpus_scene("helmet_shell").scene
    ref = r.render(scene, method="reference", rsm_size=128, rsm_fit="cone", aovs=["indirect"]).aov("indirect")
    err = {}
    for method, kw in (("vpl", {}), ("vsgl", dict(interleave=1, denoise=False))):
        f = r.render(scene, method=method, rsm_size=128, num_lights=1024, rsm_fit="cone", aovs=["indirect"], **kw)
        err[method] = vsgl.metrics.block_rmse(f.aov("indirect"), ref, 4)
    print(err)
    assert err["vsgl"] > 3 * err["vpl"], err
