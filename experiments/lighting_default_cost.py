"""What a candidate default of vsgl costs against the frame before it: by default, the defaults
of 2026-12-01 (lighting="blend", coherence=0.9) against the frame before them (lighting="asg",
coherence=0), both with lambert_lobe="hemisphere" as they were; with --variant, any option sets,
each over the first. The whole default frame (interleave 8, denoised, N = 1024, RSM 256²) at
two sizes, all variants alternated in one run so that the ratio means something on a CPU
adapter; median and quartiles of each frame's GPU total (frame.timings_ms["total"]) over
--repeats frames after one warm-up frame per configuration.

    .venv/bin/python experiments/lighting_default_cost.py [--sizes 128,512] [--repeats 5]
        [--scene NAME ...] [--variant LABEL=opt=value,... ...]"""

from __future__ import annotations

import argparse

import sys

import numpy as np

import vsgl

sys.path.insert(0, __import__("os").path.dirname(__file__))
from real_scene_bias import parse_variant  # noqa: E402

DEFAULT_VARIANTS = ["before=lighting=asg,coherence=0,lambert_lobe=hemisphere", "blend=lambert_lobe=hemisphere"]


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sizes", default="128,512")
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--scene", action="append")
    p.add_argument("--variant", action="append", help="LABEL=opt=value,... (repeatable; the first is the baseline)")
    a = p.parse_args()
    names = a.scene or ["cornell_box", "glossy_cornell", "cornell_box_original", "flight_helmet"]
    variants = dict(parse_variant(v) for v in (a.variant or DEFAULT_VARIANTS))
    labels = list(variants)
    for size in (int(s) for s in a.sizes.split(",")):
        r = vsgl.Renderer(size, size)
        for name in names:
            if name in vsgl.scenes.corpus_names() and not vsgl.scenes.corpus_available(name):
                print(f"{name}: skipped (corpus file absent)")
                continue
            scene = vsgl.scenes.load(name) if name in vsgl.scenes.names() else vsgl.scenes.corpus_scene(name).scene
            times: dict[str, list[float]] = {v: [] for v in labels}
            for v in labels:
                r.render(scene, method="vsgl", num_lights=1024, aovs=[], **variants[v])
            for _ in range(a.repeats):
                for v in labels:
                    times[v].append(r.render(scene, method="vsgl", num_lights=1024, aovs=[], **variants[v]).timings_ms["total"])
            q = {v: np.percentile(times[v], [25, 50, 75]) for v in labels}
            clock = r.render(scene, method="vsgl", num_lights=1024, aovs=[]).timings_clock
            cells = [f"{v} {q[v][1]:8.1f} ms [{q[v][0]:.1f}, {q[v][2]:.1f}]" + ("" if v == labels[0] else f" ratio {q[v][1] / q[labels[0]][1]:.3f}")
                     for v in labels]
            print(f"{size}x{size} {name:22s} " + "  ".join(cells) + f" ({clock})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
