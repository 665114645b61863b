"""Built-in procedural scenes: no files needed. Each has a default camera and one spot light.

- ``cornell_box``: the classic diffuse box with two blocks.
- ``glossy_cornell``: the box with GGX objects of roughness 0.05–0.3.
- ``caustics_ring``: a polished metal ring (roughness 0.02) on a diffuse floor.
- ``cave_flashlight``: an enclosed room lit only by a narrow spot light, glossy floor.
- ``diffuse_cornell``: the Cornell box with purely Lambertian materials (no specular
  reflectance at all, ``KHR_materials_specular`` factor 0): a frame leaves out every specular lobe.
- ``helmet_shell``: a helmet-like object at FlightHelmet's size (a 5 mm leather cap over a head,
  a metal visor band under its rim, a neck, a pedestal), lit like the FlightHelmet corpus scene:
  a curved thin shell and close-range creases, which the boxes lack.
- ``furnished_room``: a furnished room (4 × 3 m): a textured parquet floor, a normal-mapped
  plaster wall, a table, chairs, a sofa with sunk cushions, a shelf of books pressed together, a
  brushed-metal vase (roughness from a texture), toy blocks in a heap, a thin floor lamp; many
  small objects touching and interpenetrating, as real interiors have.
- ``atrium``: a courtyard at the papers' scale (about 300k triangles): fluted columns, arches,
  folded curtains (thin sheets), 1,600 floor tiles and 1,200 leaves, under a high sun-like spot.
- ``mirror_panel``: a polished metal panel (roughness 0.02) tilted 45° under a narrow spot, which
  throws the beam onto the wall behind it as a sharp bright patch (a planar caustic).

Two are animated like glTF files (``scene.animations``, ``scene.set_time(t)``): in
``cave_flashlight`` the flashlight sweeps 35° left and right over 4 s (``flashlight_sweep``), in
``glossy_cornell`` the gold sphere rolls to the front and back over 4 s (``sphere_roll``). They
show their rest pose until ``set_time`` is called.

The real-scene corpus (``corpus()``, ``corpus_scene(name)``, ``corpus_names()``): the glTF files
of the shared scene folder (``$VSGL_SCENES``, or ``shared/scenes`` beside a source checkout), each
lit by a committed light spec in ``vsgl/corpus/NAME.json``; docs/scenes.md, "The real-scene
corpus", has what each scene is for and the accuracy of each method on it.
"""

from __future__ import annotations

import json
import os
import pathlib
from dataclasses import dataclass

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


def helmet_shell() -> Scene:
    return builtin_scene("helmet_shell")


def furnished_room() -> Scene:
    return builtin_scene("furnished_room")


def atrium() -> Scene:
    return builtin_scene("atrium")


# --- The real-scene corpus ------------------------------------------------------------------
#
# Defaults, bounds and claims are chosen on real files, not only on the boxes above
# (docs/scenes.md, "The real-scene corpus"). Each corpus scene is a glTF file of the shared
# scene folder with a committed light spec (python/vsgl/corpus/NAME.json): which file, whether
# the file's own lights are kept, the lights added, in the constructors' keyword names. The
# camera is the file's own (its first camera node) or, without one, the renderer's default
# framing of the scene's bounds. The generated corpus scenes (GENERATED_CORPUS) are built-ins
# that carry what real files have and the boxes lack; they need no files and always load.

#: Where the corpus looks for the shared glTF scenes: $VSGL_SCENES, else the ``shared/scenes``
#: folder beside the repository this package was built from.
SHARED_SCENES_ENV = "VSGL_SCENES"

_CORPUS_SPECS = pathlib.Path(__file__).resolve().parent / "corpus"
#: Built-in scenes that belong to the corpus (generated in Rust like the others).
GENERATED_CORPUS = ("helmet_shell", "furnished_room", "atrium")


