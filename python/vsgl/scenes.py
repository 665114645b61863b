"""Built-in procedural scenes: no files needed. Each has a default camera and one spot light.

- ``cornell_box``: the classic diffuse box with two blocks.
- ``glossy_cornell``: the box with GGX objects of roughness 0.05–0.3.
- ``caustics_ring``: a polished metal ring (roughness 0.02) on a diffuse floor.
- ``cave_flashlight``: an enclosed room lit only by a narrow spot light, glossy floor.
- ``diffuse_cornell``: the Cornell box with purely Lambertian materials (no specular
  reflectance at all, ``KHR_materials_specular`` factor 0): a frame leaves out every specular lobe.
- ``mirror_panel``: a polished metal panel (roughness 0.02) tilted 45° under a narrow spot, which
  throws the beam onto the wall behind it as a sharp bright patch (a planar caustic).

Two are animated like glTF files (``scene.animations``, ``scene.set_time(t)``): in
``cave_flashlight`` the flashlight sweeps 35° left and right over 4 s (``flashlight_sweep``), in
``glossy_cornell`` the gold sphere rolls to the front and back over 4 s (``sphere_roll``). They
show their rest pose until ``set_time`` is called.
"""

from __future__ import annotations

from vsgl._vsgl import Scene, builtin_scene, builtin_scene_names


def names() -> list[str]:
    """Names of the built-in scenes."""
    return list(builtin_scene_names())


def load(name: str) -> Scene:
    """A new copy of the built-in scene ``name`` (ValueError for an unknown name)."""
    return builtin_scene(name)


def cornell_box() -> Scene:
    return builtin_scene("cornell_box")


def glossy_cornell() -> Scene:
    return builtin_scene("glossy_cornell")


def caustics_ring() -> Scene:
    return builtin_scene("caustics_ring")


def cave_flashlight() -> Scene:
    return builtin_scene("cave_flashlight")


def diffuse_cornell() -> Scene:
    return builtin_scene("diffuse_cornell")


def mirror_panel() -> Scene:
    return builtin_scene("mirror_panel")
