"""The live view: the camera controls and light edits on their own (no GPU), then the view
session and the notebook widget driven by simulated events (no browser), and the renderer's
resize and default camera they rely on."""

from __future__ import annotations

import math

import numpy as np
import pytest

import vsgl
from vsgl.camera_control import CameraControls, OrbitCamera
from vsgl.scene_edit import LightControls, LightEditor, light_fields
from vsgl.view_session import ViewSession

SIZE = (72, 40)


def _press(x, y, button=1, modifiers=()):
    return {"type": "pointer_down", "x": x, "y": y, "button": button, "buttons": (button,), "modifiers": modifiers}


def _move(x, y, buttons=(1,), modifiers=()):
    return {"type": "pointer_move", "x": x, "y": y, "button": 0, "buttons": buttons, "modifiers": modifiers}


def _release(x, y, button=1):
    return {"type": "pointer_up", "x": x, "y": y, "button": button, "buttons": (), "modifiers": ()}


def _key(key):
    return {"type": "key_down", "key": key, "modifiers": ()}


def _orbit(eye=(0.0, 1.0, 4.0), target=(0.0, 1.0, 0.0), fov=40.0):
    cam = vsgl.Camera.look_at(eye=eye, target=target, fov_y_deg=fov)
    return OrbitCamera(cam, pivot_distance=float(np.linalg.norm(np.subtract(target, eye))), scene_size=4.0)


def _project(point, orbit: OrbitCamera, width: float, height: float) -> np.ndarray:
    """Pixel position (x right, y down, logical pixels) of a world point, by a pinhole of the
    orbit's fov and the view's aspect; written here from the camera's basis, not from the code
    under test's moves."""
    eye, forward, right, up = orbit.basis()
    d = np.asarray(point, dtype=np.float64) - eye
    z = float(np.dot(d, forward))
    t = math.tan(math.radians(orbit.fov_y_deg) / 2)
    ndc_x = float(np.dot(d, right)) / (z * t * width / height)
    ndc_y = float(np.dot(d, up)) / (z * t)
    return np.array([(ndc_x + 1) * width / 2, (1 - ndc_y) * height / 2])


# --- camera controls (no GPU) ---------------------------------------------------------------

def test_orbit_turns_about_the_pivot_and_clamps_the_pitch():
    o = _orbit()
    c = CameraControls(o, height=SIZE[1])
    assert o.camera() is o._start  # unmoved: the very camera given
    assert not c.handle(_press(10, 10))
    assert c.handle(_move(30, 10))  # 20 px right at 40 px height: yaw -= π/2
    eye = np.asarray(o.camera().eye)
    assert np.allclose(eye, [-4.0, 1.0, 0.0], atol=1e-9), eye  # the camera went left round the pivot
    assert math.isclose(float(np.linalg.norm(eye - np.asarray(o.target))), 4.0, rel_tol=1e-12)
    assert c.handle(_move(30, 10_000))  # far down: pitch stops short of the pole
    _, forward, _, _ = o.basis()
    assert math.isclose(math.degrees(math.asin(-forward[1])), 89.0, rel_tol=1e-9)
    assert not c.handle(_release(30, 10_000))
    assert not c.handle(_move(50, 50, buttons=()))  # a move with no button held is no move


def test_pan_keeps_the_pivot_under_the_pointer():
    o = _orbit()
    c = CameraControls(o, height=SIZE[1])
    before = _project(o.target, o, *SIZE)
    eye0 = np.asarray(o.basis()[0])
    target0 = np.asarray(o.target)
    c.handle(_press(20, 20, button=3))
    assert c.handle(_move(27, 15, buttons=(3,)))
    # The scene moved with the pointer: the point that was the pivot is now 7 px right, 5 px up.
    old_pivot_now = _project(target0, o, *SIZE)
    assert np.allclose(old_pivot_now - before, [7, -5], atol=1e-9), old_pivot_now - before
    assert np.allclose(np.asarray(o.basis()[0]) - eye0, np.asarray(o.target) - target0, atol=1e-12)


