"""Optional packages in tests: the extras of pyproject.toml. Without one a test skips with the
install hint, except under CI (CI=true), which installs every extra (scripts/setup.sh): there a
missing package is a failure, so no feature behind one is left untested, as a missing GPU
adapter is a failure there (conftest.py)."""

from __future__ import annotations

import importlib
import os
from types import ModuleType

import pytest


def optional_import(module: str, reason: str) -> ModuleType:
    """The module, or a skip naming `reason` where it is not installed; a failure under CI."""
    if os.environ.get("CI"):
        try:
            return importlib.import_module(module)
        except ImportError as e:
            pytest.fail(f"CI installs every extra, but {module} does not import: {e}")
    return pytest.importorskip(module, reason=reason)
