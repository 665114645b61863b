"""VSGLs against the converged path tracer: does VSGL error fall with N and stay
below VPL's, at equal N and at equal time, on the four caustic and glossy scenes?

    .venv/bin/python experiments/vsgl_vs_pathtracer.py [--scenes ...] [--lights 256,...,65536]
        [--visibility none|raytrace] [--cache DIR] [--out results.json]

For every scene the ground truth is `pathtrace strategy="bidirectional"` (light tracing + camera
paths by MIS) at the scene's spp (cached as .npy in --cache; its own error is printed: the
block error implied by its per-pixel stderr, in the same norm). Every method renders the
`indirect` AOV at the same size, interleave 1, no denoiser, the RSM side left to the default rule
(`rsm_size_for`: 256 up to N = 16384, 512 up to 65536), and is scored by

- `block`: `vsgl.metrics.block_rmse` over 4×4-pixel blocks, ‖x̄ − t̄‖/‖t̄‖ of the block means
  (docs/error.md: block means keep the energy and placement of light and drop single-pixel
  spikes, which decide every per-pixel sum on glossy and caustic scenes);
- `mean`: the image mean over the truth's;
- on caustics_ring, `glow`: the mean indirect light on the floor outside the ring (floor points
  more than 0.7 m from its axis, found from the `normal` and `depth` AOVs and the camera) over
  the truth's there, the issue's "glow outside the caustic";
- the time per frame (`--clock`): on a GPU the frame's GPU time from its timestamps (the wall
  time of a small frame there is mostly the fixed cost of a render() call, alike for every
  method); on a CPU adapter (lavapipe) the wall clock of the render call, where only ratios
  within one run mean anything; the median of 3 for N ≤ 4096, one run above.

With `--time-rounds R` the times that decide the equal-time table are taken apart from the
errors: R rounds, each rendering every configuration with N ≤ `--time-max-lights` once, in turn
(round-robin, so a change in the machine's load during the run falls on every configuration
alike), and the median over rounds with its min–max spread is reported.

The equal-time table takes every VPL time as a budget and pits the best VSGL configuration
(any kernel, any N) that fits in it against that VPL. Prints Markdown tables.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import statistics
import time

import numpy as np

import vsgl
from vsgl.metrics import block_means, block_rmse

SPP = {"cornell_box": 1024, "glossy_cornell": 2048, "caustics_ring": 8192, "mirror_panel": 4096}
# `--variants` names: the default three, and the exact Lambertian point emitter for compact clusters
# (`lambert_lobe="exact_compact"`, docs/methods/vsgl.md "VSGLs") with either kernel, for the diffuse box;
# the papers' diffuse form without the tangent-plane fade (`plane_fade=False`, the default before
# 2026-11-29) with either kernel.
VARIANTS = {"vpl": ("vpl", {}), "vsgl": ("vsgl", {}), "vsgl node": ("vsgl", dict(kernel="node")),
            "vsgl exact_compact": ("vsgl", dict(lambert_lobe="exact_compact")),
            "vsgl node exact_compact": ("vsgl", dict(kernel="node", lambert_lobe="exact_compact")),
            "vsgl no_fade": ("vsgl", dict(lighting="asg", coherence=0.0, plane_fade=False)), "vsgl node no_fade": ("vsgl", dict(kernel="node", lighting="asg", coherence=0.0, plane_fade=False))}


def ground_truth(r: vsgl.Renderer, name: str, scene: vsgl.Scene, spp: int, cache: pathlib.Path) -> tuple[np.ndarray, np.ndarray]:
    path = cache / f"gt_{name}_{spp}.npy"
    err_path = cache / f"gt_{name}_{spp}_stderr.npy"
    if not path.exists():
        t = time.time()
        f = r.render(scene, method="pathtrace", strategy="bidirectional", spp=spp, aovs=["indirect", "stderr"])
        np.save(path, f.aov("indirect").astype(np.float64))
        np.save(err_path, f.aov("stderr").astype(np.float64))
        print(f"<!-- {name}: pathtrace {spp} spp took {time.time() - t:.0f} s -->", flush=True)
    return np.load(path), np.load(err_path)


def floor_outside_ring(r: vsgl.Renderer, scene: vsgl.Scene, radius: float = 0.7) -> np.ndarray:
    """Pixels that see the floor (y = 0) farther than `radius` from the ring's axis."""
    f = r.render(scene, method="direct", aovs=["normal", "depth"])
    normal, depth = f.aov("normal"), f.aov("depth")[..., 0]
    cam = scene.cameras[0]
    eye, fwd, up = (np.array(v, dtype=np.float64) for v in (cam.eye, cam.forward, cam.up))
    right = np.cross(fwd, up)
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    h, w = depth.shape
    t = np.tan(np.radians(cam.fov_y_deg) / 2)
    ys = (1 - 2 * (np.arange(h) + 0.5) / h) * t
    xs = (2 * (np.arange(w) + 0.5) / w - 1) * t * w / h
    dirs = fwd + xs[None, :, None] * right + ys[:, None, None] * up
    points = eye + dirs * depth[..., None]  # depth is the distance along the view axis
    on_floor = (normal[..., 1] > 0.99) & (np.abs(points[..., 1]) < 0.01)
    return on_floor & (np.hypot(points[..., 0], points[..., 2]) > radius)


