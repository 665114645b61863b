"""sampling="metropolis": Metropolis–Hastings chains kept across the frames of a
Renderer (docs/methods/metropolis.md, "Metropolis–Hastings sampling"). Each chain's state must be
distributed like a warped sample (∝ the RSM weight) at equilibrium, so the estimators keep
their expectations; chains restart from the warp when N, the RSM size, the lights' views or the
scene change; a seed sequence replays bit for bit from fresh chains.

The chains start from the warp (an exact draw from the target) and every step keeps the target
invariant, so every frame of a static scene is unbiased, not only after a burn-in. Frames of one
sequence are correlated (that is the point), so statistical errors below come from independent
chains or independent sequences, never from frames of one sequence treated as independent.
"""

from __future__ import annotations

import numpy as np
import pytest

import vsgl
from scene_builders import lit_floor_corner

SIZE = 32
RSM = 64


@pytest.fixture(scope="module")
def small(make_renderer):
    return make_renderer(SIZE, SIZE)


def _weights(renderer, scene) -> np.ndarray:
    f = renderer.render(scene, method="vsgl", rsm_size=RSM, num_lights=4, capture_rsm=True, aovs=[])
    return np.asarray(f.rsm("weight"), np.float64).reshape(RSM, RSM)



def _mean_over_fresh_sequences(r, scene, opts, replicates: int, frames: int) -> tuple[float, float]:
    """Mean indirect level over `replicates` independent metropolis sequences (fresh chains,
    disjoint seeds), whose means are i.i.d., and its standard error."""
    means = []
    for rep in range(replicates):
        r.reset_chains()
        seq = [r.render(scene, sampling="metropolis", seed=1000 * rep + k, **opts).aov("indirect").astype(np.float64).mean() for k in range(frames)]
        means.append(np.mean(seq))
    return float(np.mean(means)), float(np.std(means, ddof=1) / np.sqrt(replicates))

def test_chain_states_have_the_warp_density(small):
    """E_p[p(x)] = ∫p² over the unit square = M·Σw²/W² (closed form from the captured texel
    weights) against the chains' mean p over later frames. Each chain's time average is one
    sample; chains are independent (their lattice start is negatively correlated, which only
    shrinks the spread), so the standard error is the spread of those averages / √N."""
    scene = vsgl.scenes.cornell_box()
    w = _weights(small, scene)
    m = w.size
    expected = m * np.sum(w**2) / np.sum(w) ** 2
    small.reset_chains()
    # Long enough for a wrong acceptance ratio to show: the chains start exact, so a broken
    # step has to drift them away first (inverted ratio: 3.9 → 3.1 by frame 40).
    n, frames, burn = 1024, 40, 24
    per_frame = []
    for k in range(frames):
        v = small.render(scene, method="vsgl", rsm_size=RSM, num_lights=n, sampling="metropolis", seed=k, aovs=[]).vsgls()
        per_frame.append(np.asarray(v["pdf"], np.float64))
    p = np.stack(per_frame[burn:])  # (frames − burn, N)
    chain_means = p.mean(axis=0)
    got = chain_means.mean()
    stderr = chain_means.std(ddof=1) / np.sqrt(n)
    # Measured on lavapipe: got within ~1 stderr of expected (see docs).
    assert abs(got - expected) < 4 * stderr, (got, expected, stderr)
    # The warp itself, as a check of the closed form (independent seeds, stratified).
    warp = np.array([np.asarray(small.render(scene, method="vsgl", rsm_size=RSM, num_lights=n, seed=s, aovs=[]).vsgls()["pdf"], np.float64).mean() for s in range(6)])
    assert abs(warp.mean() - expected) < 4 * warp.std(ddof=1) / np.sqrt(len(warp)) + 1e-6 * expected, (warp, expected)


