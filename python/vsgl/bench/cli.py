# ``python -m vsgl bench``: the command line of run().

from __future__ import annotations

import argparse
import os
from typing import Any

import vsgl

# The package's docstring: main() gives it to argparse as the description (--help).
from . import __doc__
from .report import table
from .sweep import CORPUS_DEFAULT_SCENES, SAMPLINGS, default_scenes, run


def _ints(text: str) -> list[int]:
    return [int(x) for x in text.split(",") if x]


def _strs(text: str) -> list[str]:
    return [x for x in text.split(",") if x]


def _option_axis(text: str) -> tuple[str, list[Any]]:
    """NAME=V1,V2 of --option: each value as int, float, bool or text (in that order)."""
    name, sep, values = text.partition("=")
    if not sep or not name.strip() or not values.strip():
        raise argparse.ArgumentTypeError(f"expected NAME=V1,V2 (e.g. lambert_lobe=papers,hemisphere), got {text!r}")
    from vsgl.lightspec import option_value

    return name.strip(), [option_value(v) for v in values.split(",") if v.strip()]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m vsgl bench", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", type=_strs, default=None,
                   help="comma-separated built-in or corpus scene names or .gltf/.glb paths (default: cornell_box and, "
                        f"where the shared scene files are present, the corpus scenes {' and '.join(CORPUS_DEFAULT_SCENES)})")
    p.add_argument("--methods", type=_strs, default=["vpl", "vsgl"], help="comma-separated names from vsgl.METHODS (default: vpl,vsgl)")
    p.add_argument("--lights", type=_ints, default=None, help="comma-separated VPL/VSGL counts (default: 16,64,256)")
    p.add_argument("--size", default=None, help="WIDTHxHEIGHT (default: 256x256; 80x80 on a CPU adapter)")
    p.add_argument("--rsm-sizes", type=_ints, default=None, help="comma-separated RSM sides (default: 256; 128 on a CPU adapter)")
    p.add_argument("--K", type=lambda t: [float(x) for x in t.split(",")], default=None, metavar="K1,K2,...",
                   help="vsgl kernel masses K to sweep, e.g. 1,2,4 (default: the method's, 1); larger K is smoother in space and time")
    p.add_argument("--lighting", type=_strs, default=None, metavar="asg,accurate,blend",
                   help="SG lighting forms of vsgl and vsgl2 to sweep: asg (the papers'), accurate (filtered-NDF specular, clamped-cosine diffuse), blend (the two specular forms weighted by the receiver's share of the widened lobe; clamped-cosine diffuse in vsgl, diffuse= in vsgl2) (default: the methods' own, blend)")
    p.add_argument("--importance", type=_strs, default=["rsm"], metavar="rsm,brsm",
                   help="RSM sampling densities of vpl and vsgl to compare: rsm (reflected power), brsm (bidirectional importance from the camera's view); default: rsm")
    p.add_argument("--importance-interleave", type=int, default=None, metavar="K",
                   help="interleave tile side of the brsm importance map (importance_interleave, 1..16) for the brsm rows (default: the option's default)")
    p.add_argument("--sampling", type=_strs, default=None, metavar="S1,S2,...",
                   help=f"vpl and vsgl sampling to sweep, from {','.join(SAMPLINGS)} (default: the methods', stratified); "
                        "metropolis keeps Markov chains through each configuration's frames and its --sequence")
    kernel_choices = ", ".join(vsgl.method_info("vsgl")["options"]["kernel"]["choices"])
    p.add_argument("--kernels", type=_strs, default=["integral"], help=f"VSGL kernels: {kernel_choices} (default: integral)")
    p.add_argument("-O", "--option", action="append", default=[], type=_option_axis, metavar="NAME=V1,V2",
                   help="sweep any other method option (repeatable), for the methods that take it, e.g. -O lambert_lobe=papers,hemisphere "
                        "-O denoise=true,false; values are read as int, float, true/false or text")
    p.add_argument("--interleave", type=int, default=8, help="VSGL interleaving (default: 8)")
    p.add_argument("--visibility", default="none", choices=["none", "raytrace", "ism"],
                   help="visibility of the virtual lights of vpl, vsgl, vsgl2 and reference (default: none, the papers' unshadowed setting); the every-texel reference then traces its shadow rays")
    p.add_argument("--vpl-interleave", type=int, default=1,
                   help="VPL interleaving, denoised like the VSGLs (default: 1, every VPL at every pixel; 8 compares as the papers do)")
    p.add_argument("--seeds", type=int, default=None, help="seeds per stochastic configuration (default: 3; bias and noise need 2 or more)")
    p.add_argument("--frames", type=int, default=None, help="timed frames per configuration and seed (default: 5; 2 on a CPU adapter)")
    p.add_argument("--warmup", type=int, default=None, help="untimed frames first (default: 1)")
    p.add_argument("--warmup-seconds", type=float, default=1.0, help="then this long of back-to-back rendering before timing, so the GPU leaves its idle clock (default: 1)")
    p.add_argument("--reference", default="reference", choices=[m for m in vsgl.METHODS if vsgl.method_info(m)["ground_truth"]],
                   help="the ground-truth method errors are measured against (default: reference)")
    p.add_argument("--reference-rsm", type=int, default=None,
                   help="RSM side of the reference (default: 1024; 256 on a CPU adapter); its own error comes from one at half the side")
    p.add_argument("--reference-spp", type=int, default=None, help="samples per pixel of a pathtrace reference (default: 256); its own error comes from its stderr")
    p.add_argument("--reference-strategy", default="bidirectional", choices=vsgl.method_info("pathtrace")["options"]["strategy"]["choices"],
                   help="paths of a pathtrace reference: bidirectional (light tracing + camera paths by MIS, per pixel area; default), camera (pixel centres) or light")
    p.add_argument("--light", action="append", default=[], metavar="SPEC",
                   help='add a light to every scene (repeatable), e.g. "point position=0,1.5,0 intensity=10"; `python -m vsgl render --help` lists the forms')
    p.add_argument("--no-scene-lights", action="store_true", help="drop the scenes' own lights (then light them with --light)")
    p.add_argument("--plans", type=_strs, default=["auto"], help="pass plans to time: auto, full (default: auto; auto,full reports the pruned/full ratio)")
    p.add_argument("--adapter", default=None, help="adapter name substring")
    p.add_argument("--out", default="bench-out", help="output folder for CSV, JSON, plots and the reference cache (default: bench-out)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--sequence", type=int, default=0, metavar="N",
                   help="also render N frames per configuration with a moving light (the scene's animation, else its lights slid "
                        "along x) and report metrics.flicker of indirect against the reference's frames (default: 0, off)")
    p.add_argument("--cluster", default=None, metavar="ADDRESS",
                   help="run every reference and configuration as a task on a Ray cluster: auto (the one this machine belongs to), "
                        "local (one started for this run) or HOST:PORT; results are kept in OUT/cluster and a rerun measures only "
                        "what is missing (needs pip install 'vsgl[cluster]')")
    p.add_argument("--cluster-resource", default="GPU", metavar="NAME",
                   help="the Ray resource each cluster task asks one unit of (default: GPU)")
    a = p.parse_args(argv)
    size = None
    if a.size is not None:
        try:
            w, h = (int(x) for x in a.size.lower().split("x"))
        except ValueError:
            p.error(f"--size: expected WIDTHxHEIGHT, got {a.size!r}")
        size = (w, h)
    if a.seeds is not None and a.seeds < 1:
        p.error(f"--seeds: must be >= 1, got {a.seeds}")
    from vsgl.lightspec import parse_light

    try:
        add_lights = [parse_light(text) for text in a.light]
    except ValueError as e:
        p.error(f"--light: {e}")
    report = run(
        scenes=a.scene if a.scene is not None else default_scenes(), methods=a.methods, lights=a.lights, size=size, rsm_sizes=a.rsm_sizes, kernels=a.kernels,
        seeds=None if a.seeds is None else tuple(range(a.seeds)), frames=a.frames, warmup=a.warmup, warmup_seconds=a.warmup_seconds, reference=a.reference, reference_rsm=a.reference_rsm,
        reference_spp=a.reference_spp, reference_strategy=a.reference_strategy, add_lights=add_lights, scene_lights=not a.no_scene_lights, interleave=a.interleave, vpl_interleave=a.vpl_interleave, visibility=a.visibility, plans=tuple(a.plans), adapter=a.adapter, out=a.out, progress=not a.no_progress,
        sequence=a.sequence, Ks=tuple(a.K) if a.K else (None,), lightings=tuple(a.lighting) if a.lighting else (None,), importances=tuple(a.importance), importance_interleave=a.importance_interleave,
        samplings=tuple(a.sampling) if a.sampling else (None,), options=dict(a.option), cluster=a.cluster,
        cluster_gpu_resource=a.cluster_resource,
    )
    print(table(report))
    print(f"wrote     {os.path.join(a.out, 'bench.csv')}, bench.json, bench.txt and plots (with matplotlib)")
    return 0
