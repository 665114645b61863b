"""Lights written as text, for the command line (``--light``)::

    spot position=0,1.9,0 direction=0,-1,0 intensity=20 outer_cone_deg=50
    point position=0,1.5,0 intensity=10 color=1,0.9,0.8
    directional direction=-0.3,-1,-0.2 intensity=3

The first word is the type; then ``name=value`` pairs with the Python constructors' keyword
names (``vsgl.SpotLight``, ``vsgl.PointLight``, ``vsgl.DirectionalLight``) and units (W/sr,
i.e. candela for spot and point lights; lux for directional ones). Vectors are three numbers
separated by commas, with no spaces. Also here, for the same command lines: a method option's
value as typed after ``-O`` (``option_value``).
"""

from __future__ import annotations

from typing import Any, Union

import vsgl

Light = Union[vsgl.SpotLight, vsgl.PointLight, vsgl.DirectionalLight]

# type: (constructor, required fields, optional fields); vectors are the fields named in VECTORS.
KINDS: dict[str, tuple[Any, tuple[str, ...], tuple[str, ...]]] = {
    "spot": (vsgl.SpotLight, ("position", "direction", "intensity"), ("color", "inner_cone_deg", "outer_cone_deg")),
    "point": (vsgl.PointLight, ("position", "intensity"), ("color",)),
    "directional": (vsgl.DirectionalLight, ("direction", "intensity"), ("color",)),
}
VECTORS = {"position", "direction", "color"}

EXAMPLE = 'e.g. "point position=0,1.5,0 intensity=10"'


def parse_light(text: str) -> Light:
    """The light `text` describes; ``ValueError`` naming the light, the field and what was
    expected otherwise (the constructors' own checks apply too: finite values, ranges)."""
    words = text.split()
    if not words or words[0] not in KINDS:
        got = repr(words[0]) if words else "nothing"
        raise ValueError(f"light {text!r}: the first word must be the type, one of {', '.join(KINDS)}; got {got} ({EXAMPLE})")
    kind = words[0]
    make, required, optional = KINDS[kind]
    fields: dict[str, Any] = {}
    for word in words[1:]:
        name, eq, value = word.partition("=")
        if not eq or not value:
            raise ValueError(f"light {text!r}: expected name=value, got {word!r} ({EXAMPLE})")
        if name not in required + optional:
            raise ValueError(f"light {text!r}: a {kind} light has no field {name!r}; it takes {', '.join(required + optional)}")
        if name in fields:
            raise ValueError(f"light {text!r}: {name} is given twice")
        try:
            numbers = tuple(float(x) for x in value.split(","))
        except ValueError:
            raise ValueError(f"light {text!r}: {name}={value!r} is not a number{' list' if name in VECTORS else ''}") from None
        if name in VECTORS:
            if len(numbers) != 3:
                raise ValueError(f"light {text!r}: {name} needs three numbers separated by commas (x,y,z), got {len(numbers)}")
            fields[name] = numbers
        else:
            if len(numbers) != 1:
                raise ValueError(f"light {text!r}: {name} is one number, got {value!r}")
            fields[name] = numbers[0]
    missing = [n for n in required if n not in fields]
    if missing:
        raise ValueError(f"light {text!r}: a {kind} light needs {', '.join(missing)} ({EXAMPLE})")
    try:
        return make(**fields)
    except vsgl.ArgumentError as e:
        raise ValueError(f"light {text!r}: {e}") from None


def describe_lights(scene: vsgl.Scene) -> str:
    """``"2 spot, 1 point"``: the scene's lights by type (``"none"`` without any)."""
    by_type = scene.stats["lights_by_type"]
    parts = [f"{n} {kind}" for kind, n in by_type.items() if n]
    return ", ".join(parts) or "none"


def option_value(text: str) -> object:
    """A method option's value as typed on a command line (`render -O`, `bench -O`): int, float,
    true/false or text, tried in that order."""
    value = text.strip()
    if value.lower() in ("true", "false"):
        return value.lower() == "true"
    for kind in (int, float):
        try:
            return kind(value)
        except ValueError:
            continue
    return value
