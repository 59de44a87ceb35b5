"""Contexts as hitray.abi sees them: the package's default one, one made
here with hr_context_create, or any hr_context* cdata.

A registered class table must outlive its context (context.h), and the
Python objects behind it (callbacks, strings, the class) must live as long
as the table. Each context therefore has a keep-alive list: a `Context`
made here drops its list after hr_context_destroy; the package's default
context and raw cdata contexts, whose end this module cannot see, keep
theirs until the process exits.
"""

from __future__ import annotations

import threading
import weakref
from typing import Any, List, Tuple

from ._errors import check
from ._library import load

_forever_lock = threading.Lock()
_forever: List[Any] = []  # keep-alive of the default context and of raw cdata contexts


class Context:
    """A context of its own: hr_context_create now, hr_context_destroy at
    close() (or when collected). Destroy every scene made on it first."""

    def __init__(self) -> None:
        ffi, lib = load()
        out = ffi.new("hr_context **")
        check(None, lib.hr_context_create(out))
        self.ptr: Any = out[0]
        self._keep: List[Any] = []
        self._finalizer = weakref.finalize(self, _destroy, lib, self.ptr, self._keep)

    def close(self) -> None:
        """hr_context_destroy, then release the Python shape classes
        registered on it."""
        if self._finalizer.alive:
            self._finalizer()
        self.ptr = None

    def __enter__(self) -> "Context":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def check(self, status: int) -> None:
        """Raise HitrayError for a failed status, with this context's message."""
        check(self.ptr, status)

    def last_error(self) -> str:
        """This thread's last error message on this context."""
        ffi, lib = load()
        text: str = ffi.string(lib.hr_context_last_error(self.ptr)).decode("utf-8", "replace")
        return text


def _destroy(lib: Any, ptr: Any, keep: List[Any]) -> None:
    lib.hr_context_destroy(ptr)
    keep.clear()


def default_context() -> Any:
    """The package's one default hr_context* (the one hitray.Shape,
    hitray.parse_sdl and rendering use), from the extension module."""
    ffi, _ = load()
    try:
        from .. import _core
    except ImportError as e:
        raise RuntimeError("hitray.abi: the hitray extension module is not available, so "
                           "there is no default context; pass context= (a hitray.abi.Context "
                           "or an hr_context* cdata)") from e
    return ffi.cast("hr_context *", _core._context_address())


def resolve(context: Any) -> Tuple[Any, List[Any]]:
    """(hr_context* cdata, keep-alive list) for a register_shape context."""
    ffi, _ = load()
    if context is None:
        return default_context(), _forever
    if isinstance(context, Context):
        if context.ptr is None:
            raise ValueError("hitray.abi: this Context is closed")
        return context.ptr, context._keep
    if isinstance(context, ffi.CData) and ffi.typeof(context) == ffi.typeof("hr_context *"):
        if context == ffi.NULL:
            raise ValueError("hitray.abi: context is NULL")
        return context, _forever
    raise TypeError("hitray.abi: context must be None (the package's default context), a "
                    f"hitray.abi.Context or an hr_context* cdata, not {type(context).__name__}")


def keep_alive(keep: List[Any], *objects: Any) -> None:
    with _forever_lock:
        keep.extend(objects)
    if keep is _forever:
        for obj in objects:
            _hold_for_c(obj)


def _hold_for_c(obj: Any) -> None:
    """The library keeps pointers into `obj` (its callbacks, its strings) for
    the rest of the process, references Python's collector cannot see. Give
    it one it can: otherwise the collection at interpreter exit, which frees
    unreachable module contents in any order, could free a callback that a
    scene being freed in the same collection then calls."""
    try:
        import ctypes

        ctypes.pythonapi.Py_IncRef(ctypes.py_object(obj))
    except (ImportError, AttributeError):  # not CPython: the list above holds it
        pass
