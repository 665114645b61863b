"""What a VSGL cluster knows of its texels — their mean tangent plane
(light stays above it), their own footprints, and an RSM that grows with N.

Item 4: a VSGL's light stays above its cluster's mean tangent plane.

Every RSM texel reflects only into its own hemisphere, so a lone lit plane receives no
indirect light from itself. The papers' diffuse form gets exactly 0 from its horizon clamp; the
"accurate" clamped cosine and the "sg_product" form integrate the part of the incoming lobe
above the receiver's horizon, so before the fade a plane lit itself (3.9% of its direct light at
N = 4096 with "accurate"). The fade (wgsl/common/vsgl_tangent_plane.wgsl) must remove exactly
that and keep light that does reach a receiver in front of the cluster."""

from __future__ import annotations

import numpy as np
import pytest

import vsgl
from vsgl.metrics import block_rmse
from scene_builders import step_face, write_quad, write_quads

SIZE = 32


def _spot_over_plane(scene: vsgl.Scene) -> tuple[vsgl.Scene, vsgl.Camera]:
    scene.add_light(vsgl.SpotLight(position=(0.3, 2.0, 0.2), direction=(-0.1, -1, -0.05), intensity=30.0, inner_cone_deg=35, outer_cone_deg=45))
    cam = vsgl.Camera.look_at(eye=(0.5, 3.0, 2.5), target=(0, 0, 0), up=(0, 1, 0), fov_y_deg=50)
    return scene, cam


@pytest.mark.parametrize("diffuse", ["papers", "accurate", "sg_product", None])
@pytest.mark.parametrize("kernel", ["integral", "node", "density"])
def test_a_lone_plane_gets_no_indirect_light_in_every_diffuse_form(tmp_path, make_renderer, diffuse, kernel):
    # diffuse=None: the method's defaults (lighting="blend"); the others under lighting="asg".
    form = dict(lighting="asg", diffuse=diffuse) if diffuse else {}
    scene, cam = _spot_over_plane(vsgl.Scene.load(write_quad(tmp_path, half_size=3.0, roughness=0.6, specular=0.5)))
    r = make_renderer(SIZE, SIZE)
    for n in (256, 4096):
        f = r.render(scene, camera=cam, method="vsgl", num_lights=n, rsm_size=64, kernel=kernel, interleave=1, denoise=False, aovs=["direct", "indirect"], **form)
        direct = f.aov("direct").astype(np.float64)
        indirect = f.aov("indirect").astype(np.float64)
        assert direct.sum() > 0
        assert np.all(np.isfinite(indirect))
        assert indirect.max() == 0.0, f"N={n}: the plane lights itself, {indirect.sum() / direct.sum():.3%} of direct"


@pytest.mark.parametrize("method,kw", [("vsgl", {}), ("vsgl", dict(kernel="node")), ("vsgl", dict(kernel="density")),
                                       ("vsgl", dict(visibility="raytrace")), ("vsgl2", dict(plane_fade=True))])
