"""Where default vsgl's indirect diffuse goes wrong on a corpus scene: a float64 model of the
papers' VSGL (Tok15 §3, Eq. 5; Tok16s §3-4) built in NumPy from the frame's own RSM
(capture_rsm=True) over a fixed quadtree partition of it (every node of one level is a cluster:
no sampling noise), shaded at receivers drawn from the reference's indirect light, against the
same clusters' texels shaded one by one as VPLs (the every-texel reference restricted to each
cluster). Only the texels' Lambert lobes and the receivers' diffuse are modelled (diffuse-to-
diffuse transport, receiver albedo divided out). The split of the reference's light:

  behind plane   clusters whose mean tangent plane has the receiver behind it (H(p) <= 0):
                 the tangent-plane fade (plane_fade=True) removes all of their light;
  inside         the receiver within 1 sigma of the cluster's mean (Eq. 5 assumes it is far);
  far            the rest.

For each part: its share of the reference's light and the VSGL model's light over it, with and
without the fade.

    .venv/bin/python experiments/real_scene_breakdown.py [--scene flight_helmet] [--rsm 128]
        [--level 2] [--receivers 400]"""

from __future__ import annotations

import argparse
import math
import os
import sys

import numpy as np

import vsgl

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
from rsm_model import spot_texel_footprint_variance  # noqa: E402

LAMBERT_SHARPNESS = 2.2925  # LAMBERT_LOBE_SG_SHARPNESS (wgsl/common/sg.wgsl)
HEMISPHERE_GAIN = 1.1010136  # LAMBERT_LOBE_HEMISPHERE_GAIN
APPROX_SHARPNESS_MIN = 0.5  # SG_INTEGRAL_APPROX_SHARPNESS_MIN
PLANE_TOLERANCE = 1e-3  # VSGL_PLANE_TOLERANCE


erf = np.vectorize(math.erf)


def sg_integral(lam):
    lam = np.maximum(lam, 1e-12)
    return 2 * np.pi * (-np.expm1(-2 * lam)) / lam


