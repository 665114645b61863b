"""vsgl2's two reductions on the GPU: the `vsgl2_reduce` pass time of `vsgl2_reduction=
"subgroup"` against `"shared_memory"` by RSM side, on frames rendered back to back after a
warm-up (median and interquartile range; GPU timestamps). The lavapipe figures are
experiments/lavapipe/vsgl2_reduction.txt (crates/vsgl-core/examples/vsgl2_reduction_timing.rs);
this is the same comparison where timestamps bracket the work. JSON to $OUT (or out/).

    OUT=out python3 experiments/gpu_vsgl2_reduction.py [--size 1920x1080] [--rsm 256,1024,4096]
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import sys

import vsgl

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from gpu_visibility_and_flicker import timed  # noqa: E402  (warm-up, then frames back to back)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--rsm", default="256,1024,4096")
    ap.add_argument("--frames", type=int, default=20)
    ap.add_argument("--warm-seconds", type=float, default=2.0)
    a = ap.parse_args()
    w, h = (int(x) for x in a.size.split("x"))
    r = vsgl.Renderer(width=w, height=h)
    scene = vsgl.scenes.cornell_box()
    report = {"adapter": r.adapter, "size": [w, h], "rows": []}
    for rsm in (int(x) for x in a.rsm.split(",")):
        row = {"rsm_size": rsm}
        for reduction in ("subgroup", "shared_memory"):
            t = timed(r, scene, a.frames, a.warm_seconds, method="vsgl2", rsm_size=rsm, vsgl2_reduction=reduction)
            row[reduction] = t["passes_ms_median"].get("vsgl2_reduce")
        row["ratio"] = row["subgroup"] / row["shared_memory"] if row["subgroup"] and row["shared_memory"] else None
        report["rows"].append(row)
        print(f"rsm {rsm:5d}: vsgl2_reduce subgroup {row['subgroup']:.4f} ms, shared_memory {row['shared_memory']:.4f} ms, "
              f"ratio {row['ratio']:.3f}  ({r.adapter['name']})", flush=True)
    out = pathlib.Path(os.environ.get("OUT", "out"))
    out.mkdir(parents=True, exist_ok=True)
    (out / "vsgl2_reduction.json").write_text(json.dumps(report, indent=1, default=str))
    return 0


if __name__ == "__main__":
    sys.exit(main())
