"""How far each method's mean indirect light is from the every-texel reference on the real-scene
corpus (vsgl.scenes.corpus(): the shared glTF files with their committed lights), diffuse and
specular apart, with the 4x4 block error of the indirect AOV. The setting of the real-scene
accuracy measurements: unshadowed, interleave 1, no denoiser, the reference of the same RSM
(which is exactly what VSGLs and VPLs estimate, so its own error is 0 against that target).

    .venv/bin/python experiments/real_scene_bias.py [--size 128] [--rsm 128] [--n 1024]
        [--scene NAME ...] [--variant LABEL=opt=value,opt=value ...] [--json out.json]
        [--out-of-the-box] [--seeds K]

With --seeds K > 1 each row is the mean over the seeds with its standard error (± one standard
error of the mean), the mean indirect over the reference's, and each component's range.

Each variant is a vsgl (or vpl/vsgl2, with method=...) option set; the defaults print the
table of docs/scenes.md, "The real-scene corpus"."""

from __future__ import annotations

import argparse
import json
import sys

import numpy as np

import vsgl
from vsgl.lightspec import option_value
from vsgl.metrics import block_rmse

DEFAULT_VARIANTS = [
    "vpl=method=vpl",
    "vsgl",
    "before=lighting=asg,coherence=0,lambert_lobe=hemisphere",
    "blend_only=coherence=0,lambert_lobe=hemisphere",
    "asg_coherent=lighting=asg,lambert_lobe=hemisphere",
    "papers=lighting=asg,coherence=0,plane_fade=false,lambert_lobe=papers,near_field=sg,kernel_filter=trilinear",
    "node=kernel=node",
    "vsgl2=method=vsgl2",
]


def parse_variant(text: str) -> tuple[str, dict]:
    label, _, rest = text.partition("=")
    opts: dict = {}
    for item in filter(None, rest.split(",")):
        k, eq, v = item.partition("=")
        if not eq:
            raise SystemExit(f"--variant {text!r}: expected opt=value, got {item!r}")
        opts[k] = option_value(v)
    return label, opts


