"""Emissive surfaces as area lights in the path tracer: the direct light of an emissive square
against the closed-form form factor, its bounce by every strategy alike, and the leave-out rule
for scenes without emission (docs/scenes.md, "Emission")."""

from __future__ import annotations

import math

import numpy as np
import pytest

import scene_builders as sb
import vsgl

# The emitter: a unit square at height H over the floor's centre, facing down, radiance L_E.
H = 1.0
L_E = 3.0
FLOOR_ALBEDO = 0.8


def _corner_form_factor(x: float, y: float) -> float:
    """Form factor from a differential area to a parallel rectangle of sides x, y (in units of
    the height) with one corner straight above it (Howell's catalogue, configuration B-3;
    odd in each side, so rectangles not over the point follow by inclusion-exclusion)."""
    ax, ay = math.sqrt(1 + x * x), math.sqrt(1 + y * y)
    return (x / ax * math.atan(y / ax) + y / ay * math.atan(x / ay)) / (2 * math.pi)


def square_irradiance(px: float, pz: float, half: float = 0.5, h: float = H, radiance: float = L_E) -> float:
    """Irradiance at floor point (px, 0, pz) from a Lambertian square [-half, half]² at height h:
    E = π L F, F by inclusion-exclusion over the four corner rectangles."""
    xs = ((half - px) / h, (-half - px) / h)
    zs = ((half - pz) / h, (-half - pz) / h)
    f = sum(sx * sz * _corner_form_factor(x, z) for x, sx in zip(xs, (1, -1)) for z, sz in zip(zs, (1, -1)))
    return math.pi * radiance * f


def emitter_over_floor(directory, *, wall: bool = False, half: float = 0.5) -> vsgl.Scene:
    """A 6 × 6 Lambertian floor (y = 0, albedo 0.8, no specular), a black square of side
    2·``half`` at y = H facing down that emits L_E, and with ``wall`` a grey wall at z = −1
    facing the light."""
    e = half
    quads = [
        dict(corners=[(-3, 0, -3), (-3, 0, 3), (3, 0, 3), (3, 0, -3)], name="floor", base_color=(FLOOR_ALBEDO,) * 3, specular=0.0),
        dict(corners=[(-e, H, -e), (e, H, -e), (e, H, e), (-e, H, e)], name="glow", base_color=(0.0,) * 3, specular=0.0),
    ]
    if wall:
        quads.append(dict(corners=[(-3, 0, -1), (3, 0, -1), (3, 3, -1), (-3, 3, -1)], name="wall", base_color=(0.6,) * 3, specular=0.0))
    scene = vsgl.Scene.load(sb.write_quads(directory, quads))
    scene.set_material("materials[1]", emissive=(L_E, L_E, L_E))
    return scene


# Straight down at the floor's centre from under the emitter (y = H/2): the image is the floor
# around the centre, where the irradiance is symmetric in x and z (so the image's orientation
# does not matter).
FOV_DEG = 60.0
DOWN = vsgl.Camera.look_at(eye=(0.0, 0.5 * H, 0.0), target=(0.0, 0.0, 0.0), up=(0.0, 0.0, -1.0), fov_y_deg=FOV_DEG)


def expected_floor_radiance(size: int) -> np.ndarray:
    """The floor's reflected direct radiance ρ E / π at each pixel centre of DOWN."""
    half_width = 0.5 * H * math.tan(math.radians(FOV_DEG) / 2)
    c = (2 * (np.arange(size) + 0.5) / size - 1) * half_width
    return np.array([[FLOOR_ALBEDO / math.pi * square_irradiance(x, z) for x in c] for z in c])


@pytest.mark.parametrize("strategy", ["camera", "bidirectional"])
def test_an_emissive_square_lights_the_floor_as_its_form_factor_says(tmp_path, make_renderer, strategy):
    size = 16
    scene = emitter_over_floor(tmp_path)
    f = make_renderer(size, size).render(scene, DOWN, method="pathtrace", spp=256, strategy=strategy, aovs=["direct"])
    got = f.aov("direct")[..., 0].astype(np.float64)
    want = expected_floor_radiance(size)
    # 1% on the image's mean; the per-pixel Monte Carlo error of 256 samples is a few percent.
    assert got.mean() / want.mean() == pytest.approx(1.0, abs=0.01), (got.mean(), want.mean())
    assert np.abs(got / want - 1).max() < 0.15
    # The camera sees the floor only: the direct light is grey, as the emitter and the floor are.
    np.testing.assert_allclose(f.aov("direct")[..., 1], f.aov("direct")[..., 0], rtol=1e-6)


