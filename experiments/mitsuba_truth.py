#!/usr/bin/env python3
"""How far is vsgl's path-traced ground truth (`method="pathtrace"`, default strategy "bidirectional") from Mitsuba 3's light tracer (`ptracer`) with the same materials, lights and camera?

An outside check of the truth the benchmark measures every method against (experiments/pathtracer_vs_mitsuba.md,
"Against Mitsuba 3's light tracer (`experiments/mitsuba_truth.py`)"). Not run in CI and
imported by no test: it needs Mitsuba 3 (``pip install mitsuba drjit``), which vsgl does not
depend on.

Both renderers get the same scene: vsgl's world-space triangles (``scene.triangles()``), its
per-vertex shading normals, its lights and one camera (the scene's own, or vsgl's default framing
of the scene's bounds, passed to both). Mitsuba gets vsgl's material model through two Python
plugins registered here:

- ``vsgl_gltf`` (BSDF): Rd/π + Rs·D(h)·G2/(4|n·l||n·v|), Rd = base·(1 − metallic),
  Rs = mix(0.04·specular, base, metallic), GGX D with α = max(roughness², 1e-4), height-correlated
  Smith G2 = 1/(1 + Λ(l) + Λ(v)), no Fresnel; double-sided (the local frame is flipped to the
  side light arrives from). Sampled like vsgl's path tracer: the GGX lobe (visible normals,
  ``mi.MicrofacetDistribution``) with probability c_s = ΣRs/(ΣRd + ΣRs), else cosine; ``pdf`` is
  that mixture's. f is symmetric, so the light tracer's importance transport needs nothing more;
  with shading normals the integrator's own adjoint correction (Veach 1997, p. 155) applies.
- ``vsgl_spot`` (emitter): a point at ``position`` with intensity I·colour (cd) and the glTF smooth
  cone, t = clamp((cos θ − cos_outer)/max(cos_inner − cos_outer, 1e-4), 0, 1), attenuation t²;
  photons leave uniformly over the outer cone. Point lights are Mitsuba's ``point`` and
  directional lights its ``directional`` (same units: cd, lux).

Mitsuba gets lengths scaled so that the scene's bounds diagonal is 10 units (spot and point
intensities divided by the scale squared, so every radiance stays as it is; ``--mitsuba-units
world`` turns this off). Mitsuba 3.9's results depend on the length unit at both ends: at
coordinates ~1e3 (the millimetre Cornell box as it is) its camera-ray hit points were 0.06 mm
(median, 6e-5 of the scene) from an f64 intersection, which moved its direct light by up to 0.8%
in the spot's cone ramp (vsgl's matched an f64 evaluation within 2e-4 there); with a diagonal of
1 unit its ray offsets (ε·(1 + max|p|), an absolute floor) grow to ~1e-4 of the scene and its
caustics_ring indirect came out 0.8% brighter than with a diagonal of 100 or 1000 units (which
agree within 0.01%). At 10 units the direct light matches vsgl's within 8e-5 (rms) on every
scene here.

The camera is a pinhole with vsgl's vertical field of view and a ``box`` reconstruction filter, so
each Mitsuba pixel is the radiance averaged over the pixel's area, which is what vsgl's
bidirectional mode estimates for the indirect light. vsgl's ``direct`` AOV is the pixel centre's,
so the direct light is checked against a pixel-centre direct render in Mitsuba (deterministic:
the lights are points) and the full image is compared both as rendered (``image``: vsgl's centre
direct + area indirect against Mitsuba's area direct + area indirect) and like for like
(``image_c``: Mitsuba's centre direct + its area indirect).

Mitsuba's one-bounce light is ``ptracer`` with ``max_depth=3`` (light → x → y → eye, and the
direct paths) less ``max_depth=2`` (direct only) with the same seed, so the direct paths cancel
exactly; ``rr_depth`` is past both, so no Russian roulette. The light tracer alone does not
converge where the camera sees a near-mirror (light → x → mirror y → eye: the connection to the
eye goes through a lobe ~1e6 high and under a µsr wide, so such pixels are a few huge splats), so
paths whose eye-side vertex y lies on a material with roughness <= ``--camera-roughness`` (0.2)
are taken by camera paths instead (``mitsuba_camera_part``: a jittered ray finds y, y's BRDF is
sampled, x's direct light is reflected): the light tracer's connection to the eye returns 0 on
those materials, so every path is counted once. ``--camera-roughness -1`` gives the light tracer
alone. Mitsuba's own error is taken from the spread of two halves of its seeds (heavy-tailed
light, as on caustics_ring, makes that an underestimate); vsgl's from its ``stderr`` AOV.

Cross-checks (``--no-cross-check`` leaves them out): Mitsuba by camera paths for every path
(pixel-area averages, and pixel centres), against which vsgl's ``strategy="camera"`` (pixel
centres) is compared; and the share of Mitsuba's indirect light in pixels whose centre sees no
surface, which vsgl's pathtrace leaves at 0.

Usage (6–10 minutes on 2 CPU cores with lavapipe and Mitsuba's LLVM backend, which needs
libLLVM >= 16; 15 fails on Mitsuba 3.9's kernels):

    XDG_RUNTIME_DIR=/tmp python experiments/mitsuba_truth.py

writes ``truth.txt`` (the tables, with the command line at the top; ``--name`` renames it) under
``--out``, and with ``--save-images`` ``truth.npz`` with every image.
"""

from __future__ import annotations

import argparse
import glob
import os
import pathlib
import re
import shlex
import sys
import time

import numpy as np

import vsgl
from vsgl import metrics

INSTALL_HINT = (
    "mitsuba_truth.py needs Mitsuba 3 in the Python that runs it:\n"
    "    python -m pip install mitsuba drjit\n"
    "(the default variant llvm_ad_rgb also needs libLLVM 16 or newer, e.g. `apt-get install libllvm19` on Debian "
    "bookworm; the script points DRJIT_LIBLLVM_PATH at the newest one it finds, or set it yourself; "
    "--variant scalar_rgb needs none but is slow)"
)

BUILTIN = ("mirror_panel", "caustics_ring")
CORPUS = ("cornell_box_original", "cornell_box_mm", "lights_spot")
TEXTURED = ("flight_helmet", "boom_box")
DEFAULT_SCENES = BUILTIN + CORPUS
BLOCK = 4
# Acceptance on the caustic built-ins (the brief of this script).
ACCEPT_MEAN = 0.05
ACCEPT_BLOCK = 0.15
# Mitsuba's length unit: the scene's bounds diagonal is this many units (--mitsuba-units scene).
MITSUBA_DIAGONAL = 10.0


# --- Mitsuba ------------------------------------------------------------------------------------


def _find_libllvm() -> str | None:
    """The newest libLLVM shared library on the usual paths (Dr.Jit's LLVM backend needs one;
    LLVM 15 fails on Mitsuba 3.9's kernels with "Cannot select: fminimum", 19 works)."""
    found = []
    for pattern in ("/usr/lib/x86_64-linux-gnu/libLLVM*.so*", "/usr/lib/llvm-*/lib/libLLVM*.so*", "/usr/lib64/libLLVM*.so*"):
        for path in glob.glob(pattern):
            m = re.search(r"(\d+)", os.path.basename(path))
            if m:
                found.append((int(m.group(1)), path))
    return max(found)[1] if found else None