def measure(r: vsgl.Renderer, scene: vsgl.Scene, rsm: int, n: int, variants, out_of_the_box: bool = False, rsm_fit: str | None = None, seeds: int = 1) -> dict:
    aovs = ["indirect_diffuse", "indirect_specular", "indirect"]
    fit = {} if rsm_fit is None else {"rsm_fit": rsm_fit}
    ref = r.render(scene, method="reference", rsm_size=rsm, aovs=aovs, **fit)
    truth = {a: ref.aov(a).astype(np.float64) for a in aovs}
    total = truth["indirect"].mean()
    out = {"reference": {a: float(truth[a].mean()) for a in aovs}, "rows": {}}
    for label, opts in variants:
        opts = {**fit, **opts}
        method = opts.pop("method", "vsgl")
        settings = dict(opts) if out_of_the_box else {"rsm_size": rsm, "num_lights": n, **opts}
        if method == "vsgl" and not out_of_the_box:
            settings.setdefault("interleave", 1)
            settings.setdefault("denoise", False)
        if method == "vsgl2":
            settings.pop("num_lights", None)
        # vsgl2 draws nothing, so it takes no seed: its seeds are the same frame.
        takes_seed = method != "vsgl2"
        per_seed = []
        for seed in range(seeds):
            f = r.render(scene, method=method, aovs=aovs, **settings, **({"seed": seed} if takes_seed else {}))
            one = {}
            for a, short in (("indirect_diffuse", "diffuse"), ("indirect_specular", "specular")):
                ref_mean = truth[a].mean()
                one[short] = float(f.aov(a).astype(np.float64).mean() / ref_mean) if ref_mean > 0 else float("nan")
                one[short + "_share"] = float(ref_mean / total) if total > 0 else 0.0
            one["indirect"] = float(f.aov("indirect").astype(np.float64).mean() / total) if total > 0 else float("nan")
            one["block"] = float(block_rmse(f.aov("indirect"), truth["indirect"], 4)) if total > 0 else float("nan")
            one["gpu_ms"] = float(f.timings_ms.get("total", float("nan")))
            per_seed.append(one)
        # With several seeds a row is the mean over them (the block error too), with each
        # component's range over the seeds: one seed's frame is what a user sees, the mean
        # is the estimator's bias.
        row = {k: float(np.mean([o[k] for o in per_seed])) for k in per_seed[0]}
        if seeds > 1:
            for short in ("diffuse", "specular", "block"):
                row[short + "_range"] = [min(o[short] for o in per_seed), max(o[short] for o in per_seed)]
            row["seed0"] = per_seed[0]
            # The standard error of the mean over seeds: the mean's own error as an estimate of
            # the expectation (one seed's frame is heavy-tailed where a few texels carry the light).
            for short in ("diffuse", "specular", "indirect"):
                row[short + "_stderr"] = float(np.std([o[short] for o in per_seed], ddof=1) / np.sqrt(seeds))
        out["rows"][label] = row
    return out


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", type=int, default=128)
    p.add_argument("--rsm", type=int, default=128)
    p.add_argument("--n", type=int, default=1024)
    p.add_argument("--scene", action="append", help="corpus or built-in scene name (repeatable); default: every corpus scene whose file is present")
    p.add_argument("--variant", action="append", help="LABEL=opt=value,... (repeatable); default: the docs' table")
    p.add_argument("--json", help="also write the numbers here")
    p.add_argument("--out-of-the-box", action="store_true",
                   help="each method with its own defaults (N, RSM, interleave, denoiser) against the reference of an RSM of --rsm")
    p.add_argument("--seeds", type=int, default=1,
                   help="render seeds 0..SEEDS-1 and report the mean over them, each component's range and seed 0")
    p.add_argument("--rsm-fit", choices=["scene", "cone"],
                   help="rsm_fit of the reference and of every variant that does not set it (default: each method's default)")
    a = p.parse_args()
    if a.seeds < 1:
        p.error(f"--seeds: expected 1 or more, got {a.seeds}")
    variants = [parse_variant(v) for v in (a.variant or DEFAULT_VARIANTS)]
    names = a.scene or [n for n in vsgl.scenes.corpus_names() if vsgl.scenes.corpus_available(n)]
    if not names:
        print(f"no corpus scene files under {vsgl.scenes.shared_scenes_dir()}", file=sys.stderr)
        return 1
    r = vsgl.Renderer(a.size, a.size)
    results = {}
    setting = "each method's own defaults" if a.out_of_the_box else f"RSM {a.rsm}^2, N = {a.n}, interleave 1, no denoiser"
    setting += f", rsm_fit={a.rsm_fit}" if a.rsm_fit else ""
    print(f"{a.size}x{a.size}, {setting}, unshadowed; mean diffuse / specular over the every-texel reference's (RSM {a.rsm}^2), 4x4 block error")
    for name in names:
        scene = vsgl.scenes.load(name) if name in vsgl.scenes.names() else vsgl.scenes.corpus_scene(name).scene
        res = measure(r, scene, a.rsm, a.n, variants, a.out_of_the_box, a.rsm_fit, a.seeds)
        results[name] = res
        first = next(iter(res["rows"].values()))
        print(f"\n{name}: reference indirect mean {res['reference']['indirect']:.4g} (diffuse {first['diffuse_share']:.2f}, specular {first['specular_share']:.2f} of it)")
        for label, row in res["rows"].items():
            line = f"  {label:28s} {row['diffuse']:6.3f} / {row['specular']:6.3f}   block {row['block']:.3f}   {row['gpu_ms']:8.1f} ms"
            if a.seeds > 1:
                (d0, d1), (s0, s1), (b0, b1) = row["diffuse_range"], row["specular_range"], row["block_range"]
                z = row["seed0"]
                line += (f"   indirect {row['indirect']:.3f} ± {row['indirect_stderr']:.3f} (diffuse ± {row['diffuse_stderr']:.3f}, specular ± {row['specular_stderr']:.3f})"
                         f"   seeds 0-{a.seeds - 1}: diffuse {d0:.2f}-{d1:.2f}, specular {s0:.2f}-{s1:.2f}, block {b0:.2f}-{b1:.2f};"
                         f" seed 0 {z['diffuse']:.3f} / {z['specular']:.3f}, {z['block']:.3f}")
            print(line)
    if a.json:
        with open(a.json, "w") as fh:
            json.dump({"size": a.size, "rsm": a.rsm, "n": a.n, "seeds": a.seeds, "scenes": results}, fh, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
