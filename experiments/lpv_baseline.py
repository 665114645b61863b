"""How far light propagation volumes (method="lpv") are from the every-texel reference, and
what they cost next to the poster's one diffuse VSGL (vsgl2), on lavapipe.

Part 1, error: for the built-in rooms and the corpus scenes (those whose files are present),
mean indirect diffuse light over the `reference` of the same RSM (what LPV injects: its own
error against that target is 0) and the block error (4×4 blocks, relative RMS) for
lpv_iterations 8 … 64 (default: lpv_grid = 32), with and without occlusion, and two cascades.
Part 2, cost: the frame's GPU time (median of 7 back-to-back frames after 2 warm-up frames) and
the memory its buffers use (frame.memory_bytes, the RSM counted on both sides), lpv's defaults
against vsgl2 on the diffuse Cornell box, in the same run (only ratios mean anything on a CPU).

    VSGL_SCENES=../shared/scenes .venv/bin/python experiments/lpv_baseline.py [--size 128] [--rsm 128]
"""

from __future__ import annotations

import argparse
import statistics

import numpy as np

import vsgl
from vsgl.metrics import block_rmse

VARIANTS = [
    ("iterations 8", dict(lpv_iterations=8)),
    ("iterations 16", dict(lpv_iterations=16)),
    ("default (32)", dict()),
    ("iterations 64", dict(lpv_iterations=64)),
    ("no occlusion", dict(lpv_occlusion=False)),
    ("2 cascades", dict(lpv_cascades=2)),
]


def scenes():
    for name in ["diffuse_cornell", "cornell_box", "furnished_room", "atrium"]:
        yield name, vsgl.scenes.builtin_scene(name)
    for name in ["cornell_box_original", "flight_helmet", "cornell_box_mm"]:
        if vsgl.scenes.corpus_available(name):
            yield name, vsgl.scenes.corpus_scene(name).scene


def error_table(r, rsm: int) -> None:
    print(f"{'scene':22s} {'variant':15s} {'mean/ref':>9s} {'block 4x4':>10s}")
    for name, scene in scenes():
        ref = r.render(scene, method="reference", rsm_size=rsm, aovs=["indirect_diffuse"]).aov("indirect_diffuse").astype(np.float64)
        for label, opts in VARIANTS:
            f = r.render(scene, method="lpv", rsm_size=rsm, aovs=["indirect_diffuse"], **opts)
            lpv = f.aov("indirect_diffuse").astype(np.float64)
            print(f"{name:22s} {label:15s} {lpv.mean() / ref.mean():9.3f} {block_rmse(lpv, ref, 4):10.3f}", flush=True)


def frame_cost(r, scene, method: str, **opts) -> tuple[float, int, dict]:
    for _ in range(2):
        r.render(scene, method=method, aovs=["image"], **opts)
    times = []
    for _ in range(7):
        f = r.render(scene, method=method, aovs=["image"], **opts)
        times.append(f.timings_ms["total"])
    return statistics.median(times), sum(f.memory_bytes.values()), f.timings_ms


def cost_table(r, rsm: int) -> None:
    scene = vsgl.scenes.diffuse_cornell()
    lpv_ms, lpv_bytes, lpv_passes = frame_cost(r, scene, "lpv", rsm_size=rsm)
    vsgl2_ms, vsgl2_bytes, _ = frame_cost(r, scene, "vsgl2", rsm_size=rsm)
    volumes = {k: v for k, v in r.render(scene, method="lpv", rsm_size=rsm).memory_bytes.items() if k.startswith("lpv_")}
    sums = {k: v for k, v in r.render(scene, method="vsgl2", rsm_size=rsm).memory_bytes.items() if k.startswith("vsgl2_")}
    print(f"diffuse_cornell, rsm {rsm}: lpv {lpv_ms:.2f} ms, vsgl2 {vsgl2_ms:.2f} ms: lpv/vsgl2 = {lpv_ms / vsgl2_ms:.2f} (poster, GTX 770, 32³ x 4 cascades: 4.5)")
    print(f"  memory (all frame buffers, RSM included on both sides): lpv {lpv_bytes} B, vsgl2 {vsgl2_bytes} B: {lpv_bytes / vsgl2_bytes:.2f} (poster: 9.7)")
    print(f"  the methods' own buffers (RSM left out of both): lpv {sum(volumes.values())} B, vsgl2 {sum(sums.values())} B")
    print(f"  lpv's: {volumes}")
    print(f"  vsgl2's: {sums}")
    print("  lpv passes (ms):", {k: round(v, 3) for k, v in lpv_passes.items()})


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--size", type=int, default=128)
    p.add_argument("--rsm", type=int, default=128)
    a = p.parse_args()
    r = vsgl.Renderer(width=a.size, height=a.size)
    print(f"adapter {r.adapter_name if hasattr(r, 'adapter_name') else r}, {a.size}², RSM {a.rsm}²")
    error_table(r, a.rsm)
    cost_table(r, a.rsm)


if __name__ == "__main__":
    main()
