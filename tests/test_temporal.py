"""Temporal coherence: the flicker and temporal-noise metrics, and the papers' claim
that VSGLs flicker less than VPLs under a moving light, and less with a larger K.

Images are 32×32 with a 64² RSM and 8 frames (lavapipe runs the shaders on the CPU). The
moving-light sequences draw a new seed every frame (`{"seed": k}` in frame k of
`render_sequence`), as a real-time renderer would: with a fixed seed the frame-to-frame change of the random numbers is left out, and what
is measured is only how the sampling reacts to the moving light (docs/animation.md, "Temporal
coherence", has both). The methods run in their real-time configuration (interleave 8 and the
denoiser for vpl and vsgl), and flicker is taken on the `indirect` AOV, where they differ.
"""

from __future__ import annotations

import numpy as np
import pytest

import vsgl
from vsgl.metrics import flicker, temporal_std

SIZE = 32
RSM = 64
FRAMES = 8
NUM_LIGHTS = 32


def test_flicker_is_zero_for_identical_and_constant_bias_sequences():
    rng = np.random.default_rng(1)
    truth = rng.random((5, 6, 7, 3))
    assert flicker(truth, truth) == 0.0
    # A constant error changes nothing from frame to frame.
    assert flicker(truth + 0.25, truth) < 1e-12
    # Fresh noise each frame of relative RMS σ scores about √2 σ.
    noisy = truth + 0.01 * rng.standard_normal(truth.shape)
    expected = np.sqrt(2) * 0.01 / np.sqrt(np.mean(truth**2))
    assert flicker(noisy, truth) == pytest.approx(expected, rel=0.1)


def test_temporal_std_is_the_relative_per_pixel_noise():
    rng = np.random.default_rng(2)
    static = np.full((4, 5, 5, 3), 2.0)
    assert temporal_std(static) == 0.0
    noisy = 2.0 + 0.2 * rng.standard_normal((400, 5, 5, 3))
    assert temporal_std(noisy) == pytest.approx(0.1, rel=0.05)  # σ = 0.2 on a mean of 2


@pytest.mark.parametrize("call, message", [
    (lambda: flicker(np.zeros((3, 4, 4)), np.ones((2, 4, 4))), "reference_frames: shape"),
    (lambda: flicker(np.ones((1, 4, 4)), np.ones((1, 4, 4))), "frames: needs at least 2 frames"),
    (lambda: flicker(np.ones((3, 4)), np.ones((3, 4))), "frames: expected frames of shape"),
    (lambda: flicker(np.ones((3, 4, 4)), np.zeros((3, 4, 4))), "reference_frames: are zero"),
    (lambda: flicker(np.full((3, 4, 4), np.nan), np.ones((3, 4, 4))), "frames: holds 48 NaN"),
    (lambda: flicker(np.ones((3, 4, 4)), [np.ones((4, 4)), np.ones((4, 5))]), "reference_frames: expected a sequence"),
    (lambda: temporal_std(np.ones((1, 4, 4))), "frames: needs at least 2"),
    (lambda: temporal_std(np.zeros((2, 4, 4))), "frames: their mean is not positive"),
])
def test_bad_sequences_raise_value_error_naming_the_argument(call, message):
    with pytest.raises(ValueError, match=message):
        call()


@pytest.fixture(scope="module")
def small(make_renderer):
    return make_renderer(SIZE, SIZE)


@pytest.mark.parametrize("method, options", [("reference", {}), ("vsgl2", {})])
def test_a_static_scene_does_not_flicker_for_deterministic_methods(small, method, options):
    scene = vsgl.scenes.cornell_box()
    frames = np.stack([f.image for f in small.render_sequence(
        scene, [{}] * 4, method=method, aovs=["image"], rsm_size=RSM, **options)])
    assert flicker(frames, frames) == 0.0
    assert temporal_std(frames) == 0.0


def moving_spot(base: vsgl.SpotLight, k: int) -> vsgl.SpotLight:
    """The Cornell box's ceiling spot, slid 0.4 m along x over the sequence, pointing down."""
    x = -0.2 + 0.4 * k / (FRAMES - 1)
    return vsgl.SpotLight(position=(x, 1.95, 0.0), direction=(0, -1, 0), intensity=base.intensity,
                          inner_cone_deg=base.inner_cone_deg, outer_cone_deg=base.outer_cone_deg)


@pytest.fixture(scope="module")
def moving_light(small):
    scene = vsgl.scenes.cornell_box()
    base = scene.lights[0]
    lights = [[moving_spot(base, k)] for k in range(FRAMES)]
    truth = np.stack([f.aov("indirect") for f in small.render_sequence(
        scene, [{"lights": ls} for ls in lights], method="reference", aovs=["indirect"], rsm_size=RSM)])

    def sequence(method: str, **options) -> np.ndarray:
        changes = [{"lights": ls, "seed": k} for k, ls in enumerate(lights)]
        return np.stack([f.aov("indirect") for f in small.render_sequence(
            scene, changes, method=method, aovs=["indirect"], rsm_size=RSM, num_lights=NUM_LIGHTS, **options)])

    return truth, sequence, scene, lights


def test_a_seed_per_frame_in_a_sequence_equals_render_calls(small, moving_light):
    _, sequence, scene, lights = moving_light
    frames = sequence("vsgl")[:3]
    for k in range(3):
        scene.lights = lights[k]
        one = small.render(scene, method="vsgl", aovs=["indirect"], rsm_size=RSM, num_lights=NUM_LIGHTS, seed=k)
        np.testing.assert_array_equal(frames[k], one.aov("indirect"))
    assert not np.array_equal(frames[0], frames[1])
    with pytest.raises(vsgl.ArgumentError, match=r'frames\[0\]\["seed"\]'):
        list(small.render_sequence(scene, [{"seed": 1}], method="reference", rsm_size=RSM))
    with pytest.raises(vsgl.ArgumentError, match=r'frames\[0\]\["seed"\]'):
        list(small.render_sequence(scene, [{"seed": -1}], method="vsgl", rsm_size=RSM))


def test_vsgl_flickers_less_than_vpl_at_equal_n_and_less_with_larger_k(moving_light):
    truth, sequence, _, _ = moving_light
    vpl = flicker(sequence("vpl", interleave=8), truth)
    vsgl_k1 = flicker(sequence("vsgl", K=1.0), truth)
    vsgl_k4 = flicker(sequence("vsgl", K=4.0), truth)
    # Measured on lavapipe: vpl 0.93, vsgl K=1 0.13, K=4 0.093.
    assert vsgl_k1 < vpl, (vsgl_k1, vpl)
    assert vsgl_k4 < vsgl_k1, (vsgl_k4, vsgl_k1)


@pytest.mark.parametrize("method, options", [("vpl", {"interleave": 8}), ("vsgl", {"K": 1.0})])
def test_metropolis_sampling_flickers_less_than_warping_under_a_moving_light(small, moving_light, method, options):
    """sampling="metropolis" keeps one Markov chain per virtual light from frame to frame (one
    Metropolis–Hastings step each), so under the moving light with a new seed every frame most
    virtual lights move a little instead of being drawn afresh (docs/animation.md,
    "Metropolis–Hastings sampling")."""
    truth, sequence, _, _ = moving_light
    warp = flicker(sequence(method, sampling="stratified", **options), truth)
    small.reset_chains()
    chains = flicker(sequence(method, sampling="metropolis", **options), truth)
    # Measured on lavapipe: vpl 0.93 → 0.29, vsgl K=1 0.13 → 0.087.
    assert chains < warp, (method, chains, warp)
