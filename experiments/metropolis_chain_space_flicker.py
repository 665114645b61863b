"""Where should a Metropolis chain's state live between frames? Flicker (vsgl.metrics.flicker) of
the indirect light over three sequences for `vpl` (interleave 8) and `vsgl` (K = 1) with
stratified sampling and with sampling="metropolis" in chain_space="world" and "rsm", mean ± sd
over 3 seed offsets (seed k + 1000·offset in frame k, chains started afresh per offset), each
frame against the every-texel reference of that frame (the setting of tests/test_temporal.py:
32×32, RSM 64², N = 32, 8 frames). The sequences: the Cornell box's ceiling spot slid 0.4 m
along x, cave_flashlight's sweep and glossy_cornell's rolling sphere (their animations).

    .venv/bin/python experiments/metropolis_chain_space_flicker.py [--size 32] [--frames 8]"""

from __future__ import annotations

import argparse
import statistics

import numpy as np

import vsgl
from vsgl.metrics import flicker

RSM, NUM_LIGHTS, OFFSETS = 64, 32, 3
METHODS = [("vpl", dict(method="vpl", interleave=8)), ("vsgl", dict(method="vsgl", K=1.0))]
SAMPLINGS = [("stratified", {}), ("metropolis, world", dict(sampling="metropolis", chain_space="world")),
             ("metropolis, rsm", dict(sampling="metropolis", chain_space="rsm"))]


def sequences(frames: int):
    """(name, scene, the per-frame changes without seeds)."""
    box = vsgl.scenes.cornell_box()
    base = box.lights[0]
    slide = [{"lights": [vsgl.SpotLight(position=(-0.2 + 0.4 * k / (frames - 1), 1.95, 0.0), direction=(0, -1, 0), intensity=base.intensity,
                                        inner_cone_deg=base.inner_cone_deg, outer_cone_deg=base.outer_cone_deg)]} for k in range(frames)]
    yield "cornell_box, spot slid 0.4 m", box, slide
    for name, label in (("cave_flashlight", "cave_flashlight sweep"), ("glossy_cornell", "glossy_cornell rolling sphere")):
        scene = vsgl.scenes.load(name)
        duration = max(x["duration"] for x in scene.animations)
        yield label, scene, [{"time": duration * k / (frames - 1)} for k in range(frames)]


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--size", type=int, default=32)
    p.add_argument("--frames", type=int, default=8)
    a = p.parse_args()
    r = vsgl.Renderer(width=a.size, height=a.size)
    print(f"adapter {r.adapter['name']}; {a.size}x{a.size}, RSM {RSM}², N = {NUM_LIGHTS}, {a.frames} frames, mean ± sd over {OFFSETS} seed offsets")
    print("| sequence | method | " + " | ".join(label for label, _ in SAMPLINGS) + " |")
    print("|---|---|" + "---|" * len(SAMPLINGS))
    for name, scene, changes in sequences(a.frames):
        truth = np.stack([f.aov("indirect") for f in r.render_sequence(scene, changes, method="reference", aovs=["indirect"], rsm_size=RSM)])
        for method, kw in METHODS:
            cells = []
            for _, sampling in SAMPLINGS:
                values = []
                for offset in range(OFFSETS):
                    r.reset_chains()
                    seeded = [dict(c, seed=k + 1000 * offset) for k, c in enumerate(changes)]
                    frames = np.stack([f.aov("indirect") for f in r.render_sequence(scene, seeded, aovs=["indirect"], rsm_size=RSM,
                                                                                     num_lights=NUM_LIGHTS, **kw, **sampling)])
                    values.append(flicker(frames, truth))
                cells.append(f"{statistics.mean(values):.3g} ± {statistics.stdev(values):.2g}")
            print(f"| {name} | {method} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
