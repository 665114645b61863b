"""The numerical stability suite: ``python -m vsgl stability [--adapter NAME]``.

Every WGSL math function of vsgl (``wgsl/common/{math,sg,ggx,vsgl}.wgsl``) is evaluated in f32 on
the GPU and by its float64 oracle on the same inputs, over case families with the extremes of
issue 3 (SG sharpness 1e-6…1e9, roughness 1e-4…1, grazing cosines down to 1e-6 and exactly 0,
axes equal / opposite / 1e-7 rad apart, variance down to 1e-12 of d² and 0, scenes 1e5 m from
the origin, intensities 1e-8…1e8, zero power).

Each row is one (function output, case family):

* ``max_rel_error``: max over the cases of ‖gpu − ref‖ / max(‖ref‖, floor), the floor tied to
  the function's scale (docs/numerics.md, "Stability suite");
* ``bound``: the stated bound of the case with that largest error (same denominator). Every case
  has its own bound, a few ULP × the condition number of the formula at that case;
* ``worst_ratio``: max over the cases of ‖gpu − ref‖ / bound (≤ 1 when the row passes);
* ``nonfinite``: cases whose GPU output is NaN or ±Inf (must be 0);
* ``passed``: no NaN/Inf and every case within its bound.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any, Sequence

COLUMNS = ("function", "case family", "cases", "max rel. error", "bound", "err/bound", "NaN/Inf", "pass/fail")


def run(adapter: str | None = None, bound_scale: float = 1.0) -> list[dict[str, Any]]:
    """Runs the suite on ``adapter`` (None: the best adapter, or ``$VSGL_ADAPTER``).

    ``bound_scale`` multiplies every bound; it exists to show that the suite can fail (at 1e-3
    most rows do). Raises ``vsgl.NoAdapterError`` when there is no adapter.
    """
    from vsgl import _vsgl

    return _vsgl.stability_suite(adapter, bound_scale)


def exit_code(rows: Sequence[dict[str, Any]]) -> int:
    """0 when every row passed and no output was NaN/Inf, else 1 (also 1 for an empty table)."""
    if not rows:
        return 1
    ok = all(bool(r["passed"]) and int(r["nonfinite"]) == 0 for r in rows)
    return 0 if ok else 1


def format_table(rows: Sequence[dict[str, Any]]) -> str:
    """The rows as an aligned text table with the columns of ``COLUMNS``."""
    cells = [
        (
            str(r["function"]),
            str(r["family"]),
            str(r["cases"]),
            f"{r['max_rel_error']:.2e}",
            f"{r['bound']:.2e}",
            f"{r['worst_ratio']:.3f}",
            str(r["nonfinite"]),
            "pass" if r["passed"] and int(r["nonfinite"]) == 0 else "FAIL",
        )
        for r in rows
    ]
    widths = [max([len(c)] + [len(row[i]) for row in cells]) for i, c in enumerate(COLUMNS)]
    numeric = {2, 3, 4, 5, 6}

    def line(values: Sequence[str]) -> str:
        return "  ".join(v.rjust(w) if i in numeric else v.ljust(w) for i, (v, w) in enumerate(zip(values, widths))).rstrip()

    out = [line(COLUMNS), line(["-" * w for w in widths])]
    out.extend(line(c) for c in cells)
    return "\n".join(out)


def main(argv: Sequence[str] | None = None) -> int:
    """CLI entry point: prints the table and returns 0 if every row passed, 1 otherwise (2 when
    no adapter could be opened)."""
    parser = argparse.ArgumentParser(prog="python -m vsgl stability", description=__doc__.split("\n\n")[0])
    parser.add_argument("--adapter", default=None, help="adapter name substring (default: best, or $VSGL_ADAPTER)")
    parser.add_argument(
        "--bound-scale",
        type=float,
        default=1.0,
        help="multiply every bound by this (default 1; a small value shows that the suite can fail)",
    )
    parser.add_argument("--verbose", action="store_true", help="print the worst case of every failing row")
    args = parser.parse_args(argv)
    if not args.bound_scale > 0.0:
        print(f"error: --bound-scale must be positive, got {args.bound_scale}", file=sys.stderr)
        return 2

    import vsgl

    try:
        rows = run(args.adapter, args.bound_scale)
    except vsgl.NoAdapterError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    print(format_table(rows))
    failed = [r for r in rows if not (r["passed"] and int(r["nonfinite"]) == 0)]
    scale = "" if args.bound_scale == 1.0 else f" (bounds x {args.bound_scale:g})"
    print(f"\n{len(rows) - len(failed)} of {len(rows)} rows pass{scale}; {sum(int(r['nonfinite']) for r in rows)} NaN/Inf outputs")
    for r in failed if args.verbose else []:
        print(f"FAIL {r['function']} / {r['family']}: {r['worst_case']}")
    return exit_code(rows)


if __name__ == "__main__":
    sys.exit(main())
