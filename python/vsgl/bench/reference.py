"""The scene's reference: rendered once per scene, view and settings and cached on disk, with
its cost, its progress on stderr and its own error estimate."""

from __future__ import annotations

import hashlib
import json
import pathlib
import sys
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

import vsgl
from vsgl import metrics


#: Convergence order p assumed for the every-texel reference in the RSM side n (error ∝ n^−p),
#: to turn the difference of two RSM sizes into an error estimate (``_rsm_reference_error``).
#: First order is the cautious choice: point-sampled texels near contacts and glossy lobes
#: converge about that slowly, and a smooth scene (p ≈ 2) only makes the estimate an overestimate.
RSM_REFERENCE_ORDER = 1.0
#: The smallest RSM side a reference may have (the methods' option range).
MIN_RSM = 32


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
    # A reference that estimates its own error per pixel (a path tracer's stderr AOV) keeps it.
    with_stderr = "stderr" in vsgl.method_info(method)["aovs"]
    fields = ("image", "indirect", "timings", "wall_ms", "batches") + (("stderr",) if with_stderr else ())
    if path is not None and path.exists():
        data = np.load(path)
        if all(f in data for f in fields):  # older caches lack the cost and the stderr
            return _ReferenceRender(
                data["image"], data["indirect"], data["stderr"].astype(np.float64) ** 2 if "stderr" in fields else None,
                float(json.loads(str(data["timings"])).get("total", 0.0)), float(data["wall_ms"]), int(data["batches"]),
            )
    aovs = ["image", "indirect"] + (["stderr"] if with_stderr else [])
    batches = [1]

    def each_batch(done: int, total: int, unit: str) -> None:
        batches[0] += 1
        if progress is not None:
            progress(done, total, unit)

    t = time.perf_counter()
    frame = renderer.render(scene, method=method, aovs=aovs, progress=each_batch, **settings)
    wall_ms = 1e3 * (time.perf_counter() - t)
    timings = dict(frame.timings_ms)
    stderr = frame.aov("stderr") if with_stderr else None
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


@dataclass
class ReferenceBook:
    """What a scene's reference cost and its own error estimate, as the report lists them per
    scene (``book_reference``): wall and GPU milliseconds and batches over every render it took
    (its own error needs a second one), and its relative error (None without indirect light)."""

    wall_ms: float
    gpu_ms: float
    batches: int
    rel_error: float | None


def book_reference(report, scene_name: str, book: ReferenceBook) -> None:
    """Writes ``book`` into the report's per-scene reference columns."""
    report.reference_ms[scene_name] = book.wall_ms
    report.reference_gpu_ms[scene_name] = book.gpu_ms
    report.reference_batches[scene_name] = book.batches
    report.reference_rel_error[scene_name] = book.rel_error


def _scene_reference(renderer, scene, scene_name, size, reference, ref_settings, cache_dir, progress) -> tuple[_ReferenceRender, ReferenceBook]:
    """The scene's reference (showing its own progress), its cost, and its own error estimate."""
    show, close = _reference_progress(f"{scene_name}: {reference}", progress)
    if progress:
        print(f"bench: {scene_name}: the reference ({reference} {ref_settings}) first; cached in {cache_dir}", file=sys.stderr)
    try:
        ref = _reference(renderer, scene, size, reference, ref_settings, cache_dir, show)
    finally:
        close()
    book = ReferenceBook(wall_ms=ref.wall_ms, gpu_ms=ref.gpu_ms, batches=ref.batches, rel_error=None)
    scale = float(np.mean(ref.indirect.astype(np.float64) ** 2))
    if scale == 0.0:
        pass  # no indirect light: nothing to be relative to
    elif ref.indirect_var is not None:  # pathtrace: its stderr²
        book.rel_error = float(np.sqrt(np.mean(ref.indirect_var) / scale))
    else:
        n = ref_settings["rsm_size"]
        coarser = n // 2 >= MIN_RSM
        other_settings = dict(ref_settings, rsm_size=n // 2 if coarser else 2 * n)
        show, close = _reference_progress(f"{scene_name}: {reference} at rsm {other_settings['rsm_size']} (its own error)", progress)
        try:
            other = _reference(renderer, scene, size, reference, other_settings, cache_dir, show)
        finally:
            close()
        book.wall_ms += other.wall_ms
        book.gpu_ms += other.gpu_ms
        book.batches += other.batches
        book.rel_error = _rsm_reference_error(ref.indirect, other.indirect, coarser)
    return ref, book
