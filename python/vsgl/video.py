"""Animated sequences to video: ``python -m vsgl animate SCENE -o out.mp4`` and :func:`animate`.

Frames are rendered with ``Renderer.render_sequence`` (one ``{"time": k / fps}`` per frame,
which poses the scene's animations) and read back as the GPU-tone-mapped ``ldr`` AOV (sRGB
uint8). Several methods (``--compare vpl,vsgl,reference``) are tiled left to right with a
1-pixel white separator; their order is printed and stored in each PNG's ``Comment``.

Writers: a folder of PNGs when the output ends with ``/`` (standard library only), ``.gif``
and ``.mp4`` through ``imageio`` (+ ``imageio-ffmpeg`` for mp4), the optional extra
``pip install vsgl[video]``.
"""

from __future__ import annotations

import pathlib
import struct
import sys
import zlib
from typing import Any, Callable, Sequence

import numpy as np

VIDEO_EXTRA_HINT = "pip install vsgl[video]"
SEPARATOR = 255  # a white 1-pixel column between tiles


def frame_times(frames: int, fps: float) -> list[float]:
    """The time of each frame, k / fps seconds; raises ValueError naming the argument."""
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 1:
        raise ValueError(f"frames: expected a positive int, got {frames!r}")
    if not (isinstance(fps, (int, float)) and np.isfinite(fps) and fps > 0):
        raise ValueError(f"fps: expected a finite number > 0, got {fps!r}")
    return [k / float(fps) for k in range(frames)]


def tile(images: Sequence[np.ndarray]) -> np.ndarray:
    """(H, W, 4) uint8 images side by side, a 1-pixel white column between neighbours."""
    if not images:
        raise ValueError("images: expected at least one image")
    h = images[0].shape[0]
    parts: list[np.ndarray] = []
    for i, im in enumerate(images):
        if i:
            parts.append(np.full((h, 1, 4), SEPARATOR, np.uint8))
        parts.append(im)
    return np.ascontiguousarray(np.concatenate(parts, axis=1))


def write_png(path: str | pathlib.Path, rgba: np.ndarray, comment: str | None = None) -> None:
    """An 8-bit RGBA PNG (PNG spec, ISO/IEC 15948: IHDR, optional tEXt, one zlib IDAT with
    filter 0 on every row, IEND), so a PNG folder needs no optional package."""
    rgba = np.ascontiguousarray(rgba, np.uint8)
    h, w = rgba.shape[:2]

    def chunk(kind: bytes, payload: bytes) -> bytes:
        return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload) & 0xFFFFFFFF)

    rows = np.concatenate([np.zeros((h, 1), np.uint8), rgba.reshape(h, w * 4)], axis=1)
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
    if comment:
        out += chunk(b"tEXt", b"Comment\x00" + comment.encode("latin-1", "replace"))
    out += chunk(b"IDAT", zlib.compress(rows.tobytes(), 6)) + chunk(b"IEND", b"")
    pathlib.Path(path).write_bytes(out)


def _imageio(kind: str):
    try:
        import imageio.v3 as iio  # type: ignore[import-not-found,import-untyped,unused-ignore]
    except ImportError:
        raise ValueError(f"output: writing {kind} needs the optional imageio package: {VIDEO_EXTRA_HINT}") from None
    if kind == ".mp4":
        try:
            import imageio_ffmpeg  # type: ignore[import-not-found,import-untyped,unused-ignore]  # noqa: F401
        except ImportError:
            raise ValueError(f"output: writing .mp4 needs imageio-ffmpeg: {VIDEO_EXTRA_HINT}") from None
    return iio


def output_kind(output: str) -> str:
    """"png-folder", ".gif" or ".mp4"; ValueError naming ``output`` otherwise."""
    if output.endswith(("/", "\\")) or pathlib.Path(output).is_dir():
        return "png-folder"
    suffix = pathlib.Path(output).suffix.lower()
    if suffix in (".gif", ".mp4"):
        return suffix
    raise ValueError(f"output: expected a folder ending with '/', a .gif or a .mp4, got {output!r}")


def animate(
    renderer,
    scene,
    methods: Sequence[str],
    *,
    frames: int,
    fps: float,
    output: str,
    options: dict[str, Any] | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> dict[str, Any]:
    """Renders ``frames`` frames of ``scene`` at ``fps`` with each method of ``methods``, tiles
    them left to right and writes ``output``. ``options`` are render options, each passed only
    to the methods that take it. Checks the output kind (and the optional packages it needs)
    before rendering. Returns {"files": [...], "frames", "size": (W, H), "methods"}.
    """
    import vsgl

    kind = output_kind(output)
    iio = None if kind == "png-folder" else _imageio(kind)
    times = frame_times(frames, fps)
    if not methods:
        raise ValueError("methods: expected at least one method")
    for m in methods:
        if m not in vsgl.METHODS:
            raise ValueError(f"methods: unknown method {m!r}; methods: {', '.join(vsgl.METHODS)}")
    options = options or {}
    per_method: list[list[np.ndarray]] = []
    total = len(methods) * len(times)
    done = 0
    for m in methods:
        takes = vsgl.method_options(m)
        mine = {k: v for k, v in options.items() if k in takes and v is not None}
        images = []
        for frame in renderer.render_sequence(scene, [{"time": t} for t in times], method=m, aovs=["ldr"], **mine):
            images.append(frame.aov("ldr"))
            done += 1
            if progress is not None:
                progress(done, total)
        per_method.append(images)
    tiles = [tile([per_method[i][k] for i in range(len(methods))]) for k in range(len(times))]
    label = "tiles left to right: " + " | ".join(methods)
    files: list[str] = []
    if kind == "png-folder":
        folder = pathlib.Path(output)
        folder.mkdir(parents=True, exist_ok=True)
        for k, im in enumerate(tiles):
            path = folder / f"frame_{k:05d}.png"
            write_png(path, im, comment=f"vsgl animate, frame {k}, t = {times[k]:.6g} s; {label}")
            files.append(str(path))
    else:
        rgb = np.stack([im[..., :3] for im in tiles])
        if kind == ".gif":
            # GIF frame durations are in milliseconds (Pillow's plugin); loop=0 repeats forever.
            iio.imwrite(output, rgb, duration=1000.0 / fps, loop=0)
        else:
            # H.264 in yuv420p needs even sides (chroma is halved in both directions), and tiles
            # with 1-pixel separators are often odd: pad one black row/column rather than let
            # the writer resize (blurring every frame).
            pad_h, pad_w = rgb.shape[1] % 2, rgb.shape[2] % 2
            if pad_h or pad_w:
                rgb = np.pad(rgb, ((0, 0), (0, pad_h), (0, pad_w), (0, 0)))
            iio.imwrite(output, rgb, fps=fps, codec="libx264", macro_block_size=1)
        files.append(output)
    h, w = tiles[0].shape[:2]
    return {"files": files, "frames": len(tiles), "size": (w, h), "methods": list(methods), "label": label}


def main_progress(done: int, total: int) -> None:
    """One line on stderr kept up to date (a new line per 10% when stderr is not a terminal)."""
    if sys.stderr.isatty():
        print(f"\ranimate: frame {done}/{total} ({100 * done // total}%)", end="" if done < total else "\n", file=sys.stderr, flush=True)
    elif done == total or done % max(1, total // 10) == 0:
        print(f"animate: frame {done}/{total} ({100 * done // total}%)", file=sys.stderr, flush=True)