def default_camera(scene: vsgl.Scene) -> tuple[vsgl.Camera, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """renderer::default_camera's framing, with its basis for unprojecting depth."""
    lo, hi = (np.array(v, float) for v in scene.bounds)
    c = (lo + hi) / 2
    dist = 0.5 * np.linalg.norm(hi - lo) / math.sin(math.radians(22.5))
    d = np.array([0, 0.6, 1.0]) / np.linalg.norm([0, 0.6, 1.0])
    eye = c + d * dist
    fwd = (c - eye) / np.linalg.norm(c - eye)
    right = np.cross(fwd, [0, 1, 0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    return vsgl.Camera.look_at(eye=tuple(eye), target=tuple(c), fov_y_deg=45), eye, fwd, right, up


def receivers_from_reference(ref: vsgl.Frame, count: int, basis, light_position: np.ndarray, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """``count`` receivers drawn without replacement by the reference frame's indirect diffuse
    light: their positions relative to the light (unprojected from the frame's depth with the
    default camera's ``basis`` (eye, forward, right, up), 45° field of view) and their normals."""
    eye, fwd, right, up = basis
    size = ref.width
    truth = ref.aov("indirect_diffuse").sum(-1)
    rng = np.random.default_rng(seed)
    lit = np.flatnonzero(truth.ravel() > 0)
    pick = rng.choice(lit, size=min(count, lit.size), replace=False, p=truth.ravel()[lit] / truth.ravel()[lit].sum())
    yy, xx = np.divmod(pick, size)
    t = math.tan(math.radians(22.5))
    depth = ref.aov("depth")[yy, xx, 0].astype(float)
    ndc_x = 2 * (xx + 0.5) / size - 1
    ndc_y = 1 - 2 * (yy + 0.5) / size
    p = eye + depth[:, None] * (fwd + ndc_x[:, None] * t * right + ndc_y[:, None] * t * up) - light_position
    return p, ref.aov("normal")[yy, xx].astype(float)


def add_model_arguments(ap: argparse.ArgumentParser, receivers: int) -> None:
    """The options the float64 RSM models share: scene, image and RSM sides, cluster levels,
    receiver count."""
    ap.add_argument("--scene", default="flight_helmet")
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--rsm", type=int, default=128)
    ap.add_argument("--level", type=int, action="append", help="cluster level(s): nodes of 4^level texels")
    ap.add_argument("--receivers", type=int, default=receivers)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_model_arguments(ap, receivers=400)
    ap.add_argument("--coherent", type=float, action="append", default=[],
                    help="also split each node while its positional variance exceeds KAPPA x 4^level x its texels' mean footprint variance (repeatable)")
    ap.add_argument("--min-normal-coherence", type=float, default=0.0,
                    help="with --coherent, also split while the node's mean normal |N| is below this")
    a = ap.parse_args()
    c = vsgl.scenes.corpus_scene(a.scene) if a.scene in vsgl.scenes.corpus_names() else None
    scene = c.scene if c else vsgl.scenes.load(a.scene)
    (light,) = scene.lights[:1]
    cam, eye, fwd, right, up = default_camera(scene)
    r = vsgl.Renderer(a.size, a.size)
    ref = r.render(scene, camera=cam, method="reference", rsm_size=a.rsm, aovs=["indirect_diffuse", "normal", "depth"])
    f = r.render(scene, camera=cam, method="vsgl", rsm_size=a.rsm, num_lights=16, capture_rsm=True, aovs=[])
    y = f.rsm("position").reshape(-1, 3).astype(float)
    nt = f.rsm("normal").reshape(-1, 3).astype(float)
    fd = f.rsm("flux_diffuse").reshape(-1, 3).sum(-1).astype(float)
    w = f.rsm("weight").reshape(-1).astype(float)
    lp = np.array(light.position, float)
    # Each texel's footprint variance, as vsgl_moments.wgsl adds it (rsm_texel_footprint_variance):
    # a spot light's RSM spans tan(outer cone) on each side of its axis.
    footprint = spot_texel_footprint_variance(y, nt, f, a.rsm)
    p, n = receivers_from_reference(ref, a.receivers, (eye, fwd, right, up), lp)

    # How near the reference's light comes from: shares of the every-texel sum by texel distance
    # (as a fraction of the scene's bounds diagonal), for the near-field question.
    lo, hi = (np.array(v, float) for v in scene.bounds)
    diag = float(np.linalg.norm(hi - lo))
    m = fd > 0
    dv = y[m][None] - p[:, None]
    d2 = np.maximum((dv**2).sum(-1), 1e-30)
    om = dv / np.sqrt(d2)[..., None]
    e = fd[m][None] / np.pi * np.maximum(-(om * nt[m][None]).sum(-1), 0) * np.maximum((om * n[:, None]).sum(-1), 0) / d2
    dist = np.sqrt(d2) / diag
    # Each texel as a patch of its footprint, 1/(d² + 2σ²) (what kernel="node" shades a
    # single-texel VSGL with, vsgl_shading.wgsl lambert_patch_irradiance), against a point.
    patch = e * d2 / (d2 + 2 * footprint[m][None])
    print(f"{a.scene}: every texel as a patch of its footprint delivers {patch.sum() / e.sum():.3f} of the point texels' light")
    print(f"{a.scene}: the reference's light at the receivers by texel distance (fraction of the bounds diagonal {diag:.3g}):")
    for edge in (0.005, 0.01, 0.02, 0.05, 0.1):
        print(f"  within {edge:5.3f}: {e[dist < edge].sum() / e.sum():.3f}")

    side = a.rsm
    ij = np.arange(side * side)
    def split(level: int, kappa: float | None):
        """Cluster id per texel: the level's quadtree nodes, each split (recursively) while its
        positional variance exceeds kappa·4^l·(mean texel footprint variance)."""
        cluster = np.full(side * side, -1)
        next_id = 0

        def visit(l: int, x0: int, y0: int):
            nonlocal next_id
            size = 1 << l
            rows = np.arange(y0, y0 + size)
            idx = (rows[:, None] * side + np.arange(x0, x0 + size)[None]).ravel()
            idx = idx[w[idx] > 0]
            if idx.size == 0:
                return
            if kappa is not None and l > 0:
                ww = w[idx]
                mu_ = (ww[:, None] * y[idx]).sum(0) / ww.sum()
                var_ = (ww * (y[idx] ** 2).sum(-1)).sum() / ww.sum() - mu_ @ mu_
                vbar = (ww * footprint[idx]).sum() / ww.sum()
                coherence = np.linalg.norm((ww[:, None] * nt[idx]).sum(0) / ww.sum())
                if var_ > kappa * 4**l * vbar or coherence < a.min_normal_coherence:
                    half = size // 2
                    for dy in (0, half):
                        for dx in (0, half):
                            visit(l - 1, x0 + dx, y0 + dy)
                    return
            cluster[idx] = next_id
            next_id += 1

        for y0 in range(0, side, 1 << level):
            for x0 in range(0, side, 1 << level):
                visit(level, x0, y0)
        return cluster

    configs = [(l, None) for l in (a.level or [1, 2, 3])] + [(l, k) for k in a.coherent for l in (a.level or [1, 2, 3])]
    for level, kappa in configs:
        cluster = split(level, kappa)
        ids = np.unique(cluster[w > 0])
        totals = {k: np.zeros(5) for k in ("behind plane", "inside", "far")}  # ref, sg with fade, sg without, exact front fraction, soft
        by_coherence = np.zeros((2, 3))
        for cid in ids:
            m = (cluster == cid) & (fd > 0)
            if not m.any():
                continue
            yj, nj, fj, wj = y[m], nt[m], fd[m], w[m]
            # Reference restricted to the cluster: each texel a Lambertian VPL (Φ R_d/π cos).
            dv = yj[None] - p[:, None]
            d2 = np.maximum((dv**2).sum(-1), 1e-30)
            om = dv / np.sqrt(d2)[..., None]
            e_ref = (fj / np.pi * np.maximum(-(om * nj[None]).sum(-1), 0) * np.maximum((om * n[:, None]).sum(-1), 0) / d2).sum(1) / np.pi
            # The VSGL of the cluster from its sums [Tok16s §3]; diffuse lobe weights Φ R_d.
            mean_dir = (fj[:, None] * nj * (LAMBERT_SHARPNESS / (LAMBERT_SHARPNESS + 1))).sum(0) / fj.sum()
            rr = np.linalg.norm(mean_dir)
            lam_v = min(rr / max(1 - rr, 1e-12), 1e5)
            xi_v = mean_dir / max(rr, 1e-30)
            mu = (wj[:, None] * yj).sum(0) / wj.sum()
            var = max((wj * (yj**2).sum(-1)).sum() / wj.sum() - mu @ mu, 1e-6 * (wj * (yj**2).sum(-1)).sum() / wj.sum())
            nbar = (wj[:, None] * nj).sum(0) / wj.sum()
            offset = mu @ nbar - (wj * (yj * nj).sum(-1)).sum() / wj.sum()
            c_v = HEMISPHERE_GAIN * fj.sum() / sg_integral(lam_v)
            tm = mu[None] - p
            dist2 = (tm**2).sum(-1)
            var_seen = np.maximum(var, dist2 / 1e9)
            lam_s = dist2 / var_seen
            xi_mu = tm / np.sqrt(np.maximum(dist2, 1e-30))[:, None]
            v = -lam_v * xi_v[None] + lam_s[:, None] * xi_mu
            lam_in = np.linalg.norm(v, axis=-1)
            xi_in = v / np.maximum(lam_in, 1e-30)[:, None]
            dd = ((-xi_v[None] - xi_mu) ** 2).sum(-1)
            log_amp = -lam_v * lam_s / np.maximum(lam_in + lam_v + lam_s, 1e-30) * dd
            c_in = c_v / (2 * np.pi * var_seen) * np.exp(log_amp)
            e_sg = c_in / np.pi * (2 * np.pi / np.maximum(lam_in, APPROX_SHARPNESS_MIN)) * np.maximum((xi_in * n).sum(-1), 0)
            height = ((p - mu[None]) * nbar).sum(-1) + offset
            tol = PLANE_TOLERANCE * (np.sqrt(dist2) + math.sqrt(var))
            fade = np.clip((height - tol) / np.maximum(tol, 1e-30), 0, 1)
            # Heights of p above each texel's tangent plane: the exact fraction of the cluster's
            # power in front of p (what any fade could at best keep), and a normal model of it
            # from the heights' mean and variance over the cluster (second moments of n, y·n).
            h = ((p[:, None] - yj[None]) * nj[None]).sum(-1)
            front = (wj[None] * (h > 0)).sum(1) / wj.sum()
            h_var = np.maximum((wj[None] * h**2).sum(1) / wj.sum() - ((wj[None] * h).sum(1) / wj.sum()) ** 2, 0)
            soft = 0.5 * (1 + erf(height / np.sqrt(np.maximum(2 * h_var, 1e-300))))
            coherent = np.linalg.norm(nbar) >= 0.9
            behind = height <= 0
            inside = ~behind & (dist2 < var)
            for key, sel in (("behind plane", behind), ("inside", inside), ("far", ~behind & ~inside)):
                totals[key] += [e_ref[sel].sum(), (e_sg * fade)[sel].sum(), e_sg[sel].sum(), (e_sg * front)[sel].sum(), (e_sg * soft)[sel].sum()]
            by_coherence[int(coherent)] += [e_ref.sum(), (e_sg * fade).sum(), (e_sg * front).sum()]
        whole = sum(v[0] for v in totals.values())
        how = f": {len(ids)} clusters" if kappa is None else f", split while sigma^2 > {kappa:g} x 4^l x footprint or |N| < {a.min_normal_coherence:g}: {len(ids)} clusters"
        print(f"{a.scene}, RSM {a.rsm}^2, clusters of {4**level} texels (level {level}{how}), {len(p)} receivers drawn from the reference's indirect diffuse:")
        all_ = sum(totals.values())
        print(f"  all: VSGL/reference {all_[1] / whole:.3f} with the fade, {all_[2] / whole:.3f} without, {all_[3] / whole:.3f} times the exact front fraction, {all_[4] / whole:.3f} times its normal model")
        for key, (ref_sum, sg_fade, sg_plain, sg_front, sg_soft) in totals.items():
            q = max(ref_sum, 1e-300)
            print(f"  {key:13s} {ref_sum / whole:6.3f} of the reference's light; VSGL/reference there {sg_fade / q:6.3f} with the fade, {sg_plain / q:6.3f} without, {sg_front / q:6.3f} front fraction, {sg_soft / q:6.3f} normal model")
        for k, label in ((1, "coherent (|N| >= 0.9)"), (0, "incoherent (|N| < 0.9)")):
            ref_sum, sg_fade, sg_front = by_coherence[k]
            print(f"  {label:22s} clusters: {ref_sum / whole:6.3f} of the light; VSGL/reference {sg_fade / max(ref_sum, 1e-300):6.3f} with the fade, {sg_front / max(ref_sum, 1e-300):6.3f} front fraction")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
