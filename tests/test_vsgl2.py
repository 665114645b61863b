"""method="vsgl2": two VSGLs by parallel summation over the whole RSM (the 2015 poster).

Record 0 is the diffuse VSGL (the Φ·R_d-weighted Lambert lobes and positions), record 1 the
specular VSGL (Φ·R_s-weighted GGX lobes and positions); each carries only its own power."""

from __future__ import annotations

import math

import numpy as np
import pytest

import vsgl
from rsm_model import spot_texel_footprint_variance
from vsgl import bench
from scene_builders import write_quads
from shader_constants import wgsl_constant

# Constants of wgsl/common/sg.wgsl, ggx.wgsl and vsgl.wgsl (as in test_vsgl.py).
LAMBERT_LOBE_SG_SHARPNESS = wgsl_constant("common/sg.wgsl", "LAMBERT_LOBE_SG_SHARPNESS")
TOKSVIG_SHARPNESS_MAX = wgsl_constant("common/sg.wgsl", "TOKSVIG_SHARPNESS_MAX")
SG_SHARPNESS_MAX = wgsl_constant("common/sg.wgsl", "SG_SHARPNESS_MAX")
GGX_ALPHA_MIN = wgsl_constant("common/ggx.wgsl", "GGX_ALPHA_MIN")
VSGL_VARIANCE_MIN_FRACTION = wgsl_constant("common/vsgl.wgsl", "VSGL_VARIANCE_MIN_FRACTION")


def _rmse(a, b):
    return float(np.sqrt(np.mean((np.asarray(a, np.float64) - np.asarray(b, np.float64)) ** 2)))


def _cpu_vsgl2(frame: vsgl.Frame, light: vsgl.SpotLight) -> dict[str, dict[str, np.ndarray | float]]:
    """The two VSGLs in float64 from the frame's RSM readback (positions relative to the light):
    the same per-texel lobes as vsgl_moments.wgsl, summed over every texel."""
    side = frame.rsm("position").shape[1]
    y = frame.rsm("position").astype(np.float64).reshape(-1, 3)
    n = frame.rsm("normal").astype(np.float64).reshape(-1, 3)
    # Each texel's own positional variance, added to ‖y‖² as the GPU does.
    footprint = spot_texel_footprint_variance(y, n, frame, side)
    alpha = np.maximum(frame.rsm("roughness").astype(np.float64).reshape(-1) ** 2, GGX_ALPHA_MIN)
    fd = frame.rsm("flux_diffuse").astype(np.float64).reshape(-1, 3)
    fs = frame.rsm("flux_specular").astype(np.float64).reshape(-1, 3)
    wd, ws = fd.sum(-1), fs.sum(-1)
    lit = (wd + ws) > 0
    y, n, alpha, fd, fs, wd, ws, footprint = y[lit], n[lit], alpha[lit], fd[lit], fs[lit], wd[lit], ws[lit], footprint[lit]
    to_light = -y / np.linalg.norm(y, axis=-1, keepdims=True)
    c = np.sum(to_light * n, -1)
    refl = 2 * c[:, None] * n - to_light
    refl /= np.linalg.norm(refl, axis=-1, keepdims=True)
    lam_h = 2.0 / np.maximum(alpha**2, 2.0 / SG_SHARPNESS_MAX)
    lam_s = lam_h / np.maximum(4 * np.abs(c), lam_h / SG_SHARPNESS_MAX)
    mean_d = (LAMBERT_LOBE_SG_SHARPNESS / (LAMBERT_LOBE_SG_SHARPNESS + 1)) * n
    mean_s = (lam_s / (lam_s + 1))[:, None] * refl
    out = {}
    for name, flux, w, mean in (("diffuse", fd, wd, mean_d), ("specular", fs, ws, mean_s)):
        total = w.sum()
        xi = (w[:, None] * mean).sum(0) / total
        r = np.linalg.norm(xi)
        mu = (w[:, None] * y).sum(0) / total
        second = float((w * (np.sum(y * y, -1) + footprint)).sum() / total)
        out[name] = dict(
            power=flux.sum(0),
            axis=xi / r,
            sharpness=min(r / (1 - r), TOKSVIG_SHARPNESS_MAX),
            mean=mu,
            variance=max(second - float(mu @ mu), VSGL_VARIANCE_MIN_FRACTION * second),
            second=second,
        )
    return out


def _reduction_or_skip(renderer, reduction: str) -> None:
    if reduction == "subgroup" and not renderer.adapter["subgroups"]:
        pytest.skip(f"adapter {renderer.adapter['name']!r} has no subgroup operations; the shared-memory variant is tested")


