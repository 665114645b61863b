"""Point and directional lights: the Python classes, the glTF loader, direct light
against closed forms (KHR_lights_punctual units), point-light cube shadows on every face,
additivity of several lights, NaN/Inf safety, point lights in the virtual-light methods (six
cube-face RSMs: total power, agreement with the path tracer, budget split) and directional
lights there (one orthographic RSM: total power, agreement with the path tracer)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import vsgl
import gltf_fixtures as fx
from scene_builders import write_quad, write_quads

SIZE = 33  # odd, so the centre pixel's ray is exactly the optical axis


def centre(frame: vsgl.Frame, aov: str = "direct") -> np.ndarray:
    return frame.aov(aov)[SIZE // 2, SIZE // 2]


# ------------------------------------------------------------------------------------------
# API and loader
# ------------------------------------------------------------------------------------------


def test_point_and_directional_light_classes():
    p = vsgl.PointLight(position=(1, 2, 3), intensity=5.0, color=(1, 0.5, 0.25))
    assert p.position == (1, 2, 3) and p.intensity == 5.0 and p.color == (1, 0.5, 0.25)
    d = vsgl.DirectionalLight(direction=(0, -2, 0), intensity=3.0)
    assert d.direction == (0, -1, 0), "the direction is normalised"
    assert d.intensity == 3.0 and d.color == (1, 1, 1)
    assert "PointLight(" in repr(p) and "DirectionalLight(" in repr(d)


@pytest.mark.parametrize(
    "make,name",
    [
        (lambda: vsgl.PointLight(position=(0, math.nan, 0), intensity=1.0), "position"),
        (lambda: vsgl.PointLight(position=(0, 0), intensity=1.0), "position"),
        (lambda: vsgl.PointLight(position=(0, 0, 0), intensity=0.0), "intensity"),
        (lambda: vsgl.PointLight(position=(0, 0, 0), intensity=math.inf), "intensity"),
        (lambda: vsgl.PointLight(position=(0, 0, 0), intensity=1.0, color=(1, -1, 1)), "color"),
        (lambda: vsgl.DirectionalLight(direction=(0, 0, 0), intensity=1.0), "direction"),
        (lambda: vsgl.DirectionalLight(direction=(0, math.inf, 0), intensity=1.0), "direction"),
        (lambda: vsgl.DirectionalLight(direction=(0, -1, 0), intensity=-2.0), "intensity"),
        (lambda: vsgl.DirectionalLight(direction=(0, -1, 0), intensity=1.0, color=(1, 1, math.nan)), "color"),
    ],
)
def test_bad_light_arguments_raise_argument_error_naming_them(make, name):
    with pytest.raises(vsgl.ArgumentError, match=f"^{name}:"):
        make()


def test_scene_takes_a_mix_of_light_types():
    scene = vsgl.scenes.cornell_box()
    spot = scene.lights[0]
    scene.add_light(vsgl.PointLight(position=(0, 1, 0), intensity=2.0))
    scene.add_light(vsgl.DirectionalLight(direction=(0, -1, 0), intensity=3.0))
    assert [type(light) for light in scene.lights] == [vsgl.SpotLight, vsgl.PointLight, vsgl.DirectionalLight]
    assert scene.stats["lights"] == 3
    assert scene.stats["lights_by_type"] == {"spot": 1, "point": 1, "directional": 1}
    scene.lights = [vsgl.DirectionalLight(direction=(1, -1, 0), intensity=1.0), spot]
    assert [type(light) for light in scene.lights] == [vsgl.DirectionalLight, vsgl.SpotLight]
    assert scene.stats["lights_by_type"] == {"spot": 1, "point": 0, "directional": 1}
    with pytest.raises(TypeError):
        scene.add_light("a lamp")


def test_loader_reads_point_and_directional_lights_with_gltf_conventions(tmp_path):
    scene = vsgl.Scene.load(fx.write_spot_light_camera(tmp_path))
    spot, point, sun = scene.lights
    assert isinstance(point, vsgl.PointLight) and point.position == (0, 0, 0) and point.intensity == 10.0
    # KHR_lights_punctual: the light travels along its node's −Z (here rotated to −Y); the
    # node's translation does not matter for a directional light.
    assert isinstance(sun, vsgl.DirectionalLight)
    np.testing.assert_allclose(sun.direction, (0, -1, 0), atol=1e-6)
    assert sun.intensity == 2.0 and sun.color == (0.5, 1.0, 1.0)
    assert any("range = 3 is ignored" in w for w in scene.warnings), scene.warnings


# ------------------------------------------------------------------------------------------
# Direct light against closed forms
# ------------------------------------------------------------------------------------------


@pytest.mark.parametrize("method", ["direct", "pathtrace"])
@pytest.mark.parametrize("rho,intensity", [(0.8, 20.0), (0.3, 1e4)])
def test_diffuse_plane_under_point_light_matches_closed_form(tmp_path, make_renderer, method, rho, intensity):
    d = 2.0
    # specularFactor 0: a purely Lambertian plane, so L = ρ/π · I/d² exactly (l = n).
    scene = vsgl.Scene.load(write_quad(tmp_path, half_size=4.0, base_color=(rho, rho, rho), specular=0.0))
    scene.add_light(vsgl.PointLight(position=(0, d, 0), intensity=intensity))
    cam = vsgl.Camera.look_at(eye=(0, 1.5 * d, 0.5), target=(0, 0, 0), up=(0, 0, -1), fov_y_deg=30)
    frame = make_renderer(SIZE, SIZE).render(scene, camera=cam, method=method, **({"spp": 1} if method == "pathtrace" else {}))
    np.testing.assert_allclose(centre(frame), rho / math.pi * intensity / d**2, rtol=0.01)


def test_shadow_maps_that_miss_the_scene_are_left_out_and_change_nothing(tmp_path, make_renderer):
    """A point light 2 m over a 1 m plane sees the scene through its −Y face only, and a spot
    light beside it points away: their other shadow-map layers are not rendered (nor the
    RSMs of the virtual-light methods), and the plane still gets ρ/π · I/d² at its centre."""
    d, rho, intensity = 2.0, 0.8, 20.0
    scene = vsgl.Scene.load(write_quad(tmp_path, half_size=0.5, base_color=(rho, rho, rho), specular=0.0))
    scene.lights = [
        vsgl.PointLight(position=(0, d, 0), intensity=intensity),
        vsgl.SpotLight(position=(0.2, d, 0), direction=(0, 1, 0), intensity=50.0, outer_cone_deg=60),
    ]
    cam = vsgl.Camera.look_at(eye=(0, 1.5 * d, 0.5), target=(0, 0, 0), up=(0, 0, -1), fov_y_deg=30)
    r = make_renderer(SIZE, SIZE)
    frame = r.render(scene, camera=cam, method="direct")
    left_out = sorted(k for k in frame.skipped if k.startswith("shadow_map of"))
    assert left_out == [f"shadow_map of light 0 face {f}" for f in (0, 1, 2, 4, 5)] + ["shadow_map of light 1"]
    np.testing.assert_allclose(centre(frame), rho / math.pi * intensity / d**2, rtol=0.01)
    # The virtual-light methods leave out the same views' RSMs.
    vpl = r.render(scene, camera=cam, method="vpl", num_lights=64, rsm_size=32)
    assert sorted(k for k in vpl.skipped if k.startswith("virtual lights of")) == [f"virtual lights of light 0 view {f}" for f in (0, 1, 2, 4, 5)] + ["virtual lights of light 1"]
    assert vpl.settings["virtual_lights_per_light"] == [[0, 0, 0, 64, 0, 0], [0]]
    _assert_finite(vpl)


@pytest.mark.parametrize("method", ["direct", "pathtrace"])
@pytest.mark.parametrize("theta_deg", [0.0, 60.0, 80.0])
def test_diffuse_plane_under_directional_light_matches_closed_form(tmp_path, make_renderer, method, theta_deg):
    rho, e = 0.7, 3.0
    scene = vsgl.Scene.load(write_quad(tmp_path, half_size=4.0, base_color=(rho, rho, rho), specular=0.0))
    t = math.radians(theta_deg)
    scene.add_light(vsgl.DirectionalLight(direction=(math.sin(t), -math.cos(t), 0), intensity=e))
    cam = vsgl.Camera.look_at(eye=(0, 3, 0), target=(0, 0, 0), up=(0, 0, -1), fov_y_deg=30)
    frame = make_renderer(SIZE, SIZE).render(scene, camera=cam, method=method, **({"spp": 1} if method == "pathtrace" else {}))
    # Lambert under an illuminance E at θ from the normal: L = ρ/π · E · cosθ, everywhere.
    expected = rho / math.pi * e * math.cos(t)
    np.testing.assert_allclose(centre(frame), expected, rtol=0.01)
    # No falloff and no self-shadowing anywhere on the plane (the shadow map's slope bias).
    np.testing.assert_allclose(frame.aov("direct"), expected, rtol=0.01)


@pytest.mark.parametrize("method", ["direct", "pathtrace"])
def test_occluder_under_directional_light_casts_its_shadow(tmp_path, make_renderer, method):
    rho, e = 0.6, 2.0
    t = math.radians(30.0)
    quads = [square((0, 0, 0), (0, 1, 0), 3.0, base_color=(rho, rho, rho), name="floor"),
             square((0, 1, 0), (0, 1, 0), 0.5, name="occluder")]
    scene = vsgl.Scene.load(write_quads(tmp_path, quads, name="sun.gltf"))
    scene.add_light(vsgl.DirectionalLight(direction=(math.sin(t), -math.cos(t), 0), intensity=e))
    r = make_renderer(SIZE, SIZE)
    opts = {"spp": 1} if method == "pathtrace" else {}
    # The occluder's shadow is centred tan30° × its height downwind; seen past the occluder.
    shadow = (math.tan(t), 0.0, 0.0)
    f = r.render(scene, camera=vsgl.Camera.look_at(eye=(shadow[0] + 2.0, 2.5, 0), target=shadow, fov_y_deg=20), method=method, **opts)
    lit = rho / math.pi * e * math.cos(t)
    assert centre(f).max() < 0.01 * lit, f"{centre(f)} not shadowed"
    f = r.render(scene, camera=vsgl.Camera.look_at(eye=(-1.5, 2.5, 2.0), target=(-1.5, 0, 0), fov_y_deg=20), method=method, **opts)
    np.testing.assert_allclose(centre(f), lit, rtol=0.01)


# ------------------------------------------------------------------------------------------
# Point-light shadows: every cube face
# ------------------------------------------------------------------------------------------

H = 1.0  # half side of the box around the light
AXES = [np.eye(3)[k] for k in range(3)]


def square(c, n, half, **kw) -> dict:
    """A square quad centred at c with unit normal n (corners ordered so that the quad's
    normal is n) and half side `half`."""
    n = np.asarray(n, float)
    u = np.cross(n, AXES[1] if abs(n[1]) < 0.9 else AXES[0])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)  # u × v = n
    c = np.asarray(c, float)
    corners = [c - half * u - half * v, c + half * u - half * v, c + half * u + half * v, c - half * u + half * v]
    return {"corners": [tuple(p) for p in corners], "specular": 0.0, **kw}


FACES = [(k, s) for k in range(3) for s in (1.0, -1.0)]


def off_axis(k: int, b: float, c: float) -> np.ndarray:
    """b along axis (k + 1) % 3 plus c along axis (k + 2) % 3."""
    return b * AXES[(k + 1) % 3] + c * AXES[(k + 2) % 3]


def box_scene(tmp_path, occluders: bool, rho: float = 0.6) -> vsgl.Scene:
    """Six inward-facing walls of a cube of half side H around the origin; with `occluders`,
    a small square (half side 0.05·H) halfway to each wall, off the axis by (0.15, 0.05)·H so
    that its shadow (centred at (0.3, 0.1)·H on the wall, half side 0.1·H) is asymmetric: a
    cube face looked up flipped or transposed puts it elsewhere."""
    quads = [square(s * H * AXES[k], -s * AXES[k], H, base_color=(rho, rho, rho), name=f"wall{k}{s:+.0f}") for k, s in FACES]
    if occluders:
        quads += [square(s * 0.5 * H * AXES[k] + off_axis(k, 0.15 * H, 0.05 * H), -s * AXES[k], 0.05 * H, name=f"occluder{k}{s:+.0f}") for k, s in FACES]
    name = "box_occluded.gltf" if occluders else "box.gltf"
    return vsgl.Scene.load(write_quads(tmp_path, quads, name=name))


def wall_camera(k: int, s: float, target: np.ndarray) -> vsgl.Camera:
    """A camera inside the box looking at `target` on wall (k, s) obliquely, past the
    occluders: from 0.2·H along the wall's axis and 0.7·H along both other axes."""
    others = [j for j in range(3) if j != k]
    eye = s * 0.2 * H * AXES[k] + 0.7 * H * (AXES[others[0]] + AXES[others[1]])
    up = AXES[k] if k != 1 else AXES[2]
    return vsgl.Camera.look_at(eye=tuple(eye), target=tuple(target), up=tuple(up), fov_y_deg=20)


