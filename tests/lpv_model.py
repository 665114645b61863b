"""A float64 NumPy implementation of light propagation volumes (Kaplanyan & Dachsbacher 2010)
as docs/methods/lpv.md describes them: injection of RSM texels as clamped-cosine SH lobes, the
geometry volume of blocking potentials, and propagation through five faces per neighbour.
Written from the description, not from the shaders, so tests/test_lpv.py can hold the GPU
passes to it."""

from __future__ import annotations

import numpy as np

from rsm_model import spot_rsm_view

Y00 = 0.5 / np.sqrt(np.pi)
Y1 = np.sqrt(3.0 / (4.0 * np.pi))
# Solid angles of the destination cell's far face and of one side face, seen from the centre
# of the neighbour that sends light into it: rectangles of unit side at distances 1.5 and
# (side faces) offset sideways by 0.5 and extending from 0.5 to 1.5 along d.
FAR_FACE = 4.0 * np.arcsin(0.25 / (0.25 + 1.5**2))


def _rectangle_solid_angle(x0, x1, y0, y1, h):
    """Solid angle of the axis-aligned rectangle [x0, x1] × [y0, y1] at height h, seen from
    the origin (the sum of corner terms atan(xy / (h·√(x²+y²+h²))))."""
    f = lambda x, y: np.arctan(x * y / (h * np.sqrt(x * x + y * y + h * h)))
    return f(x1, y1) - f(x0, y1) - f(x1, y0) + f(x0, y0)


# A side face of the destination (at distance 0.5 sideways), spanning 0.5 … 1.5 along d and
# −0.5 … 0.5 across.
SIDE_FACE = _rectangle_solid_angle(0.5, 1.5, -0.5, 0.5, 0.5)


def clamped_cosine(m: np.ndarray) -> np.ndarray:
    """SH coefficients (c0, cx, cy, cz) of max(0, m·ω) for unit m (..., 3)."""
    m = np.asarray(m, dtype=np.float64)
    c0 = np.full(m.shape[:-1] + (1,), np.pi * Y00)
    return np.concatenate([c0, (2.0 * np.pi / 3.0) * Y1 * m], axis=-1)


def evaluate(c: np.ndarray, w: np.ndarray) -> np.ndarray:
    """An SH function (..., 4) at unit direction w (3,)."""
    return c[..., 0] * Y00 + Y1 * (c[..., 1:] @ np.asarray(w, dtype=np.float64))


def rsm_texels(frame, light_position) -> dict:
    """The captured RSM's lit texels in world space."""
    pos = frame.rsm("position").reshape(-1, 3).astype(np.float64)
    normal = frame.rsm("normal").reshape(-1, 3).astype(np.float64)
    flux = frame.rsm("flux_diffuse").reshape(-1, 3).astype(np.float64)
    side = frame.rsm("position").shape[1]
    return {"y": pos, "p": pos + np.asarray(light_position, dtype=np.float64), "n": normal / np.linalg.norm(normal, axis=-1, keepdims=True).clip(1e-300), "flux": flux, "side": side}


def inject(texels: dict, grid_min, cell: float, side: int) -> np.ndarray:
    """The light volume (side, side, side, 3, 4) [z, y, x, colour, SH] of the texels' diffuse
    flux: Φ/π·clamped cosine about n, in the cell holding p + n·cell/2."""
    vol = np.zeros((side, side, side, 3, 4))
    lit = texels["flux"].max(axis=-1) > 0
    p, n, flux = texels["p"][lit], texels["n"][lit], texels["flux"][lit]
    u = (p + 0.5 * cell * n - np.asarray(grid_min)) / cell
    inside = np.all((u >= 0) & (u < side), axis=-1)
    idx = np.floor(u[inside]).astype(int)
    lobes = clamped_cosine(n[inside]) / np.pi
    for ch in range(3):
        np.add.at(vol, (idx[:, 2], idx[:, 1], idx[:, 0], ch), lobes * flux[inside, ch : ch + 1])
    return vol


