"""Type stubs of the native extension (checked against the built module by mypy.stubtest)."""

import os
from typing import Any, Callable, Iterable, Literal, Sequence, TypedDict, overload

from typing_extensions import Unpack

import numpy as np
import numpy.typing as npt
from typing import final

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
    "__version__",
    "adapters",
    "builtin_scene",
    "builtin_scene_names",
    "check_method_options",
    "describe_method",
    "method_info",
    "method_options",
    "stability_suite",
]

__version__: str

class VsglError(Exception): ...
class SceneError(VsglError): ...
class NoAdapterError(VsglError): ...
class ShaderError(VsglError): ...
class GpuError(VsglError): ...
class NumericsError(VsglError): ...
class ArgumentError(VsglError, ValueError): ...
class ResourceLimitError(ArgumentError): ...

# The method registry (vsgl.METHODS); tests/test_api.py checks that this Literal lists it
# (private: a typing alias only, nothing of that name exists at run time).
_MethodName = Literal["direct", "vpl", "vsgl", "vsgl2", "lpv", "reference", "pathtrace"]
METHODS: tuple[_MethodName, ...]

@final
class SpotLight:
    def __new__(
        cls,
        position: Sequence[float],
        direction: Sequence[float],
        intensity: float,
        color: Sequence[float] = ...,
        inner_cone_deg: float = 30.0,
        outer_cone_deg: float = 40.0,
    ) -> SpotLight: ...
    @property
    def position(self) -> tuple[float, float, float]: ...
    @property
    def direction(self) -> tuple[float, float, float]: ...
    @property
    def intensity(self) -> float: ...
    @property
    def color(self) -> tuple[float, float, float]: ...
    @property
    def inner_cone_deg(self) -> float: ...
    @property
    def outer_cone_deg(self) -> float: ...

@final
class PointLight:
    def __new__(cls, position: Sequence[float], intensity: float, color: Sequence[float] = ...) -> PointLight: ...
    @property
    def position(self) -> tuple[float, float, float]: ...
    @property
    def intensity(self) -> float: ...
    @property
    def color(self) -> tuple[float, float, float]: ...

@final
class DirectionalLight:
    def __new__(cls, direction: Sequence[float], intensity: float, color: Sequence[float] = ...) -> DirectionalLight: ...
    @property
    def direction(self) -> tuple[float, float, float]: ...
    @property
    def intensity(self) -> float: ...
    @property
    def color(self) -> tuple[float, float, float]: ...

_Light = SpotLight | PointLight | DirectionalLight

@final
class Camera:
    @staticmethod
    def look_at(
        eye: Sequence[float],
        target: Sequence[float],
        up: Sequence[float] = ...,
        fov_y_deg: float = 45.0,
    ) -> Camera: ...
    @property
    def eye(self) -> tuple[float, float, float]: ...
    @property
    def forward(self) -> tuple[float, float, float]: ...
    @property
    def up(self) -> tuple[float, float, float]: ...
    @property
    def fov_y_deg(self) -> float: ...

@final
class Scene:
    @staticmethod
    def load(path: str | os.PathLike[str], *, max_texture_bytes: int | None = None) -> Scene: ...
    @property
    def stats(self) -> dict[str, Any]: ...
    def add_light(self, light: _Light) -> None: ...
    def set_transform(self, node_name: str, matrix: Sequence[Sequence[float]] | npt.NDArray[Any]) -> None: ...
    def transform(self, node_name: str, *, world: bool = False) -> list[list[float]]: ...
    @property
    def animations(self) -> list[dict[str, Any]]: ...
    def set_time(self, t: float) -> None: ...
    @property
    def materials(self) -> list[dict[str, Any]]: ...
    def set_material(
        self,
        name: str,
        *,
        base_color: Sequence[float] | None = None,
        metallic: float | None = None,
        roughness: float | None = None,
        emissive: Sequence[float] | None = None,
    ) -> None: ...
    @property
    def node_names(self) -> list[str]: ...
    @property
    def lights(self) -> list[_Light]: ...
    @lights.setter
    def lights(self, value: Sequence[_Light]) -> None: ...
    @property
    def cameras(self) -> list[Camera]: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def source(self) -> str: ...
    @property
    def bounds(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]: ...
    def triangles(self) -> dict[str, npt.NDArray[Any]]: ...

