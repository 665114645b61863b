"""What does counting the emitters a BSDF-sampled ray hits (weighted against next-event
estimation by the balance heuristic) buy the path tracer? Per-pixel noise and mean of the direct
and the indirect light of a glossy metal floor under a small emissive square (with a grey wall
that bounces its light), for roughness 0.05 / 0.2 / 0.6, and of CornellBox.glb (its ceiling lamp
is emissive), by strategy; the noise is the per-pixel standard deviation over --seeds renders,
relative to the mean image, and the time the median of those renders' wall times.

    .venv/bin/python experiments/emitter_bsdf_sampling.py [--size 48] [--spp 16] [--seeds 8] [--json OUT]

Run on two builds (with and without the BSDF-hit strategy) to compare; the results of both are
in emitter_bsdf_sampling.md."""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import sys
import tempfile
import time

import numpy as np

import vsgl

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))
import scene_builders as sb  # noqa: E402


def measure(r: vsgl.Renderer, scene, camera, strategy: str, spp: int, seeds: int) -> dict:
    stacks = {"direct": [], "indirect": []}
    times = []
    for s in range(seeds):
        t0 = time.perf_counter()
        f = r.render(scene, camera, method="pathtrace", strategy=strategy, spp=spp, seed=s, aovs=["direct", "indirect"])
        times.append(time.perf_counter() - t0)
        for k in stacks:
            stacks[k].append(f.aov(k).astype(np.float64))
    out = {"seconds": float(np.median(times))}
    for k, frames in stacks.items():
        x = np.stack(frames)
        mean = float(x.mean())
        out[k] = {"mean": mean, "noise": float(x.std(axis=0, ddof=1).mean() / max(mean, 1e-30))}
    return out


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=48)
    p.add_argument("--spp", type=int, default=16)
    p.add_argument("--seeds", type=int, default=8)
    p.add_argument("--json")
    a = p.parse_args()
    r = vsgl.Renderer(a.size, a.size)
    results = {}
    with tempfile.TemporaryDirectory() as d:
        cases = [(f"glossy floor roughness {rough}", sb.glossy_floor_under_small_emitter(pathlib.Path(d), rough), sb.GLOSSY_FLOOR_VIEW) for rough in (0.05, 0.2, 0.6)]
        if "cornell_box_mm" in vsgl.scenes.corpus_names():
            try:
                cases.append(("cornell_box_mm", vsgl.scenes.corpus_scene("cornell_box_mm").scene, None))
            except FileNotFoundError as e:
                print(f"cornell_box_mm left out: {e}")
        for label, scene, camera in cases:
            for strategy in ("camera", "bidirectional"):
                m = measure(r, scene, camera, strategy, a.spp, a.seeds)
                results[f"{label} / {strategy}"] = m
                print(f"{label:32s} {strategy:13s} direct mean {m['direct']['mean']:.5g} noise {m['direct']['noise']:.4f}  "
                      f"indirect mean {m['indirect']['mean']:.5g} noise {m['indirect']['noise']:.4f}  {m['seconds']:.2f} s", flush=True)
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(results, fh, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