def test_vpl_mean_over_independent_sequences_matches_the_reference(small):
    """VPLs are unbiased for the every-texel reference on the same RSM (no denoiser, every VPL
    at every pixel), so the mean indirect level of metropolis frames must match it. Replicates:
    independent sequences (fresh chains, disjoint seeds), whose means are i.i.d."""
    scene = vsgl.scenes.cornell_box()
    ref = small.render(scene, method="reference", rsm_size=RSM, aovs=["indirect"]).aov("indirect").astype(np.float64).mean()
    opts = dict(method="vpl", rsm_size=RSM, num_lights=64, interleave=1, denoise=False, aovs=["indirect"])
    replicates = 6
    mean, stderr = _mean_over_fresh_sequences(small, scene, opts, replicates=replicates, frames=8)
    assert abs(mean - ref) < 4 * stderr, (mean, ref, stderr)
    # The warp's frames, for the same check at equal cost (independent seeds).
    warp = np.array([small.render(scene, seed=s, **opts).aov("indirect").astype(np.float64).mean() for s in range(replicates)])
    assert abs(warp.mean() - ref) < 4 * warp.std(ddof=1) / np.sqrt(replicates), (warp.mean(), ref)


def test_a_seed_sequence_replays_bit_for_bit_from_fresh_chains(small):
    scene = vsgl.scenes.cornell_box()
    opts = dict(method="vsgl", rsm_size=RSM, num_lights=32, sampling="metropolis", aovs=["indirect"])

    def run():
        small.reset_chains()
        return [f.aov("indirect") for f in small.render_sequence(scene, [{"seed": k} for k in range(4)], **opts)]

    a, b = run(), run()
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)
    # The chains are kept from frame to frame: the same seed again, without a reset, continues
    # them instead of repeating frame 0, and the frames differ (the chains moved).
    again = small.render(scene, seed=0, **opts).aov("indirect")
    assert not np.array_equal(again, a[0])
    assert not np.array_equal(a[0], a[1])


def _first_after_change(small, scene, **opts):
    return small.render(scene, method="vsgl", sampling="metropolis", seed=7, aovs=["indirect"], **opts).vsgls()


@pytest.mark.parametrize("change", [dict(num_lights=48, rsm_size=RSM), dict(num_lights=32, rsm_size=32)])
def test_chains_restart_from_the_warp_when_n_or_the_rsm_size_changes(small, change):
    """After a change of N or of the RSM size the chains start afresh from the warp of the
    frame's seed: the frame equals sampling="stratified" with that seed bit for bit (the
    chains' start is the same Fibonacci lattice), with no stale state."""
    scene = vsgl.scenes.cornell_box()
    small.reset_chains()
    for k in range(3):
        small.render(scene, method="vsgl", rsm_size=RSM, num_lights=32, sampling="metropolis", seed=k, aovs=[])
    got = _first_after_change(small, scene, **change)
    warp = small.render(scene, method="vsgl", sampling="stratified", seed=7, aovs=[], **change).vsgls()
    for field in ("center", "pdf", "diffuse_power", "mean"):
        np.testing.assert_array_equal(got[field], warp[field], err_msg=field)
    assert np.all(np.isfinite(got["diffuse_power"]))
    # And the next frame steps those chains (it is no longer the warp).
    nxt = small.render(scene, method="vsgl", sampling="metropolis", seed=8, aovs=[], **change).vsgls()
    warp8 = small.render(scene, method="vsgl", sampling="stratified", seed=8, aovs=[], **change).vsgls()
    assert not np.array_equal(nxt["center"], warp8["center"])


LIGHTS = {
    "spot": lambda: vsgl.scenes.cornell_box().lights[0],
    "point": lambda: vsgl.PointLight(position=(0.0, 1.5, 0.0), intensity=3.0),
    "directional": lambda: vsgl.DirectionalLight(direction=(0.3, -1.0, 0.2), intensity=5.0),
}


