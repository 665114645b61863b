"""Error against run time: ``python -m vsgl bench`` and ``vsgl.bench.run(...)``.

Sweeps methods × light counts × RSM sizes × VSGL kernels (× K with ``--K``, × the SG lighting forms of
vsgl and vsgl2 with ``--lighting asg,accurate,blend``, × any other method option with ``-O NAME=V1,V2``,
for the methods that take it) over scenes at one resolution. For each
configuration it reports GPU time per pass and in total (median, interquartile range and
extremes over frames rendered back to back after a warm-up of ``--warmup-seconds`` of sustained
rendering, so the GPU leaves its idle clock; from timestamp queries; the SM clock before and
after the timed frames where ``nvidia-ml-py`` is installed), and the error of the ``indirect`` AOV and of the full
image against the scene's reference (``reference`` by default, computed once per scene, view
and settings, and cached on disk), as the mean and spread over seeds for stochastic methods.
Writes a terminal table, ``bench.csv``, ``bench.json`` and, with matplotlib, ``error_vs_time.png``,
``error_vs_lights.png`` and ``bias_noise_vs_lights.png``. On a CPU adapter only ratios inside one report mean anything.

Error you can trust (docs/error.md): the reference reports its own error
(``reference_rel_error``: from its stderr for ``pathtrace``, from the difference to one at half
the RSM side for ``reference``), and a row whose error is not at least 3× that is flagged
"reference too noisy". Stochastic methods get ``bias`` and ``noise`` apart and
``relmse_indirect_debiased`` (the MSE less the reference's variance) with a 90% interval, and
``equal_time`` names, per scene and time budget, the method with the lowest debiased error and
by how much it beats the runner-up.

Called with no sizes on a CPU adapter (lavapipe), the defaults scale down so the run takes about
two minutes, and the report and stderr say which.

With ``--plans auto,full`` every configuration also runs with the pass plan forced to
``"full"`` (nothing left out), and the report gives the pruned/full time ratio per configuration
(``plan_ratios``) next to both errors, which must agree: pruning never changes the image.

With ``--importance rsm,brsm`` every vpl and vsgl configuration also runs with bidirectional RSM
importance (``importance="brsm"``, its rows marked ``brsm``), so the sweep compares the two
sampling densities at equal light counts and, through ``equal_time``, at equal time;
``--importance-interleave K`` sets the brsm rows' ``importance_interleave``. Every ``--sampling``
combines with it (Metropolis chains then follow the re-weighted density).
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
# The `sampling=` values of vpl and vsgl (--sampling sweeps them).
SAMPLINGS = ("stratified", "random", "metropolis")
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
#: A row's error must be at least this many times the reference's own error to be trusted.
TRUST_FACTOR = 3.0
#: Convergence order p assumed for the every-texel reference in the RSM side n (error ∝ n^−p),
#: to turn the difference of two RSM sizes into an error estimate (``_rsm_reference_error``).
#: First order is the cautious choice: point-sampled texels near contacts and glossy lobes
#: converge about that slowly, and a smooth scene (p ≈ 2) only makes the estimate an overestimate.
RSM_REFERENCE_ORDER = 1.0
#: The smallest RSM side a reference may have (the methods' option range).
MIN_RSM = 32


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
    # Error you can trust (docs/error.md); None where the reference's indirect light is zero.
    # ‖x − ref‖/‖ref‖ of the indirect AOV, RMS over seeds: the number the trust check compares.
    rel_rmse_indirect: float | None = None
    # Relative RMS error of the mean over seeds, less noise and the reference's variance.
    bias: float | None = None
    # Relative RMS of the per-pixel standard deviation over seeds (0 for deterministic methods;
    # None for a stochastic one run with a single seed).
    noise: float | None = None
    # (MSE − mean Var(ref)) / mean(ref²) of the indirect AOV, with its 90% interval.
    relmse_indirect_debiased: float | None = None
    relmse_indirect_debiased_interval: tuple[float, float] | None = None
    # The reference's own estimated relative RMS error (the same for every row of a scene).
    reference_rel_error: float | None = None
    # True when rel_rmse_indirect < TRUST_FACTOR × reference_rel_error: the error is mostly the
    # reference's own; `notes` then holds "reference too noisy".
    reference_too_noisy: bool = False
    notes: list[str] = field(default_factory=list)
    # Perceptual and low-pass errors, mean over seeds: SSIM of the tone-mapped image and the
    # relative RMS error of 8×8 block averages of the indirect AOV.
    ssim_image: float | None = None
    block_rmse_indirect: float | None = None
    # vsgl's kernel mass K when --K sweeps it (None: the method's default, 1).
    K: float | None = None
    # vsgl / vsgl2's lighting= when --lighting sweeps it (None: the method's default, "blend").
    lighting: str | None = None
    # The RSM sampling density of vpl and vsgl, "rsm" or "brsm" (bidirectional importance,
    # --importance); None for the methods that sample nothing.
    importance: str | None = None
    # vpl's and vsgl's `sampling=` when --sampling sweeps it (None: the default, "stratified").
    sampling: str | None = None
    # Any other method options swept by --option NAME=V1,V2 (only those this method takes);
    # None when none was swept for it.
    options: dict[str, Any] | None = None
    # With --sequence N: metrics.flicker of the indirect AOV over N frames of a moving light
    # (the scene's animation, or its lights slid along x) against the every-texel reference of
    # the same frames; stochastic methods draw seed k in frame k, as a real-time renderer would.
    flicker_indirect: float | None = None


@dataclass
class Report:
    adapter: dict[str, Any]
    size: tuple[int, int]
    reference: str
    reference_settings: dict[str, Any]
    # Per scene: wall milliseconds of the whole reference render, every batch included (on a
    # CPU adapter lavapipe's timestamps cover a fraction of the work; the wall clock covers all).
    reference_ms: dict[str, float]
    frames: int
    warmup: int
    rows: list[Row] = field(default_factory=list)
    # Seconds of back-to-back rendering before each configuration's timed frames.
    warmup_seconds: float = 0.0
    # Visibility of every virtual light in the sweep ("none", "raytrace", "ism").
    visibility: str = "none"
    note: str = ""
    # Per configuration run with both plans: pruned ("auto") over "full" median total time.
    plan_ratios: list[dict[str, Any]] = field(default_factory=list)
    # Per scene: the sum of the reference's GPU timestamps over all its batches, and how many.
    reference_gpu_ms: dict[str, float] = field(default_factory=dict)
    reference_batches: dict[str, int] = field(default_factory=dict)
    # Per scene: the reference's own estimated relative RMS error of its indirect AOV, and how
    # it was estimated (reference_error_method).
    reference_rel_error: dict[str, float | None] = field(default_factory=dict)
    reference_error_method: str = ""
    # Per scene and time budget: the method with the lowest debiased error within the budget
    # and its margin over the best row of another method (see _equal_time).
    equal_time: list[dict[str, Any]] = field(default_factory=list)
    # Settings a CPU adapter scaled down from GPU_DEFAULTS (name: value used), if any.
    scaled_for_cpu: dict[str, Any] = field(default_factory=dict)
    # Frames of the flicker sequence per configuration (0: not measured) and how it moves.
    sequence: int = 0
    sequence_motion: dict[str, str] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        d = asdict(self)
        d["rows"] = [asdict(r) for r in self.rows]
        return d


def _quartiles(v: list[float]) -> tuple[float, float]:
    if len(v) < 2:
        return v[0], v[0]
    q = statistics.quantiles(v, n=4, method="inclusive")
    return q[0], q[2]


class _SmClock:
    """The SM clock in MHz through NVML (optional `nvidia-ml-py`): `read()` now, `max_mhz` the boost."""

    def __init__(self, read, max_mhz: int) -> None:
        self.read, self.max_mhz = read, max_mhz

    def warm(self, mhz: int) -> bool:
        return mhz >= CLOCK_WARM_FRACTION * self.max_mhz


#: A timed frame counts as warm when the SM clock read at least this fraction of its maximum
#: before and after it (DESIGN.md, "Clocks": idle 345–360 MHz, boost 1980 on an H200).
CLOCK_WARM_FRACTION = 0.9
#: How long the warm-up may go on past `warmup_seconds` while the clock is still below that.
CLOCK_WARM_MAX_EXTRA_S = 5.0


def _clock_for(cpu: bool) -> _SmClock | None:
    """The SM clock to watch: none on a CPU adapter, which has no clock states to leave."""
    return None if cpu else _sm_clock_reader()


def _sm_clock_reader() -> _SmClock | None:
    """The SM clock of GPU 0 through NVML, or None."""
    try:
        import pynvml  # type: ignore[import-not-found]

        pynvml.nvmlInit()
        handle = pynvml.nvmlDeviceGetHandleByIndex(0)
        max_mhz = int(pynvml.nvmlDeviceGetMaxClockInfo(handle, pynvml.NVML_CLOCK_SM))
        return _SmClock(lambda: int(pynvml.nvmlDeviceGetClockInfo(handle, pynvml.NVML_CLOCK_SM)), max_mhz)
    except Exception:  # not installed, no NVIDIA driver, no device: clocks are not reported
        return None


#: The corpus scenes a bench run without --scene adds to cornell_box: real files whose
#: every-texel reference is the path tracer's truth within 2% (docs/rendering.md, "The real-scene
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


@dataclass
class _ReferenceRender:
    image: np.ndarray
    indirect: np.ndarray
    # Variance of each value of `indirect` (stderr² of a path tracer); None when deterministic.
    indirect_var: np.ndarray | None
    gpu_ms: float
    wall_ms: float
    batches: int


def _reference(renderer, scene, size, method, settings, cache_dir, progress=None) -> _ReferenceRender:
    """Renders (or loads from the cache) one reference image with what its error needs."""
    key = _reference_key(scene, size, method, settings)
    path = None if cache_dir is None else pathlib.Path(cache_dir) / f"reference-{key}.npz"
    fields = ("image", "indirect", "timings", "wall_ms", "batches") + (("stderr",) if method == "pathtrace" else ())
    if path is not None and path.exists():
        data = np.load(path)
        if all(f in data for f in fields):  # older caches lack the cost and the stderr
            return _ReferenceRender(
                data["image"], data["indirect"], data["stderr"].astype(np.float64) ** 2 if "stderr" in fields else None,
                float(json.loads(str(data["timings"])).get("total", 0.0)), float(data["wall_ms"]), int(data["batches"]),
            )
    aovs = ["image", "indirect"] + (["stderr"] if method == "pathtrace" else [])
    batches = [1]

    def each_batch(done: int, total: int, unit: str) -> None:
        batches[0] += 1
        if progress is not None:
            progress(done, total, unit)

    t = time.perf_counter()
    frame = renderer.render(scene, method=method, aovs=aovs, progress=each_batch, **settings)
    wall_ms = 1e3 * (time.perf_counter() - t)
    timings = dict(frame.timings_ms)
    stderr = frame.aov("stderr") if method == "pathtrace" else None
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        extra = {"stderr": stderr} if stderr is not None else {}
        np.savez_compressed(path, image=frame.image, indirect=frame.aov("indirect"), timings=json.dumps(timings),
                            wall_ms=wall_ms, batches=batches[0], **extra)
    return _ReferenceRender(
        frame.image, frame.aov("indirect"), None if stderr is None else stderr.astype(np.float64) ** 2,
        float(timings.get("total", 0.0)), wall_ms, batches[0],
    )


def _rsm_reference_error(fine: np.ndarray, other: np.ndarray, other_is_coarser: bool) -> float:
    """The n² reference's relative RMS error, estimated from its difference to one at n/2 (or
    2n where n/2 is below the smallest RSM), assuming error ∝ n^−p (RSM_REFERENCE_ORDER):
    ref(n/2) − ref(n) = e(n)(2^p − 1) and ref(n) − ref(2n) = e(n)(1 − 2^−p), as in Richardson
    extrapolation. An estimate: it assumes the error's pattern is the same at both sizes."""
    p = RSM_REFERENCE_ORDER
    scale = (2**p - 1) if other_is_coarser else (1 - 2**-p)
    return metrics.rel_rmse(other, fine) / scale


