#!/usr/bin/env python3
"""Does vsgl's path tracer light a scene from its emissive surfaces as Mitsuba 3 does?

The shared CornellBox (`../shared/scenes/CornellBox/CornellBox.glb`), lit only by its ceiling
quad (emissive strength 100, no punctual light), in vsgl's `pathtrace` (emissive triangles as
area lights, `strategy` as given) and in Mitsuba 3's `path` integrator with the quad an `area`
emitter, vsgl's material model through `experiments/mitsuba_bridge.py`'s BSDF plugin and the same
camera. Mitsuba's `max_depth` 2 is the direct light (with the quad's own emission where it is
seen), 3 adds one bounce: their difference is the indirect light vsgl's `indirect` AOV holds.

Reported: the mean of direct, indirect and image over Mitsuba's, the 4×4 block error of the
indirect light and of the image, and each truth's own error (vsgl's from its `stderr` AOV,
Mitsuba's from the spread of two seeds). vsgl's `direct` is the pixel centre's, Mitsuba's a
pixel's area average, so the direct light is compared twice: as rendered, and with vsgl's
averaged over `--supersample`² sub-pixels (a render that many times larger, block-averaged).

Not run in CI (it needs Mitsuba 3: ``pip install mitsuba drjit`` and libLLVM ≥ 16 for the
default variant). Result and command: experiments/emitter_truth_mitsuba.md.
"""

from __future__ import annotations

import argparse
import pathlib
import sys
import time

import numpy as np

import vsgl
from vsgl.metrics import block_means, block_rmse

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from mitsuba_bridge import camera_of, load_mitsuba, mitsuba_scene  # noqa: E402

SCENE = pathlib.Path(__file__).resolve().parents[2] / "shared" / "scenes" / "CornellBox" / "CornellBox.glb"


def render_vsgl(scene, cam, size: int, spp: int, strategy: str, seed: int) -> dict:
    r = vsgl.Renderer(size, size)
    t = time.perf_counter()
    f = r.render(scene, cam, method="pathtrace", spp=spp, strategy=strategy, seed=seed,
                 aovs=["image", "direct", "indirect", "stderr"])
    out = {a: f.aov(a).astype(np.float64) for a in ("image", "direct", "indirect", "stderr")}
    out["seconds"] = time.perf_counter() - t
    out["emitters"] = f.settings["emitters"]
    return out


def render_mitsuba(mi, scene, cam, size: int, spp: int, seed: int, unit: float) -> dict:
    mscene, _, _, _ = mitsuba_scene(mi, scene, cam, size, min(spp, 1024), camera_roughness=-1.0, unit=unit)
    images = {}
    for depth in (2, 3):
        integrator = mi.load_dict({"type": "path", "max_depth": depth, "rr_depth": 1000, "hide_emitters": False})
        images[depth] = np.array(mi.render(mscene, integrator=integrator, seed=seed, spp=spp), np.float64)
    return {"direct": images[2], "indirect": images[3] - images[2], "image": images[3]}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=int, default=48)
    ap.add_argument("--spp", type=int, default=4096, help="vsgl samples per pixel (default 4096)")
    ap.add_argument("--strategy", default="bidirectional", choices=("camera", "light", "bidirectional"))
    ap.add_argument("--mitsuba-spp", type=int, default=4096, help="Mitsuba samples per pixel per seed (default 4096)")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--supersample", type=int, default=8, help="sub-pixels per side of the area-averaged direct check (default 8)")
    args = ap.parse_args()
    if not SCENE.exists():
        print(f"needs {SCENE} (the shared scenes)", file=sys.stderr)
        return 2
    mi, _ = load_mitsuba(args.variant)
    scene = vsgl.Scene.load(SCENE)
    cam = camera_of(scene)
    # Lengths to a 10-unit diagonal for Mitsuba (experiments/mitsuba_truth.py says why).
    unit = float(np.linalg.norm(np.subtract(*scene.bounds))) / 10.0
    v = render_vsgl(scene, cam, args.size, args.spp, args.strategy, args.seed)
    t = time.perf_counter()
    runs = [render_mitsuba(mi, scene, cam, args.size, args.mitsuba_spp, seed, unit) for seed in (1, 2)]
    mitsuba_s = time.perf_counter() - t
    m = {k: 0.5 * (runs[0][k] + runs[1][k]) for k in runs[0]}
    s = args.supersample
    fine = render_vsgl(scene, cam, args.size * s, max(1, args.spp // (s * s)), "camera", args.seed)
    v["direct (area)"] = block_means(fine["direct"], s)
    m["direct (area)"] = m["direct"]
    runs[0]["direct (area)"], runs[1]["direct (area)"] = runs[0]["direct"], runs[1]["direct"]
    print(f"CornellBox.glb, ceiling emitter only, {args.size}², vsgl pathtrace strategy={args.strategy} spp={args.spp} "
          f"({v['emitters']} emitter triangles, {v['seconds']:.1f} s), Mitsuba 3 path max_depth 2/3, 2 seeds × {args.mitsuba_spp} spp "
          f"({mitsuba_s:.1f} s)")
    print(f"{'part':<14} {'vsgl mean':>12} {'Mitsuba mean':>13} {'ratio':>8} {'block 4x4':>10} {'Mitsuba own':>12} {'vsgl own':>9}")
    for part in ("direct", "direct (area)", "indirect", "image"):
        ratio = v[part].mean() / m[part].mean()
        block = block_rmse(v[part], m[part], 4)
        own_m = block_rmse(runs[0][part], runs[1][part], 4) / 2  # the mean of two seeds: half their difference
        own_v = ""
        if part == "indirect":
            # vsgl's own block error: its stderr² averaged over a block, over the block's pixels.
            var = block_means(v["stderr"] ** 2, 4) / 16
            own_v = f"{np.sqrt(var.sum()) / np.linalg.norm(block_means(m[part], 4)):.4f}"
        print(f"{part:<14} {v[part].mean():>12.6g} {m[part].mean():>13.6g} {ratio:>8.4f} {block:>10.4f} {own_m:>12.4f} {own_v:>9}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
