"""How far the benchmark's reference is from a finer one: the every-texel reference with an
n² RSM against one with a (2n)² RSM, next to the errors of vsgl and vpl against both, at one
resolution on the best adapter. Writes JSON to $OUT (or out/).

    python experiments/gpu_reference_error.py --size 1920x1080 --rsm 512
"""

from __future__ import annotations

import argparse

import numpy as np

import vsgl
from gpu_timings import write_report


def rel_rmse(a: np.ndarray, b: np.ndarray) -> float:
    a, b = a.astype(np.float64), b.astype(np.float64)
    return float(np.sqrt(np.mean((a - b) ** 2)) / max(np.sqrt(np.mean(b**2)), 1e-30))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--scene", default="cornell_box")
    ap.add_argument("--rsm", type=int, default=512)
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.split("x"))
    r = vsgl.Renderer(width=w, height=h)
    scene = vsgl.scenes.load(args.scene)
    ind = lambda **kw: r.render(scene, aovs=["indirect"], **kw).aov("indirect")  # noqa: E731
    coarse, fine = ind(method="reference", rsm_size=args.rsm), ind(method="reference", rsm_size=2 * args.rsm)
    rows = {"reference_vs_finer": rel_rmse(coarse, fine)}
    for name, kw in {"vsgl": dict(method="vsgl", num_lights=1024, rsm_size=256), "vpl": dict(method="vpl", num_lights=1024, rsm_size=256)}.items():
        x = ind(**kw)
        rows[f"{name}_vs_reference"] = rel_rmse(x, coarse)
        rows[f"{name}_vs_finer"] = rel_rmse(x, fine)
    for k, v in rows.items():
        print(f"{k:24s} relRMSE {v:.4f}")
    write_report({"adapter": r.adapter, "size": [w, h], "scene": args.scene, "rsm": args.rsm, "rel_rmse_indirect": rows}, "reference_error.json")


if __name__ == "__main__":
    main()
