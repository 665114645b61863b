"""Same-run error and wall time of the virtual-light visibility modes on the scenes of
tests/test_visibility.py: the unlit room's indirect light against `pathtrace` (512 spp) for
visibility="none" | "raytrace" | "ism", the unoccluded corner's light kept by "ism", and the
wall time per render() of "ism" against "raytrace" at two image sizes. Ratios measured in one
run are what to compare on a CPU adapter (experiments/README.md); docs/methods/visibility.md quotes a lavapipe run.

    XDG_RUNTIME_DIR=/tmp .venv/bin/python experiments/visibility_lavapipe.py
"""

from __future__ import annotations

import pathlib
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "tests"))
import vsgl  # noqa: E402
from test_visibility import OPTIONS, _corner, _indirect, _two_rooms  # noqa: E402


def wall_ms(r, scene, cam, **opts) -> float:
    r.render(scene, camera=cam, **opts)  # warm: pipelines, BVH, point set
    times = []
    for _ in range(3):
        t = time.perf_counter()
        r.render(scene, camera=cam, **opts)
        times.append(time.perf_counter() - t)
    return float(np.median(times)) * 1e3


def main() -> None:
    tmp = pathlib.Path(tempfile.mkdtemp())
    scene, cam = _two_rooms(tmp)
    r = vsgl.Renderer(width=32, height=32)
    truth = _indirect(r.render(scene, camera=cam, method="pathtrace", spp=512, seed=1)).mean()
    print("two rooms, 32x32: unlit room's indirect light / pathtrace")
    for m in ["reference", "vpl", "vsgl", "vsgl2"]:
        row = {vis: _indirect(r.render(scene, camera=cam, method=m, visibility=vis, **OPTIONS[m])).mean() / truth for vis in ["none", "raytrace", "ism"]}
        print(f"  {m:9s} " + "  ".join(f"{k} {v:.3f}" for k, v in row.items()))
    corner, ccam = _corner(tmp)
    r24 = vsgl.Renderer(width=24, height=24)
    print("unoccluded corner, 24x24: ism / none")
    for m in ["reference", "vpl", "vsgl"]:
        a = r24.render(corner, camera=ccam, method=m, visibility="none", **OPTIONS[m]).aov("indirect").astype(np.float64)
        b = r24.render(corner, camera=ccam, method=m, visibility="ism", **OPTIONS[m]).aov("indirect").astype(np.float64)
        print(f"  {m:9s} mean {b.sum() / a.sum():.4f}  largest pixel change {np.abs(b - a).max() / a.max():.3f} of the maximum")
    print("wall ms per render() (median of 3), two rooms")
    for size in (32, 128):
        rs = vsgl.Renderer(width=size, height=size)
        for m in ["reference", "vpl", "vsgl"] if size == 32 else ["vpl", "vsgl"]:
            opts = dict(OPTIONS[m], method=m)
            if m == "vpl":
                opts["interleave"] = 8
            t = {vis: wall_ms(rs, scene, cam, visibility=vis, **opts) for vis in ["none", "raytrace", "ism"]}
            print(f"  {size}x{size} {m:9s} " + "  ".join(f"{k} {v:.0f}" for k, v in t.items()) + f"  ism/raytrace {t['ism'] / t['raytrace']:.2f}")


if __name__ == "__main__":
    main()
