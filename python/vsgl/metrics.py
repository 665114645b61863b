"""Image error metrics used by the benchmark (float64 NumPy, on linear radiance).

How each number is made and what it can and cannot tell: docs/error.md.

Per image, against a reference ``ref`` of the same shape:

- ``rmse(x, ref)``: sqrt(mean((x − ref)²)) over every pixel and channel.
- ``rel_rmse(x, ref)``: ‖x − ref‖ / ‖ref‖ (a black image scores 1).
- ``relmse(x, ref, eps)``: mean((x − ref)² / (ref² + eps)), the usual relative MSE of the
  denoising literature (Rousselle et al. 2011), with ``eps`` = 1e-2 × mean(ref²) by default
  (1e-2 of the mean of the *squared* reference, so it has the units of ref²) keeping dark pixels
  from dominating. The "symmetric" variant 0.5·(x − y)²/(y² + ε) of some papers is exactly half of
  this one for the same ε; we keep the factor 1.
- ``block_rmse(x, ref, block)``: the relative RMS error of block-averaged (low-passed) images
  (``block_means(a, block)``: the block averages themselves).
- ``ssim(x, ref)``: SSIM of the tone-mapped (clamp + sRGB) luma, Gaussian window.
- ``flip(x, ref)``: NVIDIA FLIP (LDR, on tone-mapped sRGB) when the ``flip-evaluator`` package is
  installed (``pip install vsgl[metrics]``), else ``None``.

Over a sequence of frames (temporal coherence; docs/animation.md, "Temporal coherence"):

- ``flicker(frames, reference_frames)``: RMS over pixels, channels and consecutive frame pairs
  of (Δmethod − Δreference), Δ the difference between consecutive frames, relative to the RMS
  of the reference frames. 0 when a method changes from frame to frame exactly as the truth
  does (even with a constant bias); it grows with frame-to-frame noise and with changes the
  truth does not make.
- ``temporal_std(frames)``: the per-pixel standard deviation over frames of a static view,
  averaged over pixels and channels, relative to the mean image's mean: sampling noise alone.

Over seeds of a stochastic method, against a reference with a per-pixel variance estimate:

- ``seed_errors(images, ref, ref_var)`` → :class:`SeedErrors`: ``bias`` and ``noise`` apart and
  ``relmse_debiased`` (the MSE less the reference's own variance, relative to mean(ref²)) with a
  90% bootstrap interval; ``compare_debiased(a, b)`` the ratio of two of them with its interval.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def _pair(x, ref, name: str = "x") -> tuple[np.ndarray, np.ndarray]:
    x = np.asarray(x, np.float64)
    ref = np.asarray(ref, np.float64)
    if x.shape != ref.shape:
        raise ValueError(f"{name}: shape {x.shape} differs from ref's {ref.shape}")
    return x, ref


def _finite(a: np.ndarray, name: str) -> None:
    if not np.isfinite(a).all():
        raise ValueError(f"{name}: holds {int((~np.isfinite(a)).sum())} NaN or infinite values")


def rmse(x: np.ndarray, ref: np.ndarray) -> float:
    x, ref = _pair(x, ref)
    return float(np.sqrt(np.mean((x - ref) ** 2)))


def rel_rmse(x: np.ndarray, ref: np.ndarray) -> float:
    """‖x − ref‖ / ‖ref‖ over every pixel and channel: 0 is exact, 1 is what a black image scores."""
    x, ref = _pair(x, ref)
    norm = float(np.sqrt(np.sum(ref**2)))
    if norm == 0.0:
        raise ValueError("ref: is zero everywhere, so an error relative to it is undefined")
    return float(np.sqrt(np.sum((x - ref) ** 2))) / norm


def relmse(x: np.ndarray, ref: np.ndarray, eps: float | None = None) -> float:
    """mean((x − ref)² / (ref² + eps)); ``eps`` defaults to 1e-2 × mean(ref²) (see the module)."""
    x, ref = _pair(x, ref)
    if eps is None:
        eps = 1e-2 * float(np.mean(ref**2)) or 1e-12
    return float(np.mean((x - ref) ** 2 / (ref**2 + eps)))


def block_means(a: np.ndarray, block: int) -> np.ndarray:
    """Means over block×block tiles (edge tiles average the pixels they hold); what block_rmse
    compares, and what a reference's own block error is computed from (its stderr² averaged
    over a block, over the block's pixel count, is the variance of its block mean)."""
    rows = np.arange(0, a.shape[0], block)
    cols = np.arange(0, a.shape[1], block)
    sums = np.add.reduceat(np.add.reduceat(a, rows, axis=0), cols, axis=1)
    heights = np.minimum(block, a.shape[0] - rows)
    widths = np.minimum(block, a.shape[1] - cols)
    counts = np.outer(heights, widths).reshape(len(rows), len(cols), *([1] * (a.ndim - 2)))
    return sums / counts


