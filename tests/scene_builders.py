"""Tiny glTF files for analytic tests: one square quad with one material, written with the
standard library only (the loader under test is vsgl's own)."""

from __future__ import annotations

import base64
import json
import math
import pathlib
import struct

import numpy as np

import vsgl


def write_quad(
    directory: pathlib.Path,
    *,
    half_size: float = 5.0,
    base_color=(0.8, 0.8, 0.8),
    metallic: float = 0.0,
    roughness: float = 1.0,
    specular: float | None = None,
    name: str = "quad.gltf",
) -> pathlib.Path:
    """A square in the y = 0 plane, normal +y, centred at the origin, node name "quad".
    ``specular``: a KHR_materials_specular ``specularFactor`` (omitted when None)."""
    s = half_size
    positions = [(-s, 0.0, -s), (s, 0.0, -s), (s, 0.0, s), (-s, 0.0, s)]
    normals = [(0.0, 1.0, 0.0)] * 4
    indices = [0, 2, 1, 0, 3, 2]
    blob = b"".join(struct.pack("<3f", *p) for p in positions)
    blob += b"".join(struct.pack("<3f", *n) for n in normals)
    blob += struct.pack("<6I", *indices)
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "quad", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [
            {
                "pbrMetallicRoughness": {
                    "baseColorFactor": [*base_color, 1.0],
                    "metallicFactor": metallic,
                    "roughnessFactor": roughness,
                }
            }
        ],
        "buffers": [
            {
                "byteLength": len(blob),
                "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode(),
            }
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 48},
            {"buffer": 0, "byteOffset": 96, "byteLength": 24},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-s, 0, -s], "max": [s, 0, s]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": 6, "type": "SCALAR"},
        ],
    }
    if specular is not None:
        doc["extensionsUsed"] = ["KHR_materials_specular"]
        doc["materials"][0]["extensions"] = {"KHR_materials_specular": {"specularFactor": specular}}
    path = directory / name
    path.write_text(json.dumps(doc))
    return path


