"""Per-pass GPU timings of the current build on the best adapter: median, interquartile range
and spread over timed frames after warm-up, for each built-in scene at one resolution. Writes
JSON to $OUT (or out/).

    python experiments/gpu_timings.py --size 1920x1088 --frames 20 --warm-seconds 10

`--warm-seconds` renders the configuration back to back for that long before timing it, so the
GPU leaves its idle clock (docs/error.md, cold clocks: an H200 idles at 345 MHz between short frames);
where `nvidia-smi` exists its SM clock is read before and after the timed frames.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import time

import numpy as np

import vsgl


def sm_clock_mhz() -> str:
    """The SM clock as nvidia-smi reports it (read only), or "" where there is none."""
    if not shutil.which("nvidia-smi"):
        return ""
    out = subprocess.run(["nvidia-smi", "--query-gpu=clocks.sm", "--format=csv,noheader,nounits"], capture_output=True, text=True)
    return out.stdout.strip()


def quartiles(v: list[float]) -> tuple[float, float]:
    q = statistics.quantiles(v, n=4) if len(v) >= 2 else [v[0], v[0], v[0]]
    return q[0], q[2]


def write_report(report: dict, name: str) -> None:
    """Writes `report` as JSON to $OUT/name (the device call's results), else to out/name: a
    git-ignored folder, so a local run leaves nothing to commit by mistake."""
    out = os.environ.get("OUT", "out")
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, name), "w") as fh:
        json.dump(report, fh, indent=1)


def method_options(method: str, lights: int, rsm_size: int, interleave: int, vpl_interleave: int) -> dict:
    """The sweep's settings of `method` (only those it takes)."""
    opts: dict = {}
    if method in ("vpl", "vsgl"):
        opts.update(num_lights=lights, rsm_size=rsm_size)
    if method == "vsgl":
        opts.update(interleave=interleave)
    if method == "vpl":
        opts.update(interleave=vpl_interleave)
    return opts


def time_config(r: vsgl.Renderer, scene: vsgl.Scene, method: str, opts: dict, frames: int, warmup: int, warm_seconds: float) -> dict:
    """Per-pass timings of one configuration: `warmup` frames, then `warm_seconds` of frames
    back to back (aovs=[]), then `frames` timed frames; median, quartiles, min and max per pass,
    the SM clock before and after where nvidia-smi exists."""
    for _ in range(warmup):
        r.render(scene, method=method, **opts)
    t_end = time.perf_counter() + warm_seconds
    warm_frames = 0
    while time.perf_counter() < t_end:
        r.render(scene, method=method, **{**opts, "aovs": []})
        warm_frames += 1
    clock_before = sm_clock_mhz()
    per_pass: dict[str, list[float]] = {}
    walls = []
    for _ in range(frames):
        t = time.perf_counter()
        f = r.render(scene, method=method, **opts)
        walls.append(1e3 * (time.perf_counter() - t))
        for k, v in f.timings_ms.items():
            per_pass.setdefault(k, []).append(v)
    assert all(np.isfinite(f.aov(a)).all() for a in f.aovs)
    clock_after = sm_clock_mhz()
    stats = lambda v: {"median": statistics.median(v), "q1": quartiles(v)[0], "q3": quartiles(v)[1], "min": min(v), "max": max(v)}  # noqa: E731
    row = {k: stats(v) for k, v in per_pass.items()}
    row["wall_incl_upload_readback"] = stats(walls)
    return {
        "clock": f.timings_clock, "passes": f.passes, "settings": dict(f.settings), "ms": row,
        "warm_seconds": warm_seconds, "warm_frames": warm_frames, "sm_clock_mhz_before": clock_before, "sm_clock_mhz_after": clock_after,
    }


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
    ap.add_argument("--vpl-interleave", type=int, default=1)
    ap.add_argument("--aovs", default="all", help='comma-separated AOVs to read back, or "all" (default)')
    ap.add_argument("--tag", default="", help="suffix of the JSON file name")
    ap.add_argument("--warm-seconds", type=float, default=0.0, help="render back to back this long before timing (default: 0)")
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.split("x"))
    r = vsgl.Renderer(width=w, height=h)
    print(f"adapter: {r.adapter}")
    report = {"adapter": r.adapter, "size": [w, h], "frames": args.frames, "scenes": {}}
    for name, method in [(n, m) for n in args.scenes.split(",") for m in args.methods.split(",")]:
        scene = vsgl.scenes.load(name)
        opts = method_options(method, args.lights, args.rsm_size, args.interleave, args.vpl_interleave)
        if args.aovs != "all":
            opts["aovs"] = args.aovs.split(",")
        entry = time_config(r, scene, method, opts, args.frames, args.warmup, args.warm_seconds)
        report["scenes"][f"{name}/{method}"] = entry
        cells = "  ".join(f"{k}={v['median']:.3f}[{v['min']:.3f},{v['max']:.3f}]" for k, v in entry["ms"].items())
        print(f"{name}/{method:8s} warm {entry['warm_frames']} frames, SM {entry['sm_clock_mhz_before']}->{entry['sm_clock_mhz_after']} MHz  {cells}")
    write_report(report, f"gpu_timings{args.tag}.json")


if __name__ == "__main__":
    main()
