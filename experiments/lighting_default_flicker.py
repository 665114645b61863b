"""Do vsgl's candidate defaults keep VSGLs' temporal coherence? Flicker (vsgl.metrics.flicker,
the temporal benchmark's definition) of the indirect light on the animated built-ins over their animations, a
new seed each frame, against the every-texel reference of each frame, all at N = 1024 with their
other defaults: by default for vpl, vsgl as it was before 2026-12-01 (lighting="asg",
coherence=0), with lighting="blend" alone and with both (all with lambert_lobe="hemisphere", as
they were then) and vsgl's defaults of today; with --variant, any labelled option sets
(method=vpl for VPLs), the first the one the others are compared with.

    .venv/bin/python experiments/lighting_default_flicker.py [--size 64] [--frames 16]
        [--variant LABEL=opt=value,... ...]"""

from __future__ import annotations

import argparse

import os
import sys

import numpy as np

import vsgl
from vsgl.metrics import flicker

sys.path.insert(0, os.path.dirname(__file__))
from real_scene_bias import parse_variant  # noqa: E402

DEFAULT_VARIANTS = ["vpl=method=vpl", "vsgl asg=lighting=asg,coherence=0,lambert_lobe=hemisphere",
                    "vsgl blend=coherence=0,lambert_lobe=hemisphere", "vsgl blend coherence=lambert_lobe=hemisphere", "vsgl (default)="]


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--frames", type=int, default=16)
    p.add_argument("--variant", action="append", help="LABEL=opt=value,... (repeatable; method=vpl for VPLs; the first is the baseline)")
    a = p.parse_args()
    r = vsgl.Renderer(a.size, a.size)
    runs = {}
    for label, opts in (parse_variant(v) for v in (a.variant or DEFAULT_VARIANTS)):
        runs[label] = (opts.pop("method", "vsgl"), opts)
    for name in ("cave_flashlight", "glossy_cornell"):
        scene = vsgl.scenes.load(name)
        duration = max(x["duration"] for x in scene.animations)
        times = [duration * k / (a.frames - 1) for k in range(a.frames)]
        truth = []
        for t in times:
            scene.set_time(t)
            truth.append(r.render(scene, method="reference", rsm_size=128, aovs=["indirect"]).aov("indirect"))
        out = {}
        for label, (method, kw) in runs.items():
            frames = []
            for k, t in enumerate(times):
                scene.set_time(t)
                frames.append(r.render(scene, method=method, num_lights=1024, seed=k, aovs=["indirect"], **kw).aov("indirect"))
            out[label] = flicker(np.stack(frames), np.stack(truth))
        first = next(iter(out))
        print(f"{name} ({a.size}x{a.size}, {a.frames} frames): " + ", ".join(f"{k} {v:.3f}" for k, v in out.items())
              + "; " + ", ".join(f"{first} / {k} {out[first] / v:.1f}x" for k, v in out.items() if k != first))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
