"""The Python API contract: argument validation, errors, frames, files, adapters, threads."""

from __future__ import annotations

import os
import pathlib
import re
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import vsgl


def test_public_names_exist():
    for name in ["Renderer", "Scene", "Camera", "SpotLight", "Frame", "VsglError", "SceneError", "NoAdapterError", "adapters", "scenes"]:
        assert hasattr(vsgl, name), name
    assert issubclass(vsgl.SceneError, vsgl.VsglError)
    assert issubclass(vsgl.NoAdapterError, vsgl.VsglError)
    assert vsgl.scenes.names() == ["cornell_box", "glossy_cornell", "caustics_ring", "cave_flashlight", "diffuse_cornell",
                                   "mirror_panel", "helmet_shell", "furnished_room", "atrium"]


def test_unknown_method_lists_valid_ones(renderer):
    with pytest.raises(ValueError, match=r"method.*valid methods: direct"):
        renderer.render(vsgl.scenes.cornell_box(), method="photon_mapping")
    # vsgl2 was the last planned method; it now renders and is listed.
    with pytest.raises(ValueError, match=r"valid methods: .*\bvsgl2\b"):
        renderer.render(vsgl.scenes.cornell_box(), method="vsgl3")


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(position=(0, 1, 0), direction=(0, -1, 0), intensity=-1.0), "intensity"),
        (dict(position=(0, 1, 0), direction=(0, -1, 0), intensity=0.0), "intensity"),
        (dict(position=(0, float("nan"), 0), direction=(0, -1, 0), intensity=1.0), "position"),
        (dict(position=(0, 1, 0), direction=(0, 0, 0), intensity=1.0), "direction"),
        (dict(position=(0, 1), direction=(0, -1, 0), intensity=1.0), "position"),
        (dict(position=(0, 1, 0), direction=(0, -1, 0), intensity=1.0, outer_cone_deg=120), "outer_cone_deg"),
        (dict(position=(0, 1, 0), direction=(0, -1, 0), intensity=1.0, inner_cone_deg=50, outer_cone_deg=40), "inner_cone_deg"),
        (dict(position=(0, 1, 0), direction=(0, -1, 0), intensity=1.0, color=(1, -1, 1)), "color"),
        (dict(position=(0, 1, 0), direction=(0, -1, 0), intensity=float("inf")), "intensity"),
    ],
)
def test_spot_light_rejects_bad_values(kwargs, match):
    with pytest.raises(ValueError, match=match):
        vsgl.SpotLight(**kwargs)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(eye=(0, 0, 0), target=(0, 0, 0)), "differ"),
        (dict(eye=(0, 0, 0), target=(0, 1, 0), up=(0, 1, 0)), "parallel"),
        (dict(eye=(0, 0, 0), target=(0, 0, -1), fov_y_deg=0), "fov_y_deg"),
        (dict(eye=(0, 0, 0), target=(0, 0, -1), fov_y_deg=180), "fov_y_deg"),
        (dict(eye=(0, float("inf"), 0), target=(0, 0, -1)), "eye"),
    ],
)
def test_camera_rejects_bad_values(kwargs, match):
    with pytest.raises(ValueError, match=match):
        vsgl.Camera.look_at(**kwargs)


@pytest.mark.parametrize("w,h,match", [(0, 10, "width"), (10, 0, "height"), (10, 100000, "height"), (-3, 4, "width")])
def test_renderer_rejects_bad_sizes(w, h, match):
    with pytest.raises(ValueError, match=match):
        vsgl.Renderer(width=w, height=h)


def test_render_rejects_bad_settings(renderer):
    scene = vsgl.scenes.cornell_box()
    with pytest.raises(ValueError, match="shadow_size"):
        renderer.render(scene, shadow_size=3)
    with pytest.raises(ValueError, match="plan"):
        renderer.render(scene, plan="some")
    with pytest.raises(TypeError):
        renderer.render(scene, not_an_option=1)


