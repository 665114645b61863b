"""Generators of small glTF 2.0 fixture files for the loader tests (standard library only).

Every ``write_<name>(dirpath) -> pathlib.Path`` writes one scene (plus its ``.bin`` and
images) into ``dirpath`` and returns the path to load with ``vsgl.Scene.load(path)``.
Use a fresh directory per fixture: several fixtures use the same auxiliary file names.

This module holds the valid scenes and the tables; the building blocks (buffer, PNG and GLB
encoders, the base quad and textured quad) are in ``gltf_writer``, and the files that load with
a warning or must be refused are in ``gltf_hostile_fixtures``. Every writer of both is
importable from here, so tests import this module only.

* ``VALID``: name -> (writer, expected triangle count of ``scene.stats``).
* ``WARNING_CASES``: name -> (writer, substring of one of ``scene.warnings``); these load.
* ``HOSTILE``: name -> (writer, substring of the ``vsgl.SceneError`` message). The substring
  is the glTF element the loader names (``buffers[0].uri``, ``accessors[0]``, ...);
  ``HOSTILE_KEYWORDS`` gives a second, lower-case word of the message for each.

Run ``python tests/gltf_fixtures.py --write DIR`` to write every fixture into its own
subfolder of DIR, plus ``DIR/manifest.json`` describing them (used by the Rust test
``python_fixtures_match_the_loader`` in ``crates/vsgl-core/tests/gltf_hostile.rs``).
"""

from __future__ import annotations

import base64
import json
import math
import os
import pathlib
import struct
import sys

# Re-exported: the tests take every writer (and `_quad`) from this module.
from gltf_hostile_fixtures import (
    write_absolute_uri,
    write_accessor_out_of_bounds,
    write_bad_glb_header,
    write_huge_byte_length,
    write_http_uri,
    write_index_out_of_range,
    write_invalid_json,
    write_missing_texture,
    write_node_cycle,
    write_non_finite_position,
    write_normal_map_without_uvs,
    write_oversized_image,
    write_parent_dir_uri,
    write_points_primitive,
    write_required_extension_not_used,
    write_root_listed_twice,
    write_root_with_a_parent,
    write_texture_bomb,
    write_truncated_buffer,
    write_two_parents,
    write_unsupported_required_extension,
)
from gltf_writer import (
    QUAD_IDX,
    QUAD_POS,
    QUAD_UV,
    _Bin,
    _glb,
    _png,
    _png_pixels,
    _quad,
    _root,
    _textured,
    _write_json,
    write_png_of_zeros,
)

__all__ = ["VALID", "WARNING_CASES", "HOSTILE", "HOSTILE_KEYWORDS", "write_all"]


# ------------------------------------------------------------------------------------------
# Valid scenes
# ------------------------------------------------------------------------------------------


def write_external_buffer(dirpath) -> pathlib.Path:
    """Indexed quad, buffer in an external file whose name has a space (URI "%20")."""
    d = pathlib.Path(dirpath)
    path = _quad(d, uri="my%20quad.bin", node={"translation": [5.0, 0.0, 0.0]})
    (d / "quad.bin").rename(d / "my quad.bin")
    return path


