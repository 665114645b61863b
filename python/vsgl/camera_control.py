"""Camera controls of the live views (the notebook widget, ``vsgl.view``, and the desktop
window): an orbit camera, and the mapping from pointer, wheel and key events to its moves.

Events are dicts in the remote-frame-buffer event format that ``jupyter_rfb`` delivers and that
the desktop window produces from its own events, so one mapping serves both:

- ``{"type": "pointer_down" | "pointer_move" | "pointer_up", "x", "y", "button", "buttons",
  "modifiers"}``: positions in logical pixels from the top left; ``button`` 1 is the left, 2
  the right, 3 the middle button; ``buttons`` the ones held; ``modifiers`` names such as
  ``"Shift"``, ``"Control"``, ``"Alt"``;
- ``{"type": "wheel", "dx", "dy", "x", "y", "modifiers"}``: ``dy`` > 0 scrolls down;
- ``{"type": "key_down" | "key_up", "key", "modifiers"}``: ``key`` as the browser names it
  (``"w"``, ``"Home"``, ``"Escape"``);
- ``{"type": "resize", "width", "height", "pixel_ratio"}`` (``"ratio"`` in newer versions).

The bindings (``CameraControls.BINDINGS`` lists them for help texts):

- left drag orbits about the pivot; right or middle drag pans; the wheel zooms toward it;
- W / S fly forward and back, A / D left and right, Q / E down and up (a key press moves a
  twentieth of the scene's size; the pivot moves along);
- R or Home resets to the camera the view started from (the scene's own).

The orbit keeps world +Y up and clamps the pitch short of the poles, so the camera never rolls
or flips; a camera given with another ``up`` is used as given until the first move.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np

import vsgl

Event = Mapping[str, Any]

# Pitch stops this far short of straight up or down, where yaw is undefined.
_PITCH_LIMIT = math.radians(89.0)
# A drag across the view's height turns the camera by half a turn.
_ORBIT_RADIANS_PER_HEIGHT = math.pi
# One wheel notch (100 units in browsers) scales the pivot distance by this.
_ZOOM_PER_NOTCH = 1.15
# A fly key moves this fraction of the scene's size.
_FLY_FRACTION = 1.0 / 20.0


def _unit(v: Sequence[float] | np.ndarray) -> np.ndarray:
    a = np.asarray(v, dtype=np.float64)
    n = float(np.linalg.norm(a))
    return a / n if n > 0 else a


@dataclass
class _Pose:
    target: np.ndarray  # the pivot, world space
    distance: float  # from the pivot to the eye
    yaw: float  # of the direction from the pivot to the eye, about +Y (0: toward +Z)
    pitch: float  # of that direction above the horizon


class OrbitCamera:
    """A camera that orbits, pans, zooms about a pivot and flies, starting from ``camera``.

    ``scene_size`` (the scene's bounding diagonal) scales flying and bounds zooming; the pivot
    is ``pivot_distance`` in front of the eye. ``camera()`` returns ``vsgl.Camera``: the very
    camera given until the first move (so a reset shows the scene's camera exactly), then a
    ``Camera.look_at`` from the pose."""

    def __init__(self, camera: vsgl.Camera, pivot_distance: float, scene_size: float):
        if not (math.isfinite(pivot_distance) and pivot_distance > 0):
            raise ValueError(f"pivot_distance: must be positive and finite, got {pivot_distance}")
        if not (math.isfinite(scene_size) and scene_size > 0):
            raise ValueError(f"scene_size: must be positive and finite, got {scene_size}")
        self._start = camera
        self.scene_size = float(scene_size)
        self.fov_y_deg = camera.fov_y_deg
        forward = _unit(camera.forward)
        eye = np.asarray(camera.eye, dtype=np.float64)
        to_eye = -forward
        self._start_pose = _Pose(
            target=eye + forward * pivot_distance,
            distance=float(pivot_distance),
            yaw=math.atan2(to_eye[0], to_eye[2]),
            pitch=max(-_PITCH_LIMIT, min(_PITCH_LIMIT, math.asin(max(-1.0, min(1.0, to_eye[1]))))),
        )
        self.reset()

    @classmethod
    def for_scene(cls, scene: vsgl.Scene, camera: vsgl.Camera | None = None) -> "OrbitCamera":
        """Starts from ``camera`` (the scene's default camera when None), pivoting about the
        point in front of the eye nearest the centre of the scene's bounds."""
        camera = camera if camera is not None else scene.default_camera()
        lo, hi = (np.asarray(b, dtype=np.float64) for b in scene.bounds)
        size = float(np.linalg.norm(hi - lo)) or 1.0
        along = float(np.dot(0.5 * (lo + hi) - np.asarray(camera.eye), _unit(camera.forward)))
        return cls(camera, pivot_distance=max(along, 0.05 * size), scene_size=size)

    # --- the pose ------------------------------------------------------------------------
    def reset(self) -> None:
        """Back to the camera the view started from."""
        p = self._start_pose
        self._pose = _Pose(p.target.copy(), p.distance, p.yaw, p.pitch)
        self.moved = False

    def _to_eye(self) -> np.ndarray:
        p = self._pose
        return np.array([math.cos(p.pitch) * math.sin(p.yaw), math.sin(p.pitch), math.cos(p.pitch) * math.cos(p.yaw)])

    def basis(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(eye, forward, right, up) of the current camera, unit vectors, world space."""
        if not self.moved:
            forward = _unit(self._start.forward)
            up0 = _unit(self._start.up)
            right = _unit(np.cross(forward, up0))
            return np.asarray(self._start.eye, dtype=np.float64), forward, right, np.cross(right, forward)
        to_eye = self._to_eye()
        eye = self._pose.target + to_eye * self._pose.distance
        forward = -to_eye
        right = _unit(np.cross(forward, [0.0, 1.0, 0.0]))
        return eye, forward, right, np.cross(right, forward)

    def camera(self) -> vsgl.Camera:
        if not self.moved:
            return self._start
        eye = self._pose.target + self._to_eye() * self._pose.distance
        return vsgl.Camera.look_at(eye=tuple(eye), target=tuple(self._pose.target), up=(0.0, 1.0, 0.0), fov_y_deg=self.fov_y_deg)

    @property
    def target(self) -> tuple[float, float, float]:
        return tuple(float(x) for x in self._pose.target)  # type: ignore[return-value]

    @property
    def distance(self) -> float:
        return self._pose.distance

    # --- moves (pixel arguments are logical pixels of a view ``height`` pixels tall) -------
    def orbit(self, dx: float, dy: float, height: float) -> None:
        """Turns about the pivot: a drag to the right turns the scene to the right, a drag
        down shows it more from above."""
        k = _ORBIT_RADIANS_PER_HEIGHT / max(height, 1.0)
        self._pose.yaw -= dx * k
        self._pose.pitch = max(-_PITCH_LIMIT, min(_PITCH_LIMIT, self._pose.pitch + dy * k))
        self.moved = True

    def world_per_pixel(self, depth: float, height: float) -> float:
        """World length one pixel spans at ``depth`` in front of the eye."""
        return 2.0 * depth * math.tan(math.radians(self.fov_y_deg) * 0.5) / max(height, 1.0)

    def pan(self, dx: float, dy: float, height: float) -> None:
        """Moves the camera and pivot in the view plane so the pivot's depth follows the
        pointer."""
        _, _, right, up = self.basis()
        s = self.world_per_pixel(self._pose.distance, height)
        self._pose.target = self._pose.target - right * dx * s + up * dy * s
        self.moved = True

    def zoom(self, notches: float) -> None:
        """Toward the pivot (``notches`` < 0) or away from it."""
        d = self._pose.distance * _ZOOM_PER_NOTCH ** notches
        self._pose.distance = min(max(d, 1e-4 * self.scene_size), 1e3 * self.scene_size)
        self.moved = True

    def fly(self, forward: float, right: float, up: float) -> None:
        """Moves eye and pivot together by (forward, right, up) key presses."""
        _, f, r, _ = self.basis()
        step = _FLY_FRACTION * self.scene_size
        self._pose.target = self._pose.target + (f * forward + r * right + np.array([0.0, 1.0, 0.0]) * up) * step
        self.moved = True


# key -> (forward, right, up) presses
_FLY_KEYS = {"w": (1, 0, 0), "s": (-1, 0, 0), "a": (0, -1, 0), "d": (0, 1, 0), "q": (0, 0, -1), "e": (0, 0, 1)}
_RESET_KEYS = {"r", "home"}


def event_position(event: Event) -> tuple[float, float]:
    return float(event.get("x", 0.0)), float(event.get("y", 0.0))


class CameraControls:
    """Maps events to an ``OrbitCamera``'s moves. ``handle(event)`` returns True when the
    camera changed (the caller then draws a frame) and False for events that do not move it."""

    BINDINGS = (
        ("left drag", "orbit"),
        ("right / middle drag", "pan"),
        ("wheel", "zoom"),
        ("W A S D, Q E", "fly"),
        ("R or Home", "reset to the scene's camera"),
    )

    def __init__(self, orbit: OrbitCamera, height: float):
        self.orbit = orbit
        self.height = float(height)
        self._drag: tuple[str, float, float] | None = None  # (mode, last x, last y)

    def handle(self, event: Event) -> bool:
        kind = event.get("type", event.get("event_type"))
        if kind == "resize":
            self.height = float(event.get("height", self.height))
            return False
        if kind == "pointer_down":
            button = event.get("button")
            mode = "orbit" if button == 1 else "pan" if button in (2, 3) else None
            self._drag = (mode, *event_position(event)) if mode else None
            return False
        if kind == "pointer_up":
            self._drag = None
            return False
        if kind == "pointer_move":
            if self._drag is None or not event.get("buttons"):
                return False
            mode, x0, y0 = self._drag
            x, y = event_position(event)
            if (x, y) == (x0, y0):
                return False
            self._drag = (mode, x, y)
            (self.orbit.orbit if mode == "orbit" else self.orbit.pan)(x - x0, y - y0, self.height)
            return True
        if kind == "wheel":
            dy = float(event.get("dy", 0.0))
            if dy == 0.0:
                return False
            self.orbit.zoom(dy / 100.0)
            return True
        if kind == "key_down":
            key = str(event.get("key", "")).lower()
            if key in _FLY_KEYS:
                self.orbit.fly(*_FLY_KEYS[key])
                return True
            if key in _RESET_KEYS:
                was_moved = self.orbit.moved
                self.orbit.reset()
                return was_moved
        return False