@pytest.mark.parametrize("method", ["direct", "pathtrace"])
def test_point_light_in_a_closed_box_lights_six_walls_and_occluders_shadow_each_face(tmp_path, make_renderer, method):
    rho, intensity = 0.6, 5.0
    r = make_renderer(SIZE, SIZE)
    light = vsgl.PointLight(position=(0, 0, 0), intensity=intensity)
    open_box, shadowed_box = box_scene(tmp_path, occluders=False, rho=rho), box_scene(tmp_path, occluders=True, rho=rho)
    for scene in (open_box, shadowed_box):
        scene.lights = [light]
    opts = {"spp": 1} if method == "pathtrace" else {}
    lit = rho / math.pi * intensity / H**2
    for k, s in FACES:
        wall_centre = s * H * AXES[k]
        # Without occluders each wall's centre gets ρ/π·I/H² (normal incidence at distance H).
        f = r.render(open_box, camera=wall_camera(k, s, wall_centre), method=method, **opts)
        np.testing.assert_allclose(centre(f), lit, rtol=0.01, err_msg=f"wall {k}{s:+}")
        # The occluder darkens the centre of its shadow...
        f = r.render(shadowed_box, camera=wall_camera(k, s, wall_centre + off_axis(k, 0.3 * H, 0.1 * H)), method=method, **opts)
        assert centre(f).max() < 0.01 * lit, f"wall {k}{s:+}: {centre(f)} not shadowed"
        # ... and not the mirror point through the wall's centre, lit by ρ/π·I·cosθ/d² with
        # d² = (1 + 0.3² + 0.1²)·H², cosθ = H/d.
        f = r.render(shadowed_box, camera=wall_camera(k, s, wall_centre - off_axis(k, 0.3 * H, 0.1 * H)), method=method, **opts)
        d2 = 1.1 * H**2
        np.testing.assert_allclose(centre(f), rho / math.pi * intensity * (H / math.sqrt(d2)) / d2, rtol=0.01, err_msg=f"wall {k}{s:+} mirror point")


