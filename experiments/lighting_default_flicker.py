"""Do vsgl's candidate defaults keep VSGLs' temporal coherence? Flicker (vsgl.metrics.flicker,
the temporal benchmark's definition) of the indirect light on the animated built-ins over their
animations, a new seed each frame, all at N = 1024 with their other defaults: by default vpl,
vpl with interleave 8 (vsgl's per-pixel share of the lights), vsgl's defaults, and vsgl with
interleave 1 and no denoiser; with --variant, any labelled option sets (method=vpl for VPLs),
the first the one the others are compared with.

Two truths, both every-texel references: the converged one at --reference-rsm (512 by default),
what a viewer compares a frame with, and the reference of the methods' own RSM (256², the
default of vpl and vsgl), what their virtual lights estimate. The converged truth's own flicker
error is printed first: the flicker of the reference at half its RSM against it (a finite RSM's
reference on glossy receivers is a sum of point-light highlights that crawl as the scene moves;
at RSM 128² on glossy_cornell that error, 2.4, exceeds vsgl's whole flicker). One sequence's
flicker is heavy-tailed (a single VPL next to a receiver can dominate it), so each variant runs
--seed-sets sequences (seed k + 1000 j in frame k of set j) and the median and range are printed.
Before 2026-12-04 the truth was the reference at RSM 128² and each variant one sequence: the
files under experiments/lavapipe/corpus/ were made so (--reference-rsm 128 --seed-sets 1 with
their variants reproduces their converged-truth column).

    .venv/bin/python experiments/lighting_default_flicker.py [--size 64] [--frames 16]
        [--reference-rsm 512] [--seed-sets 4] [--fixed-seed] [--scene NAME ...] [--variant LABEL=opt=value,... ...]"""

from __future__ import annotations

import argparse

import os
import sys

import numpy as np

import vsgl
from vsgl.metrics import flicker

sys.path.insert(0, os.path.dirname(__file__))
from real_scene_bias import parse_variant  # noqa: E402

DEFAULT_VARIANTS = ["vpl=method=vpl", "vpl interleave 8=method=vpl,interleave=8", "vsgl (default)=",
                    "vsgl interleave 1=interleave=1,denoise=False"]


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--frames", type=int, default=16)
    p.add_argument("--reference-rsm", type=int, default=512)
    p.add_argument("--seed-sets", type=int, default=4)
    p.add_argument("--fixed-seed", action="store_true",
                   help="one seed for every frame of a set (seed 1000 j in set j: render_sequence's default, a fixed sample pattern) instead of seed k + 1000 j in frame k")
    p.add_argument("--scene", action="append", help="animated scene (repeatable; default cave_flashlight and glossy_cornell)")
    p.add_argument("--variant", action="append", help="LABEL=opt=value,... (repeatable; method=vpl for VPLs; the first is the baseline)")
    a = p.parse_args()
    if a.frames < 2 or a.seed_sets < 1:
        p.error(f"--frames: expected 2 or more (got {a.frames}); --seed-sets: expected 1 or more (got {a.seed_sets})")
    r = vsgl.Renderer(a.size, a.size)
    runs = {}
    for label, opts in (parse_variant(v) for v in (a.variant or DEFAULT_VARIANTS)):
        runs[label] = (opts.pop("method", "vsgl"), opts)
    for name in a.scene or ["cave_flashlight", "glossy_cornell"]:
        scene = vsgl.scenes.load(name)
        duration = max(x["duration"] for x in scene.animations)
        times = [duration * k / (a.frames - 1) for k in range(a.frames)]

        def sequence(method: str, seed_set: int | None = None, **kw) -> np.ndarray:
            frames = []
            for k, t in enumerate(times):
                scene.set_time(t)
                if seed_set is not None:
                    kw["seed"] = (0 if a.fixed_seed else k) + 1000 * seed_set
                frames.append(r.render(scene, method=method, aovs=["indirect"], **kw).aov("indirect"))
            return np.stack(frames)

        own_rsm = vsgl.method_options("vsgl")["rsm_size"]
        truths = {"converged": sequence("reference", rsm_size=a.reference_rsm)}
        half = sequence("reference", rsm_size=a.reference_rsm // 2)
        if own_rsm == a.reference_rsm:
            truths["same RSM"] = truths["converged"]
        else:
            truths["same RSM"] = half if a.reference_rsm // 2 == own_rsm else sequence("reference", rsm_size=own_rsm)
        print(f"{name} ({a.size}x{a.size}, {a.frames} frames, {a.seed_sets} seed sets{', one seed per set' if a.fixed_seed else ''}; converged truth: reference at RSM "
              f"{a.reference_rsm}^2, whose own flicker error is below that of RSM {a.reference_rsm // 2}^2 against it, "
              f"{flicker(half, truths['converged']):.3f}; same-RSM truth: reference at RSM {own_rsm}^2)")
        medians = {t: {} for t in truths}
        for label, (method, kw) in runs.items():
            frames = [sequence(method, j, num_lights=1024, **kw) for j in range(a.seed_sets)]
            for t, truth in truths.items():
                values = [flicker(x, truth) for x in frames]
                medians[t][label] = float(np.median(values))
                print(f"  {label} against the {t} truth: median {medians[t][label]:.3f}, range {min(values):.3f}-{max(values):.3f} "
                      f"({', '.join(f'{v:.3f}' for v in values)})", flush=True)
        for t, m in medians.items():
            first = next(iter(m))
            print(f"  {t}: " + ", ".join(f"{first} / {k} {m[first] / v:.1f}x" for k, v in m.items() if k != first))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
