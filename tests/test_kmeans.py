"""k-means clustering VSGLs (`kernel="kmeans2d"` / `"kmeans3d"` of vsgl, the 2016 paper's
baseline): the GPU assignment (grid search, radix sort, two-level sums) against a float64
brute-force nearest-centre assignment on the captured RSM, exact cluster sums, Lloyd
iterations that only lower the within-cluster variance, and the options' errors."""

from __future__ import annotations

import numpy as np
import pytest

import vsgl
from scene_builders import columns_before_wall
from vsgl.metrics import block_rmse

EYE = (0.0, 1.0, 3.9)
CAMERA = vsgl.Camera.look_at(eye=EYE, target=(0.0, 1.0, 0.0), fov_y_deg=40)


def _render(r, scene, kernel, n=64, rsm=32, **kw):
    return r.render(scene, camera=CAMERA, method="vsgl", kernel=kernel, num_lights=n, rsm_size=rsm, capture_rsm=True,
                    interleave=1, denoise=False, aovs=["indirect_diffuse", "indirect_specular"], **kw)


def _points_and_centres(frame, scene, kernel):
    """Each texel's point and each cluster's centre in the clustering space, float64; 3D in
    frame coordinates (the records keep the centre relative to the camera, the RSM relative to
    the light)."""
    size = frame.rsm("weight").shape[0]
    v = frame.vsgls()
    if kernel == "kmeans2d":
        ys, xs = np.mgrid[0:size, 0:size]
        points = np.stack([xs.ravel() + 0.5, ys.ravel() + 0.5], -1).astype(np.float64)
        return points, v["center"].astype(np.float64)
    offset = np.asarray(scene.lights[0].position, np.float64) - np.asarray(EYE, np.float64)
    points = frame.rsm("position").reshape(-1, 3).astype(np.float64) + offset
    return points, v["shadow_target"].astype(np.float64)


def _brute_force(points, centres, lit):
    """Nearest and second-nearest centre of every lit texel (ties to the lower id, as argmin)
    and the gap between their squared distances."""
    d2 = ((points[lit, None, :] - centres[None, :, :]) ** 2).sum(-1)
    order = np.argsort(d2, axis=1, kind="stable")
    best = order[:, 0]
    gap = np.take_along_axis(d2, order[:, 1:2], 1)[:, 0] - np.take_along_axis(d2, order[:, :1], 1)[:, 0]
    return best, order[:, 1], gap


@pytest.mark.parametrize("kernel", ["kmeans2d", "kmeans3d"])
@pytest.mark.parametrize(("iterations", "n"), [(0, 64), (2, 64), (0, 512)])
def test_assignment_and_sums_equal_a_brute_force_assignment(renderer, kernel, iterations, n):
    # n = 512 centres on 1024 texels, drawn where the light is brightest: the grid has many
    # empty cells and dim texels find their centre rings of cells away.
    scene = vsgl.scenes.glossy_cornell()
    f = _render(renderer, scene, kernel, n=n, kmeans_iterations=iterations)
    v = f.vsgls()
    assert len(v) == n
    w = f.rsm("weight")[..., 0].astype(np.float64).ravel()
    lit = w > 0
    points, centres = _points_and_centres(f, scene, kernel)
    best, second, gap = _brute_force(points, centres, lit)
    # Texels whose two nearest centres are within f32 rounding of each other may go either way
    # (on a box's walls the texels form a regular grid, and a texel halfway between two centre
    # texels is a tie: measured gaps up to 3.4e-8 of the squared extent, the next 3.6e-5);
    # centres drawn at the same texel are exact ties, which both sides give the lower id.
    scale = np.ptp(points[lit], axis=0).max() ** 2
    same_centre = (centres[best] == centres[second]).all(-1)
    ambiguous = (gap <= 1e-6 * scale) & ~same_centre
    assert ambiguous.mean() < 0.1, ambiguous.mean()
    count = np.bincount(best, minlength=n)
    slack = np.bincount(best[ambiguous], minlength=n) + np.bincount(second[ambiguous], minlength=n)
    texels = v["texels"].astype(np.int64)
    assert texels.sum() == lit.sum()
    assert (count > 0).sum() >= 32, "the centres cut the RSM into many clusters"
    assert np.all(np.abs(texels - count) <= slack), np.flatnonzero(np.abs(texels - count) > slack)
    # Exact sums: each cluster's diffuse power is its texels' reflected diffuse flux.
    flux = f.rsm("flux_diffuse").reshape(-1, 3).astype(np.float64)[lit]
    for c in range(3):
        want = np.bincount(best, weights=flux[:, c], minlength=n)
        # An ambiguous texel's flux may sit in either of its two nearest clusters.
        moved = np.bincount(best[ambiguous], weights=flux[ambiguous, c], minlength=n) + np.bincount(second[ambiguous], weights=flux[ambiguous, c], minlength=n)
        assert np.all(np.abs(v["diffuse_power"][:, c] - want) <= moved + 2e-4 * want + 1e-7 * want.sum()), c
        np.testing.assert_allclose(v["diffuse_power"][:, c].sum(), flux[:, c].sum(), rtol=1e-4)
    # The mass is the cluster's share of the RSM's weight.
    np.testing.assert_allclose(v["mass"].sum(), 1.0, rtol=1e-4)


