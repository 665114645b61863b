"""What a live view shows, without the widget: the scene, its camera and light controls, the
method or the two methods compared, their options, and the display frames. The notebook widget
(``vsgl.view``) is a thin shell around a :class:`ViewSession`; a script or a test drives one the
same way, with the event dicts ``vsgl.camera_control`` describes.

- ``handle(event)`` applies an event (camera, light, divider, resize) and says whether the view
  changed; ``frame()`` renders what it shows as (H, W, 3) uint8 sRGB.
- ``compare=[a, b]`` shows method ``a`` left of a movable divider and ``b`` right of it, each
  labelled with its name (drag the divider, a white column, with the left button). A ground
  truth (``reference``, ``pathtrace``) is rendered again only when the view stops (``still()``),
  so moving stays interactive; until then its half shows its last frame.
- ``still()`` is called by the widget when no event has come for a moment: it refreshes the slow
  halves and measures the first method's error against the every-texel ``reference`` of the same
  reflective shadow map (what the virtual-light methods estimate): mean indirect light over the
  reference's, and relative RMS of 4×4 block means of the indirect light, as the bench reports.
- ``status()`` is the status line's text: the methods, GPU milliseconds of the last frame (the
  sum of the methods shown), frames per second over the last frames, the size, and the error once
  measured; ``with_overlay(frame)`` draws the short form (``overlay_text()``) into the frame's
  bottom-left corner. ``frame()`` itself is only the methods' pixels, so equal views give equal
  frames.
"""

from __future__ import annotations

import functools
import math
import time
from collections import deque
from typing import Any, Mapping, Sequence

import numpy as np

import vsgl
from vsgl import metrics
from vsgl.camera_control import CameraControls, Event, OrbitCamera, event_position
from vsgl.scene_edit import LightControls, LightEditor
from vsgl.video import draw_label



@functools.lru_cache(maxsize=None)
def _info(method: str) -> dict:
    """The registry's entry, read once per method (a frame asks it several times; 28 µs a read)."""
    return dict(vsgl.method_info(method))


def _takes(method: str, option: str) -> bool:
    return option in _info(method)["options"]


def is_slow(method: str) -> bool:
    """Ground truths (the registry's ``ground_truth``: the every-texel reference, the path
    tracer) take seconds a frame on a CPU adapter: in a comparison they are refreshed when the
    view stops, not on every move."""
    return bool(_info(method)["ground_truth"])

# The controls of the settings panel, where the method takes them (their kinds and ranges come
# from vsgl.method_info, so the panel never offers a value render would refuse).
PANEL_OPTIONS = ("num_lights", "K", "interleave", "visibility", "denoise")
# The divider is grabbed within this many logical pixels.
_DIVIDER_GRAB_PX = 4.0
# Largest side a view renders at (a 4K window at pixel ratio 1).
_MAX_SIDE = 4096


def display_aovs(method: str) -> list[str]:
    """The AOVs a view of ``method`` can show: ``ldr`` (the image tone-mapped on the GPU) first,
    then the method's own."""
    own = [a for a in _info(method)["aovs"] if a != "ldr"]
    return ["ldr", *own]


