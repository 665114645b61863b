"""Image error metrics used by the benchmark (float64 NumPy, on linear radiance).

- ``rmse(x, ref)``: sqrt(mean((x − ref)²)) over every pixel and channel.
- ``relmse(x, ref, eps)``: mean((x − ref)² / (ref² + eps)), the relative MSE of the denoising
  literature (Rousselle et al. 2011); ``eps`` (default 1e-2 × mean(ref²)) keeps dark pixels from
  dominating.
- ``flip(x, ref)``: NVIDIA FLIP (LDR, on tone-mapped sRGB) when the ``flip-evaluator`` package is
  installed, else ``None``.
"""

from __future__ import annotations

import numpy as np


def rmse(x: np.ndarray, ref: np.ndarray) -> float:
    x = np.asarray(x, np.float64)
    ref = np.asarray(ref, np.float64)
    if x.shape != ref.shape:
        raise ValueError(f"x: shape {x.shape} differs from ref's {ref.shape}")
    return float(np.sqrt(np.mean((x - ref) ** 2)))


def relmse(x: np.ndarray, ref: np.ndarray, eps: float | None = None) -> float:
    x = np.asarray(x, np.float64)
    ref = np.asarray(ref, np.float64)
    if x.shape != ref.shape:
        raise ValueError(f"x: shape {x.shape} differs from ref's {ref.shape}")
    if eps is None:
        eps = 1e-2 * float(np.mean(ref**2)) or 1e-12
    return float(np.mean((x - ref) ** 2 / (ref**2 + eps)))


def _srgb(x: np.ndarray) -> np.ndarray:
    x = np.clip(np.asarray(x, np.float64), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)


def flip(x: np.ndarray, ref: np.ndarray) -> float | None:
    """Mean LDR-FLIP of the tone-mapped images, or None without ``flip-evaluator``."""
    try:
        import flip_evaluator  # type: ignore[import-not-found]
    except ImportError:
        return None
    _, mean_error, _ = flip_evaluator.evaluate(_srgb(ref).astype(np.float32), _srgb(x).astype(np.float32), "LDR")
    return float(mean_error)
