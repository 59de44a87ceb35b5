"""hitray: a ray tracer after F.S. Hill's *Computer Graphics Using OpenGL*,
chapter 12, from Python.

    import hitray
    scene = hitray.Scene()
    scene.add(hitray.Sphere().translate(0, 1, 0), diffuse=(1, 0, 0), specular=(0.5, 0.5, 0.5),
              specularExponent=20)
    scene.add(hitray.Plane().rotate(-90, 1, 0, 0), diffuse=(0.6, 0.6, 0.6))
    scene.light((5, 8, 6), (1, 1, 1))
    image = hitray.render(scene, hitray.Camera((0, 2, 8), (0, 1, 0), (0, 1, 0), 40),
                          size=(320, 240))
    image.save("out.png")

Scenes come from code (Scene, the shape classes, Camera) or from Hill's SDL
(load_sdl, parse_sdl) or NFF, the format of the SPD benchmark scenes
(load_nff, parse_nff). Hill's queries are Scene.first_hit (getFirstHit),
Scene.hits (the Intersection of every hit) and Scene.trace (many rays as
numpy arrays; Scene.first_hits gives every field of their hits as a Hits,
Scene.occluded whether anything blocks each). Every failure of the library raises a hitray.Error subclass.
The library, its shape modules and the extension all live inside this
package; libhitray finds the modules next to itself. ``hitray.abi`` (the C
ABI through cffi, and shape classes written in Python) is imported on first
use. The library's warnings about a scene are :class:`SceneWarning` entries
of Python's ``warnings``.
"""

# No `from __future__ import annotations` here: it would leave the name
# `annotations` in the package's namespace (and dir(hitray)).
import importlib as _importlib
import typing as _typing

from . import _core
from .camera import Camera
from .errors import (ArgumentError, Error, FileError, ModuleError, NumericError, ParameterError,
                     NFFError, SceneWarning, SDLError, StateError, UnsupportedError)
from .image import Image, RenderedImage, RenderStats
from .modules import (ModuleInfo, ShapeClass, ShapeParam, add_shape_dir, load_module, modules,
                      shape_classes)
from .queries import HitInfo, Hits, Light, TraceResult
from .render import render
from .scene import Scene, SceneObject
from .sdl import load_sdl, parse_sdl
from .nff import load_nff, parse_nff
from .shapes import (Buckyball, Cone, Cube, Cylinder, Difference, Dodecahedron, Icosahedron,
                     Intersection, Mesh, Octahedron, Plane, Shape, Sphere, Square, TaperedCylinder,
                     Teapot, Tetrahedron, Torus, Union)

__version__ = "%d.%d.%d" % _core.version()

if _typing.TYPE_CHECKING:
    from . import abi

__all__ = [
    "Scene", "SceneObject", "Camera", "render", "Image", "RenderedImage", "RenderStats",
    "load_sdl", "parse_sdl", "load_nff", "parse_nff",
    "Shape", "Sphere", "Cube", "Square", "Plane", "TaperedCylinder", "Cylinder", "Cone", "Torus",
    "Mesh", "Tetrahedron", "Octahedron", "Dodecahedron", "Icosahedron", "Buckyball", "Teapot",
    "Union", "Intersection", "Difference",
    "HitInfo", "TraceResult", "Hits", "Light",
    "shape_classes", "modules", "load_module", "add_shape_dir", "ShapeClass", "ShapeParam",
    "ModuleInfo",
    "Error", "ArgumentError", "FileError", "ModuleError", "ParameterError", "SDLError",
    "NFFError", "StateError", "UnsupportedError", "NumericError", "SceneWarning",
]


def __getattr__(name: str) -> _typing.Any:
    # PEP 562: hitray.abi is imported on first use (it loads cffi and parses
    # the headers), not by every `import hitray`.
    if name == "abi":
        return _importlib.import_module(".abi", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> _typing.List[str]:
    return sorted(set(globals()) | {"abi"})
