"""The desktop window of the live view: ``python -m vsgl view SCENE`` and ``Renderer.view()``.

A window presents the renderer's frames from its own device (a wgpu surface; nothing is read
back on the default path): each method renders its ``ldr`` image on the GPU, the window composes
the methods side by side, draws its settings panel (egui) over them and presents. What is shown
and how events move it is the notebook view's :class:`~vsgl.view_session.ViewSession`, with the
same camera and light controls (``vsgl.camera_control``, ``vsgl.scene_edit``): the window turns
its events into the same event dicts.

- The loop waits for events while nothing changes, renders a frame after each change, and once
  no event has come for ``STILL_AFTER_S`` refreshes the slow halves of a comparison and
  measures the error against the reference, as the notebook view does.
- Keys beyond the camera's and the lights': ``Escape`` closes the window, ``F12`` or ``P``
  saves a screenshot (``vsgl-screenshot-NNN.png`` in ``screenshot_dir``).
- What the GPU does not make ready to show (an AOV other than ``ldr``, exposure other than 1, a
  ground truth's last frame) is rendered through the readback path and uploaded.
- ``frames=N`` renders N frames whatever the events, then closes: with ``screenshot=`` that
  is the headless run of ``--frames N --screenshot out.png [--no-ui]`` (under Xvfb, say). The
  screenshot is copied from the window's target, the texture the surface was blitted from: the
  frame presented, panel included when shown.

Without a display (``DISPLAY`` unset) or with an adapter that cannot present, opening raises
``vsgl.WindowUnavailableError`` naming the cause and pointing to the notebook view or Xvfb.
``offscreen=True`` runs the same frame path without a window (for timing where there is no
display).
"""

from __future__ import annotations

import math
import pathlib
import time
from typing import Any, Sequence

import vsgl
from vsgl import _vsgl
from vsgl.view_session import PANEL_OPTIONS, ViewSession, display_aovs, is_slow
from vsgl.video import write_png

# The view counts as stopped after this long without an event (as the notebook view).
STILL_AFTER_S = 0.6
# While idle, the loop waits this long for an event before looking at the clock again.
_IDLE_WAIT_S = 0.05
_SCREENSHOT_KEYS = ("f12", "p")
_CLOSE_KEYS = ("escape",)


def panel_controls(session: ViewSession) -> list[tuple]:
    """The panel's controls for ``session``'s methods and options (kinds and ranges from
    ``vsgl.method_info``, so the panel offers only values ``render`` takes)."""
    methods = list(vsgl.METHODS)
    out: list[tuple] = [("choice", "method", methods, session.methods[0])]
    if len(session.methods) == 2:
        out.append(("choice", "right", methods, session.methods[1]))
    out.append(("choice", "aov", display_aovs(session.methods[0]), session.aov))
    specs = vsgl.method_info(session.methods[0])["options"]
    for name in PANEL_OPTIONS:
        spec = specs.get(name)
        if spec is None:
            continue
        value = session.options.get(name, spec["default"])
        kind = spec["type"]
        if kind == "choice":
            out.append(("choice", name, [str(c) for c in spec["choices"]], str(value)))
        elif kind == "bool":
            out.append(("toggle", name, bool(value)))
        elif kind == "int":
            lo, hi = int(spec.get("min", 0)), int(spec.get("max", 4096))
            hi = min(hi, 1 << 16)  # a slider over 2^31 values is no control
            out.append(("int", name, lo, hi, min(max(int(value), lo), hi), hi / max(lo, 1) > 100))
        elif kind == "float":
            lo, hi = float(spec.get("min", 0.0)), float(spec.get("max", 100.0))
            if math.isfinite(lo) and math.isfinite(hi) and value is not None:
                out.append(("float", name, lo, hi, float(value), lo > 0 and hi / lo > 100))
    out.append(("float", "exposure", 1 / 64, 64.0, session.exposure, True))
    return out


def apply_change(session: ViewSession, name: str, value: Any) -> None:
    """Applies one panel change as the notebook panel does (render's errors propagate, the
    settings stay as they were)."""
    if name == "method":
        session.set_method(str(value), 0)
    elif name == "right":
        session.set_method(str(value), 1)
    elif name == "aov":
        session.set_aov(str(value))
    elif name == "exposure":
        session.set_exposure(float(value))
    else:
        session.set_options(**{name: value})


