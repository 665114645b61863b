"""Wall time of a render() loop on the best adapter: median and interquartile range of the
time per `render()` call and a read of each asked-for AOV (scene upload cached, the GPU frame,
readback)
and of the GPU total, for a few AOV selections. Writes JSON to $OUT (or .).

    python scripts/gpu_frame_wall.py --size 1920x1080 --frames 40 --tag _new
"""

from __future__ import annotations

import argparse
import statistics
import time

import vsgl
from gpu_timings import quartiles, write_report  # scripts/ is on sys.path when run as a script


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--frames", type=int, default=40)
    ap.add_argument("--scene", default="cornell_box")
    ap.add_argument("--methods", default="direct,vsgl")
    ap.add_argument("--tag", default="")
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.split("x"))
    r = vsgl.Renderer(width=w, height=h)
    scene = vsgl.scenes.load(args.scene)
    report = {"adapter": r.adapter, "size": [w, h], "frames": args.frames, "rows": []}
    for method in args.methods.split(","):
        opts = {"num_lights": 1024, "rsm_size": 256} if method == "vsgl" else {}
        for aovs in ([], ["image"], ["ldr"], ["image", "indirect"]):
            try:
                for _ in range(3):
                    r.render(scene, method=method, aovs=aovs, **opts)
            except ValueError as e:  # an AOV this build does not have, or the method does not make
                print(f"{method:8s} aovs={str(aovs):10s} skipped: {e}")
                continue
            walls, gpu = [], []
            for _ in range(args.frames):
                t = time.perf_counter()
                f = r.render(scene, method=method, aovs=aovs, **opts)
                # A loop uses what it read back: touching the arrays counts (an array made per
                # access would cost a copy here).
                for name in aovs:
                    f.aov(name)[0, 0, 0]
                walls.append(1e3 * (time.perf_counter() - t))
                gpu.append(f.timings_ms["total"])
            q1, q3 = quartiles(walls)
            row = {
                "method": method, "aovs": aovs, "wall_ms_median": statistics.median(walls), "wall_ms_q1": q1, "wall_ms_q3": q3,
                "gpu_ms_median": statistics.median(gpu), "allocated_bytes": f.settings.get("allocated_bytes", "n/a"),
            }
            report["rows"].append(row)
            print(f"{method:8s} aovs={str(aovs):10s} wall {row['wall_ms_median']:8.2f} ms [{row['wall_ms_q1']:.2f},{row['wall_ms_q3']:.2f}]  gpu {row['gpu_ms_median']:.3f} ms  allocated {row['allocated_bytes']}")
    write_report(report, f"frame_wall{args.tag}.json")


if __name__ == "__main__":
    main()
