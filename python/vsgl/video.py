"""Animated sequences to video: ``python -m vsgl animate SCENE -o out.mp4`` and :func:`animate`.

Frames are rendered with ``Renderer.render_sequence`` (one ``{"time": k / fps}`` per frame,
which poses the scene's animations) and read back as the GPU-tone-mapped ``ldr`` AOV (sRGB
uint8). Several methods (``--compare vpl,vsgl,reference``) are tiled left to right, each
labelled with its name (:func:`draw_label`), with a 1-pixel white separator; their order is also
printed and stored in each PNG's ``Comment``.

In a notebook, :func:`clip` returns a :class:`Clip` that plays the frames inline (PNG data
URIs and a timer; no package needed).

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

# A 3×5 pixel font for the method names drawn on compared tiles (no font package needed): each
# glyph is five rows of three bits, most significant bit on the left. Characters without a glyph
# are drawn as a filled box, so a name never loses a letter silently.
_GLYPHS: dict[str, tuple[int, ...]] = {
    "a": (2, 5, 7, 5, 5), "b": (6, 5, 6, 5, 6), "c": (3, 4, 4, 4, 3), "d": (6, 5, 5, 5, 6),
    "e": (7, 4, 6, 4, 7), "f": (7, 4, 6, 4, 4), "g": (3, 4, 5, 5, 3), "h": (5, 5, 7, 5, 5),
    "i": (7, 2, 2, 2, 7), "j": (1, 1, 1, 5, 2), "k": (5, 5, 6, 5, 5), "l": (4, 4, 4, 4, 7),
    "m": (5, 7, 7, 5, 5), "n": (6, 5, 5, 5, 5), "o": (2, 5, 5, 5, 2), "p": (6, 5, 6, 4, 4),
    "q": (2, 5, 5, 6, 3), "r": (6, 5, 6, 5, 5), "s": (3, 4, 2, 1, 6), "t": (7, 2, 2, 2, 2),
    "u": (5, 5, 5, 5, 7), "v": (5, 5, 5, 5, 2), "w": (5, 5, 7, 7, 5), "x": (5, 5, 2, 5, 5),
    "y": (5, 5, 2, 2, 2), "z": (7, 1, 2, 4, 7), "0": (7, 5, 5, 5, 7), "1": (2, 6, 2, 2, 7),
    "2": (6, 1, 2, 4, 7), "3": (6, 1, 2, 1, 6), "4": (5, 5, 7, 1, 1), "5": (7, 4, 6, 1, 6),
    "6": (3, 4, 7, 5, 7), "7": (7, 1, 2, 2, 2), "8": (7, 5, 7, 5, 7), "9": (7, 5, 7, 1, 6),
    "_": (0, 0, 0, 0, 7), "-": (0, 0, 7, 0, 0), " ": (0, 0, 0, 0, 0),
    ".": (0, 0, 0, 0, 2), ":": (0, 2, 0, 2, 0), "/": (1, 1, 2, 4, 4), "=": (0, 7, 0, 7, 0),
}


def label_box(text: str, height: int) -> tuple[int, int, int]:
    """(box height, box width, scale) of the label :func:`draw_label` draws on a tile of
    ``height`` rows: glyphs scaled by max(1, height // 90), one glyph column apart, a 1-unit
    margin."""
    scale = max(1, height // 90)
    return (5 + 2) * scale, (4 * len(text) + 1) * scale, scale


def draw_label(image: np.ndarray, text: str, bottom: bool = False) -> np.ndarray:
    """A copy of the (H, W, 4) uint8 ``image`` with ``text`` in white on a black box in its
    top-left corner, or its bottom-left one with ``bottom`` (clipped to the image)."""
    out = image.copy()
    box_h, box_w, scale = label_box(text, image.shape[0])
    top = max(image.shape[0] - box_h, 0) if bottom else 0
    out[top:top + box_h, :box_w, :3] = 0
    out[top:top + box_h, :box_w, 3] = 255
    for i, ch in enumerate(text.lower()):
        rows = _GLYPHS.get(ch, (7, 7, 7, 7, 7))
        for r, bits in enumerate(rows):
            for c in range(3):
                if bits >> (2 - c) & 1:
                    y0, x0 = top + (1 + r) * scale, (1 + 4 * i + c) * scale
                    out[y0:y0 + scale, x0:x0 + scale, :3] = 255
    return out


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
    with open(path, "wb") as fh:
        _png_bytes(fh, rgba, comment)


def _png_bytes(out, rgba: np.ndarray, comment: str | None = None) -> None:
    rgba = np.ascontiguousarray(rgba, np.uint8)
    h, w = rgba.shape[:2]

    def chunk(kind: bytes, payload: bytes) -> bytes:
        return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload) & 0xFFFFFFFF)

    rows = np.concatenate([np.zeros((h, 1), np.uint8), rgba.reshape(h, w * 4)], axis=1)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
    if comment:
        data += chunk(b"tEXt", b"Comment\x00" + comment.encode("latin-1", "replace"))
    data += chunk(b"IDAT", zlib.compress(rows.tobytes(), 6)) + chunk(b"IEND", b"")
    out.write(data)


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


def render_tiles(renderer, scene, methods: Sequence[str], times: Sequence[float], options: dict[str, Any] | None = None,
                 progress: Callable[[int, int], None] | None = None, labels: bool = False) -> list[np.ndarray]:
    """The ``ldr`` frames of ``scene`` at ``times`` for each method, tiled left to right: one
    (H, W·M + M − 1, 4) uint8 array per time. ``options`` go only to the methods that take them;
    ``labels`` draws each method's name on its tile (:func:`draw_label`)."""
    import vsgl

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
            images.append(draw_label(frame.aov("ldr"), m) if labels else frame.aov("ldr"))
            done += 1
            if progress is not None:
                progress(done, total)
        per_method.append(images)
    return [tile([per_method[i][k] for i in range(len(methods))]) for k in range(len(times))]


class Clip:
    """Frames shown as an animation in Jupyter (``_repr_html_``: the frames as PNG data URIs and
    a few lines of script that step through them at ``fps``), so a notebook needs no video
    package. ``vsgl.video.clip(renderer, scene, ["vpl", "vsgl"], frames=60)`` makes one."""

    def __init__(self, frames: Sequence[np.ndarray], fps: float = 30.0) -> None:
        arrays = [np.asarray(f) for f in frames]
        if not arrays or any(a.dtype != np.uint8 or a.ndim != 3 or a.shape[2] not in (3, 4) or a.shape != arrays[0].shape for a in arrays):
            raise ValueError("frames: expected a non-empty list of (H, W, 3 or 4) uint8 images of one shape (the ldr AOV)")
        frame_times(len(arrays), fps)  # checks fps
        self.frames = [a if a.shape[2] == 4 else np.concatenate([a, np.full(a.shape[:2] + (1,), 255, np.uint8)], axis=2) for a in arrays]
        self.fps = float(fps)

    def _repr_html_(self) -> str:
        import base64
        import io
        import uuid

        uris = []
        for f in self.frames:
            buf = io.BytesIO()
            _png_bytes(buf, f)
            uris.append("data:image/png;base64," + base64.b64encode(buf.getvalue()).decode())
        element = f"vsgl-clip-{uuid.uuid4().hex}"
        h, w = self.frames[0].shape[:2]
        scale = max(1, 320 // max(w, 1))  # tiny test renders are hard to see at 1:1
        return (
            f'<img id="{element}" src="{uris[0]}" width="{w * scale}" height="{h * scale}" style="image-rendering: pixelated">'
            f"<script>(function() {{ const f = {uris!r}; let k = 0; const img = document.getElementById('{element}');"
            f" setInterval(function() {{ k = (k + 1) % f.length; img.src = f[k]; }}, {1000.0 / self.fps:.3f}); }})();</script>"
        )


def clip(renderer, scene, methods: Sequence[str] = ("vsgl",), *, frames: int = 60, fps: float = 30.0,
         options: dict[str, Any] | None = None) -> Clip:
    """Renders ``frames`` frames of the scene's animation (time k / fps) with ``methods`` tiled
    left to right, as a :class:`Clip` for a Jupyter notebook."""
    return Clip(render_tiles(renderer, scene, methods, frame_times(frames, fps), options), fps)


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
    labels: bool | None = None,
) -> dict[str, Any]:
    """Renders ``frames`` frames of ``scene`` at ``fps`` with each method of ``methods``, tiles
    them left to right and writes ``output``. ``options`` are render options, each passed only
    to the methods that take it. ``labels``: draw each method's name on its tile, as the papers'
    figures do (default: when more than one method is compared). Checks the output kind (and the
    optional packages it needs) before rendering. Returns {"files": [...], "frames", "size":
    (W, H), "methods"}.
    """
    kind = output_kind(output)
    iio = None if kind == "png-folder" else _imageio(kind)
    times = frame_times(frames, fps)
    if labels is None:
        labels = len(methods) > 1
    tiles = render_tiles(renderer, scene, methods, times, options, progress, labels=labels)
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
