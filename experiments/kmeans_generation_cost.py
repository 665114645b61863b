"""What k-means clustering costs next to filtered importance sampling, and how far each is from
the every-texel reference, on lavapipe: the 2016 paper's Tables 1-2 as same-run ratios.

For each scene, `vsgl` at N VSGLs on an RSM of side R (the paper: 1024 VSGLs on a 512² RSM),
interleave 1, no denoiser, with kernel="integral" (the paper's filtered importance sampling),
"node", "kmeans2d" and "kmeans3d" (and kmeans3d with 4 Lloyd iterations): the generation time
(median and quartiles over frames after warm-up, the kernels alternated frame by frame, GPU timestamps) of what each kernel needs beyond the shared
RSM and moments — FIS: moment_mips + vsgl_gen; k-means: kmeans_centres + kmeans_grid +
kmeans_assign + kmeans_sort + kmeans_sum (pdf_mips, which both need, is left out of both) —
its ratio to FIS's, the dispatches, and the mean indirect diffuse / specular over the reference
of the same RSM with the block error (4x4 blocks, relative RMS): the error column the paper's
tables lack. The reference is the every-texel sum the clusters stand for, so its own error
against that target is 0. Only the ratios mean anything on a CPU adapter.

    .venv/bin/python experiments/kmeans_generation_cost.py [--size 128] [--rsm 256] [--n 1024] [--frames 15]
"""

from __future__ import annotations

import argparse
import statistics

import vsgl
from vsgl.metrics import block_rmse

KERNELS = [
    ("integral (FIS)", dict(kernel="integral")),
    ("node", dict(kernel="node")),
    ("kmeans2d", dict(kernel="kmeans2d")),
    ("kmeans3d", dict(kernel="kmeans3d")),
    ("kmeans3d, 4 iterations", dict(kernel="kmeans3d", kmeans_iterations=4)),
]
FIS_PASSES = ("moment_mips", "vsgl_gen")
KMEANS_PASSES = ("kmeans_centres", "kmeans_grid", "kmeans_assign", "kmeans_sort", "kmeans_sum")
# [Tok16] Table 1 (Crytek Sponza) and Table 2 (the other scene), GTX 970, 1920x1088, RSM 512²:
# generation ms of FIS, k-means 2D and k-means 3D.
PAPER = {"Table 1": (2.33, 16.6, 21.8), "Table 2": (2.25, 20.4, 37.7)}


def scenes():
    for name in ["glossy_cornell", "furnished_room"]:
        yield name, vsgl.scenes.builtin_scene(name)
    for name in ["cornell_box_original", "flight_helmet"]:
        if vsgl.scenes.corpus_available(name):
            yield name, vsgl.scenes.corpus_scene(name).scene


def generation_ms(frame) -> float:
    passes = KMEANS_PASSES if "kmeans_sort" in frame.timings_ms else FIS_PASSES
    return sum(frame.timings_ms.get(p, 0.0) for p in passes)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--rsm", type=int, default=256)
    ap.add_argument("--n", type=int, default=1024)
    ap.add_argument("--frames", type=int, default=15)
    a = ap.parse_args()
    r = vsgl.Renderer(width=a.size, height=a.size)
    print(f"adapter: {r.adapter['name']}; {a.size}², RSM {a.rsm}², N = {a.n}, interleave 1; median and quartiles of {a.frames} frames after 2 warm-up, the kernels alternated")
    for table, (fis, k2, k3) in PAPER.items():
        print(f"paper {table}: k-means 2D / FIS {k2 / fis:.1f}x, 3D / FIS {k3 / fis:.1f}x")
    aovs = ["indirect_diffuse", "indirect_specular"]
    for name, scene in scenes():
        ref = r.render(scene, method="reference", rsm_size=a.rsm, aovs=aovs)
        ref_d, ref_s = (float(ref.aov(x).mean()) for x in aovs)
        print(f"\n{name}")
        print(f"  {'kernel':24s} {'gen ms':>9s} {'quartiles':>15s} {'/ FIS':>7s} {'dispatches':>10s} {'diffuse':>8s} {'specular':>8s} {'block':>7s}")
        runs = [dict(method="vsgl", num_lights=a.n, rsm_size=a.rsm, interleave=1, denoise=False, **kw) for _, kw in KERNELS]
        for common in runs:
            for _ in range(2):
                r.render(scene, aovs=[], **common)
        # Alternated frame by frame, so a drift of the machine's speed reaches every kernel alike.
        times: list[list[float]] = [[] for _ in runs]
        for _ in range(a.frames):
            for i, common in enumerate(runs):
                times[i].append(generation_ms(r.render(scene, aovs=[], **common)))
        fis_ms = statistics.median(times[0])
        for (label, _), common, t in zip(KERNELS, runs, times):
            f = r.render(scene, aovs=aovs, **common)
            q1, med, q3 = statistics.quantiles(t, n=4)
            d = float(f.aov("indirect_diffuse").mean()) / ref_d if ref_d > 0 else float("nan")
            s = float(f.aov("indirect_specular").mean()) / ref_s if ref_s > 0 else float("nan")
            block = block_rmse(f.aov("indirect_diffuse") + f.aov("indirect_specular"), ref.aov("indirect_diffuse") + ref.aov("indirect_specular"), block=4)
            # FIS: one moment_mips dispatch per mip level, then vsgl_gen.
            dispatches = f.settings.get("kmeans_dispatches", a.rsm.bit_length() - 1 + 1)
            print(f"  {label:24s} {med:9.3f} {q1:7.3f}-{q3:<7.3f} {med / fis_ms:7.2f} {dispatches:>10} {d:8.3f} {s:8.3f} {block:7.3f}")

if __name__ == "__main__":
    main()