def test_wheel_zooms_and_keys_fly_and_reset():
    o = _orbit()
    c = CameraControls(o, height=SIZE[1])
    assert c.handle({"type": "wheel", "dx": 0, "dy": 200, "x": 0, "y": 0, "modifiers": ()})
    assert math.isclose(o.distance, 4.0 * 1.15 ** 2, rel_tol=1e-12)
    assert not c.handle({"type": "wheel", "dx": 5, "dy": 0, "x": 0, "y": 0, "modifiers": ()})
    eye = np.asarray(o.camera().eye)
    assert c.handle(_key("w"))  # a twentieth of the scene's size forward, pivot along
    assert np.allclose(np.asarray(o.camera().eye) - eye, [0, 0, -0.2], atol=1e-12)
    assert c.handle(_key("E"))
    assert np.allclose(np.asarray(o.camera().eye) - eye, [0, 0.2, -0.2], atol=1e-12)
    assert not c.handle(_key("x"))
    assert c.handle(_key("Home"))
    assert o.camera() is o._start
    assert not c.handle(_key("r"))  # already there: nothing to redraw


def test_orbit_camera_refuses_bad_sizes():
    cam = vsgl.Camera.look_at(eye=(0, 0, 1), target=(0, 0, 0))
    with pytest.raises(ValueError, match="pivot_distance"):
        OrbitCamera(cam, pivot_distance=0.0, scene_size=1.0)
    with pytest.raises(ValueError, match="scene_size"):
        OrbitCamera(cam, pivot_distance=1.0, scene_size=float("nan"))


# --- light edits (no GPU) --------------------------------------------------------------------

def _lit_scene():
    scene = vsgl.scenes.cornell_box()
    spot = vsgl.SpotLight(position=(0.3, 1.5, 0.2), direction=(0, -1, 0), intensity=3.0, color=(1, 0.9, 0.8),
                          inner_cone_deg=25, outer_cone_deg=35)
    scene.lights = [spot, vsgl.DirectionalLight(direction=(0, -1, 0), intensity=2.0)]
    return scene


def test_a_dragged_light_stays_under_the_pointer():
    scene = _lit_scene()
    o = _orbit()
    lights = LightControls(LightEditor(scene))
    before_fields = light_fields(scene.lights[0])
    before = _project(scene.lights[0].position, o, *SIZE)
    assert not lights.handle(_press(5, 5, modifiers=("Shift",)), o, SIZE[1])
    assert lights.claims_drag
    assert lights.handle(_move(11, 2, modifiers=("Shift",)), o, SIZE[1])
    after = _project(scene.lights[0].position, o, *SIZE)
    assert np.allclose(after - before, [6, -3], atol=1e-9), after - before
    kept = {k: v for k, v in light_fields(scene.lights[0]).items() if k != "position"}
    assert kept == {k: v for k, v in before_fields.items() if k != "position"}
    lights.handle(_release(11, 2), o, SIZE[1])
    assert not lights.claims_drag
    # Without Shift a drag is the camera's, not the light's.
    lights.handle(_press(5, 5), o, SIZE[1])
    assert not lights.claims_drag and not lights.handle(_move(9, 9), o, SIZE[1])


def test_selecting_and_turning_a_directional_light():
    scene = _lit_scene()
    o = _orbit()
    lights = LightControls(LightEditor(scene))
    lights.handle(_key("l"), o, SIZE[1])
    assert lights.editor.selected == 1
    lights.handle(_press(0, 0, modifiers=("Shift",)), o, SIZE[1])
    assert lights.handle(_move(20, 0, modifiers=("Shift",)), o, SIZE[1])  # half the height: a quarter turn about +Y
    d = np.asarray(scene.lights[1].direction)
    assert math.isclose(float(np.linalg.norm(d)), 1.0, rel_tol=1e-6)
    assert np.allclose(d, [0, -1, 0], atol=1e-6)  # straight down stays straight down under a yaw
    lights.handle(_move(20, 20, modifiers=("Shift",)), o, SIZE[1])  # a quarter turn about the camera's right
    assert abs(float(scene.lights[1].direction[1])) < 1e-6
    assert scene.lights[0].position == (0.3, 1.5, 0.2)  # the other light untouched
    lights.handle(_key("["), o, SIZE[1])
    assert lights.editor.selected == 0
    with pytest.raises(ValueError, match="light index"):
        lights.editor.select(5)


