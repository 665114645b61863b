"""The desktop window (`python -m vsgl view`, `Renderer.view`): its frame path offscreen (the
frames it presents are the renderer's `ldr` images, composed as the notebook view composes
them), the panel's controls and changes, the clear error without a display, and under Xvfb a
real window: the headless screenshot run, keys and mouse moving the camera, Escape closing it,
and a second window in the same process.

The Xvfb tests skip where Xvfb or xdotool is missing, except under CI (CI=true), which
installs both (scripts/setup.sh) and must not pass by skipping them."""

from __future__ import annotations

import os
import pathlib
import shutil
import subprocess
import sys
import time

import numpy as np
import pytest

import vsgl
from vsgl import _vsgl
from vsgl.window_view import WindowView, apply_change, panel_controls

SIZE = (96, 54)
REPO = pathlib.Path(__file__).resolve().parents[1]


def _ldr(renderer, scene, method, **options):
    return renderer.render(scene, method=method, aovs=["ldr"], **options).aov("ldr")


@pytest.fixture
def offscreen_renderer(make_renderer):
    return make_renderer(*SIZE)


def test_the_offscreen_frame_is_the_renderers_ldr_image_exactly(offscreen_renderer):
    scene = vsgl.scenes.load("cornell_box")
    view = WindowView(scene, "vsgl", renderer=offscreen_renderer, size=SIZE, ui=False, offscreen=True, num_lights=64)
    view.draw()
    shot = view.screenshot()
    assert shot.shape == (SIZE[1], SIZE[0], 4)
    expected = _ldr(offscreen_renderer, scene, "vsgl", num_lights=64, seed=0)
    assert np.array_equal(shot, expected)
    assert shot[..., :3].max() > 0


def test_a_comparison_shows_each_method_on_its_side_of_a_white_divider(offscreen_renderer):
    scene = vsgl.scenes.load("cornell_box")
    view = WindowView(scene, compare=["vpl", "vsgl"], renderer=offscreen_renderer, size=SIZE, ui=False, offscreen=True, num_lights=64)
    view.session.split = 0.25
    view.draw()
    shot = view.screenshot()[..., :3]
    cut = round(0.25 * SIZE[0])
    left = _ldr(offscreen_renderer, scene, "vpl", num_lights=64, seed=0)[..., :3]
    right = _ldr(offscreen_renderer, scene, "vsgl", num_lights=64, seed=0)[..., :3]
    assert np.array_equal(shot[:, :cut], left[:, :cut])
    assert np.array_equal(shot[:, cut + 1:], right[:, cut + 1:])
    assert (shot[:, cut] == 255).all()
    assert not np.array_equal(left[:, cut + 1:], right[:, cut + 1:])


def test_what_the_gpu_does_not_show_is_uploaded_as_the_notebook_view_shows_it(offscreen_renderer):
    scene = vsgl.scenes.load("cornell_box")
    view = WindowView(scene, "direct", renderer=offscreen_renderer, size=SIZE, ui=False, offscreen=True, aov="normal")
    view.draw()
    assert np.array_equal(view.screenshot()[..., :3], view.session.frame())


def test_the_panel_draws_over_the_frame_and_offers_the_methods_options(offscreen_renderer):
    scene = vsgl.scenes.load("cornell_box")
    plain = WindowView(scene, "vsgl", renderer=offscreen_renderer, size=SIZE, ui=False, offscreen=True)
    plain.draw()
    with_ui = WindowView(scene, "vsgl", renderer=offscreen_renderer, size=SIZE, ui=True, offscreen=True)
    with_ui.draw()
    assert not np.array_equal(plain.screenshot(), with_ui.screenshot())
    controls = {c[1]: c for c in panel_controls(with_ui.session)}
    assert controls["method"][3] == "vsgl" and set(controls["method"][2]) == set(vsgl.METHODS)
    info = vsgl.method_info("vsgl")["options"]
    for name in ("num_lights", "interleave"):
        kind, _, lo, hi, value, _ = controls[name]
        assert kind == "int" and lo >= info[name].get("min", lo) and value == info[name]["default"]
    assert controls["exposure"][4] == 1.0


