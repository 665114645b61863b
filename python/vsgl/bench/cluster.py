"""A sweep on a Ray cluster: ``python -m vsgl bench ... --cluster auto|ADDRESS --out DIR`` and
``vsgl.bench.run(..., cluster=..., out=...)`` (the optional extra ``pip install 'vsgl[cluster]'``).

- Each scene's reference is one Ray task; its result (and, with ``--sequence``, the flicker
  sequence's truth) goes to the object store once and every configuration task of that scene
  reads it from there. The driver also keeps it in the result folder, so a resumed sweep does not
  render it again.
- Each configuration is one Ray task that asks for one unit of the GPU resource
  (``cluster_gpu_resource``, default ``"GPU"``) and measures the configuration exactly as the local
  sweep does (``sweep.measure_configuration``) on its own node, with a renderer it keeps for the
  tasks that follow in the same worker process.
- The driver writes each configuration's result to ``DIR/cluster/`` as its task returns, under a
  name made from everything that decides the result, and skips on a later run every
  configuration whose file exists: an interrupted sweep reruns only what is missing. No shared
  file system is assumed; only the driver writes.
- The report is the local sweep's, built from the rows in the same order; each row names the
  adapter that timed it (``Row.adapter``), as times from different GPUs differ.

- The right GPU per task: with ``--cluster-resource GPU`` (the default) Ray assigns each task a
  GPU; Vulkan ignores ``CUDA_VISIBLE_DEVICES``, so the task finds that GPU's PCI bus id with
  ``nvidia-smi`` and opens the wgpu adapter at that bus id (``Renderer(adapter="pci:...")``). A
  task given no GPU (a custom resource, a node without NVIDIA GPUs) takes the node's best adapter,
  a CPU one where there is no GPU, and its rows say which.
"""

from __future__ import annotations

import dataclasses
import hashlib
import pickle
import socket
import sys
from pathlib import Path
from typing import Any

import numpy as np

from .reference import book_reference

CLUSTER_EXTRA_HINT = "pip install 'vsgl[cluster]'"
# How long the driver waits for a cluster address to answer before giving up.
CONNECT_TIMEOUT_S = 10.0
# The result files' format; a file of another version is measured again.
RESULT_VERSION = 3


def _ray():
    try:
        import ray
    except ImportError as e:
        raise ImportError(f"bench --cluster needs the Ray extra: {CLUSTER_EXTRA_HINT} ({e})") from e
    return ray


def connect(address: str, timeout_s: float = CONNECT_TIMEOUT_S):
    """Connects the driver to the cluster at ``address`` ("auto": the one this machine belongs
    to; "local": a cluster started here for this run; else host:port) and returns ``ray``.
    ``ConnectionError`` naming the address when it does not answer within ``timeout_s``."""
    ray = _ray()
    _check_address(address)
    if address not in ("auto", "local"):
        host, _, port = address.removeprefix("ray://").rpartition(":")
        try:
            socket.create_connection((host, int(port)), timeout=timeout_s).close()
        except OSError as e:
            raise ConnectionError(f"cluster {address}: no answer within {timeout_s:g} s ({e})") from e
    if ray.is_initialized():
        return ray  # this process already joined a cluster (ray.init): its tasks go there
    try:
        ray.init(address=None if address == "local" else address, logging_level="ERROR", log_to_driver=False)
    except ConnectionError as e:
        raise ConnectionError(f"cluster {address}: could not connect ({e})") from e
    return ray


def _check_address(address: Any) -> None:
    if isinstance(address, str) and address in ("auto", "local"):
        return
    host, _, port = address.removeprefix("ray://").rpartition(":") if isinstance(address, str) else ("", "", "")
    if not host or not port.isdigit():
        raise ValueError(f"cluster: expected auto, local or HOST:PORT, got {address!r}")


def check_arguments(cluster: Any, out: Any) -> None:
    """Refuses a cluster sweep that could not run, before anything renders."""
    _check_address(cluster)
    if out is None:
        raise ValueError("bench --cluster needs --out (out=): the driver keeps each configuration's result there, "
                         "so an interrupted sweep can resume")
    _ray()


def _light_specs(lights) -> tuple:
    """Lights as (type name, constructor fields): vsgl lights are not picklable, their fields are."""
    from vsgl.scene_edit import light_fields, light_kind

    return tuple((light_kind(light), tuple(sorted(light_fields(light).items()))) for light in lights)


def _lights(specs: tuple) -> tuple:
    from vsgl.lightspec import KINDS

    return tuple(KINDS[kind][0](**dict(fields)) for kind, fields in specs)


def nvidia_bus_ids(smi_output: str) -> dict[str, str]:
    """GPU index → PCI bus id from ``nvidia-smi --query-gpu=index,pci.bus_id
    --format=csv,noheader`` ("0, 00000000:17:00.0" a line)."""
    out = {}
    for line in smi_output.splitlines():
        index, _, bus = (part.strip() for part in line.partition(","))
        if index and bus:
            out[index] = bus
    return out


