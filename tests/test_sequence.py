"""Renderer.render_sequence: frames of a moving camera, light or node equal one-by-one render
calls of the same scene state bit for bit, and the caller's scene is never edited."""

from __future__ import annotations

import numpy as np
import pytest

import vsgl

KW = dict(num_lights=16, rsm_size=32, interleave=4)


def _frames():
    eyes = [(0.0, 1.0, 3.9), (0.3, 1.1, 3.7), (-0.4, 0.9, 3.8)]
    lights = [vsgl.SpotLight(position=(x, 1.9, 0.2), direction=(0, -1, 0), intensity=4.0, inner_cone_deg=35, outer_cone_deg=50) for x in (0.0, 0.3, -0.3)]
    move = np.eye(4)
    move[0, 3] = 0.15
    return [
        {"camera": vsgl.Camera.look_at(eye=eyes[0], target=(0, 1, 0))},
        {"camera": vsgl.Camera.look_at(eye=eyes[1], target=(0, 1, 0)), "lights": [lights[1]]},
        {"lights": [lights[2]], "transforms": {"short_block": move.tolist()}},
        {"camera": vsgl.Camera.look_at(eye=eyes[2], target=(0, 1, 0))},
    ]


@pytest.mark.parametrize("method", ["direct", "vsgl"])
def test_sequence_frames_equal_one_by_one_renders(renderer, method):
    kw = {k: v for k, v in KW.items() if k in vsgl.method_options(method)}
    scene = vsgl.scenes.cornell_box()
    before = (scene.lights[0].position, len(scene.lights))
    frames = list(renderer.render_sequence(scene, _frames(), method=method, aovs=["image", "direct"], **kw))
    assert len(frames) == 4
    assert (scene.lights[0].position, len(scene.lights)) == before, "the sequence edited the caller's scene"

    # The same states, rendered one by one on a copy edited by hand.
    copy = vsgl.scenes.cornell_box()
    camera = None
    for i, change in enumerate(_frames()):
        camera = change.get("camera", camera)
        if "lights" in change:
            copy.lights = change["lights"]
        for node, m in change.get("transforms", {}).items():
            copy.set_transform(node, m)
        want = renderer.render(copy, camera=camera, method=method, aovs=["image", "direct"], **kw)
        np.testing.assert_array_equal(frames[i].image, want.image, err_msg=f"frame {i}")
        np.testing.assert_array_equal(frames[i].aov("direct"), want.aov("direct"), err_msg=f"frame {i}")
    # The frames do differ: the camera, the light and the node moved.
    assert not np.array_equal(frames[0].image, frames[1].image)
    assert not np.array_equal(frames[1].image, frames[2].image)


def test_sequence_checks_settings_at_once_and_frames_by_name(renderer):
    scene = vsgl.scenes.cornell_box()
    with pytest.raises(vsgl.ArgumentError, match="num_lights"):
        renderer.render_sequence(scene, [{}], method="direct", num_lights=4)
    seq = renderer.render_sequence(scene, [{}, {"exposure": 2}], method="direct")
    assert next(seq).image.shape == (48, 64, 3)
    with pytest.raises(vsgl.ArgumentError, match=r"frames\[1\].*exposure"):
        next(seq)
    with pytest.raises(vsgl.ArgumentError, match=r"frames\[0\].*no node named"):
        list(renderer.render_sequence(scene, [{"transforms": {"nope": np.eye(4).tolist()}}]))
    with pytest.raises(vsgl.ArgumentError, match="frames"):
        renderer.render_sequence(scene, 3)
    # A generator works, and an empty sequence yields nothing.
    assert len(list(renderer.render_sequence(scene, ({} for _ in range(2))))) == 2
    assert list(renderer.render_sequence(scene, [])) == []


def test_the_next_frame_is_submitted_before_this_one_is_read(renderer):
    # The sequence takes item k+1 of `frames` (and submits its frame) before it reads frame k
    # back: when frame 0 is returned, the generator has handed out two items.
    taken = []

    def frames():
        for i in range(3):
            taken.append(i)
            yield {}

    seq = renderer.render_sequence(vsgl.scenes.cornell_box(), frames(), aovs=["image"])
    got = [next(seq)]
    assert taken == [0, 1]
    got.append(next(seq))
    assert taken == [0, 1, 2]
    got.append(next(seq))
    with pytest.raises(StopIteration):
        next(seq)
    # Frames 0 and 1 were read back while the next frame was on the GPU; the last had none.
    assert [f.settings["frames_in_flight"] for f in got] == [2, 2, 1]
    assert renderer.render(vsgl.scenes.cornell_box()).settings["frames_in_flight"] == 1


def test_a_steady_sequence_allocates_nothing_after_its_ring_is_made(renderer):
    # Two frames are in flight at once, so two readback slots: frame 1 makes the second slot's
    # staging buffer, and from frame 2 on nothing is allocated.
    scene = vsgl.scenes.cornell_box()
    frames = list(renderer.render_sequence(scene, [{}] * 5, method="vsgl", aovs=["image", "ldr"], **KW))
    allocated = [int(f.settings["allocated_bytes"]) for f in frames]
    assert all(a == 0 for a in allocated[2:]), allocated
    # ...and the frames are the same image, read through alternating staging buffers.
    for f in frames[1:]:
        np.testing.assert_array_equal(f.image, frames[0].image)
        np.testing.assert_array_equal(f.aov("ldr"), frames[0].aov("ldr"))


def test_an_abandoned_sequence_leaves_no_frame_counted_in_flight(renderer):
    # Leaving a sequence with frame 1 already submitted (a `break` in a for loop) drops it
    # unread; the next lone render must still report 1 frame in flight, not 2.
    seq = renderer.render_sequence(vsgl.scenes.cornell_box(), [{}] * 3, aovs=["image"])
    assert next(seq).settings["frames_in_flight"] == 2
    del seq
    import gc

    gc.collect()
    assert renderer.render(vsgl.scenes.cornell_box(), aovs=["image"]).settings["frames_in_flight"] == 1
