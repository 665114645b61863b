"""Cost and output of `vsgl_shading` in two builds, run alternately in one session.

Timings mean something only as ratios within one run on one machine (lavapipe's pass timestamps
do not bracket compute work, so the wall clock per frame is used). Install the other build's
wheel into its own folder and compare it with the build importable here:

    maturin build --release -o /tmp/base-wheel            # at the base commit
    python -m pip install --no-deps --target /tmp/base /tmp/base-wheel/*.whl
    python experiments/shading_cost_compare.py --base /tmp/base [--new /tmp/new] [--rounds 15]

Both builds run as two long-lived processes that render one frame per request, and the requests
alternate between them frame by frame (which one goes first alternates too), so a change of the
machine's load (other processes on a shared CPU) falls on both alike. Per scene it times `vsgl`
with interleave 1 (every pixel shades all N VSGLs) and interleave 8 (1/64 of the shading work,
the rest unchanged); each round renders every configuration once with each build. The report
gives new/base ratios of the interleave-1 frame per round, their median and interquartile
range, and of the shading pass alone, estimated as the difference interleave 1 − interleave 8
of the per-configuration medians.

`--check` renders a matrix of shading modes (diffuse, lighting, lambert_lobe, kernel="node",
visibility) with both builds and prints the largest relative difference of each indirect AOV
(|new − base| / max|base| over the image): 0 means bit-identical.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

import numpy as np

# Modes the shading pass branches on (vsgl2 shades with the same pass); each is one render with
# both builds under --check.
CHECK_MODES: list[tuple[str, dict]] = [
    ("cornell_box", {}),
    ("cornell_box", {"lambert_lobe": "papers"}),
    ("cornell_box", {"lambert_lobe": "exact_compact"}),
    ("cornell_box", {"diffuse": "accurate"}),
    ("cornell_box", {"diffuse": "sg_product"}),
    ("cornell_box", {"kernel": "node"}),
    ("cornell_box", {"kernel": "node", "lambert_lobe": "exact_compact", "diffuse": "accurate"}),
    ("cornell_box", {"visibility": "raytrace"}),
    ("cornell_box", {"visibility": "ism"}),
    ("glossy_cornell", {}),
    ("glossy_cornell", {"lighting": "accurate"}),
    ("glossy_cornell", {"diffuse": "sg_product", "lambert_lobe": "papers"}),
    ("glossy_cornell", {"kernel": "node", "lambert_lobe": "exact_compact"}),
    ("glossy_cornell", {"visibility": "raytrace"}),
    ("glossy_cornell", {"visibility": "ism", "lighting": "accurate"}),
    ("mirror_panel", {}),
    ("caustics_ring", {"diffuse": "accurate"}),
    ("glossy_cornell", {"method": "vsgl2"}),
    ("cornell_box", {"method": "vsgl2", "visibility": "raytrace"}),
]


def child(args: argparse.Namespace) -> None:
    """Runs inside one build's process: timings or the check renders, as JSON / npz."""
    import time

    import vsgl

    w, h = (int(x) for x in args.size.split("x"))
    r = vsgl.Renderer(width=w, height=h)
    if args.child == "serve":
        scenes = {}
        print("ready", flush=True)
        for line in sys.stdin:
            name, k = line.split()
            if name not in scenes:
                scenes[name] = vsgl.scenes.load(name)
            t0 = time.perf_counter()
            r.render(scenes[name], method="vsgl", num_lights=args.lights, rsm_size=args.rsm, interleave=int(k))
            print(time.perf_counter() - t0, flush=True)
        return
    else:
        arrays = {}
        for i, (name, opts) in enumerate(CHECK_MODES):
            opts = dict(opts)
            method = opts.pop("method", "vsgl")
            sizes = {"rsm_size": 48} if method == "vsgl2" else {"num_lights": 64, "rsm_size": 64, "interleave": 1}
            f = r.render(vsgl.scenes.load(name), method=method, **sizes, **opts)
            for aov in ("indirect_diffuse", "indirect_specular"):
                arrays[f"{i}/{aov}"] = np.asarray(f.aov(aov), dtype=np.float32)
        np.savez(args.child_out, **arrays)


