"""The live view in Jupyter: ``vsgl.view(scene, method="vsgl", **options)``.

Built on ``jupyter_rfb``'s remote-frame-buffer widget (the optional extra
``pip install vsgl[view]``). It was chosen over ``rendercanvas``'s anywidget backend because it
is the piece that backend itself builds on for notebooks: a widget that takes a NumPy frame and
gives back browser events, with the frame pipeline a live view needs already in it — JPEG while
frames follow each other, a lossless PNG once they stop, and at most ``max_buffered_frames``
(two) frames sent and not yet shown by the browser, so a slow renderer or connection slows the
frame rate instead of queueing lag. vsgl needs no canvas abstraction on top: it renders on its
own device and hands over arrays.

The widget is a thin shell around :class:`vsgl.view_session.ViewSession` (the frames, the
camera and light controls of ``vsgl.camera_control`` and ``vsgl.scene_edit``, the comparison):
displayed, it shows the frame, a status line (GPU ms, frames per second, the error against the
reference once the view stops) and a settings panel.
"""

from __future__ import annotations

import asyncio
from typing import Any

import ipywidgets as widgets
from IPython.display import display
from jupyter_rfb import RemoteFrameBuffer

import vsgl
from vsgl.camera_control import CameraControls
from vsgl.scene_edit import LightControls
from vsgl.view_session import PANEL_OPTIONS, ViewSession, display_aovs

# The view counts as stopped after this long without an event; then the slow halves are
# refreshed and the error is measured.
STILL_AFTER_S = 0.6
# The widget's throttle: frames sent and not yet confirmed by the browser.
MAX_FRAMES_IN_FLIGHT = 2


class LiveView(RemoteFrameBuffer):
    """A live view of a :class:`ViewSession` (``vsgl.view`` makes one). ``session`` is the
    state; ``panel`` the settings widgets; ``status_line`` the overlay's text widget."""

    def __init__(self, session: ViewSession, overlay: bool = True, **kwargs: Any):
        w, h = session.logical_size
        super().__init__(css_width=f"{int(w)}px", css_height=f"{int(h)}px", **kwargs)
        self.max_buffered_frames = MAX_FRAMES_IN_FLIGHT
        self.session = session
        # GPU ms, frames per second and (when stopped) the error, drawn into the frame.
        self.overlay = bool(overlay)
        self.status_line = widgets.HTML(value=self._status_html())
        self.panel = _Panel(self)
        self._still_handle: asyncio.TimerHandle | None = None
        self._still_pending = False

    # --- jupyter_rfb's two hooks -------------------------------------------------------------
    def handle_event(self, event: dict[str, Any]) -> None:
        if self.session.handle(event):
            self.request_draw()
            self._schedule_still()

    def get_frame(self) -> Any:
        still, self._still_pending = self._still_pending, False
        try:
            frame = self.session.still() if still else self.session.frame()
        except vsgl.VsglError as e:
            self.status_line.value = f"<span style='color:#b00'>{_escape(str(e))}</span>"
            return None
        self.status_line.value = self._status_html()
        return self.session.with_overlay(frame) if self.overlay else frame

    # --- the view stopping -----------------------------------------------------------------
    def _schedule_still(self) -> None:
        """Draws once more, measuring the error, when no event has come for STILL_AFTER_S."""
        if self._still_handle is not None:
            self._still_handle.cancel()
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            return  # no event loop (a plain script): call view.refresh_still() instead
        self._still_handle = loop.call_later(STILL_AFTER_S, self.refresh_still)

    def refresh_still(self) -> None:
        """Treats the view as stopped: the next frame refreshes slow halves and the error."""
        self._still_handle = None
        self._still_pending = True
        self.request_draw()

    def settings_changed(self) -> None:
        self.request_draw()
        self._schedule_still()

    def _status_html(self) -> str:
        return f"<code>{_escape(self.session.status())}</code>"

    def help_text(self) -> str:
        rows = CameraControls.BINDINGS + LightControls.BINDINGS
        return "; ".join(f"{keys}: {what}" for keys, what in rows)

    def _ipython_display_(self) -> None:
        display(widgets.VBox([self, self.status_line, self.panel.box]))


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


class _Panel:
    """The settings panel: the method (and the second compared method), the options of
    ``PANEL_OPTIONS`` the first method takes, exposure and the AOV shown. A refused value shows
    render's error in the status line and leaves the settings as they were."""

    def __init__(self, view: LiveView):
        self.view = view
        s = view.session
        self.method = widgets.Dropdown(options=list(vsgl.METHODS), value=s.methods[0], description="method")
        self.method.observe(lambda c: self._set(lambda: s.set_method(c["new"], 0)), names="value")
        row = [self.method]
        if len(s.methods) == 2:
            self.other = widgets.Dropdown(options=list(vsgl.METHODS), value=s.methods[1], description="right")
            self.other.observe(lambda c: self._set(lambda: s.set_method(c["new"], 1)), names="value")
            row.append(self.other)
        self.exposure = widgets.FloatLogSlider(value=s.exposure, base=2, min=-6, max=6, step=0.25, description="exposure")
        self.exposure.observe(lambda c: self._set(lambda: s.set_exposure(c["new"])), names="value")
        self.aov = widgets.Dropdown(options=display_aovs(s.methods[0]), value=s.aov, description="aov")
        self.aov.observe(lambda c: self._set(lambda: s.set_aov(c["new"])), names="value")
        self.options_box = widgets.HBox(self._option_widgets())
        self.help = widgets.HTML(value=f"<small>{_escape(view.help_text())}</small>")
        self.box = widgets.VBox([widgets.HBox(row + [self.aov]), self.options_box, self.exposure, self.help])

    def _set(self, change) -> None:
        s = self.view.session
        try:
            change()
        except vsgl.VsglError as e:
            self.view.status_line.value = f"<span style='color:#b00'>{_escape(str(e))}</span>"
            return
        self.aov.options = display_aovs(s.methods[0])
        self.aov.value = s.aov
        self.options_box.children = self._option_widgets()
        self.view.settings_changed()

    def _option_widgets(self) -> list:
        s = self.view.session
        specs = vsgl.method_info(s.methods[0])["options"]
        out = []
        for name in PANEL_OPTIONS:
            spec = specs.get(name)
            if spec is None:
                continue
            value = s.options.get(name, spec["default"])
            if spec["type"] == "choice":
                w = widgets.Dropdown(options=spec["choices"], value=value, description=name)
            elif spec["type"] == "bool":
                w = widgets.Checkbox(value=bool(value), description=name)
            elif spec["type"] == "int":
                w = widgets.BoundedIntText(value=int(value), min=spec.get("min", 0), max=spec.get("max", 2**31 - 1), description=name)
            else:
                w = widgets.FloatText(value=float(value), description=name)
            w.observe(lambda c, name=name: self._set(lambda: s.set_options(**{name: c["new"]})), names="value")
            out.append(w)
        return out


def view(scene: vsgl.Scene, method: str = "vsgl", overlay: bool = True, **kwargs: Any) -> LiveView:
    """See ``vsgl.view``."""
    return LiveView(ViewSession(scene, method, **kwargs), overlay=overlay)
