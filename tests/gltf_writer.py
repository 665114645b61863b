"""The building blocks of the glTF 2.0 fixtures (standard library only): one binary buffer
with its bufferViews and accessors, the root JSON, PNG and GLB encoders, and the parameterised
base scenes the fixtures vary (a unit quad, a textured quad, a PNG of zeros).

The fixtures themselves are in ``gltf_fixtures`` (valid scenes, the tables, ``--write``) and
``gltf_hostile_fixtures`` (files that load with a warning or must be refused).
"""

from __future__ import annotations

import json
import math
import pathlib
import struct
import zlib

# Unit quad in z = 0, counter-clockwise seen from +z (normals +z).
QUAD_POS = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0]
QUAD_UV = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0]
QUAD_IDX = [0, 1, 2, 0, 2, 3]


class _Bin:
    """One binary buffer with its bufferViews and accessors."""

    def __init__(self) -> None:
        self.data = bytearray()
        self.views: list[dict] = []
        self.accessors: list[dict] = []

    def view(self, payload: bytes) -> int:
        while len(self.data) % 4:
            self.data.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)})
        self.data += payload
        return len(self.views) - 1

    def floats(self, values: list[float], type_: str, ncomp: int) -> int:
        view = self.view(struct.pack(f"<{len(values)}f", *values))
        acc = {"bufferView": view, "componentType": 5126, "count": len(values) // ncomp, "type": type_}
        if type_ == "VEC3":
            cols = [values[k::3] for k in range(3)]
            if all(math.isfinite(v) for v in values):
                acc["min"] = [min(c) for c in cols]
                acc["max"] = [max(c) for c in cols]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def indices(self, values: list[int]) -> int:
        view = self.view(struct.pack(f"<{len(values)}H", *values))
        self.accessors.append({"bufferView": view, "componentType": 5123, "count": len(values), "type": "SCALAR"})
        return len(self.accessors) - 1


def _root(b: _Bin, buffer: dict, **extra) -> dict:
    root = {
        "asset": {"version": "2.0", "generator": "vsgl tests/gltf_fixtures.py"},
        "buffers": [buffer],
        "bufferViews": b.views,
        "accessors": b.accessors,
    }
    root.update(extra)
    return root


def _write_json(path: pathlib.Path, root: dict) -> pathlib.Path:
    path.write_text(json.dumps(root, indent=1))
    return path


def _png_chunk(kind: bytes, payload: bytes) -> bytes:
    """One PNG chunk: length, type, payload, CRC."""
    body = kind + payload
    return struct.pack(">I", len(payload)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def _png(width: int, height: int, rgba: tuple[int, int, int, int], with_pixels: bool = True) -> bytes:
    """An 8-bit RGBA PNG of one colour. Without pixels: the header plus a 16-byte IDAT, so
    only a loader that decodes before checking the size would notice the missing pixels."""

    out = b"\x89PNG\r\n\x1a\n" + _png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
    if with_pixels:
        row = b"\x00" + bytes(rgba) * width
        out += _png_chunk(b"IDAT", zlib.compress(row * height))
    else:
        out += _png_chunk(b"IDAT", zlib.compress(b"\x00" * 16))  # far too short for the header's size
    return out + _png_chunk(b"IEND", b"")


def _glb(root: dict, binary: bytes) -> bytes:
    j = json.dumps(root).encode()
    j += b" " * (-len(j) % 4)
    b = bytes(binary) + b"\x00" * (-len(binary) % 4)
    total = 12 + 8 + len(j) + 8 + len(b)
    return (
        b"glTF"
        + struct.pack("<II", 2, total)
        + struct.pack("<I", len(j))
        + b"JSON"
        + j
        + struct.pack("<I", len(b))
        + b"BIN\x00"
        + b
    )


def _quad(dirpath, *, uri="quad.bin", node=None, mode=None, indices=QUAD_IDX, positions=QUAD_POS,
          byte_length=None, name="quad.gltf") -> pathlib.Path:
    """Quad mesh on node 0 of scene 0, buffer written to ``quad.bin``."""
    d = pathlib.Path(dirpath)
    b = _Bin()
    pos = b.floats(positions, "VEC3", 3)
    prim = {"attributes": {"POSITION": pos}}
    if indices is not None:
        prim["indices"] = b.indices(indices)
    if mode is not None:
        prim["mode"] = mode
    (d / "quad.bin").write_bytes(bytes(b.data))
    n = {"mesh": 0, "name": "quad"}
    n.update(node or {})
    root = _root(
        b,
        {"uri": uri, "byteLength": len(b.data) if byte_length is None else byte_length},
        meshes=[{"name": "quad", "primitives": [prim]}],
        nodes=[n],
        scenes=[{"nodes": [0]}],
        scene=0,
    )
    return _write_json(d / name, root)


def _textured(dirpath, *, with_uvs=True, missing_image=False, huge_image=False, normal_map=True) -> pathlib.Path:
    d = pathlib.Path(dirpath)
    (d / "tex").mkdir(exist_ok=True)
    (d / "base color.png").write_bytes(_png(4, 2, (255, 0, 0, 255)))
    if huge_image:
        # A PNG header claiming 20000 x 20000: must be refused before decoding.
        (d / "mr.png").write_bytes(_png(20000, 20000, (0, 0, 0, 255), with_pixels=False))
    elif not missing_image:
        (d / "mr.png").write_bytes(_png(2, 2, (0, 128, 255, 255)))
    (d / "tex" / "normal.png").write_bytes(_png(2, 2, (128, 128, 255, 255)))
    b = _Bin()
    attributes = {"POSITION": b.floats(QUAD_POS, "VEC3", 3)}
    if with_uvs:
        attributes["TEXCOORD_0"] = b.floats(QUAD_UV, "VEC2", 2)
    idx = b.indices(QUAD_IDX)
    (d / "tex.bin").write_bytes(bytes(b.data))
    root = _root(
        b,
        {"uri": "tex.bin", "byteLength": len(b.data)},
        images=[{"uri": "base%20color.png"}, {"uri": "mr.png"}, {"uri": "tex/normal.png"}],
        textures=[{"source": 0}, {"source": 1}, {"source": 2}],
        materials=[{
            "name": "painted",
            "pbrMetallicRoughness": {
                "baseColorFactor": [1.0, 0.5, 0.25, 1.0],
                "baseColorTexture": {"index": 0},
                "metallicFactor": 0.25,
                "roughnessFactor": 0.75,
                "metallicRoughnessTexture": {"index": 1},
            },
            **({"normalTexture": {"index": 2, "scale": 0.5}} if normal_map else {}),
        }],
        meshes=[{"primitives": [{"attributes": attributes, "indices": idx, "material": 0}]}],
        nodes=[{"mesh": 0}],
        scenes=[{"nodes": [0]}],
    )
    return _write_json(d / "textured.gltf", root)


def _png_pixels(width: int, height: int, pixel) -> bytes:
    """An 8-bit RGBA PNG whose texel (x, y) is ``pixel(x, y)`` (an RGBA tuple)."""

    rows = b"".join(b"\x00" + b"".join(bytes(pixel(x, y)) for x in range(width)) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + _png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + _png_chunk(b"IDAT", zlib.compress(rows)) + _png_chunk(b"IEND", b""))


def write_png_of_zeros(path, side: int, channels: int = 1) -> pathlib.Path:
    """A valid 8-bit PNG of ``side`` x ``side`` black pixels (1 channel: grey, 3: RGB, 4: RGBA).
    Zeros compress about 200:1 at zlib level 1, so a 16384² grey image is a file of about a
    megabyte that decodes to 256 MiB (1 GiB as RGBA8): a decompression bomb. Rows are fed to
    zlib one block at a time, so writing it never holds the raw image in memory."""
    colour_type = {1: 0, 3: 2, 4: 6}[channels]

    z = zlib.compressobj(1)
    rows_per_block = 64
    block = bytes((1 + side * channels) * rows_per_block)  # filter byte 0 + pixels, per row
    idat = []
    for start in range(0, side, rows_per_block):
        n = min(rows_per_block, side - start)
        idat.append(z.compress(block if n == rows_per_block else block[: (1 + side * channels) * n]))
    idat.append(z.flush())
    path = pathlib.Path(path)
    path.write_bytes(
        b"\x89PNG\r\n\x1a\n"
        + _png_chunk(b"IHDR", struct.pack(">IIBBBBB", side, side, 8, colour_type, 0, 0, 0))
        + _png_chunk(b"IDAT", b"".join(idat))
        + _png_chunk(b"IEND", b"")
    )
    return path
