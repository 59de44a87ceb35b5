"""Materials as keyword arguments, named as in Hill's SDL.

``scene.add(shape, diffuse=(1, 0, 0), specularExponent=20, reflectivity=0.5)``:
each keyword is an SDL material keyword (``ambient``, ``diffuse``,
``specular``, ``emissive``, ``specularExponent``, ``reflectivity``,
``transparency``, ``speedOfLight``, ``specularFraction``,
``surfaceRoughness``, ``texture``, ``parameters``) or its snake_case
spelling (``specular_exponent``, ``speed_of_light``, ...). Defaults are
SDL's: ambient 0.1, diffuse 0.8, specular 0, emissive 0, exponent 1,
reflectivity 0, transparency 0, speed of light 1.
"""

from __future__ import annotations

from typing import Any, Dict, Mapping

from . import _convert, _core

# Python name -> kind, and SDL's camelCase names that differ, from the
# library's table of the fields (include/hitray/scene_fields.h).
_FIELDS = {name: kind for name, _, kind in _core.material_fields()}
_SDL_NAMES = {sdl: name for name, sdl, _ in _core.material_fields() if sdl != name}

MATERIAL_NAMES = tuple(sorted(set(_FIELDS) | set(_SDL_NAMES)))


def normalize(values: Mapping[str, Any]) -> Dict[str, Any]:
    """Keyword arguments to the snake_case fields the core takes, each value
    checked for its type (ranges are the library's to check: it names the
    field and the value it refuses)."""
    out: Dict[str, Any] = {}
    for key, value in values.items():
        field = _SDL_NAMES.get(key, key)
        kind = _FIELDS.get(field)
        if kind is None:
            near = _core.suggest(key, list(MATERIAL_NAMES))
            hint = f" (did you mean '{near}'?)" if near else ""
            raise TypeError(f"unknown material keyword '{key}'{hint}; the material keywords are: "
                            + ", ".join(MATERIAL_NAMES))
        if field in out:
            raise TypeError(f"material keyword '{key}' given twice (as SDL's and Python's name)")
        if kind == "color":
            out[field] = _convert.vec3(value, key)
        elif kind == "number":
            out[field] = _convert.number(value, key)
        elif kind == "integer":
            out[field] = _convert.integer(value, key)
        else:
            try:
                out[field] = tuple(_convert.number(v, key) for v in value)
            except TypeError:
                raise TypeError(f"{key}: expected a sequence of numbers, got {value!r}") from None
    return out