def load_mitsuba(variant: str):
    """Imports Mitsuba with ``variant`` and registers the two plugins; exits 2 with an install
    hint when Mitsuba is missing."""
    if variant.startswith("llvm") and "DRJIT_LIBLLVM_PATH" not in os.environ:
        lib = _find_libllvm()
        if lib:
            os.environ["DRJIT_LIBLLVM_PATH"] = lib
            version = int(re.search(r"(\d+)", os.path.basename(lib)).group(1))
            if version < 16:
                print(f"warning: the newest libLLVM found is {lib}; Mitsuba 3.9's LLVM kernels need 16 or newer "
                      "(15 aborts with 'Cannot select: fminimum')", file=sys.stderr)
    try:
        import drjit as dr
        import mitsuba as mi
    except ImportError as e:
        print(f"error: {e}\n{INSTALL_HINT}", file=sys.stderr)
        sys.exit(2)
    try:
        mi.set_variant(variant)
    except Exception as e:  # an unknown variant, or an LLVM variant without libLLVM
        print(f"error: Mitsuba variant {variant!r}: {e}\n{INSTALL_HINT}", file=sys.stderr)
        sys.exit(2)
    _register_plugins(mi, dr)
    return mi, dr


def _register_plugins(mi, dr) -> None:
    FLT_MAX = 3.4028234e38

    def lam(cos2, a2):
        # Smith Λ for GGX, written as vsgl's ggx_smith_lambda (no cancellation for small α tanθ).
        c2 = dr.maximum(cos2, 1e-38)
        a2t2 = a2 * dr.maximum(1.0 - c2, 0.0) / c2
        return a2t2 / (2.0 * (1.0 + dr.sqrt(1.0 + a2t2)))

    class GltfBRDF(mi.BSDF):
        """vsgl's glTF metallic-roughness BRDF (see the module docstring), double-sided."""

        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            self.rd = [float(props["rd_" + c]) for c in "rgb"]
            self.rs = [float(props["rs_" + c]) for c in "rgb"]
            self.alpha = max(float(props["alpha"]), 1.0e-4)
            # Paths whose last vertex before the eye lies on this material are left to the
            # camera part (see mitsuba_camera_part): the light tracer's connection to the eye
            # returns 0 here (eval in importance mode is only called by that connection).
            self.sensor_hidden = bool(props.get("sensor_hidden", False))
            wd, ws = sum(self.rd), sum(self.rs)
            self.c_s = ws / (wd + ws) if wd + ws > 0.0 else 0.0
            both = mi.BSDFFlags.FrontSide | mi.BSDFFlags.BackSide
            diffuse = mi.BSDFFlags.DiffuseReflection | both
            glossy = mi.BSDFFlags.GlossyReflection | both
            self.m_components = [int(diffuse), int(glossy)]
            self.m_flags = int(diffuse | glossy)

        def _local(self, si, wo):
            # Both directions in the frame whose +z faces the side light arrives from.
            flip = si.wi.z < 0.0
            wi = mi.Vector3f(si.wi.x, si.wi.y, dr.abs(si.wi.z))
            wo = mi.Vector3f(wo.x, wo.y, dr.select(flip, -wo.z, wo.z))
            return flip, wi, wo

        def _f_cos_pdf(self, wi, wo):
            """(f·cos θ_o, pdf) for local wi, wo with wi.z >= 0."""
            a2 = self.alpha * self.alpha
            valid = (wi.z > 0.0) & (wo.z > 0.0)
            hs = wi + wo
            hl = dr.norm(hs)
            valid &= hl > 1e-38
            h = hs / dr.maximum(hl, 1e-38)
            t = a2 * h.z * h.z + (h.x * h.x + h.y * h.y)
            d = dr.minimum(a2 / dr.maximum(dr.pi * t * t, 1e-38), FLT_MAX)
            lam_i = lam(wi.z * wi.z, a2)
            lam_o = lam(wo.z * wo.z, a2)
            g2 = 1.0 / (1.0 + lam_i + lam_o)
            spec = dr.minimum(d * g2 / dr.maximum(4.0 * wi.z * wo.z, 1e-38), FLT_MAX)
            f = mi.Color3f(self.rd) * dr.inv_pi + mi.Color3f(self.rs) * spec
            value = dr.select(valid, f * wo.z, 0.0)
            # Mixture pdf: (1 − c_s) cos/π + c_s G1(wi) D(h) / (4 wi.z) (visible normals, reflected).
            pdf_s = dr.select(dr.dot(wi, h) > 0.0, d / ((1.0 + lam_i) * 4.0 * dr.maximum(wi.z, 1e-38)), 0.0)
            pdf = (1.0 - self.c_s) * dr.maximum(wo.z, 0.0) * dr.inv_pi + self.c_s * pdf_s
            return value, dr.select(valid, pdf, 0.0)

        def sample(self, ctx, si, sample1, sample2, active=True):
            flip = si.wi.z < 0.0
            wi = mi.Vector3f(si.wi.x, si.wi.y, dr.abs(si.wi.z))
            distr = mi.MicrofacetDistribution(mi.MicrofacetType.GGX, self.alpha, True)
            m, _ = distr.sample(wi, sample2)
            wo_spec = mi.reflect(wi, m)
            wo_diff = mi.warp.square_to_cosine_hemisphere(sample2)
            specular = sample1 < self.c_s
            wo = dr.select(specular, wo_spec, wo_diff)
            value, pdf = self._f_cos_pdf(wi, wo)
            ok = active & (pdf > 0.0) & (wi.z > 0.0)
            bs = dr.zeros(mi.BSDFSample3f)
            bs.wo = mi.Vector3f(wo.x, wo.y, dr.select(flip, -wo.z, wo.z))
            bs.pdf = dr.select(ok, pdf, 0.0)
            bs.eta = 1.0
            bs.sampled_type = mi.UInt32(dr.select(specular, int(mi.BSDFFlags.GlossyReflection), int(mi.BSDFFlags.DiffuseReflection)))
            bs.sampled_component = dr.select(specular, mi.UInt32(1), mi.UInt32(0))
            weight = dr.select(ok, value / dr.maximum(pdf, 1e-38), 0.0)
            return bs, mi.Spectrum(weight)

        def eval(self, ctx, si, wo, active=True):
            if self.sensor_hidden and ctx.mode == mi.TransportMode.Importance:
                return mi.Spectrum(0.0)
            _, wi, wo = self._local(si, wo)
            value, _ = self._f_cos_pdf(wi, wo)
            return mi.Spectrum(dr.select(active, value, 0.0))

        def pdf(self, ctx, si, wo, active=True):
            _, wi, wo = self._local(si, wo)
            _, pdf = self._f_cos_pdf(wi, wo)
            return dr.select(active, pdf, 0.0)

        def eval_pdf(self, ctx, si, wo, active=True):
            _, wi, wo = self._local(si, wo)
            value, pdf = self._f_cos_pdf(wi, wo)
            return mi.Spectrum(dr.select(active, value, 0.0)), dr.select(active, pdf, 0.0)

        def traverse(self, callback):
            pass

        def to_string(self):
            return f"GltfBRDF[rd={self.rd}, rs={self.rs}, alpha={self.alpha}]"

    class GltfSpot(mi.Emitter):
        """A glTF spot light: point source, intensity I·colour (cd), smooth cone t² (see above)."""

        def __init__(self, props):
            mi.Emitter.__init__(self, props)
            self.m_flags = int(mi.EmitterFlags.DeltaPosition)
            self.position = [float(props["px"]), float(props["py"]), float(props["pz"])]
            axis = np.array([float(props["dx"]), float(props["dy"]), float(props["dz"])])
            self.axis = [float(x) for x in axis / np.linalg.norm(axis)]
            self.intensity = [float(props["ir"]), float(props["ig"]), float(props["ib"])]
            self.cos_inner = float(props["cos_inner"])
            self.cos_outer = float(props["cos_outer"])

        def profile(self, d):
            """Cone attenuation for the unit direction d leaving the light."""
            cd = dr.dot(mi.Vector3f(self.axis), d)
            t = dr.clip((cd - self.cos_outer) / max(self.cos_inner - self.cos_outer, 1.0e-4), 0.0, 1.0)
            return t * t

        def sample_ray(self, time, sample1, sample2, sample3, active=True):
            local = mi.warp.square_to_uniform_cone(mi.Point2f(sample2[0], sample2[1]), self.cos_outer)
            d = mi.Frame3f(mi.Vector3f(self.axis)).to_world(local)
            pdf = mi.warp.square_to_uniform_cone_pdf(local, self.cos_outer)
            ray = mi.Ray3f(mi.Point3f(self.position), d, time)
            weight = mi.Color3f(self.intensity) * (self.profile(d) / pdf)
            return ray, mi.Spectrum(dr.select(active, weight, 0.0))

        def sample_direction(self, it, sample, active=True):
            p = mi.Point3f(self.position)
            ds = dr.zeros(mi.DirectionSample3f)
            ds.p = p
            ds.n = 0.0
            ds.uv = 0.0
            ds.time = it.time
            ds.pdf = 1.0
            ds.delta = True
            ds.emitter = mi.EmitterPtr(self)
            to = p - it.p
            dist2 = dr.squared_norm(to)
            ds.dist = dr.sqrt(dist2)
            ds.d = to / ds.dist
            weight = mi.Color3f(self.intensity) * (self.profile(-ds.d) / dist2)
            return ds, mi.Spectrum(dr.select(active, weight, 0.0))

        def pdf_direction(self, it, ds, active=True):
            return mi.Float(0.0)

        def eval_direction(self, it, ds, active=True):
            d = ds.p - it.p
            dist2 = dr.squared_norm(d)
            return mi.Spectrum(mi.Color3f(self.intensity) * (self.profile(-d / dr.sqrt(dist2)) / dist2))

        def sample_position(self, time, sample, active=True):
            ps = dr.zeros(mi.PositionSample3f)
            ps.p = mi.Point3f(self.position)
            ps.time = time
            ps.pdf = 1.0
            ps.delta = True
            return ps, mi.Float(1.0)

        def pdf_position(self, ps, active=True):
            return mi.Float(0.0)

        def eval(self, si, active=True):
            return mi.Spectrum(0.0)

        def sample_wavelengths(self, si, sample, active=True):
            return dr.zeros(mi.Color0f), mi.Spectrum(1.0)

        def bbox(self):
            return mi.ScalarBoundingBox3f(mi.ScalarPoint3f(self.position), mi.ScalarPoint3f(self.position))

        def traverse(self, callback):
            pass

        def to_string(self):
            return f"GltfSpot[position={self.position}, axis={self.axis}]"

    mi.register_bsdf("vsgl_gltf", lambda props: GltfBRDF(props))
    mi.register_emitter("vsgl_spot", lambda props: GltfSpot(props))