def shared_scenes_dir() -> pathlib.Path:
    """The folder of shared glTF scenes the corpus files are read from (it may not exist:
    ``corpus_available()`` says whether it does)."""
    env = os.environ.get(SHARED_SCENES_ENV)
    if env:
        return pathlib.Path(env)
    return pathlib.Path(__file__).resolve().parents[2] / ".." / "shared" / "scenes"


@dataclass(frozen=True)
class CorpusScene:
    """One scene of the real-scene corpus: ``scene`` lit as its spec says (a fresh copy per
    ``corpus()`` call), its name, the file it came from (None for a generated scene) and a
    one-line description."""

    name: str
    scene: Scene
    path: pathlib.Path | None
    about: str


def corpus_names() -> list[str]:
    """Names of the corpus scenes (the shared files' whether or not the files are present, then
    the generated ones)."""
    return sorted(p.stem for p in _CORPUS_SPECS.glob("*.json")) + list(GENERATED_CORPUS)


def _corpus_spec(name: str) -> dict:
    path = _CORPUS_SPECS / f"{name}.json"
    if not path.is_file():
        raise ValueError(f"corpus scene {name!r}: no such scene; the corpus has {', '.join(corpus_names())}")
    return json.loads(path.read_text())


def _spec_light(name: str, spec: dict):
    """A light of a corpus spec, checked like a --light (vsgl.lightspec: the types, their
    required and optional fields in the constructors' keyword names)."""
    # Here, not at the top: vsgl.lightspec imports vsgl, which imports this module.
    from vsgl.lightspec import KINDS, VECTORS

    fields = dict(spec)
    kind = fields.pop("type", None)
    if kind not in KINDS:
        raise ValueError(f"corpus scene {name!r}: a light's type must be one of {', '.join(KINDS)}, got {kind!r}")
    make, required, optional = KINDS[kind]
    unknown = sorted(set(fields) - set(required) - set(optional))
    missing = [f for f in required if f not in fields]
    if unknown or missing:
        raise ValueError(f"corpus scene {name!r}: a {kind} light takes {', '.join(required + optional)} "
                         f"(needs {', '.join(required)}); got unknown {unknown}, missing {missing}")
    for key in VECTORS & set(fields):
        fields[key] = tuple(float(x) for x in fields[key])
    return make(**fields)


def corpus_available(name: str | None = None) -> bool:
    """Whether the shared scene files are here (all of them, or corpus scene ``name``'s)."""
    names = corpus_names() if name is None else [name]
    root = shared_scenes_dir()
    return all(n in GENERATED_CORPUS or (root / _corpus_spec(n)["file"]).is_file() for n in names)


def corpus_scene(name: str) -> CorpusScene:
    """Corpus scene ``name``, loaded and lit. ``FileNotFoundError`` naming the file and
    ``$VSGL_SCENES`` when the shared scene folder does not have it."""
    if name in GENERATED_CORPUS:
        return CorpusScene(name, builtin_scene(name), None, "generated (vsgl.scenes.load)")
    spec = _corpus_spec(name)
    if pathlib.PurePosixPath(spec["file"]).is_absolute() or ".." in pathlib.PurePosixPath(spec["file"]).parts:
        raise ValueError(f"corpus scene {name!r}: file {spec['file']!r} must be a path inside the shared scene folder")
    path = shared_scenes_dir() / spec["file"]
    if not path.is_file():
        raise FileNotFoundError(f"corpus scene {name!r}: {path} not found (set ${SHARED_SCENES_ENV} to the shared glTF scene folder)")
    scene = Scene.load(str(path))
    if not spec.get("scene_lights", True):
        scene.lights = []
    for light in spec.get("lights", []):
        scene.add_light(_spec_light(name, light))
    return CorpusScene(name, scene, path.resolve(), spec.get("about", ""))


def corpus(names_: list[str] | None = None) -> list[CorpusScene]:
    """The corpus scenes whose files are present (or those named), lit as their specs say."""
    chosen = names_ if names_ is not None else [n for n in corpus_names() if corpus_available(n)]
    return [corpus_scene(n) for n in chosen]