def write_quads(directory: pathlib.Path, quads: list[dict], *, name: str = "quads.gltf") -> pathlib.Path:
    """Several one-sided quads, one node, mesh and material each (node names from "name").

    Each quad is a dict with ``corners`` (four (x, y, z) points in order around the quad; the
    normal is (c1 − c0) × (c3 − c0), normalized) and optional ``base_color``, ``metallic``,
    ``roughness``, ``specular`` (a KHR_materials_specular ``specularFactor``; 0 makes a purely
    Lambertian dielectric) and ``name``.
    """
    blob = b""
    views, accessors, meshes, materials, nodes = [], [], [], [], []
    for i, q in enumerate(quads):
        c = [tuple(float(x) for x in p) for p in q["corners"]]
        e1 = [c[1][k] - c[0][k] for k in range(3)]
        e2 = [c[3][k] - c[0][k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        ln = sum(x * x for x in n) ** 0.5
        n = [x / ln for x in n]
        chunks = [
            (b"".join(struct.pack("<3f", *p) for p in c), 4, "VEC3", 5126),
            (b"".join(struct.pack("<3f", *n) for _ in c), 4, "VEC3", 5126),
            (struct.pack("<6I", 0, 1, 2, 0, 2, 3), 6, "SCALAR", 5125),
        ]
        first = len(accessors)
        for k, (data, count, kind, ctype) in enumerate(chunks):
            views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
            acc = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": kind}
            if k == 0:
                acc["min"] = [min(p[j] for p in c) for j in range(3)]
                acc["max"] = [max(p[j] for p in c) for j in range(3)]
            accessors.append(acc)
            blob += data
        meshes.append({"primitives": [{"attributes": {"POSITION": first, "NORMAL": first + 1}, "indices": first + 2, "material": i}]})
        material = {
            "pbrMetallicRoughness": {
                "baseColorFactor": [*q.get("base_color", (0.8, 0.8, 0.8)), 1.0],
                "metallicFactor": q.get("metallic", 0.0),
                "roughnessFactor": q.get("roughness", 1.0),
            }
        }
        if q.get("specular") is not None:
            material["extensions"] = {"KHR_materials_specular": {"specularFactor": q["specular"]}}
        materials.append(material)
        nodes.append({"name": q.get("name", f"quad{i}"), "mesh": i})
    doc = {
        "asset": {"version": "2.0"},
        **({"extensionsUsed": ["KHR_materials_specular"]} if any(q.get("specular") is not None for q in quads) else {}),
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }
    path = directory / name
    path.write_text(json.dumps(doc))
    return path


def two_rooms(directory: pathlib.Path):
    """A floor split by a wall at x = 0 with a narrow door (|z| < 0.15). A spot light in the
    left room lights its back wall; the camera looks at the right room's floor, which only the
    light coming through the door reaches (no direct light there). Returns (scene, camera)."""
    floor = dict(corners=[(-1.5, 0, -1), (-1.5, 0, 1), (1.5, 0, 1), (1.5, 0, -1)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="floor")
    wall_a = dict(corners=[(0, 0, -1), (0, 0, -0.15), (0, 1.5, -0.15), (0, 1.5, -1)], base_color=(0.7, 0.7, 0.7), specular=0.0, name="wall_a")
    wall_b = dict(corners=[(0, 0, 0.15), (0, 0, 1), (0, 1.5, 1), (0, 1.5, 0.15)], base_color=(0.7, 0.7, 0.7), specular=0.0, name="wall_b")
    back = dict(corners=[(-1.5, 0, -1), (-1.5, 1.5, -1), (-1.5, 1.5, 1), (-1.5, 0, 1)], base_color=(0.9, 0.9, 0.9), specular=0.0, name="back")
    scene = vsgl.Scene.load(write_quads(directory, [floor, wall_a, wall_b, back], name="two_rooms.gltf"))
    d = np.array([-0.9, -0.3, 0.0]) / math.hypot(0.9, 0.3)
    scene.lights = [vsgl.SpotLight(position=(-0.6, 0.9, 0.0), direction=tuple(d), intensity=10.0, inner_cone_deg=30, outer_cone_deg=40)]
    return scene, vsgl.Camera.look_at(eye=(1.3, 1.2, 0.0), target=(0.7, 0.0, 0.55), fov_y_deg=30)


def half_hidden_floor(directory: pathlib.Path):
    """A lit floor (2 × 2 m) and a wall along its x = −1 edge facing it, with a black panel 25 cm
    high standing on the floor at x = −0.4: the wall's lower part sees the floor's near strip and
    not the rest, so a large cluster of floor texels is partly visible from there, the near, more
    visible part bringing most of its light. The camera looks at the wall's lower part from
    between it and the panel. Returns (scene, camera)."""
    floor = dict(corners=[(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="floor")
    wall = dict(corners=[(-1, 0, 1), (-1, 0, -1), (-1, 1, -1), (-1, 1, 1)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="wall")
    panel = dict(corners=[(-0.4, 0, 1), (-0.4, 0, -1), (-0.4, 0.25, -1), (-0.4, 0.25, 1)], base_color=(0.0, 0.0, 0.0), specular=0.0, name="panel")
    scene = vsgl.Scene.load(write_quads(directory, [floor, wall, panel], name="half_hidden_floor.gltf"))
    scene.lights = [vsgl.SpotLight(position=(0.3, 3.0, 0.0), direction=(0.0, -1.0, 0.0), intensity=10.0, inner_cone_deg=40, outer_cone_deg=50)]
    return scene, vsgl.Camera.look_at(eye=(-0.6, 0.12, 0.0), target=(-1.0, 0.12, 0.0), fov_y_deg=50)


def step_face(directory: pathlib.Path):
    """A 0.3 m step: a raised block's top over the half x < 0 of a 2 × 2 m floor, its front face
    at x = 0 facing +x, lit from above and behind the face (so the face gets no direct light).
    In the RSM the floor texels at the step's foot sit beside the block's top 0.3 m higher, and
    those floor texels light the face from a texel or two away. The camera looks at the face.
    Returns (scene, camera)."""
    floor = dict(corners=[(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="floor")
    top = dict(corners=[(-1, 0.3, -1), (-1, 0.3, 1), (0, 0.3, 1), (0, 0.3, -1)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="top")
    face = dict(corners=[(0, 0, -1), (0, 0.3, -1), (0, 0.3, 1), (0, 0, 1)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="face")
    scene = vsgl.Scene.load(write_quads(directory, [floor, top, face], name="step_face.gltf"))
    scene.lights = [vsgl.SpotLight(position=(-0.3, 3.0, 0.0), direction=(0.0, -1.0, 0.0), intensity=10.0, inner_cone_deg=40, outer_cone_deg=45)]
    return scene, vsgl.Camera.look_at(eye=(1.2, 0.15, 0.0), target=(0.0, 0.15, 0.0), fov_y_deg=40)


def lit_floor_corner(directory: pathlib.Path, *, wall_roughness: float = 0.35):
    """A large floor (8 × 8) lit all over by a wide spot light, and a wall along its back edge
    (z = −4, facing +z, glossy with ``wall_roughness``); the camera looks at a small patch of the
    wall near the floor, so it sees none of the lit floor and only the floor texels near that
    patch matter: the case bidirectional RSM importance is for. Returns (scene, camera)."""
    floor = dict(corners=[(-4, 0, -4), (-4, 0, 4), (4, 0, 4), (4, 0, -4)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="floor")
    wall = dict(corners=[(-4, 0, -4), (4, 0, -4), (4, 3, -4), (-4, 3, -4)], base_color=(0.7, 0.7, 0.7), roughness=wall_roughness, name="wall")
    scene = vsgl.Scene.load(write_quads(directory, [floor, wall], name="lit_floor_corner.gltf"))
    scene.lights = [vsgl.SpotLight(position=(0.0, 5.0, 1.0), direction=(0.0, -1.0, 0.0), intensity=40.0, inner_cone_deg=55, outer_cone_deg=65)]
    return scene, vsgl.Camera.look_at(eye=(1.5, 0.4, -2.5), target=(1.5, 0.3, -4.0), fov_y_deg=30)


def columns_before_wall(directory: pathlib.Path):
    """The 2016 paper's Fig. 7 case, a light occluded by columns: a row of seven square columns
    (0.24 m wide, 1.8 m high) stands 1 m in front of a lit back wall on a floor, and a spot light
    shines at the wall past them. In the RSM the columns' lit faces and the wall between them are
    neighbours in texel space but a metre apart in the world, so a cluster of neighbouring texels
    can hold both; the floor in front gets the wall's bounce in stripes between the columns'
    shadows. The camera looks down at that floor. Returns (scene, camera)."""
    floor = dict(corners=[(-2, 0, -2), (-2, 0, 2), (2, 0, 2), (2, 0, -2)], base_color=(0.8, 0.8, 0.8), specular=0.0, name="floor")
    quads = [floor]
    x, w = -1.0, 0.12
    for i, z in enumerate(np.linspace(-1.6, 1.6, 7)):
        sides = [((x, z - w), (x, z + w)), ((x, z + w), (x - 2 * w, z + w)), ((x - 2 * w, z + w), (x - 2 * w, z - w)), ((x - 2 * w, z - w), (x, z - w))]
        for k, ((x0, z0), (x1, z1)) in enumerate(sides):
            quads.append(dict(corners=[(x0, 0, z0), (x0, 1.8, z0), (x1, 1.8, z1), (x1, 0, z1)], base_color=(0.8, 0.8, 0.8), specular=0.0, name=f"column{i}_{k}"))
    wall = dict(corners=[(-2, 0, 2), (-2, 0, -2), (-2, 2, -2), (-2, 2, 2)], base_color=(0.9, 0.9, 0.9), specular=0.0, name="wall")
    scene = vsgl.Scene.load(write_quads(directory, quads + [wall], name="columns_before_wall.gltf"))
    scene.lights = [vsgl.SpotLight(position=(1.5, 1.5, 0.0), direction=(-1.0, -0.45, 0.0), intensity=10.0, inner_cone_deg=50, outer_cone_deg=60)]
    return scene, vsgl.Camera.look_at(eye=(1.8, 2.2, 0.0), target=(-0.5, 0.0, 0.0), fov_y_deg=60)


# Looks at the floor of glossy_floor_under_small_emitter where the emitter's mirror image lies
# (the eye's ray to the image at y = −1 meets the floor at z = 1.25).
GLOSSY_FLOOR_VIEW = vsgl.Camera.look_at(eye=(0.0, 0.6, 2.0), target=(0.0, 0.0, 0.6), up=(0.0, 1.0, 0.0), fov_y_deg=50.0)


def glossy_floor_under_small_emitter(directory: pathlib.Path, roughness: float) -> vsgl.Scene:
    """A 6 × 6 metal floor (base colour 0.9, the given roughness) under a 0.2 × 0.2 square at
    y = 1 facing down that emits 20, with a grey Lambertian wall at z = −1 facing the light:
    a small emitter's reflection in a glossy lobe (next-event estimation's hard case) and the
    wall's bounce of it."""
    e = 0.1
    quads = [
        dict(corners=[(-3, 0, -3), (-3, 0, 3), (3, 0, 3), (3, 0, -3)], name="floor", base_color=(0.9,) * 3, metallic=1.0, roughness=roughness),
        dict(corners=[(-e, 1, -e), (e, 1, -e), (e, 1, e), (-e, 1, e)], name="glow", base_color=(0.0,) * 3, specular=0.0),
        dict(corners=[(-3, 0, -1), (3, 0, -1), (3, 3, -1), (-3, 3, -1)], name="wall", base_color=(0.6,) * 3, specular=0.0),
    ]
    scene = vsgl.Scene.load(write_quads(directory, quads, name=f"glossy_floor_{roughness}.gltf"))
    scene.set_material("materials[1]", emissive=(20.0, 20.0, 20.0))
    return scene


def corner_over_a_hidden_sheet(directory: pathlib.Path, sheet_side: int, *, name: str = "hidden_sheet.gltf"):
    """A lit floor corner (a 2 × 2 m floor at y = 0, walls at x = −1 and z = −1) over a flat
    sheet of ``sheet_side``² vertices (2·(side − 1)² triangles) 1 cm under the floor, where no
    camera, light or bounce can reach it. The sheet comes first in the file, so with a large
    side the visible surfaces' vertices and triangles come last in the upload (past the first
    128 MiB of each buffer), and every sheet side gives the same bounds and the same image.
    Geometry goes to a .bin beside the .gltf. Returns (scene, camera)."""
    n = int(sheet_side)
    grid = np.linspace(-1.0, 1.0, n, dtype=np.float64)
    xs, zs = np.meshgrid(grid, grid, indexing="xy")
    sheet_pos = np.stack([xs.ravel(), np.full(n * n, -0.01), zs.ravel()], axis=1).astype(np.float32)
    sheet_nrm = np.tile(np.array([0.0, -1.0, 0.0], np.float32), (n * n, 1))
    i = np.arange(n - 1, dtype=np.uint32)
    a = (i[None, :] + n * i[:, None]).ravel()
    sheet_idx = np.concatenate([np.stack([a, a + n, a + 1], 1), np.stack([a + 1, a + n, a + n + 1], 1)]).astype(np.uint32)
    quads = [
        ([(-1, 0, -1), (-1, 0, 1), (1, 0, 1), (1, 0, -1)], (0.8, 0.8, 0.8), (0, 1, 0)),  # floor
        ([(-1, 0, 1), (-1, 0, -1), (-1, 1.5, -1), (-1, 1.5, 1)], (0.8, 0.3, 0.2), (1, 0, 0)),  # wall x = −1
        ([(-1, 0, -1), (1, 0, -1), (1, 1.5, -1), (-1, 1.5, -1)], (0.2, 0.5, 0.8), (0, 0, 1)),  # wall z = −1
    ]
    meshes = [(sheet_pos, sheet_nrm, sheet_idx.ravel(), (0.5, 0.5, 0.5))]
    for corners, color, normal in quads:
        pos = np.array(corners, np.float32)
        meshes.append((pos, np.tile(np.array(normal, np.float32), (4, 1)), np.array([0, 1, 2, 0, 2, 3], np.uint32), color))
    bin_name = name.replace(".gltf", ".bin")
    views, accessors, gl_meshes, materials, nodes = [], [], [], [], []
    offset = 0
    with open(directory / bin_name, "wb") as f:
        for k, (pos, nrm, idx, color) in enumerate(meshes):
            first = len(accessors)
            for data, kind, ctype in ((pos, "VEC3", 5126), (nrm, "VEC3", 5126), (idx, "SCALAR", 5125)):
                raw = np.ascontiguousarray(data).tobytes()
                f.write(raw)
                views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(raw)})
                offset += len(raw)
                acc = {"bufferView": len(views) - 1, "componentType": ctype, "count": len(data), "type": kind}
                if kind == "VEC3" and len(accessors) == first:
                    acc["min"] = pos.min(axis=0).tolist()
                    acc["max"] = pos.max(axis=0).tolist()
                accessors.append(acc)
            gl_meshes.append({"primitives": [{"attributes": {"POSITION": first, "NORMAL": first + 1}, "indices": first + 2, "material": k}]})
            materials.append({"pbrMetallicRoughness": {"baseColorFactor": [*color, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6}})
            nodes.append({"name": "sheet" if k == 0 else f"quad{k}", "mesh": k})
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": gl_meshes,
        "materials": materials,
        "buffers": [{"byteLength": offset, "uri": bin_name}],
        "bufferViews": views,
        "accessors": accessors,
    }
    (directory / name).write_text(json.dumps(doc))
    scene = vsgl.Scene.load(directory / name)
    scene.lights = [vsgl.SpotLight(position=(0.4, 1.4, 0.4), direction=(-0.5, -1.0, -0.5), intensity=8.0, inner_cone_deg=35, outer_cone_deg=50)]
    return scene, vsgl.Camera.look_at(eye=(0.9, 1.0, 0.9), target=(-0.5, 0.2, -0.5), fov_y_deg=55)
