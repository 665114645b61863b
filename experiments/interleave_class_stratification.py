"""How well stratified are the 16 VSGL sample points each interleave class gets, and would a
nested lattice do better? vsgl draws sample i of N from the Fibonacci lattice
((i + 0.5)/N, frac(i/φ)) (wgsl/common/rsm_warp.wgsl, `warp_sample_point`) and, with interleave
k, pixel class c shades the lights i ≡ c (mod k²) (wgsl/common/interleave.wgsl). Prints, for
N = 1024 and k = 8, the union's and each class's minimum toroidal distance (× √count) and
wrap-around L2 discrepancy (× count; lower is better) for today's lattice, nested lattices that
make each class a shifted 16-point lattice, and random points. No GPU; NumPy only.

    .venv/bin/python experiments/interleave_class_stratification.py"""
from __future__ import annotations

import numpy as np

PHI = (1 + 5**0.5) / 2
N, CLASSES = 1024, 64
PER_CLASS = N // CLASSES


def min_distance(p: np.ndarray) -> float:
    d = np.abs(p[:, None, :] - p[None, :, :])
    d = np.minimum(d, 1 - d)
    r = np.sqrt((d**2).sum(-1))
    np.fill_diagonal(r, np.inf)
    return float(r.min())


def wraparound_l2(p: np.ndarray) -> float:
    # Hickernell's wrap-around L2 discrepancy in two dimensions.
    d = np.abs(p[:, None, :] - p[None, :, :])
    return float(np.sqrt(-(4 / 3) ** 2 + np.prod(1.5 - d * (1 - d), axis=-1).mean()))


def report(name: str, points: np.ndarray, cls: np.ndarray) -> None:
    parts = [points[cls == c] for c in range(CLASSES)]
    print(f"{name:34s} union: min distance x sqrt(N) {min_distance(points) * np.sqrt(N):.3f}, discrepancy x N {wraparound_l2(points) * N:6.2f}"
          f" | classes: min distance x sqrt(n) {min(min_distance(q) for q in parts) * np.sqrt(PER_CLASS):.3f},"
          f" discrepancy x n mean {np.mean([wraparound_l2(q) * PER_CLASS for q in parts]):.3f}")


def main() -> int:
    i = np.arange(N)
    c, m = i % CLASSES, i // CLASSES
    x = (i + 0.5) / N
    report("Fibonacci lattice (today's)", np.stack([x, np.mod(i / PHI, 1)], 1), c)
    report("nested: m/phi + c/phi", np.stack([x, np.mod((m + c) / PHI, 1)], 1), c)
    report("nested: m/phi + c*sqrt(2)", np.stack([x, np.mod(m / PHI + c * 2**0.5, 1)], 1), c)
    for a in (3, 7):
        report(f"nested: Korobov m*{a}/16 + c/phi/16", np.stack([x, np.mod((m * a + 0.5) / PER_CLASS + np.mod(c / PHI, 1) / PER_CLASS, 1)], 1), c)
    report("random points", np.random.default_rng(0).random((N, 2)), c)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