@pytest.mark.parametrize("reduction", ["subgroup", "shared_memory"])
@pytest.mark.parametrize("rsm_size", [128, 100, 37])
def test_two_vsgls_equal_a_float64_sum_of_the_same_rsm(renderer, rsm_size, reduction):
    """128 is a multiple of the 8×8 tile, 100 and 37 are not (partial tiles count as zero).
    Bounds: each GPU total is an f32 pairwise tree (depth ~log2 of the texel count, ≤ 15
    roundings of 2^-24 relative each, ~1e-6) over per-texel f32 lobe functions (a few ULP);
    measured worst relative errors are ~1e-7 … 1e-6, the bounds leave a factor ≥ 10.
    λ = r/(1 − r) amplifies a relative error ε of r by 1/(1 − r) (λ + 1 ≤ 5 here), and σ² =
    E‖y‖² − ‖μ‖² is known only to f32 rounding of E‖y‖² (cancellation), so it is bounded
    absolutely by that. Both implementations (subgroup sums, shared-memory tree) must meet them;
    subgroupAdd's order is the driver's, a butterfly or a serial sum over ≤ 64 lanes at worst
    (6 more roundings than a tree: still far inside the bounds)."""
    _reduction_or_skip(renderer, reduction)
    scene = vsgl.scenes.glossy_cornell()
    cam, light = scene.cameras[0], scene.lights[0]
    f = renderer.render(scene, method="vsgl2", rsm_size=rsm_size, capture_rsm=True, vsgl2_reduction=reduction)
    assert f.settings["vsgl2_reduction"] == reduction
    assert f.passes[-3:] == ["vsgl2_reduce", "vsgl_shading", "aov_pack"]  # the method, then the readback packing
    assert {"denoise", "pdf_mips", "moment_mips", "vsgl_sampling"} <= set(f.skipped)
    assert set(f.timings_ms) >= {"vsgl2_reduce", "vsgl_shading"}
    v = f.vsgls()
    assert len(v) == 2
    cpu = _cpu_vsgl2(f, light)
    offset = np.array(light.position) - np.array(cam.eye)
    worst = {}
    for i, lobe in enumerate(("diffuse", "specular")):
        other = "specular" if lobe == "diffuse" else "diffuse"
        want = cpu[lobe]
        assert np.all(v[f"{other}_power"][i] == 0)
        power = v[f"{lobe}_power"][i].astype(np.float64)
        assert np.all(want["power"] > 0)
        np.testing.assert_allclose(power, want["power"], rtol=1e-5)
        axis = v[f"{lobe}_axis"][i].astype(np.float64)
        assert axis @ want["axis"] > 1 - 1e-6
        np.testing.assert_allclose(v[f"{lobe}_sharpness"][i], want["sharpness"], rtol=1e-5 * (1 + want["sharpness"]))
        scale = math.sqrt(want["second"])  # RMS distance of the lobe's texels from the light
        np.testing.assert_allclose(v["mean"][i], want["mean"] + offset, atol=1e-5 * scale)
        np.testing.assert_allclose(v["variance"][i], want["variance"], atol=1e-5 * want["second"], rtol=1e-4)
        worst[lobe] = dict(
            power=float(np.max(np.abs(power / want["power"] - 1))),
            axis=float(1 - axis @ want["axis"]),
            sharpness=float(abs(v[f"{lobe}_sharpness"][i] / want["sharpness"] - 1)),
            mean=float(np.max(np.abs(v["mean"][i] - want["mean"] - offset)) / scale),
            variance=float(abs(v["variance"][i] - want["variance"]) / want["second"]),
        )
    print(f"rsm {rsm_size} {reduction}: relative deviations from float64 {worst}")
    assert np.isfinite(f.image).all()


def _grey_corner_scene(tmp_path):
    """Dielectric quads of one grey (R_d = 0.5, R_s = 0.04 in every channel), so R_s/R_d is the
    same at every texel; roughness differs per quad (it shapes the lobes, not the weights)."""
    grey = (0.5, 0.5, 0.5)
    quads = [
        dict(name="floor", corners=[(-2, 0, 1), (2, 0, 1), (2, 0, -2), (-2, 0, -2)], base_color=grey, roughness=0.3),
        dict(name="back", corners=[(-2, 0, -2), (2, 0, -2), (2, 2.5, -2), (-2, 2.5, -2)], base_color=grey, roughness=0.6),
        dict(name="left", corners=[(-2, 0, 1), (-2, 0, -2), (-2, 2.5, -2), (-2, 2.5, 1)], base_color=grey, roughness=0.15),
    ]
    scene = vsgl.Scene.load(write_quads(tmp_path, quads))
    scene.add_light(vsgl.SpotLight(position=(0.5, 1.8, 0.5), direction=(-0.4, -1, -0.7), intensity=10.0, inner_cone_deg=40, outer_cone_deg=55))
    cam = vsgl.Camera.look_at(eye=(0.5, 1.2, 2.2), target=(-0.5, 0.5, -2), fov_y_deg=60)
    return scene, cam


