"""`lighting=` of the VSGL methods: "asg" (the papers' SG–ASG specular and diffuse=), "accurate"
(GGX with its NDF widened by the light's spread, and the clamped-cosine diffuse) and "blend" (the
two specular forms weighted by the receiver's share of the widened lobe; both methods' default
since they were measured on the real-scene corpus, docs/scenes.md "The real-scene corpus" and
docs/methods/vsgl2.md "Two VSGLs"). Under "blend" `vsgl` shades diffuse by the clamped cosine, `vsgl2` as diffuse=
says (its one plane spans the whole RSM). The formulas are tested against quadrature in the Rust oracle
(crates/vsgl-core/src/verify/oracle/vsgl.rs) and on the GPU by the stability suite; here: the
option itself, each method's default, and finite frames on the stability scenes."""

from __future__ import annotations

import numpy as np
import pytest

import vsgl
from vsgl import stability

SMALL = dict(shadow_size=128, rsm_size=64)


@pytest.fixture(scope="module")
def renderer():
    return vsgl.Renderer(width=32, height=24)


# Each method's default lighting and the diffuse form it brings.
DEFAULTS = {"vsgl": ("blend", "accurate"), "vsgl2": ("blend", "papers")}
# The diffuse form each lighting form brings, by method, when diffuse= is not given.
BROUGHT_DIFFUSE = {("vsgl", "accurate"): "accurate", ("vsgl", "blend"): "accurate",
                   ("vsgl2", "accurate"): "accurate", ("vsgl2", "blend"): "papers"}


@pytest.mark.parametrize("form", ["accurate", "blend"])
@pytest.mark.parametrize("method,extra", [("vsgl", dict(num_lights=64, interleave=1)), ("vsgl2", {})])
def test_the_default_and_each_form_change_only_what_they_say(renderer, method, extra, form):
    scene = vsgl.scenes.glossy_cornell()
    aovs = ["indirect_diffuse", "indirect_specular"]
    default = renderer.render(scene, method=method, aovs=aovs, **SMALL, **extra)
    asg = renderer.render(scene, method=method, aovs=aovs, lighting="asg", **SMALL, **extra)
    accurate = renderer.render(scene, method=method, aovs=aovs, lighting=form, **SMALL, **extra)
    brought = BROUGHT_DIFFUSE[method, form]
    same_diffuse = renderer.render(scene, method=method, aovs=aovs, lighting="asg", diffuse=brought, **SMALL, **extra)
    default_form, default_diffuse = DEFAULTS[method]
    assert default.settings["lighting"] == default_form and accurate.settings["lighting"] == form
    # The settings name the diffuse form the frame used: the clamped cosine under "accurate".
    assert default.settings["diffuse"] == default_diffuse and accurate.settings["diffuse"] == brought
    explicit = renderer.render(scene, method=method, aovs=aovs, lighting=default_form, **SMALL, **extra)
    for aov in aovs:
        assert np.array_equal(default.aov(aov), explicit.aov(aov)), aov
    # The form's diffuse is that of the diffuse form it brings under "asg", bit for bit.
    assert np.array_equal(accurate.aov("indirect_diffuse"), same_diffuse.aov("indirect_diffuse"))
    spec_asg, spec_acc = asg.aov("indirect_specular"), accurate.aov("indirect_specular")
    assert np.isfinite(spec_acc).all() and (spec_acc >= 0).all()
    assert not np.array_equal(spec_asg, spec_acc)
    # Same light, another lobe shape: the totals agree to tens of percent, not orders.
    ratio = spec_acc.sum() / spec_asg.sum()
    print(f"{method}: indirect_specular sum {form}/asg = {ratio:.3f}")
    assert 0.5 < ratio < 2.0


def test_bad_lighting_names_the_option(renderer):
    scene = vsgl.scenes.cornell_box()
    with pytest.raises(vsgl.ArgumentError, match=r"lighting.*\"asg\", \"accurate\", \"blend\""):
        renderer.render(scene, method="vsgl", lighting="exact", **SMALL)
    with pytest.raises(vsgl.ArgumentError, match="lighting"):
        renderer.render(scene, method="vpl", lighting="accurate", **SMALL)
    # lighting="accurate" (and "blend" in vsgl) brings its own diffuse form: another one given
    # with it is refused.
    for diffuse in ("papers", "sg_product"):
        for method, form in (("vsgl2", "accurate"), ("vsgl", "accurate"), ("vsgl", "blend")):
            with pytest.raises(vsgl.ArgumentError, match=rf"diffuse.*{diffuse}.*lighting=\"{form}\""):
                renderer.render(scene, method=method, lighting=form, diffuse=diffuse, **SMALL)
    f = renderer.render(scene, method="vsgl2", lighting="accurate", diffuse="accurate", aovs=["image"], **SMALL)
    assert np.isfinite(f.image).all()


