"""Is the every-texel reference a truth on the real-scene corpus? Each corpus scene's indirect
light (diffuse / specular means) from the bidirectional path tracer (exact geometry and
visibility, converging on caustics: the independent truth, with its own standard error), from the
every-texel `reference` of an RSM (shadowed by ray tracing, as the path tracer is), and from
`vpl` and `vsgl` at N = 1024 with ray-traced virtual-light visibility, all over the path
tracer's. docs/scenes.md, "The real-scene corpus", has the table this prints.

    .venv/bin/python experiments/real_scene_truth.py [--size 128] [--rsm 128] [--spp 256]
        [--scene NAME ...] [--variant LABEL=method=...,opt=value ...]"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

import vsgl

sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parent))
from real_scene_bias import parse_variant  # noqa: E402

AOVS = ["indirect_diffuse", "indirect_specular"]
DEFAULT_VARIANTS = [
    "reference=method=reference",
    "vpl=method=vpl",
    "vsgl",
    "vsgl_blend=lighting=blend",
]


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=128)
    p.add_argument("--rsm", type=int, default=128)
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--scene", action="append")
    p.add_argument("--variant", action="append")
    a = p.parse_args()
    names = a.scene or [n for n in vsgl.scenes.corpus_names() if vsgl.scenes.corpus_available(n) and n != "lights_spot"]
    variants = [parse_variant(v) for v in (a.variant or DEFAULT_VARIANTS)]
    r = vsgl.Renderer(a.size, a.size)
    print(f"{a.size}x{a.size}; mean indirect diffuse / specular over the bidirectional path tracer's ({a.spp} spp); RSM {a.rsm}^2, N = 1024, visibility=\"raytrace\"")
    for name in names:
        scene = vsgl.scenes.load(name) if name in vsgl.scenes.names() else vsgl.scenes.corpus_scene(name).scene
        t0 = time.perf_counter()
        pt = r.render(scene, method="pathtrace", strategy="bidirectional", spp=a.spp, aovs=AOVS + ["stderr"])
        truth = [float(pt.aov(x).astype(np.float64).mean()) for x in AOVS]
        # The standard error of the image mean from the per-pixel standard errors (of the whole
        # indirect light: the path tracer reports one stderr per pixel).
        se = pt.aov("stderr").astype(np.float64)
        mean_se = float(np.sqrt((se**2).sum()) / se.size) / max(sum(truth), 1e-300)
        print(f"\n{name}: path tracer {truth[0]:.4g} / {truth[1]:.4g} (specular {truth[1] / max(sum(truth), 1e-300):.2f} of it), "
              f"its standard error {100 * mean_se:.2f}% of the mean, {time.perf_counter() - t0:.0f} s")
        for label, opts in variants:
            opts = dict(opts)
            method = opts.pop("method", "vsgl")
            settings = {"rsm_size": a.rsm, "visibility": "raytrace", **opts}
            if method != "reference":
                settings.setdefault("num_lights", 1024)
            if method == "vsgl":
                settings.setdefault("interleave", 1)
                settings.setdefault("denoise", False)
            f = r.render(scene, method=method, aovs=AOVS, **settings)
            got = [float(f.aov(x).astype(np.float64).mean()) for x in AOVS]
            print(f"  {label:24s} {got[0] / truth[0]:6.3f} / {got[1] / max(truth[1], 1e-300):6.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
