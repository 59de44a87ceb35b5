"""Shape modules and classes, as the package's context sees them now."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, List, Tuple

from . import _convert, _core

__all__ = ["ShapeClass", "ShapeParam", "ModuleInfo", "shape_classes", "modules", "load_module",
           "add_shape_dir"]


@dataclass(frozen=True)
class ShapeParam:
    """One parameter of a shape class."""

    name: str
    type: str  # "number", "string" or "object"
    required: bool
    default: float
    min: float
    max: float
    help: str
    # Whether min or max is itself outside the range (a radius "> 0").
    min_exclusive: bool = False
    max_exclusive: bool = False


@dataclass(frozen=True)
class ShapeClass:
    """A shape class: its name (an SDL keyword and ``Shape(name)``), help,
    parameters, and the module that provides it."""

    name: str
    help: str
    module: str
    closed: bool
    composite: bool
    surface_count: int
    params: Tuple[ShapeParam, ...]
    surface_names: Tuple[str, ...] = ()  # hr_hit.surface's names; () where none


@dataclass(frozen=True)
class ModuleInfo:
    """A module file on the search path: loaded, or refused and why."""

    path: str
    loaded: bool
    name: str
    description: str
    error: str
    classes: Tuple[str, ...]
    version: str = ""  # the module's metadata; "" where it gives none
    author: str = ""
    url: str = ""


def modules() -> List[ModuleInfo]:
    """Every module on the search path (scanned now), loaded or refused."""
    return [ModuleInfo(m["path"], m["loaded"], m["name"], m["description"], m["error"],
                       tuple(m["classes"]), m["version"], m["author"], m["url"])
            for m in _core.modules()]


def shape_classes() -> Dict[str, ShapeClass]:
    """Every shape class usable now, by name, each from the module that wins
    for that name (the one ``Shape(name)`` and SDL would use)."""
    names: List[str] = []
    for m in _core.modules():
        names.extend(n for n in m["classes"] if n not in names)
    out: Dict[str, ShapeClass] = {}
    for name in sorted(names):
        c = _core.find_shape_class(name)
        out[name] = ShapeClass(c["name"], c["help"], c["module"], c["closed"], c["composite"],
                               c["surface_count"], tuple(ShapeParam(**p) for p in c["params"]),
                               tuple(c["surface_names"]))
    return out


def load_module(path: _convert.PathLike) -> None:
    """Load one shape module file now; its classes win over those found by
    searching. Raises ModuleError naming the path if it is refused."""
    _core.load_module(_convert.path_bytes(path))


def add_shape_dir(directory: _convert.PathLike) -> None:
    """Search `directory` for shape modules before the default places (the
    package's own modules, then HITRAY_SHAPE_PATH)."""
    _core.add_shape_dir(_convert.path_bytes(directory, "directory"))