def _image(a: np.ndarray, name: str) -> None:
    if a.ndim not in (2, 3) or a.shape[0] < 1 or a.shape[1] < 1:
        raise ValueError(f"{name}: expected an image (H, W) or (H, W, C), got shape {a.shape}")


def block_rmse(x: np.ndarray, ref: np.ndarray, block: int = 8) -> float:
    """The relative RMS error of block-averaged images: both are averaged over block×block
    tiles (a low-pass filter), then ‖x̄ − r̄‖ / ‖r̄‖. Zero-mean noise finer than a block averages
    away, so this sees bias (wrong brightness, missing or smeared light) and not noise."""
    x, ref = _pair(x, ref)
    _image(x, "x")
    if not (isinstance(block, (int, np.integer)) and block >= 1):
        raise ValueError(f"block: must be an integer >= 1, got {block!r}")
    return rel_rmse(block_means(x, int(block)), block_means(ref, int(block)))


def srgb_encode(x: np.ndarray) -> np.ndarray:
    """Linear values clamped to [0, 1] and sRGB-encoded (as PNGs and the ``ldr`` AOV are)."""
    x = np.clip(np.asarray(x, np.float64), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)


def _display_luma(a: np.ndarray) -> np.ndarray:
    """Tone-mapped luma: clamp + sRGB per channel (as PNGs are written), then Rec. 709 weights."""
    t = srgb_encode(a)
    if t.ndim == 2:
        return t
    if t.shape[2] == 1:
        return t[..., 0]
    if t.shape[2] < 3:
        raise ValueError(f"x: expected 1 or ≥ 3 channels, got {t.shape[2]}")
    return 0.2126 * t[..., 0] + 0.7152 * t[..., 1] + 0.0722 * t[..., 2]


def _gaussian_blur(a: np.ndarray, sigma: float) -> np.ndarray:
    """Separable Gaussian filter (±3.5σ taps, an 11-tap window at σ = 1.5 as Wang et al. use),
    mirror-padded so every pixel keeps a full window even in tiny images."""
    radius = int(np.ceil(3.5 * sigma))
    taps = np.exp(-0.5 * (np.arange(-radius, radius + 1) / sigma) ** 2)
    taps /= taps.sum()
    padded = np.pad(a, radius, mode="symmetric")
    rows = sum(w * padded[i : i + a.shape[0], :] for i, w in enumerate(taps))
    return sum(w * rows[:, i : i + a.shape[1]] for i, w in enumerate(taps))