# --- the view session and the widget (lavapipe) ----------------------------------------------

@pytest.fixture
def view_renderer(make_renderer):
    return make_renderer(*SIZE)


def test_the_view_shows_what_render_gives(view_renderer):
    scene = _lit_scene()
    s = ViewSession(scene, "vsgl", renderer=view_renderer, size=SIZE, num_lights=64)
    shown = s.frame()
    direct = view_renderer.render(scene, camera=scene.default_camera(), method="vsgl", num_lights=64, seed=0, aovs=["ldr"])
    assert np.array_equal(shown, direct.aov("ldr")[..., :3])
    # Exposure 1 through the CPU tone map (the linear image) is the GPU's within one 8-bit step.
    s.set_exposure(1.0 + 1e-9)
    assert int(np.abs(s.frame().astype(int) - shown.astype(int)).max()) <= 1
    s.set_exposure(4.0)
    assert s.frame().mean() > shown.mean()


def test_events_change_the_frame_and_no_ops_do_not(view_renderer):
    scene = _lit_scene()
    s = ViewSession(scene, "vsgl", renderer=view_renderer, size=SIZE, num_lights=64)
    first = s.frame()
    assert not s.handle(_move(30, 30, buttons=()))  # hover: nothing to draw
    assert np.array_equal(s.frame(), first)
    s.handle(_press(10, 10))
    assert s.handle(_move(20, 14))
    orbited = s.frame()
    assert not np.array_equal(orbited, first)
    s.handle(_release(20, 14))
    position = scene.lights[0].position
    s.handle(_press(30, 10, modifiers=("Shift",)))
    assert s.handle(_move(40, 10, modifiers=("Shift",)))
    assert scene.lights[0].position != position
    assert not np.array_equal(s.frame(), orbited)
    s.handle(_release(40, 10))
    assert s.handle(_key("r"))
    s.scene.lights = _lit_scene().lights
    assert np.array_equal(s.frame(), first)  # reset: the scene's camera exactly


def test_resize_events_resize_the_frames_on_the_same_renderer(view_renderer):
    s = ViewSession(_lit_scene(), "vpl", renderer=view_renderer, size=SIZE, num_lights=64)
    assert s.handle({"type": "resize", "width": 30, "height": 20, "pixel_ratio": 2.0})
    assert s.frame().shape == (40, 60, 3)
    assert s.renderer is view_renderer
    assert not s.handle({"type": "resize", "width": 30, "height": 20, "pixel_ratio": 2.0})
    assert not s.handle({"type": "resize", "width": 0, "height": 20, "pixel_ratio": 1.0})
    s.handle({"type": "resize", "width": SIZE[0], "height": SIZE[1], "ratio": 1.0})
    assert s.frame().shape == (SIZE[1], SIZE[0], 3)


def test_bad_options_raise_renders_errors(view_renderer):
    scene = _lit_scene()

    def render_error(method, **options):
        with pytest.raises((vsgl.ArgumentError, TypeError)) as e:
            view_renderer.render(scene, method=method, aovs=[], **options)
        return type(e.value), str(e.value)

    # Refused values are ArgumentErrors, an option no method has is render's TypeError.
    for method, options in [("vsgl", dict(K="x")), ("vsgl", dict(num_lights=0)), ("vpl", dict(K=1.0)), ("vsgl", dict(no_such=1))]:
        with pytest.raises((vsgl.ArgumentError, TypeError)) as e:
            ViewSession(scene, method, renderer=view_renderer, size=SIZE, **options)
        assert (type(e.value), str(e.value)) == render_error(method, **options)
    # Compared methods each take what they take; an option neither takes is render's error.
    ViewSession(scene, compare=["vpl", "vsgl"], renderer=view_renderer, size=SIZE, K=0.5)
    with pytest.raises(vsgl.ArgumentError) as e:
        ViewSession(scene, compare=["vpl", "vsgl"], renderer=view_renderer, size=SIZE, lpv_cascades=2)
    assert (type(e.value), str(e.value)) == render_error("vpl", lpv_cascades=2)
    with pytest.raises(vsgl.ArgumentError, match="compare: unknown method 'vsgl3'"):
        ViewSession(scene, compare=["vpl", "vsgl3"], renderer=view_renderer, size=SIZE)
    with pytest.raises(vsgl.ArgumentError, match="aov: vsgl shows"):
        ViewSession(scene, "vsgl", renderer=view_renderer, size=SIZE, aov="stderr")
    s = ViewSession(scene, "vsgl", renderer=view_renderer, size=SIZE)
    with pytest.raises(vsgl.ArgumentError, match="interleave"):
        s.set_options(interleave=99)
    assert "interleave" not in s.options  # a refused value leaves the settings as they were


