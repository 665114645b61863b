#!/usr/bin/env python3
"""What does one emitter next to one spot light cost each method?

CornellBoxOriginal (the corpus scene: its spot light) as it is, against the same scene with its
ceiling lamp's material made emissive (L_e = (17, 12, 4), the classic Cornell box lamp's
radiance): per method, the frame's GPU total (`frame.timings_ms["total"]`) of the two
alternated in one run, median and quartiles over `--frames` frames each after a warm-up frame,
and the ratio of the medians; for scale, the same with a point light at the lamp's centre
instead of the emission (what one more point light costs). The emissive lamp becomes `emitter_lights` lights in the
shadow-mapped methods (default 1: one more cube of shadow maps and reflective shadow maps)
and area lights in `pathtrace`.

On a CPU adapter (lavapipe) only the ratios mean anything. On a GPU:
`experiments/gpu_emitter_cost.sh` runs it at 1920×1080.

    .venv/bin/python experiments/emitter_cost.py [--size 128x128] [--frames 7]

Result and command: experiments/emitter_cost.md.
"""

from __future__ import annotations

import argparse
import statistics
import sys

import numpy as np

import vsgl

LAMP_RADIANCE = (17.0, 12.0, 4.0)


def settings(method: str, quick: bool, emitter_lights: int | None) -> dict:
    if method == "pathtrace":
        return dict(spp=4 if quick else 16, strategy="camera")
    return {} if emitter_lights is None else dict(emitter_lights=emitter_lights)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", default="128x128", help="WxH (default 128x128)")
    ap.add_argument("--frames", type=int, default=7, help="timed frames per configuration (default 7)")
    # Not `reference` (every texel of every RSM: minutes a frame on lavapipe, and not a
    # real-time method) nor `pathtrace` (its GPU timer covers its last batch, not the frame).
    ap.add_argument("--methods", default="direct,vpl,vsgl,vsgl2,lpv")
    ap.add_argument("--quick", action="store_true", help="fewer path-traced samples (lavapipe)")
    ap.add_argument("--emitter-lights", type=int, default=None, help="emitter_lights (default: the methods' own)")
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.split("x"))
    spot = vsgl.scenes.corpus_scene("cornell_box_original").scene
    both = vsgl.scenes.corpus_scene("cornell_box_original").scene
    both.set_material("light", emissive=LAMP_RADIANCE)
    with_point = vsgl.scenes.corpus_scene("cornell_box_original").scene
    lo, hi = (np.array(b) for b in with_point.bounds)
    # Just under the ceiling's centre, where the lamp is.
    with_point.add_light(vsgl.PointLight(position=(0.5 * (lo[0] + hi[0]), hi[1] - 0.01 * (hi[1] - lo[1]), 0.5 * (lo[2] + hi[2])), intensity=1.0))
    r = vsgl.Renderer(w, h)
    print(f"CornellBoxOriginal, its spot light against spot + emissive lamp {LAMP_RADIANCE}, {w}x{h}, emitter_lights={args.emitter_lights or 'default'}, "
          f"{args.frames} frames each alternated, adapter {r.adapter['name']}")
    print(f"{'method':<10} {'spot ms (q1-q3)':>22} {'spot+emitter ms (q1-q3)':>26} {'ratio':>7} {'spot+point ms (q1-q3)':>24} {'ratio':>7}")
    for method in args.methods.split(","):
        kw = settings(method, args.quick, args.emitter_lights)
        configurations = (("spot", spot), ("both", both), ("point", with_point))
        for _, scene in configurations:
            r.render(scene, method=method, aovs=[], **kw)  # warm-up: pipelines, upload, BVH
        times: dict[str, list[float]] = {key: [] for key, _ in configurations}
        for _ in range(args.frames):
            for key, scene in configurations:
                times[key].append(r.render(scene, method=method, aovs=[], **kw).timings_ms["total"])

        def summary(t: list[float]) -> str:
            q = statistics.quantiles(t, n=4) if len(t) > 1 else [t[0]] * 3
            return f"{statistics.median(t):.2f} ({q[0]:.2f}-{q[2]:.2f})"

        ratio = statistics.median(times["both"]) / statistics.median(times["spot"])
        point_ratio = statistics.median(times["point"]) / statistics.median(times["spot"])
        print(f"{method:<10} {summary(times['spot']):>22} {summary(times['both']):>26} {ratio:>7.2f} {summary(times['point']):>24} {point_ratio:>7.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