def test_vsgl2_equals_vsgl_with_one_whole_image_kernel_where_they_coincide(tmp_path, renderer):
    """One `vsgl` kernel covering the whole RSM (N = 1, the integral kernel's bisection run to
    the top level) sums the same texels as `vsgl2`. The two still differ in one definition:
    `vsgl` weights both lobes' positions by Φ·(R_d + R_s), `vsgl2` each by its own Φ·R_d or
    Φ·R_s. They coincide when R_s/R_d is the same at every texel (grey dielectrics only: the
    built-in Cornell boxes have coloured walls, so their ratio varies). Then record 0 of vsgl2
    is vsgl's diffuse lobe, record 1 its specular lobe, both at vsgl's position, and the
    indirect images agree up to f32 rounding of the two summation orders (with vsgl's
    near_field="sg": vsgl2 has no near-field texels; both shade by the papers' lighting="asg")."""
    scene, cam = _grey_corner_scene(tmp_path)
    rsm = 64
    one = renderer.render(scene, camera=cam, method="vsgl", num_lights=1, rsm_size=rsm, kernel="integral", K=1.0, bisection_steps=32,
                          interleave=1, lighting="asg", coherence=0.0, near_field="sg", capture_rsm=True)
    two = renderer.render(scene, camera=cam, method="vsgl2", rsm_size=rsm, lighting="asg")
    a, b = one.vsgls(), two.vsgls()
    # The kernel reached the top level: it is the whole image.
    assert a["level"][0] == pytest.approx(math.log2(rsm), abs=1e-5), a["level"]
    # The precondition: one R_s/R_d ratio everywhere (0.04/0.5 summed over rgb).
    wd = one.rsm("flux_diffuse").astype(np.float64).sum(-1)
    ws = one.rsm("flux_specular").astype(np.float64).sum(-1)
    lit = wd > 0
    np.testing.assert_allclose(ws[lit] / wd[lit], 0.08, rtol=1e-5)
    np.testing.assert_allclose(b["diffuse_power"][0], a["diffuse_power"][0], rtol=2e-5)
    np.testing.assert_allclose(b["specular_power"][1], a["specular_power"][0], rtol=2e-5)
    assert b["diffuse_axis"][0] @ a["diffuse_axis"][0] > 1 - 1e-6
    assert b["specular_axis"][1] @ a["specular_axis"][0] > 1 - 1e-6
    np.testing.assert_allclose(b["diffuse_sharpness"][0], a["diffuse_sharpness"][0], rtol=2e-5)
    np.testing.assert_allclose(b["specular_sharpness"][1], a["specular_sharpness"][0], rtol=2e-5)
    extent = float(np.linalg.norm(np.subtract(*scene.bounds)))
    for i in (0, 1):
        np.testing.assert_allclose(b["mean"][i], a["mean"][0], atol=1e-5 * extent)
        np.testing.assert_allclose(b["variance"][i], a["variance"][0], rtol=1e-4)
    x, y = one.aov("indirect").astype(np.float64), two.aov("indirect").astype(np.float64)
    assert y.mean() > 0
    rel = _rmse(x, y) / math.sqrt(np.mean(x**2))
    print(f"vsgl(N=1) vs vsgl2 indirect: relative RMSE {rel:.2e}")
    assert rel < 1e-5


def test_vsgl2_error_on_cave_flashlight_is_reported_in_the_bench(renderer):
    scene = vsgl.scenes.load("cave_flashlight")
    ref = renderer.render(scene, method="reference", rsm_size=64).aov("indirect").astype(np.float64)
    f = renderer.render(scene, method="vsgl2", rsm_size=64)
    err = _rmse(f.aov("indirect"), ref)
    rel = err / math.sqrt(np.mean(ref**2))
    print(f"cave_flashlight vsgl2 (64² RSM) vs reference (64² RSM): RMSE {err:.4g}, relative {rel:.3f}")
    assert math.isfinite(err) and err > 0
    report = bench.run(scenes=["cave_flashlight"], methods=["vpl", "vsgl", "vsgl2"], lights=[64], size=(48, 32), rsm_sizes=[64],
                            seeds=(0,), frames=1, warmup=0, reference_rsm=64, progress=False)
    rows = {r.method: r for r in report.rows}
    assert set(rows) == {"vpl", "vsgl", "vsgl2"} and len(report.rows) == 3
    r2 = rows["vsgl2"]
    assert r2.num_lights is None and r2.rsm_size == 64 and r2.seeds == 1
    assert math.isfinite(r2.rmse_indirect) and r2.rmse_indirect > 0
    assert "vsgl2_reduce" in r2.passes_ms and "vsgl_shading" in r2.passes_ms
    print(bench.table(report))