# ------------------------------------------------------------------------------------------
# Several lights add up
# ------------------------------------------------------------------------------------------


def three_light_scene(tmp_path) -> tuple[vsgl.Scene, list]:
    quads = [
        square((0, 0, 0), (0, 1, 0), 2.0, name="floor"),
        square((0, 1, -2), (0, 0, 1), 2.0, base_color=(0.3, 0.6, 0.9), name="back"),
        square((-2, 1, 0), (1, 0, 0), 2.0, base_color=(0.9, 0.3, 0.3), name="left"),
        square((0.3, 0.6, 0.2), (0, 1, 0), 0.3, name="table"),
    ]
    for q in quads:
        q.pop("specular")  # glossy enough to exercise the specular terms too
        q["roughness"] = 0.5
    scene = vsgl.Scene.load(write_quads(tmp_path, quads, name="three.gltf"))
    lights = [
        vsgl.SpotLight(position=(0.5, 2.5, 0.5), direction=(-0.2, -1, -0.1), intensity=8.0, inner_cone_deg=35, outer_cone_deg=50),
        vsgl.PointLight(position=(-1.0, 1.5, 1.0), intensity=3.0, color=(1, 0.8, 0.6)),
        vsgl.DirectionalLight(direction=(0.5, -1, -0.7), intensity=2.0, color=(0.6, 0.8, 1)),
    ]
    return scene, lights


