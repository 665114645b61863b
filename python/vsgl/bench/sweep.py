"""The sweep, run(): its defaults, configurations, scenes, flicker sequences and each row's
trusted error."""

from __future__ import annotations

import functools
import pathlib
import statistics
import sys
from dataclasses import dataclass
from typing import Any

import numpy as np

import vsgl
from vsgl import metrics
from vsgl.scene_edit import with_fields

from .output import write
from .reference import MIN_RSM, RSM_REFERENCE_ORDER, _ReferenceRender, _scene_reference, book_reference
from .report import TRUST_FACTOR, Report, Row, _equal_time, _plan_ratios
from .timing import _clock_for, _quartiles, warm_up


@functools.lru_cache(maxsize=None)
def _info(method: str) -> dict:
    """The registry's entry, read once per method (it is asked per configuration, seed and frame)."""
    return vsgl.method_info(method)


def _stochastic(method: str) -> bool:
    """Whether the method's frames depend on ``seed`` (the registry says), so a row averages seeds."""
    return bool(_info(method)["stochastic"])


def _takes(method: str, option: str) -> bool:
    return option in _info(method)["options"]


def _makes_indirect(method: str) -> bool:
    return "indirect" in _info(method)["aovs"]


def _choices(option: str, method: str = "vsgl") -> tuple[str, ...]:
    """The values the core takes for a choice option (the registry's one list of them)."""
    return tuple(_info(method)["options"][option]["choices"])


# The `sampling=` values of vpl and vsgl (--sampling sweeps them), from the registry.
SAMPLINGS = _choices("sampling")
# sampling="metropolis": each seed's error frame comes from fresh chains stepped this many
# frames first (other seeds), so seeds are independent and the chains have left their
# stratified start (the warp's lattice) for the unstratified equilibrium they render at.
METROPOLIS_BURN_IN = 16

#: Defaults of the settings that decide the run time, on a GPU.
GPU_DEFAULTS: dict[str, Any] = {
    "size": (256, 256), "lights": (16, 64, 256), "rsm_sizes": (256,), "seeds": (0, 1, 2),
    "frames": 5, "warmup": 1, "reference_rsm": 1024, "reference_spp": 256,
}
#: The same on a CPU adapter, where lavapipe evaluates ~10⁷–10⁸ pixel·VPL pairs per second: the
#: GPU defaults took 950 s there (935 s of it the 1024² reference); these take about two minutes.
CPU_DEFAULTS: dict[str, Any] = {
    "size": (80, 80), "lights": (16, 64, 256), "rsm_sizes": (128,), "seeds": (0, 1, 2),
    "frames": 2, "warmup": 1, "reference_rsm": 256, "reference_spp": 256,
}


#: The corpus scenes a bench run without --scene adds to cornell_box: real files whose
#: every-texel reference is the path tracer's truth within 2% (docs/scenes.md, "The real-scene
#: corpus": on BoomBox and FlightHelmet it is not, so they are left to an explicit --scene).
CORPUS_DEFAULT_SCENES = ("cornell_box_original", "cornell_box_mm")


def default_scenes() -> list[str]:
    """The scenes of a bench run given no --scene: cornell_box and the corpus scenes of
    CORPUS_DEFAULT_SCENES whose files are present (a note on stderr names those that are not)."""
    present = [n for n in CORPUS_DEFAULT_SCENES if vsgl.scenes.corpus_available(n)]
    missing = [n for n in CORPUS_DEFAULT_SCENES if n not in present]
    if missing:
        print(f"bench: corpus scenes {', '.join(missing)} left out: no files under {vsgl.scenes.shared_scenes_dir()} "
              f"(set ${vsgl.scenes.SHARED_SCENES_ENV})", file=sys.stderr)
    return ["cornell_box", *present]


def _scene(name: str) -> vsgl.Scene:
    """A built-in, a corpus scene (lit by its committed spec) or a glTF file, by name."""
    if name in vsgl.scenes.names():
        return vsgl.scenes.load(name)
    if name in vsgl.scenes.corpus_names():
        return vsgl.scenes.corpus_scene(name).scene
    return vsgl.Scene.load(name)


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


