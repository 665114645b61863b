"""The readback: AOVs packed on the GPU in NumPy's layout hold exactly the values the sums
define, and `ldr` is the image tone-mapped as `Frame.save(".png")` does it."""

from __future__ import annotations

import numpy as np
import pytest

import vsgl


def _srgb8(linear: np.ndarray) -> np.ndarray:
    """Frame.save's PNG mapping (image_io::tonemap_srgb8), in float64."""
    x = np.where(np.isfinite(linear), np.clip(linear.astype(np.float64), 0.0, 1.0), 0.0)
    s = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)
    return np.floor(s * 255.0 + 0.5).astype(np.int64)


@pytest.mark.parametrize("method", ["direct", "vsgl", "pathtrace"])
def test_packed_sums_are_exact(renderer, method):
    kw = {k: v for k, v in dict(num_lights=16, rsm_size=32, spp=2).items() if k in vsgl.method_options(method)}
    f = renderer.render(vsgl.scenes.glossy_cornell(), method=method, **kw)
    if method == "direct":
        np.testing.assert_array_equal(f.image, f.aov("direct"))
        return
    # The same f32 additions in the same order as NumPy's.
    np.testing.assert_array_equal(f.aov("indirect"), f.aov("indirect_diffuse") + f.aov("indirect_specular"))
    np.testing.assert_array_equal(f.image, f.aov("direct") + f.aov("indirect"))


def test_ldr_is_the_png_mapping_of_the_image_and_only_on_request(renderer):
    scene = vsgl.scenes.cornell_box()
    f = renderer.render(scene, method="vsgl", num_lights=16, rsm_size=32, aovs=["image", "ldr"])
    ldr = f.aov("ldr")
    assert ldr.dtype == np.uint8 and ldr.shape == (48, 64, 4) and ldr.flags.c_contiguous
    assert (ldr[..., 3] == 255).all()
    want = _srgb8(f.image)
    diff = np.abs(ldr[..., :3].astype(np.int64) - want)
    # pow() on the GPU may round differently from the CPU by an ulp: at most one step, rarely.
    assert diff.max() <= 1 and (diff == 0).mean() > 0.99, (diff.max(), (diff == 0).mean())
    assert 0 < ldr[..., :3].mean() < 255
    assert "ldr" not in renderer.render(scene, method="vsgl", num_lights=16, rsm_size=32).aovs
    only = renderer.render(scene, method="direct", aovs=["ldr"])
    assert only.aovs == ["ldr"]
    direct = _srgb8(renderer.render(scene, method="direct").image)
    assert np.abs(only.aov("ldr")[..., :3].astype(np.int64) - direct).max() <= 1


def test_aov_arrays_are_the_readback_itself_not_copies(renderer):
    f = renderer.render(vsgl.scenes.cornell_box(), method="direct", aovs=["image", "depth"])
    a, b = f.image, f.image
    assert a is b and f.aov("image") is a, "each access copied the image"
    assert a.dtype == np.float32 and a.flags.c_contiguous and a.flags.writeable
    assert f.aov("depth").shape == (48, 64, 1)
