"""vsgl's scenes in Mitsuba 3, for experiments/mitsuba_truth.py (which says, in its docstring,
what is matched and why) and experiments/shadow_target_model.py: loading Mitsuba with the two
plugins that give it vsgl's material model and glTF spot light, the scene export (triangles,
shading normals, materials, lights, camera) and Mitsuba's renders of it (the light tracer's part,
the camera part, the pixel-centre direct light).

Needs Mitsuba 3 (``pip install mitsuba drjit``) only when ``load_mitsuba`` is called; importing
this module does not.
"""

from __future__ import annotations

import glob
import os
import re
import sys

import numpy as np

import vsgl

INSTALL_HINT = (
    "mitsuba_truth.py needs Mitsuba 3 in the Python that runs it:\n"
    "    python -m pip install mitsuba drjit\n"
    "(the default variant llvm_ad_rgb also needs libLLVM 16 or newer, e.g. `apt-get install libllvm19` on Debian "
    "bookworm; the script points DRJIT_LIBLLVM_PATH at the newest one it finds, or set it yourself; "
    "--variant scalar_rgb needs none but is slow)"
)


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
        """vsgl's glTF metallic-roughness BRDF (see mitsuba_truth.py's docstring), double-sided."""

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
        """A glTF spot light: point source, intensity I·colour (cd), smooth cone t² (see mitsuba_truth.py's docstring)."""

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
        if any(float(e) > 0.0 for e in m["emissive"]):
            # An emissive material is a Mitsuba area emitter (one-sided, on the side of the
            # vertex normals, which the winding fix-up above made the geometric side too): vsgl's
            # path tracer's emitter model (upload/emitters.rs). Radiance is unit-free.
            props["emitter"] = mi.load_dict({"type": "area", "radiance": {"type": "rgb", "value": [float(e) for e in m["emissive"]]}})
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