@pytest.mark.parametrize("kind", list(LIGHTS))
def test_a_static_light_keeps_its_chains_in_every_view_kind(small, kind):
    """Under a static light a world state reprojects onto itself (perspective spot, a point
    light's cube faces with their own chain ranges, an orthographic directional view), so
    between frames a chain stays, or walks at most r = RSM side/32 texels, except for the 1/32
    that jump. A broken reprojection would restart every chain from the warp each frame (an
    exact draw, so the density tests cannot see it): here, most centres would jump."""
    scene = vsgl.scenes.cornell_box()
    scene.lights = [LIGHTS[kind]()]
    small.reset_chains()
    radius = RSM / 32
    centers = []
    for k in range(4):
        f = small.render(scene, method="vsgl", rsm_size=RSM, num_lights=256, sampling="metropolis", seed=k, aovs=["indirect"])
        ind = f.aov("indirect")
        assert np.all(np.isfinite(ind)) and ind.mean() > 0
        centers.append(np.asarray(f.vsgls()["center"], np.float64))
    jumped = [np.mean(np.abs(b - a).max(axis=1) > radius * (1 + 1e-4)) for a, b in zip(centers, centers[1:])]
    # Measured on lavapipe: about 0.03 a frame (the jump probability) for every kind.
    assert max(jumped) < 0.1, jumped


def test_a_bad_sampling_value_names_the_option(small):
    scene = vsgl.scenes.cornell_box()
    with pytest.raises(vsgl.ArgumentError, match=r"sampling.*metropolis"):
        small.render(scene, method="vsgl", rsm_size=RSM, sampling="metropolis-hastings")


@pytest.mark.parametrize("space", ["world", "rsm"])
def test_chain_states_stay_put_in_the_world_when_the_light_moves(make_renderer, space):
    """chain_space="world" (the default): states are surface points, reprojected into each
    frame's RSM: when the spot slides by δ along x, a chain whose step is rejected keeps its
    point, so its kernel centre shifts by exactly the RSM image of −δ (the affine floor-to-texel
    map, fitted to the captured RSM positions of the floor). chain_space="rsm" keeps RSM
    coordinates: those centres stay where they were (shift 0) instead."""
    r = make_renderer(16, 16)
    scene = vsgl.scenes.cornell_box()
    base = scene.lights[0]

    def spot(x: float) -> vsgl.SpotLight:
        return vsgl.SpotLight(position=(x, base.position[1], base.position[2]), direction=(0, -1, 0), intensity=base.intensity,
                              inner_cone_deg=base.inner_cone_deg, outer_cone_deg=base.outer_cone_deg)

    scene.lights = [spot(0.0)]
    pos = np.asarray(r.render(scene, method="vsgl", rsm_size=RSM, num_lights=4, capture_rsm=True, aovs=[]).rsm("position"), np.float64).reshape(RSM, RSM, 3)
    floor_y = base.position[1]  # the floor is at y = 0: RSM positions are relative to the light
    rows, cols = np.nonzero(np.abs(pos[..., 1] + floor_y) < 1e-3 * floor_y)
    texel = np.stack([cols + 0.5, rows + 0.5, np.ones_like(cols)], 1).astype(np.float64)
    coef, *_ = np.linalg.lstsq(texel, np.stack([pos[rows, cols, 0], pos[rows, cols, 2]], 1), rcond=None)
    delta = 0.03
    predicted = np.linalg.solve(coef[:2].T, [-delta, 0.0])  # texels per world shift of the floor
    r.reset_chains()
    opts = dict(method="vsgl", rsm_size=RSM, num_lights=1024, sampling="metropolis", chain_space=space, aovs=[])
    before = r.render(scene, seed=1, **opts).vsgls()["center"].astype(np.float64)
    scene.lights = [spot(delta)]
    after = r.render(scene, seed=2, **opts).vsgls()["center"].astype(np.float64)
    shift = after - before
    kept_on_floor = np.sum(np.all(np.abs(shift - predicted) < 1e-2, axis=1))
    unmoved = np.sum(np.all(np.abs(shift) < 1e-2, axis=1))
    # Measured on lavapipe: world 24 of 1024 (rejected steps of chains on the floor), 0 unmoved.
    if space == "world":
        assert kept_on_floor >= 10 and unmoved == 0, (kept_on_floor, unmoved, predicted)
    else:
        assert unmoved >= 10 and kept_on_floor == 0, (kept_on_floor, unmoved, predicted)


