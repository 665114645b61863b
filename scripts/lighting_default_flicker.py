"""Do vsgl's defaults of 2026-12-01 (lighting="blend", coherence=0.9) keep VSGLs' temporal coherence? Flicker
(vsgl.metrics.flicker, issue 19's definition) of the indirect light on the animated built-ins
over their animations, a new seed each frame, for vpl, vsgl as it was before 2026-12-01
(lighting="asg", coherence=0), with lighting="blend" alone and with its defaults, all at N = 1024 with their other defaults,
against the every-texel reference of each frame.

    .venv/bin/python scripts/lighting_default_flicker.py [--size 64] [--frames 16]"""

from __future__ import annotations

import argparse

import numpy as np

import vsgl
from vsgl.metrics import flicker


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--frames", type=int, default=16)
    a = p.parse_args()
    r = vsgl.Renderer(a.size, a.size)
    runs = {"vpl": ("vpl", {}), "vsgl asg": ("vsgl", dict(lighting="asg", coherence=0.0)),
            "vsgl blend": ("vsgl", dict(coherence=0.0)), "vsgl (default)": ("vsgl", {})}
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
        print(f"{name} ({a.size}x{a.size}, {a.frames} frames): " + ", ".join(f"{k} {v:.3f}" for k, v in out.items())
              + f"; vpl / default {out['vpl'] / out['vsgl (default)']:.1f}x, vpl / asg {out['vpl'] / out['vsgl asg']:.1f}x")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
