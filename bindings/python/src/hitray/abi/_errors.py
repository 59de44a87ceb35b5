"""Errors: hr_status codes as exceptions, and the Python exceptions of shape
callbacks kept until someone asks.

A shape's hit function can only return a status; the library then reports
"a shape failed while tracing: module error" with no word of why. So a
callback that fails keeps its exception here (the first one since the last
`take_shape_error`, with its traceback), and `check` attaches it to the
HitrayError it raises: the message says what the Python code raised, and the
original exception is the __cause__.
"""

from __future__ import annotations

import threading
from typing import Any, List, Optional

from ..errors import _interrupt_behind
from ._library import load


class HitrayError(RuntimeError):
    """A libhitray call failed. `status` is the hr_status code, `status_name`
    its name, and the message is the context's last error."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = int(status)
        ffi, lib = load()
        self.status_name: str = ffi.string(lib.hr_status_name(self.status)).decode("utf-8",
                                                                               "replace")


class ShapeError(RuntimeError):
    """A Python shape class raised, or broke the hit contract, inside a
    callback from libhitray. Its __cause__ is what was raised, if anything."""


# Only the first failure is kept: in a render every thread stops at its own
# failure and the first one is the one that stopped the rest.
_pending_lock = threading.Lock()
_pending: List[ShapeError] = []
_MAX_PENDING = 1


def record_shape_error(error: ShapeError) -> None:
    with _pending_lock:
        if len(_pending) < _MAX_PENDING:
            _pending.append(error)


def take_shape_error() -> Optional[ShapeError]:
    """The first ShapeError raised in a Python shape callback since the last
    call (None if none), and forget it. hitray calls that fail check this
    to explain "a shape failed while tracing"."""
    with _pending_lock:
        error = _pending[0] if _pending else None
        _pending.clear()
        return error


def check(context: Any, status: int) -> None:
    """Raise HitrayError if `status` is not HR_OK, with the context's last
    error (context may be an hr_context* cdata or None) and the Python shape
    error behind it, if there is one."""
    if status == 0:
        return
    ffi, lib = load()
    message = ""
    if context is not None and context != ffi.NULL:
        message = ffi.string(lib.hr_context_last_error(context)).decode("utf-8", "replace")
    if not message:
        message = ffi.string(lib.hr_status_name(status)).decode("utf-8", "replace")
    cause = take_shape_error()
    interrupt = _interrupt_behind(cause)
    if interrupt is not None:
        # Ctrl-C in a shape callback stops the call: it is raised as itself,
        # never as a HitrayError that an `except HitrayError` would swallow.
        raise interrupt
    if cause is not None and str(cause) not in message:
        message = f"{message}: {cause}"
    error = HitrayError(status, message)
    if cause is not None:
        raise error from cause
    raise error
