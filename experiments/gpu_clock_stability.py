"""Does the warm-up make per-pass timings hold still? One configuration is
timed with the standard procedure (`gpu_timings.time_config`: warm-up frames, then
`--warm-seconds` back to back, then timed frames) three times:

1. at the start,
2. at the end of a sweep of every method on every built-in scene rendered back to back for
   `--sweep-seconds` (the GPU hot, its clocks and memory state after a long varied load),
3. right after a long single GPU job (`pathtrace` at a high sample count for `--job-seconds`),
   after `--idle-seconds` of idling first, so the clocks have dropped before the job.

It reports, per pass, each run's median and the largest deviation from the start run's median
(the acceptance asks for ≤ 10%). JSON to $OUT (or out/).

    python experiments/gpu_clock_stability.py --size 1920x1080 --sweep-seconds 300
"""

from __future__ import annotations

import argparse
import time

import vsgl
from gpu_timings import method_options, sm_clock_mhz, time_config, write_report  # experiments/ is on sys.path when run as a script


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--scene", default="cornell_box")
    ap.add_argument("--method", default="vsgl")
    ap.add_argument("--frames", type=int, default=30)
    ap.add_argument("--warm-seconds", type=float, default=6.0)
    ap.add_argument("--sweep-seconds", type=float, default=300.0)
    ap.add_argument("--idle-seconds", type=float, default=20.0)
    ap.add_argument("--job-seconds", type=float, default=30.0)
    ap.add_argument("--tag", default="")
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.split("x"))
    r = vsgl.Renderer(width=w, height=h)
    scene = vsgl.scenes.load(args.scene)
    opts = {**method_options(args.method, 1024, 256, 8, 1), "aovs": ["image"]}
    runs: dict[str, dict] = {}

    def timed(label: str) -> None:
        runs[label] = time_config(r, scene, args.method, opts, args.frames, 3, args.warm_seconds)
        e = runs[label]
        print(f"{label:14s} SM {e['sm_clock_mhz_before']}->{e['sm_clock_mhz_after']} MHz  total {e['ms']['total']['median']:.3f} ms", flush=True)

    timed("start")
    # The sweep: every method on every built-in scene, back to back, until the time is up.
    t_end = time.perf_counter() + args.sweep_seconds
    sweep_frames = 0
    configs = [(n, m) for n in vsgl.scenes.names() for m in ("direct", "vpl", "vsgl", "vsgl2", "reference")]
    scenes = {n: vsgl.scenes.load(n) for n in vsgl.scenes.names()}
    while time.perf_counter() < t_end:
        for name, method in configs:
            r.render(scenes[name], method=method, aovs=["image"], **method_options(method, 1024, 256, 8, 1))
            sweep_frames += 1
            if time.perf_counter() >= t_end:
                break
    print(f"sweep: {sweep_frames} frames in {args.sweep_seconds:.0f} s, SM {sm_clock_mhz()} MHz", flush=True)
    timed("after_sweep")
    time.sleep(args.idle_seconds)
    idle_clock = sm_clock_mhz()
    t_end = time.perf_counter() + args.job_seconds
    job_frames = 0
    while time.perf_counter() < t_end:
        r.render(scene, method="pathtrace", spp=256, aovs=[])
        job_frames += 1
    print(f"long job: {job_frames} pathtrace frames (256 spp) in {args.job_seconds:.0f} s after {args.idle_seconds:.0f} s idle (SM {idle_clock} MHz)", flush=True)
    timed("after_long_job")

    start = runs["start"]["ms"]
    deviation = {}
    for name, s in start.items():
        if s["median"] <= 0:
            continue
        devs = {label: runs[label]["ms"][name]["median"] / s["median"] - 1 for label in ("after_sweep", "after_long_job") if name in runs[label]["ms"]}
        deviation[name] = devs
        print(f"  {name:28s} start {s['median']:8.3f} ms  " + "  ".join(f"{k} {v:+.1%}" for k, v in devs.items()))
    worst = max((abs(v) for d in deviation.values() for v in d.values()), default=0.0)
    print(f"largest per-pass deviation from the start run: {worst:.1%} (acceptance: <= 10%)")
    write_report({"adapter": r.adapter, "size": [w, h], "scene": args.scene, "method": args.method, "opts": opts, "runs": runs,
                  "sweep_seconds": args.sweep_seconds, "sweep_frames": sweep_frames, "job_seconds": args.job_seconds, "job_frames": job_frames,
                  "deviation_from_start": deviation, "largest_deviation": worst}, f"clock_stability{args.tag}.json")


if __name__ == "__main__":
    main()
