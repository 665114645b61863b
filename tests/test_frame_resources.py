"""Frame resources persist: an unchanged configuration creates no GPU buffer, target or bind
group on its second frame, and a reused target never carries the previous frame's data into
the next."""

from __future__ import annotations

import numpy as np
import pytest

import vsgl

# strategy="camera": pathtrace's camera paths are bit-deterministic, while its default
# bidirectional strategy adds light splats with float atomics in a varying order, so frames
# would differ in their last bits for that reason alone.
SMALL = dict(num_lights=16, rsm_size=32, spp=2, shadow_size=128, interleave=4, strategy="camera")


def _kw(method: str) -> dict:
    takes = vsgl.method_options(method)
    return {k: v for k, v in SMALL.items() if k in takes}


@pytest.mark.parametrize("method", vsgl.METHODS)
def test_second_frame_allocates_nothing_and_renders_the_same(method):
    r = vsgl.Renderer(width=40, height=30)
    scene = vsgl.scenes.glossy_cornell()
    first = r.render(scene, method=method, **_kw(method))
    second = r.render(scene, method=method, **_kw(method))
    assert int(first.settings["allocated_bytes"]) > 0
    assert second.settings["allocated_bytes"] == 0, second.settings
    # ...and binds what the first frame bound: every bind group (and view) is kept.
    assert int(first.settings["bind_groups_created"]) > 0
    assert second.settings["bind_groups_created"] == 0, second.settings
    # memory_bytes reports what the frame uses, new or kept.
    assert second.memory_bytes == first.memory_bytes
    for name in first.aovs:
        np.testing.assert_array_equal(second.aov(name), first.aov(name), err_msg=f"{method}/{name}")


@pytest.mark.parametrize("method", vsgl.METHODS)
def test_a_reused_target_holds_nothing_of_the_previous_frame(method):
    """Frame B after frame A of another scene equals frame B on a fresh renderer, bit for bit
    (shading adds into its targets: a reused target that was not cleared would add A to B)."""
    kw = _kw(method)
    warm = vsgl.Renderer(width=40, height=30)
    warm.render(vsgl.scenes.caustics_ring(), method=method, **kw)
    after = warm.render(vsgl.scenes.cornell_box(), method=method, **kw)
    assert int(after.settings["allocated_bytes"]) < sum(after.memory_bytes.values()), "nothing was reused: the test would prove nothing"
    fresh = vsgl.Renderer(width=40, height=30).render(vsgl.scenes.cornell_box(), method=method, **kw)
    for name in fresh.aovs:
        np.testing.assert_array_equal(after.aov(name), fresh.aov(name), err_msg=f"{method}/{name}")


def test_a_changed_setting_allocates_only_what_changed():
    r = vsgl.Renderer(width=40, height=30)
    scene = vsgl.scenes.cornell_box()
    r.render(scene, method="vpl", num_lights=16, rsm_size=32)
    more = r.render(scene, method="vpl", num_lights=64, rsm_size=32)
    # Only the VPL list grows (64 VPLs of 80 bytes); every target is kept.
    assert int(more.settings["allocated_bytes"]) == 64 * 80, more.settings
