"""The pass plan: each leave-out rule renders the same image as `plan="full"` on a
scene that lacks the feature, names what it left out in `frame.skipped`, does not allocate the
buffers it does not use, and does not fire on a scene that has the feature."""

from __future__ import annotations

import math

import numpy as np
import pytest

import gltf_fixtures as fx
import vsgl
from scene_builders import write_quad
from test_direct import ggx_over_rs

INDIRECT = {
    "direct": {},
    "vpl": dict(num_lights=64, rsm_size=32),
    "vsgl": dict(num_lights=64, rsm_size=32),
    "vsgl2": dict(rsm_size=32),
    "reference": dict(rsm_size=32),
}


def assert_same_image(pruned: vsgl.Frame, full: vsgl.Frame) -> None:
    """Within float rounding: the pruned variants only drop terms that are exactly 0 here, so
    the images agree to a few ULP (measured: bit-identical on lavapipe)."""
    for aov in pruned.aovs:
        np.testing.assert_allclose(pruned.aov(aov), full.aov(aov), rtol=1e-6, atol=1e-7, err_msg=aov)


# --- no specular reflectance anywhere → no specular lobes --------------------------------------


@pytest.mark.parametrize("method", list(INDIRECT))
def test_diffuse_only_scene_leaves_out_specular_lobes_without_changing_the_image(renderer, method):
    scene = vsgl.scenes.diffuse_cornell()
    assert "specular" not in scene.stats["features"]
    pruned = renderer.render(scene, method=method, **INDIRECT[method])
    full = renderer.render(scene, method=method, plan="full", **INDIRECT[method])
    assert "specular_lobes" in pruned.skipped and "specular_lobes" not in full.skipped
    assert "direct[diffuse_only]" in pruned.passes and "direct" in full.passes
    assert_same_image(pruned, full)
    assert pruned.image.mean() > 0 and np.isfinite(pruned.image).all()
    if method != "direct":
        # Indirect light is present (a vacuous comparison of black images would prove nothing),
        # and the specular targets are placeholders, not frame-sized buffers.
        assert pruned.aov("indirect_diffuse").mean() > 0
        assert not pruned.aov("indirect_specular").any()
        assert pruned.memory_bytes["indirect_specular_buffer"] == 16
        assert pruned.memory_bytes["rsm_flux_specular_buffer"] == 16
        assert full.memory_bytes["indirect_specular_buffer"] == 16 * 64 * 48
        assert sum(pruned.memory_bytes.values()) < sum(full.memory_bytes.values())


@pytest.mark.parametrize("method", ["direct", "vpl", "vsgl", "vsgl2"])
def test_scene_with_specular_keeps_the_specular_lobes(renderer, method):
    # cornell_box is dielectric (R_s = 0.04): its specular lobes are small but not zero.
    scene = vsgl.scenes.cornell_box()
    assert "specular" in scene.stats["features"]
    f = renderer.render(scene, method=method, **INDIRECT[method])
    assert "specular_lobes" not in f.skipped
    assert not any("diffuse_only" in p for p in f.passes)
    if method != "direct":
        assert f.aov("indirect_specular").max() > 0