def test_the_emitting_side_is_the_one_the_normals_point_to(tmp_path, make_renderer):
    # The same square with its vertex normals flipped up: it emits away from the floor, which
    # stays dark (a one-sided emitter, as a glTF front face and Mitsuba's area emitter).
    quads = [
        dict(corners=[(-3, 0, -3), (-3, 0, 3), (3, 0, 3), (3, 0, -3)], name="floor", specular=0.0),
        dict(corners=[(-0.5, H, -0.5), (-0.5, H, 0.5), (0.5, H, 0.5), (0.5, H, -0.5)], name="glow", base_color=(0.0,) * 3, specular=0.0),
    ]
    scene = vsgl.Scene.load(sb.write_quads(tmp_path, quads))
    scene.set_material("materials[1]", emissive=(L_E, L_E, L_E))
    r = make_renderer(8, 8)
    for method, kw in (("pathtrace", dict(spp=16, strategy="camera")), ("vsgl", dict(num_lights=64, rsm_size=32))):
        f = r.render(scene, DOWN, method=method, aovs=["direct", "indirect"], **kw)
        assert not f.aov("direct").any() and not f.aov("indirect").any(), method
        # Nothing lies in front of the emitter (the top of the scene's bounds): the frame says
        # why the scene is dark.
        assert len(f.warnings) == 1 and "nothing lies in front of its emissive surfaces" in f.warnings[0], f.warnings


def test_every_strategy_finds_the_same_bounce_of_an_emitter(tmp_path, make_renderer):
    # The wall's reflection of the emitter's light onto the floor: camera paths reach it by
    # next-event estimation at the wall, light tracing by photons from the emitter, and the
    # bidirectional mix by both with MIS weights. Their means agree within their errors. A
    # small emitter (area 1/4: each triangle's point density 4, not 1) so a density left out of
    # one side of the MIS weights shows.
    scene = emitter_over_floor(tmp_path, wall=True, half=0.25)
    cam = vsgl.Camera.look_at(eye=(0.0, 1.6, 2.5), target=(0.0, 0.3, -0.5), fov_y_deg=60.0)
    _assert_strategies_agree(make_renderer(16, 16), scene, cam, spp=64)


def _assert_strategies_agree(r: vsgl.Renderer, scene: vsgl.Scene, cam: vsgl.Camera, spp: int) -> None:
    """The mean indirect light of the light and bidirectional strategies within 4 standard
    errors (plus 1%) of camera paths'."""
    means, errors = {}, {}
    for strategy in ("camera", "light", "bidirectional"):
        f = r.render(scene, cam, method="pathtrace", spp=spp, strategy=strategy, aovs=["indirect", "stderr"])
        ind = f.aov("indirect")
        means[strategy] = float(ind.mean())
        errors[strategy] = float(np.sqrt((f.aov("stderr") ** 2).sum()) / ind.size)
    assert means["camera"] > 0, means
    for strategy in ("light", "bidirectional"):
        tolerance = 4 * math.hypot(errors["camera"], errors[strategy]) + 0.01 * means["camera"]
        assert abs(means[strategy] - means["camera"]) < tolerance, (means, errors)


def test_every_strategy_finds_the_same_glossy_bounce_of_a_small_emitter(tmp_path, make_renderer):
    # The floor's glossy reflection of the small emitter's light, seen in the wall's bounce and
    # the wall's light reflected in the floor: three camera-side ways to reach the emitter
    # (next-event estimation, the BSDF-sampled ray, and both against photons in bidirectional
    # mode) must agree, which they do only if every strategy's density is in every weight.
    scene = sb.glossy_floor_under_small_emitter(tmp_path, 0.2)
    _assert_strategies_agree(make_renderer(16, 16), scene, sb.GLOSSY_FLOOR_VIEW, spp=128)


