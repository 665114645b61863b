"""Shared fixtures: one renderer per session on the best adapter (lavapipe in CI).

Without any adapter the GPU tests skip with the install hint, except under CI (CI=true),
where a missing adapter is a failure: CI must never pass by skipping everything.
"""

from __future__ import annotations

import inspect
import os
import pathlib

import pytest

import vsgl

SHARED_SCENES = pathlib.Path(__file__).resolve().parents[1] / ".." / "shared" / "scenes"


def _open(width: int, height: int) -> vsgl.Renderer:
    try:
        return vsgl.Renderer(width=width, height=height)
    except vsgl.NoAdapterError as e:
        if os.environ.get("CI"):
            pytest.fail(f"CI has no GPU adapter: {e}")
        pytest.skip(f"no GPU adapter: {e}")


@pytest.fixture(scope="session")
def renderer() -> vsgl.Renderer:
    return _open(64, 48)


@pytest.fixture(scope="session")
def make_renderer():
    cache: dict[tuple[int, int], vsgl.Renderer] = {}

    def make(width: int, height: int) -> vsgl.Renderer:
        if (width, height) not in cache:
            cache[(width, height)] = _open(width, height)
        return cache[(width, height)]

    return make


@pytest.fixture
def shared_scenes() -> pathlib.Path:
    if not SHARED_SCENES.is_dir():
        pytest.skip(f"skipping: {SHARED_SCENES} not found (the shared scene folder is absent)")
    return SHARED_SCENES.resolve()


# The fixtures that open a Renderer; a test that needs one (directly or through another
# fixture) or builds one in its body is marked `gpu`, so `pytest -m "not gpu"` runs the rest.
# Tests that open one another way (the CLI, bench, the scene suite) carry the mark themselves.
GPU_FIXTURES = {"renderer", "make_renderer", "tiny"}


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        uses_fixture = GPU_FIXTURES & set(getattr(item, "fixturenames", ()))
        function = getattr(item, "function", None)
        try:
            builds_one = function is not None and "vsgl.Renderer(" in inspect.getsource(function)
        except (OSError, TypeError):
            builds_one = False
        if uses_fixture or builds_one:
            item.add_marker(pytest.mark.gpu)