def _reference_progress(label: str, enabled: bool):
    """A progress(done, total, unit) callback showing the reference's own batches on stderr (a
    tqdm bar, or a line without tqdm), and a function that ends it. (None, no-op) when disabled."""
    if not enabled:
        return None, lambda: None
    state: dict[str, Any] = {}

    def show(done: int, total: int, unit: str) -> None:
        try:
            from tqdm import tqdm
        except ImportError:
            print(f"\r{label}: {done}/{total} {unit} ({100.0 * done / max(total, 1):.0f}%)", end="", file=sys.stderr, flush=True)
            state["line"] = True
            return
        if "bar" not in state:
            state["bar"] = tqdm(total=total, unit=unit, unit_scale=True, desc=label, file=sys.stderr, leave=False)
        state["bar"].update(done - state["bar"].n)

    def close() -> None:
        if "bar" in state:
            state["bar"].close()
        if state.get("line"):
            print(file=sys.stderr)

    return show, close


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
) -> Report:
    """Runs the sweep and returns a :class:`Report`; with ``out`` also writes CSV, JSON and plots.

    Settings left at None take GPU_DEFAULTS, or CPU_DEFAULTS on a CPU adapter (then printed to
    stderr and listed in ``report.scaled_for_cpu``)."""
    if frames is not None and frames < 1:
        raise ValueError(f"frames: must be >= 1, got {frames}")
    if not (warmup_seconds >= 0 and np.isfinite(warmup_seconds)):
        raise ValueError(f"warmup_seconds: must be finite and >= 0, got {warmup_seconds}")
    if reference not in ("reference", "pathtrace"):
        raise ValueError(f"reference: must be \"reference\" or \"pathtrace\", got {reference!r}")
    if reference_strategy not in ("camera", "bidirectional", "light"):
        raise ValueError(f"reference_strategy: must be \"camera\", \"bidirectional\" or \"light\", got {reference_strategy!r}")
    unknown = [m for m in methods if m not in vsgl.METHODS]
    if unknown:
        raise ValueError(f"methods: unknown {unknown}; valid: {', '.join(vsgl.METHODS)}")
    bad_plans = [p for p in plans if p not in ("auto", "full")]
    if bad_plans or not plans:
        raise ValueError(f"plans: expected a non-empty list of \"auto\" and \"full\", got {list(plans)}")
    if seeds is not None and len(seeds) < 1:
        raise ValueError("seeds: expected at least one seed")
    if not Ks or any(K is not None and not (isinstance(K, (int, float)) and np.isfinite(K) and K > 0) for K in Ks):
        raise ValueError(f"Ks: expected kernel masses K > 0 (or None for the default), got {list(Ks)}")
    if not lightings:
        raise ValueError("lightings: expected SG lighting forms of vsgl (or None for the default), got none")
    for lighting in lightings:
        if lighting is not None:
            # The core's option spec is the one list of forms (vsgl.method_options("vsgl")).
            try:
                vsgl.check_method_options("vsgl", lighting=lighting)
            except vsgl.ArgumentError as e:
                raise ValueError(f"lightings: {e}") from e
    bad_importance = [i for i in importances if i not in ("rsm", "brsm")]
    if bad_importance or not importances:
        raise ValueError(f"importances: expected a non-empty list of \"rsm\" and \"brsm\", got {list(importances)}")
    if importance_interleave is not None and not (isinstance(importance_interleave, int) and 1 <= importance_interleave <= 16):
        raise ValueError(f"importance_interleave: expected an integer 1..16 (or None for the default), got {importance_interleave!r}")
    if not samplings or any(s not in (None, *SAMPLINGS) for s in samplings):
        raise ValueError(f"samplings: expected values from {', '.join(SAMPLINGS)} (or None for the default), got {list(samplings)}")
    options = dict(options or {})
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
    if visibility not in ("none", "raytrace", "ism"):
        raise ValueError(f"visibility: must be \"none\", \"raytrace\" or \"ism\", got {visibility!r}")
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
    configs = []
    for m in methods:
        if m in ("vpl", "vsgl"):
            for n in lights:
                for r in rsm_sizes:
                    for k in (kernels if m == "vsgl" else (None,)):
                        for K in (Ks if m == "vsgl" else (None,)):
                            for li in (lightings if m == "vsgl" else (None,)):
                                for imp in importances:
                                    for s in samplings:
                                        configs.append((m, n, r, k, K, li, imp, s))
        elif m in ("reference", "vsgl2"):
            # Deterministic and without a light count: one configuration per RSM size.
            for r in rsm_sizes:
                for li in (lightings if m == "vsgl2" else (None,)):
                    configs.append((m, None, r, None, None, li, None, None))
        else:
            configs.append((m, None, None, None, None, None, None, None))
    # --option axes, for the methods that take each option; then the plans, which alternate
    # inside one configuration so both see the same machine state.
    configs = [(*c, extra) for c in configs for extra in _option_combinations(c[0], options)]
    # A value the method refuses fails here, naming the option, before the scenes' references
    # (minutes on a GPU at high spp) are rendered.
    for m, *_rest, extra in configs:
        vsgl.check_method_options(m, **dict(extra))
    configs = [(*c, plan) for c in configs for plan in plans]
    # Per row (by its index in report.rows): its SeedErrors, for the equal-time comparisons.
    seed_stats: dict[int, metrics.SeedErrors] = {}
    for scene_name in scenes:
        scene = _lit_scene(scene_name, scene_lights, add_lights)
        motion = None
        if sequence:
            motion, truth_frames = _sequence_truth(renderer, scene_name, scene_lights, add_lights, sequence, reference_rsm)
            report.sequence_motion[scene_name] = motion
        ref = _scene_reference(renderer, scene, scene_name, (w, h), reference, ref_settings, cache_dir, progress, report)
        ref_error = report.reference_rel_error[scene_name]
        ref_has_light = bool(np.any(ref.indirect != 0))
        bar = _progress(len(configs), progress)
        for method, n, rsm, kernel, K, lighting, importance, sampling, extra, plan in configs:
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
            if method == "vpl":
                # 1: every VPL at every pixel (the baseline); 8: the papers' equal-footing
                # comparison, interleaved and denoised like the VSGLs.
                settings["interleave"] = vpl_interleave
            if method in ("vpl", "vsgl", "vsgl2", "reference") and visibility != "none":
                settings["visibility"] = visibility
            run_seeds = seeds if method in STOCHASTIC else (0,)
            # Read back only what the errors need (readback is most of the wall time).
            settings["aovs"] = ["image"] if method == "direct" else ["image", "indirect"]
            totals: list[float] = []
            per_pass: dict[str, list[float]] = {}
            errs: dict[str, list[float]] = {"rmse_indirect": [], "rmse_image": [], "relmse_indirect": [], "relmse_image": [], "flip": [], "ssim": []}
            indirects: list[np.ndarray] = []
            # Sustained load first: frames back to back (nothing read back) until the GPU has left
            # its idle clock (DESIGN.md, "Clocks"): `warmup_seconds`, and where NVML reads the SM
            # clock, on until it is warm (at most CLOCK_WARM_MAX_EXTRA_S more). Then every seed's
            # frames back to back, and the errors only after them: a second of CPU work for the
            # metrics between seeds let an H200 fall back to 360–900 MHz, which made some rows of
            # a sweep 2–7x slower than their neighbours.
            warm_frames = 0
            t_end = time.perf_counter() + report.warmup_seconds
            quiet = {k: v for k, v in settings.items() if k != "aovs"}
            while time.perf_counter() < t_end or (
                    sm_clock is not None and not sm_clock.warm(sm_clock.read()) and time.perf_counter() < t_end + CLOCK_WARM_MAX_EXTRA_S):
                renderer.render(scene, method=method, aovs=[], **quiet)
                warm_frames += 1
            clocks: list[int] = []
            seed_frames: list[Any] = []
            for seed in run_seeds:
                if method in STOCHASTIC:
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
                _trust(row, indirects, ref, method in STOCHASTIC, seed_stats, len(report.rows))
            if sequence:
                seq = _sequence_frames(renderer, scene_name, scene_lights, add_lights, sequence, method, settings)
                row.flicker_indirect = metrics.flicker(seq, truth_frames) if np.any(truth_frames != 0) else None
            if all(np.array_equal(x, ref.indirect) for x in indirects):
                # Bit for bit the reference (same method and settings): it cannot judge itself,
                # and it does not compete in equal_time.
                row.notes.append("the reference itself")
            report.rows.append(row)
            bar.update(1)
        bar.close()
    report.plan_ratios = _plan_ratios(report.rows)
    report.equal_time = _equal_time(report.rows, seed_stats)
    if out is not None:
        write(report, out)
    return report


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
        moved = []
        for light in scene.lights:
            if isinstance(light, vsgl.SpotLight):
                x, y, z = light.position
                moved.append(vsgl.SpotLight(position=(x + dx, y, z), direction=light.direction, intensity=light.intensity,
                                            color=light.color, inner_cone_deg=light.inner_cone_deg, outer_cone_deg=light.outer_cone_deg))
            elif isinstance(light, vsgl.PointLight):
                x, y, z = light.position
                moved.append(vsgl.PointLight(position=(x + dx, y, z), intensity=light.intensity, color=light.color))
            else:
                moved.append(light)
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
        seed = {"seed": k} if method in STOCHASTIC else {}
        frame = renderer.render(scene, method=method, aovs=["indirect"] if method != "direct" else ["image"], **quiet, **seed)
        out.append(frame.aov("indirect") if method != "direct" else np.zeros_like(frame.image))
    return np.stack(out)


