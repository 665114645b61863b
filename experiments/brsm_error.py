"""Bidirectional RSM importance against the RSM density: where the view sees little of the
lit area, does N = 1024 with importance="brsm" beat N = 4096 without? relRMSE of the indirect
AOV against the every-texel `reference` of the same RSM (whose own error against that target is
0: it is the sum both estimate), mean ± standard error over seeds.

    .venv/bin/python experiments/brsm_error.py [--size 48] [--rsm 64] [--seeds 3] [--pathtrace SPP]
                                                [--importance-interleave 1,2,4]

With --importance-interleave K1,K2,… the brsm column is repeated for each interleaved importance
map (`importance_interleave`); the default is the option's default only.

With --pathtrace SPP the errors are measured against a bidirectional `pathtrace` of SPP samples
per pixel instead (its own relative error, from its stderr, and the reference's error against
it are printed first), on lit_floor_corner only.

Scenes: lit_floor_corner (tests/scene_builders.py: a wide spot light over an 8 × 8 floor, the
camera on a small patch of the wall beside it) and caustics_ring seen up close (the ring's inside
and a small part of its lit floor)."""

from __future__ import annotations

import argparse
import pathlib
import sys
import tempfile

import numpy as np

import vsgl
from vsgl.metrics import rel_rmse

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tests"))
from scene_builders import lit_floor_corner  # noqa: E402

VARIANTS = [
    ("vpl", dict(interleave=1, denoise=False)),
    ("vsgl", {}),
    ("vsgl", dict(interleave=1, denoise=False)),
    ("vsgl", dict(kernel="node", interleave=1, denoise=False)),
]


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=48)
    p.add_argument("--rsm", type=int, default=64)
    p.add_argument("--seeds", type=int, default=3)
    p.add_argument("--pathtrace", type=int, default=0, metavar="SPP", help="measure against pathtrace with SPP samples per pixel")
    p.add_argument("--importance-interleave", default=None, metavar="K1,K2,…", help="a brsm column per importance_interleave value")
    a = p.parse_args()
    brsm_columns = [("brsm", 1024, {})]
    if a.importance_interleave:
        brsm_columns = [("brsm", 1024, {"importance_interleave": int(k)}) for k in a.importance_interleave.split(",")]
    r = vsgl.Renderer(width=a.size, height=a.size)
    scenes = [("lit_floor_corner", *lit_floor_corner(pathlib.Path(tempfile.mkdtemp()))),
              ("caustics_ring close-up", vsgl.scenes.caustics_ring(), vsgl.Camera.look_at(eye=(0.0, 0.9, -0.9), target=(0.0, 0.0, 0.1), fov_y_deg=25))]
    if a.pathtrace:
        scenes = scenes[:1]
        print(f"{a.size}x{a.size}, RSM {a.rsm}², {a.seeds} seeds; relRMSE of indirect vs pathtrace, {a.pathtrace} spp")
    else:
        print(f"{a.size}x{a.size}, RSM {a.rsm}², {a.seeds} seeds; relRMSE of indirect vs the same-RSM reference (its own error: 0)")
    print("columns: rsm 1024, rsm 4096, " + ", ".join(f"brsm 1024 {c}" for _, _, c in brsm_columns))
    for name, scene, cam in scenes:
        ref = r.render(scene, camera=cam, method="reference", rsm_size=a.rsm).aov("indirect")
        if a.pathtrace:
            pt = r.render(scene, camera=cam, method="pathtrace", spp=a.pathtrace, strategy="bidirectional")
            truth = pt.aov("indirect").astype(np.float64)
            own = float(np.sqrt(np.mean(pt.aov("stderr").astype(np.float64) ** 2) / np.mean(truth**2)))
            print(f"pathtrace's own relative error {own:.4f}; the reference (RSM {a.rsm}²) against it: {rel_rmse(ref, truth):.4f}")
            ref = truth
        for method, extra in VARIANTS:
            cells = []
            for imp, n, more in [("rsm", 1024, {}), ("rsm", 4096, {}), *brsm_columns]:
                errs = [rel_rmse(r.render(scene, camera=cam, method=method, num_lights=n, rsm_size=a.rsm, importance=imp, seed=s, **extra, **more).aov("indirect"), ref)
                        for s in range(a.seeds)]
                cells.append((np.mean(errs), np.std(errs, ddof=1) / np.sqrt(len(errs)) if len(errs) > 1 else float("nan")))
            verdict = "yes" if all(c[0] <= cells[1][0] for c in cells[2:]) else "NO"
            opts = ",".join(f"{k}={v}" for k, v in extra.items()) or "defaults"
            print(f"{name:<24}{method:<5}{opts:<42}" + "".join(f"{m:9.4f} ± {s:.4f}" for m, s in cells) + f"   brsm@1024 <= rsm@4096: {verdict}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
