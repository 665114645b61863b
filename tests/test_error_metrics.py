"""The error metrics of docs/error.md on synthetic images whose true errors are known."""

from __future__ import annotations

import numpy as np
import pytest

from optional_packages import optional_import
from vsgl import metrics


def _truth(rng, shape=(48, 64, 3)):
    # Smooth-ish positive radiance with some structure (a ramp plus texture).
    ramp = np.linspace(0.3, 1.2, shape[1])[None, :, None]
    return ramp + 0.3 * rng.random(shape)


def test_debiased_mse_recovers_the_true_mse_against_a_noisy_reference():
    """A method with known bias b and noise σ, against a reference with known per-pixel variance
    v: the plain MSE sits ≈ v above the truth b² + σ², the debiased one recovers it within its
    interval, and bias and noise come apart."""
    rng = np.random.default_rng(7)
    truth = _truth(rng)
    b, sigma, ref_sigma, seeds = 0.05, 0.1, 0.15, 4
    images = truth + b + rng.normal(0.0, sigma, (seeds, *truth.shape))
    ref = truth + rng.normal(0.0, ref_sigma, truth.shape)
    e = metrics.seed_errors(images, ref, np.full(truth.shape, ref_sigma**2))
    scale = np.mean(ref**2)
    true_relmse = (b**2 + sigma**2) / scale
    lo, hi = e.interval
    assert lo <= e.relmse_debiased <= hi
    assert lo <= true_relmse <= hi
    # The plain MSE is off by the reference's variance, far outside the interval.
    assert e.relmse > hi
    assert e.relmse - true_relmse == pytest.approx(ref_sigma**2 / scale, rel=0.1)
    assert e.reference_floor == pytest.approx(ref_sigma**2 / scale)
    assert e.bias == pytest.approx(b / np.sqrt(scale), rel=0.15)
    assert e.noise == pytest.approx(sigma / np.sqrt(scale), rel=0.05)
    # The decomposition is consistent: debiased ≈ bias² + noise².
    assert e.relmse_debiased == pytest.approx(e.bias**2 + e.noise**2, rel=1e-9)


def test_bias_and_noise_separate_a_biased_from_a_noisy_method():
    rng = np.random.default_rng(8)
    truth = _truth(rng)
    biased = metrics.seed_errors(truth[None] * 1.1 + rng.normal(0, 1e-3, (3, *truth.shape)), truth)
    noisy = metrics.seed_errors(truth + rng.normal(0, 0.1, (3, *truth.shape)), truth)
    assert biased.bias > 10 * biased.noise
    assert noisy.noise > 10 * noisy.bias
    single = metrics.seed_errors(truth[None] + 0.1, truth)
    assert single.noise is None and single.seeds == 1


def test_compare_debiased_orders_two_methods_beyond_chance():
    rng = np.random.default_rng(9)
    truth = _truth(rng)
    ref = truth + rng.normal(0, 0.1, truth.shape)
    var = np.full(truth.shape, 0.01)
    good = metrics.seed_errors(truth + rng.normal(0, 0.05, (3, *truth.shape)), ref, var)
    bad = metrics.seed_errors(truth + rng.normal(0, 0.1, (3, *truth.shape)), ref, var)
    c = metrics.compare_debiased(good, bad)
    assert c["ratio"] == pytest.approx(4.0, rel=0.15)
    assert 1.0 < c["ratio_interval"][0] <= c["ratio"] <= c["ratio_interval"][1]
    assert c["difference_interval"][0] > 0
    other_ref = metrics.seed_errors(truth[None], truth)
    with pytest.raises(ValueError, match="other"):
        metrics.compare_debiased(good, other_ref)