def test_panel_changes_are_checked_as_render_checks_them(offscreen_renderer):
    scene = vsgl.scenes.load("cornell_box")
    view = WindowView(scene, "vsgl", renderer=offscreen_renderer, size=SIZE, ui=False, offscreen=True)
    apply_change(view.session, "num_lights", 64)
    assert view.session.options["num_lights"] == 64
    with pytest.raises(vsgl.ArgumentError, match="num_lights"):
        apply_change(view.session, "num_lights", 0)
    assert view.session.options["num_lights"] == 64
    apply_change(view.session, "method", "vpl")
    assert view.session.methods == ["vpl"]


def test_bad_window_arguments_name_themselves(offscreen_renderer):
    with pytest.raises(vsgl.ArgumentError, match="size"):
        _vsgl.ViewWindow.offscreen(offscreen_renderer, 0, 10)
    window = _vsgl.ViewWindow.offscreen(offscreen_renderer, *SIZE)
    with pytest.raises(vsgl.ArgumentError, match="image"):
        window.upload_image(0, np.zeros((3, 3, 3), np.uint8))
    with pytest.raises(vsgl.ArgumentError, match="slot"):
        window.render_into(2, vsgl.scenes.load("cornell_box"))
    with pytest.raises(vsgl.ArgumentError, match="num_lights"):
        window.render_into(0, vsgl.scenes.load("cornell_box"), method="vsgl", num_lights=0)


def _run(args, env, timeout=300):
    return subprocess.run([sys.executable, "-m", "vsgl", "view", *args], env=env, capture_output=True, text=True, timeout=timeout, cwd=REPO)


@pytest.mark.gpu
def test_without_a_display_the_window_says_why_and_what_to_use_instead():
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    r = _run(["--frames", "1", "--size", "32x18"], env)
    assert r.returncode == 3, r.stderr
    assert "DISPLAY is not set" in r.stderr and "vsgl.view" in r.stderr and "Xvfb" in r.stderr


# --- a real window under Xvfb ---------------------------------------------------------------

def _need(tool: str) -> None:
    if shutil.which(tool) is None:
        if os.environ.get("CI"):
            pytest.fail(f"CI must have {tool} (scripts/setup.sh installs it)")
        pytest.skip(f"{tool} is not installed (apt-get install xvfb xdotool)")


