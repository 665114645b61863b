"""Values that would overflow later are refused where they are given, with the real cause
(scene/limits.rs: coordinates within ±1e18 m, intensities up to 1e32), vectors normalise without
overflow, and a frame that still computes NaN or Inf (extreme intensity at an extreme scale) is
refused by the frame path instead of handed out."""

from __future__ import annotations

import numpy as np
import pytest

import gltf_fixtures
import vsgl


def test_an_intensity_that_overflows_f32_radiance_is_refused():
    with pytest.raises(vsgl.ArgumentError, match=r"intensity: must be positive and at most 1e32"):
        vsgl.SpotLight(position=(0, 1, 0), direction=(0, -1, 0), intensity=3e38)
    assert vsgl.SpotLight(position=(0, 1, 0), direction=(0, -1, 0), intensity=1e32).intensity == pytest.approx(1e32)


def test_huge_direction_components_normalise_without_overflow():
    d = vsgl.SpotLight(position=(0, 1, 0), direction=(0, -1e300, 1e300), intensity=1).direction
    np.testing.assert_allclose(d, (0, -np.sqrt(0.5), np.sqrt(0.5)), rtol=1e-12)
    d = vsgl.SpotLight(position=(0, 1, 0), direction=(1e-310, 0, 0), intensity=1).direction
    assert d == (1.0, 0.0, 0.0)


@pytest.mark.parametrize("kw", [dict(eye=(0, 1, 1e300), target=(0, 1, 0)), dict(eye=(0, 1, 3), target=(0, -3e38, 0))])
def test_a_camera_beyond_the_coordinate_bound_names_it(kw):
    which = "eye" if kw["eye"][2] > 1e18 else "target"
    with pytest.raises(vsgl.ArgumentError, match=rf"{which}: coordinates must be finite and within ±1e18 m"):
        vsgl.Camera.look_at(**kw)


def test_a_light_beyond_the_coordinate_bound_names_it():
    with pytest.raises(vsgl.ArgumentError, match=r"position: coordinates must be finite and within"):
        vsgl.SpotLight(position=(0, 1e19, 0), direction=(0, -1, 0), intensity=1)


def test_a_transform_that_moves_geometry_out_of_range_is_refused_and_not_applied(renderer):
    scene = vsgl.scenes.cornell_box()
    before = renderer.render(scene, aovs=["image"]).image
    m = np.eye(4)
    m[0, 3] = 3e38
    node = scene.node_names[0]
    with pytest.raises(vsgl.ArgumentError, match=r"beyond ±1e18 m .*not applied"):
        scene.set_transform(node, m.tolist())
    np.testing.assert_array_equal(renderer.render(scene, aovs=["image"]).image, before)


def test_a_file_with_a_node_out_of_range_is_a_scene_error_naming_it(tmp_path):
    path = gltf_fixtures._quad(tmp_path, node={"translation": [3e38, 0, 0]})
    with pytest.raises(vsgl.SceneError, match=r"nodes\[0\].*beyond ±1e18 m"):
        vsgl.Scene.load(str(path))
    # 1e17 m is representable: it loads.
    vsgl.Scene.load(str(gltf_fixtures._quad(tmp_path, node={"translation": [1e17, 0, 0]}, name="far.gltf")))


def _scaled_box(scale: float, intensity: float):
    scene = vsgl.scenes.cornell_box()
    m = np.eye(4)
    m[:3, :3] *= scale
    for n in scene.node_names:
        scene.set_transform(n, m.tolist())
    light = scene.lights[0]
    scene.lights = [vsgl.SpotLight(position=tuple(scale * np.array(light.position)), direction=light.direction, intensity=intensity,
                                   inner_cone_deg=light.inner_cone_deg, outer_cone_deg=light.outer_cone_deg)]
    cam = scene.cameras[0]
    eye = scale * np.array(cam.eye)
    camera = vsgl.Camera.look_at(eye=tuple(eye), target=tuple(eye + np.array(cam.forward)), up=cam.up, fov_y_deg=cam.fov_y_deg)
    return scene, camera