def test_frame_aovs_and_metadata(renderer):
    frame = renderer.render(vsgl.scenes.cornell_box())
    assert set(frame.aovs) >= {"image", "direct", "albedo", "normal", "depth"}
    for name in frame.aovs:
        arr = frame.aov(name)
        assert arr.dtype == np.float32 and arr.flags.c_contiguous
        assert arr.shape[:2] == (48, 64)
    assert frame.aov("depth").shape == (48, 64, 1)
    n = frame.aov("normal")
    hit = frame.aov("depth")[..., 0] > 0
    np.testing.assert_allclose(np.linalg.norm(n[hit], axis=-1), 1.0, atol=1e-4)
    with pytest.raises(ValueError, match="unknown AOV"):
        frame.aov("nope")
    assert frame.settings["method"] == "direct"
    assert frame.settings["width"] == 64
    assert "total" in frame.timings_ms


@pytest.mark.parametrize("method", ["direct", "vsgl", "vsgl2", "pathtrace"])
def test_aovs_reads_back_only_what_is_asked_and_the_same_values(renderer, method):
    scene = vsgl.scenes.cornell_box()
    # Camera paths for pathtrace: they are bit-deterministic, while the default bidirectional
    # strategy adds its light splats with float atomics in a varying order (docs/methods/pathtrace.md).
    small = dict(num_lights=16, rsm_size=32, spp=2, strategy="camera")
    kw = dict(method=method, **{k: v for k, v in small.items() if k in vsgl.method_options(method)})
    full = renderer.render(scene, **kw)
    for asked in (["image"], ["indirect_specular", "depth"], ["albedo", "image", "normal"], []):
        if method == "direct":
            asked = [a for a in asked if not a.startswith("indirect")]
        frame = renderer.render(scene, aovs=asked, **kw)
        # Listed in the frame's usual order, whatever order they were asked in.
        assert frame.aovs == [a for a in full.aovs if a in asked]
        for name in asked:
            np.testing.assert_array_equal(frame.aov(name), full.aov(name), err_msg=f"{method}: {name}")
        left_out = [a for a in full.aovs if a not in asked]
        for name in left_out:
            with pytest.raises(ValueError, match="aovs= did not name it"):
                frame.aov(name)
    if method != "direct":
        assert full.aov("indirect").max() > 0.0, "the comparison above would be vacuous"


def test_aovs_indirect_specular_alone_on_a_diffuse_only_scene(renderer):
    # Without specular materials the specular target is a placeholder and the AOV is zeros; it
    # must still be there when asked for alone (no diffuse readback to borrow the shape from).
    scene = vsgl.scenes.load("diffuse_cornell")
    frame = renderer.render(scene, method="vsgl", num_lights=16, rsm_size=32, aovs=["indirect_specular"])
    assert frame.aovs == ["indirect_specular"]
    spec = frame.aov("indirect_specular")
    assert spec.shape == (48, 64, 3) and not spec.any()


def test_aovs_argument_errors(renderer):
    scene = vsgl.scenes.cornell_box()
    with pytest.raises(ValueError, match=r"aovs: unknown AOV \"shadow\""):
        renderer.render(scene, aovs=["image", "shadow"])
    with pytest.raises(ValueError, match=r"aovs: \"indirect\" is not made by method=\"direct\""):
        renderer.render(scene, aovs=["indirect"])
    with pytest.raises(ValueError, match=r"aovs: \"stderr\" is not made by method=\"vsgl\""):
        renderer.render(scene, method="vsgl", aovs=["stderr"])
    with pytest.raises(TypeError):
        renderer.render(scene, aovs="image")  # a string is not a list of names


def test_untextured_variant_equals_full_plan(renderer):
    scene = vsgl.scenes.glossy_cornell()
    pruned = renderer.render(scene)
    full = renderer.render(scene, plan="full")
    assert "material_texture_fetch" in pruned.skipped
    assert "material_texture_fetch" not in full.skipped
    np.testing.assert_allclose(pruned.image, full.image, rtol=1e-6, atol=1e-7)