def to_display(x: np.ndarray, aov: str, exposure: float) -> np.ndarray:
    """(H, W, 3) uint8 of an AOV: ``ldr`` as the GPU tone-mapped it; radiance as
    ``Frame.save(".png")`` writes it (times ``exposure``, clamped, sRGB); normals as 0.5·n + 0.5;
    depth and other single channels over their largest finite value."""
    if aov == "ldr":
        return np.ascontiguousarray(np.asarray(x)[..., :3], dtype=np.uint8)
    a = np.asarray(x, dtype=np.float32)
    a = np.where(np.isfinite(a), a, 0.0)
    if aov == "normal":
        v = np.clip(0.5 * a[..., :3] + 0.5, 0.0, 1.0)
    elif a.shape[-1] == 1:
        peak = float(a.max()) if a.size else 0.0
        v = np.repeat(a / peak if peak > 0 else a, 3, axis=-1)
    else:
        v = metrics.srgb_encode(a[..., :3] * exposure)
    return np.ascontiguousarray((np.clip(v, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8))


def _check_methods(method: str, compare: Sequence[str] | None) -> list[str]:
    methods = [method] if compare is None else list(compare)
    if compare is not None and not 1 <= len(methods) <= 2:
        raise vsgl.ArgumentError(f"compare: one or two method names, got {len(methods)}: {methods}")
    for m in methods:
        if m not in vsgl.METHODS:
            name = "method" if compare is None else "compare"
            raise vsgl.ArgumentError(f"{name}: unknown method {m!r}; choose from {', '.join(vsgl.METHODS)}")
    return methods


def split_options(methods: Sequence[str], options: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Each method's share of ``options``: those it takes. An option no method takes raises the
    ArgumentError ``render`` raises for it (from the first method); values are checked as
    ``render`` checks them."""
    taken = [set(vsgl.method_options(m)) for m in methods]
    orphans = {k: v for k, v in options.items() if not any(k in t for t in taken)}
    if orphans:
        vsgl.check_method_options(methods[0], **orphans)
    shares = [{k: v for k, v in options.items() if k in t} for t in taken]
    for m, share in zip(methods, shares):
        vsgl.check_method_options(m, **share)
    return shares


class ViewSession:
    """A live view's state and frame source (see the module's documentation)."""

    def __init__(self, scene: vsgl.Scene, method: str = "vsgl", *, compare: Sequence[str] | None = None,
                 renderer: vsgl.Renderer | None = None, size: tuple[int, int] = (640, 360),
                 camera: vsgl.Camera | None = None, aov: str = "ldr", exposure: float = 1.0, seed: int = 0,
                 **options: Any):
        self.methods = _check_methods(method, compare)
        self._shares = split_options(self.methods, options)
        self.options = dict(options)
        self.scene = scene
        width, height = _check_size(size)
        self.pixel_ratio = 1.0
        self.logical_size = (float(width), float(height))
        self.renderer = renderer if renderer is not None else vsgl.Renderer(width, height)
        if (self.renderer.width, self.renderer.height) != (width, height):
            self.renderer.resize(width, height)
        self.orbit = OrbitCamera.for_scene(scene, camera)
        self.camera_controls = CameraControls(self.orbit, height)
        self.light_controls = LightControls(LightEditor(scene))
        self.seed = seed
        self._rsm_size: int | None = None  # the RSM side the last virtual-light frame used
        self._slow_cache: dict[str, tuple[tuple[int, int], np.ndarray]] = {}
        self.split = 0.5
        self._divider_drag = False
        self.aov = "ldr"
        self.set_aov(aov)
        self.exposure = 1.0
        self.set_exposure(exposure)
        self._frame_seconds: deque[float] = deque(maxlen=16)
        self.gpu_ms: float | None = None
        self.error: dict[str, float] | None = None
        self.frames = 0

    # --- settings (the panel's, checked as render checks them) ------------------------------
    def set_options(self, **changes: Any) -> None:
        """Changes options (None removes one, back to its default); raises render's
        ArgumentError and keeps the old options when a value is refused."""
        merged = {k: v for k, v in {**self.options, **changes}.items() if v is not None}
        self._shares = split_options(self.methods, merged)
        self.options = merged
        self._slow_cache.clear()
        self.error = None

    def set_method(self, method: str, index: int = 0) -> None:
        """Shows ``method`` as the ``index``-th method; options it does not take are dropped."""
        methods = list(self.methods)
        methods[index] = method
        _check_methods(methods[0], methods if len(methods) > 1 else None)
        kept = {k: v for k, v in self.options.items() if any(k in vsgl.method_options(m) for m in methods)}
        self._shares = split_options(methods, kept)
        self.methods, self.options = methods, kept
        if self.aov not in display_aovs(self.methods[0]):
            self.aov = "ldr"
        self._slow_cache.clear()
        self.error = None

    def set_aov(self, aov: str) -> None:
        shown = display_aovs(self.methods[0])
        if aov not in shown:
            raise vsgl.ArgumentError(f"aov: {self.methods[0]} shows {', '.join(shown)}; got {aov!r}")
        self.aov = aov
        self._slow_cache.clear()

    def set_exposure(self, exposure: float) -> None:
        if not (isinstance(exposure, (int, float)) and math.isfinite(exposure) and exposure > 0):
            raise vsgl.ArgumentError(f"exposure: must be positive and finite, got {exposure!r}")
        self.exposure = float(exposure)
        self._slow_cache.clear()

    # --- events ----------------------------------------------------------------------------
    def divider_x(self) -> float | None:
        """The divider's position in logical pixels, None without a comparison."""
        return self.split * self.logical_size[0] if len(self.methods) == 2 else None

    def handle(self, event: Event) -> bool:
        """Applies ``event``; True when the frame shown changes."""
        kind = event.get("type", event.get("event_type"))
        if kind == "resize":
            return self._resize(event)
        if kind == "close":
            return False
        divider = self.divider_x()
        if kind == "pointer_down" and divider is not None and event.get("button") == 1 \
                and not event.get("modifiers") and abs(event_position(event)[0] - divider) <= _DIVIDER_GRAB_PX:
            self._divider_drag = True
            return False
        if self._divider_drag:
            if kind == "pointer_up":
                self._divider_drag = False
                return False
            if kind == "pointer_move":
                split = min(max(event_position(event)[0] / self.logical_size[0], 0.0), 1.0)
                changed, self.split = split != self.split, split
                return changed
        height = self.logical_size[1]
        lights_changed = self.light_controls.handle(event, self.orbit, height)
        if self.light_controls.claims_drag and kind in ("pointer_down", "pointer_move"):
            changed = lights_changed
        else:
            changed = self.camera_controls.handle(event) or lights_changed
        if changed:
            self.error = None  # the slow halves keep their last frame until the view stops
        return changed

    def _resize(self, event: Event) -> bool:
        ratio = float(event.get("pixel_ratio", event.get("ratio", 1.0)) or 1.0)
        w, h = float(event.get("width", 0)), float(event.get("height", 0))
        if not (w >= 1 and h >= 1 and math.isfinite(w * h * ratio)):
            return False
        self.logical_size, self.pixel_ratio = (w, h), ratio
        self.camera_controls.handle(event)
        size = (min(max(1, round(w * ratio)), _MAX_SIDE), min(max(1, round(h * ratio)), _MAX_SIDE))
        if size == (self.renderer.width, self.renderer.height):
            return False
        self.renderer.resize(*size)
        self._slow_cache.clear()
        self.error = None
        return True

    # --- frames ----------------------------------------------------------------------------
    def render_options(self, method: str, share: Mapping[str, Any]) -> dict[str, Any]:
        """The keyword options a frame of ``method`` renders with (its share of the view's
        options, the view's seed, and for the reference the RSM side of the compared method)."""
        opts = dict(share)
        if _takes(method, "seed"):
            opts.setdefault("seed", self.seed)
        if method == "reference" and self._rsm_size is not None:
            # The every-texel reference of the RSM the compared method uses, which is what
            # virtual lights estimate (and costs what that method's generation reads).
            opts.setdefault("rsm_size", self._rsm_size)
        return opts

    def note_frame(self, method: str, frame: vsgl.Frame) -> None:
        """Keeps what a later frame needs of ``frame``: the RSM side a virtual-light method
        resolved (the reference of a comparison uses it)."""
        rsm = frame.settings.get("rsm_size")
        if method != "reference" and isinstance(rsm, int):
            self._rsm_size = rsm

    def _render(self, method: str, share: Mapping[str, Any], aovs: list[str]) -> vsgl.Frame:
        opts = self.render_options(method, share)
        f = self.renderer.render(self.scene, camera=self.orbit.camera(), method=method, aovs=aovs, **opts)  # type: ignore[call-overload]
        self.note_frame(method, f)
        return f

    def _method_image(self, method: str, share: Mapping[str, Any], still: bool,
                      with_indirect: bool = False) -> tuple[np.ndarray, float, np.ndarray | None]:
        """(display image, GPU ms, the `indirect` AOV when asked for) of one method; a slow
        method's last image while the view moves."""
        size = (self.renderer.width, self.renderer.height)
        cached = self._slow_cache.get(method)
        if is_slow(method) and not still and cached is not None and cached[0] == size:
            return cached[1], 0.0, None
        aov = self.aov if self.aov in display_aovs(method) else "ldr"
        if aov == "ldr" and self.exposure != 1.0:
            aov = "image"  # the GPU's tone map has exposure 1: expose the linear image here
        aovs = [aov] + (["indirect"] if with_indirect and aov != "indirect" else [])
        f = self._render(method, share, aovs)
        image = to_display(f.aov(aov), aov, self.exposure)
        if is_slow(method):
            self._slow_cache[method] = (size, image)
        return image, float(f.timings_ms.get("total", 0.0)), f.aov("indirect") if with_indirect else None

    def _errors_measured(self) -> bool:
        """Whether the first method has an error to measure (it makes indirect light from an
        RSM, and is not itself a ground truth)."""
        return _takes(self.methods[0], "rsm_size") and not is_slow(self.methods[0])

    def frame(self, still: bool = False) -> np.ndarray:
        """The frame the view shows now, (H, W, 3) uint8 at the renderer's size."""
        return self._frame(still, with_indirect=False)[0]

    def _frame(self, still: bool, with_indirect: bool) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        started = time.perf_counter()
        images: list[np.ndarray] = [np.empty(0, np.uint8)] * len(self.methods)
        indirects: dict[str, np.ndarray] = {}
        gpu_ms = 0.0
        # Slow methods last: a reference then uses the RSM side the compared method resolved.
        for i in sorted(range(len(self.methods)), key=lambda i: is_slow(self.methods[i])):
            method = self.methods[i]
            wanted = with_indirect and (i == 0 or method == "reference") and "indirect" in _info(method)["aovs"]
            images[i], ms, indirect = self._method_image(method, self._shares[i], still, wanted)
            if indirect is not None:
                indirects[method] = indirect
            gpu_ms += ms
        out = images[0] if len(images) == 1 else self._composite(images)
        self.count_frame(time.perf_counter() - started, gpu_ms)
        return out, indirects

    def count_frame(self, seconds: float, gpu_ms: float) -> None:
        """Counts a frame shown, for the status line: its wall seconds (render to shown) and the
        GPU milliseconds of the methods it rendered."""
        self._frame_seconds.append(seconds)
        self.gpu_ms = gpu_ms
        self.frames += 1

    def _composite(self, images: list[np.ndarray]) -> np.ndarray:
        h, w = images[0].shape[:2]
        cut = min(max(int(round(self.split * w)), 0), w)
        out = images[0].copy()
        out[:, cut:] = images[1][:, cut:]
        if 0 < cut:
            left = draw_label(np.dstack([out[:, :cut], np.full((h, cut, 1), 255, np.uint8)]), self.methods[0])
            out[:, :cut] = left[..., :3]
        if cut < w:
            right = draw_label(np.dstack([out[:, cut:], np.full((h, w - cut, 1), 255, np.uint8)]), self.methods[1])
            out[:, cut:] = right[..., :3]
        out[:, min(cut, w - 1)] = 255
        return out

    def overlay_text(self) -> str:
        """The overlay a view draws into the frame's bottom-left corner (``with_overlay``): GPU
        ms and frames per second of the last frames, and the error once the view has stopped."""
        parts = [] if self.gpu_ms is None else [f"{self.gpu_ms:.1f} ms"]
        fps = self.fps()
        if fps is not None:
            parts.append(f"{fps:.1f} fps")
        if self.error is not None:
            parts.append(f"ind/ref {self.error['mean_over_reference']:.2f} blk {self.error['block_error']:.2f}")
        return "  ".join(parts)

    def with_overlay(self, image: np.ndarray) -> np.ndarray:
        """``image`` (a frame of ``frame()``) with ``overlay_text()`` drawn in its bottom-left
        corner, white on black in the 3×5 font of the comparison labels."""
        text = self.overlay_text()
        if not text:
            return image
        h, w = image.shape[:2]
        rgba = np.dstack([image, np.full((h, w, 1), 255, np.uint8)])
        return np.ascontiguousarray(draw_label(rgba, text, bottom=True)[..., :3])

    def fps(self) -> float | None:
        """Frames per second this session renders (render, readback and compositing, the median
        of the last 16 frames; the rate frames reach the browser can only be lower)."""
        t = sorted(self._frame_seconds)
        return 1.0 / t[len(t) // 2] if t and t[len(t) // 2] > 0 else None

    # --- when the view stops ---------------------------------------------------------------
    def still(self) -> np.ndarray:
        """The view has stopped: refreshes slow methods' halves, measures the error, and
        returns the frame to show. Each method shown renders once (its image and its indirect
        light together), and the reference once more only when it is not one of them."""
        out, indirects = self._frame(True, with_indirect=self._errors_measured())
        self.error = self._error(indirects)
        return out

    def measure_error(self) -> dict[str, float] | None:
        """The first method's indirect light against the every-texel reference of the same
        reflective shadow map, or None for a method without one (``direct``, ``reference``,
        ``pathtrace``)."""
        return self._error({})

    def _error(self, indirects: Mapping[str, np.ndarray]) -> dict[str, float] | None:
        if not self._errors_measured():
            return None
        method = self.methods[0]
        x = indirects.get(method)
        if x is None:
            x = self._render(method, self._shares[0], ["indirect"]).aov("indirect")
        r = indirects.get("reference")
        if r is None:
            r = self._render("reference", {}, ["indirect"]).aov("indirect")
        ref_mean = float(r.mean())
        if ref_mean <= 0:
            return {"mean_over_reference": float("nan"), "block_error": float("nan")}
        block = 4 if min(r.shape[:2]) >= 4 else 1
        return {"mean_over_reference": float(x.mean()) / ref_mean, "block_error": metrics.block_rmse(x, r, block)}

    def status(self) -> str:
        parts = [" | ".join(self.methods)]
        if self.gpu_ms is not None:
            parts.append(f"{self.gpu_ms:.2f} GPU ms")
        fps = self.fps()
        if fps is not None:
            parts.append(f"{fps:.1f} fps")
        parts.append(f"{self.renderer.width}×{self.renderer.height}")
        if self.error is not None:
            parts.append(f"indirect over reference {self.error['mean_over_reference']:.3f}, "
                         f"4×4 block error {self.error['block_error']:.3f}")
        return " · ".join(parts)


def _check_size(size: Any) -> tuple[int, int]:
    try:
        w, h = (int(v) for v in size)
    except (TypeError, ValueError):
        raise vsgl.ArgumentError(f"size: (width, height) in pixels, got {size!r}") from None
    if not (1 <= w <= _MAX_SIDE and 1 <= h <= _MAX_SIDE):
        raise vsgl.ArgumentError(f"size: each side in 1..{_MAX_SIDE}, got {size!r}")
    return w, h
