"""Constants of the WGSL sources, read from the shaders themselves so that the tests check the
digits the GPU uses instead of copies of them."""

from __future__ import annotations

import pathlib
import re

WGSL = pathlib.Path(__file__).resolve().parent.parent / "wgsl"


def wgsl_constant(file: str, name: str) -> float:
    """A top-level `const NAME: f32|u32|i32 = value;` of wgsl/`file` (e.g. "common/sg.wgsl")."""
    src = (WGSL / file).read_text()
    match = re.search(rf"^const {name}: (?:f32|u32|i32) = ([0-9.eE+-]+)[ui]?;", src, re.MULTILINE)
    assert match, f"{name} not found in wgsl/{file}"
    return float(match.group(1))