def test_the_back_of_a_lit_plane_gets_no_indirect_light(tmp_path, make_renderer, method, kw):
    """A lone quad lit from its front by a point light, seen from behind (the renderer shades a
    back face with its normal turned to the camera). Every texel reflects into the front
    half-space only, so the back gets exactly 0, as from the every-texel reference. The papers'
    diffuse form multiplies the texel's Lambert SG, whose axis comes from behind the receiver,
    with the positional SG seen from the receiver; near the plane the product's axis tips over
    the back's horizon. Without the tangent-plane fade the back received about half of the
    front's direct light (0.51-0.54 here; experiments/plane_fade_error.py for other distances), and
    shadow rays to the texels, which lie on the plane, do not stop it.
    `plane_fade` is vsgl's default with lighting="asg" (its default lighting, "blend", shades the
    clamped-cosine diffuse, which always fades); vsgl2 takes it as an option."""
    quad = write_quad(tmp_path, half_size=1.0, specular=0.0)
    scene = vsgl.Scene.load(quad)
    scene.add_light(vsgl.PointLight(position=(0.0, 0.3, 0.2), intensity=3.0))
    front = vsgl.Camera.look_at(eye=(0.3, 1.5, 1.5), target=(0, 0, 0), up=(0, 1, 0), fov_y_deg=60)
    back = vsgl.Camera.look_at(eye=(0.3, -1.5, 1.5), target=(0, 0, 0), up=(0, 1, 0), fov_y_deg=60)
    r = make_renderer(SIZE, SIZE)
    direct = r.render(scene, camera=front, method="direct", aovs=["direct"]).aov("direct").astype(np.float64).sum()
    assert direct > 0
    extra = dict(num_lights=1024, interleave=1, denoise=False) if method == "vsgl" else {}
    reference = r.render(scene, camera=back, method="reference", rsm_size=64, aovs=["indirect"]).aov("indirect")
    assert reference.max() == 0.0
    papers = dict(lighting="asg", near_field="sg") if method == "vsgl" else {}
    unfaded = r.render(scene, camera=back, method=method, rsm_size=64, aovs=["indirect"], **extra, **{**kw, **papers, "plane_fade": False})
    leak = unfaded.aov("indirect").astype(np.float64).sum() / direct
    print(f"{method} {kw}: the back's indirect light over the front's direct, without the fade {leak:.3f}")
    assert leak > 0.2, "the papers' form no longer lights the back: the fade has nothing to remove here"
    # The method's default and, for vsgl, the papers' form with the fade.
    for form in ({}, papers) if papers else ({},):
        faded = r.render(scene, camera=back, method=method, rsm_size=64, aovs=["indirect"], **extra, **kw, **form)
        assert faded.settings["plane_fade"] is True
        indirect = faded.aov("indirect").astype(np.float64)
        assert np.all(np.isfinite(indirect))
        assert indirect.max() == 0.0, f"{form}: the back of the plane gets {indirect.sum() / direct:.3f} of the front's direct light"


def test_plane_fade_false_is_refused_where_the_form_always_fades(renderer):
    """`plane_fade=False` only unfades diffuse="papers"; with a form that always fades it names
    the argument instead of being ignored, and `frame.settings` shows the fade a frame used."""
    scene = vsgl.scenes.cornell_box()
    kw = {"vsgl": dict(num_lights=64, rsm_size=64, aovs=["indirect"]), "vsgl2": dict(rsm_size=64, aovs=["indirect"])}
    for method, form in (("vsgl", dict(lighting="asg", diffuse="accurate")), ("vsgl", dict(lighting="blend")), ("vsgl", {}), ("vsgl2", dict(diffuse="sg_product"))):
        with pytest.raises(vsgl.ArgumentError, match=r"^plane_fade: .* always fades"):
            renderer.render(scene, method=method, plane_fade=False, **form, **kw[method])
        assert renderer.render(scene, method=method, **form, **kw[method]).settings["plane_fade"] is True
    assert renderer.render(scene, method="vsgl2", **kw["vsgl2"]).settings["plane_fade"] is False
    assert renderer.render(scene, method="vsgl", lighting="asg", **kw["vsgl"]).settings["plane_fade"] is True
    assert renderer.render(scene, method="vsgl", lighting="asg", plane_fade=False, **kw["vsgl"]).settings["plane_fade"] is False