def test_rsm_size_for_vsgl2(renderer):
    scene = vsgl.scenes.cornell_box()
    for bad in (20, 4097):
        with pytest.raises(ValueError, match="rsm_size"):
            renderer.render(scene, method="vsgl2", rsm_size=bad)
    # Non-powers of two are only for vsgl2.
    with pytest.raises(ValueError, match="rsm_size"):
        renderer.render(scene, method="vsgl", rsm_size=100)
    f = renderer.render(scene, method="vsgl2", rsm_size=33)
    assert f.settings["rsm_size"] == 33 and f.settings["diffuse"] == "papers"
    assert np.isfinite(f.image).all() and f.aov("indirect").mean() > 0


@pytest.mark.parametrize("diffuse", ["papers", "accurate", "sg_product"])
def test_vsgl2_diffuse_forms(renderer, diffuse):
    """The poster shades the diffuse part by the SG product integral; the other forms are options.
    On the Cornell box (lavapipe, 64² RSM) the mean indirect diffuse relative to "papers" is
    measured at 1.004 ("accurate") and 0.979 ("sg_product"); the bound only asks for the same
    order of magnitude."""
    scene = vsgl.scenes.cornell_box()
    base = renderer.render(scene, method="vsgl2", rsm_size=64)
    f = renderer.render(scene, method="vsgl2", rsm_size=64, diffuse=diffuse)
    assert f.settings["diffuse"] == diffuse
    d = f.aov("indirect_diffuse").astype(np.float64)
    assert np.isfinite(d).all() and d.mean() > 0
    ratio = d.mean() / base.aov("indirect_diffuse").astype(np.float64).mean()
    print(f"diffuse={diffuse}: mean indirect diffuse / papers = {ratio:.3f}")
    assert 0.5 < ratio < 2.0
    # The specular part does not depend on the diffuse form.
    np.testing.assert_array_equal(f.aov("indirect_specular"), base.aov("indirect_specular"))
    with pytest.raises(ValueError, match="diffuse"):
        renderer.render(scene, method="vsgl2", rsm_size=64, diffuse="nope")


def test_reduction_setting_is_checked_and_defaults_to_subgroups_where_available(renderer):
    scene = vsgl.scenes.cornell_box()
    f = renderer.render(scene, method="vsgl2", rsm_size=32)
    want = "subgroup" if renderer.adapter["subgroups"] else "shared_memory"
    assert f.settings["vsgl2_reduction"] == want
    with pytest.raises(ValueError, match="vsgl2_reduction"):
        renderer.render(scene, method="vsgl2", vsgl2_reduction="warp")
    if not renderer.adapter["subgroups"]:
        with pytest.raises(ValueError, match="vsgl2_reduction.*SUBGROUP"):
            renderer.render(scene, method="vsgl2", vsgl2_reduction="subgroup")


def test_the_default_specular_reaches_the_references_on_a_rough_box():
    # cornell_box's walls are rough dielectrics (R_s 0.04): the papers' SG–ASG product, a
    # small-angle warp of the NDF, delivered 0.13 of the every-texel reference's specular there
    # with vsgl2's one specular VSGL (0.07–0.28 on the real-scene corpus), lighting="blend"
    # 0.70 at 128² with the same diffuse (docs/methods/vsgl2.md, "Two VSGLs"). Unshadowed, against
    # the reference of the same RSM, which is what the two VSGLs estimate.
    r = vsgl.Renderer(width=48, height=48)
    scene = vsgl.scenes.cornell_box()
    aovs = ["indirect_specular", "indirect_diffuse"]
    ref = r.render(scene, method="reference", rsm_size=64, aovs=aovs)
    default = r.render(scene, method="vsgl2", rsm_size=64, aovs=aovs)
    papers = r.render(scene, method="vsgl2", rsm_size=64, lighting="asg", aovs=aovs)

    def ratio(f, aov):
        return float(f.aov(aov).astype(np.float64).mean() / ref.aov(aov).astype(np.float64).mean())

    print(f"vsgl2 specular over the reference's: default {ratio(default, 'indirect_specular'):.3f}, asg {ratio(papers, 'indirect_specular'):.3f}")
    assert default.settings["lighting"] == "blend"
    assert 0.5 < ratio(default, "indirect_specular") < 1.2
    assert ratio(papers, "indirect_specular") < 0.35
    # Its diffuse is the papers' form either way.
    assert np.array_equal(default.aov("indirect_diffuse"), papers.aov("indirect_diffuse"))