def test_ssim_is_one_for_identical_images_and_falls_with_noise():
    rng = np.random.default_rng(10)
    # Values inside the display range, so clamping does not hide the noise.
    x = 0.1 + 0.5 * _truth(rng) / 1.5
    assert metrics.ssim(x, x) == 1.0
    a = metrics.ssim(x + rng.normal(0, 0.01, x.shape), x)
    b = metrics.ssim(x + rng.normal(0, 0.05, x.shape), x)
    assert 1.0 > a > b > 0.0
    # Structure counts, not only local means: the same pattern with its contrast inverted (equal
    # means and variances, opposite covariance) scores ≈ −1. Built in display (sRGB) values.
    pattern = np.where(rng.random((32, 32)) < 0.5, 1.0, -1.0)
    to_linear = lambda d: ((d + 0.055) / 1.055) ** 2.4  # noqa: E731
    assert metrics.ssim(to_linear(0.5 - 0.2 * pattern), to_linear(0.5 + 0.2 * pattern)) < -0.9
    # Radiance above 1 clips to white, as a display shows it.
    assert metrics.ssim(x + 5.0, x + 7.0) == pytest.approx(1.0)
    # Grey images work, and a tiny image still has a full (mirrored) window.
    assert metrics.ssim(x[..., 0], x[..., 0]) == 1.0
    assert metrics.ssim(x[:3, :2], x[:3, :2]) == 1.0


def test_block_rmse_ignores_zero_mean_fine_noise_that_rmse_sees():
    rng = np.random.default_rng(11)
    x = _truth(rng, (64, 64, 3))
    # Zero mean within every 8×8 block: a ±d checkerboard.
    d = 0.2
    checker = d * np.where((np.arange(64)[:, None] + np.arange(64)[None, :]) % 2 == 0, 1.0, -1.0)[..., None]
    assert metrics.block_rmse(x + checker, x, block=8) < 1e-12
    assert metrics.rel_rmse(x + checker, x) == pytest.approx(d / np.sqrt(np.mean(x**2)))
    # A bias does not average away.
    assert metrics.block_rmse(x * 1.1, x) == pytest.approx(0.1)
    # Edge blocks average the pixels they hold (a 13×10 image in 8×8 blocks).
    assert metrics.block_rmse(x[:13, :10] * 1.1, x[:13, :10]) == pytest.approx(0.1)


def test_rel_rmse_matches_its_definition():
    ref = np.array([3.0, 4.0])
    assert metrics.rel_rmse(np.zeros(2), ref) == 1.0
    assert metrics.rel_rmse(np.array([3.0, 5.0]), ref) == pytest.approx(1 / 5)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: metrics.ssim(np.zeros((4, 4, 3)), np.zeros((4, 5, 3))), "x"),
        (lambda: metrics.ssim(np.full((4, 4), np.nan), np.zeros((4, 4))), "x"),
        (lambda: metrics.block_rmse(np.ones((4, 4)), np.ones((4, 4)), block=0), "block"),
        (lambda: metrics.rel_rmse(np.ones(3), np.zeros(3)), "ref"),
        (lambda: metrics.seed_errors(np.ones((2, 4, 4)), np.ones((4, 5))), "images"),
        (lambda: metrics.seed_errors(np.ones((2, 4, 4)), np.ones((4, 4)), np.ones((4, 5))), "ref_var"),
        (lambda: metrics.seed_errors(np.ones((2, 4, 4)), np.ones((4, 4)), -np.ones((4, 4))), "ref_var"),
        (lambda: metrics.seed_errors(np.ones((2, 4, 4)), np.zeros((4, 4))), "ref"),
        (lambda: metrics.seed_errors(np.ones((2, 4, 4)), np.ones(4)), "ref"),
    ],
)
def test_bad_inputs_raise_value_error_naming_the_argument(call, name):
    with pytest.raises(ValueError, match=f"^{name}:"):
        call()


def test_flip_where_installed():
    optional_import("flip_evaluator", reason="flip-evaluator is not installed (pip install vsgl[metrics]): metrics.flip returns None")
    rng = np.random.default_rng(12)
    x = 0.1 + 0.5 * _truth(rng) / 1.5
    assert metrics.flip(x, x) == pytest.approx(0.0, abs=1e-6)
    assert metrics.flip(x + rng.normal(0, 0.05, x.shape), x) > 0.01