def _floor_and_wall(tmp_path):
    """A lit floor (y = 0) and an unlit wall (x = −1) facing it (the cone ends 0.56 m short of
    the wall): everything the wall receives comes from the floor's clusters, from in front of
    their tangent plane, and the floor receives nothing."""
    quads = [
        {"name": "floor", "corners": [(-1, 0, -2), (-1, 0, 2), (3, 0, 2), (3, 0, -2)], "specular": 0.0},
        {"name": "wall", "corners": [(-1, 0, -2), (-1, 3, -2), (-1, 3, 2), (-1, 0, 2)], "specular": 0.0},
    ]
    scene = vsgl.Scene.load(write_quads(tmp_path, quads))
    scene.add_light(vsgl.SpotLight(position=(1.0, 2.5, 0.0), direction=(0, -1, 0), intensity=40.0, inner_cone_deg=20, outer_cone_deg=30))
    cam = vsgl.Camera.look_at(eye=(3.5, 1.5, 0.0), target=(-1, 1.0, 0), up=(0, 1, 0), fov_y_deg=60)
    return scene, cam


@pytest.mark.parametrize("diffuse", ["accurate", "sg_product"])
def test_the_fade_keeps_light_that_reaches_a_receiver_in_front_of_the_cluster(tmp_path, make_renderer, diffuse):
    """The wall's indirect light with the fade against the every-texel reference (same RSM,
    exact per-texel hemispheres). With quadtree-node clusters, which converge to the reference,
    the wall keeps its light within 2% at N = 4096 (measured: 0.998 "accurate", 0.996
    "sg_product"); with the default kernel the fade costs nothing next to the papers' form (both
    0.848 here: what is missing is the SG approximation's, not the fade's). The floor, which
    sees the floor's clusters edge-on, gets exactly 0, as in the reference."""
    scene, cam = _floor_and_wall(tmp_path)
    r = make_renderer(SIZE, SIZE)
    kw = dict(camera=cam, rsm_size=64, aovs=["indirect", "normal"])
    ref = r.render(scene, method="reference", **kw)
    normal = ref.aov("normal")
    wall = normal[..., 0] > 0.9
    floor = normal[..., 1] > 0.9
    assert wall.sum() > 50 and floor.sum() > 50
    assert ref.aov("indirect")[floor].max() == 0.0
    want = ref.aov("indirect")[wall].astype(np.float64).sum()
    assert want > 0
    ratio = {}
    for kernel, form in (("node", diffuse), ("integral", diffuse), ("integral", "papers")):
        f = r.render(scene, method="vsgl", num_lights=4096, interleave=1, denoise=False, kernel=kernel, lighting="asg", diffuse=form, **kw)
        ratio[kernel, form] = f.aov("indirect")[wall].astype(np.float64).sum() / want
        assert f.aov("indirect")[floor].max() == 0.0, (kernel, form)
    print(f"wall indirect vsgl / reference: {ratio}")
    assert abs(ratio["node", diffuse] - 1) < 0.02
    assert ratio["integral", diffuse] > ratio["integral", "papers"] - 0.15
    if diffuse == "accurate":
        assert abs(ratio["integral", "accurate"] - ratio["integral", "papers"]) < 0.01


@pytest.mark.parametrize("diffuse", ["papers", "accurate", "sg_product"])
def test_two_vsgls_of_a_lone_plane_do_not_light_it(tmp_path, make_renderer, diffuse):
    """vsgl2's two VSGLs carry the plane of all texels (vsgl2_moments.wgsl)."""
    scene, cam = _spot_over_plane(vsgl.Scene.load(write_quad(tmp_path, half_size=3.0, roughness=0.6, specular=0.5)))
    f = make_renderer(SIZE, SIZE).render(scene, camera=cam, method="vsgl2", rsm_size=64, diffuse=diffuse, aovs=["direct", "indirect"])
    assert f.aov("direct").sum() > 0
    indirect = f.aov("indirect").astype(np.float64)
    assert indirect.max() == 0.0, f"{indirect.sum() / f.aov('direct').astype(np.float64).sum():.3%} of direct"