def test_direct_light_of_three_light_types_adds_up(tmp_path, renderer):
    scene, lights = three_light_scene(tmp_path)
    cam = vsgl.Camera.look_at(eye=(1.5, 2.0, 3.0), target=(0, 0.5, 0), fov_y_deg=60)
    scene.lights = lights
    together = renderer.render(scene, camera=cam, method="direct").aov("direct").astype(np.float64)
    parts = []
    for light in lights:
        scene.lights = [light]
        parts.append(renderer.render(scene, camera=cam, method="direct").aov("direct").astype(np.float64))
    assert all(p.max() > 0.05 * together.max() for p in parts), "every light must contribute"
    # Same per-light terms, summed in another order: equal to float rounding.
    np.testing.assert_allclose(together, sum(parts), rtol=1e-5, atol=1e-6 * together.max())


def test_reference_indirect_light_of_three_light_types_adds_up(tmp_path, renderer):
    """The every-texel reference sums each light's RSMs (one spot, six point faces, one
    orthographic): three lights together give the sum of the three alone."""
    scene, lights = three_light_scene(tmp_path)
    cam = vsgl.Camera.look_at(eye=(1.5, 2.0, 3.0), target=(0, 0.5, 0), fov_y_deg=60)
    scene.lights = lights
    together = renderer.render(scene, camera=cam, method="reference", rsm_size=32).aov("indirect").astype(np.float64)
    parts = []
    for light in lights:
        scene.lights = [light]
        parts.append(renderer.render(scene, camera=cam, method="reference", rsm_size=32).aov("indirect").astype(np.float64))
    assert all(p.max() > 0.05 * together.max() for p in parts), "every light must contribute"
    np.testing.assert_allclose(together, sum(parts), rtol=1e-4, atol=1e-5 * together.max())


def test_pathtrace_of_three_light_types_adds_up_within_its_error(tmp_path, renderer):
    scene, lights = three_light_scene(tmp_path)
    cam = vsgl.Camera.look_at(eye=(1.5, 2.0, 3.0), target=(0, 0.5, 0), fov_y_deg=60)
    scene.lights = lights
    opts = dict(method="pathtrace", spp=16)
    f = renderer.render(scene, camera=cam, seed=1, **opts)
    together, var = f.image.astype(np.float64), f.aov("stderr").astype(np.float64) ** 2
    total = np.zeros_like(together)
    for i, light in enumerate(lights):
        scene.lights = [light]
        g = renderer.render(scene, camera=cam, seed=10 + i, **opts)
        total += g.image
        var += g.aov("stderr").astype(np.float64) ** 2
    lit = var > 0
    assert lit.mean() > 0.5
    # Independent estimates: the difference has variance Σσ². Over all pixels the mean
    # difference is within 3σ of its own standard error, and per pixel at most 1% exceed 4σ.
    diff = together - total
    assert abs(diff[lit].mean()) < 3.0 * math.sqrt(var[lit].sum()) / lit.sum()
    assert (np.abs(diff[lit]) > 4.0 * np.sqrt(var[lit])).mean() < 0.01


# ------------------------------------------------------------------------------------------
# NaN / Inf safety
# ------------------------------------------------------------------------------------------


def _assert_finite(frame: vsgl.Frame) -> None:
    for name in frame.aovs:
        assert np.isfinite(frame.aov(name)).all(), f"AOV {name} has NaN/Inf"


@pytest.mark.parametrize("method", ["direct", "pathtrace"])
def test_awkward_light_placements_are_finite(tmp_path, renderer, method):
    opts = {"spp": 2} if method == "pathtrace" else {}
    scene = vsgl.scenes.cornell_box()
    cam = scene.cameras[0] if scene.cameras else None
    # A point light inside the tall block (x ∈ [−0.65, −0.05], y ∈ [0, 1.2], z ∈ [−0.6, 0]).
    scene.lights = [vsgl.PointLight(position=(-0.35, 0.6, -0.3), intensity=5.0)]
    _assert_finite(renderer.render(scene, camera=cam, method=method, **opts))
    # A point light exactly at the camera, and one on a wall (x = 1 is a wall of the box).
    eye = (0.0, 1.0, 1.5)
    at_eye = vsgl.Camera.look_at(eye=eye, target=(0, 1, 0), fov_y_deg=60)
    for position in [eye, (1.0, 1.0, 0.0), (-1.0, 1.0, 0.0)]:
        scene.lights = [vsgl.PointLight(position=position, intensity=5.0)]
        _assert_finite(renderer.render(scene, camera=at_eye, method=method, **opts))
    # A directional light parallel to the floor and the back wall, and one along a wall's normal.
    for direction in [(1, 0, 0), (0, -1, 0), (0, 0, -1)]:
        scene.lights = [vsgl.DirectionalLight(direction=direction, intensity=2.0)]
        _assert_finite(renderer.render(scene, camera=at_eye, method=method, **opts))


# ------------------------------------------------------------------------------------------
# Point lights in the virtual-light methods: six cube-face RSMs
# ------------------------------------------------------------------------------------------


@pytest.mark.parametrize("rsm_size", [32, 64])
def test_point_light_rsm_flux_adds_up_to_4pi_i_in_a_closed_box(tmp_path, renderer, rsm_size):
    rho, intensity = 0.6, 5.0
    scene = box_scene(tmp_path, occluders=False, rho=rho)
    # Off-centre, so the faces see the walls at different distances and angles.
    scene.lights = [vsgl.PointLight(position=(0.1, -0.2, 0.15), intensity=intensity)]
    frame = renderer.render(scene, method="vpl", num_lights=16, rsm_size=rsm_size, capture_rsm=True)
    flux = frame.rsm("flux_diffuse")
    assert flux.shape == (6 * rsm_size, rsm_size, 3), "the six cube faces, stacked"
    # Every direction meets a wall: the RSM texels' flux sums to the light's power 4π·I,
    # times the walls' R_d.
    np.testing.assert_allclose(flux.astype(np.float64).sum(axis=(0, 1)), rho * 4.0 * math.pi * intensity, rtol=0.005)