def test_bsdf_sampling_finds_a_small_emitters_reflection_in_a_glossy_floor(tmp_path, make_renderer):
    # A 0.2 m emitter mirrored in a metal floor of roughness 0.05: its reflection is a lobe far
    # narrower than the emitter's solid angle, so a point drawn on the emitter by area seldom
    # lands in it, and next-event estimation alone gave fireflies (per-pixel noise over seeds
    # 1.47 of the mean at 48², 16 spp; experiments/emitter_bsdf_sampling.md). The BSDF-sampled
    # ray finds it (0.078), and it keeps its mean: the power-heuristic weights of the two sum to
    # one (the glossy direct light against the 64-point quadrature of emitter_lights at
    # roughness 0.2, where the quadrature resolves the lobe: measured 1.002).
    r = make_renderer(24, 24)
    sharp = sb.glossy_floor_under_small_emitter(tmp_path, 0.05)
    frames = np.stack([r.render(sharp, sb.GLOSSY_FLOOR_VIEW, method="pathtrace", spp=16, seed=s, aovs=["direct"]).aov("direct")
                       for s in range(4)]).astype(np.float64)
    noise = frames.std(axis=0, ddof=1).mean() / frames.mean()
    assert noise < 0.3, noise
    glossy = sb.glossy_floor_under_small_emitter(tmp_path, 0.2)
    pt = r.render(glossy, sb.GLOSSY_FLOOR_VIEW, method="pathtrace", spp=512, aovs=["direct"]).aov("direct").astype(np.float64)
    quadrature = r.render(glossy, sb.GLOSSY_FLOOR_VIEW, method="direct", emitter_lights=1, aovs=["direct"]).aov("direct").astype(np.float64)
    assert pt.mean() / quadrature.mean() == pytest.approx(1.0, abs=0.01), (pt.mean(), quadrature.mean())


def test_a_scene_without_emission_leaves_the_emitter_code_out(tmp_path, make_renderer):
    r = make_renderer(8, 8)
    f = r.render(vsgl.scenes.cornell_box(), method="pathtrace", spp=2, strategy="camera", aovs=["image"])
    assert f.settings["emitters"] == 0 and "emissive" in f.skipped["emission"]
    # The emissive square is two triangles, each an emitter.
    f = r.render(emitter_over_floor(tmp_path), DOWN, method="pathtrace", spp=2, strategy="camera", aovs=["image"])
    assert f.settings["emitters"] == 2 and "emission" not in f.skipped


# --- The other methods: emissive surfaces as clusters of lights (option emitter_lights) -------

@pytest.mark.slow
def test_emitter_lights_light_the_floor_as_the_form_factor_says(tmp_path, make_renderer):
    # Each cluster is shadowed like a point light but lit from its patches: its direct light is
    # a 64-point midpoint rule over its area. At a receiver as far from the unit square as it
    # is wide (the hardest case short of touching) one light is within 0.3% of the form factor
    # (the cluster's centre alone, a point light, was 1.27 of it on average). The issue's
    # bounds: `reference` within 1%, `vsgl` (interleave 1) within 5%.
    size = 16
    scene = emitter_over_floor(tmp_path)
    want = expected_floor_radiance(size)
    r = make_renderer(size, size)
    for method, kw in (("direct", {}), ("reference", dict(rsm_size=32)), ("vsgl", dict(interleave=1, denoise=False))):
        for lights in (1, 4, 16):
            f = r.render(scene, DOWN, method=method, emitter_lights=lights, aovs=["direct"], **kw)
            got = f.aov("direct")[..., 0].astype(np.float64)
            assert got.mean() / want.mean() == pytest.approx(1.0, abs=0.01), (method, lights, got.mean() / want.mean())
            assert np.abs(got / want - 1).max() < 0.02, (method, lights)
    assert f.settings["emitter_lights"] == 16
    assert r.render(scene, DOWN, method="vsgl", aovs=[]).settings["emitter_lights"] == 1