def test_a_single_texel_vsgl_is_an_area_light_of_the_texels_footprint(tmp_path, make_renderer):
    """Each texel adds its own positional variance to Σw‖y‖². With a 32² RSM
    and N = 4096 quadtree-node VSGLs, every VSGL is one texel, so its σ² must be the texel's
    footprint, (a²/12)(1 + 1/cos²θ) with a² = Δω·d² its cross-section perpendicular to the
    light. Δω is taken from the RSM's own flux (Φ = I·ρ_d·Δω inside the inner cone on a
    Lambertian plane), d and θ from the captured positions and normals: nothing here is
    computed by the code under test. Without footprints σ² is the rounding floor, 1e-6·d²."""
    rho, intensity = 0.5, 30.0
    scene = vsgl.Scene.load(write_quad(tmp_path, half_size=3.0, base_color=(rho, rho, rho), specular=0.0))
    scene.add_light(vsgl.SpotLight(position=(0.3, 2.0, 0.2), direction=(0.4, -1, -0.2), intensity=intensity, inner_cone_deg=50, outer_cone_deg=55))
    cam = vsgl.Camera.look_at(eye=(0.5, 3.0, 2.5), target=(0, 0, 0), up=(0, 1, 0), fov_y_deg=50)
    n = 32
    f = make_renderer(SIZE, SIZE).render(scene, camera=cam, method="vsgl", num_lights=4096, rsm_size=n, kernel="node", capture_rsm=True)
    v = f.vsgls()
    # Dim nodes (cone edge) may stop above level 0: only single-texel VSGLs are checked.
    single = v["level"] == 0
    assert single.mean() > 0.5
    y = f.rsm("position").astype(np.float64).reshape(n * n, 3)
    normal = f.rsm("normal").astype(np.float64).reshape(n * n, 3)
    flux = f.rsm("flux_diffuse").astype(np.float64).reshape(n * n, 3)[:, 0]
    d2 = np.maximum((y**2).sum(axis=1), 1e-30)
    cos_surface = np.abs((normal * -y).sum(axis=1)) / np.sqrt(d2)
    solid_angle = flux / (intensity * rho)
    want = solid_angle * d2 * (1 + 1 / np.maximum(cos_surface, 0.1) ** 2) / 12
    # Texels well inside the inner cone (the cone factor is 1 there), away from the quad's edge.
    axis = np.array([0.4, -1, -0.2]) / np.linalg.norm([0.4, -1, -0.2])
    inside = ((y / np.sqrt(d2)[:, None]) @ axis > np.cos(np.radians(45))) & (flux > 0)
    texel = np.floor(v["center"]).astype(int)
    index = texel[:, 1] * n + texel[:, 0]
    pick = inside[index] & single
    assert pick.sum() > 500
    got = v["variance"].astype(np.float64)[pick]
    ratio = got / want[index[pick]]
    print(f"single-texel σ² / footprint: median {np.median(ratio):.4f}, range {ratio.min():.4f}…{ratio.max():.4f}")
    np.testing.assert_allclose(ratio, 1.0, rtol=0.02)


def test_the_default_rsm_grows_with_num_lights(renderer):
    """Without rsm_size, vpl and vsgl take max(256, 2^ceil(log2(2*sqrt(N)))) up to 1024 (at least
    four texels per virtual light); a given rsm_size is kept."""
    scene = vsgl.scenes.cornell_box()
    for method in ("vpl", "vsgl"):
        for n, side in ((4096, 256), (16385, 512), (70000, 1024)):
            f = renderer.render(scene, method=method, num_lights=n, interleave=8, aovs=["indirect"])
            assert f.settings["rsm_size"] == side, (method, n, f.settings["rsm_size"])
        f = renderer.render(scene, method=method, num_lights=70000, rsm_size=64, interleave=8, aovs=["indirect"])
        assert f.settings["rsm_size"] == 64


# --- Normal coherence of the kernels (coherence=, docs/scenes.md "The real-scene corpus") -----

