"""glTF fixtures that are not clean scenes: files that load with a warning, and hostile or
malformed files that must raise ``vsgl.SceneError`` (truncated buffers, URIs out of the folder,
node cycles, a decompression bomb, ...). Each ``write_<name>(dirpath) -> pathlib.Path`` is
listed with what it must produce in ``gltf_fixtures.WARNING_CASES`` / ``HOSTILE`` (the
animation's malformed samplers stay in ``gltf_fixtures``, beside the animated scene they vary).
"""

from __future__ import annotations

import json
import pathlib
import struct

from gltf_writer import QUAD_POS, _quad, _textured, _write_json, write_png_of_zeros


# ------------------------------------------------------------------------------------------
# Loads, with a warning
# ------------------------------------------------------------------------------------------


def write_points_primitive(dirpath) -> pathlib.Path:
    """mode 0 (POINTS): skipped with a warning naming meshes[0].primitives[0]; 0 triangles."""
    return _quad(dirpath, mode=0, indices=None)


def write_normal_map_without_uvs(dirpath) -> pathlib.Path:
    """Normal-mapped material on a primitive without TEXCOORD_0: normal map dropped."""
    return _textured(dirpath, with_uvs=False)


def write_root_listed_twice(dirpath) -> pathlib.Path:
    """scenes[0].nodes lists nodes[0] twice (glTF requires unique root nodes)."""
    path = _quad(dirpath)
    root = json.loads(path.read_text())
    root["scenes"] = [{"nodes": [0, 0]}]
    return _write_json(path, root)


def write_root_with_a_parent(dirpath) -> pathlib.Path:
    """scenes[0].nodes lists nodes[1], a child of nodes[0] (a scene must list root nodes)."""
    path = _quad(dirpath)
    root = json.loads(path.read_text())
    root["nodes"] = [{"children": [1]}, {"mesh": 0}]
    root["scenes"] = [{"nodes": [0, 1]}]
    return _write_json(path, root)


def write_required_extension_not_used(dirpath) -> pathlib.Path:
    """extensionsRequired names an extension that extensionsUsed does not list."""
    path = _quad(dirpath)
    root = json.loads(path.read_text())
    root["extensionsRequired"] = ["KHR_mesh_quantization"]
    return _write_json(path, root)


# ------------------------------------------------------------------------------------------
# Hostile and malformed files: each must raise vsgl.SceneError
# ------------------------------------------------------------------------------------------


def write_truncated_buffer(dirpath) -> pathlib.Path:
    """quad.bin is 5 bytes shorter than the buffer's byteLength."""
    d = pathlib.Path(dirpath)
    path = _quad(d)
    data = (d / "quad.bin").read_bytes()
    (d / "quad.bin").write_bytes(data[:-5])
    return path


def write_accessor_out_of_bounds(dirpath) -> pathlib.Path:
    """POSITION accessor count 5 in a bufferView that holds 4 VEC3."""
    path = _quad(dirpath)
    root = json.loads(path.read_text())
    root["accessors"][0]["count"] = 5
    return _write_json(path, root)


def write_index_out_of_range(dirpath) -> pathlib.Path:
    """Index 7 with 4 vertices."""
    return _quad(dirpath, indices=[0, 1, 2, 0, 2, 7])


def write_parent_dir_uri(dirpath) -> pathlib.Path:
    """Buffer URI "../outside.bin" (the target exists, outside the scene folder)."""
    d = pathlib.Path(dirpath)
    scene_dir = d / "scene"
    scene_dir.mkdir(exist_ok=True)
    path = _quad(scene_dir, uri="../outside.bin")
    (d / "outside.bin").write_bytes((scene_dir / "quad.bin").read_bytes())
    return path


def write_absolute_uri(dirpath) -> pathlib.Path:
    return _quad(dirpath, uri="/etc/passwd")


def write_http_uri(dirpath) -> pathlib.Path:
    return _quad(dirpath, uri="http://example.com/quad.bin")


def write_missing_texture(dirpath) -> pathlib.Path:
    """images[1] ("mr.png") does not exist."""
    return _textured(dirpath, missing_image=True)


def write_oversized_image(dirpath) -> pathlib.Path:
    """images[1] is a PNG whose header claims 20000 x 20000 pixels (almost no pixel data)."""
    return _textured(dirpath, huge_image=True)


def write_invalid_json(dirpath) -> pathlib.Path:
    path = pathlib.Path(dirpath) / "invalid.gltf"
    path.write_text('{"asset": {"version": "2.0"}, "nodes": [')
    return path


def write_node_cycle(dirpath) -> pathlib.Path:
    """nodes 0 -> 1 -> 2 -> 0: every node has exactly one parent."""
    path = _quad(dirpath)
    root = json.loads(path.read_text())
    root["nodes"] = [{"children": [1]}, {"children": [2]}, {"children": [0], "mesh": 0}]
    return _write_json(path, root)


def write_two_parents(dirpath) -> pathlib.Path:
    """nodes[1] is a child of both nodes[0] and nodes[2]."""
    path = _quad(dirpath)
    root = json.loads(path.read_text())
    root["nodes"] = [{"children": [1]}, {"mesh": 0}, {"children": [1]}]
    root["scenes"] = [{"nodes": [0, 2]}]
    return _write_json(path, root)


def write_huge_byte_length(dirpath) -> pathlib.Path:
    """byteLength 10**15: must fail at once, without allocating."""
    return _quad(dirpath, byte_length=10**15)


def write_non_finite_position(dirpath) -> pathlib.Path:
    pos = list(QUAD_POS)
    pos[4] = float("nan")
    return _quad(dirpath, positions=pos)


def write_bad_glb_header(dirpath) -> pathlib.Path:
    """A GLB whose header declares a length of 4 bytes (less than the header itself)."""
    path = pathlib.Path(dirpath) / "bad.glb"
    path.write_bytes(b"glTF" + struct.pack("<II", 2, 4))
    return path


def write_unsupported_required_extension(dirpath) -> pathlib.Path:
    path = _quad(dirpath)
    root = json.loads(path.read_text())
    root["extensionsUsed"] = root["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    return _write_json(path, root)


def write_texture_bomb(dirpath, side: int = 16384, channels: int = 1) -> pathlib.Path:
    """`write_textured` whose metallicRoughness image ``mr.png`` is ``write_png_of_zeros``."""
    path = _textured(dirpath)
    write_png_of_zeros(pathlib.Path(dirpath) / "mr.png", side, channels)
    return path
