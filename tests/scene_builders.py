"""Tiny glTF files for analytic tests: one square quad with one material, written with the
standard library only (the loader under test is vsgl's own)."""

from __future__ import annotations

import base64
import json
import pathlib
import struct


def write_quad(
    directory: pathlib.Path,
    *,
    half_size: float = 5.0,
    base_color=(0.8, 0.8, 0.8),
    metallic: float = 0.0,
    roughness: float = 1.0,
    name: str = "quad.gltf",
) -> pathlib.Path:
    """A square in the y = 0 plane, normal +y, centred at the origin, node name "quad"."""
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
    path = directory / name
    path.write_text(json.dumps(doc))
    return path
