"""The papers' tables next to ours: ``python -m vsgl reproduce``.

For each table the seed papers report — the 2015 paper's Table 1 (indirect-illumination passes
of VPLs and VSGLs, with and without bidirectional RSM importance), the 2016 paper's Table 1 (VSGL
generation by filtered importance sampling against k-means in 2D image space and 3D world space,
for the camera view's importance VSGLs and the light view's VSGLs) and the 2015 poster's Table 1
(one diffuse VSGL against cascaded light propagation volumes, time and memory) — it prints the
paper's numbers, ours on the current adapter (median of back-to-back frames after warm-up, the
configurations of a table alternated frame by frame), the ratios that compare across hardware
(each column over the table's baseline), and the error column the papers lack: each
configuration's mean indirect light over the every-texel reference of the same RSM and its block
error (4×4 blocks, relative RMS) against it. The reference is the sum over every RSM texel that
the virtual lights stand for, so its own error against that target is 0; a stochastic
configuration's error is the mean over 3 seeds.

On a CPU adapter (lavapipe) absolute times mean nothing: only the ratios are printed, and the
defaults shrink (``--size``, ``--rsm``) so the run takes a few minutes."""

from __future__ import annotations

import argparse
import statistics
import sys
from dataclasses import dataclass
from typing import Any, Callable, Sequence

import numpy as np

#: [Tok15] Table 1, the 331K-triangle scene (AMD R9 290X, 1920×1088, RSM 256², 1024 lights,
#: 8×8 interleaving, 64² adaptive ISMs, 4096 view VSGLs for BRSM): ms per row for VPLs (with
#: the importance map of [REH*11]), VSGLs without and with BRSM.
TOK15_TABLE1: list[tuple[str, tuple[float | None, float | None, float | None]]] = [
    ("G-buffer", (0.42, 0.42, 0.42)),
    ("Reflective shadow map", (0.35, 0.35, 0.35)),
    ("Additional G-buffer", (None, None, 1.48)),
    ("Additional reflective shadow map", (None, 0.19, 0.19)),
    ("Importance map", (0.69, 0.04, 0.78)),
    ("VPL/VSGL sampling", (0.02, 0.02, 0.02)),
    ("Adaptive imperfect shadow maps", (15.15, 15.41, 15.71)),
    ("Radiance evaluation", (3.25, 4.44, 4.44)),
    ("Denoising filter", (2.68, 2.68, 2.68)),
]
#: Our passes in each row of [Tok15] Table 1 (`frame.timings_ms` names).
TOK15_PASSES: dict[str, tuple[str, ...]] = {
    "G-buffer": ("visibility", "material"),
    "Reflective shadow map": ("rsm_visibility", "rsm_material", "rsm_flux"),
    "Additional G-buffer": ("brsm_view_gbuffer", "brsm_view_moments", "brsm_view_mips", "brsm_view_vsgl_gen"),
    "Additional reflective shadow map": ("vsgl_moments", "moment_mips"),
    "Importance map": ("pdf_mips", "brsm_importance", "brsm_importance_filter", "brsm_mix", "brsm_pdf_mips"),
    "VPL/VSGL sampling": ("vpl_sample", "vsgl_gen"),
    "Adaptive imperfect shadow maps": ("ism_splat", "ism_pull", "ism_push"),
    "Radiance evaluation": ("vpl_shading", "vsgl_shading"),
    "Denoising filter": ("denoise",),
}