def _resolve_defaults(given: dict[str, Any], cpu: bool) -> tuple[dict[str, Any], dict[str, Any]]:
    """The settings to use (the caller's, else the adapter's defaults) and those a CPU adapter
    scaled down from the GPU defaults."""
    defaults = CPU_DEFAULTS if cpu else GPU_DEFAULTS
    used = {k: (defaults[k] if v is None else v) for k, v in given.items()}
    scaled = {k: defaults[k] for k, v in given.items() if v is None and defaults[k] != GPU_DEFAULTS[k]}
    return used, scaled


def _core_check(axis: str, **options: Any) -> None:
    """`vsgl.check_method_options("vsgl", **options)`, its error prefixed with the sweep's `axis`."""
    try:
        vsgl.check_method_options("vsgl", **options)
    except vsgl.ArgumentError as e:
        raise ValueError(f"{axis}: {e}") from e


def _check_arguments(*, frames, warmup_seconds, reference, reference_strategy, methods, plans, seeds, Ks, lightings, importances, importance_interleave, samplings, options, sequence) -> None:
    """The sweep's own arguments (ranges and choices of method options are the core's: each is
    handed to `vsgl.check_method_options`, so this holds no second copy of them)."""
    if frames is not None and frames < 1:
        raise ValueError(f"frames: must be >= 1, got {frames}")
    if not (warmup_seconds >= 0 and np.isfinite(warmup_seconds)):
        raise ValueError(f"warmup_seconds: must be finite and >= 0, got {warmup_seconds}")
    truths = [m for m in vsgl.METHODS if vsgl.method_info(m)["ground_truth"]]
    if reference not in truths:
        raise ValueError(f"reference: must be one of {', '.join(map(repr, truths))} (the ground-truth methods), got {reference!r}")
    strategies = vsgl.method_info("pathtrace")["options"]["strategy"]["choices"]
    if reference_strategy not in strategies:
        raise ValueError(f"reference_strategy: must be one of {', '.join(map(repr, strategies))} (pathtrace's strategy=), got {reference_strategy!r}")
    unknown = [m for m in methods if m not in vsgl.METHODS]
    if unknown:
        raise ValueError(f"methods: unknown {unknown}; valid: {', '.join(vsgl.METHODS)}")
    bad_plans = [p for p in plans if p not in ("auto", "full")]
    if bad_plans or not plans:
        raise ValueError(f"plans: expected a non-empty list of \"auto\" and \"full\", got {list(plans)}")
    if seeds is not None and (isinstance(seeds, (str, bytes)) or not hasattr(seeds, "__len__")
                              or not all(isinstance(x, int) and not isinstance(x, bool) for x in seeds)):
        raise ValueError(f"seeds: expected a list of integer seeds, e.g. (0, 1), got {seeds!r}")
    if seeds is not None and len(seeds) < 1:
        raise ValueError("seeds: expected at least one seed")
    if not Ks:
        raise ValueError("Ks: expected kernel masses K (or None for the default), got none")
    if not lightings:
        raise ValueError("lightings: expected SG lighting forms of vsgl (or None for the default), got none")
    # The core's option specs are the one list of ranges and forms (vsgl.method_options("vsgl")).
    for axis, option, values in (("Ks", "K", Ks), ("lightings", "lighting", lightings)):
        for value in values:
            if value is not None:
                _core_check(axis, **{option: value})
    known_importances = _choices("importance")
    if not importances or any(i not in known_importances for i in importances):
        raise ValueError(f"importances: expected a non-empty list of {', '.join(map(repr, known_importances))}, got {list(importances)}")
    if importance_interleave is not None:
        _core_check("importance_interleave", importance="brsm", importance_interleave=importance_interleave)
    if not samplings or any(s not in (None, *SAMPLINGS) for s in samplings):
        raise ValueError(f"samplings: expected values from {', '.join(SAMPLINGS)} (or None for the default), got {list(samplings)}")
    for name, values in options.items():
        takers = [m for m in methods if name in vsgl.method_options(m)]
        if not takers:
            raise ValueError(f"options: {name!r} is an option of none of the methods {list(methods)}; `python -m vsgl methods` lists each one's")
        if name in SWEPT_ELSEWHERE:
            raise ValueError(f"options: {name!r} has its own axis or setting ({SWEPT_ELSEWHERE[name]}); use that")
        if isinstance(values, (str, bytes)) or not hasattr(values, "__len__") or len(values) == 0:
            raise ValueError(f"options: {name!r} needs a non-empty list of values, got {values!r}")
    if isinstance(sequence, bool) or not isinstance(sequence, int) or sequence < 0 or sequence == 1:
        raise ValueError(f"sequence: expected 0 (off) or a number of frames >= 2, got {sequence!r}")