# --- The shared scene ---------------------------------------------------------------------------


def camera_of(scene) -> vsgl.Camera:
    """The scene's own camera, or vsgl's default framing of its bounds
    (crates/vsgl-core/src/renderer/mod.rs, default_camera), made explicit so both renderers get it."""
    if scene.cameras:
        return scene.cameras[0]
    lo, hi = (np.array(b, np.float64) for b in scene.bounds)
    c = 0.5 * (lo + hi)
    r = 0.5 * max(float(np.linalg.norm(hi - lo)), 1e-12)
    dist = r / np.sin(np.radians(22.5))
    eye = c + np.array([0.0, 0.6, 1.0]) / np.linalg.norm([0.0, 0.6, 1.0]) * dist
    return vsgl.Camera.look_at(eye=tuple(eye), target=tuple(c), up=(0.0, 1.0, 0.0), fov_y_deg=45.0)


def material_params(m: dict) -> dict:
    base = np.array(m["base_color"][:3], np.float64).clip(0.0, None)
    metallic = float(np.clip(m["metallic"], 0.0, 1.0))
    roughness = float(np.clip(m["roughness"], 0.0, 1.0))
    rd = base * (1.0 - metallic)
    rs = (1.0 - metallic) * 0.04 * float(m["specular"]) + metallic * base
    return {"rd": rd, "rs": rs, "alpha": max(roughness * roughness, 1.0e-4)}


def camera_side(m: dict, camera_roughness: float) -> bool:
    """Whether paths ending (eye side) on material m are left to the camera part: glossy ones
    (roughness <= camera_roughness with some specular reflectance), where connecting a light path
    to the eye through a near-delta lobe gives the light tracer fireflies that do not average out."""
    p = material_params(m)
    return float(m["roughness"]) <= camera_roughness and float(np.sum(p["rs"])) > 0.0


