"""Wall time of a render() loop on the best adapter: median and interquartile range of the
time per `render()` call and a read of each asked-for AOV (scene upload cached, the GPU frame,
readback)
and of the GPU total, for a few AOV selections. Writes JSON to $OUT (or out/).

    python experiments/gpu_frame_wall.py --size 1920x1080 --frames 40 --tag _new
"""

from __future__ import annotations

import argparse
import statistics
import time

import vsgl
from gpu_timings import quartiles, write_report  # experiments/ is on sys.path when run as a script


def orbit(scene, frames: int) -> list:
    """Cameras on a small circle around the scene's first camera, looking where it looks."""
    import math

    cam = scene.cameras[0] if scene.cameras else None
    if cam is None:
        return [None] * frames
    out = []
    for k in range(frames):
        a = 2 * math.pi * k / frames
        eye = tuple(e + 0.05 * d for e, d in zip(cam.eye, (math.cos(a), math.sin(a), 0.0)))
        target = tuple(e + f for e, f in zip(cam.eye, cam.forward))
        out.append(vsgl.Camera.look_at(eye=eye, target=target, up=cam.up, fov_y_deg=cam.fov_y_deg))
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--frames", type=int, default=40)
    ap.add_argument("--scene", default="cornell_box")
    ap.add_argument("--methods", default="direct,vsgl")
    ap.add_argument("--tag", default="")
    args = ap.parse_args()
    w, h = (int(x) for x in args.size.split("x"))
    r = vsgl.Renderer(width=w, height=h)
    scene = vsgl.scenes.load(args.scene)
    report = {"adapter": r.adapter, "size": [w, h], "frames": args.frames, "rows": []}
    for method in args.methods.split(","):
        opts = {"num_lights": 1024, "rsm_size": 256} if method == "vsgl" else {}
        for aovs in ([], ["image"], ["ldr"], ["image", "indirect"]):
            try:
                for _ in range(3):
                    r.render(scene, method=method, aovs=aovs, **opts)
            except ValueError as e:  # an AOV this build does not have, or the method does not make
                print(f"{method:8s} aovs={str(aovs):10s} skipped: {e}")
                continue
            walls, gpu, rb = [], [], []
            for _ in range(args.frames):
                t = time.perf_counter()
                f = r.render(scene, method=method, aovs=aovs, **opts)
                # A loop uses what it read back: touching the arrays counts (an array made per
                # access would cost a copy here).
                for name in aovs:
                    f.aov(name)[0, 0, 0]
                walls.append(1e3 * (time.perf_counter() - t))
                gpu.append(f.timings_ms["total"])
                rb.append(float(f.settings["readback_ms"]))
            q1, q3 = quartiles(walls)
            row = {
                "loop": "render", "method": method, "aovs": aovs, "wall_ms_median": statistics.median(walls), "wall_ms_q1": q1, "wall_ms_q3": q3,
                "gpu_ms_median": statistics.median(gpu), "allocated_bytes": f.settings.get("allocated_bytes", "n/a"),
                "readback_ms_median": statistics.median(rb),
            }
            report["rows"].append(row)
            print(f"render   {method:8s} aovs={str(aovs):10s} wall {row['wall_ms_median']:8.2f} ms [{row['wall_ms_q1']:.2f},{row['wall_ms_q3']:.2f}]  gpu {row['gpu_ms_median']:.3f} ms  allocated {row['allocated_bytes']}")
            # The same frames through render_sequence with a camera orbiting the first one:
            # frame k+1 is on the GPU while frame k is read, and the moving camera reuses the
            # scene upload. Wall per frame = time between consecutive frames arriving.
            cams = orbit(scene, args.frames)
            arrivals, readback, uploads = [], [], set()
            t = time.perf_counter()
            for f in r.render_sequence(scene, [{"camera": c} if c else {} for c in cams], method=method, aovs=aovs, **opts):
                for name in aovs:
                    f.aov(name)[0, 0, 0]
                now = time.perf_counter()
                arrivals.append(1e3 * (now - t))
                t = now
                readback.append(float(f.settings["readback_ms"]))
                uploads.add(f.settings["scene_upload"])
            walls = arrivals[2:]  # the first frames fill the pipeline
            q1, q3 = quartiles(walls)
            row = {
                "loop": "render_sequence", "method": method, "aovs": aovs, "wall_ms_median": statistics.median(walls), "wall_ms_q1": q1,
                "wall_ms_q3": q3, "readback_ms_median": statistics.median(readback), "scene_uploads": sorted(uploads),
            }
            report["rows"].append(row)
            print(f"sequence {method:8s} aovs={str(aovs):10s} wall {row['wall_ms_median']:8.2f} ms [{q1:.2f},{q3:.2f}]  readback {row['readback_ms_median']:.3f} ms  uploads {row['scene_uploads']}")
    write_report(report, f"frame_wall{args.tag}.json")


if __name__ == "__main__":
    main()
