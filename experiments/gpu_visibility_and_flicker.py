"""Virtual-light visibility and temporal flicker on a GPU, in one device call (results as JSON under $OUT):

- visibility: per-pass GPU time (median, IQR over frames rendered back to back after a warm-up)
  at 1920×1080 of vsgl (1024 VSGLs, 8×8 interleaving), vpl (1024) and reference with
  visibility none / raytrace / ism on cornell_box, and the error of the unlit room's indirect
  light with and without visibility on the two-room scene of tests/test_visibility.py against
  pathtrace (bidirectional), to set against the papers' 10–16 ms imperfect shadow maps and to
  choose the default;
- temporal: error, flicker and time for vpl, vsgl K = 1, 2, 4 and vsgl2 on the animated
  built-ins (`python -m vsgl bench --sequence`), run by experiments/gpu_bench_vs_pathtracer.sh's sibling call.

    OUT=out python3 experiments/gpu_visibility_and_flicker.py --size 1920x1080 --frames 20 --warm-seconds 3
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import statistics
import sys
import time

import numpy as np

import vsgl

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tests"))
from scene_builders import two_rooms  # noqa: E402  (the scene of tests/test_visibility.py)


def timed(renderer, scene, frames, warm_seconds, **opts):
    end = time.perf_counter() + warm_seconds
    while time.perf_counter() < end:
        for _ in renderer.render_sequence(scene, [{}] * 8, aovs=[], **opts):
            pass
    totals, passes = [], {}
    for f in renderer.render_sequence(scene, [{}] * frames, aovs=[], **opts):
        totals.append(f.timings_ms.get("total", 0.0))
        for name, ms in f.timings_ms.items():
            passes.setdefault(name, []).append(ms)
    q = statistics.quantiles(totals, n=4) if len(totals) > 1 else [totals[0]] * 3
    return {"total_ms_median": statistics.median(totals), "total_ms_iqr": [q[0], q[2]],
            "passes_ms_median": {k: statistics.median(v) for k, v in passes.items()}}


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--frames", type=int, default=20)
    ap.add_argument("--warm-seconds", type=float, default=3.0)
    ap.add_argument("--leak-size", default="480x270", help="image size of the two-room leak check")
    ap.add_argument("--leak-spp", type=int, default=1024, help="samples per pixel of its ground truth")
    ap.add_argument("--rsm-size", type=int, default=256)
    ap.add_argument("--methods", default="vsgl,vpl,reference",
                    help="methods to time (reference with shadow rays costs 64x vpl's rays at RSM 256)")
    a = ap.parse_args()
    w, h = (int(x) for x in a.size.split("x"))
    out = pathlib.Path(os.environ.get("OUT", "out"))
    out.mkdir(parents=True, exist_ok=True)
    r = vsgl.Renderer(width=w, height=h)
    report = {"adapter": r.adapter, "size": [w, h], "timings": {}, "leak": {}}
    scene = vsgl.scenes.cornell_box()
    for method, opts in (("vsgl", dict(num_lights=1024, interleave=8, rsm_size=a.rsm_size)), ("vpl", dict(num_lights=1024, rsm_size=a.rsm_size)),
                         ("reference", dict(rsm_size=a.rsm_size))):
        if method not in a.methods.split(","):
            continue
        for visibility in ("none", "raytrace", "ism"):
            key = f"{method}/{visibility}"
            try:
                report["timings"][key] = timed(r, scene, a.frames, a.warm_seconds, method=method, visibility=visibility, **opts)
            except Exception as e:  # a figure that cannot be taken is reported, not fatal
                report["timings"][key] = {"error": str(e)}
            print(key, report["timings"][key].get("total_ms_median", report["timings"][key].get("error")), flush=True)
            (out / "visibility.json").write_text(json.dumps(report, indent=1, default=str))  # kept if a later step times out
    scene, cam = two_rooms(out)
    lw, lh = (int(x) for x in a.leak_size.split("x"))
    small = vsgl.Renderer(width=lw, height=lh)
    truth = small.render(scene, camera=cam, method="pathtrace", spp=a.leak_spp, strategy="bidirectional", seed=1)
    t = truth.aov("indirect").astype(np.float64).sum(-1).mean()
    report["leak"]["pathtrace_bidirectional_mean"] = t
    for method, opts in (("reference", dict(rsm_size=a.rsm_size)), ("vpl", dict(num_lights=1024, rsm_size=a.rsm_size)),
                         ("vsgl", dict(num_lights=1024, rsm_size=a.rsm_size)), ("vsgl2", dict(rsm_size=a.rsm_size))):
        for visibility in ("none", "raytrace", "ism"):
            f = small.render(scene, camera=cam, method=method, visibility=visibility, **opts)
            report["leak"][f"{method}/{visibility}"] = f.aov("indirect").astype(np.float64).sum(-1).mean() / t
    print(json.dumps(report["leak"], indent=1))
    (out / "visibility.json").write_text(json.dumps(report, indent=1, default=str))
    return 0


if __name__ == "__main__":
    sys.exit(main())