def mitsuba_scene(mi, scene, cam, size: int, spp_per_pass: int, camera_roughness: float, unit: float = 1.0):
    """The vsgl scene as a Mitsuba scene (the integrator is passed to mi.render), the meshes and
    names of its camera-side (glossy) materials, and all its meshes (one per material).
    Lengths are divided by ``unit`` and point and spot intensities by unit², which leaves every
    radiance as it is (I/d² is unchanged; directional lights are given as irradiance)."""
    tri = scene.triangles()
    pos = np.asarray(tri["positions"], np.float64) / unit
    nrm = np.asarray(tri["normals"], np.float64)
    mat = np.asarray(tri["material"], np.int64)
    # Surfaces are double-sided, so the winding is free: make each triangle's geometric normal
    # agree with its vertex normals, so Mitsuba's shading-normal leak test keeps the light that
    # vsgl (which flips both normals to the viewer's side) keeps.
    ng = np.cross(pos[:, 1] - pos[:, 0], pos[:, 2] - pos[:, 0])
    back = np.einsum("tj,tj->t", ng, nrm.sum(axis=1)) < 0.0
    pos[back] = pos[back][:, ::-1]
    nrm[back] = nrm[back][:, ::-1]
    d = {"type": "scene"}
    glossy, glossy_names, meshes = [], [], []
    for k, m in enumerate(scene.materials):
        sel = mat == k
        if not sel.any():
            continue
        p = material_params(m)
        hidden = camera_side(m, camera_roughness)
        bsdf = mi.load_dict({"type": "vsgl_gltf", "alpha": p["alpha"], "sensor_hidden": hidden,
                             **{f"rd_{c}": float(v) for c, v in zip("rgb", p["rd"])},
                             **{f"rs_{c}": float(v) for c, v in zip("rgb", p["rs"])}})
        n = int(sel.sum())
        props = mi.Properties()
        props["bsdf"] = bsdf
        mesh = mi.Mesh(f"mat{k}", 3 * n, n, props=props, has_vertex_normals=True, has_vertex_texcoords=False)
        params = mi.traverse(mesh)
        params["vertex_positions"] = mi.Float(pos[sel].reshape(-1).astype(np.float32))
        params["vertex_normals"] = mi.Float(nrm[sel].reshape(-1).astype(np.float32))
        params["faces"] = mi.UInt32(np.arange(3 * n, dtype=np.uint32))
        params.update()
        d[f"mesh{k}"] = mesh
        meshes.append(mesh)
        if hidden:
            glossy.append(mesh)
            glossy_names.append(m["name"])
    for i, light in enumerate(scene.lights):
        color = np.array(light.color, np.float64)
        if isinstance(light, vsgl.SpotLight):
            d[f"light{i}"] = {
                "type": "vsgl_spot",
                **dict(zip(("px", "py", "pz"), (float(c) / unit for c in light.position))),
                **dict(zip(("dx", "dy", "dz"), map(float, light.direction))),
                **dict(zip(("ir", "ig", "ib"), map(float, light.intensity * color / unit**2))),
                "cos_inner": float(np.cos(np.radians(light.inner_cone_deg))),
                "cos_outer": float(np.cos(np.radians(light.outer_cone_deg))),
            }
        elif isinstance(light, vsgl.PointLight):
            d[f"light{i}"] = {"type": "point", "position": [float(c) / unit for c in light.position],
                              "intensity": {"type": "rgb", "value": [float(c) for c in light.intensity * color / unit**2]}}
        elif isinstance(light, vsgl.DirectionalLight):
            d[f"light{i}"] = {"type": "directional", "direction": list(map(float, light.direction)),
                              "irradiance": {"type": "rgb", "value": [float(c) for c in light.intensity * color]}}
        else:
            raise ValueError(f"unsupported light {light!r}")
    eye = np.array(cam.eye, np.float64) / unit
    diag = float(np.linalg.norm(np.subtract(*scene.bounds))) / unit
    d["sensor"] = {
        "type": "perspective",
        "fov_axis": "y",
        "fov": float(cam.fov_y_deg),
        "near_clip": 1e-4 * diag,
        "far_clip": 1e4 * diag + float(np.linalg.norm(eye)),
        "to_world": mi.ScalarTransform4f().look_at(origin=list(eye), target=list(eye + np.array(cam.forward)), up=list(cam.up)),
        "film": {"type": "hdrfilm", "width": size, "height": size, "pixel_format": "rgb",
                 "component_format": "float32", "rfilter": {"type": "box"}},
        "sampler": {"type": "independent", "sample_count": spp_per_pass},
    }
    return mi.load_dict(d), glossy, glossy_names, meshes


def _direct_at(mi, dr, mscene, si, d_in, active):
    """Σ over lights of f(l, −d_in)·⟨n, l⟩·e with a shadow ray, vsgl's rule that the light be on
    the viewer's side of the geometric surface included (d_in: the ray that found si)."""
    bsdf = si.bsdf()
    ctx = mi.BSDFContext()
    total = mi.Color3f(0.0)
    for emitter in mscene.emitters():
        ds, w = emitter.sample_direction(si, mi.Point2f(0.5, 0.5), active)
        ok = active & (dr.dot(si.n, -d_in) * dr.dot(si.n, ds.d) > 0.0)
        ok &= ~mscene.ray_test(si.spawn_ray_to(ds.p), ok)
        f = bsdf.eval(ctx, si, si.to_local(ds.d), ok)
        total += dr.select(ok, mi.Color3f(f * w), 0.0)
    return total


def _seeded_sampler(mi, seed: int, wavefront: int):
    sampler = mi.load_dict({"type": "independent"})
    sampler.seed(seed, wavefront)
    return sampler


