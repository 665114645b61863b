"""How fast the live view's frame source runs: ViewSession.frame() (render, `ldr` readback,
compositing) and the widget's encode (jupyter_rfb's JPEG while moving, PNG when still), with the
camera orbiting a step each frame, on cornell_box and a corpus scene; median and quartiles over
the frames after two warm-up frames. Then the desktop window's frame path (WindowView.draw():
render with `ldr` kept on the GPU, compose, the egui panel, blit, present; no readback):
offscreen (a BGRA8 texture stands in for the surface) and, where DISPLAY is set, in a real
window presenting without vsync.

    .venv/bin/python experiments/live_view_frame_rate.py --size 320x180 --frames 20

The issue's targets: >= 30 fps at 960x540 on a GPU for the widget's source, and on lavapipe both
front ends working at 320x180 with the frame rate said. Result: live_view_frame_rate.md.
"""

from __future__ import annotations

import argparse
import statistics
import time

import os

import vsgl
from vsgl.view_session import ViewSession
from vsgl.window_view import WindowView


def _quartiles(xs):
    q = statistics.quantiles(xs, n=4)
    return q[0], statistics.median(xs), q[2]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="320x180")
    ap.add_argument("--frames", type=int, default=20)
    ap.add_argument("--scenes", default="cornell_box,flight_helmet")
    ap.add_argument("--compare", default="vsgl;vpl,vsgl")
    args = ap.parse_args()
    w, h = (int(v) for v in args.size.split("x"))
    try:  # the widget's own encoder (JPEG through simplejpeg, PNG); absent where the view extra is
        from jupyter_rfb._utils import array2compressed
    except ImportError:
        def array2compressed(array, quality):
            return None
        print("jupyter_rfb not installed: encode times are of nothing (0)")

    renderer = vsgl.Renderer(w, h)
    print(f"adapter {renderer.adapter['name']}, {w}x{h}, {args.frames} frames after 2 warm-up frames")
    print("| scene | methods | frame() ms (q1 / median / q3) | JPEG ms | PNG ms | GPU ms | fps (frame + JPEG) |")
    print("|---|---|---|---|---|---|---|")
    window_rows = []
    for name in args.scenes.split(","):
        if name in vsgl.scenes.names():
            scene = vsgl.scenes.load(name)
        elif vsgl.scenes.corpus_available(name):
            scene = vsgl.scenes.corpus_scene(name).scene
        else:
            print(f"| {name} | skipped: the shared scene files are absent |")
            continue
        for methods in args.compare.split(";"):
            ms = methods.split(",")
            s = ViewSession(scene, ms[0], compare=ms if len(ms) > 1 else None, renderer=renderer, size=(w, h))
            frame_ms, jpeg_ms, png_ms, gpu = [], [], [], []
            for i in range(args.frames + 2):
                s.orbit.orbit(2.0, 0.0, h)
                t0 = time.perf_counter()
                img = s.frame()
                t1 = time.perf_counter()
                array2compressed(img, 80)
                t2 = time.perf_counter()
                array2compressed(img, 100)
                t3 = time.perf_counter()
                if i >= 2:
                    frame_ms.append(1e3 * (t1 - t0))
                    jpeg_ms.append(1e3 * (t2 - t1))
                    png_ms.append(1e3 * (t3 - t2))
                    gpu.append(s.gpu_ms or 0.0)
            q1, med, q3 = _quartiles(frame_ms)
            jpeg = statistics.median(jpeg_ms)
            print(f"| {name} | {methods} | {q1:.1f} / {med:.1f} / {q3:.1f} | {jpeg:.2f} | {statistics.median(png_ms):.2f} "
                  f"| {statistics.median(gpu):.1f} | {1e3 / (med + jpeg):.1f} |")
            window_rows.append((name, scene, ms))

    print()
    print("| scene | methods | window | draw() ms (q1 / median / q3) | GPU ms | fps | present() alone ms |")
    print("|---|---|---|---|---|---|---|")
    kinds = ["offscreen"] + (["X11 window, no vsync"] if os.environ.get("DISPLAY") else [])
    for name, scene, ms in window_rows:
        for kind in kinds:
            view = WindowView(scene, ms[0], compare=ms if len(ms) > 1 else None, renderer=renderer, size=(w, h),
                              ui=True, vsync=False, offscreen=kind == "offscreen")
            draw_ms, gpu, present_ms = [], [], []
            for i in range(args.frames + 2):
                view.session.orbit.orbit(2.0, 0.0, h)
                view.window.poll_events(0.0)
                t0 = time.perf_counter()
                view.draw()
                t1 = time.perf_counter()
                view.present()  # what a panel-only repaint costs: compose, panel, blit, present
                t2 = time.perf_counter()
                if i >= 2:
                    draw_ms.append(1e3 * (t1 - t0))
                    gpu.append(view.session.gpu_ms or 0.0)
                    present_ms.append(1e3 * (t2 - t1))
            view.window.close()
            q1, med, q3 = _quartiles(draw_ms)
            print(f"| {name} | {','.join(ms)} | {kind} | {q1:.1f} / {med:.1f} / {q3:.1f} | {statistics.median(gpu):.1f} | {1e3 / med:.1f} | {statistics.median(present_ms):.1f} |")


if __name__ == "__main__":
    main()