def test_vsgl2s_blend_shades_diffuse_as_diffuse_says(renderer):
    # vsgl2's one diffuse VSGL spans the whole RSM: under lighting="blend" its diffuse is the
    # form diffuse= names (each one bit for bit that form under "asg"), and plane_fade stays off.
    scene = vsgl.scenes.glossy_cornell()
    aovs = ["indirect_diffuse", "indirect_specular"]
    for diffuse in ("papers", "accurate", "sg_product"):
        blend = renderer.render(scene, method="vsgl2", lighting="blend", diffuse=diffuse, aovs=aovs, **SMALL)
        asg = renderer.render(scene, method="vsgl2", lighting="asg", diffuse=diffuse, aovs=aovs, **SMALL)
        assert blend.settings["diffuse"] == diffuse
        assert blend.settings["plane_fade"] is (diffuse != "papers")
        assert np.array_equal(blend.aov("indirect_diffuse"), asg.aov("indirect_diffuse")), diffuse
        assert not np.array_equal(blend.aov("indirect_specular"), asg.aov("indirect_specular")), diffuse


def test_a_papers_form_under_vsgls_default_lighting_says_to_give_asg(renderer):
    # vsgl's default lighting="blend" brings the clamped-cosine diffuse, which always fades: the
    # papers' diffuse forms and plane_fade=False need lighting="asg", and the error says so and
    # that the default is what refused them.
    scene = vsgl.scenes.cornell_box()
    for kw, name in ((dict(diffuse="papers"), "diffuse"), (dict(diffuse="sg_product"), "diffuse"), (dict(plane_fade=False), "plane_fade")):
        with pytest.raises(vsgl.ArgumentError, match=rf"{name}.*lighting=\"blend\" \(the method's default\).*lighting=\"asg\""):
            renderer.render(scene, method="vsgl", **kw, **SMALL)
        f = renderer.render(scene, method="vsgl", lighting="asg", **kw, aovs=["image"], **SMALL)
        assert np.isfinite(f.image).all()


@pytest.mark.parametrize("form", ["accurate", "blend"])
@pytest.mark.parametrize("method", ["vsgl", "vsgl2"])
def test_accurate_lighting_is_finite_on_the_stability_scenes(renderer, method, form):
    # Every case of the scene-level stability suite (moved 1e5 m, scaled 1e∓3, intensities 1e-8
    # and 1e30, a grazing light, roughness 1e-4, the camera inside geometry): no NaN/Inf (the
    # renderer raises NumericsError for one) and no negative light.
    settings = dict(stability.small_settings(method), lighting=form)
    for name in ("cornell_box", "glossy_cornell", "caustics_ring"):
        for case, scene, camera, *_ in stability._scene_cases(name):
            f = renderer.render(scene, camera, method=method, aovs=["image", "indirect_specular"], **settings)
            spec = f.aov("indirect_specular")
            assert np.isfinite(f.image).all() and np.isfinite(spec).all(), (name, case)
            assert (spec >= 0).all(), (name, case)


def test_blend_gives_rough_walls_the_point_lights_specular(renderer):
    # glossy_cornell's walls and ceiling are roughness 1 (GGX α = 1, R_s 0.04). With an RSM of
    # 32² and N = 4·32², every node VSGL is one texel, the same emitter as a VPL, whose specular
    # is the exact GGX at a point: the two must agree there up to the VSGL's footprint. The
    # papers' SG–ASG product, a small-angle warp of the NDF, loses most of that light at any light
    # size (docs/methods/vsgl.md, "SG lighting"); lighting="blend" takes the filtered-NDF form there.
    scene = vsgl.scenes.glossy_cornell()
    r = vsgl.Renderer(width=32, height=32)
    single = dict(num_lights=4096, rsm_size=32, interleave=1, denoise=False, aovs=["indirect_specular", "albedo", "normal"])
    vpl = r.render(scene, method="vpl", **single)
    # The walls and ceiling: base colour red, green or white (not the steel block's or the gold
    # sphere's) and a normal that is not the floor's.
    albedo = vpl.aov("albedo")
    metal = [np.abs(albedo - np.array(c)).max(-1) < 0.02 for c in ([0.8, 0.8, 0.85], [1.0, 0.78, 0.34])]
    rough = (albedo.max(-1) > 0.05) & ~metal[0] & ~metal[1] & (vpl.aov("normal")[..., 1] < 0.9)
    assert rough.mean() > 0.3, "the walls and ceiling should fill a third of the view"

    def wall_ratio(**kw):
        f = r.render(scene, method="vsgl", kernel="node", **single, **kw)
        return f.aov("indirect_specular")[rough].sum() / vpl.aov("indirect_specular")[rough].sum()

    asg, blend = wall_ratio(lighting="asg"), wall_ratio(lighting="blend")
    print(f"rough-wall specular over the VPLs': asg {asg:.3f}, blend {blend:.3f}")
    assert 0.85 < blend < 1.3
    assert asg < 0.6