def mitsuba_camera_part(mi, dr, mscene, glossy, size: int, spp: int, spp_per_pass: int, seed: int, jitter: bool = True):
    """Pixel-area averages of the light of the paths whose eye-side vertex y lies on a glossy
    (camera-side) material, by camera paths: a jittered ray per sample finds y; direct light at y
    from every light, and one bounce: y's BRDF sampled (the plugin's mixture), x found, x's direct
    light reflected. Returns (direct, indirect), (H, W, 3). The light tracer leaves exactly these
    paths out (sensor_hidden), so the two parts add up to every path once. ``jitter=False``: every
    camera ray through the pixel centre (what vsgl's strategy="camera" estimates)."""
    npix = size * size
    acc = {"direct": np.zeros((npix, 3)), "indirect": np.zeros((npix, 3))}
    if not glossy:
        return tuple(a.reshape(size, size, 3) for a in acc.values())
    sensor = mscene.sensors()[0]
    ctx = mi.BSDFContext()
    done, pass_index = 0, 0
    while done < spp:
        k = min(spp_per_pass, spp - done)
        sampler = _seeded_sampler(mi, (seed * 1000003 + pass_index) & 0xFFFFFFFF, npix * k)
        idx = dr.arange(mi.UInt32, npix * k)
        pix = idx // k
        px = mi.Float(pix % size)
        py = mi.Float(pix // size)
        jx, jy = (sampler.next_1d(), sampler.next_1d()) if jitter else (0.5, 0.5)
        pos = mi.Point2f((px + jx) / size, (py + jy) / size)
        ray, _ = sensor.sample_ray(0.0, 0.5, pos, mi.Point2f(0.5, 0.5))
        si = mscene.ray_intersect(ray)
        on = mi.Bool(False)
        for mesh in glossy:
            on |= si.shape == mi.ShapePtr(mesh)
        on &= si.is_valid()
        direct = _direct_at(mi, dr, mscene, si, ray.d, on)
        bs, w = si.bsdf().sample(ctx, si, sampler.next_1d(), sampler.next_2d(), on)
        wo = si.to_world(bs.wo)
        go = on & (bs.pdf > 0.0) & (dr.dot(si.n, wo) * dr.dot(si.n, -ray.d) > 0.0)
        ray2 = si.spawn_ray(wo)
        si2 = mscene.ray_intersect(ray2, go)
        go &= si2.is_valid()
        indirect = dr.select(go, mi.Color3f(w) * _direct_at(mi, dr, mscene, si2, ray2.d, go), 0.0)
        for key, value in (("direct", direct), ("indirect", indirect)):
            acc[key] += np.array(value, np.float64).T.reshape(npix, k, 3).sum(axis=1)
        done += k
        pass_index += 1
    return tuple((a / spp).reshape(size, size, 3) for a in acc.values())


def mitsuba_centre_direct(mi, dr, mscene, size: int) -> np.ndarray:
    """Direct light at each pixel centre (what vsgl's ``direct`` AOV holds): the camera ray
    through (px + 0.5, py + 0.5), the first hit, every light with a shadow ray. Deterministic."""
    sensor = mscene.sensors()[0]
    idx = dr.arange(mi.UInt32, size * size)
    px = mi.Float(idx % size)
    py = mi.Float(idx // size)
    pos = mi.Point2f((px + 0.5) / size, (py + 0.5) / size)
    ray, _ = sensor.sample_ray(0.0, 0.5, pos, mi.Point2f(0.5, 0.5))
    si = mscene.ray_intersect(ray)
    total = _direct_at(mi, dr, mscene, si, ray.d, si.is_valid())
    out = np.array(total, np.float64).T  # (pixels, 3)
    return out.reshape(size, size, 3)


def render_mitsuba(mi, dr, mscene, glossy, size: int, spp: int, spp_per_pass: int, seeds) -> dict:
    """Per seed: the light tracer's part (ptracer max_depth 3 and 2, same seed, paths ending on a
    camera-side material left out) plus the camera part. Lists of (H, W, 3) images under
    'image', 'direct', 'indirect', and the parts under 'pt_*' / 'cam_*'."""
    out = {k: [] for k in ("image", "direct", "indirect", "pt_direct", "pt_indirect", "cam_direct", "cam_indirect")}
    integrators = {depth: mi.load_dict({"type": "ptracer", "max_depth": depth, "rr_depth": 1000,
                                         "hide_emitters": True, "samples_per_pass": spp_per_pass})
                   for depth in (2, 3)}
    for seed in seeds:
        img = np.array(mi.render(mscene, integrator=integrators[3], seed=seed, spp=spp), np.float64)
        pt_dir = np.array(mi.render(mscene, integrator=integrators[2], seed=seed, spp=spp), np.float64)
        cam_dir, cam_ind = mitsuba_camera_part(mi, dr, mscene, glossy, size, spp, spp_per_pass, seed)
        out["pt_direct"].append(pt_dir)
        out["pt_indirect"].append(img - pt_dir)
        out["cam_direct"].append(cam_dir)
        out["cam_indirect"].append(cam_ind)
        out["direct"].append(pt_dir + cam_dir)
        out["indirect"].append(img - pt_dir + cam_ind)
        out["image"].append(img + cam_dir + cam_ind)
    return out


# --- Comparison ---------------------------------------------------------------------------------


def ratio(x, ref) -> float:
    r = float(np.mean(ref))
    return float(np.mean(x)) / r if r > 0.0 else float("nan")


def block_err(x, ref) -> float:
    """vsgl.metrics.block_rmse with 4×4 blocks (‖B(x) − B(ref)‖/‖B(ref)‖, B the 4×4 block means)."""
    if not np.any(ref):
        return float("nan")
    return metrics.block_rmse(np.asarray(x, np.float64), np.asarray(ref, np.float64), BLOCK)


def _block_counts(shape) -> np.ndarray:
    """Pixels per 4×4 block (edge blocks hold fewer), shaped like metrics.block_means' output."""
    heights = np.minimum(BLOCK, shape[0] - np.arange(0, shape[0], BLOCK))
    widths = np.minimum(BLOCK, shape[1] - np.arange(0, shape[1], BLOCK))
    return np.outer(heights, widths).reshape(len(heights), len(widths), *([1] * (len(shape) - 2)))


def vsgl_noise(x, stderr) -> tuple[float, float]:
    """vsgl's own relative error: per pixel sqrt(mean(stderr²))/rms(x), and that of the 4×4 block
    means (metrics.block_means: a block's stderr² averaged over it, over its pixel count, is the
    variance of its mean) relative to ‖B(x)‖."""
    x = np.asarray(x, np.float64)
    s2 = np.asarray(stderr, np.float64) ** 2
    rms = float(np.sqrt(np.mean(x**2)))
    if rms == 0.0:
        return float("nan"), float("nan")
    pixel = float(np.sqrt(np.mean(s2))) / rms
    var_b = metrics.block_means(s2, BLOCK) / _block_counts(s2.shape)
    block = float(np.sqrt(np.sum(var_b)) / np.sqrt(np.sum(metrics.block_means(x, BLOCK) ** 2)))
    return pixel, block


def seed_noise(a, b) -> tuple[float, float]:
    """The error of the mean m = (a + b)/2 of two seeds, from their difference: per pixel
    rms(a − b)/2 / rms(m), and of the 4×4 block means ‖B(a) − B(b)‖/2 / ‖B(m)‖."""
    a, b = np.asarray(a, np.float64), np.asarray(b, np.float64)
    m = 0.5 * (a + b)
    rms = float(np.sqrt(np.mean(m**2)))
    if rms == 0.0:
        return float("nan"), float("nan")
    pixel = 0.5 * float(np.sqrt(np.mean((a - b) ** 2))) / rms
    ba, bb, bm = (metrics.block_means(v, BLOCK) for v in (a, b, m))
    block = 0.5 * float(np.sqrt(np.sum((ba - bb) ** 2)) / np.sqrt(np.sum(bm**2)))
    return pixel, block


def orientation(x, ref) -> str:
    """Which of the image, its left-right and up-down flips matches ``ref`` best (block error);
    a flip that matches as well as the image itself means the view is symmetric under it."""
    cands = {"as is": x, "flipped L-R": x[:, ::-1], "flipped U-D": x[::-1]}
    errs = {k: block_err(v, ref) for k, v in cands.items()}
    best = min(errs.values())
    ties = [k for k in ("flipped L-R", "flipped U-D") if errs[k] <= best + 1e-3]
    if errs["as is"] <= best + 1e-3:
        verdict = "as is" + (f" (the view is symmetric: {', '.join(ties)} matches as well)" if ties else "")
    else:
        verdict = "FLIPPED: " + min(errs, key=lambda k: errs[k])
    return verdict + " [" + ", ".join(f"{k} {v:.4f}" for k, v in errs.items()) + "]"


def mean_sigma(x, x_se2_sum, ref, ref_se2_sum) -> float:
    """Standard error of ratio(x, ref) from the two images' per-pixel variances (summed)."""
    n = np.asarray(x).size
    mx, mr = float(np.mean(x)), float(np.mean(ref))
    if mr <= 0.0 or mx <= 0.0:
        return float("nan")
    return (mx / mr) * float(np.sqrt(x_se2_sum / (n * mx) ** 2 + ref_se2_sum / (n * mr) ** 2))


def vsgl_area_direct(scene, cam, size: int, factor: int) -> np.ndarray:
    """vsgl's direct light averaged over each pixel's area: the pathtrace ``direct`` AOV (traced,
    deterministic, at the pixel centre) at factor× the resolution, averaged over factor×factor
    sub-pixels (their centres are a stratified grid over the pixel)."""
    r = vsgl.Renderer(width=size * factor, height=size * factor)
    f = r.render(scene, camera=cam, method="pathtrace", spp=1, seed=1, strategy="camera", aovs=["direct"])
    d = np.asarray(f.aov("direct"), np.float64)
    return d.reshape(size, factor, size, factor, 3).mean(axis=(1, 3))


def cross_checks(mi, dr, mscene, meshes, scene, cam, args, renderer) -> dict:
    """Each side against itself by another strategy: Mitsuba's camera paths for every path
    (every material camera-side; pixel-area averages, and pixel centres), and vsgl's
    strategy="camera" (pixel centres, no light tracing)."""
    size, spp, seeds = args.size, args.mitsuba_spp, range(101, 101 + args.mitsuba_seeds)
    out = {}
    for key, jitter in (("mts_cam_area", True), ("mts_cam_centre", False)):
        runs = [mitsuba_camera_part(mi, dr, mscene, meshes, size, spp, args.spp_per_pass, s, jitter=jitter)[1] for s in seeds]
        out[key] = np.mean(runs, axis=0)
        out[key + "_noise"] = seed_noise(np.mean(runs[0::2], axis=0), np.mean(runs[1::2], axis=0))
    f = renderer.render(scene, camera=cam, method="pathtrace", spp=args.spp, seed=args.seed, strategy="camera",
                        aovs=["indirect", "stderr"])
    out["vsgl_camera"] = np.asarray(f.aov("indirect"), np.float64)
    out["vsgl_camera_noise"] = vsgl_noise(out["vsgl_camera"], np.asarray(f.aov("stderr"), np.float64))
    return out


def load_scene(name: str):
    if name in vsgl.scenes.names():
        return vsgl.scenes.load(name), None
    if name in TEXTURED:
        return None, "textured (base colour, metallic-roughness and normal textures are not given to Mitsuba here): skipped"
    if name not in vsgl.scenes.corpus_names():
        raise SystemExit(f"--scenes: unknown scene {name!r}")
    if not vsgl.scenes.corpus_available(name):
        return None, f"its file is not under {vsgl.scenes.shared_scenes_dir()}: skipped"
    scene = vsgl.scenes.corpus_scene(name).scene
    if any(m["textures"] for m in scene.materials):
        return None, "textured: skipped"
    return scene, None


def drop_emission(scene) -> list[str]:
    """Emission lights nothing in vsgl; only the camera sees it. Mitsuba's emitters would light
    the scene, so emission is turned off in vsgl for the comparison (both sides without it)."""
    names = sorted({m["name"] for m in scene.materials if any(v > 0.0 for v in m["emissive"])})
    for n in names:
        scene.set_material(n, emissive=(0.0, 0.0, 0.0))
    return names


def compare_scene(mi, dr, name, scene, args, renderer) -> tuple[dict, dict]:
    size = args.size
    cam = camera_of(scene)
    t0 = time.perf_counter()
    f = renderer.render(scene, camera=cam, method="pathtrace", spp=args.spp, seed=args.seed,
                        aovs=["image", "indirect", "direct", "stderr", "depth"])
    t_vsgl = time.perf_counter() - t0
    v = {k: np.asarray(f.aov(k), np.float64) for k in ("image", "indirect", "direct", "stderr")}
    # Pixels whose centre sees no surface (depth 0): vsgl's camera strategy leaves them at 0; its
    # bidirectional default (since this comparison found the gap) takes their area's light.
    background = np.asarray(f.aov("depth"), np.float64).reshape(size, size) == 0.0
    v_area_direct = vsgl_area_direct(scene, cam, size, args.supersample)

    # The scene's diagonal is MITSUBA_DIAGONAL units in Mitsuba (see the module docstring).
    unit = float(np.linalg.norm(np.subtract(*scene.bounds))) / MITSUBA_DIAGONAL if args.mitsuba_units == "scene" else 1.0
    mscene, glossy, glossy_names, meshes = mitsuba_scene(mi, scene, cam, size, args.spp_per_pass, args.camera_roughness, unit)
    mc = mitsuba_centre_direct(mi, dr, mscene, size)
    t0 = time.perf_counter()
    m = render_mitsuba(mi, dr, mscene, glossy, size, args.mitsuba_spp, args.spp_per_pass, seeds=range(1, args.mitsuba_seeds + 1))
    t_mts = time.perf_counter() - t0
    mean = {k: np.mean(m[k], axis=0) for k in m}
    half = {k: (np.mean(m[k][0::2], axis=0), np.mean(m[k][1::2], axis=0)) for k in m}
    # m = (a + b)/2 for a, b the means of two halves of the seeds: E[((a − b)/2)²] = Var(m), so
    # the halves' spread is the error of the mean of all seeds as it stands.
    image_c = mc + mean["indirect"]
    # A scene without indirect light (a lone plane): vsgl's is 0, Mitsuba's the rounding of its
    # same-seed difference.
    no_indirect = not np.any(v["indirect"]) and abs(float(mean["indirect"].mean())) <= 1e-4 * float(mean["image"].mean())
    covered = ~background[..., None]
    x = cross_checks(mi, dr, mscene, meshes, scene, cam, args, renderer) if args.cross_check and not no_indirect else None
    nan2 = (float("nan"), float("nan"))
    row = {
        "scene": name, "strategy": f.settings.get("strategy", "?"), "unit": unit, "camera_side": glossy_names,
        "ind_v": float(v["indirect"].mean()), "ind_m": float(mean["indirect"].mean()),
        "ind_ratio": float("nan") if no_indirect else ratio(v["indirect"], mean["indirect"]),
        # Mitsuba's per-pixel variance of its mean from the two halves of its seeds: ((a − b)/2)².
        "ind_sigma": float("nan") if no_indirect else mean_sigma(
            v["indirect"], float(np.sum(v["stderr"] ** 2)), mean["indirect"],
            float(np.sum(((half["indirect"][0] - half["indirect"][1]) / 2.0) ** 2))),
        "ind_blk": float("nan") if no_indirect else block_err(v["indirect"], mean["indirect"]),
        "cam_share": float(mean["cam_indirect"].mean() / mean["indirect"].mean()) if not no_indirect else float("nan"),
        "img_ratio": ratio(v["image"], mean["image"]), "img_blk": block_err(v["image"], mean["image"]),
        "imgc_ratio": ratio(v["image"], image_c), "imgc_blk": block_err(v["image"], image_c),
        "dir_ratio": ratio(v["direct"], mc), "dir_blk": block_err(v["direct"], mc),
        "dir_maxrel": float(np.max(np.abs(v["direct"] - mc)) / max(float(np.max(mc)), 1e-30)),
        "orientation": orientation(v["direct"], mc) if np.any(mc) else "-",
        "adir_ratio": ratio(v_area_direct, mean["direct"]), "adir_blk": block_err(v_area_direct, mean["direct"]),
        "m_ac_ratio": ratio(mean["direct"], mc), "m_ac_blk": block_err(mean["direct"], mc),
        "bg_share": float("nan") if no_indirect else float((mean["indirect"] * ~covered).sum() / mean["indirect"].sum()),
        "bg_ratio": float("nan") if no_indirect else ratio(v["indirect"], mean["indirect"] * covered),
        "bg_blk": float("nan") if no_indirect else block_err(v["indirect"], mean["indirect"] * covered),
        "v_noise_ind": nan2 if no_indirect else vsgl_noise(v["indirect"], v["stderr"]),
        "v_noise_img": vsgl_noise(v["image"], v["stderr"]),
        "m_noise_ind": nan2 if no_indirect else seed_noise(*half["indirect"]),
        "m_noise_img": seed_noise(*half["image"]),
        "m_noise_adir": seed_noise(*half["direct"]),
        "t_vsgl": t_vsgl, "t_mts": t_mts,
    }
    if x is not None:
        row.update({
            "x_cam_ratio": ratio(x["mts_cam_area"], mean["indirect"]), "x_cam_blk": block_err(x["mts_cam_area"], mean["indirect"]),
            "x_cam_noise": x["mts_cam_area_noise"],
            "x_vcam_ratio": ratio(x["vsgl_camera"], x["mts_cam_centre"]), "x_vcam_blk": block_err(x["vsgl_camera"], x["mts_cam_centre"]),
            "x_vcam_noise": float(np.hypot(x["vsgl_camera_noise"][1], x["mts_cam_centre_noise"][1])),
            "x_bg_ratio": ratio(v["indirect"], x["mts_cam_area"] * covered), "x_bg_blk": block_err(v["indirect"], x["mts_cam_area"] * covered),
        })
    arrays = {f"{name}.vsgl.{k}": a for k, a in v.items()}
    arrays[f"{name}.vsgl.direct_area"] = v_area_direct
    arrays[f"{name}.mitsuba.direct_centre"] = mc
    for k in ("image", "indirect", "direct", "cam_indirect"):
        for i, a in enumerate(m[k]):
            arrays[f"{name}.mitsuba.{k}.seed{i + 1}"] = a
    return row, {k: a.astype(np.float32) for k, a in arrays.items()}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default=",".join(DEFAULT_SCENES), help="comma-separated (default: %(default)s)")
    ap.add_argument("--size", type=int, default=48, help="image side in pixels (default 48)")
    ap.add_argument("--spp", type=int, default=4096, help="vsgl pathtrace samples per pixel (default 4096)")
    ap.add_argument("--mitsuba-spp", type=int, default=32768,
                    help="Mitsuba samples per pixel per seed: ptracer light paths = spp × pixels, and as many camera paths (default 32768)")
    ap.add_argument("--mitsuba-seeds", type=int, default=2, help="independent Mitsuba seeds, averaged (even, >= 2: the spread of their two halves is Mitsuba's own error)")
    ap.add_argument("--spp-per-pass", type=int, default=1024, help="Mitsuba samples per pixel per wavefront pass (memory; default 1024)")
    ap.add_argument("--camera-roughness", type=float, default=0.2,
                    help="paths whose eye-side vertex is on a material this smooth (or smoother) are taken by camera paths, "
                         "the rest by the light tracer (default 0.2; -1: the light tracer takes every path)")
    ap.add_argument("--mitsuba-units", choices=("scene", "world"), default="scene",
                    help="lengths given to Mitsuba: scaled so the scene's bounds diagonal is 10 units (default), or as they are "
                         "(world); see the module docstring for why")
    ap.add_argument("--supersample", type=int, default=8, help="sub-pixels per side of vsgl's area-averaged direct check (default 8)")
    ap.add_argument("--no-cross-check", dest="cross_check", action="store_false",
                    help="leave out the cross-checks (Mitsuba camera paths for every path; vsgl strategy=\"camera\")")
    ap.add_argument("--variant", default="llvm_ad_rgb", help="Mitsuba variant (default llvm_ad_rgb; scalar_rgb works without LLVM, slowly)")
    ap.add_argument("--seed", type=int, default=1, help="vsgl seed (default 1)")
    ap.add_argument("--out", default="out/mitsuba/", help="output folder (default %(default)s)")
    ap.add_argument("--name", default="truth", help="output file name without extension (default %(default)s)")
    ap.add_argument("--save-images", action="store_true", help="also write NAME.npz with every image")
    args = ap.parse_args(argv)
    if args.mitsuba_seeds < 2 or args.mitsuba_seeds % 2:
        ap.error("--mitsuba-seeds: an even number >= 2 (two equal halves give Mitsuba's own error)")

    mi, dr = load_mitsuba(args.variant)
    out_dir = pathlib.Path(args.out)
    out_dir.mkdir(parents=True, exist_ok=True)
    given = sys.argv[1:] if argv is None else list(argv)
    command = " ".join(["XDG_RUNTIME_DIR=/tmp python experiments/mitsuba_truth.py"] + [shlex.quote(a) for a in given])
    renderer = vsgl.Renderer(width=args.size, height=args.size)
    rows, notes, arrays = [], [], {}
    t_all = time.perf_counter()
    for name in [s.strip() for s in args.scenes.split(",") if s.strip()]:
        scene, why = load_scene(name)
        if scene is None:
            print(f"{name}: {why}", flush=True)
            notes.append(f"{name}: {why}")
            continue
        emissive = drop_emission(scene)
        if emissive:
            notes.append(f"{name}: emission of {', '.join(emissive)} set to 0 in vsgl (there it only shows to the camera and lights nothing; "
                         "in Mitsuba it would light the scene)")
        row, arr = compare_scene(mi, dr, name, scene, args, renderer)
        rows.append(row)
        arrays.update(arr)
        print(f"{name}: indirect vsgl/Mitsuba {row['ind_ratio']:.4f} blk4 {row['ind_blk']:.4f}; image {row['img_ratio']:.4f} "
              f"blk4 {row['img_blk']:.4f}; direct (centre) {row['dir_ratio']:.5f} blk4 {row['dir_blk']:.5f}; "
              f"vsgl {row['t_vsgl']:.1f} s, Mitsuba {row['t_mts']:.1f} s", flush=True)
    text = format_report(command, args, rows, notes, mi, time.perf_counter() - t_all)
    (out_dir / f"{args.name}.txt").write_text(text)
    if args.save_images:
        np.savez_compressed(out_dir / f"{args.name}.npz", **arrays)
    print(text)
    return 0


def _f(x, w=8, p=4):
    if isinstance(x, float) and not np.isfinite(x):
        return format("-", f">{w}")
    return format(x, f">{w}.{p}f")


def _pair(t):
    if not np.isfinite(t[0]):
        return format("-", ">16")
    return f"{t[0]:>8.4f}/{t[1]:<7.4f}"


def format_report(command, args, rows, notes, mi, wall) -> str:
    L = [f"# {command}", ""]
    split = (f"ptracer for paths whose eye-side vertex has roughness > {args.camera_roughness:g}, camera paths for the rest. "
             if args.camera_roughness >= 0.0 else "ptracer for every path. ")
    L.append(f"vsgl {vsgl.__version__} pathtrace (default strategy), {args.size}x{args.size}, {args.spp} spp, seed {args.seed}, lavapipe. "
             f"Mitsuba {mi.__version__} {args.variant}, {args.mitsuba_seeds} seeds x {args.mitsuba_spp} spp, box filter, no Russian roulette: "
             + split + f"Whole run {wall:.0f} s.")
    L.append(f"ratio = mean(vsgl)/mean(Mitsuba) over pixels and channels; blk4 = vsgl.metrics.block_rmse(vsgl, Mitsuba, 4). "
             f"Acceptance on {', '.join(BUILTIN)}: |ratio - 1| <= {ACCEPT_MEAN}, blk4 <= {ACCEPT_BLOCK}.")
    L.append("")
    L.append("## The gap")
    L.append("indirect: vsgl 'indirect' vs Mitsuba's one-bounce light (ptracer max_depth 3 - max_depth 2, same seed; + camera part). "
             "+-: the ratio's standard error from both renderers' own errors. cam: the camera part's share of Mitsuba's indirect.")
    L.append("image: vsgl 'image' (its direct is the pixel centre's) vs Mitsuba's (area-averaged direct + indirect); "
             "image_c: vs Mitsuba's centre direct + its indirect (like for like).")
    hdr = f"{'scene':<22}{'ind vsgl':>10}{'ind mts':>10}{'ratio':>8}{'+-':>8}{'blk4':>8}{'cam':>6} |{'image':>8}{'blk4':>8} |{'image_c':>8}{'blk4':>8}"
    L += [hdr, "-" * len(hdr)]
    for r in rows:
        L.append(f"{r['scene']:<22}{_f(r['ind_v'], 10, 5)}{_f(r['ind_m'], 10, 5)}{_f(r['ind_ratio'])}{_f(r['ind_sigma'])}{_f(r['ind_blk'])}{_f(r['cam_share'], 6, 2)} |"
                 f"{_f(r['img_ratio'])}{_f(r['img_blk'])} |{_f(r['imgc_ratio'])}{_f(r['imgc_blk'])}")
    L.append("")
    L.append("## Where the indirect gap sits (cross-checks)")
    L.append("bg: share of Mitsuba's indirect in pixels whose centre sees no surface; vsgl's strategy=\"camera\" leaves those pixels at 0, "
             "its bidirectional default takes the part of their area that covers a surface. excl bg: vsgl vs Mitsuba with those pixels zeroed in "
             "Mitsuba too. M cam/M: Mitsuba's camera paths for every path (area averages) vs the light-tracer-based result above (noise: the "
             "camera paths' own block error). v cam/M cam: vsgl strategy=\"camera\" vs Mitsuba's camera paths, both at pixel centres "
             "(noise: both block errors combined). excl bg (M cam): vsgl vs Mitsuba's camera paths with the background-centre pixels zeroed. "
             "Camera paths alone do not converge on caustics (mirror_panel, caustics_ring: see their noise); there the cross-checks say nothing.")
    hdr = (f"{'scene':<22}{'bg':>7} |{'excl bg':>8}{'blk4':>8} |{'M cam/M':>8}{'blk4':>8}{'noise':>8} |"
           f"{'v cam/M cam':>12}{'blk4':>8}{'noise':>8} |{'excl bg (M cam)':>16}{'blk4':>8}")
    L += [hdr, "-" * len(hdr)]
    for r in rows:
        g = lambda k: r.get(k, float("nan"))  # noqa: E731
        L.append(f"{r['scene']:<22}{_f(g('bg_share'), 7)} |{_f(g('bg_ratio'))}{_f(g('bg_blk'))} |"
                 f"{_f(g('x_cam_ratio'))}{_f(g('x_cam_blk'))}{_f(g('x_cam_noise')[1] if 'x_cam_noise' in r else float('nan'))} |"
                 f"{_f(g('x_vcam_ratio'), 12)}{_f(g('x_vcam_blk'))}{_f(g('x_vcam_noise'))} |{_f(g('x_bg_ratio'), 16)}{_f(g('x_bg_blk'))}")
    L.append("")
    L.append("## Each renderer's own error (relative, per pixel / of the 4x4 block means) and time")
    L.append("vsgl: sqrt(mean(stderr^2))/rms, and the block means' stderr (block-averaged stderr^2 over the pixel count) over their norm; "
             "Mitsuba: from its seeds' spread. noise: sqrt(vsgl^2 + Mitsuba^2) of the block figures, the blk4 that noise alone gives.")
    hdr = f"{'scene':<22}{'vsgl ind':>16}{'mts ind':>16}{'noise':>8} |{'vsgl img':>16}{'mts img':>16}{'noise':>8} |{'vsgl s':>8}{'mts s':>8}"
    L += [hdr, "-" * len(hdr)]
    for r in rows:
        nb_i = float(np.hypot(r["v_noise_ind"][1], r["m_noise_ind"][1]))
        nb_m = float(np.hypot(r["v_noise_img"][1], r["m_noise_img"][1]))
        L.append(f"{r['scene']:<22}{_pair(r['v_noise_ind'])}{_pair(r['m_noise_ind'])}{_f(nb_i)} |"
                 f"{_pair(r['v_noise_img'])}{_pair(r['m_noise_img'])}{_f(nb_m)} |{r['t_vsgl']:>8.1f}{r['t_mts']:>8.1f}")
    L.append("")
    L.append("## Direct light (materials, lights, camera)")
    L.append("centre: vsgl 'direct' vs Mitsuba's deterministic pixel-centre direct light (maxrel = max|diff| / max(Mitsuba)). "
             f"area: vsgl's direct averaged over {args.supersample}x{args.supersample} sub-pixels vs Mitsuba's area-averaged direct "
             "(ptracer max_depth 2 + camera part; mts err its own block error). mts a/c: Mitsuba's area vs its centre direct "
             "(the sampling-position difference alone).")
    hdr = f"{'scene':<22}{'centre':>10}{'blk4':>10}{'maxrel':>10} |{'area':>8}{'blk4':>8}{'mts err':>9} |{'mts a/c':>8}{'blk4':>8}"
    L += [hdr, "-" * len(hdr)]
    for r in rows:
        L.append(f"{r['scene']:<22}{_f(r['dir_ratio'], 10, 6)}{_f(r['dir_blk'], 10, 6)}{_f(r['dir_maxrel'], 10, 6)} |"
                 f"{_f(r['adir_ratio'])}{_f(r['adir_blk'])}{_f(r['m_noise_adir'][1], 9)} |{_f(r['m_ac_ratio'])}{_f(r['m_ac_blk'])}")
    L.append("")
    L.append("## Checks")
    for r in rows:
        L.append(f"{r['scene']}: vsgl strategy {r['strategy']}; Mitsuba length unit {r['unit']:.4g}; camera-side materials {r['camera_side'] or 'none'}; "
                 f"orientation by the direct light (blk4 of vsgl's direct, and of its flips, vs Mitsuba's): {r['orientation']}")
    for r in rows:
        if r["scene"] in BUILTIN:
            ok_m = abs(r["ind_ratio"] - 1.0) <= ACCEPT_MEAN and abs(r["img_ratio"] - 1.0) <= ACCEPT_MEAN
            ok_b = r["ind_blk"] <= ACCEPT_BLOCK and r["img_blk"] <= ACCEPT_BLOCK
            L.append(f"{r['scene']}: acceptance (indirect and image) mean {'met' if ok_m else 'MISSED'}, block {'met' if ok_b else 'MISSED'}")
    if notes:
        L += ["", "## Notes"] + notes
    return "\n".join(L) + "\n"


if __name__ == "__main__":
    sys.exit(main())