@pytest.mark.parametrize("kernel", ["kmeans2d", "kmeans3d"])
def test_lloyd_iterations_only_lower_the_within_cluster_variance(renderer, kernel):
    scene = vsgl.scenes.glossy_cornell()
    variances = []
    for iterations in range(4):
        f = _render(renderer, scene, kernel, kmeans_iterations=iterations)
        w = f.rsm("weight")[..., 0].astype(np.float64).ravel()
        lit = w > 0
        points, centres = _points_and_centres(f, scene, kernel)
        best, _, _ = _brute_force(points, centres, lit)
        p, wl = points[lit], w[lit]
        sums = np.stack([np.bincount(best, weights=wl * p[:, d], minlength=len(centres)) for d in range(p.shape[1])], -1)
        weight = np.bincount(best, weights=wl, minlength=len(centres))
        means = sums / np.maximum(weight, 1e-300)[:, None]
        variances.append(float((wl * ((p - means[best]) ** 2).sum(-1)).sum() / wl.sum()))
    print(kernel, variances)
    assert all(b <= a * (1 + 1e-5) for a, b in zip(variances, variances[1:])), variances
    assert variances[-1] < 0.95 * variances[0], variances


def test_kmeans_is_deterministic_and_timed_under_the_papers_names(renderer):
    scene = vsgl.scenes.glossy_cornell()
    a, b = (_render(renderer, scene, "kmeans3d", kmeans_iterations=1) for _ in range(2))
    assert a.vsgls().tobytes() == b.vsgls().tobytes()
    assert {"kmeans_centres", "kmeans_grid", "kmeans_assign", "kmeans_sort", "kmeans_sum"} <= set(a.timings_ms)
    assert "vsgl_gen" not in a.timings_ms
    # 1 + 2 rounds × (grid + 3·3 cell-sort + ranges + assign + 3·1 texel-sort + 2 sums)
    assert a.settings["kmeans_dispatches"] == 1 + 2 * (1 + 9 + 1 + 1 + 3 + 2)


@pytest.mark.parametrize("kernel", ["kmeans2d", "kmeans3d"])
def test_kmeans_vsgls_light_the_box_as_the_reference_does(renderer, kernel):
    # Exact cluster totals: the mean indirect light is near the every-texel reference's.
    scene = vsgl.scenes.cornell_box()
    kw = dict(camera=CAMERA, rsm_size=64, aovs=["indirect_diffuse"])
    ref = renderer.render(scene, method="reference", **kw).aov("indirect_diffuse").mean()
    got = renderer.render(scene, method="vsgl", kernel=kernel, num_lights=256, interleave=1, denoise=False, **kw).aov("indirect_diffuse")
    assert np.isfinite(got).all()
    ratio = float(got.mean() / ref)
    print(kernel, ratio)
    assert 0.85 < ratio < 1.15, ratio


