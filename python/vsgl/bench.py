"""Error against run time: ``python -m vsgl bench`` and ``vsgl.bench.run(...)``.

Sweeps methods × light counts × RSM sizes × VSGL kernels over scenes at one resolution. For each
configuration it reports GPU time per pass and in total (median, interquartile range and
extremes over frames rendered back to back after a warm-up of ``--warmup-seconds`` of sustained
rendering, so the GPU leaves its idle clock; from timestamp queries; the SM clock before and
after the timed frames where ``nvidia-ml-py`` is installed), and the error of the ``indirect`` AOV and of the full
image against the scene's reference (``reference`` by default, computed once per scene, view
and settings, and cached on disk), as the mean and spread over seeds for stochastic methods.
Writes a terminal table, ``bench.csv``, ``bench.json`` and, with matplotlib, ``error_vs_time.png``
and ``error_vs_lights.png``. On a CPU adapter only ratios inside one report mean anything.

With ``--plans auto,full`` every configuration also runs with the pass plan forced to
``"full"`` (nothing left out), and the report gives the pruned/full time ratio per configuration
(``plan_ratios``) next to both errors, which must agree: pruning never changes the image.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import json
import os
import pathlib
import statistics
import sys
import time
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

import vsgl
from vsgl import metrics

STOCHASTIC = {"vpl", "vsgl"}


@dataclass
class Row:
    scene: str
    method: str
    num_lights: int | None
    rsm_size: int | None
    kernel: str | None
    seeds: int
    total_ms_median: float
    total_ms_min: float
    total_ms_max: float
    passes_ms: dict[str, float]
    rmse_indirect: float
    rmse_indirect_std: float
    rmse_image: float
    relmse_indirect: float
    relmse_image: float
    flip_image: float | None
    plan: str = "auto"
    total_ms_q1: float = 0.0
    total_ms_q3: float = 0.0
    # Per pass: (first quartile, third quartile) of its time over the timed frames.
    passes_iqr_ms: dict[str, tuple[float, float]] = field(default_factory=dict)
    # Untimed frames rendered back to back before the timed ones (the warm-up).
    warmup_frames: int = 0
    # SM clock (MHz) before and after the timed frames, where NVML is available.
    sm_clock_mhz: tuple[int, int] | None = None


@dataclass
class Report:
    adapter: dict[str, Any]
    size: tuple[int, int]
    reference: str
    reference_settings: dict[str, Any]
    reference_ms: dict[str, float]
    frames: int
    warmup: int
    rows: list[Row] = field(default_factory=list)
    # Seconds of back-to-back rendering before each configuration's timed frames.
    warmup_seconds: float = 0.0
    note: str = ""
    # Per configuration run with both plans: pruned ("auto") over "full" median total time.
    plan_ratios: list[dict[str, Any]] = field(default_factory=list)

    def to_json(self) -> dict[str, Any]:
        d = asdict(self)
        d["rows"] = [asdict(r) for r in self.rows]
        return d


def _quartiles(v: list[float]) -> tuple[float, float]:
    if len(v) < 2:
        return v[0], v[0]
    q = statistics.quantiles(v, n=4, method="inclusive")
    return q[0], q[2]


def _sm_clock_reader():
    """A function returning the SM clock in MHz through NVML (optional `nvidia-ml-py`), or None."""
    try:
        import pynvml  # type: ignore[import-not-found]

        pynvml.nvmlInit()
        handle = pynvml.nvmlDeviceGetHandleByIndex(0)
        return lambda: int(pynvml.nvmlDeviceGetClockInfo(handle, pynvml.NVML_CLOCK_SM))
    except Exception:  # not installed, no NVIDIA driver, no device: clocks are not reported
        return None


def _scene(name: str) -> vsgl.Scene:
    if name in vsgl.scenes.names():
        return vsgl.scenes.load(name)
    return vsgl.Scene.load(name)


def _reference_key(scene: vsgl.Scene, size: tuple[int, int], method: str, settings: dict[str, Any]) -> str:
    cam = scene.cameras[0] if scene.cameras else None
    blob = json.dumps(
        {
            "scene": scene.source,
            "stats": scene.stats,
            "lights": [repr(l) for l in scene.lights],
            "camera": repr(cam),
            "size": size,
            "method": method,
            "settings": settings,
            "version": vsgl.__version__,
        },
        sort_keys=True,
        default=str,
    )
    return hashlib.sha256(blob.encode()).hexdigest()[:20]


def _reference(renderer, scene, size, method, settings, cache_dir):
    key = _reference_key(scene, size, method, settings)
    path = None if cache_dir is None else pathlib.Path(cache_dir) / f"reference-{key}.npz"
    if path is not None and path.exists():
        data = np.load(path)
        return data["image"], data["indirect"], json.loads(str(data["timings"]))
    frame = renderer.render(scene, method=method, aovs=["image", "indirect"], **settings)
    image, indirect = frame.image, frame.aov("indirect")
    timings = dict(frame.timings_ms)
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        np.savez_compressed(path, image=image, indirect=indirect, timings=json.dumps(timings))
    return image, indirect, timings


def _progress(total: int, enabled: bool):
    if enabled:
        try:
            from tqdm import tqdm

            return tqdm(total=total, unit="config", file=sys.stderr)
        except ImportError:
            pass

    class _Silent:
        def update(self, _n=1):
            pass

        def close(self):
            pass

    return _Silent()


def run(
    scenes=("cornell_box",),
    methods=("vpl", "vsgl"),
    lights=(16, 64, 256),
    size=(256, 256),
    rsm_sizes=(256,),
    kernels=("integral",),
    seeds=(0, 1, 2),
    frames=5,
    warmup=1,
    warmup_seconds=1.0,
    reference="reference",
    reference_rsm=1024,
    reference_spp=256,
    interleave=8,
    vpl_interleave=1,
    plans=("auto",),
    adapter=None,
    out=None,
    cache_dir=None,
    progress=True,
) -> Report:
    """Runs the sweep and returns a :class:`Report`; with ``out`` also writes CSV, JSON and plots."""
    if frames < 1:
        raise ValueError(f"frames: must be >= 1, got {frames}")
    if not (warmup_seconds >= 0 and np.isfinite(warmup_seconds)):
        raise ValueError(f"warmup_seconds: must be finite and >= 0, got {warmup_seconds}")
    if reference not in ("reference", "pathtrace"):
        raise ValueError(f"reference: must be \"reference\" or \"pathtrace\", got {reference!r}")
    unknown = [m for m in methods if m not in vsgl.METHODS]
    if unknown:
        raise ValueError(f"methods: unknown {unknown}; valid: {', '.join(vsgl.METHODS)}")
    bad_plans = [p for p in plans if p not in ("auto", "full")]
    if bad_plans or not plans:
        raise ValueError(f"plans: expected a non-empty list of \"auto\" and \"full\", got {list(plans)}")
    w, h = size
    renderer = vsgl.Renderer(width=w, height=h, adapter=adapter)
    ref_settings: dict[str, Any] = {"rsm_size": reference_rsm} if reference == "reference" else {"spp": reference_spp}
    if out is not None and cache_dir is None:
        cache_dir = pathlib.Path(out) / "cache"
    cpu = renderer.adapter["device_type"] == "Cpu"
    sm_clock = None if cpu else _sm_clock_reader()
    report = Report(
        adapter=dict(renderer.adapter),
        size=(w, h),
        reference=reference,
        reference_settings=ref_settings,
        reference_ms={},
        frames=frames,
        warmup=warmup,
        # A CPU adapter has no clock states to leave: no warm-up time there.
        warmup_seconds=0.0 if cpu else warmup_seconds,
        note="CPU adapter: absolute times are meaningless; compare only ratios within this report (no warm-up time)." if cpu else "",
    )
    configs = []
    for m in methods:
        if m in ("vpl", "vsgl"):
            for n in lights:
                for r in rsm_sizes:
                    for k in (kernels if m == "vsgl" else (None,)):
                        configs.append((m, n, r, k))
        elif m in ("reference", "vsgl2"):
            # Deterministic and without a light count: one configuration per RSM size.
            for r in rsm_sizes:
                configs.append((m, None, r, None))
        else:
            configs.append((m, None, None, None))
    # Plans alternate inside one configuration so both see the same machine state.
    configs = [(*c, plan) for c in configs for plan in plans]
    bar = _progress(len(configs) * len(scenes), progress)
    for scene_name in scenes:
        scene = _scene(scene_name)
        t = time.perf_counter()
        ref_image, ref_indirect, ref_timings = _reference(renderer, scene, (w, h), reference, ref_settings, cache_dir)
        report.reference_ms[scene_name] = ref_timings.get("total", 1e3 * (time.perf_counter() - t))
        for method, n, rsm, kernel, plan in configs:
            settings: dict[str, Any] = {"plan": plan}
            if n is not None:
                settings["num_lights"] = n
            if rsm is not None:
                settings["rsm_size"] = rsm
            if kernel is not None:
                settings.update(kernel=kernel, interleave=interleave)
            if method == "vpl":
                # 1: every VPL at every pixel (the baseline); 8: the papers' equal-footing
                # comparison, interleaved and denoised like the VSGLs.
                settings["interleave"] = vpl_interleave
            run_seeds = seeds if method in STOCHASTIC else (0,)
            # Read back only what the errors need (readback is most of the wall time).
            settings["aovs"] = ["image"] if method == "direct" else ["image", "indirect"]
            totals: list[float] = []
            per_pass: dict[str, list[float]] = {}
            errs: dict[str, list[float]] = {"rmse_indirect": [], "rmse_image": [], "relmse_indirect": [], "relmse_image": [], "flip": []}
            # Sustained load first: frames back to back (nothing read back) until the GPU has left
            # its idle clock (DESIGN.md, "Clocks"); the seeds that follow keep it busy.
            warm_frames = 0
            t_end = time.perf_counter() + report.warmup_seconds
            quiet = {k: v for k, v in settings.items() if k != "aovs"}
            while time.perf_counter() < t_end:
                renderer.render(scene, method=method, aovs=[], **quiet)
                warm_frames += 1
            clocks: list[int] = []
            for seed in run_seeds:
                if method in STOCHASTIC:
                    settings["seed"] = seed
                for _ in range(warmup):
                    renderer.render(scene, method=method, **settings)
                if sm_clock is not None:
                    clocks.append(sm_clock())
                frame = None
                for _ in range(frames):
                    frame = renderer.render(scene, method=method, **settings)
                    totals.append(frame.timings_ms["total"])
                    for k2, v in frame.timings_ms.items():
                        if k2 != "total":
                            per_pass.setdefault(k2, []).append(v)
                if sm_clock is not None:
                    clocks.append(sm_clock())
                indirect = frame.aov("indirect") if "indirect" in frame.aovs else np.zeros_like(ref_indirect)
                errs["rmse_indirect"].append(metrics.rmse(indirect, ref_indirect))
                errs["rmse_image"].append(metrics.rmse(frame.image, ref_image))
                errs["relmse_indirect"].append(metrics.relmse(indirect, ref_indirect))
                errs["relmse_image"].append(metrics.relmse(frame.image, ref_image))
                f = metrics.flip(frame.image, ref_image)
                if f is not None:
                    errs["flip"].append(f)
            report.rows.append(
                Row(
                    scene=scene_name,
                    method=method,
                    num_lights=n,
                    rsm_size=rsm,
                    kernel=kernel,
                    seeds=len(run_seeds),
                    total_ms_median=statistics.median(totals),
                    total_ms_min=min(totals),
                    total_ms_max=max(totals),
                    passes_ms={k2: statistics.median(v) for k2, v in per_pass.items()},
                    total_ms_q1=_quartiles(totals)[0],
                    total_ms_q3=_quartiles(totals)[1],
                    passes_iqr_ms={k2: _quartiles(v) for k2, v in per_pass.items()},
                    warmup_frames=warm_frames,
                    sm_clock_mhz=(min(clocks), max(clocks)) if clocks else None,
                    rmse_indirect=float(np.mean(errs["rmse_indirect"])),
                    rmse_indirect_std=float(np.std(errs["rmse_indirect"])),
                    rmse_image=float(np.mean(errs["rmse_image"])),
                    relmse_indirect=float(np.mean(errs["relmse_indirect"])),
                    relmse_image=float(np.mean(errs["relmse_image"])),
                    flip_image=float(np.mean(errs["flip"])) if errs["flip"] else None,
                    plan=plan,
                )
            )
            bar.update(1)
    bar.close()
    report.plan_ratios = _plan_ratios(report.rows)
    if out is not None:
        write(report, out)
    return report


def _plan_ratios(rows: list[Row]) -> list[dict[str, Any]]:
    """Pairs each "auto" row with the "full" row of the same configuration."""
    key = lambda r: (r.scene, r.method, r.num_lights, r.rsm_size, r.kernel)  # noqa: E731
    full = {key(r): r for r in rows if r.plan == "full"}
    out = []
    for r in rows:
        f = full.get(key(r)) if r.plan == "auto" else None
        if f is not None:
            out.append({
                "scene": r.scene, "method": r.method, "num_lights": r.num_lights, "rsm_size": r.rsm_size, "kernel": r.kernel,
                "auto_ms": r.total_ms_median, "full_ms": f.total_ms_median, "ratio": r.total_ms_median / f.total_ms_median,
                "passes_ratio": {k: r.passes_ms[k] / f.passes_ms[k] for k in r.passes_ms if f.passes_ms.get(k, 0) > 0},
                "rmse_image_auto": r.rmse_image, "rmse_image_full": f.rmse_image,
            })
    return out


def table(report: Report) -> str:
    lines = [
        f"adapter   {report.adapter['name']} ({report.adapter['device_type']}), {report.size[0]}x{report.size[1]}, "
        f"{report.frames} timed frames back to back after {report.warmup} warm-up frame(s) and {report.warmup_seconds:g} s of sustained rendering",
        f"reference {report.reference} {report.reference_settings}; its cost (ms): "
        + ", ".join(f"{k} {v:.1f}" for k, v in report.reference_ms.items()),
    ]
    if report.note:
        lines.append(f"note      {report.note}")
    head = f"{'scene':<16}{'plan':<6}{'method':<10}{'N':>6}{'rsm':>6}{'kernel':>10}{'total ms':>11}{'IQR':>20}{'[min,max]':>20}{'RMSE ind.':>12}{'± seeds':>10}{'RMSE img':>11}{'relMSE':>10}"
    lines += [head, "-" * len(head)]
    for r in report.rows:
        lines.append(
            f"{r.scene:<16}{r.plan:<6}{r.method:<10}{r.num_lights or '-':>6}{r.rsm_size or '-':>6}{r.kernel or '-':>10}"
            f"{r.total_ms_median:>11.3f}{f'[{r.total_ms_q1:.3f},{r.total_ms_q3:.3f}]':>20}{f'[{r.total_ms_min:.3f},{r.total_ms_max:.3f}]':>20}"
            f"{r.rmse_indirect:>12.5g}{r.rmse_indirect_std:>10.2g}{r.rmse_image:>11.5g}{r.relmse_indirect:>10.4g}"
        )
    for p in report.plan_ratios:
        lines.append(
            f"plan      {p['scene']} {p['method']} N={p['num_lights'] or '-'} rsm={p['rsm_size'] or '-'}: pruned/full time "
            f"{p['ratio']:.3f} ({p['auto_ms']:.3f} / {p['full_ms']:.3f} ms), image RMSE {p['rmse_image_auto']:.5g} vs {p['rmse_image_full']:.5g}"
        )
    return "\n".join(lines)


def write(report: Report, out) -> None:
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "bench.json").write_text(json.dumps(report.to_json(), indent=1))
    with open(out / "bench.csv", "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(["scene", "plan", "method", "num_lights", "rsm_size", "kernel", "seeds", "total_ms_median", "total_ms_q1", "total_ms_q3", "total_ms_min", "total_ms_max",
                         "rmse_indirect", "rmse_indirect_std", "rmse_image", "relmse_indirect", "relmse_image", "flip_image", "passes_ms"])
        for r in report.rows:
            writer.writerow([r.scene, r.plan, r.method, r.num_lights, r.rsm_size, r.kernel, r.seeds, r.total_ms_median, r.total_ms_q1, r.total_ms_q3, r.total_ms_min, r.total_ms_max,
                             r.rmse_indirect, r.rmse_indirect_std, r.rmse_image, r.relmse_indirect, r.relmse_image, r.flip_image, json.dumps(r.passes_ms)])
    (out / "bench.txt").write_text(table(report) + "\n")
    _plots(report, out)


def _plots(report: Report, out: pathlib.Path) -> None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    title = f"{report.adapter['name']}, {report.size[0]}x{report.size[1]}"
    series: dict[tuple, list[Row]] = {}
    for r in report.rows:
        series.setdefault((r.scene, r.method, r.rsm_size, r.kernel), []).append(r)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for (scene, method, rsm, kernel), rows in series.items():
        rows = [r for r in rows if r.rmse_indirect > 0]
        if rows:
            label = f"{scene} {method}" + (f" {kernel}" if kernel else "") + (f" rsm{rsm}" if rsm else "")
            ax.loglog([r.total_ms_median for r in rows], [r.rmse_indirect for r in rows], "o-", label=label)
    ax.set_xlabel("GPU time per frame (ms)")
    ax.set_ylabel("RMSE of indirect vs reference")
    ax.set_title(title + (" (CPU: ratios only)" if report.note else ""), fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "error_vs_time.png", dpi=120)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for (scene, method, rsm, kernel), rows in series.items():
        rows = [r for r in rows if r.num_lights and r.rmse_indirect > 0]
        if rows:
            label = f"{scene} {method}" + (f" {kernel}" if kernel else "") + (f" rsm{rsm}" if rsm else "")
            ax.loglog([r.num_lights for r in rows], [r.rmse_indirect for r in rows], "o-", label=label)
    ax.set_xlabel("number of VPLs / VSGLs")
    ax.set_ylabel("RMSE of indirect vs reference")
    ax.set_title(title, fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "error_vs_lights.png", dpi=120)
    plt.close(fig)


def _ints(text: str) -> list[int]:
    return [int(x) for x in text.split(",") if x]


def _strs(text: str) -> list[str]:
    return [x for x in text.split(",") if x]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m vsgl bench", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", type=_strs, default=["cornell_box"], help="comma-separated built-in names or .gltf/.glb paths (default: cornell_box)")
    p.add_argument("--methods", type=_strs, default=["vpl", "vsgl"], help="comma-separated names from vsgl.METHODS (default: vpl,vsgl)")
    p.add_argument("--lights", type=_ints, default=[16, 64, 256], help="comma-separated VPL/VSGL counts (default: 16,64,256)")
    p.add_argument("--size", default="256x256", help="WIDTHxHEIGHT (default: 256x256)")
    p.add_argument("--rsm-sizes", type=_ints, default=[256], help="comma-separated RSM sides (default: 256)")
    p.add_argument("--kernels", type=_strs, default=["integral"], help="VSGL kernels: integral, density (default: integral)")
    p.add_argument("--interleave", type=int, default=8, help="VSGL interleaving (default: 8)")
    p.add_argument("--vpl-interleave", type=int, default=1,
                   help="VPL interleaving, denoised like the VSGLs (default: 1, every VPL at every pixel; 8 compares as the papers do)")
    p.add_argument("--seeds", type=int, default=3, help="seeds per stochastic configuration (default: 3)")
    p.add_argument("--frames", type=int, default=5, help="timed frames per configuration and seed (default: 5)")
    p.add_argument("--warmup", type=int, default=1, help="untimed frames first (default: 1)")
    p.add_argument("--warmup-seconds", type=float, default=1.0, help="then this long of back-to-back rendering before timing, so the GPU leaves its idle clock (default: 1)")
    p.add_argument("--reference", default="reference", choices=["reference", "pathtrace"], help="what errors are measured against (default: reference)")
    p.add_argument("--reference-rsm", type=int, default=1024, help="RSM side of the reference (default: 1024)")
    p.add_argument("--reference-spp", type=int, default=256, help="samples per pixel of a pathtrace reference (default: 256)")
    p.add_argument("--plans", type=_strs, default=["auto"], help="pass plans to time: auto, full (default: auto; auto,full reports the pruned/full ratio)")
    p.add_argument("--adapter", default=None, help="adapter name substring")
    p.add_argument("--out", default="bench-out", help="output folder for CSV, JSON, plots and the reference cache (default: bench-out)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    a = p.parse_args(argv)
    try:
        w, h = (int(x) for x in a.size.lower().split("x"))
    except ValueError:
        p.error(f"--size: expected WIDTHxHEIGHT, got {a.size!r}")
    report = run(
        scenes=a.scene, methods=a.methods, lights=a.lights, size=(w, h), rsm_sizes=a.rsm_sizes, kernels=a.kernels,
        seeds=tuple(range(a.seeds)), frames=a.frames, warmup=a.warmup, warmup_seconds=a.warmup_seconds, reference=a.reference, reference_rsm=a.reference_rsm,
        reference_spp=a.reference_spp, interleave=a.interleave, vpl_interleave=a.vpl_interleave, plans=tuple(a.plans), adapter=a.adapter, out=a.out, progress=not a.no_progress,
    )
    print(table(report))
    print(f"wrote     {os.path.join(a.out, 'bench.csv')}, bench.json, bench.txt and plots (with matplotlib)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