def _configurations(*, methods, lights, rsm_sizes, kernels, Ks, lightings, importances, samplings, options, plans) -> list[tuple]:
    """Every configuration of the sweep: (method, N, RSM size, kernel, K, lighting, importance,
    sampling, other options, plan), each axis only for the methods that take its option."""
    configs = []
    # Each axis for the methods that take its option (the registry's option lists).
    def axis(m: str, option: str, values):
        return values if _takes(m, option) else (None,)

    for m in methods:
        if _takes(m, "num_lights"):
            for n in lights:
                for r in rsm_sizes:
                    for k in axis(m, "kernel", kernels):
                        for K in axis(m, "K", Ks):
                            for li in axis(m, "lighting", lightings):
                                for imp in axis(m, "importance", importances):
                                    for s in axis(m, "sampling", samplings):
                                        configs.append((m, n, r, k, K, li, imp, s))
        elif _takes(m, "rsm_size"):
            # Without a light count (every texel, or two sums over them): one configuration
            # per RSM size.
            for r in rsm_sizes:
                for li in axis(m, "lighting", lightings):
                    configs.append((m, None, r, None, None, li, None, None))
        else:
            configs.append((m, None, None, None, None, None, None, None))
    # --option axes, for the methods that take each option; then the plans, which alternate
    # inside one configuration so both see the same machine state.
    configs = [(*c, extra) for c in configs for extra in _option_combinations(c[0], options)]
    # A value the method refuses, or a combination it refuses (K with a k-means kernel), fails
    # here, naming the option, before the scenes' references (minutes on a GPU at high spp) are
    # rendered.
    for m, _n, _r, kernel, K, lighting, importance, sampling, extra in configs:
        axes = dict(kernel=kernel, K=K, lighting=lighting, importance=importance, sampling=sampling)
        vsgl.check_method_options(m, **{k: v for k, v in axes.items() if v is not None}, **dict(extra))
    return [(*c, plan) for c in configs for plan in plans]


