"""Per-pass GPU timings of the current build on the best adapter: median and spread over timed
frames after warm-up, for each built-in scene at one resolution. Writes JSON to $OUT (or .).

    python scripts/gpu_timings.py --size 1920x1088 --frames 20
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time

import numpy as np

import vsgl


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="1920x1088")
    ap.add_argument("--frames", type=int, default=20)
    ap.add_argument("--warmup", type=int, default=3)
    ap.add_argument("--scenes", default=",".join(vsgl.scenes.names()))
    ap.add_argument("--methods", default="direct", help="comma-separated methods (default: direct)")
    ap.add_argument("--lights", type=int, default=1024)
    ap.add_argument("--rsm-size", type=int, default=256)
    ap.add_argument("--interleave", type=int, default=8)
    ap.add_argument("--aovs", default="all", help='comma-separated AOVs to read back, or "all" (default)')
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.split("x"))
    r = vsgl.Renderer(width=w, height=h)
    print(f"adapter: {r.adapter}")
    report = {"adapter": r.adapter, "size": [w, h], "frames": args.frames, "scenes": {}}
    for name, method in [(n, m) for n in args.scenes.split(",") for m in args.methods.split(",")]:
        scene = vsgl.scenes.load(name)
        opts = {} if args.aovs == "all" else {"aovs": args.aovs.split(",")}
        if method in ("vpl", "vsgl"):
            opts.update(num_lights=args.lights, rsm_size=args.rsm_size)
        if method == "vsgl":
            opts.update(interleave=args.interleave)
        for _ in range(args.warmup):
            r.render(scene, method=method, **opts)
        per_pass: dict[str, list[float]] = {}
        walls = []
        for _ in range(args.frames):
            t = time.perf_counter()
            f = r.render(scene, method=method, **opts)
            walls.append(1e3 * (time.perf_counter() - t))
            for k, v in f.timings_ms.items():
                per_pass.setdefault(k, []).append(v)
        assert all(np.isfinite(f.aov(a)).all() for a in f.aovs)
        row = {k: {"median": statistics.median(v), "min": min(v), "max": max(v)} for k, v in per_pass.items()}
        row["wall_incl_upload_readback"] = {"median": statistics.median(walls), "min": min(walls), "max": max(walls)}
        report["scenes"][f"{name}/{method}"] = {"clock": f.timings_clock, "passes": f.passes, "settings": dict(f.settings), "ms": row}
        cells = "  ".join(f"{k}={v['median']:.3f}[{v['min']:.3f},{v['max']:.3f}]" for k, v in row.items())
        print(f"{name}/{method:8s} {cells}")
    out = os.environ.get("OUT", ".")
    with open(os.path.join(out, "gpu_timings.json"), "w") as fh:
        json.dump(report, fh, indent=1)


if __name__ == "__main__":
    main()