def test_point_light_indirect_light_of_reference_agrees_with_the_path_tracer(tmp_path, make_renderer):
    """In a closed convex box nothing occludes a bounce, so the every-texel `reference` (made
    from the six face RSMs) and the path tracer (no RSM at all) estimate the same integral."""
    scene = box_scene(tmp_path, occluders=False)
    scene.lights = [vsgl.PointLight(position=(0.1, -0.2, 0.15), intensity=5.0)]
    cam = vsgl.Camera.look_at(eye=(0.5, 0.5, 0.9), target=(-1, -0.5, -1), fov_y_deg=70)
    r = make_renderer(32, 24)
    ref = r.render(scene, camera=cam, method="reference", rsm_size=64).aov("indirect").astype(np.float64)
    pt = r.render(scene, camera=cam, method="pathtrace", spp=64)
    est, err = pt.aov("indirect").astype(np.float64), pt.aov("stderr").astype(np.float64)
    # Mean over the image: the path tracer's own error of the mean is ~0.1%; the reference's
    # discretisation (64² texels per face) is below 1%.
    assert abs(ref.mean() / est.mean() - 1.0) < 0.01 + 3.0 * math.sqrt((err**2).sum()) / err.size / est.mean()
    # Per wall region too: quarters of the image within 3%.
    h, w = ref.shape[:2]
    for ys in (slice(0, h // 2), slice(h // 2, h)):
        for xs in (slice(0, w // 2), slice(w // 2, w)):
            assert ref[ys, xs].mean() == pytest.approx(est[ys, xs].mean(), rel=0.03)


def test_vpl_with_a_point_light_converges_to_the_reference(tmp_path, renderer):
    scene = box_scene(tmp_path, occluders=False)
    scene.lights = [vsgl.PointLight(position=(0.1, -0.2, 0.15), intensity=5.0)]
    cam = vsgl.Camera.look_at(eye=(0.5, 0.5, 0.9), target=(-1, -0.5, -1), fov_y_deg=70)
    ref = renderer.render(scene, camera=cam, method="reference", rsm_size=32).aov("indirect").astype(np.float64)
    # Same RSM: VPLs importance-sampled from it are an unbiased estimate of the reference sum.
    vpl = np.mean([renderer.render(scene, camera=cam, method="vpl", num_lights=1024, rsm_size=32, seed=s).aov("indirect") for s in range(4)], axis=0)
    assert vpl.mean() == pytest.approx(ref.mean(), rel=0.01)


def _face_powers(frame: vsgl.Frame, views: int) -> np.ndarray:
    """The power each captured RSM view reflects: the sum of its texels' sampling weights
    (views stacked along the first axis)."""
    weight = np.asarray(frame.rsm("weight"), np.float64)
    return weight.reshape(views, -1).sum(axis=1)


@pytest.mark.parametrize("method", ["vpl", "vsgl"])
@pytest.mark.parametrize("num_lights", [600, 64, 7])
def test_virtual_light_budget_is_split_over_lights_and_faces_by_rsm_power(tmp_path, renderer, method, num_lights):
    """num_lights is the frame's total: every RSM (the spot's, the point light's six faces)
    gets 1 + its power's share of the rest, the shares adding up to num_lights."""
    scene = box_scene(tmp_path, occluders=False)
    spot = vsgl.SpotLight(position=(0, 0.9, 0), direction=(0, -1, 0), intensity=3.0)
    # Off centre, so the faces' powers differ (the near walls reflect more).
    point = vsgl.PointLight(position=(0.5, -0.6, 0.15), intensity=5.0)
    cam = vsgl.Camera.look_at(eye=(0.5, 0.5, 0.9), target=(-1, -0.5, -1), fov_y_deg=70)
    opts = dict(method=method, num_lights=num_lights, rsm_size=32, capture_rsm=True)
    scene.lights = [point, spot]
    frame = renderer.render(scene, camera=cam, **opts)
    faces, spot_share = frame.settings["virtual_lights_per_light"]
    shares = faces + spot_share
    powers = list(_face_powers(frame, 6))
    _assert_finite(frame)
    assert frame.aov("indirect").max() > 0
    scene.lights = [spot, point]
    swapped = renderer.render(scene, camera=cam, **opts)
    powers.append(_face_powers(swapped, 1)[0])
    spot_first, rest = swapped.settings["virtual_lights_per_light"]
    assert spot_first + rest == shares[-1:] + shares[:-1], "the split depends on the lights' order"
    assert len(shares) == 7 and sum(shares) == num_lights
    powers = np.array(powers)
    assert np.all(powers > 0) and powers.max() > 1.5 * powers.min(), f"test scene should have unequal face powers: {powers}"
    expected = 1 + (num_lights - 7) * powers / powers.sum()
    assert np.all(np.abs(np.array(shares) - expected) < 1), f"shares {shares} not ~ 1 + power share {expected.round(2)}"


@pytest.mark.parametrize("method", ["vpl", "vsgl"])
def test_cube_faces_that_see_nothing_are_left_out_and_lose_no_light(tmp_path, renderer, method):
    """A point light 1 m above a 1 m floor with a low wall: all the geometry lies in the cone
    |y| > |x|, |z| below the light, so only the −y face's RSM reflects light. The other five
    get no virtual lights and no pass; the image still agrees with `reference`, which renders
    every face."""
    floor = dict(corners=[(-0.5, 0.0, -0.5), (-0.5, 0.0, 0.5), (0.5, 0.0, 0.5), (0.5, 0.0, -0.5)], base_color=(0.7, 0.7, 0.7), specular=0.0)
    wall = dict(corners=[(0.3, 0.0, -0.3), (0.3, 0.0, 0.3), (0.3, 0.35, 0.3), (0.3, 0.35, -0.3)], base_color=(0.5, 0.6, 0.7), specular=0.0)
    scene = vsgl.Scene.load(write_quads(tmp_path, [floor, wall], name="floor_wall.gltf"))
    scene.lights = [vsgl.PointLight(position=(0.0, 1.0, 0.0), intensity=4.0)]
    cam = vsgl.Camera.look_at(eye=(-1.2, 0.8, 1.0), target=(0.0, 0.1, 0.0), fov_y_deg=50)  # sees the wall's lit side
    n = 256
    frame = renderer.render(scene, camera=cam, method=method, num_lights=n, rsm_size=32, seed=0)
    assert frame.settings["virtual_lights_per_light"] == [[0, 0, 0, n, 0, 0]]
    left_out = [what for what in frame.skipped if what.startswith("virtual lights of light 0 view")]
    assert sorted(left_out) == [f"virtual lights of light 0 view {v}" for v in (0, 1, 2, 4, 5)]
    _assert_finite(frame)
    assert frame.aov("indirect").mean() > 0
    if method == "vpl":
        # Importance-sampled from the same RSMs, so unbiased: the mean over seeds agrees with
        # the every-texel sum over all six faces (per-seed spread 0.3% at 1024: 4 seeds, 0.16%).
        ref = renderer.render(scene, camera=cam, method="reference", rsm_size=32).aov("indirect").astype(np.float64)
        got = np.mean([renderer.render(scene, camera=cam, method="vpl", num_lights=1024, rsm_size=32, seed=s).aov("indirect") for s in range(4)], axis=0)
        assert got.mean() == pytest.approx(ref.mean(), rel=0.01)
    # (VSGLs sit ~35% under the reference here, with a spot light in the point light's place
    # too: their kernels blur the floor–wall contact; that bias is the kernels', not the split's.)


@pytest.mark.parametrize("method,low", [("vsgl", 0.8), ("vsgl2", 0.55)])
def test_vsgl_methods_light_a_box_from_a_point_light(tmp_path, make_renderer, method, low):
    """A smoke check, not an accuracy test: VSGLs approximate, and in this box they come out
    low against `reference` (measured: vsgl 0.87, vsgl2 0.69 — two VSGLs per cube face; for
    an upward spot light of 89° at the same place 0.89 and 0.84). Missing cube faces are
    caught by the flux and path-tracer tests above, not here."""
    scene = box_scene(tmp_path, occluders=False)
    cam = vsgl.Camera.look_at(eye=(0.5, 0.5, 0.9), target=(-1, -0.5, -1), fov_y_deg=70)
    r = make_renderer(32, 24)
    scene.lights = [vsgl.PointLight(position=(0.1, -0.2, 0.15), intensity=5.0)]
    ref = r.render(scene, camera=cam, method="reference", rsm_size=64).aov("indirect").mean()
    opts = dict(num_lights=1024, rsm_size=64) if method == "vsgl" else dict(rsm_size=64)
    got = r.render(scene, camera=cam, method=method, **opts).aov("indirect").mean()
    assert low * ref < got < 1.05 * ref


# ------------------------------------------------------------------------------------------
# Directional lights in the virtual-light methods: one orthographic RSM
# ------------------------------------------------------------------------------------------

# Margin of the directional light's orthographic box over the scene's bounding sphere
# (DIRECTIONAL_BOX_MARGIN in crates/vsgl-core/src/frame/uniforms.rs): the RSM's half-width is
# R = 0.5 · 1.01 · (diagonal of the scene bounds).
BOX_MARGIN = 1.01


@pytest.mark.parametrize("rsm_size", [32, 64])
def test_directional_light_rsm_flux_is_rho_e_times_the_lit_area(tmp_path, renderer, rsm_size):
    """A square of side 2a facing the light straight down receives E·(2a)² (the flux through
    its cross-section), so its RSM texels sum to ρ·E·A. The scene's bounds are set by a small
    quad hidden in the square's shadow, at the depth h that makes the square's edges fall on
    texel edges (a = N/4 texels of 2R/N), so the texel count is exact and any error in texel
    area, ray direction or the origin of the rays shows."""
    rho, e, a = 0.6, 3.0, 1.0
    # R = a·N/(2k) with k = N/4 texels per half side: R = 2a, and 0.5·1.01·√(8a² + h²) = R.
    r = 2.0 * a
    h = math.sqrt((2.0 * r / BOX_MARGIN) ** 2 - 8.0 * a * a)
    quads = [
        square((0, 0, 0), (0, 1, 0), a, base_color=(rho, rho, rho), name="lit"),
        square((0, -h, 0), (0, 1, 0), 0.1 * a, base_color=(rho, rho, rho), name="hidden"),
    ]
    scene = vsgl.Scene.load(write_quads(tmp_path, quads, name="directional_plane.gltf"))
    scene.lights = [vsgl.DirectionalLight(direction=(0, -1, 0), intensity=e)]
    cam = vsgl.Camera.look_at(eye=(0, 2, 0.5), target=(0, 0, 0), fov_y_deg=60)
    frame = renderer.render(scene, camera=cam, method="vpl", num_lights=16, rsm_size=rsm_size, capture_rsm=True)
    flux = frame.rsm("flux_diffuse").astype(np.float64)
    assert flux.shape == (rsm_size, rsm_size, 3)
    lit = flux.sum(axis=2) > 0
    assert lit.sum() == (rsm_size // 2) ** 2, "the square covers (N/2)² texels"
    np.testing.assert_allclose(flux.sum(axis=(0, 1)), rho * e * (2 * a) ** 2, rtol=0.005)
    # Positions are relative to the RSM's image plane, R above the bounds' centre (y = −h/2)
    # along the light: the lit square is at depth R − h/2 below it.
    pos = frame.rsm("position")[lit]
    np.testing.assert_allclose(pos[:, 1], -(r - h / 2), rtol=1e-4)
    # … and span it: texel centres from −a + R/N to a − R/N across (rays parallel, starting on
    # the image plane, not all at its centre).
    for k in (0, 2):
        np.testing.assert_allclose([pos[:, k].min(), pos[:, k].max()], [-a + r / rsm_size, a - r / rsm_size], atol=1e-4)


def open_box_scene(tmp_path, rho: float = 0.6, metal_floor: bool = False) -> vsgl.Scene:
    """box_scene without its top wall (y = +H): a convex open box, so nothing occludes a
    bounce inside it, and a directional light from above lights the floor and a wall. With
    `metal_floor` the floor is a rough metal (all its reflection is the GGX lobe, whose
    direction depends on where the light comes from)."""
    def material(k, s):
        return {"metallic": 1.0, "roughness": 0.4} if metal_floor and (k, s) == (1, -1.0) else {}
    quads = [square(s * H * AXES[k], -s * AXES[k], H, base_color=(rho, rho, rho), name=f"wall{k}{s:+.0f}", **material(k, s)) for k, s in FACES if (k, s) != (1, 1.0)]
    return vsgl.Scene.load(write_quads(tmp_path, quads, name="open_box.gltf"))


SUN = (0.45, -1.0, 0.3)  # into the open top, slanted: the box's walls cast shadows on the floor
BOX_CAMERA = dict(eye=(0.5, 0.5, 0.9), target=(-1, -0.5, -1), fov_y_deg=70)


@pytest.mark.parametrize("metal_floor", [False, True])
def test_directional_light_indirect_light_of_reference_agrees_with_the_path_tracer(tmp_path, make_renderer, metal_floor):
    """The every-texel `reference` from the orthographic RSM against the path tracer (no RSM):
    in the convex open box nothing occludes a bounce, so both estimate the same integral. The
    sun is slanted, so the walls shadow part of the floor and the outer faces of two walls are
    lit too (their light goes outwards: none of it may reach the inside)."""
    scene = open_box_scene(tmp_path, metal_floor=metal_floor)
    scene.lights = [vsgl.DirectionalLight(direction=SUN, intensity=3.0)]
    # The metal floor's glossy reflection of the sun goes up towards +x, +z: look there.
    cam = vsgl.Camera.look_at(eye=(-0.6, 0.2, -0.6), target=(1, 0.6, 1), fov_y_deg=70) if metal_floor else vsgl.Camera.look_at(**BOX_CAMERA)
    r = make_renderer(32, 24)
    ref = r.render(scene, camera=cam, method="reference", rsm_size=64).aov("indirect").astype(np.float64)
    pt = r.render(scene, camera=cam, method="pathtrace", spp=512)
    est, err = pt.aov("indirect").astype(np.float64), pt.aov("stderr").astype(np.float64)
    sigma = math.sqrt((err**2).sum()) / err.size
    print("reference/pathtrace", ref.mean() / est.mean(), "sigma/mean", sigma / est.mean())
    assert ref.mean() > 0
    # As for the point light: 3σ of the path tracer's image mean plus 1% for the reference's
    # discretisation (64² texels). Measured: 0.998 (diffuse) and 0.999 (metal floor), σ ≈ 0.14%
    # and 0.43% of the mean.
    assert abs(ref.mean() - est.mean()) < 3.0 * sigma + 0.01 * est.mean(), (ref.mean(), est.mean(), sigma)
    h, w = ref.shape[:2]
    for ys in (slice(0, h // 2), slice(h // 2, h)):
        for xs in (slice(0, w // 2), slice(w // 2, w)):
            assert ref[ys, xs].mean() == pytest.approx(est[ys, xs].mean(), rel=0.05)


@pytest.mark.parametrize("method,low", [("vpl", 0.98), ("vsgl", 0.75), ("vsgl2", 0.5)])
def test_virtual_light_methods_render_a_directional_light(tmp_path, make_renderer, method, low):
    """vpl converges to `reference`; for the VSGL methods a smoke range, not an accuracy test
    (measured with the sun straight down: vpl 1.001, vsgl 0.83, vsgl2 0.57 of reference; a spot
    light straight down at the same box: vsgl 0.82, vsgl2 0.89). With the slanted SUN the VSGLs
    come out high (vsgl 2.06, vsgl2 1.66; a spot light from the same direction: 1.57, 1.26):
    clusters mixing the lit outer wall faces with the floor leak the outer faces' light in."""
    scene = open_box_scene(tmp_path)
    scene.lights = [vsgl.DirectionalLight(direction=(0, -1, 0), intensity=3.0)]
    cam = vsgl.Camera.look_at(**BOX_CAMERA)
    r = make_renderer(32, 24)
    ref = r.render(scene, camera=cam, method="reference", rsm_size=64).aov("indirect").mean()
    opts = dict(num_lights=1024, rsm_size=64) if method != "vsgl2" else dict(rsm_size=64)
    frame = r.render(scene, camera=cam, method=method, **opts)
    _assert_finite(frame)
    got = frame.aov("indirect").mean()
    assert low * ref < got < (1.02 if method == "vpl" else 1.05) * ref


def test_vsgl_glossy_lobes_of_a_directional_light_face_the_light(tmp_path, make_renderer):
    """The VSGL moments' GGX lobe of each RSM texel is fitted for light arriving from
    −direction (rsm_lobe_means with the light's direction): vsgl against `reference` for a
    metal floor's glossy bounce of the slanted sun. Measured 0.937; with the lobes fitted for
    light from the RSM's image-plane centre instead (the spot/point rule) 0.882. VSGLs are an
    approximation: this is a regression range, tight on purpose."""
    scene = open_box_scene(tmp_path, metal_floor=True)
    scene.lights = [vsgl.DirectionalLight(direction=SUN, intensity=3.0)]
    cam = vsgl.Camera.look_at(eye=(-0.6, 0.2, -0.6), target=(1, 0.6, 1), fov_y_deg=70)
    r = make_renderer(32, 24)
    ref = r.render(scene, camera=cam, method="reference", rsm_size=64).aov("indirect").mean()
    got = r.render(scene, camera=cam, method="vsgl", num_lights=1024, rsm_size=64).aov("indirect").mean()
    assert 0.91 * ref < got < 1.05 * ref


def test_the_shared_lights_spot_scene_renders_all_three_spots(shared_scenes, renderer):
    # LightsSpot (three coloured spots) renders all three: the frame is
    # the sum of the three one-light frames, each of which lights something.
    path = str(shared_scenes / "LightsSpot" / "LightsSpot.gltf")
    scene = vsgl.Scene.load(path)
    assert scene.stats["lights_by_type"] == {"spot": 3, "point": 0, "directional": 0}
    full = renderer.render(scene, method="direct", aovs=["image"]).image
    parts = []
    for light in scene.lights:
        one = vsgl.Scene.load(path)
        one.lights = [light]
        parts.append(renderer.render(one, method="direct", aovs=["image"]).image)
    assert all(p.max() > 0 for p in parts), "a spot lights nothing"
    np.testing.assert_allclose(sum(parts), full, rtol=1e-6, atol=1e-7 * float(full.max()))


# ------------------------------------------------------------------------------------------
# Lights from the command line (`--light`, vsgl.lightspec)
# ------------------------------------------------------------------------------------------


def test_light_specs_make_each_light_type():
    from vsgl.lightspec import parse_light

    spot = parse_light("spot position=0,1.9,0.5 direction=0,-1,0 intensity=20 color=1,0.5,0.25 inner_cone_deg=10 outer_cone_deg=25")
    assert isinstance(spot, vsgl.SpotLight)
    assert spot.position == pytest.approx((0, 1.9, 0.5)) and spot.direction == pytest.approx((0, -1, 0))
    assert (spot.intensity, spot.inner_cone_deg, spot.outer_cone_deg) == pytest.approx((20, 10, 25))
    assert spot.color == pytest.approx((1, 0.5, 0.25))
    point = parse_light("  point   intensity=3.5 position=-1,2,3e-1 ")
    assert isinstance(point, vsgl.PointLight) and point.position == pytest.approx((-1, 2, 0.3)) and point.intensity == 3.5
    sun = parse_light("directional direction=0,-2,0 intensity=7")
    assert isinstance(sun, vsgl.DirectionalLight) and sun.direction == pytest.approx((0, -1, 0)) and sun.color == pytest.approx((1, 1, 1))


@pytest.mark.parametrize(
    "text,says",
    [
        ("", "first word must be the type"),
        ("lamp position=0,0,0 intensity=1", "'lamp'"),
        ("point position=0,1 intensity=1", "position needs three numbers"),
        ("point position=0,1,0", "needs intensity"),
        ("point position=0,1,0 intensity=1 direction=0,-1,0", "no field 'direction'"),
        ("point position=0,1,0 intensity=x", "intensity='x' is not a number"),
        ("point position=0,1,0 intensity=1 intensity=2", "intensity is given twice"),
        ("point position=0,1,0 intensity", "expected name=value"),
        ("directional direction=0,0,0 intensity=1", "direction"),
        ("spot position=0,1,0 direction=0,-1,0 intensity=-1", "intensity"),
    ],
)
def test_bad_light_specs_name_what_is_wrong(text, says):
    from vsgl.lightspec import parse_light

    with pytest.raises(ValueError, match=f"light {text!r}" if text else "light ''") as e:
        parse_light(text)
    assert says in str(e.value)


@pytest.mark.gpu
def test_cli_lights_a_scene_with_every_light_type(tmp_path):
    import subprocess
    import sys

    out = tmp_path / "lit.npy"
    args = [sys.executable, "-m", "vsgl", "render", "cornell_box", "--method", "vpl", "--size", "24x16", "--lights", "32", "--rsm-size", "32",
            "--no-error", "--no-scene-lights", "--light", "point position=0,1,0 intensity=3",
            "--light", "directional direction=0.2,-1,-0.3 intensity=2", "-o", str(out)]
    run = subprocess.run(args, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert "lights    1 point, 1 directional" in run.stdout
    assert np.load(out).mean() > 0
    dark = subprocess.run(args[:args.index("--light")] + ["-o", str(tmp_path / "dark.npy")], capture_output=True, text=True, timeout=300)
    assert "lights    none" in dark.stdout and "no light" in dark.stdout
    bad = subprocess.run(args[:-2] + ["--light", "point position=0,1 intensity=3"], capture_output=True, text=True, timeout=300)
    assert bad.returncode == 2 and "argument --light" in bad.stderr and "three numbers" in bad.stderr