def test_save_png_and_npy(tmp_path, renderer):
    from PIL import Image

    frame = renderer.render(vsgl.scenes.cornell_box())
    frame.save(tmp_path / "a.png")
    frame.save(tmp_path / "a.npy")
    frame.save(tmp_path / "a.exr")
    assert (tmp_path / "a.exr").read_bytes()[:4] == b"\x76\x2f\x31\x01"  # OpenEXR magic
    png = np.asarray(Image.open(tmp_path / "a.png"))
    assert png.shape == (48, 64, 3) and png.max() > 0
    np.testing.assert_array_equal(np.load(tmp_path / "a.npy"), frame.image)
    assert frame._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(ValueError, match="extension"):
        frame.save(tmp_path / "a.tiff")
    with pytest.raises(ValueError, match="exposure"):
        frame.save(tmp_path / "b.png", exposure=0)


def test_adapters_lists_what_the_renderer_uses(renderer):
    names = [a["name"] for a in vsgl.adapters()]
    assert renderer.adapter["name"] in names


def test_adapter_filter_that_matches_nothing_raises_no_adapter_error():
    with pytest.raises(vsgl.NoAdapterError, match="matches no adapter"):
        vsgl.Renderer(width=8, height=8, adapter="no-such-gpu-xyz")


def test_no_vulkan_driver_gives_install_hint():
    # A Vulkan loader that finds no driver: the error must say how to install one.
    env = dict(os.environ, VK_ICD_FILENAMES="/nonexistent/icd.json", VK_DRIVER_FILES="/nonexistent/icd.json")
    env.pop("VSGL_ADAPTER", None)
    code = "import vsgl\ntry:\n    vsgl.Renderer(width=8, height=8)\nexcept vsgl.NoAdapterError as e:\n    print('NOADAPTER', e)\n"
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert "NOADAPTER" in out.stdout, out.stdout + out.stderr
    assert "apt-get install mesa-vulkan-drivers libvulkan1" in out.stdout


def test_render_releases_the_gil(make_renderer):
    r = make_renderer(256, 256)
    scene = vsgl.scenes.glossy_cornell()
    r.render(scene, shadow_size=2048)  # warm up
    ticks = 0
    stop = False

    def count():
        nonlocal ticks
        while not stop:
            ticks += 1
            time.sleep(0)

    t = threading.Thread(target=count)
    t.start()
    before = ticks
    start = time.perf_counter()
    for _ in range(3):
        r.render(scene, shadow_size=2048)
    elapsed = time.perf_counter() - start
    during = ticks - before
    stop = True
    t.join()
    # With the GIL held for the whole render the counter could only run in the short gaps
    # between renders; released, it keeps ticking all along.
    assert during > 1000, f"only {during} ticks in {elapsed:.3f}s of rendering"


def test_scene_stats_and_repr():
    s = vsgl.scenes.glossy_cornell()
    st = s.stats
    assert st["triangles"] > 1000 and st["lights"] == 1 and st["cameras"] == 1
    assert "metallic" in st["features"] and "textures" not in st["features"]
    assert "glossy_cornell" in repr(s)
    assert "gold_sphere" in s.node_names
    (lo, hi) = s.bounds
    assert lo[1] == pytest.approx(0.0) and hi[1] == pytest.approx(2.0)


def test_methods_registry_is_the_one_list():
    assert vsgl.METHODS[0] == "direct" and set(vsgl.METHODS) >= {"vpl", "vsgl", "vsgl2", "reference", "pathtrace"}
    for name in vsgl.METHODS:
        text = vsgl.describe_method(name)
        assert text.startswith(f"{name}: ")
        for option, default in vsgl.method_options(name).items():
            assert f"{option}=" in text, (name, option)
    with pytest.raises(vsgl.ArgumentError, match="valid methods"):
        vsgl.describe_method("photon_mapping")


