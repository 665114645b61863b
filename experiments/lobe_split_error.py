"""VSGL light split by the receiver's lobe against the path tracer's own split (experiments/sg_lighting_forms.md,
"SG lighting" and "Open: shadow rays take too much of the VSGLs' specular light").

    .venv/bin/python experiments/lobe_split_error.py [--scene glossy_cornell] [--size 64] [--spp 2048]
        [--lights 1024,4096] [--shadow-lights 256,4096,16384]

Part 1: `vsgl` with lighting="asg", diffuse="accurate", lighting="accurate" and "blend", unshadowed, each
lobe's image mean over the truth's and its 4x4-block error (vsgl.metrics.block_rmse), against
`pathtrace strategy="bidirectional"` (cached in --cache). Part 2: how much of each lobe
visibility="raytrace" keeps (shadowed mean over unshadowed mean) for vpl, vsgl and node VSGLs.
Lavapipe takes about 80 s for the 64² truth and 2–3 min for each N = 16384 row with shadow rays."""

from __future__ import annotations

import argparse
import pathlib

import numpy as np

import vsgl
from vsgl.metrics import block_rmse


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default="glossy_cornell")
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--spp", type=int, default=2048)
    p.add_argument("--lights", default="1024,4096")
    p.add_argument("--shadow-lights", default="256,4096,16384")
    p.add_argument("--cache", type=pathlib.Path, default=pathlib.Path("out/cache/lobe_split_truths"))
    a = p.parse_args()
    scene = vsgl.scenes.load(a.scene)
    r = vsgl.Renderer(a.size, a.size)
    a.cache.mkdir(parents=True, exist_ok=True)
    path = a.cache / f"truth_{a.scene}_{a.size}_{a.spp}.npz"
    if not path.exists():
        f = r.render(scene, method="pathtrace", strategy="bidirectional", spp=a.spp, aovs=["indirect_diffuse", "indirect_specular"])
        np.savez(path, d=f.aov("indirect_diffuse"), s=f.aov("indirect_specular"))
    truth = np.load(path)
    td, ts = truth["d"].astype(np.float64), truth["s"].astype(np.float64)
    print(f"truth ({a.scene} {a.size}², {a.spp} spp): diffuse mean {td.mean():.5g}, specular mean {ts.mean():.5g}\n")
    print("| N | form | diffuse mean | diffuse block | specular mean | specular block |\n|---|---|--:|--:|--:|--:|")
    for n in (int(x) for x in a.lights.split(",")):
        for form, kw in (("asg", dict(lighting="asg")), ("asg, diffuse=accurate", dict(lighting="asg", diffuse="accurate")), ("accurate", dict(lighting="accurate")), ("blend", dict(lighting="blend"))):
            f = r.render(scene, method="vsgl", num_lights=n, interleave=1, denoise=False, aovs=["indirect_diffuse", "indirect_specular"], **kw)
            d, s = f.aov("indirect_diffuse").astype(np.float64), f.aov("indirect_specular").astype(np.float64)
            print(f"| {n} | {form} | {d.mean() / td.mean():.3f}× | {block_rmse(d, td, 4):.3f} | {s.mean() / ts.mean():.3f}× | {block_rmse(s, ts, 4):.3f} |", flush=True)
    print("\nShadowed over unshadowed image mean, per lobe:\n\n| method | N | diffuse | specular |\n|---|--:|--:|--:|")
    # The every-texel reference casts each texel's own exact shadow ray: the share of light that
    # visibility should keep at this RSM. The virtual lights follow.
    rows = [(f"reference RSM {side}", "reference", dict(rsm_size=side), "every texel") for side in (64, 128)]
    rows += [(label, method, dict(kw, num_lights=int(n), interleave=1, denoise=False), n)
             for label, method, kw in (("vpl", "vpl", {}), ("vsgl", "vsgl", {}), ("vsgl node", "vsgl", dict(kernel="node")))
             for n in a.shadow_lights.split(",")]
    # RSM 64 with N = 4·64²: every node VSGL is one texel, its shadow ray aimed at that texel's
    # point exactly as a VPL's is; what differs from the VPL row is only how each pair is weighted.
    single = dict(num_lights=16384, rsm_size=64, interleave=1, denoise=False)
    rows += [("vpl, RSM 64", "vpl", single, 16384), ("vsgl node, RSM 64 (one texel each)", "vsgl", dict(single, kernel="node"), 16384)]
    for label, method, kw, n in rows:
        means = {}
        for vis in ("none", "raytrace"):
            f = r.render(scene, method=method, visibility=vis, aovs=["indirect_diffuse", "indirect_specular"], **kw)
            means[vis] = (f.aov("indirect_diffuse").mean(), f.aov("indirect_specular").mean())
        print(f"| {label} | {n} | {means['raytrace'][0] / means['none'][0]:.3f} | {means['raytrace'][1] / means['none'][1]:.3f} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
