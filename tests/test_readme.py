"""The README's Python example runs as written (at a smaller size, to keep the suite fast)."""

from __future__ import annotations

import pathlib
import re

import pytest


@pytest.mark.gpu
def test_readme_python_example_runs(tmp_path, monkeypatch):
    readme = (pathlib.Path(__file__).resolve().parents[1] / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", readme, re.S)
    assert blocks, "README has a Python example"
    code = blocks[0].replace("width=640, height=360", "width=64, height=36")
    assert "width=64, height=36" in code
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    exec(compile(code, "README.md", "exec"), namespace)
    frame = namespace["frame"]
    assert frame.image.shape == (36, 64, 3)
    assert (tmp_path / "out.png").is_file()
