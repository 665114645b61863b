"""Float64 models of what an RSM texel stands for, shared by the tests that re-generate VSGLs
from a captured RSM (test_vsgl.py, test_vsgl2.py)."""

from __future__ import annotations

import numpy as np

import vsgl


def spot_rsm_view(frame: vsgl.Frame, light_index: int = 0) -> tuple[np.ndarray, float]:
    """The axis and tan(half field of view) of a spot light's RSM in ``frame``
    (``frame.settings["rsm_view"]``: the cone's, or narrower where ``rsm_fit="scene"`` fitted it
    to the scene)."""
    view = frame.settings["rsm_view"][light_index]
    return np.array(view["forward"], dtype=np.float64), float(view["tan"])


def spot_texel_footprint_variance(y: np.ndarray, normal: np.ndarray, frame: vsgl.Frame, side: int) -> np.ndarray:
    """Each texel's own positional variance for the first light's square RSM
    of ``side`` texels in ``frame`` (a spot light): a cross-section a² = Δω·d²,
    Δω = t²(2/N)²cos³α (t = tan of the RSM's half field of view, α the angle to its axis),
    stretched by 1/cos θ on the surface: (a²/12)(1 + 1/max(cos θ, 0.1)²). ``y``: texel
    positions relative to the light, (..., 3)."""
    axis, t = spot_rsm_view(frame)
    d2 = np.maximum(np.sum(y * y, -1), 1e-300)
    cos_axis = np.abs(np.sum(y * axis, -1)) / np.sqrt(d2)
    cross_section = t * t * (2.0 / side) ** 2 * cos_axis**3 * d2
    cos_surface = np.abs(np.sum(-y * normal, -1)) / np.sqrt(d2)
    return cross_section * (1 + 1 / np.maximum(cos_surface, 0.1) ** 2) / 12
