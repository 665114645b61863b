#!/usr/bin/env python3
"""Is k-means' nearest-centre grid at least as cheap as the paper's binary radix tree?

The 2016 paper keeps its k-means centres in a binary radix tree [Tok16 Appendix D; the tree of
Karras 2012]; `kernel="kmeans2d"/"kmeans3d"` walks a uniform grid of about two centres a cell in
rings around the texel's cell instead (wgsl/passes/kmeans_grid.wgsl, kmeans_assign.wgsl). Both
are exact. Their GPU cost is memory traffic per texel, so this counts it, on the very centres and
texels of corpus scenes (`capture_rsm=True`, the VSGL records' centres, N = `--num-lights`):

- grid: a model of kmeans_assign.wgsl (its cell size rule, rings and ring bound, float64), counting
  the cells visited (an 8-byte range each) and the centres tested (a 4-byte id and a 16-byte
  centre each);
- radix tree: centres sorted by 30-bit Morton code in their bounds, the binary radix tree over the
  sorted codes (each node split where its range's highest differing bit changes), each node's box
  the bounds of its centres; a depth-first nearest-centre search that visits the nearer child
  first and skips boxes farther than the best so far, counting the nodes whose two child boxes
  are read (2 × 24 bytes) and the centres tested (16 bytes).

Every texel's nearest centre is checked against a brute-force argmin for both models. Lavapipe
renders the frames; the counts do not depend on the adapter.

    VSGL_SCENES=../shared/scenes .venv/bin/python experiments/kmeans_search_cost.py [--texels 4096]

Result: experiments/kmeans_generation_cost.md, "Grid or radix tree".
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

import vsgl

MAX_DIM_2D = 256
MAX_DIM_3D = 64
TARGET_CENTRES_PER_CELL = 2.0


def grid_of(centres: np.ndarray, space: str, rsm_size: int):
    """(origin, cell side, dims), as kmeans_grid.wgsl's `cells` entry point makes them."""
    n = len(centres)
    target = max(n / TARGET_CENTRES_PER_CELL, 1.0)
    if space == "kmeans2d":
        side = int(np.clip(np.ceil(np.sqrt(target)), 1, MAX_DIM_2D))
        return np.zeros(3), rsm_size / side, np.array([side, side, 1])
    lo, hi = centres.min(0), centres.max(0)
    extent = np.maximum(hi - lo, 0.0)
    e = np.sort(extent)[::-1]
    h3 = (e[0] * e[1] * e[2] / target) ** (1 / 3)
    if 0 < h3 <= e[2]:
        h = h3
    else:
        h2 = np.sqrt(e[0] * e[1] / target)
        h = h2 if 0 < h2 <= e[1] else e[0] / target
    h = max(h, e[0] / MAX_DIM_3D)
    if not (h > 0):
        h = 1.0
    dims = np.clip(np.ceil(extent / h).astype(int), 1, MAX_DIM_3D)
    return lo, h, dims


def grid_search(points, centres, grid, prune=False):
    """`prune`: also skip a cell whose box (grown by 1e-4 of its side) is farther from the texel
    than the best centre so far (exact: no centre in it can be nearer, nor as near), as
    kmeans_assign.wgsl does since 2026-12-04."""
    origin, h, dims = grid
    cell_of = lambda p: np.clip(np.floor((p - origin) / h).astype(int), 0, dims - 1)  # noqa: E731
    buckets: dict[tuple, list[int]] = {}
    for i, c in enumerate(centres):
        buckets.setdefault(tuple(cell_of(c)), []).append(i)
    nearest, cells, tested = [], 0, 0
    rings = int(dims.max())
    for p in points:
        home = cell_of(p)
        best, best_id = np.inf, -1
        for r in range(rings):
            if r >= 1 and best < ((r - 1) * h) ** 2:
                break
            lo, hi = np.maximum(home - r, 0), np.minimum(home + r, dims - 1)
            for z in range(lo[2], hi[2] + 1):
                for y in range(lo[1], hi[1] + 1):
                    for x in range(lo[0], hi[0] + 1):
                        if max(abs(x - home[0]), abs(y - home[1]), abs(z - home[2])) != r:
                            continue
                        if prune:
                            c_lo = origin + h * np.array([x, y, z]) - 1e-4 * h
                            gap = np.maximum(np.maximum(c_lo - p, p - (c_lo + h * (1 + 2e-4))), 0.0)
                            if float((gap * gap).sum()) > best:
                                continue
                        cells += 1
                        for k in buckets.get((x, y, z), ()):
                            tested += 1
                            d2 = float(((centres[k] - p) ** 2).sum())
                            if d2 < best or (d2 == best and k < best_id):
                                best, best_id = d2, k
        nearest.append(best_id)
    return np.array(nearest), cells / len(points), tested / len(points)


def morton30(q: np.ndarray) -> np.ndarray:
    """30-bit Morton codes of 10-bit integer coordinates (n × 3)."""
    def spread(v):
        v = v.astype(np.uint64) & 0x3FF
        v = (v | (v << 16)) & 0x030000FF
        v = (v | (v << 8)) & 0x0300F00F
        v = (v | (v << 4)) & 0x030C30C3
        v = (v | (v << 2)) & 0x09249249
        return v
    return (spread(q[:, 0]) << 2) | (spread(q[:, 1]) << 1) | spread(q[:, 2])


