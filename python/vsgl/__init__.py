"""vsgl: real-time one-bounce glossy global illumination with virtual spherical Gaussian lights.

A Rust renderer on wgpu (the whole GPU pipeline in WGSL) used from Python::

    import vsgl
    r = vsgl.Renderer(width=320, height=240)
    frame = r.render(vsgl.scenes.cornell_box())
    frame.image          # (H, W, 3) float32 linear radiance
    frame.save("out.png")
"""

from vsgl._vsgl import (
    Camera,
    Frame,
    GpuError,
    NoAdapterError,
    Renderer,
    Scene,
    SceneError,
    ShaderError,
    SpotLight,
    VsglError,
    __version__,
    adapters,
)
from vsgl import scenes

__all__ = [
    "Camera",
    "Frame",
    "GpuError",
    "NoAdapterError",
    "Renderer",
    "Scene",
    "SceneError",
    "ShaderError",
    "SpotLight",
    "VsglError",
    "__version__",
    "adapters",
    "scenes",
]
