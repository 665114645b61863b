"""Which texel should a VSGL's one shadow ray aim at? A float64 model over the frame's own RSM
(capture_rsm=True) with every visibility traced by Mitsuba 3 (`scene.triangles()`, the same
geometry vsgl traces), at receivers drawn from the every-texel reference's indirect diffuse.

Each cluster (a quadtree node of 4^level lit texels) delivers L_c = sum_i e_i, its texels' point
Lambert light at the receiver, unshadowed; shadowed, the every-texel reference has
sum_i e_i V_i. One shadow ray per cluster stands for its visibility V_c, and L_c V_c is summed:

  power      the ray aims at a texel drawn by the RSM's importance weight w (the VSGL's sampled
             centre texel, Tok15 Eq. 3's V with vsgl's target): E[V_c] = sum w_i V_i / sum w_i;
  mean       at the cluster's mean position mu (Tok15 Eq. 3 as written);
  resampled  at one of M texels drawn by w, picked by its geometric term at the receiver
             g_i = max(-w_i.n_i, 0) max(w_i.n, 0) / (d_i^2 + 2 sigma_i^2) (resampled importance:
             as M grows the pick follows each texel's share of the cluster's light there, and
             E[V_c] tends to sum e_i V_i / sum e_i, the reference's own shadowing).

Printed: each estimate's shadowed light over the reference's (1 = the reference's shadows).

    .venv/bin/python experiments/shadow_target_model.py [--scene flight_helmet] [--level 2]
        [--receivers 200] [--candidates 1 2 4 8]"""

from __future__ import annotations

import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import mitsuba_bridge  # noqa: E402  (the Mitsuba loader and scene conversion of experiments/mitsuba_truth.py)
import real_scene_breakdown as breakdown  # noqa: E402  (its default camera)