#: [Tok16] Table 1 (GTX 970, 1920×1088, RSM 512², 2048 camera-view VSGLs for BRSM, 1024 light-view
#: VSGLs): generation ms of the previous filtered importance sampling, the paper's, k-means 2D
#: and k-means 3D; and the totals of its Table 2 (another PDF).
TOK16_TABLE1_TOTALS = {"integral": 2.330, "kmeans2d": 16.561, "kmeans3d": 21.772}
TOK16_TABLE2_TOTALS = {"integral": 2.246, "kmeans2d": 20.388, "kmeans3d": 37.683}
TOK16_TABLE1_ROWS: dict[str, list[tuple[str, float]]] = {
    "integral": [("Additional G-buffer", 0.816), ("Mipmapping (camera)", 0.968), ("Filtered sampling (camera)", 0.092),
                 ("Additional RSM", 0.165), ("Mipmapping (light)", 0.201), ("Filtered sampling (light)", 0.088)],
    "kmeans2d": [("Cluster assignment", 3.004 + 0.619), ("Sort", 1.541 + 0.306), ("Sum", 9.096 + 1.995)],
    "kmeans3d": [("Cluster assignment", 5.009 + 0.860), ("Sort", 1.517 + 0.299), ("Sum", 9.856 + 4.231)],
}
#: Our passes in each row (both views' k-means passes carry the same names).
TOK16_PASSES: dict[str, tuple[str, ...]] = {
    "Additional G-buffer": ("brsm_view_gbuffer", "brsm_view_moments"),
    "Mipmapping (camera)": ("brsm_view_mips",),
    "Filtered sampling (camera)": ("brsm_view_vsgl_gen",),
    "Additional RSM": ("vsgl_moments",),
    "Mipmapping (light)": ("moment_mips",),
    "Filtered sampling (light)": ("vsgl_gen",),
    # The centres and their grid are our stand-in for the paper's tree (part of its assignment).
    "Cluster assignment": ("kmeans_centres", "kmeans_grid", "kmeans_assign"),
    "Sort": ("kmeans_sort",),
    "Sum": ("kmeans_sum",),
}

#: [Tok15 poster] Table 1 (GTX 770, 699k triangles, the LDDE path): one diffuse VSGL against
#: LPVs of 32³ cells × 4 cascades. Per column: the paper's ms and bytes, our configuration, the
#: passes its time sums, and the label prefixes of its own buffers (the RSM, the G-buffer and the
#: frame targets are left out on both sides alike).
POSTER_TABLE1: list[tuple[str, float, float, dict[str, Any], tuple[str, ...], tuple[str, ...]]] = [
    ("VSGL", 0.492, 204e3, dict(method="vsgl2"), ("vsgl2_reduce", "vsgl_shading"), ("vsgl2_",)),
    ("LPV", 2.232, 1984e3, dict(method="lpv", lpv_grid=32, lpv_cascades=4), ("lpv_inject", "lpv_geometry", "lpv_geometry_merge", "lpv_propagate", "lpv_lookup"), ("lpv_",)),
]


@dataclass
class Measured:
    """One configuration of a table, measured."""

    label: str
    timings: dict[str, float]  # median ms per pass over the timed frames
    total_ms: float  # median of the frames' sums over the table's passes
    diffuse: float  # mean indirect diffuse over the reference's
    block: float  # block error of the indirect light against the reference
    memory: dict[str, int]
    dispatches: int | None = None


def _medians(frames: list[dict[str, float]]) -> dict[str, float]:
    names = {n for f in frames for n in f}
    return {n: statistics.median(f.get(n, 0.0) for f in frames) for n in names}


#: Seeds each stochastic configuration's error is averaged over.
ERROR_SEEDS = 3
#: Seconds of back-to-back frames before a table's timed frames on a GPU (the bench's default;
#: on a GPU the warm-up also goes on until NVML reads a warm SM clock, where it can).
WARMUP_SECONDS = 1.0