def assigned_adapter(adapter: str | None, gpu_ids: list, bus_ids: dict[str, str]) -> str | None:
    """The ``Renderer(adapter=...)`` a task uses: the one the sweep names; else the GPU Ray
    assigned it, by PCI bus id (Vulkan ignores CUDA_VISIBLE_DEVICES, so the index alone would
    pick the wrong GPU on a node with several); else None, the best adapter there is (a CPU
    adapter on a node without GPUs, which each row's ``adapter`` then names)."""
    if adapter is not None:
        return adapter
    if not gpu_ids:
        return None
    index = str(gpu_ids[0])
    if index not in bus_ids:
        raise RuntimeError(f"cluster task: GPU {index} assigned by Ray has no PCI bus id in nvidia-smi's list ({bus_ids or 'empty'})")
    return f"pci:{bus_ids[index]}"


def _task_adapter(adapter: str | None) -> str | None:
    import subprocess

    import ray

    gpu_ids = ray.get_gpu_ids()
    bus_ids: dict[str, str] = {}
    if adapter is None and gpu_ids:
        smi = subprocess.run(["nvidia-smi", "--query-gpu=index,pci.bus_id", "--format=csv,noheader"], capture_output=True, text=True,
                             timeout=30, check=True)
        bus_ids = nvidia_bus_ids(smi.stdout)
    return assigned_adapter(adapter, gpu_ids, bus_ids)


# One renderer per worker process and size: tasks that follow reuse its compiled passes.
_RENDERERS: dict[tuple, Any] = {}


def _renderer(size: tuple[int, int], adapter: str | None):
    import vsgl

    adapter = _task_adapter(adapter)
    key = (tuple(size), adapter)
    if key not in _RENDERERS:
        _RENDERERS[key] = vsgl.Renderer(width=size[0], height=size[1], adapter=adapter)
    return _RENDERERS[key]


def _reference_task(scene_name: str, scene_lights: bool, light_specs: tuple, size, adapter, reference: str,
                    ref_settings: dict, sequence: int, reference_rsm) -> dict[str, Any]:
    """A scene's reference and its own error (and the flicker sequence's truth), on a worker."""
    from . import sweep
    from .reference import _scene_reference

    renderer = _renderer(size, adapter)
    lights = _lights(light_specs)
    scene = sweep._lit_scene(scene_name, scene_lights, lights)
    ref, book = _scene_reference(renderer, scene, scene_name, size, reference, ref_settings, None, False)
    out: dict[str, Any] = {"ref": ref, "book": book, "motion": None, "truth": None}
    if sequence:
        out["motion"], out["truth"] = sweep._sequence_truth(renderer, scene_name, scene_lights, lights, sequence, reference_rsm)
    return out


def _configuration_task(scene_name: str, light_specs: tuple, size, adapter, reference: dict[str, Any], config: tuple,
                        shared) -> tuple:
    """One configuration measured on a worker: (row, per-seed errors, the adapter's type)."""
    from . import sweep
    from .timing import _clock_for

    renderer = _renderer(size, adapter)
    lights = _lights(light_specs)
    shared = dataclasses.replace(shared, add_lights=lights)
    scene = sweep._lit_scene(scene_name, shared.scene_lights, lights)
    cpu = renderer.adapter["device_type"] == "Cpu"
    row, stats = sweep.measure_configuration(renderer, scene_name, scene, reference["ref"], reference["book"].rel_error,
                                             config, shared, _clock_for(cpu), reference["truth"])
    row.adapter = renderer.adapter["name"]
    return row, stats, renderer.adapter["device_type"]


def _key(*parts: Any) -> str:
    return hashlib.sha256(repr(parts).encode()).hexdigest()[:24]


def _load(path: Path):
    try:
        version, value = pickle.loads(path.read_bytes())
    except (OSError, pickle.UnpicklingError, ValueError, EOFError):
        return None
    return value if version == RESULT_VERSION else None


def _store(path: Path, value: Any) -> None:
    tmp = path.with_suffix(".tmp")
    tmp.write_bytes(pickle.dumps((RESULT_VERSION, value)))
    tmp.replace(path)  # whole or absent: an interrupted write leaves no half file


