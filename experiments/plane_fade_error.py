"""What `plane_fade` (the tangent-plane fade under the papers' diffuse form) changes, against the
every-texel `reference` of the same RSM (unshadowed: exact Lambertian texels, each reflecting into
its own hemisphere; the sum the VSGLs estimate). docs/methods/vsgl.md, "The cluster's tangent plane".

1. The back of a lit plane: a lone quad lit from its front by a point light at several distances,
   seen from behind; its indirect light over the front's direct light (the reference's is 0).
2. The built-in scenes at --size², RSM 128: `vsgl` (N = 4096, interleave 1, no denoiser) and
   `vsgl2`, with and without the fade; block error over 4×4 pixels (mean over the reference's).
   The every-texel reference of the same RSM is the exact sum the VSGLs estimate: it has no
   sampling error of its own.
3. The fade's cost: wall clock of the render call, `vsgl` N = 1024, RSM 128, interleave 1, with
   and without the fade alternating frame by frame (--rounds, the first dropped as warm-up); the
   median of the paired ratios with their quartiles. On a CPU adapter only this ratio means
   anything; on a GPU take `bench`'s timestamps instead (experiments/gpu_blend.sh).

    .venv/bin/python experiments/plane_fade_error.py [--size 64] [--parts 1,2,3] [--rounds 16]"""

from __future__ import annotations

import argparse
import pathlib
import sys
import statistics
import tempfile
import time

import numpy as np

import vsgl
from vsgl.metrics import block_rmse

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests"))
from scene_builders import write_quad  # noqa: E402


def back_of_a_lit_plane(size: int) -> None:
    r = vsgl.Renderer(size, size)
    front = vsgl.Camera.look_at(eye=(0.3, 1.5, 1.5), target=(0, 0, 0), up=(0, 1, 0), fov_y_deg=60)
    back = vsgl.Camera.look_at(eye=(0.3, -1.5, 1.5), target=(0, 0, 0), up=(0, 1, 0), fov_y_deg=60)
    print("| light's distance | " + " | ".join(f"{m} {k} fade={pf}" for m, k in (("vsgl", "integral"), ("vsgl", "node"), ("vsgl2", "")) for pf in (False, True)) + " |")
    with tempfile.TemporaryDirectory() as d:
        quad = write_quad(pathlib.Path(d), half_size=1.0, specular=0.0)
        for dist in (0.05, 0.2, 0.5, 2.0):
            scene = vsgl.Scene.load(quad)
            scene.add_light(vsgl.PointLight(position=(0.0, dist, 0.2), intensity=3.0))
            direct = r.render(scene, camera=front, method="direct", aovs=["direct"]).aov("direct").astype(np.float64).sum()
            cells = []
            for method, kernel in (("vsgl", "integral"), ("vsgl", "node"), ("vsgl2", "")):
                extra = dict(num_lights=4096, interleave=1, denoise=False, kernel=kernel) if method == "vsgl" else {}
                for fade in (False, True):
                    f = r.render(scene, camera=back, method=method, rsm_size=128, lighting="asg", coherence=0.0, plane_fade=fade, aovs=["indirect"], **extra)
                    cells.append(f"{f.aov('indirect').astype(np.float64).sum() / direct:.3f}")
            print(f"| {dist} m | " + " | ".join(cells) + " |", flush=True)


def builtins(size: int) -> None:
    r = vsgl.Renderer(size, size)
    print("| scene | vsgl without | vsgl with | vsgl2 without | vsgl2 with |")
    print("|---|---|---|---|---|")
    for name in vsgl.scenes.names():
        scene = vsgl.scenes.builtin_scene(name)
        kw = dict(rsm_size=128, aovs=["indirect"])
        truth = r.render(scene, method="reference", **kw).aov("indirect").astype(np.float64)
        cells = []
        for method, extra in (("vsgl", dict(num_lights=4096, interleave=1, denoise=False)), ("vsgl2", {})):
            for fade in (False, True):
                img = r.render(scene, method=method, lighting="asg", coherence=0.0, plane_fade=fade, **extra, **kw).aov("indirect").astype(np.float64)
                cells.append(f"{block_rmse(img, truth, 4):.3f} ({img.mean() / truth.mean():.2f}×)")
        print(f"| {name} | " + " | ".join(cells) + " |", flush=True)


def cost(size: int, rounds: int) -> None:
    r = vsgl.Renderer(size, size)
    for name in ("cornell_box", "glossy_cornell"):
        scene = vsgl.scenes.builtin_scene(name)
        times: dict[bool, list[float]] = {True: [], False: []}
        for k in range(rounds):
            for fade in (True, False):
                start = time.perf_counter()
                r.render(scene, method="vsgl", num_lights=1024, rsm_size=128, interleave=1, denoise=False, lighting="asg", coherence=0.0, plane_fade=fade, aovs=["indirect"])
                if k > 0:
                    times[fade].append(time.perf_counter() - start)
        ratios = sorted(a / b for a, b in zip(times[True], times[False]))
        q = statistics.quantiles(ratios, n=4)
        print(f"{name}: with {statistics.median(times[True]) * 1e3:.1f} ms, without {statistics.median(times[False]) * 1e3:.1f} ms; "
              f"paired ratio {statistics.median(ratios):.3f} [{q[0]:.3f}, {q[2]:.3f}] over {len(ratios)} rounds", flush=True)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--parts", default="1,2,3")
    p.add_argument("--rounds", type=int, default=16)
    a = p.parse_args()
    parts = set(a.parts.split(","))
    if "1" in parts:
        back_of_a_lit_plane(a.size)
    if "2" in parts:
        builtins(a.size)
    if "3" in parts:
        cost(a.size, a.rounds)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
