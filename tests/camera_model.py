"""The renderer's pinhole camera in NumPy, for tests that recompute pixels independently."""

from __future__ import annotations

import math

import numpy as np

import vsgl


def camera_rays(cam: vsgl.Camera, w: int, h: int) -> np.ndarray:
    """Unit view rays through the pixel centres of a w×h image, shape (h, w, 3)."""
    fwd, up = np.array(cam.forward), np.array(cam.up)
    right = np.cross(fwd, up)
    t = math.tan(math.radians(cam.fov_y_deg) / 2)
    x = (np.arange(w) + 0.5) / w * 2 - 1
    y = 1 - (np.arange(h) + 0.5) / h * 2
    rays = fwd + x[None, :, None] * right * t * w / h + y[:, None, None] * up * t
    return rays / np.linalg.norm(rays, axis=-1, keepdims=True)