def ssim(x: np.ndarray, ref: np.ndarray, sigma: float = 1.5) -> float:
    """Mean SSIM (Wang et al. 2004) of the tone-mapped luma of ``x`` against ``ref``: a Gaussian
    window of standard deviation ``sigma`` pixels, C1 = (0.01)², C2 = (0.03)² for the [0, 1]
    range. 1 for identical images, lower for any difference in local mean, contrast or structure.
    Values above 1 clip to white first: SSIM judges what a display shows, not HDR radiance."""
    x, ref = _pair(x, ref)
    _image(x, "x")
    _finite(x, "x")
    _finite(ref, "ref")
    if not (sigma > 0 and np.isfinite(sigma)):
        raise ValueError(f"sigma: must be finite and > 0, got {sigma}")
    a, b = _display_luma(x), _display_luma(ref)
    c1, c2 = 0.01**2, 0.03**2
    mu_a, mu_b = _gaussian_blur(a, sigma), _gaussian_blur(b, sigma)
    # Local (co)variances as blurred products less the products of blurred means: fine in
    # float64 on values in [0, 1]; tiny negative variances from rounding are clamped.
    var_a = np.maximum(_gaussian_blur(a * a, sigma) - mu_a**2, 0.0)
    var_b = np.maximum(_gaussian_blur(b * b, sigma) - mu_b**2, 0.0)
    cov = _gaussian_blur(a * b, sigma) - mu_a * mu_b
    index = ((2 * mu_a * mu_b + c1) * (2 * cov + c2)) / ((mu_a**2 + mu_b**2 + c1) * (var_a + var_b + c2))
    return float(np.mean(index))


def flip(x: np.ndarray, ref: np.ndarray) -> float | None:
    """Mean LDR-FLIP of the tone-mapped images, or None without ``flip-evaluator``."""
    try:
        import flip_evaluator  # type: ignore[import-not-found]
    except ImportError:
        return None
    _, mean_error, _ = flip_evaluator.evaluate(srgb_encode(ref).astype(np.float32), srgb_encode(x).astype(np.float32), "LDR")
    return float(mean_error)


# --- Bias, noise and the debiased error over seeds ------------------------------------------

#: Two-sided coverage of the intervals below.
CONFIDENCE = 0.9
#: Bootstrap replicates: enough for stable 5% / 95% percentiles (their spread is ~1% of the width).
RESAMPLES = 2000


@dataclass
class SeedErrors:
    """A stochastic method's error over K seeds against a reference with per-pixel variance.

    All three headline numbers are relative to mean(ref²) (not per pixel, unlike ``relmse``), so
    ``relmse_debiased ≈ bias² + noise²`` and sqrt(relmse_debiased) compares with ``rel_rmse``.
    """

    seeds: int
    #: Relative RMS error of the mean image over seeds, less what noise and the reference's
    #: variance add to it: sqrt(max(0, mean((x̄ − ref)²) − mean(s²)/K − mean(Var ref)) / mean(ref²)).
    bias: float
    #: Relative RMS of the per-pixel standard deviation over seeds: sqrt(mean(s²) / mean(ref²))
    #: (s² with K − 1 in the denominator); None with one seed (no spread to measure).
    noise: float | None
    #: Plain MSE over seeds relative to mean(ref²): what the error column measured before.
    relmse: float
    #: (MSE − mean(Var ref)) / mean(ref²): the method's own expected squared error.
    relmse_debiased: float
    #: CONFIDENCE interval of ``relmse_debiased`` (percentile bootstrap over seeds and pixel tiles).
    interval: tuple[float, float]
    #: mean(Var ref) / mean(ref²): the floor that the plain ``relmse`` cannot go below.
    reference_floor: float
    # Per-tile sums kept for the bootstrap (and for compare_debiased): squared error per seed
    # (K, T), reference variance (T,), ref² (T,), values per tile (T,).
    _error_sums: np.ndarray
    _variance_sums: np.ndarray
    _ref_sq_sums: np.ndarray
    _counts: np.ndarray

    def bootstrap(self, seed_counts: np.ndarray, tile_counts: np.ndarray) -> np.ndarray:
        """The debiased relative MSE under resampling weights: seed_counts (B, K), tile_counts (B, T)."""
        per_tile = seed_counts @ self._error_sums / self.seeds  # (B, T): mean over the drawn seeds
        error = np.einsum("bt,bt->b", per_tile, tile_counts)
        variance = tile_counts @ self._variance_sums
        ref_sq = tile_counts @ self._ref_sq_sums
        return (error - variance) / np.maximum(ref_sq, 1e-300)


