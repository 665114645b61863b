"""Error of `lambert_lobe=` (docs/methods/vsgl.md, "VSGLs": Lambert lobes), the three tables of the
section, for `vsgl` at interleave 1 without the denoiser:

1. cornell_box 64², RSM 128, against the every-texel `reference` of the same RSM (exact
   Lambertian texels, unshadowed: the sum the VSGLs estimate), relRMSE / 4×4-block error (mean);
2. cornell_box 64², `visibility="raytrace"`, against the bidirectional path tracer (1024 spp,
   cached in --cache as experiments/vsgl_vs_pathtracer.py does; its own block error printed), block
   error (mean), with `vpl` for comparison;
3. lit_floor_corner 32², RSM 128, against a bidirectional path tracer of 4096 spp (its own
   relRMSE from its stderr printed), relRMSE (mean).

    .venv/bin/python experiments/lambert_lobe_error.py [--parts 1,2,3] [--cache out/cache/pathtracer_truths]
"""

from __future__ import annotations

import argparse
import pathlib
import sys
import tempfile

import numpy as np

import vsgl
from vsgl.metrics import block_means, block_rmse, rel_rmse

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "tests"))
from vsgl_vs_pathtracer import ground_truth  # noqa: E402
from scene_builders import lit_floor_corner  # noqa: E402

FORMS = ("papers", "hemisphere", "exact_compact")


def row(label: str, cells: list[str]) -> None:
    print(f"| {label} | " + " | ".join(cells) + " |")


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--parts", default="1,2,3")
    p.add_argument("--cache", type=pathlib.Path, default=pathlib.Path("out/cache/pathtracer_truths"))
    a = p.parse_args()
    parts = {int(x) for x in a.parts.split(",")}
    a.cache.mkdir(parents=True, exist_ok=True)
    vsgl_kw = dict(method="vsgl", interleave=1, denoise=False, aovs=["indirect"])
    if 1 in parts:
        lights = [256, 1024, 4096, 16384]
        r = vsgl.Renderer(64, 64)
        scene = vsgl.scenes.cornell_box()
        ref = r.render(scene, method="reference", rsm_size=128, aovs=["indirect"]).aov("indirect").astype(np.float64)
        print("\n1. cornell_box 64², RSM 128, against the same-RSM every-texel reference: relRMSE / block (mean)\n")
        print("| `lambert_lobe` | " + " | ".join(f"N = {n}" for n in lights) + " |\n|---|" + "---|" * len(lights))
        for form in FORMS:
            cells = []
            for n in lights:
                img = r.render(scene, num_lights=n, rsm_size=128, lambert_lobe=form, **vsgl_kw).aov("indirect").astype(np.float64)
                cells.append(f"{rel_rmse(img, ref):.3f} / {block_rmse(img, ref, 4):.3f} ({img.mean() / ref.mean():.2f}×)")
            row(f'`"{form}"`', cells)
    if 2 in parts:
        lights = [256, 1024, 4096]
        r = vsgl.Renderer(64, 64)
        scene = vsgl.scenes.cornell_box()
        truth, stderr = ground_truth(r, "cornell_box", scene, 1024, a.cache)
        own = float(np.sqrt((block_means(stderr**2, 4) / 16).mean() / (block_means(truth, 4) ** 2).mean()))
        print(f"\n2. cornell_box 64², visibility raytrace, against pathtrace 1024 spp (own block error {own:.3f}): block (mean)\n")
        print("| method | " + " | ".join(f"N = {n}" for n in lights) + " |\n|---|" + "---|" * len(lights))
        for label, kw in [("`vpl`", dict(method="vpl"))] + [(f'`vsgl` `"{f}"`', dict(method="vsgl", lambert_lobe=f)) for f in FORMS]:
            cells = []
            for n in lights:
                img = r.render(scene, num_lights=n, interleave=1, denoise=False, visibility="raytrace", aovs=["indirect"], **kw).aov("indirect").astype(np.float64)
                cells.append(f"{block_rmse(img, truth, 4):.3f} ({img.mean() / truth.mean():.2f}×)")
            row(label, cells)
    if 3 in parts:
        lights = [1024, 4096]
        r = vsgl.Renderer(32, 32)
        scene, cam = lit_floor_corner(pathlib.Path(tempfile.mkdtemp()))
        path = a.cache / "gt_lit_floor_corner_32_4096.npz"
        if not path.exists():
            f = r.render(scene, camera=cam, method="pathtrace", strategy="bidirectional", spp=4096, aovs=["indirect", "stderr"])
            np.savez(path, truth=f.aov("indirect"), stderr=f.aov("stderr"))
        gt = np.load(path)
        truth, stderr = gt["truth"].astype(np.float64), gt["stderr"].astype(np.float64)
        own = float(np.sqrt((stderr**2).mean() / (truth**2).mean()))
        ref = r.render(scene, camera=cam, method="reference", rsm_size=128, aovs=["indirect"]).aov("indirect")
        print(f"\n3. lit_floor_corner 32², RSM 128, against pathtrace 4096 spp (own relRMSE {own:.3f}; "
              f"the reference {rel_rmse(ref, truth):.3f}): relRMSE (mean)\n")
        print("| `lambert_lobe` | " + " | ".join(f"N = {n}" for n in lights) + " |\n|---|" + "---|" * len(lights))
        for form in FORMS:
            cells = []
            for n in lights:
                img = r.render(scene, camera=cam, num_lights=n, rsm_size=128, lambert_lobe=form, **vsgl_kw).aov("indirect").astype(np.float64)
                cells.append(f"{rel_rmse(img, truth):.3f} ({img.mean() / truth.mean():.2f}×)")
            row(f'`"{form}"`', cells)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