def test_compare_splits_labels_and_moves_the_divider(view_renderer):
    scene = _lit_scene()
    s = ViewSession(scene, compare=["vpl", "vsgl"], renderer=view_renderer, size=SIZE, num_lights=64)
    both = s.frame()
    vpl = view_renderer.render(scene, method="vpl", num_lights=64, seed=0, aovs=["ldr"]).aov("ldr")[..., :3]
    vsgl_ = view_renderer.render(scene, method="vsgl", num_lights=64, seed=0, aovs=["ldr"]).aov("ldr")[..., :3]
    cut = SIZE[0] // 2
    assert (both[:, cut] == 255).all()  # the divider
    assert np.array_equal(both[20:, : cut], vpl[20:, : cut])  # below the labels: each method's own pixels
    assert np.array_equal(both[20:, cut + 1:], vsgl_[20:, cut + 1:])
    assert (both[:7, :13] != vpl[:7, :13]).any() and (both[:7, cut:cut + 13] != vsgl_[:7, cut:cut + 13]).any()  # labels
    s.handle(_press(cut + 2, 20))  # grab the divider...
    assert s.handle(_move(cut + 20, 20))  # ...and wipe it right; the camera stays
    assert s.orbit.camera() is s.orbit._start
    assert (s.frame()[:, cut + 20] == 255).all()


