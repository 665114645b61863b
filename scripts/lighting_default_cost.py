"""What vsgl's defaults of 2026-12-01 (lighting="blend", coherence=0.9) cost against the frame
before them (lighting="asg", coherence=0): the whole default frame (interleave 8, denoised, N = 1024, RSM 256²) at two
sizes, both forms alternated in one run so that the ratio means something on a CPU adapter;
median and quartiles of each frame's GPU total (frame.timings_ms["total"]) over --repeats frames
after one warm-up frame per configuration.

    .venv/bin/python scripts/lighting_default_cost.py [--sizes 128,512] [--repeats 5]
        [--scene NAME ...]"""

from __future__ import annotations

import argparse

import numpy as np

import vsgl


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sizes", default="128,512")
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--scene", action="append")
    a = p.parse_args()
    names = a.scene or ["cornell_box", "glossy_cornell", "cornell_box_original", "flight_helmet"]
    forms = ("asg", "blend")
    # "asg": the default frame before 2026-12-01; "blend": today's (with coherence=0.9).
    extra = {"asg": dict(lighting="asg", coherence=0.0), "blend": {}}
    for size in (int(s) for s in a.sizes.split(",")):
        r = vsgl.Renderer(size, size)
        for name in names:
            if name in vsgl.scenes.corpus_names() and not vsgl.scenes.corpus_available(name):
                print(f"{name}: skipped (corpus file absent)")
                continue
            scene = vsgl.scenes.load(name) if name in vsgl.scenes.names() else vsgl.scenes.corpus_scene(name).scene
            times: dict[str, list[float]] = {f: [] for f in forms}
            for form in forms:
                r.render(scene, method="vsgl", num_lights=1024, aovs=[], **extra[form])
            for _ in range(a.repeats):
                for form in forms:
                    times[form].append(r.render(scene, method="vsgl", num_lights=1024, aovs=[], **extra[form]).timings_ms["total"])
            q = {f: np.percentile(times[f], [25, 50, 75]) for f in forms}
            clock = r.render(scene, method="vsgl", num_lights=1024, aovs=[]).timings_clock
            print(f"{size}x{size} {name:22s} before {q['asg'][1]:8.1f} ms [{q['asg'][0]:.1f}, {q['asg'][2]:.1f}]  "
                  f"now {q['blend'][1]:8.1f} ms [{q['blend'][0]:.1f}, {q['blend'][2]:.1f}]  ratio {q['blend'][1] / q['asg'][1]:.3f} ({clock})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