def test_stub_literal_lists_every_method_and_render_leaves_options_to_the_registry():
    stub = (pathlib.Path(vsgl.__file__).parent / "_vsgl.pyi").read_text()
    literal = re.search(r"_MethodName = Literal\[([^\]]*)\]", stub)
    assert literal is not None
    assert tuple(re.findall(r'"([a-z0-9_]+)"', literal.group(1))) == vsgl.METHODS
    # The render docstring points at the registry (describe_method, method_info) instead of
    # keeping a second, hand-written list of every method's options that can fall behind: no
    # section per method, and no method option named as a keyword (`name=` or `name (`) beyond
    # the frame's own.
    assert "describe_method" in vsgl.Renderer.render.__doc__
    for doc in (vsgl.Renderer.render.__doc__, vsgl.Renderer.render_sequence.__doc__):
        assert not re.search(rf'^\s*- "(?:{"|".join(vsgl.METHODS)})":', doc, re.MULTILINE)
        own = {"capture_rsm", "seed"}
        named = {o for m in vsgl.METHODS for o in vsgl.method_options(m) if o not in own and re.search(rf"\b{o}(?:=| \()", doc)}
        assert not named, named


def test_bad_arguments_are_argument_errors_both_ways(renderer):
    assert issubclass(vsgl.ArgumentError, vsgl.VsglError) and issubclass(vsgl.ArgumentError, ValueError)
    scene = vsgl.scenes.cornell_box()
    for kwargs in (dict(shadow_size=3), dict(method="vsgl", interleave=0), dict(method="nope")):
        with pytest.raises(vsgl.VsglError):
            renderer.render(scene, **kwargs)
        with pytest.raises(vsgl.ArgumentError):
            renderer.render(scene, **kwargs)
    with pytest.raises(vsgl.ArgumentError, match="intensity"):
        vsgl.SpotLight(position=(0, 1, 0), direction=(0, -1, 0), intensity=-1.0)


@pytest.mark.parametrize(
    "method,option",
    [("direct", "num_lights"), ("vsgl2", "num_lights"), ("pathtrace", "rsm_size"), ("reference", "seed"), ("vsgl", "vpl_clamp"), ("vpl", "spp")],
)
def test_an_option_the_method_does_not_take_is_rejected_by_name(renderer, method, option):
    with pytest.raises(vsgl.ArgumentError, match=rf"{option}.*not an option of method=\"{method}\""):
        renderer.render(vsgl.scenes.cornell_box(), method=method, **{option: 1})


def test_option_types_are_checked(renderer):
    with pytest.raises(vsgl.ArgumentError, match="num_lights"):
        renderer.render(vsgl.scenes.cornell_box(), method="vpl", num_lights="many")
    with pytest.raises(vsgl.ArgumentError, match="denoise"):
        renderer.render(vsgl.scenes.cornell_box(), method="vsgl", denoise=1)
    # None means the method's default.
    f = renderer.render(vsgl.scenes.cornell_box(), method="vsgl2", rsm_size=None, aovs=["image"])
    assert f.settings["rsm_size"] == vsgl.method_options("vsgl2")["rsm_size"]


@pytest.mark.gpu
def test_cli_prints_no_mesa_runtime_dir_warning(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "XDG_RUNTIME_DIR"}
    out = subprocess.run(
        [sys.executable, "-m", "vsgl", "render", "cornell_box", "--method", "direct", "--size", "32x24", "-o", str(tmp_path / "a.png")],
        capture_output=True, text=True, env=env, timeout=300,
    )
    assert out.returncode == 0, out.stderr
    assert "XDG_RUNTIME_DIR" not in out.stderr, out.stderr
    methods = subprocess.run([sys.executable, "-m", "vsgl", "methods"], capture_output=True, text=True, env=env, timeout=300)
    assert methods.returncode == 0 and all(m in methods.stdout for m in vsgl.METHODS)


