"""The exceptions hitray raises.

Every failure of the library raises a subclass of :class:`Error` that carries
the library's own message (which names what was wrong: the file, line and
column of a scene file, the path of a shape module, the name of a shape
parameter). Errors in Python arguments (a wrong type, a colour that is not
three numbers) raise the usual ``TypeError`` or ``ValueError``.
"""

from __future__ import annotations

import sys
from typing import Optional

__all__ = [
    "Error",
    "ArgumentError",
    "FileError",
    "ModuleError",
    "ParameterError",
    "SDLError",
    "NFFError",
    "StateError",
    "UnsupportedError",
    "NumericError",
]


class Error(Exception):
    """A failure reported by libhitray.

    Attributes:
        message: the library's message.
        status: the library's status code (``HR_ERROR_*`` in the C headers).
    """

    def __init__(self, message: str, status: int = 0) -> None:
        super().__init__(message)
        self.message = message
        self.status = status


class ArgumentError(Error, ValueError):
    """A value the library refused: a material or light colour out of range,
    a degenerate camera, a ray with a zero direction, an image size of 0."""


class FileError(Error, OSError):
    """A file could not be read or written (a scene file, an image)."""

    def __init__(self, message: str, status: int = 3, filename: Optional[str] = None) -> None:
        Error.__init__(self, message, status)
        self.filename = filename

    def __str__(self) -> str:
        return self.message


class ModuleError(Error):
    """No shape module provides a class, or a module was refused (the message
    names the module's path and why)."""


class ParameterError(Error, ValueError):
    """A shape refused its parameters (the message names the parameter)."""


class SDLError(Error):
    """An error in a scene file.

    Attributes:
        filename: the file (or the name given to :func:`hitray.parse_sdl`).
        line: 1-based line, 0 if unknown.
        column: 1-based column, 0 if unknown.
    """

    def __init__(self, message: str, status: int = 6, filename: Optional[str] = None,
                 line: int = 0, column: int = 0) -> None:
        super().__init__(message, status)
        self.filename = filename
        self.line = line
        self.column = column


class NFFError(SDLError):
    """An error in an NFF scene file (:func:`hitray.load_nff`). It is an
    :class:`SDLError` too, so one ``except SDLError`` catches an error in a
    scene file of either format; ``filename``, ``line`` and ``column`` are
    the same."""


class SceneWarning(UserWarning):
    """A warning of the library's about a scene: accepted, but probably not
    what was meant (no objects at all; a coefficient below the threshold
    that lets it spawn rays, such as ``reflectivity 0.08`` under the default
    ``minReflectivity 0.5``).

    Attributes:
        code: the library's HR_WARNING_* number (1: empty scene, 2: below
            threshold).
        filename: the scene file, None when not from a file.
        line: 1-based line, 0 if unknown.
        column: 1-based column, 0 if unknown.
    """

    def __init__(self, message: str, code: int = 0, filename: Optional[str] = None,
                 line: int = 0, column: int = 0) -> None:
        super().__init__(message)
        self.code = code
        self.filename = filename
        self.line = line
        self.column = column


class StateError(Error):
    """A call in the wrong state (for instance querying an uncommitted scene
    through the low-level core)."""


class UnsupportedError(Error):
    """A feature this build does not have (SDL's ``diamond``: Hill's reader
    loaded it from a mesh file that was never published)."""


class NumericError(Error, ValueError):
    """A degenerate transform (a zero scale factor, a zero rotation axis, a
    singular matrix) or non-finite input."""


# Status codes of include/hitray/common.h.
_INVALID_ARGUMENT = 1
_OUT_OF_MEMORY = 2
_IO = 3
_MODULE = 4
_PARAMETER = 5
_SDL = 6
_STATE = 7
_CANCELLED = 8
_UNSUPPORTED = 9
_NUMERIC = 10

_BY_STATUS = {
    _INVALID_ARGUMENT: ArgumentError,
    _MODULE: ModuleError,
    _PARAMETER: ParameterError,
    _STATE: StateError,
    _UNSUPPORTED: UnsupportedError,
    _NUMERIC: NumericError,
}


def _from_status(status: int, message: str, filename: Optional[str], line: int,
                 column: int) -> BaseException:
    """The exception for a status of the library (called by hitray._core).

    An error located in a scene file (a line is known) is an SDLError whatever
    its status, so that every error of a scene file can be caught as one and
    carries its place; the status tells what kind it was.
    """
    cause = _python_shape_error()
    interrupt = _interrupt_behind(cause)
    if interrupt is not None:
        # Ctrl-C reached a Python shape's hit on the main thread: it is the
        # user's interrupt, not a shape's failure.
        return interrupt
    if cause is not None and str(cause) not in message:
        message = f"{message}: {cause}"
    error = _exception(status, message, filename, line, column)
    error.__cause__ = cause
    return error


def _exception(status: int, message: str, filename: Optional[str], line: int,
               column: int) -> Error:
    if status == _OUT_OF_MEMORY:
        return Error(message, status)  # not MemoryError: Python's own is for its heap
    if status == _SDL or (line > 0 and filename is not None):
        return SDLError(message, status, filename, line, column)
    if status == _IO:
        return FileError(message, status, filename)
    return _BY_STATUS.get(status, Error)(message, status)


def _interrupt_behind(error: Optional[BaseException]) -> Optional[BaseException]:
    """The KeyboardInterrupt a shape error was caused by, if any."""
    seen = 0
    while error is not None and seen < 100:
        if isinstance(error, KeyboardInterrupt):
            return error
        error, seen = error.__cause__, seen + 1
    return None


def _python_shape_error() -> Optional[BaseException]:
    """What a shape class written in Python (hitray.abi.register_shape) raised
    inside a callback, if one did: the library only knows that "a shape
    failed", so the Python message and traceback are added here."""
    errors = sys.modules.get("hitray.abi._errors")
    return errors.take_shape_error() if errors is not None else None
