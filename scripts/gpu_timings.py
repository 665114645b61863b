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
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.split("x"))
    r = vsgl.Renderer(width=w, height=h)
    print(f"adapter: {r.adapter}")
    report = {"adapter": r.adapter, "size": [w, h], "frames": args.frames, "scenes": {}}
    for name in args.scenes.split(","):
        scene = vsgl.scenes.load(name)
        for _ in range(args.warmup):
            r.render(scene)
        per_pass: dict[str, list[float]] = {}
        walls = []
        for _ in range(args.frames):
            t = time.perf_counter()
            f = r.render(scene)
            walls.append(1e3 * (time.perf_counter() - t))
            for k, v in f.timings_ms.items():
                per_pass.setdefault(k, []).append(v)
        assert np.isfinite(f.image).all()
        row = {k: {"median": statistics.median(v), "min": min(v), "max": max(v)} for k, v in per_pass.items()}
        row["wall_incl_upload_readback"] = {"median": statistics.median(walls), "min": min(walls), "max": max(walls)}
        report["scenes"][name] = {"clock": f.timings_clock, "passes": f.passes, "ms": row}
        cells = "  ".join(f"{k}={v['median']:.3f}[{v['min']:.3f},{v['max']:.3f}]" for k, v in row.items())
        print(f"{name:16s} {cells}")
    out = os.environ.get("OUT", ".")
    with open(os.path.join(out, "gpu_timings.json"), "w") as fh:
        json.dump(report, fh, indent=1)


if __name__ == "__main__":
    main()
