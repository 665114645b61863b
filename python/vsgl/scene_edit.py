"""Scene edits of the live views (the notebook widget, ``vsgl.view``, and the desktop window):
select a light and drag it. Events are the dicts ``vsgl.camera_control`` describes.

Bindings (``LightControls.BINDINGS``):

- Shift + left drag moves the selected light: a spot or point light slides parallel to the
  image plane at its own depth, so it stays under the pointer; a directional light turns (a
  drag across the view's height turns it by half a turn);
- L (or ``]``) selects the next light, ``[`` the previous one.

A light is replaced, not mutated (``vsgl`` lights are immutable values): the edited scene's
``lights`` list gets a new light of the same type with every other field kept.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

import vsgl
from vsgl.camera_control import Event, OrbitCamera, event_position
from vsgl.lightspec import KINDS

_KIND_OF = {make: kind for kind, (make, _, _) in KINDS.items()}


def light_kind(light: Any) -> str:
    """The type name ``vsgl.lightspec`` gives ``light``: "spot", "point" or "directional"."""
    return _KIND_OF[type(light)]


def light_fields(light: Any) -> dict[str, Any]:
    """Every constructor field of ``light``, by the constructor's keyword names."""
    _, required, optional = KINDS[light_kind(light)]
    return {name: getattr(light, name) for name in required + optional}


def with_fields(light: Any, **changes: Any) -> Any:
    """A light of ``light``'s type with ``changes`` applied and every other field kept."""
    make = KINDS[light_kind(light)][0]
    return make(**{**light_fields(light), **changes})


def _rotate(v: np.ndarray, axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' rotation of ``v`` about unit ``axis``."""
    c, s = math.cos(angle), math.sin(angle)
    return v * c + np.cross(axis, v) * s + axis * float(np.dot(axis, v)) * (1.0 - c)


class LightEditor:
    """Edits ``scene``'s lights: which one is selected, and moves of the selected one."""

    def __init__(self, scene: vsgl.Scene):
        self.scene = scene
        self.selected = 0

    @property
    def light(self) -> Any | None:
        lights = self.scene.lights
        return lights[self.selected] if 0 <= self.selected < len(lights) else None

    def select(self, index: int) -> None:
        n = len(self.scene.lights)
        if not 0 <= index < max(n, 1):
            raise ValueError(f"light index: must be in 0..{n - 1} (the scene has {n} lights), got {index}")
        self.selected = index

    def select_next(self, step: int = 1) -> bool:
        n = len(self.scene.lights)
        if n < 2:
            return False
        self.selected = (self.selected + step) % n
        return True

    def _replace(self, light: Any) -> None:
        lights = list(self.scene.lights)
        lights[self.selected] = light
        self.scene.lights = lights

    def drag(self, dx: float, dy: float, orbit: OrbitCamera, height: float) -> bool:
        """Moves the selected light by a pointer move of (dx, dy) logical pixels in a view
        ``height`` pixels tall, seen through ``orbit``'s camera. False when there is no light
        or it cannot move (a positional light at or behind the eye's plane)."""
        light = self.light
        if light is None or (dx == 0 and dy == 0):
            return False
        eye, forward, right, up = orbit.basis()
        if isinstance(light, vsgl.DirectionalLight):
            k = math.pi / max(height, 1.0)
            d = np.asarray(light.direction, dtype=np.float64)
            d = _rotate(d, np.array([0.0, 1.0, 0.0]), -dx * k)
            d = _rotate(d, right, -dy * k)
            self._replace(with_fields(light, direction=tuple(float(x) for x in d)))
            return True
        p = np.asarray(light.position, dtype=np.float64)
        depth = float(np.dot(p - eye, forward))
        if depth <= 0:
            return False
        s = orbit.world_per_pixel(depth, height)
        p = p + right * dx * s - up * dy * s
        self._replace(with_fields(light, position=tuple(float(x) for x in p)))
        return True


class LightControls:
    """Maps events to a ``LightEditor``'s edits. ``handle(event, orbit, height)`` returns True
    when the scene's lights changed; it claims Shift + left drags (``claims_drag``) so the
    camera controls leave them alone."""

    BINDINGS = (
        ("Shift + left drag", "move the selected light"),
        ("L or ], [", "select the next / previous light"),
    )

    def __init__(self, editor: LightEditor):
        self.editor = editor
        self._last: tuple[float, float] | None = None

    @property
    def claims_drag(self) -> bool:
        return self._last is not None

    def handle(self, event: Event, orbit: OrbitCamera, height: float) -> bool:
        kind = event.get("type", event.get("event_type"))
        if kind == "pointer_down":
            shift = "Shift" in tuple(event.get("modifiers", ()))
            self._last = event_position(event) if event.get("button") == 1 and shift else None
            return False
        if kind == "pointer_up":
            self._last = None
            return False
        if kind == "pointer_move" and self._last is not None:
            if not event.get("buttons"):
                self._last = None
                return False
            x, y = event_position(event)
            x0, y0 = self._last
            self._last = (x, y)
            return self.editor.drag(x - x0, y - y0, orbit, height)
        if kind == "key_down":
            key = str(event.get("key", "")).lower()
            if key in ("l", "]"):
                self.editor.select_next(1)
                return False
            if key == "[":
                self.editor.select_next(-1)
                return False
        return False
