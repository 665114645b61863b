"""Timing of the vsgl2 reduction's two implementations (subgroup sums vs the shared-memory tree)
on the best adapter: median `vsgl2_reduce` time over frames that alternate between the two, so
both see the same machine state. Writes JSON to $OUT (or .). On a CPU adapter only the ratio
between the two means anything.

    python scripts/vsgl2_reduction_timing.py --rsm-sizes 128,256,512,1024 --frames 15
"""

from __future__ import annotations

import argparse
import json
import os
import statistics

import vsgl


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rsm-sizes", default="128,256,512,1024")
    ap.add_argument("--frames", type=int, default=15)
    ap.add_argument("--warmup", type=int, default=2)
    ap.add_argument("--scene", default="cave_flashlight")
    args = ap.parse_args()
    r = vsgl.Renderer(width=64, height=48)
    if not r.adapter["subgroups"]:
        raise SystemExit(f"adapter {r.adapter['name']!r} has no subgroup operations: nothing to compare")
    scene = vsgl.scenes.load(args.scene)
    variants = ("subgroup", "shared_memory")
    report = {"adapter": r.adapter, "scene": args.scene, "frames": args.frames, "rows": []}
    for n in (int(x) for x in args.rsm_sizes.split(",")):
        times: dict[str, list[float]] = {v: [] for v in variants}
        for i in range(args.warmup + args.frames):
            for v in variants:
                f = r.render(scene, method="vsgl2", rsm_size=n, vsgl2_reduction=v)
                if i >= args.warmup:
                    times[v].append(f.timings_ms["vsgl2_reduce"])
        med = {v: statistics.median(t) for v, t in times.items()}
        row = {"rsm_size": n, "median_ms": med, "min_ms": {v: min(t) for v, t in times.items()},
               "subgroup_over_shared": med["subgroup"] / med["shared_memory"]}
        report["rows"].append(row)
        print(f"rsm {n:5d}: subgroup {med['subgroup']:.4f} ms, shared_memory {med['shared_memory']:.4f} ms, "
              f"ratio {row['subgroup_over_shared']:.3f}  ({r.adapter['name']})")
    out = os.environ.get("OUT", ".")
    with open(os.path.join(out, "vsgl2_reduction_timing.json"), "w") as fh:
        json.dump(report, fh, indent=1)


if __name__ == "__main__":
    main()
