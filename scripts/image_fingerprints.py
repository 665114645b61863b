"""Fingerprints of every method on every built-in scene: a bit-level check for refactors.

Renders each (scene, method) with small, fixed settings and records the SHA-256 of every AOV's
bytes together with the frame's passes, skipped passes and settings rows. A refactor that must
not change behaviour (docs/architecture.md) is checked by writing fingerprints before it and
comparing after it on the same machine and driver:

    .venv/bin/python scripts/image_fingerprints.py --out /tmp/before.json
    ... change the code, rebuild ...
    .venv/bin/python scripts/image_fingerprints.py --compare /tmp/before.json

The comparison exits non-zero and lists every difference. Fingerprints are only comparable on
the same adapter and driver (float rounding differs between GPUs), so none is committed.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys

import numpy as np

import vsgl
from vsgl.stability import small_settings

# Rows of frame.settings that name the machine or the run rather than the image.
UNSTABLE_SETTINGS = {"adapter", "scene_upload", "readback_ms", "scene_upload_ms", "bvh_build_ms"}


def fingerprint(renderer: vsgl.Renderer, scene_name: str, method: str) -> dict:
    scene = vsgl.scenes.load(scene_name)
    # The scene suite's small settings (vsgl.stability.small_settings), so the sweep runs in
    # about a minute on lavapipe.
    frame = renderer.render(scene, method=method, **small_settings(method))
    aovs = {}
    for name in frame.aovs:
        arr = np.ascontiguousarray(frame.aov(name))
        aovs[name] = {"sha256": hashlib.sha256(arr.tobytes()).hexdigest(), "shape": list(arr.shape), "mean": float(arr.mean())}
    return {
        "aovs": aovs,
        "passes": list(frame.passes),
        "skipped": dict(frame.skipped),
        "settings": {k: v for k, v in frame.settings.items() if k not in UNSTABLE_SETTINGS},
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", help="write fingerprints to this JSON file")
    ap.add_argument("--compare", help="compare against fingerprints written earlier; exit 1 on any difference")
    ap.add_argument("--size", default="48x32", help="WxH of each render (default 48x32)")
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.split("x"))
    renderer = vsgl.Renderer(width=w, height=h)
    methods = list(vsgl.METHODS)
    result = {}
    for scene_name in vsgl.scenes.names():
        for method in methods:
            result[f"{scene_name}/{method}"] = fingerprint(renderer, scene_name, method)
    doc = {"adapter": renderer.adapter["name"], "size": [w, h], "frames": result}
    if args.out:
        with open(args.out, "w") as f:
            json.dump(doc, f, indent=1, sort_keys=True)
        print(f"wrote {len(result)} fingerprints to {args.out}")
    if args.compare:
        with open(args.compare) as f:
            before = json.load(f)
        problems = []
        if before["adapter"] != doc["adapter"] or before["size"] != doc["size"]:
            problems.append(f"not comparable: {before['adapter']} {before['size']} vs {doc['adapter']} {doc['size']}")
        for key in sorted(set(before["frames"]) | set(result)):
            a, b = before["frames"].get(key), result.get(key)
            if a is None or b is None:
                problems.append(f"{key}: only in {'after' if a is None else 'before'}")
                continue
            for part in ("aovs", "passes", "skipped", "settings"):
                if a[part] != b[part]:
                    problems.append(f"{key}: {part} differ:\n  before {a[part]}\n  after  {b[part]}")
        for p in problems:
            print(p)
        print(f"{len(result)} frames compared, {len(problems)} differences")
        return 1 if problems else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