def run(
    scenes=("cornell_box",),
    methods=("vpl", "vsgl"),
    lights=None,
    size=None,
    rsm_sizes=None,
    kernels=("integral",),
    seeds=None,
    frames=None,
    warmup=None,
    warmup_seconds=1.0,
    reference="reference",
    reference_rsm=None,
    reference_spp=None,
    reference_strategy="bidirectional",
    add_lights=(),
    scene_lights=True,
    interleave=8,
    vpl_interleave=1,
    visibility="none",
    plans=("auto",),
    adapter=None,
    out=None,
    cache_dir=None,
    progress=True,
    sequence=0,
    Ks=(None,),
    lightings=(None,),
    importances=("rsm",),
    samplings=(None,),
    importance_interleave=None,
    options=None,
    cluster=None,
    cluster_gpu_resource="GPU",
    _on_cluster_result=None,
) -> Report:
    """Runs the sweep and returns a :class:`Report`; with ``out`` also writes CSV, JSON and plots.

    ``cluster`` ("auto", "local" or HOST:PORT, with ``out``): every reference and configuration
    runs as a Ray task asking for one ``cluster_gpu_resource``, results are kept in
    ``out/cluster/`` and a rerun measures only what is missing (``vsgl.bench.cluster``).

    Settings left at None take GPU_DEFAULTS, or CPU_DEFAULTS on a CPU adapter (then printed to
    stderr and listed in ``report.scaled_for_cpu``)."""
    options = dict(options or {})
    if cluster is not None:
        from .cluster import check_arguments as _check_cluster

        _check_cluster(cluster, out)
    _check_arguments(frames=frames, warmup_seconds=warmup_seconds, reference=reference, reference_strategy=reference_strategy,
                     methods=methods, plans=plans, seeds=seeds, Ks=Ks, lightings=lightings, importances=importances,
                     importance_interleave=importance_interleave, samplings=samplings, options=options, sequence=sequence)
    # The adapter decides the defaults; a tiny renderer finds it (~0.1 s) before the real one.
    probe = vsgl.Renderer(width=8, height=8, adapter=adapter) if size is None else None
    renderer = probe or vsgl.Renderer(width=size[0], height=size[1], adapter=adapter)
    cpu = renderer.adapter["device_type"] == "Cpu"
    given = {"size": size, "lights": lights, "rsm_sizes": rsm_sizes, "seeds": seeds, "frames": frames,
             "warmup": warmup, "reference_rsm": reference_rsm, "reference_spp": reference_spp}
    used, scaled = _resolve_defaults(given, cpu)
    size, lights, rsm_sizes, seeds = used["size"], used["lights"], used["rsm_sizes"], used["seeds"]
    frames, warmup, reference_rsm, reference_spp = used["frames"], used["warmup"], used["reference_rsm"], used["reference_spp"]
    w, h = size
    if probe is not None:
        renderer = vsgl.Renderer(width=w, height=h, adapter=adapter)
    # A pathtrace reference combines light tracing with camera paths by default (caustics
    # converge), and so averages each pixel's area where the methods shade its centre: at
    # geometric edges that difference is part of the error it reports (docs/error.md).
    if visibility not in _choices("visibility"):
        raise ValueError(f"visibility: must be one of {', '.join(map(repr, _choices('visibility')))}, got {visibility!r}")
    ref_settings: dict[str, Any] = {"rsm_size": reference_rsm} if reference == "reference" else {"spp": reference_spp, "strategy": reference_strategy}
    if reference == "reference" and visibility != "none":
        # The every-texel reference shadows its VPLs exactly (ray traced) whenever the methods
        # shadow theirs, so their error is the method's and not the shadows'.
        ref_settings["visibility"] = "raytrace"
    if out is not None and cache_dir is None:
        cache_dir = pathlib.Path(out) / "cache"
    sm_clock = _clock_for(cpu)
    notes = []
    if cpu:
        notes.append("CPU adapter: absolute times are meaningless; compare only ratios within this report (no warm-up time).")
    if scaled:
        said = ", ".join(f"{k} {_shown(k, v)} (GPU default {_shown(k, GPU_DEFAULTS[k])})" for k, v in scaled.items())
        notes.append(f"CPU adapter: defaults scaled down to finish in about two minutes: {said}; set any of them to override.")
        print(f"bench: {notes[-1]}", file=sys.stderr)
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
        note=" ".join(notes),
        scaled_for_cpu=scaled,
        sequence=sequence,
        visibility=visibility,
        reference_error_method=(
            "pathtrace: sqrt(mean(stderr²) / mean(ref²)) of the indirect AOV, the expected relative RMS error of its mean"
            if reference == "pathtrace" else
            f"reference: relRMSE to the reference at half the RSM side (double below {2 * MIN_RSM}), assuming error ∝ "
            f"rsm_size^-{RSM_REFERENCE_ORDER:g}; an estimate; taken as deterministic (zero variance) in the debiased error"
        ),
    )
    configs = _configurations(methods=methods, lights=lights, rsm_sizes=rsm_sizes, kernels=kernels, Ks=Ks, lightings=lightings,
                              importances=importances, samplings=samplings, options=options, plans=plans)
    # Per row (by its index in report.rows): its SeedErrors, for the equal-time comparisons.
    seed_stats: dict[int, metrics.SeedErrors] = {}
    shared = SweepSettings(interleave=interleave, vpl_interleave=vpl_interleave, visibility=visibility,
                           importance_interleave=importance_interleave, seeds=tuple(seeds), frames=frames, warmup=warmup,
                           warmup_seconds=report.warmup_seconds, sequence=sequence, scene_lights=scene_lights,
                           add_lights=tuple(add_lights))
    if cluster is not None:
        # Every reference and configuration as a task on the cluster (vsgl.bench.cluster).
        from .cluster import sweep_on_cluster

        seed_stats = sweep_on_cluster(report, cluster=cluster, scenes=scenes, configs=configs, shared=shared, size=(w, h), adapter=adapter,
                                      reference=reference, ref_settings=ref_settings, reference_rsm=reference_rsm, out=out,
                                      gpu_resource=cluster_gpu_resource, progress=progress, on_result=_on_cluster_result)
        scenes = ()  # measured there
    for scene_name in scenes:
        scene = _lit_scene(scene_name, scene_lights, add_lights)
        motion, truth_frames = None, None
        if sequence:
            motion, truth_frames = _sequence_truth(renderer, scene_name, scene_lights, add_lights, sequence, reference_rsm)
            report.sequence_motion[scene_name] = motion
        ref, book = _scene_reference(renderer, scene, scene_name, (w, h), reference, ref_settings, cache_dir, progress)
        book_reference(report, scene_name, book)
        ref_error = report.reference_rel_error[scene_name]
        bar = _progress(len(configs), progress)
        for config in configs:
            row, stats = measure_configuration(renderer, scene_name, scene, ref, ref_error, config, shared, sm_clock, truth_frames)
            if stats is not None:
                seed_stats[len(report.rows)] = stats
            report.rows.append(row)
            bar.update(1)
        bar.close()
    report.plan_ratios = _plan_ratios(report.rows)
    report.equal_time = _equal_time(report.rows, seed_stats)
    if out is not None:
        write(report, out)
    return report


