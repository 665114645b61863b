"""`python -m vsgl animate` and vsgl.video: a PNG folder has one file per
frame of the tiled size holding the rendered `ldr` frames; .gif/.mp4 round-trip through imageio
where the optional extra is installed (skipped otherwise, and a failure under CI, which installs
it); without it `animate` fails with the install hint before anything is rendered."""

from __future__ import annotations

import sys
import zlib

import numpy as np
import pytest

import vsgl
from optional_packages import optional_import
from vsgl import video
from vsgl.__main__ import main

W, H, FRAMES, FPS = 24, 16, 3, 2.0
OPTIONS = {"rsm_size": 64, "num_lights": 16}


def read_png(path) -> np.ndarray:
    """Decodes the PNGs `video.write_png` makes (8-bit RGBA, filter 0, one IDAT)."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, size = 8, b"", None
    while pos < len(data):
        n = int.from_bytes(data[pos:pos + 4], "big")
        kind, payload = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            size = (int.from_bytes(payload[:4], "big"), int.from_bytes(payload[4:8], "big"))
        elif kind == b"IDAT":
            idat += payload
        pos += 12 + n
    w, h = size
    rows = np.frombuffer(zlib.decompress(idat), np.uint8).reshape(h, 1 + 4 * w)
    assert (rows[:, 0] == 0).all()
    return rows[:, 1:].reshape(h, w, 4)


@pytest.fixture(scope="module")
def tiny(make_renderer):
    return make_renderer(W, H)


def rendered(renderer, method: str) -> list[np.ndarray]:
    scene = vsgl.scenes.cave_flashlight()
    takes = vsgl.method_options(method)
    opts = {k: v for k, v in OPTIONS.items() if k in takes}
    times = video.frame_times(FRAMES, FPS)
    return [f.aov("ldr") for f in renderer.render_sequence(scene, [{"time": t} for t in times], method=method, aovs=["ldr"], **opts)]


def test_a_png_folder_holds_every_tiled_frame(tiny, tmp_path):
    out = tmp_path / "frames"
    result = video.animate(tiny, vsgl.scenes.cave_flashlight(), ["vpl", "vsgl"], frames=FRAMES, fps=FPS,
                           output=f"{out}/", options=OPTIONS)
    files = sorted(out.glob("*.png"))
    assert len(files) == FRAMES and result["size"] == (2 * W + 1, H)
    vpl, vsgl_frames = rendered(tiny, "vpl"), rendered(tiny, "vsgl")
    # Two methods compared: each tile carries its name in a black box at its top-left, 7 rows
    # (5-row glyphs and a margin) by 4·len + 1 columns at this height (scale 1).
    for k, f in enumerate(files):
        image = read_png(f)
        assert image.shape == (H, 2 * W + 1, 4)
        assert (image[:, W] == 255).all(), "the separator column"
        for tile_image, raw, name, white in ((image[:, :W], vpl[k], "vpl", 24), (image[:, W + 1:], vsgl_frames[k], "vsgl", 32)):
            box_w = 4 * len(name) + 1
            outside = np.ones((H, W), bool)
            outside[:7, :box_w] = False
            np.testing.assert_array_equal(tile_image[outside], raw[outside])
            box = tile_image[:7, :box_w, :3]
            assert set(np.unique(box)) <= {0, 255}
            # Lit pixels of the glyphs (v 9, p 8, l 7: 24; v 9, s 7, g 9, l 7: 32): the name, drawn.
            assert int((box == 255).all(-1).sum()) == white, name
        assert b"vpl | vsgl" in f.read_bytes()
    # The sweep moves the light: consecutive frames differ.
    assert not np.array_equal(read_png(files[0]), read_png(files[1]))


@pytest.mark.gpu
def test_the_cli_writes_a_png_folder(tmp_path, capsys):
    out = tmp_path / "cli"
    rc = main(["animate", "cave_flashlight", "--method", "vsgl2", "--frames", "2", "--fps", "4",
               "--size", f"{W}x{H}", "--rsm-size", "64", "-o", f"{out}/"])
    assert rc == 0
    assert len(list(out.glob("*.png"))) == 2
    captured = capsys.readouterr()
    assert "flashlight_sweep" in captured.out and "frame 2/2" in captured.err


@pytest.mark.gpu
@pytest.mark.parametrize("suffix", [".gif", ".mp4"])
def test_video_files_need_the_extra(tmp_path, monkeypatch, suffix):
    monkeypatch.setitem(sys.modules, "imageio", None)  # import imageio → ImportError
    monkeypatch.setitem(sys.modules, "imageio.v3", None)
    with pytest.raises(ValueError, match=r"pip install vsgl\[video\]"):
        video.animate(None, None, ["vsgl"], frames=1, fps=1, output=str(tmp_path / f"out{suffix}"))
    assert main(["animate", "-o", str(tmp_path / f"out{suffix}")]) == 2


def test_bad_arguments_name_themselves(tmp_path):
    with pytest.raises(ValueError, match="output: expected a folder"):
        video.output_kind(str(tmp_path / "out.avi"))
    with pytest.raises(ValueError, match="frames: expected a positive int"):
        video.frame_times(0, 30)
    with pytest.raises(ValueError, match="fps: expected a finite number"):
        video.frame_times(3, float("nan"))


@pytest.mark.parametrize("suffix, tolerance, methods", [
    (".gif", 1.0, ["vsgl"]),
    (".mp4", 3.0, ["vsgl"]),
    (".mp4", 3.0, ["vsgl", "vpl"]),  # 2·24 + 1 = 49 columns: padded to 50 for H.264
])
def test_video_round_trip(tiny, tmp_path, suffix, tolerance, methods):
    iio = optional_import("imageio.v3", reason="imageio not installed (pip install vsgl[video]); round trip not checked")
    if suffix == ".mp4":
        optional_import("imageio_ffmpeg", reason="imageio-ffmpeg not installed (pip install vsgl[video])")
    path = tmp_path / f"out{suffix}"
    result = video.animate(tiny, vsgl.scenes.cave_flashlight(), methods, frames=FRAMES, fps=FPS, output=str(path), options=OPTIONS, labels=False)
    decoded = np.asarray(iio.imread(path))[..., :3].astype(np.float64)
    w, h = result["size"]
    if suffix == ".mp4":
        assert decoded.shape[1:3] == (h + h % 2, w + w % 2)
    decoded = decoded[:, :h, :w]
    expected = np.stack([video.tile(list(images)) for images in zip(*(rendered(tiny, m) for m in methods))])
    expected = expected[..., :3].astype(np.float64)
    assert decoded.shape == expected.shape
    # GIF quantises to a palette (exact here: the dark tiny frames have few colours; measured 0)
    # and H.264 is lossy (measured mean 1.2 levels of 255, max 24).
    assert np.abs(decoded - expected).mean() < tolerance


def test_a_clip_plays_in_jupyter(tiny):
    c = video.clip(tiny, vsgl.scenes.cave_flashlight(), ["vsgl2"], frames=3, fps=5, options=OPTIONS)
    html = c._repr_html_()
    assert len(c.frames) == 3 and html.count("data:image/png;base64,") == 4  # first frame + the list of 3
    assert "setInterval" in html and "200.000" in html  # 1000 ms / 5 fps
    with pytest.raises(ValueError, match="frames: expected a non-empty list"):
        video.Clip([np.zeros((4, 4, 3), np.float32)])
    with pytest.raises(ValueError, match="fps: expected a finite number"):
        video.Clip([np.zeros((4, 4, 4), np.uint8)], fps=0)