def test_chains_restart_when_the_lights_view_set_changes(small):
    """A spot light replaced by a point light (one RSM view → six): fresh chains, so the frame
    equals the warp's with the same seed bit for bit; replacing the spot by a moved spot keeps
    them (the frame differs from the warp's)."""
    scene = vsgl.scenes.cornell_box()
    spot = scene.lights[0]
    opts = dict(method="vsgl", rsm_size=RSM, num_lights=48, aovs=[])
    small.reset_chains()
    for k in range(3):
        small.render(scene, sampling="metropolis", seed=k, **opts)
    moved = vsgl.SpotLight(position=(0.05, spot.position[1], 0.0), direction=(0, -1, 0), intensity=spot.intensity,
                           inner_cone_deg=spot.inner_cone_deg, outer_cone_deg=spot.outer_cone_deg)
    scene.lights = [moved]
    kept = small.render(scene, sampling="metropolis", seed=5, **opts).vsgls()
    assert not np.array_equal(kept["center"], small.render(scene, seed=5, **opts).vsgls()["center"])
    scene.lights = [vsgl.PointLight(position=(0.0, 1.5, 0.0), intensity=3.0)]
    got = small.render(scene, sampling="metropolis", seed=6, **opts).vsgls()
    warp = small.render(scene, seed=6, **opts).vsgls()
    for field in ("center", "pdf", "diffuse_power"):
        np.testing.assert_array_equal(got[field], warp[field], err_msg=field)


# importance="brsm" with sampling="metropolis": the chains target the re-weighted density the
# estimators divide by (docs/methods/metropolis.md, "Metropolis–Hastings sampling"; the derivation is in
# wgsl/passes/metropolis_step.wgsl). The scene is one where that density is far from the RSM's
# own: a wide spot lights an 8 × 8 floor and the camera sees a small patch of wall beside it.
BRSM = dict(importance="brsm", importance_lights=256)


def test_brsm_chain_states_have_the_brsm_density(small, tmp_path):
    """E_π[p(x)] = M·Σπ²/Π² with π the captured sampling weights (brsm_mix's level 0, the
    view's VSGLs seeded by the chains' first seed, 0) against the chains' mean p over later
    frames, as test_chain_states_have_the_warp_density does for the RSM's weights. Chains that
    targeted the RSM's weights w instead would average M·Σwπ/(WΠ), asserted to be many standard
    errors away so that this test can tell the two apart."""
    scene, cam = lit_floor_corner(tmp_path)
    f = small.render(scene, camera=cam, method="vsgl", rsm_size=RSM, num_lights=4, capture_rsm=True, seed=0, aovs=[], **BRSM)
    pi = np.asarray(f.rsm("sampling_weight"), np.float64).ravel()
    w = np.asarray(f.rsm("weight"), np.float64).ravel()
    m = pi.size
    expected = m * np.sum(pi**2) / np.sum(pi) ** 2
    wrong = m * np.sum(w * pi) / (np.sum(w) * np.sum(pi))
    small.reset_chains()
    n, frames, burn = 1024, 40, 24
    per_frame = []
    for k in range(frames):
        v = small.render(scene, camera=cam, method="vsgl", rsm_size=RSM, num_lights=n, sampling="metropolis", seed=k, aovs=[], **BRSM).vsgls()
        per_frame.append(np.asarray(v["pdf"], np.float64))
    chain_means = np.stack(per_frame[burn:]).mean(axis=0)
    got = chain_means.mean()
    stderr = chain_means.std(ddof=1) / np.sqrt(n)
    print("brsm chain density", got, "expected", expected, "stderr", stderr, "w-target", wrong)
    assert abs(wrong - expected) > 20 * stderr, (wrong, expected, stderr)
    assert abs(got - expected) < 4 * stderr, (got, expected, stderr)
    # The brsm warp itself (independent seeds, stratified), as a check of the closed form: its
    # view VSGLs are seeded by each frame's seed, so each seed has its own π; seed 0's is the one
    # captured above.
    warp = np.asarray(small.render(scene, camera=cam, method="vsgl", rsm_size=RSM, num_lights=n, seed=0, aovs=[], **BRSM).vsgls()["pdf"], np.float64)
    assert abs(warp.mean() - expected) < 4 * warp.std(ddof=1) / np.sqrt(n), (warp.mean(), expected)