def test_a_punctual_light_and_an_emitter_add_up(tmp_path, make_renderer):
    # Light is linear: a frame lit by a point light and the emitter together is the sum of the
    # frame lit by each alone (deterministic methods: within float rounding; stochastic ones in
    # the mean).
    scene = emitter_over_floor(tmp_path, wall=True)
    lamp = vsgl.PointLight(position=(0.8, 0.6, 0.5), intensity=0.7)
    cam = vsgl.Camera.look_at(eye=(0.0, 1.6, 2.5), target=(0.0, 0.3, -0.5), fov_y_deg=60.0)
    r = make_renderer(16, 16)
    emitter_only = scene
    both = emitter_over_floor(tmp_path, wall=True)
    both.lights = [lamp]
    lamp_only = emitter_over_floor(tmp_path, wall=True)
    lamp_only.set_material("materials[1]", emissive=(0.0, 0.0, 0.0))
    lamp_only.lights = [lamp]
    for method, kw in (("direct", {}), ("reference", dict(rsm_size=32)), ("reference", dict(rsm_size=32, emitter_direct="sg", visibility="raytrace"))):
        frames = [r.render(s, cam, method=method, aovs=["direct", "indirect"] if method != "direct" else ["direct"], **kw)
                  for s in (both, lamp_only, emitter_only)]
        for aov in frames[0].aovs:
            total = frames[1].aov(aov).astype(np.float64) + frames[2].aov(aov)
            assert frames[1].aov(aov).any() and frames[2].aov(aov).any(), (method, aov)
            np.testing.assert_allclose(frames[0].aov(aov), total, rtol=1e-5, atol=1e-6 * total.max(), err_msg=f"{method} {aov}")
    # The stochastic methods add up in the mean: with both, num_lights is split over more
    # lights and the random streams differ, so only their expectations are additive (measured
    # 0.9992, 0.9981 and 1.0012 of the sum in indirect light; the direct light's sum exact).
    for method, kw in (("vpl", dict(num_lights=4096, rsm_size=64)),
                       ("vsgl", dict(num_lights=4096, rsm_size=64, interleave=1, denoise=False)),
                       ("pathtrace", dict(spp=256, strategy="camera"))):
        frames = [r.render(s, cam, method=method, aovs=["direct", "indirect"], **kw) for s in (both, lamp_only, emitter_only)]
        for aov, tolerance in (("direct", 1e-4), ("indirect", 0.02)):
            means = [float(f.aov(aov).mean()) for f in frames]
            assert means[1] > 0 and means[2] > 0, (method, aov, means)
            assert means[0] / (means[1] + means[2]) == pytest.approx(1.0, abs=tolerance), (method, aov, means)


def test_without_emitters_the_emitter_lights_change_nothing(make_renderer):
    r = make_renderer(16, 16)
    scene = vsgl.scenes.cornell_box()
    frames = [r.render(scene, method="vsgl", num_lights=64, rsm_size=32, emitter_lights=b, aovs=["image"]) for b in (1, 64)]
    np.testing.assert_array_equal(frames[0].image, frames[1].image)
    assert frames[0].passes == frames[1].passes


@pytest.mark.slow
def test_the_emitter_lit_cornell_box_in_the_virtual_light_methods(shared_scenes, make_renderer):
    """CornellBox.glb lit by its ceiling alone (64², RSM 128², N = 1024): vpl and vsgl
    (interleave 1) estimate the same-RSM reference within 10% in diffuse and specular, as with
    punctual lights on the corpus (measured 1.009 / 1.008 and 1.015 / 0.965); VPLs with their
    visibility estimate the path tracer's area-light truth (measured 0.998; unshadowed, the
    reference is 1.22 of it, as CornellBoxOriginal's spot light's is 1.15)."""
    scene = vsgl.Scene.load(shared_scenes / "CornellBox" / "CornellBox.glb")
    r = make_renderer(64, 64)
    aovs = ["indirect_diffuse", "indirect_specular"]
    ref = r.render(scene, method="reference", rsm_size=128, aovs=aovs)
    for method, kw in (("vpl", {}), ("vsgl", dict(interleave=1, denoise=False))):
        f = r.render(scene, method=method, rsm_size=128, num_lights=1024, aovs=aovs, **kw)
        ratios = [float(f.aov(a).mean() / ref.aov(a).mean()) for a in aovs]
        assert all(abs(x - 1) <= 0.10 for x in ratios), (method, ratios)
    truth = r.render(scene, method="pathtrace", spp=256, aovs=["indirect"]).aov("indirect").mean()
    shadowed = r.render(scene, method="vpl", rsm_size=128, num_lights=4096, visibility="raytrace", aovs=["indirect"]).aov("indirect").mean()
    assert shadowed / truth == pytest.approx(1.0, abs=0.05)