def _tiles(shape: tuple[int, int], tile: int, min_tiles: int = 64) -> tuple[np.ndarray, int]:
    """Tile index per pixel: tile×tile squares, shrunk (to 1) until there are ≥ min_tiles."""
    h, w = shape
    while tile > 1 and -(-h // tile) * -(-w // tile) < min_tiles:
        tile //= 2
    rows, cols = np.arange(h) // tile, np.arange(w) // tile
    return rows[:, None] * (-(-w // tile)) + cols[None, :], -(-h // tile) * -(-w // tile)


def _tile_sums(values: np.ndarray, tile_of_pixel: np.ndarray, tiles: int) -> np.ndarray:
    """Sums over each tile of per-pixel values (..., H, W) → (..., T)."""
    lead = values.shape[:-2]
    flat = values.reshape(-1, tile_of_pixel.size)
    sums = np.stack([np.bincount(tile_of_pixel.ravel(), weights=row, minlength=tiles) for row in flat])
    return sums.reshape(*lead, tiles)


def seed_errors(images, ref, ref_var=None, *, tile: int = 8, resamples: int = RESAMPLES, rng=0) -> SeedErrors:
    """Bias, noise and the debiased error of K renders of one method (one per seed).

    ``images``: (K, H, W[, C]), the same configuration with K different seeds. ``ref``: (H, W[, C]).
    ``ref_var``: the variance of each reference value, same shape as ``ref`` (for a path-traced
    reference its stderr²; None or zeros for a reference taken as deterministic).

    E[mean over seeds of (x_k − ref)²] = bias² + σ² + Var(ref) per pixel, so subtracting
    mean(ref_var) leaves the method's own error: ``relmse_debiased`` = (MSE − mean(ref_var)) /
    mean(ref²). It is an unbiased estimate, so it can come out below 0 when the method is far
    better than the reference can tell.

    The interval is a percentile bootstrap that resamples both sources of chance at once: the
    K seeds with replacement (the method's noise, which VPL sets and denoisers correlate across
    the whole image, so pixels are not independent draws of it) and tiles of tile×tile pixels
    with replacement (the reference's per-pixel noise and the spread of the error over the image;
    tiles keep neighbouring pixels together, as a denoiser correlates them). Resampling pixels as
    well as seeds counts the image's own spread of error as chance, which widens the interval:
    it errs on the safe side. With few seeds (K < 5) the seed part is itself rough.
    """
    x = np.asarray(images, np.float64)
    ref = np.asarray(ref, np.float64)
    if ref.ndim not in (2, 3) or ref.shape[0] < 1 or ref.shape[1] < 1:
        raise ValueError(f"ref: expected an image (H, W) or (H, W, C), got shape {ref.shape}")
    if x.ndim != ref.ndim + 1 or x.shape[1:] != ref.shape or x.shape[0] < 1:
        raise ValueError(f"images: expected shape (K, {', '.join(map(str, ref.shape))}) with K ≥ 1 seeds, got {x.shape}")
    var = np.zeros_like(ref) if ref_var is None else np.asarray(ref_var, np.float64)
    if var.shape != ref.shape:
        raise ValueError(f"ref_var: shape {var.shape} differs from ref's {ref.shape}")
    _finite(x, "images")
    _finite(ref, "ref")
    _finite(var, "ref_var")
    if (var < 0).any():
        raise ValueError("ref_var: variances must be >= 0")
    if not (isinstance(tile, (int, np.integer)) and tile >= 1):
        raise ValueError(f"tile: must be an integer >= 1, got {tile!r}")
    if not (isinstance(resamples, (int, np.integer)) and resamples >= 10):
        raise ValueError(f"resamples: must be an integer >= 10, got {resamples!r}")
    ref_sq_mean = float(np.mean(ref**2))
    if ref_sq_mean == 0.0:
        raise ValueError("ref: is zero everywhere, so an error relative to it is undefined")
    k = x.shape[0]
    # Sum channels into per-pixel values so a tile or pixel is resampled with all its channels.
    def per_pixel(a: np.ndarray) -> np.ndarray:
        return a.sum(axis=-1) if ref.ndim == 3 else a

    tile_of_pixel, tiles = _tiles(ref.shape[:2], int(tile))
    error_sums = _tile_sums(per_pixel((x - ref) ** 2), tile_of_pixel, tiles)
    variance_sums = _tile_sums(per_pixel(var), tile_of_pixel, tiles)
    ref_sq_sums = _tile_sums(per_pixel(ref**2), tile_of_pixel, tiles)
    counts = _tile_sums(per_pixel(np.ones_like(ref)), tile_of_pixel, tiles)

    mse = float(np.mean((x - ref) ** 2))
    ref_variance = float(np.mean(var))
    mean_image = x.mean(axis=0)
    spread = float(np.mean(x.var(axis=0, ddof=1))) if k > 1 else None
    bias_sq = float(np.mean((mean_image - ref) ** 2)) - (spread or 0.0) / k - ref_variance
    out = SeedErrors(
        seeds=k,
        bias=float(np.sqrt(max(bias_sq, 0.0) / ref_sq_mean)),
        noise=None if spread is None else float(np.sqrt(spread / ref_sq_mean)),
        relmse=mse / ref_sq_mean,
        relmse_debiased=(mse - ref_variance) / ref_sq_mean,
        interval=(0.0, 0.0),
        reference_floor=ref_variance / ref_sq_mean,
        _error_sums=error_sums,
        _variance_sums=variance_sums,
        _ref_sq_sums=ref_sq_sums,
        _counts=counts,
    )
    seed_counts, tile_counts = _resampling_weights(k, tiles, int(resamples), rng)
    out.interval = _percentiles(out.bootstrap(seed_counts, tile_counts))
    return out


def _resampling_weights(seeds: int, tiles: int, resamples: int, rng) -> tuple[np.ndarray, np.ndarray]:
    """How often each seed and each tile is drawn in each bootstrap replicate (multinomial counts)."""
    gen = np.random.default_rng(rng)
    seed_counts = gen.multinomial(seeds, np.full(seeds, 1.0 / seeds), size=resamples).astype(np.float64)
    tile_counts = gen.multinomial(tiles, np.full(tiles, 1.0 / tiles), size=resamples).astype(np.float64)
    return seed_counts, tile_counts


def _percentiles(values: np.ndarray) -> tuple[float, float]:
    tail = 100 * (1 - CONFIDENCE) / 2
    lo, hi = np.percentile(values, [tail, 100 - tail])
    return float(lo), float(hi)


def compare_debiased(best: SeedErrors, other: SeedErrors, *, resamples: int = RESAMPLES, rng=0) -> dict:
    """How much larger ``other``'s debiased error is than ``best``'s, with CONFIDENCE intervals.

    The two are resampled on the same pixel tiles (they share the reference and its noise, which
    cancels in part from the difference) and each on its own seeds. Both must be measured against
    the same reference at the same size. Returns ``difference`` (other − best, in units of
    mean(ref²)) and ``ratio`` (other / best), each with its ``*_interval``; an interval that
    excludes 0 (difference) or 1 (ratio) says the order is beyond chance. The ratio and its bounds
    are None where undefined: when ``best``'s debiased error is ≤ 0 in the estimate or in more than
    the interval's tail of replicates (``best`` is better than the reference can resolve).
    """
    if best._counts.shape != other._counts.shape or not np.array_equal(best._counts, other._counts):
        raise ValueError("other: measured on another image size or tiling than best")
    if not np.allclose(best._ref_sq_sums, other._ref_sq_sums, rtol=1e-12, atol=0.0):
        raise ValueError("other: measured against another reference than best")
    gen = np.random.default_rng(rng)
    tiles = best._counts.shape[0]
    tile_counts = gen.multinomial(tiles, np.full(tiles, 1.0 / tiles), size=resamples).astype(np.float64)

    def seeds_of(e: SeedErrors) -> np.ndarray:
        return gen.multinomial(e.seeds, np.full(e.seeds, 1.0 / e.seeds), size=resamples).astype(np.float64)

    a = best.bootstrap(seeds_of(best), tile_counts)
    b = other.bootstrap(seeds_of(other), tile_counts)
    # A replicate where best's error is ≤ 0 has an unbounded ratio: it counts as +inf, so the
    # upper bound becomes None once such replicates exceed the upper tail.
    ratios = np.full_like(a, np.inf)
    np.divide(b, a, out=ratios, where=a > 0)
    # No interpolation between order statistics: it would subtract inf from inf.
    lo, hi = (float(v) for v in np.quantile(ratios, [(1 - CONFIDENCE) / 2, (1 + CONFIDENCE) / 2], method="inverted_cdf"))
    finite = lambda v: v if np.isfinite(v) else None  # noqa: E731
    defined = best.relmse_debiased > 0
    return {
        "difference": other.relmse_debiased - best.relmse_debiased,
        "difference_interval": _percentiles(b - a),
        "ratio": other.relmse_debiased / best.relmse_debiased if defined else None,
        "ratio_interval": (finite(lo), finite(hi)) if defined else (None, None),
    }


def _sequence(frames, name: str) -> np.ndarray:
    """``frames`` as a float64 array (F, H, W[, C]) of at least two finite images."""
    try:
        a = np.asarray(frames, np.float64)
    except (TypeError, ValueError) as e:
        raise ValueError(f"{name}: expected a sequence of images of one shape ({e})") from None
    if a.ndim not in (3, 4) or a.shape[1] < 1 or a.shape[2] < 1:
        raise ValueError(f"{name}: expected frames of shape (F, H, W) or (F, H, W, C), got {a.shape}")
    if a.shape[0] < 2:
        raise ValueError(f"{name}: needs at least 2 frames, got {a.shape[0]}")
    _finite(a, name)
    return a


def flicker(frames, reference_frames) -> float:
    """Temporal error of a sequence against the true sequence:

        flicker = sqrt(mean_{k, pixels} ((x_{k+1} − x_k) − (r_{k+1} − r_k))²) / sqrt(mean r²)

    over the F − 1 consecutive pairs of ``frames`` x and ``reference_frames`` r, both of shape
    (F, H, W[, C]). A method whose error is the same in every frame scores 0; noise that is
    drawn anew each frame scores about √2 × its relative RMS. Raises ValueError naming the
    argument for shapes that differ, fewer than 2 frames, NaN/Inf or an all-zero reference.
    """
    x = _sequence(frames, "frames")
    r = _sequence(reference_frames, "reference_frames")
    if x.shape != r.shape:
        raise ValueError(f"reference_frames: shape {r.shape} differs from frames' {x.shape}")
    scale = float(np.sqrt(np.mean(r**2)))
    if scale == 0.0:
        raise ValueError("reference_frames: are zero everywhere, so a flicker relative to them is undefined")
    change_error = np.diff(x, axis=0) - np.diff(r, axis=0)
    return float(np.sqrt(np.mean(change_error**2))) / scale


def temporal_std(frames) -> float:
    """Per-pixel standard deviation over ``frames`` (F, H, W[, C]) of a static view with a
    static light, averaged over pixels and channels, relative to the mean of the per-pixel mean
    image: the frame-to-frame sampling noise alone (0 for a deterministic method). The standard
    deviation is the sample one (divisor F − 1), an unbiased variance for any F ≥ 2. Raises
    ValueError naming ``frames`` for a bad shape, fewer than 2 frames, NaN/Inf or a black mean.
    """
    x = _sequence(frames, "frames")
    mean_level = float(np.mean(x))
    if mean_level <= 0.0:
        raise ValueError("frames: their mean is not positive, so a noise relative to it is undefined")
    return float(np.mean(np.std(x, axis=0, ddof=1))) / mean_level
