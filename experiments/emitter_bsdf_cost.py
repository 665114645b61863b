#!/usr/bin/env python3
"""What do the path tracer's BSDF-sampled emitter rays cost? One build's timings, to alternate
with another build's in separate processes (same machine, same background):

    python experiments/emitter_bsdf_cost.py PACKAGE_DIR OUT.json

PACKAGE_DIR holds a `vsgl` package (with its built `_vsgl` module) to import instead of the
installed one. Per scene and strategy: the median wall time of 3 renders (64², spp 16, after
one warm render) and the image mean. Scenes: CornellBox.glb lit by its ceiling lamp (from the
shared scene folder, $VSGL_SCENES or ../shared/scenes) and tests/scene_builders.py's glossy floor
under a small emitter at roughness 0.05. Result: experiments/emitter_bsdf_sampling.md, "Cost".
"""
import json
import os
import pathlib
import sys
import tempfile
import time

pkg, out = sys.argv[1], sys.argv[2]
repo = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, pkg)
sys.path.insert(0, str(repo / "tests"))
import vsgl  # noqa: E402
from scene_builders import GLOSSY_FLOOR_VIEW, glossy_floor_under_small_emitter  # noqa: E402

shared = pathlib.Path(os.environ.get("VSGL_SCENES", repo.parent / "shared" / "scenes"))
d = pathlib.Path(tempfile.mkdtemp())
r = vsgl.Renderer(width=64, height=64)
box = vsgl.Scene.load(shared / "CornellBox" / "CornellBox.glb")
floor = glossy_floor_under_small_emitter(d, 0.05)
res = {}
for name, scene, cam in [("cornellbox_glb", box, None), ("glossy_floor", floor, GLOSSY_FLOOR_VIEW)]:
    for strategy in ("camera", "bidirectional"):
        kw = dict(spp=16, seed=3, strategy=strategy, aovs=["image"])
        if cam is not None:
            kw["camera"] = cam
        f = r.render(scene, method="pathtrace", **kw)
        ts = []
        for _ in range(3):
            t = time.perf_counter(); f = r.render(scene, method="pathtrace", **kw); ts.append(time.perf_counter() - t)
        res[f"{name}/{strategy}"] = [sorted(ts)[1], float(f.aov("image").mean())]
        print(name, strategy, res[f"{name}/{strategy}"], flush=True)
json.dump(res, open(out, "w"))