def test_an_emitter_past_a_lights_intensity_is_refused_by_name(tmp_path, make_renderer):
    # Radiance 1e30 (within the loader's 1e32) over a square a million units wide: a cluster
    # sends 1e42, past f32 and the 1e32 a light may have. The clusters refuse it with the cause
    # (the frame would otherwise saturate at FLT_MAX); the path tracer, which samples the
    # radiance itself, renders it.
    big = 1e6
    quads = [
        dict(corners=[(-3 * big, 0, -3 * big), (-3 * big, 0, 3 * big), (3 * big, 0, 3 * big), (3 * big, 0, -3 * big)], name="floor", specular=0.0),
        dict(corners=[(-0.5 * big, big, -0.5 * big), (0.5 * big, big, -0.5 * big), (0.5 * big, big, 0.5 * big), (-0.5 * big, big, 0.5 * big)],
             name="glow", base_color=(0.0,) * 3, specular=0.0),
    ]
    scene = vsgl.Scene.load(sb.write_quads(tmp_path, quads))
    scene.set_material("materials[1]", emissive=(1e30, 1e30, 1e30))
    cam = vsgl.Camera.look_at(eye=(0.0, 0.5 * big, 0.0), target=(0.0, 0.0, 0.0), up=(0.0, 0.0, -1.0), fov_y_deg=60.0)
    r = make_renderer(8, 8)
    with pytest.raises(vsgl.VsglError, match=r"emissive surfaces: must be positive and at most 1e32 \(candela: a cluster's radiance × area"):
        r.render(scene, cam, method="vsgl", num_lights=64, rsm_size=32)
    f = r.render(scene, cam, method="pathtrace", spp=8, strategy="camera", aovs=["direct"])
    assert np.isfinite(f.aov("direct")).all() and f.aov("direct").max() < 1e30


# --- emitter_direct="sg": the emitter lights' points as VSGLs, shadowed by `visibility` -------

def test_emitter_vsgls_light_the_floor_as_the_form_factor_says(tmp_path, make_renderer):
    # Each of the 64 points becomes a VSGL of its part's spread; under the unit square at height
    # 1 they give 1.005 of the form factor with one light and 1.0013 with four (measured; the
    # point sum: 1.003 and 1.0007). The bounds: reference 1%, vsgl (interleave 1) 5%.
    size = 16
    scene = emitter_over_floor(tmp_path)
    want = expected_floor_radiance(size)
    r = make_renderer(size, size)
    for method, kw in (("reference", dict(rsm_size=32)), ("vsgl", dict(interleave=1, denoise=False))):
        for visibility in ("raytrace", "ism"):
            f = r.render(scene, DOWN, method=method, emitter_direct="sg", visibility=visibility, aovs=["direct"], **kw)
            got = f.aov("direct")[..., 0].astype(np.float64)
            assert got.mean() / want.mean() == pytest.approx(1.0, abs=0.01), (method, visibility, got.mean() / want.mean())
            assert np.abs(got / want - 1).max() < 0.02, (method, visibility)
            assert any(p.startswith("emitter_direct") for p in f.passes), f.passes


def _plate_under_the_emitter(directory) -> vsgl.Scene:
    """The emitter over the floor with a black 0.3 × 0.3 plate half-way down: the plate's shadow
    on the floor is penumbra everywhere (no floor point has the whole lamp hidden)."""
    p = 0.15
    quads = [
        dict(corners=[(-3, 0, -3), (-3, 0, 3), (3, 0, 3), (3, 0, -3)], name="floor", base_color=(FLOOR_ALBEDO,) * 3, specular=0.0),
        dict(corners=[(-0.5, H, -0.5), (0.5, H, -0.5), (0.5, H, 0.5), (-0.5, H, 0.5)], name="glow", base_color=(0.0,) * 3, specular=0.0),
        dict(corners=[(-p, 0.5 * H, -p), (-p, 0.5 * H, p), (p, 0.5 * H, p), (p, 0.5 * H, -p)], name="plate", base_color=(0.0,) * 3, specular=0.0),
    ]
    scene = vsgl.Scene.load(sb.write_quads(directory, quads))
    scene.set_material("materials[1]", emissive=(L_E, L_E, L_E))
    return scene


