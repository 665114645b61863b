"""Cost and output of `vsgl_shading` in two builds, run alternately in one session.

Timings mean something only as ratios within one run on one machine (lavapipe's pass timestamps
do not bracket compute work, so the wall clock per frame is used). Install the other build's
wheel into its own folder and compare it with the build importable here:

    maturin build --release -o /tmp/base-wheel            # at the base commit
    python -m pip install --no-deps --target /tmp/base /tmp/base-wheel/*.whl
    python scripts/shading_cost_compare.py --base /tmp/base [--new /tmp/new] --rounds 5

Each round renders every scene with both builds in separate processes, alternating which goes
first, and records the median wall clock per frame of `vsgl` with interleave 1 (every pixel
shades all N VSGLs) and with interleave 8 (1/64 of the shading work, the rest unchanged). The
difference of the two estimates the shading pass alone; the report gives new/base ratios of the
frame and of that difference per round, and their median and range.

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
    if args.child == "time":
        out = {}
        for name in args.scenes.split(","):
            scene = vsgl.scenes.load(name)
            for k in (1, 8):
                opts = dict(method="vsgl", num_lights=args.lights, rsm_size=args.rsm, interleave=k)
                r.render(scene, **opts)  # warm-up: pipelines, uploads
                times = []
                for _ in range(args.frames):
                    t0 = time.perf_counter()
                    r.render(scene, **opts)
                    times.append(time.perf_counter() - t0)
                out[f"{name}/k{k}"] = statistics.median(times)
        print(json.dumps(out))
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
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--frames", type=int, default=5, help="timed frames per configuration and round")
    ap.add_argument("--size", default="64x64")
    ap.add_argument("--lights", type=int, default=1024)
    ap.add_argument("--rsm", type=int, default=128)
    ap.add_argument("--scenes", default="cornell_box,diffuse_cornell,glossy_cornell")
    ap.add_argument("--check", action="store_true", help="compare the indirect AOVs of the mode matrix instead of timing")
    ap.add_argument("--child", choices=["time", "check"], help=argparse.SUPPRESS)
    ap.add_argument("--child-out", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        child(args)
        return 0
    if not args.base:
        ap.error("--base is required")
    common = ["--size", args.size, "--lights", str(args.lights), "--rsm", str(args.rsm), "--scenes", args.scenes, "--frames", str(args.frames)]
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
    rows: dict[str, list[float]] = {}
    for rnd in range(args.rounds):
        order = [("base", args.base), ("new", args.new)]
        if rnd % 2:
            order.reverse()
        got = {label: json.loads(run_child(path, ["--child", "time", *common]).stdout) for label, path in order}
        for name in args.scenes.split(","):
            b1, b8 = got["base"][f"{name}/k1"], got["base"][f"{name}/k8"]
            n1, n8 = got["new"][f"{name}/k1"], got["new"][f"{name}/k8"]
            rows.setdefault(f"{name} frame", []).append(n1 / b1)
            rows.setdefault(f"{name} shading (k1 - k8)", []).append((n1 - n8) / (b1 - b8))
            print(f"round {rnd}: {name}: base k1 {b1 * 1e3:.1f} ms k8 {b8 * 1e3:.1f} ms; new k1 {n1 * 1e3:.1f} ms k8 {n8 * 1e3:.1f} ms", flush=True)
    print("new/base ratio: median [min, max] over rounds")
    for key, v in rows.items():
        print(f"  {key:40s} {statistics.median(v):.3f} [{min(v):.3f}, {max(v):.3f}]")
    return 0


if __name__ == "__main__":
    sys.exit(main())