@pytest.fixture(scope="module")
def xvfb():
    _need("Xvfb")
    _need("xdotool")
    for number in range(90, 120):
        if not pathlib.Path(f"/tmp/.X11-unix/X{number}").exists() and not pathlib.Path(f"/tmp/.X{number}-lock").exists():
            break
    display = f":{number}"
    proc = subprocess.Popen(["Xvfb", display, "-screen", "0", "1024x768x24", "-nolisten", "tcp"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 20
    while not pathlib.Path(f"/tmp/.X11-unix/X{number}").exists():
        if time.time() > deadline or proc.poll() is not None:
            proc.kill()
            pytest.fail(f"Xvfb {display} did not start")
        time.sleep(0.1)
    env = dict(os.environ, DISPLAY=display)
    env.pop("WAYLAND_DISPLAY", None)
    yield env
    proc.terminate()
    proc.wait(timeout=10)


@pytest.mark.gpu
def test_the_headless_screenshot_is_the_rendered_frame(xvfb, tmp_path, make_renderer):
    out = tmp_path / "shot.png"
    r = _run(["cornell_box", "--size", "96x54", "--frames", "30", "--screenshot", str(out), "--no-ui", "-O", "num_lights=64"], xvfb)
    assert r.returncode == 0, r.stderr
    from PIL import Image

    shot = np.asarray(Image.open(out))
    expected = _ldr(make_renderer(96, 54), vsgl.scenes.load("cornell_box"), "vsgl", num_lights=64, seed=0)
    assert shot.shape == expected.shape
    assert np.abs(shot.astype(int) - expected.astype(int)).max() <= 1


_DRIVEN = """
import sys, vsgl
from vsgl.window_view import WindowView
scene = vsgl.scenes.load("cornell_box")
for run in range(2):
    view = WindowView(scene, "direct", size=(96, 54), ui=False, title=f"vsgl-test-{run}", screenshot_dir=sys.argv[1] + f"/{run}")
    print("opened", run, flush=True)
    print(view.run(), flush=True)
print("done", flush=True)
"""


def _xdotool(env, *args):
    return subprocess.run(["xdotool", *args], env=env, capture_output=True, text=True, timeout=30)


def _window_id(env, title, deadline):
    while time.time() < deadline:
        r = _xdotool(env, "search", "--name", title)
        if r.returncode == 0 and r.stdout.split():
            return r.stdout.split()[0]
        time.sleep(0.2)
    pytest.fail(f"no window named {title} appeared")


def _shot(env, folder: pathlib.Path, count: int, deadline: float) -> np.ndarray:
    """Presses P and waits for the count-th screenshot the window saves."""
    from PIL import Image

    _xdotool(env, "key", "p")
    path = folder / f"vsgl-screenshot-{count:03d}.png"
    while time.time() < deadline:
        if path.exists():
            time.sleep(0.3)  # the PNG is written at once; let the write finish
            return np.asarray(Image.open(path))
        time.sleep(0.1)
    pytest.fail(f"{path} was not written")


@pytest.mark.gpu
def test_keys_and_the_mouse_move_the_camera_and_escape_closes_the_window(xvfb, tmp_path):
    proc = subprocess.Popen([sys.executable, "-c", _DRIVEN, str(tmp_path)], env=xvfb, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=REPO)
    deadline = time.time() + 240
    try:
        for run in range(2):
            wid = _window_id(xvfb, f"vsgl-test-{run}", deadline)
            _xdotool(xvfb, "windowfocus", "--sync", wid)
            folder = tmp_path / str(run)
            first = _shot(xvfb, folder, 0, deadline)
            _xdotool(xvfb, "key", "d")  # fly right
            moved = _shot(xvfb, folder, 1, deadline)
            assert not np.array_equal(first, moved), "a key did not move the camera"
            _xdotool(xvfb, "key", "r")  # back to the scene's camera, exactly
            back = _shot(xvfb, folder, 2, deadline)
            assert np.array_equal(first, back)
            # A left drag orbits.
            _xdotool(xvfb, "mousemove", "--window", wid, "40", "27", "mousedown", "1")
            _xdotool(xvfb, "mousemove", "--window", wid, "70", "27")
            _xdotool(xvfb, "mouseup", "1")
            orbited = _shot(xvfb, folder, 3, deadline)
            assert not np.array_equal(first, orbited), "a drag did not orbit the camera"
            if run == 1:
                # A resized window renders at its new size.
                _xdotool(xvfb, "windowsize", "--sync", wid, "120", "64")
                resized = _shot(xvfb, folder, 4, deadline)
                assert resized.shape == (64, 120, 4), resized.shape
            _xdotool(xvfb, "key", "Escape")
        out, err = proc.communicate(timeout=max(deadline - time.time(), 10))
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, err
    assert out.count("opened") == 2 and "done" in out, out


@pytest.mark.gpu
def test_renderer_view_runs_a_window_and_returns_when_it_closes(xvfb, tmp_path):
    code = ("import vsgl; r = vsgl.Renderer(64, 36); "
            "print(r.view(vsgl.scenes.load('cornell_box'), 'direct', frames=2, ui=False, size=(64, 36), "
            f"screenshot={str(tmp_path / 'r.png')!r}))")
    r = subprocess.run([sys.executable, "-c", code], env=xvfb, capture_output=True, text=True, timeout=300, cwd=REPO)
    assert r.returncode == 0, r.stderr
    assert "'frames': 2" in r.stdout and (tmp_path / "r.png").exists()