@final
class Frame:
    @property
    def image(self) -> npt.NDArray[np.float32]: ...
    def aov(self, name: str) -> npt.NDArray[np.float32] | npt.NDArray[np.uint8]: ...
    @property
    def aovs(self) -> list[str]: ...
    def rsm(self, name: str) -> npt.NDArray[np.float32]: ...
    def lpv(self, name: str) -> npt.NDArray[np.float32]: ...
    def vsgls(self) -> npt.NDArray[np.void]: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def timings_ms(self) -> dict[str, float]: ...
    @property
    def timings_clock(self) -> str: ...
    @property
    def passes(self) -> list[str]: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def skipped(self) -> dict[str, str]: ...
    @property
    def memory_bytes(self) -> dict[str, int]: ...
    @property
    def settings(self) -> dict[str, int | float | bool | str | list[Any] | dict[str, Any] | None]: ...
    def save(self, path: str | os.PathLike[str], exposure: float = 1.0) -> None: ...
    def _repr_png_(self) -> bytes: ...

@final
class FrameSequence:
    def __iter__(self) -> FrameSequence: ...
    def __next__(self) -> Frame: ...

@final
class Renderer:
    def __new__(cls, width: int = 640, height: int = 360, adapter: str | None = None) -> Renderer: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def adapter(self) -> dict[str, Any]: ...
    def clear_scene_cache(self) -> None: ...
    def reset_chains(self) -> None: ...
    # --- begin: per-method overloads, generated by scripts/option_stubs.py from the method registry ---
    @overload
    def render(
        self,
        scene: Scene,
        camera: Camera | None = None,
        method: Literal["direct"] = "direct",
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        progress: Callable[[int, int, str], object] | None = None,
        **options: Unpack[_DirectOptions],
    ) -> Frame: ...
    @overload
    def render(
        self,
        scene: Scene,
        camera: Camera | None = None,
        method: Literal["vpl"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        progress: Callable[[int, int, str], object] | None = None,
        **options: Unpack[_VplOptions],
    ) -> Frame: ...
    @overload
    def render(
        self,
        scene: Scene,
        camera: Camera | None = None,
        method: Literal["vsgl"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        progress: Callable[[int, int, str], object] | None = None,
        **options: Unpack[_VsglOptions],
    ) -> Frame: ...
    @overload
    def render(
        self,
        scene: Scene,
        camera: Camera | None = None,
        method: Literal["vsgl2"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        progress: Callable[[int, int, str], object] | None = None,
        **options: Unpack[_Vsgl2Options],
    ) -> Frame: ...
    @overload
    def render(
        self,
        scene: Scene,
        camera: Camera | None = None,
        method: Literal["lpv"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        progress: Callable[[int, int, str], object] | None = None,
        **options: Unpack[_LpvOptions],
    ) -> Frame: ...
    @overload
    def render(
        self,
        scene: Scene,
        camera: Camera | None = None,
        method: Literal["reference"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        progress: Callable[[int, int, str], object] | None = None,
        **options: Unpack[_ReferenceOptions],
    ) -> Frame: ...
    @overload
    def render(
        self,
        scene: Scene,
        camera: Camera | None = None,
        method: Literal["pathtrace"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        progress: Callable[[int, int, str], object] | None = None,
        **options: Unpack[_PathtraceOptions],
    ) -> Frame: ...
    @overload
    def render_sequence(
        self,
        scene: Scene,
        frames: Iterable[dict[str, Any]],
        camera: Camera | None = None,
        method: Literal["direct"] = "direct",
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        **options: Unpack[_DirectOptions],
    ) -> FrameSequence: ...
    @overload
    def render_sequence(
        self,
        scene: Scene,
        frames: Iterable[dict[str, Any]],
        camera: Camera | None = None,
        method: Literal["vpl"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        **options: Unpack[_VplOptions],
    ) -> FrameSequence: ...
    @overload
    def render_sequence(
        self,
        scene: Scene,
        frames: Iterable[dict[str, Any]],
        camera: Camera | None = None,
        method: Literal["vsgl"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        **options: Unpack[_VsglOptions],
    ) -> FrameSequence: ...
    @overload
    def render_sequence(
        self,
        scene: Scene,
        frames: Iterable[dict[str, Any]],
        camera: Camera | None = None,
        method: Literal["vsgl2"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        **options: Unpack[_Vsgl2Options],
    ) -> FrameSequence: ...
    @overload
    def render_sequence(
        self,
        scene: Scene,
        frames: Iterable[dict[str, Any]],
        camera: Camera | None = None,
        method: Literal["lpv"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        **options: Unpack[_LpvOptions],
    ) -> FrameSequence: ...
    @overload
    def render_sequence(
        self,
        scene: Scene,
        frames: Iterable[dict[str, Any]],
        camera: Camera | None = None,
        method: Literal["reference"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        **options: Unpack[_ReferenceOptions],
    ) -> FrameSequence: ...
    @overload
    def render_sequence(
        self,
        scene: Scene,
        frames: Iterable[dict[str, Any]],
        camera: Camera | None = None,
        method: Literal["pathtrace"] = ...,
        *,
        plan: Literal["auto", "full"] = "auto",
        aovs: Sequence[str] | None = None,
        **options: Unpack[_PathtraceOptions],
    ) -> FrameSequence: ...
    # --- end: per-method overloads ---

def adapters() -> list[dict[str, Any]]: ...
def describe_method(name: str) -> str: ...
# What `method_info` returns (a plain dict at run time; the name is private so stubtest does not
# look for a class in the extension).
class _MethodInfo(TypedDict):
    name: str
    summary: str
    aovs: list[str]
    direct_light: Literal["shadow_mapped", "by_method"]
    ground_truth: bool
    stochastic: bool
    # Per option: "type" ("int", "float", "bool", "choice"), its range or "choices", "default", "help".
    options: dict[str, dict[str, Any]]

def method_info(name: str) -> _MethodInfo: ...
def method_options(name: str) -> dict[str, int | float | bool | str]: ...
def check_method_options(name: str, **options: int | float | bool | str | None) -> None: ...
def builtin_scene_names() -> list[str]: ...
def builtin_scene(name: str) -> Scene: ...
def stability_suite(adapter: str | None = None, bound_scale: float = 1.0) -> list[dict[str, Any]]: ...

# --- begin: per-method options, generated by scripts/option_stubs.py from the method registry ---
class _DirectOptions(TypedDict, total=False):
    shadow_size: int
class _VplOptions(TypedDict, total=False):
    shadow_size: int
    num_lights: int
    rsm_size: int
    sampling: Literal["stratified", "random", "metropolis"]
    chain_space: Literal["world", "rsm"]
    seed: int
    vpl_clamp: float
    interleave: int
    denoise: bool
    denoise_form: Literal["gather", "exchange"]
    visibility: Literal["none", "ism", "raytrace"]
    ism_size: int
    ism_points: int
    ism_points_per_map: int
    ism_bias: float
    ism_pcf: int
    importance: Literal["rsm", "brsm"]
    importance_lights: int
    importance_interleave: int
    rsm_fit: Literal["scene", "cone"]
    capture_rsm: bool
class _VsglOptions(TypedDict, total=False):
    shadow_size: int
    num_lights: int
    rsm_size: int
    sampling: Literal["stratified", "random", "metropolis"]
    chain_space: Literal["world", "rsm"]
    seed: int
    kernel: Literal["integral", "density", "node", "kmeans2d", "kmeans3d"]
    kmeans_iterations: int
    kernel_filter: Literal["nodes", "trilinear"]
    K: float
    coherence: float
    bisection_steps: int
    interleave: int
    denoise: bool
    denoise_form: Literal["gather", "exchange"]
    diffuse: Literal["papers", "accurate", "sg_product"]
    lighting: Literal["asg", "accurate", "blend"]
    lambert_lobe: Literal["exact_compact", "hemisphere", "papers"]
    plane_fade: bool
    visibility: Literal["none", "ism", "raytrace"]
    ism_size: int
    ism_points: int
    ism_points_per_map: int
    ism_bias: float
    ism_pcf: int
    shadow_target: Literal["resampled", "centre"]
    near_field: Literal["texels", "sg"]
    importance: Literal["rsm", "brsm"]
    importance_lights: int
    importance_interleave: int
    rsm_fit: Literal["scene", "cone"]
    capture_rsm: bool
class _Vsgl2Options(TypedDict, total=False):
    shadow_size: int
    rsm_size: int
    diffuse: Literal["papers", "accurate", "sg_product"]
    lighting: Literal["asg", "accurate", "blend"]
    lambert_lobe: Literal["exact_compact", "hemisphere", "papers"]
    plane_fade: bool
    vsgl2_reduction: Literal["auto", "subgroup", "shared_memory"]
    visibility: Literal["none", "ism", "raytrace"]
    ism_size: int
    ism_points: int
    ism_points_per_map: int
    ism_bias: float
    ism_pcf: int
    rsm_fit: Literal["scene", "cone"]
    capture_rsm: bool
class _LpvOptions(TypedDict, total=False):
    shadow_size: int
    rsm_size: int
    lpv_grid: int
    lpv_cascades: int
    lpv_iterations: int
    lpv_occlusion: bool
    capture_lpv: bool
    rsm_fit: Literal["scene", "cone"]
    capture_rsm: bool
class _ReferenceOptions(TypedDict, total=False):
    shadow_size: int
    rsm_size: int
    vpl_clamp: float
    visibility: Literal["none", "ism", "raytrace"]
    ism_size: int
    ism_points: int
    ism_points_per_map: int
    ism_bias: float
    ism_pcf: int
    rsm_fit: Literal["scene", "cone"]
    capture_rsm: bool
class _PathtraceOptions(TypedDict, total=False):
    spp: int
    seed: int
    time_budget_s: float
    strategy: Literal["camera", "bidirectional", "light"]
# --- end: per-method options ---