def _measure(renderer, scene, configs: Sequence[tuple[str, dict[str, Any]]], passes: Callable[[str], Sequence[str]], rsm: int, frames: int,
             shadowed: bool = False) -> list[Measured]:
    """Each configuration warmed up as the bench warms up (`bench.timing.warm_up`: sustained
    frames until the SM clock is warm on a GPU), then `frames` frames alternated across them,
    then one frame with AOVs for the error against the reference of the same RSM (its virtual
    lights shadowed by ray tracing when the configurations shadow theirs)."""
    import vsgl
    from vsgl.bench.timing import _clock_for, warm_up
    from vsgl.metrics import block_rmse

    aovs = ["indirect_diffuse", "indirect_specular"]
    ref = renderer.render(scene, method="reference", rsm_size=rsm, aovs=aovs, **({"visibility": "raytrace"} if shadowed else {}))
    ref_indirect = ref.aov("indirect_diffuse").astype(np.float64) + ref.aov("indirect_specular")
    ref_diffuse = float(ref.aov("indirect_diffuse").mean())
    cpu = renderer.adapter["device_type"] == "Cpu"
    clock = _clock_for(cpu)
    for _, kw in configs:
        # Two frames compile and allocate what the configuration needs, on any adapter.
        for _ in range(2):
            renderer.render(scene, aovs=[], **kw)
    for _, kw in configs:
        warm_up(lambda: renderer.render(scene, aovs=[], **kw), 0.0 if cpu else WARMUP_SECONDS / len(configs), clock)
    clocks = [clock.read()] if clock is not None else []
    timed: list[list[dict[str, float]]] = [[] for _ in configs]
    for _ in range(frames):
        for i, (_, kw) in enumerate(configs):
            timed[i].append(dict(renderer.render(scene, aovs=[], **kw).timings_ms))
    if clock is not None:
        clocks.append(clock.read())
        if not all(clock.warm(c) for c in clocks):
            print(f"  note: SM clock {min(clocks)}-{max(clocks)} of {clock.max_mhz} MHz before/after the timed frames: some ran cold", file=sys.stderr)
    out = []
    for (label, kw), times in zip(configs, timed):
        # The error of a stochastic configuration is the mean over ERROR_SEEDS seeds: one seed's
        # frame at small N is noise as much as bias.
        seeds = range(ERROR_SEEDS) if "seed" in vsgl.method_options(kw["method"]) else [None]
        frames_ = [renderer.render(scene, aovs=aovs, **kw, **({} if seed is None else {"seed": seed})) for seed in seeds]
        f = frames_[0]
        wanted = passes(label)
        totals = [sum(t.get(p, 0.0) for p in wanted) for t in times]
        indirect = [g.aov("indirect_diffuse").astype(np.float64) + g.aov("indirect_specular") for g in frames_]
        out.append(Measured(
            label=label, timings=_medians(times), total_ms=statistics.median(totals),
            diffuse=float(np.mean([g.aov("indirect_diffuse").mean() for g in frames_])) / ref_diffuse if ref_diffuse > 0 else float("nan"),
            block=float(np.mean([block_rmse(i, ref_indirect, block=4) for i in indirect])) if np.any(ref_indirect) else float("nan"),
            memory=dict(f.memory_bytes), dispatches=f.settings.get("kmeans_dispatches"),
        ))
    return out


def _ms(value: float | None, cpu: bool) -> str:
    if value is None:
        return "-"
    return "(cpu)" if cpu else f"{value:.3f}"


def _ratio(a: float | None, b: float | None) -> str:
    return "-" if a is None or b is None or not b else f"{a / b:.2f}x"


def tok15_table1(renderer, scene, size_rsm: int, lights: int, view_lights: int, frames: int, cpu: bool) -> str:
    common = dict(num_lights=lights, rsm_size=size_rsm, visibility="ism", interleave=8)
    brsm = dict(importance="brsm", importance_lights=view_lights)
    configs = [("VPLs", dict(method="vpl", denoise=True, **common, **brsm)),
               ("VSGLs w/o BRSM", dict(method="vsgl", **common)),
               ("VSGLs with BRSM", dict(method="vsgl", **common, **brsm))]
    every = tuple(p for ps in TOK15_PASSES.values() for p in ps)
    got = _measure(renderer, scene, configs, lambda _: every, size_rsm, frames, shadowed=True)
    lines = [f"2015 paper, Table 1: indirect-illumination passes (ms); ours at RSM {size_rsm}², N = {lights}, "
             f"{view_lights} view VSGLs for BRSM, visibility=\"ism\", interleave 8",
             f"  {'row':34s} {'paper VPL':>9s} {'VSGL':>7s} {'+BRSM':>7s}   {'ours VPL':>9s} {'VSGL':>7s} {'+BRSM':>7s}"]
    for row, paper in TOK15_TABLE1:
        ours = [sum(m.timings.get(p, 0.0) for p in TOK15_PASSES[row]) or None for m in got]
        lines.append(f"  {row:34s} " + " ".join(f"{_ms(v, False):>{w}s}" for v, w in zip(paper, (9, 7, 7)))
                     + "   " + " ".join(f"{_ms(v, cpu):>{w}s}" for v, w in zip(ours, (9, 7, 7))))
    paper_totals = [sum(v[k] or 0.0 for _, v in TOK15_TABLE1) for k in range(3)]
    lines.append(f"  total over VPLs' (paper): VSGL {_ratio(paper_totals[1], paper_totals[0])}, +BRSM {_ratio(paper_totals[2], paper_totals[0])}; "
                 f"ours: VSGL {_ratio(got[1].total_ms, got[0].total_ms)}, +BRSM {_ratio(got[2].total_ms, got[0].total_ms)}")
    lines.append("  error (not in the paper; the reference's own error against that target is 0), indirect diffuse over the reference (shadowed by ray tracing) / block error: "
                 + ", ".join(f"{m.label} {m.diffuse:.3f} / {m.block:.3f}" for m in got))
    return "\n".join(lines)


