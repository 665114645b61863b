#!/usr/bin/env python3
"""What does a scene past one storage binding cost each method?

The lit corner over a hidden sheet of tests/scene_builders.py (`corner_over_a_hidden_sheet`):
the same visible surfaces over a sheet of side² vertices under the floor. At side 1830 (3.35M
vertices, 6.69M triangles) the vertices, the BVH's nodes and the triangle corners span several
128 MiB pages and every shader that reads them runs its `STORAGE_PAGED` variant
(docs/scenes.md, "Large scenes"). Per method: the first frame's wall time (upload, and the BVH
build for the traced ones, with `bvh_build_ms` and `bvh_bytes_per_triangle`), then the GPU
total (`frame.timings_ms["total"]`) of `--frames` frames, median, against the same surfaces
over a two-triangle sheet (one page, no page test) alternated with them. The difference is what
the bulk costs the rasteriser and the traversal plus the page tests, not the page tests alone.

On a CPU adapter (lavapipe) only the ratios mean anything; `experiments/gpu_large_scene.sh`
runs it on a GPU.

    .venv/bin/python experiments/large_scene_cost.py [--side 1830] [--size 64x64] [--frames 3]
"""

from __future__ import annotations

import argparse
import pathlib
import statistics
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests"))

import vsgl  # noqa: E402
from scene_builders import corner_over_a_hidden_sheet  # noqa: E402


def settings(method: str, quick: bool) -> dict:
    if method == "pathtrace":
        return dict(spp=1 if quick else 16, strategy="camera")
    if method.endswith("/raytrace"):
        return dict(visibility="raytrace")
    return {}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--side", type=int, default=1830, help="sheet side in vertices (default 1830: 6.69M triangles)")
    ap.add_argument("--size", default="64x64", help="WxH (default 64x64)")
    ap.add_argument("--frames", type=int, default=3, help="timed frames per scene and method (default 3)")
    ap.add_argument("--methods", default="direct,vpl,vsgl,vsgl2,lpv,vsgl/raytrace,pathtrace")
    ap.add_argument("--quick", action="store_true", help="one path-traced sample (lavapipe)")
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.split("x"))
    folder = pathlib.Path(tempfile.mkdtemp())
    t = time.perf_counter()
    large, camera = corner_over_a_hidden_sheet(folder, args.side, name="large.gltf")
    load_s = time.perf_counter() - t
    small, _ = corner_over_a_hidden_sheet(folder, 2, name="small.gltf")
    r = vsgl.Renderer(w, h)
    print(f"hidden sheet of {args.side}^2 vertices: {large.stats['triangles']} triangles, written and loaded in {load_s:.1f} s; "
          f"{w}x{h}, {args.frames} frames each, adapter {r.adapter['name']}")
    print("| method | first frame s (large) | bvh_build_ms | BVH bytes/triangle | GPU ms large (median) | GPU ms small (median) | large / small |")
    print("|---|---|---|---|---|---|---|")
    for entry in args.methods.split(","):
        method = entry.split("/")[0]
        kw = settings(entry, args.quick)
        t = time.perf_counter()
        first = r.render(large, method=method, camera=camera, **kw)
        first_s = time.perf_counter() - t
        build = first.settings.get("bvh_build_ms")
        per_tri = first.settings.get("bvh_bytes_per_triangle")
        times = {"large": [], "small": []}
        # Alternated, so both see the same clocks; each switch re-uploads, outside the GPU total.
        for _ in range(args.frames):
            for name, scene in (("large", large), ("small", small)):
                times[name].append(r.render(scene, method=method, camera=camera, aovs=[], **kw).timings_ms["total"])
        lg, sm = statistics.median(times["large"]), statistics.median(times["small"])
        fmt = lambda x: "—" if x is None else f"{x:.0f}" if x > 10 else f"{x:.1f}"  # noqa: E731
        print(f"| {entry} | {first_s:.1f} | {fmt(build)} | {fmt(per_tri)} | {lg:.2f} | {sm:.2f} | {lg / sm:.2f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