def _shown(name: str, value: Any) -> str:
    if name == "size":
        return f"{value[0]}x{value[1]}"
    if isinstance(value, (tuple, list)):
        return ",".join(map(str, value))
    return str(value)


def _scene_reference(renderer, scene, scene_name, size, reference, ref_settings, cache_dir, progress, report) -> _ReferenceRender:
    """The scene's reference (showing its own progress), its cost, and its own error estimate."""
    show, close = _reference_progress(f"{scene_name}: {reference}", progress)
    if progress:
        print(f"bench: {scene_name}: the reference ({reference} {ref_settings}) first; cached in {cache_dir}", file=sys.stderr)
    try:
        ref = _reference(renderer, scene, size, reference, ref_settings, cache_dir, show)
    finally:
        close()
    report.reference_ms[scene_name] = ref.wall_ms
    report.reference_gpu_ms[scene_name] = ref.gpu_ms
    report.reference_batches[scene_name] = ref.batches
    scale = float(np.mean(ref.indirect.astype(np.float64) ** 2))
    if scale == 0.0:
        report.reference_rel_error[scene_name] = None  # no indirect light: nothing to be relative to
    elif ref.indirect_var is not None:  # pathtrace: its stderr²
        report.reference_rel_error[scene_name] = float(np.sqrt(np.mean(ref.indirect_var) / scale))
    else:
        n = ref_settings["rsm_size"]
        coarser = n // 2 >= MIN_RSM
        other_settings = dict(ref_settings, rsm_size=n // 2 if coarser else 2 * n)
        show, close = _reference_progress(f"{scene_name}: {reference} at rsm {other_settings['rsm_size']} (its own error)", progress)
        try:
            other = _reference(renderer, scene, size, reference, other_settings, cache_dir, show)
        finally:
            close()
        report.reference_ms[scene_name] += other.wall_ms
        report.reference_gpu_ms[scene_name] += other.gpu_ms
        report.reference_batches[scene_name] += other.batches
        report.reference_rel_error[scene_name] = _rsm_reference_error(ref.indirect, other.indirect, coarser)
    return ref


def _trust(row: Row, indirects: list[np.ndarray], ref: _ReferenceRender, stochastic: bool, seed_stats: dict, index: int) -> None:
    """Fills the row's relative error, bias, noise, debiased error and the trust flag."""
    row.rel_rmse_indirect = float(np.sqrt(np.mean([metrics.rel_rmse(x, ref.indirect) ** 2 for x in indirects])))
    row.block_rmse_indirect = float(np.mean([metrics.block_rmse(x, ref.indirect) for x in indirects]))
    stats = metrics.seed_errors(np.stack(indirects), ref.indirect, ref.indirect_var)
    seed_stats[index] = stats
    row.bias = stats.bias
    # A deterministic method has no noise; a stochastic one with one seed cannot show its own.
    row.noise = stats.noise if stochastic else 0.0
    row.relmse_indirect_debiased = stats.relmse_debiased
    row.relmse_indirect_debiased_interval = stats.interval
    if row.reference_rel_error is not None and not row.rel_rmse_indirect >= TRUST_FACTOR * row.reference_rel_error:
        row.reference_too_noisy = True
        row.notes.append("reference too noisy")


def _kernel_label(kernel: str | None, K: float | None) -> str | None:
    """The kernel as tables and plots name it: with K when --K set it ("integral K=4")."""
    if kernel is None:
        return None
    return kernel if K is None else f"{kernel} K={K:g}"


def _method_label(r: Row) -> str:
    """The method as tables and plots name it: with its lighting when --lighting set it
    ("vsgl:accurate") and the options --option swept ("vsgl(lambert_lobe=papers)")."""
    label = r.method + (f":{r.lighting}" if r.lighting else "")
    if r.options:
        label += "(" + ",".join(f"{k}={v}" for k, v in r.options.items()) + ")"
    return label


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


def _label(r: Row) -> str:
    k = " ".join(x for x in (_kernel_label(r.kernel, r.K), r.sampling) if x)
    return _method_label(r) + (f"[{k}]" if k else "") + ("+brsm" if r.importance == "brsm" else "")


def _brief(r: Row) -> dict[str, Any]:
    return {"method": _method_label(r), "kernel": _kernel_label(r.kernel, r.K), "importance": r.importance, "sampling": r.sampling, "num_lights": r.num_lights, "rsm_size": r.rsm_size, "total_ms": r.total_ms_median,
            "relmse_indirect_debiased": r.relmse_indirect_debiased, "interval": r.relmse_indirect_debiased_interval,
            "reference_too_noisy": r.reference_too_noisy}


def _equal_time(rows: list[Row], seed_stats: dict[int, metrics.SeedErrors]) -> list[dict[str, Any]]:
    """Per scene, for each time budget of the sweep (each distinct median total time of its
    rows): the row with the lowest debiased error among those within the budget, and the best
    row of another method within it, with the runner-up's excess error over the best (ratio and
    difference, 90% intervals from a bootstrap on shared pixel tiles). The pruned plan's rows
    count where both plans ran; the reference itself does not compete, nor do rows timed on a
    cold clock (their note says so)."""
    plan = "auto" if any(r.plan == "auto" for r in rows) else rows[0].plan if rows else "auto"
    out: list[dict[str, Any]] = []
    for scene in dict.fromkeys(r.scene for r in rows):
        eligible = [i for i, r in enumerate(rows) if r.scene == scene and r.plan == plan and i in seed_stats and "the reference itself" not in r.notes
                    and not any(n.startswith("clock cold") for n in r.notes)]
        budgets = sorted({rows[i].total_ms_median for i in eligible})
        if not budgets:
            out.append({"scene": scene, "budget_ms": None, "best": None, "runner_up": None, "runner_up_vs_best": None,
                        "why": "no row with a debiased error (the reference has no indirect light, or only the reference ran)"})
        for budget in budgets:
            within = sorted((i for i in eligible if rows[i].total_ms_median <= budget), key=lambda i: seed_stats[i].relmse_debiased)
            best = within[0]
            others = [i for i in within if _label(rows[i]) != _label(rows[best])]
            runner = others[0] if others else None
            out.append({
                "scene": scene, "budget_ms": budget, "best": _brief(rows[best]),
                "runner_up": _brief(rows[runner]) if runner is not None else None,
                "runner_up_vs_best": metrics.compare_debiased(seed_stats[best], seed_stats[runner]) if runner is not None else None,
            })
    return out


def _plan_ratios(rows: list[Row]) -> list[dict[str, Any]]:
    """Pairs each "auto" row with the "full" row of the same configuration."""
    key = lambda r: (r.scene, r.method, r.num_lights, r.rsm_size, r.kernel, r.K, r.lighting, r.importance, r.sampling, _method_label(r))  # noqa: E731
    full = {key(r): r for r in rows if r.plan == "full"}
    out = []
    for r in rows:
        f = full.get(key(r)) if r.plan == "auto" else None
        if f is not None:
            out.append({
                "scene": r.scene, "method": _method_label(r), "num_lights": r.num_lights, "rsm_size": r.rsm_size, "kernel": r.kernel,
                "auto_ms": r.total_ms_median, "full_ms": f.total_ms_median, "ratio": r.total_ms_median / f.total_ms_median,
                "passes_ratio": {k: r.passes_ms[k] / f.passes_ms[k] for k in r.passes_ms if f.passes_ms.get(k, 0) > 0},
                "rmse_image_auto": r.rmse_image, "rmse_image_full": f.rmse_image,
            })
    return out


def _interval(iv) -> str:
    return f"[{iv[0]:.3g},{iv[1]:.3g}]" if iv is not None else "-"


def _num(v, fmt: str) -> str:
    return "-" if v is None else format(v, fmt)


def table(report: Report) -> str:
    ref_error = ", ".join(f"{k} {_num(v, '.3g')}" for k, v in report.reference_rel_error.items())
    cost = ", ".join(
        f"{k} {v / 1e3:.1f} s wall over {report.reference_batches.get(k, 1)} batch(es) ({report.reference_gpu_ms.get(k, 0.0):.1f} ms GPU timestamps)"
        for k, v in report.reference_ms.items()
    )
    lines = [
        f"adapter   {report.adapter['name']} ({report.adapter['device_type']}), {report.size[0]}x{report.size[1]}, "
        f"{report.frames} timed frames back to back after {report.warmup} warm-up frame(s) and {report.warmup_seconds:g} s of sustained rendering",
        f"reference {report.reference} {report.reference_settings}; its own error (relative RMS of indirect, estimated): {ref_error}",
        f"          rows whose error is under {TRUST_FACTOR:g}x that are flagged 'reference too noisy'; its cost: {cost}",
        f"visibility {report.visibility} (of every virtual light in the sweep)",
    ]
    if report.note:
        lines.append(f"note      {report.note}")
    if report.sequence:
        moves = ", ".join(f"{k}: {v}" for k, v in report.sequence_motion.items())
        lines.append(f"flicker   metrics.flicker of indirect over {report.sequence} frames against the reference's frames "
                     f"(seed k in frame k for vpl and vsgl; {moves})")
    flick = bool(report.sequence)
    # The sampling column only when --sampling swept it.
    samp = any(r.sampling is not None for r in report.rows)
    head = (f"{'scene':<16}{'plan':<6}{'method':<16}{'N':>6}{'rsm':>6}{'kernel':>14}{'imp.':>6}{format('sampling', '>12') if samp else ''}{'total ms':>11}{'IQR':>20}{'RMSE ind.':>12}{'± seeds':>10}"
            f"{'rel ind.':>10}{'bias':>9}{'noise':>9}{'debiased':>11}{'90%':>20}{'SSIM':>7}{format('flicker', '>9') if flick else ''}  flag")
    lines += [head, "-" * len(head)]
    for r in report.rows:
        lines.append(
            f"{r.scene:<16}{r.plan:<6}{_method_label(r):<16}{r.num_lights or '-':>6}{r.rsm_size or '-':>6}{_kernel_label(r.kernel, r.K) or '-':>14}"
            f"{r.importance or '-':>6}{format(r.sampling or '-', '>12') if samp else ''}{r.total_ms_median:>11.3f}{f'[{r.total_ms_q1:.3f},{r.total_ms_q3:.3f}]':>20}"
            f"{r.rmse_indirect:>12.5g}{r.rmse_indirect_std:>10.2g}{_num(r.rel_rmse_indirect, '.4g'):>10}{_num(r.bias, '.3g'):>9}{_num(r.noise, '.3g'):>9}"
            f"{_num(r.relmse_indirect_debiased, '.4g'):>11}{_interval(r.relmse_indirect_debiased_interval):>20}{_num(r.ssim_image, '.3f'):>7}"
            f"{format(_num(r.flicker_indirect, '.4g'), '>9') if flick else ''}  {'; '.join(r.notes)}"
        )
    for p in report.plan_ratios:
        lines.append(
            f"plan      {p['scene']} {p['method']} N={p['num_lights'] or '-'} rsm={p['rsm_size'] or '-'}: pruned/full time "
            f"{p['ratio']:.3f} ({p['auto_ms']:.3f} / {p['full_ms']:.3f} ms), image RMSE {p['rmse_image_auto']:.5g} vs {p['rmse_image_full']:.5g}"
        )
    # Consecutive budgets with the same winner and runner-up say the same: one line for them.
    groups: list[list[dict[str, Any]]] = []
    for e in report.equal_time:
        same = lambda a: (a["scene"], json.dumps(a["best"]), json.dumps(a["runner_up"]))  # noqa: E731
        if groups and same(groups[-1][-1]) == same(e):
            groups[-1].append(e)
        else:
            groups.append([e])
    for g in groups:
        lines.append(_equal_time_line(g[0], g[-1]["budget_ms"]))
    return "\n".join(lines)


def _equal_time_line(e: dict[str, Any], last_budget_ms: float | None = None) -> str:
    if e["best"] is None:
        return f"equal time {e['scene']}: {e['why']}"

    def who(b: dict[str, Any]) -> str:
        variant = " ".join(x for x in (b["kernel"], b.get("sampling")) if x)
        name = b["method"] + (f"[{variant}]" if variant else "") + (f" N={b['num_lights']}" if b["num_lights"] else "")
        return f"{name} {b['relmse_indirect_debiased']:.4g} {_interval(b['interval'])}"

    budget = f"<= {e['budget_ms']:.3f} ms" if last_budget_ms in (None, e["budget_ms"]) else f"<= {e['budget_ms']:.3f} to {last_budget_ms:.3f} ms"
    line = f"equal time {e['scene']} {budget}: best {who(e['best'])}"
    c = e["runner_up_vs_best"]
    if c is None:
        return line + "; no other method within this budget"
    lo, hi = c["ratio_interval"]
    ratio = "undefined (best below the reference's resolution)" if c["ratio"] is None else (
        f"{c['ratio']:.3g}x [{_num(lo, '.3g')},{_num(hi, '.3g')}]")
    return line + f"; runner-up {who(e['runner_up'])}: {ratio} the best's debiased error, difference {c['difference']:.3g} {_interval(c['difference_interval'])}"


CSV_COLUMNS = [
    "scene", "plan", "method", "num_lights", "rsm_size", "kernel", "K", "lighting", "importance", "sampling", "options", "seeds", "total_ms_median", "total_ms_q1", "total_ms_q3", "total_ms_min", "total_ms_max",
    "rmse_indirect", "rmse_indirect_std", "rmse_image", "relmse_indirect", "relmse_image", "flip_image", "rel_rmse_indirect", "bias", "noise",
    "relmse_indirect_debiased", "relmse_indirect_debiased_lo", "relmse_indirect_debiased_hi", "reference_rel_error", "reference_too_noisy",
    "ssim_image", "block_rmse_indirect", "flicker_indirect", "notes", "passes_ms",
]


def write(report: Report, out) -> None:
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "bench.json").write_text(json.dumps(report.to_json(), indent=1))
    with open(out / "bench.csv", "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(CSV_COLUMNS)
        for r in report.rows:
            iv = r.relmse_indirect_debiased_interval or (None, None)
            values = dict(asdict(r), relmse_indirect_debiased_lo=iv[0], relmse_indirect_debiased_hi=iv[1], notes="; ".join(r.notes), passes_ms=json.dumps(r.passes_ms),
                          options=";".join(f"{k}={v}" for k, v in (r.options or {}).items()))
            writer.writerow([values[c] for c in CSV_COLUMNS])
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
        series.setdefault((r.scene, _method_label(r), r.rsm_size, " ".join(x for x in (_kernel_label(r.kernel, r.K), r.sampling) if x) or None, r.importance), []).append(r)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for (scene, method, rsm, kernel, importance), rows in series.items():
        rows = [r for r in rows if r.rel_rmse_indirect]
        if rows:
            label = f"{scene} {method}" + (f" {kernel}" if kernel else "") + (" brsm" if importance == "brsm" else "") + (f" rsm{rsm}" if rsm else "")
            ax.loglog([r.total_ms_median for r in rows], [r.rel_rmse_indirect for r in rows], "o-", label=label)
    # The reference's own error is the floor no error can be judged below: a row needs 3× it.
    for scene, floor in report.reference_rel_error.items():
        if floor:
            ax.axhline(floor, linestyle="--", color="grey", linewidth=1)
            ax.axhline(TRUST_FACTOR * floor, linestyle=":", color="grey", linewidth=1)
            ax.annotate(f"{scene}: reference's own error (dashed), {TRUST_FACTOR:g}x (dotted)", (0.01, floor), xycoords=("axes fraction", "data"), fontsize=6, color="grey")
    ax.set_xlabel("GPU time per frame (ms)")
    ax.set_ylabel("relative RMS error of indirect vs reference")
    ax.set_title(title + (" (CPU: ratios only)" if report.note else ""), fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "error_vs_time.png", dpi=120)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for (scene, method, rsm, kernel, importance), rows in series.items():
        rows = [r for r in rows if r.num_lights and r.rmse_indirect > 0]
        if rows:
            label = f"{scene} {method}" + (f" {kernel}" if kernel else "") + (" brsm" if importance == "brsm" else "") + (f" rsm{rsm}" if rsm else "")
            ax.loglog([r.num_lights for r in rows], [r.rmse_indirect for r in rows], "o-", label=label)
    ax.set_xlabel("number of VPLs / VSGLs")
    ax.set_ylabel("RMSE of indirect vs reference")
    ax.set_title(title, fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "error_vs_lights.png", dpi=120)
    plt.close(fig)
    # Bias (solid) and noise (dashed) apart: what separates VSGL (bias) from VPL (noise).
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for (scene, method, rsm, kernel, importance), rows in series.items():
        rows = [r for r in rows if r.num_lights and r.bias is not None and r.noise is not None]
        if rows:
            label = f"{scene} {method}" + (f" {kernel}" if kernel else "") + (" brsm" if importance == "brsm" else "") + (f" rsm{rsm}" if rsm else "")
            (line,) = ax.plot([r.num_lights for r in rows], [max(r.bias, 1e-6) for r in rows], "o-", label=f"{label}: bias")
            ax.plot([r.num_lights for r in rows], [max(r.noise, 1e-6) for r in rows], "s--", color=line.get_color(), label=f"{label}: noise")
    for scene, floor in report.reference_rel_error.items():
        if floor:
            ax.axhline(floor, linestyle=":", color="grey", linewidth=1, label=f"{scene}: reference's own error")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("number of VPLs / VSGLs")
    ax.set_ylabel("relative bias and noise of indirect (over seeds)")
    ax.set_title(title, fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "bias_noise_vs_lights.png", dpi=120)
    plt.close(fig)


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
    p.add_argument("--kernels", type=_strs, default=["integral"], help="VSGL kernels: integral, density, node (default: integral)")
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
    p.add_argument("--reference", default="reference", choices=["reference", "pathtrace"], help="what errors are measured against (default: reference)")
    p.add_argument("--reference-rsm", type=int, default=None,
                   help="RSM side of the reference (default: 1024; 256 on a CPU adapter); its own error comes from one at half the side")
    p.add_argument("--reference-spp", type=int, default=None, help="samples per pixel of a pathtrace reference (default: 256); its own error comes from its stderr")
    p.add_argument("--reference-strategy", default="bidirectional", choices=["camera", "bidirectional", "light"],
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
        samplings=tuple(a.sampling) if a.sampling else (None,), options=dict(a.option),
    )
    print(table(report))
    print(f"wrote     {os.path.join(a.out, 'bench.csv')}, bench.json, bench.txt and plots (with matplotlib)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