def test_brsm_vpl_mean_over_independent_sequences_matches_the_reference(small, tmp_path):
    """brsm-weighted VPLs from Metropolis chains are unbiased for the every-texel reference on
    the same RSM: the mean indirect level over independent sequences (fresh chains, disjoint
    seeds, so each has its own view VSGLs) agrees with it within 4 standard errors. Both clamp
    the VPL distance at 0.1 of the scene's diagonal (tests/test_brsm.py says why). Chains that
    targeted the RSM's weights while dividing by the brsm density fail this (docs)."""
    scene, cam = lit_floor_corner(tmp_path)
    ref = small.render(scene, camera=cam, method="reference", rsm_size=RSM, vpl_clamp=0.1, aovs=["indirect"]).aov("indirect").astype(np.float64).mean()
    opts = dict(camera=cam, method="vpl", rsm_size=RSM, num_lights=64, interleave=1, denoise=False, vpl_clamp=0.1, aovs=["indirect"], **BRSM)
    mean, stderr = _mean_over_fresh_sequences(small, scene, opts, replicates=8, frames=8)
    print("brsm metropolis", mean, "reference", ref, "stderr", stderr)
    assert abs(mean - ref) < 4 * stderr, (mean, ref, stderr)


def test_brsm_chains_restart_when_the_importance_changes(small):
    """Chains at equilibrium for the RSM's weights are not for the brsm density: switching
    `importance` starts them afresh from the warp, so the first frame equals the stratified
    warp of the same seed bit for bit."""
    scene = vsgl.scenes.cornell_box()
    opts = dict(method="vpl", rsm_size=RSM, num_lights=32, aovs=["indirect"])
    small.reset_chains()
    for k in range(3):
        small.render(scene, sampling="metropolis", seed=k, **opts)
    switched = small.render(scene, sampling="metropolis", seed=5, **BRSM, **opts).aov("indirect")
    warp = small.render(scene, seed=5, **BRSM, **opts).aov("indirect")
    np.testing.assert_array_equal(switched, warp)


def test_brsm_target_stays_fixed_while_the_chains_run(small, tmp_path):
    """Each step keeps this frame's target invariant; a target that changed from frame to frame
    (view VSGLs seeded by each frame's seed) would leave the chains distributed by the previous
    frame's density. So the chains' view VSGLs keep the seed they started with: in a static
    scene a centre that stayed put (a rejected step) has the same density bit for bit in the
    next frame, whatever that frame's seed."""
    scene, cam = lit_floor_corner(tmp_path)
    opts = dict(camera=cam, method="vsgl", rsm_size=RSM, num_lights=256, sampling="metropolis", aovs=[], **BRSM)
    small.reset_chains()
    frames = [small.render(scene, seed=k, **opts).vsgls() for k in (0, 1, 2)]
    for a, b in zip(frames, frames[1:]):
        stayed = np.all(a["center"] == b["center"], axis=-1)
        assert stayed.sum() > 16, stayed.sum()
        np.testing.assert_array_equal(a["pdf"][stayed], b["pdf"][stayed])
