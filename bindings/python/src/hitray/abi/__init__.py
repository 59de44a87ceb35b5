"""hitray.abi: libhitray's C ABI from Python through cffi (ABI mode), and
shape classes written in Python.

- ``ffi`` and ``lib``: every declaration of the public headers (read from the
  headers themselves at first use, see _cdefs) and the loaded libhitray, the
  same instance the hitray extension uses. ``lib.hr_scene_create`` and so on
  are the C functions; ``lib.HR_OK`` and the other #define integers are there
  too, and the #define strings are in ``STRING_CONSTANTS``.
- ``register_shape(name, cls, context=None)``: a Python class as a shape
  class behind the same vtable as a C module (see _pyshape for the class's
  contract and docs/python-shapes.md for its cost).
- ``Context``: a context of its own, for using the ABI without the extension.
- ``check(ctx, status)`` raises ``HitrayError`` for a failed call, with the
  Python shape error behind it, if any; ``take_shape_error()`` gives that
  error to code that reports failures its own way.
- ``use_library(path)`` loads another libhitray (a build tree's) instead of
  the package's; call it before anything else here.
"""

from typing import Any

from ._context import Context, default_context
from ._errors import HitrayError, ShapeError, check, take_shape_error
from ._library import LibraryError, declarations, load, loaded_library_path, use_library
from ._params import Param
from ._pyshape import register_shape

__all__ = [
    "Context", "HitrayError", "LibraryError", "Param", "STRING_CONSTANTS", "ShapeError",
    "check", "declarations", "default_context", "ffi", "lib", "load", "loaded_library_path",
    "register_shape", "take_shape_error", "use_library",
]


def __getattr__(name: str) -> Any:
    # ffi, lib and the string constants load the library on first use, so
    # use_library can still choose which.
    if name == "ffi":
        return load()[0]
    if name == "lib":
        return load()[1]
    if name == "STRING_CONSTANTS":
        return dict(declarations().strings)
    raise AttributeError(f"module 'hitray.abi' has no attribute {name!r}")
