"""Wall-clock cost of bidirectional RSM importance by `importance_interleave` (experiments/brsm_cost_and_error.md,
"Bidirectional RSM importance", "Passes and cost"). Lavapipe's GPU timestamps do not cover its
compute work, so whole frames are timed with the wall clock, every configuration once per round
in turn (so all see the same machine state), and the median over rounds is reported with its
ratio to importance="rsm" of the same run; only ratios within one run mean anything.

    .venv/bin/python experiments/brsm_importance_timing.py [--size 128] [--rsm 128] [--rounds 3] [--interleaves 1,2,4]

Scene: lit_floor_corner (tests/scene_builders.py); N = 1024, the methods' default interleave
(vpl 8 here, as in the docs' table), importance_lights 2048 (the default)."""

from __future__ import annotations

import argparse
import pathlib
import sys
import tempfile
import time

import numpy as np

import vsgl

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tests"))
from scene_builders import lit_floor_corner  # noqa: E402


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=128)
    p.add_argument("--rsm", type=int, default=128)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--interleaves", default="1,2,4")
    a = p.parse_args()
    ks = [int(k) for k in a.interleaves.split(",")]
    scene, cam = lit_floor_corner(pathlib.Path(tempfile.mkdtemp()))
    r = vsgl.Renderer(width=a.size, height=a.size)
    configs = []
    for method in ("vsgl", "vpl"):
        base = dict(camera=cam, method=method, num_lights=1024, rsm_size=a.rsm, interleave=8, aovs=["indirect"])
        configs.append((method, "rsm", base))
        for k in ks:
            configs.append((method, f"brsm k={k}", dict(base, importance="brsm", importance_interleave=k)))
    for _, _, opts in configs:  # warm-up: pipelines compiled, buffers made
        r.render(scene, **opts)
    times: dict[int, list[float]] = {i: [] for i in range(len(configs))}
    for _ in range(a.rounds):
        for i, (_, _, opts) in enumerate(configs):
            t = time.perf_counter()
            r.render(scene, **opts).aov("indirect")
            times[i].append(1000 * (time.perf_counter() - t))
    print(f"lit_floor_corner {a.size}x{a.size}, RSM {a.rsm}², N = 1024, interleave 8, 2048 view VSGLs; wall ms per frame, median of {a.rounds}")
    rsm_ms = {}
    for i, (method, label, _) in enumerate(configs):
        med = float(np.median(times[i]))
        if label == "rsm":
            rsm_ms[method] = med
        print(f"{method:<5}{label:<12}{med:10.1f} ms  ×{med / rsm_ms[method]:.2f} of rsm   runs {', '.join(f'{t:.0f}' for t in times[i])}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