@pytest.mark.parametrize("kernel", ["integral", "density", "node"])
def test_kernels_do_not_straddle_a_crease(make_renderer, kernel):
    """With the default coherence=0.9 no kernel larger than about a texel has texels whose mean
    normal is shorter than 0.9 (each record's plane_normal is that mean at its final kernel); the
    papers' kernels (coherence=0) put 9-24 of cornell_box's 64 VSGLs across its corners."""
    r = make_renderer(64, 64)
    scene = vsgl.scenes.cornell_box()
    counts = {}
    for c in (0.0, None):
        kw = {} if c is None else dict(coherence=c)
        f = r.render(scene, method="vsgl", rsm_size=64, num_lights=64, kernel=kernel, aovs=[], **kw)
        v = f.vsgls()
        coherence = np.linalg.norm(v["plane_normal"], axis=1)
        counts[c] = int(((coherence < 0.9) & (v["level"] > 0.5)).sum())
    assert counts[None] == 0, counts
    assert counts[0.0] >= 5, counts  # measured: 24 (integral, density), 9 (node)


@pytest.mark.parametrize("kernel_filter,seeds,bound", [("trilinear", (0,), 0.95), ("nodes", (0, 1, 2), 0.97)])
def test_coherent_kernels_lower_the_block_error_on_the_box(make_renderer, kernel_filter, seeds, bound):
    # Measured: cornell_box at N = 64, 4x4 block error against the every-texel reference, with
    # the papers' trilinear read 0.241 -> 0.217 when coherence came (0.095 -> 0.086 under
    # today's shading). Reading kernels at their nodes (the default kernel_filter) already keeps
    # a texel-sized kernel off its neighbours, and coherence adds less: 0.085 -> 0.083,
    # 0.093 -> 0.087 and 0.110 -> 0.102 at seeds 0, 1, 2 (their mean 5% lower).
    r = make_renderer(64, 64)
    scene = vsgl.scenes.cornell_box()
    ref = r.render(scene, method="reference", rsm_size=64, aovs=["indirect"]).aov("indirect")
    err = {}
    for c in (0.0, 0.9):
        err[c] = np.mean([
            block_rmse(r.render(scene, method="vsgl", rsm_size=64, num_lights=64, interleave=1, denoise=False, coherence=c,
                                kernel_filter=kernel_filter, seed=seed, aovs=["indirect"]).aov("indirect"), ref, 4)
            for seed in seeds
        ])
    assert err[0.9] < bound * err[0.0], err


def test_coherence_is_checked(renderer):
    scene = vsgl.scenes.cornell_box()
    for bad in (1.5, -0.1):
        with pytest.raises(vsgl.ArgumentError, match="coherence"):
            renderer.render(scene, method="vsgl", coherence=bad, num_lights=16, rsm_size=32)
    f = renderer.render(scene, method="vsgl", coherence=1.0, lighting="asg", plane_fade=False, num_lights=16, rsm_size=32, aovs=["image"])
    assert np.isfinite(f.image).all() and f.settings["coherence"] == 1.0


# --- How the filtered kernels read the mips (kernel_filter=, experiments/vsgl_defaults_on_the_corpus.md "Kernels read at
# their node") ------------------------------------------------------------------------------------

_SHELF_EYE = (0.0, 2.0, 2.5)


