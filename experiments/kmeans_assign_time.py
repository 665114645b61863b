#!/usr/bin/env python3
"""The k-means frame's wall time, one build (alternate two builds in separate
processes, same machine and background):

    VSGL_SCENES=../shared/scenes python experiments/kmeans_assign_time.py PACKAGE_DIR OUT.json

PACKAGE_DIR holds a `vsgl` package (with its built `_vsgl` module) to import instead of the
installed one. Per corpus scene and kernel ("kmeans2d", "kmeans3d"): the median wall time of 9
renders (after 2 warm-up) at 16² (so the RSM's 65k texels, not the shading, fill the frame), RSM
256², N = 1024, interleave 1. (Lavapipe's timestamps put the assignment at 0.04–0.12 ms, less
than its work can take on 2 cores: they do not time it, so the wall time does.) Result:
experiments/kmeans_generation_cost.md, "Grid or radix tree".
"""
import json
import statistics
import sys
import time

sys.path.insert(0, sys.argv[1])
import vsgl  # noqa: E402

r = vsgl.Renderer(16, 16)
out = {}
for name in ("flight_helmet", "cornell_box_original", "furnished_room"):
    scene = vsgl.scenes.corpus_scene(name).scene
    for kernel in ("kmeans2d", "kmeans3d"):
        kw = dict(method="vsgl", kernel=kernel, num_lights=1024, rsm_size=256, interleave=1, aovs=[])
        times = []
        for _ in range(11):
            t = time.perf_counter()
            r.render(scene, **kw)
            times.append((time.perf_counter() - t) * 1e3)
        times = times[2:]
        out[f"{name}/{kernel}"] = statistics.median(times)
        print(name, kernel, round(out[f"{name}/{kernel}"], 3), flush=True)
json.dump(out, open(sys.argv[2], "w"))