@pytest.mark.slow
def test_emitter_vsgls_with_shadow_rays_cast_the_penumbra_of_an_area_light(tmp_path, make_renderer):
    # Seen from the lamp's centre (the cube of emitter_direct="points") the plate hides the
    # floor under it: 0.30 of the truth's light, block error 0.71 (measured). A shadow ray per
    # (pixel, point) sees each part of the lamp: 0.987 and 0.023 against the path tracer at
    # 512 spp (whose own per-pixel noise is a few %; the 4×4 block means average it away).
    from vsgl import metrics

    scene = _plate_under_the_emitter(tmp_path)
    cam = vsgl.Camera.look_at(eye=(0.0, 0.25, 0.0), target=(0.0, 0.0, 0.0), up=(0.0, 0.0, -1.0), fov_y_deg=110.0)
    r = make_renderer(16, 16)
    truth = r.render(scene, cam, method="pathtrace", spp=512, aovs=["direct"]).aov("direct").astype(np.float64)
    kw = dict(method="vsgl", interleave=1, denoise=False, aovs=["direct"])
    hard = r.render(scene, cam, emitter_direct="points", **kw).aov("direct").astype(np.float64)
    soft = r.render(scene, cam, emitter_direct="sg", visibility="raytrace", **kw).aov("direct").astype(np.float64)
    assert metrics.block_rmse(hard, truth, 4) > 0.3
    assert soft.mean() / truth.mean() == pytest.approx(1.0, abs=0.03)
    assert metrics.block_rmse(soft, truth, 4) < 0.05


def test_emitter_vsgls_need_a_visibility_and_a_known_name(tmp_path, make_renderer):
    r = make_renderer(8, 8)
    scene = emitter_over_floor(tmp_path)
    with pytest.raises(vsgl.ArgumentError, match=r"emitter_direct.*visibility=\"raytrace\""):
        r.render(scene, DOWN, method="vpl", emitter_direct="sg")
    with pytest.raises(vsgl.ArgumentError, match="emitter_direct"):
        r.render(scene, DOWN, method="vpl", emitter_direct="area", visibility="raytrace")
    with pytest.raises(vsgl.ArgumentError, match="not an option of method=\"direct\""):
        r.render(scene, DOWN, method="direct", emitter_direct="sg")


def test_without_emitters_emitter_vsgls_change_nothing(make_renderer):
    # The option is read, but a scene without emissive surfaces has no emitter light: the same
    # passes and bits as emitter_direct="points" with the same visibility.
    r = make_renderer(16, 16)
    scene = vsgl.scenes.cornell_box()
    # The first frame builds the BVH, which the two compared then reuse.
    frames = [r.render(scene, method="vpl", num_lights=64, rsm_size=32, visibility="raytrace", emitter_direct=e, aovs=["image"]) for e in ("points", "points", "sg")][1:]
    np.testing.assert_array_equal(frames[0].image, frames[1].image)
    assert frames[0].passes == frames[1].passes


def test_an_emitter_lights_nothing_behind_its_own_plane_through_its_vsgls(tmp_path, make_renderer):
    # The lamp emits downwards only: its back, seen from above, gets no light from its own
    # VSGLs, which lie a millionth of the scene under it, behind their plane, where both the
    # diffuse and the glossy terms fade out (without the glossy fade the back of the shared
    # CornellBox's lamp was lit ~3e10 times over). The floor around it matches the point sum.
    quads = [
        dict(corners=[(-3, 0, -3), (-3, 0, 3), (3, 0, 3), (3, 0, -3)], name="floor", base_color=(FLOOR_ALBEDO,) * 3, specular=0.0),
        dict(corners=[(-0.5, H, -0.5), (0.5, H, -0.5), (0.5, H, 0.5), (-0.5, H, 0.5)], name="glow", base_color=(0.7,) * 3, roughness=0.3),
    ]
    scene = vsgl.Scene.load(sb.write_quads(tmp_path, quads))
    scene.set_material("materials[1]", emissive=(L_E, L_E, L_E))
    above = vsgl.Camera.look_at(eye=(0.0, 1.8, 1.2), target=(0.0, H, 0.0), fov_y_deg=70.0)
    r = make_renderer(16, 16)
    kw = dict(method="vpl", num_lights=16, visibility="raytrace", aovs=["direct"])
    points = r.render(scene, above, emitter_direct="points", **kw).aov("direct")
    sg = r.render(scene, above, emitter_direct="sg", **kw).aov("direct")
    assert points.max() > 0
    np.testing.assert_allclose(sg, points, rtol=0.02, atol=1e-3 * points.max())
