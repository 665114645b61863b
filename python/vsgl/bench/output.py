"""A report's files: bench.json, bench.csv, bench.txt and, with matplotlib, the plots."""

from __future__ import annotations

import csv
import json
import pathlib
from dataclasses import asdict

from .report import TRUST_FACTOR, Report, Row, _kernel_label, _method_label, table


CSV_COLUMNS = [
    "scene", "plan", "method", "num_lights", "rsm_size", "kernel", "K", "lighting", "importance", "sampling", "options", "seeds", "total_ms_median", "total_ms_q1", "total_ms_q3", "total_ms_min", "total_ms_max",
    "rmse_indirect", "rmse_indirect_std", "rmse_image", "relmse_indirect", "relmse_image", "flip_image", "rel_rmse_indirect", "bias", "noise",
    "relmse_indirect_debiased", "relmse_indirect_debiased_lo", "relmse_indirect_debiased_hi", "reference_rel_error", "reference_too_noisy",
    "ssim_image", "block_rmse_indirect", "flicker_indirect", "notes", "passes_ms", "adapter",
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