class WindowView:
    """A desktop window around a :class:`ViewSession` (see the module's documentation)."""

    def __init__(self, scene: vsgl.Scene, method: str = "vsgl", *, compare: Sequence[str] | None = None,
                 renderer: vsgl.Renderer | None = None, size: tuple[int, int] = (960, 540),
                 camera: vsgl.Camera | None = None, aov: str = "ldr", exposure: float = 1.0, seed: int = 0,
                 ui: bool = True, vsync: bool = True, offscreen: bool = False, title: str | None = None,
                 screenshot_dir: str | pathlib.Path = ".", **options: Any):
        self.session = ViewSession(scene, method, compare=compare, renderer=renderer, size=size, camera=camera,
                                   aov=aov, exposure=exposure, seed=seed, **options)
        r = self.session.renderer
        w, h = r.width, r.height
        self.ui = bool(ui)
        if offscreen:
            self.window = _vsgl.ViewWindow.offscreen(r, w, h, ui=self.ui)
        else:
            name = title or f"vsgl: {' | '.join(self.session.methods)}"
            self.window = _vsgl.ViewWindow.open(r, name, w, h, ui=self.ui, vsync=vsync)
        self.screenshot_dir = pathlib.Path(screenshot_dir)
        self.screenshots: list[pathlib.Path] = []
        self.message = ""  # the last refused setting's error, shown in the status line
        self._sync_size()

    def _sync_size(self) -> None:
        """Renders at the window's size in physical pixels (a scaled display makes it larger
        than the size asked for in logical pixels)."""
        w, h = self.window.size
        if (w, h) != (self.session.renderer.width, self.session.renderer.height):
            ratio = self.window.pixel_ratio or 1.0
            self.session.handle({"type": "resize", "width": w / ratio, "height": h / ratio, "pixel_ratio": ratio})

    # --- events ----------------------------------------------------------------------------
    def handle(self, event: dict[str, Any]) -> bool:
        """Applies a window event; True when the frame shown changes."""
        kind = event.get("type")
        if kind == "key_down":
            key = str(event.get("key", "")).lower()
            if key in _CLOSE_KEYS:
                self.window.close()
                return False
            if key in _SCREENSHOT_KEYS:
                self.save_screenshot()
                return False
        changed = self.session.handle(event)
        if kind == "resize":
            self._sync_size()
        return changed

    # --- frames ----------------------------------------------------------------------------
    def draw(self, still: bool = False) -> bool:
        """Renders each method into the window and presents. Returns whether the panel changed
        a setting (then the next frame differs)."""
        s = self.session
        started = time.perf_counter()
        gpu_ms = 0.0
        for i in sorted(range(len(s.methods)), key=lambda i: is_slow(s.methods[i])):
            method = s.methods[i]
            if s.aov == "ldr" and s.exposure == 1.0 and not is_slow(method):
                f = self.window.render_into(i, s.scene, s.orbit.camera(), method, **s.render_options(method, s._shares[i]))
                s.note_frame(method, f)
                gpu_ms += float(f.timings_ms.get("total", 0.0))
            else:
                image, ms, _ = s._method_image(method, s._shares[i], still)
                self.window.upload_image(i, image)
                gpu_ms += ms
        if still and s._errors_measured():
            s.error = s.measure_error()
        changed = self.present()
        s.count_frame(time.perf_counter() - started, gpu_ms)
        return changed

    def present(self) -> bool:
        """Presents the images the window has, with the panel drawn over them (a panel that
        needs drawing again costs no render). Returns whether the panel changed a setting."""
        s = self.session
        w = self.window.size[0]
        split = None if len(s.methods) == 1 else min(max(int(round(s.split * w)), 0), w)
        if not self.ui:
            self.window.present(split)
            return False
        ratio = self.window.pixel_ratio or 1.0
        labels = [] if split is None else [(s.methods[0], 0.0), (s.methods[1], split / ratio)]
        status = self.message or s.status()
        changed = False
        for name, value in self.window.present(split, panel_controls(s), status, labels):
            try:
                apply_change(s, name, value)
                self.message = ""
                changed = True
            except vsgl.VsglError as e:
                self.message = f"{name}: {e}"
        return changed

    def screenshot(self):
        """The last frame presented, (H, W, 4) uint8."""
        return self.window.screenshot()

    def save_screenshot(self, path: str | pathlib.Path | None = None) -> pathlib.Path:
        if path is None:
            self.screenshot_dir.mkdir(parents=True, exist_ok=True)
            path = self.screenshot_dir / f"vsgl-screenshot-{len(self.screenshots):03d}.png"
        path = pathlib.Path(path)
        write_png(path, self.screenshot(), comment=f"vsgl view: {self.session.status()}")
        self.screenshots.append(path)
        return path

    def run(self, frames: int | None = None, screenshot: str | pathlib.Path | None = None) -> dict[str, Any]:
        """Runs the window until it is closed (or for ``frames`` frames), then closes it;
        ``screenshot``: saves the last frame presented there. Returns the frames drawn, their
        median wall milliseconds and the screenshot's path."""
        if frames is not None and frames < 1:
            raise vsgl.ArgumentError(f"frames: at least 1, got {frames!r}")
        drawn = 0
        dirty, still_pending = True, False
        last_change = time.perf_counter()
        walls: list[float] = []
        try:
            while not self.window.closed and (frames is None or drawn < frames):
                idle = frames is None and not dirty
                repaint = False
                for event in self.window.poll_events(_IDLE_WAIT_S if idle else 0.0):
                    if event["type"] == "repaint":
                        repaint = True
                    elif self.handle(event):
                        dirty = True
                if self.window.closed:
                    break
                now = time.perf_counter()
                if dirty or frames is not None:
                    if dirty:
                        still_pending, last_change = True, now
                    dirty = self.draw()
                elif still_pending and now - last_change >= STILL_AFTER_S:
                    dirty = self.draw(still=True)
                    still_pending = False
                else:
                    if repaint:
                        dirty = self.present()
                    continue
                walls.append(time.perf_counter() - now)
                drawn += 1
            shot = self.save_screenshot(screenshot) if screenshot is not None and drawn else None
        finally:
            self.window.close()
        walls.sort()
        return {"frames": drawn, "median_frame_ms": 1e3 * walls[len(walls) // 2] if walls else None,
                "screenshot": None if shot is None else str(shot)}


def view(scene: vsgl.Scene, method: str = "vsgl", *, frames: int | None = None,
         screenshot: str | pathlib.Path | None = None, **kwargs: Any) -> dict[str, Any]:
    """Opens a desktop window on ``scene`` and runs it until it is closed (``Renderer.view``
    and ``python -m vsgl view``); keyword arguments as :class:`WindowView`'s. Returns what
    :meth:`WindowView.run` returns."""
    return WindowView(scene, method, **kwargs).run(frames=frames, screenshot=screenshot)