@pytest.mark.parametrize("kernel", ["kmeans2d", "kmeans3d"])
def test_with_bidirectional_importance_both_sides_are_kmeans_clusters(renderer, kernel):
    # importance="brsm": the view's VSGLs are k-means clusters of the camera's G-buffer (as
    # the paper ran its baseline) and the RSM's centres are drawn from the re-weighted
    # density; the RSM's clusters still sum every lit texel once, so their total power is the
    # RSM's whatever density drew the centres.
    f = _render(renderer, vsgl.scenes.glossy_cornell(), kernel, importance="brsm", importance_lights=64)
    assert "brsm_view_vsgl_gen" not in f.timings_ms and "vsgl_gen" not in f.timings_ms
    assert {"brsm_importance", "kmeans_assign", "kmeans_sum"} <= set(f.timings_ms)
    flux = f.rsm("flux_diffuse").reshape(-1, 3).astype(np.float64)
    np.testing.assert_allclose(f.vsgls()["diffuse_power"].astype(np.float64).sum(0), flux.sum(0), rtol=1e-4)
    # The re-weighted density drew the centres: they differ from those of the RSM's own weights.
    plain = _render(renderer, vsgl.scenes.glossy_cornell(), kernel)
    assert not np.array_equal(f.vsgls()["center"], plain.vsgls()["center"])
    assert np.isfinite(f.aov("indirect_diffuse")).all() and f.aov("indirect_diffuse").mean() > 0


@pytest.mark.parametrize(
    ("options", "named"),
    [
        (dict(kernel="kmeans2d", K=2.0), "K"),
        (dict(kernel="kmeans3d", coherence=0.5), "coherence"),
        (dict(kernel="kmeans3d", kernel_filter="trilinear"), "kernel_filter"),
        (dict(kernel="integral", kmeans_iterations=2), "kmeans_iterations"),
        (dict(kernel="kmeans2d", sampling="metropolis"), "sampling"),
        (dict(kernel="kmeans2d", kmeans_iterations=65), "kmeans_iterations"),
    ],
)
def test_options_that_do_not_apply_to_kmeans_are_errors_naming_them(renderer, options, named):
    with pytest.raises(vsgl.ArgumentError, match=named):
        renderer.render(vsgl.scenes.cornell_box(), method="vsgl", rsm_size=32, num_lights=16, aovs=[], **options)


def test_3d_kmeans_keeps_the_columns_indirect_shadows_sharper_than_2d(make_renderer, tmp_path):
    # The 2016 paper's Fig. 7: with one shadow test per VSGL (the papers' visibility: a ray to
    # the cluster's centre, shadow_target="centre"), a 2D cluster that holds both a column's lit
    # face and the wall a metre behind it is shadowed as one, and the floor's striped bounce
    # light blurs; 3D clusters keep column and wall apart. Measured (3 seeds, N = 128, 64², RSM
    # 64², against the reference shadowed by ray tracing): block error 2D 0.163, 3D 0.119; mean
    # 0.872 and 0.970 of the reference's (ISM visibility: 0.195 and 0.141).
    r = make_renderer(64, 64)
    scene, cam = columns_before_wall(tmp_path)
    ref = r.render(scene, camera=cam, method="reference", rsm_size=64, visibility="raytrace", aovs=["indirect"]).aov("indirect")
    errors = {}
    for kernel in ("kmeans2d", "kmeans3d"):
        errors[kernel] = np.mean([
            block_rmse(r.render(scene, camera=cam, method="vsgl", kernel=kernel, num_lights=128, rsm_size=64, interleave=1, denoise=False,
                                visibility="raytrace", shadow_target="centre", seed=seed, aovs=["indirect"]).aov("indirect"), ref, block=4)
            for seed in range(3)
        ])
    print(errors)
    assert errors["kmeans3d"] < 0.85 * errors["kmeans2d"], errors