@pytest.mark.gpu
def test_cli_option_flag_reaches_every_method_option(tmp_path):
    """`render -O NAME=VALUE` passes any option of the method (typed: int, float, bool, text);
    a wrong name or value is the library's error naming the option, not a traceback."""
    base = [sys.executable, "-m", "vsgl", "render", "cornell_box", "--method", "vsgl", "--size", "24x16", "--lights", "64",
            "--rsm-size", "32", "--no-error"]
    a = subprocess.run(base + ["-O", "lambert_lobe=papers", "-O", "denoise=false", "-O", "K=2", "-o", str(tmp_path / "a.npy")],
                       capture_output=True, text=True, timeout=300)
    assert a.returncode == 0, a.stderr
    b = subprocess.run(base + ["-o", str(tmp_path / "b.npy")], capture_output=True, text=True, timeout=300)
    assert b.returncode == 0, b.stderr
    # The options took effect: the papers' lobe and K = 2 without the denoiser are another image.
    assert not np.array_equal(np.load(tmp_path / "a.npy"), np.load(tmp_path / "b.npy"))
    bad = subprocess.run(base + ["-O", "lambert_lobe=sphere", "-o", str(tmp_path / "c.npy")], capture_output=True, text=True, timeout=300)
    assert bad.returncode == 2 and "lambert_lobe" in bad.stderr and "Traceback" not in bad.stderr, bad.stderr
    malformed = subprocess.run(base + ["-O", "lambert_lobe", "-o", str(tmp_path / "d.npy")], capture_output=True, text=True, timeout=300)
    assert malformed.returncode == 2 and "NAME=VALUE" in malformed.stderr, malformed.stderr


def test_scene_triangles_are_the_world_space_geometry():
    """`Scene.triangles()` gives every triangle in world space (what another renderer needs to
    render the same scene): the counts of `stats`, the corners of `bounds`, node transforms
    applied to positions and (inverse transpose) normals, materials indexed as `materials`."""
    scene = vsgl.scenes.cornell_box()
    t = scene.triangles()
    n = scene.stats["triangles"]
    assert t["positions"].shape == (n, 3, 3) and t["normals"].shape == (n, 3, 3) and t["uvs"].shape == (n, 3, 2)
    assert t["material"].shape == (n,) and 0 <= t["material"].min() and t["material"].max() < len(scene.materials)
    lo, hi = scene.bounds
    np.testing.assert_allclose(t["positions"].reshape(-1, 3).min(axis=0), lo, atol=1e-6)
    np.testing.assert_allclose(t["positions"].reshape(-1, 3).max(axis=0), hi, atol=1e-6)
    np.testing.assert_allclose(np.linalg.norm(t["normals"], axis=-1), 1.0, atol=1e-5)
    # A node scaled 2× along x and moved: its positions move alike, its normals by the inverse
    # transpose (a normal with x and y parts turns towards y).
    node = scene.node_names[0]
    m = np.diag([2.0, 1.0, 1.0, 1.0])
    m[:3, 3] = (1e5, 0.0, 0.0)
    before = t
    scene.set_transform(node, (m @ np.array(scene.transform(node))).tolist())
    after = scene.triangles()
    moved = np.zeros(n, bool)
    moved[: len(after["material"])] = np.any(np.abs(after["positions"] - before["positions"]) > 0, axis=(1, 2))
    assert moved.any()
    p0, p1 = before["positions"][moved], after["positions"][moved]
    np.testing.assert_allclose(p1[..., 0], 2.0 * p0[..., 0] + 1e5, rtol=1e-12)
    np.testing.assert_array_equal(p1[..., 1:], p0[..., 1:])
    n0 = before["normals"][moved].astype(np.float64)
    want = n0 * np.array([0.5, 1.0, 1.0])
    want /= np.linalg.norm(want, axis=-1, keepdims=True)
    np.testing.assert_allclose(after["normals"][moved], want, atol=1e-6)