def radix_tree(centres: np.ndarray):
    """Binary radix tree over the centres' Morton codes: (children, boxes, leaf centre ids)
    with node 0 the root; a child index < 0 is leaf −1 − k of the sorted order."""
    lo, hi = centres.min(0), centres.max(0)
    span = np.where(hi > lo, hi - lo, 1.0)
    codes = morton30(np.clip(((centres - lo) / span * 1023.0).astype(int), 0, 1023))
    order = np.argsort(codes, kind="stable")
    codes = codes[order]
    children, boxes = [], []

    def build(first: int, last: int) -> int:
        if first == last:
            return -1 - first
        node = len(children)
        children.append(None)
        boxes.append((centres[order[first:last + 1]].min(0), centres[order[first:last + 1]].max(0)))
        a, b = int(codes[first]), int(codes[last])
        if a == b:
            split = (first + last) // 2
        else:
            bit = (a ^ b).bit_length() - 1
            split = first + int(np.searchsorted((codes[first:last + 1] >> bit) & 1, 1)) - 1
        children[node] = (build(first, split), build(split + 1, last))
        return node

    build(0, len(centres) - 1)
    return children, boxes, order


def tree_search(points, centres, tree):
    children, boxes, order = tree

    def box_d2(node, p):
        if node < 0:
            return float(((centres[order[-1 - node]] - p) ** 2).sum())
        lo, hi = boxes[node]
        d = np.maximum(np.maximum(lo - p, p - hi), 0.0)
        return float((d * d).sum())

    nearest, nodes, tested = [], 0, 0
    for p in points:
        best, best_id = np.inf, -1
        stack = [0]
        while stack:
            node = stack.pop()
            if node < 0:
                k = int(order[-1 - node])
                tested += 1
                d2 = float(((centres[k] - p) ** 2).sum())
                if d2 < best or (d2 == best and k < best_id):
                    best, best_id = d2, k
                continue
            nodes += 1
            kids = sorted(children[node], key=lambda c: box_d2(c, p) if c >= 0 else 0.0)
            for c in reversed(kids):
                if c < 0 or box_d2(c, p) <= best:
                    stack.append(c)
        nearest.append(best_id)
    return np.array(nearest), nodes / len(points), tested / len(points)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", default="flight_helmet,cornell_box_original,furnished_room")
    ap.add_argument("--num-lights", type=int, default=1024)
    ap.add_argument("--rsm-size", type=int, default=256)
    ap.add_argument("--texels", type=int, default=4096, help="lit texels sampled per scene (default 4096)")
    a = ap.parse_args()
    r = vsgl.Renderer(64, 64)
    rng = np.random.default_rng(1)
    print(f"N = {a.num_lights}, RSM {a.rsm_size}^2, {a.texels} lit texels a scene; bytes per texel: grid 8/cell + 20/centre, tree 48/node + 16/centre")
    print("| scene | space | grid: cells / centres / bytes | pruned grid: cells / centres / bytes | radix tree: nodes / centres / bytes | tree ÷ grid | tree ÷ pruned grid |")
    print("|---|---|---|---|---|---|---|")
    for name in a.scenes.split(","):
        cs = vsgl.scenes.corpus_scene(name)
        for space in ("kmeans2d", "kmeans3d"):
            camera = cs.scene.default_camera()
            f = r.render(cs.scene, camera=camera, method="vsgl", kernel=space, num_lights=a.num_lights, rsm_size=a.rsm_size, capture_rsm=True,
                         interleave=1, denoise=False, aovs=[])
            size = f.rsm("weight").shape[0]
            lit = f.rsm("weight").reshape(-1) > 0
            v = f.vsgls()
            if space == "kmeans2d":
                ys, xs = np.mgrid[0:size, 0:size]
                points = np.stack([xs.ravel() + 0.5, ys.ravel() + 0.5, np.zeros(size * size)], -1)
                centres = np.concatenate([v["center"].astype(np.float64), np.zeros((len(v["center"]), 1))], 1)
            else:
                # Both relative to the light: the records' centres are relative to the camera.
                offset = np.asarray(cs.scene.lights[0].position, np.float64) - np.asarray(camera.eye, np.float64)
                points = f.rsm("position").reshape(-1, 3).astype(np.float64) + offset
                centres = v["shadow_target"].astype(np.float64)
            pick = rng.choice(np.flatnonzero(lit), size=min(a.texels, int(lit.sum())), replace=False)
            pts = points[pick]
            brute = np.argmin(((pts[:, None, :] - centres[None, :, :]) ** 2).sum(-1), axis=1)
            g_near, g_cells, g_tested = grid_search(pts, centres, grid_of(centres, space, size))
            p_near, p_cells, p_tested = grid_search(pts, centres, grid_of(centres, space, size), prune=True)
            t_near, t_nodes, t_tested = tree_search(pts, centres, radix_tree(centres))
            d2 = lambda ids: ((pts - centres[ids]) ** 2).sum(-1)  # noqa: E731
            assert np.allclose(d2(p_near), d2(brute)) and np.allclose(d2(g_near), d2(brute)) and np.allclose(d2(t_near), d2(brute)), "a search missed the nearest centre"
            g_bytes, t_bytes = 8 * g_cells + 20 * g_tested, 48 * t_nodes + 16 * t_tested
            p_bytes = 8 * p_cells + 20 * p_tested
            print(f"| {name} | {space[-2:]} | {g_cells:.1f} / {g_tested:.1f} / {g_bytes:.0f} | {p_cells:.1f} / {p_tested:.1f} / {p_bytes:.0f} "
                  f"| {t_nodes:.1f} / {t_tested:.1f} / {t_bytes:.0f} | {t_bytes / g_bytes:.2f} | {t_bytes / p_bytes:.2f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
