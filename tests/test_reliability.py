"""Reliability against hostile input and misuse (issue #20): the texture memory budget of
`Scene.load` holds against decompression bombs, `Frame.save` failures are `OSError`s, and a
frame says how to get an AOV it did not read back. (The loader's spec-violation warnings are
cases of `gltf_fixtures.WARNING_CASES`, tested in test_gltf.py.)"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import pytest

import gltf_fixtures as fx
import vsgl

MIB = 1 << 20
# What a process that imported vsgl and NumPy and read a small scene may hold besides the
# textures: the interpreter, the extension, the allocator's slack. Measured: 13 MiB.
RSS_MARGIN = 300 * 1000 * 1000

# The peak is the kernel's high-water mark of the process's resident set, VmHWM, which starts
# afresh at exec. `getrusage(RUSAGE_SELF).ru_maxrss` is printed too but not used: Linux carries
# it across fork + exec, so a child of a large pytest process reports the parent's peak (710 MiB
# measured in the full suite) before it has done anything.
_LOAD_AND_MEASURE = textwrap.dedent(
    """
    import json, resource, sys
    import vsgl

    def hwm():
        with open("/proc/self/status") as f:
            return next(int(l.split()[1]) * 1024 for l in f if l.startswith("VmHWM:"))

    path, budget = sys.argv[1], sys.argv[2]
    kwargs = {} if budget == "default" else {"max_texture_bytes": int(budget)}
    before = hwm()
    try:
        scene = vsgl.Scene.load(path, **kwargs)
        outcome = "loaded %d textures" % scene.stats["textures"]
    except vsgl.SceneError as e:
        outcome = "SceneError: %s" % e
    maxrss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024  # KiB on Linux
    print(json.dumps({"outcome": outcome, "before": before, "peak": hwm(), "ru_maxrss": maxrss}))
    """
)


def _load_in_subprocess(path, budget) -> dict:
    """Loads `path` in a fresh interpreter (so the peak is this load's, not the test
    session's) and returns {"outcome", "before", "peak", "ru_maxrss"} in bytes."""
    out = subprocess.run(
        [sys.executable, "-c", _LOAD_AND_MEASURE, str(path), str(budget)],
        capture_output=True, text=True, timeout=120, env={**os.environ, "RUST_LOG": "off"},
    )
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.mark.skipif(not os.path.exists("/proc/self/status"), reason="needs /proc/self/status (VmHWM)")
def test_decompression_bomb_is_refused_at_the_default_budget_without_allocating(tmp_path):
    # The bomb: 16384² grey zeros, a ~1 MB PNG that decodes to 256 MiB and is kept as
    # 1 GiB of RGBA8. Before the budget it loaded and peaked at 1.3 GiB.
    path = fx.write_texture_bomb(tmp_path, side=16384, channels=1)
    assert path.parent.joinpath("mr.png").stat().st_size < 2 * MIB
    r = _load_in_subprocess(path, "default")
    assert r["outcome"].startswith("SceneError"), r
    message = r["outcome"]
    for needle in ("textured.gltf", "images[1]", "mr.png", "16384×16384", str(512 * MIB), "max_texture_bytes="):
        assert needle in message, f"the error names {needle!r}: {message}"
    assert r["peak"] <= 512 * MIB + RSS_MARGIN, f"peak RSS {r['peak'] / MIB:.0f} MiB: {r}"


@pytest.mark.skipif(not os.path.exists("/proc/self/status"), reason="needs /proc/self/status (VmHWM)")
def test_bomb_under_a_small_budget_is_refused_and_peak_rss_stays_bounded(tmp_path):
    # 8192² RGB zeros: 192 MiB decoded, 256 MiB as RGBA8, under a 16 MiB budget. Without the
    # check from the header the load peaks near 450 MiB + the interpreter, far above the bound.
    budget = 16 * MIB
    path = fx.write_texture_bomb(tmp_path, side=8192, channels=3)
    r = _load_in_subprocess(path, budget)
    assert r["outcome"].startswith("SceneError") and "images[1]" in r["outcome"], r
    assert str(budget) in r["outcome"], r
    assert r["peak"] <= budget + RSS_MARGIN, f"peak RSS {r['peak'] / MIB:.0f} MiB: {r}"


def test_budget_counts_the_decode_buffer_and_earlier_textures(tmp_path):
    # textured.gltf decodes its base colour (4×2 RGBA8, 32 bytes), then mr.png, here 256² RGB:
    # 256 KiB kept as RGBA8 plus 192 KiB of decoder output while it is converted, then the
    # 2×2 normal map. The peak is while mr.png is converted.
    path = fx.write_texture_bomb(tmp_path, side=256, channels=3)
    need = 4 * 2 * 4 + 256 * 256 * 4 + 256 * 256 * 3
    scene = vsgl.Scene.load(path, max_texture_bytes=need)
    assert scene.stats["textures"] == 3
    with pytest.raises(vsgl.SceneError, match=r"images\[1\].*while it is decoded"):
        vsgl.Scene.load(path, max_texture_bytes=need - 1)


@pytest.mark.parametrize("bad", [0, -1, 1.5, True, "1GB", 2**70])
def test_max_texture_bytes_is_validated_by_name(tmp_path, bad):
    path = fx.write_textured(tmp_path)
    with pytest.raises(vsgl.ArgumentError, match="max_texture_bytes"):
        vsgl.Scene.load(path, max_texture_bytes=bad)


def test_max_texture_bytes_is_keyword_only(tmp_path):
    path = fx.write_textured(tmp_path)
    with pytest.raises(TypeError):
        vsgl.Scene.load(path, 1 << 30)  # type: ignore[misc]


def test_save_to_an_unwritable_path_raises_os_error_naming_it(tmp_path, renderer):
    frame = renderer.render(vsgl.scenes.cornell_box(), method="direct", aovs=["image"])
    target = tmp_path / "no such folder" / "out.png"
    with pytest.raises(OSError) as info:
        frame.save(target)
    assert not isinstance(info.value, ValueError)
    assert isinstance(info.value, FileNotFoundError)
    assert str(target) in str(info.value) and info.value.filename == str(target)
    # A path that is a folder: IsADirectoryError, also an OSError naming the path.
    (tmp_path / "dir.png").mkdir()
    with pytest.raises(OSError, match="dir.png"):
        frame.save(tmp_path / "dir.png")
    # A bad extension is still a bad argument value, not an I/O failure.
    with pytest.raises(vsgl.ArgumentError, match="extension"):
        frame.save(tmp_path / "out.bmp")


def test_an_aov_not_read_back_says_how_to_ask_for_it(renderer):
    scene = vsgl.scenes.cornell_box()
    frame = renderer.render(scene, method="direct", aovs=[])
    for get in (lambda: frame.image, lambda: frame.aov("image"), lambda: frame.aov("depth")):
        with pytest.raises(vsgl.ArgumentError, match="was not read back") as info:
            get()
        assert "aovs=[" in str(info.value), str(info.value)
    frame = renderer.render(scene, method="direct", aovs=["depth"])
    with pytest.raises(vsgl.ArgumentError, match=r'aovs=\["depth", "image"\]'):
        frame.image
    # An AOV the method never makes is a different mistake, and says so.
    with pytest.raises(vsgl.ArgumentError, match="does not make AOV"):
        frame.aov("indirect")