import vsgl  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
from rsm_model import spot_texel_footprint_variance  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    breakdown.add_model_arguments(ap, receivers=200)
    ap.add_argument("--candidates", type=int, nargs="+", default=[1, 2, 4, 8])
    ap.add_argument("--repeats", type=int, default=8, help="draws per estimate (the resampled pick is random)")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    a = ap.parse_args()
    mi, dr = mitsuba_bridge.load_mitsuba(a.variant)
    c = vsgl.scenes.corpus_scene(a.scene) if a.scene in vsgl.scenes.corpus_names() else None
    scene = c.scene if c else vsgl.scenes.load(a.scene)
    (light,) = scene.lights[:1]
    cam, eye, fwd, right, up = breakdown.default_camera(scene)
    mscene, _, _, _ = mitsuba_bridge.mitsuba_scene(mi, scene, cam, a.size, 1, 0.0)
    r = vsgl.Renderer(a.size, a.size)
    ref = r.render(scene, camera=cam, method="reference", rsm_size=a.rsm, aovs=["indirect_diffuse", "normal", "depth"])
    f = r.render(scene, camera=cam, method="vsgl", rsm_size=a.rsm, num_lights=16, capture_rsm=True, aovs=[])
    lp = np.array(light.position, float)
    y = f.rsm("position").reshape(-1, 3).astype(float)
    nt = f.rsm("normal").reshape(-1, 3).astype(float)
    fd = f.rsm("flux_diffuse").reshape(-1, 3).sum(-1).astype(float)
    w = f.rsm("weight").reshape(-1).astype(float)
    footprint = spot_texel_footprint_variance(y, nt, f, a.rsm)
    p, n = breakdown.receivers_from_reference(ref, a.receivers, (eye, fwd, right, up), lp)
    rng = np.random.default_rng(1)  # the resampled picks
    n /= np.maximum(np.linalg.norm(n, axis=-1, keepdims=True), 1e-30)
    lo, hi = (np.array(v, float) for v in scene.bounds)
    diag = float(np.linalg.norm(hi - lo))

    def visible(origins: np.ndarray, targets: np.ndarray) -> np.ndarray:
        """1 where nothing blocks the segment (origins lifted off their surface, stopping short)."""
        seg = targets - origins
        length = np.maximum(np.linalg.norm(seg, axis=-1), 1e-30)
        out = np.empty(len(origins))
        step = 1 << 20
        for s in range(0, len(origins), step):
            o, d, l = origins[s:s + step], seg[s:s + step] / length[s:s + step, None], length[s:s + step]
            ray = mi.Ray3f(mi.Point3f(*(o + lp).T.astype(np.float32)), mi.Vector3f(*d.T.astype(np.float32)))
            ray.maxt = mi.Float((l * (1 - 1e-4) - 1e-5 * diag).astype(np.float32))
            out[s:s + step] = 1.0 - np.asarray(mscene.ray_test(ray), float)
        return out

    origin = p + n * (1e-5 * diag)
    m = fd > 0
    idx = np.flatnonzero(m)
    # Every lit texel seen from every receiver: its point Lambert light and its visibility.
    dv = y[idx][None] - p[:, None]
    d2 = np.maximum((dv**2).sum(-1), 1e-30)
    om = dv / np.sqrt(d2)[..., None]
    geo = np.maximum(-(om * nt[idx][None]).sum(-1), 0) * np.maximum((om * n[:, None]).sum(-1), 0)
    e = fd[idx][None] / np.pi * geo / d2
    g = geo / (d2 + 2 * footprint[idx][None])
    vis = visible(np.repeat(origin, len(idx), axis=0), np.tile(y[idx], (len(p), 1))).reshape(len(p), len(idx))
    print(f"{a.scene}: {len(p)} receivers x {len(idx)} lit texels; the reference keeps {(e * vis).sum() / e.sum():.3f} of its light under shadows")

    side = a.rsm
    tx, ty = idx % side, idx // side
    for level in a.level or [1, 2, 3, 4]:
        node = (ty >> level) * (side >> level) + (tx >> level)
        ids, inverse = np.unique(node, return_inverse=True)
        k = len(ids)
        L = np.zeros((len(p), k))
        np.add.at(L.T, inverse, e.T)
        shadowed = np.zeros((len(p), k))
        np.add.at(shadowed.T, inverse, (e * vis).T)
        wi = w[idx]
        wsum = np.bincount(inverse, weights=wi, minlength=k)
        v_power = np.zeros((len(p), k))
        np.add.at(v_power.T, inverse, (vis * wi[None]).T)
        v_power /= np.maximum(wsum, 1e-300)[None]
        mu = np.stack([np.bincount(inverse, weights=wi * y[idx][:, j], minlength=k) for j in range(3)], -1) / np.maximum(wsum, 1e-300)[:, None]
        v_mean = visible(np.repeat(origin, k, axis=0), np.tile(mu, (len(p), 1))).reshape(len(p), k)
        ref_sum = shadowed.sum()
        line = [f"power {np.sum(L * v_power) / ref_sum:.3f}", f"mean {np.sum(L * v_mean) / ref_sum:.3f}"]
        # Resampled picks: M candidates per (receiver, cluster) drawn by w (inverse CDF over
        # each cluster's texels), one kept by g.
        order = np.argsort(inverse, kind="stable")
        start = np.searchsorted(inverse[order], np.arange(k))
        count = np.bincount(inverse, minlength=k)
        cdf = np.zeros(len(idx))
        for cid in range(k):
            s0, s1 = start[cid], start[cid] + count[cid]
            cw = np.cumsum(wi[order[s0:s1]])
            cdf[s0:s1] = cw / cw[-1]
        for M in a.candidates:
            acc = 0.0
            for rep in range(a.repeats):
                u = rng.random((len(p), k, M))
                local = np.empty((len(p), k, M), np.int64)
                for cid in range(k):
                    s0, s1 = start[cid], start[cid] + count[cid]
                    local[:, cid] = np.minimum(np.searchsorted(cdf[s0:s1], u[:, cid]), count[cid] - 1) + s0
                cand = order[local]  # texel index into idx
                gc = np.take_along_axis(g, cand.reshape(len(p), -1), 1).reshape(len(p), k, M)
                total = gc.sum(-1, keepdims=True)
                choose = (rng.random((len(p), k, 1)) * total > np.cumsum(gc, -1) - gc).sum(-1) - 1
                choose = np.clip(choose, 0, M - 1)
                chosen = np.take_along_axis(cand, choose[..., None], -1)[..., 0]
                vc = np.take_along_axis(vis, chosen, 1)
                acc += np.sum(L * vc) / ref_sum
            line.append(f"resampled M={M} {acc / a.repeats:.3f}")
        print(f"  level {level} ({4**level} texels, {k} clusters), shadowed light over the reference's: " + ", ".join(line))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