def texel_areas(texels: dict, frame) -> np.ndarray:
    """Each texel's area on the surface for a spot light's RSM: the cross-section
    t²(2/N)²cos³α·d² over the cosine to the light, floored at 0.1."""
    axis, t = spot_rsm_view(frame)
    y, n, side = texels["y"], texels["n"], texels["side"]
    d2 = np.maximum(np.sum(y * y, -1), 1e-300)
    cos_axis = np.abs(y @ axis) / np.sqrt(d2)
    cross = t * t * (2.0 / side) ** 2 * cos_axis**3 * d2
    cos_surface = np.maximum(np.abs(np.sum(-y * n, -1)) / np.sqrt(d2), 0.1)
    return cross / cos_surface


def geometry(texels: dict, areas: np.ndarray, grid_min, cell: float, side: int, background: np.ndarray) -> np.ndarray:
    """The geometry volume (side+1,)*3 + (4,) [z, y, x, SH]: min(A/s², 1)·clamped cosine about n
    at the light-volume corner nearest each texel."""
    vol = np.zeros((side + 1, side + 1, side + 1, 4))
    keep = ~background
    p, n, a = texels["p"][keep], texels["n"][keep], areas[keep]
    u = (p - np.asarray(grid_min)) / cell + 0.5
    inside = np.all((u >= 0) & (u < side + 1), axis=-1)
    idx = np.floor(u[inside]).astype(int)
    lobes = clamped_cosine(n[inside]) * np.minimum(a[inside] / cell**2, 1.0)[:, None]
    np.add.at(vol, (idx[:, 2], idx[:, 1], idx[:, 0]), lobes)
    return vol


AXES = [np.array(v, dtype=np.int64) for v in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1))]


def _geometry_at(gv: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Trilinear read of the geometry volume at corner coordinates u (x, y, z)."""
    side = gv.shape[0] - 1
    base = np.clip(np.floor(u).astype(int), 0, side - 1)
    t = np.clip(u - base, 0.0, 1.0)
    out = np.zeros(4)
    for k in range(8):
        o = np.array([k & 1, (k >> 1) & 1, (k >> 2) & 1])
        w = np.prod(np.where(o == 1, t, 1.0 - t))
        c = base + o
        out += w * gv[c[2], c[1], c[0]]
    return out


def propagate_once(current: np.ndarray, gv: np.ndarray | None) -> np.ndarray:
    """One gathering step: every cell collects, from each face neighbour at −d, the flux that
    neighbour's intensity sends through the destination's far face and four side faces,
    re-emitted as Φ_f/π·clamped cosine about the face normal; with `gv`, attenuated by
    1 − clamp(B(−d)) at the shared face."""
    side = current.shape[0]
    out = np.zeros_like(current)
    for z in range(side):
        for y in range(side):
            for x in range(side):
                cell = np.array([x, y, z])
                for d in AXES:
                    src = cell - d
                    if np.any(src < 0) or np.any(src >= side):
                        continue
                    trans = 1.0
                    if gv is not None:
                        b = evaluate(_geometry_at(gv, cell + 0.5 - 0.5 * d), -d.astype(float))
                        trans = 1.0 - np.clip(b, 0.0, 1.0)
                    sh = current[src[2], src[1], src[0]]
                    axis = int(np.flatnonzero(d)[0])
                    faces = [(d.astype(float), d.astype(float), FAR_FACE)]
                    for other in range(3):
                        if other == axis:
                            continue
                        for sign in (1.0, -1.0):
                            s = np.zeros(3)
                            s[other] = sign
                            w = d + 0.5 * s
                            faces.append((w / np.linalg.norm(w), s, SIDE_FACE))
                    for toward, normal, omega in faces:
                        flux = omega * np.maximum(0.0, evaluate(sh, toward)) * trans
                        out[z, y, x] += flux[:, None] * clamped_cosine(normal)[None, :] / np.pi
    return out


def propagate(injected: np.ndarray, gv: np.ndarray | None, iterations: int) -> np.ndarray:
    """Injected light plus `iterations` propagation steps, occlusion from the second on."""
    total, current = injected.copy(), injected
    for i in range(iterations):
        current = propagate_once(current, gv if i > 0 else None)
        total += current
    return total