def tok16_table1(renderer, scene, size_rsm: int, lights: int, view_lights: int, frames: int, cpu: bool) -> str:
    common = dict(method="vsgl", num_lights=lights, rsm_size=size_rsm, importance="brsm", importance_lights=view_lights, interleave=8)
    configs = [(k, dict(common, kernel=k)) for k in ("integral", "kmeans2d", "kmeans3d")]
    rows = {k: [r for r, _ in TOK16_TABLE1_ROWS[k]] for k in TOK16_TABLE1_ROWS}
    got = _measure(renderer, scene, configs, lambda k: tuple(p for r in rows[k] for p in TOK16_PASSES[r]), size_rsm, frames)
    lines = [f"2016 paper, Table 1: VSGL generation (ms), both views; ours at RSM {size_rsm}², {lights} light-view and "
             f"{view_lights} camera-view VSGLs; error against the every-texel reference (its own error against that target: 0)"]
    for m in got:
        lines.append(f"  {m.label}:")
        for row, paper in TOK16_TABLE1_ROWS[m.label]:
            ours = sum(m.timings.get(p, 0.0) for p in TOK16_PASSES[row])
            lines.append(f"    {row:28s} paper {paper:7.3f}   ours {_ms(ours, cpu):>8s}")
    base = got[0].total_ms
    for m in got:
        paper1, paper2 = TOK16_TABLE1_TOTALS[m.label], TOK16_TABLE2_TOTALS[m.label]
        dispatches = f", {m.dispatches} dispatches for both views (paper 39)" if m.dispatches else ""
        lines.append(f"  {m.label:9s} total over FIS: paper {_ratio(paper1, TOK16_TABLE1_TOTALS['integral'])} (Table 2: "
                     f"{_ratio(paper2, TOK16_TABLE2_TOTALS['integral'])}), ours {_ratio(m.total_ms, base)}{dispatches}; "
                     f"error (not in the paper): diffuse {m.diffuse:.3f}, block {m.block:.3f}")
    return "\n".join(lines)


def poster_table1(renderer, scene, size_rsm: int, frames: int, cpu: bool) -> str:
    columns = {label: (ms, mem, passes, prefixes) for label, ms, mem, _, passes, prefixes in POSTER_TABLE1}
    configs = [(label, dict(kw, rsm_size=size_rsm)) for label, _, _, kw, _, _ in POSTER_TABLE1]
    got = _measure(renderer, scene, configs, lambda label: columns[label][2], size_rsm, frames)
    memory = [sum(b for name, b in m.memory.items() if name.startswith(columns[m.label][3])) for m in got]
    (p_vs_ms, p_vs_mem), (p_lpv_ms, p_lpv_mem) = ((ms, mem) for _, ms, mem, _, _, _ in POSTER_TABLE1)
    return "\n".join([
        f"2015 poster, Table 1: one diffuse VSGL (vsgl2 on a diffuse-only scene) against LPVs (32³ cells × 4 cascades); ours at RSM {size_rsm}²",
        f"  time:   paper VSGL {p_vs_ms} ms, LPV {p_lpv_ms} ms ({_ratio(p_lpv_ms, p_vs_ms)}); ours VSGL {_ms(got[0].total_ms, cpu)}, "
        f"LPV {_ms(got[1].total_ms, cpu)} ({_ratio(got[1].total_ms, got[0].total_ms)})",
        f"  memory: paper VSGL {p_vs_mem / 1e3:.0f} kB, LPV {p_lpv_mem / 1e3:.0f} kB ({_ratio(p_lpv_mem, p_vs_mem)}); ours VSGL "
        f"{memory[0] / 1e3:.0f} kB, LPV {memory[1] / 1e3:.0f} kB ({_ratio(memory[1], memory[0])}) (each side's own buffers; the RSM, "
        "G-buffer and frame targets in neither)",
        "  error (not in the paper; the reference's own error against that target is 0), indirect diffuse over the reference / block error: "
        + ", ".join(f"{m.label} {m.diffuse:.3f} / {m.block:.3f}" for m in got),
    ])