def sweep_on_cluster(report, *, cluster: str, scenes, configs, shared, size, adapter, reference: str, ref_settings: dict,
                     reference_rsm, out, gpu_resource: str = "GPU", progress: bool = True, on_result=None) -> dict[int, Any]:
    """Fills ``report`` (rows, references) from tasks on the cluster; returns the per-row
    per-seed errors for the equal-time comparison. ``on_result(done, total)`` is called after
    each configuration's result is stored (a test interrupts the sweep from it)."""
    check_arguments(cluster, out)
    ray = connect(cluster)
    available = ray.cluster_resources().get(gpu_resource, 0)
    # A cluster without GPUs (a laptop's `--cluster local`, CI): with the default resource the
    # tasks take one CPU each and render on the node's CPU adapter, and the report says so.
    cpu_only = gpu_resource == "GPU" and available < 1
    if cpu_only:
        report.note = (report.note + " " if report.note else "") + (
            "Cluster: it offers no GPU, so each task took one CPU and its node's CPU adapter.")
    elif available < 1:
        raise ValueError(f"cluster {cluster}: no {gpu_resource!r} resource to schedule tasks on (the cluster has "
                         f"{', '.join(sorted(ray.cluster_resources())) or 'nothing'}); pass cluster_gpu_resource= "
                         f"(--cluster-resource) naming the one its GPU nodes offer")
    folder = Path(out) / "cluster"
    folder.mkdir(parents=True, exist_ok=True)
    light_specs = _light_specs(shared.add_lights)
    plain = dataclasses.replace(shared, add_lights=())
    # One unit of the GPU resource per task (Ray names its own GPUs with num_gpus).
    if cpu_only:
        ask: dict[str, Any] = {"num_cpus": 1}
    elif gpu_resource == "GPU":
        ask = {"num_cpus": 0, "num_gpus": 1}
    else:
        ask = {"num_cpus": 0, "resources": {gpu_resource: 1}}
    ref_remote = ray.remote(**ask)(_reference_task)
    config_remote = ray.remote(**ask)(_configuration_task)
    view = (tuple(size), adapter, reference, tuple(sorted(ref_settings.items())))
    # Per scene: the reference's result, from the folder or a task.
    # Every missing reference is submitted before any is waited for, so they render side by side.
    references: dict[str, Any] = {}
    missing: dict[str, tuple[Any, Path]] = {}
    for scene_name in scenes:
        path = folder / f"reference-{_key(scene_name, shared.scene_lights, light_specs, view, shared.sequence)}.pkl"
        value = _load(path)
        if value is None:
            missing[scene_name] = (ref_remote.remote(scene_name, shared.scene_lights, light_specs, size, adapter, reference, ref_settings,
                                                     shared.sequence, reference_rsm), path)
        else:
            references[scene_name] = value
    for scene_name, (task, path) in missing.items():
        references[scene_name] = ray.get(task)
        _store(path, references[scene_name])
    for scene_name in scenes:
        value = references[scene_name]
        book_reference(report, scene_name, value["book"])
        if value["motion"] is not None:
            report.sequence_motion[scene_name] = value["motion"]
    # Every configuration of every scene: from the folder, else a task.
    jobs = [(s, c) for s in scenes for c in configs]
    results: dict[int, Any] = {}
    pending: dict[Any, tuple[int, Path]] = {}
    ref_refs = {s: ray.put(v) for s, v in references.items()}
    for i, (scene_name, config) in enumerate(jobs):
        path = folder / f"config-{_key(scene_name, light_specs, view, config, plain)}.pkl"
        value = _load(path)
        if value is not None:
            results[i] = value
            continue
        pending[config_remote.remote(scene_name, light_specs, size, adapter, ref_refs[scene_name], config, plain)] = (i, path)
    resumed = len(results)
    if progress:
        print(f"bench: cluster {cluster}: {len(pending)} configurations to run, {resumed} read back from {folder}", file=sys.stderr)
    while pending:
        ready, _ = ray.wait(list(pending), num_returns=1)
        for ref in ready:
            i, path = pending.pop(ref)
            results[i] = ray.get(ref)
            _store(path, results[i])
            if on_result is not None:
                on_result(len(results), len(jobs))
    seed_stats: dict[int, Any] = {}
    cpu_rows = 0
    for i in range(len(jobs)):
        row, stats, device_type = results[i]
        if stats is not None:
            seed_stats[len(report.rows)] = stats
        report.rows.append(row)
        cpu_rows += device_type == "Cpu"
    if cpu_rows and not cpu_only:
        report.note = (report.note + " " if report.note else "") + (
            f"Cluster: {cpu_rows} of {len(jobs)} rows were timed on a CPU adapter (no GPU was assigned or found): their times "
            "compare only with rows of the same adapter.")
    report.cluster = {"address": cluster, "resource": gpu_resource, "ran": len(jobs) - resumed, "resumed": resumed,
                      "adapters": sorted({r.adapter for r in report.rows if r.adapter})}
    return seed_stats


def same_rows_but_timing(a, b) -> list[str]:
    """Where two reports' rows differ in anything but the timing columns and the adapter that
    timed them (empty when they agree): what a cluster sweep must reproduce of a local one."""
    timing = {"total_ms_median", "total_ms_min", "total_ms_max", "total_ms_q1", "total_ms_q3", "passes_ms", "passes_iqr_ms",
              "warmup_frames", "sm_clock_mhz", "adapter"}
    out = []
    if len(a.rows) != len(b.rows):
        return [f"{len(a.rows)} rows against {len(b.rows)}"]
    for i, (x, y) in enumerate(zip(a.rows, b.rows)):
        for f in dataclasses.fields(x):
            if f.name in timing:
                continue
            u, v = getattr(x, f.name), getattr(y, f.name)
            if not (u == v or (isinstance(u, float) and isinstance(v, float) and np.isnan(u) and np.isnan(v))):
                out.append(f"row {i} ({x.scene} {x.method} {x.num_lights}): {f.name} {u!r} != {v!r}")
    return out