def write_glb(dirpath) -> pathlib.Path:
    """Indexed quad in a .glb whose BIN chunk holds buffer 0."""
    b = _Bin()
    pos = b.floats(QUAD_POS, "VEC3", 3)
    idx = b.indices(QUAD_IDX)
    root = _root(
        b,
        {"byteLength": len(b.data)},
        meshes=[{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
        nodes=[{"mesh": 0, "scale": [2.0, 2.0, 2.0]}],
        scenes=[{"nodes": [0]}],
        scene=0,
    )
    path = pathlib.Path(dirpath) / "quad.glb"
    path.write_bytes(_glb(root, bytes(b.data)))
    return path


def write_data_uri(dirpath) -> pathlib.Path:
    """Indexed quad whose buffer is a base64 data: URI."""
    b = _Bin()
    pos = b.floats(QUAD_POS, "VEC3", 3)
    idx = b.indices(QUAD_IDX)
    uri = "data:application/octet-stream;base64," + base64.b64encode(bytes(b.data)).decode()
    root = _root(
        b,
        {"uri": uri, "byteLength": len(b.data)},
        meshes=[{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
        nodes=[{"mesh": 0}],
    )
    return _write_json(pathlib.Path(dirpath) / "data_uri.gltf", root)


# The texture transform of ``write_texture_transform``: KHR_texture_transform's offset,
# rotation (radians, counter-clockwise) and scale; a uniform scale, so that the mip level the
# baked twin computes from its UVs is the one the transform's level shift gives.
TEXTURE_TRANSFORM = {"offset": [0.25, -0.5], "rotation": 0.6, "scale": [1.5, 1.5]}


def texture_transform_matrix(t=TEXTURE_TRANSFORM) -> list[list[float]]:
    """The extension's M = T·R·S as two rows (uv' = M·(u, v, 1))."""
    (ou, ov), r, (su, sv) = t["offset"], t["rotation"], t["scale"]
    c, s = math.cos(r), math.sin(r)
    return [[su * c, sv * s, ou], [-su * s, sv * c, ov]]


def write_texture_transform(dirpath, *, baked: bool = False, ignored: bool = False) -> pathlib.Path:
    """A unit quad with an 8×8 texture of four coloured quadrants and a checker, used as base
    colour and emissive texture under KHR_texture_transform (TEXTURE_TRANSFORM), required.
    ``baked``: the twin without the extension, whose TEXCOORD_0 is the transformed one (the
    same image where the transform is honoured); ``ignored``: the same quad with untransformed
    UVs and no extension (what a loader that ignored the extension would show)."""
    d = pathlib.Path(dirpath)

    def texel(x, y):
        quadrant = [(230, 40, 30), (40, 200, 60), (30, 60, 220), (240, 220, 40)][(x >= 4) + 2 * (y >= 4)]
        k = 1.0 if (x + y) % 2 else 0.55
        return tuple(int(c * k) for c in quadrant) + (255,)

    (d / "quadrants.png").write_bytes(_png_pixels(8, 8, texel))
    uv = list(QUAD_UV)
    if baked:
        m = texture_transform_matrix()
        uv = [v for k in range(0, len(QUAD_UV), 2)
              for v in (m[0][0] * QUAD_UV[k] + m[0][1] * QUAD_UV[k + 1] + m[0][2],
                        m[1][0] * QUAD_UV[k] + m[1][1] * QUAD_UV[k + 1] + m[1][2])]
    b = _Bin()
    attributes = {"POSITION": b.floats(QUAD_POS, "VEC3", 3), "TEXCOORD_0": b.floats(uv, "VEC2", 2)}
    idx = b.indices(QUAD_IDX)
    (d / "tt.bin").write_bytes(bytes(b.data))
    transform = {} if (baked or ignored) else {"extensions": {"KHR_texture_transform": dict(TEXTURE_TRANSFORM)}}
    extensions = {} if (baked or ignored) else {"extensionsUsed": ["KHR_texture_transform"], "extensionsRequired": ["KHR_texture_transform"]}
    root = _root(
        b,
        {"uri": "tt.bin", "byteLength": len(b.data)},
        images=[{"uri": "quadrants.png"}],
        textures=[{"source": 0}],
        materials=[{
            "name": "quadrants",
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, **transform}, "metallicFactor": 0.0, "roughnessFactor": 1.0},
            "emissiveFactor": [1.0, 1.0, 1.0],
            "emissiveTexture": {"index": 0, **transform},
        }],
        meshes=[{"primitives": [{"attributes": attributes, "indices": idx, "material": 0}]}],
        nodes=[{"mesh": 0}],
        scenes=[{"nodes": [0]}],
        **extensions,
    )
    return _write_json(d / "texture_transform.gltf", root)


# A curved patch (a quarter cylinder, so normals vary) for the quantization fixture.
def _patch(n: int = 6):
    pos, nrm, uv, idx = [], [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            a = 0.5 * math.pi * i / n
            pos += [math.cos(a), j / n, -math.sin(a)]
            nrm += [math.cos(a), 0.0, -math.sin(a)]
            uv += [i / n, j / n]
    for j in range(n):
        for i in range(n):
            k = j * (n + 1) + i
            idx += [k, k + 1, k + n + 2, k, k + n + 2, k + n + 1]
    return pos, nrm, uv, idx


def write_quantized(dirpath, *, quantized: bool = True) -> pathlib.Path:
    """A textured quarter cylinder under KHR_mesh_quantization, required: positions as
    normalized SHORT with the dequantization scale and offset on the node, normals as
    normalized BYTE, texture coordinates as normalized UNSIGNED_SHORT. ``quantized=False``:
    the twin with the same values in FLOAT, computed from the integers, and no node scale."""
    d = pathlib.Path(dirpath)
    (d / "checker.png").write_bytes(_png_pixels(4, 4, lambda x, y: (220, 200, 60, 255) if (x + y) % 2 else (40, 90, 200, 255)))
    pos, nrm, uv, idx = _patch()
    # Positions span [-1, 1] per axis after a node scale of 1 and an offset (the usual
    # quantizer's layout): q = round(32767·(p − centre)/half).
    lo = [min(pos[k::3]) for k in range(3)]
    hi = [max(pos[k::3]) for k in range(3)]
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    half = max((b - a) / 2 for a, b in zip(lo, hi))
    qpos = [round(32767 * (p - centre[k % 3]) / half) for k, p in enumerate(pos)]
    qnrm = [round(127 * v) for v in nrm]
    quv = [round(65535 * v) for v in uv]
    b = _Bin()
    node: dict = {"mesh": 0}
    if quantized:
        def packed(values, fmt, per, pad_to, size):
            # Each element padded to a multiple of 4 bytes (glTF's vertex attribute alignment).
            out = bytearray()
            for k in range(0, len(values), per):
                out += struct.pack(f"<{per}{fmt}", *values[k:k + per])
                out += b"\x00" * (pad_to - per * size)
            return bytes(out)

        def accessor(payload, ctype, count, type_, stride):
            view = b.view(payload)
            b.views[view]["byteStride"] = stride
            b.views[view]["target"] = 34962
            b.accessors.append({"bufferView": view, "componentType": ctype, "normalized": True, "count": count, "type": type_})
            return len(b.accessors) - 1

        nv = len(pos) // 3
        attributes = {
            "POSITION": accessor(packed(qpos, "h", 3, 8, 2), 5122, nv, "VEC3", 8),
            "NORMAL": accessor(packed(qnrm, "b", 3, 4, 1), 5120, nv, "VEC3", 4),
            "TEXCOORD_0": accessor(packed(quv, "H", 2, 4, 2), 5123, nv, "VEC2", 4),
        }
        b.accessors[attributes["POSITION"]]["min"] = [min(qpos[k::3]) / 32767 for k in range(3)]
        b.accessors[attributes["POSITION"]]["max"] = [max(qpos[k::3]) / 32767 for k in range(3)]
        node.update(translation=centre, scale=[half] * 3)
        extensions = {"extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"]}
    else:
        fpos = [centre[k % 3] + half * max(q / 32767, -1.0) for k, q in enumerate(qpos)]
        fnrm = [max(q / 127, -1.0) for q in qnrm]
        attributes = {
            "POSITION": b.floats(fpos, "VEC3", 3),
            "NORMAL": b.floats(fnrm, "VEC3", 3),
            "TEXCOORD_0": b.floats([q / 65535 for q in quv], "VEC2", 2),
        }
        extensions = {}
    indices = b.indices(idx)
    (d / "patch.bin").write_bytes(bytes(b.data))
    root = _root(
        b,
        {"uri": "patch.bin", "byteLength": len(b.data)},
        images=[{"uri": "checker.png"}],
        textures=[{"source": 0}],
        materials=[{"name": "checker", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 0.5}}],
        meshes=[{"primitives": [{"attributes": attributes, "indices": indices, "material": 0}]}],
        nodes=[node],
        scenes=[{"nodes": [0]}],
        **extensions,
    )
    return _write_json(d / "patch.gltf", root)


# The emissive GLB's material: L_e = factor × strength × texel (texel decoded from sRGB).
EMISSIVE_FACTOR = (1.0, 0.5, 0.25)
EMISSIVE_STRENGTH = 40.0
EMISSIVE_TEXEL_SRGB = (255, 128, 64)


def srgb_to_linear(c8: int) -> float:
    """An 8-bit sRGB code as linear [0, 1] (IEC 61966-2-1)."""
    c = c8 / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def emissive_radiance() -> tuple[float, float, float]:
    """The emitted radiance the emissive GLB's quad must show in every pixel it covers."""
    return tuple(f * EMISSIVE_STRENGTH * srgb_to_linear(t) for f, t in zip(EMISSIVE_FACTOR, EMISSIVE_TEXEL_SRGB))


def write_emissive_glb(dirpath) -> pathlib.Path:
    """A .glb unit quad (z = 0, facing +z, UVs) whose material emits: emissiveFactor ×
    KHR_materials_emissive_strength × an emissive texture (an embedded one-colour sRGB PNG).
    Base colour black, so any light it reflected would not change what it shows."""
    b = _Bin()
    pos = b.floats(QUAD_POS, "VEC3", 3)
    uv = b.floats(QUAD_UV, "VEC2", 2)
    idx = b.indices(QUAD_IDX)
    image_view = b.view(_png(2, 2, (*EMISSIVE_TEXEL_SRGB, 255)))
    root = _root(
        b,
        {"byteLength": 0},  # set below, once the buffer is complete
        extensionsUsed=["KHR_materials_emissive_strength"],
        images=[{"bufferView": image_view, "mimeType": "image/png"}],
        textures=[{"source": 0}],
        materials=[{
            "name": "glow",
            "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0},
            "emissiveFactor": list(EMISSIVE_FACTOR),
            "emissiveTexture": {"index": 0},
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": EMISSIVE_STRENGTH}},
        }],
        meshes=[{"primitives": [{"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx, "material": 0}]}],
        nodes=[{"mesh": 0, "name": "glow"}],
        scenes=[{"nodes": [0]}],
        scene=0,
    )
    root["buffers"][0]["byteLength"] = len(b.data)
    path = pathlib.Path(dirpath) / "emissive.glb"
    path.write_bytes(_glb(root, bytes(b.data)))
    return path


def write_textured(dirpath) -> pathlib.Path:
    """Quad with UVs, no NORMAL/TANGENT; baseColor + metallicRoughness + normal PNG textures.
    The loader generates normals (+z) and tangents (+x, w = +1)."""
    return _textured(dirpath)


def write_textured_without_normal_map(dirpath) -> pathlib.Path:
    """As `write_textured`, without the normal map (textures, but no tangent frames needed)."""
    return _textured(dirpath, normal_map=False)


def write_hierarchy(dirpath) -> pathlib.Path:
    """Quad on a child node (translation 1,0,0) of a parent (translation 1,2,3, scale 2):
    vertex (0,0,0) lands at (3,2,3). Node 2 is outside the scene: its mesh is not instanced."""
    d = pathlib.Path(dirpath)
    path = _quad(d)
    root = json.loads(path.read_text())
    root["nodes"] = [
        {"name": "parent", "translation": [1.0, 2.0, 3.0], "scale": [2.0, 2.0, 2.0], "children": [1]},
        {"name": "child", "translation": [1.0, 0.0, 0.0], "mesh": 0},
        {"name": "orphan", "mesh": 0},
    ]
    return _write_json(path, root)


def write_spot_light_camera(dirpath) -> pathlib.Path:
    """A spot light at (0,5,0) pointing down (-y), intensity 450, cones 0.3/0.5, and a
    perspective camera (yfov 0.8) at (0,1,10) looking down -z; plus a point light of 10 cd at
    the origin whose ``range`` 3 is ignored (warning), and a directional light of 2 lux on a
    node at (1,2,3) rotated like the spot (light travelling along -y)."""
    s = math.sqrt(0.5)
    d = pathlib.Path(dirpath)
    path = _quad(d)
    root = json.loads(path.read_text())
    root["extensionsUsed"] = ["KHR_lights_punctual"]
    root["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "color": [1.0, 0.5, 0.0], "intensity": 450.0,
         "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}},
        {"type": "point", "intensity": 10.0, "range": 3.0},
        {"type": "directional", "intensity": 2.0, "color": [0.5, 1.0, 1.0]},
    ]}}
    root["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}]
    root["nodes"] += [
        {"name": "spot", "translation": [0.0, 5.0, 0.0], "rotation": [-s, 0.0, 0.0, s],
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "bulb", "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"name": "cam", "translation": [0.0, 1.0, 10.0], "camera": 0},
        {"name": "sun", "translation": [1.0, 2.0, 3.0], "rotation": [-s, 0.0, 0.0, s],
         "extensions": {"KHR_lights_punctual": {"light": 2}}},
    ]
    root["scenes"] = [{"nodes": [0, 1, 2, 3, 4]}]
    return _write_json(path, root)


# Keyframes of ``write_animated`` (hand-checked values in tests/test_animation.py).
ANIM_TIMES = [0.0, 1.0, 3.0]
ANIM_TRANSLATIONS = [0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 2.0, 4.0, 0.0]
# Rotation about +y: 0°, 90°, 180° (x, y, z, w).
ANIM_ROTATIONS = [0.0, 0.0, 0.0, 1.0,
                  0.0, math.sin(math.pi / 4), 0.0, math.cos(math.pi / 4),
                  0.0, 1.0, 0.0, 0.0]
ANIM_SCALES = [1.0, 1.0, 1.0, 3.0, 3.0, 3.0, 1.0, 1.0, 1.0]
# CUBICSPLINE translation of the child over [0, 2]: (in-tangent, value, out-tangent) per key.
ANIM_SPLINE_TIMES = [0.0, 2.0]
ANIM_SPLINE_VALUES = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0,
                      0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0]


def _animated(dirpath, *, times=None, translations=None, spline_times=None, sampler_count_off=False) -> pathlib.Path:
    """A quad on node "mover" (rest translation (5, 0, 0), scale 2) with a spot light on a child
    node "lamp" (rest: 1 m above its parent, pointing down -y), and two animations:
    "move" drives the mover's translation (LINEAR), rotation (LINEAR, slerp) and scale (STEP)
    at ``ANIM_TIMES``; "wiggle" drives the lamp's translation by CUBICSPLINE over [0, 2]."""
    d = pathlib.Path(dirpath)
    b = _Bin()
    pos = b.floats(QUAD_POS, "VEC3", 3)
    idx = b.indices(QUAD_IDX)
    t = b.floats(ANIM_TIMES if times is None else times, "SCALAR", 1)
    tr = b.floats(ANIM_TRANSLATIONS if translations is None else translations, "VEC3", 3)
    rot = b.floats(ANIM_ROTATIONS, "VEC4", 4)
    sc = b.floats(ANIM_SCALES, "VEC3", 3)
    st = b.floats(ANIM_SPLINE_TIMES if spline_times is None else spline_times, "SCALAR", 1)
    sv = b.floats(ANIM_SPLINE_VALUES, "VEC3", 3)
    if sampler_count_off:
        b.accessors[sv]["count"] = 4  # 4 outputs for 2 times: a spline needs 3 per time
    (d / "animated.bin").write_bytes(bytes(b.data))
    s = math.sqrt(0.5)
    root = _root(
        b,
        {"uri": "animated.bin", "byteLength": len(b.data)},
        meshes=[{"name": "quad", "primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
        nodes=[
            {"name": "mover", "mesh": 0, "translation": [5.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0], "children": [1]},
            {"name": "lamp", "translation": [0.0, 1.0, 0.0], "rotation": [-s, 0.0, 0.0, s],
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        scenes=[{"nodes": [0]}],
        scene=0,
        extensionsUsed=["KHR_lights_punctual"],
        extensions={"KHR_lights_punctual": {"lights": [
            {"type": "spot", "intensity": 10.0, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}}]}},
        animations=[
            {"name": "move",
             "samplers": [{"input": t, "output": tr},
                          {"input": t, "output": rot, "interpolation": "LINEAR"},
                          {"input": t, "output": sc, "interpolation": "STEP"}],
             "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}},
                          {"sampler": 1, "target": {"node": 0, "path": "rotation"}},
                          {"sampler": 2, "target": {"node": 0, "path": "scale"}}]},
            {"name": "wiggle",
             "samplers": [{"input": st, "output": sv, "interpolation": "CUBICSPLINE"}],
             "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}]},
        ],
    )
    return _write_json(d / "animated.gltf", root)


def write_animated(dirpath) -> pathlib.Path:
    return _animated(dirpath)


def write_animation_counts_mismatch(dirpath) -> pathlib.Path:
    """The CUBICSPLINE sampler has 4 outputs for 2 times (it needs 6)."""
    return _animated(dirpath, sampler_count_off=True)


def write_animation_times_not_increasing(dirpath) -> pathlib.Path:
    """Keyframe times 0, 1, 1 of the "move" samplers."""
    return _animated(dirpath, times=[0.0, 1.0, 1.0])


def write_animation_nan_output(dirpath) -> pathlib.Path:
    """A NaN in the translation keyframes."""
    return _animated(dirpath, translations=[0.0, 0.0, 0.0, float("nan"), 0.0, 0.0, 2.0, 4.0, 0.0])


# ------------------------------------------------------------------------------------------
# Tables
# ------------------------------------------------------------------------------------------

VALID = {
    "external_buffer": (write_external_buffer, 2),
    "glb": (write_glb, 2),
    "data_uri": (write_data_uri, 2),
    "textured": (write_textured, 2),
    "hierarchy": (write_hierarchy, 2),
    "spot_light_camera": (write_spot_light_camera, 2),
    "emissive_glb": (write_emissive_glb, 2),
    "animated": (write_animated, 2),
    "texture_transform": (write_texture_transform, 2),
    "quantized": (write_quantized, 72),
}

WARNING_CASES = {
    "points_primitive": (write_points_primitive, "meshes[0].primitives[0]"),
    "normal_map_without_uvs": (write_normal_map_without_uvs, "normal map dropped"),
    "root_listed_twice": (write_root_listed_twice, "nodes[0] is listed twice as a root"),
    "root_with_a_parent": (write_root_with_a_parent, "nodes[1] is not a root node"),
    "required_extension_not_used": (write_required_extension_not_used, "not listed in extensionsUsed"),
}

HOSTILE = {
    "truncated_buffer": (write_truncated_buffer, "buffers[0].uri"),
    "accessor_out_of_bounds": (write_accessor_out_of_bounds, "accessors[0]"),
    "index_out_of_range": (write_index_out_of_range, "meshes[0].primitives[0]"),
    "parent_dir_uri": (write_parent_dir_uri, "buffers[0].uri"),
    "absolute_uri": (write_absolute_uri, "buffers[0].uri"),
    "http_uri": (write_http_uri, "buffers[0].uri"),
    "missing_texture": (write_missing_texture, "images[1]"),
    "oversized_image": (write_oversized_image, "images[1]"),
    "invalid_json": (write_invalid_json, "JSON"),
    "node_cycle": (write_node_cycle, "nodes["),
    "two_parents": (write_two_parents, "nodes[1]"),
    "huge_byte_length": (write_huge_byte_length, "buffers[0]"),
    "non_finite_position": (write_non_finite_position, "accessors[0]"),
    "bad_glb_header": (write_bad_glb_header, "GLB header"),
    "unsupported_required_extension": (write_unsupported_required_extension, "extensionsRequired[0]"),
    "animation_counts_mismatch": (write_animation_counts_mismatch, "animations[1].samplers[0]"),
    "animation_times_not_increasing": (write_animation_times_not_increasing, "animations[0].samplers[0].input"),
    "animation_nan_output": (write_animation_nan_output, "animations[0].samplers[0].output"),
}

# A second word of each hostile case's message (compare lower-cased).
HOSTILE_KEYWORDS = {
    "truncated_buffer": "truncated",
    "accessor_out_of_bounds": "out of bounds",
    "index_out_of_range": "out of range",
    "parent_dir_uri": "escapes",
    "absolute_uri": "absolute",
    "http_uri": "not allowed",
    "missing_texture": "mr.png",
    "oversized_image": "16384",
    "invalid_json": "invalid",
    "node_cycle": "cycle",
    "two_parents": "two parents",
    "huge_byte_length": "limit",
    "non_finite_position": "non-finite",
    "bad_glb_header": "length",
    "unsupported_required_extension": "not supported",
    "animation_counts_mismatch": "2 keyframe times but 4 output values",
    "animation_times_not_increasing": "strictly increasing",
    "animation_nan_output": "non-finite",
}


def write_all(dirpath) -> dict:
    """Writes every fixture into its own subfolder of ``dirpath``; returns (and writes as
    ``manifest.json``) {name: {"path", "kind", "expect"}}."""
    root = pathlib.Path(dirpath)
    root.mkdir(parents=True, exist_ok=True)
    manifest = {}
    for kind, table in (("valid", VALID), ("warning", WARNING_CASES), ("hostile", HOSTILE)):
        for name, (writer, expect) in table.items():
            sub = root / name
            sub.mkdir(exist_ok=True)
            entry = {"path": str(writer(sub)), "kind": kind, "expect": expect}
            if kind == "hostile":
                entry["keyword"] = HOSTILE_KEYWORDS[name]
            manifest[name] = entry
    (root / "manifest.json").write_text(json.dumps(manifest, indent=1))
    return manifest


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] != "--write":
        sys.exit(f"usage: {os.path.basename(sys.argv[0])} --write DIR")
    for name, entry in write_all(sys.argv[2]).items():
        print(f"{entry['kind']:8} {name:32} {entry['path']}")