@dataclass(frozen=True)
class SweepSettings:
    """What every configuration of a sweep shares, besides its scene and reference: enough to
    measure one configuration anywhere (in this process, or as a task on a cluster node)."""

    interleave: int
    vpl_interleave: int
    visibility: str
    importance_interleave: int | None
    seeds: tuple[int, ...]
    frames: int
    warmup: int
    warmup_seconds: float
    sequence: int
    scene_lights: bool
    add_lights: tuple = ()


def measure_configuration(renderer, scene_name: str, scene, ref: _ReferenceRender, ref_error: float | None, config: tuple,
                          run: SweepSettings, sm_clock=None, truth_frames: np.ndarray | None = None) -> tuple[Row, "metrics.SeedErrors | None"]:
    """One row of the sweep: ``config`` (an entry of ``_configurations``) rendered on ``scene``
    against its reference, timed after the warm-up, with its errors; and its per-seed errors
    for the equal-time comparison (None where the reference has no indirect light)."""
    method, n, rsm, kernel, K, lighting, importance, sampling, extra, plan = config
    interleave, vpl_interleave, visibility = run.interleave, run.vpl_interleave, run.visibility
    importance_interleave, seeds, frames, warmup = run.importance_interleave, run.seeds, run.frames, run.warmup
    ref_has_light = bool(np.any(ref.indirect != 0))
    stats = None
    settings: dict[str, Any] = {"plan": plan, **dict(extra)}
    if sampling is not None:
        settings["sampling"] = sampling
    # Metropolis chains start afresh for each configuration (they are kept from frame to
    # frame of the renderer otherwise), so rows do not depend on their order.
    renderer.reset_chains()
    if n is not None:
        settings["num_lights"] = n
    if rsm is not None:
        settings["rsm_size"] = rsm
    if kernel is not None:
        settings.update(kernel=kernel, interleave=interleave)
    if K is not None:
        settings["K"] = float(K)
    if lighting is not None:
        settings["lighting"] = lighting
    if importance == "brsm":
        # The default, "rsm", is left unsaid so the sweep's rsm rows render as before.
        settings["importance"] = importance
        if importance_interleave is not None:
            settings["importance_interleave"] = importance_interleave
    if kernel is None and _takes(method, "interleave"):
        # VPLs: 1: every VPL at every pixel (the baseline); 8: the papers'
        # equal-footing comparison, interleaved and denoised like the VSGLs.
        settings["interleave"] = vpl_interleave
    if _takes(method, "visibility") and visibility != "none":
        settings["visibility"] = visibility
    run_seeds = seeds if _stochastic(method) else (0,)
    # Read back only what the errors need (readback is most of the wall time).
    settings["aovs"] = ["image", "indirect"] if _makes_indirect(method) else ["image"]
    totals: list[float] = []
    per_pass: dict[str, list[float]] = {}
    errs: dict[str, list[float]] = {"rmse_indirect": [], "rmse_image": [], "relmse_indirect": [], "relmse_image": [], "flip": [], "ssim": []}
    indirects: list[np.ndarray] = []
    # Sustained load first: frames back to back (nothing read back) until the GPU has left
    # its idle clock (docs/error.md, cold clocks): `warmup_seconds`, and where NVML reads the SM
    # clock, on until it is warm (at most CLOCK_WARM_MAX_EXTRA_S more). Then every seed's
    # frames back to back, and the errors only after them: a second of CPU work for the
    # metrics between seeds let an H200 fall back to 360–900 MHz, which made some rows of
    # a sweep 2–7x slower than their neighbours.
    quiet = {k: v for k, v in settings.items() if k != "aovs"}
    warm_frames = warm_up(lambda: renderer.render(scene, method=method, aovs=[], **quiet), run.warmup_seconds, sm_clock)
    clocks: list[int] = []
    seed_frames: list[Any] = []
    for seed in run_seeds:
        if _stochastic(method):
            settings["seed"] = seed
        if sampling == "metropolis":
            renderer.reset_chains()
            for j in range(METROPOLIS_BURN_IN):
                renderer.render(scene, method=method, aovs=[], **{**quiet, "seed": (seed + 1) * 1_000_003 + j})
        for _ in range(warmup):
            renderer.render(scene, method=method, **settings)
        if sm_clock is not None:
            clocks.append(sm_clock.read())
        frame = None
        for _ in range(frames):
            frame = renderer.render(scene, method=method, **settings)
            totals.append(frame.timings_ms["total"])
            for k2, v in frame.timings_ms.items():
                if k2 != "total":
                    per_pass.setdefault(k2, []).append(v)
        if sm_clock is not None:
            clocks.append(sm_clock.read())
        seed_frames.append(frame)
    for frame in seed_frames:
        indirect = frame.aov("indirect") if "indirect" in frame.aovs else np.zeros_like(ref.indirect)
        indirects.append(indirect)
        errs["rmse_indirect"].append(metrics.rmse(indirect, ref.indirect))
        errs["rmse_image"].append(metrics.rmse(frame.image, ref.image))
        errs["relmse_indirect"].append(metrics.relmse(indirect, ref.indirect))
        errs["relmse_image"].append(metrics.relmse(frame.image, ref.image))
        errs["ssim"].append(metrics.ssim(frame.image, ref.image))
        f = metrics.flip(frame.image, ref.image)
        if f is not None:
            errs["flip"].append(f)
    row = Row(
        scene=scene_name,
        method=method,
        num_lights=n,
        rsm_size=rsm,
        kernel=kernel,
        K=K,
        lighting=lighting,
        importance=importance,
        sampling=sampling,
        options=dict(extra) or None,
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
        ssim_image=float(np.mean(errs["ssim"])),
        reference_rel_error=ref_error,
    )
    if clocks and not sm_clock.warm(min(clocks)):
        # Its times are not comparable with warm rows: said in the row, not hidden.
        row.notes.append(f"clock cold ({min(clocks)}-{max(clocks)} of {sm_clock.max_mhz} MHz)")
    if ref_has_light:
        stats = _trust(row, indirects, ref, _stochastic(method))
    if run.sequence:
        seq = _sequence_frames(renderer, scene_name, run.scene_lights, run.add_lights, run.sequence, method, settings)
        row.flicker_indirect = metrics.flicker(seq, truth_frames) if np.any(truth_frames != 0) else None
    if all(np.array_equal(x, ref.indirect) for x in indirects):
        # Bit for bit the reference (same method and settings): it cannot judge itself,
        # and it does not compete in equal_time.
        row.notes.append("the reference itself")
    return row, stats