def _shelf_over_floor(directory):
    """A 1 × 2 m shelf board 0.3 m over a 2 × 2 m floor, both lit from straight above: in the RSM
    the board's texels sit beside floor texels 0.3 m lower, with the same normal (so coherence
    cannot tell them apart)."""
    floor = dict(corners=[(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="floor")
    board = dict(corners=[(-1, 0.3, -1), (-1, 0.3, 1), (0, 0.3, 1), (0, 0.3, -1)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="board")
    scene = vsgl.Scene.load(write_quads(directory, [floor, board], name="shelf_over_floor.gltf"))
    scene.lights = [vsgl.SpotLight(position=(0.0, 3.0, 0.0), direction=(0.0, -1.0, 0.0), intensity=10.0, inner_cone_deg=40, outer_cone_deg=45)]
    return scene, vsgl.Camera.look_at(eye=_SHELF_EYE, target=(0.0, 0.0, 0.0), fov_y_deg=50)


@pytest.mark.parametrize("kernel", ["integral", "density"])
def test_texel_sized_kernels_stay_on_the_surface_across_a_depth_jump(tmp_path, make_renderer, kernel):
    """A kernel of about one texel is that texel with kernel_filter="nodes" (the default): its
    VSGL's mean lies on the board or on the floor. The papers' trilinear read blends the centre
    texel with its neighbours whatever the kernel's size, so at the board's edge a one-texel
    VSGL's mean hangs in the 0.3 m gap between board and floor (measured: 27 of 1024 VSGLs more
    than 3 cm from both, with either kernel; none with "nodes"), where it sends no receiver the
    light either texel would."""
    r = make_renderer(32, 32)
    scene, camera = _shelf_over_floor(tmp_path)
    in_gap = {}
    for kernel_filter in ("nodes", "trilinear"):
        f = r.render(scene, camera=camera, method="vsgl", rsm_size=32, num_lights=1024, kernel=kernel, kernel_filter=kernel_filter, aovs=[])
        v = f.vsgls()
        assert f.settings["kernel_filter"] == kernel_filter
        one_texel = v["level"] < 0.05
        height = v["mean"][:, 1] + _SHELF_EYE[1]  # records are relative to the eye
        off_surface = np.minimum(np.abs(height), np.abs(height - 0.3)) > 0.03
        assert one_texel.sum() > 256, int(one_texel.sum())
        in_gap[kernel_filter] = int((one_texel & off_surface).sum())
    assert in_gap["nodes"] == 0, in_gap
    assert in_gap["trilinear"] >= 5, in_gap


def test_kernels_read_at_their_node_keep_the_light_a_step_sends_its_face(tmp_path, make_renderer):
    """At the foot of a step (scene_builders.step_face) the floor texels that light the step's
    face from a texel or two away sit in the RSM beside the step's top, 0.3 m higher. The papers'
    bilinear read pulls each of those VSGLs up into the step, behind the face's plane, and the
    light drops; read at their nodes they stay on the floor. Against the every-texel reference
    (64², RSM 32, N = 1024, interleave 1) the 4×4 block error measured 0.120 ("trilinear") against
    0.058 ("nodes"), the mean 0.923 against 0.969 (seed 1: 0.126 / 0.064, 0.918 / 0.964)."""
    r = make_renderer(64, 64)
    scene, camera = step_face(tmp_path)
    ref = r.render(scene, camera=camera, method="reference", rsm_size=32, aovs=["indirect"]).aov("indirect")
    got = {}
    for kernel_filter in ("trilinear", None):
        chosen = {} if kernel_filter is None else dict(kernel_filter=kernel_filter)
        f = r.render(scene, camera=camera, method="vsgl", rsm_size=32, num_lights=1024, interleave=1, denoise=False, aovs=["indirect"], **chosen)
        img = f.aov("indirect")
        got[f.settings["kernel_filter"]] = (float(block_rmse(img, ref, 4)), float(img.mean() / ref.mean()))
    assert "nodes" in got, f"the default kernel_filter is not nodes: {got}"
    assert got["nodes"][0] < 0.7 * got["trilinear"][0], got
    assert abs(got["nodes"][1] - 1) < 0.6 * abs(got["trilinear"][1] - 1), got


def test_kernel_filter_is_refused_with_node_kernels(renderer):
    scene = vsgl.scenes.cornell_box()
    with pytest.raises(vsgl.ArgumentError, match="kernel_filter"):
        renderer.render(scene, method="vsgl", kernel="node", kernel_filter="trilinear", num_lights=16, rsm_size=32)
    with pytest.raises(vsgl.ArgumentError, match="kernel_filter"):
        renderer.render(scene, method="vsgl", kernel_filter="bilinear", num_lights=16, rsm_size=32)
    assert renderer.render(scene, method="vsgl", num_lights=16, rsm_size=32, aovs=[]).settings["kernel_filter"] == "nodes"
