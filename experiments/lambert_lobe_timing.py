"""Cost of `lambert_lobe=` (docs/methods/vsgl.md, "VSGLs": Lambert lobes): wall-clock seconds per
frame and the `vsgl_shading` pass time of `vsgl` with each form, in round-robin rounds so that a
change of the machine's load falls on every form alike (on a CPU adapter only the ratios
within one run mean anything).

    .venv/bin/python experiments/lambert_lobe_timing.py [--size 64] [--lights 1024,4096] [--rounds 5]
        [--scene cornell_box]
"""

from __future__ import annotations

import argparse
import statistics
import time

import vsgl

FORMS = ("papers", "hemisphere", "exact_compact")


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--lights", default="1024,4096")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--scene", default="cornell_box")
    a = p.parse_args()
    r = vsgl.Renderer(a.size, a.size)
    scene = vsgl.scenes.load(a.scene)
    configs = [(form, int(n)) for n in a.lights.split(",") for form in FORMS]
    wall: dict[tuple[str, int], list[float]] = {c: [] for c in configs}
    shading: dict[tuple[str, int], list[float]] = {c: [] for c in configs}
    for form, n in configs:  # compile every pipeline variant before timing
        r.render(scene, method="vsgl", num_lights=n, interleave=1, denoise=False, lambert_lobe=form, aovs=["indirect"])
    for _ in range(a.rounds):
        for form, n in configs:
            t = time.perf_counter()
            f = r.render(scene, method="vsgl", num_lights=n, interleave=1, denoise=False, lambert_lobe=form, aovs=["indirect"])
            wall[(form, n)].append(time.perf_counter() - t)
            shading[(form, n)].append(sum(ms for name, ms in f.timings_ms.items() if name.startswith("vsgl_shading")))
    # lavapipe's timestamps do not bracket a pass's work (vsgl_shading reads ~0.1 ms of a ~1 s
    # frame): on a CPU adapter only the wall clock is reported.
    cpu = r.adapter["device_type"] == "Cpu"
    print(f"{a.scene} {a.size}², interleave 1, {a.rounds} round-robin rounds; median [min, max]; "
          f"{'CPU adapter: wall clock only, compare ratios' if cpu else 'clock: ' + f.timings_clock}\n")
    print("| N | `lambert_lobe` | wall s/frame | wall over papers' |" + ("" if cpu else " `vsgl_shading` ms | shading over papers' |"))
    print("|---|---|---|---|" + ("" if cpu else "---|---|"))
    for form, n in configs:
        w, s = wall[(form, n)], shading[(form, n)]
        row = f"| {n} | {form} | {statistics.median(w):.3f} [{min(w):.3f}, {max(w):.3f}] | {statistics.median(w) / statistics.median(wall[('papers', n)]):.3f} |"
        if not cpu:
            base = statistics.median(shading[("papers", n)])
            row += f" {statistics.median(s):.3f} [{min(s):.3f}, {max(s):.3f}] | {statistics.median(s) / base if base > 0 else float('nan'):.3f} |"
        print(row)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