def _lit_scene(scene_name: str, scene_lights: bool, add_lights) -> vsgl.Scene:
    """A fresh copy of the scene with the bench's light options applied."""
    scene = _scene(scene_name)
    if not scene_lights:
        scene.lights = []
    for light in add_lights:
        scene.add_light(light)
    return scene


def _sequence_changes(scene: vsgl.Scene, frames: int) -> tuple[str, list[dict[str, Any]]]:
    """Per frame: {"time": t} over the scene's animations when it has any, else {"lights": ...}
    with every spot and point light slid along +x across 10% of the bounds diagonal (a
    directional light has no position and stays). Returns (a description, the changes)."""
    if scene.animations:
        duration = max(a["duration"] for a in scene.animations)
        times = [duration * k / (frames - 1) for k in range(frames)]
        return f"animation over {duration:g} s", [{"time": t} for t in times]
    lo, hi = (np.array(v) for v in scene.bounds)
    span = 0.1 * float(np.linalg.norm(hi - lo))
    changes = []
    for k in range(frames):
        dx = span * (k / (frames - 1) - 0.5)
        moved = [with_fields(light, position=(light.position[0] + dx, *light.position[1:])) if hasattr(light, "position") else light
                 for light in scene.lights]
        changes.append({"lights": moved})
    return f"lights slid {span:.3g} along +x", changes


