"""What a sweep reports: its rows and report, the labels tables and plots give them, the
equal-time and plan comparisons, and the terminal table."""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from typing import Any

from vsgl import metrics


#: A row's error must be at least this many times the reference's own error to be trusted.
TRUST_FACTOR = 3.0


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
    # The adapter that rendered and timed this row, where it is not the report's own: a cluster
    # task's GPU (`bench --cluster`); None in a local sweep.
    adapter: str | None = None


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
    # `bench --cluster`: the address, the GPU resource each task asked for, and how many
    # configurations ran now and how many were read back from an earlier, interrupted run's
    # result folder; empty in a local sweep.
    cluster: dict[str, Any] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        d = asdict(self)
        d["rows"] = [asdict(r) for r in self.rows]
        return d


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
