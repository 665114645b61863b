"""vsgl: real-time one-bounce glossy global illumination with virtual spherical Gaussian lights.

A Rust renderer on wgpu (the whole GPU pipeline in WGSL) used from Python::

    import vsgl
    r = vsgl.Renderer(width=320, height=240)
    frame = r.render(vsgl.scenes.cornell_box())
    frame.image          # (H, W, 3) float32 linear radiance
    frame.save("out.png")
"""

import atexit as _atexit
import os as _os
import shutil as _shutil
import tempfile as _tempfile


def _prepare_device_environment() -> None:
    """Called by the extension just before it opens a GPU instance (``Renderer()``,
    ``adapters()``, ``stability_suite()``), not at import: Mesa's Vulkan drivers warn
    "XDG_RUNTIME_DIR is invalid or not set" on every device when the machine has no user
    session (CI, containers, ssh). Headless rendering needs no runtime dir, so a private one
    (mode 0700, removed at exit) is set then, unless the user set one."""
    if not _os.environ.get("XDG_RUNTIME_DIR"):
        runtime_dir = _tempfile.mkdtemp(prefix="vsgl-runtime-")
        _os.environ["XDG_RUNTIME_DIR"] = runtime_dir
        _atexit.register(_shutil.rmtree, runtime_dir, ignore_errors=True)


from vsgl._vsgl import (
    METHODS,
    ArgumentError,
    Camera,
    DirectionalLight,
    Frame,
    FrameSequence,
    GpuError,
    NumericsError,
    NoAdapterError,
    PointLight,
    Renderer,
    ResourceLimitError,
    Scene,
    SceneError,
    ShaderError,
    SpotLight,
    VsglError,
    WindowUnavailableError,
    __version__,
    adapters,
    check_method_options,
    describe_method,
    method_info,
    method_options,
)
from vsgl import scenes

__all__ = [
    "METHODS",
    "ArgumentError",
    "Camera",
    "DirectionalLight",
    "Frame",
    "FrameSequence",
    "GpuError",
    "NumericsError",
    "NoAdapterError",
    "PointLight",
    "Renderer",
    "ResourceLimitError",
    "Scene",
    "SceneError",
    "ShaderError",
    "SpotLight",
    "VsglError",
    "WindowUnavailableError",
    "__version__",
    "adapters",
    "check_method_options",
    "describe_method",
    "method_info",
    "method_options",
    "scenes",
    "view",
]

# The submodules beyond `scenes` load on first use, so `import vsgl` stays light (bench pulls in
# statistics and plotting helpers) while `vsgl.metrics.rmse(...)` works without an import of
# its own (PEP 562).
_LAZY_SUBMODULES = ("bench", "camera_control", "lightspec", "metrics", "reproduce", "scene_edit", "stability", "video", "view_session", "window_view")

VIEW_EXTRA_HINT = "pip install 'vsgl[view]'"


def view(scene: Scene, method: str = "vsgl", **kwargs):
    """A live view in Jupyter: the frame, a status line and a settings panel.

    ``vsgl.view(scene, "vsgl", num_lights=1024)``, or ``compare=["vpl", "vsgl"]`` for two methods
    either side of a movable divider. Keywords: ``renderer`` (a ``Renderer`` to draw with; one is
    made otherwise), ``size=(640, 360)``, ``camera`` (the scene's default camera when None),
    ``aov="ldr"``, ``exposure=1.0``, ``seed=0``, ``overlay=True`` (GPU ms, frames per second and,
    when stopped, the error, drawn into the frame); the rest are the methods' options, checked as
    ``render`` checks them. Mouse and keys: ``vsgl.camera_control`` and ``vsgl.scene_edit``.
    Needs the notebook extra (``pip install 'vsgl[view]'``: jupyter_rfb, ipywidgets)."""
    try:
        from vsgl.notebook_view import view as _view
    except ImportError as e:
        raise ImportError(f"vsgl.view needs the notebook extra: {VIEW_EXTRA_HINT} ({e})") from e
    return _view(scene, method, **kwargs)


def __getattr__(name: str):
    if name in _LAZY_SUBMODULES:
        import importlib

        return importlib.import_module(f"vsgl.{name}")
    raise AttributeError(f"module 'vsgl' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY_SUBMODULES))