def _sequence_truth(renderer, scene_name, scene_lights, add_lights, frames, reference_rsm) -> tuple[str, np.ndarray]:
    """The every-texel reference's indirect AOV for each frame of the flicker sequence."""
    scene = _lit_scene(scene_name, scene_lights, add_lights)
    motion, changes = _sequence_changes(scene, frames)
    truth = np.stack([f.aov("indirect") for f in renderer.render_sequence(
        scene, changes, method="reference", aovs=["indirect"], rsm_size=reference_rsm)])
    return motion, truth


def _sequence_frames(renderer, scene_name, scene_lights, add_lights, frames, method, settings) -> np.ndarray:
    """The method's indirect AOV over the flicker sequence, seed k in frame k for a
    stochastic method (fresh random numbers every frame, as a real-time renderer draws them)."""
    scene = _lit_scene(scene_name, scene_lights, add_lights)
    _, changes = _sequence_changes(scene, frames)
    quiet = {k: v for k, v in settings.items() if k not in ("aovs", "seed")}
    # sampling="metropolis": the sequence starts from fresh chains, kept through its frames.
    renderer.reset_chains()
    out = []
    for k, change in enumerate(changes):
        if "time" in change:
            scene.set_time(change["time"])
        else:
            scene.lights = change["lights"]
        seed = {"seed": k} if _stochastic(method) else {}
        indirect = _makes_indirect(method)
        frame = renderer.render(scene, method=method, aovs=["indirect"] if indirect else ["image"], **quiet, **seed)
        out.append(frame.aov("indirect") if indirect else np.zeros_like(frame.image))
    return np.stack(out)


def _shown(name: str, value: Any) -> str:
    if name == "size":
        return f"{value[0]}x{value[1]}"
    if isinstance(value, (tuple, list)):
        return ",".join(map(str, value))
    return str(value)


def _trust(row: Row, indirects: list[np.ndarray], ref: _ReferenceRender, stochastic: bool) -> "metrics.SeedErrors":
    """Fills the row's relative error, bias, noise, debiased error and the trust flag; returns
    the per-seed errors (for the equal-time comparison)."""
    row.rel_rmse_indirect = float(np.sqrt(np.mean([metrics.rel_rmse(x, ref.indirect) ** 2 for x in indirects])))
    row.block_rmse_indirect = float(np.mean([metrics.block_rmse(x, ref.indirect) for x in indirects]))
    stats = metrics.seed_errors(np.stack(indirects), ref.indirect, ref.indirect_var)
    row.bias = stats.bias
    # A deterministic method has no noise; a stochastic one with one seed cannot show its own.
    row.noise = stats.noise if stochastic else 0.0
    row.relmse_indirect_debiased = stats.relmse_debiased
    row.relmse_indirect_debiased_interval = stats.interval
    if row.reference_rel_error is not None and not row.rel_rmse_indirect >= TRUST_FACTOR * row.reference_rel_error:
        row.reference_too_noisy = True
        row.notes.append("reference too noisy")
    return stats


# Options that have their own axis or setting in the sweep: --option would fight it.
SWEPT_ELSEWHERE = {
    "num_lights": "--lights", "rsm_size": "--rsm-sizes", "kernel": "--kernels", "K": "--K", "lighting": "--lighting",
    "importance": "--importance", "importance_interleave": "--importance-interleave", "sampling": "--sampling",
    "interleave": "--interleave / --vpl-interleave", "visibility": "--visibility", "seed": "--seeds", "plan": "--plans",
}


def _option_combinations(method: str, options: dict[str, Any]) -> list[tuple[tuple[str, Any], ...]]:
    """Every combination of the --option values this method takes, as (name, value) pairs; one
    empty combination when it takes none of them."""
    combos: list[tuple[tuple[str, Any], ...]] = [()]
    for name, values in options.items():
        if name in vsgl.method_options(method):
            combos = [(*c, (name, v)) for c in combos for v in values]
    return combos
