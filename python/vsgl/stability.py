"""The numerical stability suite: ``python -m vsgl stability [--adapter NAME]``.

Every WGSL math function of vsgl (``wgsl/common/{math,sg,ggx,vsgl}.wgsl``) is evaluated in f32 on
the GPU and by its float64 oracle on the same inputs, over case families with the extremes
(SG sharpness 1e-6…1e9, roughness 1e-4…1, grazing cosines down to 1e-6 and exactly 0,
axes equal / opposite / 1e-7 rad apart, variance down to 1e-12 of d² and 0, scenes 1e5 m from
the origin, intensities 1e-8…1e8, zero power).

Each row is one (function output, case family):

* ``max_rel_error``: max over the cases of ‖gpu − ref‖ / max(‖ref‖, floor), the floor tied to
  the function's scale (docs/numerics.md, "Stability suite");
* ``bound``: the stated bound of the case with that largest error (same denominator). Every case
  has its own bound, a few ULP × the condition number of the formula at that case;
* ``worst_ratio``: max over the cases of ‖gpu − ref‖ / bound (≤ 1 when the row passes);
* ``nonfinite``: cases whose GPU output is NaN or ±Inf (must be 0);
* ``passed``: no NaN/Inf and every case within its bound.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any, Sequence

COLUMNS = ("function", "case family", "cases", "max rel. error", "bound", "err/bound", "NaN/Inf", "pass/fail")


def run(adapter: str | None = None, bound_scale: float = 1.0) -> list[dict[str, Any]]:
    """Runs the suite on ``adapter`` (None: the best adapter, or ``$VSGL_ADAPTER``).

    ``bound_scale`` multiplies every bound; it exists to show that the suite can fail (at 1e-3
    most rows do). Raises ``vsgl.NoAdapterError`` when there is no adapter.
    """
    from vsgl import _vsgl

    return _vsgl.stability_suite(adapter, bound_scale)


def exit_code(rows: Sequence[dict[str, Any]]) -> int:
    """0 when every row passed and no output was NaN/Inf, else 1 (also 1 for an empty table)."""
    if not rows:
        return 1
    ok = all(bool(r["passed"]) and int(r["nonfinite"]) == 0 for r in rows)
    return 0 if ok else 1


def format_table(rows: Sequence[dict[str, Any]]) -> str:
    """The rows as an aligned text table with the columns of ``COLUMNS``."""
    cells = [
        (
            str(r["function"]),
            str(r["family"]),
            str(r["cases"]),
            f"{r['max_rel_error']:.2e}",
            f"{r['bound']:.2e}",
            f"{r['worst_ratio']:.3f}",
            str(r["nonfinite"]),
            "pass" if r["passed"] and int(r["nonfinite"]) == 0 else "FAIL",
        )
        for r in rows
    ]
    widths = [max([len(c)] + [len(row[i]) for row in cells]) for i, c in enumerate(COLUMNS)]
    numeric = {2, 3, 4, 5, 6}

    def line(values: Sequence[str]) -> str:
        return "  ".join(v.rjust(w) if i in numeric else v.ljust(w) for i, (v, w) in enumerate(zip(values, widths))).rstrip()

    out = [line(COLUMNS), line(["-" * w for w in widths])]
    out.extend(line(c) for c in cells)
    return "\n".join(out)


# ---------------------------------------------------------------------------------------------
# The scene-level suite: every method end to end on built-in scenes under stiff and extreme
# transformations.
# ---------------------------------------------------------------------------------------------

SCENE_COLUMNS = ("scene", "method", "case", "rel. RMSE", "bound", "surface px", "flipped px", "NaN/Inf", "pass/fail")

#: Small values of the options that decide a frame's cost, each given to the methods that take
#: it (`small_settings`), so the whole suite runs in about a minute on lavapipe.
SMALL_SETTINGS: dict[str, Any] = {"shadow_size": 256, "num_lights": 64, "rsm_size": 64, "spp": 8, "seed": 1}
#: Interleaving at most this (vsgl's default 8 leaves one of 64 VSGLs per pixel).
SMALL_INTERLEAVE = 4


def small_settings(method: str, **sizes: Any) -> dict[str, Any]:
    """`SMALL_SETTINGS`, with `sizes` over them, for the options `method` takes (from the
    registry, so a new method needs no row anywhere), and its interleave capped at
    `SMALL_INTERLEAVE`."""
    import vsgl

    takes = vsgl.method_options(method)
    settings = {k: v for k, v in {**SMALL_SETTINGS, **sizes}.items() if k in takes}
    if "interleave" in takes and "interleave" not in sizes:
        settings["interleave"] = min(int(takes["interleave"]), SMALL_INTERLEAVE)
    return settings


#: Invariance bound: relative RMSE of an image against the untransformed scene's, over the
#: pixels that did not flip.
INVARIANCE_BOUND = 1e-3
#: A pixel "flips" when it differs by more than 1% from the base. Only the path tracer may flip
#: pixels: its shadow rays are exact and hard, so under the f32 rounding of a scaled scene a ray
#: that grazes an edge can change from hit to miss, moving a pixel (its direct light, or one of
#: its 8 bounce samples) between lit and shadowed. Measured at 32×24, 8 spp: 5–7 of 768 pixels
#: (0.7–0.9%) on cornell_box and glossy_cornell scaled 1e-3 and 1e3, none moved 1e5 m or with
#: scaled intensities. The other methods are continuous in the geometry (filtered shadow maps,
#: virtual lights) and may flip none. The pixels that did not flip must meet INVARIANCE_BOUND.
#:
#: Pixels whose *visible surface* changed are not compared at all ("surface px"): a pixel centre
#: that lies on the edge between two triangles, within the f32 rounding of the transformed
#: vertices, is covered by either, in every method alike, and then shows another surface's light.
#: They are found from the G-buffer (normal turned by more than 0.5°, or depth off by more than
#: 1e-3 relative after undoing the scale), widened by the denoiser's window (offsets −k … k−1
#: of interleave k) where a frame was denoised, since a changed G-buffer pixel changes the
#: filter weights of its neighbours. Seen on an H200: cornell_box and glossy_cornell scaled
#: 1e-3 and 1e3 put 4 pixels of the ceiling/left-wall edge on the wall instead of the ceiling
#: (indirect light 0.03 instead of 0.05 there: 4% of the image's RMS), and lavapipe does the
#: same at scale 0.37 (the "scaled 0.37" case below), while 1e-3 and 1e3 happen to round alike
#: there. At most SURFACE_FRACTION of the pixels may change surface; the rest must be invariant.
SURFACE_FRACTION = 0.02
#: Pixels a method whose direct light it traces itself (exact, hard shadow rays: the registry's
#: direct_light "by_method") may flip; the others may flip none.
TRACED_FLIP_FRACTION = 0.01


#: The scene of the suite that comes from a glTF file (written by `write_room_gltf`): the
#: built-ins are moved through the API, which is f64 throughout, while a file carries its own
#: offset in its node translations, which the loader must read in f64 too.
FILE_SCENE = "room_gltf"
#: The offset `write_room_gltf` puts into the moved file's nodes: 1e5 m, with digits below the
#: 8 mm an f32 keeps there (100000.3 is 100000.3125 in f32).
FILE_OFFSET = (100000.3, -99999.7, 100000.1)


def write_room_gltf(directory, offset=(0.0, 0.0, 0.0)):
    """Writes ``room.gltf`` into `directory` and returns its path: a closed room (floor,
    ceiling, three walls, a red and a green one) with a turned glossy box, a spot light on a
    node and a perspective camera on a node. Every node stands at `offset` + its place in the
    room, and each mesh is modelled around its node, as exporters write scenes far from the
    origin; the buffer is a data URI, so the file is the whole scene."""
    import base64
    import json
    import math
    import pathlib
    import struct

    data = bytearray()
    views: list[dict] = []
    accessors: list[dict] = []

    def accessor(values, fmt, type_, ncomp, target):
        while len(data) % 4:
            data.append(0)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(values) * 4 if fmt == "f" else len(values) * 2, "target": target})
        data.extend(struct.pack(f"<{len(values)}{fmt}", *values))
        acc = {"bufferView": len(views) - 1, "componentType": 5126 if fmt == "f" else 5123, "count": len(values) // ncomp, "type": type_}
        if type_ == "VEC3":
            acc["min"] = [min(values[k::3]) for k in range(3)]
            acc["max"] = [max(values[k::3]) for k in range(3)]
        accessors.append(acc)
        return len(accessors) - 1

    def mesh_of(faces):
        """faces: (corner, edge u, edge v, normal) quads, counter-clockwise seen along -normal."""
        pos, nrm, idx = [], [], []
        for corner, eu, ev, n in faces:
            k = len(pos) // 3
            for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
                pos += [corner[i] + a * eu[i] + b * ev[i] for i in range(3)]
                nrm += list(n)
            idx += [k, k + 1, k + 2, k, k + 2, k + 3]
        return {"primitives": [{"attributes": {"POSITION": accessor(pos, "f", "VEC3", 3, 34962), "NORMAL": accessor(nrm, "f", "VEC3", 3, 34962)},
                                "indices": accessor(idx, "H", "SCALAR", 1, 34963)}]}

    w, h = 2.0, 3.0  # half width, height
    meshes, materials, nodes = [], [], []

    def add(name, faces, place, material, rotation=None):
        meshes.append(mesh_of(faces))
        materials.append(material)
        meshes[-1]["primitives"][0]["material"] = len(materials) - 1
        node = {"name": name, "mesh": len(meshes) - 1, "translation": [o + p for o, p in zip(offset, place)]}
        if rotation is not None:
            node["rotation"] = rotation
        nodes.append(node)

    def matte(name, rgb, roughness=0.8):
        return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1.0], "metallicFactor": 0.0, "roughnessFactor": roughness}}

    add("floor", [((-w, 0, w), (2 * w, 0, 0), (0, 0, -2 * w), (0, 1, 0))], (0.0, 0.0, 0.0), matte("floor", (0.7, 0.7, 0.65), 0.5))
    add("ceiling", [((-w, 0, -w), (2 * w, 0, 0), (0, 0, 2 * w), (0, -1, 0))], (0.0, h, 0.0), matte("ceiling", (0.75, 0.75, 0.75)))
    add("back", [((-w, -h / 2, 0), (2 * w, 0, 0), (0, h, 0), (0, 0, 1))], (0.0, h / 2, -w), matte("back", (0.7, 0.7, 0.7)))
    add("left", [((0, -h / 2, w), (0, 0, -2 * w), (0, h, 0), (1, 0, 0))], (-w, h / 2, 0.0), matte("red", (0.7, 0.1, 0.08)))
    add("right", [((0, -h / 2, -w), (0, 0, 2 * w), (0, h, 0), (-1, 0, 0))], (w, h / 2, 0.0), matte("green", (0.1, 0.6, 0.12)))
    c = 0.4
    box = [((-c, -c, c), (2 * c, 0, 0), (0, 2 * c, 0), (0, 0, 1)), ((c, -c, -c), (-2 * c, 0, 0), (0, 2 * c, 0), (0, 0, -1)),
           ((c, -c, c), (0, 0, -2 * c), (0, 2 * c, 0), (1, 0, 0)), ((-c, -c, -c), (0, 0, 2 * c), (0, 2 * c, 0), (-1, 0, 0)),
           ((-c, c, c), (2 * c, 0, 0), (0, 0, -2 * c), (0, 1, 0)), ((-c, -c, -c), (2 * c, 0, 0), (0, 0, 2 * c), (0, -1, 0))]
    turn = math.radians(20.0)
    add("box", box, (0.5, c, -0.4), {"name": "glossy box", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.7, 0.5, 1.0], "metallicFactor": 0.5,
                                                                                     "roughnessFactor": 0.3}},
        rotation=[0.0, math.sin(turn / 2), 0.0, math.cos(turn / 2)])
    s = math.sqrt(0.5)
    nodes.append({"name": "spot", "translation": [o + p for o, p in zip(offset, (-0.3, h - 0.1, 0.2))], "rotation": [-s, 0.0, 0.0, s],
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    nodes.append({"name": "camera", "translation": [o + p for o, p in zip(offset, (0.0, 1.5, 5.5))], "camera": 0})
    uri = "data:application/octet-stream;base64," + base64.b64encode(bytes(data)).decode()
    root = {
        "asset": {"version": "2.0", "generator": "vsgl.stability.write_room_gltf"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "intensity": 30.0, "spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.9}}]}},
        "buffers": [{"uri": uri, "byteLength": len(data)}], "bufferViews": views, "accessors": accessors,
        "materials": materials, "meshes": meshes, "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.05}}],
        "scenes": [{"nodes": list(range(len(nodes)))}], "scene": 0,
    }
    path = pathlib.Path(directory) / "room.gltf"
    path.write_text(json.dumps(root))
    return path


def _file_scene(offset=(0.0, 0.0, 0.0)):
    """The room of `write_room_gltf` loaded from a file written with `offset`, and its camera."""
    import tempfile

    import vsgl

    with tempfile.TemporaryDirectory(prefix="vsgl-room-") as d:
        scene = vsgl.Scene.load(write_room_gltf(d, offset))
    return scene, scene.cameras[0]


def _load_scene(name: str):
    """A built-in by name, or the file scene (FILE_SCENE)."""
    import vsgl

    return _file_scene()[0] if name == FILE_SCENE else vsgl.scenes.load(name)


def transformed_scene(name: str, scale: float = 1.0, offset=(0.0, 0.0, 0.0), intensity_scale: float = 1.0):
    """Built-in scene `name` (or FILE_SCENE) with every node scaled by `scale` about the origin and moved by
    `offset`, its lights moved alike with intensities × `intensity_scale`, and its first camera
    moved alike. Light transport is invariant under this when intensity_scale = scale²
    (radiance ~ I/d²), and linear in intensity_scale."""
    import numpy as np

    import vsgl

    scene = _load_scene(name)
    offset = np.asarray(offset, dtype=float)
    m = np.eye(4)
    m[:3, :3] *= scale
    m[:3, 3] = offset
    # Read before the nodes move: a light on a node (the file scene's spot) follows its node.
    lights = scene.lights
    for node in scene.node_names:
        # Composed with the node's own transform (the file scene's nodes carry their places);
        # every node of the suite's scenes is a root, so each is moved once.
        local = np.array(scene.transform(node))
        if not np.array_equal(local, np.array(scene.transform(node, world=True))):
            raise ValueError(f"{name}: node {node!r} has a parent; transformed_scene moves root nodes only")
        scene.set_transform(node, (m @ local).tolist())
    moved = []
    for light in lights:
        pos = tuple(scale * np.array(light.position) + offset)
        if isinstance(light, vsgl.SpotLight):
            moved.append(vsgl.SpotLight(position=pos, direction=light.direction, intensity=light.intensity * intensity_scale, color=light.color,
                                        inner_cone_deg=light.inner_cone_deg, outer_cone_deg=light.outer_cone_deg))
        elif isinstance(light, vsgl.PointLight):
            moved.append(vsgl.PointLight(position=pos, intensity=light.intensity * intensity_scale, color=light.color))
        else:
            moved.append(vsgl.DirectionalLight(direction=light.direction, intensity=light.intensity * intensity_scale, color=light.color))
    scene.lights = moved
    cam = scene.cameras[0]
    eye = scale * np.array(cam.eye) + offset
    camera = vsgl.Camera.look_at(eye=tuple(eye), target=tuple(eye + np.array(cam.forward)), up=cam.up, fov_y_deg=cam.fov_y_deg)
    return scene, camera


def _scene_cases(name: str):
    """(case, scene, camera, divide the image by, geometric scale) for the cases of one scene.
    Invariance cases are compared with the base image after the division (depth after dividing
    by the scale); the others need only be finite."""
    import numpy as np

    import vsgl

    yield "base", *transformed_scene(name), None, 1.0
    yield "moved 1e5 m", *transformed_scene(name, offset=(1e5, -1e5, 1e5)), 1.0, 1.0
    if name == FILE_SCENE:
        # The same file with the offset in its nodes' translations (geometry, light, camera).
        yield "moved 1e5 m in the file", *_file_scene(FILE_OFFSET), 1.0, 1.0
    yield "scaled 1e-3 (I x 1e-6)", *transformed_scene(name, 1e-3, intensity_scale=1e-6), 1.0, 1e-3
    yield "scaled 1e3 (I x 1e6)", *transformed_scene(name, 1e3, intensity_scale=1e6), 1.0, 1e3
    # Not a power of ten: its rounding differs from the base's, so edge pixels change surface on
    # lavapipe too (see SURFACE_FRACTION).
    yield "scaled 0.37 (I x 0.1369)", *transformed_scene(name, 0.37, intensity_scale=0.37**2), 1.0, 0.37
    yield "intensity x 1e-8", *transformed_scene(name, intensity_scale=1e-8), 1e-8, 1.0
    # 1e30 is below the 1e32 limit but far above any real light: finite, and linear.
    scene, cam = transformed_scene(name)
    factor = 1e30 / max(light.intensity for light in scene.lights)
    yield "intensity 1e30 cd", *transformed_scene(name, intensity_scale=factor), factor, 1.0
    # A spot light on a wall's plane, aiming along it: grazing at every point of that wall.
    scene, cam = transformed_scene(name)
    lo, hi = scene.bounds
    mid = tuple((np.array(lo) + np.array(hi)) / 2)
    scene.lights = [vsgl.SpotLight(position=(lo[0], mid[1], mid[2]), direction=(0.0, 0.0, -1.0), intensity=5.0, outer_cone_deg=60.0, inner_cone_deg=30.0)]
    yield "light grazing a wall", scene, cam, None, 1.0
    # Every material at roughness 1e-4 (α = 1e-8), the stiff end of the GGX grids: near-mirror
    # lobes in the direct light, the RSM's specular lobes, the VSGL lobe fits (sharpness near
    # its clamp) and the path tracer's visible-normal sampling; no NaN or Inf.
    scene, cam = transformed_scene(name)
    for material in {m["name"] for m in scene.materials}:
        scene.set_material(material, roughness=1e-4)
    yield "roughness 1e-4", scene, cam, None, 1.0
    # The camera inside the scene's geometry bounds at its centre, looking down: whatever it
    # sees (possibly the inside of an object), no NaN or Inf.
    scene, _ = transformed_scene(name)
    yield "camera inside geometry", scene, vsgl.Camera.look_at(eye=mid, target=(mid[0], mid[1] - 1.0, mid[2] + 1e-3)), None, 1.0


def surface_changed(normal_a, depth_a, normal_b, depth_b):
    """Pixels that see another surface in b than in a: the normal turned by more than 0.5° or the
    depth (already in the same units) off by more than 1e-3 of itself."""
    import numpy as np

    # The background has a zero normal in both: the same "surface".
    hit_a, hit_b = (normal_a**2).sum(axis=-1) > 0.25, (normal_b**2).sum(axis=-1) > 0.25
    turned = (hit_a != hit_b) | (hit_a & hit_b & ((normal_a * normal_b).sum(axis=-1) < np.cos(np.radians(0.5))))
    moved = np.abs(depth_b - depth_a) > 1e-3 * np.maximum(np.abs(depth_a), np.abs(depth_b))
    return turned | moved


def widen(mask, k: int):
    """`mask` grown by the denoiser's reach around each set pixel: a pixel reads offsets −k … k−1
    per axis, so a changed pixel reaches −(k − 1) … k of itself; ±k per axis covers both."""
    import numpy as np

    if k <= 1 or not mask.any():
        return mask
    out = np.zeros_like(mask)
    h, w = mask.shape
    for y, x in zip(*np.nonzero(mask)):
        out[max(y - k, 0):min(y + k + 1, h), max(x - k, 0):min(x + k + 1, w)] = True
    return out


def scene_suite(scenes: Sequence[str] = ("cornell_box", "glossy_cornell", "caustics_ring", "helmet_shell", "furnished_room", "atrium", FILE_SCENE),
                methods: Sequence[str] | None = None,
                size: tuple[int, int] = (32, 24), adapter: str | None = None) -> list[dict[str, Any]]:
    """Renders every method on `scenes` under each case of `_scene_cases` and returns one row per
    (scene, method, case): ``rel_rmse`` against the base image (invariance cases, else None),
    ``rel_rmse_unflipped`` (the same without the pixels that flipped or changed surface, which
    must be within ``bound``), ``flipped``, ``surface`` (pixels that see another surface,
    SURFACE_FRACTION), ``bound``, ``nonfinite`` (True when the frame had NaN/Inf: vsgl refuses it with
    NumericsError) and ``passed``."""
    import numpy as np

    import vsgl

    renderer = vsgl.Renderer(width=size[0], height=size[1], adapter=adapter)
    rows: list[dict[str, Any]] = []
    for name in scenes:
        cases = list(_scene_cases(name))
        for method in methods or vsgl.METHODS:
            settings = small_settings(method)
            flip_fraction = TRACED_FLIP_FRACTION if vsgl.method_info(method)["direct_light"] == "by_method" else 0.0
            base = None
            for case, scene, camera, divide, geometry_scale in cases:
                row: dict[str, Any] = {"scene": name, "method": method, "case": case, "rel_rmse": None, "bound": None, "flipped": 0,
                                       "surface": 0, "nonfinite": False}
                try:
                    frame = renderer.render(scene, camera, method=method, aovs=["image", "normal", "depth"], **settings)
                except vsgl.NumericsError:
                    row.update(nonfinite=True, passed=False)
                    rows.append(row)
                    continue
                image = frame.image.astype(np.float64)
                normal, depth = frame.aov("normal").astype(np.float64), frame.aov("depth")[..., 0].astype(np.float64) / geometry_scale
                if case == "base":
                    base, base_normal, base_depth = image, normal, depth
                elif divide is not None and base is not None:
                    scaled = image / divide
                    scale = max(float(np.abs(base).max()), 1e-30)
                    surface = surface_changed(base_normal, base_depth, normal, depth)
                    unsure = widen(surface, int(frame.settings.get("interleave") or 1)) if frame.settings.get("denoise") is True else surface
                    flipped = (np.abs(scaled - base).max(axis=-1) > 1e-2 * np.maximum(np.abs(base).max(axis=-1), 1e-3 * scale)) & ~unsure
                    keep = ~(flipped | unsure)
                    rel = lambda a, b: float(np.sqrt(np.mean((a - b) ** 2)) / np.sqrt(np.mean(b**2))) if b.size and np.any(b) else 0.0  # noqa: E731
                    row.update(rel_rmse=rel(scaled, base), rel_rmse_unflipped=rel(scaled[keep], base[keep]), bound=INVARIANCE_BOUND,
                               flipped=int(flipped.sum()), surface=int(surface.sum()))
                allowed_flips = int(flip_fraction * size[0] * size[1])
                row["passed"] = row["rel_rmse"] is None or (row["rel_rmse_unflipped"] <= INVARIANCE_BOUND and row["flipped"] <= allowed_flips
                                                            and row["surface"] <= SURFACE_FRACTION * size[0] * size[1])
                rows.append(row)
    return rows


def format_scene_table(rows: Sequence[dict[str, Any]]) -> str:
    cells = [
        (r["scene"], r["method"], r["case"], "" if r["rel_rmse"] is None else f"{r['rel_rmse']:.2e}",
         "" if r["bound"] is None else f"{r['bound']:.0e}", str(r["surface"]), str(r["flipped"]), "yes" if r["nonfinite"] else "0",
         "pass" if r["passed"] else "FAIL")
        for r in rows
    ]
    widths = [max([len(c)] + [len(row[i]) for row in cells]) for i, c in enumerate(SCENE_COLUMNS)]
    line = lambda values: "  ".join(v.ljust(w) for v, w in zip(values, widths)).rstrip()  # noqa: E731
    return "\n".join([line(SCENE_COLUMNS), line(["-" * w for w in widths])] + [line(c) for c in cells])


def main(argv: Sequence[str] | None = None) -> int:
    """CLI entry point: prints the table and returns 0 if every row passed, 1 otherwise (2 when
    no adapter could be opened)."""
    parser = argparse.ArgumentParser(prog="python -m vsgl stability", description=__doc__.split("\n\n")[0])
    parser.add_argument("--adapter", default=None, help="adapter name substring (default: best, or $VSGL_ADAPTER)")
    parser.add_argument(
        "--bound-scale",
        type=float,
        default=1.0,
        help="multiply every bound by this (default 1; a small value shows that the suite can fail)",
    )
    parser.add_argument("--verbose", action="store_true", help="print the worst case of every failing row")
    parser.add_argument("--scenes", action="store_true",
                        help="also run the scene-level suite: every method on built-in scenes and a glTF room (also written 1e5 m out in the file) moved 1e5 m, scaled 1e-3, 0.37 and 1e3, "
                             "with intensities 1e-8 and 1e30, a grazing light, roughness 1e-4 and the camera inside geometry")
    args = parser.parse_args(argv)
    if not args.bound_scale > 0.0:
        print(f"error: --bound-scale must be positive, got {args.bound_scale}", file=sys.stderr)
        return 2

    import vsgl

    try:
        rows = run(args.adapter, args.bound_scale)
    except vsgl.NoAdapterError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    print(format_table(rows))
    failed = [r for r in rows if not (r["passed"] and int(r["nonfinite"]) == 0)]
    scale = "" if args.bound_scale == 1.0 else f" (bounds x {args.bound_scale:g})"
    print(f"\n{len(rows) - len(failed)} of {len(rows)} rows pass{scale}; {sum(int(r['nonfinite']) for r in rows)} NaN/Inf outputs")
    for r in failed if args.verbose else []:
        print(f"FAIL {r['function']} / {r['family']}: {r['worst_case']}")
    code = exit_code(rows)
    if args.scenes:
        scene_rows = scene_suite(adapter=args.adapter)
        print()
        print(format_scene_table(scene_rows))
        bad = [r for r in scene_rows if not r["passed"]]
        print(f"\n{len(scene_rows) - len(bad)} of {len(scene_rows)} scene rows pass; {sum(r['nonfinite'] for r in scene_rows)} frames with NaN/Inf")
        code = max(code, 1 if bad else 0)
    return code


if __name__ == "__main__":
    sys.exit(main())