def main(argv: list[str] | None = None) -> int:
    import vsgl

    p = argparse.ArgumentParser(prog="python -m vsgl reproduce", description=__doc__.splitlines()[0],
                                epilog="On a CPU adapter only the ratios are printed.")
    p.add_argument("--size", type=str, default=None, help="WxH of each frame (default: 1920x1088 on a GPU, 96x54 on a CPU)")
    p.add_argument("--rsm", type=int, default=None, help="RSM side (default: the papers' 256 / 512 on a GPU, 64 on a CPU)")
    p.add_argument("--frames", type=int, default=None, help="timed frames per configuration (default: 20 on a GPU, 3 on a CPU)")
    p.add_argument("--tables", type=str, default="tok15,tok16,poster", help="which tables: tok15, tok16, poster (comma-separated)")
    p.add_argument("--scene", type=str, default=None,
                   help="the scene of the 2015 and 2016 tables: a built-in, a corpus scene (e.g. flight_helmet) or a glTF file "
                        "(default: glossy_cornell); the poster's table keeps the diffuse Cornell box, its LDDE setting")
    p.add_argument("--adapter", type=str, default=None, help="adapter name filter (as for render)")
    a = p.parse_args(argv)
    tables = [t.strip() for t in a.tables.split(",") if t.strip()]
    unknown = [t for t in tables if t not in ("tok15", "tok16", "poster")]
    if unknown or not tables:
        p.error(f"--tables: unknown {unknown}; choose from tok15, tok16, poster")
    probe = vsgl.Renderer(width=8, height=8, adapter=a.adapter)
    cpu = probe.adapter["device_type"] == "Cpu"
    if a.size is not None:
        w, h = (int(v) for v in a.size.lower().split("x"))
    else:
        w, h = (96, 54) if cpu else (1920, 1088)
    frames = a.frames if a.frames is not None else (3 if cpu else 20)
    if frames < 1:
        p.error(f"--frames: must be >= 1, got {frames}")
    from vsgl.bench.sweep import _scene

    scene_name = a.scene or "glossy_cornell"
    renderer = vsgl.Renderer(width=w, height=h, adapter=a.adapter)
    print(f"adapter: {renderer.adapter['name']} ({renderer.adapter['device_type']}), {w}x{h}, scene {scene_name}, median of {frames} frames "
          "after the warm-up, configurations alternated")
    if cpu:
        print("CPU adapter: absolute times are meaningless; only the ratios (within a table) are printed")
    for table in tables:
        if table == "tok15":
            rsm = a.rsm or (64 if cpu else 256)
            print("\n" + tok15_table1(renderer, _scene(scene_name), rsm, 1024 if not cpu else 256, 4096 if not cpu else 256, frames, cpu))
        elif table == "tok16":
            rsm = a.rsm or (64 if cpu else 512)
            print("\n" + tok16_table1(renderer, _scene(scene_name), rsm, 1024 if not cpu else 256, 2048 if not cpu else 256, frames, cpu))
        else:
            rsm = a.rsm or (64 if cpu else 128)
            print("\n" + poster_table1(renderer, vsgl.scenes.builtin_scene("diffuse_cornell"), rsm, frames, cpu))
    sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
