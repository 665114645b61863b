#!/usr/bin/env python3
"""Do emitter VSGLs shadowed by the virtual-light visibility (`emitter_direct="sg"`) give the
soft shadows of an area light that the cube of shadow maps of `emitter_direct="points"` cannot?

The shared CornellBox.glb lit by its ceiling quad alone (the boxes cast the shadows), at
`--size`: the direct light of `vpl` (the direct light does not depend on the method's virtual
lights) per setting, against the path tracer's direct light at `--spp` samples per pixel. The
truth's own error is measured as the block error between two path-traced halves of different
seeds (each of spp/2), divided by √2 for one of them, then halved again for their mean's.
Reported per setting: mean direct light over the truth's, the 4×4 block error (relative RMS of
block means: bias such as a hard shadow edge, not noise), the per-pixel relative RMS, and the
frame's wall milliseconds (median of `--frames`, rows alternated, same run: on lavapipe only
ratios mean anything, and its GPU timestamps do not resolve the shading passes), over the
"points, 1 light" row of the same `visibility`.

    VSGL_SCENES=../shared/scenes .venv/bin/python experiments/emitter_soft_shadows.py [--size 64] [--spp 1024] [--frames 3]

Result: experiments/emitter_soft_shadows.md.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

import vsgl
from vsgl import metrics

# Every row shades the method's VPLs with the same `visibility` as its baseline row, so the
# frames differ only in the emitters' direct light ("points" ignores `visibility`).
SETTINGS = [
    ("points, 1 light", dict(emitter_direct="points", visibility="raytrace", emitter_lights=1)),
    ("points, 4 lights", dict(emitter_direct="points", visibility="raytrace", emitter_lights=4)),
    ("points, 16 lights", dict(emitter_direct="points", visibility="raytrace", emitter_lights=16)),
    ("sg + raytrace, 1 light", dict(emitter_direct="sg", visibility="raytrace", emitter_lights=1)),
    ("sg + raytrace, 4 lights", dict(emitter_direct="sg", visibility="raytrace", emitter_lights=4)),
    ("points, 1 light (vpl with ism)", dict(emitter_direct="points", visibility="ism", emitter_lights=1)),
    ("sg + ism, 1 light", dict(emitter_direct="sg", visibility="ism", emitter_lights=1)),
]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--frames", type=int, default=3)
    args = ap.parse_args()
    scene = vsgl.scenes.corpus_scene("cornell_box_mm").scene
    scene.lights = []  # the ceiling quad alone
    r = vsgl.Renderer(args.size, args.size)
    halves = [r.render(scene, method="pathtrace", spp=args.spp // 2, seed=s, aovs=["direct"]).aov("direct").astype(np.float64) for s in (1, 2)]
    truth = 0.5 * (halves[0] + halves[1])
    own_block = metrics.block_rmse(halves[0], halves[1], 4) / np.sqrt(2) / np.sqrt(2)
    own_pixel = metrics.rel_rmse(halves[0], halves[1]) / np.sqrt(2) / np.sqrt(2)
    print(f"adapter {r.adapter['name']}, {args.size}², truth: pathtrace direct at {args.spp} spp "
          f"(its own error: block {own_block:.4f}, per pixel {own_pixel:.4f})")
    print("| emitter direct light | mean / truth | 4×4 block error | per-pixel rel. RMS | frame wall ms (median) | over points, 1 light |")
    print("|---|---|---|---|---|---|")
    images, walls = {}, {label: [] for label, _ in SETTINGS}
    for round_ in range(args.frames + 1):
        for label, opts in SETTINGS:
            t0 = time.perf_counter()
            f = r.render(scene, method="vpl", num_lights=64, aovs=["direct"], **opts)
            if round_ > 0:  # the first round compiles and builds (BVH, point set)
                walls[label].append(1e3 * (time.perf_counter() - t0))
            images[label] = f.aov("direct").astype(np.float64)
    for label, opts in SETTINGS:
        x = images[label]
        ms = statistics.median(walls[label])
        base_label = "points, 1 light" if opts["visibility"] == "raytrace" else "points, 1 light (vpl with ism)"
        base = statistics.median(walls[base_label])
        print(f"| {label} | {x.mean() / truth.mean():.4f} | {metrics.block_rmse(x, truth, 4):.4f} | {metrics.rel_rmse(x, truth):.4f} | {ms:.0f} | {ms / base:.2f} |")

if __name__ == "__main__":
    main()