# Which time decides the equal-time table (`cost`): on a GPU the wall time of a 256² frame is
# mostly the fixed cost of a render() call (submission, readback, Python), the same for every
# method, so the GPU's own time (the frame's timestamp total) is the budget there; on a CPU
# adapter the timestamps do not bracket compute work and the wall time is the only clock.
CLOCK = "wall"


def fmt_time(seconds: float) -> str:
    return f"{seconds * 1e3:.2f} ms" if seconds < 0.1 else f"{seconds:.2f} s"


def timed(r: vsgl.Renderer, scene: vsgl.Scene, repeats: int, **kw) -> tuple[np.ndarray, float, dict]:
    """The indirect AOV, the median cost per frame in seconds (by CLOCK) and the frame's settings."""
    times, frame = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        frame = r.render(scene, aovs=["indirect"], **kw)
        img = frame.aov("indirect").astype(np.float64)
        wall = time.perf_counter() - t
        times.append(frame.timings_ms["total"] * 1e-3 if CLOCK == "gpu" else wall)
    return img, statistics.median(times), dict(frame.settings)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scenes", default="cornell_box,glossy_cornell,caustics_ring,mirror_panel")
    p.add_argument("--lights", default="256,1024,4096,16384,65536")
    p.add_argument("--variants", default="vpl,vsgl,vsgl node", help="comma-separated, from: " + ", ".join(VARIANTS))
    p.add_argument("--visibility", default="none", choices=["none", "raytrace"])
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--brsm", action="store_true", help="also vpl and vsgl with importance='brsm' at N = 1024")
    p.add_argument("--cache", type=pathlib.Path, default=pathlib.Path("out/cache/pathtracer_truths"))
    p.add_argument("--out", type=pathlib.Path, default=None)
    p.add_argument("--time-rounds", type=int, default=0, help="round-robin timing rounds for the equal-time table")
    p.add_argument("--time-max-lights", type=int, default=16384)
    p.add_argument("--clock", choices=["auto", "wall", "gpu"], default="auto",
                   help="time that decides the equal-time table: auto = the GPU's timestamps on a GPU, the wall clock on a CPU adapter")
    a = p.parse_args()
    a.cache.mkdir(parents=True, exist_ok=True)
    lights = [int(n) for n in a.lights.split(",")]
    variants = [v.strip() for v in a.variants.split(",")]
    unknown = [v for v in variants if v not in VARIANTS]
    if unknown:
        p.error(f"--variants: unknown {', '.join(unknown)}; expected names from {', '.join(VARIANTS)}")
    r = vsgl.Renderer(a.size, a.size)
    global CLOCK
    CLOCK = a.clock if a.clock != "auto" else ("wall" if r.adapter.get("device_type") == "Cpu" or not r.adapter.get("timestamps") else "gpu")
    print(f"<!-- adapter {r.adapter.get('name')} ({r.adapter.get('device_type')}); times: {CLOCK} clock -->")
    results = []
    for name in a.scenes.split(","):
        scene = vsgl.scenes.load(name)
        truth, stderr = ground_truth(r, name, scene, SPP[name], a.cache)
        # The truth's own block error in the same norm: its block means' variance is the
        # block-averaged stderr² over the 16 pixels of a block.
        own = float(np.sqrt((block_means(stderr**2, 4) / 16).mean() / (block_means(truth, 4) ** 2).mean()))
        glow_mask = floor_outside_ring(r, scene) if name == "caustics_ring" else None
        print(f"\n### {name} ({a.size}², visibility {a.visibility}; truth: bidirectional pathtrace {SPP[name]} spp, "
              f"its own block error {own:.3f}, mean {truth.mean():.4g})")
        if glow_mask is not None:
            g_err = float(np.sqrt((stderr[glow_mask] ** 2).sum()) / glow_mask.sum())
            print(f"glow region: {int(glow_mask.sum())} floor pixels outside r = 0.7 m; truth there "
                  f"{truth[glow_mask].mean():.3g} ± {g_err:.2g}")
        print("\n| method | " + " | ".join(f"N = {n}" for n in lights) + " |")
        print("|---|" + "---|" * len(lights))
        configs = [(v, n, {}) for v in variants for n in lights]
        if a.brsm:
            configs += [(v + " brsm", 1024, dict(importance="brsm")) for v in ("vpl", "vsgl")]
        rows: dict[str, list[str]] = {}
        for label, n, extra in configs:
            method, kw = VARIANTS[label.replace(" brsm", "")]
            kw = dict(kw, **extra, num_lights=n, interleave=1, denoise=False, visibility=a.visibility)
            if n == lights[0]:
                r.render(scene, method=method, aovs=["indirect"], **dict(kw, num_lights=64))  # compile the pipelines
            img, secs, settings = timed(r, scene, 3 if n <= 4096 else 1, method=method, **kw)
            res = dict(scene=name, variant=label, num_lights=n, visibility=a.visibility, rsm_size=settings.get("rsm_size"),
                       block=block_rmse(img, truth, 4), mean=float(img.mean() / truth.mean()), seconds=secs, clock=CLOCK,
                       truth_own_block=own)
            if glow_mask is not None:
                res["glow"] = float(img[glow_mask].mean() / truth[glow_mask].mean())
            results.append(res)
            cell = f"{res['block']:.3f} ({res['mean']:.2f}×" + (f", glow {res['glow']:.2f}×" if "glow" in res else "") + f"; {fmt_time(secs)})"
            rows.setdefault(label, []).append(cell if not extra else f"N = {n}: {cell}")
            print(f"<!-- {label} N={n}: {cell} -->", flush=True)
        for label, cells in rows.items():
            print(f"| {label} | " + " | ".join(cells) + " |")
        if a.time_rounds:
            round_robin_times(r, scene, [x for x in results if x["scene"] == name], a.time_rounds, a.time_max_lights)
        equal_time(results, name)
    if a.out:
        a.out.write_text(json.dumps(results, indent=1))
    return 0


