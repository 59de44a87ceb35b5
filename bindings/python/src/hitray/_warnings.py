"""The library's warnings as Python ``warnings``: what it accepted and acted
on but that is probably not what was meant (a scene with no objects, a
reflectivity below minReflectivity). The library keeps them per thread until
the call that raised them returns; :func:`issue` turns them into
:class:`hitray.SceneWarning` entries, attributed to the line of the first
caller outside the package."""

from __future__ import annotations

import os
import sys
import types
import warnings
from typing import Optional

from . import _core
from .errors import SceneWarning

__all__ = ["issue", "discard"]


_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


def _caller_level() -> int:
    """The stack level of the nearest frame outside this package, for
    warnings.warn (1 is the frame calling warn)."""
    frame: Optional[types.FrameType] = sys._getframe(2)  # issue's caller; warn's level 2
    level = 2
    while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE):
        frame = frame.f_back
        level += 1
    return level


def issue() -> None:
    """Issue every pending warning of this thread."""
    pending = _core.take_warnings()
    if not pending:
        return
    level = _caller_level()
    for code, message, filename, line, column in pending:
        warnings.warn(SceneWarning(message, code, filename or None, line, column),
                      stacklevel=level)


def discard() -> None:
    """Drop this thread's pending warnings (a rebuild repeats a read whose
    warnings were issued already)."""
    _core.take_warnings()