def test_submodules_are_reachable_after_import_vsgl_and_load_on_first_use():
    # A fresh interpreter: this session's tests have imported them already.
    code = (
        "import sys, vsgl\n"
        "assert 'vsgl.bench' not in sys.modules and 'vsgl.metrics' not in sys.modules\n"
        "assert vsgl.metrics.rmse is sys.modules['vsgl.metrics'].rmse\n"
        "for name in ('bench', 'lightspec', 'stability', 'video'):\n"
        "    assert getattr(vsgl, name).__name__ == 'vsgl.' + name and name in dir(vsgl)\n"
        "try:\n"
        "    vsgl.no_such_module\n"
        "except AttributeError as e:\n"
        "    assert 'no_such_module' in str(e)\n"
        "else:\n"
        "    raise SystemExit('no AttributeError')\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_every_choice_option_refuses_an_unknown_string_naming_it():
    # A choice option is a string option; an unknown value must be an error that names the
    # option and lists its values, never a silent default.
    checked = 0
    for method in vsgl.METHODS:
        for option, default in vsgl.method_options(method).items():
            if not isinstance(default, str):
                continue
            with pytest.raises(vsgl.ArgumentError, match=rf'^{option}: must be .*"{default}".*, got "no_such_choice"'):
                vsgl.check_method_options(method, **{option: "no_such_choice"})
            checked += 1
    assert checked >= 25, checked


def test_import_leaves_the_environment_alone_and_opening_a_device_sets_a_runtime_dir():
    # Mesa warns without XDG_RUNTIME_DIR; vsgl sets a private one where a GPU instance is
    # opened, not at import, and leaves one the user set alone.
    env = {k: v for k, v in os.environ.items() if k != "XDG_RUNTIME_DIR"}
    code = (
        "import os, vsgl\n"
        "assert 'XDG_RUNTIME_DIR' not in os.environ, 'set at import'\n"
        "vsgl.adapters()\n"
        "d = os.environ['XDG_RUNTIME_DIR']\n"
        "assert os.path.basename(d).startswith('vsgl-runtime-') and os.path.isdir(d), d\n"
        "assert os.stat(d).st_mode & 0o777 == 0o700\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, env=env)
    code_kept = "import os, vsgl\nvsgl.adapters()\nassert os.environ['XDG_RUNTIME_DIR'] == '/tmp', os.environ['XDG_RUNTIME_DIR']\n"
    subprocess.run([sys.executable, "-c", code_kept], check=True, env={**env, "XDG_RUNTIME_DIR": "/tmp"})


def test_cli_leaves_num_lights_to_the_method_unless_given(monkeypatch, tmp_path):
    # `render` and `animate` pass --lights only when given, so each method keeps its own
    # default (vsgl 1024, vpl 256) as the library does.
    from vsgl.__main__ import main

    seen: list[dict] = []

    class Stop(Exception):
        pass

    class RecordingRenderer:
        def __init__(self, **_):
            pass

        def render(self, scene, **options):
            seen.append(options)
            raise Stop

        def render_sequence(self, scene, changes, **options):
            return self.render(scene, **options)

    monkeypatch.setattr(vsgl, "Renderer", RecordingRenderer)
    out = str(tmp_path / "x.png")
    for method in ("vsgl", "vpl"):
        with pytest.raises(Stop):
            main(["render", "cornell_box", "--method", method, "--size", "8x8", "-o", out])
        assert seen[-1]["method"] == method and "num_lights" not in seen[-1], seen[-1]
    with pytest.raises(Stop):
        main(["render", "cornell_box", "--method", "vpl", "--size", "8x8", "--lights", "64", "-o", out])
    assert seen[-1]["num_lights"] == 64
    with pytest.raises(Stop):
        main(["animate", "cave_flashlight", "--method", "vsgl", "--frames", "2", "--size", "8x8", "-o", str(tmp_path / "f") + "/"])
    assert "num_lights" not in seen[-1], seen[-1]


def test_frame_settings_are_typed_as_their_values(renderer):
    """Counts are ints, fractions floats, flags bools, budgets lists: no caller compares against
    "0" or splits "0+0+0+256+0+0". Text only where the value is a name."""
    f = renderer.render(vsgl.scenes.cornell_box(), method="vsgl", num_lights=16, rsm_size=32, aovs=[])
    s = f.settings
    for name in ("width", "num_lights", "rsm_size", "seed", "interleave", "allocated_bytes", "frames_in_flight"):
        assert type(s[name]) is int, (name, s[name])
    for name in ("K", "coherence", "readback_ms"):
        assert type(s[name]) is float, (name, s[name])
    for name in ("denoise", "plane_fade", "capture_rsm"):
        assert type(s[name]) is bool, (name, s[name])
    assert s["num_lights"] == 16 and s["denoise"] is True and s["capture_rsm"] is False
    assert s["virtual_lights_per_light"] == [[16]]
    (view,) = s["rsm_view"]
    assert len(view["forward"]) == 3 and abs(np.linalg.norm(view["forward"]) - 1) < 1e-5 and view["tan"] > 0
    # Whatever stays text is a name, never a number or flag written out.
    for name, value in s.items():
        if isinstance(value, str):
            assert not re.fullmatch(r"-?[0-9.e+-]+|true|false", value), (name, value)
    # A point light beside the spot light: its RSM frame is not a spot's, so None.
    both = vsgl.scenes.cornell_box()
    both.lights = [*both.lights, vsgl.PointLight(position=(0.0, 0.5, 0.0), intensity=1.0)]
    views = renderer.render(both, method="vpl", num_lights=12, rsm_size=32, aovs=[]).settings["rsm_view"]
    assert isinstance(views[0], dict) and views[1] is None


def test_check_method_options_catches_options_that_contradict_each_other():
    """The method's own parse runs, not only each option's range: a papers' diffuse form given
    with lighting="accurate" (which brings its own) fails before any render, naming diffuse."""
    vsgl.check_method_options("vsgl", lighting="asg", diffuse="papers")
    with pytest.raises(vsgl.ArgumentError, match="diffuse"):
        vsgl.check_method_options("vsgl", lighting="accurate", diffuse="papers")
    with pytest.raises(vsgl.ArgumentError, match="kernel_filter"):
        vsgl.check_method_options("vsgl", kernel="node", kernel_filter="trilinear")


def test_method_info_says_what_each_method_is():
    """The registry's facts, which the bench and the CLI read instead of listing methods."""
    info = {m: vsgl.method_info(m) for m in vsgl.METHODS}
    assert [m for m in vsgl.METHODS if info[m]["ground_truth"]] == ["reference", "pathtrace"]
    assert {m for m in vsgl.METHODS if info[m]["stochastic"]} == {"vpl", "vsgl", "pathtrace"}
    assert "indirect" not in info["direct"]["aovs"] and "stderr" in info["pathtrace"]["aovs"]
    assert all(("stderr" in i["aovs"]) == (m == "pathtrace") for m, i in info.items())
    assert info["pathtrace"]["direct_light"] == "by_method" and info["vsgl"]["direct_light"] == "shadow_mapped"
    assert info["vsgl"]["summary"] in vsgl.describe_method("vsgl")
    with pytest.raises(vsgl.ArgumentError, match="unknown method"):
        vsgl.method_info("kmeans")


def test_stub_option_types_are_generated_from_the_registry(tmp_path):
    """Each method's options are a TypedDict in the stub with one overload of render and
    render_sequence per method, written by scripts/option_stubs.py from `method_info`; the
    committed stub must equal what the registry generates now, and a stale stub is caught."""
    root = pathlib.Path(__file__).resolve().parents[1]
    script = root / "scripts" / "option_stubs.py"
    check = subprocess.run([sys.executable, str(script), "--check"], capture_output=True, text=True)
    assert check.returncode == 0, check.stderr
    stub = (root / "python" / "vsgl" / "_vsgl.pyi").read_text()
    for name in vsgl.METHODS:
        for option, spec in vsgl.method_info(name)["options"].items():
            assert f"    {option}: " in stub, (name, option)
            if spec["type"] == "choice":
                assert all(f'"{c}"' in stub for c in spec["choices"]), (name, option)
    # A stale stub (an option the registry does not have) fails the check.
    import importlib.util

    spec = importlib.util.spec_from_file_location("option_stubs", script)
    option_stubs = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(option_stubs)
    stale = stub.replace("    kernel_filter: ", "    kernel_filtre: ", 1)
    assert option_stubs.regenerate(stale) != stale and option_stubs.regenerate(stub) == stub