def test_specular_factor_of_khr_materials_specular_scales_the_dielectric_f0(tmp_path, make_renderer):
    """L = (ρ/π + 0.04·s·f_ggx)·I/d² straight below the light (l = v = n, roughness 1); s = 0
    is Lambertian, and only then is the specular variant left out."""
    rho, intensity, d, size = 0.6, 10.0, 1.5, 33
    r = make_renderer(size, size)
    cam = vsgl.Camera.look_at(eye=(0, 1.5 * d, 0), target=(0, 0, 0), up=(0, 0, -1), fov_y_deg=30)
    for s in (0.0, 0.5, 1.0):
        scene = vsgl.Scene.load(write_quad(tmp_path, half_size=2 * d, base_color=(rho,) * 3, specular=s, name=f"q{s}.gltf"))
        scene.add_light(vsgl.SpotLight(position=(0, d, 0), direction=(0, -1, 0), intensity=intensity, inner_cone_deg=30, outer_cone_deg=40))
        f = r.render(scene, camera=cam)
        expected = (rho / math.pi + 0.04 * s * ggx_over_rs(1.0, 1.0, 1.0, 1.0)) * intensity / d**2
        np.testing.assert_allclose(f.aov("direct")[size // 2, size // 2], expected, rtol=0.01)
        assert ("specular_lobes" in f.skipped) == (s == 0.0)


def test_specular_factor_out_of_range_is_clamped_like_the_other_factors(tmp_path, renderer):
    # glTF limits specularFactor to [0, 1]; the loader clamps it as it clamps metallicFactor.
    below = vsgl.Scene.load(write_quad(tmp_path, specular=-0.5, name="below.gltf"))
    above = vsgl.Scene.load(write_quad(tmp_path, specular=1.5, name="above.gltf"))
    assert "specular" not in below.stats["features"] and "specular" in above.stats["features"]


# --- no textures → untextured material; no normal maps → no tangent frames ----------------------


def _lit(scene: vsgl.Scene) -> vsgl.Scene:
    scene.add_light(vsgl.SpotLight(position=(0, 0, 3), direction=(0, 0, -1), intensity=10.0, outer_cone_deg=60, inner_cone_deg=50))
    return scene


CAM = vsgl.Camera.look_at(eye=(0, 0, 3), target=(0, 0, 0))


def test_textured_scene_without_normal_maps_leaves_out_tangent_frames(tmp_path, renderer):
    scene = _lit(vsgl.Scene.load(fx.write_textured_without_normal_map(tmp_path)))
    assert "textures" in scene.stats["features"] and "normal_maps" not in scene.stats["features"]
    for method, kw in (("direct", {}), ("vsgl", INDIRECT["vsgl"])):
        pruned = renderer.render(scene, camera=CAM, method=method, **kw)
        full = renderer.render(scene, camera=CAM, method=method, plan="full", **kw)
        assert "material[no_normal_maps]" in pruned.passes and "material" in full.passes
        assert "normal_map_tangent_frames" in pruned.skipped
        assert "material_texture_fetch" not in pruned.skipped
        assert_same_image(pruned, full)
        assert pruned.image.mean() > 0


def test_normal_mapped_scene_keeps_tangent_frames_and_textures(tmp_path, renderer):
    scene = _lit(vsgl.Scene.load(fx.write_textured(tmp_path)))
    f = renderer.render(scene, camera=CAM)
    assert "material" in f.passes
    assert "normal_map_tangent_frames" not in f.skipped and "material_texture_fetch" not in f.skipped


def test_untextured_scene_uses_the_untextured_variant(renderer):
    scene = vsgl.scenes.glossy_cornell()
    pruned = renderer.render(scene, method="vsgl", **INDIRECT["vsgl"])
    full = renderer.render(scene, method="vsgl", plan="full", **INDIRECT["vsgl"])
    assert "rsm_material[untextured]" in pruned.passes and "rsm_material" in full.passes
    assert {"material_texture_fetch", "normal_map_tangent_frames"} <= set(pruned.skipped)
    assert_same_image(pruned, full)


# --- settings-driven rules ------------------------------------------------------------------------


def test_scene_without_lights_renders_no_shadow_map(renderer):
    scene = vsgl.scenes.cornell_box()
    scene.lights = []
    f = renderer.render(scene, method="vsgl", **INDIRECT["vsgl"])
    assert "shadow_map" in f.skipped and "shadow_map" not in f.passes
    assert f.memory_bytes["shadow_map_depth_texture"] == 16 * 16 * 4
    lit = renderer.render(vsgl.scenes.cornell_box(), shadow_size=256)
    assert "shadow_map" in lit.passes and lit.memory_bytes["shadow_map_depth_texture"] == 256 * 256 * 4


def test_two_vsgls_take_the_summation_path_without_a_pyramid(renderer):
    f = renderer.render(vsgl.scenes.cornell_box(), method="vsgl2", rsm_size=32)
    assert {"pdf_mips", "moment_mips", "vsgl_sampling", "denoise"} <= set(f.skipped)
    assert "vsgl_moment_chain_buffer" not in f.memory_bytes and f.memory_bytes["rsm_weight_pyramid_buffer"] == 16
    many = renderer.render(vsgl.scenes.cornell_box(), method="vsgl", **INDIRECT["vsgl"])
    assert "vsgl_moment_chain_buffer" in many.memory_bytes and "moment_mips" in many.passes
    assert many.memory_bytes["rsm_weight_pyramid_buffer"] > 32 * 32 * 4


def test_unshadowed_virtual_lights_render_no_virtual_shadow_maps(renderer):
    f = renderer.render(vsgl.scenes.cornell_box(), method="vpl", visibility="none", **INDIRECT["vpl"])
    assert "vpl_shadow_maps" in f.skipped


def test_full_plan_leaves_out_no_scene_feature(renderer):
    f = renderer.render(vsgl.scenes.diffuse_cornell(), method="vsgl", plan="full", **INDIRECT["vsgl"])
    assert not {"specular_lobes", "material_texture_fetch", "normal_map_tangent_frames"} & set(f.skipped)
    assert all("[" not in p for p in f.passes), f.passes