def test_still_measures_the_error_and_refreshes_slow_halves(view_renderer):
    scene = _lit_scene()
    s = ViewSession(scene, compare=["vsgl", "reference"], renderer=view_renderer, size=SIZE, num_lights=64, rsm_size=32)
    s.frame()
    assert s.error is None
    s.still()
    assert set(s.error) == {"mean_over_reference", "block_error"}
    assert 0.5 < s.error["mean_over_reference"] < 1.5 and s.error["block_error"] >= 0
    assert "indirect over reference" in s.status() and "GPU ms" in s.status()
    # Moving drops the error, and the reference half keeps its last frame until the view stops.
    s.handle(_press(5, 30))
    s.handle(_move(6, 30))
    assert s.error is None
    right_moving = s.frame()[:, SIZE[0] // 2 + 1:]
    right_still = s.still()[:, SIZE[0] // 2 + 1:]
    assert not np.array_equal(right_moving, right_still)
    assert ViewSession(scene, "direct", renderer=view_renderer, size=SIZE).measure_error() is None


class _CountingRenderer:
    """The renderer, with its render calls counted by method."""

    def __init__(self, renderer):
        self._renderer, self.calls = renderer, []

    def render(self, scene, method, **kw):
        self.calls.append(method)
        return self._renderer.render(scene, method=method, **kw)

    def __getattr__(self, name):
        return getattr(self._renderer, name)


def test_a_stopped_view_renders_each_method_once(view_renderer):
    counting = _CountingRenderer(view_renderer)
    compared = ViewSession(_lit_scene(), compare=["vsgl", "reference"], renderer=counting, size=SIZE, num_lights=64, rsm_size=32)
    compared.still()
    assert sorted(counting.calls) == ["reference", "vsgl"] and compared.error is not None
    counting.calls.clear()
    alone = ViewSession(_lit_scene(), "vsgl", renderer=counting, size=SIZE, num_lights=64, rsm_size=32)
    alone.still()
    assert sorted(counting.calls) == ["reference", "vsgl"]  # the reference only for the error
    # The error equals the one measured by separate renders.
    assert alone.error == alone.measure_error()


def test_the_widget_keeps_two_frames_in_flight(view_renderer):
    view = vsgl.view(_lit_scene(), "vsgl", renderer=view_renderer, size=SIZE, num_lights=64)
    sent = []
    view.send = lambda msg, buffers=None: sent.append(msg)
    view._has_visible_views = True
    for _ in range(5):  # five draws asked for, no frame confirmed by the browser
        view.request_draw()
        view._rfb_maybe_draw()
    assert [m["index"] for m in sent] == [1, 2]
    view._frame_feedback = {"index": 1, "timestamp": 0.0, "localtime": 0.0}  # the browser showed frame 1
    view.request_draw()
    view._rfb_maybe_draw()
    assert [m["index"] for m in sent] == [1, 2, 3]
    assert sent[-1]["mimetype"] == "image/jpeg"  # moving frames are JPEG; the lossless one follows when still


def test_the_widget_routes_events_and_shows_errors(view_renderer):
    view = vsgl.view(_lit_scene(), "vsgl", renderer=view_renderer, size=SIZE, num_lights=64)
    first = view.get_frame()
    # Through jupyter_rfb's own message handler, as the browser's events arrive.
    view._rfb_handle_msg(view, {"type": "pointer_down", "x": 5, "y": 5, "button": 1, "buttons": [1], "modifiers": [], "timestamp": 0}, [])
    view._rfb_handle_msg(view, {"type": "pointer_move", "x": 25, "y": 5, "button": 0, "buttons": [1], "modifiers": [], "timestamp": 0}, [])
    assert view._rfb_draw_requested
    assert not np.array_equal(view.get_frame(), first)
    assert "GPU ms" in view.status_line.value
    view.panel.method.value = "vpl"  # the panel: options vpl does not take are dropped
    assert view.session.methods == ["vpl"] and "K" not in [w.description for w in view.panel.options_box.children]
    num_lights = next(w for w in view.panel.options_box.children if w.description == "num_lights")
    num_lights.value = 32
    assert view.session.options["num_lights"] == 32
    view.panel.aov.value = "indirect"
    assert view.get_frame().shape == (SIZE[1], SIZE[0], 3)
    view.refresh_still()
    view.get_frame()
    assert "indirect over reference" in view.status_line.value


def test_the_widget_draws_its_overlay_into_the_frame(view_renderer):
    view = vsgl.view(_lit_scene(), "vsgl", renderer=view_renderer, size=SIZE, num_lights=64)
    shown = view.get_frame()
    plain = view.session.frame()
    rows = np.flatnonzero((shown != plain).any(axis=(1, 2)))
    assert rows.size and rows.min() >= SIZE[1] - 7  # the bottom strip only (5 rows of glyphs and a margin)
    assert "ms" in view.session.overlay_text()
    view.refresh_still()
    view.get_frame()
    assert "ind/ref" in view.session.overlay_text()
    off = vsgl.view(_lit_scene(), "vsgl", renderer=view_renderer, size=SIZE, num_lights=64, overlay=False)
    assert np.array_equal(off.get_frame(), off.session.frame())


def test_renderer_resize_keeps_frames_as_a_new_renderer_would(make_renderer):
    scene = vsgl.scenes.cornell_box()
    r = vsgl.Renderer(40, 30)
    r.resize(SIZE[0], SIZE[1])
    assert (r.width, r.height) == SIZE
    resized = r.render(scene, method="vsgl", num_lights=64, aovs=["image"]).image
    fresh = make_renderer(*SIZE).render(scene, method="vsgl", num_lights=64, aovs=["image"]).image
    assert np.array_equal(resized, fresh)
    with pytest.raises(vsgl.ArgumentError, match="height: must be in 1..=16384"):
        r.resize(10, 0)
    assert (r.width, r.height) == SIZE


def test_default_camera_is_the_one_render_uses(view_renderer, tmp_path):
    from gltf_fixtures import write_glb

    with_camera = vsgl.scenes.cornell_box()
    assert with_camera.default_camera().eye == with_camera.cameras[0].eye  # a scene's own: its first
    without = vsgl.Scene.load(write_glb(tmp_path))
    without.add_light(vsgl.PointLight(position=(0, 2, 0), intensity=5.0))
    assert without.cameras == []  # framed from its bounds
    for scene in (with_camera, without):
        a = view_renderer.render(scene, method="direct", aovs=["image"]).image
        b = view_renderer.render(scene, camera=scene.default_camera(), method="direct", aovs=["image"]).image
        assert np.array_equal(a, b)