def round_robin_times(r: vsgl.Renderer, scene: vsgl.Scene, results: list[dict], rounds: int, max_lights: int) -> None:
    """Re-times the configurations with N ≤ max_lights in turn; replaces `seconds` by the median."""
    todo = [x for x in results if x["num_lights"] <= max_lights]
    samples: dict[int, list[float]] = {id(x): [] for x in todo}
    for _ in range(rounds):
        for x in todo:
            method, kw = VARIANTS[x["variant"].replace(" brsm", "")]
            extra = dict(importance="brsm") if "brsm" in x["variant"] else {}
            _, secs, _ = timed(r, scene, 1, method=method, **kw, **extra, num_lights=x["num_lights"], interleave=1,
                               denoise=False, visibility=x["visibility"])
            samples[id(x)].append(secs)
    print(f"\nTimes ({CLOCK} clock), median over {rounds} round-robin rounds [min, max]:\n")
    for x in todo:
        t = samples[id(x)]
        x.update(seconds=statistics.median(t), seconds_min=min(t), seconds_max=max(t), time_rounds=rounds)
        print(f"- {x['variant']} N = {x['num_lights']}: {fmt_time(x['seconds'])} [{fmt_time(min(t))}, {fmt_time(max(t))}]")
    for x in results:
        if x["num_lights"] > max_lights:
            x["seconds_untimed"] = x.pop("seconds")  # one run under other load: not a budget


def equal_time(results: list[dict], scene: str) -> None:
    mine = [r for r in results if r["scene"] == scene and "brsm" not in r["variant"] and "seconds" in r]
    vpls = sorted((r for r in mine if r["variant"] == "vpl"), key=lambda r: r["seconds"])
    vsgls = [r for r in mine if r["variant"].startswith("vsgl")]
    if not vpls or not vsgls:
        return
    print(f"\nEqual time on {scene}: every VPL time is a budget; the best VSGL configuration that fits it")
    print(f"\n| budget ({CLOCK} clock) | vpl | best vsgl within it | vsgl below vpl? |\n|---|---|---|---|")
    for v in vpls:
        fits = [s for s in vsgls if s["seconds"] <= v["seconds"] * 1.05]
        if not fits:
            print(f"| {fmt_time(v['seconds'])} | N = {v['num_lights']}: {v['block']:.3f} | none fits | — |")
            continue
        best = min(fits, key=lambda s: s["block"])
        print(f"| {fmt_time(v['seconds'])} | N = {v['num_lights']}: {v['block']:.3f} | {best['variant']} N = {best['num_lights']}: "
              f"{best['block']:.3f} ({fmt_time(best['seconds'])}) | {'yes' if best['block'] < v['block'] else '**no**'} |")


if __name__ == "__main__":
    raise SystemExit(main())