@pytest.mark.parametrize("method", ["vpl", "vsgl"])
def test_a_frame_with_non_finite_values_is_refused_naming_the_aovs(renderer, method):
    # 1e32 cd in a box of 0.2 mm: radiance ~ I/d² ~ 1e40 overflows f32. Each input alone is
    # valid; the frame path counts the non-finite values on the GPU and refuses the frame.
    scene, camera = _scaled_box(1e-4, 1e32)
    with pytest.raises(vsgl.NumericsError, match=r'non-finite values \(NaN or Inf\) in the frame: \d+ in "image"'):
        renderer.render(scene, camera, method=method, rsm_size=64, aovs=["image", "ldr"])
    # The renderer is still usable, and the same intensity at 1e-3 scale renders finite.
    scene, camera = _scaled_box(1e-3, 1e32)
    f = renderer.render(scene, camera, method=method, rsm_size=64, aovs=["image"])
    assert np.isfinite(f.image).all() and f.image.max() > 1e30


# Python ints of any size reach the range checks (crates/vsgl-py/src/args.rs): never a bare
# OverflowError, always an ArgumentError naming the argument and what it allows.
@pytest.mark.parametrize("kw, message", [
    (dict(width=2**64), r"width: must be in 1\.\.=16384, got 18446744073709551616"),
    (dict(height=2**64), r"height: must be in 1\.\.=16384, got 18446744073709551616"),
    (dict(width=-2**70), r"width: must be in 1\.\.=16384, got -1180591620717411303424"),
    (dict(height=10**5000), r"height: must be in 1\.\.=16384, got 2\*\*16609 or beyond \(16610 bits\)"),
])
def test_a_huge_renderer_size_names_the_argument_and_its_range(kw, message):
    with pytest.raises(vsgl.ArgumentError, match=message):
        vsgl.Renderer(**kw)


@pytest.mark.parametrize("method, kw, message", [
    ("pathtrace", dict(spp=2**70), r"spp: must be in 1\.\.=65536, got 1180591620717411303424"),
    ("pathtrace", dict(spp=-2**70), r"spp: must be in 1\.\.=65536, got -1180591620717411303424"),
    ("direct", dict(shadow_size=2**64), r"shadow_size: must be in 16\.\.=8192, got 18446744073709551616"),
    ("pathtrace", dict(time_budget_s=10**400), r"time_budget_s: must be finite and >= 0, got 2\*\*1328 or beyond"),
])
def test_a_huge_render_option_names_the_option_and_its_range(renderer, method, kw, message):
    with pytest.raises(vsgl.ArgumentError, match=message):
        renderer.render(vsgl.scenes.cornell_box(), method=method, **kw)


def test_a_huge_texture_budget_names_its_range(tmp_path):
    with pytest.raises(vsgl.ArgumentError, match=r"max_texture_bytes: must be in 1\.\.=18446744073709551615, got 1208925819614629174706176"):
        vsgl.Scene.load(gltf_fixtures.write_glb(tmp_path), max_texture_bytes=2**80)
    # 2**64 - 1 is the largest budget and loads.
    assert vsgl.Scene.load(gltf_fixtures.write_glb(tmp_path), max_texture_bytes=2**64 - 1).stats["triangles"] == 2


@pytest.mark.parametrize("make, message", [
    (lambda: vsgl.SpotLight(position=(0, 1, 0), direction=(0, -1, 0), intensity=10**400), r"intensity: must be finite, got inf"),
    (lambda: vsgl.PointLight(position=(10**400, 0, 0), intensity=1.0), r"position: every component must be finite"),
    (lambda: vsgl.Camera.look_at(eye=(0, 1, 3), target=(0, 1, 0), fov_y_deg=-10**400), r"fov_y_deg: must be finite, got -inf"),
])
def test_a_float_argument_given_a_huge_int_names_the_argument(make, message):
    # An int past f64's range is the float it rounds to (±inf), which the checks refuse by name.
    with pytest.raises(vsgl.ArgumentError, match=message):
        make()
    # Ints within range are floats as before (2**200 is a finite float).
    assert vsgl.SpotLight(position=(0, 1, 0), direction=(0, -1, 0), intensity=2**100).intensity == pytest.approx(2.0**100)