def run_child(path: str | None, extra: list[str]) -> subprocess.CompletedProcess:
    env = dict(os.environ)
    if path:
        env["PYTHONPATH"] = path + os.pathsep + env.get("PYTHONPATH", "")
    env.setdefault("XDG_RUNTIME_DIR", "/tmp")
    return subprocess.run([sys.executable, __file__, *extra], env=env, capture_output=True, text=True, check=True)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--base", required=False, help="folder holding the base build's `vsgl` package")
    ap.add_argument("--new", default=None, help="folder holding the new build (default: the one importable here)")
    ap.add_argument("--rounds", type=int, default=15)
    ap.add_argument("--warmup", type=int, default=2, help="untimed frames per configuration and build first")
    ap.add_argument("--size", default="64x64")
    ap.add_argument("--lights", type=int, default=1024)
    ap.add_argument("--rsm", type=int, default=128)
    ap.add_argument("--scenes", default="cornell_box,diffuse_cornell,glossy_cornell")
    ap.add_argument("--check", action="store_true", help="compare the indirect AOVs of the mode matrix instead of timing")
    ap.add_argument("--child", choices=["serve", "check"], help=argparse.SUPPRESS)
    ap.add_argument("--child-out", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(args)
        return 0
    if not args.base:
        ap.error("--base is required")
    common = ["--size", args.size, "--lights", str(args.lights), "--rsm", str(args.rsm), "--scenes", args.scenes]
    if args.check:
        with tempfile.TemporaryDirectory() as tmp:
            files = {}
            for label, path in (("base", args.base), ("new", args.new)):
                files[label] = os.path.join(tmp, f"{label}.npz")
                run_child(path, ["--child", "check", "--child-out", files[label], *common])
            base, new = np.load(files["base"]), np.load(files["new"])
            worst = 0.0
            for key in base.files:
                i, aov = key.split("/")
                scale = float(np.abs(base[key]).max())
                diff = float(np.abs(new[key] - base[key]).max())
                rel = diff / scale if scale > 0 else diff
                worst = max(worst, rel)
                name, opts = CHECK_MODES[int(i)]
                print(f"{name:15s} {json.dumps(opts):70s} {aov:18s} max|base| {scale:.3e}  max rel diff {rel:.2e}")
            print(f"largest relative difference: {worst:.2e}")
        return 0
    servers = {label: start_server(path, common) for label, path in (("base", args.base), ("new", args.new))}
    configs = [(name, k) for name in args.scenes.split(",") for k in (1, 8)]
    for name, k in configs:
        for _ in range(args.warmup):
            for server in servers.values():
                render_once(server, name, k)
    times: dict[tuple[str, str, int], list[float]] = {}
    for rnd in range(args.rounds):
        for name, k in configs:
            order = ["base", "new"] if rnd % 2 == 0 else ["new", "base"]
            for label in order:
                times.setdefault((label, name, k), []).append(render_once(servers[label], name, k))
        print(f"round {rnd}: " + "; ".join(f"{name} k{k} base {times[('base', name, k)][-1] * 1e3:.0f} ms new {times[('new', name, k)][-1] * 1e3:.0f} ms" for name, k in configs), flush=True)
    for server in servers.values():
        server.stdin.close()
        server.wait()
    print(f"new/base ratio over {args.rounds} rounds ({args.size}, N = {args.lights}, RSM {args.rsm})")
    for name in args.scenes.split(","):
        ratios = [n / b for n, b in zip(times[("new", name, 1)], times[("base", name, 1)])]
        q = statistics.quantiles(ratios, n=4) if len(ratios) >= 2 else [ratios[0]] * 3
        med = {key: statistics.median(v) for key, v in times.items() if key[1] == name}
        shading = (med[("new", name, 1)] - med[("new", name, 8)]) / (med[("base", name, 1)] - med[("base", name, 8)])
        print(f"  {name:16s} interleave-1 frame {statistics.median(ratios):.3f} (IQR {q[0]:.3f}-{q[2]:.3f}); "
              f"shading (k1 - k8 of medians) {shading:.3f}; base k1 {med[('base', name, 1)] * 1e3:.0f} ms, k8 {med[('base', name, 8)] * 1e3:.0f} ms")
    return 0


def start_server(path: str | None, common: list[str]) -> subprocess.Popen:
    env = dict(os.environ)
    if path:
        env["PYTHONPATH"] = path + os.pathsep + env.get("PYTHONPATH", "")
    env.setdefault("XDG_RUNTIME_DIR", "/tmp")
    proc = subprocess.Popen([sys.executable, __file__, "--child", "serve", *common], env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "ready"
    return proc


def render_once(server: subprocess.Popen, name: str, k: int) -> float:
    server.stdin.write(f"{name} {k}\n")
    server.stdin.flush()
    return float(server.stdout.readline())


if __name__ == "__main__":
    sys.exit(main())
